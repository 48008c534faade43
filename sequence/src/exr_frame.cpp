#include "exr_frame.hpp"

#include <string_view>
#include <utility>

#include <OpenEXR/Iex.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <Imath/half.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#if defined(__x86_64__)
#include <immintrin.h>
#if defined(__x86_64__)
#include <cpuid.h>
#endif
#endif
#include <cstring>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore::sequence {
namespace {

constexpr const char* kFormatAttribute = "nearshore_format";
constexpr const char* kIndexAttribute = "nearshore_frame_index";
constexpr const char* kTimeAttribute = "nearshore_time_s";
constexpr const char* kCorruptFrameFix =
    "the frame is truncated or corrupt; verify the sequence's checksums with SequenceReader::verify_checksums "
    "and re-bake";

Imf::Compression to_exr(Compression compression) {
  switch (compression) {
    case Compression::kNone: return Imf::NO_COMPRESSION;
    case Compression::kZip: return Imf::ZIP_COMPRESSION;
    case Compression::kPiz: return Imf::PIZ_COMPRESSION;
    case Compression::kB44: return Imf::B44_COMPRESSION;
    case Compression::kDwaa: return Imf::DWAA_COMPRESSION;
    case Compression::kRle: return Imf::RLE_COMPRESSION;
    case Compression::kZips: return Imf::ZIPS_COMPRESSION;
    case Compression::kPxr24: return Imf::PXR24_COMPRESSION;
  }
  return Imf::ZIP_COMPRESSION;
}

// OpenEXR writes through an OStream; this one keeps the file in memory so the writer can hash
// the exact bytes and write them atomically in one go.
class MemoryOutput : public Imf::OStream {
 public:
  MemoryOutput() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (position_ + n > bytes_.size()) bytes_.resize(position_ + n);
    std::memcpy(bytes_.data() + position_, c, static_cast<std::size_t>(n));
    position_ += static_cast<std::size_t>(n);
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t position) override { position_ = position; }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
  std::size_t position_ = 0;
};

// Reads a file already in memory (the reader hashes it first). Every read is bounds-checked, so
// a truncated file becomes an exception, never a read past the buffer.
class MemoryInput : public Imf::IStream {
 public:
  MemoryInput(std::span<const std::byte> bytes, const std::string& name)
      : Imf::IStream(name.c_str()), data_(reinterpret_cast<const char*>(bytes.data())), size_(bytes.size()) {}
  bool isMemoryMapped() const override { return true; }
  char* readMemoryMapped(int n) override {
    check(n);
    // OpenEXR only reads through this pointer.
    char* p = const_cast<char*>(data_) + position_;
    position_ += static_cast<std::size_t>(n);
    return p;
  }
  bool read(char c[], int n) override {
    check(n);
    std::memcpy(c, data_ + position_, static_cast<std::size_t>(n));
    position_ += static_cast<std::size_t>(n);
    return position_ < size_;
  }
  uint64_t tellg() override { return position_; }
  void seekg(uint64_t position) override { position_ = position; }

 private:
  void check(int n) const {
    if (n < 0 || position_ > size_ || static_cast<std::size_t>(n) > size_ - position_)
      throw Iex::InputExc("unexpected end of file");
  }
  const char* data_;
  std::size_t size_;
  std::size_t position_ = 0;
};

// OpenEXR 3.1 sizes an attribute's buffer from the size field in the file before it reads the
// value, so one flipped bit in a header can ask for gigabytes (found by the libFuzzer target).
// Walk the single-part header ourselves first (OpenEXR file layout: magic, version, then
// attributes "name\0 type\0 int32 size, value" up to an empty name) and refuse any attribute
// whose value would run past the end of the file. `header_bytes` may be a prefix of the file;
// the walk stops where it ends (sizes are still bounded by `file_size`).
// The data window is checked here too, against the grid of `manifest`: OpenEXR's InputFile sizes
// its line buffers and decompressor from the data window while it opens the file, before
// validate_header can look at it, so a bent window in a compressed frame made it allocate 566 MB
// (found by the libFuzzer target with -malloc_limit_mb=500). Tiled headers are refused for the
// same reason (their tile buffers come from the tile description); frames are scanline files.
void check_header_attribute_sizes(std::span<const std::byte> header_bytes, std::uint64_t file_size,
                                  const std::string& source, const GridGeometry& grid) {
  const auto corrupt = [&](const std::string& problem) {
    return Error(source, problem, kCorruptFrameFix);
  };
  const std::size_t available = header_bytes.size();
  const auto byte_at = [&](std::size_t k) { return static_cast<unsigned char>(header_bytes[k]); };
  if (available < 8) return;  // OpenEXR refuses it
  // Names and type names are at most 31 bytes, 255 with the long-names flag (bit 10 of the version
  // field). OpenEXR stops reading a name at that length even without its terminating zero, so a
  // longer one would be split where this scan does not split it, and OpenEXR would take a size
  // this scan never saw (a fuzzed frame made it allocate 1.6 GB): refuse it here instead.
  const bool long_names = (byte_at(5) & 0x04) != 0;
  // Version field bits 9 (tiled), 11 (deep) and 12 (multi-part): a frame is none of these.
  if ((byte_at(5) & (0x02 | 0x08 | 0x10)) != 0)
    throw corrupt("its version field marks a tiled, deep or multi-part file; a frame is a single-part scanline file");
  const std::size_t longest_name = long_names ? 255 : 31;
  std::size_t position = 8;  // magic number and version field
  // The end (its zero) of the name starting at `start`, or `available` if the prefix ends first.
  const auto name_end_from = [&](std::size_t start, const char* what) {
    for (std::size_t k = start; k < available; ++k) {
      if (byte_at(k) == 0) return k;
      if (k - start >= longest_name)
        throw corrupt(fmt::format("a header attribute's {} at byte {} is longer than {} bytes", what, start,
                                  longest_name));
    }
    return available;
  };
  while (position < available) {
    if (byte_at(position) == 0) return;  // end of header
    const std::size_t name_end = name_end_from(position, "name");
    if (name_end + 1 >= available) return;  // beyond the prefix: OpenEXR checks the rest
    const std::size_t type_end = name_end_from(name_end + 1, "type name");
    if (type_end >= available || type_end + 4 >= available) return;  // beyond the prefix: OpenEXR checks the rest
    const std::int32_t size = static_cast<std::int32_t>(static_cast<std::uint32_t>(byte_at(type_end + 1)) |
                                                        static_cast<std::uint32_t>(byte_at(type_end + 2)) << 8 |
                                                        static_cast<std::uint32_t>(byte_at(type_end + 3)) << 16 |
                                                        static_cast<std::uint32_t>(byte_at(type_end + 4)) << 24);
    const std::size_t value_start = type_end + 5;
    if (size < 0 || static_cast<std::uint64_t>(size) > file_size - std::min<std::uint64_t>(file_size, value_start))
      throw corrupt(fmt::format("header attribute '{}' claims {} bytes but the file has {} bytes in all",
                                std::string(reinterpret_cast<const char*>(header_bytes.data()) + position, name_end - position),
                                size, file_size));
    // Where OpenEXR goes on reading: a value of a known type is read by its structure, whatever
    // size the file claims (a channel list up to its empty name, an int as 4 bytes), so the next
    // attribute starts where the structure ends; strings and unknown types take the claimed size.
    const std::string type(reinterpret_cast<const char*>(header_bytes.data()) + name_end + 1, type_end - name_end - 1);
    if (type == "chlist") {
      std::size_t k = value_start;
      while (k < available && byte_at(k) != 0) {
        k = name_end_from(k, "channel name");
        if (k >= available) return;  // beyond the prefix: OpenEXR checks the rest
        k += 1 + 16;  // pixel type, pLinear and reserved, x and y sampling
      }
      if (k >= available) return;
      position = k + 1;
      continue;
    }
    static constexpr std::pair<std::string_view, std::size_t> kFixedSizes[] = {
        {"box2i", 16}, {"box2f", 16}, {"compression", 1}, {"lineOrder", 1}, {"envmap", 1}, {"deepImageState", 1},
        {"int", 4},    {"float", 4},  {"double", 8},      {"v2i", 8},       {"v2f", 8},    {"v2d", 16},
        {"v3i", 12},   {"v3f", 12},   {"v3d", 24},        {"m33f", 36},     {"m33d", 72},  {"m44f", 64},
        {"m44d", 128}, {"rational", 8}, {"timecode", 8},  {"keycode", 28},  {"tiledesc", 9}, {"chromaticities", 32}};
    std::size_t value_size = static_cast<std::size_t>(size);
    for (const auto& [known, bytes] : kFixedSizes)
      if (type == known) value_size = bytes;
    const std::string_view name(reinterpret_cast<const char*>(header_bytes.data()) + position, name_end - position);
    if (name == "dataWindow" && type == "box2i" && value_start + 16 <= available) {
      const auto int_at = [&](std::size_t k) {
        return static_cast<std::int32_t>(static_cast<std::uint32_t>(byte_at(k)) | static_cast<std::uint32_t>(byte_at(k + 1)) << 8 |
                                         static_cast<std::uint32_t>(byte_at(k + 2)) << 16 |
                                         static_cast<std::uint32_t>(byte_at(k + 3)) << 24);
      };
      const std::int32_t min_x = int_at(value_start), min_y = int_at(value_start + 4);
      const std::int32_t max_x = int_at(value_start + 8), max_y = int_at(value_start + 12);
      if (min_x != 0 || min_y != 0 || max_x != grid.columns - 1 || max_y != grid.rows - 1)
        throw Error(source,
                    fmt::format("has a header data window of pixels ({}, {})-({}, {}) but the grid is {} x {}", min_x,
                                min_y, max_x, max_y, grid.columns, grid.rows),
                    "the frame does not belong to this sequence; rewrite the sequence");
    }
    position = value_start + value_size;
  }
}

// ---- finite samples -------------------------------------------------------------------------------
// A frame holds the state of a bake that ran to the end, so every sample is finite: the writer
// refuses NaN and infinity, and a NaN or an infinity on disk is a damaged or altered file (or a
// value beyond half's 65504 rounded to infinity). Downstream nothing would notice: the loop
// builder takes NaN for a distance (a seam of R = 0), the player draws a wall. So each decoder
// counts non-finite samples in the same pass that converts them (an exponent field of all ones:
// 0x7c00 in a half, 0x7f800000 in a float), and only when the count is not zero looks for the cell.
constexpr std::uint16_t kHalfExponent = 0x7c00;
constexpr std::uint32_t kFloatExponent = 0x7f800000u;

// Throws naming the frame file, the channel and the first non-finite cell of raster row `row`.
// `values` is that row as decoded (`columns` samples), `geometry` the frame's grid.
[[noreturn]] void throw_non_finite(const std::string& source, const GridGeometry& geometry, int channel,
                                   const float* values, int row) {
  int column = 0;
  while (column + 1 < geometry.columns && std::isfinite(values[column])) ++column;
  throw Error(source,
              fmt::format("channel '{}' holds {} at cell (column {}, row {}; x {:.1f} m, y {:.1f} m): a frame "
                          "holds only finite values",
                          kChannelNames[channel], values[column], column, row, geometry.cell_centre_x_m(column),
                          geometry.cell_centre_y_m(row)),
              "the file was damaged or altered after the bake, or a value overflowed its half-float channel; "
              "check the sequence with SequenceReader::verify_checksums and re-bake it (storing the channel as "
              "float if its values exceed 65504)");
}

// Copies `count` little-endian floats into `target`; returns how many are NaN or infinite.
int copy_floats_counting_non_finite(const unsigned char* source, float* target, int count) {
  std::memcpy(target, source, static_cast<std::size_t>(count) * 4);
  int non_finite = 0;
  for (int k = 0; k < count; ++k) non_finite += (std::bit_cast<std::uint32_t>(target[k]) & kFloatExponent) == kFloatExponent;
  return non_finite;
}

Raster<float>* selected_raster(Frame& frame, ChannelSelection selection, int channel) {
  switch (channel) {
    case 0: return selection.surface_elevation ? &frame.surface_elevation_m : nullptr;
    case 1: return selection.flux_x ? &frame.flux_x_m2_s : nullptr;
    case 2: return selection.flux_y ? &frame.flux_y_m2_s : nullptr;
    default: return selection.breaking ? &frame.breaking : nullptr;
  }
}

// Checks a frame's header against the manifest: format, frame index, size, channels.
void validate_header(Imf::InputFile& file, const std::string& source, const SequenceManifest& manifest,
                     int expected_index) {
  const Imf::Header& header = file.header();
  const auto* format = header.findTypedAttribute<Imf::StringAttribute>(kFormatAttribute);
  if (!format || format->value() != kFrameFormat)
    throw Error(source, "is an EXR file but not a nearshore sequence frame", "rewrite the sequence with `nearshore bake`");
  const auto* index = header.findTypedAttribute<Imf::IntAttribute>(kIndexAttribute);
  if (!index || index->value() != expected_index)
    throw Error(source, fmt::format("holds frame {} but the manifest puts frame {} here",
                                    index ? std::to_string(index->value()) : std::string("(none)"), expected_index),
                "the folder's files were renamed or mixed; rewrite the sequence");
  const int columns = manifest.geometry.columns, rows = manifest.geometry.rows;
  const Imath::Box2i window = header.dataWindow();
  if (window.min.x != 0 || window.min.y != 0 || window.max.x != columns - 1 || window.max.y != rows - 1)
    throw Error(source,
                fmt::format("covers pixels ({}, {})-({}, {}) but the grid is {} x {}", window.min.x, window.min.y,
                            window.max.x, window.max.y, columns, rows),
                "the frame does not belong to this sequence; rewrite the sequence");
  for (int c = 0; c < 4; ++c) {
    const Imf::Channel* channel = header.channels().findChannel(kChannelNames[c]);
    if (!channel || (channel->type != Imf::HALF && channel->type != Imf::FLOAT) || channel->xSampling != 1 ||
        channel->ySampling != 1)
      throw Error(source, fmt::format("has no full-resolution half/float '{}' channel", kChannelNames[c]),
                  "rewrite the sequence with `nearshore bake`");
  }
}

// Validates the header against the manifest and decodes raster rows [first_row, first_row+count).
void decode(Imf::InputFile& file, const std::string& source, const SequenceManifest& manifest, int expected_index,
            int first_row, int row_count, ChannelSelection selection, Frame& frame) {
  validate_header(file, source, manifest, expected_index);
  const Imf::Header& header = file.header();
  const auto* time = header.findTypedAttribute<Imf::DoubleAttribute>(kTimeAttribute);
  const int columns = manifest.geometry.columns, rows = manifest.geometry.rows;
  frame.index = expected_index;
  frame.time_s = time ? time->value() : manifest.frame_time_s(expected_index);
  // Raster rows [first_row, first_row + row_count) are EXR lines [rows - first_row - row_count, rows - first_row).
  // OpenEXR copies each channel in its stored type into a scratch buffer (a plain copy, no
  // per-pixel conversion); one pass then converts half to float and flips north-up lines into
  // south-up rows.
  const int first_line = rows - first_row - row_count;
  const std::size_t cells = static_cast<std::size_t>(columns) * static_cast<std::size_t>(row_count);
  thread_local std::vector<half> half_scratch[4];
  thread_local std::vector<float> float_scratch[4];
  Imf::FrameBuffer frame_buffer;
  bool stored_half[4] = {};
  for (int c = 0; c < 4; ++c) {
    Raster<float>* raster = selected_raster(frame, selection, c);
    if (!raster) {
      if (Raster<float>* unused = selected_raster(frame, ChannelSelection::all(), c)) *unused = Raster<float>();
      continue;
    }
    if (raster->columns() != columns || raster->rows() != row_count) *raster = Raster<float>(columns, row_count);
    stored_half[c] = header.channels().findChannel(kChannelNames[c])->type == Imf::HALF;
    const std::size_t size = stored_half[c] ? sizeof(half) : sizeof(float);
    char* scratch;
    if (stored_half[c]) {
      half_scratch[c].resize(cells);
      scratch = reinterpret_cast<char*>(half_scratch[c].data());
    } else {
      float_scratch[c].resize(cells);
      scratch = reinterpret_cast<char*>(float_scratch[c].data());
    }
    const std::ptrdiff_t line_bytes = static_cast<std::ptrdiff_t>(columns) * static_cast<std::ptrdiff_t>(size);
    frame_buffer.insert(kChannelNames[c], Imf::Slice(stored_half[c] ? Imf::HALF : Imf::FLOAT,
                                                     scratch - first_line * line_bytes, size,
                                                     static_cast<std::size_t>(line_bytes)));
  }
  file.setFrameBuffer(frame_buffer);
  file.readPixels(first_line, first_line + row_count - 1);
  for (int c = 0; c < 4; ++c) {
    Raster<float>* raster = selected_raster(frame, selection, c);
    if (!raster) continue;
    for (int line = 0; line < row_count; ++line) {
      float* target = &(*raster)(0, row_count - 1 - line);
      const std::size_t offset = static_cast<std::size_t>(line) * static_cast<std::size_t>(columns);
      int non_finite = 0;
      if (stored_half[c]) {
        const half* samples = half_scratch[c].data() + offset;
        for (int column = 0; column < columns; ++column) {
          target[column] = samples[column];
          non_finite += (samples[column].bits() & kHalfExponent) == kHalfExponent;
        }
      } else {
        non_finite = copy_floats_counting_non_finite(
            reinterpret_cast<const unsigned char*>(float_scratch[c].data() + offset), target, columns);
      }
      if (non_finite) throw_non_finite(source, manifest.geometry, c, target, first_row + row_count - 1 - line);
    }
  }
}



// half -> float for a run of little-endian samples, counting the NaN and infinite ones in the same
// pass. x86-64 machines with F16C convert 8 at a time (chosen at run time, so the build needs no
// -march flag); elsewhere Imath's table.
int halves_to_floats_portable(const unsigned char* source, float* target, int count) {
  int non_finite = 0;
  for (int k = 0; k < count; ++k) {
    std::uint16_t bits;
    std::memcpy(&bits, source + 2 * k, 2);
    target[k] = imath_half_to_float(bits);
    non_finite += (bits & kHalfExponent) == kHalfExponent;
  }
  return non_finite;
}
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
// CPUID leaf 1, ECX bit 28 (AVX) and bit 29 (F16C). Asked directly: clang 14 (the libFuzzer build)
// does not know "f16c" as a __builtin_cpu_supports feature.
bool cpu_has_avx_and_f16c() {
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return false;
  return (ecx & (1u << 28)) && (ecx & (1u << 29));
}
__attribute__((target("avx,f16c"))) int halves_to_floats_f16c(const unsigned char* source, float* target, int count) {
  const __m128i exponent = _mm_set1_epi16(static_cast<short>(kHalfExponent));
  __m128i any_non_finite = _mm_setzero_si128();
  int k = 0;
  for (; k + 8 <= count; k += 8) {
    const __m128i halves = _mm_loadu_si128(reinterpret_cast<const __m128i*>(source + 2 * k));
    _mm256_storeu_ps(target + k, _mm256_cvtph_ps(halves));
    any_non_finite = _mm_or_si128(any_non_finite, _mm_cmpeq_epi16(_mm_and_si128(halves, exponent), exponent));
  }
  return (_mm_movemask_epi8(any_non_finite) != 0) + halves_to_floats_portable(source + 2 * k, target + k, count - k);
}
int halves_to_floats(const unsigned char* source, float* target, int count) {
  static const bool has_f16c = cpu_has_avx_and_f16c();
  return has_f16c ? halves_to_floats_f16c(source, target, count) : halves_to_floats_portable(source, target, count);
}
#else
int halves_to_floats(const unsigned char* source, float* target, int count) {
  return halves_to_floats_portable(source, target, count);
}
#endif

// Uncompressed frames (the measured default, docs/formats/sequence.md) are read straight from the
// file layout of the OpenEXR specification: magic and version (8 bytes), attributes up to a null
// byte, one 64-bit offset per scan line, then per line: int32 y, int32 byte count, and each channel's
// samples in channel-name order. One pass converts half to float and flips north-up lines to
// south-up rows; every offset and size is checked against the buffer (the reader is fuzzed).
void decode_uncompressed(std::span<const std::byte> bytes, const Imf::Header& header, const std::string& source,
                         const SequenceManifest& manifest, int expected_index, ChannelSelection selection,
                         Frame& frame) {
  const int columns = manifest.geometry.columns, rows = manifest.geometry.rows;
  const std::size_t size = bytes.size();
  const unsigned char* data = reinterpret_cast<const unsigned char*>(bytes.data());
  auto corrupt = [&](const std::string& what) {
    return Error(source, "cannot be decoded: " + what, kCorruptFrameFix);
  };
  auto load32 = [&](std::size_t at) {
    std::int32_t value;
    std::memcpy(&value, data + at, 4);
    return value;
  };
  if (size < 9) throw corrupt("too short");
  std::uint32_t version;
  std::memcpy(&version, data + 4, 4);
  if ((version & ~0xffu & ~0x400u) != 0) throw corrupt("not a single-part scanline file");
  std::size_t at = 8;
  while (true) {  // attributes: name\0 type\0 int32 size value
    if (at >= size) throw corrupt("header runs past the end");
    if (data[at] == 0) {
      ++at;
      break;
    }
    for (int field = 0; field < 2; ++field) {
      const void* end = std::memchr(data + at, 0, size - at);
      if (!end) throw corrupt("header runs past the end");
      at = static_cast<std::size_t>(static_cast<const unsigned char*>(end) - data) + 1;
    }
    if (at + 4 > size) throw corrupt("header runs past the end");
    const std::int32_t attribute_size = load32(at);
    if (attribute_size < 0 || static_cast<std::size_t>(attribute_size) > size - at - 4) throw corrupt("bad attribute size");
    at += 4 + static_cast<std::size_t>(attribute_size);
  }
  if (rows < 0 || at + static_cast<std::size_t>(rows) * 8 > size) throw corrupt("line offset table is truncated");
  const std::size_t table = at;
  // Channels in file order (ChannelList iterates by name) and where each lies within a line.
  struct Part {
    Raster<float>* raster;
    bool is_half;
    std::size_t offset;
    int channel;  // index into kChannelNames (-1: not one of them, skipped)
  };
  std::vector<Part> parts;
  std::size_t line_bytes = 0;
  for (auto channel = header.channels().begin(); channel != header.channels().end(); ++channel) {
    const bool is_half = channel.channel().type == Imf::HALF;
    if (!is_half && channel.channel().type != Imf::FLOAT) throw corrupt("unexpected channel type");
    Raster<float>* raster = nullptr;
    int index = -1;
    for (int c = 0; c < 4; ++c)
      if (std::strcmp(channel.name(), kChannelNames[c]) == 0) {
        raster = selected_raster(frame, selection, c);
        index = c;
      }
    parts.push_back({raster, is_half, line_bytes, index});
    line_bytes += static_cast<std::size_t>(columns) * (is_half ? 2 : 4);
  }
  for (int c = 0; c < 4; ++c) {
    Raster<float>* raster = selected_raster(frame, selection, c);
    if (!raster) {
      if (Raster<float>* unused = selected_raster(frame, ChannelSelection::all(), c)) *unused = Raster<float>();
    } else if (raster->columns() != columns || raster->rows() != rows) {
      *raster = Raster<float>(columns, rows);
    }
  }
  for (int line = 0; line < rows; ++line) {
    std::uint64_t offset;
    std::memcpy(&offset, data + table + static_cast<std::size_t>(line) * 8, 8);
    if (offset > size || size - offset < 8 || size - offset - 8 < line_bytes) throw corrupt(fmt::format("line {} lies outside the file", line));
    if (load32(offset) != line || load32(offset + 4) != static_cast<std::int32_t>(line_bytes))
      throw corrupt(fmt::format("line {} has a wrong header", line));
    const unsigned char* samples = data + offset + 8;
    for (const Part& part : parts) {
      if (!part.raster) continue;
      float* target = &(*part.raster)(0, rows - 1 - line);
      const unsigned char* source_bytes = samples + part.offset;
      const int non_finite = part.is_half ? halves_to_floats(source_bytes, target, columns)
                                          : copy_floats_counting_non_finite(source_bytes, target, columns);
      if (non_finite) throw_non_finite(source, manifest.geometry, part.channel, target, rows - 1 - line);
    }
  }
  const auto* time = header.findTypedAttribute<Imf::DoubleAttribute>(kTimeAttribute);
  frame.index = expected_index;
  frame.time_s = time ? time->value() : manifest.frame_time_s(expected_index);
}

}  // namespace

namespace detail {

std::string encode_frame(const GridGeometry& geometry, const FrameEncoding& encoding, int index, double time_s,
                         const std::array<const Raster<float>*, 4>& channels) {
  const int columns = geometry.columns, rows = geometry.rows;
  const Precision precisions[4] = {encoding.surface_elevation, encoding.flux, encoding.flux, encoding.breaking};
  // EXR line 0 is the northern row: copy each channel flipped (the one flip of this format),
  // rounding to half where the channel is stored as half (round to nearest even, Imath).
  std::vector<std::vector<float>> float_lines(4);
  std::vector<std::vector<half>> half_lines(4);
  Imf::Header header(columns, rows);
  header.compression() = to_exr(encoding.compression);
  header.insert(kFormatAttribute, Imf::StringAttribute(std::string(kFrameFormat)));
  header.insert(kIndexAttribute, Imf::IntAttribute(index));
  header.insert(kTimeAttribute, Imf::DoubleAttribute(time_s));
  Imf::FrameBuffer frame_buffer;
  for (int c = 0; c < 4; ++c) {
    const bool as_half = precisions[c] == Precision::kHalf;
    header.channels().insert(kChannelNames[c], Imf::Channel(as_half ? Imf::HALF : Imf::FLOAT));
    auto fill = [&](auto& lines) {
      lines.assign(geometry.cell_count(), 0.0f);
      if (!channels[c]) return;
      for (int row = 0; row < rows; ++row) {
        const float* source = &(*channels[c])(0, row);
        auto* target = &lines[static_cast<std::size_t>(rows - 1 - row) * columns];
        for (int column = 0; column < columns; ++column) target[column] = source[column];
      }
    };
    if (as_half) {
      fill(half_lines[c]);
      frame_buffer.insert(kChannelNames[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(half_lines[c].data()),
                                                       sizeof(half), sizeof(half) * columns));
    } else {
      fill(float_lines[c]);
      frame_buffer.insert(kChannelNames[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(float_lines[c].data()),
                                                       sizeof(float), sizeof(float) * columns));
    }
  }
  MemoryOutput output;
  {
    Imf::OutputFile file(output, header);
    file.setFrameBuffer(frame_buffer);
    file.writePixels(rows);
  }  // the destructor completes the file (line offset table)
  return output.take();
}

void decode_frame_rows(const std::filesystem::path& path, const SequenceManifest& manifest, int expected_index,
                       int first_row, int row_count, ChannelSelection selection, Frame& frame) {
  if (first_row < 0 || row_count < 1 || first_row + row_count > manifest.geometry.rows)
    throw Error(path.string(), fmt::format("rows {}..{} requested but the grid has {} rows", first_row,
                                           first_row + row_count - 1, manifest.geometry.rows),
                "ask for rows inside the grid");
  try {
    // The header of a nearshore frame is a few hundred bytes; 64 KiB covers any real one.
    std::vector<std::byte> header(65536);
    std::ifstream stream(path, std::ios::binary);
    stream.read(reinterpret_cast<char*>(header.data()), static_cast<std::streamsize>(header.size()));
    check_header_attribute_sizes(std::span(header.data(), static_cast<std::size_t>(stream.gcount())),
                                 std::filesystem::file_size(path), path.string(), manifest.geometry);
    Imf::InputFile file(path.c_str());
    decode(file, path.string(), manifest, expected_index, first_row, row_count, selection, frame);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(path.string(), std::string("cannot be decoded: ") + e.what(), kCorruptFrameFix);
  }
}

}  // namespace detail

void decode_frame(std::span<const std::byte> bytes, const std::string& source, const SequenceManifest& manifest,
                  int expected_index, ChannelSelection channels, Frame& frame) {
  try {
    check_header_attribute_sizes(bytes, bytes.size(), source, manifest.geometry);
    MemoryInput input(bytes, source);
    Imf::InputFile file(input);
    if (file.header().compression() == Imf::NO_COMPRESSION && file.header().channels().begin() != file.header().channels().end()) {
      // Validate exactly as the general path does (header, index, size, channels), then copy.
      validate_header(file, source, manifest, expected_index);
      decode_uncompressed(bytes, file.header(), source, manifest, expected_index, channels, frame);
      return;
    }
    decode(file, source, manifest, expected_index, 0, manifest.geometry.rows, channels, frame);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(source, std::string("cannot be decoded: ") + e.what(), kCorruptFrameFix);
  }
}

}  // namespace nearshore::sequence

#include <OpenEXR/ImfThreading.h>

namespace nearshore::sequence {
void set_exr_worker_threads(int threads) { Imf::setGlobalThreadCount(std::max(0, threads)); }
}  // namespace nearshore::sequence
