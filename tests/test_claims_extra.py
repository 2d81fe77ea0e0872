"""The quantities of harp_analysis.analyses.claims.extra and the conic helpers of
harp_analysis.engines.kepler, checked against independent physics: closed forms, numerical
integration, limits and bounds."""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from harp_analysis.analyses import comparisons, rotating
from harp_analysis.analyses.claims import extra
from harp_analysis.analyses.harp import apogees
from harp_analysis.engines import kepler, mks, threedof
from harp_analysis.foundation import earth
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models.launch import baseline_chapter_4, chapter_2
from harp_analysis.models.projectiles import LP

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
    ceiling = extra.tangent_line_ceiling_m(reach, phi)
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
            ceiling = extra.tangent_line_ceiling_m(flight.attrs["range_m"], math.radians(34))
            assert flight.attrs["apogee_altitude_m"] < ceiling


def test_v3_drag_free_apogee_is_a_quarter_of_range_times_tan_on_a_flat_earth():
    assert extra.v3_drag_free_apogee_km(43.0, 34.0) == pytest.approx(
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
    apogee, reach = extra.flat_fire_apogee_and_range_m(speed, phi, k, g)
    numeric_apogee, numeric_reach = _flat_fire_numerically(speed, phi, k, g)
    assert apogee == pytest.approx(numeric_apogee, rel=1e-6)
    assert reach == pytest.approx(numeric_reach, rel=1e-6)


def test_flat_fire_without_drag_is_the_vacuum_parabola():
    speed, phi, g = 700.0, math.radians(34.0), 9.81
    apogee, reach = extra.flat_fire_apogee_and_range_m(speed, phi, 1e-12, g)
    assert apogee == pytest.approx(speed**2 * math.sin(phi) ** 2 / (2 * g), rel=1e-6)
    assert reach == pytest.approx(speed**2 * math.sin(2 * phi) / g, rel=1e-6)


@pytest.mark.parametrize("projectile, elevation", [("HP", 50.0), ("LP", 50.0), ("baseline", 45.0)])
@pytest.mark.parametrize("measure", ["apogee", "range"])
def test_the_simulation_lies_between_vacuum_and_constant_sea_level_air(
    projectile, elevation, measure
):
    """Drag only lowers a flight, and the real air is never denser than at the gun."""
    assert extra.kepler_over_3dof(projectile, elevation, measure) > 1
    assert extra.flat_fire_over_3dof(projectile, elevation, measure) < 1


# --- Chapter 3 --------------------------------------------------------------------------------
def test_kepler_handoff_is_exact_in_a_vacuum():
    for measure in ("path", "radial", "apogee"):
        error = extra.kepler_handoff_error_km("HP", 50.0, 30.0, measure, "vacuum")
        assert abs(error) < 1e-6  # km


def test_kepler_handoff_error_shrinks_with_altitude_and_path_is_under_radial():
    errors = [extra.kepler_handoff_error_km("HP", 50.0, a) for a in (20, 30, 40, 60)]
    assert all(a > b for a, b in zip(errors, errors[1:]))
    assert extra.kepler_handoff_error_km("HP", 50.0, 30.0) < (
        extra.kepler_handoff_error_km("HP", 50.0, 30.0, "radial")
    )
    with pytest.raises(ValueError, match="apogee"):
        extra.kepler_handoff_error_km("HP", 50.0, 100.0)


def test_natural_over_driving_frequency_is_one_over_eq_3_27():
    tau = 0.117e-3 * R * math.tan(math.radians(50.0))
    assert extra.natural_over_driving_frequency("HP", 50.0) == pytest.approx(1 / tau)


# --- Chapter 4 --------------------------------------------------------------------------------
def test_beta_limit_elevation_solves_eq_3_22():
    elevation = extra.beta_limit_elevation_deg("baseline", 0.25)
    cd0 = baseline_chapter_4(elevation).launch_drag_coefficient  # eq 4.8 at the launch Mach
    beta = mks.decay_factor_beta(cd0, 1.225, 0.008, 11.6, math.radians(elevation), 0.117e-3)
    assert float(beta) == pytest.approx(0.25, rel=1e-9)
    assert math.isnan(extra.beta_limit_elevation_deg("LP", 0.25))  # 0.39 even at 90 deg


def test_beta_accuracy_limit_grows_with_the_allowed_error_and_brackets_hp():
    one, two = extra.beta_accuracy_limit(1.0), extra.beta_accuracy_limit(2.0)
    assert 0 < one < two
    # HP itself (beta 0.2745) errs by 2.21 km at apogee, more than 2 km
    assert two < 0.2745


def test_min_mach_is_below_the_launch_mach_and_the_whole_flight_is_slower():
    ascent = extra.min_mach_below(40.0, "ascent")
    flight = extra.min_mach_below(40.0, "flight")
    assert 1 < flight <= ascent < 2157.0 / 340.0


def test_variant_speed_increase_is_the_flown_launches_and_about_a_fifth():
    """The increase is that of the launches Fig 4.17's comparison flies (the 3DOF's first
    speed), and Ch. 4 C's "20 % increase" to the printed 2.59 km/s's rounding."""
    faster = comparisons.case("baseline", 45.0, **comparisons.VARIANTS["speed_plus_20pct"])[0]
    baseline = comparisons.case("baseline", 45.0)[0]
    flown = faster.speed_m_s.iloc[0] / baseline.speed_m_s.iloc[0] - 1
    assert extra.variant_speed_increase() == pytest.approx(flown, rel=1e-9)
    assert extra.variant_speed_increase() == pytest.approx(0.20, abs=0.005 / 2.157)


# --- Chapter 6 --------------------------------------------------------------------------------
def test_density_at_the_standard_sea_level_temperature_is_the_standards():
    assert extra.density_at_temperature_kg_m3(288.15) == pytest.approx(1.2250, abs=5e-5)
    assert extra.fahrenheit_to_kelvin(32.0) == pytest.approx(273.15)
    assert extra.fahrenheit_to_kelvin(212.0) == pytest.approx(373.15)


def test_site_density_from_the_mach_column_uses_its_speed_of_sound():
    a = apogees.speed_of_sound("barbados")[0]
    temperature = a**2 / (1.4 * 287.05)
    expected = 101325.0 / (287.05287 * temperature)
    assert extra.site_density_kg_m3("barbados") == pytest.approx(expected, rel=1e-4)


def test_eq_6_4_apogee_is_the_true_zero_of_eq_6_1():
    for site in ("barbados", "yuma"):
        solution = extra.harp_solution(site)
        theta = np.atleast_1d(solution.apogee_angle_eq_6_4)
        # tau theta at apogee is large, so the dropped terms are below e^-20 of the kept ones
        assert np.all(solution.tau[:, 0] * theta > 20)
        assert extra.apogee_drive_ratio(site) < math.exp(-20)
        assert extra.apogee_simplification_shift_km(site) < 1e-6


def test_min_measured_apogee():
    table = apogees.appendix_rounds("yuma")
    assert extra.min_measured_apogee_km("yuma") == pytest.approx(table.apogee_m.min() / 1e3)


# --- Chapter 7 --------------------------------------------------------------------------------
def test_late_arrival_miss_is_speed_times_delay_plus_the_gravity_drop():
    level = extra.late_arrival_miss_m(2000.0, 0.5, 0.0, 9.81)
    assert level == pytest.approx(math.hypot(1000.0, 9.81 * 0.125))
    vertical = extra.late_arrival_miss_m(2000.0, 0.5, 90.0, 9.81)
    assert vertical == pytest.approx(1000.0 - 9.81 * 0.125)


# === Chapters 1-3 and 7, Appendices: the sweep's rows (second part of claims_extra) ===========
from scipy import constants  # noqa: E402

from harp_analysis.analyses import effort, scenarios  # noqa: E402
from harp_analysis.analyses.comparisons import chapter_4_launch  # noqa: E402
from harp_analysis.models import atmosphere  # noqa: E402
from harp_analysis.models.launch import HP_CHAPTER_2  # noqa: E402
from harp_analysis.models.projectiles import BASELINE, HP  # noqa: E402


def test_the_highest_harp_apogee_is_590000_feet():
    assert extra.max_measured_apogee_km("both") == pytest.approx(590_000 * 0.3048e-3, 1e-4)
    assert extra.max_measured_apogee_km("barbados") < extra.max_measured_apogee_km()


def test_mlt_operations_go_as_the_number_of_segments():
    one, two = (extra.mlt_over_3dof_orders(length) for length in (1000.0, 2000.0))
    assert one - two == pytest.approx(math.log10(2.0), abs=0.01)
    flops = effort.effort_table().flops  # the effort table's MLT flies 1 km segments
    assert one == pytest.approx(math.log10(flops["MLT"] / flops["3DOF"]), abs=1e-9)


def test_mks_apogee_miss_share_against_a_separate_6dof_run():
    six = scenarios.reference_6dof("HP", "spherical").attrs["apogee_altitude_m"]
    mks_apogee = float(mks.for_launch(HP_CHAPTER_2, warn=False).apogee_altitude())
    assert extra.mks_apogee_miss_share() == pytest.approx(abs(mks_apogee - six) / six, 1e-3)


def test_flat_fire_miss_is_the_gap_between_the_flat_fire_and_3dof_ranges():
    launch = chapter_4_launch("HP", 50.0).but(cross_wind_m_s=0.0, spin_rad_s=0.0)
    simulated = threedof.simulate_3dof(launch).attrs["range_m"]
    flat = extra.flat_fire_over_3dof("HP", 50.0, "range") * simulated
    assert extra.flat_fire_miss_km("HP", 50.0, "range") == pytest.approx(
        (simulated - flat) / 1e3, rel=1e-6
    )


def test_orbital_drag_uses_the_1976_density_at_200_km():
    # the printed 1976 table: 2.541e-10 kg/m^3 at 200 km (the ussa1976 package that
    # atmosphere.standard_density tabulates runs 3 % above it there, 0.15 % at 100 km)
    density, radius = 2.541e-10, R + 200e3
    speed_squared, gravity = GM / radius, GM / radius**2  # circular orbit
    drag = 0.5 * density * speed_squared * 2.2 * BASELINE.reference_area_m2 / BASELINE.mass_kg
    assert extra.orbital_drag_to_gravity(200.0) == pytest.approx(drag / gravity, rel=0.05)
    assert extra.orbital_drag_to_gravity(400.0) < extra.orbital_drag_to_gravity(200.0)


def _stormer_final_x(dt, correct_start):
    """x at t = 10 of the oscillator x'' = -x (x = 1, x' = 1 at 0) flown by Appendix A's
    recurrence x2 = 2 x1 - x0 + a dt^2, started as the listing does (x1 = x0 + v0 dt) or with
    the a dt^2/2 term. (The Earth's gravity is too uniform over a flight for the recurrence's
    own second-order error to stand out of the round-off.)"""
    x0, v0 = 1.0, 1.0
    x1 = x0 + v0 * dt - (0.5 * x0 * dt**2 if correct_start else 0.0)
    for _ in range(round(10.0 / dt) - 1):
        x0, x1 = x1, 2 * x1 - x0 - x1 * dt**2
    return x1


@pytest.mark.parametrize("correct_start, order", [(True, 2.0), (False, 1.0)])
def test_observed_order_of_the_stormer_recurrence(correct_start, order):
    finals = [_stormer_final_x(dt, correct_start) for dt in (0.05, 0.025, 0.0125)]
    assert extra.observed_order(*finals) == pytest.approx(order, abs=0.06)


def test_observed_order_of_known_error_laws():
    for p in (1.0, 2.0, 4.0):
        assert extra.observed_order(*(3.0 + 0.7 * h**p for h in (0.2, 0.1, 0.05))) == (
            pytest.approx(p, abs=1e-9)
        )
    assert math.isnan(extra.observed_order(1.0, 2.0, 1.0))  # not converging


def test_similar_inertia_is_a_scaled_cylinders():
    def cylinder(mass, radius, length):  # pitch inertia of a solid cylinder about its centre
        return mass * (3 * radius**2 + length**2) / 12

    scale = (HP.mass_kg / LP.mass_kg) ** (1 / 3)
    radius, length, density = 0.0134, 0.75, 7800.0
    small = density * math.pi * radius**2 * length
    ratio = cylinder(small * scale**3, radius * scale, length * scale) / cylinder(
        small, radius, length
    )
    assert extra.similar_inertia_kg_m2("pitch") / LP.pitch_inertia_kg_m2 == pytest.approx(
        ratio, rel=1e-12
    )


def test_lp_angle_of_attack_in_the_air_is_the_cross_wind_angle_at_the_muzzle():
    expected = math.degrees(math.atan2(5.0, 2022.0))
    assert extra.max_angle_of_attack_below_deg("LP", 30.0) == pytest.approx(expected, abs=1e-3)


def test_mach_over_speed_ratio_is_the_speeds_of_sound_ratio():
    sound = atmosphere.two_segment_speed_of_sound(np.array([0.0, 20e3]))
    assert extra.mach_over_speed_ratio_max("HP") == pytest.approx(sound[0] / sound[1], rel=2e-3)


def test_turn_in_a_vacuum_follows_from_energy_and_angular_momentum():
    speed, phi, top = HP.launch_speed_m_s, math.radians(50.0), 20e3
    radius = R + top
    speed_at = math.sqrt(speed**2 - 2 * GM * (1 / R - 1 / radius))
    angle = math.acos(R * speed * math.cos(phi) / (radius * speed_at))
    turn = extra.ascent_change_below("HP", "turn", 20.0, atmosphere="vacuum")
    assert turn == pytest.approx(math.degrees(phi - angle), abs=1e-3)
    assert extra.ascent_change_below("HP", "speed", 20.0, atmosphere="vacuum") == (
        pytest.approx(1 - speed_at / speed, abs=1e-6)
    )


def test_gravity_dominant_share_grows_with_the_ratio():
    shares = [extra.gravity_dominant_share("HP", n) for n in (0.1, 1.0, 1e9)]
    assert shares[0] < shares[1] < shares[2] == pytest.approx(1.0, abs=1e-12)


def test_text_gm_with_the_codata_constant():
    assert constants.G == pytest.approx(6.67430e-11, rel=1e-12)
    assert extra.text_gm_over_appendix_gm() == pytest.approx(
        6.67430e-11 * 5.972e24 / 398600.4418e9, rel=1e-12
    )


def test_break_jump_from_the_printed_equations():
    below = 1.22581 * (1 - 0.00002257 * 10769.0) ** 4.256  # eq 2.2
    above = 0.37454745  # eq 2.1 at its start
    assert extra.two_segment_break_jump() == pytest.approx(above / below - 1, abs=2e-6)


@pytest.mark.parametrize("projectile", ["HP", "LP"])
def test_ascent_momentum_loss_near_the_straight_line_decay(projectile):
    # eq 3.23: h_inf = h0 exp(-beta) for a straight climb through eq 3.11's air
    beta = comparisons.mks_beta(projectile, 50.0)
    assert extra.momentum_loss(projectile, "ascent") == pytest.approx(1 - math.exp(-beta), abs=0.03)
    assert 0 < extra.momentum_loss(projectile, "reentry") < 1


def test_rotation_shift_of_a_short_vacuum_shot_is_the_first_order_one():
    # east, north, up at 45 deg N; fired north at 45 deg elevation, 200 m/s
    latitude, speed, omega = math.radians(45.0), 200.0, earth.ROTATION_RATE_RAD_S
    g = GM / R**2
    spin = omega * np.array([0.0, math.cos(latitude), math.sin(latitude)])
    velocity = speed * np.array([0.0, math.cos(math.pi / 4), math.sin(math.pi / 4)])
    t = 2 * velocity[2] / g
    # r'' = g - 2 Omega x v - Omega x (Omega x r), to first order about the vacuum parabola
    shift = (
        -np.cross(spin, velocity) * t**2
        - np.cross(spin, [0.0, 0.0, -g]) * t**3 / 3
        + 0.5 * omega**2 * R * math.cos(latitude) * np.array([0.0, -math.sin(latitude), 0.0]) * t**2
        + 0.5 * omega**2 * R * math.cos(latitude) ** 2 * np.array([0.0, 0.0, 1.0]) * t**2
    )
    on_ground = shift[:2] + velocity[:2] * shift[2] / velocity[2]  # later landing, further on
    computed = extra.rotation_impact_shift_km(speed, 45.0, 45.0, 0.0, atmosphere="vacuum")
    assert computed * 1e3 == pytest.approx(np.linalg.norm(on_ground), rel=0.02)


def test_only_a_rotating_earth_tells_launch_sites_apart():
    assert extra.nonrotating_spread_m(45.0) < 1e-2
    assert extra.nonrotating_spread_m(45.0, earth.ROTATION_RATE_RAD_S) > 1e3


def test_baseline_momentum_share_near_the_straight_line_decay():
    beta = comparisons.mks_beta("baseline", 30.0)
    gamma = math.exp(-atmosphere.TEXT_DECAY_CONSTANT_PER_M * 20e3)
    straight = (1 - math.exp(beta * (gamma - 1))) / (1 - math.exp(-beta))
    share = extra.baseline_momentum_loss_share_below(20.0, elevations_deg=(30.0,))
    assert share == pytest.approx(straight, abs=0.03)


def test_converged_series_apogee_solves_eq_3_30_with_the_double_exponential():
    solution = mks.for_launch(chapter_4_launch("LP", 50.0), n_terms=15, warn=False)
    c3, beta, tau = (float(x[0, 0]) for x in (solution.c3, solution.beta, solution.tau))
    r0, phi = R, math.radians(50.0)

    def rhs(theta, y):  # eq 3.30 with the series summed: c3 exp(-2 beta e^{-tau theta})
        return [y[1], c3 * math.exp(-2 * beta * math.exp(-tau * theta)) - y[0]]

    top = lambda theta, y: y[1]  # noqa: E731
    top.terminal, top.direction = True, 1
    ode = solve_ivp(
        rhs,
        (0, 1.0),
        [1 / r0, -math.tan(phi) / r0],
        rtol=1e-12,
        atol=1e-20,
        events=top,
        first_step=1e-7,
        max_step=1e-3,
    )
    apogee = 1 / ode.y_events[0][0][0] - r0
    assert float(solution.apogee_altitude()) == pytest.approx(apogee, abs=0.1)
    needed = extra.series_terms_needed("LP", 50.0, 1.0)
    fewer = mks.for_launch(chapter_4_launch("LP", 50.0), n_terms=needed - 1, warn=False)
    assert abs(float(fewer.apogee_altitude()) - apogee) > 1.0


def test_firing_solutions_agree_and_hit_the_point():
    elevation_mks, _, _ = extra.firing_solution("mks")
    elevation_3dof, iterations, evaluations = extra.firing_solution("3dof")
    assert elevation_mks == pytest.approx(elevation_3dof, abs=0.1)  # the MKS's accuracy
    flight = threedof.simulate_3dof(baseline_chapter_4(elevation_3dof), output_step_s=0.1)
    up = flight[flight.time_s <= flight.attrs["apogee_time_s"]]
    assert np.interp(150e3, up.ground_range_m, up.altitude_m) == pytest.approx(100e3, abs=1.0)
    assert evaluations > 100 * iterations


def test_pointing_shift_in_a_vacuum_turns_the_velocity():
    launch = baseline_chapter_4(45.0, atmosphere="vacuum")
    shift = extra.position_shift_m(launch, elevation_error_mrad=1.0, at_s=10.0)
    assert shift == pytest.approx(2157.0 * 10.0 * 1e-3, rel=5e-3)
    speed_shift = extra.position_shift_m(launch, speed_error_m_s=1.0, at_s=10.0)
    assert speed_shift == pytest.approx(10.0, rel=5e-3)


def test_mks_lands_where_the_3dof_does_in_a_vacuum():
    assert extra.mks_impact_miss_km("baseline", 45.0, atmosphere="vacuum") < 1e-3


def test_mach_column_share_recomputed_independently():
    rounds = apogees.appendix_rounds("barbados")
    rounds = rounds[~rounds.duplicate_of_earlier_row]
    mach = rounds.muzzle_speed_m_s / apogees.speed_of_sound("barbados")[0]
    within = float(np.mean(np.abs(mach - rounds.mach) <= 0.005 + 1e-12))
    assert extra.appendix_column_share_within_rounding("barbados", "mach") == within


def test_appendix_a_rotation_terms_in_a_vacuum():
    # at the equator the printed omega R is right and without air the sign of the air
    # velocity does not matter
    assert abs(extra.appendix_a_rotation_effect_error_km(atmosphere="vacuum")) < 0.02
    # at 45 deg N the printed omega R adds omega R (1 - cos 45 deg) of eastward speed
    latitude, speed, elevation = math.radians(45.0), 2157.0, math.radians(45.0)
    surface = earth.ROTATION_RATE_RAD_S * R

    def apogee(east_extra):
        east, up = speed * math.cos(elevation) + east_extra, speed * math.sin(elevation)
        conic = kepler.conic_from_state(R, math.hypot(east, up), math.atan2(up, east))
        return conic.apogee_radius_m - R

    expected = apogee(surface) - apogee(surface * math.cos(latitude))
    computed = extra.appendix_a_rotation_effect_error_km(45.0, 90.0, atmosphere="vacuum")
    assert computed * 1e3 == pytest.approx(expected, rel=0.02)


def test_printed_angle_of_attack_is_the_tangent():
    ratio = extra.printed_angle_of_attack_ratio("HP")
    alpha = float(scenarios.reference_6dof("HP").angle_of_attack_rad.max())
    assert ratio == pytest.approx(1 + alpha**2 / 3 + 2 * alpha**4 / 15, rel=1e-5)
    assert math.degrees(alpha) > 4  # the large angle outside the air (Ch. 4 A)


# --- Issue 26: statements scored --------------------------------------------------------------
def test_the_clock_s_launch_error_shrinks_as_the_speed_does():
    """Appendix A's clock leads its positions by one step, so the MKS is V dt ahead: below 30 km
    on the way up that part has fallen with the speed, while the MKS's own error (zero at
    launch) has grown, so the error left lies between the speed ratio and 1."""
    rows, _ = rotating.appendix_a_errors(0.1, 45.0)
    climbing = rows[(rows.time_s <= rows.attrs["apogee_time_s"]) & (rows.altitude_m < 30e3)]
    speed_ratio = climbing.speed_m_s.min() / rows.speed_m_s.iloc[0]
    assert speed_ratio < extra.launch_error_left_below(30.0, 0.1, 45.0) < 1.0
    assert rotating.appendix_a_errors(0.1, 45.0)[1].total_geometric_m.iloc[0] == pytest.approx(
        rotating.appendix_a_launch_error_m(0.1, 45.0)
    )


@pytest.mark.parametrize("engine", ["6DOF", "MLT", "3DOF"])
def test_the_descent_s_fastest_point_is_slower_than_the_gun_and_faster_than_impact(engine):
    """Drag takes energy all the way: the fastest point on the way down is slower than the
    launch (2022 m/s, Chapter 2 A) and faster than the apogee's speed and the impact."""
    loss = extra.reentry_speed_loss(engine, "HP")
    assert loss.impact_speed_m_s < loss.peak_speed_m_s < 2022.0
    assert 0.0 < loss.loss < 1.0 and 0.0 < loss.flight_share < 0.5


def test_off_design_error_at_the_design_launch_is_chapter_4_s():
    design = extra.off_design_error(45.0, 2157.0)
    assert design.error_km == pytest.approx(comparisons.error_at_apogee_km("baseline", 45.0))
    assert design.share_of_apogee == pytest.approx(
        comparisons.error_at_apogee_km("baseline", 45.0, relative=True)
    )


def test_the_corrected_angular_momentum_slows_the_error_s_growth():
    """Taking h_inf from the 3DOF's apogee removes the mismatch that drives the growth."""
    growth = extra.error_growth()
    assert growth.impact_over_apogee > 1.0
    assert growth.corrected_impact_over_apogee < growth.impact_over_apogee
    assert growth.corrected_impact_km < growth.impact_km
