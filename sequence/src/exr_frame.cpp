#include "exr_frame.hpp"

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
#include <cstring>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore::sequence {
namespace {

constexpr const char* kFormatAttribute = "nearshore_format";
constexpr const char* kIndexAttribute = "nearshore_frame_index";
constexpr const char* kTimeAttribute = "nearshore_time_s";

Imf::Compression to_exr(Compression compression) {
  switch (compression) {
    case Compression::kNone: return Imf::NO_COMPRESSION;
    case Compression::kZip: return Imf::ZIP_COMPRESSION;
    case Compression::kPiz: return Imf::PIZ_COMPRESSION;
    case Compression::kB44: return Imf::B44_COMPRESSION;
    case Compression::kDwaa: return Imf::DWAA_COMPRESSION;
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

Raster<float>* selected_raster(Frame& frame, ChannelSelection selection, int channel) {
  switch (channel) {
    case 0: return selection.surface_elevation ? &frame.surface_elevation_m : nullptr;
    case 1: return selection.flux_x ? &frame.flux_x_m2_s : nullptr;
    case 2: return selection.flux_y ? &frame.flux_y_m2_s : nullptr;
    default: return selection.breaking ? &frame.breaking : nullptr;
  }
}

void flip_rows(Raster<float>& raster) {
  const int columns = raster.columns();
  for (int low = 0, high = raster.rows() - 1; low < high; ++low, --high)
    std::swap_ranges(&raster(0, low), &raster(0, low) + columns, &raster(0, high));
}

// Validates the header against the manifest and decodes raster rows [first_row, first_row+count).
void decode(Imf::InputFile& file, const std::string& source, const SequenceManifest& manifest, int expected_index,
            int first_row, int row_count, ChannelSelection selection, Frame& frame) {
  const Imf::Header& header = file.header();
  const auto* format = header.findTypedAttribute<Imf::StringAttribute>(kFormatAttribute);
  if (!format || format->value() != kFrameFormat)
    throw Error(source, "is an EXR file but not a nearshore sequence frame", "rewrite the sequence with `nearshore bake`");
  const auto* index = header.findTypedAttribute<Imf::IntAttribute>(kIndexAttribute);
  if (!index || index->value() != expected_index)
    throw Error(source, fmt::format("holds frame {} but the manifest puts frame {} here",
                                    index ? std::to_string(index->value()) : std::string("(none)"), expected_index),
                "the folder's files were renamed or mixed; rewrite the sequence");
  const auto* time = header.findTypedAttribute<Imf::DoubleAttribute>(kTimeAttribute);
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
  frame.index = expected_index;
  frame.time_s = time ? time->value() : manifest.frame_time_s(expected_index);
  // Raster rows [first_row, first_row + row_count) are EXR lines [rows - first_row - row_count, rows - first_row).
  const int first_line = rows - first_row - row_count;
  const std::ptrdiff_t row_stride = static_cast<std::ptrdiff_t>(columns) * static_cast<std::ptrdiff_t>(sizeof(float));
  Imf::FrameBuffer frame_buffer;
  for (int c = 0; c < 4; ++c) {
    Raster<float>* raster = selected_raster(frame, selection, c);
    if (!raster) {
      if (Raster<float>* unused = selected_raster(frame, ChannelSelection::all(), c)) *unused = Raster<float>();
      continue;
    }
    if (raster->columns() != columns || raster->rows() != row_count) *raster = Raster<float>(columns, row_count);
    char* base = reinterpret_cast<char*>(raster->data()) - first_line * row_stride;
    frame_buffer.insert(kChannelNames[c],
                        Imf::Slice(Imf::FLOAT, base, sizeof(float), static_cast<std::size_t>(row_stride)));
  }
  file.setFrameBuffer(frame_buffer);
  file.readPixels(first_line, first_line + row_count - 1);
  for (int c = 0; c < 4; ++c)
    if (Raster<float>* raster = selected_raster(frame, selection, c)) flip_rows(*raster);
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
    Imf::InputFile file(path.c_str());
    decode(file, path.string(), manifest, expected_index, first_row, row_count, selection, frame);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(path.string(), std::string("cannot be decoded: ") + e.what(),
                "the frame is truncated or corrupt; check it with `nearshore loops --verify` and re-bake");
  }
}

}  // namespace detail

void decode_frame(std::span<const std::byte> bytes, const std::string& source, const SequenceManifest& manifest,
                  int expected_index, ChannelSelection channels, Frame& frame) {
  try {
    MemoryInput input(bytes, source);
    Imf::InputFile file(input);
    decode(file, source, manifest, expected_index, 0, manifest.geometry.rows, channels, frame);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(source, std::string("cannot be decoded: ") + e.what(),
                "the frame is truncated or corrupt; check it with `nearshore loops --verify` and re-bake");
  }
}

}  // namespace nearshore::sequence
