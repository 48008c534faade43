// libFuzzer target for the bake case-file parser (ctest label `fuzz`, a bounded run): TOML or JSON
// text -> detail::parse_case_text (toml++ / nlohmann json) -> parse_bake_case, the whole road of
// `nearshore bake CASE` up to the solver (which is not built: the harbour grid, the wave maker, the
// deep-water coupling and the solver parameters are). The input is used raw, or as edits applied to
// valid cases made at start-up: byte flips and cuts, and numbers replaced by extreme ones (0, -1,
// 1e308, 1e-300, inf, nan, 2^31) so the key checks, not only the syntax, are reached. Every input
// must end in success or a nearshore::Error; anything else (crash, sanitizer report, another
// exception, a timeout, running out of memory) is a finding.
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "../../support/fuzz_edits.hpp"
#include <vector>

#include "../../../bake/src/case_reader.hpp"
#include "nearshore/bake/bake_case.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"

using namespace nearshore;
using namespace nearshore::bake;

namespace {

// Valid cases, small enough that one parse takes milliseconds: a flume with a regular maker,
// sponges and gauges; the Berkhoff shoal with an irregular maker; a flume driven by a small
// deep-water field.
const std::vector<std::string>& seeds() {
  static const std::vector<std::string> texts = {
      "title = \"small flume\"\n"
      "[bathymetry]\nkind = \"profile\"\nlength_m = 12.0\nwidth_m = 0.6\nspacing_m = 0.1\n"
      "profile = [[0.0, 0.5], [12.0, 0.5]]\n"
      "[time]\nduration_s = 8.0\nspin_up_s = 2.0\noutput_interval_s = 0.5\ncourant_number = 0.5\n"
      "checkpoint_interval_s = 0.0\ngauge_interval_s = 0.05\n"
      "[wave_maker]\nkind = \"regular\"\nfacing = \"west\"\nsource_line_m = 3.0\nheight_m = 0.02\nperiod_s = 2.0\n"
      "ramp_time_s = 2.0\n"
      "[solver]\nchezy_coefficient = 0.0\nadi_passes = 1\n[solver.breaking]\nonset_celerity_fraction = 0.65\n"
      "[[sponges]]\nside = \"west\"\nwidth_m = 2.0\n[[sponges]]\nside = \"east\"\nwidth_m = 3.0\n"
      "[[porous_blocks]]\nx_range_m = [8.0, 9.0]\ny_range_m = [0.0, 0.6]\nporosity = 0.4\n"
      "[[gauges]]\nname = \"g1\"\nx_m = 5.0\ny_m = 0.3\n[[gauges]]\nname = \"g2\"\nx_m = 7.5\ny_m = 0.3\n",
      "title = \"Berkhoff shoal, coarse\"\n"
      "[bathymetry]\nkind = \"berkhoff_shoal\"\nlength_m = 30.0\nwidth_m = 20.0\nspacing_m = 0.5\n"
      "centre_m = [13.15, 10.0]\nrotation_deg = 20.0\ndeep_depth_m = 0.45\nslope = 0.02\n"
      "[time]\nduration_s = 40.0\nspin_up_s = 30.0\noutput_interval_s = 0.5\ntime_step_s = 0.05\n"
      "[wave_maker]\nkind = \"irregular\"\nfacing = \"west\"\nsource_line_m = 3.0\nspectrum = \"jonswap\"\n"
      "significant_height_m = 0.05\npeak_period_s = 4.0\nfrequency_count = 8\nspreading_s = 0\nseed = 3\nloop_period_s = 40.0\n"
      "min_frequency_hz = 0.2\nmax_frequency_hz = 0.45\n"
      "[[sponges]]\nside = \"east\"\nwidth_m = 2.0\n",
      "[bathymetry]\nkind = \"profile\"\nlength_m = 200.0\nwidth_m = 40.0\nspacing_m = 2.0\n"
      "profile = [[0.0, 10.0], [150.0, 10.0], [200.0, -1.0]]\n"
      "[time]\nduration_s = 120.0\nspin_up_s = 60.0\noutput_interval_s = 0.5\n"
      "[wave_maker]\nkind = \"deep_water\"\nfacing = \"west\"\nsource_line_m = 20.0\nloop_period_s = 60.0\n"
      "[deep_water]\nspectrum = \"beaufort\"\nbeaufort_force = 4\nwind_direction_deg = 0.0\nseed = 7\n"
      "grid_size = 16\ncascade_count = 1\nshortest_wavelength_m = 4.0\n"};
  return texts;
}

// A seed that no longer parses (the schema moved on) would leave the fuzzer mutating errors only:
// stop with the message instead.
void check_seeds_parse() {
  static const bool checked = [] {
    for (std::size_t i = 0; i < seeds().size(); ++i) {
      try {
        parse_bake_case(detail::parse_case_text(seeds()[i], detail::CaseSyntax::kToml, "seed"), "/nonexistent/seed.toml");
      } catch (const Error& error) {
        std::fprintf(stderr, "fuzz_case_file: seed %zu no longer parses: %s\n", i, error.what());
        std::abort();
      }
    }
    return true;
  }();
  (void)checked;
}

// The numbers an edit may put in place of one in the text.
const char* const kExtremes[] = {"0", "-1", "1e308", "1e-300", "inf", "nan", "2147483648", "-0.0", "1e9", "3"};


}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  ProgressBar::set_quiet(true);
  check_seeds_parse();
  const int mode = data[0] % 4;
  const std::string& seed = seeds()[data[1] % seeds().size()];
  data += 2;
  size -= 2;
  const std::filesystem::path case_file = "/nonexistent-fuzz-folder/case.toml";  // relative paths lead nowhere
  std::string text;
  detail::CaseSyntax syntax = mode == 1 || mode == 3 ? detail::CaseSyntax::kJson : detail::CaseSyntax::kToml;
  if (mode < 2)
    text.assign(reinterpret_cast<const char*>(data), size);
  else if (mode == 2)
    text = nearshore::fuzzing::edited(seed, data, size, kExtremes);
  else  // the same seed as JSON, edited as JSON text
    text = nearshore::fuzzing::edited(detail::parse_case_text(seed, detail::CaseSyntax::kToml, "seed").dump(), data, size, kExtremes);
  if (std::getenv("FUZZ_CASE_PRINT")) std::fprintf(stderr, "---- case text ----\n%s\n----\n", text.c_str());
  try {
    parse_bake_case(detail::parse_case_text(text, syntax, case_file.string()), case_file);
  } catch (const Error&) {
  }
  return 0;
}
