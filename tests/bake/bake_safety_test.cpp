// What a bake does to the folder it writes into (issue 13): a case that cannot finish is refused
// before the folder is touched, a complete sequence or a checkpoint is never destroyed unasked,
// and the temporary files of killed writers are cleaned up.
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::bake {
namespace {
namespace fs = std::filesystem;
using testing::scratch_folder;
using testing::small_flume_case;
using testing::write_text;

// Every file of the folder, name -> bytes.
std::map<std::string, std::string> folder_contents(const fs::path& folder) {
  std::map<std::string, std::string> contents;
  for (const auto& item : fs::directory_iterator(folder)) {
    std::ifstream in(item.path(), std::ios::binary);
    contents[item.path().filename().string()] = {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  return contents;
}

// The message of the nearshore::Error run_bake throws, or "" when it does not.
std::string bake_error(const BakeCase& bake_case, const BakeOptions& options) {
  try {
    run_bake(bake_case, options);
  } catch (const Error& error) {
    return error.what();
  }
  return {};
}

class BakeSafety : public ::testing::Test {
 protected:
  void SetUp() override {
    ProgressBar::set_quiet(true);
    folder_ = scratch_folder();
    bake_case_ = read_bake_case(write_text(folder_ / "case.toml", small_flume_case(8.0, 2.0)));
    options_.output_folder = folder_ / "out";
  }
  fs::path folder_;
  BakeCase bake_case_;
  BakeOptions options_;
};

TEST_F(BakeSafety, ACaseThatCannotFinishLeavesAGoodSequenceByteForByte) {
  run_bake(bake_case_, options_);
  const auto before = folder_contents(options_.output_folder);
  ASSERT_TRUE(before.count("manifest.json"));
  // duration_s = 1e20 once overflowed the step count, emptied the folder and failed at finish().
  BakeCase endless = bake_case_;
  endless.timing.duration_s = 1e20;
  for (const bool overwrite : {false, true}) {
    BakeOptions options = options_;
    options.overwrite = overwrite;  // even allowed to replace it, a bake that cannot run leaves it be
    const std::string message = bake_error(endless, options);
    EXPECT_NE(message.find("case.toml: key `time.duration_s` = 1e+20 s is"), std::string::npos) << message;
    EXPECT_NE(message.find("more than a bake can count"), std::string::npos) << message;
    EXPECT_EQ(folder_contents(options_.output_folder), before);
  }
  // A plan with more frames than a sequence can number is refused the same way.
  BakeCase too_many_frames = bake_case_;
  too_many_frames.timing.duration_s = 1e8;
  too_many_frames.timing.output_interval_s = bake_case_.solver.time_step_s;
  EXPECT_NE(bake_error(too_many_frames, options_).find("more than a sequence can number"), std::string::npos);
  EXPECT_EQ(folder_contents(options_.output_folder), before);
  sequence::SequenceReader(options_.output_folder).verify_checksums();
}

TEST_F(BakeSafety, ACompleteSequenceIsReplacedOnlyWithOverwrite) {
  run_bake(bake_case_, options_);
  const auto before = folder_contents(options_.output_folder);
  const std::string message = bake_error(bake_case_, options_);
  EXPECT_NE(message.find(options_.output_folder.string() + ": holds a complete sequence (manifest.json)"), std::string::npos)
      << message;
  EXPECT_NE(message.find("BakeOptions::overwrite"), std::string::npos) << message;
  EXPECT_EQ(folder_contents(options_.output_folder), before);
  options_.overwrite = true;
  EXPECT_EQ(run_bake(bake_case_, options_).frames, 13);
  EXPECT_EQ(folder_contents(options_.output_folder), before);  // the same case bakes the same bytes
}

TEST_F(BakeSafety, ACheckpointIsNotDeletedWhenResumeIsForgotten) {
  // A checkpoint with frames before it, as a killed bake leaves them (bake_run_test kills for real).
  run_bake(bake_case_, options_);
  write_text(checkpoint_path(options_.output_folder), "a checkpoint");
  fs::remove(options_.output_folder / "manifest.json");
  const auto before = folder_contents(options_.output_folder);
  const std::string message = bake_error(bake_case_, options_);
  EXPECT_NE(message.find("holds checkpoint.bin, the checkpoint of an unfinished bake"), std::string::npos) << message;
  EXPECT_NE(message.find("set BakeOptions::resume to continue that bake, or BakeOptions::overwrite"), std::string::npos)
      << message;
  EXPECT_EQ(folder_contents(options_.output_folder), before);
  // A resume that cannot use the checkpoint stops before it removes anything either.
  options_.resume = true;
  EXPECT_NE(bake_error(bake_case_, options_).find("is not a nearshore bake checkpoint"), std::string::npos);
  EXPECT_EQ(folder_contents(options_.output_folder), before);
  options_.resume = false;
  options_.overwrite = true;
  EXPECT_EQ(run_bake(bake_case_, options_).frames, 13);
  EXPECT_FALSE(fs::exists(checkpoint_path(options_.output_folder)));
}

TEST_F(BakeSafety, TemporaryFilesOfKilledWritersAreRemovedAndOthersKept) {
  fs::create_directories(options_.output_folder / "deep_water_tiles");
  for (const fs::path& file : {options_.output_folder / "frame_000004.exr.tmp-99999", options_.output_folder / "checkpoint.bin.tmp-1",
                               options_.output_folder / "deep_water_tiles" / "frame_000000.exr.tmp-7",
                               options_.output_folder / "my notes.txt"})
    write_text(file, "left by a killed writer");
  run_bake(bake_case_, options_);
  EXPECT_FALSE(fs::exists(options_.output_folder / "frame_000004.exr.tmp-99999"));
  EXPECT_FALSE(fs::exists(options_.output_folder / "checkpoint.bin.tmp-1"));
  EXPECT_FALSE(fs::exists(options_.output_folder / "deep_water_tiles" / "frame_000000.exr.tmp-7"));
  EXPECT_TRUE(fs::exists(options_.output_folder / "my notes.txt"));
}

TEST_F(BakeSafety, TheLockFileLeavesTheSequenceValid) {
  run_bake(bake_case_, options_);
  EXPECT_TRUE(fs::exists(options_.output_folder / ".nearshore.lock"));
  const sequence::SequenceReader reader(options_.output_folder);
  reader.verify_checksums();
  EXPECT_EQ(reader.frame_count(), 13);
}

}  // namespace
}  // namespace nearshore::bake
