#include "nearshore/ocean/spectrum_registry.hpp"

#include <numbers>

#include "nearshore/core/error.hpp"
#include "nearshore/ocean/sea_state_beaufort.hpp"

namespace nearshore::ocean {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

double direction_rad(SpectrumParameters& parameters, const std::string& key, double default_rad) {
  return kDegree * parameters.number(key, default_rad / kDegree, -360.0, 360.0, false,
                                     "direction of travel in degrees counter-clockwise from +x (east)");
}

// A spectrum that still cannot be built from checked keys says why under `spectrum`.
template <class Make>
auto built(SpectrumParameters& parameters, Make&& make) -> decltype(make()) {
  try {
    return make();
  } catch (const Error& error) {
    parameters.fail("spectrum", "cannot be built: " + error.problem(), error.fix());
  }
  throw Error("spectrum", "was not built", "report this: SpectrumParameters::fail returned");  // unreachable
}

// ---- frequency spectra (Hs, Tp) and their directional form -------------------------------------
double significant_height_m(SpectrumParameters& p) {
  return p.positive("significant_height_m", std::nullopt, "significant wave height Hs in metres");
}
double peak_period_s(SpectrumParameters& p) { return p.positive("peak_period_s", std::nullopt, "peak period Tp in seconds"); }
double peak_enhancement(SpectrumParameters& p) {
  return p.number("peak_enhancement", 3.3, 1.0, 20.0, false, "JONSWAP gamma (1 = Pierson-Moskowitz)");
}

std::shared_ptr<const FrequencySpectrum> jonswap(SpectrumParameters& p) {
  const double hs = significant_height_m(p), tp = peak_period_s(p), gamma = peak_enhancement(p);
  return built(p, [&]() -> std::shared_ptr<const FrequencySpectrum> { return std::make_shared<JonswapSpectrum>(hs, tp, gamma); });
}
std::shared_ptr<const FrequencySpectrum> pierson_moskowitz(SpectrumParameters& p) {
  const double hs = significant_height_m(p), tp = peak_period_s(p);
  return built(p, [&]() -> std::shared_ptr<const FrequencySpectrum> { return std::make_shared<PiersonMoskowitzSpectrum>(hs, tp); });
}
std::shared_ptr<const FrequencySpectrum> tma(SpectrumParameters& p) {
  const std::shared_ptr<const FrequencySpectrum> deep = jonswap(p);
  const double depth_m = p.positive("tma_depth_m", std::nullopt, "depth of the TMA transformation in metres");
  return built(p, [&]() -> std::shared_ptr<const FrequencySpectrum> { return std::make_shared<TmaSpectrum>(deep, depth_m); });
}

// A frequency spectrum with cos^2s spreading, converted to wavenumbers at the defaults' depth.
template <std::shared_ptr<const FrequencySpectrum> (*Frequency)(SpectrumParameters&)>
std::shared_ptr<const WavenumberSpectrum> directional(SpectrumParameters& p, const SpectrumDefaults& defaults) {
  const std::shared_ptr<const FrequencySpectrum> spectrum = Frequency(p);
  const double mean_direction_rad = direction_rad(p, "mean_direction_deg", defaults.direction_rad);
  const double spreading_s = p.number("spreading_s", 20.0, 1.0, 1000.0, false, "cos^2s exponent s (10-25 wind sea, 75 swell)");
  return built(p, [&]() -> std::shared_ptr<const WavenumberSpectrum> {
    return std::make_shared<DirectionalWavenumberSpectrum>(
        spectrum, std::make_shared<CosineSquaredSpreading>(mean_direction_rad, spreading_s), defaults.still_water_depth_m);
  });
}

// ---- wind spectra (wavenumber) -------------------------------------------------------------------
std::shared_ptr<const WavenumberSpectrum> phillips(SpectrumParameters& p, const SpectrumDefaults& defaults) {
  const double wind_m_s = p.positive("wind_speed_m_s", std::nullopt, "wind speed U of Lw = U^2 / g in m/s");
  const double hs_m = p.positive("significant_height_m", std::nullopt, "significant wave height Hs in metres (sets A)");
  const double wind_direction_rad = direction_rad(p, "wind_direction_deg", defaults.direction_rad);
  return built(p, [&]() -> std::shared_ptr<const WavenumberSpectrum> {
    return std::make_shared<PhillipsSpectrum>(PhillipsSpectrum::amplitude_for_significant_wave_height(hs_m, wind_m_s),
                                              wind_m_s, wind_direction_rad);
  });
}

std::shared_ptr<const WavenumberSpectrum> unified(SpectrumParameters& p, const SpectrumDefaults& defaults) {
  const double wind_m_s = p.positive("wind_speed_10_m_s", std::nullopt, "wind speed 10 m above the sea in m/s");
  if (p.has("inverse_wave_age") && p.has("fetch_m"))
    p.fail("inverse_wave_age", "and fetch_m are both given", "give one of them (the fetch sets the inverse wave age)");
  const double fetch_m = p.number("fetch_m", 0.0, 0.0, std::numeric_limits<double>::infinity(), true, "fetch in metres");
  const double given_age = p.number("inverse_wave_age", 0.84, 0.84, 5.0, false, "Omega_c = U10 / c_p (0.84 fully developed .. 5 young)");
  const double wind_direction_rad = direction_rad(p, "wind_direction_deg", defaults.direction_rad);
  return built(p, [&]() -> std::shared_ptr<const WavenumberSpectrum> {
    const double inverse_wave_age = fetch_m > 0 ? UnifiedSpectrum::inverse_wave_age_from_fetch(wind_m_s, fetch_m) : given_age;
    return std::make_shared<UnifiedSpectrum>(wind_m_s, inverse_wave_age, wind_direction_rad);
  });
}

std::shared_ptr<const WavenumberSpectrum> pm_ittc(SpectrumParameters& p, const SpectrumDefaults& defaults) {
  const double wind_m_s = p.positive("wind_speed_10_m_s", std::nullopt, "wind speed 10 m above the sea in m/s");
  const double wind_direction_rad = direction_rad(p, "wind_direction_deg", defaults.direction_rad);
  return built(p, [&]() -> std::shared_ptr<const WavenumberSpectrum> { return std::make_shared<PmIttcSpectrum>(wind_m_s, wind_direction_rad); });
}

std::shared_ptr<const WavenumberSpectrum> beaufort(SpectrumParameters& p, const SpectrumDefaults& defaults) {
  const int force = p.integer("beaufort_force", std::nullopt, 1, 12, "Beaufort force (1 light air .. 12 hurricane; 0 is a flat sea)");
  const std::size_t choice = p.choice("beaufort_spectrum", "seed", {"seed", "phillips", "unified"});
  const double wind_direction_rad = direction_rad(p, "wind_direction_deg", defaults.direction_rad);
  return built(p, [&]() -> std::shared_ptr<const WavenumberSpectrum> {
    return beaufort_preset(force, wind_direction_rad, static_cast<BeaufortSpectrum>(choice)).spectrum;
  });
}

}  // namespace

const std::vector<SpectrumEntry>& spectrum_registry() {
  static const std::vector<SpectrumEntry> registry = {
      {"jonswap", "JONSWAP (Hasselmann et al. 1973): Hs, Tp, gamma", jonswap, directional<jonswap>},
      {"pierson_moskowitz", "Pierson-Moskowitz (1964), fully developed: Hs, Tp", pierson_moskowitz,
       directional<pierson_moskowitz>},
      {"tma", "TMA (Bouws et al. 1985): JONSWAP in finite depth", tma, directional<tma>},
      {"phillips", "Phillips (Tessendorf 1999; seed 000 eq. 3.8): wind speed, Hs", nullptr, phillips},
      {"unified", "unified (Elfouhaily et al. 1997): U10, wave age or fetch", nullptr, unified},
      {"pm_ittc", "PM-ITTC (seed 001 eq. 15): U10", nullptr, pm_ittc},
      {"beaufort", "a Beaufort force preset (seed 000 table 3.1)", nullptr, beaufort},
  };
  return registry;
}

std::vector<std::string> spectrum_names(bool with_frequency_spectrum_only) {
  std::vector<std::string> names;
  for (const SpectrumEntry& entry : spectrum_registry())
    if (!with_frequency_spectrum_only || entry.frequency) names.emplace_back(entry.name);
  return names;
}

const SpectrumEntry& spectrum_entry(std::string_view name) {
  for (const SpectrumEntry& entry : spectrum_registry())
    if (entry.name == name) return entry;
  std::string known;
  for (const std::string& entry : spectrum_names(false)) known += (known.empty() ? "" : ", ") + entry;
  throw Error("spectrum \"" + std::string(name) + "\"", "is not a spectrum nearshore knows", "use one of " + known);
}

}  // namespace nearshore::ocean
