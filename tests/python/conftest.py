"""Fixtures of the Python module's tests (tests/python/CMakeLists.txt runs them through ctest with
PYTHONPATH at the built package): one small real bake per session, with its loop tables."""
import os
import pathlib

import pytest

import nearshore

SOURCE = pathlib.Path(__file__).resolve().parents[2]
CASE = SOURCE / "python" / "examples" / "bay_gauges.toml"


@pytest.fixture(scope="session")
def case_file():
    return CASE


@pytest.fixture(scope="session")
def baked(tmp_path_factory):
    """The example bay baked through nearshore.bake and analysed by nearshore.loops (a few seconds)."""
    folder = tmp_path_factory.mktemp("bake") / "bay"
    summary = nearshore.bake(CASE, folder)
    report = nearshore.loops(folder)
    return folder, summary, report


@pytest.fixture(scope="session")
def c_library():
    """libnearshore.so, the C API the queries are compared with (its path from ctest)."""
    path = os.environ.get("NEARSHORE_C_LIBRARY")
    if not path:
        pytest.skip("NEARSHORE_C_LIBRARY is not set (ctest sets it to the built libnearshore.so)")
    return path
