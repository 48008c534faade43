#include "nearshore/core/atomic_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core_test_folders.hpp"
#include "nearshore/core/error.hpp"

namespace fs = std::filesystem;
using nearshore::core_testing::fresh_core_folder;

namespace {
std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST(AtomicFile, WritesAndReplaces) {
  const fs::path folder = fresh_core_folder("replace");
  nearshore::write_text_atomically(folder / "a.txt", "first");
  nearshore::write_text_atomically(folder / "a.txt", "second");
  EXPECT_EQ(read_all(folder / "a.txt"), "second");
  EXPECT_EQ(std::distance(fs::directory_iterator(folder), fs::directory_iterator{}), 1) << "no temporary left";
}

TEST(AtomicFile, FailedWriterLeavesOldContentAndNoTemporary) {
  const fs::path folder = fresh_core_folder("fail");
  nearshore::write_text_atomically(folder / "a.txt", "kept");
  EXPECT_THROW(nearshore::write_file_atomically(folder / "a.txt",
                                                [](const fs::path& temporary) {
                                                  std::ofstream(temporary) << "half";
                                                  throw nearshore::Error("a.txt", "simulated failure");
                                                }),
               nearshore::Error);
  EXPECT_EQ(read_all(folder / "a.txt"), "kept");
  EXPECT_EQ(std::distance(fs::directory_iterator(folder), fs::directory_iterator{}), 1);
}

TEST(AtomicFile, FullDiskIsAClearErrorAndReplacesNothing) {
  // /dev/full answers every write with ENOSPC: the same path a full disk takes.
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "/dev/full not available";
  const fs::path folder = fresh_core_folder("full");
  nearshore::write_text_atomically(folder / "a.txt", "kept");
  try {
    nearshore::write_file_atomically(folder / "a.txt", [](const fs::path&) {
      std::FILE* full = std::fopen("/dev/full", "wb");
      ASSERT_NE(full, nullptr);
      std::fputs("x", full);
      const bool failed = std::fflush(full) != 0;
      std::fclose(full);
      if (failed) throw nearshore::Error("a.txt", "write failed: No space left on device", "free disk space");
    });
    FAIL() << "expected an error";
  } catch (const nearshore::Error& e) {
    EXPECT_NE(std::string(e.what()).find("No space left"), std::string::npos);
  }
  EXPECT_EQ(read_all(folder / "a.txt"), "kept");
}

TEST(AtomicFile, MissingFolderNamesThePath) {
  try {
    nearshore::write_text_atomically("/nonexistent_nearshore_folder/x.txt", "x");
    FAIL() << "expected an error";
  } catch (const nearshore::Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_nearshore_folder/x.txt"), std::string::npos) << e.what();
  }
}

TEST(RequireReadableFile, MissingFileMessageNamesFileAndFix) {
  try {
    nearshore::require_readable_file("/no/such/chart.000", "an S-57 chart");
    FAIL();
  } catch (const nearshore::Error& e) {
    EXPECT_EQ(std::string(e.what()), "/no/such/chart.000: does not exist; give the path of an S-57 chart");
  }
}

// A writer killed between its temporary file and the rename leaves NAME.tmp-PID; the next writer
// of the folder removes exactly those (issue 13), nothing that merely looks similar.
TEST(AtomicFile, RemovesOnlyStaleTemporaryFiles) {
  const fs::path folder = fresh_core_folder("stale");
  for (const char* name : {"frame_000003.exr.tmp-4711", "checkpoint.bin.tmp-12", "notes.tmp-draft", ".tmp-5", "frame.exr",
                           "a.tmp-", "b.tmp-12345678901"})
    std::ofstream(folder / name) << "x";
  fs::create_directories(folder / "sub.tmp-7");  // a folder is no temporary file
  EXPECT_EQ(nearshore::remove_stale_temporary_files(folder), 2);
  std::vector<std::string> left;
  for (const auto& item : fs::directory_iterator(folder)) left.push_back(item.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{".tmp-5", "a.tmp-", "b.tmp-12345678901", "frame.exr", "notes.tmp-draft", "sub.tmp-7"}));
  EXPECT_EQ(nearshore::remove_stale_temporary_files(folder / "missing"), 0);
}

TEST(AtomicFile, AFullDiskIsSaidInWords) {
  EXPECT_NE(nearshore::write_failure_reason(ENOSPC).find("(the disk is full)"), std::string::npos);
  EXPECT_EQ(nearshore::write_failure_reason(EACCES).find("full"), std::string::npos);
}
