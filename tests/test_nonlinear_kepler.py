"""The unlinearised Modified Kepler equation against independent physics: the Kepler conic at
beta = 0, planar Cartesian integrations with a transverse force and with drag along the
velocity (each prescribed to give eq 3.23's h(theta)), the thin-atmosphere limit, and the
natural frequency and frequency response of Fig 3.4."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from harp_analysis.engines import kepler, mks
from harp_analysis.engines import nonlinear_kepler as nk
from harp_analysis.foundation import earth
from harp_analysis.models.atmosphere import get_atmosphere
from harp_analysis.models.launch import HP_CHAPTER_2, baseline_chapter_4
from harp_analysis.models.projectiles import HP

ELEVATIONS_DEG = (30.0, 45.0, 65.0, 85.0)
#: Chapter 2 A's HP at 50 deg and 2022 m/s, without its wind (the MKS has none).
HP_50 = HP_CHAPTER_2.but(cross_wind_m_s=0.0)


@pytest.fixture(scope="module")
def hp50():
    return mks.for_launch(HP_50, warn=False)


@pytest.mark.parametrize("form", nk.FORMS)
@pytest.mark.parametrize("elevation_deg", ELEVATIONS_DEG)
def test_beta_zero_is_the_kepler_conic(form, elevation_deg):
    launch = mks.ModifiedKeplerSolution(2157.0, math.radians(elevation_deg), 0.0, 500.0, warn=False)
    conic = kepler.ballistic_conic(2157.0, math.radians(elevation_deg))
    numerical = nk.solve(launch, form)
    assert numerical.apogee_altitude() == pytest.approx(conic.apogee_altitude_m, rel=1e-9)
    assert numerical.impact_range_m == pytest.approx(conic.ground_range_m, rel=1e-9)


def test_eq_3_29_with_tan_phi_of_eq_3_28_is_eq_3_25(hp50):
    a, b = nk.solve(hp50, "eq_3_25"), nk.solve(hp50, "eq_3_29")
    assert b.impact_angle == pytest.approx(a.impact_angle, rel=1e-10)
    # each solution ends at its own impact event, equal to the last few ulps either way
    theta = np.linspace(0.0, min(a.impact_angle, b.impact_angle), 50)
    assert b.u(theta) == pytest.approx(a.u(theta), rel=1e-10)


@pytest.mark.parametrize("n_terms, linear_terms", [(3, 3), (None, 30)])
def test_eq_3_30_numerically_is_the_closed_form(hp50, n_terms, linear_terms):
    error = nk.linearisation_error(hp50, "eq_3_30", n_terms=n_terms, linear_terms=linear_terms)
    # the closed form's own truncation makes the difference at (3, 3): none is expected
    assert abs(error.apogee_m) < 1e-3 and abs(error.range_m) < 1e-3


def _planar_flight(launch, transverse):
    """Cartesian x'' = -GM x/r^3 + a: with a transverse force a = h'(theta) h e_theta / r^3
    (eq 3.1 as printed) or with drag along the velocity a = h'(theta) v / r^2 (eq 3.10); both
    make dh/dt = h'(theta) theta_dot, i.e. h(theta) of eq 3.23. Returns (apogee radius,
    impact angle)."""
    beta, tau, h_inf = launch.beta[0, 0], launch.tau[0, 0], launch.h_inf[0, 0]
    r0, phi0, v0 = launch.radius_m[0, 0], launch.elevation_rad[0, 0], launch.speed_m_s[0, 0]

    def rhs(t, s):
        x, y, vx, vy = s
        r = math.hypot(x, y)
        theta = math.atan2(y, x)
        gamma = math.exp(-tau * theta)
        dh_dtheta = -tau * beta * gamma * h_inf * math.exp(beta * gamma)
        if transverse:
            h = x * vy - y * vx
            ax, ay = dh_dtheta * h * -y / r**4, dh_dtheta * h * x / r**4
        else:
            ax, ay = dh_dtheta * vx / r**2, dh_dtheta * vy / r**2
        g = -earth.GM_M3_S2 / r**3
        return vx, vy, g * x + ax, g * y + ay

    def impact(t, s):
        return math.hypot(s[0], s[1]) - r0

    impact.terminal, impact.direction = True, -1.0
    start = (r0, 0.0, v0 * math.sin(phi0), v0 * math.cos(phi0))
    result = solve_ivp(
        rhs,
        (0.0, 3000.0),
        start,
        method="DOP853",
        rtol=1e-12,
        atol=1e-6,
        events=impact,
        dense_output=True,
    )
    times = np.linspace(0.0, result.t[-1], 4001)
    x, y = result.sol(times)[:2]
    end = result.y_events[0][0]
    return np.hypot(x, y).max(), math.atan2(end[1], end[0])


def test_eq_3_9_is_the_motion_under_a_transverse_force(hp50):
    apogee_radius, impact_angle = _planar_flight(hp50, transverse=True)
    numerical = nk.solve(hp50, "eq_3_25")
    assert numerical.apogee_altitude() + earth.RADIUS_M == pytest.approx(apogee_radius, rel=1e-8)
    assert numerical.impact_angle == pytest.approx(impact_angle, rel=1e-8)


def test_drag_along_the_velocity_cancels_the_u_prime_term(hp50):
    """The radial drag -D sin(phi) cancels (1/L)(dL/dtheta) u': eq 3.30 is then exact."""
    apogee_radius, impact_angle = _planar_flight(hp50, transverse=False)
    linear = nk.solve(hp50, "eq_3_30")
    assert linear.apogee_altitude() + earth.RADIUS_M == pytest.approx(apogee_radius, rel=1e-8)
    assert linear.impact_angle == pytest.approx(impact_angle, rel=1e-8)


def test_thin_atmosphere_limit():
    """tau -> infinity: the transverse force of eq 3.25 cuts only the horizontal speed by
    e^-beta, eq 3.30 cuts the whole velocity (straight-line drag), then Kepler conics."""
    speed, phi0, beta = 2157.0, math.radians(50.0), 0.2
    launch = mks.ModifiedKeplerSolution(speed, phi0, beta, 1e5, warn=False)
    horizontal, vertical = speed * math.cos(phi0) * math.exp(-beta), speed * math.sin(phi0)
    transverse = kepler.ballistic_conic(
        math.hypot(horizontal, vertical), math.atan2(vertical, horizontal)
    )
    straight = kepler.ballistic_conic(speed * math.exp(-beta), phi0)
    for form, conic in (("eq_3_25", transverse), ("eq_3_30", straight)):
        numerical = nk.solve(launch, form)
        assert numerical.apogee_altitude() == pytest.approx(conic.apogee_altitude_m, rel=1e-3)
        assert numerical.impact_range_m == pytest.approx(conic.ground_range_m, rel=1e-3)


def test_linearisation_error_is_first_order_in_beta():
    """Halving beta halves the eq 3.25 - eq 3.30 difference: not a second-order effect."""

    def error(beta):
        launch = mks.ModifiedKeplerSolution(2157.0, math.radians(50.0), beta, 889.3, warn=False)
        return nk.linearisation_error(launch).apogee_m

    assert error(0.02) / error(0.01) == pytest.approx(2.0, rel=0.05)


def test_truncated_driving_function_converges(hp50):
    theta = np.linspace(0.0, 0.01, 7)
    full = nk.driving_function(hp50, theta)
    assert nk.driving_function(hp50, theta, n_terms=25) == pytest.approx(full, rel=1e-14)
    assert full[0] == pytest.approx(hp50.c3[0, 0] * math.exp(-2 * hp50.beta[0, 0]))


def test_natural_frequency_starts_high_and_decays_to_one(hp50):
    omega = nk.natural_frequency(hp50, np.linspace(0.0, 0.05, 50))
    assert omega[0] == pytest.approx(nk.initial_natural_frequency(hp50))
    assert np.all(np.diff(omega) <= 0) and omega[-1] == pytest.approx(1.0, abs=1e-12)
    on_path = nk.natural_frequency(hp50, 0.0, tan_phi=math.tan(math.radians(50.0)))
    assert on_path == pytest.approx(omega[0])


def test_initial_natural_frequency_does_not_depend_on_k():
    """tau beta = r0 Cd0 rho0 A / (2 m cos phi0): k cancels."""
    values = [
        nk.initial_natural_frequency(mks.for_launch(HP_50, warn=False, decay_constant_per_m=k))
        for k in (0.117e-3, 0.14e-3)
    ]
    assert values[0] == pytest.approx(values[1], rel=1e-12)
    # By hand from eqs 3.22, 3.27 and 3.29: Cd0 = -CX0 at launch, rho0 of eq 3.11
    # (1.225 kg/m^3), tan(50 deg).
    air = get_atmosphere("two_segment")
    phi = np.radians(50.0)
    cd0 = HP.drag_law(2022.0 / air.speed_of_sound(0.0))
    rho0 = 1.225
    tau_beta = earth.RADIUS_M * cd0 * rho0 * HP.reference_area_m2 / (2 * HP.mass_kg * np.cos(phi))
    assert values[0] == pytest.approx(np.sqrt(1 + tau_beta * np.tan(phi)), rel=1e-9)


def test_frequency_response_limits():
    assert nk.frequency_response(0.0, 3.0) == pytest.approx(1 / 9)
    assert nk.frequency_response(3.0, 3.0) == math.inf
    large = np.array([1e4, 1e6])
    assert nk.frequency_response(large, 1.0) * large**2 == pytest.approx(1.0, rel=1e-7)
    ratio = nk.frequency_response(large, 1.0) / nk.frequency_response(large, 20.0)
    assert np.all(ratio < 1) and ratio[-1] == pytest.approx(1.0, abs=1e-9)


def test_driving_rates(hp50):
    assert nk.driving_rates(hp50, 3) == pytest.approx(hp50.tau[0, 0] * np.array([1, 2, 3]))


def test_bad_input_is_named(hp50):
    many = mks.for_launch([baseline_chapter_4(45.0), baseline_chapter_4(50.0)], warn=False)
    with pytest.raises(ValueError, match="form"):
        nk.solve(hp50, "eq_3_31")
    with pytest.raises(ValueError, match="n_terms"):
        nk.solve(hp50, n_terms=0)
    with pytest.raises(ValueError, match="n_terms"):
        nk.solve(hp50, n_terms=2.5)
    with pytest.raises(ValueError, match="n_terms"):
        nk.driving_rates(hp50, 2.5)
    with pytest.raises(ValueError, match="theta_max_rad"):
        nk.solve(hp50, theta_max_rad=-1.0)
    with pytest.raises(ValueError, match="single launch"):
        nk.initial_natural_frequency(many)
    with pytest.raises(ValueError, match="theta_rad"):
        nk.solve(hp50).u(10.0)
    with pytest.raises(ValueError, match="omega"):
        nk.frequency_response(-1.0, 1.0)
    with pytest.raises(ValueError, match="natural_frequency"):
        nk.frequency_response(1.0, 0.0)
    with pytest.raises(ValueError, match="tan_phi"):
        nk.natural_frequency(hp50, 0.0, tan_phi=-1.0)


@pytest.mark.parametrize("form", ["eq_3_25", "eq_3_30"])
def test_solve_for_launch_is_solve_of_the_launch_mks(hp50, form):
    by_launch = nk.solve_for_launch(HP_50, form)
    direct = nk.solve(hp50, form)
    assert by_launch.apogee_altitude() == pytest.approx(direct.apogee_altitude(), rel=1e-12)
    assert by_launch.impact_angle == pytest.approx(direct.impact_angle, rel=1e-12)
    # options of the MKS pass through: a thinner atmosphere scale changes the launch
    other = nk.solve_for_launch(HP_50, form, decay_constant_per_m=0.14e-3)
    assert other.apogee_altitude() != pytest.approx(direct.apogee_altitude(), rel=1e-6)
    with pytest.raises(TypeError, match="Launch"):
        nk.solve_for_launch(HP, form)


@pytest.mark.parametrize("n_terms", [1, 3, 6])
def test_the_closed_form_solves_eq_3_30_to_rounding(n_terms):
    """Notebook 03's derivation check (comparisons.series_residual): u'' + u equals the driving
    function truncated to the solution's own terms, everywhere from launch to impact."""
    from harp_analysis.analyses import comparisons

    assert comparisons.series_residual(mks.for_launch(HP_50, n_terms=n_terms, warn=False)) < 1e-12
