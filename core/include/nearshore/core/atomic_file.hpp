#pragma once
// Atomic output: every file nearshore writes goes to a temporary name in the same folder, is
// flushed to disk, and is renamed over the final name only when complete. A crash, a kill or a
// full disk therefore never leaves a truncated output under the real name.
#include <filesystem>
#include <functional>
#include <span>
#include <string_view>

namespace nearshore {

/// Calls `write_to(temporary_path)`, which must create that file completely, then fsyncs it and
/// renames it to `final_path`. On any exception the temporary file is removed and the exception
/// is rethrown (as nearshore::Error naming final_path when it was a filesystem failure).
void write_file_atomically(const std::filesystem::path& final_path,
                           const std::function<void(const std::filesystem::path& temporary_path)>& write_to);

/// Writes the bytes atomically (see above). Throws nearshore::Error on a short write (e.g. disk full).
void write_bytes_atomically(const std::filesystem::path& final_path, std::span<const std::byte> bytes);
void write_text_atomically(const std::filesystem::path& final_path, std::string_view text);

/// Creates `folder` (and parents) or throws Error naming it and the reason.
void create_output_folder(const std::filesystem::path& folder);

}  // namespace nearshore
