// library.json (sequence/library_index.hpp): a round trip keeps every field; malformed files are
// refused naming the file and the key; the selection rule is checked on grids whose answer is known
// by hand (the weights of multilinear interpolation, the circle, the sector, missing corners).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>

#include "nearshore/core/error.hpp"
#include "nearshore/sequence/library_index.hpp"

namespace nearshore::sequence {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

const std::string kChecksum = "xxh64:0123456789abcdef";

// A 3 x 2 sweep (direction x tide), every state baked unless told otherwise.
LibraryIndex sweep_index(std::vector<double> directions = {75, 90, 105}, std::vector<double> tides = {0.0, 1.0}) {
  LibraryIndex index;
  index.title = "test";
  index.library_file = "library.toml";
  index.base_case = "harbour.toml";
  index.axes = {{SeaQuantity::kDirection, directions, {}}, {SeaQuantity::kTide, tides, {}}};
  for (double direction : directions)
    for (double tide : tides) {
      LibraryIndex::State state;
      state.id = "dir" + std::to_string(static_cast<int>(direction)) + "_tide" + std::to_string(static_cast<int>(tide * 10));
      state.conditions.direction_deg = direction;
      state.conditions.tide_m = tide;
      state.status = LibraryStateStatus::kBaked;
      state.sequence = "states/" + state.id;
      state.case_file = "cases/" + state.id + ".json";
      state.manifest_checksum = kChecksum;
      state.loops_checksum = kChecksum;
      state.cost_cell_steps = 1e6;
      state.run = {"baked", 1, 2.5};
      index.states.push_back(state);
    }
  return index;
}

int state_of(const LibraryIndex& index, double direction, double tide) {
  for (std::size_t s = 0; s < index.states.size(); ++s)
    if (index.states[s].conditions.direction_deg == direction && index.states[s].conditions.tide_m == tide)
      return static_cast<int>(s);
  return -1;
}

double weight_of(const LibrarySelection& selection, int state) {
  for (const LibraryStateWeight& w : selection.blend)
    if (w.state == state) return w.weight;
  return 0.0;
}

TEST(LibraryIndex, RoundTripKeepsEveryField) {
  LibraryIndex index = sweep_index();
  index.axes.push_back({SeaQuantity::kSpectrum, {}, {"jonswap"}});
  for (LibraryIndex::State& state : index.states) state.conditions.spectrum = "jonswap";
  index.states[1].status = LibraryStateStatus::kFailed;
  index.states[1].error = "cases/x.json: key `wave_maker.period_s` = 0.05 is out of range; give ...";
  index.states[1].manifest_checksum = index.states[1].loops_checksum = "";
  index.states[2].status = LibraryStateStatus::kPending;
  index.states[2].run = {"", -1, 0.0};
  const std::string text = library_index_to_json(index).dump(1);
  EXPECT_EQ(parse_library_index(text, "library.json"), index);

  const fs::path folder = fs::path(NEARSHORE_BINARY_DIR) / "tests" / "library" / "scratch" / "RoundTrip";
  fs::remove_all(folder);
  fs::create_directories(folder);
  write_library_index(folder, index);
  EXPECT_EQ(read_library_index(folder), index);
  EXPECT_EQ(index.count(LibraryStateStatus::kBaked), 4);
}

// Each edit of a good file must be refused with one Error naming the file and `expected`.
void expect_refused(const std::function<void(json&)>& edit, const std::string& expected) {
  json document = library_index_to_json(sweep_index());
  edit(document);
  try {
    parse_library_index(document.dump(), "lib/library.json");
    ADD_FAILURE() << "accepted an index expected to fail with: " << expected;
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("lib/library.json"), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << "missing '" << expected << "' in: " << message;
    EXPECT_FALSE(error.fix().empty()) << message;
  }
}

TEST(LibraryIndex, MalformedFilesAreRefusedNamingTheKey) {
  expect_refused([](json& d) { d["format"] = "nearshore loops"; }, "is not a sea-state library index");
  expect_refused([](json& d) { d["version"] = 2; }, "newer than version 1");
  expect_refused([](json& d) { d["version"] = 0; }, "which no nearshore writes");
  expect_refused([](json& d) { d.erase("axes"); }, "has no \"axes\"");
  expect_refused([](json& d) { d["axes"][0]["quantity"] = "colour"; }, "\"axes[0].quantity\" is \"colour\"");
  expect_refused([](json& d) { d["axes"][0]["values"] = json::array({75, 435}); }, "the same direction");
  expect_refused([](json& d) { d["axes"][1]["values"] = json::array(); }, "has no values");
  expect_refused([](json& d) { d["axes"][1]["quantity"] = "direction_deg"; }, "a second time");
  expect_refused([](json& d) { d["states"].erase(0); }, "holds 5 states but the axes make 6");
  expect_refused([](json& d) { d["states"][1]["id"] = d["states"][0]["id"]; }, "the id of an earlier state");
  expect_refused([](json& d) { d["states"][1]["id"] = "../x"; }, "\"states[1].id\"");
  expect_refused([](json& d) { d["states"][1]["conditions"]["tide_m"] = 0.0; }, "are those of an earlier state");
  expect_refused([](json& d) { d["states"][2]["conditions"]["tide_m"] = 0.5; }, "\"states[2].conditions.tide_m\" is 0.5, not a value");
  expect_refused([](json& d) { d["states"][2]["conditions"].erase("direction_deg"); }, "has no \"states[2].conditions.direction_deg\"");
  expect_refused([](json& d) { d["states"][2]["conditions"]["height_m"] = 1.0; }, "has no height_m axis");
  expect_refused([](json& d) { d["states"][3]["status"] = "done"; }, "\"states[3].status\" is \"done\"");
  expect_refused([](json& d) { d["states"][3]["sequence"] = "/tmp/elsewhere"; }, "not a relative path inside");
  expect_refused([](json& d) { d["states"][3]["case_file"] = "../../etc/x.json"; }, "not a relative path inside");
  expect_refused([](json& d) { d["states"][3]["manifest_checksum"] = "xxh64:12"; }, "is baked but its manifest_checksum");
  expect_refused([](json& d) { d["states"][3]["status"] = "failed"; }, "failed but its \"error\" is empty");
  expect_refused([](json& d) { d["states"][3]["cost_cell_steps"] = -1; }, "cost_cell_steps\" is -1");
  expect_refused([](json& d) { d["states"][3]["run"]["action"] = "guessed"; }, "\"states[3].run.action\" is \"guessed\"");
  expect_refused([](json& d) { d["states"][3]["run"]["rank"] = -2; }, "\"states[3].run.rank\" is -2");
  expect_refused([](json& d) { d["states"] = "all"; }, "\"states\" is \"all\", not an array");
  for (const std::string text : {"", "{", "[1, 2]", "{\"format\": \"nearshore library\", \"version\": 1.5}"}) {
    EXPECT_THROW(parse_library_index(text, "library.json"), Error) << text;
  }
}

TEST(LibraryIndex, AMissingFileNamesTheCommandThatWritesIt) {
  try {
    read_library_index("/nonexistent/library");
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("nearshore library LIBRARY.toml -o /nonexistent/library"), std::string::npos)
        << error.what();
  }
}

// Multilinear interpolation: in the middle of a cell every corner weighs 1/4; on a state, that state.
TEST(LibrarySelection, BlendsTheFourCornersOfTheCellBilinearly) {
  const LibraryIndex index = sweep_index();
  SeaConditions request;
  request.direction_deg = 82.5;  // a half of the 75-90 step
  request.tide_m = 0.25;         // a quarter of the 0-1 step
  const LibrarySelection selection = select_library_states(index, request);
  ASSERT_EQ(selection.blend.size(), 4u);
  EXPECT_NEAR(weight_of(selection, state_of(index, 75, 0)), 0.5 * 0.75, 1e-12);
  EXPECT_NEAR(weight_of(selection, state_of(index, 90, 0)), 0.5 * 0.75, 1e-12);
  EXPECT_NEAR(weight_of(selection, state_of(index, 75, 1)), 0.5 * 0.25, 1e-12);
  EXPECT_NEAR(weight_of(selection, state_of(index, 90, 1)), 0.5 * 0.25, 1e-12);
  // Nearest in axis steps: (0.5, 0.25) from (75, 0) and (90, 0) alike; the first found wins the tie.
  EXPECT_EQ(selection.nearest, state_of(index, 75, 0));

  request.direction_deg = 90;
  request.tide_m = 1.0;
  const LibrarySelection exact = select_library_states(index, request);
  ASSERT_EQ(exact.blend.size(), 1u);
  EXPECT_EQ(exact.blend[0].state, state_of(index, 90, 1));
  EXPECT_DOUBLE_EQ(exact.blend[0].weight, 1.0);
  EXPECT_EQ(exact.nearest, state_of(index, 90, 1));
}

TEST(LibrarySelection, HoldsValuesOutsideTheSweepAtItsEnds) {
  const LibraryIndex index = sweep_index();
  SeaConditions request;
  request.direction_deg = 100;
  request.tide_m = 3.0;  // above the highest tide: held at 1 m, no extrapolation
  const LibrarySelection selection = select_library_states(index, request);
  ASSERT_EQ(selection.blend.size(), 2u);
  EXPECT_NEAR(weight_of(selection, state_of(index, 90, 1)), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(weight_of(selection, state_of(index, 105, 1)), 2.0 / 3.0, 1e-12);
  EXPECT_EQ(selection.nearest, state_of(index, 105, 1));
  // A direction outside the 75-105 sector (its largest gap, 330 degrees, is not swept) is held at
  // the nearer end: 180 is 75 degrees from 105 and 105 from 75.
  request.direction_deg = 180;
  request.tide_m = 0.0;
  const LibrarySelection outside = select_library_states(index, request);
  ASSERT_EQ(outside.blend.size(), 1u);
  EXPECT_EQ(outside.blend[0].state, state_of(index, 105, 0));
  // An unset quantity is held at its axis's first value.
  SeaConditions tide_only;
  tide_only.tide_m = 0.5;
  const LibrarySelection unset = select_library_states(index, tide_only);
  ASSERT_EQ(unset.blend.size(), 2u);
  EXPECT_NEAR(weight_of(unset, state_of(index, 75, 0)), 0.5, 1e-12);
  EXPECT_NEAR(weight_of(unset, state_of(index, 75, 1)), 0.5, 1e-12);
}

TEST(LibrarySelection, DirectionsAroundTheCompassBlendAcrossNorthOfEast) {
  // Every 90 degrees around the circle: 350 lies between 270 and 0 (=360), 80 of 90 from 270.
  const LibraryIndex index = sweep_index({0, 90, 180, 270}, {0.0});
  SeaConditions request;
  request.direction_deg = 350;
  request.tide_m = 0.0;
  const LibrarySelection selection = select_library_states(index, request);
  ASSERT_EQ(selection.blend.size(), 2u);
  EXPECT_NEAR(weight_of(selection, state_of(index, 0, 0)), 80.0 / 90.0, 1e-12);
  EXPECT_NEAR(weight_of(selection, state_of(index, 270, 0)), 10.0 / 90.0, 1e-12);
  EXPECT_EQ(selection.nearest, state_of(index, 0, 0));
  request.direction_deg = -10;  // the same direction
  EXPECT_EQ(select_library_states(index, request).blend, selection.blend);
}

TEST(LibrarySelection, CornersNotBakedAreDroppedAndTheOthersRenormalised) {
  LibraryIndex index = sweep_index();
  SeaConditions request;
  request.direction_deg = 82.5;
  request.tide_m = 0.25;
  index.states[state_of(index, 75, 0)].status = LibraryStateStatus::kFailed;
  index.states[state_of(index, 75, 0)].error = "unstable";
  const LibrarySelection selection = select_library_states(index, request);
  ASSERT_EQ(selection.blend.size(), 3u);
  const double kept = 0.5 * 0.75 + 0.5 * 0.25 + 0.5 * 0.25;
  EXPECT_NEAR(weight_of(selection, state_of(index, 90, 0)), 0.5 * 0.75 / kept, 1e-12);
  EXPECT_NEAR(weight_of(selection, state_of(index, 75, 1)), 0.5 * 0.25 / kept, 1e-12);
  EXPECT_EQ(selection.blend.front().state, state_of(index, 90, 0));  // heaviest first
  EXPECT_EQ(selection.nearest, state_of(index, 90, 0));
  // No corner baked: the nearest baked state alone.
  for (double direction : {75.0, 90.0})
    for (double tide : {0.0, 1.0}) index.states[state_of(index, direction, tide)].status = LibraryStateStatus::kPending;
  const LibrarySelection fallback = select_library_states(index, request);
  ASSERT_EQ(fallback.blend.size(), 1u);
  EXPECT_EQ(fallback.blend[0].state, state_of(index, 105, 0));
  // Nothing baked: nothing chosen.
  for (LibraryIndex::State& state : index.states) state.status = LibraryStateStatus::kPending;
  EXPECT_EQ(select_library_states(index, request).nearest, -1);
  EXPECT_TRUE(select_library_states(index, request).blend.empty());
}

TEST(LibrarySelection, TheSpectrumAskedForIsPreferred) {
  LibraryIndex index;
  index.axes = {{SeaQuantity::kSpectrum, {}, {"jonswap", "pierson_moskowitz"}}, {SeaQuantity::kHeight, {1.0, 2.0}, {}}};
  for (const char* spectrum : {"jonswap", "pierson_moskowitz"})
    for (double height : {1.0, 2.0}) {
      LibraryIndex::State state;
      state.id = std::string(spectrum) + std::to_string(static_cast<int>(height));
      state.conditions.spectrum = spectrum;
      state.conditions.height_m = height;
      state.status = LibraryStateStatus::kBaked;
      index.states.push_back(state);
    }
  SeaConditions request;
  request.spectrum = "pierson_moskowitz";
  request.height_m = 1.9;
  const LibrarySelection selection = select_library_states(index, request);
  EXPECT_EQ(selection.nearest, 3);
  ASSERT_EQ(selection.blend.size(), 2u);
  EXPECT_NEAR(weight_of(selection, 3), 0.9, 1e-12);
  EXPECT_NEAR(weight_of(selection, 2), 0.1, 1e-12);
  // Only jonswap baked: the nearest falls back to it.
  index.states[2].status = index.states[3].status = LibraryStateStatus::kFailed;
  EXPECT_EQ(select_library_states(index, request).nearest, 1);
}

}  // namespace
}  // namespace nearshore::sequence
