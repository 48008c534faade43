// bake_runner CASE OUT [--resume]: runs one bake in its own process, so bake_run_test can kill it
// with SIGKILL part-way and resume it (a real kill, not a simulated one).
#include <cstdio>
#include <string>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/core/progress.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bake_runner CASE OUT [--resume]\n");
    return 2;
  }
  try {
    nearshore::ProgressBar::set_quiet(true);
    nearshore::bake::BakeOptions options;
    options.output_folder = argv[2];
    options.resume = argc > 3 && std::string(argv[3]) == "--resume";
    nearshore::bake::run_bake(nearshore::bake::read_bake_case(argv[1]), options);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
  return 0;
}
