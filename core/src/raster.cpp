#include "nearshore/core/raster.hpp"

namespace nearshore {

// Square cells keep the one key "spacing_m" (so files of square grids are byte for byte what they
// were before rectangular cells). Rectangular cells are written as "spacing_x_m" and "spacing_y_m"
// WITHOUT "spacing_m": a reader that predates them then fails on the missing key instead of
// silently taking dx for dy (docs/formats.md).
void to_json(nlohmann::json& out, const GridGeometry& g) {
  out = nlohmann::json{{"columns", g.columns},       {"rows", g.rows},
                       {"spacing_m", g.spacing_m},   {"origin_x_m", g.origin_x_m},
                       {"origin_y_m", g.origin_y_m}, {"crs_wkt", g.crs_wkt},
                       {"projection", g.projection.is_null() ? nlohmann::json::object() : g.projection}};
  if (!g.square_cells()) {
    out.erase("spacing_m");
    out["spacing_x_m"] = g.spacing_x_m();
    out["spacing_y_m"] = g.spacing_y_m();
  }
}

void from_json(const nlohmann::json& in, GridGeometry& g) {
  in.at("columns").get_to(g.columns);
  in.at("rows").get_to(g.rows);
  if (in.contains("spacing_m")) {
    g.set_spacing(in.at("spacing_m").get<double>(), in.at("spacing_m").get<double>());
  } else {
    g.set_spacing(in.at("spacing_x_m").get<double>(), in.at("spacing_y_m").get<double>());
  }
  in.at("origin_x_m").get_to(g.origin_x_m);
  in.at("origin_y_m").get_to(g.origin_y_m);
  g.crs_wkt = in.value("crs_wkt", std::string{});
  g.projection = in.value("projection", nlohmann::json::object());
}

}  // namespace nearshore
