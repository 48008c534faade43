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


def built_file(variable, what):
    """The path ctest puts in `variable`; the test is skipped where it is not set or not there."""
    path = os.environ.get(variable)
    if not path or not os.path.exists(path):
        pytest.skip(f"{variable} is not {what} (ctest sets it)")
    return path


@pytest.fixture(scope="session")
def c_library():
    """libnearshore.so, the C API the queries are compared with."""
    return built_file("NEARSHORE_C_LIBRARY", "the built libnearshore.so")


@pytest.fixture(scope="session")
def cli():
    """The built `nearshore` executable, whose outputs the functions' are compared with."""
    return built_file("NEARSHORE_CLI", "the built `nearshore` executable")
