// What bad luck does to a bake, done for real (issue 13): two processes baking into one folder at
// once, kill -9 of a bake half-way through a frame, a checkpoint and the manifest, then resume; a
// full disk on a small tmpfs. Each starts fault_runner (fault_runner.cpp), which kills or pauses
// itself at the chosen write; the result is compared byte for byte with an uninterrupted bake.
#include <sched.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "bake_test_support.hpp"
#include "fault_support.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/core/folder_lock.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::bake {
namespace {
namespace fs = std::filesystem;
using namespace faults;

std::vector<std::string> temporary_files(const fs::path& folder) {
  std::vector<std::string> found;
  for (const auto& item : fs::recursive_directory_iterator(folder))
    if (item.path().filename().string().find(".tmp-") != std::string::npos) found.push_back(item.path().string());
  return found;
}

// The folders hold the same files with the same bytes (the manifest too: it records no clock).
void expect_same_folders(const fs::path& reference, const fs::path& other) {
  std::set<std::string> names, other_names;
  for (const auto& item : fs::directory_iterator(reference)) names.insert(item.path().filename().string());
  for (const auto& item : fs::directory_iterator(other)) other_names.insert(item.path().filename().string());
  EXPECT_EQ(names, other_names);
  int compared = 0;
  for (const std::string& name : names) {
    if (!other_names.count(name)) continue;
    EXPECT_TRUE(file_bytes(reference / name) == file_bytes(other / name)) << name << " differs";
    ++compared;
  }
  EXPECT_GT(compared, 14);  // 13 frames, manifest, depth.exr, gauges.csv, the lock file
}

class Faults : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = scratch_folder();
    // 13 frames (t = 2 ... 8 s, every 0.5 s), checkpoints at t = 2, 4 and 6 s: 720 cells, 400 steps.
    case_file_ = testing::write_text(folder_ / "case.toml", testing::small_flume_case(8.0, 2.0));
  }
  fs::path bake_reference() {
    const fs::path reference = folder_ / "uninterrupted";
    EXPECT_TRUE(exited_with(wait_for(start_runner({"bake", case_file_.string(), reference.string()})), 0));
    return reference;
  }
  // Kills a bake with `fault`, resumes it, and compares with an uninterrupted bake.
  void kill_then_resume(const std::string& fault, const std::string& expected_leftover) {
    const fs::path killed = folder_ / "killed";
    const int status = wait_for(start_runner({"bake", case_file_.string(), killed.string()}, fault));
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "the fault " << fault << " never struck";
    EXPECT_FALSE(fs::exists(killed / "manifest.json")) << "the killed bake looks complete";
    EXPECT_TRUE(fs::exists(checkpoint_path(killed)));
    // The kill struck inside the write: its temporary file is there, half written or unrenamed.
    const std::vector<std::string> left = temporary_files(killed);
    ASSERT_EQ(left.size(), 1u);
    EXPECT_NE(left.front().find(expected_leftover + ".tmp-"), std::string::npos) << left.front();
    // Without resume (or overwrite) a new bake refuses the folder: it holds the checkpoint.
    const fs::path refused_log = folder_ / "refused.txt";
    EXPECT_TRUE(exited_with(wait_for(start_runner({"bake", case_file_.string(), killed.string()}, {}, refused_log)), 1));
    EXPECT_NE(file_bytes(refused_log).find("BakeOptions::resume"), std::string::npos) << file_bytes(refused_log);

    const fs::path resume_log = folder_ / "resume.txt";
    ASSERT_TRUE(exited_with(wait_for(start_runner({"bake", case_file_.string(), killed.string(), "resume"}, {}, resume_log)), 0))
        << file_bytes(resume_log);
    EXPECT_TRUE(temporary_files(killed).empty());
    EXPECT_FALSE(fs::exists(checkpoint_path(killed)));
    EXPECT_TRUE(exited_with(wait_for(start_runner({"verify", killed.string()})), 0));
    expect_same_folders(bake_reference(), killed);
  }

  fs::path folder_, case_file_;
};

TEST_F(Faults, TwoBakesIntoOneFolderTheSecondIsRefusedAndTheFirstCompletes) {
  const fs::path output = folder_ / "out", go = folder_ / "go";
  // The first bake stops inside its fourth frame write (holding the folder) until told to go on.
  const pid_t first = start_runner({"bake", case_file_.string(), output.string()},
                                   "pause-in-write:frame_000003.exr:1:" + go.string(), folder_ / "first.txt");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(go.string() + ".waiting") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(fs::exists(go.string() + ".waiting")) << file_bytes(folder_ / "first.txt");

  // A second bake into the same folder, even one allowed to overwrite, is refused at once, naming
  // the folder and the first one's PID; so is a loops run that would write its tables there.
  const auto started = std::chrono::steady_clock::now();
  const fs::path second_log = folder_ / "second.txt", loops_log = folder_ / "loops.txt";
  const int second = wait_for(start_runner({"bake", case_file_.string(), output.string(), "overwrite"}, {}, second_log));
  const int loops = wait_for(start_runner({"loops", output.string()}, {}, loops_log));
  const double refused_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  EXPECT_TRUE(exited_with(second, 1));
  EXPECT_TRUE(exited_with(loops, 1));
  for (const fs::path& log : {second_log, loops_log}) {
    const std::string message = file_bytes(log);
    EXPECT_NE(message.find(output.string() + ": is in use"), std::string::npos) << message;
    EXPECT_NE(message.find("PID " + std::to_string(first)), std::string::npos) << message;
    EXPECT_NE(message.find("baking " + case_file_.string()), std::string::npos) << message;
  }
  EXPECT_LT(refused_s, 10.0);  // at once, not after waiting for the lock

  std::ofstream(go).put('\n');
  const int status = wait_for(first);
  ASSERT_TRUE(exited_with(status, 0)) << file_bytes(folder_ / "first.txt");
  EXPECT_TRUE(exited_with(wait_for(start_runner({"verify", output.string()})), 0));
  expect_same_folders(bake_reference(), output);
  // The lock went with the first bake: the folder is free again.
  EXPECT_EQ(folder_lock_holder(output), "");
  EXPECT_TRUE(exited_with(wait_for(start_runner({"bake", case_file_.string(), output.string(), "overwrite"})), 0));
}

TEST_F(Faults, KillDuringAFrameWriteThenResumeGivesTheSameSequence) {
  kill_then_resume("kill-in-write:frame_000006.exr:1", "frame_000006.exr");  // t = 5 s, after the checkpoint at 4 s
}

TEST_F(Faults, KillDuringACheckpointWriteThenResumeGivesTheSameSequence) {
  kill_then_resume("kill-in-write:checkpoint.bin:2", "checkpoint.bin");  // the t = 4 s checkpoint; t = 2 s is kept
}

TEST_F(Faults, KillDuringTheManifestWriteThenResumeGivesTheSameSequence) {
  kill_then_resume("kill-in-write:manifest.json:1", "manifest.json");
}

TEST_F(Faults, KillBeforeTheManifestIsRenamedThenResumeGivesTheSameSequence) {
  kill_then_resume("kill-before-rename:manifest.json:1", "manifest.json");
}

// A full disk, for real: a 2 MiB tmpfs in a mount namespace of a child process (so nothing is left
// mounted whatever happens), filled up but for a few pages. Needs the right to mount (root or
// CAP_SYS_ADMIN); where it is missing the test says so and is skipped.
TEST_F(Faults, FullDiskNamesTheFileAndLeavesAnEarlierSequenceUntouched) {
  const fs::path disk = folder_ / "tmpfs";
  fs::create_directories(disk);
  testing::write_text(folder_ / "good.toml", testing::small_flume_case(8.0, 0.0));
  // The first checkpoint (t = 0.5 s, 52 KiB) comes before the first frame; the other case has none.
  testing::write_text(folder_ / "checkpoints.toml", testing::small_flume_case(8.0, 0.5));
  testing::write_text(folder_ / "frames.toml", testing::small_flume_case(8.0, 0.0));
  const std::string script = R"(
    set -u
    "$RUNNER" bake "$S/good.toml" "$D/good" 2> "$S/good.txt" || exit 10
    (cd "$D/good" && cksum *) > "$S/good_before.txt"
    # Fill the file system, then give back a few pages: room for the lock file, depth.exr and
    # gauges.csv, not for a checkpoint (52 KiB) or, in the second bake, for a frame (7 KiB).
    dd if=/dev/zero of="$D/filler" bs=4096 2> /dev/null
    truncate -s -16K "$D/filler"
    "$RUNNER" bake "$S/checkpoints.toml" "$D/new" 2> "$S/refused.txt"; echo $? > "$S/refused.rc"
    "$RUNNER" bake "$S/checkpoints.toml" "$D/new" allow-over-budget 2> "$S/checkpoint.txt"; echo $? > "$S/checkpoint.rc"
    ls -A "$D/new" > "$S/checkpoint_listing.txt"
    rm -rf "$D/new"
    truncate -s +4K "$D/filler"
    "$RUNNER" bake "$S/frames.toml" "$D/new" allow-over-budget 2> "$S/frame.txt"; echo $? > "$S/frame.rc"
    ls -A "$D/new" > "$S/frame_listing.txt"
    "$RUNNER" verify "$D/good" > "$S/verify.txt" 2>&1; echo $? > "$S/verify.rc"
    (cd "$D/good" && cksum *) > "$S/good_after.txt"
  )";
  const pid_t child = fork();
  if (child == 0) {
    const auto skip = [&](const std::string& why) {
      std::ofstream(folder_ / "skip.txt") << why << ": " << std::strerror(errno);
      _exit(77);
    };
    if (unshare(CLONE_NEWNS) != 0) skip("unshare(CLONE_NEWNS) for a private mount namespace failed");
    if (mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) skip("making the mounts private failed");
    if (mount("nearshore-faults", disk.c_str(), "tmpfs", 0, "size=2m") != 0) skip("mount -t tmpfs failed");
    setenv("RUNNER", FAULT_RUNNER_PATH, 1);
    setenv("S", folder_.c_str(), 1);
    setenv("D", disk.c_str(), 1);
    execl("/bin/sh", "sh", "-c", script.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  const int status = wait_for(child);
  if (exited_with(status, 77)) GTEST_SKIP() << "no tmpfs to fill: " << file_bytes(folder_ / "skip.txt");
  ASSERT_TRUE(exited_with(status, 0)) << "the script stopped (status " << status << "): " << file_bytes(folder_ / "good.txt");
  const auto text = [&](const char* name) { return file_bytes(folder_ / name); };

  // Without allow_over_budget the bake is refused before it writes anything, with the numbers.
  EXPECT_EQ(text("refused.rc"), "1\n");
  EXPECT_NE(text("refused.txt").find("of disk"), std::string::npos) << text("refused.txt");
  EXPECT_NE(text("refused.txt").find("is free in"), std::string::npos) << text("refused.txt");
  // Allowed over budget, it meets the full disk: the message names the file and says so.
  EXPECT_EQ(text("checkpoint.rc"), "1\n");
  EXPECT_NE(text("checkpoint.txt").find("checkpoint.bin: writing the checkpoint failed after"), std::string::npos)
      << text("checkpoint.txt");
  EXPECT_NE(text("checkpoint.txt").find("No space left on device (the disk is full)"), std::string::npos) << text("checkpoint.txt");
  EXPECT_EQ(text("frame.rc"), "1\n");
  EXPECT_NE(text("frame.txt").find("/new/frame_00000"), std::string::npos) << text("frame.txt");  // one of the first frames
  EXPECT_NE(text("frame.txt").find(".exr: write failed after"), std::string::npos) << text("frame.txt");
  EXPECT_NE(text("frame.txt").find("(the disk is full)"), std::string::npos) << text("frame.txt");
  // No temporary file is left behind, and nothing looks complete.
  for (const char* listing : {"checkpoint_listing.txt", "frame_listing.txt"}) {
    EXPECT_EQ(text(listing).find(".tmp-"), std::string::npos) << text(listing);
    EXPECT_EQ(text(listing).find("manifest.json"), std::string::npos) << text(listing);
  }
  // The earlier sequence on the same full disk is untouched and verifies.
  EXPECT_EQ(text("verify.rc"), "0\n") << text("verify.txt");
  EXPECT_EQ(text("good_before.txt"), text("good_after.txt"));
  EXPECT_NE(text("good_before.txt").find("manifest.json"), std::string::npos);
}

}  // namespace
}  // namespace nearshore::bake
