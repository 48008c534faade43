"""Sequence.to_xarray (issue 45): the frames as an xarray Dataset with x/y in metres, time, and the
georeference as attributes; skipped where python3-xarray is not installed."""
import numpy as np
import pytest

import nearshore

xr = pytest.importorskip("xarray")


def test_the_frames_as_a_dataset(baked):
    folder, _, _ = baked
    sequence = nearshore.Sequence(folder)
    data = sequence.to_xarray(frames=slice(5, 15))
    g = sequence.geometry
    assert dict(data.sizes) == {"time": 10, "y": g.rows, "x": g.columns}
    np.testing.assert_array_equal(data.time.values, sequence.times_s[5:15])
    np.testing.assert_array_equal(data.x.values, g.x_m)
    np.testing.assert_array_equal(data.y.values, g.y_m)
    np.testing.assert_array_equal(data.easting_m.values, g.x_m + g.origin_x_m)
    # Each variable holds the frame's values at (time, row, column): row 0 the southern row.
    frame = sequence.frame(9)
    np.testing.assert_array_equal(data.surface_elevation_m.isel(time=4).values, frame.surface_elevation_m)
    np.testing.assert_array_equal(data.flux_y_m2_s.sel(time=frame.time_s).values, frame.flux_y_m2_s)
    # Selection by metres: the cell whose centre is nearest (a gauge's x, y).
    cell = data.surface_elevation_m.sel(x=121.0, y=101.0, method="nearest")
    column, row = int(121.0 // g.spacing_x_m), int(101.0 // g.spacing_y_m)
    assert float(cell.isel(time=0)) == float(sequence.frame(5).surface_elevation_m[row, column])
    np.testing.assert_array_equal(data.still_water_depth_m.values, sequence.harbour_grid().still_water_depth_m)
    assert data.attrs["crs_wkt"] == g.crs_wkt and data.attrs["spacing_x_m"] == g.spacing_x_m
    assert data.attrs["loop_period_s"] == sequence.manifest["loop_period_s"]
    # One channel only: the others are left out.
    assert set(sequence.to_xarray(frames=[0, 1], channels=["breaking"]).data_vars) == {"breaking", "still_water_depth_m", "land"}
