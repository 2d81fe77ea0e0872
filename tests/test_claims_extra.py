"""The quantities of harp_analysis.claims_extra and the conic helpers of harp_analysis.kepler,
checked against independent physics: closed forms, numerical integration, limits and bounds."""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from harp_analysis import claims_extra, earth, harp, kepler, mks, threedof
from harp_analysis.launch import baseline_chapter_4, chapter_2
from harp_analysis.projectiles import LP
from harp_analysis.validation import ModelValidityWarning

R, GM = earth.RADIUS_M, earth.GM_M3_S2


# --- kepler.speed_for_range and conic_from_state ----------------------------------------------
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


# --- Chapter 1 --------------------------------------------------------------------------------
def test_tangent_line_ceiling_is_the_flat_tangent_plus_the_earths_drop():
    reach, phi = 43e3, math.radians(34.0)
    t, angle = math.tan(phi), reach / R
    ceiling = claims_extra.tangent_line_ceiling_m(reach, phi)
    # R cos(phi)/cos(Theta + phi) - R in powers of Theta: the flat tangent s tan(phi), then the
    # sphere's drop below the tangent plane and the slant of the ray
    series = R * (angle * t + angle**2 * (0.5 + t**2) + angle**3 * (t**3 + 5 * t / 6))
    assert ceiling == pytest.approx(series, abs=0.05)
    assert ceiling == pytest.approx(reach * t, rel=0.01)


def test_no_trajectory_climbs_above_its_launch_tangent_line():
    """A heavily dragged flight (LP through the air at 34 deg) and the drag-free one."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        for atmosphere in ("two_segment", "vacuum"):
            launch = chapter_2(LP, elevation_deg=34.0, cross_wind_m_s=0.0, atmosphere=atmosphere)
            flight = threedof.simulate_3dof(launch)
            ceiling = claims_extra.tangent_line_ceiling_m(flight.attrs["range_m"], math.radians(34))
            assert flight.attrs["apogee_altitude_m"] < ceiling


def test_v3_drag_free_apogee_is_a_quarter_of_range_times_tan_on_a_flat_earth():
    assert claims_extra.v3_drag_free_apogee_km(43.0, 34.0) == pytest.approx(
        43.0 * math.tan(math.radians(34.0)) / 4, rel=0.005
    )


def _flat_fire_numerically(speed, phi, k, g):
    """The flat-fire equations du/dt = -k' u^2, dw/dt = -g - k' u w (k' = k sec(phi0))."""
    rate = k / math.cos(phi)

    def rhs(t, y):
        return [y[2], y[3], -rate * y[2] ** 2, -g - rate * y[2] * y[3]]

    land = lambda t, y: y[1] if t > 0 else 1.0  # noqa: E731
    land.terminal, land.direction = True, -1
    top = lambda t, y: y[3]  # noqa: E731
    state = [0.0, 0.0, speed * math.cos(phi), speed * math.sin(phi)]
    solution = solve_ivp(rhs, (0, 1e4), state, rtol=1e-11, atol=1e-9, events=(land, top))
    return solution.y_events[1][0][1], solution.y_events[0][0][0]


@pytest.mark.parametrize("k", [1e-9, 2.5e-5, 1e-4])
def test_flat_fire_closed_form_matches_its_differential_equations(k):
    speed, phi, g = 2022.0, math.radians(50.0), 9.8
    apogee, reach = claims_extra.flat_fire_apogee_and_range_m(speed, phi, k, g)
    numeric_apogee, numeric_reach = _flat_fire_numerically(speed, phi, k, g)
    assert apogee == pytest.approx(numeric_apogee, rel=1e-6)
    assert reach == pytest.approx(numeric_reach, rel=1e-6)


def test_flat_fire_without_drag_is_the_vacuum_parabola():
    speed, phi, g = 700.0, math.radians(34.0), 9.81
    apogee, reach = claims_extra.flat_fire_apogee_and_range_m(speed, phi, 1e-12, g)
    assert apogee == pytest.approx(speed**2 * math.sin(phi) ** 2 / (2 * g), rel=1e-6)
    assert reach == pytest.approx(speed**2 * math.sin(2 * phi) / g, rel=1e-6)


@pytest.mark.parametrize("projectile, elevation", [("HP", 50.0), ("LP", 50.0), ("baseline", 45.0)])
@pytest.mark.parametrize("measure", ["apogee", "range"])
def test_the_simulation_lies_between_vacuum_and_constant_sea_level_air(
    projectile, elevation, measure
):
    """Drag only lowers a flight, and the real air is never denser than at the gun."""
    assert claims_extra.kepler_over_3dof(projectile, elevation, measure) > 1
    assert claims_extra.flat_fire_over_3dof(projectile, elevation, measure) < 1


# --- Chapter 3 --------------------------------------------------------------------------------
def test_kepler_handoff_is_exact_in_a_vacuum():
    for measure in ("path", "radial", "apogee"):
        error = claims_extra.kepler_handoff_error_km("HP", 50.0, 30.0, measure, "vacuum")
        assert abs(error) < 1e-6  # km


def test_kepler_handoff_error_shrinks_with_altitude_and_path_is_under_radial():
    errors = [claims_extra.kepler_handoff_error_km("HP", 50.0, a) for a in (20, 30, 40, 60)]
    assert all(a > b for a, b in zip(errors, errors[1:]))
    assert claims_extra.kepler_handoff_error_km("HP", 50.0, 30.0) < (
        claims_extra.kepler_handoff_error_km("HP", 50.0, 30.0, "radial")
    )
    with pytest.raises(ValueError, match="apogee"):
        claims_extra.kepler_handoff_error_km("HP", 50.0, 100.0)


def test_natural_over_driving_frequency_is_one_over_eq_3_27():
    tau = 0.117e-3 * R * math.tan(math.radians(50.0))
    assert claims_extra.natural_over_driving_frequency("HP", 50.0) == pytest.approx(1 / tau)


# --- Chapter 4 --------------------------------------------------------------------------------
def test_beta_limit_elevation_solves_eq_3_22():
    elevation = claims_extra.beta_limit_elevation_deg("baseline", 0.25)
    cd0 = baseline_chapter_4(elevation).launch_drag_coefficient  # eq 4.8 at the launch Mach
    beta = mks.decay_factor_beta(cd0, 1.225, 0.008, 11.6, math.radians(elevation), 0.117e-3)
    assert float(beta) == pytest.approx(0.25, rel=1e-9)
    assert math.isnan(claims_extra.beta_limit_elevation_deg("LP", 0.25))  # 0.39 even at 90 deg


def test_beta_accuracy_limit_grows_with_the_allowed_error_and_brackets_hp():
    one, two = claims_extra.beta_accuracy_limit(1.0), claims_extra.beta_accuracy_limit(2.0)
    assert 0 < one < two
    # HP itself (beta 0.2745) errs by 2.21 km at apogee, more than 2 km
    assert two < 0.2745


def test_min_mach_is_below_the_launch_mach_and_the_whole_flight_is_slower():
    ascent = claims_extra.min_mach_below(40.0, "ascent")
    flight = claims_extra.min_mach_below(40.0, "flight")
    assert 1 < flight <= ascent < 2157.0 / 340.0


def test_variant_speed_increase():
    assert claims_extra.variant_speed_increase() == pytest.approx(2590 / 2157 - 1)


# --- Chapter 6 --------------------------------------------------------------------------------
def test_density_at_the_standard_sea_level_temperature_is_the_standards():
    assert claims_extra.density_at_temperature_kg_m3(288.15) == pytest.approx(1.2250, abs=5e-5)
    assert claims_extra.fahrenheit_to_kelvin(32.0) == pytest.approx(273.15)
    assert claims_extra.fahrenheit_to_kelvin(212.0) == pytest.approx(373.15)


def test_site_density_from_the_mach_column_uses_its_speed_of_sound():
    a = harp.speed_of_sound("barbados")[0]
    temperature = a**2 / (1.4 * 287.05)
    expected = 101325.0 / (287.05287 * temperature)
    assert claims_extra.site_density_kg_m3("barbados") == pytest.approx(expected, rel=1e-4)


def test_eq_6_4_apogee_is_the_true_zero_of_eq_6_1():
    for site in ("barbados", "yuma"):
        solution = claims_extra.harp_solution(site)
        theta = np.atleast_1d(solution.apogee_angle_eq_6_4)
        # tau theta at apogee is large, so the dropped terms are below e^-20 of the kept ones
        assert np.all(solution.tau[:, 0] * theta > 20)
        assert claims_extra.apogee_drive_ratio(site) < math.exp(-20)
        assert claims_extra.apogee_simplification_shift_km(site) < 1e-6


def test_min_measured_apogee():
    table = harp.appendix_rounds("yuma")
    assert claims_extra.min_measured_apogee_km("yuma") == pytest.approx(table.apogee_m.min() / 1e3)


# --- Chapter 7 --------------------------------------------------------------------------------
def test_late_arrival_miss_is_speed_times_delay_plus_the_gravity_drop():
    level = claims_extra.late_arrival_miss_m(2000.0, 0.5, 0.0, 9.81)
    assert level == pytest.approx(math.hypot(1000.0, 9.81 * 0.125))
    vertical = claims_extra.late_arrival_miss_m(2000.0, 0.5, 90.0, 9.81)
    assert vertical == pytest.approx(1000.0 - 9.81 * 0.125)
