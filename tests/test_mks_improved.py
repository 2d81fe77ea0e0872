"""The better MKS (issue 17, part 3): exact in the drag-free limit, a continuous non-increasing
angular momentum, an asymptote and a flight closer to the 3DOF than the dissertation's MKS on
launches the fit never saw. Thresholds come from the comparison itself (improved against the
dissertation's), from the closed-form conic, or from rounding; none from earlier output."""

import importlib
import inspect
import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from harp_analysis.analyses import mks_improvement
from harp_analysis.engines import kepler, mks, mks_improved
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models.launch import HP_CHAPTER_2, LP_CHAPTER_2, baseline_chapter_4

NON_ROTATING_JUDGED = [
    launch for launch in mks_improvement.JUDGING if launch.rotation_rate_rad_s == 0.0
]


def _rms(values) -> float:
    return float(np.sqrt(np.mean(np.square(values))))


@pytest.fixture(scope="module")
def judged():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        return mks_improvement.judge()


@pytest.mark.parametrize("elevation", [30.0, 55.0, 85.0])
def test_in_a_vacuum_it_is_the_kepler_conic(elevation):
    """No air: no loss on the way up or down, and the improved MKS is eq 3.8's conic: apogee,
    range and time of flight of the closed form (kepler.ballistic_conic)."""
    launch = baseline_chapter_4(elevation, atmosphere="vacuum")
    solution = mks_improved.solve(launch)
    conic = kepler.ballistic_conic(launch.speed_m_s, launch.elevation_rad)
    assert solution.ascent.beta[0, 0] == 0.0 and solution.beta_reentry == 0.0
    # to 10 um: rounding of 1/u at r = 6.6e6 m and the apogee's Newton step (1e-12 rad)
    assert solution.apogee_altitude_m == pytest.approx(float(conic.apogee_altitude_m), abs=1e-5)
    assert solution.impact_angle == pytest.approx(float(conic.range_angle_rad), rel=1e-12)
    # the time quadrature (3-point Gauss on 4000 intervals) against Kepler's equation
    assert solution.impact_time_s == pytest.approx(float(conic.time_of_flight_s), rel=1e-9)
    assert solution.apogee_time_s == pytest.approx(float(conic.time_to_apogee_s), rel=1e-9)


def test_the_dissertation_variant_is_the_mks_of_the_text():
    """Through the same interface, the 'dissertation' variant is mks.for_launch's MKS."""
    launch = baseline_chapter_4(45.0)
    text = mks.for_launch(launch, warn=False)
    variant = mks_improved.dissertation(launch)
    assert variant.beta_reentry == 0.0
    assert variant.apogee_altitude_m == pytest.approx(float(text.apogee_altitude()), rel=1e-12)
    assert variant.impact_angle == pytest.approx(float(text.impact_angle), rel=1e-12)


@pytest.mark.parametrize(
    "launch",
    NON_ROTATING_JUDGED,
    ids=lambda launch: f"{launch.projectile.name}-{launch.elevation_deg:g}",
)
def test_angular_momentum_is_continuous_and_never_rises(launch):
    """On a non-rotating Earth, h(theta) runs from h0 at launch to h_inf e^{-beta_re} at
    impact, continuous (no step larger than its steepest slope allows on the grid) and
    non-increasing (to rounding)."""
    solution = mks_improved.solve(launch)
    theta = np.linspace(0.0, solution.impact_angle, 20001)
    h = np.ravel(solution.angular_momentum(theta))
    # at launch the re-entry branch's tail, exp(-beta_re e^{-tau_re theta_imp}), is 1 to 1e-6
    tail = math.exp(-solution.beta_reentry * math.exp(-solution.tau_reentry * theta[-1]))
    assert tail == pytest.approx(1.0, abs=1e-6)
    assert h[0] == pytest.approx(float(solution.ascent.h0[0, 0]) * tail, rel=1e-12)
    # at impact the ascent's branch is h_inf exp(beta e^{-tau theta_imp}), all but spent
    beta, tau = float(solution.ascent.beta[0, 0]), float(solution.ascent.tau[0, 0])
    spent = math.exp(beta * math.exp(-tau * theta[-1]))
    assert spent == pytest.approx(1.0, abs=1e-4)
    end = float(solution.ascent.h_inf[0, 0]) * spent * math.exp(-solution.beta_reentry)
    assert h[-1] == pytest.approx(end, rel=1e-12)
    assert np.all(np.diff(h) <= 1e-12 * h[0])
    # d ln h / dtheta is at most beta tau (ascent) or beta_re tau_re (re-entry)
    steepest = max(
        float(solution.ascent.beta[0, 0] * solution.ascent.tau[0, 0]),
        solution.beta_reentry * solution.tau_reentry,
    )
    assert np.max(np.abs(np.diff(np.log(h)))) <= steepest * (theta[1] - theta[0]) * (1 + 1e-9)


def test_the_ascent_is_its_own_fixed_point():
    """Its beta is the loss integral along its own path: integrating the rate again along the
    returned solution gives the same beta (to the fixed point's tolerance)."""
    launch = baseline_chapter_4(40.0)
    solution = mks_improved.solve(launch)
    air = mks_improved._Air(launch, solution.plane)
    loss, tau, _ = mks_improved._along_ascent(solution.ascent, air)
    assert loss == pytest.approx(float(solution.ascent.beta[0, 0]), rel=1e-8)
    assert tau == pytest.approx(float(solution.ascent.tau[0, 0]), rel=1e-8)


# Launches whose loss rate has each kind of kink: the two-segment air's jump at 10.769 km (the
# baseline fired west from the equator, where the rotating air also counts most), HP's and LP's
# Mach tables, and Appendix A's three layers.
KINKED = [
    mks_improvement.TRAINING[6],
    *(launch for launch in mks_improvement.JUDGING if launch.projectile.name in ("HP", "LP")),
    baseline_chapter_4(45.0, atmosphere="three_layer"),
]


def _name(launch) -> str:
    return f"{launch.projectile.name}-{launch.elevation_deg:g}-{launch.atmosphere}"


def _flown(launch):
    """The improved MKS of ``launch`` and its air, as its losses take them."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)  # beta > 0.25 for LP
        solution = mks_improved.solve(launch)
    return solution, mks_improved._Air(launch, solution.plane)


@pytest.fixture(scope="module")
def reference():
    """benchmarks/bench_mks_improved.py: the losses in numpy and scipy, as before compilation."""
    folder = str(Path(__file__).resolve().parents[1] / "benchmarks")
    sys.path.insert(0, folder)
    try:
        return importlib.import_module("bench_mks_improved")
    finally:
        sys.path.remove(folder)


@pytest.mark.parametrize("launch", KINKED[:3], ids=_name)
def test_the_compiled_ascent_loss_is_the_numpy_quadrature(reference, launch):
    """The compiled loss rate and trapezoids against the numpy formula and numpy's trapezoid
    on the same grid (to rounding: the grids' points agree to a few ulps)."""
    solution, air = _flown(launch)
    compiled = mks_improved._along_ascent(solution.ascent, air)
    numpy = reference.reference_ascent(launch, solution.ascent, air)
    assert compiled == pytest.approx(numpy, rel=1e-11)


@pytest.mark.parametrize("launch", KINKED, ids=_name)
def test_the_reentry_march_meets_scipys_at_a_tight_tolerance(reference, launch):
    """The compiled march (rtol 1e-10, restarted on the air's breakpoints) against scipy's
    DOP853 at rtol 1e-12 on the numpy rate, on the same grid: the same loss to 1e-9 of it, and
    the same tau_re, though scipy has to find the kinks by shrinking its steps."""
    solution, air = _flown(launch)
    theta, loss, tau = mks_improved._along_descent(solution.ascent, air)
    scipy_theta, scipy_loss, scipy_tau = reference.reference_descent(
        launch, solution.ascent, air, rtol=1e-12, atol=1e-15
    )
    np.testing.assert_allclose(theta, scipy_theta, rtol=1e-12)
    assert np.max(np.abs(loss - scipy_loss)) <= 1e-9 * scipy_loss[-1]
    assert tau == pytest.approx(scipy_tau, rel=1e-9)


@pytest.mark.parametrize(
    "launches, tolerance",
    [
        (mks_improvement.TRAINING + mks_improvement.JUDGING, 1e-9),
        # the 1976 air interpolated in its table kinks at every row, unseen by the steps
        ((baseline_chapter_4(45.0, atmosphere="us1976"),), 1e-7),
    ],
    ids=["fitted-and-judged", "us1976"],
)
def test_the_reentry_march_is_converged(launches, tolerance):
    """At its tolerances the march is within ``tolerance`` of itself at rtol 1e-13 (the loss
    on the whole grid, relative to its total): on every launch the fit and the judging see
    (_REENTRY_RTOL's comment), and on the 1976 atmosphere with its seven breakpoints."""
    for launch in launches:
        solution, air = _flown(launch)
        loss = mks_improved._along_descent(solution.ascent, air)[1]
        converged = mks_improved._along_descent(solution.ascent, air, 1e-13, 1e-16)[1]
        assert np.max(np.abs(loss - converged)) <= tolerance * converged[-1], launch


def test_asymptote_is_closer_to_the_3dof_than_the_dissertations():
    """h_inf against the 3DOF's h at apogee (above 40 km, no drag left; Fig 4.12's measure):
    closer on every non-rotating judged launch, and in RMS over the whole judging set (on the
    rotating Earth Chapter 5's V_tangent direction, kept, leaves per-launch noise)."""
    errors = mks_improvement.asymptote_errors()
    still = errors[errors.latitude_deg.eq(0.0) & errors.bearing_deg.eq(90.0)]
    still = still.iloc[: len(NON_ROTATING_JUDGED)]
    assert np.all(still.improved.abs() < still.dissertation.abs())
    assert _rms(errors.improved) < _rms(errors.dissertation)


def test_beats_the_dissertations_mks_on_the_judging_set(judged):
    """The issue's test. Max position error: lower on every judged launch. Impact-point miss:
    lower on every non-rotating judged launch and in RMS over all; on the rotating Earth the
    impact is per launch at the mercy of the cross-track push kept as an impulse at launch, so
    it is judged in aggregate (the error maps show where)."""
    pivot = judged.pivot_table(
        index=["projectile", "elevation_deg", "latitude_deg", "bearing_deg", "rotating"],
        columns="variant",
        values=["max_error_m", "impact_miss_m"],
    )
    assert len(pivot) == len(mks_improvement.JUDGING)
    max_error, miss = pivot["max_error_m"], pivot["impact_miss_m"]
    assert np.all(max_error.improved < max_error.dissertation)
    still = miss.xs(False, level="rotating")
    assert np.all(still.improved < still.dissertation)
    assert _rms(miss.improved) < _rms(miss.dissertation)
    turning = miss.xs(True, level="rotating")  # not only carried by the still-Earth launches
    assert _rms(turning.improved) < _rms(turning.dissertation)


def test_a_denser_day_flies_as_a_lighter_projectile():
    """Its loss integral is rho A / (2 m) Cd(M) along the path: 8 % more air at every height is
    8 % less mass (the engines' suite asks the same of every engine)."""
    from dataclasses import replace

    launch = baseline_chapter_4(45.0)
    lighter = launch.but(
        projectile=replace(
            launch.projectile, name="lighter", mass_kg=launch.projectile.mass_kg / 1.08
        )
    )
    denser = mks_improved.solve(launch.but(density_change_fraction=0.08))
    assert denser.apogee_altitude_m < mks_improved.solve(launch).apogee_altitude_m - 100.0
    assert denser.apogee_altitude_m == pytest.approx(
        mks_improved.solve(lighter).apogee_altitude_m, rel=1e-9
    )


def test_fit_sees_only_the_training_launches(monkeypatch):
    """Structural: fit takes the training launches and nothing else, the two sets share no
    launch, and every MKS the fit solves is a training launch's."""
    assert list(inspect.signature(mks_improvement.fit).parameters) == ["training"]
    assert not set(mks_improvement.TRAINING) & set(mks_improvement.JUDGING)
    seen = []
    solve = mks_improved.solve

    def recording(launch, *args, **kwargs):
        seen.append(launch)
        return solve(launch, *args, **kwargs)

    monkeypatch.setattr(mks_improved, "solve", recording)
    fitted = mks_improvement.fit(mks_improvement.TRAINING)
    assert seen and set(seen) <= set(mks_improvement.TRAINING)
    assert fitted == mks_improvement.calibration()


def test_error_map_has_both_variants_on_its_grid():
    grid = mks_improvement.error_map((0.0, 180.0), (45.0,), (30.0,), progress=False)
    assert len(grid) == 2
    assert list(grid.bearing_deg) == [0.0, 180.0]
    for variant in mks_improved.VARIANTS:
        for measure in ("impact_miss_m", "max_error_m"):
            assert np.all(np.isfinite(grid[f"{variant}_{measure}"]))
            assert np.all(grid[f"{variant}_{measure}"] > 0.0)


def test_warns_where_the_air_carries_much_of_the_angular_momentum():
    """Fired west at 85 deg from the equator, the surface's 465 m/s eastward overtakes the gun's
    188 m/s westward: inertially a slow eastward shot, whose h the air's omega r0^2 dwarfs."""
    launch = mks_improvement._rotating(85.0, 0.0, 270.0)
    low, high = mks_improved.AIR_MOMENTUM_SHARE_RANGE
    assert not low < mks_improved.air_momentum_share(launch) <= high
    with pytest.warns(ModelValidityWarning, match="angular momentum"):
        try:
            mks_improved.solve(launch)
        except ValueError:
            pass  # it may also find no finite re-entry decay; the warning came first
    assert mks_improved.air_momentum_share(baseline_chapter_4(45.0)) == 0.0


WESTWARD = {
    # Barbados at 30.8 deg: a trial step of the re-entry march lost all of h (issue 25)
    "Barbados": dict(
        elevation_deg=30.845228653704602,
        bearing_deg=269.9255856283873,
    ),
    # a judging launch of bench_calibrated_mks (seed 8): its march divided by zero elsewhere,
    # one CI run in ten drew such a launch
    "judged": dict(
        speed_m_s=1737.4792937999712,
        elevation_deg=34.52519019462498,
        bearing_deg=275.92821269285685,
        latitude_deg=-17.302772339443926,
        longitude_deg=108.08976626372919,
        density_change_fraction=0.03453505051614414,
    ),
}


@pytest.mark.parametrize("changes", WESTWARD.values(), ids=WESTWARD)
def test_a_westward_descent_that_loses_all_its_momentum_is_named(changes):
    """Fired west, the air turning with the Earth drags the descent's inertial h toward its
    own: the re-entry march divided by zero (ZeroDivisionError: the march compiled with
    Python's division, where uncompiled numpy gives inf); the march shortens a trial step that
    loses all of h, as scipy's does (issue 25), divides as numpy does, and the decay that
    still loses all of h is refused by name."""
    from harp_analysis.analyses.fire_control.firing import BARBADOS_HP

    launch = BARBADOS_HP.but(**changes)
    with pytest.raises(ValueError, match="loses all of h before the impact"):
        mks_improved.solve(launch)
    assert math.isfinite(mks_improved.dissertation(launch).apogee_altitude_m)


@settings(max_examples=15, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_a_launch_across_the_judged_band_is_solved_or_refused_by_name(seed):
    """Launches drawn as bench_calibrated_mks draws its judging launches (every projectile, sites
    on the turning and the still Earth, speeds and elevations across the calibrated band): the
    improved MKS solves each or refuses it with a ValueError, never another error (a westward
    descent raised ZeroDivisionError on one fresh draw in ten)."""
    from harp_analysis.analyses import mks_calibration

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        for gun in mks_calibration.judging_guns(seed):
            for launch in mks_calibration.judging_launches(gun, 4, seed):
                try:
                    mks_improved.solve(launch)
                except ValueError:
                    pass


def test_a_reentry_decay_that_lands_before_the_apogee_is_named():
    """LP at 30 deg and 2000 m/s: beta_re = 1.2 puts the solution below the launch radius at
    the ascent's apogee; brentq said only "f(a) and f(b) must have different signs"."""
    with pytest.raises(ValueError, match="no impact after its apogee"):
        mks_improved.solve(LP_CHAPTER_2.but(speed_m_s=2000.0, elevation_deg=30.0))


def test_bad_input_is_refused_by_name():
    with pytest.raises(TypeError, match="launch"):
        mks_improved.solve("baseline")
    with pytest.raises(TypeError, match="calibration"):
        mks_improved.solve(baseline_chapter_4(45.0), 1.0)
    with pytest.raises(ValueError, match="variant"):
        mks_improved.flight(baseline_chapter_4(45.0), "better")
    with pytest.raises(TypeError, match="training"):
        mks_improvement.fit([])


@given(st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=3)))
def test_calibration_checks_its_factor(value):
    try:
        calibration = mks_improved.Calibration(reentry_scale=value)
    except (TypeError, ValueError) as error:
        assert "reentry_scale" in str(error)
    else:
        assert math.isfinite(calibration.reentry_scale) and calibration.reentry_scale >= 0.0


def test_map_shares_count_the_points_as_drawn():
    """Four points: the improved MKS better at two (one inside the band), one unsolved."""
    import pandas as pd

    low, high = mks_improved.AIR_MOMENTUM_SHARE_RANGE
    frame = pd.DataFrame(
        {
            "air_momentum_share": [0.0, 0.1, high + 1.0, low - 1.0],
            "dissertation_impact_miss_m": [100.0, 100.0, 100.0, 100.0],
            "improved_impact_miss_m": [50.0, 150.0, 50.0, np.nan],
            "dissertation_max_error_m": [1.0, 1.0, 1.0, 1.0],
            "improved_max_error_m": [2.0, 2.0, 2.0, 2.0],
        }
    )
    shares = mks_improvement.map_shares(frame)
    assert shares.points == 4 and shares.inside == 2 and shares.unsolved == 1
    assert shares.better_impact_miss_m == 0.5 and shares.better_impact_miss_m_inside == 0.5
    assert shares.better_max_error_m == 0.0


def test_beyond_the_drag_it_was_judged_on_the_improved_mks_warns():
    """MAX_JUDGED_BETA is the largest beta of the fitting and judging launches (not a number
    chosen to pass a grid); beyond it the improved MKS warns, and indeed misses the 3DOF's
    apogee by far more than it does inside (HP at 1 km/s and 45 deg, beta 0.54)."""
    from harp_analysis.engines import eci, threedof

    judged = mks_improvement.TRAINING + mks_improvement.JUDGING
    betas = [
        float(eci.correction_for_launch(one).solution(warn=False).beta.flat[0]) for one in judged
    ]
    assert max(betas) <= mks_improved.MAX_JUDGED_BETA < max(betas) + 0.01
    beyond = HP_CHAPTER_2.but(speed_m_s=1000.0, elevation_deg=45.0, cross_wind_m_s=0.0)
    with pytest.warns(ModelValidityWarning, match=r"improved MKS beta = 0.53\d > 0.47"):
        solution = mks_improved.solve(beyond)
    reference = threedof.simulate_3dof(beyond).attrs["apogee_altitude_m"]
    assert abs(solution.apogee_altitude_m / reference - 1.0) > 0.1


def test_error_differences_are_not_blown_up_by_a_lucky_miss():
    """Figure X.7's measure: the text's MKS missing by 18.6 m by luck and the improved one by
    690 m is 37 times worse as a ratio, but 671.4 m as the difference the map draws; where the
    improved MKS has no solution the difference is NaN, not a number."""
    import pandas as pd

    frame = pd.DataFrame(
        {
            "dissertation_impact_miss_m": [18.6, 2000.0, 500.0],
            "improved_impact_miss_m": [690.0, 150.0, np.nan],
            "dissertation_max_error_m": [1000.0, 3000.0, 800.0],
            "improved_max_error_m": [400.0, 3000.0, np.nan],
        }
    )
    differences = mks_improvement.error_differences_m(frame)
    assert differences.impact_miss_m[0] == pytest.approx(671.4)
    assert differences.impact_miss_m[1] == pytest.approx(-1850.0)
    assert differences.max_error_m.tolist()[:2] == [-600.0, 0.0]
    assert differences.iloc[2].isna().all()
