#include "nearshore/bake/structure_layers.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "nearshore/core/error.hpp"
#include "nearshore/ocean/linear_waves.hpp"

namespace nearshore::bake {

using boussinesq::LayerResponse;

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

nlohmann::json structure_layers_record(const std::vector<StructureLayer>& layers) {
  auto response = [](const LayerResponse& r) {
    return nlohmann::json{{"porosity", r.porosity},
                          {"stone_diameter_m", r.stone_diameter_m},
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
                         {"stone_diameter_m", layer.stone_diameter_m},
                         {"stones_fitted", layer.stones_fitted},
                         {"depth_m", layer.depth_m},
                         {"face_width_m", layer.face_width_m},
                         {"widening_m", layer.widening_m},
                         {"core_cells", layer.core_cells},
                         {"face_cells", layer.face_cells}};
    if (layer.fitted) {
      entry["peak_period_s"] = layer.wave_period_s;
      entry["flume_depth_m"] = layer.flume_depth_m;
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
    text += fmt::format("; {:.0f} m of faces{} at porosity {:.2f}{} in {:.1f} m of water, {} wall cells", layer.face_width_m,
                        layer.widening_m > 0 ? fmt::format(" (widened by {:.0f} m to absorb enough)", layer.widening_m) : std::string(),
                        layer.face_porosity,
                        layer.stones_fitted ? fmt::format(" with effective stones of {:.2g} m (finer than the solver's: porosity alone "
                                                          "could not absorb enough)",
                                                          layer.stone_diameter_m)
                                            : std::string(),
                        layer.depth_m, layer.core_cells);
    // Fitted in deeper water than the layer stands in (beyond the shared fits' 10 % bins): say so.
    if (layer.flume_depth_m > 1.1 * layer.depth_m)
      text += fmt::format(" (fitted in {:.1f} m: the shallowest water in which the grid's cells carry the sea's shortest wave)",
                          layer.flume_depth_m);
  }
  return text;
}

}  // namespace nearshore::bake
