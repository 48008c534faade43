// Briggs et al. (1995): a solitary wave round a conical island (NTHMP benchmark problem 6). The
// case data/cases/conical_island.toml (case A; B and C with their heights) on the grid that
// scripts/conical_island_grid.awk writes, run through the bake road; the surface elevation at the
// four island gauges against the measurements (data/validation/briggs_1995/), and FUNWAVE-TVD's
// own stored run of case A scored by the same function. Numbers and plots: docs/validation.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

constexpr std::array<const char*, 4> kGauges = {"g6", "g9", "g16", "g22"};

// Time and the elevation at gauges 6, 9, 16, 22, as the folder's files hold them.
struct IslandRecord {
  std::vector<double> time_s;
  std::array<std::vector<double>, 4> elevation_m;
};

IslandRecord read_island_record(const std::string& file_name) {
  const fs::path path = fs::path(NEARSHORE_SOURCE_DIR) / "data" / "validation" / "briggs_1995" / file_name;
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path.string() + ": cannot open");
  IslandRecord record;
  for (std::string line; std::getline(file, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    double t = 0;
    std::array<double, 4> eta{};
    if (!(fields >> t >> eta[0] >> eta[1] >> eta[2] >> eta[3])) throw std::runtime_error(path.string() + ": bad line '" + line + "'");
    record.time_s.push_back(t);
    for (int g = 0; g < 4; ++g) record.elevation_m[g].push_back(eta[g]);
  }
  return record;
}

std::size_t largest_index(const std::vector<double>& v) {
  return static_cast<std::size_t>(std::max_element(v.begin(), v.end()) - v.begin());
}

struct IslandGaugeScore {
  double crest_measured_m = 0, crest_model_m = 0, crest_ratio = 0;
  double travel_error_s = 0;  ///< (model's crest time - its gauge 6 crest time) - the same measured
  double rms_over_height = 0;  ///< RMS difference over 2 s before to 6 s after the measured crest, / H
};
struct IslandScores {
  double shift_s = 0;  ///< added to the model's clock to put it on the laboratory's
  std::array<IslandGaugeScore, 4> gauges;
};

// Each measured gauge's zero: its mean over the first 2 s (offsets up to 3 mm before the wave, README).
IslandRecord zeroed(IslandRecord record) {
  for (std::vector<double>& gauge : record.elevation_m) {
    double zero = 0;
    int count = 0;
    for (std::size_t i = 0; i < record.time_s.size() && record.time_s[i] < record.time_s.front() + 2.0; ++i) zero += gauge[i], ++count;
    zero /= std::max(count, 1);
    for (double& v : gauge) v -= zero;
  }
  return record;
}

// The model's clock set so that its crest at gauge 6 (the first the wave meets) falls when the
// measured one does: the laboratory's wave maker and a model's initial wave start at different
// times, and every model is compared after such a shift (FUNWAVE-TVD's script adds a fixed lag per
// case). `measured` from its zeros (zeroed). Then per gauge: the crest (the largest elevation
// within the window), the error in the crest's travel time from gauge 6, and the RMS difference in
// the window.
IslandScores score_island(const IslandRecord& measured, const IslandRecord& model, double height_m) {
  const std::array<std::vector<double>, 4>& lab = measured.elevation_m;
  const double lab_crest6_s = measured.time_s[largest_index(lab[0])];
  const double model_crest6_s = model.time_s[largest_index(model.elevation_m[0])];
  const double shift_s = lab_crest6_s - model_crest6_s;
  IslandScores scores;
  scores.shift_s = shift_s;
  for (int g = 0; g < 4; ++g) {
    IslandGaugeScore& s = scores.gauges[g];
    const std::size_t crest = largest_index(lab[g]);
    const double crest_s = measured.time_s[crest];
    s.crest_measured_m = lab[g][crest];
    double sum = 0, model_crest_s = 0;
    int count = 0;
    s.crest_model_m = -1e300;
    for (std::size_t i = 0; i < measured.time_s.size(); ++i) {
      const double t = measured.time_s[i];
      if (t <= crest_s - 2.0 || t >= crest_s + 6.0) continue;
      const double m = sample_at(model.time_s, model.elevation_m[g], t - shift_s);
      if (!std::isfinite(m)) continue;
      if (m > s.crest_model_m) s.crest_model_m = m, model_crest_s = t;
      sum += (m - lab[g][i]) * (m - lab[g][i]);
      ++count;
    }
    s.crest_ratio = s.crest_model_m / s.crest_measured_m;
    s.travel_error_s = (model_crest_s - lab_crest6_s) - (crest_s - lab_crest6_s);
    s.rms_over_height = count > 0 ? std::sqrt(sum / count) / height_m : NAN;
  }
  return scores;
}

IslandRecord model_record(const fs::path& gauges_csv) {
  const bake::GaugeTable table = bake::read_gauges_csv(gauges_csv);
  IslandRecord record;
  record.time_s = table.time_s;
  for (int g = 0; g < 4; ++g) {
    const auto found = std::find(table.names.begin(), table.names.end(), kGauges[g]);
    if (found == table.names.end()) throw std::runtime_error(gauges_csv.string() + ": no gauge " + kGauges[g]);
    record.elevation_m[g] = table.elevation_m[static_cast<std::size_t>(found - table.names.begin())];
  }
  return record;
}

// The grid of scripts/conical_island_grid.awk (the one description of the basin, also the users'),
// at `cell` metres, in the build folder.
fs::path island_grid(double cell_m) {
  const fs::path grid = fs::path(NEARSHORE_BINARY_DIR) / "validation" / fmt::format("conical_island_{:.2f}.asc", cell_m);
  fs::create_directories(grid.parent_path());
  const fs::path script = fs::path(NEARSHORE_SOURCE_DIR) / "scripts" / "conical_island_grid.awk";
  const std::string command = fmt::format("awk -f '{}' -v cell={} > '{}'", script.string(), cell_m, grid.string());
  if (std::system(command.c_str()) != 0) throw std::runtime_error("failed: " + command);
  return grid;
}

// Bars from FUNWAVE-TVD's own stored run of case A scored by the same function (it gives, against
// these data: crest ratios 1.04-1.28, travel-time errors up to +0.32 s, RMS/H up to 0.35; printed
// by the test): a crest within 30 % of the measured, the travel from gauge 6 within 0.35 s (its
// 0.32 s and the records' 0.04 s sampling), RMS/H at most 0.35. Cases B and C (H/d 0.09 and 0.18,
// C breaking on the front slope) are held to the same bars; there is no reference run of them.
// CI's 0.1 m cells: the crest behind the island (where the two waves that wrapped round it meet)
// arrives 0.36 s late in case A (0.12 s on the case's 0.05 m cells), so there 0.5 s.
constexpr double kCrestRatioBar = 0.30, kRmsBar = 0.35;
constexpr double kTravelBar_s = kFull ? 0.35 : 0.50;

void print_scores(const std::string& who, const std::array<IslandGaugeScore, 4>& scores) {
  std::printf("%s\n  gauge  crest measured  model  ratio  travel error  RMS/H\n", who.c_str());
  for (int g = 0; g < 4; ++g)
    std::printf("  %-5s  %13.4f  %6.4f  %5.2f  %+11.2f s  %5.3f\n", kGauges[g], scores[g].crest_measured_m, scores[g].crest_model_m,
                scores[g].crest_ratio, scores[g].travel_error_s, scores[g].rms_over_height);
}

void check_island_case(char name, double height_m) {
  const std::string run_name = fmt::format("conical_island_{}", static_cast<char>(std::tolower(name)));
  // CI: cells of 0.1 m (d / 3.2; the 3.6 m slope 36 cells) instead of the case's 0.05 m.
  const double cell_m = kFull ? 0.05 : 0.10;
  const fs::path grid = island_grid(cell_m);
  const auto summary = bake_case("conical_island", run_name, [&](json& document) {
    document["bathymetry"]["file"] = grid.string();
    document["wave_maker"]["height_m"] = height_m;
  });
  const IslandRecord measured = zeroed(read_island_record(fmt::format("case_{}.txt", static_cast<char>(std::tolower(name)))));
  const IslandRecord model = model_record(summary.gauges_csv);
  const IslandScores scored = score_island(measured, model, height_m);
  const auto& scores = scored.gauges;
  print_scores(fmt::format("conical island, case {} (H = {} m), {} m cells:", name, height_m, cell_m), scores);
  json results = json::array();
  for (int g = 0; g < 4; ++g)
    results.push_back({{"gauge", kGauges[g]},
                       {"crest_measured_m", scores[g].crest_measured_m},
                       {"crest_model_m", scores[g].crest_model_m},
                       {"crest_ratio", scores[g].crest_ratio},
                       {"travel_error_s", scores[g].travel_error_s},
                       {"rms_over_height", scores[g].rms_over_height}});
  write_results(run_name, {{"case", std::string(1, name)}, {"height_m", height_m}, {"cell_m", cell_m}, {"gauges", results}});

  // The figure: each gauge's record, measured (points, from its zero) and model (line), on the
  // laboratory's clock as the scores set it.
  std::vector<LinePlot> plots;
  const double shift_s = scored.shift_s;
  for (int g = 0; g < 4; ++g) {
    const double crest_s = measured.time_s[largest_index(measured.elevation_m[g])];
    LinePlot plot{fmt::format("case {}, gauge {}: crest {:.1f} mm measured, {:.1f} mm model", name, kGauges[g] + 1,  // "g6" -> "6"
                              1000 * scores[g].crest_measured_m, 1000 * scores[g].crest_model_m),
                  "laboratory time (s)", "surface elevation (m)", {}, 640, 300};
    PlotSeries lab{"Briggs et al. (1995)", {}, {}, kDataColour, true}, mod{"model", {}, {}, kModelColour, false};
    for (std::size_t i = 0; i < measured.time_s.size(); ++i)
      if (std::abs(measured.time_s[i] - crest_s) < 6.0) lab.x.push_back(measured.time_s[i]), lab.y.push_back(measured.elevation_m[g][i]);
    for (std::size_t i = 0; i < model.time_s.size(); ++i)
      if (std::abs(model.time_s[i] + shift_s - crest_s) < 6.0) mod.x.push_back(model.time_s[i] + shift_s), mod.y.push_back(model.elevation_m[g][i]);
    plot.series = {lab, mod};
    plots.push_back(plot);
  }
  write_png(tile_plots(plots, 2), output_folder(run_name) / (run_name + ".png"));

  for (int g = 0; g < 4; ++g) {
    EXPECT_LE(std::abs(scores[g].crest_ratio - 1.0), kCrestRatioBar) << "case " << name << ", gauge " << kGauges[g];
    EXPECT_LE(std::abs(scores[g].travel_error_s), kTravelBar_s) << "case " << name << ", gauge " << kGauges[g];
    EXPECT_LE(scores[g].rms_over_height, kRmsBar) << "case " << name << ", gauge " << kGauges[g];
  }
}

// The bars' source: FUNWAVE-TVD's stored case-A run passes them, scored by the same function.
TEST(VALIDATION_SUITE(ConicalIsland), FunwaveTvdsOwnRunOfCaseAMeetsTheBars) {
  const auto scores = score_island(zeroed(read_island_record("case_a.txt")), read_island_record("funwave_tvd_case_a.txt"), 0.0144).gauges;
  print_scores("FUNWAVE-TVD's stored run of case A (its benchmark folder), scored by the same function:", scores);
  for (int g = 0; g < 4; ++g) {
    EXPECT_LE(std::abs(scores[g].crest_ratio - 1.0), kCrestRatioBar) << kGauges[g];
    EXPECT_LE(std::abs(scores[g].travel_error_s), 0.35) << kGauges[g];  // its 0.05 m cells: the full bar
    EXPECT_LE(scores[g].rms_over_height, kRmsBar) << kGauges[g];
  }
  // What the bars rest on (the README's figures): its crest 28 % high on the front slope.
  EXPECT_NEAR(scores[1].crest_ratio, 1.28, 0.01);
}

TEST(VALIDATION_SUITE(ConicalIsland), CaseAGaugesRoundTheIsland) { check_island_case('A', 0.0144); }
TEST(VALIDATION_SUITE(ConicalIsland), CaseBGaugesRoundTheIsland) { check_island_case('B', 0.02912); }
TEST(VALIDATION_SUITE(ConicalIsland), CaseCBreakingOnTheFrontSlope) { check_island_case('C', 0.05792); }

}  // namespace
}  // namespace nearshore::validation
