"""Surface queries from Python equal the C API's bit for bit (issue 45): nearshore.Sea.query and
libnearshore.so's nearshore_sea_query_at, called through ctypes on the same sequence, points and
display times. Both run StreamingEngine::snapshot_at and SurfaceSampler::states; the C API rounds
the doubles to float, so the float32 rounding of Python's values must equal its floats exactly."""
import ctypes

import numpy as np
import pytest

import nearshore


class SurfaceSample(ctypes.Structure):  # nearshore_surface_sample (capi/include/nearshore.h)
    _fields_ = [("elevation_m", ctypes.c_float), ("velocity_x_m_s", ctypes.c_float),
                ("velocity_y_m_s", ctypes.c_float), ("normal", ctypes.c_float * 3), ("dry", ctypes.c_int)]


def open_c_sea(library_path, folder):
    c = ctypes.CDLL(library_path)
    c.nearshore_last_error.restype = ctypes.c_char_p
    c.nearshore_sea_open.argtypes = [ctypes.c_char_p, ctypes.c_void_p, ctypes.POINTER(ctypes.c_void_p)]
    c.nearshore_sea_query_at.argtypes = [ctypes.c_void_p, ctypes.c_double, ctypes.POINTER(ctypes.c_double),
                                         ctypes.c_size_t, ctypes.POINTER(SurfaceSample)]
    c.nearshore_sea_close.argtypes = [ctypes.c_void_p]
    sea = ctypes.c_void_p()
    status = c.nearshore_sea_open(str(folder).encode(), None, ctypes.byref(sea))  # NULL: the default options
    assert status == 0, c.nearshore_last_error().decode()
    return c, sea


def c_query(c, sea, time_s, x, y):
    xy = np.ascontiguousarray(np.stack([x, y], axis=1), dtype=np.float64)
    samples = (SurfaceSample * len(x))()
    status = c.nearshore_sea_query_at(sea, time_s, xy.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), len(x), samples)
    assert status == 0, c.nearshore_last_error().decode()
    return samples


def bits(values):
    return np.asarray(values, dtype=np.float32).view(np.uint32)


def test_python_queries_equal_the_c_api_bit_for_bit(baked, c_library):
    folder, _, _ = baked
    sea = nearshore.Sea(folder)
    c, c_sea = open_c_sea(c_library, folder)
    try:
        g = sea.geometry
        rng = np.random.default_rng(45)
        # Inside the harbour (its blending zone, the beach and the dry land included) and beyond
        # its rectangle (the deep water alone), 400 points.
        x = np.concatenate([rng.uniform(0.0, g.width_m, 300), rng.uniform(-150.0, g.width_m + 150.0, 100)])
        y = np.concatenate([rng.uniform(0.0, g.height_m, 300), rng.uniform(-150.0, g.height_m + 150.0, 100)])
        # On keyframes, between them, and past the bake's 55 s of frames (the plan loops).
        for time_s in (0.0, 0.5, 3.217, 17.75, 61.3):
            ours = sea.query(x, y, time_s)
            theirs = c_query(c, c_sea, time_s, x, y)
            elevation = np.array([s.elevation_m for s in theirs], np.float32)
            velocity_x = np.array([s.velocity_x_m_s for s in theirs], np.float32)
            velocity_y = np.array([s.velocity_y_m_s for s in theirs], np.float32)
            normal = np.array([list(s.normal) for s in theirs], np.float32)
            dry = np.array([s.dry for s in theirs]) == 1
            np.testing.assert_array_equal(bits(ours.elevation_m), elevation.view(np.uint32))
            np.testing.assert_array_equal(bits(ours.velocity_x_m_s), velocity_x.view(np.uint32))
            np.testing.assert_array_equal(bits(ours.velocity_y_m_s), velocity_y.view(np.uint32))
            np.testing.assert_array_equal(bits(ours.normal), normal.view(np.uint32))
            np.testing.assert_array_equal(ours.dry, dry)
            # Not a comparison of zeros: waves, currents and dry land are all there.
            assert np.abs(elevation).max() > 0.05 and np.abs(velocity_x).max() > 0.01 and dry.any()
        # Points at several times in one call: each time's points as that time's own query.
        times = np.where(np.arange(len(x)) % 2 == 0, 3.217, 17.75)
        mixed = sea.query(x, y, times)
        for time_s in (3.217, 17.75):
            at = times == time_s
            np.testing.assert_array_equal(mixed.elevation_m[at], sea.query(x[at], y[at], time_s).elevation_m)
    finally:
        c.nearshore_sea_close(c_sea)


class SeaOptions(ctypes.Structure):  # nearshore_sea_options (API version 5 and later)
    _fields_ = [("struct_size", ctypes.c_uint32), ("plan", ctypes.c_int), ("seed", ctypes.c_uint64),
                ("ring_keyframes", ctypes.c_int), ("deep_water_interval_s", ctypes.c_double),
                ("beaufort_force", ctypes.c_int), ("wind_direction_deg", ctypes.c_double),
                ("verify_checksums", ctypes.c_int), ("time_mode", ctypes.c_int), ("ready_timeout_s", ctypes.c_double)]


def test_vertical_velocity_equals_the_c_api_in_lockstep(baked, c_library):
    """d eta / dt from Python equals nearshore_sea_query_vertical_velocity of a lockstep sea advanced
    to the same time (which shows exactly the keyframes of that time)."""
    folder, _, _ = baked
    c = ctypes.CDLL(c_library)
    c.nearshore_last_error.restype = ctypes.c_char_p
    c.nearshore_sea_options_init.argtypes = [ctypes.POINTER(SeaOptions)]
    c.nearshore_sea_open.argtypes = [ctypes.c_char_p, ctypes.POINTER(SeaOptions), ctypes.POINTER(ctypes.c_void_p)]
    c.nearshore_sea_advance.argtypes = [ctypes.c_void_p, ctypes.c_double]
    c.nearshore_sea_query_vertical_velocity.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double),
                                                        ctypes.c_size_t, ctypes.POINTER(ctypes.c_float)]
    c.nearshore_sea_close.argtypes = [ctypes.c_void_p]
    options = SeaOptions()
    c.nearshore_sea_options_init(ctypes.byref(options))
    assert options.struct_size == ctypes.sizeof(SeaOptions)  # the layout above is the header's
    options.time_mode = 1  # NEARSHORE_TIME_LOCKSTEP
    c_sea = ctypes.c_void_p()
    assert c.nearshore_sea_open(str(folder).encode(), ctypes.byref(options), ctypes.byref(c_sea)) == 0, \
        c.nearshore_last_error().decode()
    try:
        sea = nearshore.Sea(folder)
        rng = np.random.default_rng(6)
        x, y = rng.uniform(0.0, 400.0, 200), rng.uniform(0.0, 200.0, 200)
        xy = np.ascontiguousarray(np.stack([x, y], axis=1))
        for time_s in (2.25, 9.1):
            assert c.nearshore_sea_advance(c_sea, time_s) == 0, c.nearshore_last_error().decode()
            theirs = (ctypes.c_float * len(x))()
            status = c.nearshore_sea_query_vertical_velocity(
                c_sea, xy.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), len(x), theirs)
            assert status == 0, c.nearshore_last_error().decode()
            ours = sea.query(x, y, time_s).vertical_velocity_m_s
            np.testing.assert_array_equal(bits(ours), np.array(theirs, np.float32).view(np.uint32))
            assert np.abs(ours).max() > 0.01
    finally:
        c.nearshore_sea_close(c_sea)


def test_query_shapes_and_errors(baked):
    folder, _, _ = baked
    sea = nearshore.Sea(folder)
    xx, yy = np.meshgrid(np.linspace(10, 390, 7), np.linspace(10, 190, 5))
    result = sea.query(xx, yy, 4.0)
    assert result.elevation_m.shape == (5, 7) and result.normal.shape == (5, 7, 3)
    np.testing.assert_allclose(np.linalg.norm(result.normal, axis=-1), 1.0, rtol=1e-12)
    grid = sea.harbour_elevation(4.0)
    assert grid.shape == (50, 100) and grid.dtype == np.float32
    with pytest.raises(nearshore.Error, match="not finite"):
        sea.query([np.nan], [1.0], 0.0)
    with pytest.raises(nearshore.Error, match="time_s"):
        sea.query([1.0], [1.0], -2.0)
    with pytest.raises(nearshore.Error, match="time_s"):
        sea.harbour_elevation(float("inf"))
    with pytest.raises(nearshore.Error, match="plan"):
        nearshore.Sea(folder, plan="sideways")
