// The writing rules every command follows (issue 44): a stream writer's failed write is never
// renamed into place and says why (OpenVDB's io::File ignored its stream: a full disk left
// truncated .vdb files), and an output folder is checked before anything is written into it: never
// the folder an input comes from, never another command's outputs unless allowed.
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "core_test_folders.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/atomic_stream.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/output_folder.hpp"

namespace {
namespace fs = std::filesystem;
using nearshore::core_testing::fresh_core_folder;

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(AtomicStream, WritesSeeksBackAndRenamesWhenComplete) {
  const fs::path folder = fresh_core_folder("atomic_stream");
  // As OpenVDB writes an archive: a placeholder, the data, then back to fill in the offset.
  nearshore::write_stream_atomically(folder / "out.bin", [](std::ostream& out) {
    out << "offset:????|";
    const std::string large(200000, 'x');  // past the stream's buffer
    out.write(large.data(), static_cast<std::streamsize>(large.size()));
    const std::streampos end = out.tellp();
    out.seekp(7);
    out << "0012";
    out.seekp(end);
    out << "|end";
  });
  const std::string written = bytes_of(folder / "out.bin");
  EXPECT_EQ(written.size(), 12u + 200000u + 4u);
  EXPECT_EQ(written.substr(0, 12), "offset:0012|");
  EXPECT_EQ(written.substr(written.size() - 4), "|end");
  EXPECT_EQ(nearshore::remove_stale_temporary_files(folder), 0);
}

// A write that fails part-way (here the file-size limit, EFBIG, as a full disk gives ENOSPC) while
// the writer carries on as OpenVDB does: nothing is renamed, the old file stays, and the message
// names the file and the reason. In a child process: the limit and its signal are per process.
TEST(AtomicStream, AFailedWriteIsNeverRenamedIntoPlaceAndSaysWhy) {
  const fs::path folder = fresh_core_folder("atomic_stream_failure");
  const fs::path file = folder / "grid.vdb", report = folder / "report.txt";
  nearshore::write_text_atomically(file, "the complete old file");
  const pid_t child = fork();
  if (child == 0) {
    signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{100000, 100000};
    setrlimit(RLIMIT_FSIZE, &limit);
    std::string message = "no error";
    try {
      nearshore::write_stream_atomically(
          file, [](std::ostream& out) {
            const std::string block(65536, 'v');
            for (int i = 0; i < 8; ++i) out.write(block.data(), static_cast<std::streamsize>(block.size()));
          },
          "the VDB");
    } catch (const nearshore::Error& error) {
      message = error.what();
    }
    std::ofstream(report) << message;
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  const std::string message = bytes_of(report);
  EXPECT_NE(message.find(file.string() + ": writing the VDB failed after"), std::string::npos) << message;
  EXPECT_NE(message.find("File too large"), std::string::npos) << message;
  EXPECT_NE(message.find("nothing was replaced"), std::string::npos) << message;
  EXPECT_EQ(bytes_of(file), "the complete old file");
  EXPECT_EQ(nearshore::remove_stale_temporary_files(folder), 0);  // the temporary file went with the error
}

TEST(OutputFolder, KnowsWhichCommandsOutputsAFolderHolds) {
  const fs::path folder = fresh_core_folder("output_kinds");
  using nearshore::OutputKind;
  EXPECT_EQ(nearshore::output_kind_of_folder(folder / "missing"), OutputKind::kNone);
  EXPECT_EQ(nearshore::output_kind_of_folder(folder), OutputKind::kNone);
  const auto make = [&](const std::string& name, std::initializer_list<const char*> files) {
    fs::create_directories(folder / name);
    for (const char* file : files) std::ofstream(folder / name / file) << "x";
    return folder / name;
  };
  std::string marker;
  EXPECT_EQ(nearshore::output_kind_of_folder(make("sequence", {"manifest.json", "depth.exr"}), &marker), OutputKind::kSequence);
  EXPECT_EQ(marker, "manifest.json");
  EXPECT_EQ(nearshore::output_kind_of_folder(make("unfinished", {"checkpoint.bin", "depth.exr"})), OutputKind::kSequence);
  EXPECT_EQ(nearshore::output_kind_of_folder(make("harbour", {"depth.exr", "summary.json", "depth.tif"})), OutputKind::kHarbourGrid);
  EXPECT_EQ(nearshore::output_kind_of_folder(make("library", {"library.json"})), OutputKind::kLibrary);
  EXPECT_EQ(nearshore::output_kind_of_folder(make("export", {"sequence.nc", "wave_statistics.tif"})), OutputKind::kNone);
}

std::string refusal(const fs::path& output, nearshore::OutputKind own, bool overwrite,
                    const std::vector<nearshore::InputFolder>& inputs) {
  try {
    nearshore::check_output_folder(output, own, overwrite, inputs, "Request::output_folder", overwrite ? "" : "Request::overwrite");
  } catch (const nearshore::Error& error) {
    return error.what();
  }
  return "";
}

TEST(OutputFolder, RefusesAnInputsFolderAlwaysAndAnotherCommandsOutputsUnlessAllowed) {
  const fs::path folder = fresh_core_folder("output_rules");
  using nearshore::OutputKind;
  fs::create_directories(folder / "sequence");
  std::ofstream(folder / "sequence" / "manifest.json") << "{}";
  // The input's own folder, however it is spelled, overwrite or not.
  const std::vector<nearshore::InputFolder> input = {{folder / "sequence", "the sequence being exported"}};
  for (const bool overwrite : {false, true}) {
    const std::string message = refusal(folder / "sequence" / "." / "", OutputKind::kNone, overwrite, input);
    EXPECT_NE(message.find("is the folder the sequence being exported comes from"), std::string::npos) << message;
    EXPECT_NE(message.find("choose another Request::output_folder"), std::string::npos) << message;
  }
  // Another command's outputs: refused unless allowed; a folder of its own kind is its own.
  EXPECT_NE(refusal(folder / "sequence", OutputKind::kHarbourGrid, false, {})
                .find("holds a baked sequence (written by nearshore bake) (manifest.json)"),
            std::string::npos);
  EXPECT_NE(refusal(folder / "sequence", OutputKind::kHarbourGrid, false, {}).find("or set Request::overwrite"), std::string::npos);
  EXPECT_EQ(refusal(folder / "sequence", OutputKind::kHarbourGrid, true, {}), "");
  EXPECT_EQ(refusal(folder / "sequence", OutputKind::kSequence, false, {}), "");
  EXPECT_EQ(refusal(folder / "new", OutputKind::kNone, false, input), "");
}

}  // namespace
