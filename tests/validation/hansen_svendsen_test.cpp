// Hansen & Svendsen (1979): regular waves shoaling and breaking on a 1:34.26 slope (issue 19).
// Case data/cases/hansen_svendsen.toml (test 031041, plunging) run through the bake road, and test
// 061071 (spilling) from the same file with its period and height; the wave height and the mean
// water level at every measured point (data/validation/hansen_svendsen_1979/, x from the slope's
// toe) against the model's gauges there. Numbers and plots: docs/validation.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <fmt/core.h>
#include <gtest/gtest.h>

#include "laboratory_data.hpp"
#include "nearshore/bake/bake_gauges.hpp"
#include "validation_bake.hpp"
#include "validation_plots.hpp"

namespace nearshore::validation {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

struct HansenSvendsenPoint {
  double x_m = 0, wave_height_m = 0, mean_level_m = 0;  // x from the toe of the slope
};

// A table of the folder: '#' comment lines, then "x_m wave_height_m mean_water_level_m" (the README):
// the measurements test_<id>.txt and FUNWAVE-TVD's published results funwave_tvd_<id>_<closure>.txt.
std::vector<HansenSvendsenPoint> read_hansen_svendsen_table(const std::string& file_name) {
  const fs::path path = fs::path(NEARSHORE_SOURCE_DIR) / "data" / "validation" / "hansen_svendsen_1979" / file_name;
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path.string() + ": cannot open");
  std::vector<HansenSvendsenPoint> points;
  for (std::string line; std::getline(file, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    HansenSvendsenPoint p;
    if (!(fields >> p.x_m >> p.wave_height_m >> p.mean_level_m)) throw std::runtime_error(path.string() + ": bad line '" + line + "'");
    points.push_back(p);
  }
  return points;
}
std::vector<HansenSvendsenPoint> read_hansen_svendsen(const std::string& test_id) { return read_hansen_svendsen_table("test_" + test_id + ".txt"); }

TEST(VALIDATION_SUITE(LaboratoryData), HansenSvendsenTablesHoldTheReadmesBreakPoints) {
  const auto plunging = read_hansen_svendsen("031041"), spilling = read_hansen_svendsen("061071");
  ASSERT_EQ(plunging.size(), 40u);
  ASSERT_EQ(spilling.size(), 41u);
  auto highest = [](const std::vector<HansenSvendsenPoint>& points) {
    return *std::max_element(points.begin(), points.end(),
                             [](const auto& a, const auto& b) { return a.wave_height_m < b.wave_height_m; });
  };
  EXPECT_NEAR(highest(plunging).x_m, 9.15, 0.01);  // the README: breaks at 9.15 m, H = 0.094 m
  EXPECT_NEAR(highest(plunging).wave_height_m, 0.094, 0.0005);
  EXPECT_NEAR(highest(spilling).x_m, 8.22, 0.01);  // 8.22 m, H = 0.104 m
  EXPECT_NEAR(highest(spilling).wave_height_m, 0.104, 0.0005);
}

struct HansenSvendsenScore {
  double height_rmse_m = 0, level_rmse_m = 0, offshore_height_m = 0;
  double shoaling_height_rmse_m = 0, surf_zone_height_rmse_m = 0;  // before / after the measured break point
  double model_break_x_m = 0, data_break_x_m = 0;          // where the largest height is
  double set_down_before_break_m = 0, set_up_at_last_point_m = 0;  // model, relative to the toe
  // The set-up RMSE up to and including the measured break point, and after it: where the wave
  // closure's set-down is judged, and where the surf zone's (the roller's delay, docs/validation.md).
  double set_up_rmse_to_break_m = 0, set_up_rmse_after_break_m = 0;
  std::vector<double> set_up_model_m, set_up_data_m;        // at the measured points, relative to the toe
  // The experiment's bars: FUNWAVE-TVD's published result, scored the same way (the better of its
  // closures; the eddy-viscosity one, published for 031041 only, is printed beside it).
  double reference_height_rmse_m = 0, reference_level_rmse_m = 0;
};
// Regression bars kept beside the experiment's where they are tighter: the CI grid's H RMSE / H0 at
// most 13 % (the bar of 031041 is 14.0 %), and the set-up RMSE at most 1.3 mm on both grids (the bar
// of 061071 is 2.21 mm). Set on 2026-11-27 from the scores then (CI grid 11.2 % and 11.4 %, 0.70
// and 0.84 mm) plus a margin; the scores since 2026-11-29 are well inside them (the test below).
constexpr double kHeightRegressionBar = 0.13;
constexpr double kSetUpRegressionBar_m = 0.0013;

// Scores heights and mean levels at the measured points against the data: the whole profile, the
// shoaling zone (before the measured break point) and the surf zone (after it), the break point, and
// the set-up. The mean level is compared relative to its value at the toe (the first point), for the
// model and the data alike. The flume was closed and at rest before the waves, and its level at the
// toe is within 0.1 mm of still water. A model's reference may differ: ours is the sponge behind the
// source, where the waves have died out: across the sponge the radiation stress S_xx of the waves
// leaving into it falls to zero, so the whole wave region sits S_xx / (rho g d) =
// (a^2 / 2)(2 n - 1/2) / d below it (0.8 mm for 031041, 1.9 mm for 061071; the model shows 0.6 and
// 1.6 mm at the toe). That offset is where the level is pinned, not the slope's set-down and set-up
// that the experiment measured.
HansenSvendsenScore score_against_data(const std::vector<HansenSvendsenPoint>& data, const std::vector<double>& h_model,
                                       const std::vector<double>& level_model) {
  std::vector<double> x, h_data;
  for (const auto& point : data) {
    x.push_back(point.x_m);
    h_data.push_back(point.wave_height_m);
  }
  const std::size_t data_break = std::max_element(h_data.begin(), h_data.end()) - h_data.begin();
  const std::size_t model_break = std::max_element(h_model.begin(), h_model.end()) - h_model.begin();
  auto zone_rmse = [&](std::size_t begin, std::size_t end) {
    return root_mean_square_error(std::vector<double>(h_model.begin() + begin, h_model.begin() + end),
                                  std::vector<double>(h_data.begin() + begin, h_data.begin() + end));
  };
  HansenSvendsenScore score;
  for (std::size_t i = 0; i < x.size(); ++i) {
    score.set_up_model_m.push_back(level_model[i] - level_model.front());
    score.set_up_data_m.push_back(data[i].mean_level_m - data.front().mean_level_m);
  }
  score.height_rmse_m = root_mean_square_error(h_model, h_data);
  score.level_rmse_m = root_mean_square_error(score.set_up_model_m, score.set_up_data_m);
  score.offshore_height_m = h_data.front();
  score.shoaling_height_rmse_m = zone_rmse(0, data_break);
  score.surf_zone_height_rmse_m = zone_rmse(data_break + 1, h_data.size());
  auto set_up_zone_rmse = [&](std::size_t begin, std::size_t end) {
    return root_mean_square_error(std::vector<double>(score.set_up_model_m.begin() + begin, score.set_up_model_m.begin() + end),
                                  std::vector<double>(score.set_up_data_m.begin() + begin, score.set_up_data_m.begin() + end));
  };
  score.set_up_rmse_to_break_m = set_up_zone_rmse(0, data_break + 1);
  score.set_up_rmse_after_break_m = set_up_zone_rmse(data_break + 1, x.size());
  score.model_break_x_m = x[model_break];
  score.data_break_x_m = x[data_break];
  for (std::size_t i = 0; i < x.size() && x[i] < score.data_break_x_m; ++i)
    score.set_down_before_break_m = std::min(score.set_down_before_break_m, score.set_up_model_m[i]);
  score.set_up_at_last_point_m = score.set_up_model_m.back();
  return score;
}

// Linear interpolation of a profile table at x (constant beyond its ends).
double interpolate(const std::vector<HansenSvendsenPoint>& table, double x_m, double HansenSvendsenPoint::*field) {
  if (x_m <= table.front().x_m) return table.front().*field;
  for (std::size_t i = 1; i < table.size(); ++i)
    if (x_m <= table[i].x_m) {
      const double w = (x_m - table[i - 1].x_m) / (table[i].x_m - table[i - 1].x_m);
      return (1 - w) * (table[i - 1].*field) + w * (table[i].*field);
    }
  return table.back().*field;
}

// The reference: FUNWAVE-TVD's own published result for this experiment (data/validation/
// hansen_svendsen_1979/README.md), scored by the same function at the measured points. Its stations
// are 0.1 m apart; linear interpolation between them moves H by at most (0.1 m)^2 / 8 |H''|, a few
// hundredths of a millimetre on the shoaling slope (H'' < 0.02 1/m there).
struct ReferenceResult {
  std::string closure;
  std::vector<HansenSvendsenPoint> profile;
  HansenSvendsenScore score;
};
ReferenceResult score_reference(const std::vector<HansenSvendsenPoint>& data, const std::string& test_id, const std::string& closure) {
  ReferenceResult reference{closure, read_hansen_svendsen_table("funwave_tvd_" + test_id + "_" + closure + ".txt"), {}};
  std::vector<double> h, level;
  for (const auto& point : data) {
    h.push_back(interpolate(reference.profile, point.x_m, &HansenSvendsenPoint::wave_height_m));
    level.push_back(interpolate(reference.profile, point.x_m, &HansenSvendsenPoint::mean_level_m));
  }
  reference.score = score_against_data(data, h, level);
  return reference;
}

// Runs one test and scores it. The gauges sit at the measured points (toe at x = 16 m in the case
// frame, on the flume's centre line); H is the mean crest-to-trough height and the mean level the
// mean over the whole periods of [spin-up, end].
HansenSvendsenScore run_hansen_svendsen(const std::string& test_id, double period_s, double height_m, std::vector<LinePlot>& plots) {
  const std::vector<HansenSvendsenPoint> data = read_hansen_svendsen(test_id);
  const std::string run_name = "hansen_svendsen_" + test_id;
  constexpr double kToe_m = 16.0;
  double spin_up_s = 0, end_s = 0;
  const auto summary = bake_case("hansen_svendsen", run_name, [&](json& document) {
    if (!kFull) {
      // CI: cells twice as large (0.05 m: 31 per wavelength at the 061071 break point, 63 at 031041's),
      // still three across.
      document["bathymetry"]["spacing_m"] = 2 * document["bathymetry"]["spacing_m"].get<double>();
      document["bathymetry"]["width_m"] = 2 * document["bathymetry"]["width_m"].get<double>();
    }
    document["wave_maker"]["period_s"] = period_s;
    document["wave_maker"]["height_m"] = height_m;
    document["wave_maker"]["ramp_time_s"] = 2 * period_s;
    document["gauges"] = json::array();
    const double centre_y = 0.5 * document["bathymetry"]["width_m"].get<double>();
    for (std::size_t i = 0; i < data.size(); ++i) add_gauge(document, fmt::format("p{:02d}", i), kToe_m + data[i].x_m, centre_y);
    spin_up_s = document["time"]["spin_up_s"].get<double>();
    end_s = document["time"]["duration_s"].get<double>();
  });
  const bake::GaugeTable gauges = bake::read_gauges_csv(summary.gauges_csv);
  // Whole periods ending at the end of the run, starting at or after the spin-up.
  const double start_s = end_s - std::floor((end_s - spin_up_s) / period_s) * period_s;
  std::size_t first = 0, last = 0;
  while (first < gauges.time_s.size() && gauges.time_s[first] < start_s - 1e-9) ++first;
  last = gauges.time_s.size();
  std::vector<double> x, h_model, h_data, level_model, level_data;
  json results = {{"cells", summary.cells}, {"time_step_s", summary.time_step_s}, {"window_s", {start_s, end_s}},
                  {"period_s", period_s}, {"requested_height_m", height_m}};
  for (std::size_t i = 0; i < data.size(); ++i) {
    const auto& column = bake::gauge_column(gauges, fmt::format("p{:02d}", i));
    x.push_back(data[i].x_m);
    h_model.push_back(mean_wave_height_m(gauges.time_s, column, period_s, start_s, end_s));
    level_model.push_back(mean_level_m(column, first, last));
    h_data.push_back(data[i].wave_height_m);
    level_data.push_back(data[i].mean_level_m);
    results["points"].push_back({{"x_m", x.back()}, {"height_model_m", h_model.back()}, {"height_data_m", h_data.back()},
                                 {"mean_level_model_m", level_model.back()}, {"mean_level_data_m", level_data.back()}});
  }
  HansenSvendsenScore score = score_against_data(data, h_model, level_model);
  // The field's reference model on the same experiment (README): shock-capturing for both tests,
  // and for 031041 also the eddy-viscosity closure, the one this solver's default follows.
  std::vector<ReferenceResult> references{score_reference(data, test_id, "shock_capturing")};
  if (test_id == "031041") references.push_back(score_reference(data, test_id, "eddy_viscosity"));
  score.reference_height_rmse_m = references.front().score.height_rmse_m;
  score.reference_level_rmse_m = references.front().score.level_rmse_m;
  for (const ReferenceResult& reference : references) {
    score.reference_height_rmse_m = std::min(score.reference_height_rmse_m, reference.score.height_rmse_m);
    score.reference_level_rmse_m = std::min(score.reference_level_rmse_m, reference.score.level_rmse_m);
  }
  const std::size_t data_break = std::max_element(h_data.begin(), h_data.end()) - h_data.begin();
  const std::size_t model_break = std::max_element(h_model.begin(), h_model.end()) - h_model.begin();
  results["mean_level_at_toe_model_m"] = level_model.front();
  results["height_rmse_m"] = score.height_rmse_m;
  results["set_up_rmse_m"] = score.level_rmse_m;  // relative to the toe
  results["shoaling_height_rmse_m"] = score.shoaling_height_rmse_m;
  results["surf_zone_height_rmse_m"] = score.surf_zone_height_rmse_m;
  results["set_up_rmse_to_break_m"] = score.set_up_rmse_to_break_m;
  results["set_up_rmse_after_break_m"] = score.set_up_rmse_after_break_m;
  results["break_point"] = {{"data_x_m", x[data_break]}, {"data_height_m", h_data[data_break]},
                            {"model_x_m", x[model_break]}, {"model_height_m", h_model[model_break]}};
  std::printf("Hansen-Svendsen %s (T = %.2f s, H = %.4f m): H RMSE %.4f m (%.1f %% of H0), shoaling %.4f m, surf zone %.4f m; "
              "break point model x = %.2f m H = %.4f m, data x = %.2f m H = %.4f m; set-up RMSE (from the toe) %.2f mm (to the measured break "
              "point %.2f mm, after it %.2f mm; set-up data %.2f mm at %.2f m, model %.2f mm); model level at the toe %+.2f mm\n",
              test_id.c_str(), period_s, height_m, score.height_rmse_m, 100 * score.height_rmse_m / score.offshore_height_m,
              score.shoaling_height_rmse_m, score.surf_zone_height_rmse_m, x[model_break], h_model[model_break], x[data_break],
              h_data[data_break], 1000 * score.level_rmse_m, 1000 * score.set_up_rmse_to_break_m, 1000 * score.set_up_rmse_after_break_m,
              1000 * score.set_up_data_m.back(), x.back(), 1000 * score.set_up_at_last_point_m,
              1000 * level_model.front());
  for (const ReferenceResult& reference : references) {
    const HansenSvendsenScore& r = reference.score;
    std::printf("  reference FUNWAVE-TVD (%s, published): H RMSE %.4f m (%.1f %% of H0), shoaling %.4f m, surf zone %.4f m; "
                "break point x = %.2f m; set-up RMSE %.2f mm (to the measured break point %.2f mm, after it %.2f mm); H at the toe %.4f m\n",
                reference.closure.c_str(), r.height_rmse_m, 100 * r.height_rmse_m / r.offshore_height_m, r.shoaling_height_rmse_m,
                r.surf_zone_height_rmse_m, r.model_break_x_m, 1000 * r.level_rmse_m, 1000 * r.set_up_rmse_to_break_m,
                1000 * r.set_up_rmse_after_break_m, reference.profile.front().wave_height_m);
    results["reference_funwave_tvd"][reference.closure] = {{"height_rmse_m", r.height_rmse_m}, {"set_up_rmse_m", r.level_rmse_m},
                                                           {"shoaling_height_rmse_m", r.shoaling_height_rmse_m},
                                                           {"surf_zone_height_rmse_m", r.surf_zone_height_rmse_m},
                                                           {"set_up_rmse_to_break_m", r.set_up_rmse_to_break_m},
                                                           {"set_up_rmse_after_break_m", r.set_up_rmse_after_break_m}};
  }
  for (std::size_t i = 0; i < x.size(); ++i)
    std::printf("  x %.2f m: H model %.4f data %.4f m, mean level model %+.2f data %+.2f mm\n", x[i], h_model[i], h_data[i],
                1000 * level_model[i], 1000 * level_data[i]);
  write_results(run_name, results);
  const std::string what = fmt::format("test {} (T = {:.2f} s)", test_id, period_s);
  LinePlot height_plot{"Hansen & Svendsen (1979) " + what + ": wave height", "x from the toe of the 1:34.26 slope (m)", "H (m)", {}, 720, 400};
  height_plot.series.push_back({"model", x, h_model, kModelColour, false});
  height_plot.series.push_back({"measured", x, h_data, kDataColour, true});
  const ReferenceResult& reference = references.front();
  std::vector<double> reference_x, reference_h, reference_set_up;
  for (const auto& point : reference.profile)
    if (point.x_m <= x.back() + 0.05) {
      reference_x.push_back(point.x_m);
      reference_h.push_back(point.wave_height_m);
      reference_set_up.push_back(point.mean_level_m - reference.profile.front().mean_level_m);
    }
  height_plot.series.push_back({"FUNWAVE-TVD (published)", reference_x, reference_h, kReferenceColour, false});
  LinePlot level_plot{what + ": mean water level, relative to the toe", "x from the toe of the 1:34.26 slope (m)", "mean eta - mean eta at x = 0 (m)", {}, 720, 400};
  level_plot.series.push_back({"model", x, score.set_up_model_m, kModelColour, false});
  level_plot.series.push_back({"measured", x, score.set_up_data_m, kDataColour, true});
  level_plot.series.push_back({"FUNWAVE-TVD (published)", reference_x, reference_set_up, kReferenceColour, false});
  plots.push_back(height_plot);
  plots.push_back(level_plot);
  return score;
}

TEST(VALIDATION_SUITE(HansenSvendsen1979), WaveHeightAndSetUpOnTheSlope) {
  std::vector<LinePlot> plots;
  // Test 031041 as the case file holds it, 061071 with its own period and the height at its toe.
  const HansenSvendsenScore plunging = run_hansen_svendsen("031041", 3.33, 0.0411, plots);
  const HansenSvendsenScore spilling = run_hansen_svendsen("061071", 1.0 / 0.6, 0.0686, plots);
  fs::create_directories(output_folder("hansen_svendsen"));
  write_png(tile_plots(plots, 2), output_folder("hansen_svendsen") / "hansen_svendsen.png");
  // The experiment's bars (docs/validation.md, "Hansen & Svendsen"): what the field's reference model
  // reaches on this very experiment, scored by the same function: FUNWAVE-TVD's own published result
  // (README; H RMSE 14.0 % of H0 for 031041 with its shock-capturing closure, 16.6 % with its eddy
  // viscosity, 11.5 % for 061071; set-up RMSE 0.67 (0.77 eddy viscosity) and 2.21 mm). That result
  // was itself set up for this case (a wave maker requested 17 % below the measured toe height, 0.034
  // against 0.0411 m, whose wave reaches the toe 9 % low, and a breaking onset of 1.0 sqrt(g h)
  // instead of its default 0.65), so reaching it with published defaults is a fair
  // bar, not a lax one. With issue 19's defaults (fully nonlinear equations, second-order generation,
  // the breaking event travelling with the front, Kennedy et al.'s thresholds on the still-water
  // depth, and since 2026-11-29 the fully nonlinear terms fading where cells break) both tests meet
  // all four bars on both grids (full: H 12.2 % and 9.7 %, set-up 0.47 and 0.35 mm; CI: 10.3 % and
  // 10.2 %, 0.47 and 0.37 mm; before the fade 031041's set-up was 0.76 mm, docs/validation.md), and
  // both grids assert them, beside the regression bars where those are tighter. Every score is
  // printed against its bar.
  for (const HansenSvendsenScore& score : {plunging, spilling}) {
    std::printf("Hansen-Svendsen: H RMSE %.1f %% of H0 (the experiment's bar, FUNWAVE-TVD's published %.1f %%: %s), set-up RMSE "
                "%.2f mm (FUNWAVE-TVD's %.2f mm: %s)\n",
                100 * score.height_rmse_m / score.offshore_height_m, 100 * score.reference_height_rmse_m / score.offshore_height_m,
                score.height_rmse_m <= score.reference_height_rmse_m ? "met" : "MISSED", 1000 * score.level_rmse_m,
                1000 * score.reference_level_rmse_m, score.level_rmse_m <= score.reference_level_rmse_m ? "met" : "MISSED");
    EXPECT_LE(score.height_rmse_m, score.reference_height_rmse_m);
    EXPECT_LE(score.level_rmse_m, score.reference_level_rmse_m);
    if (!kFull) {
      EXPECT_LE(score.height_rmse_m, kHeightRegressionBar * score.offshore_height_m);
    }
    EXPECT_LE(score.level_rmse_m, kSetUpRegressionBar_m);
    // What the model must get right whatever its breaking: the break point (the largest height) within
    // one surf-zone wavelength of the measured one, set-down before it and set-up after it.
    EXPECT_LE(std::abs(score.model_break_x_m - score.data_break_x_m), 1.2);
    EXPECT_LT(score.set_down_before_break_m, 0.0);
    EXPECT_GT(score.set_up_at_last_point_m, 0.0);
  }
}

}  // namespace
}  // namespace nearshore::validation
