#include "nearshore/bake/structure_layers.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <fmt/core.h>
#include <tbb/parallel_for.h>

#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/bathymetry/structure_footprint.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/ocean/linear_waves.hpp"

// lay_structures (structure_layers.hpp): the footprints and the flume's fits. Apart from the sea
// state and the records (structure_layers.cpp) because it links the solver, which the case-file
// fuzzer (clang) cannot build.
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

// The core and face cells of every structure at the grid's cells (step 2 of the header). Only the
// cells a structure touches are kept (sorted index lists): a real chart has hundreds of structures
// on millions of cells.
class StructureCells {
 public:
  explicit StructureCells(const HarbourGrid& grid)
      : grid_(grid), core_(grid.structures.size()), faces_(grid.structures.size()) {}

  const std::vector<std::size_t>& core(std::size_t s) const { return core_[s]; }
  const std::vector<std::size_t>& faces(std::size_t s) const { return faces_[s]; }

  // Structure s's footprint with its faces widened by `widening_m`.
  void lay_footprint(std::size_t s, double widening_m) {
    std::unordered_map<std::size_t, unsigned char> part;  // cell -> 1 face, 2 core
    bathymetry::for_each_footprint_cell(
        grid_.geometry, grid_.still_water_depth_m, grid_.structures[s], bathymetry::kMinimumStructureFaceCells,
        [&](int c, int r, bathymetry::FootprintPart which) {
          unsigned char& p = part[static_cast<std::size_t>(r) * grid_.geometry.columns + c];
          p = std::max<unsigned char>(p, which == bathymetry::FootprintPart::kCore ? 2 : 1);
        },
        widening_m);
    core_[s].clear();
    faces_[s].clear();
    for (const auto& [i, which] : part) (which == 2 ? core_[s] : faces_[s]).push_back(i);
    std::sort(core_[s].begin(), core_[s].end());
    std::sort(faces_[s].begin(), faces_[s].end());
  }

  // The faces of an impermeable line structure as its core dilated by exactly `cells` cells (cell
  // centres within cells x the cell size of a core cell's centre), so both sides of a straight
  // breakwater get the number of cells the flume was fitted with: laid by distance from the
  // centre line, one side got N and the other N + 1 depending on where the line fell in its cell,
  // and a thin layer's reflection swings with its width (docs/structures.md).
  void dilate_core(std::size_t s, int cells) {
    const GridGeometry& g = grid_.geometry;
    const double dx = g.spacing_x_m(), dy = g.spacing_y_m(), cell_m = g.smaller_spacing_m();
    const double reach_m = cells * cell_m + 1e-6 * cell_m;
    const int reach_c = static_cast<int>(std::ceil(reach_m / dx)), reach_r = static_cast<int>(std::ceil(reach_m / dy));
    const std::unordered_set<std::size_t> core(core_[s].begin(), core_[s].end());
    std::unordered_set<std::size_t> faces;
    for (std::size_t i : core_[s]) {
      const int c0 = static_cast<int>(i % g.columns), r0 = static_cast<int>(i / g.columns);
      for (int r = std::max(0, r0 - reach_r); r <= std::min(g.rows - 1, r0 + reach_r); ++r)
        for (int c = std::max(0, c0 - reach_c); c <= std::min(g.columns - 1, c0 + reach_c); ++c) {
          const std::size_t j = static_cast<std::size_t>(r) * g.columns + c;
          if (!core.contains(j) && std::hypot((c - c0) * dx, (r - r0) * dy) <= reach_m) faces.insert(j);
        }
    }
    faces_[s].assign(faces.begin(), faces.end());
    std::sort(faces_[s].begin(), faces_[s].end());
  }

  // Whether structure s gets its faces by dilate_core: a line with an impermeable core on the grid.
  bool faces_follow_core(std::size_t s) const {
    const CoastalStructure& structure = grid_.structures[s];
    return bathymetry::has_impermeable_core(structure) && !structure.lines.empty() && !core_[s].empty();
  }

 private:
  const HarbourGrid& grid_;
  std::vector<std::vector<std::size_t>> core_, faces_;
};

// Step 1 and the layer's measures for step 3: the coefficient structure s asks for, its footprint,
// the still-water depth in front of it and the faces' width, and whether its faces can be fitted.
StructureLayer plan_structure(const HarbourGrid& grid, std::size_t s, StructureCells& cells, const boussinesq::SolverParameters& solver,
                              const StructureSeaState& sea, std::vector<std::string>& warnings, double fallback_porosity) {
  const GridGeometry& g = grid.geometry;
  const double cell_m = g.smaller_spacing_m();
  const double core_reach_m = 0.5 * std::hypot(g.spacing_x_m(), g.spacing_y_m()) * std::sqrt(0.5);
  const int minimum_face_cells = bathymetry::kMinimumStructureFaceCells;
  const bool can_fit = sea.significant_wave_height_m > 0.0 && sea.peak_period_s > 0.0;
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
  cells.lay_footprint(s, 0.0);
  std::vector<double> face_depths;
  for (std::size_t i : cells.faces(s))
    if (grid.still_water_depth_m.values()[i] > solver.dry_depth_m && grid.land.values()[i] == kWaterCell)
      face_depths.push_back(grid.still_water_depth_m.values()[i]);
  layer.core_cells = cells.core(s).size();
  layer.face_cells = cells.faces(s).size();
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
  layer.stone_diameter_m = solver.porous.stone_diameter_m;
  if (structure.porosity < 0.0 && !can_fit && layer.face_cells > 0)
    warnings.push_back(fmt::format("structure '{}' ({}): the wave maker gives no sea state (height and peak period) to fit its "
                                   "porous faces to; they keep porosity {:.2f}",
                                   structure.name, structure.kind, fallback_porosity));
  return layer;
}

// The shallowest still water in which the sea's shortest flume wave is kFlumeCellsPerShortestWave
// cells long (Airy: tanh k d = omega^2 / (g k) at k = 2 pi / (N dx)); 0 where no depth makes it so
// long (a wave shorter than that even in deep water, which the bake would not carry) or no sea.
double shallowest_resolved_depth_m(const StructureSeaState& sea, double cell_m) {
  double shortest_period_s = INFINITY;
  for (const auto& wave : sea.waves) shortest_period_s = std::min(shortest_period_s, wave.period_s);
  if (!std::isfinite(shortest_period_s) || !(cell_m > 0.0)) return 0.0;
  const double k = 2.0 * std::numbers::pi / (kFlumeCellsPerShortestWave * cell_m);
  const double omega = 2.0 * std::numbers::pi / shortest_period_s;
  const double tanh_kd = omega * omega / (ocean::kGravity_m_s2 * k);
  return tanh_kd < 1.0 ? std::atanh(tanh_kd) / k : 0.0;
}

// The fit a planned layer asks of the flume (step 3), its faces laid to the fitted count.
FitRequest request_of_layer(const HarbourGrid& grid, std::size_t s, const StructureLayer& layer, double shallowest_fitted_depth_m) {
  const bool impermeable = bathymetry::has_impermeable_core(grid.structures[s]);
  FitRequest request;
  request.wall_behind = impermeable;
  request.target = std::round(1000.0 * (impermeable ? layer.reflection_requested : layer.transmission_requested)) / 1000.0;
  request.layer_cells = std::max(1, static_cast<int>(std::lround(layer.face_width_m / grid.geometry.smaller_spacing_m())));
  // Depths within 10 % share a fit (k h within +- 5 %: the layer's response moves by less than
  // the fit's tolerance; a real chart has hundreds of piers at as many depths).
  request.depth_m = std::exp(std::round(std::log(layer.depth_m) / 0.1) * 0.1);
  // Water too shallow for the grid to carry the sea's shortest wave: the fit is made where it can.
  request.depth_m = std::max(request.depth_m, shallowest_fitted_depth_m);
  return request;
}

// Step 3 for one request: the flume's fit of the porosity, the faces widened where a layer is too
// thin against the wave, and the layer's stones made finer where even that absorbs too little.
FitResult run_fit(const FitRequest& request, const StructureSeaState& sea, const boussinesq::SolverParameters& solver, double cell_m) {
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
  FitResult result;
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
    // Still too much comes back (or through): the layer's resistance is fitted too, with finer
    // effective stones (structure_layers.hpp): a short wave crosses a layer of the solver's stones
    // with little loss, reflects from the core and crosses back.
    auto value = [&](const LayerResponse& r) { return request.wall_behind ? r.reflection_coefficient : r.transmission_coefficient; };
    const double solver_stone_diameter_m = flume.solver.porous.stone_diameter_m;
    if (!result.fit.reached && value(result.fit.response) > request.target && solver_stone_diameter_m > 0.0) {
      boussinesq::PorosityFit best = result.fit;
      int runs = result.fit.flume_runs;
      for (int step = 1; step <= kMostStoneDiameterSteps && !best.reached; ++step) {
        PorousLayerFlume finer = flume;
        finer.solver.porous.stone_diameter_m = solver_stone_diameter_m * std::pow(10.0, -0.5 * step);
        const boussinesq::PorosityFit fit = request.wall_behind
                                                ? boussinesq::fit_porosity_to_reflection(finer, request.target, kStructureFitTolerance)
                                                : boussinesq::fit_porosity_to_transmission(finer, request.target, kStructureFitTolerance);
        runs += fit.flume_runs;
        if (fit.reached || std::abs(value(fit.response) - request.target) < std::abs(value(best.response) - request.target)) best = fit;
      }
      result.fit = best;
      result.fit.flume_runs = runs;
    }
    result.across_band = result.fit.response.per_wave;
  } catch (const Error& error) {
    result.failure = error.problem();  // said per structure below; the bake goes on with the fallback
  }
  return result;
}

// A fitted layer takes its fit's result: porosity, stones, the record, the widened faces; a request
// out of reach or a flume that failed is said, naming the structure.
void take_fit(const HarbourGrid& grid, std::size_t s, const FitRequest& request, const FitResult& result, StructureCells& cells,
              const boussinesq::SolverParameters& solver, StructureLayer& layer, std::vector<std::string>& warnings) {
  if (!result.failure.empty()) {
    layer.fitted = false;
    warnings.push_back(fmt::format("structure '{}' ({}): its faces could not be fitted ({}); they keep porosity {:.2f}", layer.name,
                                   layer.kind, result.failure, layer.face_porosity));
    return;
  }
  layer.face_porosity = result.fit.response.porosity;
  layer.stone_diameter_m = result.fit.response.stone_diameter_m;
  layer.stones_fitted = layer.stone_diameter_m != solver.porous.stone_diameter_m;
  layer.in_the_sea = result.fit.response;
  layer.across_band = result.across_band;
  layer.reached = result.fit.reached;
  layer.flume_runs = result.fit.flume_runs;
  if (result.widening_cells > 0) {
    const double cell_m = grid.geometry.smaller_spacing_m();
    layer.widening_m = result.widening_cells * cell_m;
    layer.face_width_m += layer.widening_m;
    // Widening moves only the faces' outer edge; the core stays.
    if (cells.faces_follow_core(s))
      cells.dilate_core(s, request.layer_cells + result.widening_cells);
    else
      cells.lay_footprint(s, layer.widening_m);
    layer.core_cells = cells.core(s).size();
    layer.face_cells = cells.faces(s).size();
  }
  if (!layer.reached) {
    const bool wall = bathymetry::has_impermeable_core(grid.structures[s]);
    warnings.push_back(fmt::format(
        "structure '{}' ({}): its {:.0f} m of porous faces at {:.1f} m depth (widened by {:.0f} m and their stones made as fine as "
        "{:.2g} m, as far as either goes) {} {} {:.2f} in the sea of {:.1f} s peak period; the closest is {:.2f} (porosity {:.2f}, "
        "stones {:.2g} m)",
        layer.name, layer.kind, layer.face_width_m, layer.depth_m, layer.widening_m,
        solver.porous.stone_diameter_m * std::pow(10.0, -0.5 * kMostStoneDiameterSteps),
        wall ? (layer.in_the_sea.reflection_coefficient > layer.reflection_requested ? "cannot reflect as little as" : "cannot reflect as much as")
             : (layer.in_the_sea.transmission_coefficient > layer.transmission_requested ? "cannot transmit as little as" : "cannot transmit as much as"),
        wall ? "Kr" : "Kt", wall ? layer.reflection_requested : layer.transmission_requested, layer.wave_period_s,
        wall ? layer.in_the_sea.reflection_coefficient : layer.in_the_sea.transmission_coefficient, layer.face_porosity,
        layer.stone_diameter_m));
  }
}

}  // namespace

std::vector<StructureLayer> lay_structures(HarbourGrid& grid, const boussinesq::SolverParameters& solver, const StructureSeaState& sea,
                                           std::vector<std::string>& warnings, double fallback_porosity) {
  const GridGeometry& g = grid.geometry;
  grid.porosity = Raster<float>(g.columns, g.rows, 1.0f);
  grid.porous_stone_diameter_m = Raster<float>();
  StructureCells cells(grid);
  std::vector<StructureLayer> layers;
  std::map<FitRequest, FitResult> fits;
  std::vector<FitRequest> request_of(grid.structures.size());

  // Steps 1-3 of the header: coefficients, footprint, the flume each structure needs.
  const double shallowest_fitted_depth_m = shallowest_resolved_depth_m(sea, g.smaller_spacing_m());
  for (std::size_t s = 0; s < grid.structures.size(); ++s) {
    layers.push_back(plan_structure(grid, s, cells, solver, sea, warnings, fallback_porosity));
    if (!layers.back().fitted) continue;
    request_of[s] = request_of_layer(grid, s, layers.back(), shallowest_fitted_depth_m);
    layers.back().flume_depth_m = request_of[s].depth_m;
    fits.emplace(request_of[s], FitResult{});
    if (cells.faces_follow_core(s)) {
      cells.dilate_core(s, request_of[s].layer_cells);
      layers.back().face_cells = cells.faces(s).size();
    }
  }

  // The flume runs, in parallel over the distinct requests.
  std::vector<std::pair<const FitRequest, FitResult>*> work;
  for (auto& entry : fits) work.push_back(&entry);
  tbb::parallel_for(std::size_t{0}, work.size(),
                    [&](std::size_t i) { work[i]->second = run_fit(work[i]->first, sea, solver, g.smaller_spacing_m()); });

  // Step 2's cells get their porosity: faces first, then cores (a core always wins).
  for (std::size_t s = 0; s < layers.size(); ++s) {
    StructureLayer& layer = layers[s];
    if (layer.fitted) take_fit(grid, s, request_of[s], fits.at(request_of[s]), cells, solver, layer, warnings);
    const float n = static_cast<float>(layer.face_porosity);
    for (std::size_t i : cells.faces(s)) grid.porosity.values()[i] = std::min(grid.porosity.values()[i], n);
    // Stones of its own: the grid's stone diameter channel, the solver's D elsewhere; where two
    // structures' faces meet, the finer stones (the more resistance) as the lower porosity above.
    if (layer.stones_fitted) {
      if (grid.porous_stone_diameter_m.size() == 0)
        grid.porous_stone_diameter_m = Raster<float>(g.columns, g.rows, static_cast<float>(solver.porous.stone_diameter_m));
      const float diameter = static_cast<float>(layer.stone_diameter_m);
      for (std::size_t i : cells.faces(s))
        grid.porous_stone_diameter_m.values()[i] = std::min(grid.porous_stone_diameter_m.values()[i], diameter);
    }
  }
  for (std::size_t s = 0; s < layers.size(); ++s)
    for (std::size_t i : cells.core(s)) grid.porosity.values()[i] = 0.0f;
  return layers;
}

}  // namespace nearshore::bake
