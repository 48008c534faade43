#pragma once
// Atomic output: every file nearshore writes goes to a temporary name in the same folder, is
// flushed to disk, and is renamed over the final name only when complete. A crash, a kill or a
// full disk therefore never leaves a truncated output under the real name.
#include <filesystem>
#include <functional>
#include <span>
#include <string>
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

/// Whether `name` is a temporary name of write_file_atomically ("frame_000012.exr.tmp-4711").
bool is_temporary_file_name(std::string_view name);

/// Removes the temporary files (see is_temporary_file_name) that writers killed in `folder` left
/// behind (a kill -9 or power loss skips the cleanup above); not in sub-folders. Call it only while
/// holding the folder's lock (folder_lock.hpp), when no other writer can be using them. Returns how
/// many were removed; a missing folder holds none.
int remove_stale_temporary_files(const std::filesystem::path& folder);

/// strerror(error_number), and for ENOSPC / EDQUOT that the disk (or the quota) is full, in words:
/// what a write failure message says after the file's name.
std::string write_failure_reason(int error_number);

}  // namespace nearshore
