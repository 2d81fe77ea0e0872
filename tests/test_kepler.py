"""The conic helpers of harp_analysis.engines.kepler that the ledger's Chapter 1 and 3 rows use
(speed_for_range, conic_from_state), checked against closed forms, the flat-Earth limit and a
numerical two-body orbit."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from harp_analysis.engines import kepler
from harp_analysis.foundation import earth

# Appendix A's Earth, written out (not read from the package, so that a slip in its constants
# fails here): R = 6378 km, GM = 398600.4418 km^3/s^2.
R, GM = 6_378_000.0, 3.986004418e14


def test_the_package_earth_is_appendix_a():
    assert (earth.RADIUS_M, earth.GM_M3_S2) == (R, GM)


@pytest.mark.parametrize("range_km, elevation_deg", [(43.0, 34.0), (200.0, 50.0), (900.0, 70.0)])
def test_speed_for_range_lands_at_the_range_and_has_the_closed_form_apogee(range_km, elevation_deg):
    phi = math.radians(elevation_deg)
    speed = kepler.speed_for_range(range_km * 1e3, phi)
    conic = kepler.ballistic_conic(speed, phi)  # energy and eccentricity: another route
    assert float(conic.ground_range_m) == pytest.approx(range_km * 1e3, rel=1e-9)
    # u(0) = u(Theta) = 1/R gives u_min = (1 - tan(phi) tan(Theta/4)) / R
    apogee = R / (1 - math.tan(phi) * math.tan(range_km * 1e3 / R / 4)) - R
    assert float(conic.apogee_altitude_m) == pytest.approx(apogee, rel=1e-9)


def test_speed_for_range_tends_to_the_flat_earth_range_formula():
    g, phi, reach = 9.81, math.radians(34.0), 1_000.0
    radius = 1e12  # a huge planet with the same surface gravity: flat Earth, constant g
    speed = kepler.speed_for_range(reach, phi, radius_m=radius, gm_m3_s2=g * radius**2)
    assert speed**2 == pytest.approx(g * reach / math.sin(2 * phi), rel=1e-6)


def test_speed_for_range_refuses_impossible_ranges():
    with pytest.raises(ValueError, match="range angle"):
        kepler.speed_for_range(4 * R, 0.5)
    with pytest.raises(ValueError, match="flight_path_angle_rad"):
        kepler.speed_for_range(1e5, math.pi / 2)


def _two_body(radius, speed, angle, theta_end):
    """Radius against central angle from a numerical two-body integration in the plane."""

    def rhs(t, y):
        r = math.hypot(y[0], y[1])
        return [y[2], y[3], -GM * y[0] / r**3, -GM * y[1] / r**3]

    state = [radius, 0.0, speed * math.sin(angle), speed * math.cos(angle)]
    angle_reached = lambda t, y: math.atan2(y[1], y[0]) - theta_end  # noqa: E731
    angle_reached.terminal = True
    solution = solve_ivp(
        rhs, (0, 5000), state, rtol=1e-12, atol=1e-6, dense_output=True, events=angle_reached
    )
    times = np.linspace(0, solution.t[-1], 400)
    x, y = solution.sol(times)[:2]
    return np.arctan2(y, x), np.hypot(x, y)


def test_conic_from_state_follows_a_numerical_two_body_orbit():
    radius, speed, angle = R + 30e3, 1700.0, math.radians(35.0)
    theta, r = _two_body(radius, speed, angle, 0.05)
    conic = kepler.conic_from_state(radius, speed, angle)
    assert np.max(np.abs(conic.radius(theta) - r)) < 1e-3  # m
    assert conic.apogee_radius_m == pytest.approx(r.max(), abs=1.0)


def test_conic_from_state_at_the_surface_is_the_ballistic_conic():
    speed, phi = 2157.0, math.radians(45.0)
    conic = kepler.conic_from_state(R, speed, phi)
    ballistic = kepler.ballistic_conic(speed, phi)
    assert conic.apogee_radius_m == pytest.approx(float(ballistic.apogee_radius_m), rel=1e-12)
    theta = float(ballistic.range_angle_rad)
    assert float(conic.radius(theta)) == pytest.approx(R, rel=1e-12)
    # a symmetric conic: it lands at the launch angle, and is level at the apogee
    assert float(conic.flight_path_angle(theta)) == pytest.approx(-phi, abs=1e-12)
    assert float(conic.flight_path_angle(theta / 2)) == pytest.approx(0.0, abs=1e-12)


def test_an_open_conic_has_no_apogee():
    escape = math.sqrt(2 * GM / R)
    assert math.isinf(kepler.conic_from_state(R, 1.01 * escape, 0.3).apogee_radius_m)
