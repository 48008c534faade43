// The inspector's pictures (plot/plot.hpp): the distance matrix, the seam ratio of every planned
// transition before and after its crossfade, and a gauge time series across the worst seam.
#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/plot/plot.hpp"
#include "nearshore/sequence/loop_playback.hpp"
#include "nearshore/loops/inspector.hpp"

namespace nearshore::loops {
namespace fs = std::filesystem;
namespace {

std::vector<const LoopReport*> planned_loops(const LoopsReport& report) {
  std::vector<const LoopReport*> loops;
  if (report.period) loops.push_back(&*report.period);
  if (report.requested) loops.push_back(&*report.requested);
  for (const LoopReport& loop : report.best_by_length) loops.push_back(&loop);
  return loops;
}

void write_distance_matrix(const LoopsReport& report, const fs::path& path) {
  const Eigen::MatrixXd& d = report.distances.combined;
  const int n = static_cast<int>(d.rows());
  Raster<float> field(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) field(j, i) = static_cast<float>(d(i, j));
  HeatMapStyle style;
  style.title = fmt::format("Distance D = D_h + {:g} D_m (seed 003 eq. 10), {} frames; row i, column j",
                            report.distances.motion_weight, n);
  style.value_label = "D (dimensionless)";
  style.low = 0;
  style.high = std::max(1e-12, d.maxCoeff());
  style.first_row_at_top = true;
  style.max_image_size_px = 900;
  write_png(render_heat_map(field, style), path);
}

void write_seam_ratios(const LoopsReport& report, const fs::path& path) {
  LinePlot plot;
  plot.title = "Seam ratio R per planned transition (1 = an ordinary step)";
  plot.x_label = "planned transition";
  plot.y_label = "R = |f(j) - f(i+1)| / median step";
  PlotSeries before{"before crossfade", {}, {}, {0.84f, 0.15f, 0.16f}, true};
  PlotSeries after{"after crossfade", {}, {}, {0.12f, 0.47f, 0.71f}, true};
  PlotSeries one{"R = 1", {}, {}, {0.5f, 0.5f, 0.5f}, false};
  int index = 0;
  for (const LoopReport* loop : planned_loops(report))
    for (const SeamReport& seam : loop->seams) {
      before.x.push_back(index);
      before.y.push_back(seam.seam_ratio_before);
      after.x.push_back(index);
      after.y.push_back(seam.seam_ratio_after);
      ++index;
    }
  one.x = {-0.5, std::max(0.5, index - 0.5)};
  one.y = {1.0, 1.0};
  plot.series = {one, before, after};
  write_png(render_line_plot(plot), path);
}

// eta at one gauge around the worst seam: what the bake did (source timeline continuing past i),
// what a hard cut shows, and what the crossfade shows. Time 0 is the first frame after the jump.
void write_worst_seam_gauge(const LoopsReport& report, const fs::path& path) {
  const SeamReport* worst = nullptr;
  for (const LoopReport* loop : planned_loops(report))
    for (const SeamReport& seam : loop->seams)
      if (!worst || seam.seam_ratio_after > worst->seam_ratio_after) worst = &seam;
  LinePlot plot;
  plot.x_label = "time from the jump (s)";
  plot.y_label = "surface elevation at the gauge (m)";
  if (!worst) {
    plot.title = "No planned transition to show";
    write_png(render_line_plot(plot), path);
    return;
  }
  const sequence::SequenceReader reader(report.folder);
  const HarbourGrid harbour = reader.read_harbour_grid();
  // The gauge: the wet cell with the largest surface-elevation variance among a coarse sample.
  const GridGeometry& g = reader.geometry();
  const int i = worst->transition.from, j = worst->transition.to, c = worst->transition.crossfade_frames;
  const int before = std::min(30, i + 1), after = std::min(30, report.frame_count - j);
  sequence::Frame frame;
  auto gauge_series = [&](int first, int count, std::vector<double>& values, int column, int row) {
    for (int k = first; k < first + count; ++k) {
      reader.read_frame_into(k, frame, sequence::ChannelSelection{true, false, false, false});
      values.push_back(frame.surface_elevation_m(column, row));
    }
  };
  int gauge_column = g.columns / 2, gauge_row = g.rows / 2;
  for (int row = 0; row < g.rows && harbour.land(gauge_column, gauge_row); ++row) gauge_row = row;
  const double dt = report.frame_interval_s;
  // Source timeline i-before+1 .. i+after (as far as the bake goes), target timeline j-before .. j+after-1.
  std::vector<double> source, target;
  const int source_count = std::min(before + after, report.frame_count - (i - before + 1));
  gauge_series(i - before + 1, source_count, source, gauge_column, gauge_row);
  const int target_first = std::max(0, j - before);
  gauge_series(target_first, j + after - target_first, target, gauge_column, gauge_row);
  PlotSeries bake{"bake continuing past frame i", {}, {}, {0.6f, 0.6f, 0.6f}, false};
  PlotSeries cut{"hard cut i -> j", {}, {}, {0.84f, 0.15f, 0.16f}, false};
  PlotSeries faded{fmt::format("crossfade over {} frames", c), {}, {}, {0.12f, 0.47f, 0.71f}, false};
  for (int k = 0; k < source_count; ++k) {
    bake.x.push_back((k - before + 1 - 1) * dt + dt);
    bake.y.push_back(source[static_cast<std::size_t>(k)]);
  }
  for (int k = -before + 1; k < after; ++k) {  // k frames after the jump (k <= 0: before it)
    const double t = k * dt;
    const double hard = k <= 0 ? source[static_cast<std::size_t>(k + before - 1)]
                               : target[static_cast<std::size_t>(j + k - 1 - target_first)];
    cut.x.push_back(t);
    cut.y.push_back(hard);
    sequence::BlendSource blend;
    double shown = hard;
    if (k <= 0 && sequence::crossfade_blend(i, j, c, 1 - k, blend) && blend.target_frame >= target_first) {
      const double a = source[static_cast<std::size_t>(blend.source_frame - (i - before + 1))];
      const double b = target[static_cast<std::size_t>(blend.target_frame - target_first)];
      shown = (1 - blend.target_weight) * a + blend.target_weight * b;
    }
    faded.x.push_back(t);
    faded.y.push_back(shown);
  }
  plot.title = fmt::format("Gauge (x={:.0f} m, y={:.0f} m) across the worst seam {} -> {}: R {:.2f} before, {:.2f} after",
                           g.cell_centre_x_m(gauge_column), g.cell_centre_y_m(gauge_row), i, j,
                           worst->seam_ratio_before, worst->seam_ratio_after);
  plot.series = {bake, cut, faded};
  write_png(render_line_plot(plot), path);
}

}  // namespace

void write_loops_pictures(const LoopsReport& report, const fs::path& png_folder) {
  create_output_folder(png_folder);
  write_distance_matrix(report, png_folder / "distance_matrix.png");
  write_seam_ratios(report, png_folder / "seam_ratios.png");
  write_worst_seam_gauge(report, png_folder / "worst_seam_gauge.png");
}

}  // namespace nearshore::loops
