"""nearshore for Python: baked harbour sequences as NumPy arrays, the runtime's surface queries, and
the pipeline's bake and loops steps as functions (docs/python.md).

Everything here calls the C++ library through the compiled module ``_nearshore``; this file only
names things and shapes arguments. Arrays of a grid are (rows, columns) with row 0 the SOUTHERN row
(``imshow(..., origin="lower")``); positions are site metres, x east and y north of the grid's
south-west corner, as in the C API. Library errors raise :class:`nearshore.Error` with the library's
message (the file or value at fault, the problem, the fix).
"""
from __future__ import annotations

import dataclasses
import os
import warnings
from typing import Optional, Sequence as _Seq

import numpy as np

from . import _nearshore
from ._nearshore import Error

__all__ = ["Error", "Geometry", "Frame", "HarbourGrid", "Gauges", "SurfaceQuery", "Sequence", "Sea",
           "RecordSpectrum", "record_spectrum", "bake", "loops", "read_case", "CHANNELS"]

CHANNELS = ("surface_elevation", "flux_x", "flux_y", "breaking")


@dataclasses.dataclass(frozen=True)
class Geometry:
    """The harbour grid's georeference: cells, spacing (m), the south-west corner in the CRS."""
    columns: int
    rows: int
    spacing_x_m: float
    spacing_y_m: float
    origin_x_m: float
    origin_y_m: float
    crs_wkt: str
    projection: object

    @property
    def width_m(self) -> float:
        return self.columns * self.spacing_x_m

    @property
    def height_m(self) -> float:
        return self.rows * self.spacing_y_m

    @property
    def x_m(self) -> np.ndarray:
        """Cell-centre x of each column, site metres."""
        return (np.arange(self.columns) + 0.5) * self.spacing_x_m

    @property
    def y_m(self) -> np.ndarray:
        """Cell-centre y of each row (row 0 south), site metres."""
        return (np.arange(self.rows) + 0.5) * self.spacing_y_m


def _geometry(raw: dict) -> Geometry:
    """GridGeometry as core's to_json writes it (one "spacing_m" for square cells)."""
    return Geometry(columns=raw["columns"], rows=raw["rows"],
                    spacing_x_m=raw.get("spacing_x_m", raw.get("spacing_m")),
                    spacing_y_m=raw.get("spacing_y_m", raw.get("spacing_m")),
                    origin_x_m=raw["origin_x_m"], origin_y_m=raw["origin_y_m"],
                    crs_wkt=raw["crs_wkt"], projection=raw["projection"])


@dataclasses.dataclass(frozen=True)
class Frame:
    """One baked frame; channels not read are None. Arrays share the decoded frame's memory."""
    index: int
    time_s: float
    surface_elevation_m: Optional[np.ndarray]
    flux_x_m2_s: Optional[np.ndarray]
    flux_y_m2_s: Optional[np.ndarray]
    breaking: Optional[np.ndarray]


@dataclasses.dataclass(frozen=True)
class HarbourGrid:
    """depth.exr: still-water depth (m, positive down), land (0 water, 1 land, 2 outside the chart),
    porosity, signed coast distance (m) and, where stored, the porous stone diameter (m)."""
    geometry: Geometry
    still_water_depth_m: np.ndarray
    land: np.ndarray
    porosity: np.ndarray
    coast_distance_m: np.ndarray
    porous_stone_diameter_m: Optional[np.ndarray]


@dataclasses.dataclass(frozen=True)
class RecordSpectrum:
    """Welch's spectrum of an elevation record and the sea state read from it (ocean/record_spectrum.hpp):
    one-sided variance density (m^2/Hz) at frequency_hz, Hm0 = 4 sqrt(m0), Tp, Tm01 = m0/m1,
    Tm02 = sqrt(m0/m2)."""
    frequency_hz: np.ndarray
    variance_density_m2_hz: np.ndarray
    frequency_resolution_hz: float
    segment_samples: int
    segment_count: int
    significant_height_hm0_m: float
    peak_period_s: float
    mean_period_tm01_s: float
    zero_crossing_period_tm02_s: float


def record_spectrum(elevation_m, sample_interval_s: float, segment_samples: int = 0,
                    min_frequency_hz: float = 0.0, max_frequency_hz: float = 0.0) -> RecordSpectrum:
    """Welch's spectrum (Hann, half-overlapping segments of segment_samples; 0: a quarter of the
    record) of evenly spaced elevations (m) and its Hm0, Tp, Tm01, Tm02 over the band
    [min_frequency_hz, max_frequency_hz] (0: the first bin above 0, the Nyquist frequency)."""
    raw = _nearshore.record_spectrum(np.ascontiguousarray(elevation_m, dtype=np.float64), float(sample_interval_s),
                                     int(segment_samples), float(min_frequency_hz), float(max_frequency_hz))
    return RecordSpectrum(**raw)


@dataclasses.dataclass(frozen=True)
class Gauges:
    """gauges.csv: elevation_m[g, k] at gauge names[g] and time time_s[k] (s, m)."""
    names: list
    time_s: np.ndarray
    elevation_m: np.ndarray

    def __getitem__(self, name: str) -> np.ndarray:
        if name not in self.names:
            raise KeyError(f"no gauge {name!r}; the gauges are {', '.join(self.names)}")
        return self.elevation_m[self.names.index(name)]

    def statistics(self, from_time_s: float = 0.0, segment_samples: int = 0) -> dict:
        """{gauge name: RecordSpectrum} of each record from from_time_s on (leave out the spin-up)."""
        keep = self.time_s >= from_time_s
        times = self.time_s[keep]
        if times.size < 2:
            raise Error(f"gauges: fewer than 2 samples from t = {from_time_s} s (from_time_s); "
                        "give an earlier time")
        steps = np.diff(times)
        if np.max(np.abs(steps - steps[0])) > 1e-6 * steps[0]:
            raise Error("gauges: the samples are not evenly spaced in time; a spectrum needs even spacing")
        interval_s = float((times[-1] - times[0]) / (times.size - 1))
        return {name: record_spectrum(self.elevation_m[g][keep], interval_s, segment_samples)
                for g, name in enumerate(self.names)}


@dataclasses.dataclass(frozen=True)
class SurfaceQuery:
    """The surface at query points (arrays of the points' shape; normal has a last axis of 3)."""
    elevation_m: np.ndarray
    velocity_x_m_s: np.ndarray
    velocity_y_m_s: np.ndarray
    vertical_velocity_m_s: np.ndarray
    slope_x: np.ndarray
    slope_y: np.ndarray
    normal: np.ndarray
    harbour_weight: np.ndarray
    dry: np.ndarray


class Sequence:
    """A baked sequence folder (`nearshore bake -o DIR`): manifest, frames, harbour grid, gauges,
    loop plans. Opening reads and checks manifest.json only."""

    def __init__(self, folder: str | os.PathLike):
        self._reader = _nearshore.SequenceReader(os.fspath(folder))
        self.folder = os.fspath(folder)
        self.manifest: dict = self._reader.manifest
        self.geometry = _geometry(self._reader.geometry)
        self.frame_count: int = self._reader.frame_count
        self.frame_interval_s: float = self._reader.frame_interval_s

    def __len__(self) -> int:
        return self.frame_count

    @property
    def times_s(self) -> np.ndarray:
        """The bake's simulated time of every frame, s."""
        return np.array([self._reader.frame_time_s(k) for k in range(self.frame_count)])

    def frame(self, index: int, channels: _Seq[str] = CHANNELS, verify: bool = False) -> Frame:
        """Frame `index` (0 .. frame_count - 1); `channels` a subset of CHANNELS; `verify` checks
        the file's XXH64 against the manifest first."""
        return Frame(**self._reader.read_frame(index, list(channels), verify))

    def harbour_grid(self) -> HarbourGrid:
        raw = self._reader.read_harbour_grid()
        raw["geometry"] = _geometry(raw["geometry"])
        return HarbourGrid(**raw)

    def gauges(self) -> Gauges:
        """The bake's gauge records (DIR/gauges.csv)."""
        return Gauges(**_nearshore.read_gauges_csv(os.path.join(self.folder, "gauges.csv")))

    def loops_file(self) -> Optional[dict]:
        """loops.json (written by `nearshore loops` or :func:`loops`) as validated by the library:
        the report's keys with its loop plans ("period_loop", "requested_loop",
        "best_loops_by_length"), the random walk and the transitions; None when there is none."""
        if not os.path.exists(os.path.join(self.folder, "loops.json")):
            return None
        return _nearshore.read_loops_file(self.folder)

    def verify_checksums(self) -> None:
        self._reader.verify_checksums()


class Sea:
    """A sequence (or a sea-state library folder, at `conditions` "KEY=VALUE,...") streamed as the
    C API's nearshore_sea_open streams it, with its defaults; `plan` is "auto", "exact period",
    "optimal loop", "random walk" or "frame order". Times are display seconds of the sea's
    timeline (0 is the first step of its plan)."""

    def __init__(self, folder: str | os.PathLike, conditions: str = "", plan: str = "auto", seed: int = 0):
        self._sea = _nearshore.Sea(os.fspath(folder), conditions, plan, seed)
        self.geometry = _geometry(self._sea.geometry)
        self.frame_interval_s: float = self._sea.frame_interval_s

    @property
    def plan(self) -> str:
        return self._sea.plan

    def query(self, x_m, y_m, time_s, lattice: bool = False) -> SurfaceQuery:
        """The surface at points (x_m, y_m) (site metres, any broadcastable shapes) and display
        time(s) `time_s` (a number or an array of the points' shape): nearshore_sea_query_at's
        values in double precision (the C API rounds them to float). `lattice`: evaluate the
        deep water's choppy field at the undisplaced lattice point (what a vertex shader draws)."""
        x, y, t = np.broadcast_arrays(np.asarray(x_m, float), np.asarray(y_m, float), np.asarray(time_s, float))
        shape = x.shape
        x, y, t = x.ravel(), y.ravel(), t.ravel()
        fields = {f.name: None for f in dataclasses.fields(SurfaceQuery)}
        # One snapshot per distinct time, as the C API makes one per nearshore_sea_query_at call.
        for time in np.unique(t):
            at = np.flatnonzero(t == time)
            part = self._sea.query_at(float(time), np.ascontiguousarray(x[at]), np.ascontiguousarray(y[at]), lattice)
            if len(at) == len(t):
                fields = part
                break
            for name, values in part.items():
                if fields[name] is None:
                    fields[name] = np.empty((len(t),) + values.shape[1:], values.dtype)
                fields[name][at] = values
        if len(t) == 0:
            fields = self._sea.query_at(0.0, np.empty(0), np.empty(0), lattice)
        return SurfaceQuery(**{name: values.reshape(shape + values.shape[1:]) for name, values in fields.items()})

    def harbour_elevation(self, time_s: float) -> np.ndarray:
        """The harbour's elevation at every cell centre at display time `time_s`, as shown (joined
        in time like the renderer and the queries); (rows, columns), float32, m."""
        return self._sea.harbour_elevation_at(float(time_s))


def bake(case_file, output_folder, resume: bool = False, overwrite: bool = False,
         allow_over_budget: bool = False, progress: bool = False) -> dict:
    """`nearshore bake CASE -o DIR [--resume] [--overwrite] [--allow-over-budget]`: the same library
    calls (bake/bake_case.hpp read_bake_case, bake/bake_run.hpp run_bake). Returns the summary
    `--json` prints; the case's warnings also go through :mod:`warnings`. `progress`: the progress
    bar on stderr."""
    summary = _nearshore.bake(os.fspath(case_file), os.fspath(output_folder), resume, overwrite,
                              allow_over_budget, progress)
    for warning in summary.get("warnings", []):
        warnings.warn(warning, stacklevel=2)
    return summary


def loops(sequence_folder, loop_s: float = 0.0, lengths_s=(10, 20, 30, 60, 120, 300), max_crossfade_s: float = 2.0,
          period_crossfade_s: float = 10.0, recompute: bool = False, verify: bool = False, write: bool = True,
          memory_mb: float = 1024.0, threads: int = 2, progress: bool = False) -> dict:
    """`nearshore loops SEQUENCE` with its options (`--loop-s`, `--lengths-s`, `--max-crossfade-s`,
    `--period-crossfade-s`, `--recompute`, `--verify`, `--no-write` as write=False, `--memory-mb`,
    `--threads`): the library's analyse_loops. Returns the report `--json` prints; writes
    loops.json and loops_gram.bin into the folder unless write is False."""
    return _nearshore.loops(os.fspath(sequence_folder), loop_s, [float(v) for v in lengths_s], max_crossfade_s,
                            period_crossfade_s, recompute, verify, write, memory_mb, threads, progress)


def read_case(case_file, allow_over_budget: bool = False) -> dict:
    """A case file read and checked as `nearshore bake` reads it: geometry, timing, gauges (name,
    x_m, y_m in site metres), warnings, wave conditions."""
    case = _nearshore.read_case(os.fspath(case_file), allow_over_budget)
    case["geometry"] = _geometry(case["geometry"])
    return case
