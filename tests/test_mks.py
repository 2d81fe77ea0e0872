"""The Modified Kepler Solution against independent physics: the closed-form Kepler conic at
beta = 0, its own initial conditions, the differential equation it solves, and convergence."""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from harp_analysis.engines import kepler, mks
from harp_analysis.foundation import earth
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models import trajectory
from harp_analysis.models.launch import HP_CHAPTER_2, LP_CHAPTER_2, Launch, baseline_chapter_4
from harp_analysis.models.projectiles import BASELINE, HP

ELEVATIONS_DEG = (30.0, 45.0, 65.0, 85.0)
ELEVATIONS = np.radians(ELEVATIONS_DEG)
#: Chapter 2 A's HP at 50 deg and 2022 m/s without its wind (the MKS has none).
HP_50 = HP_CHAPTER_2.but(cross_wind_m_s=0.0)
ESCAPE_SPEED_M_S = math.sqrt(2 * earth.GM_M3_S2 / earth.RADIUS_M)


def _baseline(*elevations_deg, speed_m_s=2157.0):
    """Chapter 4 B's baseline cone at each elevation (a list of launches)."""
    return [Launch(BASELINE, speed_m_s, elevation) for elevation in elevations_deg]


def test_beta_zero_is_the_kepler_conic():
    solution = mks.ModifiedKeplerSolution(2157.0, ELEVATIONS, 0.0, 500.0, warn=False)
    conic = kepler.ballistic_conic(2157.0, ELEVATIONS)
    assert solution.apogee_altitude() == pytest.approx(conic.apogee_altitude_m, rel=1e-12)
    assert solution.impact_angle == pytest.approx(conic.range_angle_rad, rel=1e-12)
    times = solution.time(solution.impact_angle[:, None], order=16)[:, -1]
    assert times == pytest.approx(conic.time_of_flight_s, rel=1e-9)


@pytest.mark.parametrize("n_terms", [1, 2, 3, 5, 8])
def test_initial_conditions_hold_for_every_series_length(n_terms):
    solution = mks.for_launch(_baseline(*ELEVATIONS_DEG), n_terms=n_terms)
    assert solution.radius(0.0)[:, 0] == pytest.approx(earth.RADIUS_M, rel=1e-12)
    assert solution.speed(0.0)[:, 0] == pytest.approx(2157.0, rel=1e-12)
    assert solution.flight_path_angle(0.0)[:, 0] == pytest.approx(ELEVATIONS, rel=1e-12)


def test_solves_the_linear_modified_kepler_equation():
    """u'' + u equals eq 3.30's right-hand side, truncated to the same number of terms."""
    solution = mks.for_launch(baseline_chapter_4(45.0), n_terms=4)
    theta = np.linspace(0.0, solution.impact_angle, 200)
    beta, tau, c3 = solution.beta[0, 0], solution.tau[0, 0], solution.c3[0, 0]
    forcing = c3 * sum(
        (-2 * beta * np.exp(-tau * theta)) ** n / math.factorial(n) for n in range(4)
    )
    residual = solution.d2u_dtheta2(theta) + solution.u(theta) - forcing
    assert np.max(np.abs(residual)) < 1e-12 * c3


def test_agrees_with_direct_numerical_integration():
    """Integrate eq 3.30 numerically from the same launch: the closed form matches."""
    solution = mks.for_launch(HP_50, warn=False, n_terms=3)
    beta, tau, c3 = solution.beta[0, 0], solution.tau[0, 0], solution.c3[0, 0]

    def rhs(theta, y):
        forcing = c3 * sum(
            (-2 * beta * np.exp(-tau * theta)) ** n / math.factorial(n) for n in range(3)
        )
        return [y[1], forcing - y[0]]

    theta = np.linspace(0, solution.impact_angle, 50)
    u0 = [1 / earth.RADIUS_M, -np.tan(np.radians(50.0)) / earth.RADIUS_M]
    numeric = solve_ivp(
        rhs, (0, theta[-1]), u0, t_eval=theta, rtol=1e-12, atol=1e-20, method="DOP853"
    )
    assert numeric.y[0] == pytest.approx(solution.u(theta), rel=1e-9)


def test_series_converges_as_terms_are_added():
    apogees = [mks.for_launch(HP_50, n_terms=n, warn=False).apogee_altitude() for n in range(1, 10)]
    steps = np.abs(np.diff(apogees))
    assert np.all(steps[2:] < steps[1:-1])  # monotone once past the first terms
    assert steps[-1] < 1e-3  # metres are settled by nine terms
    # The infinite series sums to exp(-2 beta gamma): compare with a long series.
    assert apogees[-1] == pytest.approx(
        mks.for_launch(HP_50, n_terms=20, warn=False).apogee_altitude(), abs=1e-4
    )


def test_time_quadrature_converges():
    solution = mks.for_launch(_baseline(*ELEVATIONS_DEG))
    theta = np.linspace(0.0, 1.0, 300)[None, :] * solution.impact_angle[:, None]
    coarse, fine = solution.time(theta, order=3), solution.time(theta, order=24)
    assert np.max(np.abs(coarse - fine)) < 1e-9


def test_apogee_methods_agree():
    """Eq 6.4 drops the driving terms, which have died out by apogee: same answer."""
    solution = mks.for_launch(_baseline(*ELEVATIONS_DEG))
    assert solution.apogee_altitude("eq_6_4") == pytest.approx(solution.apogee_altitude(), abs=1e-3)
    assert np.abs(solution.du_dtheta(solution.apogee_angle[:, None])).max() < 1e-18


def test_speed_and_angular_momentum():
    solution = mks.for_launch(baseline_chapter_4(45.0))
    theta = np.linspace(0, solution.impact_angle, 100)
    h = solution.angular_momentum(theta)
    assert h[0] == pytest.approx(2157.0 * earth.RADIUS_M * np.cos(np.radians(45)))
    assert h[-1] == pytest.approx(solution.h_inf[0, 0], rel=1e-6)  # eq 3.23's asymptote
    assert np.all(np.diff(h) <= 0) and h[-1] < h[0]
    # Above the atmosphere the speed obeys the vis-viva law of the conic with h_inf.
    r, v = solution.radius(theta[50:]), solution.speed(theta[50:])
    energy = 0.5 * v**2 - earth.GM_M3_S2 / r
    assert np.ptp(energy) / abs(energy.mean()) < 1e-9


def test_vectorised_matches_single():
    many = mks.for_launch(_baseline(30.0, 65.0))
    for i, elevation in enumerate((30.0, 65.0)):
        one = mks.for_launch(baseline_chapter_4(elevation))
        assert many.apogee_altitude()[i] == pytest.approx(one.apogee_altitude())
        assert many.impact_angle[i] == pytest.approx(one.impact_angle)


def test_validity_warnings():
    with pytest.warns(ModelValidityWarning, match="beta"):
        mks.for_launch(HP_50)
    with pytest.warns(ModelValidityWarning) as caught:  # slow and flat: both limits
        mks.for_launch(Launch(BASELINE, 800.0, 10.0))
    assert {"beta", "sensible atmosphere"} <= {
        word for w in caught for word in ("beta", "sensible atmosphere") if word in str(w.message)
    }
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mks.for_launch(baseline_chapter_4(45.0))


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"speed_m_s": -1.0}, "speed_m_s"),
        ({"elevation_rad": 2.0}, "elevation_rad"),
        ({"beta": np.nan}, "beta"),
        ({"tau": -1.0}, "tau"),
        ({"n_terms": 0}, "n_terms"),
        ({"n_terms": 2.5}, "n_terms"),  # refused, not truncated to 2
    ],
)
def test_bad_input_is_named(kwargs, name):
    arguments = dict(speed_m_s=2000.0, elevation_rad=0.8, beta=0.1, tau=500.0) | kwargs
    n_terms = arguments.pop("n_terms", 3)
    with pytest.raises(ValueError, match=name):
        mks.ModifiedKeplerSolution(**arguments, n_terms=n_terms)
    with pytest.raises(ValueError, match="elevation_deg"):
        mks.for_launch(baseline_chapter_4(90.0))


def test_sample_matches_the_individual_functions():
    solution = mks.for_launch(baseline_chapter_4(65.0))
    theta = np.linspace(0, solution.impact_angle, 50)
    table = solution.sample(theta)
    assert table["altitude_m"] == pytest.approx(solution.altitude(theta))
    assert table["speed_m_s"] == pytest.approx(solution.speed(theta))
    assert table["time_s"] == pytest.approx(solution.time(theta))
    assert table["flight_path_angle_rad"] == pytest.approx(solution.flight_path_angle(theta))


@pytest.mark.parametrize("launch", ["HP", HP, 45.0, [baseline_chapter_4(45.0), "HP"]])
def test_for_launch_takes_launches_only(launch):
    with pytest.raises(TypeError, match="Launch"):
        mks.for_launch(launch)


def test_for_launch_refuses_no_launches():
    with pytest.raises(ValueError, match="at least one Launch"):
        mks.for_launch([])


def test_for_launch_refuses_rotation_and_warns_for_wind():
    with pytest.raises(ValueError, match="rotation_rate_rad_s"):
        mks.for_launch(baseline_chapter_4(45.0, rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S))
    with pytest.warns(ModelValidityWarning, match="cross_wind_m_s"):
        mks.for_launch(baseline_chapter_4(45.0, cross_wind_m_s=5.0))
    with pytest.raises(ValueError, match="n_terms"):
        mks.for_launch(baseline_chapter_4(45.0), n_terms=2.5)


def test_for_launch_takes_rho0_and_cd0_of_the_launch():
    """beta of eq 3.22 from the launch's own Cd0 (at its Mach) and eq 3.11's air at the gun
    (rho0 = 1.225 kg/m^3 at sea level, 1.225 exp(-k a) above); a site above sea level lowers
    rho0 and raises r0 (the launch conditions hold at r0 = R + altitude)."""
    for launch in (baseline_chapter_4(45.0), baseline_chapter_4(45.0, site_altitude_m=2000.0)):
        solution = mks.for_launch(launch)
        radius = earth.RADIUS_M + launch.site_altitude_m
        beta = mks.decay_factor_beta(
            launch.launch_drag_coefficient,
            1.225 * np.exp(-1.17e-4 * launch.site_altitude_m),
            BASELINE.reference_area_m2,
            BASELINE.mass_kg,
            launch.elevation_rad,
        )
        assert solution.beta[0, 0] == pytest.approx(beta, rel=1e-12)
        assert solution.radius(0.0) == pytest.approx(radius, rel=1e-12)
        assert solution.altitude(0.0) == pytest.approx(0.0, abs=1e-6)
    high = mks.for_launch(baseline_chapter_4(45.0, site_altitude_m=2000.0))
    assert high.beta[0, 0] < mks.for_launch(baseline_chapter_4(45.0)).beta[0, 0]


@pytest.mark.parametrize("factor", [0.99, 1.01])
def test_escape_follows_the_vacuum_escape_speed(factor):
    """At beta = 0 the MKS is Kepler's conic: it escapes exactly above sqrt(2 GM / R)."""
    speed = factor * ESCAPE_SPEED_M_S
    solution = mks.ModifiedKeplerSolution(speed, ELEVATIONS, 0.0, 500.0, warn=False)
    escapes = factor > 1
    assert np.all(solution.escapes == escapes)
    assert np.all(np.isnan(solution.apogee_altitude()) == escapes)
    assert np.all(np.isnan(solution.impact_angle) == escapes)
    energy = 0.5 * speed**2 - earth.GM_M3_S2 / earth.RADIUS_M
    semi_major = -earth.GM_M3_S2 / (2 * energy)  # negative for a hyperbola
    eccentricity = np.sqrt(
        1 - (speed * earth.RADIUS_M * np.cos(ELEVATIONS)) ** 2 / (earth.GM_M3_S2 * semi_major)
    )
    assert solution.asymptotic_eccentricity == pytest.approx(eccentricity, rel=1e-9)
    if not escapes:  # apogees beyond a quarter of the way round (c2 > 0) are found too
        assert np.any(solution.c2 > 0)
        conic = kepler.ballistic_conic(speed, ELEVATIONS)
        assert solution.apogee_altitude() == pytest.approx(conic.apogee_altitude_m, rel=1e-9)
        assert solution.impact_angle == pytest.approx(conic.range_angle_rad, rel=1e-9)


def test_hyperbolic_launches_warn_with_a_reason():
    # 12 km/s leaves the ground above escape speed, but the MKS's drag decay (h_inf) binds it:
    # an apogee millions of km out, beyond the Earth's sphere of influence.
    fast = Launch(BASELINE, 12000.0, 45.0)
    assert fast.speed_m_s > ESCAPE_SPEED_M_S
    with pytest.warns(ModelValidityWarning, match="sphere of influence"):
        bound = mks.for_launch(fast)
    assert not bound.escapes[0]
    assert bound.apogee_altitude() > mks.EARTH_SPHERE_OF_INFLUENCE_M
    # Faster still, the asymptotic angular momentum gives an escape orbit: no apogee at all.
    with pytest.warns(ModelValidityWarning, match="escape orbit") as caught:
        escaping = mks.for_launch(fast.but(speed_m_s=15000.0))
    assert "no apogee" in str(caught[0].message)
    assert escaping.escapes[0] and escaping.asymptotic_eccentricity[0] > 1
    assert np.isnan(escaping.apogee_altitude()) and np.isnan(escaping.impact_angle)
    with pytest.raises(ValueError, match="escapes"):
        mks.simulate_mks(fast.but(speed_m_s=15000.0), warn=False)


def test_grazing_elevation_fails_at_the_call_naming_the_elevation():
    """At 0.001 deg beta (eq 3.22) is ~4000: h_inf = h0 exp(-beta) underflows. The call says
    so, naming the elevation, instead of a NaN surfacing deep inside (no RuntimeWarning)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        for warn in (True, False):
            with pytest.raises(ValueError, match="elevation"):
                mks.for_launch(baseline_chapter_4(0.001), warn=warn)
            with pytest.raises(ValueError, match="elevation"):
                mks.simulate_mks(baseline_chapter_4(0.001), warn=warn)


def test_a_vertical_launch_fails_at_the_call_naming_its_cause():
    """At 89.9999 deg h0 = V r0 cos(elevation) (eq 6.13) all but vanishes and the constants
    cancel: the call names that cause and asks for a lower elevation, not a higher one."""
    with pytest.raises(ValueError, match="all but vanishes.*lower the elevation"):
        mks.for_launch(baseline_chapter_4(89.9999), warn=False)


@pytest.mark.parametrize("speed_m_s", [300.0, 1000.0])
def test_a_launch_whose_mks_descends_from_the_muzzle_is_named(speed_m_s):
    """LP at 5 deg and 300 or 1000 m/s: beta ~ 6 puts the first zero of du/dtheta behind the
    gun; the table's call said only "theta_rad must be sorted and non-negative" (issue 25)."""
    launch = LP_CHAPTER_2.but(speed_m_s=speed_m_s, elevation_deg=5.0)
    for call in (mks.for_launch, mks.simulate_mks):
        with pytest.raises(ValueError, match=r"no ascent at elevation_rad = 0.0872665 \(5 deg\)"):
            call(launch, warn=False)


@pytest.fixture(scope="module")
def barbados_shot():
    """The baseline cone at 65 deg, fired at bearing 109 deg from 13 N, 59.5 W."""
    launch = baseline_chapter_4(65.0, bearing_deg=109.0, latitude_deg=13.0, longitude_deg=-59.5)
    return launch, mks.simulate_mks(launch)


def test_simulate_mks_is_the_shared_table(barbados_shot):
    launch, table = barbados_shot
    assert set(trajectory.BASE_COLUMNS) <= set(table.columns)
    assert set(trajectory.METADATA_KEYS) <= set(table.attrs)
    assert table.attrs["engine"] == "MKS" and table.attrs["launch"] is launch
    assert table.attrs["impact"] and table.attrs["stop_reason"] == "impact"
    assert np.all(np.isfinite(table[list(trajectory.BASE_COLUMNS)].to_numpy()))
    assert np.all(np.diff(table.time_s) > 0)


def test_simulate_mks_apogee_and_impact_are_the_solution(barbados_shot):
    launch, table = barbados_shot
    solution = mks.for_launch(launch)
    assert table.attrs["apogee_altitude_m"] == pytest.approx(solution.apogee_altitude(), rel=1e-12)
    assert table.altitude_m.max() == pytest.approx(solution.apogee_altitude(), rel=1e-12)
    assert table.attrs["apogee_ground_range_m"] == pytest.approx(
        earth.RADIUS_M * solution.apogee_angle, rel=1e-12
    )
    assert table.attrs["range_m"] == pytest.approx(earth.RADIUS_M * solution.impact_angle)
    assert table.altitude_m.iloc[-1] == pytest.approx(0.0, abs=1e-6)
    grid = np.linspace(0.0, solution.impact_angle, 4001)
    assert table.attrs["time_of_flight_s"] == pytest.approx(solution.time(grid)[-1], rel=1e-9)


def test_simulate_mks_starts_at_the_launch_point_in_the_launch_plane(barbados_shot):
    launch, table = barbados_shot
    lat, lon, bearing = np.radians([13.0, -59.5, 109.0])
    up = np.array([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)])
    east = np.array([-np.sin(lon), np.cos(lon), 0.0])
    north = np.cross(up, east)
    downrange = np.sin(bearing) * east + np.cos(bearing) * north
    first = table.iloc[0]
    assert first[["x_m", "y_m", "z_m"]].to_numpy(float) == pytest.approx(
        earth.RADIUS_M * up, abs=1e-6
    )
    assert first.time_s == 0.0
    assert first.altitude_m == pytest.approx(0.0, abs=1e-6)
    assert first.ground_range_m == 0.0 and first.cross_range_m == 0.0
    assert first.speed_m_s == pytest.approx(2157.0, rel=1e-12)
    assert first.flight_path_angle_rad == pytest.approx(np.radians(65.0), rel=1e-12)
    assert first.specific_angular_momentum_m2_s == pytest.approx(
        2157.0 * earth.RADIUS_M * np.cos(np.radians(65.0)), rel=1e-12
    )
    positions = table[["x_m", "y_m", "z_m"]].to_numpy()
    radius = np.linalg.norm(positions, axis=1)
    assert positions @ np.cross(downrange, up) == pytest.approx(0.0, abs=1e-6 * radius.max())
    angle = np.arctan2(positions @ downrange, positions @ up)
    assert earth.RADIUS_M * angle == pytest.approx(
        table.ground_range_m.to_numpy(), rel=1e-9, abs=1e-6
    )
    assert radius - earth.RADIUS_M == pytest.approx(table.altitude_m.to_numpy(), abs=1e-6)


def test_solution_is_the_printed_form():
    """u, u' and u'' (evaluated about eq 6.4's angle) are c1 sin + c2 cos + sum A_n e^{-n tau
    theta} and its derivatives, written out here from the constants."""
    solution = mks.for_launch(_baseline(20.0, *ELEVATIONS_DEG), n_terms=4, warn=False)
    theta = np.linspace(0.0, 1.0, 40)[None, :] * solution.impact_angle[:, None]
    c1, c2, amplitudes, rates = solution.c1, solution.c2, solution.amplitudes, solution.rates
    decay = amplitudes[:, :, None] * np.exp(-rates[:, :, None] * theta[:, None, :])
    sin, cos = np.sin(theta), np.cos(theta)
    printed = (
        c1 * sin + c2 * cos + decay.sum(axis=1),
        c1 * cos - c2 * sin - (rates[:, :, None] * decay).sum(axis=1),
        -c1 * sin - c2 * cos + (rates[:, :, None] ** 2 * decay).sum(axis=1),
    )
    computed = (solution.u(theta), solution.du_dtheta(theta), solution.d2u_dtheta2(theta))
    for ours, theirs in zip(computed, printed):
        assert np.max(np.abs(ours - theirs)) < 1e-14 * np.max(np.abs(c2))


def test_small_angle_sine_and_cosine_are_libms_to_an_ulp():
    angles = np.concatenate([np.linspace(-1 / 32, 1 / 32, 2001), np.geomspace(1e-12, 0.03, 200)])
    for angle in angles:
        sin, cos = mks._sin_cos(angle)
        assert abs(sin - math.sin(angle)) <= np.spacing(abs(math.sin(angle)))
        assert abs(cos - math.cos(angle)) <= np.spacing(math.cos(angle))


def test_one_launch_of_numbers_equals_one_of_arrays():
    """Numbers take one compiled call for the constants, apogee and impact; arrays compute the
    apogee and impact when asked: the same kernels, the same numbers."""
    numbers = (2157.0, math.radians(65.0), 0.09, 1600.0)
    one = mks.ModifiedKeplerSolution(*numbers)
    arrays = mks.ModifiedKeplerSolution(*(np.array([x]) for x in numbers))
    assert one.single and not arrays.single
    assert one.apogee_altitude() == arrays.apogee_altitude()[0]
    assert one.apogee_altitude("eq_6_4") == arrays.apogee_altitude("eq_6_4")[0]
    assert one.impact_angle == arrays.impact_angle[0]
    assert one.apogee_angle == arrays.apogee_angle[0]


def test_apogee_and_impact_are_where_they_claim():
    """du/dtheta vanishes at the apogee and u is back at 1/r0 at the impact, to the rounding
    of the largest term, c3 (Newton's iterations stop where rounding dominates their steps)."""
    solution = mks.for_launch(_baseline(20.0, *ELEVATIONS_DEG, 89.0), warn=False)
    apogee, impact = solution.apogee_angle[:, None], solution.impact_angle[:, None]
    assert np.all(np.abs(solution.du_dtheta(apogee)) < 1e-14 * solution.c3)
    assert np.all(np.abs(solution.u(impact) - 1 / solution.radius_m) < 1e-14 * solution.c3)
    assert solution.altitude(apogee)[:, 0] == pytest.approx(solution.apogee_altitude(), rel=1e-12)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"speed_m_s": np.array([2000.0, -1.0])}, "speed_m_s"),
        ({"elevation_rad": np.array([0.8, 2.0])}, "elevation_rad"),
        ({"beta": np.array([0.1, np.nan])}, "beta"),
        ({"tau": np.array([500.0, -1.0])}, "tau"),
        ({"radius_m": np.array([6.4e6, np.inf])}, "radius_m"),
        ({"speed_m_s": np.array([2000.0, np.inf])}, "speed_m_s"),
        ({"drive_scale": np.array([1.0, np.nan])}, "drive_scale"),
        # plain numbers, on a domain's open end: one launch takes its own kernel
        ({"speed_m_s": 0.0}, "speed_m_s"),
        ({"elevation_rad": math.pi / 2}, "elevation_rad"),
        ({"decay_scale": np.inf}, "decay_scale"),
    ],
)
def test_a_launch_outside_a_domain_is_named(kwargs, name):
    """Arrays and numbers pass the door unchecked and the constants' kernel holds each launch
    to its argument's domain: whichever it refuses, the error names the argument."""
    arguments = dict(speed_m_s=2000.0, elevation_rad=0.8, beta=0.1, tau=500.0) | kwargs
    with pytest.raises(ValueError, match=name):
        mks.ModifiedKeplerSolution(**arguments)


def test_arguments_of_different_lengths_are_refused():
    with pytest.raises(ValueError, match="one length"):
        mks.ModifiedKeplerSolution(2000.0, np.array([0.5, 0.8]), np.array([0.1, 0.1, 0.1]), 500.0)


WARM_UP_THEN_USE = """
import json, numpy as np, numba
from harp_analysis.engines import mks
from harp_analysis.models.launch import baseline_chapter_4
kernels = [k for k in vars(mks).values() if isinstance(k, numba.core.registry.CPUDispatcher)]
count = lambda: sum(len(k.signatures) for k in kernels)
mks.warm_up()
warmed = count()
solution = mks.for_launch([baseline_chapter_4(45.0), baseline_chapter_4(65.0)])
solution.time(solution.impact_angle[:, None])
one = mks.ModifiedKeplerSolution(2157.0, 0.8, 0.1, 500.0)
one.sample(np.linspace(0.0, one.impact_angle, 5))
print(json.dumps([warmed, count()]))
"""


def test_warm_up_compiles_what_a_first_use_needs():
    """In a fresh interpreter, after warm_up a scalar and a batched solution, sampled and timed,
    compile no further kernel signature: the compiling happened at warm-up, not at first use."""
    import json
    import os
    import subprocess
    import sys

    if os.environ.get("NUMBA_DISABLE_JIT") == "1":
        pytest.skip("NUMBA_DISABLE_JIT=1: there are no kernels to compile")
    run = subprocess.run(
        [sys.executable, "-c", WARM_UP_THEN_USE],
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    assert run.returncode == 0, run.stderr
    warmed, after_use = json.loads(run.stdout)
    assert warmed > 0
    assert after_use == warmed


def test_the_constants_are_read_only_views():
    """Writing to a constant would not change the solution (its table feeds the kernels)."""
    solution = mks.for_launch([baseline_chapter_4(45.0), baseline_chapter_4(60.0)])
    with pytest.raises(ValueError, match="read-only"):
        solution.c1[0, 0] = 0.0
    first = solution.apogee_angle.copy()
    solution.apogee_angle[0] = 0.0  # a caller's copy: the solution keeps its own
    assert np.array_equal(solution.apogee_angle, first)
    with pytest.raises(ValueError, match="read-only"):
        solution.impact_angle[0] = 0.0
