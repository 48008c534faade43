#!/usr/bin/env bash
# README command 1: installs the dependencies, builds (Release) and runs `nearshore demo`, which
# generates the demo harbour and takes it chart -> bathymetry grid -> bake -> loops -> screenshot.
# Outputs go to demo-out/ (or the folder given as the first argument).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh release
out="${1:-demo-out}"
exec xvfb-run -a -s "-screen 0 1280x720x24" ./build/release/tools/nearshore demo -o "$out"
