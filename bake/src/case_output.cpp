// [output]: how a bake stores its frames and which maps it writes beside them (docs/commands/bake.md,
// "[output]"). Every key is optional; the defaults are the measured ones (docs/formats/sequence.md,
// "Compression: measured, and the default") and half channels.
//
//   frame_compression = "none" | "zip" | "zips" | "rle" | "piz" | "pxr24" | "b44" | "dwaa"
//   frame_precision   = "half" | "float"                      (every channel)
//                     | { surface_elevation = "float", flux = "half", breaking = "half" }
//   wave_statistics   = true | false                          (DIR/wave_statistics.tif and
//                                                              DIR/wave_statistics_runup.geojson)
#include "case_reader.hpp"

#include "nearshore/sequence/sequence_format.hpp"

namespace nearshore::bake::detail {
namespace {

const std::vector<std::string> kPrecisionNames = {"half", "float"};

sequence::Precision precision_from_index(std::size_t index) {
  return index == 0 ? sequence::Precision::kHalf : sequence::Precision::kFloat;
}

// frame_precision: one name for every channel, or a table naming channels (the others keep half).
// Both flux components share one precision, as the manifest records them (sequence_format.cpp).
void read_frame_precision(TableReader& output, sequence::FrameEncoding& encoding) {
  if (!output.has_table("frame_precision")) {
    const std::size_t all = output.choice("frame_precision", "half", kPrecisionNames);
    encoding.surface_elevation = encoding.flux = encoding.breaking = precision_from_index(all);
    return;
  }
  TableReader channels = output.table("frame_precision");
  encoding.surface_elevation = precision_from_index(channels.choice("surface_elevation", "half", kPrecisionNames));
  encoding.flux = precision_from_index(channels.choice("flux", "half", kPrecisionNames));
  encoding.breaking = precision_from_index(channels.choice("breaking", "half", kPrecisionNames));
  channels.finish();
}

}  // namespace

BakeOutput read_output(TableReader& output) {
  BakeOutput result;
  std::vector<std::string> codec_names;
  for (sequence::Compression compression : sequence::all_compressions())
    codec_names.emplace_back(sequence::compression_name(compression));
  const std::string default_codec(sequence::compression_name(result.frame_encoding.compression));
  result.frame_encoding.compression =
      sequence::all_compressions()[output.choice("frame_compression", default_codec, codec_names)];
  read_frame_precision(output, result.frame_encoding);
  result.wave_statistics = output.boolean("wave_statistics", false);  // bake_case.hpp: memory
  return result;
}

}  // namespace nearshore::bake::detail
