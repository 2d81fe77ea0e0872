"""The Modified Kepler Solution against independent physics: the closed-form Kepler conic at
beta = 0, its own initial conditions, the differential equation it solves, and convergence."""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from harp_analysis import earth, kepler, mks
from harp_analysis.projectiles import BASELINE, HP
from harp_analysis.validation import ModelValidityWarning

ELEVATIONS = np.radians([30.0, 45.0, 65.0, 85.0])


def test_beta_zero_is_the_kepler_conic():
    solution = mks.ModifiedKeplerSolution(2157.0, ELEVATIONS, 0.0, 500.0, warn=False)
    conic = kepler.ballistic_conic(2157.0, ELEVATIONS)
    assert solution.apogee_altitude() == pytest.approx(conic.apogee_altitude_m, rel=1e-12)
    assert solution.impact_angle == pytest.approx(conic.range_angle_rad, rel=1e-12)
    times = solution.time(solution.impact_angle[:, None], order=16)[:, -1]
    assert times == pytest.approx(conic.time_of_flight_s, rel=1e-9)


@pytest.mark.parametrize("n_terms", [1, 2, 3, 5, 8])
def test_initial_conditions_hold_for_every_series_length(n_terms):
    solution = mks.for_projectile(BASELINE, np.degrees(ELEVATIONS), n_terms=n_terms)
    assert solution.radius(0.0)[:, 0] == pytest.approx(earth.RADIUS_M, rel=1e-12)
    assert solution.speed(0.0)[:, 0] == pytest.approx(2157.0, rel=1e-12)
    assert solution.flight_path_angle(0.0)[:, 0] == pytest.approx(ELEVATIONS, rel=1e-12)


def test_solves_the_linear_modified_kepler_equation():
    """u'' + u equals eq 3.30's right-hand side, truncated to the same number of terms."""
    solution = mks.for_projectile(BASELINE, 45.0, n_terms=4)
    theta = np.linspace(0.0, solution.impact_angle, 200)
    beta, tau, c3 = solution.beta[0, 0], solution.tau[0, 0], solution.c3[0, 0]
    forcing = c3 * sum(
        (-2 * beta * np.exp(-tau * theta)) ** n / math.factorial(n) for n in range(4)
    )
    residual = solution.d2u_dtheta2(theta) + solution.u(theta) - forcing
    assert np.max(np.abs(residual)) < 1e-12 * c3


def test_agrees_with_direct_numerical_integration():
    """Integrate eq 3.30 numerically from the same launch: the closed form matches."""
    solution = mks.for_projectile(HP, 50.0, warn=False, n_terms=3)
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
    apogees = [
        mks.for_projectile(HP, 50.0, n_terms=n, warn=False).apogee_altitude() for n in range(1, 10)
    ]
    steps = np.abs(np.diff(apogees))
    assert np.all(steps[2:] < steps[1:-1])  # monotone once past the first terms
    assert steps[-1] < 1e-3  # metres are settled by nine terms
    # The infinite series sums to exp(-2 beta gamma): compare with a long series.
    assert apogees[-1] == pytest.approx(
        mks.for_projectile(HP, 50.0, n_terms=20, warn=False).apogee_altitude(), abs=1e-4
    )


def test_time_quadrature_converges():
    solution = mks.for_projectile(BASELINE, np.degrees(ELEVATIONS))
    theta = np.linspace(0.0, 1.0, 300)[None, :] * solution.impact_angle[:, None]
    coarse, fine = solution.time(theta, order=3), solution.time(theta, order=24)
    assert np.max(np.abs(coarse - fine)) < 1e-9


def test_apogee_methods_agree():
    """Eq 6.4 drops the driving terms, which have died out by apogee: same answer."""
    solution = mks.for_projectile(BASELINE, np.degrees(ELEVATIONS))
    assert solution.apogee_altitude("eq_6_4") == pytest.approx(solution.apogee_altitude(), abs=1e-3)
    assert np.abs(solution.du_dtheta(solution.apogee_angle[:, None])).max() < 1e-18


def test_speed_and_angular_momentum():
    solution = mks.for_projectile(BASELINE, 45.0)
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
    many = mks.for_projectile(BASELINE, [30.0, 65.0])
    for i, elevation in enumerate((30.0, 65.0)):
        one = mks.for_projectile(BASELINE, elevation)
        assert many.apogee_altitude()[i] == pytest.approx(one.apogee_altitude())
        assert many.impact_angle[i] == pytest.approx(one.impact_angle)


def test_validity_warnings():
    with pytest.warns(ModelValidityWarning, match="beta"):
        mks.for_projectile(HP, 50.0)
    with pytest.warns(ModelValidityWarning) as caught:  # slow and flat: both limits
        mks.for_projectile(BASELINE, 10.0, speed_m_s=800.0)
    assert {"beta", "sensible atmosphere"} <= {
        word for w in caught for word in ("beta", "sensible atmosphere") if word in str(w.message)
    }
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mks.for_projectile(BASELINE, 45.0)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"speed_m_s": -1.0}, "speed_m_s"),
        ({"elevation_rad": 2.0}, "elevation_rad"),
        ({"beta": np.nan}, "beta"),
        ({"tau": -1.0}, "tau"),
        ({"n_terms": 0}, "n_terms"),
    ],
)
def test_bad_input_is_named(kwargs, name):
    arguments = dict(speed_m_s=2000.0, elevation_rad=0.8, beta=0.1, tau=500.0) | kwargs
    n_terms = arguments.pop("n_terms", 3)
    with pytest.raises(ValueError, match=name):
        mks.ModifiedKeplerSolution(**arguments, n_terms=n_terms)
    with pytest.raises(ValueError, match="elevation_deg"):
        mks.for_projectile(BASELINE, 90.0)


def test_sample_matches_the_individual_functions():
    solution = mks.for_projectile(BASELINE, 65.0)
    theta = np.linspace(0, solution.impact_angle, 50)
    table = solution.sample(theta)
    assert table["altitude_m"] == pytest.approx(solution.altitude(theta))
    assert table["speed_m_s"] == pytest.approx(solution.speed(theta))
    assert table["time_s"] == pytest.approx(solution.time(theta))
    assert table["flight_path_angle_rad"] == pytest.approx(solution.flight_path_angle(theta))
