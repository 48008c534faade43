#pragma once
// The baked field's slopes at every distance (issue 41): the slope moments of a harbour keyframe
// as a mip-mapped texture, so that a pixel covering many cells gets the mean slope over its
// footprint and the variance of the slopes it cannot resolve, instead of one point sample of a
// swell it aliases. The variance goes into the BRDF's roughness: LEADR (Dupuy, Heitz, Iehl,
// Poulin, Neyret & Ostromoukhov 2013, "Linear Efficient Antialiased Displacement and Reflectance
// Mapping"; Olano & Baker 2010 "LEAN mapping"): a texture of (s_x, s_y, s_x^2, s_y^2) filters
// linearly, and Var s = E[s^2] - E[s]^2 over the footprint is the slope variance the microfacet
// distribution (seed 000 eq. 3.13) gains where the picture cannot show the waves. Bruneton,
// Neyret & Holzschuch 2010 section 4 do the same for the FFT cascades (detail_normal_weight).
// GL-free: the renderer uploads these levels as they are (keyframe_textures.cpp), and the CPU
// sampler below is the twin of the shader's textureLod (shaders/common.glsl, the same names).
#include <array>
#include <utility>
#include <vector>

#include "nearshore/core/raster.hpp"

namespace nearshore::playback {

/// One level of the pyramid: `columns` x `rows` texels of four floats (g_x, g_y, g_x^2, g_y^2), row
/// 0 south. g is the rise per cell (m): the slope times the cell size, so the texture is the same
/// for any cell shape and the shader divides by dx, dy (dx^2, dy^2 for the squares).
struct SlopeMomentLevel {
  int columns = 0, rows = 0;
  std::vector<float> texels;  ///< 4 per texel, row-major
};

/// Level 0 per cell (i, j): g_x = (eta(i+1, j) - eta(i-1, j)) / 2, g_y likewise (central
/// differences, the neighbour clamped at the grid's edge: what the shader's clamp-to-edge
/// lookups of eta gave before), and their squares. Each further level halves each axis (floor,
/// at least 1) until both are 1; texel k of a level of m texels averages the finer level's n texels
/// over [k n / m, (k + 1) n / m) weighted by overlap (an exact box filter also for odd sizes; an
/// even size is the plain mean of texels 2k and 2k + 1), summed in double, x then y, rounded to
/// float once. A pure function of eta (the same bits on any thread): the renderer computes it on a
/// worker when a keyframe is staged (keyframe_textures.cpp).
std::vector<SlopeMomentLevel> slope_moment_pyramid(const Raster<float>& surface_elevation_m);
/// The same into `pyramid`, reusing its levels' storage (no fresh memory to fault in when it holds
/// a pyramid of the same grid: the render thread's, for keyframes it computes itself).
void slope_moment_pyramid(const Raster<float>& surface_elevation_m, std::vector<SlopeMomentLevel>& pyramid);

/// The levels' sizes (columns, rows) for a grid of `columns` x `rows`, level 0 first: what
/// slope_moment_pyramid returns, known before it is computed (the textures are allocated then).
std::vector<std::pair<int, int>> slope_moment_level_sizes(int columns, int rows);

/// The mip level a pixel reads (GL's lambda): log2 of its footprint (m; the larger of the two
/// screen axes, as the detail normals' footprint) over the cell size, at least 0.
double baked_slope_lod(double footprint_m, double cell_m);

/// The twin of textureLod with GL_LINEAR_MIPMAP_LINEAR and clamp-to-edge: bilinear between texel
/// centres ((i + 0.5) / n) on levels floor(lod) and the next, linear between them; lod clamped to
/// [0, last level]. (u, v) in [0, 1] over the grid.
std::array<double, 4> sample_slope_moments(const std::vector<SlopeMomentLevel>& pyramid, double u, double v, double lod);

/// What the shading takes from the moments of two keyframes at a point (`fraction` of the way
/// from `from` to `to`, cells dx x dy): the mean slope (x, y), and the slope variance per axis
/// the footprint holds, 0.5 (Var s_x + Var s_y), each keyframe's variance (E[g^2] - E[g]^2) / d^2
/// interpolated in time (the variance of each frame's footprint, not of the blend of two).
struct FilteredSlope {
  double slope_x = 0.0, slope_y = 0.0;
  double variance_per_axis = 0.0;
};
FilteredSlope filtered_baked_slope(const std::array<double, 4>& from, const std::array<double, 4>& to, double fraction,
                                   double spacing_x_m, double spacing_y_m);

}  // namespace nearshore::playback
