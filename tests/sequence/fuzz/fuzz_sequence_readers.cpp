// libFuzzer target for the sequence readers (ctest label `fuzz`, a bounded run). The input is
// either used raw or, for deeper coverage, as a list of edits (position, xor byte) and a cut
// applied to a valid frame or manifest made at start-up: both the OpenEXR path (ZIP) and
// nearshore's own uncompressed reader (NONE) are reached. Every input must end in success or a
// nearshore::Error; anything else (crash, sanitizer report, other exception) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "../../../sequence/src/exr_frame.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/sequence/sequence_format.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

using namespace nearshore;
using namespace nearshore::sequence;

namespace {

struct Seeds {
  SequenceManifest manifest;
  std::string manifest_text;
  std::string frames[2];  // NONE, ZIP
};

const Seeds& seeds() {
  static const Seeds made = [] {
    Seeds s;
    GridGeometry geometry;
    geometry.columns = 11;
    geometry.rows = 6;
    geometry.spacing_m = 3;
    s.manifest.geometry = geometry;
    s.manifest.frame_count = 1;
    s.manifest.frame_interval_s = 0.5;
    s.manifest.harbour_grid = {"depth.exr", 100, "xxh64:0123456789abcdef"};
    s.manifest.frames = {{"frame_000000.exr", 100, "xxh64:0123456789abcdef"}};
    s.manifest_text = manifest_to_json(s.manifest).dump();
    Raster<float> field(geometry.columns, geometry.rows);
    for (std::size_t k = 0; k < field.size(); ++k) field.values()[k] = 0.01f * static_cast<float>(k);
    const std::array<const Raster<float>*, 4> channels = {&field, &field, &field, &field};
    FrameEncoding encoding;
    encoding.flux = Precision::kFloat;
    encoding.compression = Compression::kNone;
    s.frames[0] = detail::encode_frame(geometry, encoding, 0, 0.0, channels);
    encoding.compression = Compression::kZip;
    s.frames[1] = detail::encode_frame(geometry, encoding, 0, 0.0, channels);
    return s;
  }();
  return made;
}

std::string edited(std::string base, const std::uint8_t* data, std::size_t size) {
  for (std::size_t k = 0; k + 3 <= size; k += 3) {
    const std::size_t at = (static_cast<std::size_t>(data[k]) << 8 | data[k + 1]) % (base.size() + 1);
    if (data[k + 2] == 0)
      base.resize(at);  // a cut
    else if (at < base.size())
      base[at] = static_cast<char>(base[at] ^ data[k + 2]);
  }
  return base;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const Seeds& s = seeds();
  const int mode = data[0] % 4;
  ++data;
  --size;
  try {
    if (mode == 0) {
      parse_manifest(std::string(reinterpret_cast<const char*>(data), size), "manifest.json");
    } else if (mode == 1) {
      parse_manifest(edited(s.manifest_text, data, size), "manifest.json");
    } else {
      const std::string bytes = edited(s.frames[mode - 2], data, size);
      Frame frame;
      decode_frame(std::as_bytes(std::span(bytes.data(), bytes.size())), "frame_000000.exr", s.manifest, 0,
                   ChannelSelection::all(), frame);
    }
  } catch (const Error&) {
  }
  return 0;
}
