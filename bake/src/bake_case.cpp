// The case file -> BakeCase: the sections are read by case_*.cpp (case_reader.hpp), assembled and
// cross-checked here (time step against the output, gauge and loop intervals; the deep-water
// coupling of the wave maker).
#include "nearshore/bake/bake_case.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "case_reader.hpp"

namespace nearshore::bake {

using namespace nearshore::ocean;       // spectra, sea states, the deep-water field
using namespace nearshore::boussinesq;  // the solver and its parameters
using namespace detail;                 // the section readers
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct TimeRequest {
  double time_step_s = 0.0, courant_number = 0.5;
};

TimeRequest read_timing(TableReader& time, BakeTiming& timing) {
  timing.duration_s = time.positive("duration_s", std::nullopt, "simulated duration in seconds");
  timing.spin_up_s = time.non_negative("spin_up_s", 0.0, "spin-up in seconds");
  timing.output_interval_s = time.positive("output_interval_s", std::nullopt, "simulated seconds between frames");
  timing.checkpoint_interval_s = time.non_negative("checkpoint_interval_s", 0.0, "simulated seconds between checkpoints (0 = none)");
  timing.gauge_interval_s = time.non_negative("gauge_interval_s", 0.0, "simulated seconds between gauge samples (0 = every step)");
  TimeRequest request;
  if (time.has("time_step_s") && time.has("courant_number"))
    time.fail(time.full("time_step_s"), "and time.courant_number are both given", "give one of them");
  request.time_step_s = time.non_negative("time_step_s", 0.0, "time step in seconds");
  request.courant_number = time.positive("courant_number", 0.5, "Courant number (|U| + sqrt(g d_max)) dt / dx, U the [current]");
  if (request.courant_number > kMaxCourantNumber)
    time.fail(time.full("courant_number"),
              fmt::format("= {} is above {}, the solver's stability limit of sqrt(g d_max) dt / dx (docs/solver.md)",
                          request.courant_number, kMaxCourantNumber),
              fmt::format("give time.courant_number <= {} (0.5, the default, is safe)", kMaxCourantNumber));
  if (timing.spin_up_s >= timing.duration_s)
    time.fail(time.full("spin_up_s"), fmt::format("= {} s is not shorter than time.duration_s = {} s", timing.spin_up_s, timing.duration_s),
              "make the duration longer than the spin-up, or shorten the spin-up");
  if (timing.output_interval_s > timing.duration_s - timing.spin_up_s)
    time.fail(time.full("output_interval_s"), "is longer than the time after spin-up", "give a shorter output interval or a longer duration");
  // One file per frame: bounded before anything is computed (kMaxFrames, case_reader.hpp).
  const double frames = std::floor((timing.duration_s - timing.spin_up_s) / timing.output_interval_s * (1 + 1e-12)) + 1;
  if (frames > kMaxFrames)
    time.fail(time.full("duration_s"),
              fmt::format("= {} s with time.spin_up_s = {} s and time.output_interval_s = {} s makes {:.3g} frames, "
                          "more than the limit of {:.0f} (one file each; a million 1-second frames are 11.6 days of sea)",
                          timing.duration_s, timing.spin_up_s, timing.output_interval_s, frames, kMaxFrames),
              "shorten time.duration_s (a looping sea needs one loop period of frames after the spin-up) or "
              "lengthen time.output_interval_s");
  return request;
}

// The resolved time step against the solver's stability limit and the step budget, before the
// solver sees it (the solver refuses the same Courant number, but names SolverParameters, not the
// case file's key). `d_max` as the solver takes it: the deepest cell of the grid.
void check_time_step(TableReader& time, const TimeRequest& request, const BakeCase& bake_case) {
  const double step_s = bake_case.solver.time_step_s;
  // The smaller cell size: the Courant number of rectangular cells is sqrt(g d_max) dt / min(dx, dy).
  const double spacing_m = bake_case.harbour.geometry.smaller_spacing_m();
  const double deepest_m = deepest_still_water_m(bake_case.harbour);
  const bool step_given = request.time_step_s > 0.0;
  const std::string step_text = step_given && step_s != request.time_step_s
                                    ? fmt::format("{} s (reduced to {:.6g} s to divide the output interval)", request.time_step_s, step_s)
                                    : fmt::format("{:.6g} s", step_s);
  if (deepest_m > 0.0) {
    // With a current the gravity wave it carries (boussinesq::courant_speed_m_s).
    const boussinesq::ImposedCurrent& current = bake_case.solver.current;
    const double speed_m_s = boussinesq::courant_speed_m_s(deepest_m, current);
    const double courant = speed_m_s * step_s / spacing_m;
    const double largest_step_s = kMaxCourantNumber * spacing_m / speed_m_s;
    const std::string speed_text =
        current.any() ? fmt::format("(|U| + sqrt(g d_max)) dt / min(dx, dy) = {:.3g} (|U| {:.3g} m/s, the [current]; ", courant,
                                    current.speed_m_s())
                      : fmt::format("sqrt(g d_max) dt / min(dx, dy) = {:.3g} (", courant);
    if (courant > kMaxCourantNumber)  // only a given time step gets here: courant_number is bounded above
      time.fail(time.full("time_step_s"),
                fmt::format("= {} gives a Courant number {}d_max {} m, the deepest cell; "
                            "min(dx, dy) {} m), above {}, the solver's stability limit (docs/solver.md)",
                            step_text, speed_text, deepest_m, spacing_m, kMaxCourantNumber),
                fmt::format("give time.time_step_s <= {:.4g} s, or leave it out and give time.courant_number "
                            "(0.5 by default)", largest_step_s));
  }
  const double steps = std::ceil(bake_case.timing.duration_s / step_s * (1 - 1e-12));
  if (steps <= kMaxSolverSteps) return;
  const std::string limit = fmt::format("more than the limit of {:.0f} (about a day on one core for a 300 x 300 grid)", kMaxSolverSteps);
  if (step_given)
    time.fail(time.full("time_step_s"),
              fmt::format("= {} makes {:.3g} solver steps over time.duration_s = {} s, {}", step_text, steps,
                          bake_case.timing.duration_s, limit),
              "give a longer time.time_step_s, or leave it out and give time.courant_number (0.5 by default), or "
              "shorten time.duration_s");
  time.fail(time.full("duration_s"),
            fmt::format("= {} s makes {:.3g} solver steps of {:.6g} s (time.courant_number = {} with min(dx, dy) {} m and the deepest "
                        "water {} m), {}",
                        bake_case.timing.duration_s, steps, step_s, request.courant_number, spacing_m, deepest_m, limit),
            "shorten time.duration_s, or give the bathymetry a coarser spacing_m");
}

// The wet/dry threshold where [solver] leaves it out: the solver's default, a centimetre (a harbour's:
// a thousandth of its 10 m of water), or a 300th of the deepest water, the smaller. The threshold is a
// film thickness the scheme treats as no water, so its scale is the water's: in a laboratory flume of
// a few decimetres the centimetre holds the run-up tongue back (Synolakis' (1987) solitary wave on
// 0.30 m runs up 17 % short with it), and from a 300th of the depth the run-up is within 0.3 % of R
// of its converged value, while cases scored at gauges in the water do not move (docs/validation.md,
// "The wet/dry threshold"). Any grid 3 m deep or deeper keeps the centimetre. A grid with no water
// keeps it too (there is no depth to scale by).
constexpr double kDepthsPerDryDepth = 300.0;

double default_dry_depth_m(const HarbourGrid& harbour) {
  const double harbour_dry_depth_m = boussinesq::SolverParameters{}.dry_depth_m;
  const double deepest_m = deepest_still_water_m(harbour);
  if (!(deepest_m > 0.0)) return harbour_dry_depth_m;
  return std::min(harbour_dry_depth_m, deepest_m / kDepthsPerDryDepth);
}

// The grid-scale filter where [solver] leaves it out (docs/solver.md, "Grid-scale filter"): the
// solver's order 8 on grids finer than a quarter of the deepest water, off on coarser ones. The
// filter is there for a mode of fine grids: unfiltered, a narrow flume's across mode blows up within
// 200 s at d/dx = 12 and grows with an e-folding time of 160-300 s at d/dx = 3-6 and 800 s at 2. Its
// cost is at walls: the edge of its mask beside a quay or pier tips a mode along the wall over, which
// grows with an e-folding time of 13-20 s at d/dx = 1.4-2 (and decays at 1); a harbour bake on cells
// of half the depth showed it as two-cell stripes in Hs along its breakwaters. So a harbour grid
// (cells a quarter of the deepest water long or longer) runs without it and a laboratory grid with
// it; the growth figures were measured 2026-11-28 from still water with noise.
// The depth is the deepest the equations see: every term runs on min(d, effective_depth_limit_m)
// (docs/solver.md, "Effective depth"), so water deeper than the limit makes no mode the filter
// must catch. Measured on the true depth, Commencement Bay's 169 m made its 12 m cells "fine" where
// the equations see 47.5 m (d/dx 4.0), and the filter's mode grew beside Browns Point's staircase
// shore to Hs 7.4 m under a 0.34 m swell (docs/solver.md, "The water beside a wall").
constexpr double kFilteredDepthsPerCell = 4.0;

double deepest_seen_water_m(const HarbourGrid& harbour, double effective_depth_limit_m) {
  const double deepest_m = deepest_still_water_m(harbour);
  return effective_depth_limit_m > 0.0 ? std::min(deepest_m, effective_depth_limit_m) : deepest_m;
}

int default_shapiro_filter_order(const HarbourGrid& harbour, double effective_depth_limit_m) {
  const int solver_order = boussinesq::SolverParameters{}.shapiro_filter_order;
  const double spacing_m = harbour.geometry.smaller_spacing_m();
  return deepest_seen_water_m(harbour, effective_depth_limit_m) > kFilteredDepthsPerCell * spacing_m ? solver_order : 0;
}

}  // namespace

long whole_steps(double interval_s, double step_s) {
  if (!(step_s > 0.0) || !(interval_s > 0.0)) return -1;
  const double ratio = interval_s / step_s;
  const long n = std::lround(ratio);
  return (n >= 1 && std::abs(ratio - static_cast<double>(n)) <= 1e-9 * std::max(1.0, ratio)) ? n : -1;
}

double resolve_time_step(double requested_time_step_s, double courant_number, const HarbourGrid& harbour,
                         double output_interval_s, const boussinesq::ImposedCurrent& current) {
  double step_s = requested_time_step_s;
  if (!(step_s > 0.0)) {
    float deepest_m = 0.f;
    for (float depth : harbour.still_water_depth_m.values()) deepest_m = std::max(deepest_m, depth);
    // Courant number of the shallow-water celerity in the deepest water carried by the current:
    // (|U| + sqrt(g d_max)) dt / min(dx, dy) (boussinesq::courant_speed_m_s).
    step_s = courant_number * harbour.geometry.smaller_spacing_m() / boussinesq::courant_speed_m_s(std::max(deepest_m, 0.01f), current);
  }
  const double steps_per_output = std::ceil(output_interval_s / step_s * (1.0 - 1e-12));
  return output_interval_s / std::max(1.0, steps_per_output);
}

BakeCase parse_bake_case(const json& document, const fs::path& case_file, const CaseReadOptions& options) {
  const std::string subject = case_file.string();
  const fs::path base = case_file.parent_path();
  TableReader root(document, "", subject);
  BakeCase bake_case;
  bake_case.case_file = case_file;
  bake_case.source = document;
  (void)root.string("title", "", "a title for the record");

  TableReader bathymetry = root.table("bathymetry");
  if (!root.has("bathymetry")) root.fail("bathymetry", "is missing", "add a [bathymetry] table (docs/commands/bake.md)");
  bake_case.harbour = read_bathymetry(bathymetry, base, options);
  if (bathymetry.has("file")) bake_case.input_files.push_back(bathymetry.path("file", base));
  bathymetry.finish();
  const GridGeometry& geometry = bake_case.harbour.geometry;

  if (!root.has("time")) root.fail("time", "is missing", "add a [time] table with duration_s and output_interval_s");
  TableReader time = root.table("time");
  const TimeRequest request = read_timing(time, bake_case.timing);
  time.finish();

  TableReader solver = root.table("solver");
  bake_case.solver = read_solver(solver);
  DispersionBound dispersion_bound;
  dispersion_bound.dispersion_coefficient = bake_case.solver.dispersion_coefficient;
  dispersion_bound.effective_depth_limit_given = solver.has("effective_depth_limit_m");
  dispersion_bound.effective_depth_limit_m = bake_case.solver.effective_depth_limit_m;
  if (!solver.has("dry_depth_m")) bake_case.solver.dry_depth_m = default_dry_depth_m(bake_case.harbour);
  // A cell with less water than dry_depth_m is dry. A threshold of a tenth of the deepest water
  // dries the sea under the troughs of its own waves; the default is a 300th (at most 1 cm), and
  // the centimetre already held Synolakis' run-up 17 % short on 0.30 m of water (the comment on
  // kDepthsPerDryDepth). A larger one stopped the solver with a message that blamed the time step
  // (issue 44).
  if (const double deepest_m = deepest_still_water_m(bake_case.harbour);
      deepest_m > 0 && bake_case.solver.dry_depth_m > 0.1 * deepest_m)
    solver.fail(solver.full("dry_depth_m"),
                fmt::format("= {} m is more than a tenth of the deepest still water ({:.3g} m): cells with less water than "
                            "this count as dry, so the sea would dry out under the troughs of its own waves",
                            bake_case.solver.dry_depth_m, deepest_m),
                fmt::format("give solver.dry_depth_m <= {:.3g} m (a film of water: millimetres; left out, the bake "
                            "takes a 300th of the deepest water, at most 1 cm)",
                            0.1 * deepest_m));
  const bool filter_order_given = solver.has("shapiro_filter_order");  // derived below, from the depth the equations see
  solver.finish();
  for (TableReader& entry : root.tables("sponges")) {
    SpongeLayer sponge;
    sponge.side = side_from_index(entry.choice("side", std::nullopt, kSideNames));
    const bool across_x = sponge.side == Side::kWest || sponge.side == Side::kEast;
    const double extent_m = across_x ? geometry.width_m() : geometry.height_m();
    sponge.width_m = entry.number("width_m", std::nullopt, 0.0, 0.5 * extent_m, true, "sponge width in metres, at most half the grid");
    entry.finish();
    bake_case.solver.sponges.push_back(sponge);
  }
  // An imposed steady current (docs/solver.md, "Currents"): the flux the waves ride on, held at the
  // grid's edges and kept by the sponges. Tidal streams reach 5 m/s in the strongest races.
  if (root.has("current")) {
    TableReader current = root.table("current");
    bake_case.solver.current.velocity_x_m_s =
        current.number("u_m_s", 0.0, -5.0, 5.0, false, "the current's velocity toward the east in m/s");
    bake_case.solver.current.velocity_y_m_s =
        current.number("v_m_s", 0.0, -5.0, 5.0, false, "the current's velocity toward the north in m/s");
    current.finish();
  }
  // A tide (docs/solver.md, "Tides"): the still-water level as a series over the bake, above the
  // level the bathymetry's still_water_level_m put the grid at (the library's fixed tide, the
  // same key's owner, sets that start).
  if (root.has("tide")) {
    TableReader tide = root.table("tide");
    const std::string meaning = "[[time_s, level_m], ...] with increasing times, levels in metres above the grid's still water";
    for (const auto& [time_s, level_m] : tide.pairs("level_m", meaning)) {
      if (!bake_case.tide_level.time_s.empty() && !(time_s > bake_case.tide_level.time_s.back()))
        tide.fail(tide.full("level_m"), fmt::format("has time {} s after {} s: the times must increase", time_s, bake_case.tide_level.time_s.back()),
                  "write it as " + meaning);
      if (!(std::abs(level_m) <= 30.0))
        tide.fail(tide.full("level_m"), fmt::format("has a level of {} m", level_m),
                  "give levels within +-30 m of the grid's still water (the largest tidal range is 16 m)");
      bake_case.tide_level.time_s.push_back(time_s);
      bake_case.tide_level.elevation_m.push_back(level_m);
    }
    tide.finish();
  }
  bake_case.solver.courant_number = request.courant_number;
  // The step divides the shorter of the output and gauge intervals, and that divides the longer, so
  // frames and gauge samples fall exactly on steps.
  const BakeTiming& timing = bake_case.timing;
  double divided_interval_s = timing.output_interval_s;
  if (timing.gauge_interval_s > 0) {
    divided_interval_s = std::min(timing.output_interval_s, timing.gauge_interval_s);
    if (whole_steps(std::max(timing.output_interval_s, timing.gauge_interval_s), divided_interval_s) < 1)
      time.fail(time.full("gauge_interval_s"), fmt::format("= {} s neither divides time.output_interval_s = {} s nor is a multiple of it",
                                                           timing.gauge_interval_s, timing.output_interval_s),
                "choose a gauge interval such as output_interval_s / 10");
  }
  bake_case.solver.time_step_s =
      resolve_time_step(request.time_step_s, request.courant_number, bake_case.harbour, divided_interval_s, bake_case.solver.current);
  check_time_step(time, request, bake_case);

  if (!root.has("wave_maker")) root.fail("wave_maker", "is missing", "add a [wave_maker] table (kind = \"none\" for a basin at rest)");
  TableReader maker = root.table("wave_maker");
  MakerRequest maker_request;
  bake_case.wave_maker = read_wave_maker(maker, bake_case.harbour, base, dispersion_bound, bake_case.solver.sponges, maker_request);
  maker.finish();
  // The effective-depth limit the band needs (docs/solver.md, "Effective depth"), unless [solver]
  // gives one: from the highest frequency the maker makes; 0 (inactive) where the grid is nowhere
  // deeper than k d = 3 for it, so such a case runs exactly as before the limit existed. Set before
  // the deep-water coupling below, which sees the solver's depths through it.
  if (!dispersion_bound.effective_depth_limit_given) {
    double highest_rad_s = maker_request.from_deep_water ? maker_request.band.max_frequency_rad_s : 0.0;
    for (const WaveComponent& component : bake_case.wave_maker.sea_state.components)
      highest_rad_s = std::max(highest_rad_s, component.angular_frequency_rad_s);
    bake_case.solver.effective_depth_limit_m = automatic_effective_depth_limit_m(bake_case.harbour, highest_rad_s);
  }
  if (!filter_order_given)
    bake_case.solver.shapiro_filter_order = default_shapiro_filter_order(bake_case.harbour, bake_case.solver.effective_depth_limit_m);
  bake_case.solitary_wave = maker_request.solitary_wave;
  bake_case.warnings.insert(bake_case.warnings.end(), maker_request.warnings.begin(), maker_request.warnings.end());
  if (maker_request.from_deep_water && !root.has("deep_water"))
    root.fail("deep_water", "is missing, but wave_maker.kind = \"deep_water\" takes its waves from it",
              "add a [deep_water] table with a spectrum (docs/commands/bake.md), or give the wave maker "
              "another kind");
  if (root.has("deep_water")) {
    TableReader deep = root.table("deep_water");
    DeepWaterDrive drive;
    bake_case.deep_water =
        read_deep_water(deep, bake_case.wave_maker, maker_request, bake_case.harbour, drive, bake_case);
    deep.finish();
    if (drive.drives_wave_maker) {
      // The maker makes the field's own waves, phases moved to the solver's frame
      // (deep_water_coupling.hpp): at the offshore edge both are the same waves to linear order.
      try {
        const DeepWaterField field(*bake_case.deep_water);
        bake_case.deep_water_maker =
            couple_wave_maker(field, bake_case.wave_maker, bake_case.harbour, bake_case.solver, drive.band);
      } catch (const Error& error) {
        deep.fail("deep_water", "cannot be built: " + error.problem(), error.fix());
      }
      bake_case.wave_maker.sea_state = bake_case.deep_water_maker->sea_state;
      if (bake_case.wave_maker.sea_state.components.empty())
        deep.fail("deep_water",
                  "leaves the wave maker no component (none inside its band travelling into the domain "
                  "within 78 degrees)",
                  "turn the waves towards the domain (wave_maker.facing, the spectrum's direction), widen "
                  "the maker's frequency band, "
                  "or use a larger deep_water tile (finer lattice cells)");
    }
  }
  // The harbour's structures laid at this grid's cells, their porous faces fitted to the sea the
  // wave maker now makes (structure_layers.hpp); then the case's own porous blocks over them.
  if (!bake_case.harbour.structures.empty())
    bake_case.structure_layers =
        lay_structures(bake_case.harbour, bake_case.solver, structure_sea_state(bake_case.wave_maker), bake_case.warnings);
  apply_porous_blocks(root.tables("porous_blocks"), bake_case.harbour);
  const double loop_period_s = bake_case.wave_maker.sea_state.loop_period_s;
  if (loop_period_s > 0 && whole_steps(loop_period_s, bake_case.timing.output_interval_s) < 1)
    time.fail(time.full("output_interval_s"), fmt::format("= {} s does not divide wave_maker.loop_period_s = {} s",
                                                          bake_case.timing.output_interval_s, loop_period_s),
              "choose an output interval that divides the loop period into whole frames");

  for (TableReader& entry : root.tables("gauges")) {
    GaugeSpec gauge;
    gauge.name = entry.string("name", std::nullopt, "gauge name");
    // x_m/y_m from the south-west corner, easting_m/northing_m or lat/lon (case_bathymetry.cpp).
    const ProjectedPoint place = read_case_position(entry, bake_case.harbour, fmt::format("gauge \"{}\" ({})", gauge.name, entry.full("").substr(0, entry.full("").size() - 1)), bake_case.warnings);
    gauge.x_m = place.x_m;
    gauge.y_m = place.y_m;
    entry.finish();
    if (gauge.name.empty() || gauge.name.find_first_of(",\"\n") != std::string::npos)
      entry.fail(entry.full("name"), fmt::format("= \"{}\" is empty or holds a comma, quote or newline", gauge.name),
                 "name gauges with letters, digits, '_' or '-' (they become gauges.csv column names)");
    for (const GaugeSpec& other : bake_case.gauges)
      if (other.name == gauge.name)
        entry.fail(entry.full("name"), fmt::format("= \"{}\" is used by another gauge", gauge.name), "give every gauge its own name");
    bake_case.gauges.push_back(gauge);
  }
  TableReader output = root.table("output");
  bake_case.output = read_output(output);
  output.finish();
  root.finish();

  bake_case.wave_conditions = wave_record(bake_case.wave_maker, document.value("wave_maker", json::object()));
  if (bake_case.deep_water_maker) {
    bake_case.wave_conditions["driven_by_deep_water"] = true;
    bake_case.wave_conditions["deep_water_variance_fraction"] =
        bake_case.deep_water_maker->variance_fraction();
  }
  if (maker_request.split) {
    // The split and its Hs budget, for the record and the bake's report (docs/commands/bake.md).
    const SpectrumSplit& split = *maker_request.split;
    bake_case.wave_conditions["spectrum_split"] = {
        {"bake_min_frequency_hz", split.min_frequency_hz},
        {"bake_max_frequency_hz", split.max_frequency_hz},
        {"bake_components", split.bake_components},
        {"deep_water_components", split.left_components},
        {"bake_significant_wave_height_m", split.bake_significant_height_m},
        {"deep_water_significant_wave_height_m", split.left_significant_height_m},
        {"total_significant_wave_height_m", split.total_significant_height_m},
        {"deep_water_layer_present", bake_case.deep_water.has_value()},
        {"reason", split.reason},
        // Where the runtime's inside layer starts (docs/runtime.md "The split"): the field's waves
        // above it are drawn on top of the bake. Driven by the field, the maker made the field's
        // own waves up to its highest frequency; else its cells end half-way between its highest
        // component and the lowest left one (sea_state_builder.hpp: cells tile the band).
        {"split_frequency_hz", bake_case.deep_water_maker ? split.max_frequency_hz
                                                          : 0.5 * (split.max_frequency_hz + split.left_min_frequency_hz)}};
  }
  if (bake_case.deep_water)
    if (const auto* sum = dynamic_cast<const SpectrumSum*>(bake_case.deep_water->spectrum.get())) {
      // The local seas of [[deep_water.local_sea]] (case_sea_state.cpp): the FFT layer's alone. Inside
      // the harbour the runtime draws the layer above the split frequency only, so a local sea's
      // variance below it is reported as not drawn there.
      const double depth_m = bake_case.deep_water->still_water_depth_m;
      const double split_hz = bake_case.wave_conditions.contains("spectrum_split")
                                  ? bake_case.wave_conditions["spectrum_split"]["split_frequency_hz"].get<double>()
                                  : 0.0;
      const double split_wavenumber_rad_m =
          split_hz > 0.0 ? wavenumber_from_frequency(2.0 * std::numbers::pi * split_hz, depth_m) : 0.0;
      json seas = json::array();
      for (std::size_t i = 1; i < sum->parts().size(); ++i) {
        const WavenumberSpectrum& part = *sum->parts()[i];
        const double below_split_m2 = split_wavenumber_rad_m > 0.0 ? part.moment_between(0.0, split_wavenumber_rad_m) : 0.0;
        seas.push_back({{"spectrum", part.to_json()},
                        {"significant_wave_height_m", part.significant_wave_height_m()},
                        {"below_split_significant_wave_height_m", 4.0 * std::sqrt(below_split_m2)}});
      }
      bake_case.wave_conditions["local_seas"] = seas;
    }
  bake_case.solver_record = solver_record_of(bake_case);
  return bake_case;
}

nlohmann::json solver_record_of(const BakeCase& bake_case) {
  nlohmann::json record = solver_record(bake_case.solver);
  if (!bake_case.tide_level.time_s.empty()) {  // only with a tide: a record without one is as before
    nlohmann::json levels = nlohmann::json::array();
    for (std::size_t i = 0; i < bake_case.tide_level.time_s.size(); ++i)
      levels.push_back({bake_case.tide_level.time_s[i], bake_case.tide_level.elevation_m[i]});
    record["tide_level_m"] = levels;
  }
  if (!bake_case.structure_layers.empty()) record["structure_layers"] = structure_layers_record(bake_case.structure_layers);
  return record;
}

std::string describe_derived_solver_settings(const BakeCase& bake_case) {
  const auto solver = bake_case.source.find("solver");
  auto given = [&](const char* key) { return solver != bake_case.source.end() && solver->is_object() && solver->contains(key); };
  std::string text;
  const double solver_default_m = SolverParameters{}.dry_depth_m;
  if (!given("dry_depth_m") && bake_case.solver.dry_depth_m < solver_default_m)
    text = fmt::format("wet/dry threshold: {:.2g} mm, a {:.0f}th of the {:.3g} m deepest water (solver.dry_depth_m left out; "
                       "a harbour {:.3g} m deep or deeper gets {:.0f} cm; docs/solver.md, \"Wet and dry\")",
                       1000.0 * bake_case.solver.dry_depth_m, kDepthsPerDryDepth, deepest_still_water_m(bake_case.harbour),
                       kDepthsPerDryDepth * solver_default_m, 100.0 * solver_default_m);
  if (!given("shapiro_filter_order") && bake_case.solver.shapiro_filter_order != SolverParameters{}.shapiro_filter_order)
    text += fmt::format("{}grid-scale filter: off, the {:.3g} m cells are not finer than 1/{:.0f} of the {:.3g} m deepest water{} "
                        "(solver.shapiro_filter_order left out; finer grids get order {}; docs/solver.md, \"Grid-scale filter\")",
                        text.empty() ? "" : "\n", bake_case.harbour.geometry.smaller_spacing_m(), kFilteredDepthsPerCell,
                        deepest_seen_water_m(bake_case.harbour, bake_case.solver.effective_depth_limit_m),
                        deepest_seen_water_m(bake_case.harbour, bake_case.solver.effective_depth_limit_m) < deepest_still_water_m(bake_case.harbour)
                            ? " the equations see (the effective depth)" : "",
                        SolverParameters{}.shapiro_filter_order);
  return text;
}

std::string describe_carried_band(const BakeCase& bake_case) {
  std::string text;
  if (bake_case.solver.effective_depth_limit_m > 0.0 &&
      bake_case.solver.effective_depth_limit_m < deepest_still_water_m(bake_case.harbour))
    text += fmt::format("effective depth: the equations see at most {:.1f} m of the {:.1f} m deepest water (k d <= 3 for the "
                        "shortest baked wave; docs/solver.md, \"Effective depth\")",
                        bake_case.solver.effective_depth_limit_m, deepest_still_water_m(bake_case.harbour));
  if (bake_case.wave_conditions.contains("spectrum_split")) {
    const json& split = bake_case.wave_conditions["spectrum_split"];
    if (!text.empty()) text += "\n";
    text += fmt::format("spectrum split: Hs {:.2f} m = the bake's {:.2f} m ({} components, {:.3f}-{:.3f} Hz) + the deep-water "
                        "layer's {:.2f} m ({} components above {:.3f} Hz: {}){}",
                        split["total_significant_wave_height_m"].get<double>(), split["bake_significant_wave_height_m"].get<double>(),
                        split["bake_components"].get<int>(), split["bake_min_frequency_hz"].get<double>(),
                        split["bake_max_frequency_hz"].get<double>(), split["deep_water_significant_wave_height_m"].get<double>(),
                        split["deep_water_components"].get<int>(), split["bake_max_frequency_hz"].get<double>(),
                        split["reason"].get<std::string>(),
                        split["deep_water_layer_present"].get<bool>()
                            ? ""
                            : "; the case has no [deep_water], so nothing draws them: add one (docs/commands/bake.md)");
  }
  if (bake_case.wave_conditions.contains("local_seas"))
    for (const json& sea : bake_case.wave_conditions["local_seas"]) {
      if (!text.empty()) text += "\n";
      const json& spectrum = sea["spectrum"];
      text += fmt::format("local sea: Hs {:.2f} m ({}{}) in the deep-water layer only, none of it baked (it is not made at the "
                          "source line); Hs {:.3f} m of it lies below the split frequency, which the runtime does not draw "
                          "inside the harbour",
                          sea["significant_wave_height_m"].get<double>(), spectrum.value("name", std::string("spectrum")),
                          spectrum.contains("peak_period_s") ? fmt::format(", Tp {:.2f} s", spectrum["peak_period_s"].get<double>()) : std::string(),
                          sea["below_split_significant_wave_height_m"].get<double>());
    }
  return text;
}

json read_case_document(const fs::path& case_file) { return parse_case_document(case_file); }

BakeCase read_bake_case(const fs::path& case_file, const CaseReadOptions& options) {
  return parse_bake_case(parse_case_document(case_file), case_file, options);
}

}  // namespace nearshore::bake
