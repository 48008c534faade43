#pragma once
// loops.json: the loop tables `nearshore loops` (loops/inspector.hpp) writes into a sequence folder
// and every player reads (loop_playback.hpp), as one typed, versioned contract
// (docs/formats/sequence.md, "loops.json and loops_gram.bin"). The writer and the reader are the
// two functions below; nothing else spells a key of the file.
//
// Version rule: the file carries "format": "nearshore loops" and "version": kLoopsFileVersion. A
// reader refuses any other format and any version it does not know (a newer one included), naming
// the file; keys it does not know are ignored. A change that removes, renames or re-types a key, or
// changes what a value means, is a new version.
//
// JSON has no infinity: the +infinity the inspector can hold (no period match, a dead end's future
// cost) is written as null, and every number field reads null back as +infinity.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace nearshore::sequence {

inline constexpr std::string_view kLoopsFileFormat = "nearshore loops";
inline constexpr int kLoopsFileVersion = 1;
inline constexpr const char* kLoopsFileName = "loops.json";
/// The Gram matrices beside it (loops/distance.hpp reads and writes them).
inline constexpr const char* kLoopsGramFileName = "loops_gram.bin";

/// loops.json, parsed and validated. Frame indices count from 0 in the bake's frames; ratios R are
/// |f(j) - f(i+1)| / median_k |f(k+1) - f(k)| in the metric of seed 003 eq. 10.
struct LoopsFile {
  /// "parameters": the options the transition table was built with (loops/transitions.hpp).
  struct Parameters {
    double motion_weight_delta = 1.0;  ///< delta of eq. 10: weight of the flux distance
    int filter_half_width_frames = 2;  ///< m of the diagonal filter
    double sigma = 0;                  ///< sigma of eq. 11 that was used
    double sigma_factor = 0;           ///< the factor of the mean jump cost sigma came from
    double future_discount_alpha = 0;  ///< alpha of the future cost
    double cost_exponent_p = 0;        ///< p of the future cost
    int candidates_per_frame = 0;      ///< local-minimum jumps kept per frame
    int min_jump_frames = 0;           ///< |j - (i+1)| below this is not a jump
    double min_probability = 0;        ///< pruning threshold of random playback
    int max_crossfade_frames = 0;      ///< longest crossfade of an ordinary jump
    int period_crossfade_frames = 0;   ///< longest crossfade of the exact-period jump (plan c)
    bool operator==(const Parameters&) const = default;
  };
  /// "graph": the transition graph at a glance.
  struct Graph {
    int candidate_jumps = 0, usable_jumps = 0;
    int dead_end_count = 0;            ///< "dead_ends": frames with no transition of probability > 0
    int reachable_dead_end_count = 0;  ///< "reachable_dead_ends": of those, reachable by a random walk
    int first_playable_frame = -1;     ///< the first frame with a finite future (-1: none)
    bool operator==(const Graph&) const = default;
  };
  /// "detected_period": the period read off the frames (loops/inspector.hpp DetectedPeriod).
  struct DetectedPeriod {
    bool found = false;
    int lag_frames = 0;
    double lag_s = 0;
    double seam_ratio = 0;  ///< min_k D(k, k + lag) / median step (+infinity: no lag to try)
    int matched_frame = 0;
    bool operator==(const DetectedPeriod&) const = default;
  };
  /// One jump of a loop (an entry of "seams"): after frame `from` the player shows `to`, the last
  /// `crossfade_frames` frames before it being blends (loop_playback.hpp).
  struct Seam {
    int from = 0, to = 0, crossfade_frames = 0;
    int run_before_frames = 0;        ///< frames shown since the previous jump landed
    double seam_ratio_before = 0;     ///< R without crossfade
    double seam_ratio_after = 0;      ///< R across the crossfade
    double volume_jump_m3 = 0;        ///< V(j) - V(i+1)
    double volume_jump_after_m3 = 0;  ///< the largest per-step volume deviation across the crossfade
    double energy_jump_fraction = 0;  ///< (E(j) - E(i+1)) / mean E
    double energy_dip_fraction = 0;   ///< min over blends of E(blend) / E(linear interpolation) - 1
    bool operator==(const Seam&) const = default;
  };
  /// One planned loop: a cycle starts at `start_frame` (where its last jump lands) and shows
  /// `length_frames` frames, taking `seams` in order.
  struct Loop {
    std::string kind;  ///< "period" or "optimal"
    int start_frame = 0, length_frames = 0;
    double length_s = 0;
    double cost = 0;  ///< sum over jumps of C^p
    double worst_seam_ratio_before = 0, worst_seam_ratio_after = 0;
    std::vector<Seam> seams;
    bool operator==(const Loop&) const = default;
  };
  /// One row of the transition table ("transitions", columns in "transition_columns").
  struct Transition {
    int from = 0, to = 0;
    double probability = 0;  ///< T_ij after pruning (0: kept for loop planning only)
    double cost = 0;         ///< C_ij
    double future_cost = 0;  ///< D''_ij (+infinity: leads to a dead end)
    int crossfade_frames = 0;
    double seam_ratio = 0, seam_ratio_after = 0;
    bool operator==(const Transition&) const = default;
  };
  /// "random_walk": where and with which seed an endless player starts.
  struct RandomWalk {
    int start_frame = -1;
    std::uint64_t seed = 1;
    bool operator==(const RandomWalk&) const = default;
  };
  /// The inspector's report: also what `nearshore loops --json` prints (loops_report_to_json).
  struct Report {
    std::string sequence;  ///< the folder analysed, as it was given
    int frame_count = 0;
    double frame_interval_s = 0;
    double loop_period_s = 0;  ///< the manifest's (0: not a periodic bake)
    Parameters parameters;
    double height_scale_m = 0, motion_scale_m2_s = 0;  ///< the scales of eq. 10's two distances
    double median_step = 0;                            ///< median_k D(k, k+1), the denominator of R
    double median_volume_step_m3 = 0;
    Graph graph;
    DetectedPeriod detected_period;
    std::optional<Loop> period_loop;  ///< plan (c) of a periodic bake
    double requested_loop_s = 0;      ///< plan (b)'s requested length (0: none asked for)
    std::optional<Loop> requested_loop;
    std::vector<Loop> best_loops_by_length;
    double worst_seam_ratio_after = 0;  ///< the --max-seam gate's value
    bool gram_reused = false;
    double distance_seconds = 0, table_seconds = 0;  ///< wall time of the two stages
    bool operator==(const Report&) const = default;
  };

  Report report;
  std::string sequence_manifest_checksum;      ///< XXH64 of manifest.json ("xxh64:<16 hex digits>")
  std::string gram_file = kLoopsGramFileName;  ///< the Gram matrices beside it
  std::string gram_checksum;                   ///< XXH64 of that file
  RandomWalk random_walk;
  std::vector<Transition> transitions;  ///< grouped by `from`, natural successor first

  /// Exact comparison, field by field (a round trip through the file must give equality).
  bool operator==(const LoopsFile&) const = default;
};

/// The report alone, as `nearshore loops --json` prints it.
nlohmann::json loops_report_to_json(const LoopsFile::Report& report);
/// The whole file (the report plus format, version, checksums, random walk and transitions).
nlohmann::json loops_file_to_json(const LoopsFile& file);

/// Writes `folder`/loops.json atomically. Throws nearshore::Error naming the file if it cannot.
void write_loops_file(const std::filesystem::path& folder, const LoopsFile& file);

/// Parses and validates loops.json text: every problem (not JSON, another format, an unknown or
/// newer version, a missing key, a wrong type, a frame index outside the bake, a loop that does not
/// close) is a nearshore::Error naming `source`, the key and the fix. Never crashes and throws
/// nothing else on malformed input.
LoopsFile parse_loops_file(std::string_view text, const std::string& source);

/// Reads and validates `folder`/loops.json (a missing file is an Error too).
LoopsFile read_loops_file(const std::filesystem::path& folder);

}  // namespace nearshore::sequence
