#pragma once
// The uniforms of surface.glsl (private to the water renderer): the snapshot's formula for the sea
// surface, the site's constants and the layers' height patches. Every program that places the
// surface (the water, the height pass, the terrain, the meshes, the deep-water foam) sets them
// through this one function, so every pass sees the same sea.
#include <glad/gl.h>

#include "keyframe_textures.hpp"
#include "nearshore/playback/vector3.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"
#include "surface_layer_gpu.hpp"

namespace nearshore::playback {

/// One draw's view of the surface: what the snapshot blends, the keyframe textures bound for it,
/// and the site's static data (SiteTextures).
struct SurfaceFormula {
  const runtime::SurfaceSnapshot& snapshot;
  const KeyframeTextures::Bound& bound;
  const runtime::HarbourSite* site;  ///< null: the open sea only
  float open_sea_depth_m;            ///< the depth the lighting assumes beyond the harbour grid
  bool has_relative_wave_height;     ///< the site's K texture is on its unit
  const PatchUniforms& patches;
  int patch_count;  ///< of `patches`, how many this draw adds (0: none)
  /// The site's surroundings as the skirt reads them (SiteTextures; their texture on its unit):
  /// their cells in the site frame, null without.
  const GridGeometry* surroundings = nullptr;
  float surroundings_edge_blend_m = 0.f;  ///< SurroundingGround::edge_blend_m
};

/// The uniforms of surface.glsl for `program` (in use), seen from `eye_m` on an earth of
/// `earth_radius_m` (0: flat).
void set_surface_uniforms(GLuint program, const SurfaceFormula& formula, const Vector3& eye_m,
                          double earth_radius_m);

}  // namespace nearshore::playback
