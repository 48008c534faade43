#include <gtest/gtest.h>

#include <cmath>

#include "loops_test_support.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/loops/distance.hpp"
#include "nearshore/loops/synthetic_sea.hpp"

namespace nearshore::loops {
namespace {
using namespace testing;

// The streamed block-Gram distances equal brute-force pairwise norms of the decoded frames.
// Tolerance 1e-9 of the largest distance: the Gram route loses digits to cancellation in
// G_ii + G_jj - 2 G_ij, about sqrt(eps) of |f|^2 at worst for nearly equal frames, far below.
TEST(Distance, StreamedGramMatchesBruteForceAcrossStripes) {
  const auto folder = fresh_folder("brute_force");
  const GridGeometry geometry = small_geometry(20, 70);
  write_sea_sequence(folder, irregular_sea(6.0, 8, 1.0, 8.0, 0.3, 7), geometry, 30, 0.5, 0,
                     {sequence::Compression::kZip, sequence::Precision::kFloat, sequence::Precision::kFloat,
                      sequence::Precision::kFloat});
  const sequence::SequenceReader reader(folder);
  GramOptions options;
  options.memory_budget_bytes = 20 * 30 * 3 * sizeof(double) * 20;  // 20 rows per stripe: 4 stripes (one short)
  const GramMatrices gram = compute_gram_matrices(reader, options);
  const DistanceMatrices d = distances_from_gram(gram, 0.7);
  std::vector<sequence::Frame> frames;
  for (int k = 0; k < 30; ++k) frames.push_back(reader.read_frame(k));
  double worst_height = 0, worst_motion = 0, worst_volume = 0;
  for (int i = 0; i < 30; ++i) {
    double volume = 0;
    for (float v : frames[i].surface_elevation_m.values()) volume += v * 25.0;
    worst_volume = std::max(worst_volume, std::abs(volume - gram.volume_m3[i]));
    for (int j = 0; j < 30; ++j) {
      double h = 0, p = 0, q = 0;
      for (std::size_t c = 0; c < geometry.cell_count(); ++c) {
        h += std::pow(double(frames[i].surface_elevation_m.values()[c]) - frames[j].surface_elevation_m.values()[c], 2);
        p += std::pow(double(frames[i].flux_x_m2_s.values()[c]) - frames[j].flux_x_m2_s.values()[c], 2);
        q += std::pow(double(frames[i].flux_y_m2_s.values()[c]) - frames[j].flux_y_m2_s.values()[c], 2);
      }
      worst_height = std::max(worst_height, std::abs(std::sqrt(h) - d.height(i, j)));
      worst_motion = std::max(worst_motion, std::abs(std::sqrt(p) + std::sqrt(q) - d.motion(i, j)));
    }
  }
  EXPECT_LT(worst_height, 1e-9 * d.height_scale);
  EXPECT_LT(worst_motion, 1e-9 * d.motion_scale);
  EXPECT_LT(worst_volume, 1e-9 * 20 * 70 * 25.0);
  // eq. (8)-(10): each part normalised to a maximum of 1, D = D_h + delta D_m.
  EXPECT_NEAR((d.height / d.height_scale).maxCoeff(), 1.0, 1e-12);
  EXPECT_NEAR(d.combined(3, 17), d.height(3, 17) / d.height_scale + 0.7 * d.motion(3, 17) / d.motion_scale, 1e-12);
  EXPECT_EQ(d.combined(5, 5), 0.0);
}

TEST(Distance, GramFileRoundTripsExactly) {
  const auto folder = fresh_folder("gram_file");
  GramMatrices gram;
  gram.elevation = Eigen::MatrixXd::Random(5, 5);
  gram.flux_x = Eigen::MatrixXd::Random(5, 5);
  gram.flux_y = Eigen::MatrixXd::Random(5, 5);
  gram.volume_m3 = {1, 2, 3, 4, 5.5};
  gram.cell_area_m2 = 16;
  std::filesystem::create_directories(folder);
  write_gram(folder / "g.bin", gram);
  const GramMatrices back = read_gram(folder / "g.bin", 5);
  EXPECT_EQ(back.elevation, gram.elevation);
  EXPECT_EQ(back.flux_y, gram.flux_y);
  EXPECT_EQ(back.volume_m3, gram.volume_m3);
  EXPECT_THROW(read_gram(folder / "g.bin", 6), Error);
}

}  // namespace
}  // namespace nearshore::loops
