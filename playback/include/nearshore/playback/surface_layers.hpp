#pragma once
// SurfaceLayers: what a host adds to the sea a WaterRenderer draws, without the renderer knowing
// where it comes from (the viewer fills them from ships::ShipFleet, docs/ships.md "What a renderer
// needs"; a host behind the C API from its own objects). Three kinds, all in the site frame:
//
//  - HeightPatch: a local height field (a ship's bow wave) ADDED to the shown surface's elevation,
//    in the vertex shader (so the height pass, the dry test and the drawn surface see it) and to its
//    slope (the normal). The sum is the one ShipFleet::shown_elevation_m makes on the CPU.
//  - FoamDecal: an oriented quad of foam (a stern-wake decal) shaded as the sea's own foam.
//  - SolidMesh: a rigid triangle mesh (a hull) in its body frame with a pose, lit like the land
//    (common.glsl shade_lambertian) and depth-tested against the sea, so the waterline shows.
//
// The renderer reads the pointers only during render(); the host owns the data.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nearshore/core/image.hpp"

namespace nearshore::playback {

/// columns x rows heights (m above still water), row 0 south; texel (i, j) centred at
/// (origin_x_m + (i + 0.5) spacing_m, origin_y_m + (j + 0.5) spacing_m). Between texel centres
/// bilinear; outside the square of the outermost centres 0 (ships::BowWave::elevation_m's rule).
/// It is added where the shown surface point lies (after the deep water's choppy shift).
struct HeightPatch {
  double origin_x_m = 0.0, origin_y_m = 0.0, spacing_m = 1.0;
  int columns = 0, rows = 0;          ///< at least 2 x 2
  const float* heights_m = nullptr;   ///< columns * rows floats
  /// Changes whenever the heights or the origin change: the patch is uploaded again only then.
  unsigned long long serial = 0;
};

/// A quad of foam on the surface: centred at (x_m, y_m), length_m along yaw_rad (counter-clockwise
/// from east) by width_m across, covering opacity in [0, 1] at its middle and fading to its edges.
/// Overlapping decals take the larger cover (no build-up where a wake crosses itself).
struct FoamDecal {
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0, length_m = 1.0, width_m = 1.0, opacity = 1.0;
  int variant = 0;  ///< 0-3: which streak pattern breaks the foam up
};

/// A closed triangle mesh in its body frame, placed by world = position_m + R body (R row-major,
/// body -> site frame). Counter-clockwise triangles are not required: both sides are lit.
struct SolidMesh {
  /// Names the geometry: the vertices are uploaded once per id and must not change under it.
  std::uint64_t id = 0;
  const float* vertices_m = nullptr;        ///< x, y, z per vertex, body frame
  std::size_t vertex_count = 0;
  const std::uint32_t* triangles = nullptr; ///< three vertex indices per triangle
  std::size_t triangle_count = 0;
  std::array<double, 3> position_m = {0.0, 0.0, 0.0};
  std::array<double, 9> rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  Rgb albedo_above = {0.55f, 0.55f, 0.52f};  ///< topsides
  Rgb albedo_below = {0.35f, 0.08f, 0.06f};  ///< the bottom paint, below boot_top_z_m
  double boot_top_z_m = 0.0;                 ///< body z where the bottom paint ends (the design waterline)
};

struct SurfaceLayers {
  std::vector<HeightPatch> height_patches;  ///< at most kMaxHeightPatches, summed where they overlap
  std::vector<FoamDecal> foam_decals;       ///< drawn into a foam map of RendererSettings::decal_foam_texels
  std::vector<SolidMesh> meshes;

  static constexpr int kMaxHeightPatches = 16;
};

}  // namespace nearshore::playback
