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
