// What the export refuses, with messages that name the object and the fix, and what it leaves.
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "export_test_support.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/export/export_sequence.hpp"

namespace nearshore::exports {
namespace {
using testing::TestWave;
namespace fs = std::filesystem;

std::string message_of(const ExportRequest& request) {
  try {
    export_sequence(request);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(ExportRequests, FormatNamesRoundTripAndOthersAreRefused) {
  for (ExportFormat format : all_export_formats()) EXPECT_EQ(parse_export_format(export_format_name(format)), format);
  EXPECT_EQ(export_format_name(ExportFormat::kExrDisplacement), "exr-displacement");
  try {
    parse_export_format("hdf5");
    FAIL() << "hdf5 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("netcdf, geotiff, exr-displacement, vdb or agitation"), std::string::npos) << e.what();
  }
}

TEST(ExportRequests, FramesOutsideTheSequenceAreRefusedBeforeAnythingIsWritten) {
  const fs::path folder = testing::scratch_folder();
  TestWave::write(folder / "sequence");
  for (const FrameRange frames : {FrameRange{0, 61}, FrameRange{-1, 5}, FrameRange{8, 8}, FrameRange{60, -1}}) {
    const std::string message = message_of({folder / "sequence", folder / "out", ExportFormat::kGeotiff, frames});
    EXPECT_NE(message.find("ExportRequest::frames"), std::string::npos) << message;
    EXPECT_NE(message.find("frames 0 .. 59"), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(folder / "out"));
}

TEST(ExportRequests, AnUnfinishedSequenceIsRefused) {
  const fs::path folder = testing::scratch_folder();
  TestWave::write(folder / "sequence");
  fs::remove(folder / "sequence" / "manifest.json");
  const std::string message = message_of({folder / "sequence", folder / "out", ExportFormat::kNetcdf, {}});
  EXPECT_NE(message.find("manifest.json"), std::string::npos) << message;
}

// The export never writes into the sequence it reads (issue 44: `export SEQ --to geotiff -o SEQ`
// replaced the bake's own wave_statistics.tif, statistics of every solver step that no frame can
// rebuild), nor into another command's outputs (a harbour grid, a library, another sequence).
TEST(ExportRequests, NeverWritesIntoTheSequenceItReadsNorAnotherCommandsOutputs) {
  const fs::path folder = testing::scratch_folder();
  TestWave::write(folder / "sequence");
  write_text_atomically(folder / "sequence" / "wave_statistics.tif", "the bake's statistics of every solver step");
  for (const ExportFormat format : all_export_formats()) {
    const std::string message = message_of({folder / "sequence", folder / "sequence", format, {}});
    EXPECT_NE(message.find("is the folder the sequence being exported (ExportRequest::sequence_folder) comes from"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("choose another ExportRequest::output_folder"), std::string::npos) << message;
  }
  std::ifstream kept(folder / "sequence" / "wave_statistics.tif");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "the bake's statistics of every solver step");
  TestWave::write(folder / "other");
  const std::string message = message_of({folder / "sequence", folder / "other", ExportFormat::kGeotiff, {}});
  EXPECT_NE(message.find("holds a baked sequence (written by nearshore bake) (manifest.json)"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(folder / "other" / "wave_statistics.tif"));
}

// Files are written under temporary names and renamed: what an interrupted export left behind
// (a temporary of a killed run) is removed, and a finished export holds only whole files.
TEST(ExportRequests, LeavesOnlyWholeFilesAndCleansAKilledRunsTemporaries) {
  const fs::path folder = testing::scratch_folder();
  TestWave::write(folder / "sequence");
  fs::create_directories(folder / "out");
  const fs::path stale = folder / "out" / "sequence.nc.tmp-999999";
  ASSERT_TRUE(is_temporary_file_name(stale.filename().string()));
  write_text_atomically(stale, "half a file");
  const ExportSummary summary = export_sequence({folder / "sequence", folder / "out", ExportFormat::kVdb, {0, 3}});
  EXPECT_FALSE(fs::exists(stale));
  int files = 0;
  for (const auto& item : fs::directory_iterator(folder / "out")) {
    const std::string name = item.path().filename().string();
    EXPECT_FALSE(is_temporary_file_name(name)) << name;
    files += name != ".nearshore.lock";
  }
  EXPECT_EQ(files, 3);
  const nlohmann::json json = summary.to_json();
  EXPECT_EQ(json["format"], "vdb");
  EXPECT_EQ(json["files"].size(), 3u);
  EXPECT_EQ(json["files"][0]["file"], (folder / "out" / "surface_000000.vdb").string());
  EXPECT_EQ(json["total_bytes"], summary.total_bytes());
}

}  // namespace
}  // namespace nearshore::exports
