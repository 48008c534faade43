#pragma once
// One road from a spectrum's name in a case file (or a host's settings) to its class: each entry
// names the spectrum and builds it from its parameters. A new spectrum is one class, one entry in
// spectrum_registry.cpp and one test case (STYLE.md, pbrt's single factory route); the bake's case
// reader and the runtime's settings both go through here.
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nearshore/ocean/spectrum.hpp"
#include "nearshore/ocean/spectrum_wavenumber.hpp"

namespace nearshore::ocean {

/// How a spectrum's builder reads its parameters: a case file's table (the bake), a JSON object or
/// a host's settings. The reader knows where the values come from, so it reports missing keys and
/// out-of-range values itself, naming its own file and key.
class SpectrumParameters {
 public:
  virtual ~SpectrumParameters() = default;
  virtual bool has(const std::string& key) const = 0;
  /// A number in [minimum, maximum] (> minimum when exclusive_minimum); `fallback` when absent,
  /// required when it is nullopt. `meaning` says what it is, with its unit, for messages.
  virtual double number(const std::string& key, std::optional<double> fallback, double minimum, double maximum,
                        bool exclusive_minimum, const std::string& meaning) = 0;
  virtual int integer(const std::string& key, std::optional<int> fallback, int minimum, int maximum,
                      const std::string& meaning) = 0;
  /// One of `choices`, as its index.
  virtual std::size_t choice(const std::string& key, std::optional<std::string> fallback,
                             const std::vector<std::string>& choices) = 0;
  /// Reports a problem with `key` (throws; never returns).
  [[noreturn]] virtual void fail(const std::string& key, const std::string& problem, const std::string& fix) = 0;

  double positive(const std::string& key, std::optional<double> fallback, const std::string& meaning) {
    return number(key, fallback, 0.0, std::numeric_limits<double>::infinity(), true, meaning);
  }
};

/// What a directional spectrum takes when its parameters do not say: the direction waves travel
/// (radians counter-clockwise from +x, east) and the still-water depth (m; <= 0 deep) at which a
/// frequency spectrum is converted to wavenumbers.
struct SpectrumDefaults {
  double direction_rad = 0.0;
  double still_water_depth_m = 0.0;
};

struct SpectrumEntry {
  std::string_view name;     ///< the case file's name: "jonswap", "phillips", ...
  std::string_view summary;  ///< one line, with the reference
  /// The frequency spectrum, for the irregular wave maker; null for spectra defined in wavenumbers
  /// (the wind spectra), which cannot drive a maker along a line.
  std::shared_ptr<const FrequencySpectrum> (*frequency)(SpectrumParameters&);
  /// The directional wavenumber spectrum, for the deep-water field.
  std::shared_ptr<const WavenumberSpectrum> (*wavenumber)(SpectrumParameters&, const SpectrumDefaults&);
};

/// Every spectrum nearshore knows, in the order documented in docs/commands/bake.md.
const std::vector<SpectrumEntry>& spectrum_registry();
/// The names, all of them or only those with a frequency spectrum.
std::vector<std::string> spectrum_names(bool with_frequency_spectrum_only);
/// The entry of `name`; throws nearshore::Error listing the known names.
const SpectrumEntry& spectrum_entry(std::string_view name);

}  // namespace nearshore::ocean
