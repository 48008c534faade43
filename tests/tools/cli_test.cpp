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

#include "nearshore/core/progress.hpp"
#include "nearshore/loops/synthetic_sea.hpp"

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

// A small finished sequence (24 x 16 cells) for the commands to run on: a sea of three harmonics of
// `sea_period_s`, baked every `frame_interval_s`, whose manifest claims `loop_period_s` (0: none).
// Milliseconds to write.
fs::path small_sequence(const std::string& name, double sea_period_s, double loop_period_s, int frames,
                        double frame_interval_s) {
  nearshore::ProgressBar::set_quiet(true);
  const fs::path folder = scratch(name) / "sequence";
  nearshore::GridGeometry geometry;
  geometry.columns = 24;
  geometry.rows = 16;
  geometry.spacing_m = 5.0;
  nearshore::loops::write_sea_sequence(folder, nearshore::loops::periodic_sea(sea_period_s, 3, 1.5, 8.0, 5), geometry,
                                       frames, frame_interval_s, loop_period_s);
  return folder;
}

const char* const kSubcommands[] = {"bathy", "bake", "loops", "library", "play", "demo", "bench"};

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
  // In range for the command line (a half-width is any count of frames), too wide for this bake:
  // only the library can tell, and it names its parameter; the command adds the flag.
  const fs::path sequence = small_sequence("filter_too_wide", 8.0, 8.0, 90, 0.25);
  const CommandResult loops = run("loops " + sequence.string() + " --no-write --filter-width 44");
  EXPECT_EQ(loops.status, 1) << loops.output;
  EXPECT_NE(loops.output.find("TransitionOptions::filter_half_width (--filter-width)"), std::string::npos)
      << loops.output;
  EXPECT_FALSE(fs::exists(sequence / "loops.json"));
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

// Issue 13, item 3: every number on every command line has a range, checked before any work. Before,
// `loops --lengths-s -0.5` on a sequence of 0.5 s frames crashed (a plan indexed at length -1),
// and the rest were accepted: NaN seams, a discount of 2, no candidates. Now each ends in one line
// naming the flag and the allowed range, with CLI11's status for a value that fails a check (105,
// docs/commands/*.md).
TEST(Cli, EveryNumberOnTheCommandLineIsRangeCheckedBeforeAnyWork) {
  const fs::path sequence = small_sequence("out_of_range", 8.0, 8.0, 40, 0.5);
  const std::string seq = sequence.string(), out = (sequence.parent_path() / "out").string();
  const struct {
    std::string arguments, flag, allowed;
  } cases[] = {
      {"loops " + seq + " --lengths-s -1", "--lengths-s", "> 0"},
      {"loops " + seq + " --lengths-s 10,-0.5", "--lengths-s", "> 0"},
      {"loops " + seq + " --delta -1", "--delta", ">= 0"},
      {"loops " + seq + " --candidates 0", "--candidates", "[1, 1000]"},
      {"loops " + seq + " --alpha 2", "--alpha", "[0, 1)"},
      {"loops " + seq + " --min-probability 2", "--min-probability", "[0, 1)"},
      {"loops " + seq + " --loop-s -5", "--loop-s", "> 0"},
      {"loops " + seq + " --max-seam nan", "--max-seam", ">= 0"},
      {"loops " + seq + " --sigma inf", "--sigma", ">= 0"},
      {"loops " + seq + " --threads 0", "--threads", "[1, 1024]"},
      {"loops " + seq + " --max-crossfade-s -1", "--max-crossfade-s", ">= 0"},
      {"play " + seq + " --time nan", "--time", "[0, 1e+09]"},
      {"play " + seq + " --eye 1,2,nan", "--eye", "any finite number"},
      {"play " + seq + " --sun-elevation 91", "--sun-elevation", "[-90, 90]"},
      {"play " + seq + " --beaufort 13", "--beaufort", "[0, 12]"},
      {"play " + seq + " --size 8,100", "--size", "[16, 8192]"},
      {"play " + seq + " --crossfade -1", "--crossfade", "[0, 3600]"},
      {"bathy " + seq + "/soundings.xyz --spacing 0 -o " + out, "--spacing", "(0, 100000]"},
      {"bathy " + seq + "/soundings.xyz --spacing 10 --structure quay=10:nan -o " + out, "--structure",
       "porosity must be in [0, 1]"},
      {"bathy " + seq + "/soundings.xyz --spacing 10 --bbox 1,2,nan,4 -o " + out, "--bbox", "not finite"},
      {"demo -o " + out + " --spacing 0", "--spacing", "[2, 50]"},
      {"bench bathy --grid 1", "--grid", "[2, 100000]"},
      {"bench bake --steps 0", "--steps", "[1, 1e+06]"},
      {"bench play --seconds 0", "--seconds", "[1, 36000]"},
      {"bench ships --points 0", "--points", "["},
      {"bench deepwater --beaufort 13", "--beaufort", "[1, 12]"},
      {"bench loops --distance-frames 1", "--distance-frames", "[2, 100000]"},
  };
  for (const auto& c : cases) {
    const CommandResult result = run(c.arguments);
    EXPECT_EQ(result.status, 105) << c.arguments << "\n" << result.output;
    EXPECT_EQ(result.output.rfind(c.flag + ": ", 0), 0u) << c.arguments << "\n" << result.output;
    EXPECT_NE(result.output.find(c.allowed), std::string::npos) << c.arguments << "\n" << result.output;
  }
  EXPECT_FALSE(fs::exists(sequence / "loops.json"));  // nothing ran
  EXPECT_FALSE(fs::exists(out));
}

// The same crash through the library: a length in range for the command line but shorter than one
// frame of this sequence is refused by nearshore::loops::analyse_loops (LoopsOptions), which names
// its field; the command adds the flag. Exit 1, nothing written.
TEST(Cli, LoopLengthShorterThanOneFrameIsRefusedByTheLibrary) {
  const fs::path sequence = small_sequence("sub_frame_length", 8.0, 8.0, 40, 0.5);
  const CommandResult loops = run("loops " + sequence.string() + " --lengths-s 10,0.2");
  EXPECT_EQ(loops.status, 1) << loops.output;
  EXPECT_NE(loops.output.find("error: LoopsOptions::report_lengths_s (--lengths-s) holds 0.2 s"), std::string::npos)
      << loops.output;
  EXPECT_FALSE(fs::exists(sequence / "loops.json"));
}

// Issue 13, item 7: a quality gate with nothing to judge fails (it passed with exit 0).
TEST(Cli, MaxSeamFailsWhenThereIsNoLoopToJudge) {
  // Not periodic by its manifest, and no loop in the only bucket asked for (longer than the bake).
  const fs::path irregular = small_sequence("no_loop", 8.0, 0.0, 40, 0.5);
  const CommandResult none = run("loops " + irregular.string() + " --no-write --lengths-s 100 --max-seam 1");
  EXPECT_EQ(none.status, 2) << none.output;
  EXPECT_NE(none.output.find("--max-seam 1 fails: no loop was planned"), std::string::npos) << none.output;
  // A --loop-s loop that cannot be made: the gate was asked about that one.
  const fs::path periodic = small_sequence("no_requested_loop", 8.0, 8.0, 40, 0.5);
  const CommandResult missing = run("loops " + periodic.string() + " --no-write --loop-s 1000 --max-seam 1");
  EXPECT_EQ(missing.status, 2) << missing.output;
  EXPECT_NE(missing.output.find("no loop of exactly 1000 s (--loop-s) can be made"), std::string::npos)
      << missing.output;
  // With a loop to judge the gate still passes: the exact period of this sea has a seam of ~0.
  const CommandResult judged = run("loops " + periodic.string() + " --no-write --max-seam 1");
  EXPECT_EQ(judged.status, 0) << judged.output;
}

// Issue 13, item 9: paths that are not there end with exit 1 and the path (as the docs promise),
// not CLI11's 105 for a failed ExistingFile/ExistingDirectory check.
TEST(Cli, MissingPathsExitOneNamingThePath) {
  const fs::path folder = scratch("missing_paths");
  for (const std::string& arguments :
       {std::string("loops /nonexistent/bake"), std::string("play /nonexistent/bake --screenshot x.png"),
        std::string("bake /nonexistent/harbour.toml -o ") + (folder / "out").string(),
        std::string("bathy /nonexistent/soundings.xyz --spacing 10 -o ") + (folder / "out").string()}) {
    const CommandResult result = run(arguments);
    EXPECT_EQ(result.status, 1) << arguments << "\n" << result.output;
    EXPECT_NE(result.output.find("error: /nonexistent/"), std::string::npos) << arguments << "\n" << result.output;
    EXPECT_NE(result.output.find("does not exist"), std::string::npos) << arguments << "\n" << result.output;
  }
  EXPECT_FALSE(fs::exists(folder / "out"));
}

// Issue 13, item 9: a manifest.json that is a folder gave "std::bad_alloc".
TEST(Cli, ManifestThatIsAFolderIsNamedAsOne) {
  const fs::path sequence = small_sequence("manifest_folder", 8.0, 8.0, 40, 0.5);
  fs::remove(sequence / "manifest.json");
  fs::create_directory(sequence / "manifest.json");
  for (const std::string& arguments : {"loops " + sequence.string(), "play " + sequence.string() + " --screenshot " +
                                                                          (sequence.parent_path() / "x.png").string()}) {
    const CommandResult result = run(arguments);
    EXPECT_EQ(result.status, 1) << arguments << "\n" << result.output;
    EXPECT_NE(result.output.find("manifest.json: is a folder, not the manifest file a bake writes"), std::string::npos)
        << arguments << "\n" << result.output;
    EXPECT_EQ(result.output.find("bad_alloc"), std::string::npos) << arguments << "\n" << result.output;
  }
}

// Issue 13, item 9: a bake whose loop period holds two wave periods has frames that repeat every
// wave period; that divides the manifest's period and agrees with it (it was reported as "NOT the
// manifest's period"). Likewise frames found to repeat after two loop periods (the search starts at
// 10 s, so a 8 s period is found at 16 s).
TEST(Cli, PeriodFoundInTheFramesThatDividesOrIsAMultipleOfTheManifestsAgrees) {
  const fs::path two_waves = small_sequence("two_wave_periods", 12.0, 24.0, 56, 0.5);
  const CommandResult divides = run("loops " + two_waves.string() + " --no-write --lengths-s 12");
  EXPECT_EQ(divides.status, 0) << divides.output;
  // The search may pick either lag of this sea (12 s or 24 s); this sequence's best is 12 s.
  ASSERT_NE(divides.output.find("period found in the frames: 12.0 s"), std::string::npos) << divides.output;
  EXPECT_NE(divides.output.find("the frames repeat every 12 s, which divides the manifest's 24 s loop period"),
            std::string::npos)
      << divides.output;
  EXPECT_EQ(divides.output.find("NOT"), std::string::npos) << divides.output;
  const fs::path short_period = small_sequence("short_period", 8.0, 8.0, 40, 0.5);
  const CommandResult multiple = run("loops " + short_period.string() + " --no-write --lengths-s 8");
  EXPECT_EQ(multiple.status, 0) << multiple.output;
  ASSERT_NE(multiple.output.find("period found in the frames: 16.0 s"), std::string::npos) << multiple.output;
  EXPECT_NE(multiple.output.find("2 of the manifest's 8 s loop periods"), std::string::npos) << multiple.output;
  EXPECT_EQ(multiple.output.find("NOT"), std::string::npos) << multiple.output;
}

}  // namespace
