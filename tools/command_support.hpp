#pragma once
// What every subcommand of `nearshore` shares: its registration function, the plain "not built
// yet" answer for a subcommand whose issue is still open, the range every number on the command
// line is checked against, and the translation of library errors into the command's own flags.
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

namespace nearshore::tools {

/// Every subcommand file defines one of these; nearshore.cpp calls them all.
void add_bathy_command(CLI::App& app);
void add_bake_command(CLI::App& app);
void add_loops_command(CLI::App& app);
void add_play_command(CLI::App& app);
void add_demo_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_library_command(CLI::App& app);
void add_export_command(CLI::App& app);
/// `nearshore bench <stage>` subcommands, one file each (bench_<stage>.cpp): their flags; the
/// measurements are bench/'s (nearshore/bench/*_bench.hpp).
void add_bench_bathy(CLI::App& bench);
void add_bench_bake(CLI::App& bench);
void add_bench_deepwater(CLI::App& bench);
void add_bench_loops(CLI::App& bench);
void add_bench_play(CLI::App& bench);
void add_bench_library(CLI::App& bench);
void add_bench_ships(CLI::App& bench);

/// What `nearshore play SEQ --frames 15 --screenshot PNG --size W,H` does, for the demo: a headless
/// picture of the sequence through the runtime. Returns a one-line description.
std::string write_playback_screenshot(const std::filesystem::path& sequence_folder, const std::filesystem::path& png,
                                      int width_px, int height_px);

/// Thrown by a subcommand callback to end the program with this exit status (after printing).
struct ExitStatus {
  int code;
};

/// A subcommand that is not built yet: it says so plainly and exits with status 3. It never
/// prints results it did not compute.
CLI::App* add_unbuilt_command(CLI::App& app, const std::string& name, const std::string& description,
                              const std::string& example, const std::string& tracking_issue);

/// The example line shown at the end of a subcommand's --help.
void set_example(CLI::App& command, const std::string& example);

/// One end of the range an option's numbers must lie in (number_in).
struct Bound {
  double value;
  bool inclusive;
};
inline Bound at_least(double value) { return {value, true}; }
inline Bound above(double value) { return {value, false}; }
inline Bound at_most(double value) { return {value, true}; }
inline Bound below(double value) { return {value, false}; }
/// No limit on this side (the number must still be finite).
Bound unbounded();

/// Every number an option takes, checked while the command line is parsed: a finite number (NaN and
/// infinities are refused) between `low` and `high`. A value outside ends the program before any
/// work with CLI11's message and its exit status for a value that fails a check (105, documented in
/// docs/commands/*.md), e.g. `nearshore loops SEQ --alpha 2`:
///   --alpha: 2 is out of range: allowed [0, 1)
/// For a list option (--lengths-s 10,20) every element is checked. --help shows the range.
CLI::Validator number_in(Bound low, Bound high);
/// Any finite number.
CLI::Validator finite_number();

/// Library errors name the C++ parameter at fault ("BathyRequest::spacing_m = 0: ..."), never a
/// command-line flag, so that a host engine behind the API can act on them. A command that sets
/// parameters from its own flags lists them, {parameter, flag}, and its users read both:
/// "BathyRequest::spacing_m (--spacing) = 0: ...".
using FlagTable = std::vector<std::pair<std::string, std::string>>;

/// `text` with " (flag)" after every whole occurrence of a parameter of `flags`.
std::string name_flags(const std::string& text, const FlagTable& flags);

/// `callback` (a subcommand's), rethrowing any nearshore::Error it throws with its subject, problem
/// and fix passed through name_flags: command->callback(naming_flags_in_errors(flags, [...] {...})).
std::function<void()> naming_flags_in_errors(FlagTable flags, std::function<void()> callback);

}  // namespace nearshore::tools
