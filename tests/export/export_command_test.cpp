// `nearshore export` run as a user runs it (a child process) on the test sequence: --help with the
// example and the page, --json listing what it wrote, and bad frames named by their flag.
#include <sys/wait.h>

#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "export_test_support.hpp"

namespace nearshore::exports {
namespace {
using testing::TestWave;
namespace fs = std::filesystem;

struct CommandResult {
  int status = -1;
  std::string output;  // stdout, and stderr after it when `with_stderr`
};

CommandResult run(const std::string& arguments, bool with_stderr = true) {
  const std::string command = std::string(NEARSHORE_EXECUTABLE) + " " + arguments + (with_stderr ? " 2>&1" : " 2>/dev/null");
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) result.output.append(buffer, n);
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

TEST(ExportCommand, HelpShowsTheFormatsTheExampleAndThePage) {
  const CommandResult help = run("export --help");
  EXPECT_EQ(help.status, 0) << help.output;
  for (const char* expected : {"--to", "netcdf", "exr-displacement", "--frames", "--json", "Example",
                               "nearshore export", "docs/commands/export.md"})
    EXPECT_NE(help.output.find(expected), std::string::npos) << expected << "\n" << help.output;
  EXPECT_TRUE(fs::exists(fs::path(NEARSHORE_SOURCE_DIR) / "docs" / "commands" / "export.md"));
}

TEST(ExportCommand, JsonListsTheFilesWrittenWithTheirSizes) {
  const fs::path folder = testing::scratch_folder();
  const fs::path sequence = TestWave::write(folder / "sequence");
  const CommandResult exported =
      run("export " + sequence.string() + " --to vdb --frames 10:13 -o " + (folder / "vdb").string() + " --json", false);
  ASSERT_EQ(exported.status, 0) << exported.output;
  const nlohmann::json summary = nlohmann::json::parse(exported.output);
  EXPECT_EQ(summary["format"], "vdb");
  EXPECT_EQ(summary["frames"]["first"], 10);
  EXPECT_EQ(summary["frames"]["count"], 3);
  ASSERT_EQ(summary["files"].size(), 3u);
  for (const auto& file : summary["files"])
    EXPECT_EQ(file["bytes"].get<std::uintmax_t>(), fs::file_size(file["file"].get<std::string>())) << file;
  EXPECT_EQ(summary["files"][2]["file"], (folder / "vdb" / "surface_000012.vdb").string());
}

TEST(ExportCommand, TextSummaryNamesTheFilesAndTheDisplacement) {
  const fs::path folder = testing::scratch_folder();
  const fs::path sequence = TestWave::write(folder / "sequence");
  const CommandResult exported =
      run("export " + sequence.string() + " --to exr-displacement --frames :4 -o " + (folder / "exr").string(), false);
  ASSERT_EQ(exported.status, 0) << exported.output;
  EXPECT_NE(exported.output.find("exported frames 0 .. 3"), std::string::npos) << exported.output;
  EXPECT_NE(exported.output.find("displacement_000003.exr"), std::string::npos) << exported.output;
  EXPECT_NE(exported.output.find("horizontal displacement: depth-averaged"), std::string::npos) << exported.output;
}

TEST(ExportCommand, BadFramesEndInOneMessageNamingTheFlag) {
  const fs::path folder = testing::scratch_folder();
  const fs::path sequence = TestWave::write(folder / "sequence");
  const std::string out = " -o " + (folder / "out").string();
  const CommandResult malformed = run("export " + sequence.string() + " --to geotiff --frames 3:x" + out);
  EXPECT_EQ(malformed.status, 105) << malformed.output;  // CLI11's status for a value that fails a check
  EXPECT_NE(malformed.output.find("--frames"), std::string::npos) << malformed.output;
  const CommandResult outside = run("export " + sequence.string() + " --to geotiff --frames 50:61" + out);
  EXPECT_EQ(outside.status, 1) << outside.output;
  EXPECT_NE(outside.output.find("ExportRequest::frames (--frames)"), std::string::npos) << outside.output;
  const CommandResult format = run("export " + sequence.string() + " --to hdf5" + out);
  EXPECT_NE(format.status, 0);
  EXPECT_NE(format.output.find("--to"), std::string::npos) << format.output;
  EXPECT_FALSE(fs::exists(folder / "out"));
}

}  // namespace
}  // namespace nearshore::exports
