// Issue 13, item 3: options out of their range are refused by the library with a nearshore::Error
// naming the field, never a crash. `nearshore loops SEQ --lengths-s -0.5` on a sequence of 0.5 s
// frames segfaulted (a plan indexed at length -1, then LoopPlan::schedule on garbage).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "loops_test_support.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/loops/inspector.hpp"
#include "nearshore/loops/plans.hpp"
#include "nearshore/loops/synthetic_sea.hpp"
#include "nearshore/loops/transitions.hpp"

namespace nearshore::loops {
namespace {
using namespace testing;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// 40 frames of 0.5 s of a sea with an 8 s period: a few milliseconds to write and analyse.
std::filesystem::path small_periodic_sequence(const std::string& name) {
  const auto folder = fresh_folder(name);
  write_sea_sequence(folder, periodic_sea(8.0, 3, 1.5, 8.0, 5), small_geometry(), 40, 0.5, 8.0);
  return folder;
}

TEST(BadOptions, LoopLengthsShorterThanOneFrameAreRefusedNamingTheField) {
  const auto folder = small_periodic_sequence("lengths");
  for (double length_s : {-0.5, -1.0, 0.0, 0.2, kNaN}) {
    LoopsOptions options;
    options.write_tables = false;
    options.report_lengths_s = {10, length_s};
    const std::string error = error_of([&] { analyse_loops(folder, options); });
    EXPECT_NE(error.find("LoopsOptions::report_lengths_s holds"), std::string::npos) << length_s << ": " << error;
    EXPECT_NE(error.find("at least one frame (0.5 s"), std::string::npos) << length_s << ": " << error;
  }
  LoopsOptions requested;
  requested.write_tables = false;
  requested.requested_loop_s = -5;
  EXPECT_NE(error_of([&] { analyse_loops(folder, requested); }).find("LoopsOptions::requested_loop_s = -5"),
            std::string::npos);
  LoopsOptions crossfade;
  crossfade.write_tables = false;
  crossfade.max_crossfade_s = kNaN;
  EXPECT_NE(error_of([&] { analyse_loops(folder, crossfade); }).find("LoopsOptions::max_crossfade_s"),
            std::string::npos);
  crossfade.max_crossfade_s = 2;
  crossfade.period_crossfade_s = -1;
  EXPECT_NE(error_of([&] { analyse_loops(folder, crossfade); }).find("LoopsOptions::period_crossfade_s"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(folder / kLoopsFile));
  // One frame is the shortest loop length there is, and it is accepted.
  LoopsOptions shortest;
  shortest.write_tables = false;
  shortest.report_lengths_s = {0.5, 8};
  EXPECT_NO_THROW(analyse_loops(folder, shortest));
}

TEST(BadOptions, TransitionOptionsOutOfRangeAreRefusedNamingTheField) {
  // Any symmetric distances will do: the options are checked before they are used.
  DistanceMatrices distances;
  distances.combined = Eigen::MatrixXd::Zero(20, 20);
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) distances.combined(i, j) = std::abs(std::sin(0.7 * i) - std::sin(0.7 * j)) + 0.01 * (i != j);
  EXPECT_NO_THROW(build_transition_table(distances, TransitionOptions{}));
  const struct {
    const char* field;
    std::function<void(TransitionOptions&)> spoil;
  } cases[] = {
      {"motion_weight", [](TransitionOptions& o) { o.motion_weight = -1; }},
      {"filter_half_width", [](TransitionOptions& o) { o.filter_half_width = -1; }},
      {"sigma", [](TransitionOptions& o) { o.sigma = kNaN; }},
      {"sigma_factor", [](TransitionOptions& o) { o.sigma_factor = 0; }},
      {"future_discount", [](TransitionOptions& o) { o.future_discount = 2; }},
      {"future_discount", [](TransitionOptions& o) { o.future_discount = 1; }},
      {"cost_exponent", [](TransitionOptions& o) { o.cost_exponent = kNaN; }},
      {"candidates_per_frame", [](TransitionOptions& o) { o.candidates_per_frame = 0; }},
      {"min_jump_frames", [](TransitionOptions& o) { o.min_jump_frames = 0; }},
      {"min_probability", [](TransitionOptions& o) { o.min_probability = 2; }},
      {"max_crossfade_frames", [](TransitionOptions& o) { o.max_crossfade_frames = -3; }},
  };
  for (const auto& c : cases) {
    TransitionOptions options;
    c.spoil(options);
    const std::string error = error_of([&] { build_transition_table(distances, options); });
    EXPECT_NE(error.find(std::string("TransitionOptions::") + c.field + " = "), std::string::npos)
        << c.field << ": " << error;
  }
  GramMatrices gram;
  gram.elevation = gram.flux_x = gram.flux_y = Eigen::MatrixXd::Identity(4, 4);
  EXPECT_NE(error_of([&] { distances_from_gram(gram, -1); }).find("TransitionOptions::motion_weight"),
            std::string::npos);
}

TEST(BadOptions, GramOptionsWithoutThreadsAreRefused) {
  const auto folder = small_periodic_sequence("gram");
  const sequence::SequenceReader reader(folder);
  GramOptions options;
  options.threads = 0;
  EXPECT_NE(error_of([&] { compute_gram_matrices(reader, options); }).find("GramOptions::threads = 0"),
            std::string::npos);
}

// A plan of no frames (what a length that rounds to zero or below asks for) is an error when it is
// scheduled, not an out-of-range read.
TEST(BadOptions, LoopPlanOfNoFramesCannotBeScheduled) {
  LoopPlan plan;
  plan.length_frames = 0;
  EXPECT_NE(error_of([&] { plan.schedule(); }).find("shorter than one frame"), std::string::npos);
  plan.length_frames = -2;
  EXPECT_NE(error_of([&] { plan.frames(); }).find("shorter than one frame"), std::string::npos);
  plan.length_frames = 4;
  plan.start_frame = -1;
  EXPECT_NE(error_of([&] { plan.schedule(); }).find("starts before frame 0"), std::string::npos);
}

}  // namespace
}  // namespace nearshore::loops
