// The frame codecs a case file may ask for ([output] frame_compression): every name nearshore
// writes survives the manifest, an unknown one is refused with the list, and PXR24's rounding of
// float channels stays within its 24-bit bound.
#include <Imath/half.h>

#include <gtest/gtest.h>

#include "nearshore/core/error.hpp"
#include "nearshore/sequence/sequence_reader.hpp"
#include "test_sequence.hpp"

namespace nearshore::sequence::testing {
namespace {

TEST(SequenceCodecs, EveryCodecNameRoundTripsThroughTheManifest) {
  ASSERT_GE(all_compressions().size(), 8u);
  for (Compression compression : all_compressions()) {
    EXPECT_EQ(parse_compression(compression_name(compression)), compression) << compression_name(compression);
    const auto folder = fresh_folder(std::string("codec_") + std::string(compression_name(compression)));
    write_test_sequence(folder, 1, FrameEncoding{compression, Precision::kHalf, Precision::kFloat, Precision::kHalf});
    const SequenceReader reader(folder);
    EXPECT_EQ(reader.manifest().encoding.compression, compression);
    EXPECT_EQ(reader.manifest().encoding.flux, Precision::kFloat);
    EXPECT_NO_THROW(reader.read_frame(0, ChannelSelection::all(), Verify::kYes)) << compression_name(compression);
  }
}

TEST(SequenceCodecs, AnUnknownCodecNamesEveryKnownOne) {
  try {
    parse_compression("zstd");
    FAIL() << "zstd was accepted";
  } catch (const Error& error) {
    for (Compression compression : all_compressions())
      EXPECT_NE(error.fix().find(compression_name(compression)), std::string::npos) << error.what();
  }
}

// PXR24 keeps the sign, the 8 exponent bits and the top 15 mantissa bits of a float, rounded to
// nearest (OpenEXR's ImfPxr24Compressor.cpp): relative error <= 2^-16. The bound 2^-15 leaves a
// factor 2 for the rounding of the last kept bit; half channels stay exact (round-trip test).
TEST(SequenceCodecs, Pxr24RoundsFloatChannelsToTwentyFourBits) {
  const GridGeometry geometry = test_geometry();
  const TestFields expected(geometry, 1);
  const auto folder = fresh_folder("codec_pxr24_float");
  write_test_sequence(folder, 2, FrameEncoding{Compression::kPxr24, Precision::kFloat, Precision::kFloat, Precision::kHalf});
  const Frame frame = SequenceReader(folder).read_frame(1);
  double worst_relative = 0;
  bool any_rounded = false;
  for (std::size_t k = 0; k < expected.eta.size(); ++k) {
    const double exact = expected.eta.values()[k], stored = frame.surface_elevation_m.values()[k];
    if (exact != 0) worst_relative = std::max(worst_relative, std::abs(stored - exact) / std::abs(exact));
    any_rounded = any_rounded || stored != exact;
  }
  EXPECT_LE(worst_relative, std::ldexp(1.0, -15));
  EXPECT_TRUE(any_rounded) << "PXR24 stored every float exactly: is it still the codec written?";
}

}  // namespace
}  // namespace nearshore::sequence::testing
