"""Modified Linear Theory (mlt.py) against independent physics: convergence to its continuous
limit as segments shrink (second order with mid-segment coefficients, first order with
start-of-segment ones), McCoy's epicyclic roots from the raw M829 tables, the exact parabola
and the Kepler conic in vacuum, the 6DOF's no-roll derivatives minus exactly the products
that eq L1 drops, the closed-form segment's own derivative, the output table and its shared
metadata, truncated flights, the launches MLT refuses and bad input.

Flights are Chapter 2 A's launch (50 deg, 2022 m/s, 10 rad/s of spin, a 5 m/s cross wind:
launch.chapter_2) unless they say otherwise."""

import dataclasses
import math
import warnings

import numpy as np
import pytest

from harp_analysis.engines import kepler, mlt, sixdof
from harp_analysis.foundation import earth
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models import rigid_body
from harp_analysis.models.atmosphere import get_atmosphere
from harp_analysis.models.drag import M829
from harp_analysis.models.launch import HP_CHAPTER_2, LP_CHAPTER_2, baseline_chapter_4, chapter_2
from harp_analysis.models.projectiles import HP, LP
from harp_analysis.models.trajectory import BASE_COLUMNS, METADATA_KEYS, TruncatedFlightWarning

R, GM = earth.RADIUS_M, earth.GM_M3_S2
G0 = GM / R**2
ELEVATION = math.radians(50.0)
AIR = get_atmosphere("two_segment")
POSITION = ["x_m", "y_m", "z_m"]


def _raw(name, mach):
    """An M829 coefficient straight from Appendix B's table, linear in Mach."""
    return float(np.interp(mach, M829.mach, getattr(M829, name)))


# --- segments shrinking to the continuous limit -----------------------------------------------
SEGMENTS_M = (2000.0, 1000.0, 500.0, 100.0)


@pytest.fixture(scope="module")
def limit():
    """The linear-theory equations integrated tightly: what MLT must converge to."""
    return mlt.simulate_linear_theory_limit(LP_CHAPTER_2, rtol=1e-11)


def _position_error(flight, reference):
    """Largest distance between the two flights at the 0.5 s rows both have before either
    lands (the impact rows, at different times, are left out)."""
    a, b = flight.iloc[:-1], reference.iloc[:-1]
    common = np.intersect1d(a.time_s, b.time_s)
    assert len(common) > 400  # ~225 s of flight at 0.5 s
    pa = a.set_index("time_s").loc[common, POSITION].to_numpy()
    pb = b.set_index("time_s").loc[common, POSITION].to_numpy()
    return float(np.max(np.linalg.norm(pa - pb, axis=1)))


@pytest.mark.parametrize(
    "coefficients_at, order_range",
    [("middle", (1.6, 2.5)), ("average", (1.6, 2.5)), ("start", (0.8, 1.25))],
)
def test_segments_converge_to_the_linear_theory_limit(limit, coefficients_at, order_range):
    """Freezing the coefficients at the segment's middle (or the mean of its ends) is the
    midpoint (trapezoid) rule: error O(L^2); at its start, the rectangle rule: O(L)."""
    position, range_error = {}, {}
    for length in SEGMENTS_M:
        flight = mlt.simulate_mlt(
            LP_CHAPTER_2, segment_length_m=length, coefficients_at=coefficients_at
        )
        position[length] = _position_error(flight, limit)
        range_error[length] = abs(flight.attrs["range_m"] - limit.attrs["range_m"])
    order = math.log10(range_error[1000.0] / range_error[100.0])
    print(f"\nLP, coefficients at {coefficients_at}: max position error / range error (m)")
    for length in SEGMENTS_M:
        print(f"  {length:6.0f} m: {position[length]:10.3f} / {range_error[length]:10.3f}")
    print(f"  observed order (range, 1000 m -> 100 m): {order:.3f}")
    errors = [position[length] for length in SEGMENTS_M]
    assert all(fine < coarse for coarse, fine in zip(errors, errors[1:]))
    assert position[100.0] < position[2000.0] / 10
    assert order_range[0] < order < order_range[1]


# --- McCoy's epicyclic roots ------------------------------------------------------------------
def _mccoy(projectile, altitude, speed, spin):
    """McCoy (Modern Exterior Ballistics ch. 10) with constant velocity, from the raw tables:
    P, M, H, T and the extra product A C of the exact characteristic polynomial."""
    d, m = projectile.diameter_m, projectile.mass_kg
    ix, iy = projectile.roll_inertia_kg_m2, projectile.pitch_inertia_kg_m2
    rho = float(AIR.density(altitude))
    mach = speed / float(AIR.speed_of_sound(altitude))
    cna, cmq, arm = (_raw(name, mach) for name in ("cna", "cmq", "sldel"))
    p_ = ix / iy * spin * d / speed
    m_ = math.pi * rho * d**4 * cna * arm / (8 * iy)  # k_t^-2 C_Malpha*, C_Malpha D = CNA SLDEL
    t_ = math.pi * rho * d**3 * cna / (8 * m)  # C_Nalpha*
    c_ = math.pi * rho * d**5 * cmq / (16 * iy)  # k_t^-2 C_Mq*
    return p_, m_, t_ - c_, t_, t_ * c_


FLIGHT_STATES = [  # projectile, altitude (m), speed (m/s), roll rate (rad/s)
    (LP, 100.0, 2000.0, 445.0),
    (LP, 5000.0, 1800.0, 250.0),
    (HP, 20000.0, 1500.0, 300.0),
    (HP, 40000.0, 1000.0, 100.0),
    (LP, 60000.0, 900.0, 400.0),
]


@pytest.mark.parametrize("projectile, altitude, speed, spin", FLIGHT_STATES)
def test_epicyclic_roots_are_mccoys(projectile, altitude, speed, spin):
    model = rigid_body.rigid_body_model(projectile, "two_segment", (0.0, 0.0, 0.0), "spherical")
    state = (0.0, 0.0, -altitude, 0.0, 0.7, 0.0, speed, 0.0, 0.0, spin, 0.0, 0.0)
    c = mlt.segment_coefficients(model, state)
    fast, slow = mlt.epicyclic_roots(c, projectile.diameter_m)
    p_, m_, h_, t_, ac = _mccoy(projectile, altitude, speed, spin)

    # The coefficients themselves, from the raw tables.
    d = projectile.diameter_m
    assert c.speed == speed
    assert c.gyroscopic == pytest.approx(p_, rel=1e-12)
    assert d * c.static_moment == pytest.approx(m_, rel=1e-12)
    assert c.lift == pytest.approx(t_, rel=1e-12)
    assert c.lift - c.damping == pytest.approx(h_, rel=1e-12)

    # Fin-stabilised: statically stable (M < 0), so Sg = P^2 / (4M) < 0; both modes damped.
    assert m_ < 0 and p_**2 / (4 * m_) < 0
    assert c.gyroscopic**2 / (4 * d * c.static_moment) < 0
    assert fast.real < 0 and slow.real < 0

    # Exact roots of lambda^2 + (H - iP) lambda - (M + A C + i P T) = 0.
    exact = sorted(
        np.roots([1.0, h_ - 1j * p_, -(m_ + ac + 1j * p_ * t_)]), key=lambda z: -abs(z.imag)
    )
    for root, reference in zip((fast, slow), exact):
        assert abs(root - reference) <= 1e-10 * abs(reference)

    # McCoy's first-order closed forms. Expanding the square root of the discriminant,
    # S^2 (1 - eps) with S = sqrt(P^2 - 4M), eps = (i P (4T - 2H) + H^2 + 4AC) / S^2:
    # the frequencies drop (H^2 + 4AC) / (4S) and both drop ~S |eps|^2 / 16 (bounded by twice).
    s = math.sqrt(p_**2 - 4 * m_)
    eps = (abs(p_ * (4 * t_ - 2 * h_)) + abs(h_**2 + 4 * ac)) / s**2
    second_order = s * eps**2 / 8 + 1e-12 * s
    frequencies = ((p_ + s) / 2, (p_ - s) / 2)
    dampings = (-(h_ - p_ * (2 * t_ - h_) / s) / 2, -(h_ + p_ * (2 * t_ - h_) / s) / 2)
    for root, frequency, damping in zip((fast, slow), frequencies, dampings):
        assert abs(root.imag - frequency) <= (abs(h_**2 + 4 * ac) / (2 * s) + second_order)
        assert root.imag == pytest.approx(frequency, rel=1e-3)
        assert abs(root.real - damping) <= second_order
        assert second_order < 1e-3 * abs(damping)  # the check discriminates


# --- vacuum ----------------------------------------------------------------------------------
@pytest.mark.parametrize("length", [2000.0, 500.0])
def test_vacuum_uniform_gravity_is_the_exact_parabola(length):
    """Without air and with constant gravity eqs L2-L7 are exact at any segment length."""
    flight = mlt.simulate_mlt(
        chapter_2(LP, cross_wind_m_s=0.0),
        aerodynamics=False,
        gravity="uniform",
        segment_length_m=length,
    )
    t = flight.time_s.to_numpy()
    x = 2022.0 * math.cos(ELEVATION) * t
    z = -2022.0 * math.sin(ELEVATION) * t + G0 * t**2 / 2
    error = np.hypot(flight.x_m - x, flight.z_m - z)
    travelled_km = np.maximum(2022.0 * t / 1e3, 1.0)
    assert flight.attrs["impact"] and t[-1] > 300.0
    assert np.max(error / travelled_km) < 1e-8  # rounding only: 1e-8 m per km
    assert np.max(np.abs(flight.y_m)) < 1e-8
    assert np.max(np.abs(flight.pitch_rad - ELEVATION)) < 1e-15
    assert np.max(np.abs(flight.yaw_rad)) < 1e-15


def test_vacuum_central_gravity_converges_to_the_kepler_conic():
    """The frozen gravity vector is the only error: it converges as segments shrink, at second
    order (mid-segment gravity), to the conic of a surface launch at the elevation."""
    conic = kepler.ballistic_conic(2022.0, ELEVATION)
    apogee, time_of_flight = {}, {}
    for length in (2000.0, 500.0, 100.0):
        attrs = mlt.simulate_mlt(LP_CHAPTER_2, aerodynamics=False, segment_length_m=length).attrs
        apogee[length] = abs(attrs["apogee_altitude_m"] - conic.apogee_altitude_m)
        time_of_flight[length] = abs(attrs["time_of_flight_s"] - conic.time_of_flight_s)
        print(
            f"\nvacuum, {length:.0f} m: apogee error {apogee[length]:.3e} m, "
            f"time of flight error {time_of_flight[length]:.3e} s"
        )
    for errors in (apogee, time_of_flight):
        assert errors[100.0] < errors[500.0] < errors[2000.0]
        assert errors[2000.0] / errors[500.0] > 10  # (2000 / 500)^2 = 16 at second order
    # Second order from the 2 km error (2.3 cm, 2.3e-5 s): (1/20)^2 of it, with a margin of 10.
    assert apogee[100.0] < 1e-3 and apogee[100.0] < apogee[2000.0] / 40
    assert time_of_flight[100.0] < 1e-6


# --- the linearised derivatives ----------------------------------------------------------------
def _air_state(model, theta, psi, lateral, w_ratio, rate, *, x=2e4, z=-8e3, u=1700.0, p=300.0):
    """A no-roll state whose air-relative v, w are (lateral, w_ratio lateral); q, r likewise."""
    ct, st, cp, sp = math.cos(theta), math.sin(theta), math.cos(psi), math.sin(psi)
    wx, wy, wz = model.wind
    v_w = -sp * wx + cp * wy
    w_w = st * cp * wx + st * sp * wy + ct * wz
    return np.array(
        [
            x,
            0.0,
            z,
            0.3,
            theta,
            psi,
            u,
            v_w + lateral,
            w_w + w_ratio * lateral,
            p,
            rate,
            w_ratio * rate,
        ]
    )


def _dropped_products(model, state):
    """6DOF minus linear theory, term by term: what eq L1 drops (and nothing else)."""
    x, y, z, _, theta, psi, u, v, w, p, q, r = state
    ct, st, cp, sp = math.cos(theta), math.sin(theta), math.cos(psi), math.sin(psi)
    wx, wy, wz = model.wind
    ua = u - (ct * cp * wx + ct * sp * wy - st * wz)
    va = v - (-sp * wx + cp * wy)
    wa = w - (st * cp * wx + st * sp * wy + ct * wz)
    lateral = va**2 + wa**2
    speed = math.sqrt(ua**2 + lateral)
    rho = float(AIR.density(-z))  # the model's flat density altitude
    mach = speed / float(AIR.speed_of_sound(-z))
    cx0, cx2 = _raw("cx0", mach), _raw("cx2", mach)
    drag_factor = math.pi * rho * model.d**2 / (8 * model.mass)
    tan = math.tan(theta)
    dropped = np.zeros(12)
    dropped[3] = r * tan  # phi' = p + r tan(theta)
    dropped[6] = (
        drag_factor * (cx0 * speed * (speed - ua) + cx2 * lateral)  # one V frozen, CX2
        - (q * w - r * v)
    )
    dropped[7] = -r * (u - speed) - r * tan * w  # u = V; frame roll rate
    dropped[8] = q * (u - speed) + r * tan * v
    dropped[10] = -tan * r**2
    dropped[11] = tan * q * r
    return dropped


@pytest.mark.parametrize("psi", [0.0, 0.02])
def test_6dof_minus_linear_theory_is_exactly_the_dropped_products(psi):
    """At finite lateral states (3 m/s, 0.05 rad/s, a 5 m/s cross wind) the 6DOF's no-roll
    derivative (Magnus inert, y = 0 so both gravities agree) minus linear theory's is the sum
    of the products eq L1 lists, to rounding."""
    model = rigid_body.rigid_body_model(LP, "two_segment", (0.0, 5.0, 0.0), "flat")
    state = _air_state(model, 0.8, psi, 3.0, -0.7, 0.05)
    full = np.array(sixdof.right_hand_side(0.0, state, model.kernel))
    linear = np.array(mlt.linear_theory_derivatives(model, state.tolist()))
    dropped = _dropped_products(model, state)
    assert np.max(np.abs(dropped[6:9] / full[6:9])) > 1e-3  # the products matter here
    scale = np.abs(full) + np.abs(linear) + 1.0
    np.testing.assert_allclose(full - linear, dropped, rtol=0, atol=1e-11 * np.max(scale))
    np.testing.assert_array_equal(full[[0, 1, 2, 4, 5]], np.array(linear)[[0, 1, 2, 4, 5]])


@pytest.mark.parametrize("theta", [0.8, -0.6])
def test_linear_theory_is_the_6dof_at_small_lateral_states(theta):
    """v, w (air-relative) of a mm/s and q, r of 1e-6 rad/s: the dropped products are below
    1e-6 of every derivative. (psi = 0: no wind along the axis, which u = V would also drop.)"""
    model = rigid_body.rigid_body_model(LP, "two_segment", (0.0, 5.0, 0.0), "flat")
    state = _air_state(model, theta, 0.0, 1e-3, -0.7, 1e-6)
    full = np.array(sixdof.right_hand_side(0.0, state, model.kernel))
    linear = np.array(mlt.linear_theory_derivatives(model, state.tolist()))
    np.testing.assert_allclose(linear[6:9], full[6:9], rtol=1e-6)
    np.testing.assert_allclose(linear[10:], full[10:], rtol=1e-6)
    assert linear[9] == pytest.approx(full[9], rel=1e-13)  # p': exact
    np.testing.assert_array_equal(linear[[0, 1, 2, 4, 5]], full[[0, 1, 2, 4, 5]])
    assert linear[3] == pytest.approx(full[3], rel=1e-8)  # phi': r tan(theta) dropped


def test_closed_form_segment_has_the_linear_theory_derivative():
    """d/ds of propagate_segment at s = 0, times V/D, is linear_theory_derivatives at the same
    state (coefficients and rotation taken there): forward differences converge at first order,
    central ones agree to 1e-7."""
    model = rigid_body.rigid_body_model(LP, "two_segment", (0.0, 5.0, 0.0), "flat")
    theta, psi = 0.8, 0.02
    state = _air_state(model, theta, psi, 2.0, -0.75, 0.03, x=1.2e4, z=-6e3, u=1750.0, p=320.0)
    state[1] = 30.0
    state = tuple(state.tolist())
    c = mlt.segment_coefficients(model, state)
    ct, st, cp, sp = math.cos(theta), math.sin(theta), math.cos(psi), math.sin(psi)
    rows = ((ct * cp, ct * sp, -st), (-sp, cp, 0.0), (st * cp, st * sp, ct))
    exact = np.array(mlt.linear_theory_derivatives(model, list(state)))
    per_calibre = c.speed / model.d
    x0 = np.array(state)

    def at(h):
        return np.array(mlt.propagate_segment(model, state, c, rows, 1.0 / ct, h))

    def relative(estimate, h):
        rounding = 8 * np.finfo(float).eps * (np.abs(x0) + 1.0) * per_calibre / h
        return np.max(np.abs(estimate - exact) / (np.abs(exact) + rounding))

    forward = [relative((at(h) - x0) / h * per_calibre, h) for h in (1e-1, 1e-2, 1e-3)]
    assert forward[0] / forward[1] > 5 and forward[1] / forward[2] > 5
    assert forward[2] < 1e-5
    h = 1e-2
    assert relative((at(h) - at(-h)) / (2 * h) * per_calibre, 2 * h) < 1e-7


# --- bad input and validity ------------------------------------------------------------------
@pytest.mark.parametrize(
    "options, match",
    [
        ({"segment_length_m": 0.0}, "segment_length_m"),
        ({"segment_length_m": -5.0}, "segment_length_m"),
        ({"segment_length_m": math.nan}, "segment_length_m"),
        ({"segment_length_m": 1e6}, "longer than the flight"),
        ({"segment_length_m": 1e7}, "longer than the flight"),
        ({"segment_length_m": 1e-3}, "segment_length_m = 0.001 m would need"),  # hung
        ({"coefficients_at": "end"}, "coefficients_at"),
        ({"gravity": "flat"}, "gravity"),
        ({"density_altitude": "round"}, "density_altitude"),
        ({"max_time_s": 0.0}, "max_time_s"),
        ({"output_step_s": -0.5}, "output_step_s"),
    ],
)
def test_bad_input_is_named(options, match):
    with pytest.raises(ValueError, match=match):
        mlt.simulate_mlt(LP_CHAPTER_2, **options)


@pytest.mark.parametrize(
    "options, match",
    [
        ({"density_altitude": "round"}, "density_altitude"),
        ({"rtol": 0.0}, "rtol"),
        ({"max_time_s": -1.0}, "max_time_s"),
        ({"output_step_s": 0.0}, "output_step_s"),
    ],
)
def test_bad_linear_theory_limit_input_is_named(options, match):
    with pytest.raises(ValueError, match=match):
        mlt.simulate_linear_theory_limit(LP_CHAPTER_2, **options)


@pytest.mark.parametrize(
    "changes", [{"elevation_deg": 0.0}, {"elevation_deg": 95.0}, {"elevation_deg": math.nan}]
)
def test_bad_elevation_is_named_when_the_launch_is_built(changes):
    with pytest.raises(ValueError, match="elevation_deg"):
        chapter_2(LP, **changes)


_ENGINES = {"MLT": mlt.simulate_mlt, "linear-theory limit": mlt.simulate_linear_theory_limit}


@pytest.mark.parametrize("engine", _ENGINES)
@pytest.mark.parametrize(
    "changes, name",
    [
        ({"elevation_deg": 90.0}, "elevation_deg"),  # a valid launch at the Euler singularity
        ({"rotation_rate_rad_s": earth.ROTATION_RATE_RAD_S}, "rotation_rate_rad_s"),
        ({"site_altitude_m": 100.0}, "site_altitude_m"),
    ],
)
def test_launch_mlt_cannot_fly_is_refused_by_name(engine, changes, name):
    launch = LP_CHAPTER_2.but(**changes)
    with pytest.raises(ValueError, match=name):
        _ENGINES[engine](launch)


@pytest.mark.parametrize("engine", _ENGINES)
def test_only_a_launch_is_flown(engine):
    with pytest.raises(TypeError, match="Launch"):
        _ENGINES[engine](LP)
    with pytest.raises(TypeError):  # the old keywords are now fields of the Launch
        _ENGINES[engine](LP_CHAPTER_2, crosswind_m_s=5.0)


def test_projectile_without_aerodynamics_is_named():
    with pytest.raises(ValueError, match="projectile 'baseline' has no aero"):
        mlt.simulate_mlt(baseline_chapter_4(50.0))


def test_statically_unstable_projectile_is_flagged():
    """The centre of pressure moved ahead of the centre of mass (SLDEL > 0): M > 0, a mode
    grows, the angle of attack leaves the small-angle range in dense air."""
    aero = dataclasses.replace(M829, sldel=tuple(-x for x in M829.sldel))
    unstable = dataclasses.replace(LP, name="LP_unstable", aero=aero)
    # The divergent closed form overflows the air's exponential on the way (np.errstate):
    # the flight after the warning is not physical and is not checked here.
    with pytest.warns(ModelValidityWarning, match="angle of attack"), np.errstate(over="ignore"):
        mlt.simulate_mlt(chapter_2(unstable))


@pytest.mark.parametrize(
    "launch", [HP_CHAPTER_2.but(elevation_deg=70.0), LP_CHAPTER_2.but(elevation_deg=80.0)]
)
def test_a_reentry_linear_theory_cannot_turn_is_warned_of(launch):
    """Steep shots keep their attitude over the vacuum arc and come down backwards (an angle of
    attack above 90 deg) where the air is too thin for the dense-air check; the 6DOF turns them
    into the wind, MLT bounces off the thin air and climbs again (issue 25: HP's range 206 km
    against the 6DOF's 173 km, LP's -6.4 km, unwarned)."""
    with pytest.warns(ModelValidityWarning, match="climbs back"):
        flight = mlt.simulate_mlt(launch)
    turned = sixdof.simulate_6dof(launch)
    assert abs(flight.attrs["range_m"] - turned.attrs["range_m"]) > 10e3  # what it warns of


def test_reference_flight_is_within_linear_theory():
    with warnings.catch_warnings():
        warnings.simplefilter("error", ModelValidityWarning)
        flight = mlt.simulate_mlt(LP_CHAPTER_2)
    assert flight.angle_of_attack_rad.max() < math.radians(mlt.MAX_SMALL_ANGLE_DEG)


# --- the output table ------------------------------------------------------------------------
def test_flight_table_matches_the_6dof():
    flight = mlt.simulate_mlt(LP_CHAPTER_2)
    with pytest.warns(TruncatedFlightWarning):
        six = sixdof.simulate_6dof(LP_CHAPTER_2, max_time_s=1.0, output_step_s=0.5)
    assert tuple(flight.columns) == tuple(six.columns) == BASE_COLUMNS + rigid_body.EXTRA_COLUMNS
    attrs = flight.attrs
    assert set(METADATA_KEYS) <= set(attrs) and set(METADATA_KEYS) <= set(six.attrs)
    assert attrs["engine"] == "MLT" and attrs["launch"] == LP_CHAPTER_2
    assert attrs["stop_reason"] == "impact"
    assert attrs["impact"] is True and abs(flight.altitude_m.iloc[-1]) < 1e-6
    assert attrs["time_of_flight_s"] == flight.time_s.iloc[-1]
    assert np.allclose(np.diff(flight.time_s.iloc[:-1]), 0.5)
    assert attrs["apogee_altitude_m"] == pytest.approx(flight.altitude_m.max(), abs=5.0)
    assert attrs["segment_length_m"] == 1000.0 and attrs["coefficients_at"] == "middle"
    # Each segment is 1000 m of (air-relative) arc: the path length counts the segments.
    speed = flight.speed_m_s.to_numpy()
    arc = float(np.sum(np.diff(flight.time_s) * (speed[1:] + speed[:-1]) / 2))
    assert attrs["steps"] - 1 < arc / 1000.0 * (1 + 1e-3) + 1e-9
    assert arc / 1000.0 * (1 - 1e-3) < attrs["steps"]
    assert flight.mach.iloc[0] == pytest.approx(
        math.hypot(2022.0, 5.0) / float(AIR.speed_of_sound(0.0))
    )


def test_table_rows_are_the_closed_form_of_their_segment():
    """The table's rows (the closed forms of eqs L2-L7, compiled) are the same closed forms
    run by Python, to rounding, across a segment in dense air with lateral motion."""
    model = rigid_body.rigid_body_model(LP, "two_segment", (0.0, 5.0, 0.0), "flat")
    state = tuple(_air_state(model, 0.8, 0.02, 2.0, -0.75, 0.03, z=-3e3).tolist())
    segment = mlt._solve_segment(model, state, 0.0, 1000.0 / model.d, "middle", True, False)
    times = np.linspace(0.0, segment.duration_s(model), 7)
    rows = mlt._states_at(model, [segment], times)
    calibres = times * segment.coefficients.speed / model.d
    python = np.array([segment.at(model, s) for s in calibres]).T
    assert np.max(np.abs(rows[7:9])) > 1.0  # lateral motion at work
    # each state to 1e-12 of its largest value across the segment
    scale = np.max(np.abs(python), axis=1, keepdims=True)
    assert np.all(np.abs(rows - python) <= 1e-12 * scale)


@pytest.mark.parametrize(
    "coefficients_at, per_segment", [("start", 1), ("middle", 2), ("average", 2)]
)
def test_rhs_evaluations_count_the_coefficient_evaluations(
    monkeypatch, coefficients_at, per_segment
):
    """Eq L8: the start's coefficients for the first pass, then the middle's or the end's."""
    calls, original = [], mlt.segment_coefficients

    def counted(*args, **kwargs):
        calls.append(args[1])
        return original(*args, **kwargs)

    monkeypatch.setattr(mlt, "segment_coefficients", counted)
    attrs = mlt.simulate_mlt(LP_CHAPTER_2, coefficients_at=coefficients_at).attrs
    assert attrs["rhs_evaluations"] == len(calls) == per_segment * attrs["steps"]


def test_linear_theory_limit_carries_the_shared_metadata(limit):
    attrs = limit.attrs
    assert set(METADATA_KEYS) <= set(attrs)
    assert attrs["engine"] == "linear-theory limit" and attrs["launch"] == LP_CHAPTER_2
    assert attrs["stop_reason"] == "impact" and attrs["impact"] is True
    assert abs(limit.altitude_m.iloc[-1]) < 1e-6
    # The apogee event lies between the rows: at or above the highest, within a metre of it.
    assert 0.0 <= attrs["apogee_altitude_m"] - limit.altitude_m.max() < 1.0
    top = limit.time_s[limit.altitude_m.idxmax()]
    assert abs(attrs["apogee_time_s"] - top) <= 0.25


@pytest.mark.parametrize("engine", _ENGINES)
def test_flight_cut_off_by_max_time_warns_and_says_why(engine):
    """Before its apogee: no impact, the table ends at max_time_s, no apogee recorded."""
    with pytest.warns(TruncatedFlightWarning, match="max_time_s = 20 s"):
        flight = _ENGINES[engine](LP_CHAPTER_2, max_time_s=20.0, output_step_s=5.0)
    attrs = flight.attrs
    assert set(METADATA_KEYS) <= set(attrs) and attrs["engine"] == engine
    assert attrs["stop_reason"] == "max_time" and attrs["impact"] is False
    assert math.isnan(attrs["apogee_time_s"]) and math.isnan(attrs["apogee_altitude_m"])
    assert list(flight.time_s) == pytest.approx([0.0, 5.0, 10.0, 15.0, 20.0], abs=1e-9)
    assert attrs["time_of_flight_s"] == pytest.approx(20.0, abs=1e-9)
    assert attrs["range_m"] == flight.ground_range_m.iloc[-1] > 0.0
    assert flight.altitude_m.iloc[-1] > 10e3


def test_segments_longer_than_the_updates_of_linear_theory_warn():
    with pytest.warns(ModelValidityWarning, match="segment_length_m = 20000 m"):
        mlt.simulate_mlt(LP_CHAPTER_2, segment_length_m=20_000.0)


@pytest.mark.parametrize("speed_m_s, elevation_deg", [(300.0, 89.9), (1000.0, 88.0)])
def test_a_flight_whose_linear_solution_diverges_is_refused_by_name(speed_m_s, elevation_deg):
    """Near the vertical the speed falls toward zero at apogee, and linear theory, which follows
    the arc length at one speed per segment, overflows (it raised OverflowError and
    ZeroDivisionError from deep inside, or failed in numpy's arange on a NaN time)."""
    launch = LP_CHAPTER_2.but(speed_m_s=speed_m_s, elevation_deg=elevation_deg, cross_wind_m_s=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        with pytest.raises(ValueError, match=r"MLT cannot fly LP at elevation_deg = 8.*diverges"):
            mlt.simulate_mlt(launch)
