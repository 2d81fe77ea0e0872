"""Chapter 7 B's error budget, checked against physics and statistics rather than its output:

- no uncertainty, no spread; a vacuum flight has no MKS model error (both are the conic);
- the gun's own displacement for a wrong latitude is R dphi; a late shot is v dt behind;
- each input's effect is linear in its size (the one-at-a-time table may be rescaled);
- plain Monte Carlo converges as N^-1/2 (the chi-square law of a sample standard deviation),
  the scrambled Sobol' sample faster;
- the moments folded chunk by chunk equal those of the whole sample.
"""

import math
from dataclasses import replace

import numpy as np
import pandas as pd
import pytest

from harp_analysis.analyses import error_budget
from harp_analysis.analyses.error_budget import CHAPTER_7B, Moments, Uncertainty
from harp_analysis.foundation import earth

LAUNCHES = error_budget.representative_launches()
BASELINE_45 = LAUNCHES["baseline, 45 deg"]
BY_NAME = {u.name: u for u in CHAPTER_7B}


def test_no_uncertainty_no_spread():
    still = tuple(replace(u, sd=0.0) for u in CHAPTER_7B)
    spread = error_budget.dispersion(BASELINE_45, still, samples=16, chunk=8, progress=False)
    assert (spread == 0.0).all()


def test_vacuum_flight_has_no_model_error():
    """In vacuum the ECI MKS and the rotating 3DOF both fly the inertial Kepler conic: what is
    left is the frames' bookkeeping (turning Earth, longitude, time), which must add nothing."""
    vacuum = LAUNCHES["Martlet, Barbados"].but(atmosphere="vacuum", longitude_deg=-59.6)
    error = error_budget.model_error(vacuum)
    assert error.max() < 1.0  # m, over a flight some 200 km high


def test_a_wrong_latitude_moves_the_gun_by_r_dphi():
    latitude = BY_NAME["latitude"]
    table = error_budget.one_at_a_time(BASELINE_45, (latitude,))
    gun_shift = earth.RADIUS_M * math.radians(latitude.sd)
    # the flight from a gun 31 m further north is the same flight, turned with the Earth
    assert table.impact_m.iloc[0] == pytest.approx(gun_shift, rel=0.02)


def test_a_late_shot_is_where_the_punctual_one_was_that_much_earlier():
    """On the turning Earth the air and the wind turn with it: a shot fired dt late flies the
    same Earth-fixed path dt later. Its miss at the apogee time is the punctual flight's
    displacement over the last dt before it (flown to both times), and nothing at impact."""
    late = replace(BY_NAME["fire time"], sd=0.05)
    table = error_budget.one_at_a_time(BASELINE_45, (late,))
    _, apogee_time, _ = error_budget.nominal(BASELINE_45)
    at = error_budget.fly_3dof(BASELINE_45, max_time_s=apogee_time).end_position_m
    earlier = error_budget.fly_3dof(BASELINE_45, max_time_s=apogee_time - late.sd).end_position_m
    assert table.impact_m.iloc[0] == 0.0
    assert table.position_m.iloc[0] == pytest.approx(np.linalg.norm(at - earlier), rel=1e-4)


@pytest.mark.parametrize("name", ["elevation", "muzzle speed", "air density", "cross wind"])
def test_each_input_acts_linearly_at_its_size(name):
    one = BY_NAME[name]
    single = error_budget.one_at_a_time(BASELINE_45, (one,)).iloc[0]
    double = error_budget.one_at_a_time(BASELINE_45, (replace(one, sd=2 * one.sd),)).iloc[0]
    assert double.impact_m == pytest.approx(2 * single.impact_m, rel=0.02)


def test_monte_carlo_converges_as_one_over_root_n():
    """The bearing alone moves the impact across the line of fire linearly (previous test), so
    the cross-range spread is |slope| sd exactly, and a plain Monte Carlo sample standard
    deviation of N flights scatters about it by sd / sqrt(2 (N - 1)) (the chi-square law):
    the root-mean-square error over independent seeds falls 4 times from N = 32 to 512. The
    scrambled Sobol' sample of 512 does better than the plain one."""
    bearing = (BY_NAME["bearing"],)
    truth = abs(error_budget.one_at_a_time(BASELINE_45, bearing).impact_crossrange_m.iloc[0])

    def relative_errors(samples, method, seeds):
        return np.array(
            [
                error_budget.dispersion(
                    BASELINE_45,
                    bearing,
                    samples=samples,
                    seed=seed,
                    method=method,
                    chunk=256,
                    progress=False,
                ).sd_impact_crossrange_m
                / truth
                - 1.0
                for seed in seeds
            ]
        )

    seeds = range(12)
    small = np.sqrt(np.mean(relative_errors(32, "random", seeds) ** 2))
    large = np.sqrt(np.mean(relative_errors(512, "random", seeds) ** 2))
    assert small == pytest.approx(1 / math.sqrt(2 * 31), rel=0.5)
    assert large == pytest.approx(1 / math.sqrt(2 * 511), rel=0.5)
    slope = math.log(large / small) / math.log(512 / 32)
    assert slope == pytest.approx(-0.5, abs=0.2)
    sobol = np.sqrt(np.mean(relative_errors(512, "sobol", range(4)) ** 2))
    assert sobol < large


def test_moments_fold_chunk_by_chunk():
    rows = np.random.default_rng(1).normal(size=(1000, 3)) * [1.0, 1e3, 1e-3] + 1e6
    whole = Moments.of(rows)
    folded = Moments.of(rows[:7])
    for start in range(7, 1000, 331):
        folded = folded.add(Moments.of(rows[start : start + 331]))
    assert folded.count == 1000
    assert np.allclose(folded.mean, whole.mean, rtol=1e-14)
    assert np.allclose(folded.covariance, np.cov(rows.T), rtol=1e-9)


def test_sensitivity_indices_name_the_driver_of_each_output():
    """Bearing drives the cross range and nothing else; the day's density, a drag term, moves
    the apogee and the range and not the cross range."""
    indices = error_budget.sensitivity_indices(BASELINE_45, base_samples=64, progress=False)
    assert indices.impact_crossrange_ST.idxmax() in ("bearing", "cross wind")
    assert indices.loc["bearing", "impact_crossrange_ST"] > 0.5
    assert indices.loc["bearing", "apogee_ST"] < 0.01
    assert indices.loc["air density", "impact_crossrange_ST"] < 0.01
    assert indices.loc["air density", "apogee_ST"] > 0.2


def test_bad_uncertainties_are_named():
    with pytest.raises(TypeError, match=r"uncertainties\[0\]"):
        error_budget.dispersion(BASELINE_45, ("elevation",), progress=False)
    with pytest.raises(ValueError, match="sd"):
        error_budget.dispersion(
            BASELINE_45, (Uncertainty("x", "speed_m_s", -1.0, "-"),), progress=False
        )
    with pytest.raises(ValueError, match="method"):
        error_budget.dispersion(BASELINE_45, CHAPTER_7B, method="latin", progress=False)
    with pytest.raises(ValueError, match="uncertainties"):
        error_budget.dispersion(BASELINE_45, (), progress=False)
    with pytest.raises(ValueError, match="launch_name"):
        error_budget.required_pointing_mrad("a howitzer")


@pytest.mark.parametrize(
    "samples, error, pattern",
    [
        (10**12, ValueError, r"samples must lie in \[16, 1.04858e\+06\]; got 1e\+12"),
        (1, ValueError, r"samples must lie in \[16, "),
        (15, ValueError, r"samples must lie in \[16, "),
        (64.5, ValueError, "samples must be a whole number; got 64.5"),
        ("64", TypeError, "samples must be a whole number; got '64'"),
        (True, TypeError, "samples must be a whole number"),
    ],
)
def test_sample_counts_are_bounded_by_name(samples, error, pattern):
    """A count that would allocate until the machine stops, or give no spread at all, fails
    at the call (before any flight)."""
    with pytest.raises(error, match=pattern):
        error_budget.dispersion(BASELINE_45, samples=samples, progress=False)


def test_chunks_and_base_samples_are_bounded_by_name():
    with pytest.raises(ValueError, match=r"chunk must lie in \[1, 16384\]"):
        error_budget.dispersion(BASELINE_45, chunk=0, progress=False)
    with pytest.raises(ValueError, match=r"base_samples must lie in \[8, 65536\]"):
        error_budget.sensitivity_indices(BASELINE_45, base_samples=2**30, progress=False)
    with pytest.raises(TypeError, match="launch must be a Launch; got str"):
        error_budget.dispersion("HP", progress=False)
    with pytest.raises(TypeError, match="launches must map names to Launch; got list"):
        error_budget.budget_table([BASELINE_45], progress=False)


def test_uncertainties_may_be_a_list():
    """A list is as good as a tuple (it once failed as "unhashable type: 'list'")."""
    elevation = [BY_NAME["elevation"]]
    table = error_budget.one_at_a_time(BASELINE_45, elevation)
    assert table.equals(error_budget.one_at_a_time(BASELINE_45, tuple(elevation)))


def test_editing_a_shared_result_changes_no_later_result():
    """The nominal flight is shared by every dispersion of the launch: an edit of the arrays
    a caller got once turned the next apogee spread from 639 m into 104,505 m."""
    spread = error_budget.dispersion(BASELINE_45, samples=16, chunk=16, progress=False)
    outputs, _, axes = error_budget.nominal(BASELINE_45)
    outputs[:] = 0.0
    axes[:] = 1.0
    error = error_budget.model_error(BASELINE_45)
    error[:] = 0.0
    table = error_budget.one_at_a_time(BASELINE_45)
    table.iloc[:, :] = 0.0
    again = error_budget.dispersion(BASELINE_45, samples=16, chunk=16, progress=False)
    pd.testing.assert_series_equal(again, spread)
    assert error_budget.model_error(BASELINE_45).min() > 0.0
    assert (error_budget.one_at_a_time(BASELINE_45).abs().sum() > 0.0).all()
