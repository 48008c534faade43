#pragma once
// The harbour site's static data on the GPU (private to the water renderer): still-water depth,
// porosity, the structures' outline at still water (site_terrain.hpp), land, the coastline's distance field and the relative wave height K as textures, and
// the terrain lattice the seabed, land and structures are drawn on. Uploaded once per site (a
// sequence keeps its site). Needs the renderer's current GL context.
#include <glad/gl.h>

#include <cstddef>
#include <memory>

#include "gl_mesh.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"

namespace nearshore::playback {

class SiteTextures {
 public:
  SiteTextures() = default;
  ~SiteTextures() { release(); }
  SiteTextures(const SiteTextures&) = delete;
  SiteTextures& operator=(const SiteTextures&) = delete;

  /// Uploads `site`'s rasters and terrain when it is not the site held (null: none); structures
  /// known only by their porous cells stand `cell_structure_crest_m` high. Returns the texture
  /// bytes sent (0 for the same site). Throws nearshore::Error when its rasters and its grid disagree in size.
  std::size_t bind_site(const std::shared_ptr<const runtime::HarbourSite>& site, float cell_structure_crest_m);
  const runtime::HarbourSite* site() const { return site_.get(); }
  const std::shared_ptr<const runtime::HarbourSite>& shared_site() const { return site_; }

  /// The sea beyond the grid (lighting only): the deepest still-water depth on the grid's edges,
  /// at least 5 m; kept from the last site when there is none.
  float open_sea_depth_m() const { return open_sea_depth_m_; }
  bool has_relative_wave_height() const { return relative_wave_height_ != 0; }
  /// The ground lattice over the site and its skirt, then the structures: attribute 0 the
  /// position (metres, site frame), 1 the distance inland, 2 the TerrainMaterial.
  const Mesh& terrain() const { return terrain_; }
  /// The surroundings the skirt reads (site_terrain.hpp), in the site frame; empty without. Their
  /// cells are what surface.glsl's u_surroundings_origin_m / u_surroundings_size_m place.
  const GridGeometry& surroundings_cells() const { return surroundings_cells_; }
  double surroundings_edge_blend_m() const { return surroundings_edge_blend_m_; }
  bool has_surroundings() const { return surroundings_ != 0; }

  /// Depth, porosity, the structure mask, land, coast distance and K on their SamplerUnits (0 without a site); leaves
  /// the last of those units active.
  void bind_units() const;

 private:
  void release();
  std::shared_ptr<const runtime::HarbourSite> site_;
  GLuint depth_ = 0, porosity_ = 0, structure_mask_ = 0, land_ = 0, coast_ = 0, relative_wave_height_ = 0;
  GLuint surroundings_ = 0;  // RG: w * elevation, w (SurroundingGround); 0 without surroundings
  Mesh terrain_;
  GridGeometry surroundings_cells_;
  double surroundings_edge_blend_m_ = 0.0;
  float open_sea_depth_m_ = 20.f;
};

}  // namespace nearshore::playback
