#!/usr/bin/env bash
# The Debian packages installed on a fresh Debian 12 (docs/packages.md, "Install them"): mmdebstrap
# makes a bookworm root with nothing but apt's base, apt-get installs the packages there from the
# archive's mirrors, then in that chroot: `import nearshore`, the packaged `nearshore` bakes the
# small bay, and with only a C compiler, pkg-config and CMake added (Eigen and nlohmann_json
# removed), samples/query_track.c builds by pkg-config and samples/ship_track.c by
# find_package(nearshore), and both run on the bake; asking for the C++ component fails naming
# Eigen and nlohmann_json. Where the OSG packages are given, the OpenSceneGraph sample builds by
# find_package(nearshore_osg) first (with g++) and loads the installed libraries. Needs root, mmdebstrap and the network (not a CI test: the CI test
# is tests/packaging). 80 s here on 2026-11-30 (load about 3) and 190 MB from the mirror.
# Usage: scripts/check-debs-on-fresh-debian.sh [DEB_DIR (build/release/debs)] [WORK (/tmp/nearshore-fresh-debian)]
set -euo pipefail
cd "$(dirname "$0")/.."
debs=$(realpath "${1:-build/release/debs}")
work="${2:-/tmp/nearshore-fresh-debian}"
ls "$debs"/*.deb > /dev/null
root="$work/root"
rm -rf "$root"
mkdir -p "$work"
mirror=http://deb.debian.org
mmdebstrap --variant=apt --components=main bookworm "$root" "deb $mirror/debian bookworm main" \
  "deb $mirror/debian bookworm-updates main" "deb $mirror/debian-security bookworm-security main"
mkdir -p "$root/root/debs" "$root/root/src"
cp "$debs"/*.deb "$root/root/debs/"
cp samples/query_track.c samples/ship_track.c tests/samples/small_bay.toml "$root/root/src/"
cp /etc/resolv.conf "$root/etc/resolv.conf"
cat > "$root/root/check.sh" <<'CHECK'
set -euxo pipefail
export DEBIAN_FRONTEND=noninteractive
cat /etc/debian_version
apt-get update -q
apt-get install -y -q /root/debs/*.deb
python3 -c "import nearshore; print(nearshore.__file__)"
nearshore --version
cd /root
nearshore bake src/small_bay.toml -o small_bay > bake.log && nearshore loops small_bay > loops.log
apt-get install -y -q --no-install-recommends gcc libc6-dev pkg-config cmake make
if [ -e /usr/share/doc/libnearshore-osg-dev/nearshore_osgviewer.cpp ]; then
  # The OpenSceneGraph sample by find_package(nearshore_osg), with what libnearshore-osg-dev pulled in.
  apt-get install -y -q --no-install-recommends g++
  mkdir -p osg-host
  cat > osg-host/CMakeLists.txt <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(osg_host CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(nearshore_osg REQUIRED CONFIG)
find_package(OpenGL REQUIRED COMPONENTS OpenGL)
add_executable(nearshore_osgviewer /usr/share/doc/libnearshore-osg-dev/nearshore_osgviewer.cpp)
target_link_libraries(nearshore_osgviewer PRIVATE nearshore::osg ${OPENSCENEGRAPH_LIBRARIES} OpenGL::GL)
CMAKE
  cmake -S osg-host -B osg-host/build -DCMAKE_BUILD_TYPE=Release && cmake --build osg-host/build
  test "$(ldd osg-host/build/nearshore_osgviewer | grep -cE 'libnearshore(_osg)?\.so\.0 => /(usr/)?lib/')" -eq 2
  if ldd osg-host/build/nearshore_osgviewer | grep 'not found'; then exit 1; fi
fi
apt-get remove -y -q libeigen3-dev nlohmann-json3-dev
gcc -std=c11 -Wall -Wextra -Werror src/query_track.c $(pkg-config --cflags --libs nearshore) -lm -o query_track
./query_track small_bay 5
mkdir -p host
cat > host/CMakeLists.txt <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(host C)
find_package(nearshore 0.1 REQUIRED CONFIG ${NEARSHORE_COMPONENTS})
add_executable(ship_track /root/src/ship_track.c)
target_link_libraries(ship_track PRIVATE nearshore::c m)
CMAKE
cmake -S host -B host/build && cmake --build host/build
./host/build/ship_track small_bay 5 | tail -2
if cmake -S host -B host/build_cxx "-DNEARSHORE_COMPONENTS=COMPONENTS;cxx" > cxx.log 2>&1; then exit 1; fi
grep -q "needs nlohmann_json 3.10 and Eigen3 3.4" cxx.log
echo "fresh Debian $(cat /etc/debian_version): packages installed, samples built and run"
CHECK
mount --bind /dev "$root/dev"
trap 'umount "$root/dev"; umount "$root/proc"' EXIT
mount -t proc proc "$root/proc"
chroot "$root" /bin/bash /root/check.sh
