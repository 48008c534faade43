#!/usr/bin/env python3
"""Worked example of docs/python.md: bake a small bay, then plot the significant wave height Hs at
its gauges, three ways: from the bake's gauge records (gauges.csv), from the baked frames at the
gauges' cells, and from the runtime's surface queries (what a viewer or a ship simulator is shown).

    PYTHONPATH=build/release/python python3 python/examples/gauges_hs.py --output gauges-hs-out

Writes OUTPUT/bay (the sequence) and OUTPUT/gauges_hs.png, and prints the table of Hs per gauge.
Hs here is the spectral Hm0 = 4 sqrt(m0), m0 the variance of the surface elevation.
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")  # no display needed: the figure goes to a PNG
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import nearshore  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent


def hm0(elevation_m, axis=-1):
    """4 sqrt(m0), m0 the variance of the elevation record (its mean removed)."""
    return 4.0 * np.std(elevation_m, axis=axis)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--case", default=HERE / "bay_gauges.toml", type=pathlib.Path)
    parser.add_argument("--output", default=pathlib.Path("gauges-hs-out"), type=pathlib.Path)
    args = parser.parse_args()
    args.output.mkdir(parents=True, exist_ok=True)

    # 1. The case as `nearshore bake` reads it (gauge positions in site metres), then the bake.
    case = nearshore.read_case(args.case)
    folder = args.output / "bay"
    summary = nearshore.bake(args.case, folder, overwrite=True)
    print(f"baked {summary['outputs']['frames']} frames of {summary['cells']} cells in {summary['wall_time_s']:.1f} s")

    # 2. The sequence: gauge records, frames and the harbour grid, as NumPy arrays.
    sequence = nearshore.Sequence(folder)
    gauges = sequence.gauges()
    grid = sequence.harbour_grid()
    g = grid.geometry
    names = [gauge["name"] for gauge in case["gauges"]]
    x = np.array([gauge["x_m"] for gauge in case["gauges"]])
    y = np.array([gauge["y_m"] for gauge in case["gauges"]])
    columns = np.minimum((x / g.spacing_x_m).astype(int), g.columns - 1)
    rows = np.minimum((y / g.spacing_y_m).astype(int), g.rows - 1)
    depth_m = grid.still_water_depth_m[rows, columns]

    # Gauge records after the spin-up: the same stretch of time the frames hold.
    after_spin_up = gauges.time_s >= case["spin_up_s"]
    hs_gauges = hm0(gauges.elevation_m[:, after_spin_up])
    # Frames: the elevation of the cell under each gauge (nearest cell centre), every frame.
    eta_frames = np.array([sequence.frame(k, channels=["surface_elevation"]).surface_elevation_m[rows, columns]
                           for k in range(sequence.frame_count)])
    hs_frames = hm0(eta_frames, axis=0)
    # Runtime: the shown surface at the gauges, every 0.25 s of display time over the frames' span.
    # The folder has no loops.json, so the sea plays the frames in order: display time t shows bake
    # time spin_up_s + t, the stretch the two estimates above use.
    sea = nearshore.Sea(folder)
    times_s = np.arange(0.0, (sequence.frame_count - 1) * sequence.frame_interval_s, 0.25)
    tt, xx = np.meshgrid(times_s, x, indexing="ij")
    shown = sea.query(xx, np.broadcast_to(y, xx.shape), tt).elevation_m
    hs_shown = hm0(shown, axis=0)

    print(f"{'gauge':<12} {'x (m)':>6} {'depth (m)':>9} {'Hs gauges':>10} {'Hs frames':>10} {'Hs shown':>9}")
    for k, name in enumerate(names):
        print(f"{name:<12} {x[k]:6.0f} {depth_m[k]:9.2f} {hs_gauges[k]:10.3f} {hs_frames[k]:10.3f} {hs_shown[k]:9.3f}")

    # 3. The figure: Hs along the gauge line, the bed under it, and two records.
    figure, (top, middle, bottom) = plt.subplots(3, 1, figsize=(8, 9), constrained_layout=True)
    top.plot(x, hs_gauges, "o-", label="gauge records (gauges.csv, 0.1 s, after spin-up)")
    top.plot(x, hs_frames, "s--", label="baked frames at the gauge cells (0.5 s)")
    top.plot(x, hs_shown, "^:", label="runtime queries, nearshore.Sea (0.25 s)")
    top.set_xlabel("x, distance east of the grid's west edge (m)")
    top.set_ylabel("Hs = 4 sqrt(m0) (m)")
    top.set_ylim(bottom=0.0)
    top.set_title(f"Hs at the gauges of {args.case.name} (Beaufort 4 from the west)")
    top.grid(True, alpha=0.3)
    top.legend(fontsize=8)

    profile_row = int(np.median(rows))
    middle.fill_between(g.x_m, -grid.still_water_depth_m[profile_row], -14.0, color="tan", label="bed")
    middle.axhline(0.0, color="tab:blue", linewidth=1, label="still water")
    middle.plot(x, np.zeros_like(x), "kv", label="gauges")
    for k, name in enumerate(names):
        middle.annotate(name, (x[k], 0.5), rotation=45, fontsize=7)
    top.set_xlim(0.0, g.width_m)
    middle.set_xlim(0.0, g.width_m)
    middle.set_ylim(-14.0, 6.0)
    middle.set_xlabel("x (m)")
    middle.set_ylabel("elevation above still water (m)")
    middle.legend(fontsize=8, loc="lower left")

    shown_window = gauges.time_s >= gauges.time_s[-1] - 20.0
    for k in (0, len(names) - 1):
        bottom.plot(gauges.time_s[shown_window], gauges.elevation_m[k, shown_window], label=names[k])
    bottom.set_xlabel("bake time t (s)")
    bottom.set_ylabel("surface elevation (m)")
    bottom.set_title("the last 20 s of two gauge records")
    bottom.grid(True, alpha=0.3)
    bottom.legend(fontsize=8)

    png = args.output / "gauges_hs.png"
    figure.savefig(png, dpi=100)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
