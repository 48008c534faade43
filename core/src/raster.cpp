#include "nearshore/core/raster.hpp"

namespace nearshore {

void to_json(nlohmann::json& out, const GridGeometry& g) {
  out = nlohmann::json{{"columns", g.columns},       {"rows", g.rows},
                       {"spacing_m", g.spacing_m},   {"origin_x_m", g.origin_x_m},
                       {"origin_y_m", g.origin_y_m}, {"crs_wkt", g.crs_wkt},
                       {"projection", g.projection.is_null() ? nlohmann::json::object() : g.projection}};
}

void from_json(const nlohmann::json& in, GridGeometry& g) {
  in.at("columns").get_to(g.columns);
  in.at("rows").get_to(g.rows);
  in.at("spacing_m").get_to(g.spacing_m);
  in.at("origin_x_m").get_to(g.origin_x_m);
  in.at("origin_y_m").get_to(g.origin_y_m);
  g.crs_wkt = in.value("crs_wkt", std::string{});
  g.projection = in.value("projection", nlohmann::json::object());
}

}  // namespace nearshore
