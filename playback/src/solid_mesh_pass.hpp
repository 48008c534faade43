#pragma once
// Hulls and other solids of SurfaceLayers::meshes (private to the water renderer), lit as the land
// and depth-tested against everything drawn; drawn before the sea so the sea's depth test hides
// what is under water, and again mirrored for the local reflection.
#include <glad/gl.h>

#include "nearshore/playback/camera.hpp"
#include "nearshore/playback/lighting.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "surface_layer_gpu.hpp"
#include "surface_uniforms.hpp"

namespace nearshore::playback {

class SolidMeshPass {
 public:
  SolidMeshPass();  ///< links mesh.vert/frag; needs the renderer's current GL context
  ~SolidMeshPass();
  SolidMeshPass(const SolidMeshPass&) = delete;
  SolidMeshPass& operator=(const SolidMeshPass&) = delete;

  /// The meshes into the bound framebuffer, each uploaded by `layer_gpu` on first sight (its
  /// bytes added to statistics.layer_upload_bytes). `mirror` (the reflection pass): z -> -z, the
  /// eye mirrored too so each face turns towards the eye that sees its image; only what stands
  /// above still water, as linear radiance. Without a mirror statistics.meshes counts them.
  void draw(const SurfaceLayers& layers, SurfaceLayerGpu& layer_gpu, const SurfaceFormula& formula,
            const LightingFrame& light, const CameraView& view, double earth_radius_m,
            FrameStatistics& statistics, const Matrix4* mirror = nullptr) const;

 private:
  GLuint program_ = 0;
};

}  // namespace nearshore::playback
