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
           "RecordSpectrum", "DirectionalRecordSpectrum", "record_spectrum", "directional_record_spectrum", "direction_from_deg",
           "bake", "loops", "read_case", "bathy", "library", "operability", "export", "EXPORT_FORMATS", "CHANNELS"]

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
class DirectionalRecordSpectrum(RecordSpectrum):
    """A RecordSpectrum with the sea's directions from the flux (or velocity) recorded with the
    elevation, the PUV method (ocean/record_spectrum.hpp): per bin the first-order coefficients a1,
    b1, the direction atan2(b1, a1) and Kuik's spread; the direction at the peak bin, and the mean
    direction and spread over the band weighted by the elevation's spectrum. Directions are those
    the waves travel TOWARDS, degrees counter-clockwise from east (the grid's x axis), in
    (-180, 180]; :func:`direction_from_deg` gives the compass direction they come from. NaN where
    there is no variance."""
    a1: np.ndarray
    b1: np.ndarray
    direction_deg: np.ndarray
    spread_deg: np.ndarray
    peak_direction_deg: float
    mean_direction_deg: float
    directional_spread_deg: float


def directional_record_spectrum(elevation_m, flux_x, flux_y, sample_interval_s: float, segment_samples: int = 0,
                                min_frequency_hz: float = 0.0, max_frequency_hz: float = 0.0) -> DirectionalRecordSpectrum:
    """:func:`record_spectrum` of the elevation and the directions from the east and north
    components of the flux (m^2/s) or velocity (m/s) sampled with it (the PUV method)."""
    records = [np.ascontiguousarray(r, dtype=np.float64) for r in (elevation_m, flux_x, flux_y)]
    raw = _nearshore.directional_record_spectrum(*records, float(sample_interval_s), int(segment_samples),
                                                 float(min_frequency_hz), float(max_frequency_hz))
    return DirectionalRecordSpectrum(**raw)


def direction_from_deg(towards_deg):
    """The compass direction waves come FROM (degrees clockwise from north, [0, 360)) of a
    direction of travel counter-clockwise from east: 270 - towards, modulo 360."""
    return np.mod(270.0 - np.asarray(towards_deg, dtype=float), 360.0)


@dataclasses.dataclass(frozen=True)
class Gauges:
    """gauges.csv: elevation_m[g, k] at gauge names[g] and time time_s[k] (s, m); with the
    gauge_fluxes.csv beside it, the depth-integrated flux flux_x_m2_s[g, k], flux_y_m2_s[g, k]
    (east, north; m^2/s), else None."""
    names: list
    time_s: np.ndarray
    elevation_m: np.ndarray
    flux_x_m2_s: Optional[np.ndarray] = None
    flux_y_m2_s: Optional[np.ndarray] = None

    def __getitem__(self, name: str) -> np.ndarray:
        if name not in self.names:
            raise KeyError(f"no gauge {name!r}; the gauges are {', '.join(self.names)}")
        return self.elevation_m[self.names.index(name)]

    def statistics(self, from_time_s: float = 0.0, segment_samples: int = 0) -> dict:
        """{gauge name: spectrum} of each record from from_time_s on (leave out the spin-up): a
        DirectionalRecordSpectrum where the fluxes were read (a bake's gauges), else a RecordSpectrum."""
        keep = self.time_s >= from_time_s
        times = self.time_s[keep]
        if times.size < 2:
            raise Error(f"gauges: fewer than 2 samples from t = {from_time_s} s (from_time_s); "
                        "give an earlier time")
        steps = np.diff(times)
        if np.max(np.abs(steps - steps[0])) > 1e-6 * steps[0]:
            raise Error("gauges: the samples are not evenly spaced in time; a spectrum needs even spacing")
        interval_s = float((times[-1] - times[0]) / (times.size - 1))
        if self.flux_x_m2_s is None:
            return {name: record_spectrum(self.elevation_m[g][keep], interval_s, segment_samples)
                    for g, name in enumerate(self.names)}
        return {name: directional_record_spectrum(self.elevation_m[g][keep], self.flux_x_m2_s[g][keep],
                                                  self.flux_y_m2_s[g][keep], interval_s, segment_samples)
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
        """The bake's gauge records (DIR/gauges.csv, with DIR/gauge_fluxes.csv where it is there)."""
        fluxes = os.path.join(self.folder, "gauge_fluxes.csv")
        return Gauges(**_nearshore.read_gauges_csv(os.path.join(self.folder, "gauges.csv"),
                                                   fluxes if os.path.exists(fluxes) else ""))

    def gauge_statistics(self) -> Optional[dict]:
        """DIR/gauge_statistics.csv as the bake wrote it: {gauge name: {column: value}} (numbers as
        floats, "gauge" left out; columns in docs/formats/sequence.md); None when there is none."""
        path = os.path.join(self.folder, "gauge_statistics.csv")
        if not os.path.exists(path):
            return None
        import csv
        with open(path, newline="") as file:
            return {row.pop("gauge"): {key: float(value) for key, value in row.items()} for row in csv.DictReader(file)}

    def loops_file(self) -> Optional[dict]:
        """loops.json (written by `nearshore loops` or :func:`loops`) as validated by the library:
        the report's keys with its loop plans ("period_loop", "requested_loop",
        "best_loops_by_length"), the random walk and the transitions; None when there is none."""
        if not os.path.exists(os.path.join(self.folder, "loops.json")):
            return None
        return _nearshore.read_loops_file(self.folder)

    def verify_checksums(self) -> None:
        self._reader.verify_checksums()

    def to_xarray(self, frames=None, channels: _Seq[str] = CHANNELS):
        """The frames as an xarray Dataset (needs python3-xarray; ImportError without it): variables
        surface_elevation_m, flux_x_m2_s, flux_y_m2_s, breaking on (time, y, x) for the `channels`
        read, and the harbour grid's still_water_depth_m and land on (y, x). Coordinates: x and y
        the cell centres in site metres (row 0 south, so y increases with the index), easting_m
        and northing_m the same in the grid's CRS (x + origin_x_m, y + origin_y_m), time the bake's
        simulated time of each frame (s). Attributes: the georeference (crs_wkt, origin_x_m,
        origin_y_m, spacing_x_m, spacing_y_m, projection as JSON) and the manifest's seed,
        loop_period_s and frame_interval_s. `frames`: a slice or a list of indices (default all).
        The frames are read into memory (frames x cells x 4 bytes per channel)."""
        import json

        import xarray as xr

        indices = list(range(self.frame_count))
        if frames is not None:
            indices = indices[frames] if isinstance(frames, slice) else [int(k) for k in frames]
        g = self.geometry
        names = {"surface_elevation": "surface_elevation_m", "flux_x": "flux_x_m2_s", "flux_y": "flux_y_m2_s",
                 "breaking": "breaking"}
        units = {"surface_elevation": "m", "flux_x": "m2 s-1", "flux_y": "m2 s-1", "breaking": "1"}
        meaning = {"surface_elevation": "surface elevation above still water",
                   "flux_x": "depth-integrated flux P along +x (east)",
                   "flux_y": "depth-integrated flux Q along +y (north)", "breaking": "breaking indicator 0..1"}
        stacks = {c: np.empty((len(indices), g.rows, g.columns), np.float32) for c in channels}
        times = np.empty(len(indices))
        for n, k in enumerate(indices):
            frame = self.frame(k, channels=list(channels))
            times[n] = frame.time_s
            for c in channels:
                stacks[c][n] = getattr(frame, names[c])
        grid = self.harbour_grid()
        variables = {names[c]: (("time", "y", "x"), stacks[c], {"units": units[c], "long_name": meaning[c]})
                     for c in channels}
        variables["still_water_depth_m"] = (("y", "x"), np.asarray(grid.still_water_depth_m),
                                            {"units": "m", "long_name": "still-water depth, positive down"})
        variables["land"] = (("y", "x"), np.asarray(grid.land), {"long_name": "0 water, 1 land, 2 outside the chart"})
        coords = {"time": ("time", times, {"units": "s", "long_name": "simulated time of the bake"}),
                  "x": ("x", g.x_m, {"units": "m", "long_name": "x east of the grid's south-west corner"}),
                  "y": ("y", g.y_m, {"units": "m", "long_name": "y north of the grid's south-west corner"}),
                  "easting_m": ("x", g.x_m + g.origin_x_m, {"units": "m", "long_name": "x in the grid's CRS"}),
                  "northing_m": ("y", g.y_m + g.origin_y_m, {"units": "m", "long_name": "y in the grid's CRS"})}
        attrs = {"crs_wkt": g.crs_wkt, "origin_x_m": g.origin_x_m, "origin_y_m": g.origin_y_m,
                 "spacing_x_m": g.spacing_x_m, "spacing_y_m": g.spacing_y_m, "projection": json.dumps(g.projection),
                 "seed": str(self.manifest.get("seed")), "loop_period_s": self.manifest.get("loop_period_s", 0.0),
                 "frame_interval_s": self.frame_interval_s, "source": os.path.abspath(self.folder)}
        return xr.Dataset(variables, coords=coords, attrs=attrs)


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
        warnings.warn(_nearshore.with_keywords(warning), stacklevel=2)
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


def _box(value, name: str):
    """A bounding box as four finite numbers, the first corner south-west of the second (as the
    CLI's --bbox and --bbox-m are checked)."""
    if value is None:
        return None
    box = [float(v) for v in value]
    if len(box) != 4 or not all(np.isfinite(box)) or not (box[0] < box[2] and box[1] < box[3]):
        raise Error(f"{name}: {value!r} is not (x0, y0, x1, y1) with x0 < x1 and y0 < y1; "
                    "give four finite numbers, the south-west corner first")
    return box


def bathy(inputs, output_folder, spacing_m: float, bbox=None, bbox_m=None, sign: str = "auto",
          projection: str = "utm", xyz_crs: str = "", structures: Optional[dict] = None,
          water_level_m: float = 0.0, min_depth_m: float = 0.5, max_slope: float = 0.0,
          land_elevation_m: float = 2.0, coastline_band_m: float = 200.0, fill_uncovered: bool = False,
          leave_one_out: bool = False, marks: Optional[dict] = None, progress: bool = False,
          surroundings_margin_m: Optional[float] = None) -> dict:
    """`nearshore bathy INPUTS --spacing S -o DIR` with its options (docs/commands/bathy.md):
    `bbox` (lon0, lat0, lon1, lat1) is --bbox, `bbox_m` (x0, y0, x1, y1) --bbox-m, `sign`,
    `projection`, `xyz_crs` --xyz-crs, `structures` {name: (crest_width_m, porosity)} the repeated
    --structure NAME=WIDTH_M:POROSITY, `water_level_m` --water-level, `min_depth_m` --min-depth,
    `max_slope` --max-slope, `land_elevation_m` --land-elevation, `coastline_band_m`
    --coastline-band, `fill_uncovered` --fill-uncovered, `leave_one_out` --leave-one-out,
    `marks` {name: position} the repeated --mark NAME:POSITION and `surroundings_margin_m`
    --surroundings-margin (None: the grid's longer side; 0: no surroundings). Writes depth.tif, depth.exr,
    coastline.vdb, preview.png and summary.json into output_folder and returns the summary
    `--json` prints; its warnings also go through :mod:`warnings`."""
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    styles = {}
    for name, (width_m, porosity) in (structures or {}).items():
        if not (np.isfinite(width_m) and width_m > 0):
            raise Error(f"structures[{name!r}]: the crest width {width_m} m is not a finite number > 0; give metres")
        if not 0 <= porosity <= 1:
            raise Error(f"structures[{name!r}]: the porosity {porosity} is outside [0, 1]; "
                        "give 0 (a vertical wall) to 1 (transparent), 0.3-0.5 for a rubble mound")
        styles[str(name)] = (float(width_m), float(porosity))
    summary = _nearshore.bathy([os.fspath(p) for p in inputs], os.fspath(output_folder), float(spacing_m),
                               _box(bbox, "bbox"), _box(bbox_m, "bbox_m"), sign, projection, xyz_crs, styles,
                               float(water_level_m), float(min_depth_m), float(max_slope), float(land_elevation_m),
                               float(coastline_band_m), bool(fill_uncovered), bool(leave_one_out),
                               [(str(k), str(v)) for k, v in (marks or {}).items()], bool(progress),
                               -1.0 if surroundings_margin_m is None else float(surroundings_margin_m))
    for warning in summary.get("warnings", []):
        warnings.warn(_nearshore.with_keywords(warning), stacklevel=2)
    return summary


def library(library_file, output_folder, overwrite: bool = False, threads: int = 0, progress: bool = False) -> dict:
    """`nearshore library LIBRARY.toml -o DIR [--overwrite] [--threads N]` (docs/library.md): one
    looping sequence per state of the sweep and the index library.json, serially (an MPI run is
    the CLI's, under mpirun or srun). Returns the summary `--json` prints. A state that failed
    raises :class:`Error` naming it (the others are baked and kept), as the CLI exits 2.
    `progress`: a line on stderr per state."""
    return _nearshore.library(os.fspath(library_file), os.fspath(output_folder), bool(overwrite), int(threads),
                              bool(progress))


def operability(library_folder, occurrence, berths, threshold_hs_m: float, output_folder=None, hold: str = "") -> dict:
    """`nearshore library operability LIB --occurrence F --berths F --threshold-hs H [-o DIR]
    [--hold C]` (docs/port-study.md): each berth's downtime over an occurrence table. Returns what
    `--json` prints, with "files" (operability.csv, operability_conditions.csv, operability.png)
    when output_folder is given."""
    return _nearshore.operability(os.fspath(library_folder), os.fspath(occurrence), os.fspath(berths),
                                  float(threshold_hs_m), os.fspath(output_folder) if output_folder else "", hold)


EXPORT_FORMATS = ("netcdf", "geotiff", "exr-displacement", "vdb", "agitation")


def export(sequence_folder, to: str, output_folder, frames=None, incident_hs_m: float = 0.0, berths=None,
           progress: bool = False) -> dict:
    """`nearshore export SEQ --to FORMAT -o DIR [--frames A:B] [--incident-hs H] [--berths F]`
    (docs/commands/export.md): `to` one of EXPORT_FORMATS; `frames` a slice, a (first, end) pair
    (end None or -1: to the last frame) or one frame index; `incident_hs_m` and `berths` for
    "agitation" only. Returns the summary `--json` prints (files and sizes)."""
    if frames is None:
        first, end = 0, -1
    elif isinstance(frames, slice):
        if frames.step not in (None, 1):
            raise Error(f"frames: {frames!r} has a step; give consecutive frames (first:end)")
        first, end = frames.start or 0, -1 if frames.stop is None else frames.stop
    elif isinstance(frames, (int, np.integer)):
        first, end = int(frames), int(frames) + 1
    else:
        first, end = frames
        end = -1 if end is None else end
    if int(first) < 0 or (int(end) < -1):
        raise Error(f"frames: {frames!r} holds a negative frame; give frames counted from 0 (end -1: the last)")
    return _nearshore.export(os.fspath(sequence_folder), to, os.fspath(output_folder), (int(first), int(end)),
                             float(incident_hs_m), os.fspath(berths) if berths else "", bool(progress))
