#!/usr/bin/env bash
# The worked real-chart case end to end (issue 14 item 7; docs/commands/bake.md, "Example: a real
# chart"): NOAA ENC US5WA22M -> harbour grid of Commencement Bay -> bake of data/cases/tacoma.toml ->
# loop tables -> a playback screenshot and a wave-height map.
#
#   scripts/tacoma.sh                 the full case: 4.6 m cells (1490 x 1292), 1035 s of sea.
#                                     1 h 39 min on this 2-core machine with neighbours (docs/commands/bake.md) and
#                                     about 2 GiB of frames; resumable (run it again after a kill).
#   TACOMA_SPACING=12 TACOMA_SPIN_UP_S=90 scripts/tacoma.sh
#                                     the coarse variant docs/ shows (12 m cells, 225 s of sea)
#
# Environment: NEARSHORE (the executable; default build/release/tools/nearshore), TACOMA_OUT (default
# out/tacoma), TACOMA_SPACING (cell size, metres), TACOMA_SPIN_UP_S and TACOMA_LOOP_S (override the
# case's spin-up and loop period, for a shorter run). Run from the repository root. A screenshot needs
# a display, or xvfb-run (Debian xvfb) which the script uses when there is no DISPLAY.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
nearshore="${NEARSHORE:-build/release/tools/nearshore}"
out="${TACOMA_OUT:-out/tacoma}"
spacing="${TACOMA_SPACING:-4.6}"
chart="${NEARSHORE_SHARED_DIR:-../shared}/charts/tacoma_us5wa22m/US5WA22M.000"
[[ -x "$nearshore" ]] || { echo "tacoma.sh: $nearshore is not built (scripts/build.sh release, or set NEARSHORE)" >&2; exit 1; }
[[ -f "$chart" ]] || { echo "tacoma.sh: the chart $chart is missing (set NEARSHORE_SHARED_DIR)" >&2; exit 1; }
mkdir -p "$out"

# 1. The harbour grid over the bay, with the gauges of the case marked on the preview by lat/lon.
marks=(--mark "thea_foss_mouth:lat=47.2620,lon=-122.4383" --mark "blair_waterway:lat=47.2680,lon=-122.3965"
       --mark "general_anchorage:lat=47.2907,lon=-122.4266" --mark "mid_bay:lat=47.2850,lon=-122.4450"
       --mark "old_tacoma_offshore:lat=47.2850,lon=-122.4700")
"$nearshore" bathy "$chart" --bbox -122.475,47.252,-122.385,47.305 --spacing "$spacing" "${marks[@]}" -o "$out/harbour"

# 2. The case, pointed at that grid (and shortened when asked).
case_file="$out/tacoma.toml"
sed -e "s|^file = .*|file = \"harbour/depth.exr\"|" data/cases/tacoma.toml > "$case_file"
if [[ -n "${TACOMA_SPIN_UP_S:-}" || -n "${TACOMA_LOOP_S:-}" ]]; then
  spin_up="${TACOMA_SPIN_UP_S:-900}"; loop="${TACOMA_LOOP_S:-120}"
  sed -i -e "s|^spin_up_s = .*|spin_up_s = $spin_up|" -e "s|^loop_period_s = .*|loop_period_s = $loop|" \
         -e "s|^duration_s = .*|duration_s = $(awk "BEGIN { print $spin_up + $loop + 15 }")|" "$case_file"
fi

# 3. The bake (resumes a killed one), timed with its peak memory.
resume=()
[[ -f "$out/sequence/checkpoint.bin" ]] && resume=(--resume)
/usr/bin/time -v "$nearshore" bake "$case_file" -o "$out/sequence" "${resume[@]}" 2> >(tee "$out/bake-stderr.txt" >&2)
echo "load average after the bake: $(cat /proc/loadavg)"

# 4. Loop tables, the wave-statistics map (Hs), a playback screenshot.
"$nearshore" loops "$out/sequence"
"$nearshore" export "$out/sequence" --to geotiff -o "$out/export"
run_gl=()
[[ -z "${DISPLAY:-}" ]] && run_gl=(xvfb-run -a -s "-screen 0 1280x720x24")
"${run_gl[@]}" "$nearshore" play "$out/sequence" --frames 30 --size 1280,720 \
    --eye "lat=47.2700,lon=-122.4500,z_m=180" --target "lat=47.2640,lon=-122.4300" \
    --screenshot "$out/playback.png"
echo "tacoma.sh: wrote $out/harbour/preview.png, $out/sequence, $out/export (wave statistics GeoTIFF), $out/playback.png"
