"""A baked sequence read through nearshore.Sequence: manifest, grid with its georeference, frames
and gauges as NumPy arrays sharing the library's memory, loop plans, and the library's errors."""
import numpy as np
import pytest

import nearshore


def test_bake_summary_and_manifest_agree(baked, case_file):
    folder, summary, _ = baked
    sequence = nearshore.Sequence(folder)
    case = nearshore.read_case(case_file)
    assert summary["outputs"]["frames"] == sequence.frame_count == len(sequence)
    assert sequence.frame_interval_s == case["output_interval_s"] == 0.5
    assert sequence.manifest["frame_count"] == sequence.frame_count
    # Frames start after the spin-up, one output interval apart.
    times = sequence.times_s
    assert times[0] == pytest.approx(case["spin_up_s"])
    np.testing.assert_allclose(np.diff(times), 0.5)


def test_harbour_grid_is_the_case_profile_with_its_georeference(baked):
    folder, _, _ = baked
    sequence = nearshore.Sequence(folder)
    grid = sequence.harbour_grid()
    g = grid.geometry
    assert (g.columns, g.rows, g.spacing_x_m, g.spacing_y_m) == (100, 50, 4.0, 4.0)
    assert g == sequence.geometry
    assert isinstance(g.crs_wkt, str)  # a laboratory grid: no CRS, empty text
    assert grid.still_water_depth_m.shape == (50, 100) and grid.still_water_depth_m.dtype == np.float32
    # The case's profile: 12 m on the flat part, 12 - 14 (x - 250) / 150 on the beach, land past 385.7 m.
    x = g.x_m
    expected = np.where(x <= 250.0, 12.0, 12.0 - 14.0 * (x - 250.0) / 150.0)
    np.testing.assert_allclose(grid.still_water_depth_m[25], expected, atol=1e-4)
    assert grid.land.dtype == np.uint8
    assert not grid.land[:, x < 380].any() and grid.land[:, x > 390].all()
    # Zero-copy: the arrays are views of the grid the library read (their base owns it).
    assert not grid.still_water_depth_m.flags.owndata and grid.still_water_depth_m.base is not None


def test_frames_are_views_of_the_decoded_channels(baked):
    folder, _, _ = baked
    sequence = nearshore.Sequence(folder)
    frame = sequence.frame(7)
    assert frame.index == 7 and frame.time_s == sequence.times_s[7]
    for channel in (frame.surface_elevation_m, frame.flux_x_m2_s, frame.flux_y_m2_s, frame.breaking):
        assert channel.shape == (50, 100) and channel.dtype == np.float32
        assert not channel.flags.owndata
        assert np.isfinite(channel).all()
    # Waves are there: a Beaufort 4 sea has decimetres of elevation over the flat part.
    assert 0.05 < np.abs(frame.surface_elevation_m[:, 20:60]).max() < 3.0
    only = sequence.frame(7, channels=["surface_elevation"], verify=True)
    assert only.flux_x_m2_s is None and only.breaking is None
    np.testing.assert_array_equal(only.surface_elevation_m, frame.surface_elevation_m)


def test_gauges_are_the_case_gauges(baked, case_file):
    folder, _, _ = baked
    gauges = nearshore.Sequence(folder).gauges()
    case = nearshore.read_case(case_file)
    assert gauges.names == [g["name"] for g in case["gauges"]]
    assert gauges.elevation_m.shape == (len(gauges.names), len(gauges.time_s))
    np.testing.assert_allclose(np.diff(gauges.time_s), 0.1, atol=1e-9)
    assert gauges["toe_240m"] is not None and gauges["toe_240m"].shape == gauges.time_s.shape
    assert case["gauges"][0]["x_m"] == 120.0 and case["gauges"][0]["y_m"] == 100.0  # site metres
    with pytest.raises(KeyError, match="flat_120m"):
        gauges["nowhere"]


def test_loop_plans_are_read_back(baked):
    folder, _, report = baked
    loops = nearshore.Sequence(folder).loops_file()
    assert loops is not None
    assert loops["format"] == "nearshore loops" and loops["frame_count"] == report["frame_count"]
    # A periodic bake (loop_period_s = 40 s): the exact-period loop of 80 frames.
    assert report["period_loop"]["length_frames"] == 80
    assert loops["period_loop"] == report["period_loop"]
    assert loops["transitions"] and loops["random_walk"]["start_frame"] >= 0


def test_library_errors_carry_the_library_message(baked, tmp_path, case_file):
    folder, _, _ = baked
    # The library's message, its option named as the keyword that sets it (BakeOptions::resume).
    with pytest.raises(nearshore.Error, match=r"manifest.json: does not exist.*resume=True"):
        nearshore.Sequence(tmp_path)
    with pytest.raises(nearshore.Error, match="frame_000999.exr|999"):
        nearshore.Sequence(folder).frame(999)
    with pytest.raises(nearshore.Error, match="no_such_case.toml"):
        nearshore.bake(tmp_path / "no_such_case.toml", tmp_path / "out")
    # A complete sequence is not replaced without overwrite=True (the CLI's --overwrite).
    with pytest.raises(nearshore.Error, match="overwrite=True"):
        nearshore.bake(case_file, folder)
    with pytest.raises(nearshore.Error, match="not a frame channel"):
        nearshore.Sequence(folder).frame(0, channels=["height"])


def test_bake_equals_the_command_line_bake(baked, case_file, tmp_path, cli):
    """nearshore.bake makes the calls `nearshore bake` makes: the same frames and gauge records."""
    import json
    import subprocess
    folder, _, _ = baked
    subprocess.run([cli, "bake", str(case_file), "-o", str(tmp_path / "cli"), "--json"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    ours = json.loads((folder / "manifest.json").read_text())
    theirs = json.loads((tmp_path / "cli" / "manifest.json").read_text())
    assert [f["checksum"] for f in ours["frames"]] == [f["checksum"] for f in theirs["frames"]]
    for name in ("gauges.csv", "gauge_fluxes.csv", "gauge_statistics.csv"):
        assert (folder / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
