// Deep water inside the domain (issue 14 item 1): a bake over a 74 m channel takes the swell it can
// carry under an effective-depth limit, splits an irregular sea between the bake and the FFT
// deep-water layer with its Hs budget, and refuses only a sea it cannot carry at all, with a band
// and keys that exist. docs/solver.md "Effective depth", docs/commands/bake.md "The spectrum is split".
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/boussinesq/model_dispersion.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::bake {
namespace {

using namespace testing;

// A 1 km flume 74 m deep (the depth of Commencement Bay, issue 14), 5 m cells, waves from the west.
std::string channel_case(const std::string& maker, double spacing_m = 5.0) {
  return "title = \"deep channel\"\n"
         "[bathymetry]\nkind = \"profile\"\nlength_m = 1000.0\nwidth_m = 20.0\nspacing_m = " + std::to_string(spacing_m) + "\n"
         "profile = [[0.0, 74.0], [1000.0, 74.0]]\n"
         "[time]\nduration_s = 24.0\nspin_up_s = 16.0\noutput_interval_s = 4.0\n"
         "[wave_maker]\nfacing = \"west\"\nsource_line_m = 150.0\nramp_time_s = 8.0\n" + maker +
         "[[sponges]]\nside = \"west\"\nwidth_m = 120.0\n[[sponges]]\nside = \"east\"\nwidth_m = 250.0\n";
}

// A swell of 7-8.7 s: k d = 3.8 .. 5.5 over 74 m, beyond the k d = 3 (0.100 Hz, 10 s) the grid
// carries there without a limit; the case the issue saw refused with an inverted band.
const std::string kSwell =
    "kind = \"irregular\"\nsignificant_height_m = 1.0\npeak_period_s = 8.0\nfrequency_count = 16\n"
    "min_frequency_hz = 0.115\nmax_frequency_hz = 0.14\n";

TEST(BakeEffectiveDepth, SwellOverADeepChannelBakesUnderTheLimit) {
  ProgressBar::set_quiet(true);
  const auto folder = scratch_folder();
  const BakeCase c = read_bake_case(write_text(folder / "case.toml", channel_case(kSwell)));
  // The whole band is carried (no split) and the solver sees at most the depth where the band's
  // shortest wave has k d = 3.
  EXPECT_FALSE(c.wave_conditions.contains("spectrum_split"));
  double highest = 0.0;
  for (const auto& component : c.wave_maker.sea_state.components) highest = std::max(highest, component.angular_frequency_rad_s);
  EXPECT_NEAR(c.solver.effective_depth_limit_m, boussinesq::effective_depth_limit_m(highest), 1e-9);
  EXPECT_LT(c.solver.effective_depth_limit_m, 74.0);
  EXPECT_GT(c.solver.effective_depth_limit_m, 30.0);
  EXPECT_DOUBLE_EQ(c.solver_record["effective_depth_limit_m"].get<double>(), c.solver.effective_depth_limit_m);
  // And it bakes: the waves arrive and stay finite.
  BakeOptions options;
  options.output_folder = folder / "out";
  const BakeSummary summary = run_bake(c, options);
  EXPECT_EQ(summary.frames, 3);
  EXPECT_TRUE(std::filesystem::exists(options.output_folder / "manifest.json"));
  EXPECT_NE(describe_carried_band(c).find("effective depth: the equations see at most"), std::string::npos);
}

TEST(BakeEffectiveDepth, AGivenLimitIsKeptAndZeroTurnsItOff) {
  const auto folder = scratch_folder();
  std::string text = channel_case("kind = \"regular\"\nheight_m = 0.5\nperiod_s = 8.0\n");
  // A regular 8 s wave (k d = 4.6 over 74 m) gets the limit where its k d = 3: 47.5 m.
  EXPECT_NEAR(read_bake_case(write_text(folder / "a.toml", text)).solver.effective_depth_limit_m, 47.47, 0.01);
  text += "[solver]\neffective_depth_limit_m = 0.0\n";
  EXPECT_DOUBLE_EQ(read_bake_case(write_text(folder / "b.toml", text)).solver.effective_depth_limit_m, 0.0);
  text.replace(text.find("= 0.0\n", text.find("effective_depth_limit_m")), 6, "= 40.0\n");
  EXPECT_DOUBLE_EQ(read_bake_case(write_text(folder / "c.toml", text)).solver.effective_depth_limit_m, 40.0);
}

// The grid-scale filter's default reads the depth the equations see (docs/solver.md, "Grid-scale
// filter"): 15 m cells over the 74 m channel are finer than a quarter of its true depth but not of
// the 47.5 m the 8 s wave's limit leaves, so the filter is off, as on a harbour grid; without the
// limit the equations see 74 m and the filter is on. Measured on the true depth, Commencement Bay's
// 12 m bake got the filter and its mode beside a staircase shore (Hs 7.4 m under a 0.34 m swell).
TEST(BakeEffectiveDepth, TheGridScaleFilterFollowsTheDepthTheEquationsSee) {
  const auto folder = scratch_folder();
  std::string text = channel_case("kind = \"regular\"\nheight_m = 0.5\nperiod_s = 8.0\n", 15.0);
  const BakeCase limited = read_bake_case(write_text(folder / "limited.toml", text));
  ASSERT_NEAR(limited.solver.effective_depth_limit_m, 47.47, 0.01);
  EXPECT_EQ(limited.solver.shapiro_filter_order, 0);
  EXPECT_EQ(limited.solver_record["shapiro_filter_order"].get<int>(), 0);
  const std::string report = describe_derived_solver_settings(limited);
  RecordProperty("report", report);
  EXPECT_NE(report.find("not finer than 1/4 of the 47.5 m deepest water the equations see"), std::string::npos) << report;
  text += "[solver]\neffective_depth_limit_m = 0.0\n";
  const BakeCase unlimited = read_bake_case(write_text(folder / "unlimited.toml", text));
  EXPECT_EQ(unlimited.solver.shapiro_filter_order, boussinesq::SolverParameters{}.shapiro_filter_order);
}

// Where the grid is nowhere deeper than k d = 3 for the band, the limit is inactive: such a case
// runs exactly as before the limit existed (the shared laboratory cases are all of this kind).
TEST(BakeEffectiveDepth, InactiveWhereTheBandStaysWithinKdThree) {
  const BakeCase c = read_bake_case(write_text(scratch_folder() / "case.toml", small_flume_case()));
  EXPECT_DOUBLE_EQ(c.solver.effective_depth_limit_m, 0.0);
  EXPECT_DOUBLE_EQ(c.solver_record["effective_depth_limit_m"].get<double>(), 0.0);
}

// Every shared case the repository ships that reads here (the demo harbour's need its grid from
// `nearshore demo`) keeps the limit inactive: its results are those of the solver before the limit.
TEST(BakeEffectiveDepth, InactiveInEverySharedCase) {
  int read = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(NEARSHORE_SOURCE_DIR) / "data" / "cases")) {
    if (entry.path().extension() != ".toml") continue;
    // The real chart's case needs the limit (a 168 m deep bay; docs/commands/bake.md, "Example: a
    // real chart"): it was written with it, so no result of it predates the limit.
    if (entry.path().filename() == "tacoma.toml") continue;
    try {
      const BakeCase c = read_bake_case(entry.path());
      EXPECT_DOUBLE_EQ(c.solver.effective_depth_limit_m, 0.0) << entry.path();
      ++read;
    } catch (const Error& error) {
      std::printf("not read here: %s\n", error.what());  // a grid that is not on this machine
    }
  }
  EXPECT_GE(read, 3);  // berkhoff, berkhoff_rect, mase_kirby, synolakis
}

// A deep-water maker over the channel asking for a band beyond k d = 3 at 74 m: the coupling sees
// the limited depth the solver sees (source line, drift model), the field keeps the true depth.
TEST(BakeEffectiveDepth, DeepWaterCouplingSeesTheLimitedDepth) {
  const std::string maker = "kind = \"deep_water\"\nloop_period_s = 480.0\nmin_frequency_hz = 0.1\nmax_frequency_hz = 0.125\n";
  const std::string field =
      "[deep_water]\nspectrum = \"jonswap\"\nsignificant_height_m = 1.0\npeak_period_s = 8.5\nspreading_s = 10.0\n"
      "grid_size = 64\ncascade_count = 1\nseed = 5\n";
  const BakeCase c = read_bake_case(write_text(scratch_folder() / "case.toml", channel_case(maker) + field));
  ASSERT_TRUE(c.deep_water_maker.has_value());
  const double limit_m = c.solver.effective_depth_limit_m;
  EXPECT_GT(limit_m, 0.0);
  EXPECT_LT(limit_m, 74.0);
  EXPECT_NEAR(c.deep_water_maker->source_depth_m, limit_m, 1e-4);  // float cells, as the solver holds them
  for (double depth_m : c.deep_water_maker->inland.depth_m) EXPECT_LE(depth_m, limit_m + 1e-4);
  EXPECT_NEAR(c.deep_water->still_water_depth_m, 74.0, 1e-9);  // the field: Airy over the true depth
  EXPECT_FALSE(c.wave_maker.sea_state.components.empty());
  // The default band (no max_frequency_hz) stays what 74 m carries without a limit: no limit.
  std::string by_default = maker;
  by_default.replace(by_default.find("max_frequency_hz = 0.125\n"), 25, "");
  EXPECT_DOUBLE_EQ(read_bake_case(write_text(scratch_folder() / "default.toml", channel_case(by_default) + field))
                       .solver.effective_depth_limit_m, 0.0);
}

// A broad JONSWAP swell (the automatic 99.5 % band) over the channel: the bake keeps what it
// carries, the rest is left to the deep-water layer, and the variances add up.
TEST(BakeEffectiveDepth, BroadSeaIsSplitWithItsHsBudget) {
  const std::string sea =
      "kind = \"irregular\"\nsignificant_height_m = 1.0\npeak_period_s = 8.0\nfrequency_count = 48\nseed = 3\n";
  const BakeCase c = read_bake_case(write_text(scratch_folder() / "case.toml", channel_case(sea)));
  ASSERT_TRUE(c.wave_conditions.contains("spectrum_split"));
  const auto& split = c.wave_conditions["spectrum_split"];
  const double bake_m = split["bake_significant_wave_height_m"], left_m = split["deep_water_significant_wave_height_m"];
  const double total_m = split["total_significant_wave_height_m"];
  EXPECT_NEAR(bake_m * bake_m + left_m * left_m, total_m * total_m, 1e-9 * total_m * total_m);
  EXPECT_GT(bake_m, 0.0);
  EXPECT_GT(left_m, 0.0);
  EXPECT_EQ(split["bake_components"].get<int>() + split["deep_water_components"].get<int>(), 48);
  EXPECT_EQ(static_cast<int>(c.wave_maker.sea_state.components.size()), split["bake_components"].get<int>());
  EXPECT_LT(split["bake_min_frequency_hz"].get<double>(), split["bake_max_frequency_hz"].get<double>());
  EXPECT_FALSE(split["deep_water_layer_present"].get<bool>());
  // The bake's report prints the budget, and says that without [deep_water] nothing draws the rest.
  const std::string report = describe_carried_band(c);
  EXPECT_NE(report.find("spectrum split: Hs 1.00 m"), std::string::npos) << report;
  EXPECT_NE(report.find("add one"), std::string::npos) << report;
  std::printf("%s\n", report.c_str());
  // Every baked component lies inside the recorded band.
  for (const auto& component : c.wave_maker.sea_state.components)
    EXPECT_LE(component.angular_frequency_rad_s / (2 * std::numbers::pi), split["bake_max_frequency_hz"].get<double>() * (1 + 1e-12));
}

// The wind sea (Hs 0.6 m, Tp 3.5 s) on 10 m cells: nothing of it is carried (8 cells per
// wavelength need waves of 80 m, 7 s), so it is refused, with a correct band and existing keys.
TEST(BakeEffectiveDepth, SeaTheGridCannotCarryIsRefusedWithACellSize) {
  const std::string wind_sea = "kind = \"irregular\"\nsignificant_height_m = 0.6\npeak_period_s = 3.5\n";
  expect_case_error(channel_case(wind_sea, 10.0), {"key `wave_maker`", "all above", "use cells of at most"});
  try {
    read_bake_case(write_text(scratch_folder() / "case.toml", channel_case(wind_sea, 10.0)));
  } catch (const Error& error) {
    const std::string message = error.what();
    std::printf("%s\n", message.c_str());
    EXPECT_EQ(message.find("rad_s"), std::string::npos) << message;
    EXPECT_EQ(message.find("max_frequency_hz = "), std::string::npos) << message;  // no (inverted) band proposed
  }
  // An inverted band given by hand names the case file's keys, in Hz.
  expect_case_error(channel_case(wind_sea + "min_frequency_hz = 0.196\nmax_frequency_hz = 0.100\n"),
                    {"key `wave_maker.min_frequency_hz`", "is not below wave_maker.max_frequency_hz"});
}

// The case: a swell split between the bake and the FFT layer, and the bay's own wind sea
// (Hs 0.6 m, Tp 3.5 s) given to the FFT layer alone ([[deep_water.local_sea]]). Independent seas:
// the layer's Hs is sqrt(1.0^2 + 0.6^2) = 1.166 m (the registry's quadrature to 0.1 %), the bake's
// components stay the swell's, and the report names the local sea.
TEST(BakeEffectiveDepth, LocalWindSeaGoesToTheDeepWaterLayerAlone) {
  const std::string swell =
      "kind = \"irregular\"\nsignificant_height_m = 1.0\npeak_period_s = 8.0\nfrequency_count = 48\nseed = 3\n"
      "spreading_s = 75.0\nloop_period_s = 240.0\n";
  const std::string deep_water =
      "[deep_water]\ngrid_size = 64\n"
      "[[deep_water.local_sea]]\nspectrum = \"jonswap\"\nsignificant_height_m = 0.6\npeak_period_s = 3.5\n"
      "mean_direction_deg = 10.0\nspreading_s = 20.0\n";
  const BakeCase without = read_bake_case(write_text(scratch_folder() / "swell.toml", channel_case(swell) + "[deep_water]\ngrid_size = 64\n"));
  const BakeCase c = read_bake_case(write_text(scratch_folder() / "case.toml", channel_case(swell) + deep_water));
  ASSERT_TRUE(c.deep_water.has_value());
  EXPECT_NEAR(c.deep_water->spectrum->significant_wave_height_m(), std::hypot(1.0, 0.6), 1e-3 * std::hypot(1.0, 0.6));
  ASSERT_EQ(c.wave_maker.sea_state.components.size(), without.wave_maker.sea_state.components.size());
  for (std::size_t i = 0; i < c.wave_maker.sea_state.components.size(); ++i)
    EXPECT_EQ(c.wave_maker.sea_state.components[i].amplitude_m, without.wave_maker.sea_state.components[i].amplitude_m);
  ASSERT_TRUE(c.wave_conditions.contains("local_seas"));
  const auto& sea = c.wave_conditions["local_seas"][0];
  EXPECT_NEAR(sea["significant_wave_height_m"].get<double>(), 0.6, 1e-3 * 0.6);
  // A 3.5 s JONSWAP holds almost nothing below the swell's split frequency (about 0.1 Hz).
  EXPECT_LT(sea["below_split_significant_wave_height_m"].get<double>(), 0.01);
  const std::string report = describe_carried_band(c);
  EXPECT_NE(report.find("local sea: Hs 0.60 m"), std::string::npos) << report;
  // A field that drives the wave maker would make the local sea at the source line too: refused.
  expect_case_error(channel_case(swell) + "[deep_water]\ngrid_size = 64\ndrive_wave_maker = true\n"
                        "[[deep_water.local_sea]]\nspectrum = \"jonswap\"\nsignificant_height_m = 0.6\npeak_period_s = 3.5\n",
                    {"key `deep_water.local_sea`", "drives the wave maker"});
  // An unknown key in a local sea is named with its place.
  expect_case_error(channel_case(swell) + deep_water + "fetch_km = 5.0\n", {"deep_water.local_sea[0].fetch_km"});
}

}  // namespace
}  // namespace nearshore::bake
