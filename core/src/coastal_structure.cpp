#include "nearshore/core/coastal_structure.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "nearshore/core/error.hpp"

namespace nearshore {

double CoastalStructure::footprint_half_width_m(double depth_m) const {
  return 0.5 * crest_width_m + side_slope * (crest_elevation_m + std::max(depth_m, 0.0));
}

void to_json(nlohmann::json& out, const CoastalStructure& s) {
  out = nlohmann::json{{"name", s.name},
                       {"kind", s.kind},
                       {"lines", s.lines},
                       {"polygons", s.polygons},
                       {"crest_width_m", s.crest_width_m},
                       {"crest_elevation_m", s.crest_elevation_m},
                       {"side_slope", s.side_slope},
                       {"reflection_coefficient", s.reflection_coefficient},
                       {"roughness_factor", s.roughness_factor},
                       {"transmission_coefficient", s.transmission_coefficient}};
  if (s.porosity >= 0.0) out["porosity"] = s.porosity;
}

void from_json(const nlohmann::json& in, CoastalStructure& s) {
  const std::string subject = "coastal structure " + in.value("name", std::string("(unnamed)"));
  auto number = [&](const char* key, double lowest, double highest, double fallback) {
    const double value = in.contains(key) ? in.at(key).get<double>() : fallback;
    if (!(value >= lowest && value <= highest))
      throw Error(subject, fmt::format("`{}` = {} is outside {} .. {}", key, value, lowest, highest),
                  "rewrite the harbour grid with `nearshore bathy`");
    return value;
  };
  s.name = in.value("name", std::string());
  s.kind = in.value("kind", std::string());
  s.lines = in.value("lines", std::vector<StructureLine>{});
  s.polygons = in.value("polygons", std::vector<std::vector<StructureLine>>{});
  // Bounds: what a built structure can be (the largest breakwaters are ~100 m wide at the crest,
  // crests stand at most ~30 m above the sea, faces are 1:10 at their gentlest).
  s.crest_width_m = number("crest_width_m", 0.0, 1000.0, 0.0);
  s.crest_elevation_m = number("crest_elevation_m", -100.0, 100.0, 0.0);
  s.side_slope = number("side_slope", 0.0, 20.0, 0.0);
  s.reflection_coefficient = number("reflection_coefficient", -1.0, 1.0, 1.0);
  if (s.reflection_coefficient < 0.0) s.reflection_coefficient = -1.0;
  s.roughness_factor = number("roughness_factor", 0.3, 1.0, 1.0);
  s.transmission_coefficient = number("transmission_coefficient", 0.0, 1.0, 0.0);
  s.porosity = in.contains("porosity") ? number("porosity", 0.0, 1.0, -1.0) : -1.0;
}

}  // namespace nearshore
