#pragma once
// Distances between the frames of a sequence, seed 003 eq. (8)-(10):
//   D^h_ij = |h_i - h_j| / max |h_i - h_j|                                   (8)
//   D^m_ij = (|P_i - P_j| + |Q_i - Q_j|) / max (|P_i - P_j| + |Q_i - Q_j|)    (9)
//   D_ij   = D^h_ij + delta D^m_ij                                           (10)
// with |.| the L2 norm over the cells. All of them come from three Gram matrices
// G_ij = <f_i, f_j> (one per channel eta, P, Q): |f_i - f_j|^2 = G_ii + G_jj - 2 G_ij. The Gram
// matrices are built from row stripes of all frames streamed from disk (the sequence never has to
// fit in memory) with Eigen matrix products on both cores; any linear combination of frames (a
// crossfade) has its norm in closed form from them too.
#include <cstdint>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::loops {

struct GramMatrices {
  Eigen::MatrixXd elevation;  ///< <eta_i, eta_j>, m^2 summed over cells
  Eigen::MatrixXd flux_x;     ///< <P_i, P_j>, (m^2/s)^2
  Eigen::MatrixXd flux_y;     ///< <Q_i, Q_j>
  std::vector<double> volume_m3;  ///< sum of eta * cell area per frame (the water volume above still water)
  double cell_area_m2 = 1;
  int frame_count() const { return static_cast<int>(elevation.rows()); }
};

struct GramOptions {
  std::size_t memory_budget_bytes = std::size_t{1} << 30;  ///< for one stripe of all frames (3 doubles per cell)
  int threads = 2;                                          ///< decode and matrix products
};

/// Streams every frame of `reader` once per stripe of rows. Shows a ProgressBar.
GramMatrices compute_gram_matrices(const sequence::SequenceReader& reader, const GramOptions& options = {});

/// Un-normalised distances |h_i - h_j| (m) and |P_i - P_j| + |Q_i - Q_j| (m^2/s), and eq. (10).
struct DistanceMatrices {
  Eigen::MatrixXd height;  ///< |h_i - h_j|_2
  Eigen::MatrixXd motion;  ///< |P_i - P_j|_2 + |Q_i - Q_j|_2
  double height_scale = 1, motion_scale = 1;  ///< the maxima of eq. (8) and (9)
  double motion_weight = 1;                   ///< delta of eq. (10)
  Eigen::MatrixXd combined;                   ///< D of eq. (10)
};
DistanceMatrices distances_from_gram(const GramMatrices& gram, double motion_weight);

/// |sum_k w_k f_{frame_k}| in the metric of eq. (10) (height / height_scale + delta * motion /
/// motion_scale) for a linear combination of frames: the distance between blended frames.
double combination_distance(const GramMatrices& gram, const DistanceMatrices& distances,
                            const std::vector<int>& frames, const std::vector<double>& weights);

/// Gram matrices on disk (loops_gram.bin): a small text header line then little-endian doubles.
void write_gram(const std::filesystem::path& path, const GramMatrices& gram);
GramMatrices read_gram(const std::filesystem::path& path, int expected_frames);

}  // namespace nearshore::loops
