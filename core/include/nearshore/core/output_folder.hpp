#pragma once
// Whose outputs a folder holds, and the two rules every command follows before it writes one
// (issue 44, docs/reliability.md "Output folders"):
//  1. it never writes into a folder its own inputs come from: `export SEQ -o SEQ` would replace the
//     bake's wave_statistics.tif (statistics of every solver step, which no frame can rebuild), a
//     bake written into the harbour grid folder its case reads would replace the grid with its
//     resampled copy;
//  2. it refuses a folder that holds another command's outputs (a sequence, a harbour grid, a
//     library) unless its caller asked to overwrite: `bathy -o SEQ` replaced a sequence's depth.exr.
// Each kind is known by the file its command writes last or alone (see output_kind_of_folder).
#include <filesystem>
#include <string>
#include <vector>

namespace nearshore {

enum class OutputKind {
  kNone,         ///< nothing of the below (an empty folder, an export, anything else)
  kSequence,     ///< `nearshore bake`: manifest.json, or checkpoint.bin of an unfinished bake
  kHarbourGrid,  ///< `nearshore bathy`: summary.json beside depth.exr, or coastline.vdb, without a manifest
  kLibrary,      ///< `nearshore library`: library.json
};

/// What `folder` holds (kNone for a missing folder); `marker`, if given, gets the file that says so.
OutputKind output_kind_of_folder(const std::filesystem::path& folder, std::string* marker = nullptr);

/// "a baked sequence (written by nearshore bake)", for messages.
std::string describe_output_kind(OutputKind kind);

/// A folder a command reads from, and what it reads there ("the sequence being exported").
struct InputFolder {
  std::filesystem::path folder;
  std::string what;
};

/// The rules above for a command about to write into `output_folder` (which may not exist yet).
/// `own_kind` is what the command writes (a folder of that kind is its own to replace, under its own
/// rules); `overwrite` is whether the caller allowed replacing another kind's outputs, and
/// `output_parameter` / `overwrite_parameter` name the caller's fields in the message
/// ("ExportRequest::output_folder"; empty when the command has no such permission). Throws Error
/// naming the folder, what it holds or which input comes from it, and the fix.
void check_output_folder(const std::filesystem::path& output_folder, OutputKind own_kind, bool overwrite,
                         const std::vector<InputFolder>& inputs, const std::string& output_parameter,
                         const std::string& overwrite_parameter);

}  // namespace nearshore
