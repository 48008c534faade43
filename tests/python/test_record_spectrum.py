"""Sea-state parameters from elevation records through nearshore.record_spectrum and
Gauges.statistics: the Python road to ocean::record_spectrum (checked against regular, JONSWAP and
white-noise records in tests/ocean/record_spectrum_test.cpp)."""
import numpy as np
import pytest

import nearshore


def test_a_regular_wave_gives_its_height_and_period():
    # eta = a cos(2 pi t / T) on a 0.2 m set-up: Hm0 = 2 sqrt(2) a, every period T (the C++ test's
    # record and bars: leakage of 25.6 bins, log-parabola peak within 0.05 of a bin).
    dt, period_s, a = 0.25, 10.0, 0.5
    t = np.arange(4800) * dt
    s = nearshore.record_spectrum(0.2 + a * np.cos(2 * np.pi * t / period_s + 0.3), dt)
    assert (s.segment_samples, s.segment_count) == (1024, 9)
    assert s.significant_height_hm0_m == pytest.approx(2 * np.sqrt(2) * a, rel=1e-3)
    assert s.mean_period_tm01_s == pytest.approx(period_s, rel=1e-3)
    assert s.zero_crossing_period_tm02_s == pytest.approx(period_s, rel=2e-3)
    assert s.peak_period_s == pytest.approx(period_s, abs=0.05 * period_s**2 * s.frequency_resolution_hz)
    # The density (m^2/Hz) integrates to m0 over the band (first bin above 0 to Nyquist).
    m0 = s.variance_density_m2_hz[1:].sum() * s.frequency_resolution_hz
    assert 4 * np.sqrt(m0) == pytest.approx(s.significant_height_hm0_m, rel=1e-12)
    assert s.frequency_hz[-1] == pytest.approx(0.5 / dt)


def test_gauge_statistics_of_the_bake(baked, case_file):
    folder, _, _ = baked
    spin_up_s = nearshore.read_case(case_file)["spin_up_s"]
    gauges = nearshore.Sequence(folder).gauges()
    statistics = gauges.statistics(from_time_s=spin_up_s)
    assert list(statistics) == gauges.names
    after = gauges.time_s >= spin_up_s
    for g, name in enumerate(gauges.names):
        s = statistics[name]
        record = gauges.elevation_m[g][after]
        # The same as the function on the same samples, bit for bit.
        times = gauges.time_s[after]
        direct = nearshore.record_spectrum(record, (times[-1] - times[0]) / (times.size - 1))
        assert s.significant_height_hm0_m == direct.significant_height_hm0_m
        np.testing.assert_array_equal(s.variance_density_m2_hz, direct.variance_density_m2_hz)
        # Parseval: Welch's m0 is the record's variance with each half-overlapping Hann segment
        # weighting its middle (and the first and last few seconds less); on 55 s of a Beaufort 4
        # sea (about ten 5.5 s waves) the two weightings gave 0.956-1.037 at the six gauges: bar 10 %.
        assert s.significant_height_hm0_m == pytest.approx(4 * np.std(record), rel=0.10), name
        assert s.peak_period_s > 0 and s.mean_period_tm01_s > s.zero_crossing_period_tm02_s > 0


def test_bad_records_raise_the_library_error():
    with pytest.raises(nearshore.Error, match="elevation_m holds 10 samples"):
        nearshore.record_spectrum(np.zeros(10), 0.5)
    record = np.zeros(100)
    record[42] = np.nan
    with pytest.raises(nearshore.Error, match=r"elevation_m\[42\]"):
        nearshore.record_spectrum(record, 0.5)


def _flux_per_elevation_m_s(omega_rad_s, depth_m):
    """Linear theory: the depth-integrated flux under eta is (omega / k) eta along the direction of
    travel; k from the dispersion relation omega^2 = g k tanh(k d) (Newton from the deep-water k)."""
    k = omega_rad_s**2 / 9.81
    for _ in range(50):
        f = 9.81 * k * np.tanh(k * depth_m) - omega_rad_s**2
        df = 9.81 * (np.tanh(k * depth_m) + k * depth_m / np.cosh(k * depth_m) ** 2)
        k -= f / df
    return omega_rad_s / k


def test_a_regular_wave_gives_its_direction():
    # eta, P, Q of one linear wave of 8 s in 15 m travelling towards 35 degrees (counter-clockwise
    # from east), on a set-up and a steady current: a1 = cos 35, b1 = sin 35 at every bin (the C++
    # test's record, tests/ocean/record_spectrum_test.cpp).
    dt, period_s, a, depth_m, towards_deg = 0.2, 8.0, 0.4, 15.0, 35.0
    omega = 2 * np.pi / period_s
    wave = a * np.cos(omega * np.arange(3000) * dt + 1.1)
    flux = _flux_per_elevation_m_s(omega, depth_m) * wave
    theta = np.radians(towards_deg)
    s = nearshore.directional_record_spectrum(0.1 + wave, 0.8 + flux * np.cos(theta), -0.3 + flux * np.sin(theta), dt)
    assert s.peak_direction_deg == pytest.approx(towards_deg, abs=0.05)
    assert s.mean_direction_deg == pytest.approx(towards_deg, abs=0.05)
    assert s.directional_spread_deg < 0.5
    # Coming from 235 degrees on the compass (clockwise from north).
    assert nearshore.direction_from_deg(s.mean_direction_deg) == pytest.approx(235.0, abs=0.05)
    # The elevation's parameters are record_spectrum's.
    assert s.significant_height_hm0_m == nearshore.record_spectrum(0.1 + wave, dt).significant_height_hm0_m


def test_the_bake_writes_gauge_statistics_with_the_incident_direction(baked, case_file):
    folder, summary, _ = baked
    sequence = nearshore.Sequence(folder)
    table = sequence.gauge_statistics()
    assert summary["outputs"]["gauge_statistics_csv"] == str(folder / "gauge_statistics.csv")
    gauges = sequence.gauges()
    assert list(table) == gauges.names
    assert gauges.flux_x_m2_s.shape == gauges.elevation_m.shape
    spin_up_s = nearshore.read_case(case_file)["spin_up_s"]
    statistics = gauges.statistics(from_time_s=spin_up_s)
    for name, row in table.items():
        s = statistics[name]
        assert row["from_time_s"] == pytest.approx(spin_up_s)
        # The file's values (written %.6g from the bake's doubles) are the library's on the records
        # read back (%.9g): the same to rounding.
        assert row["significant_height_hm0_m"] == pytest.approx(s.significant_height_hm0_m, rel=1e-5)
        assert row["peak_period_s"] == pytest.approx(s.peak_period_s, rel=1e-5)
        assert row["mean_direction_deg"] == pytest.approx(s.mean_direction_deg, abs=1e-3)
        assert row["mean_direction_from_deg"] == pytest.approx(nearshore.direction_from_deg(s.mean_direction_deg), abs=1e-3)
    # The case's sea travels towards 0 degrees (wind_direction_deg = 0: towards the east, up the
    # beach; compass from 270) in components paired at +-theta with equal amplitudes (the maker's
    # mean direction is 0.0, spread 30 degrees). On 55 s of it (about ten waves, 2 Welch bins over
    # the maker's 0.075-0.2 Hz band) the six gauges read -1.7 to 21 degrees: the few crossing
    # components of one short realisation, not a bias of the method (the oblique test below). The
    # bar here is that of a sample: within 30 degrees (one spread) at every gauge.
    for name, row in table.items():
        assert abs(row["mean_direction_deg"]) < 30.0, (name, row)
        assert 0.0 < row["directional_spread_deg"] < 60.0, (name, row)


def test_an_oblique_wave_baked_gives_its_direction_at_the_gauges(tmp_path):
    # tests/python/oblique_regular.toml: a regular 6 s wave generated towards 20 degrees over a
    # flat 10 m bed, sponges on the other three sides. The centre gauge read 20.35 degrees (spread
    # 3.2) and the one 64 m north-east of it 22.9 (spread 1.9): what is left of the source line's
    # ends and the sponges, which in a basin half as wide turned the centre's reading to 27.7. Bars:
    # 3 degrees at the centre, 5 at the other; the spread under 6 degrees (a long-crested wave).
    import pathlib
    case = pathlib.Path(__file__).with_name("oblique_regular.toml")
    summary = nearshore.bake(case, tmp_path / "oblique")
    table = nearshore.Sequence(tmp_path / "oblique").gauge_statistics()
    assert summary["outputs"]["gauge_statistics_csv"].endswith("gauge_statistics.csv")
    assert table["centre"]["mean_direction_deg"] == pytest.approx(20.0, abs=3.0)
    assert table["north"]["mean_direction_deg"] == pytest.approx(20.0, abs=5.0)
    assert table["centre"]["peak_direction_deg"] == pytest.approx(20.0, abs=3.0)
    assert table["centre"]["mean_direction_from_deg"] == pytest.approx(250.0, abs=3.0)
    for row in table.values():
        assert row["directional_spread_deg"] < 6.0, row
        assert row["peak_period_s"] == pytest.approx(6.0, rel=0.03)
