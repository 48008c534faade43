// BoussinesqSolver::save_state / load_state: everything needed to continue bit-identically, with
// the grid, dt and bathymetry fingerprint and an XXH64 checksum of the state checked on load.
#include <cstdint>
#include <cstring>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "nearshore/core/error.hpp"
#include "solver_implementation.hpp"

namespace nearshore::boussinesq {
namespace {

constexpr std::uint64_t kStateMagic = 0x31535342454E534EULL;  // "NSNEBSS1"
// Version 4: the fully nonlinear remainder's history (its evaluation count after the step count, its
// force and last value after the nine arrays), written only by a solver with the fully nonlinear
// terms; the seed's equations still write version 3, byte for byte as before.
// Version 3: the eddy viscosity and the breaking strength are stored as float (the solver holds
// them in float, docs/solver.md "Memory"). Version 2 (all arrays double) is still read.
// Version 2: the checksum and the fingerprint are XXH64 (version 1 used FNV-1a).
constexpr std::uint32_t kStateVersion = 4;
constexpr std::uint32_t kOldestReadableVersion = 2;

template <class T>
void write_pod(std::ostream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}
template <class T>
void read_pod(std::istream& in, T& value) {
  in.read(reinterpret_cast<char*>(&value), sizeof(T));
}

// One array of the state as it is stored: its bytes and the size of one value.
struct StoredArray {
  std::byte* data;
  std::size_t count;
  std::size_t value_bytes;  // 8 (double) or 4 (float)
};

template <class T>
StoredArray stored(std::vector<T>& values) {
  return {reinterpret_cast<std::byte*>(values.data()), values.size(), sizeof(T)};
}
StoredArray stored(Raster<float>& raster) {
  return {reinterpret_cast<std::byte*>(raster.values().data()), raster.values().size(), sizeof(float)};
}

// The arrays of the state, in file order (a template: the solver's Implementation is private): nine,
// and in version 4 (the fully nonlinear equations) the four arrays of their history.
template <class Implementation>
std::vector<StoredArray> state_arrays(Implementation& s, std::uint32_t version) {
  std::vector<StoredArray> arrays = {stored(s.eta), stored(s.eta_previous_t), stored(s.flux_x), stored(s.flux_y),
                                     stored(s.flux_x_increment), stored(s.flux_y_increment), stored(s.eddy_viscosity),
                                     stored(s.breaking_start_s), stored(s.breaking_output)};
  if (version >= 4 && s.nonlinear)
    for (auto* history : {&s.nonlinear->force_x_storage(), &s.nonlinear->force_y_storage(), &s.nonlinear->last_x_storage(),
                          &s.nonlinear->last_y_storage()})
      arrays.push_back(stored(*history));
  return arrays;
}

}  // namespace

void BoussinesqSolver::save_state(std::ostream& out) const {
  // The arrays are only read; state_arrays takes them through the one list of the file order.
  const Implementation& s = *implementation_;
  const std::uint32_t version = s.nonlinear ? kStateVersion : 3;
  const std::vector<StoredArray> arrays = state_arrays(const_cast<Implementation&>(*implementation_), version);
  write_pod(out, kStateMagic);
  write_pod(out, version);
  write_pod(out, s.fingerprint);
  write_pod(out, s.time_s);
  write_pod(out, s.step_count);
  std::uint64_t checksum = hash_bytes(&s.time_s, sizeof s.time_s);
  checksum = hash_bytes(&s.step_count, sizeof s.step_count, checksum);
  if (version >= 4) {
    const std::int32_t evaluations = s.nonlinear->evaluations();
    write_pod(out, evaluations);
    checksum = hash_bytes(&evaluations, sizeof evaluations, checksum);
  }
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
    const std::uint64_t size = arrays[a].count;
    const std::size_t bytes = arrays[a].count * arrays[a].value_bytes;
    write_pod(out, size);
    out.write(reinterpret_cast<const char*>(arrays[a].data), static_cast<std::streamsize>(bytes));
    checksum = hash_bytes(arrays[a].data, bytes, checksum);
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
  if (version < kOldestReadableVersion || version > kStateVersion)
    throw Error(subject, "has version " + std::to_string(version) + ", this solver reads versions " +
                             std::to_string(kOldestReadableVersion) + " to " + std::to_string(kStateVersion),
                "resume with the nearshore build that wrote it, or start the bake again");
  read_pod(in, fingerprint);
  if (fingerprint != s.fingerprint)
    throw Error(subject, "was written for a different grid, bathymetry, time step or equations (SolverParameters::equations)",
                "resume with the same case file and harbour grid, or start the bake again");
  double time = 0.0;
  long steps = 0;
  read_pod(in, time);
  read_pod(in, steps);
  std::int32_t evaluations = 0;
  if (version >= 4) read_pod(in, evaluations);
  std::uint64_t checksum = hash_bytes(&time, sizeof time);
  checksum = hash_bytes(&steps, sizeof steps, checksum);
  if (version >= 4) checksum = hash_bytes(&evaluations, sizeof evaluations, checksum);
  if (!in || evaluations < 0 || evaluations > 2)
    throw Error(subject, "is truncated or corrupt (the nonlinear history count is " + std::to_string(evaluations) + ")",
                "start the bake again from the last good checkpoint");
  const std::vector<StoredArray> arrays = state_arrays(s, version);
  // Everything is read and checked before anything is replaced: a damaged file leaves the solver as it was.
  std::vector<std::vector<std::byte>> loaded(arrays.size());
  for (std::size_t a = 0; a < arrays.size(); ++a) {
    std::uint64_t size = 0;
    read_pod(in, size);
    if (!in || size != arrays[a].count)
      throw Error(subject, "is truncated or corrupt (array " + std::to_string(a) + " has the wrong size)", "start the bake again from the last good checkpoint");
    const std::size_t value_bytes = version == 2 ? sizeof(double) : arrays[a].value_bytes;
    loaded[a].resize(size * value_bytes);
    in.read(reinterpret_cast<char*>(loaded[a].data()), static_cast<std::streamsize>(loaded[a].size()));
    checksum = hash_bytes(loaded[a].data(), loaded[a].size(), checksum);
  }
  std::uint64_t stored_checksum = 0;
  read_pod(in, stored_checksum);
  if (!in || stored_checksum != checksum)
    throw Error(subject, "is truncated or corrupt (checksum mismatch)", "start the bake again from the last good checkpoint");
  for (std::size_t a = 0; a < arrays.size(); ++a) {
    if (loaded[a].size() == arrays[a].count * arrays[a].value_bytes) {
      std::memcpy(arrays[a].data, loaded[a].data(), loaded[a].size());
    } else {  // a version 2 double array into a float one
      for (std::size_t i = 0; i < arrays[a].count; ++i) {
        double value = 0.0;
        std::memcpy(&value, loaded[a].data() + i * sizeof(double), sizeof value);
        const float narrowed = static_cast<float>(value);
        std::memcpy(arrays[a].data + i * sizeof(float), &narrowed, sizeof narrowed);
      }
    }
    std::vector<std::byte>().swap(loaded[a]);
  }
  s.time_s = time;
  s.step_count = steps;
  if (s.nonlinear) {
    if (version < 4) s.nonlinear->reset();  // no history stored: the next step starts it again
    else s.nonlinear->evaluations() = evaluations;
  }
  s.eddy_viscosity_active = true;  // the loaded nu is transposed on the next step
  s.publish();
}

}  // namespace nearshore::boussinesq
