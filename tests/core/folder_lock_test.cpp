// FolderLock: one writer per folder, the refused one told who holds it; the kernel frees the lock
// of a holder that is killed, so a crash never leaves a folder locked.
#include "nearshore/core/folder_lock.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "core_test_folders.hpp"
#include "nearshore/core/error.hpp"

namespace fs = std::filesystem;

namespace {

fs::path fresh_lock_folder(const std::string& name) { return nearshore::core_testing::fresh_core_folder("lock_" + name); }

// The message of the Error that locking `folder` throws, or "" when it does not.
std::string refusal(const fs::path& folder) {
  try {
    nearshore::FolderLock lock(folder, "second writer");
  } catch (const nearshore::Error& error) {
    return error.what();
  }
  return {};
}

}  // namespace

TEST(FolderLock, ASecondWriterIsRefusedNamingTheFolderAndTheHolder) {
  const fs::path folder = fresh_lock_folder("second");
  {
    const nearshore::FolderLock lock(folder, "baking harbour.toml");
    const std::string message = refusal(folder);
    EXPECT_NE(message.find(folder.string() + ": is in use"), std::string::npos) << message;
    EXPECT_NE(message.find("PID " + std::to_string(::getpid())), std::string::npos) << message;
    EXPECT_NE(message.find("baking harbour.toml"), std::string::npos) << message;
    EXPECT_NE(message.find("another folder"), std::string::npos) << "no fix in: " << message;
    EXPECT_NE(nearshore::folder_lock_holder(folder).find("PID " + std::to_string(::getpid())), std::string::npos);
  }
  // Released and emptied: the next writer gets it, two finished folders hold the same bytes.
  EXPECT_EQ(refusal(folder), "");
  EXPECT_TRUE(fs::exists(folder / nearshore::kFolderLockFile));
  EXPECT_EQ(fs::file_size(folder / nearshore::kFolderLockFile), 0u);
  EXPECT_EQ(nearshore::folder_lock_holder(folder), "");
}

TEST(FolderLock, MovedLockStaysHeldUntilItsLastOwnerGoes) {
  const fs::path folder = fresh_lock_folder("moved");
  std::optional<nearshore::FolderLock> outer;
  {
    nearshore::FolderLock lock(folder, "moving");
    outer.emplace(std::move(lock));
  }
  EXPECT_NE(refusal(folder), "");
  outer.reset();
  EXPECT_EQ(refusal(folder), "");
}

TEST(FolderLock, AKilledHolderLeavesTheFolderFree) {
  const fs::path folder = fresh_lock_folder("killed");
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t child = fork();
  if (child == 0) {
    const nearshore::FolderLock lock(folder, "held by a child");
    const char byte = 1;
    if (write(ready[1], &byte, 1) != 1) _exit(1);
    pause();  // until killed
    _exit(0);
  }
  char byte = 0;
  ASSERT_EQ(read(ready[0], &byte, 1), 1);
  const std::string message = refusal(folder);
  EXPECT_NE(message.find("PID " + std::to_string(child)), std::string::npos) << message;
  EXPECT_NE(message.find("held by a child"), std::string::npos) << message;
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  EXPECT_EQ(refusal(folder), "");  // no stale lock, whatever the file still says
  close(ready[0]);
  close(ready[1]);
}

TEST(FolderLock, AFolderThatCannotHoldTheLockFileSaysWhy) {
  const fs::path folder = fresh_lock_folder("missing") / "not_there";
  const std::string message = refusal(folder);
  EXPECT_NE(message.find("cannot create its lock file"), std::string::npos) << message;
}
