#pragma once
// Agitation: what a port study delivers from a harbour bake (issue 39; docs/port-study.md). The
// disturbance (agitation) coefficient of every water cell,
//     K(x, y) = Hs(x, y) / Hs_incident,                                                      (1)
// the ratio that harbour-agitation studies map (Goda 2000, "Random Seas and Design of Maritime
// Structures", 3.5; the "disturbance coefficient" of MIKE 21 BW), and its values at named berths.
//   Hs(x, y)     = 4 sqrt(m0), m0 the variance of the surface elevation about its mean: the bake's
//                  own every-step statistics (wave_statistics.tif band 2, docs/formats/wave-statistics.md)
//                  where the sequence has them and the whole sequence is asked for, else the
//                  frames' (SurfaceStatistics, the geotiff export's accumulator);
//   Hs_incident  = the wave maker's: 4 sqrt(sum a_i^2 / 2) over the components the manifest's
//                  wave_conditions record (the same spectral Hm0 as Hs(x, y), so a regular wave of
//                  height H gives sqrt(2) H on both sides and K is the height ratio), or for a split
//                  spectrum the baked part's `spectrum_split.bake_significant_wave_height_m`;
//                  AgitationOptions::incident_significant_wave_height_m overrides it.
// K includes everything between the wave maker and the cell: shoaling and refraction on the
// approach as well as diffraction, transmission and reflection by the structures.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/raster.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::exports {

/// The wave maker's significant height recorded in a manifest's wave_conditions (see (1)): the
/// baked part of a split spectrum, else 4 sqrt(sum a^2 / 2) of the recorded components. nullopt
/// when the record holds neither (a time-series maker, a hand-written sequence).
std::optional<double> recorded_incident_significant_wave_height_m(const nlohmann::json& wave_conditions);

/// The significant wave height of every cell of a sequence, and where it came from.
struct SignificantWaveHeight {
  Raster<float> significant_wave_height_m;  ///< NaN on land and outside the chart
  std::string source;  ///< "bake statistics (wave_statistics.tif, N solver steps)" or "frames A-B (N frames)"
};

/// Hs of the frames [first_frame, end_frame) of `reader`: the bake's wave_statistics.tif band 2
/// when `first_frame` = 0, `end_frame` = the frame count and the file is in the folder (every
/// solver step, not only the frames), else 4 standard deviations of eta over those frames. Throws
/// nearshore::Error naming wave_statistics.tif when it is unreadable or not of the grid's size.
SignificantWaveHeight sequence_significant_wave_height(const sequence::SequenceReader& reader, const HarbourGrid& harbour,
                                                       int first_frame, int end_frame);

/// (1) over the grid: NaN where Hs is NaN (land, no data).
Raster<float> agitation_coefficient(const Raster<float>& significant_wave_height_m, double incident_significant_wave_height_m);

/// A named place where a ship lies, in the grid frame: metres from the grid's south-west corner
/// (x east, y north), as the case files' gauges are placed.
struct Berth {
  std::string name;
  double x_m = 0.0, y_m = 0.0;
  std::optional<double> longitude_deg, latitude_deg;  ///< when the file gave them
  std::string place;  ///< "berths.csv:4": where the file defines it, for messages
};

/// Reads berths from `file`:
///   - CSV (.csv, .txt) with the header `name,x_m,y_m` (grid frame) or `name,longitude,latitude`
///     (WGS 84 degrees, projected with the grid's projection); blank lines and lines starting
///     with '#' are skipped;
///   - GeoJSON (.geojson, .json): a FeatureCollection of Point features, RFC 7946 longitude and
///     latitude, each with a string property `name`.
/// Throws nearshore::Error naming the file and line (or feature) and the fix for any other header,
/// a missing or non-numeric field, an empty or repeated name, longitude/latitude on a grid without
/// a projection, a file with no berth.
std::vector<Berth> read_berths(const std::filesystem::path& file, const GridGeometry& geometry);

/// `field` at (x_m, y_m) of the grid frame, bilinear between the four cell centres around it over
/// the wet ones only (water cells with a finite value; the weights of the others are dropped and
/// the rest renormalised), so a quay's land never pulls a berth's value down. nullopt when the
/// point lies outside the grid or in a cell that is land or outside the chart.
std::optional<double> wet_bilinear_value(const Raster<float>& field, const HarbourGrid& harbour, double x_m, double y_m);

/// Hs and K at one berth.
struct BerthValue {
  Berth berth;
  double significant_wave_height_m = 0.0;
  double agitation_coefficient = 0.0;
};

/// Hs and K (1) at each berth (wet_bilinear_value). Throws nearshore::Error naming the berth, its
/// place in its file and its position for a berth outside the grid or on land.
std::vector<BerthValue> berth_values(const std::vector<Berth>& berths, const Raster<float>& significant_wave_height_m,
                                     double incident_significant_wave_height_m, const HarbourGrid& harbour);

/// {"name", "x_m", "y_m", ["longitude", "latitude"], "significant_wave_height_m", "agitation_coefficient"}.
nlohmann::json berth_value_json(const BerthValue& value);

}  // namespace nearshore::exports
