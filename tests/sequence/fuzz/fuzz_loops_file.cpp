// libFuzzer target for the loops.json reader, parse_loops_file (ctest label `fuzz`, a bounded run).
// The input is used raw, or as edits applied to a valid file made at start-up (every section set:
// parameters, graph, detected period, a period loop and an optimal one with seams, transitions):
// byte flips and cuts, and numbers replaced by extreme ones (-1, 0, 1e308, 2^31, 1e400, ...) so the
// validation of indices, lengths and loops is reached, not only the JSON syntax. Every input must
// end in success or a nearshore::Error; anything else (crash, sanitizer report, another exception)
// is a finding.
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "../../support/fuzz_edits.hpp"

#include "nearshore/core/error.hpp"
#include "nearshore/sequence/loops_file.hpp"

using namespace nearshore;
using namespace nearshore::sequence;

namespace {

std::string make_seed() {
  LoopsFile file;
  LoopsFile::Report& r = file.report;
  r.sequence = "bakes/harbour";
  r.frame_count = 40;
  r.frame_interval_s = 0.25;
  r.loop_period_s = 8.0;
  r.parameters = {.motion_weight_delta = 1.5, .filter_half_width_frames = 2, .sigma = 0.0123, .sigma_factor = 0.1,
                  .future_discount_alpha = 0.995, .cost_exponent_p = 2, .candidates_per_frame = 4,
                  .min_jump_frames = 3, .min_probability = 0.01, .max_crossfade_frames = 8,
                  .period_crossfade_frames = 40};
  r.height_scale_m = 0.61;
  r.motion_scale_m2_s = 2.4;
  r.median_step = 0.0371;
  r.median_volume_step_m3 = 12.5;
  r.graph = {.candidate_jumps = 97, .usable_jumps = 61, .dead_end_count = 3, .reachable_dead_end_count = 0,
             .first_playable_frame = 2};
  r.detected_period = {.found = true, .lag_frames = 32, .lag_s = 8.0, .seam_ratio = 0.004, .matched_frame = 5};
  const LoopsFile::Seam period_seam{.from = 37, .to = 5, .crossfade_frames = 4, .run_before_frames = 33,
                                    .seam_ratio_before = 0.02, .seam_ratio_after = 0.004, .volume_jump_m3 = -0.75,
                                    .volume_jump_after_m3 = 0.125, .energy_jump_fraction = 0.001,
                                    .energy_dip_fraction = -0.0002};
  r.period_loop = LoopsFile::Loop{.kind = "period", .start_frame = 5, .length_frames = 33, .length_s = 8.25,
                                  .cost = 4e-6, .worst_seam_ratio_before = 0.02, .worst_seam_ratio_after = 0.004,
                                  .seams = {period_seam}};
  r.requested_loop_s = 5;
  const LoopsFile::Loop two_jumps{.kind = "optimal", .start_frame = 4, .length_frames = 20, .length_s = 5,
                                  .cost = 0.3, .worst_seam_ratio_before = 1.4, .worst_seam_ratio_after = 0.7,
                                  .seams = {{.from = 12, .to = 20, .crossfade_frames = 3, .run_before_frames = 9},
                                            {.from = 30, .to = 4, .crossfade_frames = 4, .run_before_frames = 11}}};
  r.requested_loop = two_jumps;
  r.best_loops_by_length = {two_jumps, *r.period_loop};
  r.worst_seam_ratio_after = 0.7;
  r.distance_seconds = 0.75;
  r.table_seconds = 0.03125;
  file.sequence_manifest_checksum = "xxh64:0123456789abcdef";
  file.gram_checksum = "xxh64:fedcba9876543210";
  file.random_walk = {.start_frame = 2, .seed = 7};
  file.transitions = {{.from = 12, .to = 13, .probability = 0.9}, {.from = 12, .to = 20, .probability = 0.1},
                      {.from = 30, .to = 4, .probability = 0.0}, {.from = 37, .to = 5, .probability = 1.0}};
  const std::string text = loops_file_to_json(file).dump(1);
  try {
    parse_loops_file(text, "seed");
  } catch (const Error& error) {  // the format moved on: the seed must be brought up to date
    std::fprintf(stderr, "fuzz_loops_file: the seed no longer parses: %s\n", error.what());
    std::abort();
  }
  return text;
}

const char* const kExtremes[] = {"0", "-1", "1e308", "1e400", "2147483648", "-2147483649", "0.5", "nan", "40", "39"};


}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const std::string seed = make_seed();
  const bool raw = data[0] % 2 == 0;
  const std::string text = raw ? std::string(reinterpret_cast<const char*>(data + 1), size - 1) : nearshore::fuzzing::edited(seed, data + 1, size - 1, kExtremes);
  try {
    parse_loops_file(text, "loops.json");
  } catch (const Error&) {
  }
  return 0;
}
