// BoussinesqSolver::save_state / load_state: everything needed to continue bit-identically, with
// the grid, dt and bathymetry fingerprint and an XXH64 checksum of the state checked on load.
#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "nearshore/core/error.hpp"
#include "solver_implementation.hpp"

namespace nearshore::boussinesq {
namespace {

constexpr std::uint64_t kStateMagic = 0x31535342454E534EULL;  // "NSNEBSS1"
// Version 2: the checksum and the fingerprint are XXH64 (version 1 used FNV-1a).
constexpr std::uint32_t kStateVersion = 2;

template <class T>
void write_pod(std::ostream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}
template <class T>
void read_pod(std::istream& in, T& value) {
  in.read(reinterpret_cast<char*>(&value), sizeof(T));
}

}  // namespace

void BoussinesqSolver::save_state(std::ostream& out) const {
  const Implementation& s = *implementation_;
  const std::vector<const std::vector<double>*> arrays = {&s.eta, &s.eta_previous_t, &s.flux_x, &s.flux_y, &s.flux_x_increment,
                                                          &s.flux_y_increment, &s.eddy_viscosity, &s.breaking_start_s,
                                                          &s.breaking_strength};
  write_pod(out, kStateMagic);
  write_pod(out, kStateVersion);
  write_pod(out, s.fingerprint);
  write_pod(out, s.time_s);
  write_pod(out, s.step_count);
  std::uint64_t checksum = hash_bytes(&s.time_s, sizeof s.time_s);
  checksum = hash_bytes(&s.step_count, sizeof s.step_count, checksum);
  // The solver writes a stream and knows no file: the caller that opened it names the file and the
  // reason (bake_run.cpp's checkpoint does); this says how far the state got.
  const auto stop_if_failed = [&](std::size_t arrays_written) {
    if (!out)
      throw Error("solver state",
                  "writing the state failed after " + std::to_string(arrays_written) + " of " + std::to_string(arrays.size()) +
                      " arrays: the output stream reported an error (a full disk, a closed or read-only file)",
                  "free disk space and check the file the stream writes to");
  };
  stop_if_failed(0);
  for (std::size_t a = 0; a < arrays.size(); ++a) {
    const std::uint64_t size = arrays[a]->size();
    write_pod(out, size);
    out.write(reinterpret_cast<const char*>(arrays[a]->data()), static_cast<std::streamsize>(size * sizeof(double)));
    checksum = hash_bytes(arrays[a]->data(), size * sizeof(double), checksum);
    stop_if_failed(a);
  }
  write_pod(out, checksum);
  stop_if_failed(arrays.size());
}

void BoussinesqSolver::load_state(std::istream& in) {
  Implementation& s = *implementation_;
  const std::string subject = "solver state";
  std::uint64_t magic = 0, fingerprint = 0;
  std::uint32_t version = 0;
  read_pod(in, magic);
  read_pod(in, version);
  if (!in || magic != kStateMagic)
    throw Error(subject, "is not a Boussinesq solver state (wrong magic number)", "give the checkpoint the bake wrote");
  if (version != kStateVersion)
    throw Error(subject, "has version " + std::to_string(version) + ", this solver reads version " + std::to_string(kStateVersion),
                "resume with the nearshore build that wrote it, or start the bake again");
  read_pod(in, fingerprint);
  if (fingerprint != s.fingerprint)
    throw Error(subject, "was written for a different grid, bathymetry or time step",
                "resume with the same case file and harbour grid, or start the bake again");
  double time = 0.0;
  long steps = 0;
  read_pod(in, time);
  read_pod(in, steps);
  std::uint64_t checksum = hash_bytes(&time, sizeof time);
  checksum = hash_bytes(&steps, sizeof steps, checksum);
  const std::vector<std::vector<double>*> arrays = {&s.eta, &s.eta_previous_t, &s.flux_x, &s.flux_y, &s.flux_x_increment,
                                                    &s.flux_y_increment, &s.eddy_viscosity, &s.breaking_start_s,
                                                    &s.breaking_strength};
  std::vector<std::vector<double>> loaded(arrays.size());
  for (std::size_t a = 0; a < arrays.size(); ++a) {
    std::uint64_t size = 0;
    read_pod(in, size);
    if (!in || size != arrays[a]->size())
      throw Error(subject, "is truncated or corrupt (array " + std::to_string(a) + " has the wrong size)", "start the bake again from the last good checkpoint");
    loaded[a].resize(size);
    in.read(reinterpret_cast<char*>(loaded[a].data()), static_cast<std::streamsize>(size * sizeof(double)));
    checksum = hash_bytes(loaded[a].data(), size * sizeof(double), checksum);
  }
  std::uint64_t stored = 0;
  read_pod(in, stored);
  if (!in || stored != checksum)
    throw Error(subject, "is truncated or corrupt (checksum mismatch)", "start the bake again from the last good checkpoint");
  for (std::size_t a = 0; a < arrays.size(); ++a) arrays[a]->swap(loaded[a]);
  s.time_s = time;
  s.step_count = steps;
  s.eddy_viscosity_active = true;  // the loaded nu is transposed on the next step
  s.publish();
}

}  // namespace nearshore::boussinesq
