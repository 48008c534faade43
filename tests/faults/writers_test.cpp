// Every writer of every format on a full disk, for real (issue 44): a small tmpfs filled but for
// about half of what each output needs. OpenVDB's io::File never looked at its stream, so a full
// disk left empty or truncated .vdb files renamed into place with exit status 0; HDF5 segfaulted
// at exit after a failed NetCDF write. Each writer must now stop with an error naming the file and
// saying the disk is full, and every file it leaves under its final name must be complete (the
// same size as the same output written on a roomy disk: VDB files differ only in their UUID).
#include <sys/wait.h>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <gtest/gtest.h>

#include "bake_test_support.hpp"
#include "fault_support.hpp"

namespace nearshore::faults {
namespace {

// name -> size of every regular file in `folder` (none for a missing folder).
std::map<std::string, std::uintmax_t> file_sizes_in(const fs::path& folder) {
  std::map<std::string, std::uintmax_t> sizes;
  std::error_code ec;
  for (const auto& item : fs::directory_iterator(folder, ec))
    if (item.is_regular_file()) sizes[item.path().filename().string()] = item.file_size();
  return sizes;
}

// "name size" lines as the script below writes them.
std::map<std::string, std::uintmax_t> parse_sizes(const std::string& text) {
  std::map<std::string, std::uintmax_t> sizes;
  std::istringstream lines(text);
  std::string name;
  std::uintmax_t size = 0;
  while (lines >> name >> size) sizes[name] = size;
  return sizes;
}

std::uintmax_t pages_of(std::uintmax_t bytes) { return (bytes + 4095) / 4096 * 4096; }

// Soundings (lon lat depth) over about 1.1 x 1.1 km that shoal from 20 m in the west to land in
// the east: a harbour grid with a coastline, so coastline.vdb has a band of voxels to write.
std::string sloping_soundings() {
  std::string text = "lon lat depth\n";
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j)
      text += fmt::format("{:.5f} {:.5f} {:.2f}\n", -122.43 + 0.0015 * i, 47.27 + 0.001 * j, 20.0 - 3.0 * i);
  return text;
}

TEST(FullDisk, EveryWriterStopsNamingTheFileAndLeavesNothingTruncated) {
  const fs::path folder = scratch_folder();
  const fs::path sequence = folder / "sequence";
  const fs::path case_file = bake::testing::write_text(folder / "case.toml", bake::testing::small_flume_case(8.0, 0.0));
  ASSERT_TRUE(exited_with(wait_for(start_runner({"bake", case_file.string(), sequence.string()})), 0));
  const fs::path soundings = bake::testing::write_text(folder / "soundings.xyz", sloping_soundings());

  // What each writer writes on a roomy disk.
  struct Writer {
    std::string name;                    // the output folder's name on the full disk
    std::vector<std::string> arguments;  // fault_runner's, with OUT for the output
    std::string failing_file;            // the file the message must name
  };
  const std::vector<Writer> writers = {
      {"vdb", {"export", sequence.string(), "vdb", "OUT"}, ".vdb"},
      {"netcdf", {"export", sequence.string(), "netcdf", "OUT"}, "sequence.nc"},
      {"geotiff", {"export", sequence.string(), "geotiff", "OUT"}, "wave_statistics"},
      {"exr", {"export", sequence.string(), "exr-displacement", "OUT"}, ".exr"},
      {"stack", {"loops-vdb", sequence.string(), "OUT/stack.vdb"}, "stack.vdb"},
      {"harbour", {"bathy", "OUT", soundings.string(), "spacing=5"}, "coastline.vdb"},
  };
  const auto with_output = [](std::vector<std::string> arguments, const fs::path& output) {
    for (std::string& argument : arguments)
      if (const auto at = argument.find("OUT"); at == 0) argument = output.string() + argument.substr(3);
    return arguments;
  };
  std::string script = R"SH(
    set -u
    run_full() {  # NAME FREE_BYTES ARGUMENTS...: run fault_runner with FREE_BYTES of room
      name=$1; free=$2; shift 2
      mkdir -p "$D/$name"
      # Fill the disk (appending: a file extended by truncate is a hole and takes no room), then
      # give back FREE_BYTES.
      cat /dev/zero >> "$D/filler" 2> /dev/null
      FULL=$(stat -c %s "$D/filler")
      truncate -s $((FULL - free)) "$D/filler"
      "$RUNNER" "$@" 2> "$S/$name.txt"; echo $? > "$S/$name.rc"
      for f in "$D/$name"/*; do [ -f "$f" ] && echo "$(basename "$f") $(stat -c %s "$f")"; done > "$S/$name.sizes"
      rm -rf "$D/$name"
    }
  )SH";
  for (const Writer& writer : writers) {
    const fs::path reference = folder / ("reference_" + writer.name);
    fs::create_directories(reference);
    const fs::path log = folder / ("reference_" + writer.name + ".txt");
    ASSERT_TRUE(exited_with(wait_for(start_runner(with_output(writer.arguments, reference), {}, log)), 0)) << file_bytes(log);
    // Room for about half of it: what is written first fits, the rest cannot. For the harbour grid,
    // room for depth.tif and depth.exr and half of coastline.vdb (written in that order).
    const auto sizes = file_sizes_in(reference);
    std::uintmax_t room = 0;
    for (const auto& [name, size] : sizes) room += pages_of(size);
    if (writer.name == "harbour") {
      ASSERT_GT(sizes.at("coastline.vdb"), 16384u) << "the level set is too small to be cut in half";
      room = pages_of(sizes.at("depth.tif")) + pages_of(sizes.at("depth.exr")) + pages_of(sizes.at("coastline.vdb") / 2);
    } else {
      room /= 2;
    }
    script += "run_full " + writer.name + " " + std::to_string(room);
    for (const std::string& argument : with_output(writer.arguments, "$D/" + writer.name)) script += " \"" + argument + "\"";
    script += "\n";
  }

  const fs::path disk = folder / "tmpfs";
  const int status = run_on_small_disk(disk, "16m", script, {{"RUNNER", FAULT_RUNNER_PATH}, {"S", folder.string()}},
                                       folder / "skip.txt");
  if (exited_with(status, 77)) GTEST_SKIP() << "no tmpfs to fill: " << file_bytes(folder / "skip.txt");
  ASSERT_TRUE(exited_with(status, 0)) << "the script stopped (status " << status << ")";

  for (const Writer& writer : writers) {
    SCOPED_TRACE(writer.name);
    const std::string message = file_bytes(folder / (writer.name + ".txt"));
    // An error (exit 1, not a crash: HDF5's clean-up at exit segfaulted after a failed write).
    EXPECT_EQ(file_bytes(folder / (writer.name + ".rc")), "1\n") << message;
    EXPECT_NE(message.find(writer.failing_file), std::string::npos) << message;
    // NetCDF is refused before it starts (HDF5 cannot recover from a full disk); the others meet it.
    EXPECT_NE(message.find(writer.name == "netcdf" ? "MB are free in" : "(the disk is full)"), std::string::npos) << message;
    // Whatever is left under a final name is complete; no temporary file remains; it did not finish.
    const auto reference = file_sizes_in(folder / ("reference_" + writer.name));
    const auto left = parse_sizes(file_bytes(folder / (writer.name + ".sizes")));
    for (const auto& [name, size] : left) {
      ASSERT_TRUE(reference.count(name)) << name << " is not an output of a complete run";
      EXPECT_EQ(size, reference.at(name)) << name << " was left truncated";
    }
    EXPECT_LT(left.size(), reference.size()) << "the writer did not meet the full disk";
  }
}

}  // namespace
}  // namespace nearshore::faults
