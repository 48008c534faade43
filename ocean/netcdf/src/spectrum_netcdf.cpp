// Spectra from wave models' NetCDF output (spectrum_netcdf.hpp): the netCDF C API, one variable
// read at one (time, location) into SampledDirectionalSpectrum.
#include "nearshore/ocean/spectrum_netcdf.hpp"

#include <netcdf.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore::ocean {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// An open NetCDF file whose every failure names the file, the variable and the fix.
class NetcdfFile {
 public:
  explicit NetcdfFile(const std::filesystem::path& path) : path_(path) {
    require_readable_file(path, "a wave model's NetCDF spectral output");
    if (const int status = nc_open(path.c_str(), NC_NOWRITE, &id_); status != NC_NOERR)
      throw Error(path.string(), fmt::format("cannot be opened as NetCDF: {}", nc_strerror(status)),
                  "give the .nc file the wave model wrote (ww3_ounp point output, or SWAN's SPECOUT to a .nc file)");
  }
  ~NetcdfFile() { nc_close(id_); }
  NetcdfFile(const NetcdfFile&) = delete;
  NetcdfFile& operator=(const NetcdfFile&) = delete;

  bool has_variable(const std::string& name) const {
    int variable = 0;
    return nc_inq_varid(id_, name.c_str(), &variable) == NC_NOERR;
  }
  int variable(const std::string& name, const std::string& meaning) const {
    int variable = 0;
    if (nc_inq_varid(id_, name.c_str(), &variable) != NC_NOERR)
      throw Error(path_.string(), fmt::format("has no variable `{}` ({})", name, meaning),
                  "check that the file is the format given by wave_maker.spectrum_format (ncdump -h shows its variables)");
    return variable;
  }
  std::string text_attribute(int variable, const char* attribute) const {
    std::size_t length = 0;
    if (nc_inq_attlen(id_, variable, attribute, &length) != NC_NOERR) return {};
    std::string text(length, '\0');
    if (nc_get_att_text(id_, variable, attribute, text.data()) != NC_NOERR) return {};
    return std::string(text.c_str());
  }
  std::optional<double> number_attribute(int variable, const char* attribute) const {
    double value = 0.0;
    if (nc_get_att_double(id_, variable, attribute, &value) != NC_NOERR) return std::nullopt;
    return value;
  }
  // (name, length) of each dimension of the variable, in storage order.
  std::vector<std::pair<std::string, std::size_t>> dimensions(int variable) const {
    int count = 0;
    nc_inq_varndims(id_, variable, &count);
    std::vector<int> ids(static_cast<std::size_t>(count));
    nc_inq_vardimid(id_, variable, ids.data());
    std::vector<std::pair<std::string, std::size_t>> result;
    for (int id : ids) {
      char name[NC_MAX_NAME + 1] = {};
      std::size_t length = 0;
      nc_inq_dim(id_, id, name, &length);
      result.emplace_back(name, length);
    }
    return result;
  }
  // A 1-D coordinate variable, read as double.
  std::vector<double> coordinate(const std::string& name, const std::string& meaning) const {
    const int v = variable(name, meaning);
    const auto dims = dimensions(v);
    if (dims.size() != 1)
      throw Error(path_.string(), fmt::format("variable `{}` ({}) has {} dimensions, not 1", name, meaning, dims.size()),
                  "give a file whose coordinate variables are one-dimensional");
    std::vector<double> values(dims.front().second);
    nc_get_var_double(id_, v, values.data());
    return values;
  }
  std::vector<double> slab(int variable, const std::vector<std::size_t>& start, const std::vector<std::size_t>& count) const {
    std::size_t total = 1;
    for (std::size_t c : count) total *= c;
    std::vector<double> values(total);
    if (const int status = nc_get_vara_double(id_, variable, start.data(), count.data(), values.data()); status != NC_NOERR)
      throw Error(path_.string(), fmt::format("cannot read the spectrum: {}", nc_strerror(status)), "check the file is complete");
    return values;
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int id_ = -1;
};

// Per degree (x 180 / pi to per radian) or per radian, from the units attribute as WW3 and SWAN
// write it ("m2 s rad-1", "m2/Hz/degr", "m2 s degree-1"); refused otherwise.
double to_per_radian(const NetcdfFile& file, const std::string& name, const std::string& units) {
  const std::string u = lower(units);
  const bool variance = u.rfind("m2", 0) == 0 || u.rfind("m^2", 0) == 0;
  if (variance && (u.find("rad") != std::string::npos)) return 1.0;
  if (variance && (u.find("deg") != std::string::npos)) return 180.0 / std::numbers::pi;
  throw Error(file.path().string(),
              fmt::format("variable `{}` has units \"{}\", not a variance density per Hz and per degree or radian "
                          "(\"m2 s rad-1\", \"m2/Hz/degr\")",
                          name, units),
              "write the variance density (SWAN: VaDens, not EnDens; WW3: efth)");
}

}  // namespace

SampledDirectionalSpectrum read_netcdf_spectrum(const std::filesystem::path& path, const NetcdfSpectrumSelection& selection) {
  const NetcdfFile file(path);
  const bool ww3 = selection.layout == NetcdfSpectrumLayout::kWavewatch3;
  std::string name = "efth";
  if (!ww3) name = file.has_variable("density") ? "density" : "energy";
  const int density = file.variable(name, ww3 ? "WAVEWATCH III's directional variance density efth(time, station, frequency, direction)"
                                              : "SWAN's 2-D variance density (density or energy)");
  // The dimensions, by name.
  const auto dims = file.dimensions(density);
  int frequency_dim = -1, direction_dim = -1, time_dim = -1, location_dim = -1;
  for (std::size_t i = 0; i < dims.size(); ++i) {
    const std::string d = lower(dims[i].first);
    int& slot = d.find("freq") != std::string::npos ? frequency_dim
                : d.find("dir") != std::string::npos ? direction_dim
                : d.find("time") != std::string::npos ? time_dim
                                                      : location_dim;
    if (slot >= 0)
      throw Error(path.string(), fmt::format("variable `{}` has dimensions {} and {} of one kind", name, dims[static_cast<std::size_t>(slot)].first, dims[i].first),
                  "give a file with one frequency, one direction, at most one time and one location dimension");
    slot = static_cast<int>(i);
  }
  if (frequency_dim < 0 || direction_dim < 0)
    throw Error(path.string(), fmt::format("variable `{}` has no frequency or no direction dimension", name),
                "give a 2-D (frequency-direction) spectrum, not a 1-D one");
  std::vector<std::size_t> start(dims.size(), 0), count(dims.size(), 1);
  const auto pick = [&](int dim, std::size_t index, const char* what, const char* key) {
    if (dim < 0) {
      if (index > 0)
        throw Error(path.string(), fmt::format("variable `{}` has no {} dimension, so {} index {} does not exist", name, what, what, index + 1),
                    fmt::format("leave {} out", key));
      return;
    }
    const auto& [dim_name, length] = dims[static_cast<std::size_t>(dim)];
    if (index >= length)
      throw Error(path.string(), fmt::format("has {} {}s (dimension `{}` of `{}`), so {} index {} does not exist", length, what, dim_name, name, what, index + 1),
                  fmt::format("give {} from 1 to {}", key, length));
    start[static_cast<std::size_t>(dim)] = index;
  };
  pick(location_dim, selection.location_index, "location", "wave_maker.spectrum_location");
  pick(time_dim, selection.time_index, "time", "wave_maker.spectrum_time_index");
  const std::size_t nf = dims[static_cast<std::size_t>(frequency_dim)].second, nd = dims[static_cast<std::size_t>(direction_dim)].second;
  count[static_cast<std::size_t>(frequency_dim)] = nf;
  count[static_cast<std::size_t>(direction_dim)] = nd;
  std::vector<double> values = file.slab(density, start, count);
  // The slab is row-major over the variable's dimensions with the other counts 1: frequency before
  // direction or after it.
  const bool frequency_first = frequency_dim < direction_dim;
  const auto value_at = [&](std::size_t f, std::size_t d) { return frequency_first ? values[f * nd + d] : values[d * nf + f]; };

  const double scale = file.number_attribute(density, "scale_factor").value_or(1.0);
  const double offset = file.number_attribute(density, "add_offset").value_or(0.0);
  const std::optional<double> fill = file.number_attribute(density, "_FillValue");
  const double per_radian = to_per_radian(file, name, file.text_attribute(density, "units"));

  // Frequencies (Hz) and the direction convention.
  const std::string frequency_name = dims[static_cast<std::size_t>(frequency_dim)].first;
  const std::string direction_name = dims[static_cast<std::size_t>(direction_dim)].first;
  const std::vector<double> frequencies = file.coordinate(frequency_name, "frequencies in Hz");
  const std::vector<double> directions_deg = file.coordinate(direction_name, "directions in degrees");
  const int direction_variable = file.variable(direction_name, "directions in degrees");
  const std::string convention = lower(file.text_attribute(direction_variable, "standard_name") + " " +
                                       file.text_attribute(direction_variable, "long_name"));
  const bool from = convention.find("from") != std::string::npos;
  const bool to = convention.find("to_direction") != std::string::npos || convention.find("to direction") != std::string::npos;
  if (from == to)
    throw Error(path.string(),
                fmt::format("variable `{}` does not say whether its directions are where waves come from or go to "
                            "(standard_name \"{}\")",
                            direction_name, file.text_attribute(direction_variable, "standard_name")),
                "set its standard_name to sea_surface_wave_from_direction or sea_surface_wave_to_direction");
  // Direction of travel, counter-clockwise from east: nautical "from" 270 - D; WW3's nautical "to"
  // 90 - D; SWAN's "to" is its Cartesian CDIR, D itself.
  const auto travel_rad = [&](double d) {
    if (from) return wrap_angle_rad((270.0 - d) * kDegree);
    return wrap_angle_rad((ww3 ? 90.0 - d : d) * kDegree);
  };

  SampledDirectionalSpectrum result;
  result.source = fmt::format("{}, variable {}, location {}, time {}", path.string(), name, selection.location_index + 1,
                              selection.time_index + 1);
  result.frequencies_hz = frequencies;
  std::vector<std::size_t> order(nd);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return travel_rad(directions_deg[a]) < travel_rad(directions_deg[b]); });
  for (std::size_t k : order) result.directions_rad.push_back(travel_rad(directions_deg[k]));
  result.density_m2_hz_rad.reserve(nf * nd);
  for (std::size_t f = 0; f < nf; ++f)
    for (std::size_t k : order) {
      const double raw = value_at(f, k);
      if ((fill && raw == *fill) || !std::isfinite(raw))
        throw Error(path.string(), fmt::format("variable `{}` has a missing value at frequency {}, direction {} of {}", name, f + 1, k + 1, result.source),
                    "choose a location and time the model computed (wave_maker.spectrum_location, spectrum_time_index)");
      result.density_m2_hz_rad.push_back((raw * scale + offset) * per_radian);
    }
  check_sampled_spectrum(result);
  return result;
}

}  // namespace nearshore::ocean
