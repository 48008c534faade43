#include "site_textures.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gl_program.hpp"
#include "gl_texture.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/playback/site_terrain.hpp"

namespace nearshore::playback {

namespace {

// One R channel raster, rows packed (GL_UNPACK_ALIGNMENT 1: an R8 row need not be 4-byte aligned).
GLuint site_texture(GLenum internal_format, GLenum type, int columns, int rows, const void* data,
                    GLint filter) {
  const GLuint texture = new_texture(GL_TEXTURE_2D, filter, GL_CLAMP_TO_EDGE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(internal_format), columns, rows, 0, GL_RED, type, data);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  return texture;
}

// K of the site with land and structure cells (NaN) given their water neighbours' mean, so the
// bilinear filter brings no NaN to the water beside a quay (and no unsheltered halo).
std::vector<float> relative_wave_height_filled(const Raster<float>& k) {
  const int columns = k.columns(), rows = k.rows();
  std::vector<float> filled(k.values());
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      if (std::isfinite(k(i, j))) continue;
      double sum = 0.0;
      int count = 0;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ii = i + di, jj = j + dj;
          if (ii < 0 || jj < 0 || ii >= columns || jj >= rows || !std::isfinite(k(ii, jj))) continue;
          sum += k(ii, jj);
          ++count;
        }
      filled[std::size_t(j) * columns + i] = count > 0 ? float(sum / count) : 1.f;
    }
  return filled;
}

}  // namespace

std::size_t SiteTextures::bind_site(const std::shared_ptr<const runtime::HarbourSite>& site,
                                   float cell_structure_crest_m) {
  if (site == site_) return 0;
  release();
  site_ = site;
  if (!site_) return 0;
  const HarbourGrid& h = site_->harbour;
  const int columns = h.geometry.columns, rows = h.geometry.rows;
  if (columns < 2 || rows < 2 || h.still_water_depth_m.columns() != columns || h.land.columns() != columns ||
      h.porosity.columns() != columns || h.still_water_depth_m.rows() != rows || h.land.rows() != rows ||
      h.porosity.rows() != rows)
    throw Error("harbour site",
                "its grid is " + std::to_string(columns) + " x " + std::to_string(rows) +
                    " cells but its depth, land or porosity raster has another size",
                "build the HarbourSite from one HarbourGrid of at least 2 x 2 cells");
  depth_ = site_texture(GL_R32F, GL_FLOAT, columns, rows, h.still_water_depth_m.data(), GL_LINEAR);
  porosity_ = site_texture(GL_R32F, GL_FLOAT, columns, rows, h.porosity.data(), GL_LINEAR);
  land_ = site_texture(GL_R8, GL_UNSIGNED_BYTE, columns, rows, h.land.data(), GL_NEAREST);
  // The coastline's distance field for the shoreline waves; infinite (no coast) becomes far.
  std::vector<float> coast(std::size_t(columns) * rows, 1e4f);
  if (h.coast_distance_m.columns() == columns && h.coast_distance_m.rows() == rows)
    for (std::size_t k = 0; k < coast.size(); ++k)
      coast[k] = std::isfinite(h.coast_distance_m.data()[k])
                     ? std::clamp(h.coast_distance_m.data()[k], -1e4f, 1e4f)
                     : 1e4f;
  coast_ = site_texture(GL_R32F, GL_FLOAT, columns, rows, coast.data(), GL_LINEAR);
  std::size_t bytes = std::size_t(columns) * rows * 9;
  const Raster<float>& k = site_->relative_wave_height;
  if (k.columns() == columns && k.rows() == rows) {
    const std::vector<float> filled = relative_wave_height_filled(k);
    glActiveTexture(GLenum(GL_TEXTURE0 + kRelativeWaveHeight));
    relative_wave_height_ = site_texture(GL_R32F, GL_FLOAT, columns, rows, filled.data(), GL_LINEAR);
    glActiveTexture(GL_TEXTURE0);
    bytes += std::size_t(columns) * rows * 4;
  }
  // The sea beyond the grid takes the deepest depth found on its edges (lighting only).
  float edge_depth = 0.f;
  for (int i = 0; i < columns; ++i)
    edge_depth = std::max({edge_depth, h.still_water_depth_m(i, 0), h.still_water_depth_m(i, rows - 1)});
  for (int j = 0; j < rows; ++j)
    edge_depth = std::max({edge_depth, h.still_water_depth_m(0, j), h.still_water_depth_m(columns - 1, j)});
  open_sea_depth_m_ = std::max(edge_depth, 5.f);
  // The ground, skirt and structures (site_terrain.hpp), and the structures' outline at still
  // water that the water's mask reads (surface.glsl, is_dry).
  TerrainOptions options;
  options.cell_structure_crest_m = cell_structure_crest_m;
  options.open_sea_depth_m = open_sea_depth_m_;
  const TerrainMesh mesh = build_site_terrain(h, options);
  const Raster<float>& mask = mesh.structure_mask;
  structure_mask_ = site_texture(GL_R8, GL_FLOAT, mask.columns(), mask.rows(), mask.data(), GL_LINEAR);
  terrain_ = upload_mesh(mesh.vertices, mesh.indices, {3, 1, 1});
  bytes += mask.size();
  // The skirt's ground beyond the grid (surface.glsl u_surroundings): w * elevation and w, read
  // bilinearly like the CPU's twin (SurroundingGround).
  const SurroundingGround& outer = mesh.surroundings;
  if (!outer.empty()) {
    std::vector<float> texels(outer.weight.size() * 2);
    for (std::size_t k = 0; k < outer.weight.size(); ++k)
      texels[2 * k] = outer.weighted_elevation_m.data()[k], texels[2 * k + 1] = outer.weight.data()[k];
    glActiveTexture(GLenum(GL_TEXTURE0 + kSurroundings));
    surroundings_ = new_texture(GL_TEXTURE_2D, GL_LINEAR, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32F, outer.weight.columns(), outer.weight.rows(), 0, GL_RG, GL_FLOAT, texels.data());
    glActiveTexture(GL_TEXTURE0);
    surroundings_cells_ = outer.cells;
    surroundings_edge_blend_m_ = outer.edge_blend_m;
    bytes += texels.size() * sizeof(float);
  }
  return bytes;  // texture bytes (FrameStatistics::upload_bytes)
}

void SiteTextures::bind_units() const {
  const auto bind = [](int unit, GLuint texture) {
    glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D, texture);
  };
  bind(kDepth, depth_);
  bind(kPorosity, porosity_);
  bind(kStructureMask, structure_mask_);
  bind(kLand, land_);
  bind(kCoast, coast_);
  bind(kRelativeWaveHeight, relative_wave_height_);
  bind(kSurroundings, surroundings_);
}

void SiteTextures::release() {
  for (GLuint* texture : {&depth_, &porosity_, &structure_mask_, &land_, &coast_, &relative_wave_height_, &surroundings_})
    if (*texture) glDeleteTextures(1, texture), *texture = 0;
  terrain_.release();
  surroundings_cells_ = GridGeometry{};
  surroundings_edge_blend_m_ = 0.0;
  site_.reset();
}

}  // namespace nearshore::playback
