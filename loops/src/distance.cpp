#include "nearshore/loops/distance.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <fmt/core.h>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/sequence/checksum.hpp"

namespace nearshore::loops {
namespace fs = std::filesystem;
namespace {

constexpr const char* kGramHeader = "nearshore loops gram 1";

// G += X^T X for one stripe, X = cells x frames. The upper block triangle is split into tiles of
// frames so both cores work; each tile is one Eigen GEMM.
void accumulate_gram(const Eigen::MatrixXd& stripe, Eigen::MatrixXd& gram) {
  const int frames = static_cast<int>(stripe.cols());
  const int tile = 128;
  const int tiles = (frames + tile - 1) / tile;
  std::vector<std::pair<int, int>> pairs;
  for (int a = 0; a < tiles; ++a)
    for (int b = a; b < tiles; ++b) pairs.emplace_back(a, b);
  tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t p) {
    const auto [a, b] = pairs[p];
    const int a0 = a * tile, an = std::min(tile, frames - a0);
    const int b0 = b * tile, bn = std::min(tile, frames - b0);
    gram.block(a0, b0, an, bn).noalias() += stripe.middleCols(a0, an).transpose() * stripe.middleCols(b0, bn);
  });
}

}  // namespace

GramMatrices compute_gram_matrices(const sequence::SequenceReader& reader, const GramOptions& options) {
  if (options.threads < 1)
    throw Error(fmt::format("GramOptions::threads = {}", options.threads), "is not a thread count",
                "give GramOptions::threads 1 or more");
  if (options.memory_budget_bytes == 0)
    throw Error("GramOptions::memory_budget_bytes = 0", "leaves no memory for a stripe of rows",
                "give GramOptions::memory_budget_bytes a budget in bytes, e.g. 1 GiB");
  const GridGeometry& geometry = reader.geometry();
  const int frames = reader.frame_count(), columns = geometry.columns, rows = geometry.rows;
  const std::size_t bytes_per_row = static_cast<std::size_t>(columns) * frames * 3 * sizeof(double);
  // Stripes of whole EXR chunks (32 lines covers every codec's block) where the budget allows.
  int stripe_rows = static_cast<int>(std::max<std::size_t>(1, options.memory_budget_bytes / bytes_per_row));
  if (stripe_rows >= 32) stripe_rows -= stripe_rows % 32;
  stripe_rows = std::min(stripe_rows, rows);
  GramMatrices gram;
  gram.elevation = Eigen::MatrixXd::Zero(frames, frames);
  gram.flux_x = Eigen::MatrixXd::Zero(frames, frames);
  gram.flux_y = Eigen::MatrixXd::Zero(frames, frames);
  gram.volume_m3.assign(static_cast<std::size_t>(frames), 0.0);
  gram.cell_area_m2 = geometry.cell_area_m2();
  tbb::task_arena arena(std::max(1, options.threads));
  ProgressBar progress("distance matrix", static_cast<double>(rows), "rows");
  Eigen::MatrixXd stripe[3];
  for (int first_row = 0; first_row < rows; first_row += stripe_rows) {
    const int count = std::min(stripe_rows, rows - first_row);
    const Eigen::Index cells = static_cast<Eigen::Index>(count) * columns;
    for (auto& s : stripe) s.resize(cells, frames);
    arena.execute([&] {
      tbb::parallel_for(0, frames, [&](int index) {
        sequence::Frame frame;
        reader.read_frame_rows(index, first_row, count, frame, sequence::ChannelSelection::dynamics());
        const Raster<float>* fields[3] = {&frame.surface_elevation_m, &frame.flux_x_m2_s, &frame.flux_y_m2_s};
        double volume = 0;
        for (int c = 0; c < 3; ++c) {
          const float* values = fields[c]->data();
          double* column = stripe[c].col(index).data();
          for (Eigen::Index k = 0; k < cells; ++k) column[k] = values[k];
        }
        for (Eigen::Index k = 0; k < cells; ++k) volume += stripe[0](k, index);
        gram.volume_m3[static_cast<std::size_t>(index)] += volume * gram.cell_area_m2;
      });
      accumulate_gram(stripe[0], gram.elevation);
      accumulate_gram(stripe[1], gram.flux_x);
      accumulate_gram(stripe[2], gram.flux_y);
    });
    progress.update(first_row + count, fmt::format("{} frames", frames));
  }
  progress.finish();
  // Only the upper block triangle was accumulated: mirror it.
  for (Eigen::MatrixXd* g : {&gram.elevation, &gram.flux_x, &gram.flux_y})
    *g = g->triangularView<Eigen::Upper>().toDenseMatrix().selfadjointView<Eigen::Upper>();
  return gram;
}

namespace {
Eigen::MatrixXd pairwise_norms(const Eigen::MatrixXd& gram) {
  const Eigen::Index n = gram.rows();
  Eigen::MatrixXd norms(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i)
      norms(i, j) = i == j ? 0.0 : std::sqrt(std::max(0.0, gram(i, i) + gram(j, j) - 2 * gram(i, j)));
  return norms;
}
}  // namespace

DistanceMatrices distances_from_gram(const GramMatrices& gram, double motion_weight) {
  if (!(motion_weight >= 0 && std::isfinite(motion_weight)))
    throw Error(fmt::format("motion weight delta of eq. 10 (TransitionOptions::motion_weight) = {}", motion_weight),
                "is not a finite number >= 0", "give TransitionOptions::motion_weight a value in [0, inf), e.g. 1");
  DistanceMatrices d;
  d.motion_weight = motion_weight;
  d.height = pairwise_norms(gram.elevation);
  d.motion = pairwise_norms(gram.flux_x) + pairwise_norms(gram.flux_y);
  // eq. (8), (9): normalised by the largest distance; a constant sequence has none (scale 1).
  d.height_scale = d.height.size() && d.height.maxCoeff() > 0 ? d.height.maxCoeff() : 1.0;
  d.motion_scale = d.motion.size() && d.motion.maxCoeff() > 0 ? d.motion.maxCoeff() : 1.0;
  d.combined = d.height / d.height_scale + motion_weight * d.motion / d.motion_scale;  // eq. (10)
  return d;
}

double combination_distance(const GramMatrices& gram, const DistanceMatrices& distances, const std::vector<int>& frames,
                            const std::vector<double>& weights) {
  auto norm = [&](const Eigen::MatrixXd& g) {
    double sum = 0;
    for (std::size_t a = 0; a < frames.size(); ++a)
      for (std::size_t b = 0; b < frames.size(); ++b) sum += weights[a] * weights[b] * g(frames[a], frames[b]);
    return std::sqrt(std::max(0.0, sum));
  };
  return norm(gram.elevation) / distances.height_scale +
         distances.motion_weight * (norm(gram.flux_x) + norm(gram.flux_y)) / distances.motion_scale;
}

void write_gram(const fs::path& path, const GramMatrices& gram) {
  const int n = gram.frame_count();
  std::string bytes = fmt::format("{} frames={} cell_area_m2={:.17g}\n", kGramHeader, n, gram.cell_area_m2);
  const std::size_t header = bytes.size();
  const std::size_t matrix_bytes = static_cast<std::size_t>(n) * n * sizeof(double);
  bytes.resize(header + 3 * matrix_bytes + n * sizeof(double));
  char* out = bytes.data() + header;
  for (const Eigen::MatrixXd* g : {&gram.elevation, &gram.flux_x, &gram.flux_y}) {
    std::memcpy(out, g->data(), matrix_bytes);  // column-major, little-endian (x86-64, aarch64)
    out += matrix_bytes;
  }
  std::memcpy(out, gram.volume_m3.data(), n * sizeof(double));
  write_bytes_atomically(path, std::as_bytes(std::span(bytes.data(), bytes.size())));
}

GramMatrices read_gram(const fs::path& path, int expected_frames) {
  const std::string bytes = sequence::read_file_bytes(path);
  const std::size_t newline = bytes.find('\n');
  int n = -1;
  double area = 0;
  if (newline == std::string::npos || bytes.rfind(kGramHeader, 0) != 0 ||
      std::sscanf(bytes.c_str() + std::strlen(kGramHeader), " frames=%d cell_area_m2=%lf", &n, &area) != 2)
    throw Error(path.string(), "is not a nearshore Gram matrix file", "delete it and run `nearshore loops` again");
  const std::size_t matrix_bytes = static_cast<std::size_t>(std::max(n, 0)) * std::max(n, 0) * sizeof(double);
  if (n != expected_frames || bytes.size() != newline + 1 + 3 * matrix_bytes + n * sizeof(double))
    throw Error(path.string(), fmt::format("holds {} frames ({} bytes) but the sequence has {}", n, bytes.size(),
                                           expected_frames),
                "the sequence changed since; recompute the distances with LoopsOptions::recompute");
  GramMatrices gram;
  gram.cell_area_m2 = area;
  const char* in = bytes.data() + newline + 1;
  for (Eigen::MatrixXd* g : {&gram.elevation, &gram.flux_x, &gram.flux_y}) {
    g->resize(n, n);
    std::memcpy(g->data(), in, matrix_bytes);
    in += matrix_bytes;
  }
  gram.volume_m3.resize(static_cast<std::size_t>(n));
  std::memcpy(gram.volume_m3.data(), in, n * sizeof(double));
  return gram;
}

}  // namespace nearshore::loops
