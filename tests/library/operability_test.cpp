// Operability of berths over a library (issue 39; library/include/nearshore/library/operability.hpp):
// the occurrence table's parser and its refusals, the downtime of (2) against a hand-computed case,
// and a whole computation over a library of two synthetic states of known agitation (sequences
// written with the real sequence writer, the index with the real index writer). Milliseconds.
#include <cmath>
#include <fstream>
#include <numbers>

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/library/operability.hpp"
#include "nearshore/sequence/library_index.hpp"
#include "nearshore/sequence/sequence_writer.hpp"
#include "library_test_files.hpp"

namespace nearshore::library {
namespace {

namespace fs = std::filesystem;
using testing::write_text_file;

fs::path operability_scratch() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path folder = fs::path(NEARSHORE_BINARY_DIR) / "tests" / "library" / "scratch" /
                          (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

std::string error_of(const fs::path& file) {
  try {
    read_occurrence_table(file);
  } catch (const Error& error) {
    return error.what();
  }
  return "no error";
}

TEST(Operability, OccurrenceTableIsReadInEitherDirectionConvention) {
  const fs::path folder = operability_scratch();
  const auto toward = read_occurrence_table(write_text_file(
      folder / "toward.csv", "# a wave climate\nhs_m,tp_s,direction_deg,probability\n0.5,8,90,0.6\n\n1.5, 10, 75, 0.4\n"));
  ASSERT_EQ(toward.size(), 2u);
  EXPECT_DOUBLE_EQ(toward[1].significant_wave_height_m, 1.5);
  EXPECT_DOUBLE_EQ(toward[1].direction_deg, 75.0);
  EXPECT_EQ(toward[1].place, "toward.csv:5");  // line 5: comment, header, row, blank, row
  // From the south (180 nautical) is travelling north, 90 counter-clockwise from east; from the
  // north-west (315) travels south-east, -45 = 315.
  const auto from = read_occurrence_table(
      write_text_file(folder / "from.csv", "hs_m,tp_s,direction_from_deg,probability\n1,8,180,0.5\n1,8,315,0.5\n"));
  EXPECT_DOUBLE_EQ(from[0].direction_deg, 90.0);
  EXPECT_DOUBLE_EQ(from[1].direction_deg, 315.0);
}

TEST(Operability, OccurrenceTableErrorsNameTheFileTheLineAndTheFix) {
  const fs::path folder = operability_scratch();
  const auto message = [&](const std::string& text) { return error_of(write_text_file(folder / "occ.csv", text)); };
  EXPECT_NE(message("hs,tp,dir,p\n1,8,90,1\n").find("occ.csv: line 1: the header is 'hs,tp,dir,p'"), std::string::npos);
  EXPECT_NE(message("hs_m,tp_s,direction_deg,probability\n1,8,90\n").find("line 2: '1,8,90' has 3 fields"), std::string::npos);
  EXPECT_NE(message("hs_m,tp_s,direction_deg,probability\n1,8,north,1\n").find("line 2: direction = 'north' is not a number"),
            std::string::npos);
  EXPECT_NE(message("hs_m,tp_s,direction_deg,probability\n0,8,90,1\n").find("line 2: Hs = 0 m, Tp = 8 s: both must be > 0"),
            std::string::npos);
  EXPECT_NE(message("hs_m,tp_s,direction_deg,probability\n1,8,90,60\n").find("line 2: probability = 60 is outside 0 .. 1"),
            std::string::npos);
  // 0.6 + 0.3: a missing bin of 10 % is refused; 0.6 + 0.398 (rounding) is not.
  const std::string short_sum = message("hs_m,tp_s,direction_deg,probability\n1,8,90,0.6\n2,8,90,0.3\n");
  EXPECT_NE(short_sum.find("the probabilities of its 2 conditions add up to 0.9000, not 1"), std::string::npos) << short_sum;
  EXPECT_EQ(message("hs_m,tp_s,direction_deg,probability\n1,8,90,0.6\n2,8,90,0.398\n"), "no error");
  EXPECT_NE(message("").find("is empty"), std::string::npos);
  EXPECT_NE(message("hs_m,tp_s,direction_deg,probability\n").find("has a header but no condition"), std::string::npos);
  EXPECT_NE(error_of(folder / "missing.csv").find("does not exist"), std::string::npos);
}

TEST(Operability, DowntimeIsTheProbabilityOfTheConditionsAboveTheLimit) {
  // Hand-computed: Hs 0.3, 0.5, 0.7, 1.2 m with probabilities 0.4, 0.3, 0.2, 0.1 and a 0.5 m limit:
  // 0.7 and 1.2 exceed it (0.5 is at the limit, still workable): 0.2 + 0.1 = 30 %.
  const std::vector<double> hs = {0.3, 0.5, 0.7, 1.2}, probability = {0.4, 0.3, 0.2, 0.1};
  EXPECT_NEAR(exceedance_percent(hs, probability, 0.5), 30.0, 1e-12);
  EXPECT_NEAR(exceedance_percent(hs, probability, 0.29), 100.0, 1e-12);
  EXPECT_NEAR(exceedance_percent(hs, probability, 1.2), 0.0, 1e-12);
}

// One state: a sequence over 8 x 6 cells of 10 m (the top row land) whose eta is a sinusoid of
// amplitude `amplitude_m` sampled over whole periods (Hs = 2 sqrt(2) a exactly), with a wave maker
// recorded of amplitude `maker_amplitude_m`: agitation a / maker everywhere.
void write_state(const fs::path& folder, double amplitude_m, double maker_amplitude_m) {
  GridGeometry g;
  g.columns = 8;
  g.rows = 6;
  g.set_spacing(10.0, 10.0);
  HarbourGrid harbour = HarbourGrid::open_water(g, 8.0f);
  for (int column = 0; column < g.columns; ++column) {
    harbour.land(column, g.rows - 1) = kLandCell;
    harbour.still_water_depth_m(column, g.rows - 1) = -2.0f;
  }
  sequence::SequenceDescription description;
  description.frame_interval_s = 0.5;
  description.wave_conditions = {{"components", {{{"amplitude_m", maker_amplitude_m}}}}};
  description.encoding = {sequence::Compression::kNone, sequence::Precision::kFloat, sequence::Precision::kFloat,
                          sequence::Precision::kFloat};
  sequence::SequenceWriter writer(folder, harbour, description);
  Raster<float> eta(g.columns, g.rows), zero(g.columns, g.rows, 0.0f);
  constexpr int kFrames = 40;  // two periods of 10 s at 0.5 s
  for (int index = 0; index < kFrames; ++index) {
    for (int row = 0; row < g.rows; ++row)
      for (int column = 0; column < g.columns; ++column)
        eta(column, row) = harbour.land(column, row)
                               ? 2.0f
                               : static_cast<float>(amplitude_m * std::cos(2.0 * std::numbers::pi * index / 20.0 + 0.3 * column));
    writer.write_frame(index, {&eta, &zero, &zero, &zero});
  }
  writer.finish(kFrames);
}

TEST(Operability, DowntimeOverALibraryOfKnownAgitation) {
  ProgressBar::set_quiet(true);
  const fs::path folder = operability_scratch();
  // Two states of a direction sweep: from 80 degrees the basin sees K = 0.1 / 0.25 = 0.4, from 100
  // degrees K = 0.2 / 0.25 = 0.8 (maker Hs 2 sqrt(2) 0.25 = 0.707 m in both).
  write_state(folder / "states" / "dir80", 0.1, 0.25);
  write_state(folder / "states" / "dir100", 0.2, 0.25);
  sequence::LibraryIndex index;
  index.title = "operability test";
  index.library_file = "library.toml";
  index.base_case = "base.toml";
  index.axes = {{sequence::SeaQuantity::kDirection, {80.0, 100.0}, {}}};
  for (const double direction : {80.0, 100.0}) {
    sequence::LibraryIndex::State state;
    state.id = fmt::format("dir{:.0f}", direction);
    state.conditions.direction_deg = direction;
    state.status = sequence::LibraryStateStatus::kBaked;
    state.sequence = "states/" + state.id;
    state.case_file = "cases/" + state.id + ".json";
    state.manifest_checksum = state.loops_checksum = "xxh64:0000000000000000";
    index.states.push_back(state);
  }
  sequence::write_library_index(folder, index);

  // Conditions: 1.0 m from 85 (-> dir80: Hs 0.4 m), 0.8 m from 95 (-> dir100: 0.64 m), 0.5 m from
  // 100 (-> 0.4 m), 1.5 m from 60 (outside the sweep, held at dir80: 0.6 m).
  write_text_file(folder / "occurrence.csv",
                  "hs_m,tp_s,direction_deg,probability\n1.0,8,85,0.5\n0.8,8,95,0.2\n0.5,8,100,0.2\n1.5,8,60,0.1\n");
  write_text_file(folder / "berths.csv", "name,x_m,y_m\nquay,35,25\n");
  OperabilityRequest request;
  request.library_folder = folder;
  request.occurrence_file = folder / "occurrence.csv";
  request.berths_file = folder / "berths.csv";
  request.limit_significant_wave_height_m = 0.5;
  const OperabilityResult result = compute_operability(request);
  ASSERT_EQ(result.conditions.size(), 4u);
  EXPECT_EQ(result.conditions[0].state_id, "dir80");
  EXPECT_EQ(result.conditions[1].state_id, "dir100");
  EXPECT_EQ(result.conditions[3].state_id, "dir80");
  // Hs: the float frames hold eta to 1e-8 m, the variance in double: 1e-5 on K.
  const double expected_hs[] = {0.4, 0.64, 0.4, 0.6};
  for (std::size_t c = 0; c < 4; ++c)
    EXPECT_NEAR(result.conditions[c].berth_significant_wave_height_m[0], expected_hs[c], 1e-5) << c;
  EXPECT_NEAR(result.conditions[0].scale, 1.0 / (2.0 * std::sqrt(2.0) * 0.25), 1e-9);
  // Above 0.5 m: the 0.64 m (p 0.2) and the 0.6 m (p 0.1): 30 % of the time.
  ASSERT_EQ(result.berths.size(), 1u);
  EXPECT_NEAR(result.berths[0].exceedance_percent, 30.0, 1e-9);
  EXPECT_NEAR(result.berths[0].largest_significant_wave_height_m, 0.64, 1e-5);
  // The 60-degree condition is 20 degrees from its state, more than half the 20-degree step.
  ASSERT_FALSE(result.notes.empty());
  EXPECT_NE(result.notes[0].find("1 condition (10.0 % of the time)"), std::string::npos) << result.notes[0];

  const auto files = write_operability(result, folder / "out");
  ASSERT_EQ(files.size(), 3u);
  std::ifstream csv(folder / "out" / "operability.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(header, "name,x_m,y_m,limit_hs_m,exceedance_percent,operability_percent,largest_hs_m");
  EXPECT_EQ(row.substr(0, 40), "quay,35.00,25.00,0.500,30.000,70.000,0.6");

  // A berth on land in the states is refused, naming the berth and the state.
  write_text_file(folder / "land.csv", "name,x_m,y_m\nshed,35,55\n");
  request.berths_file = folder / "land.csv";
  try {
    compute_operability(request);
    ADD_FAILURE() << "a berth on land was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("berth 'shed'"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("in state 'dir80'"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace nearshore::library
