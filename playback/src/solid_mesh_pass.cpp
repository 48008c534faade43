#include "solid_mesh_pass.hpp"

#include "gl_program.hpp"

namespace nearshore::playback {

SolidMeshPass::SolidMeshPass() {
  const std::initializer_list<const char*> surface = {"common.glsl", "surface.glsl"};
  program_ = link_program(surface, "mesh.vert.glsl", surface, "mesh.frag.glsl");
}

SolidMeshPass::~SolidMeshPass() {
  glDeleteProgram(program_);
}

void SolidMeshPass::draw(const SurfaceLayers& layers, SurfaceLayerGpu& layer_gpu,
                         const SurfaceFormula& formula, const LightingFrame& light, const CameraView& view,
                         double earth_radius_m, FrameStatistics& statistics, const Matrix4* mirror) const {
  if (layers.meshes.empty()) return;
  glUseProgram(program_);
  set_lighting_uniforms(program_, light);
  set_uniform(program_, "u_view_projection",
              mirror ? multiply(view.view_projection, *mirror) : view.view_projection);
  const Vector3 eye = mirror ? Vector3{view.eye_m[0], view.eye_m[1], -view.eye_m[2]} : view.eye_m;
  set_surface_uniforms(program_, formula, eye, earth_radius_m);
  set_uniform(program_, "u_mirror", mirror ? 1 : 0);
  for (const SolidMesh& solid : layers.meshes) {
    const SurfaceLayerGpu::GpuMesh& gpu = layer_gpu.mesh(solid, statistics.layer_upload_bytes);
    float rotation[9];
    for (int k = 0; k < 9; ++k) rotation[k] = float(solid.rotation[std::size_t(k)]);
    glUniformMatrix3fv(at(program_, "u_rotation"), 1, GL_TRUE, rotation);  // row-major
    set_uniform(program_, "u_position_m", solid.position_m);
    set_uniform(program_, "u_albedo_above", solid.albedo_above);
    set_uniform(program_, "u_albedo_below", solid.albedo_below);
    set_uniform(program_, "u_boot_top_z_m", float(solid.boot_top_z_m));
    glBindVertexArray(gpu.vertex_array);
    glDrawElements(GL_TRIANGLES, gpu.index_count, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  if (!mirror) statistics.meshes = int(layers.meshes.size());
}

}  // namespace nearshore::playback
