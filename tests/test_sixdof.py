"""The 6DOF of Appendix B against independent physics: the no-roll reformulation against the
body-frame port, the adaptive solver against Appendix B's own RK4, closed-form Kepler orbits in
vacuum, mirror symmetry, the roll equilibrium of the fins and the point-mass 3DOF; the shared
metadata, truncated flights and the launches the 6DOF refuses."""

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from harp_analysis.engines import sixdof, threedof
from harp_analysis.foundation import earth
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models import rigid_body
from harp_analysis.models.atmosphere import get_atmosphere
from harp_analysis.models.drag import M829
from harp_analysis.models.launch import HP_CHAPTER_2, LP_CHAPTER_2, Launch, chapter_2
from harp_analysis.models.projectiles import HP, LP
from harp_analysis.models.trajectory import BASE_COLUMNS, METADATA_KEYS, TruncatedFlightWarning

R, GM = earth.RADIUS_M, earth.GM_M3_S2


# --- the no-roll frame is the body frame turned back by phi -----------------------------------
def _rotate(a, b, phi):
    """Components (a, b) of a body y-z vector in the no-roll frame (turned back by phi)."""
    c, s = math.cos(phi), math.sin(phi)
    return c * a - s * b, s * a + c * b


def _body_to_no_roll(state):
    x, y, z, phi, theta, psi, u, v, w, p, q, r = state
    return np.array([x, y, z, phi, theta, psi, u, *_rotate(v, w, phi), p, *_rotate(q, r, phi)])


def _expected_no_roll_derivative(body_state, body_derivative):
    """d/dt of the no-roll state from the body state and its Appendix B derivative: the
    rotated derivative plus the turning of the rotation itself (phi' times the 90 deg turn)."""
    phi = body_state[3]
    n = _body_to_no_roll(body_state)
    d = np.array(body_derivative, dtype=float)
    phi_dot = d[3]
    dv, dw = _rotate(d[7], d[8], phi)
    dq, dr = _rotate(d[10], d[11], phi)
    d[7], d[8] = dv - phi_dot * n[8], dw + phi_dot * n[7]
    d[10], d[11] = dq - phi_dot * n[11], dr + phi_dot * n[10]
    return d


_states = st.tuples(
    st.floats(-1e3, 4e5),
    st.floats(-2e3, 2e3),
    st.floats(-1.5e5, 1.2e4),  # x y z
    st.floats(-50.0, 50.0),
    st.floats(-1.4, 1.4),
    st.floats(-0.5, 0.5),  # phi theta psi
    st.floats(150.0, 3500.0),
    st.floats(-300.0, 300.0),
    st.floats(-300.0, 300.0),  # u v w
    st.floats(-600.0, 600.0),
    st.floats(-5.0, 5.0),
    st.floats(-5.0, 5.0),  # p q r
)


@settings(max_examples=300, deadline=None)
@given(
    state=_states,
    wind=st.tuples(*[st.floats(-30.0, 30.0)] * 3),
    projectile=st.sampled_from([HP, LP]),
    density_altitude=st.sampled_from(rigid_body.DENSITY_ALTITUDES),
)
def test_no_roll_derivative_is_appendix_b_turned_into_the_no_roll_frame(
    state, wind, projectile, density_altitude
):
    kwargs = dict(wind_m_s=wind, density_altitude=density_altitude)
    body = np.array(state)
    expected = _expected_no_roll_derivative(
        body, sixdof.appendix_b_derivatives(body, projectile, **kwargs)
    )
    actual = sixdof.appendix_b_derivatives(
        _body_to_no_roll(body), projectile, frame="no_roll", **kwargs
    )
    # Each group (position, angles, velocity, rates) to 1e-9 of its own size, or of the
    # rounding of its largest cross-product term (omega x V; omega x I omega, whose x component
    # q Iz r - r Iy q is zero only in exact arithmetic in the body frame).
    omega, speed = np.max(np.abs(body[9:])), np.max(np.abs(body[6:9]))
    cross_terms = (
        0.0,
        0.0,
        omega * speed,
        omega**2 * projectile.pitch_inertia_kg_m2 / projectile.roll_inertia_kg_m2,
    )
    for group, cross in zip((slice(0, 3), slice(3, 6), slice(6, 9), slice(9, 12)), cross_terms):
        scale = max(np.max(np.abs(expected[group])), 1e-3 * cross)
        np.testing.assert_allclose(actual[group], expected[group], rtol=1e-9, atol=1e-9 * scale)


def test_appendix_b_derivative_at_launch_by_hand():
    """At launch (no wind, no yaw) the port reduces to drag plus gravity along the axis, the
    fins' roll torque and the launch's own pitch/yaw kinematics."""
    state = np.array([0, 0, 0, 0, math.radians(50), 0, 2022.0, 0, 0, 10.0, 0, 0])
    d = sixdof.appendix_b_derivatives(state, HP)
    rho = get_atmosphere("two_segment").density(0.0)
    mach = 2022.0 / get_atmosphere("two_segment").speed_of_sound(0.0)
    cx0, cldd, clp = (np.interp(mach, M829.mach, getattr(M829, c)) for c in ("cx0", "cldd", "clp"))
    qa = 0.5 * rho * 2022.0**2 * math.pi / 4 * HP.diameter_m**2
    g = GM / R**2
    assert d[:3] == pytest.approx(
        [2022 * math.cos(math.radians(50)), 0, -2022 * math.sin(math.radians(50))]
    )
    assert d[6] == pytest.approx(qa * cx0 / HP.mass_kg - g * math.sin(math.radians(50)))
    assert d[8] == pytest.approx(g * math.cos(math.radians(50)))  # gravity across the axis
    assert d[9] == pytest.approx(
        qa * HP.diameter_m * (cldd + 10 * clp * HP.diameter_m / 4044) / HP.roll_inertia_kg_m2
    )
    assert d[3] == 10.0  # phi' = p
    assert d[[1, 4, 5, 7, 10, 11]] == pytest.approx(np.zeros(6), abs=1e-12)


def test_flat_and_spherical_density_altitudes_agree_above_the_launch_point():
    state = np.array([0, 0, -3e4, 0.3, 0.5, 0.1, 1500.0, 2, -3, 200.0, 0.01, -0.02])
    flat = sixdof.appendix_b_derivatives(state, HP)
    spherical = sixdof.appendix_b_derivatives(state, HP, density_altitude="spherical")
    assert spherical == pytest.approx(flat, rel=1e-12)
    state[0] = 3e5  # downrange the surface falls away: the flat altitude reads ~7 km too low
    assert abs(sixdof.appendix_b_derivatives(state, HP)[6]) > abs(
        sixdof.appendix_b_derivatives(state, HP, density_altitude="spherical")[6]
    )


# --- adaptive no-roll solution against Appendix B's fixed-step RK4 ----------------------------
_SPAN_S = 1.0  # the first second: full air, the spin-up from 10 to 300 rad/s


@pytest.fixture(scope="module")
def rk4_runs():
    def derivatives(t, state):
        return sixdof.appendix_b_derivatives(state, HP, wind_m_s=(0.0, 5.0, 0.0))

    state0 = [0, 0, 0, 0, math.radians(50), 0, 2022.0, 0, 0, 10.0, 0, 0]
    return {
        h: sixdof.integrate_fixed_step(derivatives, state0, h, _SPAN_S)[1][-1]
        for h in (0.0005, 0.00025)
    }


@pytest.fixture(scope="module")
def adaptive_first_second():
    # Chapter 2 A's launch (50 deg, 2022 m/s, 10 rad/s, 5 m/s cross wind), as the RK4's.
    with pytest.warns(TruncatedFlightWarning):
        return sixdof.simulate_6dof(HP_CHAPTER_2, max_time_s=_SPAN_S, output_step_s=_SPAN_S)


def test_adaptive_no_roll_solution_matches_appendix_b_rk4(rk4_runs, adaptive_first_second):
    end = adaptive_first_second.iloc[-1]
    assert end.time_s == _SPAN_S and not adaptive_first_second.attrs["impact"]
    assert adaptive_first_second.attrs["stop_reason"] == "max_time"
    rk4 = rk4_runs[0.0005]
    position = end[["x_m", "y_m", "z_m"]].to_numpy(float)
    assert np.max(np.abs(position - rk4[:3])) < 3e-3  # Appendix B's own h: within 3 mm
    assert end.speed_m_s == pytest.approx(np.linalg.norm(rk4[6:9]), rel=1e-6)
    assert end.roll_rate_rad_s == pytest.approx(rk4[9], rel=1e-8)
    assert end.roll_rad == pytest.approx(rk4[3], rel=1e-8)
    assert [end.pitch_rad, end.yaw_rad] == pytest.approx(rk4[4:6], abs=5e-6)


def test_rk4_converges_to_the_adaptive_solution(rk4_runs, adaptive_first_second):
    """The RK4 error is O(h^4): Richardson extrapolation of h and h/2 removes it, leaving the
    two independent solutions within tens of micrometres of each other (the coarse RK4 itself
    is a millimetre off)."""
    coarse, fine = rk4_runs[0.0005], rk4_runs[0.00025]
    extrapolated = fine + (fine - coarse) / 15
    end = adaptive_first_second.iloc[-1]
    position = end[["x_m", "y_m", "z_m"]].to_numpy(float)
    assert np.max(np.abs(position - extrapolated[:3])) < 2e-5
    assert np.max(np.abs(position - fine[:3])) < np.max(np.abs(position - coarse[:3])) / 10
    assert [end.pitch_rad, end.yaw_rad] == pytest.approx(extrapolated[4:6], abs=3e-8)


def test_fixed_step_rk4_is_fourth_order():
    def oscillator(t, y):
        return np.array([y[1], -y[0]])

    errors = [
        abs(sixdof.integrate_fixed_step(oscillator, [1.0, 0.0], h, 2.0)[1][-1, 0] - math.cos(2.0))
        for h in (0.1, 0.05)
    ]
    assert errors[0] / errors[1] == pytest.approx(16, rel=0.05)


# --- vacuum: the closed-form Kepler orbit ------------------------------------------------------
@pytest.fixture(scope="module")
def vacuum_flight():
    # Density zero, eqs 2.1-2.2's speed of sound; Chapter 2 A's launch, cross wind included.
    assert float(get_atmosphere("vacuum").density(1e4)) == 0.0
    return sixdof.simulate_6dof(chapter_2(HP, atmosphere="vacuum"), rtol=1e-11)


def test_vacuum_flight_conserves_energy_and_angular_momentum(vacuum_flight):
    radius = vacuum_flight.altitude_m + R
    energy = 0.5 * vacuum_flight.speed_m_s**2 - GM / radius
    momentum = vacuum_flight.specific_angular_momentum_m2_s
    assert np.ptp(energy) / abs(energy.mean()) < 1e-9
    assert np.ptp(momentum) / momentum.mean() < 1e-9
    assert np.max(np.abs(vacuum_flight.cross_range_m)) == 0.0  # the cross wind acts on no air


def test_vacuum_flight_is_the_conic_of_its_launch(vacuum_flight):
    speed, elevation = 2022.0, math.radians(50.0)
    a = 1 / (2 / R - speed**2 / GM)
    h = R * speed * math.cos(elevation)
    e = math.sqrt(1 - h**2 / (GM * a))
    # Rising at launch: true anomaly nu0 in (0, pi); apogee at pi, return at 2 pi - nu0.
    nu0 = math.acos((h**2 / (GM * R) - 1) / e)
    ecc0 = 2 * math.atan(math.sqrt((1 - e) / (1 + e)) * math.tan(nu0 / 2))
    time_of_flight = 2 * (math.pi - (ecc0 - e * math.sin(ecc0))) / math.sqrt(GM / a**3)
    attrs = vacuum_flight.attrs
    assert attrs["impact"]
    assert attrs["apogee_altitude_m"] == pytest.approx(a * (1 + e) - R, abs=1.0)
    assert attrs["range_m"] == pytest.approx(2 * (math.pi - nu0) * R, abs=1.0)
    assert attrs["time_of_flight_s"] == pytest.approx(time_of_flight, abs=1e-3)
    assert attrs["apogee_time_s"] == pytest.approx(time_of_flight / 2, abs=1e-3)


# --- full flights: symmetry, wind, spin, the point mass ---------------------------------------
def _mirrored(projectile):
    """The same projectile with its fins canted the other way."""
    aero = dataclasses.replace(projectile.aero, cldd=tuple(-c for c in projectile.aero.cldd))
    return dataclasses.replace(projectile, name=projectile.name + "_mirrored", aero=aero)


@pytest.fixture(scope="module")
def flights():
    return {
        "wind": sixdof.simulate_6dof(HP_CHAPTER_2),
        "calm": sixdof.simulate_6dof(chapter_2(HP, cross_wind_m_s=0.0)),
        "calm_mirrored": sixdof.simulate_6dof(
            chapter_2(_mirrored(HP), spin_rad_s=-10.0, cross_wind_m_s=0.0)
        ),
        "spherical": sixdof.simulate_6dof(HP_CHAPTER_2, density_altitude="spherical"),
    }


def test_flight_table_and_statistics(flights):
    flight = flights["wind"]
    assert tuple(flight.columns) == BASE_COLUMNS + rigid_body.EXTRA_COLUMNS
    assert set(METADATA_KEYS) <= set(flight.attrs)
    assert flight.attrs["engine"] == "6DOF" and flight.attrs["launch"] == HP_CHAPTER_2
    assert flight.attrs["stop_reason"] == "impact"
    assert 0 < flight.attrs["steps"] < flight.attrs["rhs_evaluations"]
    assert flight.attrs["time_of_flight_s"] == flight.time_s.iloc[-1]
    assert flight.attrs["impact"] and abs(flight.altitude_m.iloc[-1]) < 1e-6
    assert np.allclose(np.diff(flight.time_s.iloc[:-1]), 0.5)
    # The no-roll frame: no spin-rate oscillation.
    assert flight.attrs["rhs_evaluations"] < 100_000
    assert flight.attrs["apogee_altitude_m"] == pytest.approx(flight.altitude_m.max(), abs=5.0)
    assert flight.mach.iloc[0] == pytest.approx(
        math.hypot(2022.0, 5.0) / get_atmosphere("two_segment").speed_of_sound(0.0)
    )


def test_calm_flight_drifts_only_by_its_spin(flights):
    """Without wind, the only asymmetry is the fins' roll direction: the cross range is small
    (spin drift, tens of metres over 240 km) and exactly mirrored by fins canted the other way."""
    calm, mirrored = flights["calm"], flights["calm_mirrored"]
    drift = np.max(np.abs(calm.cross_range_m))
    assert 1.0 < drift < 2e-4 * calm.attrs["range_m"]
    np.testing.assert_allclose(mirrored.cross_range_m, -calm.cross_range_m, atol=1e-3)
    np.testing.assert_allclose(mirrored.altitude_m, calm.altitude_m, atol=1e-3)
    assert mirrored.roll_rate_rad_s.min() < -200


def test_cross_wind_drifts_downwind(flights):
    wind, calm = flights["wind"], flights["calm"]
    drift = (wind.cross_range_m - calm.cross_range_m)[wind.time_s > 1.0]
    assert np.all(drift > 0)
    assert drift.iloc[-1] > 100.0  # hundreds of metres over 240 km from a 5 m/s wind


def test_head_wind_blows_against_the_line_of_fire():
    """The head wind adds to the air speed along the line of fire (-x in the flat frame)."""
    launch = chapter_2(HP, cross_wind_m_s=0.0, head_wind_m_s=10.0)
    with pytest.warns(TruncatedFlightWarning):
        flight = sixdof.simulate_6dof(launch, max_time_s=1.0, output_step_s=1.0)
    elevation = math.radians(50.0)
    air_speed = math.hypot(2022.0 * math.cos(elevation) + 10.0, 2022.0 * math.sin(elevation))
    sound = get_atmosphere("two_segment").speed_of_sound(0.0)
    assert flight.mach.iloc[0] == pytest.approx(air_speed / sound, rel=1e-12)
    assert flight.speed_m_s.iloc[0] == pytest.approx(2022.0, rel=1e-12)


def test_fins_spin_the_projectile_to_the_roll_equilibrium(flights):
    """Roll driving against roll damping: p d / (2V) -> -CLDD / CLP within about a second."""
    flight = flights["wind"]
    row = flight[flight.time_s == 2.0].iloc[0]
    air_speed = row.mach * get_atmosphere("two_segment").speed_of_sound(-row.z_m)
    cldd, clp = (np.interp(row.mach, M829.mach, getattr(M829, c)) for c in ("cldd", "clp"))
    assert row.roll_rate_rad_s == pytest.approx(
        -2 * air_speed * cldd / (clp * HP.diameter_m), rel=0.02
    )


def test_table_mach_and_axial_coefficient_are_each_rows_aerodynamics(flights):
    """Without wind the air speed is the speed: each row's Mach is it over the speed of sound
    at the flat altitude (below sea level at the end: the formula unchecked, as the 6DOF reads
    it), and its axial coefficient is -CX0 - CX2 sin^2(alpha) from Appendix B's table at that
    Mach (the row's angle of attack; raw tables, numpy)."""
    flight = flights["calm"]
    sound = get_atmosphere("two_segment").sound_kernel(flight.altitude_flat_m.to_numpy())
    np.testing.assert_allclose(flight.mach, flight.speed_m_s / sound, rtol=1e-12)
    cx0, cx2 = (np.interp(flight.mach, M829.mach, getattr(M829, c)) for c in ("cx0", "cx2"))
    sin_alpha = np.sin(flight.angle_of_attack_rad)
    np.testing.assert_allclose(flight.drag_coefficient, -cx0 - cx2 * sin_alpha**2, rtol=1e-12)


def test_aerodynamically_stable_flight_is_the_point_mass_3dof(flights):
    """Chapter 2 B: the fin-stabilised projectile keeps a small angle of attack in the air, so
    the 3DOF with the zero-yaw drag -CX0 flies the same trajectory (same spherical air)."""
    six = flights["spherical"].attrs
    three = threedof.simulate_3dof(HP_CHAPTER_2, output_step_s=10.0).attrs
    assert six["apogee_altitude_m"] == pytest.approx(three["apogee_altitude_m"], rel=2e-4)
    assert six["range_m"] == pytest.approx(three["range_m"], rel=2e-4)
    assert six["time_of_flight_s"] == pytest.approx(three["time_of_flight_s"], rel=2e-4)
    flight = flights["spherical"]
    ascent = (flight.altitude_m < 30e3) & (flight.time_s < six["apogee_time_s"])
    assert flight.angle_of_attack_rad[ascent].max() < math.radians(0.2)


def test_flat_density_altitude_thickens_the_descent(flights):
    """Appendix B reads the air at -z: downrange that is below the true altitude, so the flat
    flight meets denser air on the way down and lands slower and shorter."""
    flat, spherical = flights["wind"].attrs, flights["spherical"].attrs
    assert flat["impact_speed_m_s"] < 0.8 * spherical["impact_speed_m_s"]
    assert flat["range_m"] < spherical["range_m"]


# --- ends and bad input -----------------------------------------------------------------------
def test_flight_cut_off_by_max_time_warns_and_says_why():
    """Before its apogee: no impact, the table ends at max_time_s, the range is the last row's."""
    assert issubclass(TruncatedFlightWarning, ModelValidityWarning)
    with pytest.warns(TruncatedFlightWarning, match="max_time_s = 20 s"):
        flight = sixdof.simulate_6dof(LP_CHAPTER_2, max_time_s=20.0, output_step_s=5.0)
    attrs = flight.attrs
    assert set(METADATA_KEYS) <= set(attrs)
    assert attrs["stop_reason"] == "max_time" and attrs["impact"] is False
    assert math.isnan(attrs["apogee_time_s"]) and math.isnan(attrs["apogee_altitude_m"])
    assert list(flight.time_s) == [0.0, 5.0, 10.0, 15.0, 20.0]
    assert attrs["time_of_flight_s"] == 20.0
    assert attrs["range_m"] == flight.ground_range_m.iloc[-1] > 0.0
    assert flight.altitude_m.iloc[-1] > 10e3


def _without(name):
    return dataclasses.replace(HP, **{name: None})


@pytest.mark.parametrize(
    "changes, name",
    [
        ({"elevation_deg": 0.0}, "elevation_deg"),
        ({"elevation_deg": 91.0}, "elevation_deg"),
        ({"elevation_deg": np.nan}, "elevation_deg"),
        ({"speed_m_s": 0.0}, "speed_m_s"),
        ({"speed_m_s": -2022.0}, "speed_m_s"),
        ({"spin_rad_s": np.nan}, "spin_rad_s"),
        ({"cross_wind_m_s": np.inf}, "cross_wind_m_s"),
        ({"head_wind_m_s": np.nan}, "head_wind_m_s"),
        ({"atmosphere": "martian"}, "atmosphere"),
    ],
)
def test_bad_launch_is_named_when_the_launch_is_built(changes, name):
    with pytest.raises(ValueError, match=name):
        chapter_2(HP, **changes)
    with pytest.raises(ValueError, match=name):
        HP_CHAPTER_2.but(**changes)


@pytest.mark.parametrize(
    "changes, name",
    [
        ({"elevation_deg": 90.0}, "elevation_deg"),  # a valid launch at the Euler singularity
        ({"rotation_rate_rad_s": earth.ROTATION_RATE_RAD_S}, "rotation_rate_rad_s"),
        ({"rotation_rate_rad_s": -earth.ROTATION_RATE_RAD_S}, "rotation_rate_rad_s"),
        ({"site_altitude_m": 100.0}, "site_altitude_m"),
        ({"site_altitude_m": -10.0}, "site_altitude_m"),
    ],
)
def test_launch_the_6dof_cannot_fly_is_refused_by_name(changes, name):
    launch = HP_CHAPTER_2.but(**changes)
    with pytest.raises(ValueError, match=name):
        sixdof.simulate_6dof(launch)


@pytest.mark.parametrize(
    "options, name",
    [
        ({"density_altitude": "round"}, "density_altitude"),
        ({"rtol": 0.0}, "rtol"),
        ({"max_time_s": -1.0}, "max_time_s"),
        ({"output_step_s": 0.0}, "output_step_s"),
    ],
)
def test_bad_simulation_option_is_named(options, name):
    with pytest.raises(ValueError, match=name):
        sixdof.simulate_6dof(HP_CHAPTER_2, **options)


def test_only_a_launch_is_flown():
    with pytest.raises(TypeError, match="Launch"):
        sixdof.simulate_6dof(HP)
    with pytest.raises(TypeError, match="Launch"):
        sixdof.simulate_6dof("HP")
    with pytest.raises(TypeError, match="projectile"):
        Launch("HP", 2022.0, 50.0)
    with pytest.raises(TypeError, match="elevation_deg"):
        Launch(HP, 2022.0, "50")
    with pytest.raises(TypeError):  # the old keywords are now fields of the Launch
        sixdof.simulate_6dof(HP_CHAPTER_2, crosswind_m_s=5.0)


@pytest.mark.parametrize(
    "missing", ["aero", "diameter_m", "roll_inertia_kg_m2", "pitch_inertia_kg_m2"]
)
def test_projectile_without_6dof_data_is_named(missing):
    with pytest.raises(ValueError, match=f"projectile 'HP' has no {missing}"):
        sixdof.simulate_6dof(chapter_2(_without(missing)))
    with pytest.raises(ValueError, match=missing):
        sixdof.appendix_b_derivatives(np.zeros(12), _without(missing))


def test_bad_derivative_input_is_named():
    state = np.array([0, 0, 0, 0, 0.8, 0, 2022.0, 0, 0, 10.0, 0, 0])
    with pytest.raises(ValueError, match="state"):
        sixdof.appendix_b_derivatives(state[:11], HP, frame="no_roll")
    with pytest.raises(ValueError, match="state"):
        sixdof.appendix_b_derivatives(np.where(np.arange(12) == 7, np.nan, state), HP)
    with pytest.raises(ValueError, match="wind_m_s"):
        sixdof.appendix_b_derivatives(state, HP, wind_m_s=(0.0, 5.0))
    with pytest.raises(ValueError, match="density_altitude"):
        sixdof.appendix_b_derivatives(state, HP, frame="no_roll", density_altitude="curved")
    with pytest.raises(TypeError, match="projectile"):
        sixdof.appendix_b_derivatives(state, "HP")
    with pytest.raises(ValueError, match="frame"):
        sixdof.appendix_b_derivatives(state, HP, frame="inertial")
    with pytest.raises(ValueError, match="t_end_s"):
        sixdof.integrate_fixed_step(lambda t, y: y, [1.0], 0.3, 1.0)
    with pytest.raises(ValueError, match="h_s"):
        sixdof.integrate_fixed_step(lambda t, y: y, [1.0], 0.0, 1.0)


def test_reference_6dof_is_converged_under_the_method_differences():
    # Step refinement for the adaptive solver: a hundred times tighter tolerance moves HP's
    # reference flight by far less than the 16-50 m between the 3DOF or MLT and the 6DOF.
    from harp_analysis.analyses.mlt_validation import sixdof_convergence

    table = sixdof_convergence("HP", rtols=(1e-11,))
    assert table.max_position_difference_m.iloc[0] < 0.1
    assert abs(table.apogee_difference_m.iloc[0]) < 0.1
    assert abs(table.range_difference_m.iloc[0]) < 0.1
