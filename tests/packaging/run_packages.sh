#!/usr/bin/env bash
# The Debian packages of this build, installed into an empty root and used from there only
# (docs/packages.md). Usage: run_packages.sh BUILD_DIR SOURCE_DIR WORK
#  1. cpack makes the .deb files from the build (cmake/NearshorePackaging.cmake).
#  2. Each package's declared Depends is checked (check_depends.py) and every file a plain
#     `cmake --install` installs is in exactly one package.
#  3. dpkg unpacks them into WORK/root (its own database there; --force-depends, as the root holds
#     no Debian system for them to depend on: the Depends were checked against this machine's).
#  4. From that root alone: nearshore.h compiles with nothing but the C library beside it; the C
#     samples build by pkg-config and by find_package (a C host without Eigen and nlohmann_json),
#     the C++ sample by find_package; the packaged `nearshore` bakes the small bay; query_track
#     plays it; `import nearshore` finds the packaged module and queries the bake along its track.
set -euo pipefail
build_dir=$1 source_dir=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
mkdir -p "$work"
say() { echo "packages: $*"; }
start=$(date +%s.%N)
elapsed() { python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.1f} s')" "$start" "$(date +%s.%N)"; }

# 1. The packages.
cpack --config "$build_dir/CPackConfig.cmake" -B "$work/debs" > "$work/cpack.log" 2>&1 || { cat "$work/cpack.log"; exit 1; }
mapfile -t debs < <(find "$work/debs" -maxdepth 1 -name '*.deb' | sort)
say "cpack made ${#debs[@]} packages in $(elapsed)"
for deb in "${debs[@]}"; do
  printf '  %-50s %6d KiB  Depends: %s\n' "$(basename "$deb")" $(( $(stat -c %s "$deb") / 1024 )) "$(dpkg-deb -f "$deb" Depends)"
done
expected=(libnearshore0 libnearshore-dev nearshore-tools)
if grep -qE '^set\(CPACK_COMPONENTS_ALL ".*python' "$build_dir/CPackConfig.cmake"; then expected+=(python3-nearshore); fi
if grep -qE '^set\(CPACK_COMPONENTS_ALL ".*osg' "$build_dir/CPackConfig.cmake"; then expected+=(libnearshore-osg0 libnearshore-osg-dev); fi
test "${#debs[@]}" -eq "${#expected[@]}" || { echo "expected ${#expected[@]} packages (${expected[*]}), cpack made ${#debs[@]}"; exit 1; }

# 2. Their Depends, and every installed file in exactly one package.
python3 "$here/check_depends.py" "${debs[@]}"
cmake --install "$build_dir" --prefix "$work/plain" > "$work/plain-install.log"
(cd "$work/plain" && find . -type f -o -type l | sed 's|^\./||' | sort) > "$work/installed.txt"
for deb in "${debs[@]}"; do
  dpkg-deb --fsys-tarfile "$deb" | tar -t | grep -v '/$' | sed 's|^\./usr/||'
done | sort > "$work/packaged.txt"
if [ -n "$(uniq -d "$work/packaged.txt")" ]; then echo "in more than one package:"; uniq -d "$work/packaged.txt"; exit 1; fi
if ! diff -u "$work/installed.txt" "$work/packaged.txt" > "$work/files.diff"; then
  echo "installed files and packaged files differ (- only installed, + only packaged):"; cat "$work/files.diff"; exit 1
fi
say "$(wc -l < "$work/packaged.txt") files, each in exactly one package ($(elapsed))"

# 3. Unpacked by dpkg into an empty root with its own database (the packages' files and their
#    registration). Its configure step would run libnearshore0's one maintainer script, ldconfig,
#    which a root without a C library cannot run (nor should it run the machine's): the only
#    scripts allowed are that one, and configuring is left to a real Debian (docs/packages.md).
root="$work/root"
mkdir -p "$root/var/lib/dpkg/updates" "$root/var/lib/dpkg/info" "$root/var/lib/dpkg/triggers"
touch "$root/var/lib/dpkg/status"
for deb in "${debs[@]}"; do
  mkdir -p "$work/control/$(basename "$deb")"
  dpkg-deb -e "$deb" "$work/control/$(basename "$deb")"
  for script in "$work/control/$(basename "$deb")"/{preinst,postinst,prerm,postrm}; do
    test -e "$script" || continue
    if grep -vE '^(#!/bin/sh|set -e|if \[ "\$1" = "(configure|remove)" \]; then|[[:space:]]*ldconfig|fi|)$' "$script"; then
      echo "$(basename "$deb"): $(basename "$script") does more than ldconfig (above)"; exit 1
    fi
  done
done
dpkg --root="$root" --log=/dev/null --force-not-root --force-depends --unpack "${debs[@]}" > "$work/dpkg.log" 2>&1 \
  || { cat "$work/dpkg.log"; exit 1; }
for package in "${expected[@]}"; do
  test "$(dpkg-query --root="$root" -W -f '${Status}' "$package")" = "install ok unpacked"
done
usr="$root/usr"
libdir=$(dirname "$(find "$usr/lib" -name 'libnearshore.so.0' | head -1)")
test -L "$libdir/libnearshore.so.0" && test -L "$libdir/libnearshore.so"
say "dpkg unpacked ${expected[*]} into $root ($(elapsed))"

# 4a. nearshore.h needs nothing but the C library: every header it pulls in is in the root or in a
#     package of the C library and compiler, none of Eigen or nlohmann_json.
echo '#include <nearshore.h>' > "$work/nearshore_h_alone.c"
cc -std=c11 -M -I"$usr/include" "$work/nearshore_h_alone.c" | tr -d '\\' | tr ' ' '\n' | grep '^/' \
  | grep -v -e "^$root/" -e "^$work/nearshore_h_alone.c$" | sort -u > "$work/c-headers-outside-root.txt"
if grep -E 'eigen|nlohmann|nearshore' "$work/c-headers-outside-root.txt"; then echo "nearshore.h reaches outside the package"; exit 1; fi
dpkg -S $(cat "$work/c-headers-outside-root.txt") > "$work/c-header-owners.txt" 2>&1 \
  || { cat "$work/c-header-owners.txt"; echo "nearshore.h needs headers of no package"; exit 1; }
cut -d: -f1 "$work/c-header-owners.txt" | tr ',' '\n' | tr -d ' ' | sort -u > "$work/c-header-packages.txt"
if grep -vE '^(libc6-dev|linux-libc-dev|libgcc-[0-9]+-dev|gcc-[0-9]+)$' "$work/c-header-packages.txt"; then
  echo "nearshore.h needs headers of the packages above"; exit 1
fi
say "nearshore.h compiles with the root's include folder and headers of $(paste -sd' ' "$work/c-header-packages.txt") alone"

# 4b. The C samples by pkg-config from the root alone (PKG_CONFIG_LIBDIR: no system .pc files), and
#     linked against the root's library, run from there.
export PKG_CONFIG_LIBDIR="$libdir/pkgconfig"
pc_flags=$(pkg-config --cflags --libs nearshore)
test "$(realpath "$(pkg-config --variable=includedir nearshore)")" = "$(realpath "$usr/include")" \
  && test "$(realpath "$(pkg-config --variable=libdir nearshore)")" = "$(realpath "$libdir")" \
  || { echo "nearshore.pc points outside the root: $pc_flags"; exit 1; }
for sample in query_track ship_track; do
  cc -std=c11 -pedantic -Wall -Wextra -Werror "$source_dir/samples/$sample.c" $pc_flags -lm -o "$work/$sample-pc"
done
unset PKG_CONFIG_LIBDIR

# 4c. find_package(nearshore) from the root: a C host on a machine without Eigen and nlohmann_json
#     (their find_package disabled), and the C++ sample own_renderer (nearshore::nearshore).
mkdir -p "$work/hosts"
cat > "$work/hosts/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.25)
project(packaged_hosts C CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(nearshore 0.1 REQUIRED CONFIG \${NEARSHORE_COMPONENTS})
add_executable(query_track "$source_dir/samples/query_track.c")
target_link_libraries(query_track PRIVATE nearshore::c m)
if(NEARSHORE_CXX_SAMPLE)
  find_package(glfw3 3.3 REQUIRED CONFIG)
  find_package(OpenGL REQUIRED COMPONENTS OpenGL)
  add_executable(own_renderer "$source_dir/samples/own_renderer.cpp")
  target_link_libraries(own_renderer PRIVATE nearshore::nearshore glfw OpenGL::OpenGL)
endif()
CMAKE
cmake -S "$work/hosts" -B "$work/hosts/c" -G Ninja -DCMAKE_PREFIX_PATH="$usr" \
  -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON > "$work/hosts-c.log"
grep -q "^nearshore_DIR:PATH=$libdir/cmake/nearshore$" "$work/hosts/c/CMakeCache.txt" \
  || { echo "find_package found another nearshore:"; grep nearshore_DIR "$work/hosts/c/CMakeCache.txt"; exit 1; }
cmake --build "$work/hosts/c" >> "$work/hosts-c.log"
cmake -S "$work/hosts" -B "$work/hosts/cxx" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$usr" \
  -DNEARSHORE_CXX_SAMPLE=ON -DNEARSHORE_COMPONENTS="COMPONENTS;cxx" > "$work/hosts-cxx.log"
cmake --build "$work/hosts/cxx" >> "$work/hosts-cxx.log"
say "samples built against the root: query_track and ship_track by pkg-config, query_track (C, no Eigen or nlohmann_json) and own_renderer (C++) by find_package ($(elapsed))"

# 4c'. The OpenSceneGraph sample by find_package(nearshore_osg) from the root (OSG from this
#      machine, as libnearshore-osg-dev depends on libopenscenegraph-dev), linked against the
#      root's libnearshore_osg.so.0 and libnearshore.so.0.
if [[ " ${expected[*]} " == *" libnearshore-osg0 "* ]]; then
  mkdir -p "$work/osg-host"
  cat > "$work/osg-host/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.25)
project(packaged_osg_host CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(nearshore_osg REQUIRED CONFIG)
find_package(OpenGL REQUIRED COMPONENTS OpenGL)
add_executable(nearshore_osgviewer "$usr/share/doc/libnearshore-osg-dev/nearshore_osgviewer.cpp")
target_link_libraries(nearshore_osgviewer PRIVATE nearshore::osg \${OPENSCENEGRAPH_LIBRARIES} OpenGL::GL)
CMAKE
  cmake -S "$work/osg-host" -B "$work/osg-host/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$usr" \
    > "$work/osg-host.log" 2>&1 || { cat "$work/osg-host.log"; exit 1; }
  grep -q "^nearshore_osg_DIR:PATH=$libdir/cmake/nearshore_osg$" "$work/osg-host/build/CMakeCache.txt" \
    || { echo "find_package found another nearshore_osg:"; grep nearshore_osg_DIR "$work/osg-host/build/CMakeCache.txt"; exit 1; }
  cmake --build "$work/osg-host/build" >> "$work/osg-host.log" 2>&1 || { cat "$work/osg-host.log"; exit 1; }
  links=$(LD_LIBRARY_PATH="$libdir" ldd "$work/osg-host/build/nearshore_osgviewer")
  grep -q "libnearshore_osg.so.0 => $libdir/libnearshore_osg.so.0" <<< "$links" \
    && grep -q "libnearshore.so.0 => $libdir/libnearshore.so.0" <<< "$links" \
    || { echo "nearshore_osgviewer does not load the root's libraries:"; echo "$links"; exit 1; }
  say "the OpenSceneGraph sample nearshore_osgviewer built by find_package(nearshore_osg) against the root ($(elapsed))"
fi

# 4d. Run from the root: its library, its tools, its module.
export LD_LIBRARY_PATH="$libdir"
for elf in "$usr/bin/nearshore" "$libdir/libnearshore.so.0" "$work/query_track-pc" "$work/hosts/c/query_track" \
           $(find "$usr/lib/python3" -name '_nearshore*.so' 2>/dev/null); do
  links=$(ldd "$elf")
  if grep 'not found' <<< "$links"; then echo "in $elf"; exit 1; fi
done
links=$(ldd "$work/query_track-pc")
grep -q "libnearshore.so.0 => $libdir/libnearshore.so.0" <<< "$links"
"$usr/bin/nearshore" --version
sequence="$work/small_bay"
"$usr/bin/nearshore" bake "$source_dir/tests/samples/small_bay.toml" -o "$sequence" > "$work/bake.log" 2>&1 \
  || { tail -20 "$work/bake.log"; exit 1; }
"$usr/bin/nearshore" loops "$sequence" > "$work/loops.log" 2>&1 || { tail -20 "$work/loops.log"; exit 1; }
for host in "$work/query_track-pc" "$work/hosts/c/query_track"; do
  "$host" "$sequence" 10 > "$host.csv"
  test "$(wc -l < "$host.csv")" -eq 12
done
cmp "$work/query_track-pc.csv" "$work/hosts/c/query_track.csv"
if [[ " ${expected[*]} " == *" python3-nearshore "* ]]; then
  PYTHONPATH="$usr/lib/python3/dist-packages" PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 - "$usr" "$sequence" "$work/query_track-pc.csv" <<'PY'
import csv
import math
import sys

import numpy as np

import nearshore

root, sequence, track_csv = sys.argv[1:4]
assert nearshore.__file__.startswith(root), nearshore.__file__
# query_track's track (samples/query_track.c) queried through the packaged module: the C API's
# float values as it printed them (4 decimals).
g = nearshore.Sequence(sequence).geometry
rows = list(csv.DictReader(open(track_csv)))
t = np.array([float(r["time_s"]) for r in rows])
start, end = np.array([0.25 * g.width_m, 0.25 * g.height_m]), np.array([0.75 * g.width_m, 0.75 * g.height_m])
length_m = max(math.hypot(*(end - start)), 1.0)
along = np.minimum(5.0 * t, length_m)
x, y = (start[:, None] + (end - start)[:, None] * along / length_m)
water = nearshore.Sea(sequence).query(x, y, t)
printed = np.array([float(r["elevation_m"]) for r in rows])
worst = np.max(np.abs(water.elevation_m - printed))
assert worst <= 5.1e-5, (worst, water.elevation_m, printed)
print(f"packages: import nearshore from {nearshore.__file__}; its queries on query_track's track within {worst:.1e} m of the C API's printed values")
PY
fi
say "the packaged nearshore baked the small bay, query_track played it, import nearshore queried it ($(elapsed))"
