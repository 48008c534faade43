#!/usr/bin/env bash
# `nearshore play` headless on a small real bake (issue 12): identical inputs give identical
# pictures on every grid; bad input keeps playing what it can and says so (a truncated frame is
# held, a loops.json of another bake falls back to frame order); a manifest of a newer version is
# refused naming the file. Usage: run_viewer.sh NEARSHORE SEQUENCE WORK
set -euo pipefail
nearshore=$1 sequence=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
xvfb() { "${UNDER_XVFB:?the test sets it: tests/under_xvfb.sh}" --screen 1024x768x24 "$@"; }
json_field() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"; }

# 1. Every grid, twice: the same bytes; no underrun when each frame waits for its keyframes.
for grid in radial quadtree projected; do
  for run in 1 2; do
    xvfb "$nearshore" play "$sequence" --grid "$grid" --frames 6 --size 320,180 --screenshot "$work/$grid-$run.png" \
      --json > "$work/$grid-$run.json"
  done
  cmp "$work/$grid-1.png" "$work/$grid-2.png"
  test "$(json_field "$work/$grid-1.json" underruns)" = 0
done

# 2. A truncated frame on the plan's path (the period loop starts at frame 30): held, counted, named.
cp -r "$sequence" "$work/bad_frame"
truncate -s 100 "$work/bad_frame/frame_000032.exr"
xvfb "$nearshore" play "$work/bad_frame" --frames 90 --size 320,180 --json > "$work/bad_frame.json"
test "$(json_field "$work/bad_frame.json" bad_frames_held)" -ge 1
json_field "$work/bad_frame.json" last_message | grep -q "frame_000032.exr"

# 3. loops.json of another bake: the plan falls back to frame order and says why.
cp -r "$sequence" "$work/foreign_loops"
python3 - "$work/foreign_loops/loops.json" <<'PY'
import json, sys
path = sys.argv[1]
tables = json.load(open(path))
tables["sequence_manifest_checksum"] = "xxh64:0123456789abcdef"
json.dump(tables, open(path, "w"), indent=1)
PY
xvfb "$nearshore" play "$work/foreign_loops" --frames 3 --size 320,180 --json > "$work/foreign_loops.json"
json_field "$work/foreign_loops.json" plan | grep -q "frame order"
json_field "$work/foreign_loops.json" last_message | grep -q "loops.json"

# 4. A manifest of a newer version: exit 1, the message names the manifest; no window was needed.
cp -r "$sequence" "$work/newer"
sed -i 's/"version": 1,/"version": 99,/' "$work/newer/manifest.json"
if "$nearshore" play "$work/newer" --frames 1 > "$work/newer.out" 2>&1; then exit 1; fi
grep -q "manifest.json" "$work/newer.out"
echo "viewer: identical pictures, bad frames held, foreign loop tables and newer manifests handled"
