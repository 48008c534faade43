#include "nearshore/bathymetry/local_grid.hpp"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <fmt/core.h>

#include "depth_readers.hpp"
#include "nearshore/bathymetry/distance_transform.hpp"
#include "nearshore/bathymetry/natural_neighbour.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bathymetry {
namespace fs = std::filesystem;
namespace {

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();

struct DatasetCloser {
  void operator()(GDALDataset* dataset) const { GDALClose(dataset); }
};

// 1a. A raster in the file's own metres, row 0 south (Raster's convention; GDAL stores north first).
Raster<float> read_local_raster(const LocalGridRequest& request, GridGeometry& geometry, LocalGrid& out) {
  const fs::path& path = request.file;
  GDALAllRegister();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  std::unique_ptr<GDALDataset, DatasetCloser> dataset(
      GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
  CPLPopErrorHandler();
  if (!dataset || dataset->GetRasterCount() < 1)
    throw Error(path.string(), "is not a raster GDAL can read",
                "give a GeoTIFF, an ESRI ASCII grid (.asc) or 'x y depth' text (.xyz, .csv, .txt)");
  out.format = dataset->GetDriver()->GetDescription();
  const int columns = dataset->GetRasterXSize(), rows = dataset->GetRasterYSize();
  std::array<double, 6> gt{};
  const bool georeferenced = dataset->GetGeoTransform(gt.data()) == CE_None;
  if (const OGRSpatialReference* crs = dataset->GetSpatialRef()) {
    if (crs->IsGeographic())
      throw Error(path.string(), "is in longitude/latitude, not in local metres",
                  "grid it onto a map projection with BathyRequest (nearshore bathy) and name the harbour grid "
                  "it writes instead");
    if (crs->IsProjected() && std::abs(crs->GetLinearUnits() - 1.0) > 1e-9)
      throw Error(path.string(), fmt::format("its CRS counts x and y in units of {} m, not metres", crs->GetLinearUnits()),
                  "convert it to metres (gdalwarp -t_srs with a metre CRS)");
  }
  if (!georeferenced) {
    if (!request.pixel_size_m)
      throw Error(path.string(), "the raster has no georeference, so the size of its pixels is unknown",
                  "give LocalGridRequest::pixel_size_m, or write the file as an ESRI ASCII grid with xllcorner, "
                  "yllcorner and cellsize");
    gt = {0.0, (*request.pixel_size_m)[0], 0.0, rows * (*request.pixel_size_m)[1], 0.0, -(*request.pixel_size_m)[1]};
  }
  if (gt[2] != 0.0 || gt[4] != 0.0 || !(gt[1] > 0.0))
    throw Error(path.string(), "the raster is rotated or mirrored east-west", "warp it axis-aligned with gdalwarp");
  // Row order: GDAL's row 0 is north when gt[5] < 0; a raster stored south-up (gt[5] > 0) is read as is.
  const bool north_first = gt[5] < 0.0;
  const std::vector<float> values = detail::read_depth_band(*dataset, path, request.sign, gt, out.sign_used);
  geometry.columns = columns;
  geometry.rows = rows;
  geometry.set_spacing(gt[1], std::abs(gt[5]));
  geometry.origin_x_m = gt[0];
  geometry.origin_y_m = north_first ? gt[3] + rows * gt[5] : gt[3];
  Raster<float> depth(columns, rows, kNaNf);
  for (int row = 0; row < rows; ++row)
    for (int column = 0; column < columns; ++column)
      depth(column, row) = values[static_cast<std::size_t>(north_first ? rows - 1 - row : row) * columns + column];
  return depth;
}

// 1b. Text soundings in metres, gridded at spacing_m over their bounding box by Sibson interpolation.
Raster<float> grid_local_soundings(const LocalGridRequest& request, GridGeometry& geometry, LocalGrid& out) {
  const fs::path& path = request.file;
  out.format = "XYZ";
  const bool elevation = request.sign == DepthSign::kPositiveUp;
  out.sign_used = elevation ? "positive_up (from LocalGridRequest::sign)"
                            : "positive_down (soundings are depths unless LocalGridRequest::sign says otherwise)";
  if (!request.spacing_m)
    throw Error(path.string(), "is scattered soundings, which need a cell size to be gridded",
                "give LocalGridRequest::spacing_m, e.g. a tenth of the shortest wavelength's cells");
  const std::vector<detail::TextSounding> soundings = detail::read_text_soundings(path, elevation);
  std::vector<ScatteredDepth> points;
  points.reserve(soundings.size());
  double x_min = INFINITY, y_min = INFINITY, x_max = -INFINITY, y_max = -INFINITY;
  for (const auto& s : soundings) {
    points.push_back({s.x, s.y, s.depth_m});
    x_min = std::min(x_min, s.x), x_max = std::max(x_max, s.x);
    y_min = std::min(y_min, s.y), y_max = std::max(y_max, s.y);
  }
  const auto [dx, dy] = *request.spacing_m;
  // The bounding box rounded to whole cells (a micrometre of slack so 20 m / 0.1 m stays 200 cells).
  const double columns = std::ceil((x_max - x_min) / dx - 1e-9), rows = std::ceil((y_max - y_min) / dy - 1e-9);
  if (!(columns >= 2 && rows >= 1))
    throw Error(path.string(),
                fmt::format("its soundings span {} m x {} m, less than two cells of {} m x {} m", x_max - x_min,
                            y_max - y_min, dx, dy),
                "give soundings over the whole flume or basin, or a smaller LocalGridRequest::spacing_m");
  if (columns * rows > 4e8)
    throw Error(path.string(), fmt::format("gridded at {} m x {} m it makes {:.3g} cells", dx, dy, columns * rows),
                "give a larger LocalGridRequest::spacing_m");
  geometry.columns = static_cast<int>(columns);
  geometry.rows = static_cast<int>(rows);
  geometry.set_spacing(dx, dy);
  geometry.origin_x_m = x_min;
  geometry.origin_y_m = y_min;
  return NaturalNeighbourSurface(points).sample(geometry);
}

}  // namespace

bool is_text_soundings(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  return extension == ".xyz" || extension == ".csv" || extension == ".txt";
}

LocalGrid read_local_grid(const LocalGridRequest& request) {
  if (!(request.minimum_depth_m >= 0.0 && request.minimum_depth_m <= kDeepestPlausibleDepth_m))
    throw Error(fmt::format("LocalGridRequest::minimum_depth_m = {} m", request.minimum_depth_m),
                fmt::format("is outside 0 .. {:.0f} m", kDeepestPlausibleDepth_m), "give a depth in metres, 0 for none");
  for (const auto* size : {&request.spacing_m, &request.pixel_size_m})
    if (*size && !((**size)[0] > 0.0 && (**size)[1] > 0.0 && std::isfinite((**size)[0]) && std::isfinite((**size)[1])))
      throw Error(request.file.string(), fmt::format("a cell size of {} m x {} m is not a size", (**size)[0], (**size)[1]),
                  "give LocalGridRequest::spacing_m and pixel_size_m as two sizes > 0 in metres");
  require_readable_file(request.file, "a depth raster or 'x y depth' text soundings in local metres");
  // 1. The depths in the file's own metres.
  LocalGrid out;
  GridGeometry geometry;
  Raster<float> depth = is_text_soundings(request.file) ? grid_local_soundings(request, geometry, out)
                                                        : read_local_raster(request, geometry, out);
  // 2. Holes: a raster's nodata is outside the basin (walls, land); cells of a soundings grid beyond
  //    their convex hull (at most half a cell at its edges) take the nearest gridded depth.
  Raster<std::uint8_t> known(geometry.columns, geometry.rows, 0), land(geometry.columns, geometry.rows, 0);
  std::size_t known_cells = 0;
  float deepest_m = 0.0f;
  for (std::size_t i = 0; i < depth.size(); ++i) {
    known.values()[i] = std::isfinite(depth.values()[i]);
    known_cells += known.values()[i];
    if (known.values()[i]) deepest_m = std::max(deepest_m, depth.values()[i]);
  }
  if (known_cells == 0)
    throw Error(request.file.string(), "holds no depth (every cell is nodata)", "check the file with gdalinfo");
  if (known_cells < depth.size()) {
    const NearestSeed nearest = nearest_seed_transform(known, geometry.smaller_spacing_m());
    for (int row = 0; row < geometry.rows; ++row)
      for (int column = 0; column < geometry.columns; ++column) {
        if (known(column, row)) continue;
        ++out.filled_cells;
        if (out.format == "XYZ")
          depth(column, row) = depth(nearest.nearest_column(column, row), nearest.nearest_row(column, row));
        else
          depth(column, row) = -deepest_m;  // a wall as high as the deepest water is deep: never overtopped
      }
  }
  // 3. Land where still water does not reach; the minimum depth on the rest (solver stability).
  std::size_t water_cells = 0;
  for (std::size_t i = 0; i < depth.size(); ++i) {
    float& d = depth.values()[i];
    land.values()[i] = d <= 0.0f;
    if (land.values()[i]) continue;
    ++water_cells;
    if (d < request.minimum_depth_m) {
      d = static_cast<float>(request.minimum_depth_m);
      ++out.raised_cells;
    }
  }
  if (water_cells == 0)
    throw Error(request.file.string(),
                fmt::format("every cell is land: no value is a depth below still water ({})", out.sign_used),
                request.sign == DepthSign::kPositiveUp || out.sign_used.starts_with("positive_up")
                    ? "if the values are depths (positive down), set LocalGridRequest::sign to DepthSign::kPositiveDown"
                    : "if the values are elevations (positive up), set LocalGridRequest::sign to DepthSign::kPositiveUp");
  HarbourGrid& grid = out.grid;
  grid.geometry = geometry;
  grid.still_water_depth_m = std::move(depth);
  grid.land = std::move(land);
  grid.porosity = Raster<float>(geometry.columns, geometry.rows, 1.0f);
  grid.coast_distance_m = signed_coast_distance(grid.land, geometry.smaller_spacing_m());
  return out;
}

}  // namespace nearshore::bathymetry
