// The displacement EXRs read back by OpenEXR: one file per frame, numbered by the frame's index;
// B = eta, R = the excursion of the linear wave, G = 0, A = water; zero with a reason for one frame.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "export_test_support.hpp"
#include "nearshore/export/export_sequence.hpp"

namespace nearshore::exports {
namespace {
using testing::TestWave;
namespace fs = std::filesystem;

struct Displacement {
  std::vector<float> rgba;  // line 0 north, 4 floats a pixel
  std::string horizontal;
  float at(int column, int row, int channel) const {
    return rgba[(static_cast<std::size_t>(TestWave::kRows - 1 - row) * TestWave::kColumns + column) * 4 + channel];
  }
};

Displacement read_displacement(const fs::path& file) {
  Imf::InputFile input(file.c_str());
  const Imath::Box2i window = input.header().dataWindow();
  EXPECT_EQ(window.max.x - window.min.x + 1, TestWave::kColumns);
  EXPECT_EQ(window.max.y - window.min.y + 1, TestWave::kRows);
  for (const char* name : {"R", "G", "B", "A"}) {
    const Imf::Channel* channel = input.header().channels().findChannel(name);
    EXPECT_TRUE(channel && channel->type == Imf::FLOAT) << name;
  }
  Displacement result;
  result.rgba.resize(static_cast<std::size_t>(TestWave::kColumns) * TestWave::kRows * 4);
  Imf::FrameBuffer buffer;
  const std::size_t pixel = 4 * sizeof(float), line = pixel * TestWave::kColumns;
  const char* names[4] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c)
    buffer.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(result.rgba.data() + c), pixel, line));
  input.setFrameBuffer(buffer);
  input.readPixels(window.min.y, window.max.y);
  result.horizontal = input.header().typedAttribute<Imf::StringAttribute>("nearshore_horizontal_displacement").value();
  return result;
}

// Frames 20 .. 59 (two whole periods): R against xi = -(a / (k d)) sin(k x - w t), 1.5 % of a / (k d)
// (statistics_test.cpp gives the error budget); B is eta exactly (float frames); land is 0 with A = 0.
TEST(ExportExrDisplacement, FramesCarryEtaAndTheExcursionOfTheFluxes) {
  const fs::path folder = testing::scratch_folder();
  TestWave::write(folder / "sequence");
  const ExportSummary summary =
      export_sequence({folder / "sequence", folder / "out", ExportFormat::kExrDisplacement, {20, 60}});
  ASSERT_EQ(summary.files.size(), 40u);
  EXPECT_EQ(summary.files.front().file.filename(), "displacement_000020.exr");
  EXPECT_EQ(summary.files.back().file.filename(), "displacement_000059.exr");
  EXPECT_NE(summary.horizontal_displacement.find("depth-averaged"), std::string::npos);
  const double amplitude_m = TestWave::kAmplitude_m / (TestWave::k_rad_m * TestWave::kDepth_m);
  for (int index : {20, 33, 59}) {
    const Displacement d = read_displacement(folder / "out" / fs::path("displacement_0000" + std::to_string(index) + ".exr"));
    EXPECT_EQ(d.horizontal, summary.horizontal_displacement);
    const double t = TestWave::frame_time_s(index);
    for (int row = 0; row < TestWave::kRows; ++row)
      for (int column = 0; column < TestWave::kColumns; ++column) {
        if (TestWave::is_land(column, row)) {
          for (int c = 0; c < 4; ++c) EXPECT_EQ(d.at(column, row, c), 0.0f);
          continue;
        }
        const double x = (column + 0.5) * TestWave::kSpacing_m;
        EXPECT_NEAR(d.at(column, row, 0), -amplitude_m * std::sin(TestWave::k_rad_m * x - TestWave::omega_rad_s * t),
                    0.015 * amplitude_m);
        EXPECT_NEAR(d.at(column, row, 1), 0.0, 1e-9);
        EXPECT_NEAR(d.at(column, row, 2), TestWave::elevation_m(column, row, t), 1e-6);
        EXPECT_EQ(d.at(column, row, 3), 1.0f);
      }
  }
}

TEST(ExportExrDisplacement, OneFrameHasZeroHorizontalShiftAndSaysWhy) {
  const fs::path folder = testing::scratch_folder();
  TestWave::write(folder / "sequence");
  const ExportSummary summary =
      export_sequence({folder / "sequence", folder / "out", ExportFormat::kExrDisplacement, {7, 8}});
  ASSERT_EQ(summary.files.size(), 1u);
  EXPECT_EQ(summary.horizontal_displacement.rfind("zero:", 0), 0u) << summary.horizontal_displacement;
  const Displacement d = read_displacement(folder / "out" / "displacement_000007.exr");
  EXPECT_EQ(d.horizontal, summary.horizontal_displacement);
  EXPECT_EQ(d.at(5, 5, 0), 0.0f);
  EXPECT_NEAR(d.at(5, 5, 2), TestWave::elevation_m(5, 5, TestWave::frame_time_s(7)), 1e-6);
}

}  // namespace
}  // namespace nearshore::exports
