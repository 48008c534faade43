#!/usr/bin/env bash
# Builds the Debian packages of nearshore (docs/packages.md) from a Release build:
# libnearshore0, libnearshore-dev, nearshore-tools, python3-nearshore (and libnearshore-osg0, libnearshore-osg-dev
# where OpenSceneGraph is found) -> build/release/debs/*.deb.
# Usage: scripts/build-debs.sh [OUTPUT_DIR]. Builds only what the packages hold (not the tests),
# then runs lintian on them where it is installed (its findings are printed, not a failure).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-build/release/debs}"
bash scripts/build.sh release nearshore_packaged_targets
mkdir -p "$out"
rm -f "$out"/*.deb "$out"/*.ddeb
cpack --config build/release/CPackConfig.cmake -B "$out"
rm -rf "$out/_CPack_Packages"
for deb in "$out"/*.deb; do
  echo "$(basename "$deb"): Depends: $(dpkg-deb -f "$deb" Depends)"
done
if command -v lintian > /dev/null; then
  lintian "$out"/*.deb || true
else
  echo "build-debs: lintian is not installed (apt-get install lintian): packages not linted"
fi
