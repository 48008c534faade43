// Laboratory validations, each run through the same road as `nearshore bake`: the case file in
// data/cases/ is read, (for CI) coarsened, run with run_bake into the build folder, and the
// outputs on disk (gauges.csv, the frame sequence) are compared with the measurements in
// ../shared/validation. Numbers and plots: docs/validation.md.
//
// NEARSHORE_FULL_RESOLUTION = 1 (validation_full_tests, label `validation`): the case files as
// written, with the bars. = 0 (validation_tests, label `physics`): coarser grids and
// shorter records that still test the physics, with the bounds those grids can honestly meet.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <fmt/core.h>
#include <gtest/gtest.h>

#include "laboratory_data.hpp"
#include "nearshore/bake/bake_gauges.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/sequence/sequence_reader.hpp"
#include "validation_bake.hpp"
#include "validation_plots.hpp"

namespace nearshore::validation {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

// ---- the data readers and statistics (no solver) -------------------------------------------------
TEST(VALIDATION_SUITE(LaboratoryData), ReadersFindTheMeasurementsTheReadmesDescribe) {
  const auto berkhoff = read_berkhoff_transects();
  ASSERT_EQ(berkhoff.size(), 208u);  // the "208 points"
  std::map<int, double> peaks;
  for (const auto& point : berkhoff) peaks[point.transect] = std::max(peaks[point.transect], point.amplitude_ratio);
  // The measured focal peaks the issue quotes: 2.19, 2.01, 2.02 on transects 3, 4, 7.
  EXPECT_NEAR(peaks[3], 2.19, 0.005);
  EXPECT_NEAR(peaks[4], 2.01, 0.005);
  EXPECT_NEAR(peaks[7], 2.02, 0.005);
  const auto gauges = read_mase_kirby_gauges();
  ASSERT_EQ(gauges.size(), 12u);
  EXPECT_EQ(gauges.front().elevation_m.size(), 15000u);
  EXPECT_NEAR(gauges[1].x_m, 12.4, 1e-9);  // 35 cm on the 1:20 slope from x = 10 m
  // Hs = 4 sqrt(m0) of the whole 47 cm record: 6.61 cm (computed independently of this code).
  EXPECT_NEAR(significant_wave_height_m(gauges.front().elevation_m, 0, 15000), 0.0661, 0.0001);
  const auto runs = read_synolakis_runup();
  EXPECT_GT(runs.size(), 60u);
  // Near H/d = 0.0185 the table holds 0.074-0.078; the law gives 0.086 (README).
  EXPECT_NEAR(measured_runup_ratio(runs, 0.0185), 0.075, 0.004);
  EXPECT_NEAR(synolakis_runup_law(0.0185, 19.85), 0.086, 0.001);
  EXPECT_NEAR(measured_runup_ratio(runs, 0.30), 0.54, 0.02);
  EXPECT_EQ(read_synolakis_profiles("Case0_0185").size(), 5u);
  EXPECT_EQ(read_synolakis_profiles("Case0_3").size(), 4u);
}

TEST(VALIDATION_SUITE(LaboratoryData), WaveHeightOverWholePeriodsOfASine) {
  std::vector<double> t, eta;
  for (int i = 0; i < 4000; ++i) t.push_back(0.01 * i), eta.push_back(0.02 * std::sin(2 * M_PI * 0.01 * i / 1.0 + 0.3));
  // Sampling a 1 s sine at 0.01 s misses its extremes by at most 1 - cos(pi * 0.01) = 5e-4.
  EXPECT_NEAR(mean_wave_height_m(t, eta, 1.0, 30.0, 39.99), 0.04, 0.04 * 5e-4);
  EXPECT_NEAR(significant_wave_height_m(eta, 0, 4000), 4 * 0.02 / std::sqrt(2.0), 1e-4);
  EXPECT_NEAR(mean_level_m(eta, 0, 4000), 0.0, 1e-4);
  EXPECT_DOUBLE_EQ(root_mean_square_error({1, 2}, {1, 4}), std::sqrt(2.0));
}

// ---- Berkhoff et al. (1982) ----------------------------------------------------------------------
// The case `name` (berkhoff: 0.05 m square cells; berkhoff_rect: FUNWAVE-TVD's 0.05 m x 0.10 m
// rectangular cells, issue 15) scored against the 208 measured amplitude ratios with the same bars.
void score_berkhoff(const std::string& name) {
  const std::vector<BerkhoffPoint> points = read_berkhoff_transects();
  ASSERT_EQ(points.size(), 208u);
  double centre_x = 0, centre_y = 0, period_s = 0, end_s = 0;
  const auto summary = bake_case(name, name, [&](json& document) {
    // CI: cells twice as large along each axis (0.1 m instead of 0.05 m: 10 per wavelength over the
    // shoal top along the waves).
    if (!kFull) {
      json& spacing = document["bathymetry"]["spacing_m"];
      spacing = spacing.is_array() ? json::array({2 * spacing[0].get<double>(), 2 * spacing[1].get<double>()})
                                   : json(2 * spacing.get<double>());
    }
    centre_x = document["bathymetry"]["centre_m"][0].get<double>();
    centre_y = document["bathymetry"]["centre_m"][1].get<double>();
    period_s = document["wave_maker"]["period_s"].get<double>();
    end_s = document["time"]["duration_s"].get<double>();
    for (std::size_t i = 0; i < points.size(); ++i)
      add_gauge(document, fmt::format("p{:03d}", i), centre_x + points[i].downwave_m, centre_y + points[i].transverse_m);
  });
  const bake::GaugeTable gauges = bake::read_gauges_csv(summary.gauges_csv);
  // Wave height over the last five whole periods (the field is steady at the farthest transect by
  // t = 30 s: the front needs about 25 s from the source to transect 5 at the group velocity).
  std::vector<double> model(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    model[i] = 0.5 * mean_wave_height_m(gauges.time_s, bake::gauge_column(gauges, fmt::format("p{:03d}", i)), period_s,
                                        end_s - 5 * period_s, end_s) /
               kBerkhoffIncidentAmplitude_m;
  std::vector<double> data(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) data[i] = points[i].amplitude_ratio;
  json results = {{"cells", summary.cells}, {"time_step_s", summary.time_step_s}, {"wall_time_s", summary.wall_time_s}};
  std::vector<LinePlot> plots;
  for (int transect = 1; transect <= 8; ++transect) {
    std::vector<double> m, d, coordinate;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (points[i].transect == transect) {
        m.push_back(model[i]);
        d.push_back(data[i]);
        coordinate.push_back(transect <= 5 ? points[i].transverse_m : points[i].downwave_m);
      }
    const double rmse = root_mean_square_error(m, d);
    const double model_peak = *std::max_element(m.begin(), m.end()), data_peak = *std::max_element(d.begin(), d.end());
    results["transects"][std::to_string(transect)] = {{"rmse", rmse}, {"points", m.size()}, {"model_peak", model_peak}, {"data_peak", data_peak}};
    std::printf("%s transect %d: RMSE %.3f over %zu points, peak model %.3f data %.3f\n", name.c_str(), transect, rmse, m.size(), model_peak, data_peak);
    LinePlot plot;
    plot.title = fmt::format("transect {}: RMSE {:.3f}", transect, rmse);
    plot.x_label = transect <= 5 ? "across the flume (m)" : "behind the shoal centre (m)";
    plot.y_label = "A / A0";
    plot.width_px = 640, plot.height_px = 400;
    plot.series.push_back({"model", coordinate, m, kModelColour, false});
    plot.series.push_back({"Berkhoff et al. (1982)", coordinate, d, kDataColour, true});
    plots.push_back(plot);
    if (transect == 3 || transect == 4 || transect == 7) {
      // Issue 4: the focal peaks (measured 2.19, 2.01, 2.02) within 5 % at full resolution. The
      // 0.1 m CI grid resolves the focus with 10 cells per wavelength: 15 %.
      const double tolerance = kFull ? 0.05 : 0.15;
      EXPECT_NEAR(model_peak / data_peak, 1.0, tolerance) << "transect " << transect;
    }
  }
  const double overall = root_mean_square_error(model, data);
  results["overall_rmse"] = overall;
  std::printf("%s overall RMSE %.3f over %zu points (FUNWAVE-TVD reference 0.132), %.1f s wall\n", name.c_str(), overall,
              points.size(), summary.wall_time_s);
  write_results(name, results);
  write_png(tile_plots(plots, 2), output_folder(name) / "berkhoff_transects.png");
  // Issue 4: overall RMSE <= 0.13 over the 208 points (FUNWAVE-TVD scores 0.132). The CI grid has
  // half the resolution, so phase errors over the 20 m flume blur the focus: 0.2.
  EXPECT_LE(overall, kFull ? 0.13 : 0.20);
}

TEST(VALIDATION_SUITE(Berkhoff1982), AmplitudeRatiosOnTheEightTransects) { score_berkhoff("berkhoff"); }

// Issue 15: FUNWAVE-TVD's own 600 x 200 grid of 0.05 m x 0.10 m cells, the same bars.
TEST(VALIDATION_SUITE(Berkhoff1982), AmplitudeRatiosOnRectangularCells) { score_berkhoff("berkhoff_rect"); }

// ---- Mase & Kirby (1992) -------------------------------------------------------------------------
TEST(VALIDATION_SUITE(MaseKirby1992), SignificantWaveHeightAndMeanLevelAtTheTwelveGauges) {
  const std::vector<MaseKirbyGauge> measured = read_mase_kirby_gauges();
  ASSERT_EQ(measured.size(), 12u);
  double spin_up_s = 0, end_s = 0;
  const auto summary = bake_case("mase_kirby", "mase_kirby", [&](json& document) {
    if (!kFull) document["time"]["duration_s"] = 140.0;  // CI: two minutes of record instead of five
    spin_up_s = document["time"]["spin_up_s"].get<double>();
    end_s = document["time"]["duration_s"].get<double>();
  });
  const bake::GaugeTable gauges = bake::read_gauges_csv(summary.gauges_csv);
  // Statistics over [spin-up, end] of the model clock and the same span of the measured records
  // (all gauges were recorded together; the model adds the 6 m travel from the source line to the
  // 47 cm gauge, about 5 s, negligible against a window of minutes).
  std::size_t first_model = 0;
  while (first_model < gauges.time_s.size() && gauges.time_s[first_model] < spin_up_s) ++first_model;
  const std::size_t first_data = static_cast<std::size_t>(spin_up_s / kMaseKirbySampleInterval_s);
  const std::size_t last_data = static_cast<std::size_t>(end_s / kMaseKirbySampleInterval_s);
  std::vector<double> x, hs_model, hs_data, level_model, level_data;
  json results = {{"cells", summary.cells}, {"time_step_s", summary.time_step_s}, {"window_s", {spin_up_s, end_s}}};
  for (const MaseKirbyGauge& gauge : measured) {
    const auto& column = bake::gauge_column(gauges, gauge.name);
    x.push_back(gauge.x_m);
    hs_model.push_back(significant_wave_height_m(column, first_model, column.size()));
    level_model.push_back(mean_level_m(column, first_model, column.size()));
    hs_data.push_back(significant_wave_height_m(gauge.elevation_m, first_data, last_data));
    level_data.push_back(mean_level_m(gauge.elevation_m, first_data, last_data));
    results["gauges"][gauge.name] = {{"x_m", gauge.x_m}, {"hs_model_m", hs_model.back()}, {"hs_data_m", hs_data.back()},
                                     {"mean_level_model_m", level_model.back()}, {"mean_level_data_m", level_data.back()}};
    std::printf("Mase-Kirby %s (x = %.2f m): Hs model %.4f data %.4f m, mean level model %+.4f data %+.4f m\n", gauge.name.c_str(),
                gauge.x_m, hs_model.back(), hs_data.back(), level_model.back(), level_data.back());
  }
  const double hs_rmse = root_mean_square_error(hs_model, hs_data), level_rmse = root_mean_square_error(level_model, level_data);
  results["hs_rmse_m"] = hs_rmse;
  results["mean_level_rmse_m"] = level_rmse;
  std::printf("Mase-Kirby: Hs RMSE %.4f m (offshore Hs %.4f m), mean level RMSE %.4f m\n", hs_rmse, hs_data[0], level_rmse);
  write_results("mase_kirby", results);
  LinePlot hs_plot{"Mase & Kirby (1992): significant wave height", "x (m)", "Hs (m)", {}, 800, 450};
  hs_plot.series.push_back({"model", x, hs_model, kModelColour, false});
  hs_plot.series.push_back({"measured", x, hs_data, kDataColour, true});
  LinePlot level_plot{"mean water level (set-down, set-up)", "x (m)", "mean eta (m)", {}, 800, 450};
  level_plot.series.push_back({"model", x, level_model, kModelColour, false});
  level_plot.series.push_back({"measured", x, level_data, kDataColour, true});
  write_png(tile_plots({hs_plot, level_plot}, 1), output_folder("mase_kirby") / "mase_kirby_hs_setup.png");
  // Hs: the breaking model must take the energy out where the lab did. An RMSE of 10 % of the
  // offshore Hs is what Boussinesq models with eddy-viscosity breaking reach on this case
  // (FUNWAVE-TVD's benchmark plots show errors of that order at the shallowest gauges).
  EXPECT_LE(hs_rmse, 0.10 * hs_data[0]);
  // Mean level: set-down offshore and set-up in the surf zone are a few millimetres; 3 mm RMSE.
  EXPECT_LE(level_rmse, 0.003);
}

// ---- Synolakis (1987) ----------------------------------------------------------------------------
struct RunupResult {
  double runup_ratio = 0;
  std::map<int, std::pair<std::vector<double>, std::vector<double>>> profiles;  ///< t* -> (x/d, eta/d)
};

// Runs the solitary wave of H/d = `height_ratio` and measures the maximum run-up from the frames:
// the highest surface elevation of any wet cell (total depth above the dry threshold) landward of
// the initial shoreline, over all frames.
RunupResult run_synolakis(double height_ratio, const std::string& run_name, const std::vector<int>& profile_times) {
  constexpr double kDepth_m = 0.30, kCotBeta = 19.85, kShorelineX_m = 21.0;  // data/cases/synolakis.toml
  bake_case("synolakis", run_name, [&](json& document) {
    // The crest starts at X1 = X0 + L offshore, X0 = 19.85 d the toe and L = arccosh(sqrt(20)) / gamma
    // the crest-to-5 % half-length (OAR PMEL-135, BP4; the case file explains the README's L/2).
    const double gamma = std::sqrt(3.0 * height_ratio / 4.0) / kDepth_m;
    const double x1_m = kCotBeta * kDepth_m + std::acosh(std::sqrt(20.0)) / gamma;
    document["wave_maker"]["height_m"] = height_ratio * kDepth_m;
    document["wave_maker"]["crest_position_m"] = kShorelineX_m - x1_m;
    if (kFull) {
      // d / 40 in the case file's 0.045 m wide flume: six cells across, so the two-dimensional
      // scheme runs at d/dx = 40, where the grid-scale mode of docs/solver.md ("Grid-scale filter")
      // grew before the Shapiro filter.
      document["bathymetry"]["spacing_m"] = 0.0075;
    }
  });
  const sequence::SequenceReader reader(output_folder(run_name));
  // The threshold the bake ran with (the case reader's default: a 300th of the 0.30 m), as it defines wet.
  const double dry_depth_m = reader.manifest().solver.at("dry_depth_m").get<double>();
  const HarbourGrid grid = reader.read_harbour_grid();
  const int row = grid.geometry.rows / 2;
  RunupResult result;
  result.runup_ratio = -1;
  const double time_scale_s = std::sqrt(kDepth_m / ocean::kGravity_m_s2);
  for (int index = 0; index < reader.frame_count(); ++index) {
    const sequence::Frame frame = reader.read_frame(index, sequence::ChannelSelection::display());
    for (int column = 0; column < grid.geometry.columns; ++column) {
      const double depth = grid.still_water_depth_m(column, row), eta = frame.surface_elevation_m(column, row);
      if (depth <= 0 && eta + depth > dry_depth_m) result.runup_ratio = std::max(result.runup_ratio, eta / kDepth_m);
    }
    const double t_star = frame.time_s / time_scale_s;
    for (int wanted : profile_times)
      if (std::abs(t_star - wanted) < 0.5 * reader.frame_interval_s() / time_scale_s) {
        auto& [xs, etas] = result.profiles[wanted];
        for (int column = 0; column < grid.geometry.columns; ++column) {
          const double depth = grid.still_water_depth_m(column, row), eta = frame.surface_elevation_m(column, row);
          const double offshore_ratio = (kShorelineX_m - grid.geometry.cell_centre_x_m(column)) / kDepth_m;
          if (eta + depth <= dry_depth_m || offshore_ratio > 30.0) continue;  // the measured profiles reach 20 d
          xs.push_back(offshore_ratio);
          etas.push_back(eta / kDepth_m);
        }
      }
  }
  return result;
}

// One Synolakis case: run-up against the laboratory table, profiles against the snapshots, a PNG.
void check_synolakis(double height_ratio, const std::string& case_name, const std::string& run_name, double tolerance) {
  const auto runs = read_synolakis_runup();
  const auto snapshots = read_synolakis_profiles(case_name);
  std::vector<int> times;
  for (const auto& snapshot : snapshots) times.push_back(static_cast<int>(snapshot.dimensionless_time));
  const RunupResult result = run_synolakis(height_ratio, run_name, times);
  const double measured = measured_runup_ratio(runs, height_ratio);
  const double relative_error = result.runup_ratio / measured - 1.0;
  write_results(run_name, {{"height_ratio", height_ratio}, {"runup_ratio_model", result.runup_ratio}, {"runup_ratio_measured", measured},
                           {"relative_error", relative_error}, {"runup_law", synolakis_runup_law(height_ratio, 19.85)}});
  std::printf("Synolakis H/d = %.4f: R/d model %.4f, measured %.4f (%+.1f %%), non-breaking law %.4f\n", height_ratio,
              result.runup_ratio, measured, 100 * relative_error, synolakis_runup_law(height_ratio, 19.85));
  std::vector<double> lab_h, lab_r, law_h, law_r;
  for (const auto& run : runs) lab_h.push_back(run.height_ratio), lab_r.push_back(run.runup_ratio);
  for (double h = 0.005; h <= 0.045; h += 0.002) law_h.push_back(h), law_r.push_back(synolakis_runup_law(h, 19.85));
  std::vector<LinePlot> plots;
  LinePlot runup{fmt::format("maximum run-up: model {:.4f}, measured {:.4f}", result.runup_ratio, measured), "H / d", "R / d", {}, 640, 360};
  runup.series.push_back({"laboratory", lab_h, lab_r, kDataColour, true});
  runup.series.push_back({"run-up law (non-breaking)", law_h, law_r, kReferenceColour, false});
  runup.series.push_back({"model", {height_ratio}, {result.runup_ratio}, kModelColour, true});
  plots.push_back(runup);
  for (const auto& snapshot : snapshots) {
    const auto found = result.profiles.find(static_cast<int>(snapshot.dimensionless_time));
    if (found == result.profiles.end()) continue;
    LinePlot plot;
    plot.title = fmt::format("H/d = {}, t sqrt(g/d) = {}", height_ratio, snapshot.dimensionless_time);
    plot.x_label = "x / d (offshore of the initial shoreline)";
    plot.y_label = "eta / d";
    plot.width_px = 640, plot.height_px = 360;
    plot.series.push_back({"model", found->second.first, found->second.second, kModelColour, false});
    plot.series.push_back({"Synolakis (1987)", snapshot.offshore_distance_ratio, snapshot.elevation_ratio, kDataColour, true});
    plots.push_back(plot);
  }
  write_png(tile_plots(plots, 2), output_folder(run_name) / (run_name + ".png"));
  EXPECT_LE(std::abs(relative_error), tolerance) << "H/d = " << height_ratio;
}

// OAR PMEL-135 (Synolakis et al. 2007), the NTHMP standard, asks laboratory benchmarks to be met
// within 10 %. The case file's d/20 grid is already fine for this long wave, so CI holds 10 % too.
TEST(VALIDATION_SUITE(Synolakis1987), RunupOfTheNonBreakingSolitaryWave) {
  check_synolakis(0.0185, "Case0_0185", "synolakis", 0.10);
}

// The breaking wave (H/d = 0.3) collapses into a bore on the beach face: the solver's breaking
// model and moving shoreline both work hard. NTHMP's 10 % at full resolution; CI (d/20) 20 %.
TEST(VALIDATION_SUITE(Synolakis1987), RunupOfTheBreakingSolitaryWave) {
  check_synolakis(0.30, "Case0_3", "synolakis_breaking", kFull ? 0.10 : 0.20);
}

}  // namespace
}  // namespace nearshore::validation
