#pragma once
// What every subcommand of `nearshore` shares: its registration function and the plain
// "not built yet" answer for a subcommand whose issue is still open.
#include <string>

#include <CLI/CLI.hpp>

namespace nearshore::tools {

/// Every subcommand file defines one of these; nearshore.cpp calls them all.
void add_bathy_command(CLI::App& app);
void add_bake_command(CLI::App& app);
void add_loops_command(CLI::App& app);
void add_play_command(CLI::App& app);
void add_demo_command(CLI::App& app);
void add_bench_command(CLI::App& app);
/// `nearshore bench <stage>` subcommands, one file each (bench_<stage>.cpp).
void add_bench_bathy(CLI::App& bench);
void add_bench_bake(CLI::App& bench);
void add_bench_deepwater(CLI::App& bench);
void add_bench_loops(CLI::App& bench);

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

}  // namespace nearshore::tools
