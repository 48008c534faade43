// Whole sea-state libraries of the demo harbour, baked for real (issue 16's "done when"): a tiny,
// coarse library (4 states: 2 directions x 2 tides, 16 m cells, 50 s of regular swell) baked by
// library_runner, the process that makes the library calls of `nearshore library`, alone and under
// `mpirun -np 2`:
//   - the sequences under MPI are bit-identical to the serial run's;
//   - kill -9 of one rank, and of the whole job, midway; the rerun bakes only what was missing
//     (finished states are "reused": their manifests are the same files, untouched);
//   - a state with a bad parameter is recorded in the index with its error, the others bake.
// The MPI tests are skipped, saying why, in a build without MPI.
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/sequence/library_index.hpp"
#include "nearshore/sequence/loops_file.hpp"
#include "library_test_files.hpp"

namespace nearshore::library {
namespace {
namespace fs = std::filesystem;
using testing::write_text_file;
using sequence::LibraryIndex;
using sequence::LibraryStateStatus;

std::string file_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool mpi_built() { return std::string(MPIEXEC_PATH).size() > 0; }

// The live processes of session `session` (/proc/PID/stat: "pid (comm) state ppid pgrp session ...").
std::vector<pid_t> session_processes(pid_t session) {
  std::vector<pid_t> found;
  for (const auto& item : fs::directory_iterator("/proc")) {
    const std::string name = item.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string stat = file_bytes(item.path() / "stat");
    const auto close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream fields(stat.substr(close + 2));
    char state = 0;
    long ppid = 0, group = 0, sid = 0;
    fields >> state >> ppid >> group >> sid;
    if (sid == session && state != 'Z') found.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return found;
}

// kill -9 of a whole job, as a batch system ends one: mpirun and every rank at once; returns when
// none of them runs any more.
void kill_job(pid_t session) {
  for (pid_t pid : session_processes(session)) ::kill(pid, SIGKILL);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!session_processes(session).empty() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
}

// The library's base case: regular 16 s swell from the south over the demo harbour at 16 m cells
// (2 cells fewer than 8 per 135 m wavelength would be refused by an irregular maker; a regular one
// is not checked, and the tests compare runs, not physics), 30 s spun up and 20 s of frames.
const char* const kBaseCase = R"(title = "library test: demo harbour, regular swell"
[bathymetry]
kind = "harbour_grid"
file = "harbour/depth.exr"
[time]
duration_s = 50.0
spin_up_s = 30.0
output_interval_s = 1.0
courant_number = 0.5
checkpoint_interval_s = 20.0
[wave_maker]
kind = "regular"
facing = "south"
source_line_m = 120.0
height_m = 0.5
period_s = 16.0
ramp_time_s = 10.0
[[sponges]]
side = "south"
width_m = 100.0
[[sponges]]
side = "east"
width_m = 100.0
[[sponges]]
side = "west"
width_m = 100.0
)";

struct Finished {
  int status = 0;
  std::string log;
};

class LibraryRun : public ::testing::Test {
 protected:
  void SetUp() override {
    ProgressBar::set_quiet(true);
    root_ = fs::path(NEARSHORE_BINARY_DIR) / "tests" / "library" / "scratch" /
            ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(root_);
    fs::create_directories(root_);
    // The demo harbour gridded at 16 m: 100 x 75 cells.
    const bathymetry::DemoHarbourFiles chart = bathymetry::write_demo_harbour(root_ / "chart");
    bathymetry::BathyRequest request;
    request.inputs = {chart.depth_geotiff, chart.structures_geojson, chart.land_geojson, chart.coastline_geojson};
    request.spacing_m = 16.0;
    bathymetry::write_bathymetry_outputs(root_ / "harbour", bathymetry::build_harbour_grid(request));
    write_text_file(root_ / "base.toml", kBaseCase);
    library_ = write_text_file(root_ / "library.toml",
                          "title = \"library test\"\nbase_case = \"base.toml\"\n[sweep]\n"
                          "direction_deg = [80.0, 100.0]\ntide_m = [0.0, 1.0]\n");
  }

  // Runs library_runner on `library` into `folder`, alone (ranks = 0) or under mpirun -np ranks;
  // `fault` goes into NEARSHORE_LIBRARY_FAULT. Returns the exit status and the output.
  pid_t start(const fs::path& library, const fs::path& folder, int ranks, const std::string& fault = {},
              bool overwrite = false) {
    const fs::path log = folder.string() + ".log";
    const pid_t pid = fork();
    if (pid == 0) {
      setsid();  // the whole job in one session (mpirun gives each rank its own process group)
      setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
      setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
      if (!fault.empty()) setenv("NEARSHORE_LIBRARY_FAULT", fault.c_str(), 1);
      if (!std::freopen(log.c_str(), "w", stderr) || !std::freopen(log.c_str(), "a", stdout)) _exit(126);
      std::vector<std::string> arguments;
      if (ranks > 0) {
        arguments = {MPIEXEC_PATH, "--oversubscribe", "-np", std::to_string(ranks)};
        if (!fault.empty()) arguments.insert(arguments.end(), {"-x", "NEARSHORE_LIBRARY_FAULT"});
      }
      arguments.insert(arguments.end(), {LIBRARY_RUNNER_PATH, library.string(), folder.string()});
      if (overwrite) arguments.push_back("overwrite");
      std::vector<char*> argv;
      for (std::string& argument : arguments) argv.push_back(argument.data());
      argv.push_back(nullptr);
      execv(argv[0], argv.data());
      _exit(127);
    }
    return pid;
  }
  static Finished wait_for(pid_t pid, const fs::path& folder) {
    int status = 0;
    waitpid(pid, &status, 0);
    return {status, file_bytes(folder.string() + ".log")};
  }
  Finished run(const fs::path& folder, int ranks, const std::string& fault = {}) {
    return wait_for(start(library_, folder, ranks, fault), folder);
  }

  fs::path root_, library_;
};

bool exited_with(const Finished& run, int code) { return WIFEXITED(run.status) && WEXITSTATUS(run.status) == code; }

// States whose sequence and loop tables are complete (what a rerun must not bake again), with the
// modification time of their manifest in nanoseconds.
std::map<std::string, long long> complete_states(const fs::path& folder) {
  std::map<std::string, long long> complete;
  if (!fs::exists(folder / "states")) return complete;
  for (const auto& item : fs::directory_iterator(folder / "states")) {
    const fs::path manifest = item.path() / "manifest.json";
    if (!fs::exists(manifest) || !fs::exists(item.path() / "loops.json")) continue;
    struct stat info {};
    ::stat(manifest.c_str(), &info);
    complete[item.path().filename().string()] = info.st_mtim.tv_sec * 1'000'000'000LL + info.st_mtim.tv_nsec;
  }
  return complete;
}

// Every file of every state is byte-identical, except loops.json, whose report holds wall times:
// there the tables (transitions, loops, random walk) and the checksums tying them to the sequence.
void expect_same_library(const fs::path& reference, const fs::path& other) {
  const LibraryIndex a = sequence::read_library_index(reference), b = sequence::read_library_index(other);
  ASSERT_EQ(a.states.size(), b.states.size());
  int files = 0;
  for (std::size_t s = 0; s < a.states.size(); ++s) {
    EXPECT_EQ(a.states[s].id, b.states[s].id);
    EXPECT_EQ(a.states[s].status, b.states[s].status);
    EXPECT_EQ(a.states[s].manifest_checksum, b.states[s].manifest_checksum) << a.states[s].id;
    const fs::path folder_a = reference / a.states[s].sequence, folder_b = other / b.states[s].sequence;
    std::set<std::string> names_a, names_b;
    for (const auto& item : fs::directory_iterator(folder_a)) names_a.insert(item.path().filename().string());
    for (const auto& item : fs::directory_iterator(folder_b)) names_b.insert(item.path().filename().string());
    EXPECT_EQ(names_a, names_b) << a.states[s].id;
    for (const std::string& name : names_a) {
      if (name == "loops.json" || !names_b.count(name)) continue;
      EXPECT_TRUE(file_bytes(folder_a / name) == file_bytes(folder_b / name)) << a.states[s].id << "/" << name << " differs";
      ++files;
    }
    const sequence::LoopsFile loops_a = sequence::read_loops_file(folder_a), loops_b = sequence::read_loops_file(folder_b);
    EXPECT_TRUE(loops_a.transitions == loops_b.transitions) << a.states[s].id;
    EXPECT_TRUE(loops_a.random_walk == loops_b.random_walk) << a.states[s].id;
    EXPECT_TRUE(loops_a.report.best_loops_by_length == loops_b.report.best_loops_by_length) << a.states[s].id;
    EXPECT_EQ(loops_a.sequence_manifest_checksum, loops_b.sequence_manifest_checksum);
    EXPECT_EQ(loops_a.gram_checksum, loops_b.gram_checksum);
  }
  EXPECT_GT(files, 4 * 20);  // 21 frames, manifest, depth.exr, gauges.csv, gram per state
}

// After a rerun: every state baked, and those complete before it were reused, not baked again.
void expect_resumed_without_rebaking(const fs::path& folder, const std::map<std::string, long long>& before) {
  const LibraryIndex index = sequence::read_library_index(folder);
  EXPECT_EQ(index.count(LibraryStateStatus::kBaked), 4);
  const std::map<std::string, long long> after = complete_states(folder);
  for (const LibraryIndex::State& state : index.states) {
    if (before.count(state.id)) {
      EXPECT_EQ(state.run.action, "reused") << state.id;
      EXPECT_EQ(after.at(state.id), before.at(state.id)) << state.id << ": its manifest was written again";
    } else {
      EXPECT_NE(state.run.action, "reused") << state.id;
    }
  }
}

TEST_F(LibraryRun, SerialRunBakesEveryStateWithLoopTablesAndResumesWithoutBakingAgain) {
  const fs::path folder = root_ / "serial";
  const Finished first = run(folder, 0);
  ASSERT_TRUE(exited_with(first, 0)) << first.log;
  const LibraryIndex index = sequence::read_library_index(folder);
  ASSERT_EQ(index.states.size(), 4u);
  EXPECT_EQ(index.states[0].id, "dir80_tide+0");
  EXPECT_EQ(index.states[3].id, "dir100_tide+1");
  for (const LibraryIndex::State& state : index.states) {
    EXPECT_EQ(state.status, LibraryStateStatus::kBaked) << state.id << ": " << state.error;
    EXPECT_EQ(state.run.action, "baked");
    EXPECT_TRUE(fs::exists(folder / state.sequence / "loops.json"));
    EXPECT_GT(state.cost_cell_steps, 0);
  }
  // The tide raised the still water: a state at +1 m has depths 1 m more (depth.exr, the manifest's grid).
  EXPECT_NE(index.states[0].manifest_checksum, index.states[1].manifest_checksum);
  EXPECT_NE(first.log.find("library: 4/4 states done (0 failed)"), std::string::npos) << first.log;
  const std::map<std::string, long long> before = complete_states(folder);
  ASSERT_EQ(before.size(), 4u);
  const Finished again = run(folder, 0);
  ASSERT_TRUE(exited_with(again, 0)) << again.log;
  expect_resumed_without_rebaking(folder, before);
}

TEST_F(LibraryRun, KillDuringASerialRunThenRerunBakesOnlyWhatIsMissing) {
  const fs::path folder = root_ / "killed";
  const Finished killed = run(folder, 0, "kill-at-start:0:3");
  ASSERT_TRUE(WIFSIGNALED(killed.status) && WTERMSIG(killed.status) == SIGKILL) << killed.log;
  const std::map<std::string, long long> before = complete_states(folder);
  EXPECT_EQ(before.size(), 2u);
  const Finished rerun = run(folder, 0);
  ASSERT_TRUE(exited_with(rerun, 0)) << rerun.log;
  expect_resumed_without_rebaking(folder, before);
}

TEST_F(LibraryRun, MpiRunWithTwoRanksGivesBitIdenticalSequencesToASerialRun) {
  if (!mpi_built()) GTEST_SKIP() << "this build has no MPI (nearshore_library_mpi was not built)";
  const Finished serial = run(root_ / "serial", 0);
  ASSERT_TRUE(exited_with(serial, 0)) << serial.log;
  const Finished mpi = run(root_ / "mpi", 2);
  ASSERT_TRUE(exited_with(mpi, 0)) << mpi.log;
  expect_same_library(root_ / "serial", root_ / "mpi");
  // Both ranks worked: dynamic hand-out, rank 0 included.
  std::set<int> ranks;
  for (const LibraryIndex::State& state : sequence::read_library_index(root_ / "mpi").states) ranks.insert(state.run.rank);
  EXPECT_EQ(ranks, (std::set<int>{0, 1}));
  EXPECT_NE(mpi.log.find("| rank 1: "), std::string::npos) << mpi.log;
}

TEST_F(LibraryRun, KillOfOneRankThenRerunFinishesWithoutBakingFinishedStatesAgain) {
  if (!mpi_built()) GTEST_SKIP() << "this build has no MPI (nearshore_library_mpi was not built)";
  const fs::path folder = root_ / "mpi";
  // Rank 1 dies as it takes up its second state; mpirun then ends the job (Open MPI's default).
  // Rank 0's worker waits at its own second state, so rank 1 always gets a second one: without it,
  // a rank 1 slowed by the machine could see rank 0 bake the other three states and never die.
  const Finished killed = run(folder, 2, "kill-at-start:1:2,pause-at-start:0:2:" + (root_ / "rank0_paused").string());
  EXPECT_FALSE(exited_with(killed, 0)) << killed.log;
  const std::map<std::string, long long> before = complete_states(folder);
  EXPECT_GE(before.size(), 1u);
  EXPECT_LT(before.size(), 4u);
  const Finished rerun = run(folder, 2);
  ASSERT_TRUE(exited_with(rerun, 0)) << rerun.log;
  expect_resumed_without_rebaking(folder, before);
  const Finished serial = run(root_ / "serial", 0);
  ASSERT_TRUE(exited_with(serial, 0)) << serial.log;
  expect_same_library(root_ / "serial", folder);
}

TEST_F(LibraryRun, KillOfTheWholeJobThenRerunFinishesWithoutBakingFinishedStatesAgain) {
  if (!mpi_built()) GTEST_SKIP() << "this build has no MPI (nearshore_library_mpi was not built)";
  const fs::path folder = root_ / "mpi", pause = root_ / "pause";
  // Rank 1 stops as it takes up its second state; then kill -9 of mpirun and every rank at once.
  // Rank 0 waits at its own second state, so rank 1 always gets a second one (as in the test above:
  // with states of a fraction of a second, rank 0 could otherwise bake the other three first).
  const pid_t job =
      start(library_, folder, 2, "pause-at-start:1:2:" + pause.string() + ",pause-at-start:0:2:" + (root_ / "rank0_paused").string());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(pause.string() + ".waiting") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(fs::exists(pause.string() + ".waiting")) << file_bytes(folder.string() + ".log");
  kill_job(job);
  const Finished killed = wait_for(job, folder);
  ASSERT_TRUE(WIFSIGNALED(killed.status) && WTERMSIG(killed.status) == SIGKILL) << killed.log;
  ASSERT_TRUE(session_processes(job).empty()) << "a rank of the killed job still runs";
  const std::map<std::string, long long> before = complete_states(folder);
  EXPECT_GE(before.size(), 1u);
  EXPECT_LT(before.size(), 4u);
  const Finished rerun = run(folder, 2);
  ASSERT_TRUE(exited_with(rerun, 0)) << rerun.log;
  expect_resumed_without_rebaking(folder, before);
}

TEST_F(LibraryRun, ABadStateIsRecordedInTheIndexWithItsErrorAndTheOthersBake) {
  // 0.05 s waves: shorter than any the case reader accepts (0.1 s: surface tension governs).
  const fs::path library = write_text_file(root_ / "bad.toml", "base_case = \"base.toml\"\n[sweep]\nperiod_s = [16.0, 0.05]\n");
  const fs::path folder = root_ / "bad";
  const Finished bad = wait_for(start(library, folder, 0), folder);
  EXPECT_TRUE(exited_with(bad, 2)) << bad.log;
  const LibraryIndex index = sequence::read_library_index(folder);
  ASSERT_EQ(index.states.size(), 2u);
  EXPECT_EQ(index.states[0].status, LibraryStateStatus::kBaked) << index.states[0].error;
  EXPECT_EQ(index.states[1].id, "t0.05");
  EXPECT_EQ(index.states[1].status, LibraryStateStatus::kFailed);
  EXPECT_NE(index.states[1].error.find("cases/t0.05.json"), std::string::npos) << index.states[1].error;
  EXPECT_NE(index.states[1].error.find("wave_maker.period_s"), std::string::npos) << index.states[1].error;
  EXPECT_NE(bad.log.find("2/2 states done (1 failed)"), std::string::npos) << bad.log;
}

TEST_F(LibraryRun, AChangedBaseCaseIsRefusedUntouchedUnlessOverwrite) {
  const fs::path folder = root_ / "lib";
  ASSERT_TRUE(exited_with(run(folder, 0), 0));
  const std::map<std::string, long long> before = complete_states(folder);
  std::string changed = kBaseCase;
  changed.replace(changed.find("height_m = 0.5"), 14, "height_m = 0.6");
  write_text_file(root_ / "base.toml", changed);
  const Finished refused = run(folder, 0);
  EXPECT_TRUE(exited_with(refused, 1)) << refused.log;
  EXPECT_NE(refused.log.find("LibraryOptions::overwrite"), std::string::npos) << refused.log;
  EXPECT_EQ(complete_states(folder), before);
  const Finished overwritten = wait_for(start(library_, folder, 0, {}, true), folder);
  ASSERT_TRUE(exited_with(overwritten, 0)) << overwritten.log;
  for (const LibraryIndex::State& state : sequence::read_library_index(folder).states)
    EXPECT_EQ(state.run.action, "baked") << state.id;
}

}  // namespace
}  // namespace nearshore::library
