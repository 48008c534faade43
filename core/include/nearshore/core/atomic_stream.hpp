#pragma once
// Atomic output through a std::ostream (atomic_file.hpp for the rule every output follows).
#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace nearshore {

/// Writes a file through a std::ostream atomically (see above), for writers that only know streams
/// (OpenVDB's archives, the checkpoint's state writer). The stream sits on the file's descriptor
/// and keeps the errno of the first failed write or close, and supports seeking (OpenVDB seeks
/// back to fill in its grid offsets); when anything failed the file is not renamed into place and
/// an Error names `final_path`, "writing <what> failed after N bytes" and the reason ("No space
/// left on device (the disk is full)"). std::ofstream would only set badbit, which a library
/// writer (OpenVDB's io::File) never looks at: that is how full disks became truncated files.
/// An exception thrown by `write_to` after a failed write is replaced by that failure, its cause.
void write_stream_atomically(const std::filesystem::path& final_path, const std::function<void(std::ostream& out)>& write_to,
                             std::string_view what = "the file");

}  // namespace nearshore
