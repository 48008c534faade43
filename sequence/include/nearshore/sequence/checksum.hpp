#pragma once
// File checksums of the sequence manifest: XXH64 (core/hash.hpp, libxxhash), and whole-file reads
// into reusable buffers, so verifying a whole bake costs little next to reading it.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>

#include "nearshore/core/hash.hpp"

namespace nearshore::sequence {

using nearshore::checksum_text;  // the manifests' "xxh64:<16 hex digits>" (core/hash.hpp)
using nearshore::xxh64;

/// Reads a whole file (throws nearshore::Error naming it if it cannot).
std::string read_file_bytes(const std::filesystem::path& path);

/// A growable byte buffer that is not zero-filled: reading frame after frame into the same one
/// costs one read() per file and no allocation.
struct FileBuffer {
  std::unique_ptr<std::byte[]> data;
  std::size_t size = 0, capacity = 0;
  std::span<const std::byte> bytes() const { return {data.get(), size}; }
};
/// Reads a whole file into `buffer` (throws nearshore::Error naming it if it cannot).
void read_file_into(const std::filesystem::path& path, FileBuffer& buffer);

}  // namespace nearshore::sequence
