// Issue 13, item 9: paths that are not what they should be are named as such. A manifest.json that
// is a folder ended in "std::bad_alloc" (a folder opens for reading on Linux and reports a size).
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <string>

#include "nearshore/core/error.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "nearshore/sequence/loop_playback.hpp"
#include "nearshore/sequence/loops_file.hpp"
#include "nearshore/sequence/sequence_format.hpp"
#include "nearshore/sequence/sequence_reader.hpp"
#include "test_sequence.hpp"

namespace nearshore::sequence {
namespace {
using namespace testing;
namespace fs = std::filesystem;

TEST(SequencePaths, AFolderWhereAFileShouldBeIsNamedAsOne) {
  const auto folder = fresh_folder("folder_as_file");
  fs::create_directories(folder / "a_folder");
  const std::string bytes = error_message_of([&] { read_file_bytes(folder / "a_folder"); });
  EXPECT_NE(bytes.find("a_folder: is a folder, not a file"), std::string::npos) << bytes;
  FileBuffer buffer;
  const std::string into = error_message_of([&] { read_file_into(folder / "a_folder", buffer); });
  EXPECT_NE(into.find("a_folder: is a folder, not a file"), std::string::npos) << into;
}

TEST(SequencePaths, ManifestThatIsAFolderIsNamedAsOne) {
  const auto folder = fresh_folder("manifest_folder");
  write_test_sequence(folder, 2);
  fs::remove(folder / std::string(kManifestFile));
  fs::create_directory(folder / std::string(kManifestFile));
  const std::string error = error_message_of([&] { SequenceReader reader(folder); });
  EXPECT_NE(error.find("manifest.json: is a folder, not the manifest file a bake writes"), std::string::npos) << error;
  EXPECT_EQ(error.find("bad_alloc"), std::string::npos) << error;
}

TEST(SequencePaths, LoopsFileThatIsAFolderIsNamedAsOne) {
  const auto folder = fresh_folder("loops_folder");
  write_test_sequence(folder, 2);
  fs::create_directory(folder / std::string(kLoopsFileName));
  const std::string error = error_message_of([&] { read_loop_schedule(folder); });
  EXPECT_NE(error.find("loops.json: is not a regular file"), std::string::npos) << error;
}

TEST(SequencePaths, SequenceFolderThatIsMissingOrAFileIsNamedAsSuch) {
  const auto folder = fresh_folder("not_there");
  EXPECT_NE(error_message_of([&] { SequenceReader reader(folder); }).find("not_there: does not exist"), std::string::npos);
  fs::create_directories(folder);
  std::ofstream(folder / "a_file") << "x";
  EXPECT_NE(error_message_of([&] { SequenceReader reader(folder / "a_file"); }).find("a_file: is a file, not a sequence folder"),
            std::string::npos);
}

// Issue 13, item 3: a loop of no frames (what a length that rounds to zero or below asks for) is
// refused when it is scheduled, not read outside the frames.
TEST(SequencePaths, LoopOfNoFramesIsRefused) {
  EXPECT_NE(error_message_of([] { schedule_loop(0, 0, {}); }).find("shorter than one frame"), std::string::npos);
  EXPECT_NE(error_message_of([] { schedule_loop(-1, 5, {}); }).find("starts before frame 0"), std::string::npos);
  EXPECT_NE(error_message_of([] { schedule_loop(2, 5, {{4, -1, 0}}); }).find("has a jump 4 -> -1"), std::string::npos);
  EXPECT_EQ(schedule_loop(2, 3, {{4, 2, 1}}).shown.size(), 3u);
}

}  // namespace
}  // namespace nearshore::sequence
