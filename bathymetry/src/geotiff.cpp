#include "nearshore/bathymetry/geotiff.hpp"

#include "nearshore/core/geotiff_file.hpp"

namespace nearshore::bathymetry {

void write_depth_geotiff(const std::filesystem::path& path, const GridGeometry& g, const Raster<float>& depth_m,
                         const std::string& vertical_datum) {
  GeoTiffContent content;
  content.bands = {{&depth_m, "depth (m, positive down)", "m"}};
  content.metadata = {{"NEARSHORE_VALUE", "depth"}, {"NEARSHORE_DEPTH_SIGN", "positive_down"}, {"NEARSHORE_VERTICAL_DATUM", vertical_datum}};
  write_geotiff_file(path, g, content, "the depth band");
}

}  // namespace nearshore::bathymetry
