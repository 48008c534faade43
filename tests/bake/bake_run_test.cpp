// The bake run: frames, gauges and manifest in the output folder; resume after a REAL SIGKILL of a
// separate process gives byte-identical frames and gauges; the stability guard stops with one
// message naming time, cell, depth and the fix.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <thread>

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_gauges.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::bake {

using namespace nearshore::ocean;
using namespace nearshore::boussinesq;
namespace {
namespace fs = std::filesystem;
using testing::scratch_folder;
using testing::small_flume_case;
using testing::write_text;

std::string file_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Everything in the folder except the manifest (which may carry a creation time) must be equal.
void expect_same_outputs(const fs::path& a, const fs::path& b) {
  int compared = 0;
  for (const auto& entry : fs::directory_iterator(a)) {
    const auto name = entry.path().filename();
    if (name == "manifest.json") continue;
    ASSERT_TRUE(fs::exists(b / name)) << name;
    EXPECT_TRUE(file_bytes(entry.path()) == file_bytes(b / name)) << name << " differs";
    ++compared;
  }
  EXPECT_GT(compared, 3);
}

pid_t start_runner(const fs::path& case_file, const fs::path& output, bool resume) {
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string runner = BAKE_RUNNER_PATH, c = case_file.string(), o = output.string();
    if (resume) execl(runner.c_str(), runner.c_str(), c.c_str(), o.c_str(), "--resume", static_cast<char*>(nullptr));
    else execl(runner.c_str(), runner.c_str(), c.c_str(), o.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

int wait_for(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

class BakeRun : public ::testing::Test {
 protected:
  void SetUp() override { ProgressBar::set_quiet(true); }
};

TEST_F(BakeRun, WritesFramesGaugesAndTheManifestLast) {
  const auto folder = scratch_folder();
  const BakeCase c = read_bake_case(write_text(folder / "case.toml", small_flume_case(8.0, 2.0)));
  BakeOptions options;
  options.output_folder = folder / "out";
  const BakeSummary summary = run_bake(c, options);
  // Spin-up 2 s, frames every 0.5 s up to 8 s: 13 frames.
  EXPECT_EQ(summary.frames, 13);
  EXPECT_EQ(summary.cells, 720);
  EXPECT_NEAR(summary.first_frame_time_s, 2.0, 1e-9);
  EXPECT_TRUE(fs::exists(options.output_folder / "manifest.json"));
  EXPECT_TRUE(fs::exists(options.output_folder / "frame_000012.exr"));
  EXPECT_FALSE(fs::exists(options.output_folder / "frame_000013.exr"));
  EXPECT_FALSE(fs::exists(checkpoint_path(options.output_folder)));  // removed once complete
  const GaugeTable gauges = read_gauges_csv(options.output_folder / "gauges.csv");
  ASSERT_EQ(gauges.names, (std::vector<std::string>{"g1", "g2"}));
  ASSERT_EQ(static_cast<long>(gauges.time_s.size()), summary.total_steps + 1);
  EXPECT_NEAR(gauges.time_s.back(), 8.0, 1e-6);
  // The waves arrived: the gauge 2 m from the source line saw more than half the wave height.
  double highest = 0, lowest = 0;
  for (double eta : gauge_column(gauges, "g1")) highest = std::max(highest, eta), lowest = std::min(lowest, eta);
  EXPECT_GT(highest - lowest, 0.01);
  // Only finished files: no temporary names are left behind.
  for (const auto& entry : fs::directory_iterator(options.output_folder))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  // The summary for --json.
  const auto json = summary.to_json();
  EXPECT_EQ(json["outputs"]["frames"], 13);
  EXPECT_GT(json["cell_updates_per_s"].get<double>(), 0.0);
}

TEST_F(BakeRun, AnImposedCurrentFlowsThroughTheBakeAndItsOutputs) {
  // [current] (docs/solver.md, "Currents"): 0.2 m/s toward the west over the 0.5 m flume. The flux
  // the gauges record (what the frames carry, and the runtime divides by the depth) is the current's
  // u d = -0.1 m^2/s plus the waves' orbital flux, whose mean over the last wave period is small.
  const auto folder = scratch_folder();
  const BakeCase c = read_bake_case(write_text(folder / "case.toml", small_flume_case(8.0) + "[current]\nu_m_s = -0.2\n"));
  BakeOptions options;
  options.output_folder = folder / "out";
  run_bake(c, options);
  GaugeTable gauges = read_gauges_csv(options.output_folder / "gauges.csv");
  read_gauge_fluxes_csv(options.output_folder / kGaugeFluxesFile, gauges);
  for (std::size_t g = 0; g < gauges.names.size(); ++g) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < gauges.time_s.size(); ++i)
      if (gauges.time_s[i] > 6.0) sum += gauges.flux_x_m2_s[g][i], ++count;
    std::printf("%s: mean flux over 6-8 s %.5f m^2/s (the current's -0.10000)\n", gauges.names[g].c_str(), sum / count);
    // 5 %: the waves' mean flux (Stokes drift, a 2 cm wave: H^2 w / (8 tanh k d) ~ 1e-4 m^2/s) and
    // the mean over a period that is not whole at the gauge.
    EXPECT_NEAR(sum / count, -0.1, 0.005) << gauges.names[g];
  }
}

TEST_F(BakeRun, ATideRaisesTheGaugesMeanLevelAlongItsSeries) {
  // [tide] level_m (docs/solver.md, "Tides"): the level rises 4 cm over the 8 s bake. Over the last
  // wave period (6-8 s) the gauges' mean is the level's mean there, 3.5 cm, to within the regular
  // wave's own mean over a period that is not quite whole at the gauge (a few tenths of a mm) and
  // the sponges' lag behind the level (their relaxation, sigma ~ sqrt(g d)/W, is ~1 s).
  const auto folder = scratch_folder();
  const BakeCase c = read_bake_case(write_text(folder / "case.toml", small_flume_case(8.0) + "[tide]\nlevel_m = [[0.0, 0.0], [8.0, 0.04]]\n"));
  ASSERT_EQ(c.tide_level.time_s.size(), 2u);
  EXPECT_EQ(c.solver_record["tide_level_m"][1][1].get<double>(), 0.04);
  BakeOptions options;
  options.output_folder = folder / "out";
  run_bake(c, options);
  const GaugeTable gauges = read_gauges_csv(options.output_folder / "gauges.csv");
  for (const char* name : {"g1", "g2"}) {
    const std::vector<double> eta = gauge_column(gauges, name);
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < eta.size(); ++i)
      if (gauges.time_s[i] > 6.0) sum += eta[i], ++count;
    std::printf("%s: mean level over 6-8 s %.5f m (the tide's 0.03500 m)\n", name, sum / count);
    EXPECT_NEAR(sum / count, 0.035, 0.002) << name;
  }
  expect_case_error(small_flume_case() + "[tide]\nlevel_m = [[0.0, 0.0], [0.0, 0.1]]\n", {"key `tide.level_m`", "must increase"});
}

TEST_F(BakeRun, PeriodicIrregularBakeRecordsLoopPeriodSeedAndComponents) {
  const auto folder = scratch_folder();
  std::string text = small_flume_case(6.0);
  text.replace(text.find("kind = \"regular\""), 16, "kind = \"irregular\"\nsignificant_height_m = 0.02\npeak_period_s = 1.5\n"
                                                     "frequency_count = 16\nseed = 1234\nloop_period_s = 32.0\n"
                                                     "min_frequency_hz = 0.3\nmax_frequency_hz = 1.2");
  text.replace(text.find("height_m = 0.02\nperiod_s = 2.0\n"), 31, "");
  const BakeCase c = read_bake_case(write_text(folder / "case.toml", text));
  BakeOptions options;
  options.output_folder = folder / "out";
  const BakeSummary summary = run_bake(c, options);
  EXPECT_EQ(summary.seed, 1234u);
  const sequence::SequenceReader reader(options.output_folder);
  EXPECT_EQ(reader.manifest().seed, 1234u);
  EXPECT_DOUBLE_EQ(reader.manifest().loop_period_s, 32.0);
  EXPECT_EQ(reader.manifest().wave_conditions["components"].size(), 16u);
  EXPECT_EQ(reader.manifest().wave_conditions["case"]["kind"], "irregular");
  EXPECT_DOUBLE_EQ(reader.manifest().solver["time_step_s"].get<double>(), summary.time_step_s);
  EXPECT_EQ(reader.frame_count(), summary.frames);
}

TEST_F(BakeRun, ResumeAfterARealKillGivesTheSameFramesAndGauges) {
  const auto folder = scratch_folder();
  // Long enough that the runner is still working when the first checkpoint appears; if the machine
  // is so fast that it finishes first, the case is made longer and the kill tried again.
  for (double duration_s = 30.0; duration_s <= 480.0; duration_s *= 4) {
    const auto case_file = write_text(folder / "case.toml", small_flume_case(duration_s, duration_s / 6));
    const fs::path reference = folder / "uninterrupted", killed = folder / "killed";
    fs::remove_all(reference);
    fs::remove_all(killed);
    const pid_t pid = start_runner(case_file, killed, false);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(checkpoint_path(killed)) && std::chrono::steady_clock::now() < deadline) {
      if (waitpid(pid, nullptr, WNOHANG) == pid) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(30));  // kill mid-step, between checkpoints
    kill(pid, SIGKILL);
    const int status = wait_for(pid);
    if (!WIFSIGNALED(status)) continue;  // it finished before the kill: try a longer bake
    ASSERT_TRUE(fs::exists(checkpoint_path(killed)));
    EXPECT_FALSE(fs::exists(killed / "manifest.json"));  // the killed run does not look complete
    // A killed run leaves complete gauges up to its last checkpoint, never a torn file.
    const GaugeTable partial = read_gauges_csv(killed / "gauges.csv");
    EXPECT_GT(partial.time_s.size(), 1u);

    const int resumed = wait_for(start_runner(case_file, killed, true));
    ASSERT_TRUE(WIFEXITED(resumed) && WEXITSTATUS(resumed) == 0);
    BakeOptions options;
    options.output_folder = reference;
    run_bake(read_bake_case(case_file), options);
    expect_same_outputs(reference, killed);
    EXPECT_TRUE(fs::exists(killed / "manifest.json"));
    return;
  }
  FAIL() << "the runner always finished before it could be killed";
}

TEST_F(BakeRun, ResumeRefusesAnotherCaseOrAMissingCheckpoint) {
  const auto folder = scratch_folder();
  const BakeCase c = read_bake_case(write_text(folder / "case.toml", small_flume_case(8.0, 2.0)));
  BakeOptions options;
  options.output_folder = folder / "out";
  options.resume = true;
  try {
    run_bake(c, options);
    ADD_FAILURE() << "resumed without a checkpoint";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("nothing to resume"), std::string::npos) << error.what();
  }
  // A checkpoint of another case (different gauges) is refused with the fix.
  std::string other_text = small_flume_case(8.0, 2.0);
  other_text.replace(other_text.find("name = \"g2\""), 11, "name = \"g3\"");
  const BakeCase other = read_bake_case(write_text(folder / "other.toml", other_text));
  BakeOptions first;
  first.output_folder = folder / "out";
  const auto pid = start_runner(folder / "case.toml", first.output_folder, false);
  while (!fs::exists(checkpoint_path(first.output_folder)) && waitpid(pid, nullptr, WNOHANG) == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  kill(pid, SIGKILL);
  wait_for(pid);
  if (!fs::exists(checkpoint_path(first.output_folder))) GTEST_SKIP() << "the runner finished before a checkpoint could be seen";
  try {
    run_bake(other, options);
    ADD_FAILURE() << "resumed another case";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("different case"), std::string::npos) << error.what();
    // The fix it gives is one that works: without resume the folder is refused (it holds the
    // checkpoint), so it names overwrite (issue 44).
    EXPECT_NE(std::string(error.what()).find("BakeOptions::overwrite instead of BakeOptions::resume"), std::string::npos)
        << error.what();
  }
  // A checkpoint of the same case written by a solver of another physics revision, or by a nearshore
  // from before checkpoints recorded it, is refused too: resumed, one sequence would hold two physics.
  // The checkpoint stays as it was (another build may resume it).
  const fs::path checkpoint = checkpoint_path(first.output_folder);
  const auto with_header = [&](const std::string& magic, std::int32_t revision) {
    std::fstream file(checkpoint, std::ios::in | std::ios::out | std::ios::binary);
    file.write(magic.c_str(), static_cast<std::streamsize>(magic.size() + 1));
    file.seekp(16 + 8);  // magic, case fingerprint (bake_run.cpp)
    file.write(reinterpret_cast<const char*>(&revision), sizeof revision);
  };
  const auto refusal = [&]() -> std::string {
    try {
      run_bake(c, options);
    } catch (const Error& error) {
      return error.what();
    }
    return "resumed";
  };
  with_header("nearshore-ckpt5", boussinesq::kSolverPhysicsRevision + 1);
  const auto size_before = fs::file_size(checkpoint);
  std::string message = refusal();
  EXPECT_NE(message.find(fmt::format("physics revision {}, and this nearshore's solver is revision {}",
                                     boussinesq::kSolverPhysicsRevision + 1, boussinesq::kSolverPhysicsRevision)),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("BakeOptions::overwrite instead of BakeOptions::resume"), std::string::npos) << message;
  EXPECT_EQ(fs::file_size(checkpoint), size_before);
  with_header("nearshore-ckpt3", boussinesq::kSolverPhysicsRevision);
  message = refusal();
  EXPECT_NE(message.find("older nearshore (version 3"), std::string::npos) << message;
  with_header("nearshore-ckpt4", boussinesq::kSolverPhysicsRevision);
  message = refusal();
  EXPECT_NE(message.find("older nearshore (version 4, before the gauges recorded the flux"), std::string::npos) << message;
  // Its own revision again: the same checkpoint resumes and the bake completes.
  with_header("nearshore-ckpt5", boussinesq::kSolverPhysicsRevision);
  EXPECT_NO_THROW(run_bake(c, options));
  // The manifest's solver record says which physics baked the sequence.
  const auto manifest = nlohmann::json::parse(std::ifstream(first.output_folder / "manifest.json"));
  EXPECT_EQ(manifest["solver"]["physics_revision"].get<int>(), boussinesq::kSolverPhysicsRevision) << manifest["solver"].dump();
}

// The guard's message for a case: run until it stops the run, return what it said (the whole path:
// detection, message, kept checkpoint, no manifest).
std::string stability_guard_message(const std::string& case_text, const fs::path& folder) {
  fs::create_directories(folder);
  const BakeCase c = read_bake_case(write_text(folder / "case.toml", case_text));
  BakeOptions options;
  options.output_folder = folder / "out";
  try {
    run_bake(c, options);
    ADD_FAILURE() << "the guard did not stop the run";
  } catch (const Error& error) {
    const std::string message = error.what();
    if (message.find("is kept in") != std::string::npos) {
      EXPECT_TRUE(fs::exists(checkpoint_path(options.output_folder)));
    }
    EXPECT_FALSE(fs::exists(options.output_folder / "manifest.json"));
    return message;
  }
  return {};
}

TEST_F(BakeRun, StabilityGuardNamesTimeCellDepthAndTheFix) {
  // A threshold of |eta| > 0.001 x max(d, 1 m) = 1 mm is crossed by the 2 cm waves: the guard's
  // whole path runs on an otherwise healthy bake.
  const std::string low_guard = "[solver]\nblowup_elevation_depth_ratio = 0.001\n";
  std::string flume = small_flume_case(8.0, 0.5);
  const std::string message = stability_guard_message(flume + low_guard, scratch_folder());
  for (const char* fragment : {"unstable at t = ", "cell (column ", "x = ", "still-water depth 0.500 m", "time.courant_number",
                               "breaking.onset_celerity_fraction", "case.toml",
                               // six cells across: the narrow flume's own remedy is named ...
                               "the grid is 6 cells across", "bathymetry.width_m"})
    EXPECT_NE(message.find(fragment), std::string::npos) << fragment << " missing in: " << message;
  // ... and not the wall advice, which in a narrow flume made Hansen & Svendsen blow up sooner.
  EXPECT_EQ(message.find("solver.shapiro_filter_order = 0"), std::string::npos) << message;

  // The same flume 1.2 m wide (12 cells): 0.1 m cells in 0.5 m of water, the grid-scale filter's
  // known limit beside walls is named, and no flume remedy.
  flume.replace(flume.find("width_m = 0.6"), 13, "width_m = 1.2");
  const std::string wide = stability_guard_message(flume + low_guard, scratch_folder() / "wide");
  EXPECT_NE(wide.find("solver.shapiro_filter_order = 0"), std::string::npos) << wide;
  EXPECT_EQ(wide.find("cells across"), std::string::npos) << wide;
}

}  // namespace
}  // namespace nearshore::bake
