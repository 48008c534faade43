#include <gtest/gtest.h>

#include <Imath/half.h>

#include <cmath>
#include <fstream>

#include "nearshore/core/error.hpp"
#include "nearshore/sequence/sequence_reader.hpp"
#include "test_sequence.hpp"

namespace nearshore::sequence {
namespace {
using namespace testing;

double max_difference(const Raster<float>& a, const Raster<float>& b) {
  EXPECT_EQ(a.columns(), b.columns());
  EXPECT_EQ(a.rows(), b.rows());
  double worst = 0;
  for (std::size_t k = 0; k < a.size() && k < b.size(); ++k)
    worst = std::max(worst, std::abs(double(a.values()[k]) - double(b.values()[k])));
  return worst;
}

TEST(SequenceRoundTrip, FloatFramesComeBackBitExactWithManifest) {
  const auto folder = fresh_folder("float");
  const FrameEncoding encoding{Compression::kZip, Precision::kFloat, Precision::kFloat, Precision::kFloat};
  write_test_sequence(folder, 5, encoding);
  const SequenceReader reader(folder);
  EXPECT_EQ(reader.frame_count(), 5);
  EXPECT_EQ(reader.manifest().seed, 0xfeedbeefcafe1234ULL);
  EXPECT_DOUBLE_EQ(reader.frame_interval_s(), 0.25);
  EXPECT_DOUBLE_EQ(reader.geometry().origin_y_m, 4300000.0);
  EXPECT_EQ(reader.manifest().wave_conditions["period_s"], 8.0);
  EXPECT_EQ(reader.manifest().encoding.compression, Compression::kZip);
  const GridGeometry geometry = test_geometry();
  for (int index : {3, 0, 4}) {  // random access, any order
    const Frame frame = reader.read_frame(index, ChannelSelection::all(), Verify::kYes);
    const TestFields expected(geometry, index);
    EXPECT_EQ(frame.index, index);
    EXPECT_DOUBLE_EQ(frame.time_s, 30.0 + 0.25 * index);
    EXPECT_EQ(max_difference(frame.surface_elevation_m, expected.eta), 0.0);
    EXPECT_EQ(max_difference(frame.flux_x_m2_s, expected.p), 0.0);
    EXPECT_EQ(max_difference(frame.flux_y_m2_s, expected.q), 0.0);
    EXPECT_EQ(max_difference(frame.breaking, expected.breaking), 0.0);
  }
  const HarbourGrid harbour = reader.read_harbour_grid(Verify::kYes);
  EXPECT_EQ(harbour.land(0, geometry.rows - 1), 1);  // the quay is in the north, not flipped south
  EXPECT_EQ(harbour.land(0, 0), 0);
  EXPECT_FLOAT_EQ(harbour.still_water_depth_m(3, 4), 3.0f);
  reader.verify_checksums();
}

// Issue 41: the harbour grid's surroundings (the ground round it, coarser cells over a larger box,
// a second part of depth.exr) travel with the sequence and come back exactly, no-data cells (NaN)
// included; a sequence without them reads as before (the manifest does not change: depth.exr is
// one file with one checksum, its first part the grid a reader of one part reads).
TEST(SequenceRoundTrip, TheHarbourGridsSurroundingsComeBackExactly) {
  const auto folder = fresh_folder("surroundings");
  const GridGeometry geometry = test_geometry();
  HarbourGrid harbour = test_harbour(geometry);
  Surroundings& outer = harbour.surroundings;
  outer.geometry = geometry;
  outer.geometry.spacing_m = 16.0;
  outer.geometry.columns = 30;
  outer.geometry.rows = 20;
  outer.geometry.origin_x_m = geometry.origin_x_m - 166.0;
  outer.geometry.origin_y_m = geometry.origin_y_m - 114.0;
  outer.still_water_depth_m = Raster<float>(30, 20);
  for (int row = 0; row < 20; ++row)
    for (int column = 0; column < 30; ++column)
      outer.still_water_depth_m(column, row) = column > 25 ? NAN : 12.0f - 0.75f * float(row) + 0.01f * float(column);
  {
    SequenceWriter writer(folder, harbour, test_description());
    for (int index = 0; index < 2; ++index) writer.write_frame(index, TestFields(geometry, index).fields());
    writer.finish(2);
  }
  const SequenceReader reader(folder);
  const HarbourGrid again = reader.read_harbour_grid(Verify::kYes);
  EXPECT_EQ(again.still_water_depth_m.values(), harbour.still_water_depth_m.values());
  ASSERT_FALSE(again.surroundings.empty());
  EXPECT_EQ(nlohmann::json(again.surroundings.geometry), nlohmann::json(outer.geometry));
  for (int row = 0; row < 20; ++row)
    for (int column = 0; column < 30; ++column) {
      const float a = again.surroundings.still_water_depth_m(column, row), b = outer.still_water_depth_m(column, row);
      EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << column << ", " << row;
    }
  reader.verify_checksums();
  // Without surroundings: one part, as before.
  const auto plain = fresh_folder("no-surroundings");
  write_test_sequence(plain, 1);
  EXPECT_TRUE(SequenceReader(plain).read_harbour_grid(Verify::kYes).surroundings.empty());
}

// Surroundings that miss the grid, or are not in its projection, are refused naming the file's
// part and the boxes.
TEST(SequenceRoundTrip, SurroundingsThatMissTheGridAreRefusedNamingThePart) {
  const auto folder = fresh_folder("surroundings-bad");
  std::filesystem::create_directories(folder);
  const GridGeometry geometry = test_geometry();
  HarbourGrid harbour = test_harbour(geometry);
  harbour.surroundings.geometry = geometry;
  harbour.surroundings.geometry.origin_x_m += 200.0;  // east of the grid's 148 m
  harbour.surroundings.still_water_depth_m = Raster<float>(geometry.columns, geometry.rows, 5.0f);
  write_harbour_grid(folder / "depth.exr", harbour);
  try {
    read_harbour_grid(folder / "depth.exr");
    FAIL() << "surroundings that miss the grid were read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("part 1, \"surroundings\""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("do not overlap the grid's"), std::string::npos) << e.what();
  }
  harbour.surroundings.geometry = geometry;
  harbour.surroundings.geometry.projection = {{"kind", "utm"}, {"zone", 50}, {"north", true}};
  write_harbour_grid(folder / "depth.exr", harbour);
  EXPECT_THROW(read_harbour_grid(folder / "depth.exr"), Error);
}

// Issue 15: rectangular cells. The manifest records both spacings (and no "spacing_m", so a reader
// that predates them refuses the file instead of taking dx for dy); a square grid's manifest keeps
// the one key it always had, and both read back.
TEST(SequenceRoundTrip, RectangularCellsRecordBothSpacings) {
  const auto read_manifest_geometry = [](const std::filesystem::path& folder) {
    std::ifstream in(folder / "manifest.json");
    return nlohmann::json::parse(in).at("geometry");
  };
  GridGeometry rectangular = test_geometry();
  rectangular.set_spacing(4.0, 8.0);
  const auto folder = fresh_folder("rectangular");
  write_test_sequence(folder, 2, {Compression::kZip, Precision::kFloat, Precision::kFloat, Precision::kFloat}, rectangular);
  const nlohmann::json recorded = read_manifest_geometry(folder);
  EXPECT_FALSE(recorded.contains("spacing_m"));
  EXPECT_EQ(recorded.at("spacing_x_m"), 4.0);
  EXPECT_EQ(recorded.at("spacing_y_m"), 8.0);
  const SequenceReader reader(folder);
  EXPECT_DOUBLE_EQ(reader.geometry().spacing_x_m(), 4.0);
  EXPECT_DOUBLE_EQ(reader.geometry().spacing_y_m(), 8.0);
  EXPECT_DOUBLE_EQ(reader.geometry().height_m(), 8.0 * rectangular.rows);
  const HarbourGrid harbour = reader.read_harbour_grid(Verify::kYes);
  EXPECT_DOUBLE_EQ(harbour.geometry.spacing_y_m(), 8.0);
  EXPECT_EQ(max_difference(reader.read_frame(1, ChannelSelection::all(), Verify::kYes).surface_elevation_m,
                           TestFields(rectangular, 1).eta), 0.0);

  const auto square_folder = fresh_folder("square_spacing");
  write_test_sequence(square_folder, 1);
  const nlohmann::json square = read_manifest_geometry(square_folder);
  EXPECT_EQ(square.at("spacing_m"), 4.0);
  EXPECT_FALSE(square.contains("spacing_x_m"));
  EXPECT_TRUE(SequenceReader(square_folder).geometry().square_cells());
}

// Half keeps 11 significant bits: relative error <= 2^-11 after round-to-nearest (half of the
// 2^-10 spacing). Every lossless compression must return exactly the half values (PXR24 rounds
// only 32-bit floats; on half channels it is lossless).
TEST(SequenceRoundTrip, HalfFramesAreWithinHalfRoundingForLosslessCompressions) {
  const GridGeometry geometry = test_geometry();
  const TestFields expected(geometry, 2);
  for (Compression compression : {Compression::kNone, Compression::kZip, Compression::kPiz, Compression::kRle,
                                   Compression::kZips, Compression::kPxr24}) {
    const auto folder = fresh_folder(std::string("half_") + std::string(compression_name(compression)));
    write_test_sequence(folder, 3, FrameEncoding{compression, Precision::kHalf, Precision::kHalf, Precision::kHalf});
    const Frame frame = SequenceReader(folder).read_frame(2);
    for (std::size_t k = 0; k < expected.eta.size(); ++k) {
      ASSERT_EQ(frame.surface_elevation_m.values()[k], float(half(expected.eta.values()[k]))) << compression_name(compression);
      ASSERT_EQ(frame.flux_x_m2_s.values()[k], float(half(expected.p.values()[k])));
    }
  }
}

// Lossy codecs decode, with errors of the size the compression table in docs/formats/sequence.md
// reports. B44 quantises 4x4 blocks in the ordered bit space of half, which is very uneven for a
// signed field crossing zero: ~20 % of the 0.6 m amplitude here (bound 0.15 m), which is why it
// is not the default. DWAA (DCT, default level 45) stays under 2 % of the amplitude (12 mm).
TEST(SequenceRoundTrip, LossyCompressionsDecodeWithTheirKnownErrors) {
  const GridGeometry geometry = test_geometry();
  const TestFields expected(geometry, 1);
  const std::pair<Compression, double> bounds[] = {{Compression::kB44, 0.15}, {Compression::kDwaa, 0.012}};
  for (const auto& [compression, bound_m] : bounds) {
    const auto folder = fresh_folder(std::string("lossy_") + std::string(compression_name(compression)));
    write_test_sequence(folder, 2, FrameEncoding{compression, Precision::kHalf, Precision::kHalf, Precision::kHalf});
    const Frame frame = SequenceReader(folder).read_frame(1, ChannelSelection::all(), Verify::kYes);
    EXPECT_LT(max_difference(frame.surface_elevation_m, expected.eta), bound_m) << compression_name(compression);
  }
}

TEST(SequenceRoundTrip, RowStripesEqualTheFullFrame) {
  const auto folder = fresh_folder("rows");
  write_test_sequence(folder, 2, FrameEncoding{Compression::kZip, Precision::kFloat, Precision::kFloat, Precision::kFloat});
  const SequenceReader reader(folder);
  const Frame full = reader.read_frame(1);
  Frame stripe;
  for (int first_row : {0, 5, 17}) {
    const int count = std::min(6, reader.geometry().rows - first_row);
    reader.read_frame_rows(1, first_row, count, stripe, ChannelSelection::dynamics());
    ASSERT_EQ(stripe.surface_elevation_m.rows(), count);
    EXPECT_TRUE(stripe.breaking.empty());
    for (int row = 0; row < count; ++row)
      for (int column = 0; column < reader.geometry().columns; ++column) {
        ASSERT_EQ(stripe.surface_elevation_m(column, row), full.surface_elevation_m(column, first_row + row));
        ASSERT_EQ(stripe.flux_y_m2_s(column, row), full.flux_y_m2_s(column, first_row + row));
      }
  }
}

TEST(SequenceWriter, ManifestAppearsOnlyAtFinishAndMissingFramesAreRefused) {
  const auto folder = fresh_folder("unfinished");
  const GridGeometry geometry = test_geometry();
  SequenceWriter writer(folder, test_harbour(geometry), test_description());
  writer.write_frame(0, TestFields(geometry, 0).fields());
  writer.write_frame(2, TestFields(geometry, 2).fields());
  EXPECT_FALSE(std::filesystem::exists(folder / "manifest.json"));
  EXPECT_THROW(SequenceReader{folder}, Error);
  try {
    writer.finish(3);
    FAIL() << "finish with a missing frame must throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("frame 1 of 3 was never written"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(folder / "manifest.json"));
  writer.write_frame(1, TestFields(geometry, 1).fields());
  writer.finish(3);
  EXPECT_EQ(SequenceReader(folder).frame_count(), 3);
}

TEST(SequenceWriter, NonFiniteFieldIsRefusedWithItsCellAndNothingIsWritten) {
  const auto folder = fresh_folder("nan");
  const GridGeometry geometry = test_geometry();
  SequenceWriter writer(folder, test_harbour(geometry), test_description());
  TestFields fields(geometry, 0);
  fields.p(7, 4) = std::nanf("");
  try {
    writer.write_frame(0, fields.fields());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("flux_x is nan at cell (7, 4)"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(folder / "frame_000000.exr"));
  Raster<float> wrong_size(3, 3);
  FrameFields bad = fields.fields();
  bad.surface_elevation_m = &wrong_size;
  EXPECT_THROW(writer.write_frame(0, bad), Error);
}

TEST(SequenceWriter, ResumeKeepsEarlierFramesAndRewritesLaterOnes) {
  const auto folder = fresh_folder("resume");
  const GridGeometry geometry = test_geometry();
  const FrameEncoding exact{Compression::kZip, Precision::kFloat, Precision::kFloat, Precision::kFloat};
  {
    SequenceWriter first(folder, test_harbour(geometry), test_description(exact));
    for (int index = 0; index < 4; ++index) first.write_frame(index, TestFields(geometry, index).fields());
    // "crash": no finish()
  }
  SequenceWriter resumed(folder, test_harbour(geometry), test_description(exact), /*resume=*/true);
  for (int index = 2; index < 3; ++index) resumed.write_frame(index, TestFields(geometry, index).fields());
  resumed.finish(3);  // frames 0, 1 from the first run; frame 3 of the first run is dropped
  EXPECT_FALSE(std::filesystem::exists(folder / "frame_000003.exr"));
  const SequenceReader reader(folder);
  reader.verify_checksums();
  EXPECT_EQ(max_difference(reader.read_frame(1).flux_x_m2_s, TestFields(geometry, 1).p), 0.0);
  // Without resume, old frames are cleared and the folder starts over.
  SequenceWriter fresh(folder, test_harbour(geometry), test_description(exact));
  EXPECT_FALSE(std::filesystem::exists(folder / "frame_000000.exr"));
  EXPECT_FALSE(std::filesystem::exists(folder / "manifest.json"));
}

}  // namespace
}  // namespace nearshore::sequence
