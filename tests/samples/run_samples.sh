#!/usr/bin/env bash
# The three samples/ hosts, built the way a host builds them: `cmake --install` of this build into
# a prefix, then samples/ as a separate CMake project against the installed package
# (find_package(nearshore)), the C sample also compiled alone as C11 by the C compiler; then each
# is run headless on a small real bake. Usage: run_samples.sh BUILD_DIR SOURCE_DIR SEQUENCE WORK
set -euo pipefail
build_dir=$1 source_dir=$2 sequence=$3 work=$4
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build_dir" --prefix "$work/prefix" > "$work/install.log"
test -f "$work/prefix/include/nearshore.h"
test -f "$work/prefix/lib/cmake/nearshore/nearshoreConfig.cmake"
test -f "$work/prefix/lib/pkgconfig/nearshore.pc"
# C11 with a C compiler, nothing but the installed header and pkg-config.
PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig" cc -std=c11 -pedantic -Wall -Wextra -Werror \
  $(PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig" pkg-config --cflags nearshore) \
  -c "$source_dir/samples/query_track.c" -o "$work/query_track_c11.o"
PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig" cc -std=c11 -pedantic -Wall -Wextra -Werror \
  $(PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig" pkg-config --cflags nearshore) \
  -c "$source_dir/samples/ship_track.c" -o "$work/ship_track_c11.o"
# A C host of the CMake package on a machine without the C++ API's header-only dependencies
# (simulated: find_package of nlohmann_json and Eigen3 disabled): nearshore::c links; asking for
# the C++ component fails and names them.
mkdir -p "$work/c_host"
cat > "$work/c_host/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.25)
project(c_host C)
find_package(nearshore 0.1 REQUIRED CONFIG \${NEARSHORE_COMPONENTS})
add_executable(c_host "$source_dir/samples/query_track.c")
target_link_libraries(c_host PRIVATE nearshore::c m)
CMAKE
without_cxx_dependencies=(-DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON)
cmake -S "$work/c_host" -B "$work/c_host/build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
  "${without_cxx_dependencies[@]}" > "$work/c_host.log"
cmake --build "$work/c_host/build" >> "$work/c_host.log"
if cmake -S "$work/c_host" -B "$work/c_host/build_cxx" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
  "${without_cxx_dependencies[@]}" -DNEARSHORE_COMPONENTS="COMPONENTS;cxx" > "$work/c_host_cxx.log" 2>&1; then exit 1; fi
grep -q "nlohmann_json" "$work/c_host_cxx.log"
cmake -S "$source_dir/samples" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log"
cmake --build "$work/build" > "$work/build.log"
export LD_LIBRARY_PATH="$work/prefix/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

# 1. C, queries only: 21 rows of the water under the ship, never dry on this track.
"$work/build/query_track" "$sequence" 20 > "$work/track.csv"
test "$(wc -l < "$work/track.csv")" -eq 22
awk -F, 'NR > 1 && ($4 + 0 > 3 || $4 + 0 < -3 || $7 != 0) { print "implausible row: " $0; bad = 1 } END { exit bad }' "$work/track.csv"
# Bad input: a clear message and a non-zero status, no crash.
if "$work/build/query_track" /nonexistent/bake 2> "$work/missing.err"; then exit 1; fi
grep -q "/nonexistent/bake" "$work/missing.err"

# 1b. C, a ship: the small bay is flat 12 m deep to x = 250 m, then a beach rises to land at
# x = 378 m. A tug from x = 100 m heading east at 4 m/s sails, then grounds where the water is
# shallower than its 3 m draft (x about 346 m), and says so; the one placed on land is refused.
"$work/build/ship_track" "$sequence" 90 > "$work/ship.csv" 2> "$work/ship.err"
test "$(wc -l < "$work/ship.csv")" -eq 91
grep -q "ship 'Ashore': is placed on land" "$work/ship.err"
grep -q "ship 'Tug 1' ran aground" "$work/ship.err"
awk -F, 'NR == 11 && !($7 + 0 > 3.0 && $7 + 0 < 5.0) { print "not under way at 4 m/s: " $0; bad = 1 }
         END { if ($8 != 1) { print "not aground at the end: " $0; bad = 1 } exit bad }' "$work/ship.csv"

# 2. and 3. GL hosts under Xvfb (tests/under_xvfb.sh, as the GL tests).
xvfb() { "${UNDER_XVFB:?the test sets it: tests/under_xvfb.sh}" --screen 1024x768x24 "$@"; }
xvfb "$work/build/embed_window" "$sequence" 20 "$work/embed.ppm" | tee "$work/embed.log"
test -s "$work/embed.ppm"
xvfb "$work/build/own_renderer" "$sequence" 20 | tee "$work/own.log"
echo "samples: built against the installed package and ran"
