#include "nearshore/runtime/harbour_site.hpp"

#include <algorithm>
#include <string>

namespace nearshore::runtime {

namespace {
// The widest sponge of the bake (manifest solver.sponges) on a side other than `source_side`.
double widest_sponge_m(const nlohmann::json& solver, const std::string& source_side) {
  double widest = 0.0;
  if (!solver.is_object() || !solver.contains("sponges") || !solver["sponges"].is_array()) return widest;
  for (const nlohmann::json& sponge : solver["sponges"]) {
    if (!sponge.is_object() || !sponge.contains("width_m") || !sponge["width_m"].is_number()) continue;
    const std::string side = sponge.contains("side") && sponge["side"].is_string() ? sponge["side"].get<std::string>() : "";
    if (side == source_side) continue;
    widest = std::max(widest, sponge["width_m"].get<double>());
  }
  return widest;
}
}  // namespace

HarbourSite read_harbour_site(const sequence::SequenceReader& reader, double edge_fade_m, sequence::Verify verify) {
  HarbourSite site;
  site.harbour = reader.read_harbour_grid(verify);
  const GridGeometry& geometry = reader.geometry();
  site.width_m = geometry.width_m();  // columns dx, rows dy (rectangular cells alike)
  site.height_m = geometry.height_m();
  site.frame_interval_s = reader.frame_interval_s();
  const sequence::SequenceManifest& manifest = reader.manifest();
  std::string source_side;
  if (manifest.deep_water) {
    site.choppiness = manifest.deep_water->choppiness;
    if (manifest.deep_water->coupling && manifest.deep_water->coupling->blending) {
      const sequence::DeepWaterBlendingRecord& blending = *manifest.deep_water->coupling->blending;
      source_side = blending.side;
      site.source_axis = blending.axis == "x" ? 0 : 1;
      site.inward_sign = blending.side == "east" || blending.side == "north" ? -1.0 : 1.0;
      site.source_line_m = blending.source_line_m;
      site.blend_start_m = blending.start_m;
      site.blend_width_m = blending.width_m;
    }
  }
  if (manifest.solver.is_object() && manifest.solver.contains("dry_depth_m") && manifest.solver["dry_depth_m"].is_number())
    site.dry_depth_m = manifest.solver["dry_depth_m"].get<double>();
  const double smaller_side_m = std::min(site.width_m, site.height_m);
  if (edge_fade_m >= 0.0) {
    site.edge_fade_m = edge_fade_m;
  } else {
    double fade = widest_sponge_m(manifest.solver, source_side);
    if (!(fade > 0.0)) fade = site.blend_width_m;
    if (!(fade > 0.0)) fade = 0.05 * smaller_side_m;
    site.edge_fade_m = std::min(fade, 0.25 * smaller_side_m);
  }
  if (source_side.empty()) {
    // No maker record: the south edge fades like the others.
    site.source_axis = 1;
    site.inward_sign = 1.0;
    site.source_line_m = 0.0;
    site.blend_start_m = 0.0;
    site.blend_width_m = site.edge_fade_m;
  }
  return site;
}

}  // namespace nearshore::runtime
