// The `nearshore` executable run as a user runs it (a child process): every subcommand has --help
// with an example and a docs page; bad input gives one message naming the file and the fix, and a
// non-zero exit status, never a crash or a stack of exceptions.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {
namespace fs = std::filesystem;

struct CommandResult {
  int status = -1;
  std::string output;  // stdout and stderr together
};

CommandResult run(const std::string& arguments) {
  CommandResult result;
  const std::string command = std::string("\"") + NEARSHORE_EXECUTABLE + "\" " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe)) result.output += buffer.data();
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

fs::path scratch(const std::string& name) {
  const fs::path folder = fs::path(NEARSHORE_BINARY_DIR) / "test-output" / "cli" / name;
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

const char* const kSubcommands[] = {"bathy", "bake", "loops", "play", "demo", "bench"};

TEST(Cli, TopLevelHelpListsEverySubcommand) {
  const CommandResult help = run("--help");
  EXPECT_EQ(help.status, 0) << help.output;
  for (const char* name : kSubcommands) EXPECT_NE(help.output.find(name), std::string::npos) << name;
}

TEST(Cli, EverySubcommandHelpShowsARunnableExampleAndItsDocsPage) {
  for (const char* name : kSubcommands) {
    const CommandResult help = run(std::string(name) + " --help");
    EXPECT_EQ(help.status, 0) << name << ": " << help.output;
    EXPECT_NE(help.output.find("Example"), std::string::npos) << name << ": " << help.output;
    EXPECT_NE(help.output.find(std::string("nearshore ") + name), std::string::npos)
        << name << ": " << help.output;
    const std::string page = std::string("docs/commands/") + name + ".md";
    EXPECT_NE(help.output.find(page), std::string::npos) << name << ": " << help.output;
    EXPECT_TRUE(fs::exists(fs::path(NEARSHORE_SOURCE_DIR) / page)) << page;
  }
}

TEST(Cli, MissingCaseFileIsOneClearErrorNamingIt) {
  const CommandResult bake = run("bake /nonexistent/harbour.toml -o " + scratch("missing_case").string());
  EXPECT_NE(bake.status, 0);
  EXPECT_NE(bake.output.find("/nonexistent/harbour.toml"), std::string::npos) << bake.output;
  EXPECT_EQ(bake.output.find("terminate called"), std::string::npos) << bake.output;
}

TEST(Cli, UnfinishedSequenceFolderIsRefusedWithTheFix) {
  const fs::path folder = scratch("unfinished_sequence");
  const CommandResult loops = run("loops " + folder.string());
  EXPECT_EQ(loops.status, 1) << loops.output;
  EXPECT_NE(loops.output.find("manifest.json"), std::string::npos) << loops.output;
  // The library names the bake's parameter; the command line adds the flag that sets it.
  EXPECT_NE(loops.output.find("BakeOptions::resume (nearshore bake --resume)"), std::string::npos) << loops.output;
}

TEST(Cli, LibraryErrorsNameTheParameterAndTheCommandsFlag) {
  const fs::path folder = scratch("zero_spacing");
  const CommandResult bathy = run("bathy " + (folder / "soundings.xyz").string() + " --spacing 0 -o " +
                                  (folder / "out").string());
  EXPECT_EQ(bathy.status, 1) << bathy.output;
  EXPECT_NE(bathy.output.find("error: BathyRequest::spacing_m (--spacing) = 0"), std::string::npos) << bathy.output;
  EXPECT_FALSE(fs::exists(folder / "out"));
}

TEST(Cli, CaseFileSyntaxErrorNamesTheFileAndLine) {
  const fs::path folder = scratch("bad_case");
  std::ofstream(folder / "broken.toml") << "title = \"broken\"\n[time\nduration_s = 10\n";
  const CommandResult bake =
      run("bake " + (folder / "broken.toml").string() + " -o " + (folder / "out").string());
  EXPECT_EQ(bake.status, 1) << bake.output;
  EXPECT_NE(bake.output.find("broken.toml"), std::string::npos) << bake.output;
  EXPECT_NE(bake.output.find("line 2"), std::string::npos) << bake.output;
  EXPECT_FALSE(fs::exists(folder / "out" / "manifest.json"));
}

}  // namespace
