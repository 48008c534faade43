#include "nearshore/bake/structure_layers.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>
#include <unordered_map>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/bathymetry/structure_footprint.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/ocean/linear_waves.hpp"

namespace nearshore::bake {
namespace {

using boussinesq::LayerResponse;
using boussinesq::PorousLayerFlume;

double median_of_copy(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// One fit the flume makes; structures that ask the same of the same layer share it.
struct FitRequest {
  bool wall_behind = true;
  double target = 1.0;
  int layer_cells = 2;
  double depth_m = 0.0;
  bool operator<(const FitRequest& other) const {
    return std::tie(wall_behind, target, layer_cells, depth_m) < std::tie(other.wall_behind, other.target, other.layer_cells, other.depth_m);
  }
};

struct FitResult {
  boussinesq::PorosityFit fit;
  int widening_cells = 0;  ///< cells the faces were widened by to reach the request
  std::vector<LayerResponse> across_band;
  std::string failure;     ///< why the flume could not fit this layer (then the faces keep the fallback)
};

// Water shallower than this in front of a structure carries no wave the flume can stand for (a
// structure on a drying beach): its faces keep the fallback porosity, said in a warning.
constexpr double kShallowestFittedDepth_m = 0.1;

// Faces too thin to absorb what a structure does not reflect are widened a cell at a time, up to
// half a wavelength of layer or this many cells, whichever comes first (MIKE 21 BW's porosity
// layers are drawn L/4 - L/2 wide for the same reason).
constexpr int kMostWideningCells = 4;

}  // namespace

double reflection_of_slope(double side_slope, double roughness_factor, double significant_wave_height_m, double spectral_period_s) {
  if (!(side_slope > 0.0 && significant_wave_height_m > 0.0 && spectral_period_s > 0.0)) return 1.0;
  const double deep_water_wavelength_m = ocean::kGravity_m_s2 * spectral_period_s * spectral_period_s / (2.0 * std::numbers::pi);
  const double breaker_parameter = (1.0 / side_slope) / std::sqrt(significant_wave_height_m / deep_water_wavelength_m);
  const double a = 0.167 * (1.0 - std::exp(-3.2 * roughness_factor));
  const double b = 1.49 * (roughness_factor - 0.38) * (roughness_factor - 0.38) + 0.86;
  return std::tanh(a * std::pow(breaker_parameter, b));
}

StructureSeaState structure_sea_state(const boussinesq::WaveMaker& maker) {
  StructureSeaState sea;
  if (maker.kind == boussinesq::WaveMaker::Kind::kComponents && !maker.sea_state.components.empty()) {
    // m0, m_-1 and the peak of the components' variance a^2 / 2, summed over directions per frequency.
    std::map<double, double> variance_at;
    double m0 = 0.0, m_minus_1 = 0.0, lowest_rad_s = INFINITY, highest_rad_s = 0.0;
    for (const ocean::WaveComponent& component : maker.sea_state.components) {
      const double variance_m2 = 0.5 * component.amplitude_m * component.amplitude_m;
      const double w = component.angular_frequency_rad_s;
      if (!(w > 0.0)) continue;
      variance_at[w] += variance_m2;
      m0 += variance_m2;
      m_minus_1 += variance_m2 * 2.0 * std::numbers::pi / w;
      lowest_rad_s = std::min(lowest_rad_s, w);
      highest_rad_s = std::max(highest_rad_s, w);
    }
    if (m0 > 0.0) {
      const auto peak = std::max_element(variance_at.begin(), variance_at.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
      sea.significant_wave_height_m = 4.0 * std::sqrt(m0);
      sea.peak_period_s = 2.0 * std::numbers::pi / peak->first;
      sea.spectral_period_s = m_minus_1 / m0;
      sea.longest_period_s = 2.0 * std::numbers::pi / lowest_rad_s;
      sea.shortest_period_s = 2.0 * std::numbers::pi / highest_rad_s;
      constexpr int kFlumeWaves = 5;
      if (variance_at.size() <= static_cast<std::size_t>(kFlumeWaves)) {
        for (const auto& [w, variance_m2] : variance_at) sea.waves.push_back({2.0 * std::numbers::pi / w, 2.0 * std::sqrt(2.0 * variance_m2)});
      } else {
        // Equal shares of the variance, at the quantiles 0.2, 0.35, 0.5, 0.65, 0.8 of the cumulative
        // variance: the spectrum's body, held within a factor 1.9 in frequency, so that no sum,
        // difference or second harmonic of two flume waves (their bound waves: the layer's
        // resistance and the shallow water make them) falls on another's frequency and corrupts
        // its separation (a 13.6 s wave's second harmonic is a 6.8 s wave).
        constexpr double kQuantiles[kFlumeWaves] = {0.2, 0.35, 0.5, 0.65, 0.8};
        constexpr double kWidestRatio = 1.9;
        double cumulative_m2 = 0.0;
        int next = 0;
        std::vector<double> quantile_w;
        for (const auto& [w, variance_m2] : variance_at) {
          cumulative_m2 += variance_m2;
          while (next < kFlumeWaves && cumulative_m2 >= kQuantiles[next] * m0) quantile_w.push_back(w), ++next;
        }
        while (static_cast<int>(quantile_w.size()) < kFlumeWaves) quantile_w.push_back(variance_at.rbegin()->first);
        const double middle_w = quantile_w[kFlumeWaves / 2];
        const double ratio = quantile_w.back() / quantile_w.front();
        const double squeeze = ratio > kWidestRatio ? std::log(kWidestRatio) / std::log(ratio) : 1.0;
        for (double w : quantile_w)
          sea.waves.push_back({2.0 * std::numbers::pi / (middle_w * std::pow(w / middle_w, squeeze)), 2.0 * std::sqrt(2.0 * m0 / kFlumeWaves)});
      }
    }
  } else if (maker.kind == boussinesq::WaveMaker::Kind::kTimeSeries && maker.series_elevation_m.size() > 2) {
    // A measured record: Hs = 4 sigma, and the mean zero up-crossing period for every period.
    const auto& eta = maker.series_elevation_m;
    const auto& t = maker.series_time_s;
    double mean = 0.0;
    for (double e : eta) mean += e;
    mean /= static_cast<double>(eta.size());
    double variance = 0.0;
    for (double e : eta) variance += (e - mean) * (e - mean);
    variance /= static_cast<double>(eta.size());
    std::vector<double> crossings_s;
    for (std::size_t i = 1; i < eta.size(); ++i)
      if (eta[i - 1] - mean < 0.0 && eta[i] - mean >= 0.0) crossings_s.push_back(t[i]);
    if (variance > 0.0 && crossings_s.size() >= 2) {
      sea.significant_wave_height_m = 4.0 * std::sqrt(variance);
      sea.peak_period_s = sea.spectral_period_s = sea.longest_period_s = sea.shortest_period_s =
          (crossings_s.back() - crossings_s.front()) / static_cast<double>(crossings_s.size() - 1);
      sea.waves = {{sea.peak_period_s, sea.significant_wave_height_m / std::sqrt(2.0)}};
    }
  }
  return sea;
}

std::vector<StructureLayer> lay_structures(HarbourGrid& grid, const boussinesq::SolverParameters& solver, const StructureSeaState& sea,
                                           std::vector<std::string>& warnings, double fallback_porosity) {
  const GridGeometry& g = grid.geometry;
  const double cell_m = g.smaller_spacing_m();
  const double core_reach_m = 0.5 * std::hypot(g.spacing_x_m(), g.spacing_y_m()) * std::sqrt(0.5);
  const int minimum_face_cells = bathymetry::kMinimumStructureFaceCells;
  const bool can_fit = sea.significant_wave_height_m > 0.0 && sea.peak_period_s > 0.0;
  grid.porosity = Raster<float>(g.columns, g.rows, 1.0f);
  std::vector<StructureLayer> layers;
  std::vector<std::vector<std::size_t>> core_of(grid.structures.size()), faces_of(grid.structures.size());
  std::map<FitRequest, FitResult> fits;
  std::vector<FitRequest> request_of(grid.structures.size());

  // The core and face cells of structure s with its faces widened by `widening_m`.
  auto footprint = [&](std::size_t s, double widening_m) {
    std::unordered_map<std::size_t, unsigned char> part;  // cell -> 1 face, 2 core (a real chart has hundreds of structures)
    bathymetry::for_each_footprint_cell(
        g, grid.still_water_depth_m, grid.structures[s], minimum_face_cells,
        [&](int c, int r, bathymetry::FootprintPart which) {
          unsigned char& p = part[static_cast<std::size_t>(r) * g.columns + c];
          p = std::max<unsigned char>(p, which == bathymetry::FootprintPart::kCore ? 2 : 1);
        },
        widening_m);
    core_of[s].clear();
    faces_of[s].clear();
    for (const auto& [i, which] : part) (which == 2 ? core_of[s] : faces_of[s]).push_back(i);
    std::sort(core_of[s].begin(), core_of[s].end());
    std::sort(faces_of[s].begin(), faces_of[s].end());
  };

  // Steps 1-3 of the header: coefficients, footprint, the flume each structure needs.
  for (std::size_t s = 0; s < grid.structures.size(); ++s) {
    const CoastalStructure& structure = grid.structures[s];
    StructureLayer layer;
    layer.name = structure.name;
    layer.kind = structure.kind;
    layer.transmission_requested = structure.transmission_coefficient;
    layer.reflection_requested = structure.reflection_coefficient;
    layer.reflection_from = "given";
    if (structure.reflection_coefficient < 0.0) {
      layer.reflection_requested = reflection_of_slope(structure.side_slope, structure.roughness_factor, sea.significant_wave_height_m,
                                                       sea.spectral_period_s);
      const double l0 = ocean::kGravity_m_s2 * sea.spectral_period_s * sea.spectral_period_s / (2.0 * std::numbers::pi);
      layer.reflection_from = can_fit ? fmt::format("Zanuttigh & van der Meer (2008): slope 1:{:.3g}, gamma_f {:.2f}, xi {:.2f}",
                                                    structure.side_slope, structure.roughness_factor,
                                                    (1.0 / structure.side_slope) / std::sqrt(sea.significant_wave_height_m / l0))
                                      : "no sea state to compute it from";
    }
    footprint(s, 0.0);
    std::vector<double> face_depths;
    for (std::size_t i : faces_of[s])
      if (grid.still_water_depth_m.values()[i] > solver.dry_depth_m && grid.land.values()[i] == kWaterCell)
        face_depths.push_back(grid.still_water_depth_m.values()[i]);
    layer.core_cells = core_of[s].size();
    layer.face_cells = faces_of[s].size();
    if (layer.core_cells + layer.face_cells == 0)
      warnings.push_back(fmt::format("structure '{}' ({}) lies outside the grid: left out", structure.name, structure.kind));
    layer.depth_m = median_of_copy(face_depths);
    const bool impermeable = bathymetry::has_impermeable_core(structure);
    if (!structure.lines.empty()) {
      const double reach_m = std::max(structure.footprint_half_width_m(layer.depth_m), (impermeable ? core_reach_m : 0.0) + minimum_face_cells * cell_m);
      layer.face_width_m = impermeable ? reach_m - core_reach_m : 2.0 * reach_m;
    } else {
      const double outline_m = std::max(structure.side_slope * (structure.crest_elevation_m + layer.depth_m), minimum_face_cells * cell_m);
      double narrowest_m = 0.0;
      if (!impermeable) {
        narrowest_m = INFINITY;
        for (const auto& polygon : structure.polygons) {
          if (polygon.empty()) continue;
          double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
          for (const auto& [x, y] : polygon.front()) x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
          narrowest_m = std::min(narrowest_m, std::min(x1 - x0, y1 - y0));
        }
        if (!std::isfinite(narrowest_m)) narrowest_m = 0.0;
      }
      layer.face_width_m = impermeable ? outline_m : narrowest_m + 2.0 * outline_m;
    }
    layer.wave_period_s = sea.peak_period_s;
    layer.fitted = structure.porosity < 0.0 && can_fit && !face_depths.empty() && layer.face_cells > 0 && !sea.waves.empty() &&
                   layer.depth_m >= kShallowestFittedDepth_m;
    layer.face_porosity = structure.porosity >= 0.0 ? structure.porosity : fallback_porosity;
    if (structure.porosity < 0.0 && !can_fit && layer.face_cells > 0)
      warnings.push_back(fmt::format("structure '{}' ({}): the wave maker gives no sea state (height and peak period) to fit its "
                                     "porous faces to; they keep porosity {:.2f}",
                                     structure.name, structure.kind, fallback_porosity));
    if (layer.fitted) {
      FitRequest request;
      request.wall_behind = impermeable;
      request.target = std::round(1000.0 * (impermeable ? layer.reflection_requested : layer.transmission_requested)) / 1000.0;
      request.layer_cells = std::max(1, static_cast<int>(std::lround(layer.face_width_m / cell_m)));
      // Depths within 10 % share a fit (k h within +- 5 %: the layer's response moves by less than
      // the fit's tolerance; a real chart has hundreds of piers at as many depths).
      request.depth_m = std::exp(std::round(std::log(layer.depth_m) / 0.1) * 0.1);
      request_of[s] = request;
      fits.emplace(request, FitResult{});
    }
    layers.push_back(std::move(layer));
  }

  // The flume runs, in parallel over the distinct requests.
  std::vector<std::pair<const FitRequest, FitResult>*> work;
  for (auto& entry : fits) work.push_back(&entry);
  tbb::parallel_for(std::size_t{0}, work.size(), [&](std::size_t i) {
    const FitRequest& request = work[i]->first;
    PorousLayerFlume flume;
    flume.still_water_depth_m = request.depth_m;
    // The sea's waves, lowered together where the water in front of the structure is too shallow
    // to carry them unbroken (their heights summed below 0.8 d; the flume turns breaking off).
    flume.waves = sea.waves;
    double height_sum_m = 0.0;
    for (const auto& wave : flume.waves) height_sum_m += wave.height_m;
    const double lowered = std::min(1.0, 0.75 * request.depth_m / height_sum_m);
    for (auto& wave : flume.waves) wave.height_m *= lowered;
    flume.spacing_m = cell_m;
    flume.layer_width_m = request.layer_cells * cell_m;
    flume.wall_behind = request.wall_behind;
    flume.solver = solver;
    FitResult& result = work[i]->second;
    try {
    if (request.wall_behind) {
      result.fit = boussinesq::fit_porosity_to_reflection(flume, request.target, kStructureFitTolerance);
      // Too thin a layer against the wave: widen it (the request is below its chart's minimum).
      while (!result.fit.reached && result.fit.response.reflection_coefficient > request.target &&
             result.widening_cells < kMostWideningCells && result.fit.response.layer_width_wavelengths < 0.5) {
        ++result.widening_cells;
        PorousLayerFlume wider = flume;
        wider.layer_width_m = (request.layer_cells + result.widening_cells) * cell_m;
        const int runs = result.fit.flume_runs;
        result.fit = boussinesq::fit_porosity_to_reflection(wider, request.target, kStructureFitTolerance);
        result.fit.flume_runs += runs;
        flume = wider;
      }
    } else {
      result.fit = boussinesq::fit_porosity_to_transmission(flume, request.target, kStructureFitTolerance);
    }
    result.across_band = result.fit.response.per_wave;
    } catch (const Error& error) {
      result.failure = error.problem();  // said per structure below; the bake goes on with the fallback
    }
  });

  // Step 2's cells get their porosity: faces first, then cores (a core always wins).
  for (std::size_t s = 0; s < layers.size(); ++s) {
    StructureLayer& layer = layers[s];
    if (layer.fitted && !fits.at(request_of[s]).failure.empty()) {
      layer.fitted = false;
      warnings.push_back(fmt::format("structure '{}' ({}): its faces could not be fitted ({}); they keep porosity {:.2f}", layer.name,
                                     layer.kind, fits.at(request_of[s]).failure, layer.face_porosity));
    }
    if (layer.fitted) {
      const FitResult& result = fits.at(request_of[s]);
      layer.face_porosity = result.fit.response.porosity;
      layer.in_the_sea = result.fit.response;
      layer.across_band = result.across_band;
      layer.reached = result.fit.reached;
      layer.flume_runs = result.fit.flume_runs;
      if (result.widening_cells > 0) {
        layer.widening_m = result.widening_cells * cell_m;
        layer.face_width_m += layer.widening_m;
        footprint(s, layer.widening_m);
        layer.core_cells = core_of[s].size();
        layer.face_cells = faces_of[s].size();
      }
      if (!layer.reached) {
        const bool wall = bathymetry::has_impermeable_core(grid.structures[s]);
        warnings.push_back(fmt::format(
            "structure '{}' ({}): its {:.0f} m of porous faces at {:.1f} m depth (widened by {:.0f} m, as far as it goes) {} {} {:.2f} "
            "in the sea of {:.1f} s peak period; the closest is {:.2f} (porosity {:.2f})",
            layer.name, layer.kind, layer.face_width_m, layer.depth_m, layer.widening_m,
            wall ? (layer.in_the_sea.reflection_coefficient > layer.reflection_requested ? "cannot reflect as little as" : "cannot reflect as much as")
                 : (layer.in_the_sea.transmission_coefficient > layer.transmission_requested ? "cannot transmit as little as" : "cannot transmit as much as"),
            wall ? "Kr" : "Kt", wall ? layer.reflection_requested : layer.transmission_requested, layer.wave_period_s,
            wall ? layer.in_the_sea.reflection_coefficient : layer.in_the_sea.transmission_coefficient, layer.face_porosity));
      }
    }
    const float n = static_cast<float>(layer.face_porosity);
    for (std::size_t i : faces_of[s]) grid.porosity.values()[i] = std::min(grid.porosity.values()[i], n);
  }
  for (std::size_t s = 0; s < layers.size(); ++s)
    for (std::size_t i : core_of[s]) grid.porosity.values()[i] = 0.0f;
  return layers;
}

nlohmann::json structure_layers_record(const std::vector<StructureLayer>& layers) {
  auto response = [](const LayerResponse& r) {
    return nlohmann::json{{"porosity", r.porosity},
                          {"reflection_coefficient", r.reflection_coefficient},
                          {"transmission_coefficient", r.transmission_coefficient},
                          {"kh", r.relative_depth_kh},
                          {"period_s", r.period_s},
                          {"layer_width_wavelengths", r.layer_width_wavelengths}};
  };
  nlohmann::json out = nlohmann::json::array();
  for (const StructureLayer& layer : layers) {
    nlohmann::json entry{{"name", layer.name},
                         {"kind", layer.kind},
                         {"reflection_requested", layer.reflection_requested},
                         {"reflection_from", layer.reflection_from},
                         {"transmission_requested", layer.transmission_requested},
                         {"fitted", layer.fitted},
                         {"reached", layer.reached},
                         {"face_porosity", layer.face_porosity},
                         {"depth_m", layer.depth_m},
                         {"face_width_m", layer.face_width_m},
                         {"widening_m", layer.widening_m},
                         {"core_cells", layer.core_cells},
                         {"face_cells", layer.face_cells}};
    if (layer.fitted) {
      entry["peak_period_s"] = layer.wave_period_s;
      entry["in_the_sea"] = response(layer.in_the_sea);
      entry["across_band"] = nlohmann::json::array();
      for (const LayerResponse& r : layer.across_band) entry["across_band"].push_back(response(r));
    }
    out.push_back(entry);
  }
  return out;
}

std::string describe_structure_layers(const std::vector<StructureLayer>& layers) {
  std::string text;
  for (const StructureLayer& layer : layers) {
    if (!text.empty()) text += "\n";
    const bool wall = layer.transmission_requested <= 0.0;
    text += fmt::format("structure '{}' ({}): ", layer.name, layer.kind);
    if (!layer.fitted) {
      text += fmt::format("porous faces at porosity {:.2f} (not fitted), {} wall cells", layer.face_porosity, layer.core_cells);
      continue;
    }
    const double asked = wall ? layer.reflection_requested : layer.transmission_requested;
    auto value = [wall](const LayerResponse& r) { return wall ? r.reflection_coefficient : r.transmission_coefficient; };
    text += fmt::format("{} {:.2f} asked ({}), {:.2f} made in the sea's flume", wall ? "Kr" : "Kt", asked, layer.reflection_from,
                        value(layer.in_the_sea));
    if (!layer.across_band.empty()) {
      text += ", by period:";
      for (const LayerResponse& r : layer.across_band) text += fmt::format(" {:.1f} s {:.2f}", r.period_s, value(r));
    }
    text += fmt::format("; {:.0f} m of faces{} at porosity {:.2f} in {:.1f} m of water, {} wall cells", layer.face_width_m,
                        layer.widening_m > 0 ? fmt::format(" (widened by {:.0f} m to absorb enough)", layer.widening_m) : std::string(),
                        layer.face_porosity, layer.depth_m, layer.core_cells);
  }
  return text;
}

}  // namespace nearshore::bake
