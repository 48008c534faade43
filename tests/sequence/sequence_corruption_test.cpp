#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <limits>
#include <random>

#include "nearshore/core/error.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "nearshore/sequence/sequence_reader.hpp"
#include "test_sequence.hpp"

namespace nearshore::sequence {
namespace {
using namespace testing;
namespace fs = std::filesystem;

void overwrite(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

TEST(SequenceCorruption, TruncatedFrameIsRejectedWithAndWithoutVerification) {
  const auto folder = fresh_folder("truncated");
  write_test_sequence(folder, 3);
  const fs::path path = folder / "frame_000001.exr";
  std::string bytes = read_file_bytes(path);
  overwrite(path, bytes.substr(0, bytes.size() / 2));
  const SequenceReader reader(folder);
  const std::string verified = error_message_of([&] { reader.read_frame(1, ChannelSelection::all(), Verify::kYes); });
  EXPECT_NE(verified.find("frame_000001.exr"), std::string::npos) << verified;
  EXPECT_NE(verified.find("truncated"), std::string::npos) << verified;
  const std::string unverified = error_message_of([&] { reader.read_frame(1); });
  EXPECT_NE(unverified.find("frame_000001.exr: cannot be decoded"), std::string::npos) << unverified;
  EXPECT_NE(error_message_of([&] { reader.verify_checksums(); }).find("frame_000001.exr"), std::string::npos);
  EXPECT_NO_THROW(reader.read_frame(2, ChannelSelection::all(), Verify::kYes));  // the others are fine
}

TEST(SequenceCorruption, EveryFlippedByteIsCaughtByTheChecksum) {
  const auto folder = fresh_folder("flipped");
  write_test_sequence(folder, 2);
  const fs::path path = folder / "frame_000000.exr";
  const std::string original = read_file_bytes(path);
  const SequenceReader reader(folder);
  // Bytes in the header, the offset table and the pixel data.
  for (std::size_t position : {std::size_t{10}, original.size() / 3, original.size() / 2, original.size() - 1}) {
    std::string bytes = original;
    bytes[position] = static_cast<char>(bytes[position] ^ 0x10);
    overwrite(path, bytes);
    const std::string message = error_message_of([&] { reader.read_frame(0, ChannelSelection::all(), Verify::kYes); });
    EXPECT_NE(message.find("does not match the manifest"), std::string::npos) << position << ": " << message;
  }
  overwrite(path, original);
  EXPECT_NO_THROW(reader.read_frame(0, ChannelSelection::all(), Verify::kYes));
}

TEST(SequenceCorruption, SwappedFramesAreDetectedEvenWithoutChecksums) {
  const auto folder = fresh_folder("swapped");
  write_test_sequence(folder, 2);
  fs::rename(folder / "frame_000000.exr", folder / "tmp.exr");
  fs::rename(folder / "frame_000001.exr", folder / "frame_000000.exr");
  fs::rename(folder / "tmp.exr", folder / "frame_000001.exr");
  const std::string message = error_message_of([&] { SequenceReader(folder).read_frame(0); });
  EXPECT_NE(message.find("holds frame 1 but the manifest puts frame 0 here"), std::string::npos) << message;
}

TEST(SequenceCorruption, ManifestProblemsNameTheKey) {
  const auto folder = fresh_folder("manifest");
  write_test_sequence(folder, 2);
  const fs::path path = folder / "manifest.json";
  const std::string original = read_file_bytes(path);
  overwrite(path, original.substr(0, original.size() - 20));
  EXPECT_NE(error_message_of([&] { SequenceReader{folder}; }).find("is not valid JSON"), std::string::npos);
  nlohmann::json json = nlohmann::json::parse(original);
  json["version"] = 7;
  overwrite(path, json.dump());
  EXPECT_NE(error_message_of([&] { SequenceReader{folder}; }).find("format version 7"), std::string::npos);
  json = nlohmann::json::parse(original);
  json["frames"][1]["file"] = "../../etc/passwd";
  overwrite(path, json.dump());
  EXPECT_NE(error_message_of([&] { SequenceReader{folder}; }).find("not a plain file name"), std::string::npos);
  json = nlohmann::json::parse(original);
  json.erase("frame_interval_s");
  overwrite(path, json.dump());
  EXPECT_NE(error_message_of([&] { SequenceReader{folder}; }).find("has no \"frame_interval_s\""), std::string::npos);
}

// Found by the libFuzzer target: OpenEXR 3.1 allocates an attribute's buffer from the size the
// header declares, so one corrupt size field asked for 1.9 GB. Both decoders must refuse it first.
TEST(SequenceCorruption, HeaderAttributeClaimingMoreThanTheFileIsRejectedBeforeAllocation) {
  const auto folder = fresh_folder("oversized_attribute");
  write_test_sequence(folder, 1, FrameEncoding{Compression::kZip, Precision::kHalf, Precision::kFloat, Precision::kHalf},
                      test_geometry(9, 7));
  const SequenceManifest manifest = parse_manifest(read_file_bytes(folder / "manifest.json"), "manifest.json");
  std::string bytes = read_file_bytes(folder / "frame_000000.exr");
  // The first attribute starts after magic + version: "name\0type\0" then its int32 size.
  const std::size_t name_end = bytes.find('\0', 8);
  const std::size_t type_end = bytes.find('\0', name_end + 1);
  ASSERT_NE(type_end, std::string::npos);
  const std::uint32_t huge = 0x73000000u;  // 1.9 GB
  std::memcpy(bytes.data() + type_end + 1, &huge, sizeof huge);  // little-endian, as EXR is
  Frame frame;
  const std::string message = error_message_of([&] {
    decode_frame(std::as_bytes(std::span(bytes.data(), bytes.size())), "frame_000000.exr", manifest, 0,
                 ChannelSelection::all(), frame);
  });
  EXPECT_NE(message.find("claims 1929379840 bytes"), std::string::npos) << message;
  EXPECT_NE(message.find("frame_000000.exr"), std::string::npos) << message;
  // The same through the file reader (row stripes), without checksum verification.
  overwrite(folder / "frame_000000.exr", bytes);
  const SequenceReader reader(folder);
  const std::string rows_message = error_message_of([&] { reader.read_frame_rows(0, 0, 3, frame, ChannelSelection::all()); });
  EXPECT_NE(rows_message.find("claims"), std::string::npos) << rows_message;
}

// Found by the libFuzzer target with -malloc_limit_mb=500: OpenEXR sizes a compressed file's line
// buffers from the data window while it opens the file, so a bent window asked for 566 MB before
// the header could be compared with the manifest. Both decoders must refuse the window first.
TEST(SequenceCorruption, DataWindowLargerThanTheGridIsRejectedBeforeAllocation) {
  const auto folder = fresh_folder("oversized_window");
  write_test_sequence(folder, 1, FrameEncoding{Compression::kZip, Precision::kHalf, Precision::kFloat, Precision::kHalf},
                      test_geometry(9, 7));
  const SequenceManifest manifest = parse_manifest(read_file_bytes(folder / "manifest.json"), "manifest.json");
  std::string bytes = read_file_bytes(folder / "frame_000000.exr");
  const std::string attribute("dataWindow\0box2i\0", 17);
  const std::size_t at = bytes.find(attribute);
  ASSERT_NE(at, std::string::npos);
  const std::int32_t huge_column = 1 << 24;  // max.x: lines of 16.8 million pixels, 200 MB each
  std::memcpy(bytes.data() + at + attribute.size() + 4 + 8, &huge_column, sizeof huge_column);
  Frame frame;
  const std::string message = error_message_of([&] {
    decode_frame(std::as_bytes(std::span(bytes.data(), bytes.size())), "frame_000000.exr", manifest, 0,
                 ChannelSelection::all(), frame);
  });
  EXPECT_NE(message.find("header data window of pixels (0, 0)-(16777216, 6) but the grid is 9 x 7"), std::string::npos)
      << message;
  overwrite(folder / "frame_000000.exr", bytes);
  const SequenceReader reader(folder);
  const std::string rows_message = error_message_of([&] { reader.read_frame_rows(0, 0, 3, frame, ChannelSelection::all()); });
  EXPECT_NE(rows_message.find("header data window"), std::string::npos) << rows_message;
}

// Issue 13 item 4: a NaN or an infinity in a frame must stop the reader even without checksum
// verification (the loop inspector took a NaN distance for a perfect seam, the player drew a wall).
// Both decoders (NONE: nearshore's own; ZIP: OpenEXR's) and the row-stripe reader are checked, on
// frames the sequence writer wrote: an elevation of 1e6 m is a finite float, which the half channel
// stores as +infinity; and a NaN written over one float flux sample of an uncompressed frame.
class NonFiniteFrame : public ::testing::TestWithParam<Compression> {};

TEST_P(NonFiniteFrame, IsRejectedNamingTheFrameChannelAndCell) {
  const auto folder = fresh_folder(std::string("non_finite_") + std::string(compression_name(GetParam())));
  const GridGeometry geometry = test_geometry(19, 11);
  {
    SequenceWriter writer(folder, test_harbour(geometry),
                          test_description(FrameEncoding{GetParam(), Precision::kHalf, Precision::kFloat, Precision::kHalf}));
    for (int index = 0; index < 3; ++index) {
      TestFields fields(geometry, index);
      if (index == 1) fields.eta(5, 3) = 1.0e6f;  // beyond half's largest value 65504: stored as inf
      writer.write_frame(index, fields.fields());
    }
    writer.finish(3);
  }
  const SequenceReader reader(folder);
  const std::string message = error_message_of([&] { reader.read_frame(1); });
  EXPECT_NE(message.find("frame_000001.exr"), std::string::npos) << message;
  EXPECT_NE(message.find("channel 'surface_elevation' holds inf at cell (column 5, row 3; x 500022.0 m, y 4300014.0 m)"),
            std::string::npos)
      << message;
  // Only the channels asked for are decoded, and only those are checked.
  EXPECT_NO_THROW(reader.read_frame(1, ChannelSelection{false, true, true, true}));
  EXPECT_NO_THROW(reader.read_frame(0));
  EXPECT_NO_THROW(reader.read_frame(2));
  // The row-stripe reader (OpenEXR's decoder whatever the compression) names the cell in grid rows.
  Frame stripe;
  const std::string rows_message = error_message_of([&] { reader.read_frame_rows(1, 2, 4, stripe, ChannelSelection::all()); });
  EXPECT_NE(rows_message.find("frame_000001.exr"), std::string::npos) << rows_message;
  EXPECT_NE(rows_message.find("(column 5, row 3;"), std::string::npos) << rows_message;
  EXPECT_NO_THROW(reader.read_frame_rows(1, 4, 7, stripe, ChannelSelection::all()));

  if (GetParam() != Compression::kNone) return;
  // An uncompressed frame altered on disk: frame 2's flux_x sample at cell (11, 7) becomes a NaN.
  // The flux is stored as float, so the sample's four bytes appear as they are in the raster.
  const fs::path path = folder / "frame_000002.exr";
  std::string bytes = read_file_bytes(path);
  const float sample = TestFields(geometry, 2).p(11, 7);
  const std::string pattern(reinterpret_cast<const char*>(&sample), sizeof sample);
  const std::size_t at = bytes.find(pattern);
  ASSERT_NE(at, std::string::npos);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(bytes.data() + at, &nan, sizeof nan);
  overwrite(path, bytes);
  const std::string nan_message = error_message_of([&] { reader.read_frame(2); });
  EXPECT_NE(nan_message.find("frame_000002.exr: channel 'flux_x' holds nan at cell (column 11, row 7;"), std::string::npos)
      << nan_message;
  const std::string nan_rows_message = error_message_of([&] { reader.read_frame_rows(2, 0, 11, stripe, ChannelSelection::all()); });
  EXPECT_NE(nan_rows_message.find("channel 'flux_x' holds nan at cell (column 11, row 7;"), std::string::npos)
      << nan_rows_message;
}

INSTANTIATE_TEST_SUITE_P(Codecs, NonFiniteFrame, ::testing::Values(Compression::kNone, Compression::kZip),
                         [](const auto& info) { return std::string(compression_name(info.param)); });

// A deterministic mutation fuzz of both readers (the libFuzzer targets in tests/sequence/fuzz run
// the same entry points for longer): random byte flips, insertions, deletions and truncations of a
// valid manifest and a valid frame. Every outcome must be a clean parse or a nearshore::Error; a
// crash, hang or other exception fails (and the asan build catches memory errors).
// Both frame decoders are fuzzed: OpenEXR's (ZIP) and nearshore's own reader of uncompressed
// frames (NONE, the default), whose offsets and sizes must all be bounds-checked.
class SequenceFuzz : public ::testing::TestWithParam<Compression> {};

TEST_P(SequenceFuzz, MutatedManifestsAndFramesFailCleanly) {
  const auto folder = fresh_folder(std::string("fuzz_") + std::string(compression_name(GetParam())));
  write_test_sequence(folder, 1, FrameEncoding{GetParam(), Precision::kHalf, Precision::kFloat, Precision::kHalf},
                      test_geometry(9, 7));
  const std::string manifest_text = read_file_bytes(folder / "manifest.json");
  const std::string frame_bytes = read_file_bytes(folder / "frame_000000.exr");
  const SequenceManifest manifest = parse_manifest(manifest_text, "manifest.json");
  std::mt19937_64 random(20261122);
  auto mutate = [&](std::string bytes) {
    const int edits = 1 + static_cast<int>(random() % 4);
    for (int e = 0; e < edits && !bytes.empty(); ++e) {
      const std::size_t at = random() % bytes.size();
      switch (random() % 4) {
        case 0: bytes[at] = static_cast<char>(bytes[at] ^ (1 << (random() % 8))); break;
        case 1: bytes.insert(at, 1, static_cast<char>(random())); break;
        case 2: bytes.erase(at, 1 + random() % 8); break;
        default: bytes.resize(at); break;
      }
    }
    return bytes;
  };
  int manifests_rejected = 0, frames_rejected = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    try {
      parse_manifest(mutate(manifest_text), "manifest.json");
    } catch (const Error&) {
      ++manifests_rejected;
    }
    const std::string bytes = mutate(frame_bytes);
    Frame frame;
    try {
      decode_frame(std::as_bytes(std::span(bytes.data(), bytes.size())), "frame_000000.exr", manifest, 0,
                   ChannelSelection::all(), frame);
    } catch (const Error&) {
      ++frames_rejected;
    }
  }
  // Most mutations must be noticed (not a silent garbage read of the header).
  EXPECT_GT(manifests_rejected, 500);
  EXPECT_GT(frames_rejected, 300);
}

INSTANTIATE_TEST_SUITE_P(Codecs, SequenceFuzz, ::testing::Values(Compression::kNone, Compression::kZip),
                         [](const auto& info) { return std::string(compression_name(info.param)); });

}  // namespace
}  // namespace nearshore::sequence
