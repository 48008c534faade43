// LIBRARY.toml (library/library_definition.hpp): the sweep's order and ids, the case keys each
// quantity sets for each wave maker, and the refusals of bad library files.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "nearshore/core/error.hpp"
#include "nearshore/bake/bake_case.hpp"
#include "nearshore/library/library_definition.hpp"
#include "nearshore/library/library_run.hpp"
#include "library_test_files.hpp"

namespace nearshore::library {
namespace {
using testing::write_text_file;
namespace fs = std::filesystem;

fs::path scratch() {
  const fs::path folder = fs::path(NEARSHORE_BINARY_DIR) / "tests" / "library" / "scratch" /
                          ::testing::UnitTest::GetInstance()->current_test_info()->name();
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

const char* const kIrregularCase = R"(title = "irregular"
[bathymetry]
kind = "harbour_grid"
file = "harbour/depth.exr"
still_water_level_m = 0.25
[time]
duration_s = 10.0
output_interval_s = 1.0
[wave_maker]
kind = "irregular"
facing = "south"
source_line_m = 100.0
spectrum = "jonswap"
significant_height_m = 1.0
peak_period_s = 10.0
)";

TEST(LibraryDefinition, TheSweepIsEveryCombinationInTheFixedAxisOrder) {
  const fs::path folder = scratch();
  write_text_file(folder / "base.toml", kIrregularCase);
  // Written in another order than the axes': the order is fixed (direction, height, ..., tide).
  const fs::path library = write_text_file(folder / "library.toml",
                                      "title = \"t\"\nbase_case = \"base.toml\"\n[sweep]\ntide_m = [-0.5, 1.5]\n"
                                      "spectrum = [\"jonswap\", \"pierson_moskowitz\"]\ndirection_deg = [90, 105.5]\n");
  const LibraryDefinition definition = read_library_definition(library);
  ASSERT_EQ(definition.axes.size(), 3u);
  EXPECT_EQ(definition.axes[0].quantity, sequence::SeaQuantity::kDirection);
  EXPECT_EQ(definition.axes[1].quantity, sequence::SeaQuantity::kSpectrum);
  EXPECT_EQ(definition.axes[2].quantity, sequence::SeaQuantity::kTide);
  const std::vector<LibraryStateCase> states = expand_library_states(definition);
  ASSERT_EQ(states.size(), 8u);
  EXPECT_EQ(states[0].id, "dir90_jonswap_tide-0.5");
  EXPECT_EQ(states[1].id, "dir90_jonswap_tide+1.5");
  EXPECT_EQ(states[2].id, "dir90_pierson_moskowitz_tide-0.5");
  EXPECT_EQ(states[7].id, "dir105.5_pierson_moskowitz_tide+1.5");
  const nlohmann::json& last = states[7].case_document;
  EXPECT_EQ(last["wave_maker"]["mean_direction_deg"], 105.5);
  EXPECT_EQ(last["wave_maker"]["spectrum"], "pierson_moskowitz");
  EXPECT_DOUBLE_EQ(last["bathymetry"]["still_water_level_m"].get<double>(), 1.75);  // above the base's 0.25 m
  // The harbour grid's path is absolute, so the case reads the same from the library's cases/.
  EXPECT_EQ(last["bathymetry"]["file"], (folder / "harbour" / "depth.exr").string());
  EXPECT_EQ(states[7].conditions.direction_deg, 105.5);
  EXPECT_EQ(states[7].conditions.spectrum, "pierson_moskowitz");
  EXPECT_EQ(states[7].conditions.tide_m, 1.5);
  EXPECT_FALSE(states[7].conditions.height_m.has_value());
}

TEST(LibraryDefinition, NothingSweptIsOneStateTheBaseCase) {
  const fs::path folder = scratch();
  write_text_file(folder / "base.toml", kIrregularCase);
  const LibraryDefinition definition = read_library_definition(write_text_file(folder / "l.toml", "base_case = \"base.toml\"\n"));
  const std::vector<LibraryStateCase> states = expand_library_states(definition);
  ASSERT_EQ(states.size(), 1u);
  EXPECT_EQ(states[0].id, "base");
}

// `library` must be refused with one Error naming the library file and `expected`.
void expect_refused(const std::string& library, const std::string& expected, const std::string& base = kIrregularCase) {
  const fs::path folder = scratch();
  write_text_file(folder / "base.toml", base);
  const fs::path file = write_text_file(folder / "library.toml", library);
  try {
    expand_library_states(read_library_definition(file));
    ADD_FAILURE() << "accepted a library expected to fail with: " << expected;
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << "missing '" << expected << "' in: " << message;
    EXPECT_FALSE(error.fix().empty()) << message;
  }
}

TEST(LibraryDefinition, BadLibraryFilesAreRefusedNamingTheKey) {
  expect_refused("base_case = \"base.toml\"\nsweeps = 1\n", "key `sweeps` is not a key of a library file");
  expect_refused("title = \"no base\"\n", "key `base_case` is missing");
  expect_refused("base_case = \"missing.toml\"\n", "key `base_case` names a case that cannot be read");
  expect_refused("base_case = \"base.toml\"\n[sweep]\ncolour = [1]\n", "key `sweep.colour` is not a quantity");
  expect_refused("base_case = \"base.toml\"\n[sweep]\ntide_m = []\n", "key `sweep.tide_m` is not a list of values");
  expect_refused("base_case = \"base.toml\"\n[sweep]\ntide_m = [0.0, 0.0]\n", "has 0 and 0, the same value");
  expect_refused("base_case = \"base.toml\"\n[sweep]\ndirection_deg = [0.0, 360.0]\n", "the same direction");
  expect_refused("base_case = \"base.toml\"\n[sweep]\nheight_m = [\"big\"]\n", "holds \"big\", not a number");
  expect_refused("base_case = \"base.toml\"\n[sweep]\nspectrum = [1]\n", "not a spectrum's name");
  // The irregular maker has no wind: the deep-water field's wind spectra have.
  expect_refused("base_case = \"base.toml\"\n[sweep]\nwind_speed_m_s = [10, 15]\n",
                 "key `sweep.wind_speed_m_s` has no key to set in the base case");
}

TEST(LibraryDefinition, EachMakerSetsItsOwnKeys) {
  const fs::path folder = scratch();
  std::string regular = kIrregularCase;
  regular.replace(regular.find("kind = \"irregular\""), 18, "kind = \"regular\"");
  write_text_file(folder / "base.toml", regular);
  const std::vector<LibraryStateCase> states = expand_library_states(read_library_definition(write_text_file(
      folder / "l.toml", "base_case = \"base.toml\"\n[sweep]\ndirection_deg = [80]\nheight_m = [0.5]\nperiod_s = [12]\n")));
  ASSERT_EQ(states.size(), 1u);
  EXPECT_EQ(states[0].id, "dir80_h0.5_t12");
  EXPECT_EQ(states[0].case_document["wave_maker"]["direction_deg"], 80);
  EXPECT_EQ(states[0].case_document["wave_maker"]["height_m"], 0.5);
  EXPECT_EQ(states[0].case_document["wave_maker"]["period_s"], 12);

  const std::string deep_water = std::string(kIrregularCase).replace(std::string(kIrregularCase).find("kind = \"irregular\""), 18,
                                                                     "kind = \"deep_water\"") +
                                 "[deep_water]\nspectrum = \"unified\"\nwind_speed_10_m_s = 10.0\n";
  write_text_file(folder / "base.toml", deep_water);
  const std::vector<LibraryStateCase> wind = expand_library_states(read_library_definition(write_text_file(
      folder / "w.toml", "base_case = \"base.toml\"\n[sweep]\nwind_speed_m_s = [10, 20]\nwind_direction_deg = [80]\n")));
  ASSERT_EQ(wind.size(), 2u);
  EXPECT_EQ(wind[1].id, "wind20_winddir80");
  EXPECT_EQ(wind[1].case_document["deep_water"]["wind_speed_10_m_s"], 20);
  EXPECT_EQ(wind[1].case_document["deep_water"]["wind_direction_deg"], 80);
  // A wind sea travels down-wind: its direction and the wind's are one key.
  expect_refused("base_case = \"base.toml\"\n[sweep]\ndirection_deg = [80]\nwind_direction_deg = [80]\n",
                 "which another swept quantity sets too", deep_water);
}

// A sweep of 300 000 states planned silently for over an hour (issue 44): the count is refused at
// once, with the reason and each list's size; a base case nested 150 000 levels deep (it overflowed
// the stack) is refused by the case reader; the library never writes into another command's folder.
TEST(LibraryDefinition, AHugeSweepADeepBaseCaseAndAnotherCommandsFolderAreRefusedAtOnce) {
  const fs::path folder = scratch();
  write_text_file(folder / "base.toml", kIrregularCase);
  std::string heights = "height_m = [", periods = "period_s = [", directions = "direction_deg = [";
  for (int i = 0; i < 100; ++i) {
    heights += (i ? ", " : "") + std::to_string(0.5 + 0.01 * i);
    periods += (i ? ", " : "") + std::to_string(5.0 + 0.1 * i);
  }
  for (int i = 0; i < 30; ++i) directions += (i ? ", " : "") + std::to_string(i);
  const fs::path library = write_text_file(folder / "library.toml", "title = \"t\"\nbase_case = \"base.toml\"\n[sweep]\n" + heights +
                                                                        "]\n" + periods + "]\n" + directions + "]\n");
  const auto start = std::chrono::steady_clock::now();
  try {
    read_library_definition(library);
    ADD_FAILURE() << "300 000 states accepted";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("[sweep] makes 300000 states (30 direction_deg x 100 height_m x 100 period_s)"), std::string::npos)
        << message;
    EXPECT_NE(message.find("more than a library takes (10000)"), std::string::npos) << message;
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);

  const int levels = 150000;
  write_text_file(folder / "deep.json", "{\"title\": " + std::string(levels, '[') + std::string(levels, ']') + "}");
  const fs::path deep = write_text_file(folder / "deep_library.toml", "title = \"t\"\nbase_case = \"deep.json\"\n");
  try {
    read_library_definition(deep);
    ADD_FAILURE() << "a base case 150 000 levels deep was read";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("levels deep"), std::string::npos) << std::string(error.what()).substr(0, 300);
  }

  const fs::path sequence = folder / "sequence";
  fs::create_directories(sequence);
  write_text_file(sequence / "manifest.json", "{}");
  LibraryOptions options;
  options.output_folder = sequence;
  const fs::path small = write_text_file(folder / "small.toml", "title = \"t\"\nbase_case = \"base.toml\"\n");
  try {
    run_library(small, options);
    ADD_FAILURE() << "a library was written into a sequence's folder";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("holds a baked sequence"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("LibraryOptions::overwrite"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(sequence / "library.json"));
}

}  // namespace
}  // namespace nearshore::library

namespace nearshore::library {
namespace {

// The tide a library sweeps is the case key bathymetry.still_water_level_m: every depth (land
// included) gains the level exactly, and land lower than the level floods (the wet/dry line moves).
TEST(LibraryTide, TheStillWaterLevelRaisesEveryDepthAndMovesTheWetDryLine) {
  const fs::path folder = scratch();
  const std::string flume =
      "[bathymetry]\nkind = \"profile\"\nlength_m = 12.0\nwidth_m = 0.3\nspacing_m = 0.1\n"
      "profile = [[0.0, 0.5], [12.0, -0.5]]\nLEVEL\n"
      "[time]\nduration_s = 1.0\noutput_interval_s = 0.5\n[wave_maker]\nkind = \"none\"\n";
  const auto read = [&](const std::string& level) {
    std::string text = flume;
    text.replace(text.find("LEVEL"), 5, level);
    return bake::read_bake_case(write_text_file(folder / "case.toml", text)).harbour;
  };
  const HarbourGrid datum = read(""), raised = read("still_water_level_m = 0.25");
  int flooded = 0;
  for (std::size_t k = 0; k < datum.still_water_depth_m.size(); ++k) {
    EXPECT_EQ(raised.still_water_depth_m.values()[k], datum.still_water_depth_m.values()[k] + 0.25f);
    EXPECT_EQ(raised.land.values()[k], raised.still_water_depth_m.values()[k] <= 0.f ? 1 : 0);
    flooded += datum.land.values()[k] && !raised.land.values()[k];
  }
  // The beach rises 1 m in 12 m: a level 0.25 m higher moves the shoreline 3 m (30 cells) inland.
  EXPECT_EQ(flooded, 30 * datum.geometry.rows);
  EXPECT_THROW(read("still_water_level_m = 31.0"), Error);
}

}  // namespace
}  // namespace nearshore::library
