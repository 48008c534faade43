#pragma once
// The two readers of depth values that both roads share (private to bathymetry/): chart data in
// longitude/latitude (sources.cpp) and a grid in local metres (local_grid.cpp). One reading of a
// raster band (nodata, sign, undeclared NaN, implausible values) and one of "x y depth" text lines,
// so both roads refuse the same bad files with the same messages.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "nearshore/bathymetry/sources.hpp"

class GDALDataset;

namespace nearshore::bathymetry::detail {

/// Band 1 of `dataset` as depths in metres, positive down, row-major with row 0 NORTH (as GDAL
/// stores it); NaN where the band declares nodata. `geotransform` only places pixels in messages.
/// `sign_used` receives "positive_down (why)" or "positive_up (why)". Throws nearshore::Error
/// naming `path` for cells that are NaN without a NaN nodata, and for depths beyond
/// kDeepestPlausibleDepth_m / kHighestPlausibleElevation_m (after the sign is applied).
std::vector<float> read_depth_band(GDALDataset& dataset, const std::filesystem::path& path, DepthSign sign,
                                   const std::array<double, 6>& geotransform, std::string& sign_used);

/// One line of a text sounding file: its two coordinates as written and the depth (positive down).
struct TextSounding {
  double x = 0.0, y = 0.0;
  double depth_m = 0.0;
  int line = 0;  ///< 1-based line number, for messages
};

/// Every "x y value" line of a text file (separated by spaces, tabs, commas or semicolons; a first
/// line that is not three numbers is a header; blank lines skipped). `elevation` negates values
/// (positive up in the file). Throws nearshore::Error naming the file and the line for a line that
/// is not three numbers, a NaN value, an implausible depth, and a file with no soundings.
std::vector<TextSounding> read_text_soundings(const std::filesystem::path& path, bool elevation);

}  // namespace nearshore::bathymetry::detail
