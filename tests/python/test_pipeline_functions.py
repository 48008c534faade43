"""nearshore.bathy, nearshore.export, nearshore.library and Sea(library, conditions=...) (issue 45):
each function makes the library calls its command makes (tools/*_command.cpp), so on the same tiny
input it writes the same files as the CLI (NEARSHORE_CLI, set by ctest), byte for byte where the
files are deterministic; a library's sea queried from Python equals the C API's bit for bit."""
import ctypes
import filecmp
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import nearshore

from test_queries_match_c_api import SurfaceSample, bits, c_query


def run_cli(cli, *arguments):
    done = subprocess.run([cli, *map(str, arguments)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


def write_soundings(path):
    """A small bay in soundings (lon lat depth, WGS 84 degrees): 1.2 x 0.9 km off Tacoma, 20 m
    apart, shelving from 15 m in the west to land (negative depth) in the east."""
    lon = -122.440 + np.arange(60) * 0.00026   # about 20 m at 47.27 N
    lat = 47.270 + np.arange(45) * 0.00018     # about 20 m
    rows = []
    for j, la in enumerate(lat):
        for i, lo in enumerate(lon):
            rows.append(f"{lo:.6f} {la:.6f} {15.0 - 18.0 * i / 59 + 0.5 * np.sin(j / 5.0):.3f}")
    path.write_text("\n".join(rows) + "\n")
    return path


def same_files(a, b, names):
    for name in names:
        assert filecmp.cmp(a / name, b / name, shallow=False), f"{name} differs between {a} and {b}"


def test_bathy_writes_what_the_cli_writes(tmp_path, cli):
    soundings = write_soundings(tmp_path / "bay.xyz")
    options = dict(spacing_m=25.0, bbox=(-122.438, 47.2705, -122.426, 47.277), water_level_m=0.5, min_depth_m=1.0, max_slope=0.3,
                   structures={"breakwater": (20.0, 0.4)}, marks={"gauge": "lat=47.274,lon=-122.432"},
                   surroundings_margin_m=400.0)
    with pytest.warns(UserWarning, match=r"shallower than min_depth_m = 1 m"):  # the library's warning, named by keyword
        summary = nearshore.bathy(soundings, tmp_path / "py", **options)
    printed = json.loads(run_cli(cli, "bathy", soundings, "--spacing", 25, "--bbox", "-122.438,47.2705,-122.426,47.277",
                                 "--water-level", 0.5, "--min-depth", 1.0,
                                 "--max-slope", 0.3, "--structure", "breakwater=20:0.4",
                                 "--mark", "gauge:lat=47.274,lon=-122.432", "--surroundings-margin", 400,
                                 "--json", "-o", tmp_path / "cli"))
    # The grid, its GeoTIFF and the preview byte for byte; the summary up to the output folder's name.
    same_files(tmp_path / "py", tmp_path / "cli", ["depth.exr", "depth.tif", "preview.png"])
    assert json.dumps(summary).replace(str(tmp_path / "py"), "OUT") == \
        json.dumps(printed).replace(str(tmp_path / "cli"), "OUT")
    assert summary["columns"] > 0 and summary["cells"]["water"] > 0
    assert summary["water_depth_m"]["min"] >= 1.0 - 1e-6   # min_depth_m reached the library
    assert summary["surroundings"]["margin_m"] == 400.0     # and surroundings_margin_m
    with pytest.raises(nearshore.Error, match="spacing_m"):
        nearshore.bathy(soundings, tmp_path / "bad", spacing_m=-1.0)
    with pytest.raises(nearshore.Error, match="bbox"):
        nearshore.bathy(soundings, tmp_path / "bad", spacing_m=25.0, bbox=(1.0, 2.0, 0.0, 3.0))  # reversed


@pytest.mark.parametrize("to", ["netcdf", "geotiff"])
def test_export_writes_what_the_cli_writes(baked, tmp_path, cli, to):
    folder, _, _ = baked
    summary = nearshore.export(folder, to, tmp_path / "py", frames=slice(10, 30))
    printed = json.loads(run_cli(cli, "export", folder, "--to", to, "--frames", "10:30", "--json", "-o", tmp_path / "cli"))
    names = sorted(os.path.basename(f["file"]) for f in summary["files"])
    assert names == sorted(os.path.basename(f["file"]) for f in printed["files"]) and names
    assert (summary["frames"]["first"], summary["frames"]["end"]) == (10, 30)
    deterministic = [n for n in names if not n.endswith(".nc")]
    same_files(tmp_path / "py", tmp_path / "cli", deterministic)
    for name in names:
        if name.endswith(".nc"):
            # NetCDF: the same header and variables; libnetcdf writes no time stamp of its own, so the
            # whole file is the same unless the export records one.
            assert (tmp_path / "py" / name).stat().st_size == (tmp_path / "cli" / name).stat().st_size
            assert filecmp.cmp(tmp_path / "py" / name, tmp_path / "cli" / name, shallow=False)
    with pytest.raises(nearshore.Error, match="not an export format"):
        nearshore.export(folder, "png", tmp_path / "bad")
    with pytest.raises(nearshore.Error, match="agitation"):
        nearshore.export(folder, "netcdf", tmp_path / "bad", incident_hs_m=1.0)


@pytest.fixture(scope="module")
def small_library(tmp_path_factory, case_file):
    """Two states of a shortened example bay (20 s spin-up, one 40 s loop), the wind veered 30
    degrees, made by nearshore.library (two bakes and their loop tables: seconds)."""
    root = tmp_path_factory.mktemp("library")
    text = pathlib.Path(case_file).read_text()
    text = text.replace("duration_s = 145.0", "duration_s = 75.0").replace("spin_up_s = 90.0", "spin_up_s = 20.0")
    (root / "base.toml").write_text(text)
    (root / "library.toml").write_text('title = "two winds"\nbase_case = "base.toml"\n[sweep]\n'
                                       "wind_direction_deg = [0.0, 30.0]\n")
    summary = nearshore.library(root / "library.toml", root / "out")
    return root, summary


def test_library_makes_a_library_the_cli_finds_complete(small_library, cli):
    root, summary = small_library
    assert (summary["states"], summary["baked"], summary["failed"]) == (2, 2, 0)
    # The CLI on the same library file and folder: every state is already there (the same cases,
    # fingerprint for fingerprint), so it bakes nothing.
    printed = json.loads(run_cli(cli, "library", root / "library.toml", "-o", root / "out", "--json"))
    assert printed["baked"] == 2 and printed["failed"] == 0
    assert set(printed["actions"]) == {"reused"}, printed["actions"]


def test_a_library_sea_equals_the_c_api_bit_for_bit(small_library, c_library):
    root, _ = small_library
    folder = root / "out"
    c = ctypes.CDLL(c_library)
    c.nearshore_last_error.restype = ctypes.c_char_p
    c.nearshore_sea_open_library.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_void_p,
                                             ctypes.POINTER(ctypes.c_void_p)]
    c.nearshore_sea_query_at.argtypes = [ctypes.c_void_p, ctypes.c_double, ctypes.POINTER(ctypes.c_double),
                                         ctypes.c_size_t, ctypes.POINTER(SurfaceSample)]
    c.nearshore_sea_close.argtypes = [ctypes.c_void_p]
    rng = np.random.default_rng(16)
    for conditions in ("wind_direction_deg=25", "wind_direction_deg=0"):
        sea = nearshore.Sea(folder, conditions=conditions)
        c_sea = ctypes.c_void_p()
        assert c.nearshore_sea_open_library(str(folder).encode(), conditions.encode(), None, ctypes.byref(c_sea)) == 0, \
            c.nearshore_last_error().decode()
        try:
            g = sea.geometry
            x, y = rng.uniform(0.0, g.width_m, 200), rng.uniform(0.0, g.height_m, 200)
            for time_s in (0.0, 1.25, 13.7):
                ours = sea.query(x, y, time_s)
                theirs = c_query(c, c_sea, time_s, x, y)
                for name in ("elevation_m", "velocity_x_m_s", "velocity_y_m_s"):
                    np.testing.assert_array_equal(bits(getattr(ours, name)),
                                                  bits(np.array([getattr(s, name) for s in theirs], np.float32)))
                np.testing.assert_array_equal(ours.dry, np.array([s.dry != 0 for s in theirs]))
        finally:
            c.nearshore_sea_close(c_sea)
    # The two states are different seas: the same point and time differ between them.
    veered, west = nearshore.Sea(folder, conditions="wind_direction_deg=30"), nearshore.Sea(folder)
    assert not np.array_equal(veered.query(x, y, 5.0).elevation_m, west.query(x, y, 5.0).elevation_m)


def test_operability_writes_what_the_cli_writes(small_library, cli):
    root, _ = small_library
    (root / "occurrence.csv").write_text("hs_m,tp_s,direction_deg,probability\n0.5,6,0,0.5\n1.0,6,30,0.3\n1.5,6,10,0.2\n")
    (root / "berths.csv").write_text("name,x_m,y_m\nquay,300,100\nbeach,360,60\n")
    result = nearshore.operability(root / "out", root / "occurrence.csv", root / "berths.csv", 0.5, root / "ops-py")
    printed = json.loads(run_cli(cli, "library", "operability", root / "out", "--occurrence", root / "occurrence.csv",
                                 "--berths", root / "berths.csv", "--threshold-hs", 0.5, "-o", root / "ops-cli", "--json"))
    files = result.pop("files")
    assert sorted(os.path.basename(f) for f in files) == sorted(os.listdir(root / "ops-cli"))
    same_files(root / "ops-py", root / "ops-cli", [n for n in os.listdir(root / "ops-cli") if n.endswith(".csv")])
    assert result == printed
    assert [b["name"] for b in result["berths"]] == ["quay", "beach"]
    assert all(0.0 <= b["exceedance_percent"] <= 100.0 for b in result["berths"])
    with pytest.raises(nearshore.Error, match="threshold_hs_m"):
        nearshore.operability(root / "out", root / "occurrence.csv", root / "berths.csv", -1.0)
