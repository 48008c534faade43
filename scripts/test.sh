#!/usr/bin/env bash
# README command 2: installs the dependencies, builds (Release), runs every test with ctest, then
# rebuilds the `asan`-labelled suites with AddressSanitizer + UBSan and runs them.
# The full-resolution validation runs (label `validation`, minutes each) are left to
# `ctest --preset release -L validation`; CI runs the coarse physics versions (label `physics`).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
bash scripts/install-deps.sh
installed=$(date +%s)
bash scripts/build.sh release
built=$(date +%s)
ctest --preset release --output-on-failure -LE validation
tested=$(date +%s)
bash scripts/build.sh asan nearshore_asan_suites
ctest --preset asan --output-on-failure
sanitized=$(date +%s)
echo "timing: install $((installed - start)) s, build $((built - installed)) s, tests $((tested - built)) s, sanitizer build+tests $((sanitized - tested)) s"
