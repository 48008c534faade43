#!/usr/bin/env bash
# Runs a command under Xvfb, where the GL tests draw on Mesa llvmpipe (no GPU on these machines).
#   tests/under_xvfb.sh [--screen WIDTHxHEIGHTxDEPTH] COMMAND [ARGUMENTS...]
# The screen defaults to 640x480x24 (the offscreen tests size their own framebuffers; a window
# larger than the screen is clipped, so a test drawing 1280 x 1024 asks for that screen).
# Why the options:
# - -noreset: each test opens and closes its own window; Xvfb resets the server when its last client
#   leaves and refuses connections while it does ("Failed to open display" in the next test, seen
#   under load).
# - -n from the process id: xvfb-run -a searches for a free display from --server-num (99 by
#   default); two runs started together (a developer's and CI's on one machine, or ctest -j2) could
#   pick the same one, so each search starts at a number derived from this script's pid.
set -euo pipefail
screen=640x480x24
if [[ "${1:-}" == --screen ]]; then
  screen=$2
  shift 2
fi
(($# > 0)) || { echo "under_xvfb.sh: no command given (usage: under_xvfb.sh [--screen WxHxD] COMMAND...)" >&2; exit 2; }
exec "${XVFB_RUN:-xvfb-run}" -a -n $((100 + $$ % 800)) -s "-screen 0 $screen -noreset" "$@"
