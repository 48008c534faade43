// fault_runner: the process the fault tests start, so that what they do to it is real (a SIGKILL
// the process cannot catch, a second process, a full file system).
//
//   fault_runner bake CASE OUT [resume] [overwrite] [allow-over-budget]   run_bake, like `nearshore bake`
//   fault_runner verify SEQUENCE                                           every checksum of a sequence
//   fault_runner loops SEQUENCE                                            analyse_loops (writes loops.json)
//   fault_runner export SEQUENCE FORMAT OUT                                export_sequence, like `nearshore export`
//   fault_runner loops-vdb SEQUENCE OUT.vdb                                export_sequence_vdb, like `nearshore loops --vdb`
//   fault_runner bathy OUT INPUT... [spacing=M]                            build_harbour_grid + write_bathymetry_outputs
//
// With NEARSHORE_FAULT set, it stops itself at one chosen write:
//   kill-in-write:NAME:K        SIGKILL half-way through writing the K-th version of file NAME
//                               (in its temporary file, before it is renamed over NAME)
//   kill-before-rename:NAME:K   SIGKILL after the K-th version of NAME is complete, before its rename
//   pause-in-write:NAME:K:GO    in that write, create GO.waiting, wait (at most 60 s) until GO exists
// The library writes every file through write()/rename() (core/atomic_file.cpp, the checkpoint's
// stream buffer in bake_run.cpp); this executable defines both (ENABLE_EXPORTS, so the C++ runtime's
// calls come here too) and passes them on to the kernel, so the libraries run unchanged.
#include <fcntl.h>
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <thread>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/export/export_sequence.hpp"
#include "nearshore/loops/sequence_vdb.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/loops/inspector.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace {

struct Fault {
  std::string action, name, go_file;
  int version = 0;
  bool armed = false;
};

Fault& fault() {
  static Fault parsed = [] {
    Fault f;
    const char* text = std::getenv("NEARSHORE_FAULT");
    if (!text) return f;
    std::string spec = text;
    std::size_t parts[3] = {};
    std::size_t at = 0;
    for (std::size_t& part : parts) {
      part = spec.find(':', at);
      if (part == std::string::npos) break;
      at = part + 1;
    }
    if (parts[0] == std::string::npos || parts[1] == std::string::npos) return f;
    f.action = spec.substr(0, parts[0]);
    f.name = spec.substr(parts[0] + 1, parts[1] - parts[0] - 1);
    const std::string rest = spec.substr(parts[1] + 1);
    f.version = std::atoi(rest.c_str());
    if (const std::size_t colon = rest.find(':'); colon != std::string::npos) f.go_file = rest.substr(colon + 1);
    f.armed = f.version > 0;
    return f;
  }();
  return parsed;
}

// Versions of each file completed (renamed into place) so far: the one being written is one more.
std::map<std::string, int>& completed() {
  static std::map<std::string, int> counts;
  return counts;
}

// "frame_000003.exr" for a descriptor open on ".../frame_000003.exr.tmp-4711", else "".
std::string final_name_of_temporary(int descriptor) {
  char link[64], target[4096];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", descriptor);
  const ssize_t length = ::readlink(link, target, sizeof target - 1);
  if (length <= 0) return {};
  const std::string name = std::filesystem::path(std::string(target, static_cast<std::size_t>(length))).filename().string();
  const std::size_t marker = name.rfind(".tmp-");
  return marker == std::string::npos ? std::string() : name.substr(0, marker);
}

ssize_t kernel_write(int descriptor, const void* data, std::size_t size) {
  return static_cast<ssize_t>(::syscall(SYS_write, descriptor, data, size));
}

void wait_for_go(const std::string& go_file) {
  if (FILE* waiting = std::fopen((go_file + ".waiting").c_str(), "w")) std::fclose(waiting);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!std::filesystem::exists(go_file) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

}  // namespace

extern "C" ssize_t write(int descriptor, const void* data, std::size_t size) {
  Fault& f = fault();
  if (f.armed && (f.action == "kill-in-write" || f.action == "pause-in-write") && size > 0 &&
      final_name_of_temporary(descriptor) == f.name && completed()[f.name] + 1 == f.version) {
    if (f.action == "pause-in-write") {
      f.armed = false;
      wait_for_go(f.go_file);
    } else {
      // Half of this write reaches the file, then the process dies as `kill -9` would kill it.
      kernel_write(descriptor, data, std::max<std::size_t>(1, size / 2));
      ::kill(::getpid(), SIGKILL);
    }
  }
  return kernel_write(descriptor, data, size);
}

extern "C" int rename(const char* from, const char* to) {
  const std::string name = std::filesystem::path(to).filename().string();
  Fault& f = fault();
  if (f.armed && f.action == "kill-before-rename" && name == f.name && completed()[name] + 1 == f.version)
    ::kill(::getpid(), SIGKILL);
  const int result = ::renameat(AT_FDCWD, from, AT_FDCWD, to);
  if (result == 0) ++completed()[name];
  return result;
}

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: fault_runner bake CASE OUT [resume] [overwrite] [allow-over-budget] | verify SEQ | loops SEQ | "
                 "export SEQ FORMAT OUT | loops-vdb SEQ OUT | bathy OUT INPUT... [spacing=M]\n");
    return 2;
  }
  try {
    nearshore::ProgressBar::set_quiet(true);
    const std::string mode = argv[1];
    if (mode == "verify") {
      const nearshore::sequence::SequenceReader reader(argv[2]);
      reader.verify_checksums();
      std::printf("%d frames verified\n", reader.frame_count());
    } else if (mode == "loops") {
      nearshore::loops::LoopsOptions options;
      options.report_lengths_s = {1.0};
      nearshore::loops::analyse_loops(argv[2], options);
    } else if (mode == "export" && argc == 5) {
      nearshore::exports::ExportRequest request;
      request.sequence_folder = argv[2];
      request.format = nearshore::exports::parse_export_format(argv[3]);
      request.output_folder = argv[4];
      nearshore::exports::export_sequence(request);
    } else if (mode == "loops-vdb" && argc == 4) {
      nearshore::loops::export_sequence_vdb(argv[2], argv[3]);
    } else if (mode == "bathy" && argc >= 4) {
      nearshore::bathymetry::BathyRequest request;
      for (int i = 3; i < argc; ++i) {
        const std::string_view word = argv[i];
        if (word.starts_with("spacing="))
          request.spacing_m = std::atof(argv[i] + 8);
        else
          request.inputs.emplace_back(argv[i]);
      }
      nearshore::bathymetry::write_bathymetry_outputs(argv[2], nearshore::bathymetry::build_harbour_grid(request));
    } else if (mode == "bake" && argc >= 4) {
      nearshore::bake::BakeOptions options;
      options.output_folder = argv[3];
      for (int i = 4; i < argc; ++i) {
        const std::string_view word = argv[i];
        options.resume |= word == "resume";
        options.overwrite |= word == "overwrite";
        options.allow_over_budget |= word == "allow-over-budget";
      }
      nearshore::bake::run_bake(nearshore::bake::read_bake_case(argv[2]), options);
    } else {
      std::fprintf(stderr, "fault_runner: unknown mode %s\n", mode.c_str());
      return 2;
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
  return 0;
}
