#pragma once
// A sea-state library's definition: LIBRARY.toml (or .json, the same schema), read and expanded
// into one bake case per sea state (docs/library.md). The file names a base case (any case file
// `nearshore bake` reads) and the sweep: for each quantity a list of values; the library is every
// combination, in a fixed axis order (direction, height, period, spectrum, tide, wind speed, wind
// direction), the last axis varying fastest.
//
//   title = "demo harbour: swell directions and tides"
//   base_case = "harbour.toml"          # relative to this file
//   [sweep]
//   direction_deg = [75.0, 90.0, 105.0]
//   tide_m = [0.0, 1.5]
//
// Each quantity sets the base case's key that means it for the base case's wave maker (one table,
// kQuantityKeys in library_definition.cpp; docs/library.md lists it):
//   direction_deg  regular: wave_maker.direction_deg; irregular: wave_maker.mean_direction_deg;
//                  deep_water: deep_water.mean_direction_deg (deep_water.wind_direction_deg for a
//                  wind spectrum, whose waves travel down-wind)
//   height_m       wave_maker.height_m / wave_maker.significant_height_m / deep_water.significant_height_m
//   period_s       wave_maker.period_s / wave_maker.peak_period_s / deep_water.peak_period_s
//   spectrum       wave_maker.spectrum / deep_water.spectrum
//   tide_m         bathymetry.still_water_level_m, added to the base case's (any maker)
//   wind_speed_m_s deep_water.wind_speed_m_s (phillips) or deep_water.wind_speed_10_m_s (unified, pm_ittc)
//   wind_direction_deg  deep_water.wind_direction_deg (wind spectra)
// A quantity the base case's maker has no key for is refused before anything is baked, naming the
// library file, the quantity and the maker.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nearshore/sequence/library_index.hpp"

namespace nearshore::library {

struct LibraryDefinition {
  std::filesystem::path library_file;     ///< where it was read from (named in every message)
  std::string title;
  std::string base_case_as_written;       ///< the `base_case` key as written
  std::filesystem::path base_case;        ///< resolved against the library file's folder
  nlohmann::json base_document;           ///< the base case as read (read_case_document), unchecked
  std::vector<sequence::LibraryIndex::Axis> axes;  ///< the swept quantities, in the fixed axis order
};

/// One sea state of the library: its id (a folder name made of the axis values, e.g.
/// "dir90_tide+1.5"; "base" when nothing is swept), its conditions and the case it is baked from.
struct LibraryStateCase {
  std::string id;
  sequence::SeaConditions conditions;
  /// The base case with the state's keys set and its file paths (bathymetry.file, wave_maker.file)
  /// made absolute, so the case reads the same from the library's cases/ folder.
  nlohmann::json case_document;
};

/// Reads and checks LIBRARY.toml: unknown keys, a missing or unreadable base case, an empty or
/// repeated value list, a value of the wrong type: each a nearshore::Error naming the file, the key
/// and the fix.
LibraryDefinition read_library_definition(const std::filesystem::path& library_file);

/// Every combination of the axes' values, in order. Throws nearshore::Error naming the library file
/// when a quantity has no key in the base case's wave maker, or two axes set one key.
std::vector<LibraryStateCase> expand_library_states(const LibraryDefinition& definition);

}  // namespace nearshore::library
