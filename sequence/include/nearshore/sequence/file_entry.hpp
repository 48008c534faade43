#pragma once
// One file of a sequence folder as the manifest lists it: name, size and XXH64 checksum.
#include <cstdint>
#include <string>

namespace nearshore::sequence {

struct FileEntry {
  std::string file;           ///< name inside the sequence folder
  std::uint64_t bytes = 0;    ///< file size
  std::string checksum;       ///< "xxh64:<16 hex digits>"
};

}  // namespace nearshore::sequence
