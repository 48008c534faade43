#!/usr/bin/env bash
# Installs every Debian package nearshore needs to build, test and run (idempotent; run as root).
# The list and the reasons behind it: ../shared/toolchain.md and docs/architecture.md.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
APT=(apt-get -y -o DPkg::Lock::Timeout=300)
packages=(
  build-essential cmake ninja-build pkg-config ccache git dpkg-dev file help2man
  libgeographiclib-dev
  libopenexr-dev libimath-dev
  libopenvdb-dev libblosc-dev libboost-iostreams-dev libboost-dev
  libcgal-dev libgmp-dev libmpfr-dev
  libopenimageio-dev openimageio-tools libpng-dev libfreetype-dev
  libglfw3-dev libimgui-dev
  libgdal-dev gdal-bin
  libnetcdf-dev netcdf-bin
  libfftw3-dev
  libeigen3-dev
  libtbb-dev
  libcli11-dev nlohmann-json3-dev libtomlplusplus-dev
  libassimp-dev
  libopenscenegraph-dev openscenegraph
  libopenmpi-dev openmpi-bin
  libspdlog-dev libfmt-dev libxxhash-dev
  libgtest-dev libbenchmark-dev
  xvfb xauth mesa-utils libgl1-mesa-dri libegl1-mesa-dev libegl-dev libgl-dev libgles-dev
  python3 python3-glad fonts-dejavu-core
  python3-dev python3-pybind11 python3-numpy python3-pytest python3-matplotlib python3-xarray python3-pil
  clang
)
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then missing+=("$p"); fi
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi
echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
$SUDO "${APT[@]}" update
$SUDO "${APT[@]}" install --no-install-recommends "${missing[@]}"
