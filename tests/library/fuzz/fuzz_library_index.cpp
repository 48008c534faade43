// libFuzzer target for library.json's parser, parse_library_index (ctest label `fuzz`, a bounded
// run), and for the selection a runtime makes from what it accepts. The input is used raw, or as
// the shared structured edits (tests/support/fuzz_edits.hpp) of a valid index made at start-up (a
// 3 x 2 x 2 sweep of directions, tides and spectra; baked, failed and pending states). Every input
// must end in success or a nearshore::Error; anything else (crash, sanitizer report, another
// exception) is a finding. An accepted index is also asked for a state.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "../../support/fuzz_edits.hpp"

#include "nearshore/core/error.hpp"
#include "nearshore/sequence/library_index.hpp"

using namespace nearshore;
using namespace nearshore::sequence;

namespace {

std::string make_seed() {
  LibraryIndex index;
  index.title = "fuzz";
  index.library_file = "library.toml";
  index.base_case = "harbour.toml";
  index.axes = {{SeaQuantity::kDirection, {75, 90, 105}, {}},
                {SeaQuantity::kSpectrum, {}, {"jonswap", "tma"}},
                {SeaQuantity::kTide, {-1.0, 1.5}, {}}};
  int k = 0;
  for (double direction : {75.0, 90.0, 105.0})
    for (const char* spectrum : {"jonswap", "tma"})
      for (double tide : {-1.0, 1.5}) {
        LibraryIndex::State state;
        state.id = "s" + std::to_string(k);
        state.conditions.direction_deg = direction;
        state.conditions.spectrum = spectrum;
        state.conditions.tide_m = tide;
        state.status = static_cast<LibraryStateStatus>(k % 3 == 0 ? 0 : k % 3 == 1 ? 1 : 2);
        state.sequence = "states/" + state.id;
        state.case_file = "cases/" + state.id + ".json";
        if (state.status == LibraryStateStatus::kBaked)
          state.manifest_checksum = state.loops_checksum = "xxh64:0123456789abcdef";
        if (state.status == LibraryStateStatus::kFailed) state.error = "unstable at t = 12 s";
        state.cost_cell_steps = 1e6 + k;
        state.run = {state.status == LibraryStateStatus::kPending ? "" : "baked", k % 2, 1.5};
        index.states.push_back(state);
        ++k;
      }
  const std::string text = library_index_to_json(index).dump(1);
  try {
    parse_library_index(text, "seed");
  } catch (const Error& error) {  // the format moved on: the seed must be brought up to date
    std::fprintf(stderr, "fuzz_library_index: the seed no longer parses: %s\n", error.what());
    std::abort();
  }
  return text;
}

const char* const kExtremes[] = {"0", "-1", "1e308", "1e400", "2147483648", "-2147483649", "0.5", "nan", "360", "-1e-320"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const std::string seed = make_seed();
  const bool raw = data[0] % 2 == 0;
  const std::string text = raw ? std::string(reinterpret_cast<const char*>(data + 1), size - 1)
                               : nearshore::fuzzing::edited(seed, data + 1, size - 1, kExtremes);
  try {
    const LibraryIndex index = parse_library_index(text, "library.json");
    SeaConditions request;
    request.direction_deg = size > 2 ? data[1] * 1.5 : 80.0;
    request.tide_m = size > 3 ? data[2] / 64.0 - 1.0 : 0.0;
    request.spectrum = "tma";
    (void)select_library_states(index, request);
  } catch (const Error&) {
  }
  return 0;
}
