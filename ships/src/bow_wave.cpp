#include "nearshore/ships/bow_wave.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"

namespace nearshore::ships {

BowWave::BowWave(const ShipParticulars& particulars, BowWaveOptions options)
    : options_(options),
      spacing_m_(options.side_in_lengths * std::max(particulars.length_m, 1e-3) / std::max(options.cells, 2)),
      grid_(std::max(options.cells, 2), std::max(options.cells, 2), spacing_m_, EdgeKind::kOpen, options.solver) {
  if (options.cells < 16 || !(options.side_in_lengths > 1.0) || !(options.max_depth_m > 0.0) ||
      !(options.absorbing_fraction >= 0.0 && options.absorbing_fraction < 0.5))
    throw Error("BowWaveOptions",
                fmt::format("cells = {}, side_in_lengths = {}, max_depth_m = {}, absorbing_fraction = {}", options.cells,
                            options.side_in_lengths, options.max_depth_m, options.absorbing_fraction),
                "use at least 16 cells, a side over one ship length, a positive depth and a layer under half the side");
  head_.assign(static_cast<std::size_t>(options.cells + 1) * (options.cells + 1), 0.0);
  heights_m_.assign(static_cast<std::size_t>(options.cells) * options.cells, 0.0f);
}

void BowWave::set_bottom(const Seabed* seabed) {
  const int n = grid_.columns();
  const HarbourObstacles* obstacles = seabed != nullptr ? seabed->obstacles() : nullptr;
  // Whether any face is near the window at all (the field is clamped a band away from faces).
  const double half_side = 0.5 * n * spacing_m_;
  const bool near_solid =
      obstacles != nullptr &&
      obstacles->signed_distance_m((origin_i_ + 0.5 * n) * spacing_m_, (origin_j_ + 0.5 * n) * spacing_m_) <
          std::sqrt(2.0) * half_side + spacing_m_;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = (origin_i_ + i) * spacing_m_, y = (origin_j_ + j) * spacing_m_;
      const double depth = seabed != nullptr ? seabed->depth_m(x, y) : options_.max_depth_m;
      double bottom = -std::min(depth, options_.max_depth_m);
      // Corners inside a structure (or land) take its top: those cells stay dry, and the scheme's
      // wetting front reflects the waves that reach them (a wall in the grid where the structure is).
      if (near_solid) {
        const ObstacleSample o = obstacles->sample(x, y);
        if (o.signed_distance_m < 0.0) bottom = std::max(bottom, o.top_m);
      }
      grid_.set_bottom_corner(i, j, bottom);
    }
}

void hull_pressure_head(const ShipBody& body, long long origin_i, long long origin_j, double spacing_m, int n,
                        int smoothing_passes, std::vector<double>& head) {
  head.assign(static_cast<std::size_t>(n + 1) * (n + 1), 0.0);
  const HullSamples& samples = body.samples();
  const std::vector<double>& eta = body.water_elevations_m();
  const std::vector<Eigen::Vector3d> points = body.world_points_m();
  const Eigen::Matrix3d rotation = body.state().orientation.toRotationMatrix();
  const double inv_cell_area = 1.0 / (spacing_m * spacing_m);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double surface = k < eta.size() ? eta[k] : 0.0;
    const double immersion = surface - points[k].z();
    if (immersion <= 0.0) continue;
    // Vertical projection of the displaced volume (hull_samples.hpp displaced_volume_m3).
    const double volume = immersion * -(rotation.row(2).dot(samples.normal[k])) * samples.area_m2[k];
    const double u = points[k].x() / spacing_m - static_cast<double>(origin_i);
    const double v = points[k].y() / spacing_m - static_cast<double>(origin_j);
    const int i0 = static_cast<int>(std::floor(u)), j0 = static_cast<int>(std::floor(v));
    if (i0 < 0 || j0 < 0 || i0 >= n || j0 >= n) continue;
    const double a = u - i0, b = v - j0;
    const double h = volume * inv_cell_area;
    head[static_cast<std::size_t>(j0) * (n + 1) + i0] += (1 - a) * (1 - b) * h;
    head[static_cast<std::size_t>(j0) * (n + 1) + i0 + 1] += a * (1 - b) * h;
    head[static_cast<std::size_t>(j0 + 1) * (n + 1) + i0] += (1 - a) * b * h;
    head[static_cast<std::size_t>(j0 + 1) * (n + 1) + i0 + 1] += a * b * h;
  }
  // Binomial (1 2 1)/4 passes in x and y: the points are about a cell apart, so the splat alone
  // is noisy at the grid scale. The filter keeps the sum (interior) and hence the volume.
  std::vector<double> tmp(head.size());
  const std::size_t stride = static_cast<std::size_t>(n + 1);
  for (int pass = 0; pass < smoothing_passes; ++pass) {
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double l = head[j * stride + std::max(i - 1, 0)], c = head[j * stride + i],
                     r = head[j * stride + std::min(i + 1, n)];
        tmp[j * stride + i] = 0.25 * (l + 2 * c + r);
      }
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double s = tmp[std::max(j - 1, 0) * stride + i], c = tmp[j * stride + i],
                     nn = tmp[std::min(j + 1, n) * stride + i];
        head[j * stride + i] = 0.25 * (s + 2 * c + nn);
      }
  }
}

void BowWave::set_pressure_head(const ShipBody& body) {
  const int n = grid_.columns();
  hull_pressure_head(body, origin_i_, origin_j_, spacing_m_, n, options_.smoothing_passes, head_);
  const std::size_t stride = static_cast<std::size_t>(n + 1);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) grid_.set_pressure_head_corner(i, j, head_[j * stride + i]);
}

void BowWave::absorb(double dt_s) {
  const int n = grid_.columns();
  const double width = options_.absorbing_fraction * n;
  if (width <= 0.0) return;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double inside = std::min({i + 0.5, n - i - 0.5, j + 0.5, n - j - 0.5});
      if (inside >= width) continue;
      const double r = (width - inside) / width;
      const double keep = std::exp(-options_.absorbing_rate_per_s * r * r * dt_s);
      const double rest = std::max(-grid_.pressure_head_cell(i, j), grid_.bottom_cell(i, j));
      float& w = grid_.surface_m(i, j);
      w = static_cast<float>(rest + keep * (w - rest));
      grid_.discharge_x_m2_s(i, j) *= static_cast<float>(keep);
      grid_.discharge_y_m2_s(i, j) *= static_cast<float>(keep);
    }
}

void BowWave::refresh_heights() {
  const int n = grid_.columns();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      heights_m_[static_cast<std::size_t>(j) * n + i] =
          grid_.depth_m(i, j) > 1e-6 ? static_cast<float>(shown_weight_ * grid_.surface_m(i, j)) : 0.0f;
  ++serial_;
}

void BowWave::update(const ShipBody& body, const Seabed* seabed, double dt_s) {
  const int n = grid_.columns();
  const Eigen::Vector3d centre = body.to_world(body.particulars().hull_centre_m);
  const long long want_i = std::llround(centre.x() / spacing_m_) - n / 2;
  const long long want_j = std::llround(centre.y() / spacing_m_) - n / 2;
  if (!started_ || want_i != origin_i_ || want_j != origin_j_) {
    const long long di = started_ ? want_i - origin_i_ : 2LL * n, dj = started_ ? want_j - origin_j_ : 0;
    grid_.shift_window(static_cast<int>(std::clamp(di, -2LL * n, 2LL * n)),
                       static_cast<int>(std::clamp(dj, -2LL * n, 2LL * n)));
    origin_i_ = want_i;
    origin_j_ = want_j;
    set_bottom(seabed);
    set_pressure_head(body);
    grid_.update_bottom();
    grid_.rest_new_cells();
    started_ = true;
  } else {
    set_pressure_head(body);
    grid_.update_bottom();
    grid_.rest_new_cells();
  }
  last_steps_ = dt_s > 0.0 ? grid_.advance(dt_s) : 0;
  absorb(dt_s);
  refresh_heights();
}

void BowWave::set_shown_weight(double weight) {
  weight = std::clamp(weight, 0.0, 1.0);
  if (weight == shown_weight_) return;
  shown_weight_ = weight;
  if (started_) refresh_heights();
}

double field_elevation_m(const BowWaveField& f, double x_m, double y_m) {
  if (f.heights_m == nullptr || f.columns < 2 || f.rows < 2) return 0.0;
  const double u = (x_m - f.origin_x_m) / f.spacing_m - 0.5;
  const double v = (y_m - f.origin_y_m) / f.spacing_m - 0.5;
  if (!(u >= 0.0 && v >= 0.0 && u <= f.columns - 1 && v <= f.rows - 1)) return 0.0;
  const int i0 = std::min(static_cast<int>(u), f.columns - 2), j0 = std::min(static_cast<int>(v), f.rows - 2);
  const double a = u - i0, b = v - j0;
  auto h = [&](int i, int j) { return static_cast<double>((*f.heights_m)[static_cast<std::size_t>(j) * f.columns + i]); };
  return (1 - b) * ((1 - a) * h(i0, j0) + a * h(i0 + 1, j0)) + b * ((1 - a) * h(i0, j0 + 1) + a * h(i0 + 1, j0 + 1));
}

double BowWave::elevation_m(double x_m, double y_m) const {
  if (!started_) return 0.0;
  return field_elevation_m(field(), x_m, y_m);
}

BowWaveField BowWave::field() const {
  BowWaveField f;
  f.origin_x_m = static_cast<double>(origin_i_) * spacing_m_;
  f.origin_y_m = static_cast<double>(origin_j_) * spacing_m_;
  f.spacing_m = spacing_m_;
  f.columns = f.rows = grid_.columns();
  f.heights_m = &heights_m_;
  f.serial = serial_;
  return f;
}

namespace {

// The ship's frame on the grid: the window's interior (outside the absorbing layer) and the point
// xi behind the bow, `lateral` to port.
struct WakeFrame {
  WakeFrame(const BowWaveField& f, double absorbing_fraction, const ShipState& state, double length_m) : field(f) {
    side = field.columns * field.spacing_m;
    margin = absorbing_fraction * side;
    const Eigen::Vector3d forward = state.orientation * Eigen::Vector3d::UnitX();
    ahead = Eigen::Vector2d(forward.x(), forward.y()).normalized();
    port = Eigen::Vector2d(-ahead.y(), ahead.x());
    bow = Eigen::Vector2d(state.position_m.x(), state.position_m.y()) + 0.5 * length_m * ahead;
  }
  bool interior(const Eigen::Vector2d& p) const {
    return p.x() > field.origin_x_m + margin && p.x() < field.origin_x_m + side - margin &&
           p.y() > field.origin_y_m + margin && p.y() < field.origin_y_m + side - margin;
  }
  Eigen::Vector2d at(double xi, double lateral) const { return bow - xi * ahead + lateral * port; }

  BowWaveField field;
  double side = 0.0, margin = 0.0;
  Eigen::Vector2d ahead, port, bow;
};

// Least-squares line offset = a + b xi through the stations: the half-angle atan(b), the scatter,
// r^2, and whether that is a wedge (WakeAngle::wedge).
WakeAngle fit_wake_line(const std::vector<double>& xs, const std::vector<double>& ys) {
  WakeAngle out;
  if (xs.size() < 4) return out;
  const double n = static_cast<double>(xs.size());
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    mx += xs[k] / n;
    my += ys[k] / n;
  }
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    sxx += (xs[k] - mx) * (xs[k] - mx);
    sxy += (xs[k] - mx) * (ys[k] - my);
    syy += (ys[k] - my) * (ys[k] - my);
  }
  if (sxx <= 0.0) return out;
  const double slope = sxy / sxx, intercept = my - slope * mx;
  double rss = 0;
  for (std::size_t k = 0; k < xs.size(); ++k) rss += std::pow(ys[k] - intercept - slope * xs[k], 2);
  out.half_angle_deg = std::atan(slope) * 180.0 / std::numbers::pi;
  out.stations = static_cast<int>(xs.size());
  out.fit_rms_m = std::sqrt(rss / n);
  out.r_squared = syy > 0.0 ? 1.0 - rss / syy : 0.0;
  out.wedge = out.half_angle_deg > 1.0 && out.r_squared >= 0.6;
  return out;
}

}  // namespace

WakeAngle measure_wake_half_angle(const BowWave& wave, const ShipState& state, double length_m,
                                  double threshold_fraction, double start_lengths) {
  return measure_wake_half_angle(wave.field(), wave.options().absorbing_fraction, state, length_m, threshold_fraction,
                                 start_lengths);
}

WakeAngle measure_wake_half_angle(const BowWaveField& field, double absorbing_fraction, const ShipState& state,
                                  double length_m, double threshold_fraction, double start_lengths) {
  const WakeFrame frame(field, absorbing_fraction, state, length_m);
  const double side = frame.side, spacing = frame.field.spacing_m, step = 0.5 * spacing;
  // The largest |eta| behind start_lengths.
  double peak = 0.0;
  for (double xi = start_lengths * length_m; xi < side; xi += step)
    for (double lateral = -side; lateral <= side; lateral += step) {
      const Eigen::Vector2d p = frame.at(xi, lateral);
      if (!frame.interior(p)) continue;
      peak = std::max(peak, std::abs(field_elevation_m(frame.field, p.x(), p.y())));
    }
  if (peak <= 0.0) return {};
  std::vector<double> xs, ys;
  for (double xi = start_lengths * length_m; xi < side; xi += step) {
    for (int sign : {-1, 1}) {
      double outermost = -1.0;
      bool seen_interior = false;
      for (double lateral = side; lateral >= 0.0; lateral -= step) {
        const Eigen::Vector2d p = frame.at(xi, sign * lateral);
        if (!frame.interior(p)) continue;
        seen_interior = true;
        if (std::abs(field_elevation_m(frame.field, p.x(), p.y())) > threshold_fraction * peak) {
          outermost = lateral;
          break;
        }
      }
      // Only where the pattern is inside the window on this side (not cut by the absorbing layer).
      if (seen_interior && outermost >= 0.0 && frame.interior(frame.at(xi, sign * (outermost + 2 * spacing)))) {
        xs.push_back(xi);
        ys.push_back(outermost);
      }
    }
  }
  return fit_wake_line(xs, ys);
}

WakeAngle measure_wake_envelope_angle(const BowWave& wave, const ShipState& state, double length_m,
                                      double start_lengths, double min_lateral_m) {
  return measure_wake_envelope_angle(wave.field(), wave.options().absorbing_fraction, state, length_m, start_lengths,
                                     min_lateral_m);
}

WakeAngle measure_wake_envelope_angle(const BowWaveField& field, double absorbing_fraction, const ShipState& state,
                                      double length_m, double start_lengths, double min_lateral_m) {
  const WakeFrame frame(field, absorbing_fraction, state, length_m);
  const double side = frame.side, spacing = frame.field.spacing_m, step = 0.5 * spacing;
  std::vector<double> xs, ys;
  // Stations one cell apart (closer ones are not independent: the field is bilinear between cells).
  for (double xi = start_lengths * length_m; xi < side; xi += spacing) {
    for (int sign : {-1, 1}) {
      double largest = 0.0, where = -1.0;
      bool cut = false;  // the line across reached the absorbing layer while |eta| still rose
      for (double lateral = min_lateral_m; lateral <= side; lateral += step) {
        const Eigen::Vector2d p = frame.at(xi, sign * lateral);
        if (!frame.interior(p)) {
          cut = where >= lateral - 2 * spacing;  // the maximum sits at the layer's edge
          break;
        }
        const double value = std::abs(field_elevation_m(frame.field, p.x(), p.y()));
        if (value > largest) {
          largest = value;
          where = lateral;
        }
      }
      if (where >= 0.0 && largest > 0.0 && !cut) {
        xs.push_back(xi);
        ys.push_back(where);
      }
    }
  }
  return fit_wake_line(xs, ys);
}

}  // namespace nearshore::ships
