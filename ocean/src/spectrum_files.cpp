#include "nearshore/ocean/spectrum_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <numeric>
#include <optional>
#include <sstream>
#include <string_view>

#include "nearshore/core/error.hpp"
#include "nearshore/ocean/linear_waves.hpp"
#include "nearshore/ocean/spectrum_quadrature.hpp"

namespace nearshore::ocean {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

/// Nautical "coming from, clockwise from north" (deg) -> travel direction CCW from east (rad).
double nautical_from_to_travel_rad(double nautical_deg) {
  return wrap_angle_rad((270.0 - nautical_deg) * kDegree);
}

std::vector<std::string> split_tokens(std::string_view line) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) tokens.emplace_back(line.substr(start, i - start));
  }
  return tokens;
}

std::optional<double> parse_number(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

std::vector<std::string> read_lines(const std::filesystem::path& path, const std::string& what) {
  require_readable_file(path, what);
  std::ifstream in(path);
  if (!in) throw Error(path.string(), "cannot be opened for reading", "check its permissions");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
  }
  return lines;
}

// ---------------------------------------------------------------------------------------------
// SWAN .sp2 (SWAN user manual, appendix D "Spectrum files, input and output"). The format is
// line-oriented: a keyword line (its first word; the rest is a comment), then the lines of that
// block, each a number first and an optional comment after it. Lines starting with `$` are comments.

class SwanLines {
 public:
  SwanLines(const std::filesystem::path& path, std::vector<std::string> lines)
      : path_(path.string()), lines_(std::move(lines)) {}

  [[noreturn]] void fail(std::size_t line_index, const std::string& problem, const std::string& fix) const {
    throw Error(path_, fmt::format("line {}: {}", line_index + 1, problem), fix);
  }
  /// The next non-comment line's index (and its tokens), or nullopt at the end of the file.
  std::optional<std::size_t> next() {
    while (position_ < lines_.size()) {
      const std::size_t index = position_++;
      const auto tokens = split_tokens(lines_[index]);
      if (tokens.empty() || tokens.front().front() == '$') continue;
      tokens_ = tokens;
      return index;
    }
    return std::nullopt;
  }
  const std::vector<std::string>& tokens() const { return tokens_; }

  std::size_t require_line(const std::string& expected) {
    const auto index = next();
    if (!index)
      throw Error(path_, fmt::format("ends (after line {}) where {} was expected", lines_.size(), expected),
                  "write the whole file as SWAN's appendix D describes (was it cut short?)");
    return *index;
  }
  /// The next line's first word, which must be one of `keywords`.
  std::string keyword(const std::vector<std::string>& keywords, const std::string& block_meaning) {
    const std::size_t index = require_line("the " + block_meaning + " block");
    const std::string& word = tokens_.front();
    if (std::find(keywords.begin(), keywords.end(), word) == keywords.end())
      fail(index,
           fmt::format("reads '{}' where the {} block ({}) was expected", word, block_meaning,
                       fmt::join(keywords, " or ")),
           fmt::format("add the {} block (keyword, count, values) in SWAN's order", block_meaning));
    last_line_ = index;
    return word;
  }
  /// The next line's first number, with its meaning for messages.
  double number(const std::string& meaning) {
    const std::size_t index = require_line(meaning);
    last_line_ = index;
    const auto value = parse_number(tokens_.front());
    if (!value)
      fail(index, fmt::format("reads '{}' where {} (a number) was expected", tokens_.front(), meaning),
           "check the count of the block above: it must match the number of lines that follow it");
    return *value;
  }
  int count(const std::string& meaning, int minimum) {
    const double value = number(meaning);
    if (value != std::floor(value) || value < minimum || value > 1e7)
      fail(last_line_, fmt::format("{} is {}, not a whole number >= {}", meaning, value, minimum),
           "write the count as a whole number");
    return static_cast<int>(value);
  }
  std::size_t last_line() const { return last_line_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<std::string> lines_;
  std::vector<std::string> tokens_;
  std::size_t position_ = 0, last_line_ = 0;
};

}  // namespace

SampledDirectionalSpectrum read_swan_spectrum(const std::filesystem::path& path,
                                              const SwanSpectrumSelection& selection) {
  SwanLines in(path, read_lines(path, "a SWAN 2-D spectral file (.sp2)"));

  // 1. The header: SWAN, [TIME + coding option], LONLAT/LOCATIONS + count + one line each.
  {
    const auto first = in.next();
    if (!first || in.tokens().front() != "SWAN")
      throw Error(in.path(),
                  first
                      ? fmt::format("line {}: starts with '{}', not 'SWAN'", *first + 1, in.tokens().front())
                      : std::string("is empty"),
                  "give a SWAN spectral output file (SPECOUT ... SPEC2D in the SWAN command file)");
  }
  std::string word = in.keyword({"TIME", "LONLAT", "LOCATIONS"}, "TIME or locations");
  const bool timed = word == "TIME";
  if (timed) {
    in.count("the time coding option", 1);
    word = in.keyword({"LONLAT", "LOCATIONS"}, "locations (LONLAT or LOCATIONS)");
  }
  const int location_count = in.count("the number of locations", 1);
  for (int i = 0; i < location_count; ++i) {
    in.number(fmt::format("location {} of {}", i + 1, location_count));
    if (in.tokens().size() < 2 || !parse_number(in.tokens()[1]))
      in.fail(in.last_line(),
              fmt::format("location {} of {} has no second coordinate", i + 1, location_count),
              "give two coordinates (x y or lon lat) per location");
  }
  if (selection.location_index >= static_cast<std::size_t>(location_count))
    throw Error(in.path(),
                fmt::format("has {} locations; location index {} (0-based) was asked for", location_count,
                            selection.location_index),
                fmt::format("ask for a location index from 0 to {}", location_count - 1));

  // 2. Frequencies (absolute AFREQ, or relative RFREQ: the intrinsic frequency, equal to the
  //    absolute one without a current; both are taken as the wave frequency here).
  in.keyword({"AFREQ", "RFREQ"}, "frequencies (AFREQ or RFREQ)");
  const int frequency_count = in.count("the number of frequencies", 2);
  SampledDirectionalSpectrum result;
  for (int i = 0; i < frequency_count; ++i) {
    const double f = in.number(fmt::format("frequency {} of {} (Hz)", i + 1, frequency_count));
    if (!(f > 0.0) || (!result.frequencies_hz.empty() && !(f > result.frequencies_hz.back())))
      in.fail(
          in.last_line(),
          fmt::format("frequency {} of {} is {} Hz: not positive and increasing", i + 1, frequency_count, f),
          "list the frequencies in Hz from the lowest up");
    result.frequencies_hz.push_back(f);
  }

  // 3. Directions: NDIR nautical (coming from, clockwise from north), CDIR Cartesian (going to,
  //    counter-clockwise from east, the project's convention), both in degrees.
  {
    const std::size_t index = in.require_line("the directions block (NDIR or CDIR)");
    const std::string& keyword = in.tokens().front();
    if (keyword == "QUANT")
      in.fail(index, "has no directions block: this is a 1-D spectrum file (.sp1)",
              "write the 2-D spectrum (SPECOUT ... SPEC2D in the SWAN command file)");
    if (keyword != "NDIR" && keyword != "CDIR")
      in.fail(index,
              fmt::format("reads '{}' where the directions block (NDIR or CDIR) was expected", keyword),
              "add the directions block (NDIR or CDIR, count, one direction in degrees per line)");
  }
  const bool nautical = in.tokens().front() == "NDIR";
  const int direction_count = in.count("the number of directions", 2);
  std::vector<double> file_directions_rad;
  for (int i = 0; i < direction_count; ++i) {
    const double d = in.number(fmt::format("direction {} of {} (degrees)", i + 1, direction_count));
    file_directions_rad.push_back(nautical ? nautical_from_to_travel_rad(d) : wrap_angle_rad(d * kDegree));
  }

  // 4. The quantity: one, variance (m2/Hz/degr) or energy (J/m2/Hz/degr) density.
  in.keyword({"QUANT"}, "quantity (QUANT)");
  const int quantity_count = in.count("the number of quantities", 1);
  if (quantity_count != 1)
    in.fail(in.last_line(), fmt::format("lists {} quantities; a 2-D spectrum file has 1", quantity_count),
            "write the 2-D spectrum (SPEC2D), whose only quantity is VaDens or EnDens");
  const std::size_t quantity_line = in.require_line("the quantity's name (VaDens or EnDens)");
  const std::string quantity = in.tokens().front();
  if (quantity != "VaDens" && quantity != "EnDens")
    in.fail(quantity_line, fmt::format("quantity '{}' is neither VaDens nor EnDens", quantity),
            "write variance (VaDens, m2/Hz/degr) or energy (EnDens, J/m2/Hz/degr) density");
  in.require_line("the quantity's unit");
  const double exception_value = in.number("the exception value");
  if (!(selection.water_density_kg_m3 > 0.0))
    throw Error("SWAN spectrum selection",
                fmt::format("water density {} kg/m3", selection.water_density_kg_m3),
                "give the density of the water (1025 kg/m3, SWAN's default)");
  // Per degree -> per radian; energy -> variance by 1 / (rho g) (SWAN's EnDens = rho g VaDens).
  const double to_m2_hz_rad =
      (1.0 / kDegree) / (quantity == "EnDens" ? selection.water_density_kg_m3 * kGravity_m_s2 : 1.0);

  // 5. The blocks: per time (a date line when TIME) and per location FACTOR + matrix, NODATA or ZERO.
  std::vector<std::string> times_seen;
  for (int time_index = 0;; ++time_index) {
    std::string time_label = "stationary";
    if (timed) {
      const auto index = in.next();
      if (!index) break;
      time_label = in.tokens().front();
      times_seen.push_back(time_label);
    } else if (time_index > 0) {
      break;
    }
    const bool wanted_time = selection.time.empty() || selection.time == time_label || !timed;
    for (int location = 0; location < location_count; ++location) {
      const std::string block = in.keyword(
          {"FACTOR", "NODATA", "ZERO"},
          fmt::format("location {} at time {} (FACTOR, NODATA or ZERO)", location + 1, time_label));
      const bool wanted = wanted_time && static_cast<std::size_t>(location) == selection.location_index;
      const std::size_t block_line = in.last_line();
      if (block == "NODATA") {
        if (wanted)
          in.fail(block_line,
                  fmt::format("location {} at time {} is NODATA (dry or outside SWAN's grid)", location + 1,
                              time_label),
                  "choose another location or time");
        continue;
      }
      std::vector<double> density(static_cast<std::size_t>(frequency_count) * direction_count, 0.0);
      if (block == "FACTOR") {
        const double factor = in.number("the FACTOR value");
        if (!(factor >= 0.0))
          in.fail(in.last_line(), fmt::format("FACTOR is {}, not a number >= 0", factor),
                  "write FACTOR >= 0");
        // The matrix: frequency_count rows of direction_count integers, read as a stream of words
        // so a row wrapped over lines is still read; counts are checked row by row.
        for (int row = 0; row < frequency_count; ++row) {
          int column = 0;
          while (column < direction_count) {
            const std::size_t line =
                in.require_line(fmt::format("row {} of {} of the matrix", row + 1, frequency_count));
            for (const std::string& token : in.tokens()) {
              const auto value = parse_number(token);
              if (!value || *value != std::floor(*value))
                in.fail(line,
                        fmt::format("reads '{}' in row {} (frequency {} Hz) of the matrix, not an integer",
                                    token, row + 1, result.frequencies_hz[row]),
                        fmt::format("write {} integers per frequency row after FACTOR", direction_count));
              if (column >= direction_count)
                in.fail(line,
                        fmt::format("row {} of the matrix has more than {} values", row + 1, direction_count),
                        fmt::format("write {} values per row, as NDIR/CDIR says", direction_count));
              const double v = *value * factor;
              if (*value < 0.0)
                in.fail(line,
                        fmt::format("row {} column {} is {} (the file's exception value is {}): a negative "
                                    "or missing density",
                                    row + 1, column + 1, v, exception_value),
                        "write the spectrum of a location that SWAN computed, or choose another location");
              density[static_cast<std::size_t>(row) * direction_count + column] = v * to_m2_hz_rad;
              ++column;
            }
          }
        }
      }
      if (wanted) {
        // Sort the directions into increasing travel direction, carrying the columns.
        std::vector<std::size_t> order(direction_count);
        std::iota(order.begin(), order.end(), 0);
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
          return file_directions_rad[a] < file_directions_rad[b];
        });
        for (std::size_t k : order) result.directions_rad.push_back(file_directions_rad[k]);
        result.density_m2_hz_rad.resize(density.size());
        for (int row = 0; row < frequency_count; ++row)
          for (int c = 0; c < direction_count; ++c)
            result.density_m2_hz_rad[static_cast<std::size_t>(row) * direction_count + c] =
                density[static_cast<std::size_t>(row) * direction_count + order[c]];
        result.source = fmt::format("{}, location {}, time {}", in.path(), location + 1, time_label);
        check_sampled_spectrum(result);
        return result;
      }
    }
  }
  throw Error(
      in.path(),
      fmt::format("has no time '{}' (times in the file: {})", selection.time,
                  times_seen.empty() ? std::string("none") : fmt::format("{}", fmt::join(times_seen, ", "))),
      "name a time the file holds, as it writes it (e.g. 20020101.000000), or none for the first");
}

// ---------------------------------------------------------------------------------------------
// NDBC realtime2 spectral files (www.ndbc.noaa.gov/data_spec.shtml): '#' header lines, then one row
// per time, newest first: "YYYY MM DD hh mm [sep_freq] v1 (f1) v2 (f2) ...". Only .data_spec has
// the separation frequency. Missing values are 999 (999.0 for directions, 999.00 for r) and 9.999
// for the separation frequency.

namespace {

struct NdbcRow {
  std::vector<double> values, frequencies_hz;
  std::string time;
};

NdbcRow read_ndbc_row(const std::filesystem::path& path, const std::string& what,
                      bool has_separation_frequency, const std::string& wanted_time,
                      std::string* first_time) {
  const auto lines = read_lines(path, what);
  std::vector<std::string> times;
  for (std::size_t index = 0; index < lines.size(); ++index) {
    const auto tokens = split_tokens(lines[index]);
    if (tokens.empty() || tokens.front().front() == '#') continue;
    auto fail = [&](const std::string& problem, const std::string& fix) {
      throw Error(path.string(), fmt::format("line {}: {}", index + 1, problem), fix);
    };
    if (tokens.size() < 5)
      fail("has fewer than the 5 date words YYYY MM DD hh mm", "write the date first on each row");
    for (int i = 0; i < 5; ++i)
      if (!parse_number(tokens[i]))
        fail(fmt::format("date word {} is '{}', not a number", i + 1, tokens[i]),
             "write the date as YYYY MM DD hh mm");
    const std::string time =
        fmt::format("{} {} {} {} {}", tokens[0], tokens[1], tokens[2], tokens[3], tokens[4]);
    times.push_back(time);
    const std::string target =
        wanted_time.empty() ? (first_time && !first_time->empty() ? *first_time : time) : wanted_time;
    if (time != target) continue;
    NdbcRow row;
    row.time = time;
    std::size_t i = 5 + (has_separation_frequency ? 1 : 0);
    if (has_separation_frequency && (tokens.size() < 6 || !parse_number(tokens[5])))
      fail("has no separation frequency after the date",
           "write the .data_spec row as NDBC does: date, sep_freq, pairs");
    if ((tokens.size() - i) % 2 != 0 || tokens.size() == i)
      fail(fmt::format("has {} words after the date: not pairs 'value (frequency)'", tokens.size() - i),
           "write each band as 'value (frequency)'");
    for (; i < tokens.size(); i += 2) {
      const auto value = parse_number(tokens[i]);
      std::string_view f = tokens[i + 1];
      const bool bracketed = f.size() > 2 && f.front() == '(' && f.back() == ')';
      const auto frequency = bracketed ? parse_number(f.substr(1, f.size() - 2)) : std::nullopt;
      if (!value || !frequency)
        fail(fmt::format("band {} reads '{} {}', not 'value (frequency)'", row.values.size() + 1, tokens[i],
                         tokens[i + 1]),
             "write each band as a number and its frequency in brackets, e.g. 0.512 (0.100)");
      if (!(*frequency > 0.0) || (!row.frequencies_hz.empty() && !(*frequency > row.frequencies_hz.back())))
        fail(fmt::format("band {} frequency {} Hz is not positive and increasing", row.values.size() + 1,
                         *frequency),
             "list the bands from the lowest frequency up");
      row.values.push_back(*value);
      row.frequencies_hz.push_back(*frequency);
    }
    if (first_time && first_time->empty()) *first_time = time;
    return row;
  }
  const std::string target = wanted_time.empty() ? (first_time ? *first_time : std::string()) : wanted_time;
  throw Error(path.string(),
              target.empty() ? std::string("has no data rows (only '#' header lines or nothing)")
                             : fmt::format("has no row for time '{}' ({} rows read)", target, times.size()),
              "give the five files of the same buoy and time (the .data_spec file's time is the one used)");
}

}  // namespace

SampledDirectionalSpectrum read_ndbc_spectrum(const NdbcSpectrumFiles& files,
                                              const NdbcSpectrumSelection& selection) {
  if (selection.direction_count < 8 || selection.direction_count > 3600)
    throw Error("NDBC spectrum selection", fmt::format("direction_count = {}", selection.direction_count),
                "use 8 to 3600 directions (72 = 5 degrees apart)");
  // The density file sets the time; the other four must hold the same time and frequencies.
  std::string time = selection.time;
  const NdbcRow density = read_ndbc_row(files.spectral_density, "an NDBC spectral density file (.data_spec)",
                                        true, selection.time, &time);
  const NdbcRow alpha1 =
      read_ndbc_row(files.mean_direction, "an NDBC mean direction file (.swdir)", false, time, nullptr);
  const NdbcRow alpha2 = read_ndbc_row(files.principal_direction,
                                       "an NDBC principal direction file (.swdir2)", false, time, nullptr);
  const NdbcRow r1 = read_ndbc_row(files.first_coefficient, "an NDBC r1 file (.swr1)", false, time, nullptr);
  const NdbcRow r2 = read_ndbc_row(files.second_coefficient, "an NDBC r2 file (.swr2)", false, time, nullptr);
  const std::vector<std::pair<const NdbcRow*, const std::filesystem::path*>> others = {
      {&alpha1, &files.mean_direction},
      {&alpha2, &files.principal_direction},
      {&r1, &files.first_coefficient},
      {&r2, &files.second_coefficient}};
  for (const auto& [row, path] : others) {
    bool same = row->frequencies_hz.size() == density.frequencies_hz.size();
    for (std::size_t i = 0; same && i < row->frequencies_hz.size(); ++i)
      same = std::abs(row->frequencies_hz[i] - density.frequencies_hz[i]) <=
             1e-6 + 1e-4 * density.frequencies_hz[i];
    if (!same)
      throw Error(path->string(),
                  fmt::format("time {}: its {} bands' frequencies differ from the {} bands of {}", time,
                              row->frequencies_hz.size(), density.frequencies_hz.size(),
                              files.spectral_density.string()),
                  "give the five files of the same buoy (their bands must match)");
  }

  SampledDirectionalSpectrum result;
  result.frequencies_hz = density.frequencies_hz;
  const int n = selection.direction_count;
  for (int k = 0; k < n; ++k) result.directions_rad.push_back(wrap_angle_rad(-kPi + (k + 1) * 2.0 * kPi / n));
  std::sort(result.directions_rad.begin(), result.directions_rad.end());
  const double direction_step_rad = 2.0 * kPi / n;
  result.density_m2_hz_rad.assign(result.frequencies_hz.size() * n, 0.0);
  for (std::size_t i = 0; i < result.frequencies_hz.size(); ++i) {
    const double e = density.values[i];
    const double f = result.frequencies_hz[i];
    if (!(e >= 0.0) || e >= 999.0)
      throw Error(files.spectral_density.string(),
                  fmt::format("time {}: band {} ({} Hz) density is {} m2/Hz: negative or missing (999)", time,
                              i + 1, f, e),
                  "choose a time whose spectrum the buoy measured");
    if (e == 0.0) continue;  // no energy: its direction values (often 999) do not matter
    const auto check_value = [&](const NdbcRow& row, const std::filesystem::path& path, double low,
                                 double high, const char* meaning) {
      const double v = row.values[i];
      if (!(v >= low && v <= high))
        throw Error(
            path.string(),
            fmt::format("time {}: band {} ({} Hz) {} is {}, outside [{}, {}] (999 = missing) where the "
                        "density is {} m2/Hz",
                        time, i + 1, f, meaning, v, low, high, e),
            "choose a time whose directional moments the buoy measured");
      return v;
    };
    const double a1 = check_value(alpha1, files.mean_direction, 0.0, 360.0, "alpha1 (degrees)");
    const double a2 = check_value(alpha2, files.principal_direction, 0.0, 360.0, "alpha2 (degrees)");
    const double c1 = check_value(r1, files.first_coefficient, 0.0, 1.0, "r1");
    const double c2 = check_value(r2, files.second_coefficient, 0.0, 1.0, "r2");
    // D(f, a) = 1/pi (1/2 + r1 cos(a - alpha1) + r2 cos(2 (a - alpha2))), a nautical (NDBC,
    // Longuet-Higgins et al. 1963). Written in travel directions: a - alpha = -(theta - theta_alpha)
    // (the map a -> theta is a reflection plus a shift), and the cosines are even, so the same form
    // holds with theta and the converted alphas.
    const double t1 = nautical_from_to_travel_rad(a1), t2 = nautical_from_to_travel_rad(a2);
    std::vector<double> spreading(n);
    double sum = 0.0;
    for (int k = 0; k < n; ++k) {
      const double theta = result.directions_rad[k];
      spreading[k] =
          std::max(0.0, (0.5 + c1 * std::cos(theta - t1) + c2 * std::cos(2.0 * (theta - t2))) / kPi);
      sum += spreading[k] * direction_step_rad;
    }
    // Cut at zero and scaled back to a unit integral (on the grid: the periodic trapezoid rule),
    // so E(f) = the measured density exactly.
    if (!(sum > 0.0))
      throw Error(files.spectral_density.string(),
                  fmt::format("time {}: band {} spreads to nothing", time, i + 1),
                  "check r1, r2 and the directions of that band");
    for (int k = 0; k < n; ++k) result.density_m2_hz_rad[i * n + k] = e * spreading[k] / sum;
  }
  result.source =
      fmt::format("{} (with .swdir/.swdir2/.swr1/.swr2), time {}", files.spectral_density.string(), time);
  check_sampled_spectrum(result);
  return result;
}

// ---------------------------------------------------------------------------------------------
// Moments and the builder's pair.

namespace {

/// Periodic trapezoid weights of the directions (rad): half the gaps on either side.
std::vector<double> direction_weights_rad(const std::vector<double>& directions) {
  const std::size_t n = directions.size();
  std::vector<double> weight(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double next = k + 1 < n ? directions[k + 1] : directions[0] + 2.0 * kPi;
    const double previous = k > 0 ? directions[k - 1] : directions[n - 1] - 2.0 * kPi;
    weight[k] = 0.5 * (next - previous);
  }
  return weight;
}

/// E(f_i) = integral of E(f_i, theta) dtheta (m2/Hz).
std::vector<double> frequency_density_m2_hz(const SampledDirectionalSpectrum& s) {
  const auto weight = direction_weights_rad(s.directions_rad);
  std::vector<double> e(s.frequencies_hz.size(), 0.0);
  for (std::size_t i = 0; i < e.size(); ++i)
    for (std::size_t k = 0; k < weight.size(); ++k) e[i] += s.density(i, k) * weight[k];
  return e;
}

class SampledFrequencySpectrum : public FrequencySpectrum {
 public:
  explicit SampledFrequencySpectrum(std::shared_ptr<const SampledDirectionalSpectrum> s)
      : sampled_(std::move(s)), e_(frequency_density_m2_hz(*sampled_)) {
    peak_ = 2.0 * kPi / peak_period_s(*sampled_);
  }
  double density_m2_s_rad(double w) const override {
    // S(w) = E(f) df/dw = E(w / 2 pi) / 2 pi, E linear between the file's frequencies.
    const auto& f = sampled_->frequencies_hz;
    const double fw = w / (2.0 * kPi);
    if (!(fw >= f.front() && fw <= f.back())) return 0.0;
    const std::size_t i =
        std::min<std::size_t>(std::upper_bound(f.begin(), f.end(), fw) - f.begin(), f.size() - 1);
    const double t = (fw - f[i - 1]) / (f[i] - f[i - 1]);
    return ((1.0 - t) * e_[i - 1] + t * e_[i]) / (2.0 * kPi);
  }
  double peak_angular_frequency_rad_s() const override { return peak_; }
  std::string name() const override { return "file(" + sampled_->source + ")"; }

 private:
  std::shared_ptr<const SampledDirectionalSpectrum> sampled_;
  std::vector<double> e_;
  double peak_ = 0.0;
};

class SampledSpreading : public DirectionalSpreading {
 public:
  explicit SampledSpreading(std::shared_ptr<const SampledDirectionalSpectrum> s)
      : sampled_(std::move(s)),
        e_(frequency_density_m2_hz(*sampled_)),
        mean_(ocean::mean_direction_rad(*sampled_)) {}
  /// D(theta; w) = E(f, theta) / E(f), both linear in f between the file's frequencies and E(f,
  /// theta) linear in theta between its directions (periodic), so D integrates to 1 exactly.
  double density_per_rad(double theta, double w) const override {
    const auto& f = sampled_->frequencies_hz;
    const double fw = std::clamp(w / (2.0 * kPi), f.front(), f.back());
    const std::size_t i =
        std::clamp<std::size_t>(std::upper_bound(f.begin(), f.end(), fw) - f.begin(), 1, f.size() - 1);
    const double t = (fw - f[i - 1]) / (f[i] - f[i - 1]);
    const double e = (1.0 - t) * e_[i - 1] + t * e_[i];
    if (!(e > 0.0)) return 1.0 / (2.0 * kPi);  // no energy here: any unit spreading will do
    return ((1.0 - t) * along_direction(i - 1, theta) + t * along_direction(i, theta)) / e;
  }
  double mean_direction_rad() const override { return mean_; }
  std::string name() const override { return "file(" + sampled_->source + ")"; }

 private:
  double along_direction(std::size_t i, double theta) const {
    const auto& d = sampled_->directions_rad;
    const std::size_t n = d.size();
    theta = wrap_angle_rad(theta);
    // The periodic neighbours: k - 1 and k with d[k - 1] <= theta < d[k] (wrapping at the ends).
    std::size_t k = std::upper_bound(d.begin(), d.end(), theta) - d.begin();
    const std::size_t low = (k + n - 1) % n, high = k % n;
    double d_low = d[low], d_high = d[high];
    if (k == 0) d_low -= 2.0 * kPi;
    if (k == n) d_high += 2.0 * kPi;
    const double span = d_high - d_low;
    const double t = span > 0.0 ? (theta - d_low) / span : 0.0;
    return (1.0 - t) * sampled_->density(i, low) + t * sampled_->density(i, high);
  }
  std::shared_ptr<const SampledDirectionalSpectrum> sampled_;
  std::vector<double> e_;
  double mean_;
};

}  // namespace

void check_sampled_spectrum(const SampledDirectionalSpectrum& s) {
  const std::string subject = s.source.empty() ? std::string("sampled spectrum") : s.source;
  const std::size_t nf = s.frequencies_hz.size(), nd = s.directions_rad.size();
  if (nf < 2 || nd < 2 || s.density_m2_hz_rad.size() != nf * nd)
    throw Error(
        subject,
        fmt::format("has {} frequencies, {} directions and {} densities", nf, nd, s.density_m2_hz_rad.size()),
        "give at least 2 frequencies and 2 directions and one density for each pair");
  for (std::size_t i = 0; i < nf; ++i)
    if (!(s.frequencies_hz[i] > 0.0) || (i > 0 && !(s.frequencies_hz[i] > s.frequencies_hz[i - 1])))
      throw Error(
          subject,
          fmt::format("frequency {} ({} Hz) is not positive and increasing", i + 1, s.frequencies_hz[i]),
          "list distinct frequencies from the lowest up");
  double largest_gap = 0.0;
  for (std::size_t k = 0; k < nd; ++k) {
    const double next = k + 1 < nd ? s.directions_rad[k + 1] : s.directions_rad[0] + 2.0 * kPi;
    if (!(next > s.directions_rad[k]) || s.directions_rad[k] <= -kPi || s.directions_rad[k] > kPi)
      throw Error(subject, fmt::format("direction {} appears twice or is outside (-pi, pi]", k + 1),
                  "give distinct directions around the circle");
    largest_gap = std::max(largest_gap, next - s.directions_rad[k]);
  }
  // The bilinear interpolation is periodic in direction: a sector (SWAN's SECTOR grids) would
  // have its energy smeared across the missing arc. 3 x the mean spacing allows uneven grids.
  if (largest_gap > 3.0 * 2.0 * kPi / nd)
    throw Error(subject,
                fmt::format("directions leave a gap of {:.1f} degrees: they do not go round the circle",
                            largest_gap / kDegree),
                "write the spectrum on the whole circle (SWAN: CGRID ... CIRCLE)");
  double total = 0.0;
  for (double v : s.density_m2_hz_rad) {
    if (!(v >= 0.0) || !std::isfinite(v))
      throw Error(subject, fmt::format("holds a density of {} m2/Hz/rad", v), "give finite densities >= 0");
    total += v;
  }
  if (!(total > 0.0))
    throw Error(subject, "holds no energy (all densities are 0: SWAN's ZERO block, or a calm buoy)",
                "choose a location or time with waves");
}

double zeroth_moment_m2(const SampledDirectionalSpectrum& s) {
  const auto e = frequency_density_m2_hz(s);
  double m0 = 0.0;
  for (std::size_t i = 1; i < e.size(); ++i)
    m0 += 0.5 * (e[i - 1] + e[i]) * (s.frequencies_hz[i] - s.frequencies_hz[i - 1]);
  return m0;
}

double significant_wave_height_m(const SampledDirectionalSpectrum& s) {
  return 4.0 * std::sqrt(zeroth_moment_m2(s));
}

double peak_period_s(const SampledDirectionalSpectrum& s) {
  const auto e = frequency_density_m2_hz(s);
  return 1.0 / s.frequencies_hz[std::max_element(e.begin(), e.end()) - e.begin()];
}

double mean_direction_rad(const SampledDirectionalSpectrum& s) {
  // Weighted by E(f, theta) df dtheta with the same trapezoid weights as m0.
  const auto weight = direction_weights_rad(s.directions_rad);
  const auto& f = s.frequencies_hz;
  double c = 0.0, sn = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double df = 0.5 * ((i + 1 < f.size() ? f[i + 1] : f[i]) - (i > 0 ? f[i - 1] : f[i]));
    for (std::size_t k = 0; k < weight.size(); ++k) {
      const double v = s.density(i, k) * weight[k] * df;
      c += v * std::cos(s.directions_rad[k]);
      sn += v * std::sin(s.directions_rad[k]);
    }
  }
  return std::atan2(sn, c);
}

DirectionalSeaSpecification sea_specification_from_sampled(
    std::shared_ptr<const SampledDirectionalSpectrum> s) {
  if (!s)
    throw Error("sampled spectrum", "is missing", "read one with read_swan_spectrum or read_ndbc_spectrum");
  check_sampled_spectrum(*s);
  DirectionalSeaSpecification spec;
  spec.spectrum = std::make_shared<SampledFrequencySpectrum>(s);
  auto spreading = std::make_shared<SampledSpreading>(s);
  spec.spreading = spreading;
  spec.min_frequency_rad_s = 2.0 * kPi * s->frequencies_hz.front();
  spec.max_frequency_rad_s = 2.0 * kPi * s->frequencies_hz.back();
  // The half-width around the mean holding all but 1e-4 of m0 (bisection on the energy in
  // [mean - h, mean + h] of the frequency-integrated direction distribution).
  const auto& f = s->frequencies_hz;
  const double mean = spreading->mean_direction_rad();
  auto held = [&](double half_width) {
    double sum = 0.0;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const double df = 0.5 * ((i + 1 < f.size() ? f[i + 1] : f[i]) - (i > 0 ? f[i - 1] : f[i]));
      const double w = 2.0 * kPi * f[i];
      sum += df * spec.spectrum->density_m2_s_rad(w) * 2.0 * kPi *
             integrate_gauss_legendre([&](double th) { return spreading->density_per_rad(th, w); },
                                      mean - half_width, mean + half_width, 64);
    }
    return sum;
  };
  const double total = held(kPi);
  double low = 0.0, high = kPi;
  for (int iteration = 0; iteration < 30; ++iteration) {
    const double middle = 0.5 * (low + high);
    (held(middle) < (1.0 - 1e-4) * total ? low : high) = middle;
  }
  spec.direction_half_width_rad = high;
  return spec;
}

}  // namespace nearshore::ocean
