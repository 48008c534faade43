// loops.json as one typed, versioned contract (sequence/loops_file.hpp): a round trip keeps every
// field and the exact bytes, a newer or unknown version and another format are refused naming the
// file, and malformed text (truncated, mutated, a missing key, a wrong type, a frame index outside
// the bake, a loop that does not close) is a nearshore::Error, never a crash or another exception.
#include "nearshore/sequence/loops_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "test_sequence.hpp"

namespace nearshore::sequence {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::error_message_of;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A table of a 40-frame bake with every field set to a value of its own (so a swapped or dropped
// field shows), one plan of each kind and +infinity where the inspector can hold it.
LoopsFile sample_tables() {
  LoopsFile tables;
  LoopsFile::Report& r = tables.report;
  r.sequence = "bakes/harbour ö";
  r.frame_count = 40;
  r.frame_interval_s = 0.25;
  r.loop_period_s = 8.0;
  r.parameters = {.motion_weight_delta = 1.5,
                  .filter_half_width_frames = 2,
                  .sigma = 0.0123,
                  .sigma_factor = 0.1,
                  .future_discount_alpha = 0.995,
                  .cost_exponent_p = 2,
                  .candidates_per_frame = 4,
                  .min_jump_frames = 3,
                  .min_probability = 0.01,
                  .max_crossfade_frames = 8,
                  .period_crossfade_frames = 40};
  r.height_scale_m = 0.61;
  r.motion_scale_m2_s = 2.4;
  r.median_step = 0.0371;
  r.median_volume_step_m3 = 12.5;
  r.graph = {.candidate_jumps = 97,
             .usable_jumps = 61,
             .dead_end_count = 3,
             .reachable_dead_end_count = 0,
             .first_playable_frame = 2};
  r.detected_period = {
      .found = true, .lag_frames = 32, .lag_s = 8.0, .seam_ratio = 0.004, .matched_frame = 5};
  LoopsFile::Seam period_seam{.from = 37,
                              .to = 5,
                              .crossfade_frames = 4,
                              .run_before_frames = 33,
                              .seam_ratio_before = 0.02,
                              .seam_ratio_after = 0.004,
                              .volume_jump_m3 = -0.75,
                              .volume_jump_after_m3 = 0.125,
                              .energy_jump_fraction = 0.001,
                              .energy_dip_fraction = -0.0002};
  r.period_loop = LoopsFile::Loop{.kind = "period",
                                  .start_frame = 5,
                                  .length_frames = 33,
                                  .length_s = 8.25,
                                  .cost = 4e-6,
                                  .worst_seam_ratio_before = 0.02,
                                  .worst_seam_ratio_after = 0.004,
                                  .seams = {period_seam}};
  r.requested_loop_s = 5;
  LoopsFile::Loop two_jumps{.kind = "optimal",
                            .start_frame = 4,
                            .length_frames = 20,
                            .length_s = 5,
                            .cost = 0.3,
                            .worst_seam_ratio_before = 1.4,
                            .worst_seam_ratio_after = 0.7,
                            .seams = {{.from = 12, .to = 20, .crossfade_frames = 3, .run_before_frames = 9},
                                      {.from = 30, .to = 4, .crossfade_frames = 4, .run_before_frames = 11}}};
  r.requested_loop = two_jumps;
  r.best_loops_by_length = {two_jumps, *r.period_loop};
  r.worst_seam_ratio_after = 0.7;
  r.gram_reused = true;
  r.distance_seconds = 0.75;
  r.table_seconds = 0.03125;
  tables.sequence_manifest_checksum = "xxh64:0123456789abcdef";
  tables.gram_checksum = "xxh64:fedcba9876543210";
  tables.random_walk = {.start_frame = 2,
                        .seed = 0xfeedbeefcafe1234ULL};  // > 2^53: must survive JSON exactly
  tables.transitions = {{.from = 2, .to = 3, .probability = 0.9, .cost = 0, .future_cost = 0.5},
                        {.from = 2,
                         .to = 30,
                         .probability = 0.1,
                         .cost = 0.2,
                         .future_cost = 0.7,
                         .crossfade_frames = 3,
                         .seam_ratio = 0.8,
                         .seam_ratio_after = 0.3},
                        {.from = 38, .to = 39, .probability = 0, .cost = 0, .future_cost = kInfinity}};
  return tables;
}

std::string sample_text() {
  return loops_file_to_json(sample_tables()).dump(1);
}

fs::path fresh_loops_folder(const std::string& name) {
  const fs::path folder = fs::current_path() / ("loops_file_test_" + name);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

std::string error_parsing(const json& tables) {
  return error_message_of([&] { parse_loops_file(tables.dump(), "bake/loops.json"); });
}

TEST(LoopsFile, RoundTripKeepsEveryFieldAndTheBytes) {
  const fs::path folder = fresh_loops_folder("round_trip");
  const LoopsFile written = sample_tables();
  write_loops_file(folder, written);
  const LoopsFile read = read_loops_file(folder);
  EXPECT_EQ(read, written);
  EXPECT_EQ(read.random_walk.seed, 0xfeedbeefcafe1234ULL);
  EXPECT_EQ(read.transitions.back().future_cost, kInfinity);  // written as null
  // Written again, the same bytes: the type holds everything the file says.
  const std::string bytes = read_file_bytes(folder / kLoopsFileName);
  EXPECT_EQ(loops_file_to_json(read).dump(1), bytes);
  // The report (`nearshore loops --json`) is the file less what ties it to its bake.
  json file = json::parse(bytes);
  for (const char* key : {"format", "version", "sequence_manifest_checksum", "gram_file", "gram_checksum",
                          "random_walk", "transition_columns", "transitions"})
    EXPECT_EQ(file.erase(key), 1u) << key;
  EXPECT_EQ(file, loops_report_to_json(written.report));
}

TEST(LoopsFile, NoPlansAndNoTransitionsRoundTrip) {
  LoopsFile tables;
  tables.report.frame_count = 1;
  tables.report.frame_interval_s = 0.1;
  tables.report.detected_period.seam_ratio = kInfinity;  // a bake too short to look for a period
  EXPECT_EQ(parse_loops_file(loops_file_to_json(tables).dump(1), "loops.json"), tables);
}

TEST(LoopsFile, ANewerVersionIsRefusedNamingTheFile) {
  const fs::path folder = fresh_loops_folder("newer");
  json tables = loops_file_to_json(sample_tables());
  tables["version"] = kLoopsFileVersion + 1;
  write_text_atomically(folder / kLoopsFileName, tables.dump(1));
  const std::string message = error_message_of([&] { read_loops_file(folder); });
  EXPECT_NE(message.find((folder / kLoopsFileName).string()), std::string::npos) << message;
  EXPECT_NE(message.find("version 2"), std::string::npos) << message;
  EXPECT_NE(message.find("newer"), std::string::npos) << message;
  EXPECT_NE(message.find("nearshore loops " + folder.string()), std::string::npos) << message;
  // A newer file is refused as newer even when its keys changed (it is not read key by key).
  tables.erase("transitions");
  EXPECT_NE(error_parsing(tables).find("newer"), std::string::npos);
}

TEST(LoopsFile, AnUnknownVersionOrAnotherFormatIsRefused) {
  json tables = loops_file_to_json(sample_tables());
  for (const json& version : {json(0), json(-3), json(1.0), json("1"), json(nullptr)}) {
    tables["version"] = version;
    const std::string message = error_parsing(tables);
    EXPECT_NE(message.find("bake/loops.json"), std::string::npos) << message;
    EXPECT_NE(message.find("version"), std::string::npos) << message;
  }
  tables["version"] = kLoopsFileVersion;
  tables["format"] = "nearshore sequence";
  EXPECT_NE(error_parsing(tables).find("is not a loops table"), std::string::npos);
}

TEST(LoopsFile, AMissingFileIsNamed) {
  const fs::path folder = fresh_loops_folder("missing");
  const std::string message = error_message_of([&] { read_loops_file(folder); });
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
  EXPECT_NE(message.find("nearshore loops"), std::string::npos) << message;
  fs::create_directories(folder / kLoopsFileName);  // a folder where the file belongs
  EXPECT_NE(error_message_of([&] { read_loops_file(folder); }).find("not a regular file"), std::string::npos);
}

TEST(LoopsFile, EveryTruncationIsAnError) {
  const std::string text = sample_text();
  for (std::size_t length = 0; length < text.size(); ++length) {
    try {
      parse_loops_file(std::string_view(text).substr(0, length), "loops.json");
      ADD_FAILURE() << "a truncation to " << length << " bytes was accepted";
    } catch (const Error&) {
    }
  }
  EXPECT_NE(error_message_of([&] { parse_loops_file(text.substr(0, 100), "loops.json"); }).find("not valid JSON"),
            std::string::npos);
  for (const char* text_of_other_kind : {"", "[]", "null", "17", "\"loops\"", "{}", "{\"format\": 3}"})
    error_message_of([&] { parse_loops_file(text_of_other_kind, "loops.json"); });
}

// Every key at every depth is required and typed: dropping it, or giving a value of the wrong
// type, is an Error naming that key.
TEST(LoopsFile, EveryMissingKeyAndWrongTypeIsNamed) {
  const json original = loops_file_to_json(sample_tables());
  int mutations = 0;
  std::function<void(const json::json_pointer&)> visit = [&](const json::json_pointer& at) {
    const json& value = original.at(at);
    if (value.is_object()) {
      for (const auto& [key, member] : value.items()) {
        json dropped = original;
        dropped.at(at).erase(key);
        const std::string message = error_parsing(dropped);
        EXPECT_NE(message.find(key), std::string::npos) << at.to_string() << "/" << key << ": " << message;
        ++mutations;
        visit(at / key);
      }
    } else if (value.is_array()) {
      for (std::size_t k = 0; k < value.size(); ++k) visit(at / k);
    }
    if (at.empty()) return;
    // A string where a number, boolean, object or array belongs, and a number where a string does.
    json wrong = original;
    wrong.at(at) = value.is_string() ? json(7) : json("seven");
    const std::string message = error_parsing(wrong);
    // The message names the innermost key (of a row or list element: the list's key).
    json::json_pointer named = at;
    while (!named.parent_pointer().empty() && original.at(named.parent_pointer()).is_array())
      named = named.parent_pointer();
    const std::string name = named.back();
    EXPECT_NE(message.find(name), std::string::npos) << at.to_string() << ": " << message;
    ++mutations;
  };
  visit(json::json_pointer());
  EXPECT_GT(mutations, 200);
}

TEST(LoopsFile, FrameIndicesOutsideTheBakeAreRefused) {
  const json original = loops_file_to_json(sample_tables());
  auto refused = [&](const std::string& pointer, const json& value, const std::string& expected) {
    json tables = original;
    tables.at(json::json_pointer(pointer)) = value;
    const std::string message = error_parsing(tables);
    EXPECT_NE(message.find(expected), std::string::npos) << pointer << " = " << value << ": " << message;
    EXPECT_NE(message.find("nearshore loops"), std::string::npos) << message;
  };
  refused("/frame_count", 0, "\"frame_count\" is 0");
  refused("/frame_count", 18446744073709551615ULL, "\"frame_count\"");
  refused("/frame_interval_s", 0.0, "\"frame_interval_s\" is 0");
  refused("/period_loop/seams/0/to", 40, "\"period_loop.seams[0].to\" is 40, outside 0..39");
  refused("/period_loop/seams/0/from", -1, "\"period_loop.seams[0].from\" is -1");
  refused("/period_loop/seams/0/crossfade_frames", 6000000000LL, "\"period_loop.seams[0].crossfade_frames\"");
  refused("/requested_loop/start_frame", 41, "\"requested_loop.start_frame\" is 41");
  refused("/best_loops_by_length/1/seams/0/run_before_frames", -2,
          "\"best_loops_by_length[1].seams[0].run_before_frames\"");
  refused("/transitions/1/1", 40, "\"transitions[1].to\" is 40");
  refused("/transitions/2/0", -5, "\"transitions[2].from\" is -5");
  refused("/transitions/1/5", 31, "\"transitions[1].crossfade_frames\" is 31");
  refused("/random_walk/start_frame", -2, "\"random_walk.start_frame\" is -2");
  refused("/random_walk/seed", -1, "\"random_walk.seed\"");
  refused("/graph/first_playable_frame", 40, "\"graph.first_playable_frame\" is 40");
  refused("/graph/dead_ends", 41, "\"graph.dead_ends\" is 41");
  refused("/detected_period/lag_frames", 40, "\"detected_period.lag_frames\" is 40");
  refused("/detected_period/matched_frame", 1.5, "\"detected_period.matched_frame\" is 1.5, not an integer");
  refused("/transitions/0", json::array({2, 3}), "\"transitions[0]\" is a row of 2 values");
  refused("/transition_columns/2", "chance", "\"transition_columns\"");
}

// The plans a player follows must close: start where the last jump lands, run forward to each
// jump, and show length_frames frames per cycle; a crossfade's blends must be frames of the bake.
TEST(LoopsFile, LoopsThatDoNotCloseAreRefused) {
  const json original = loops_file_to_json(sample_tables());
  auto refused = [&](const std::function<void(json&)>& change, const std::string& expected) {
    json tables = original;
    change(tables);
    const std::string message = error_parsing(tables);
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  };
  refused([](json& t) { t["period_loop"]["start_frame"] = 6; }, "lands on frame 5");
  refused([](json& t) { t["period_loop"]["length_frames"] = 34; }, "show 33 frames");
  refused([](json& t) { t["period_loop"]["length_frames"] = 0; }, "\"period_loop.length_frames\" is 0");
  refused([](json& t) { t["requested_loop"]["seams"][1]["from"] = 15; }, "before frame 20");
  refused([](json& t) { t["requested_loop"]["seams"] = json::array(); }, "a loop jumps at least once");
  // Jump 37 -> 5 blends targets 5 - c .. 4: at most 5 blends.
  refused([](json& t) { t["period_loop"]["seams"][0]["crossfade_frames"] = 6; },
          "\"period_loop.seams[0].crossfade_frames\" is 6, outside 0..5");
  refused([](json& t) { t["best_loops_by_length"][0] = 3; },
          "\"best_loops_by_length[0]\" is 3, not an object");
  refused([](json& t) { t["period_loop"]["seams"][0] = "jump"; }, "\"period_loop.seams[0]\" is \"jump\"");
}

TEST(LoopsFile, NullReadsAsInfinityAndUnknownKeysAreIgnored) {
  json tables = loops_file_to_json(sample_tables());
  tables["detected_period"]["seam_ratio"] = nullptr;
  tables["a_key_of_a_later_minor_addition"] = {1, 2, 3};
  const LoopsFile read = parse_loops_file(tables.dump(), "loops.json");
  EXPECT_EQ(read.report.detected_period.seam_ratio, kInfinity);
  EXPECT_EQ(read.report.period_loop, sample_tables().report.period_loop);
}

// A deterministic mutation fuzz (the libFuzzer target runs the same entry point for longer):
// random byte flips, insertions, deletions and truncations of a valid file. Every outcome must be
// a clean parse or a nearshore::Error; the asan build catches memory errors.
TEST(LoopsFile, MutatedFilesFailCleanly) {
  const std::string text = sample_text();
  std::mt19937_64 random(20261122);
  int rejected = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string bytes = text;
    const int edits = 1 + static_cast<int>(random() % 4);
    for (int e = 0; e < edits && !bytes.empty(); ++e) {
      const std::size_t at = random() % bytes.size();
      switch (random() % 5) {
        case 0:
          bytes[at] = static_cast<char>(bytes[at] ^ (1 << (random() % 8)));
          break;
        case 1:
          bytes.insert(at, 1, static_cast<char>(random()));
          break;
        case 2:
          bytes.erase(at, 1 + random() % 8);
          break;
        case 3:
          bytes.insert(at, std::string(1 + random() % 3, "-9e[]{}\"0"[random() % 9]));
          break;
        default:
          bytes.resize(at);
          break;
      }
    }
    try {
      parse_loops_file(bytes, "loops.json");
    } catch (const Error&) {
      ++rejected;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a nearshore::Error: " << e.what() << "\n" << bytes;
      break;
    }
  }
  EXPECT_GT(rejected, 1500);
}

}  // namespace
}  // namespace nearshore::sequence
