// [wave_maker] of a case file (docs/commands/bake.md): the kinds, their keys and the checks that the
// grid carries the waves asked for.
#include "nearshore/bake/bake_time_series.hpp"
#include "nearshore/ocean/sea_state_builder.hpp"
#include "nearshore/ocean/spectrum_files.hpp"
#include "nearshore/ocean/spectrum_netcdf.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/core.h>

#include "nearshore/boussinesq/model_dispersion.hpp"
#include "nearshore/core/error.hpp"
#include "case_reader.hpp"

namespace nearshore::bake::detail {

using namespace nearshore::ocean;       // spectra, sea states, the deep-water field
using namespace nearshore::boussinesq;  // the solver and its parameters

namespace {

// ---- plausibility bounds of the waves a maker makes (docs/commands/bake.md, "Bounds") ------------
// Above 10 Hz (1.6 cm long in deep water) surface tension, which the equations leave out, governs
// the waves: capillary ripples, no wave a harbour bake makes. A period or loop longer than a day is
// a tide or a typing error, and 1e308 Hz or s overflowed the sea-state builder (found by the
// case-file fuzzer).
constexpr double kHighestWaveFrequency_hz = 10.0;
constexpr double kLongestPeriod_s = 86400.0;
constexpr const char* kFrequencyBoundReason = "above 10 Hz (1.6 cm waves) surface tension, which the solver leaves out, governs";
constexpr const char* kPeriodBoundReason = "a day; a longer period or loop is no wave a harbour bake makes";

double read_wave_period_s(TableReader& reader, const std::string& key, std::optional<double> fallback) {
  const double period_s = reader.positive(key, fallback, "wave period in seconds");
  if (period_s < 1.0 / kHighestWaveFrequency_hz || period_s > kLongestPeriod_s)
    reader.fail(reader.full(key), fmt::format("= {} s is outside {} .. {:.0f} s ({}; at most {})", period_s,
                                              1.0 / kHighestWaveFrequency_hz, kLongestPeriod_s, kFrequencyBoundReason,
                                              kPeriodBoundReason),
                "give the wave period in seconds");
  return period_s;
}

// No wave on record is higher than about 30 m (the Draupner wave 25.6 m, 1995; the highest
// significant wave height measured is 19 m, North Atlantic 2013, whose highest single waves are
// about 1.9 Hs): a height above 40 m is a wrong unit or a typing error, and the solver then blew up
// with a message that blamed the time step (issue 44).
constexpr double kHighestWaveHeight_m = 40.0;
constexpr const char* kHeightBoundReason =
    "no wave on record is higher than about 30 m (Draupner 25.6 m; the highest significant wave height measured is 19 m)";

double read_wave_height_m(TableReader& reader, const std::string& key, const std::string& meaning, double factor = 1.0) {
  const double value = reader.positive(key, std::nullopt, meaning);
  if (value * factor > kHighestWaveHeight_m)
    reader.fail(reader.full(key), fmt::format("= {} m is above {:.0f} m ({})", value, kHighestWaveHeight_m / factor, kHeightBoundReason),
                "give the " + meaning);
  return value;
}

// A ramp longer than a day never lets the waves reach their height in any bake (1e308 s was taken
// silently, issue 44); the bake's own duration bounds it further (bake_case.cpp).
double read_ramp_time_s(TableReader& reader) {
  const double ramp_s = reader.non_negative("ramp_time_s", 0.0, "smooth start in seconds");
  if (ramp_s > kLongestPeriod_s)
    reader.fail(reader.full("ramp_time_s"),
                fmt::format("= {} s is above {:.0f} s (a day: the waves would not reach their height in any bake)", ramp_s,
                            kLongestPeriod_s),
                "give the smooth start in seconds: a few wave periods");
  return ramp_s;
}

double read_loop_period_s(TableReader& reader) {
  const double loop_s = reader.non_negative("loop_period_s", 0.0, "loop period in seconds (0 = not periodic)");
  if (loop_s > kLongestPeriod_s)
    reader.fail(reader.full("loop_period_s"), fmt::format("= {} s is above {:.0f} s ({})", loop_s, kLongestPeriod_s, kPeriodBoundReason),
                "give the loop period in seconds (minutes are typical: 600 s in the demo harbour)");
  return loop_s;
}

double read_wave_frequency_hz(TableReader& reader, const std::string& key, std::optional<double> fallback, bool zero_allowed) {
  const double frequency_hz = zero_allowed ? reader.non_negative(key, fallback, "frequency in Hz")
                                           : reader.positive(key, fallback, "frequency in Hz");
  if (frequency_hz > kHighestWaveFrequency_hz || (frequency_hz > 0 && frequency_hz < 1.0 / kLongestPeriod_s))
    reader.fail(reader.full(key), fmt::format("= {} Hz is outside {:.3g} .. {} Hz ({}; periods at most {})", frequency_hz,
                                              1.0 / kLongestPeriod_s, kHighestWaveFrequency_hz, kFrequencyBoundReason,
                                              kPeriodBoundReason),
                "give the frequency in Hz");
  return frequency_hz;
}

// Waves of the regular and `components` kinds as linear components; checks the loop period.
void check_loop_period(TableReader& maker, const std::string& key, double loop_period_s, double period_s) {
  const long cycles = whole_steps(loop_period_s, period_s);
  if (cycles < 1)
    maker.fail(maker.full(key), fmt::format("= {} s does not repeat in wave_maker.loop_period_s = {} s ({:.4f} cycles)",
                                            period_s, loop_period_s, loop_period_s / period_s),
               fmt::format("make every period divide the loop period, e.g. loop_period_s = {} s",
                           period_s * std::max(1.0, std::round(loop_period_s / period_s))));
}

// The grid can carry a component only if it is long enough: k d <= 3 over the deepest water the
// solver sees (the range Madsen & Sorensen 1992 give B = 1/15; its phase speed is then within
// 4.1 % of Airy at a given frequency, model_dispersion.hpp) and at least `cells_per_wavelength`
// cells per wavelength. Over a channel deeper than that, an effective-depth limit (docs/solver.md,
// "Effective depth") lets shorter waves through. Shorter waves are not waves the bake can make:
// they alias, or travel at the wrong speed; an irregular sea leaves them to the deep-water layer.
}  // namespace

namespace {

// The deepest water the solver sees for a band reaching `highest_rad_s`.
double seen_depth_m(const HarbourGrid& grid, double highest_rad_s, const DispersionBound& bound) {
  const double deepest_m = std::max(deepest_still_water_m(grid), 1e-3);
  const double limit_m = bound.effective_depth_limit_given ? bound.effective_depth_limit_m
                                                           : automatic_effective_depth_limit_m(grid, highest_rad_s);
  return limit_m > 0.0 ? std::min(deepest_m, limit_m) : deepest_m;
}

}  // namespace

double automatic_effective_depth_limit_m(const HarbourGrid& grid, double highest_rad_s) {
  if (!(highest_rad_s > 0.0)) return 0.0;
  // Active only where the grid is deeper than the limit by more than round-off: a band that ends
  // exactly at k d = 3 over the deepest cell (the default band of a "deep_water" maker) needs none.
  const double limit_m = effective_depth_limit_m(highest_rad_s);
  return limit_m < deepest_still_water_m(grid) * (1 - 1e-6) ? limit_m : 0.0;
}

double highest_carried_frequency_rad_s(const HarbourGrid& grid, int cells_per_wavelength, double lowest_rad_s,
                                       const DispersionBound& bound) {
  const double deepest_m = std::max(deepest_still_water_m(grid), 1e-3);
  // Rectangular cells: the larger size counts, since a component may travel along either axis.
  const double coarser_spacing_m = std::max(grid.geometry.spacing_x_m(), grid.geometry.spacing_y_m());
  const double k_grid = 2 * std::numbers::pi / (cells_per_wavelength * coarser_spacing_m);
  if (bound.effective_depth_limit_given) {
    const double seen_m = seen_depth_m(grid, 0.0, bound);
    return frequency_from_wavenumber(std::min(kLargestCarriedKd / seen_m, k_grid), seen_m);
  }
  // Derived limit: the dispersion bound first, then the grid's, over the depth the solver would see
  // for that band (a shallower limit shortens the wavelength of a frequency, so the grid's bound
  // falls; a few rounds settle it, each lowering the frequency and deepening the limit).
  const double dispersion_rad_s = highest_frequency_over_effective_depth_rad_s(lowest_rad_s, deepest_m, bound.dispersion_coefficient);
  double w = std::min(dispersion_rad_s, frequency_from_wavenumber(k_grid, deepest_m));
  for (int round = 0; round < 20; ++round) {
    const double next = std::min(dispersion_rad_s, frequency_from_wavenumber(k_grid, seen_depth_m(grid, w, bound)));
    if (std::abs(next - w) <= 1e-12 * w) break;
    w = next;
  }
  return w;
}

std::string carried_band_reason(const HarbourGrid& grid, int cells_per_wavelength, double lowest_rad_s,
                                const DispersionBound& bound) {
  const GridGeometry& g = grid.geometry;
  const double deepest_m = deepest_still_water_m(grid);
  const double seen_m = seen_depth_m(grid, highest_carried_frequency_rad_s(grid, cells_per_wavelength, lowest_rad_s, bound), bound);
  const std::string depth =
      seen_m < deepest_m
          ? (bound.effective_depth_limit_given
                 ? fmt::format("k d <= 3 over solver.effective_depth_limit_m = {:.1f} m (the deepest water is {:.2f} m)", seen_m,
                               deepest_m)
                 : fmt::format("k d <= 3 over an effective-depth limit no shallower than {:.1f} m, where the band's longest wave "
                               "keeps within {:.1f} % of Airy over the deepest {:.2f} m",
                               seen_m, 100 * carried_phase_speed_tolerance(bound.dispersion_coefficient), deepest_m))
          : fmt::format("k d <= 3 at the deepest {:.2f} m", deepest_m);
  if (!g.square_cells())
    return fmt::format("{} and {} cells per wavelength on the larger side of {} m x {} m cells", depth, cells_per_wavelength,
                       g.spacing_x_m(), g.spacing_y_m());
  return fmt::format("{} and {} cells of {} m per wavelength", depth, cells_per_wavelength, g.spacing_m);
}

namespace {

double significant_height_m(const std::vector<WaveComponent>& components) {
  double variance_m2 = 0.0;
  for (const WaveComponent& c : components) variance_m2 += 0.5 * c.amplitude_m * c.amplitude_m;
  return 4.0 * std::sqrt(variance_m2);
}

// An irregular sea is split, not refused (issue 14): the bake keeps the components the grid
// carries, the FFT deep-water layer draws the rest. Refused only when the grid carries none.
SpectrumSplit split_carried(TableReader& maker, SeaState& sea, const HarbourGrid& grid, int cells_per_wavelength,
                            const DispersionBound& bound) {
  double lowest = std::numeric_limits<double>::infinity(), highest = 0.0;
  for (const WaveComponent& component : sea.components)
    lowest = std::min(lowest, component.angular_frequency_rad_s), highest = std::max(highest, component.angular_frequency_rad_s);
  const double w_max = highest_carried_frequency_rad_s(grid, cells_per_wavelength, lowest, bound);
  SpectrumSplit split;
  split.reason = carried_band_reason(grid, cells_per_wavelength, lowest, bound);
  split.total_significant_height_m = significant_height_m(sea.components);
  constexpr double kHz = 0.5 / std::numbers::pi;
  if (lowest > w_max * (1 + 1e-9)) {
    // Nothing to bake: the whole band lies above what the grid carries. Name the cell size that
    // would carry the spectrum's lowest frequency.
    const double seen_m = std::min(static_cast<double>(deepest_still_water_m(grid)),
                                   std::max(automatic_effective_depth_limit_m(grid, lowest), 1e-3));
    const double needed_spacing_m = 2 * std::numbers::pi / wavenumber_from_frequency(lowest, seen_m) / cells_per_wavelength;
    maker.fail("wave_maker",
               fmt::format("(irregular) has components from {:.3f} Hz to {:.3f} Hz, all above the {:.3f} Hz the grid carries ({})",
                           lowest * kHz, highest * kHz, w_max * kHz, split.reason),
               fmt::format("use cells of at most {:.2f} m, or fewer cells per wavelength (wave_maker.min_cells_per_wavelength)",
                           needed_spacing_m));
  }
  std::vector<WaveComponent> carried, left;
  for (const WaveComponent& component : sea.components)
    (component.angular_frequency_rad_s <= w_max * (1 + 1e-9) ? carried : left).push_back(component);
  sea.components = std::move(carried);
  double band_top = 0.0;
  for (const WaveComponent& component : sea.components) band_top = std::max(band_top, component.angular_frequency_rad_s);
  split.min_frequency_hz = lowest * kHz;
  split.max_frequency_hz = band_top * kHz;
  split.bake_components = static_cast<int>(sea.components.size());
  split.left_components = static_cast<int>(left.size());
  double left_bottom = std::numeric_limits<double>::infinity();
  for (const WaveComponent& component : left) left_bottom = std::min(left_bottom, component.angular_frequency_rad_s);
  split.left_min_frequency_hz = left.empty() ? split.max_frequency_hz : left_bottom * kHz;
  split.bake_significant_height_m = significant_height_m(sea.components);
  split.left_significant_height_m = significant_height_m(left);
  return split;
}

WaveComponent component_from(TableReader& reader, const std::string& amplitude_key, double amplitude_factor,
                             double default_direction_rad) {
  WaveComponent component;
  // An amplitude is half a height: both are bounded as heights.
  component.amplitude_m =
      amplitude_factor * read_wave_height_m(reader, amplitude_key,
                                            amplitude_key == "height_m" ? "wave height in metres" : "amplitude in metres",
                                            amplitude_key == "height_m" ? 1.0 : 2.0);
  component.angular_frequency_rad_s = 2.0 * std::numbers::pi / read_wave_period_s(reader, "period_s", std::nullopt);
  component.direction_rad = reader.number("direction_deg", default_direction_rad / kDegree, -360.0, 360.0, false,
                                          "direction of travel in degrees counter-clockwise from +x (east)") * kDegree;
  component.phase_rad = reader.number("phase_deg", 0.0, -360.0, 360.0, false, "phase in degrees") * kDegree;
  return component;
}

/// [wave_maker] spectrum_file (+ spectrum_format, spectrum_location, spectrum_time): the sea of a
/// SWAN .sp2 or of an NDBC buoy's five spectral files, as the builder's specification (the file's
/// band; the counts, loop and seed are read as for a parametric sea).
DirectionalSeaSpecification read_spectrum_file(TableReader& maker, const fs::path& base) {
  const fs::path file = maker.path("spectrum_file", base);
  const std::size_t format = maker.choice("spectrum_format", "swan_sp2", {"swan_sp2", "ndbc", "swan_netcdf", "ww3_netcdf"});
  const bool netcdf = format >= 2;
  std::string time;
  std::size_t time_index = 0;
  if (netcdf) {
    // A NetCDF file's times are numbers in its own units: chosen by index.
    if (maker.has("spectrum_time"))
      maker.fail(maker.full("spectrum_time"), "is for the text formats; a NetCDF file's time is chosen by index",
                 "give spectrum_time_index (1 = the first time)");
    time_index = static_cast<std::size_t>(maker.integer("spectrum_time_index", 1, 1, 100000000, "time in the NetCDF file, 1 = the first")) - 1;
  } else {
    time = maker.string("spectrum_time", std::string(),
                        "time as the file writes it: \"20020101.000000\" (SWAN), \"YYYY MM DD hh mm\" (NDBC)");
  }
  std::size_t location_index = 0;
  if (format != 1)
    location_index = static_cast<std::size_t>(
        maker.integer("spectrum_location", 1, 1, 10000000, "location in the file (SWAN's points, WW3's stations), 1 = the first")) - 1;
  auto sampled = std::make_shared<SampledDirectionalSpectrum>(maker.reading_file("spectrum_file", [&] {
    if (format == 0) {
      SwanSpectrumSelection swan;
      swan.time = time;
      swan.location_index = location_index;
      return read_swan_spectrum(file, swan);
    }
    if (netcdf)
      return read_netcdf_spectrum(file, {format == 3 ? NetcdfSpectrumLayout::kWavewatch3 : NetcdfSpectrumLayout::kSwan,
                                         location_index, time_index});
    // NDBC's realtime2 files of one buoy share their name: 46087.data_spec, .swdir, .swdir2, .swr1, .swr2.
    const auto sibling = [&](const char* extension) { return fs::path(file).replace_extension(extension); };
    NdbcSpectrumSelection ndbc;
    ndbc.time = time;
    return read_ndbc_spectrum({file, sibling(".swdir"), sibling(".swdir2"), sibling(".swr1"), sibling(".swr2")}, ndbc);
  }));
  return sea_specification_from_sampled(sampled);
}

// ---- the wet span a source line keeps to (issue 46; docs/solver.md, "Wave maker") ----------------
// A run of cells along the source line that the solver counts as water (still-water depth above
// 0 m, boussinesq_source.cpp): cells [begin, end) along the line.
struct WetSpan {
  int begin = 0, end = 0;
};

// The grid line of the source: the solver's cell index round((line - origin) / dx - 0.5).
int source_line_cell(const HarbourGrid& grid, bool along_x, double position_m) {
  const GridGeometry& g = grid.geometry;
  const double origin_m = along_x ? g.origin_x_m : g.origin_y_m, spacing_m = along_x ? g.spacing_x_m() : g.spacing_y_m();
  return std::clamp(static_cast<int>(std::lround((position_m - origin_m) / spacing_m - 0.5)), 0,
                    (along_x ? g.columns : g.rows) - 1);
}

std::vector<WetSpan> wet_spans(const HarbourGrid& grid, bool along_x, int line) {
  const int count = along_x ? grid.geometry.rows : grid.geometry.columns;
  std::vector<WetSpan> spans;
  for (int t = 0; t < count; ++t) {
    const bool wet = (along_x ? grid.still_water_depth_m(line, t) : grid.still_water_depth_m(t, line)) > 0.0f;
    if (!wet) continue;
    if (spans.empty() || spans.back().end != t) spans.push_back({t, t});
    spans.back().end = t + 1;
  }
  return spans;
}

// "cells 0-636 of the line, x = 0-2930 m from the south-west corner (2930 m)".
std::string describe_span(const HarbourGrid& grid, bool along_x, const WetSpan& span) {
  const double spacing_m = along_x ? grid.geometry.spacing_y_m() : grid.geometry.spacing_x_m();
  return fmt::format("cells {}-{} ({} = {:.0f}-{:.0f} m from the south-west corner, {:.0f} m long)", span.begin, span.end - 1,
                     along_x ? "y" : "x", span.begin * spacing_m, span.end * spacing_m, (span.end - span.begin) * spacing_m);
}

std::string describe_spans(const HarbourGrid& grid, bool along_x, const std::vector<WetSpan>& spans) {
  std::string text;
  for (std::size_t i = 0; i < spans.size(); ++i)
    text += fmt::format("{}{}", i == 0 ? "" : "; ", describe_span(grid, along_x, spans[i]));
  return text;
}

// Why a line over several wet spans is refused, for the messages.
constexpr const char* kDisconnectedSpanReason =
    "a source on water cut off from the rest by land (a cove behind a headland) radiates waves of its own "
    "that no offshore sea sends there; docs/solver.md, \"Wave maker\"";

// `boundary = "north"`: the line parallel to that side, inside the grid by the side's sponge width and
// source_offset_m more, so that the source's Gaussian strip (half-width 0.67 L of its peak wave,
// boussinesq_source.cpp) lies clear of the sponge: the sponge behind the line absorbs the half of
// the waves the source sends backwards, and the waves reflected in the harbour leave through it.
void place_along_boundary(TableReader& maker, const HarbourGrid& grid, const std::vector<SpongeLayer>& sponges, WaveMaker& wave_maker) {
  const Side side = wave_maker.facing;
  double sponge_width_m = 0.0;
  for (const SpongeLayer& sponge : sponges)
    if (sponge.side == side) sponge_width_m = std::max(sponge_width_m, sponge.width_m);
  if (!(sponge_width_m > 0.0))
    maker.fail(maker.full("boundary"),
               fmt::format("= \"{}\" has no sponge behind the source line: the half of the waves the source sends towards "
                           "the boundary would reflect off the grid's edge back into the harbour",
                           side_name(side)),
               fmt::format("add [[sponges]] side = \"{}\" with width_m of a wavelength or more", side_name(side)));
  // The default offset: the deep-water wavelength g T^2 / (2 pi) of the largest component, the
  // longest any depth gives that period, so the strip's 0.67 L clears the sponge by a third of a
  // wavelength or more. Kinds whose components are not known here (deep_water: the field's;
  // time_series) need it given.
  double peak_rad_s = 0.0, largest_m = 0.0;
  for (const WaveComponent& c : wave_maker.sea_state.components)
    if (c.amplitude_m > largest_m) largest_m = c.amplitude_m, peak_rad_s = c.angular_frequency_rad_s;
  const bool along_x = side == Side::kWest || side == Side::kEast;
  const double extent_m = along_x ? grid.geometry.width_m() : grid.geometry.height_m();
  std::optional<double> fallback_m;
  if (peak_rad_s > 0.0) fallback_m = 2.0 * std::numbers::pi * kGravity_m_s2 / (peak_rad_s * peak_rad_s);
  const double offset_m =
      maker.non_negative("source_offset_m", fallback_m,
                         "distance of the source line from the sponge's inner edge, metres (default: the peak wave's "
                         "deep-water wavelength; required for kinds whose waves are not known from [wave_maker])");
  const double inset_m = sponge_width_m + offset_m;
  if (inset_m >= extent_m)
    maker.fail(maker.full("boundary"),
               fmt::format("= \"{}\" puts the source line {:.1f} m inside the grid (sponge {:.1f} m + source_offset_m {:.1f} m), "
                           "beyond its {:.1f} m",
                           side_name(side), inset_m, sponge_width_m, offset_m, extent_m),
               "give a smaller source_offset_m or a narrower sponge");
  const GridGeometry& g = grid.geometry;
  const double origin_m = along_x ? g.origin_x_m : g.origin_y_m;
  const bool from_low_edge = side == Side::kWest || side == Side::kSouth;
  wave_maker.source_line_m = from_low_edge ? origin_m + inset_m : origin_m + extent_m - inset_m;
}

// The source keeps to one wet span of its line (WaveMaker::span_begin_cell): the one holding the
// source_line point, or the line's only one. A line over several spans without a point to choose
// is refused, naming them: a span cut off by land radiates a sea of its own (kDisconnectedSpanReason).
void keep_to_wet_span(TableReader& maker, const HarbourGrid& grid, const std::optional<ProjectedPoint>& point,
                      bool along_boundary, WaveMaker& wave_maker, std::vector<std::string>& warnings) {
  const bool along_x = wave_maker.facing == Side::kWest || wave_maker.facing == Side::kEast;
  const GridGeometry& g = grid.geometry;
  const int line = source_line_cell(grid, along_x, wave_maker.source_line_m);
  const double line_from_corner_m = wave_maker.source_line_m - (along_x ? g.origin_x_m : g.origin_y_m);
  const std::string key = maker.full(along_boundary ? "boundary" : point ? "source_line" : "source_line_m");
  const std::string where = fmt::format("the source line ({} = {:.1f} m from the south-west corner, grid {} {})", along_x ? "x" : "y",
                                        line_from_corner_m, along_x ? "column" : "row", line);
  const std::vector<WetSpan> spans = wet_spans(grid, along_x, line);
  if (spans.empty())
    maker.fail(key, fmt::format("puts {} over land or outside the chart along its whole length", where),
               along_boundary ? "give the side of the grid the sea comes from, or a smaller source_offset_m"
                              : "move it into open water");
  WetSpan chosen = spans.front();
  // The span holding the point; a point on land (read_case_position warned of it) holds none, and
  // the line's only span is taken, as for source_line_m.
  std::optional<WetSpan> holding;
  if (point) {
    const double spacing_m = along_x ? g.spacing_y_m() : g.spacing_x_m();
    const int t = static_cast<int>(std::floor(((along_x ? point->y_m - g.origin_y_m : point->x_m - g.origin_x_m)) / spacing_m));
    for (const WetSpan& s : spans)
      if (t >= s.begin && t < s.end) holding = s;
    if (!holding && spans.size() > 1)
      maker.fail(key,
                 fmt::format("is a point on land or outside the chart (cell {} along {}), which holds none of the line's {} wet "
                             "spans ({}): {}",
                             t, where, spans.size(), kDisconnectedSpanReason, describe_spans(grid, along_x, spans)),
                 "give a point in the open water the source is meant for");
  }
  if (holding) {
    chosen = *holding;
    if (spans.size() > 1) {
      std::vector<WetSpan> others;
      for (const WetSpan& s : spans)
        if (s.begin != chosen.begin) others.push_back(s);
      warnings.push_back(fmt::format(
          "{}: key `{}`: the source keeps to the wet span holding the point, {}; the line's other wet spans get no source "
          "({}): {}",
          maker.subject(), key, describe_span(grid, along_x, chosen), kDisconnectedSpanReason,
          describe_spans(grid, along_x, others)));
    }
  } else if (spans.size() > 1) {
    maker.fail(key,
               fmt::format("puts {} over {} wet spans cut off from each other by land ({}): {}", where, spans.size(),
                           kDisconnectedSpanReason, describe_spans(grid, along_x, spans)),
               along_boundary
                   ? "make the boundary one stretch of water: crop the grid (BathyRequest::bbox_lon_lat) or move the line "
                     "(sponge width, source_offset_m) to where the water is one span"
                   : "give source_line = { lat = ..., lon = ... } (or x_m/y_m) at a point of the span to feed, or boundary = "
                     "\"<side>\" for a source along the open boundary in front of its sponge");
  }
  wave_maker.span_begin_cell = chosen.begin;
  wave_maker.span_end_cell = chosen.end;
  // A line mostly over land makes its waves on the few wet cells left, which is rarely what was
  // meant: warn, naming the share and a depth.
  const int count = along_x ? g.rows : g.columns;
  int dry = 0;
  float highest_m = std::numeric_limits<float>::infinity();
  for (int t = 0; t < count; ++t) {
    const int column = along_x ? line : t, row = along_x ? t : line;
    if (grid.land(column, row)) ++dry, highest_m = std::min(highest_m, grid.still_water_depth_m(column, row));
  }
  if (2 * dry > count)
    warnings.push_back(fmt::format(
        "{}: key `{}` puts {} over land or outside the chart for {} of its {} cells ({:.0f} %; ground up to {:.2f} m above still "
        "water there): it makes waves only on the {} wet cells of its span, {}; move it into open water",
        maker.subject(), key, where, dry, count, 100.0 * dry / count, -highest_m, chosen.end - chosen.begin,
        describe_span(grid, along_x, chosen)));
}

}  // namespace

WaveMaker read_wave_maker(TableReader& maker, const HarbourGrid& grid, const fs::path& base,
                          const DispersionBound& bound, const std::vector<SpongeLayer>& sponges, MakerRequest& request) {
  WaveMaker wave_maker;
  const auto kind = static_cast<MakerKind>(maker.choice("kind", std::nullopt, kMakerKindNames));
  if (kind == MakerKind::kNone) return wave_maker;
  // `boundary = "north"`: the source along that open boundary, in front of its sponge, over the
  // boundary's whole wet span (placed once the sea is known, below). It sets `facing`.
  const bool along_boundary = kind != MakerKind::kSolitary && maker.has("boundary");
  if (along_boundary) {
    wave_maker.facing = side_from_index(maker.choice("boundary", std::nullopt, kSideNames));
    if (maker.has("facing") && side_from_index(maker.choice("facing", std::nullopt, kSideNames)) != wave_maker.facing)
      maker.fail(maker.full("facing"), "differs from wave_maker.boundary, whose side the waves come from",
                 "leave facing out (boundary sets it)");
    for (const char* key : {"source_line", "source_line_m"})
      if (maker.has(key))
        maker.fail(maker.full(key), "is given with wave_maker.boundary, which places the source line in front of the sponge",
                   "give one: boundary, or facing and a source line");
  } else {
    wave_maker.facing = side_from_index(maker.choice("facing", std::nullopt, kSideNames));
  }
  const bool along_x = wave_maker.facing == Side::kWest || wave_maker.facing == Side::kEast;
  const double extent_m = along_x ? grid.geometry.width_m() : grid.geometry.height_m();
  const double origin_m = along_x ? grid.geometry.origin_x_m : grid.geometry.origin_y_m;
  const std::string where = kind == MakerKind::kSolitary ? "crest_position_m" : "source_line_m";
  // Case positions are metres from the grid's south-west corner; the solver's frame includes the origin.
  // Or a point the source line passes through, [wave_maker.source_line] in any frame of
  // core/geo_position.hpp (lat/lon, the grid's CRS): the line runs parallel to the `facing` side.
  double position_m = 0.0;
  std::optional<ProjectedPoint> line_point;  // source_line = { ... }: the point whose wet span the source keeps to
  if (along_boundary) {
    // Placed below, once the sea's wavelength is known.
  } else if (kind != MakerKind::kSolitary && maker.has("source_line")) {
    if (maker.has("source_line_m"))
      maker.fail(maker.full("source_line"), "and source_line_m are both given",
                 "give one: source_line_m (metres from the south-west corner) or source_line = { lat = ..., lon = ... }");
    TableReader point_table = maker.table("source_line");
    const ProjectedPoint point = read_case_position(point_table, grid, "key `" + maker.full("source_line") + "`", request.warnings);
    point_table.finish();
    position_m = along_x ? point.x_m : point.y_m;
    line_point = point;
  } else {
    position_m = origin_m + maker.number(where, std::nullopt, 0.0, extent_m, false,
                                         fmt::format("position along {} from the south-west corner, inside the grid, metres "
                                                     "(or source_line = {{ lat = ..., lon = ... }})",
                                                     along_x ? "x" : "y"));
  }
  wave_maker.source_line_m = position_m;
  wave_maker.ramp_time_s = read_ramp_time_s(maker);
  const double default_direction_rad = direction_away_from(wave_maker.facing);
  SeaState& sea = wave_maker.sea_state;
  if (kind == MakerKind::kRegular) {
    wave_maker.kind = WaveMaker::Kind::kComponents;
    const double height_m = read_wave_height_m(maker, "height_m", "wave height (crest to trough) in metres");
    const double period_s = read_wave_period_s(maker, "period_s", std::nullopt);
    const double direction_rad = kDegree * maker.number("direction_deg", default_direction_rad / kDegree, -360.0, 360.0, false,
                                                        "direction of travel in degrees counter-clockwise from +x (east)");
    const double phase_rad = kDegree * maker.number("phase_deg", 0.0, -360.0, 360.0, false, "phase in degrees");
    sea = regular_wave_sea_state(height_m, period_s, direction_rad, phase_rad);
    // Second-order generation (WaveMaker::second_order; docs/solver.md "Wave maker").
    wave_maker.second_order = maker.boolean("second_order", wave_maker.second_order);
    sea.loop_period_s = read_loop_period_s(maker);
    if (sea.loop_period_s > 0) check_loop_period(maker, "period_s", sea.loop_period_s, period_s);
  } else if (kind == MakerKind::kIrregular) {
    wave_maker.kind = WaveMaker::Kind::kComponents;
    DirectionalSeaSpecification specification;
    const bool from_file = maker.has("spectrum_file");
    double spreading_s = 0.0;
    if (from_file) {
      // A wave model's or a buoy's spectrum (ocean/spectrum_files.hpp): it sets the shape, the
      // directions and the band; the parametric keys would contradict it.
      for (const char* key : {"spectrum", "mean_direction_deg", "spreading_s", "significant_height_m", "peak_period_s"})
        if (maker.has(key))
          maker.fail(maker.full(key), "is given with spectrum_file, whose spectrum sets the sea",
                     "remove it, or remove spectrum_file to use a parametric spectrum");
      specification = read_spectrum_file(maker, base);
    } else {
      specification.spectrum = read_frequency_spectrum(maker, "spectrum", "jonswap");
      const double mean_direction_rad = kDegree * maker.number("mean_direction_deg", default_direction_rad / kDegree, -360.0, 360.0,
                                                               false, "mean direction of travel in degrees counter-clockwise from +x");
      spreading_s = maker.non_negative("spreading_s", 0.0, "cos^2s exponent s (0 = long-crested)");
      specification.spreading = std::make_shared<CosineSquaredSpreading>(mean_direction_rad, std::max(spreading_s, 1.0));
    }
    specification.frequency_count = maker.integer("frequency_count", 64, 1, 100000, "number of frequency components");
    specification.direction_count =
        maker.integer("direction_count", from_file || spreading_s > 0 ? 16 : 1, 1, 10000, "number of directions");
    // The source function sums every component at every source cell every step: 1e5 components
    // on a 1000-cell source line are 1e8 evaluations a step, far beyond what a bake can afford.
    constexpr long kMostComponents = 100000;
    if (static_cast<long>(specification.frequency_count) * specification.direction_count > kMostComponents)
      maker.fail(maker.full("frequency_count"),
                 fmt::format("x wave_maker.direction_count = {} x {} = {} components, more than {} (the source function "
                             "sums every one at every source cell every step)",
                             specification.frequency_count, specification.direction_count,
                             static_cast<long>(specification.frequency_count) * specification.direction_count, kMostComponents),
                 "use fewer frequencies or directions (64 x 16 is plenty for a short-crested sea)");
    if (!from_file && spreading_s == 0 && specification.direction_count != 1)
      maker.fail(maker.full("direction_count"), "is above 1 for a long-crested sea (spreading_s = 0)", "set spreading_s > 0 or direction_count = 1");
    specification.loop_period_s = read_loop_period_s(maker);
    specification.seed = maker.unsigned_integer("seed", 1, "phase seed");
    if (maker.has("min_frequency_hz") || maker.has("max_frequency_hz")) {
      specification.min_frequency_rad_s = 2 * std::numbers::pi * read_wave_frequency_hz(maker, "min_frequency_hz", std::nullopt, false);
      specification.max_frequency_rad_s = 2 * std::numbers::pi * read_wave_frequency_hz(maker, "max_frequency_hz", std::nullopt, false);
      // Checked here, so that the message names the case file's keys (the builder names its own).
      if (!(specification.max_frequency_rad_s > specification.min_frequency_rad_s))
        maker.fail(maker.full("min_frequency_hz"),
                   fmt::format("= {:.4g} Hz is not below wave_maker.max_frequency_hz = {:.4g} Hz",
                               specification.min_frequency_rad_s / (2 * std::numbers::pi),
                               specification.max_frequency_rad_s / (2 * std::numbers::pi)),
                   "give min_frequency_hz < max_frequency_hz, or leave both out (the band holding 99.5 % of the variance)");
    }
    request.spectrum = specification.spectrum;
    request.spreading = specification.spreading;
    request.long_crested = from_file ? specification.direction_count == 1 : spreading_s == 0;
    const int cells_per_wavelength = maker.integer("min_cells_per_wavelength", 8, 2, 1000, "cells per wavelength the grid must give every component");
    try {
      sea = build_sea_state(specification);
    } catch (const Error& error) {
      maker.fail("wave_maker", "(irregular) cannot be built: " + error.problem(), error.fix());
    }
    SpectrumSplit split = split_carried(maker, sea, grid, cells_per_wavelength, bound);
    if (split.left_components > 0) request.split = std::move(split);
  } else if (kind == MakerKind::kDeepWater) {
    // The components are the [deep_water] field's (read_deep_water, couple_wave_maker): here only
    // the loop period both share and the band of the field the grid carries.
    wave_maker.kind = WaveMaker::Kind::kComponents;
    request.from_deep_water = true;
    sea.loop_period_s = read_loop_period_s(maker);
    const int cells_per_wavelength = maker.integer("min_cells_per_wavelength", 8, 2, 1000,
                                                   "cells per wavelength the grid must give every component");
    request.band.min_frequency_rad_s = 2 * std::numbers::pi * read_wave_frequency_hz(maker, "min_frequency_hz", 0.0, true);
    // A periodic field puts every wave on a harmonic of 2 pi / T; those below half the fundamental
    // land on frequency 0, a frozen surface with an infinite wavelength that no maker can make (it
    // hung the coupling's blending-zone search: found by the case-file fuzzer with loop_period_s = 3).
    if (sea.loop_period_s > 0)
      request.band.min_frequency_rad_s = std::max(request.band.min_frequency_rad_s, std::numbers::pi / sea.loop_period_s);
    // The band's lowest frequency bounds how shallow an effective-depth limit may be (0: no limit).
    // The default top stays what the grid carries without a limit (a case that leaves the band out
    // bakes as before the limit existed); a higher max_frequency_hz may reach what a limit carries.
    const double carried_rad_s = highest_carried_frequency_rad_s(grid, cells_per_wavelength, request.band.min_frequency_rad_s, bound);
    const double default_rad_s = std::min(carried_rad_s, highest_carried_frequency_rad_s(grid, cells_per_wavelength, 0.0, bound));
    request.band.max_frequency_rad_s =
        2 * std::numbers::pi * read_wave_frequency_hz(maker, "max_frequency_hz", std::min(default_rad_s / (2 * std::numbers::pi), kHighestWaveFrequency_hz), false);
    if (request.band.max_frequency_rad_s > carried_rad_s * (1 + 1e-9))
      maker.fail(maker.full("max_frequency_hz"),
                 fmt::format("= {:.4f} Hz is above what the grid carries ({:.4f} Hz: {})",
                             request.band.max_frequency_rad_s / (2 * std::numbers::pi),
                             carried_rad_s / (2 * std::numbers::pi),
                             carried_band_reason(grid, cells_per_wavelength, request.band.min_frequency_rad_s, bound)),
                 "leave max_frequency_hz out (the grid's limit is the default), or use a finer grid");
    if (!(request.band.max_frequency_rad_s > request.band.min_frequency_rad_s))
      maker.fail(maker.full("min_frequency_hz"), "is not below the highest frequency the maker makes",
                 "lower min_frequency_hz");
    // A narrower fan than the source line's 78 degrees, e.g. 0 in a flume whose side walls would
    // reflect oblique waves.
    const double max_angle_rad =
        kDegree * maker.number("max_angle_from_normal_deg", 78.0, 0.0, 78.0, false,
                               "largest angle between a made wave and the source line's normal, degrees");
    request.band.min_normal_fraction = std::max(request.band.min_normal_fraction, std::cos(max_angle_rad));
    if (maker.has("seed"))
      maker.fail(maker.full("seed"), "is the deep-water field's when kind = \"deep_water\"",
                 "move seed into [deep_water]");
  } else if (kind == MakerKind::kComponents) {
    wave_maker.kind = WaveMaker::Kind::kComponents;
    sea.loop_period_s = read_loop_period_s(maker);
    auto components = maker.tables("components");
    if (components.empty())
      maker.fail(maker.full("components"), "is missing or empty", "add [[wave_maker.components]] tables with amplitude_m and period_s");
    for (TableReader& entry : components) {
      sea.components.push_back(component_from(entry, "amplitude_m", 1.0, default_direction_rad));
      if (sea.loop_period_s > 0) check_loop_period(entry, "period_s", sea.loop_period_s, 2 * std::numbers::pi / sea.components.back().angular_frequency_rad_s);
      entry.finish();
    }
  } else if (kind == MakerKind::kTimeSeries) {
    wave_maker.kind = WaveMaker::Kind::kTimeSeries;
    TimeSeriesLayout layout;
    const fs::path file = maker.path("file", base);
    layout.time_column = maker.integer("time_column", 0, 0, 1000, "1-based time column (0 = none)");
    layout.elevation_column = maker.integer("elevation_column", layout.time_column > 0 ? 2 : 1, 1, 1000, "1-based elevation column");
    layout.sample_interval_s = maker.non_negative("sample_interval_s", 0.0, "sample spacing in seconds");
    layout.elevation_scale_to_m = maker.positive("elevation_scale_to_m", 1.0, "factor to metres (0.01 for cm)");
    layout.remove_mean = maker.boolean("remove_mean", true);
    if (layout.time_column == 0 && layout.sample_interval_s <= 0.0)
      maker.fail(maker.full("sample_interval_s"), "is missing and there is no time_column", "give sample_interval_s > 0 or time_column");
    TimeSeries series = maker.reading_file("file", [&] { return read_time_series(file, layout); });
    wave_maker.series_time_s = std::move(series.time_s);
    wave_maker.series_elevation_m = std::move(series.elevation_m);
  } else if (kind == MakerKind::kSolitary) {
    // Not a maker along a line: the solver starts from the wave (boussinesq/initial_conditions.hpp).
    request.solitary_wave = SolitaryWave{read_wave_height_m(maker, "height_m", "solitary wave height above still water, metres"),
                                         position_m, wave_maker.facing};
  }
  if (kind != MakerKind::kIrregular && kind != MakerKind::kDeepWater)
    sea.seed = maker.unsigned_integer("seed", 0, "phase seed (recorded; used by irregular seas)");
  if (kind != MakerKind::kSolitary) {
    if (along_boundary) place_along_boundary(maker, grid, sponges, wave_maker);
    keep_to_wet_span(maker, grid, line_point, along_boundary, wave_maker, request.warnings);
  }
  return wave_maker;
}

json wave_record(const WaveMaker& maker, const json& as_written) {
  json components = json::array();
  for (const WaveComponent& c : maker.sea_state.components)
    components.push_back({{"amplitude_m", c.amplitude_m},
                          {"angular_frequency_rad_s", c.angular_frequency_rad_s},
                          {"direction_rad", c.direction_rad},
                          {"phase_rad", c.phase_rad}});
  json record = {{"case", as_written}, {"components", components}, {"seed", maker.sea_state.seed},
                 {"loop_period_s", maker.sea_state.loop_period_s}};
  if (maker.kind == WaveMaker::Kind::kTimeSeries) record["series_samples"] = maker.series_time_s.size();
  // Where the source acts (the line and its wet span, chosen by keep_to_wet_span), in the grid frame.
  if (maker.kind != WaveMaker::Kind::kNone && maker.span_end_cell != std::numeric_limits<int>::max())
    record["source"] = {{"line_m", maker.source_line_m},
                        {"facing", side_name(maker.facing)},
                        {"span_cells", {maker.span_begin_cell, maker.span_end_cell}}};
  return record;
}


}  // namespace nearshore::bake::detail
