"""The 3DOF simulation against independent physics: closed-form Kepler orbits in vacuum,
conservation laws, symmetry, scipy's own integrator, and convergence under refinement."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from harp_analysis import earth, kepler, threedof
from harp_analysis.drag import BASELINE_CONE, M829, TabulatedDragLaw, get_drag_law
from harp_analysis.projectiles import BASELINE, HP, get_projectile
from harp_analysis.validation import ModelValidityWarning


@pytest.fixture(scope="module")
def vacuum_flight():
    return threedof.simulate_3dof(BASELINE, 45.0, atmosphere="vacuum", rtol=1e-12)


def test_vacuum_flight_is_the_closed_form_kepler_orbit(vacuum_flight):
    conic = kepler.ballistic_conic(2157.0, np.radians(45.0))
    attrs = vacuum_flight.attrs
    assert attrs["apogee_altitude_m"] == pytest.approx(conic.apogee_altitude_m, rel=1e-6)
    assert attrs["range_m"] == pytest.approx(conic.ground_range_m, rel=1e-6)
    assert attrs["time_of_flight_s"] == pytest.approx(conic.time_of_flight_s, rel=1e-6)
    assert attrs["apogee_time_s"] == pytest.approx(conic.time_to_apogee_s, rel=1e-6)


def test_vacuum_flight_conserves_energy_and_angular_momentum(vacuum_flight):
    # Rows are interpolated between steps of up to 20 s (quintic Hermite), hence 1e-8.
    radius = vacuum_flight.altitude_m + earth.RADIUS_M
    energy = 0.5 * vacuum_flight.speed_m_s**2 - earth.GM_M3_S2 / radius
    momentum = vacuum_flight.specific_angular_momentum_m2_s
    assert np.ptp(energy) / abs(energy.mean()) < 1e-8
    assert np.ptp(momentum) / momentum.mean() < 1e-8


def test_rotating_earth_in_vacuum_flies_the_inertial_conic():
    """On a rotating Earth the inertial launch velocity is the ground velocity plus the
    surface's (omega R cos(latitude), eastward); in vacuum that fixes the conic."""
    omega = earth.ROTATION_RATE_RAD_S
    flight = threedof.simulate_3dof(
        BASELINE,
        60.0,
        latitude_deg=0.0,
        bearing_deg=90.0,
        atmosphere="vacuum",
        rotation_rate_rad_s=omega,
        rtol=1e-12,
    )
    east, up = (
        2157.0 * np.cos(np.radians(60.0)) + omega * earth.RADIUS_M,
        2157.0 * np.sin(np.radians(60.0)),
    )
    conic = kepler.ballistic_conic(np.hypot(east, up), np.arctan2(up, east))
    assert flight.speed_m_s[0] == pytest.approx(np.hypot(east, up), rel=1e-12)
    assert flight.attrs["apogee_altitude_m"] == pytest.approx(conic.apogee_altitude_m, rel=1e-6)
    assert flight.attrs["time_of_flight_s"] == pytest.approx(conic.time_of_flight_s, rel=1e-6)
    # The ground has turned under the orbit: the Earth-fixed range falls short of the inertial.
    assert flight.attrs["range_m"] == pytest.approx(
        conic.ground_range_m - omega * earth.RADIUS_M * conic.time_of_flight_s, rel=1e-6
    )


@pytest.fixture(scope="module")
def baseline_flights():
    return {
        rtol: threedof.simulate_3dof(BASELINE, 45.0, rtol=rtol) for rtol in (1e-8, 1e-10, 1e-12)
    }


def test_apogee_and_range_converge_to_a_metre(baseline_flights):
    reference = baseline_flights[1e-12].attrs
    for rtol in (1e-8, 1e-10):
        attrs = baseline_flights[rtol].attrs
        assert abs(attrs["apogee_altitude_m"] - reference["apogee_altitude_m"]) < 1.0
        assert abs(attrs["range_m"] - reference["range_m"]) < 1.0


def test_agrees_with_scipy_solve_ivp(baseline_flights):
    """The same equations through scipy's own DOP853 and event location."""
    flight = baseline_flights[1e-12]
    area, mass = BASELINE.reference_area_m2, BASELINE.mass_kg
    from harp_analysis.atmosphere import get_atmosphere

    air = get_atmosphere("two_segment")

    def rhs(t, y):
        r, v = y[:3], y[3:]
        radius = np.linalg.norm(r)
        speed = np.linalg.norm(v)
        cd = BASELINE_CONE(speed / air.sound_kernel(radius - earth.RADIUS_M))
        drag = 0.5 * air.density_kernel(radius - earth.RADIUS_M) * cd * area / mass * speed
        return np.concatenate([v, -earth.GM_M3_S2 * r / radius**3 - drag * v])

    def impact(t, y):
        return np.linalg.norm(y[:3]) - earth.RADIUS_M if t > 1 else 1.0

    impact.terminal, impact.direction = True, -1
    elevation = np.radians(45.0)
    y0 = [earth.RADIUS_M, 0, 0, 2157 * np.sin(elevation), 2157 * np.cos(elevation), 0]
    reference = solve_ivp(
        rhs, (0, 1000), y0, method="DOP853", rtol=1e-12, atol=1e-9, events=impact, dense_output=True
    )
    t_impact = reference.t_events[0][0]
    assert flight.attrs["time_of_flight_s"] == pytest.approx(t_impact, abs=1e-6)
    times = flight.time_s.to_numpy()[::25]
    expected = reference.sol(times)
    assert np.max(np.abs(flight[["x_m", "y_m", "z_m"]].to_numpy()[::25].T - expected[:3])) < 0.01


@pytest.mark.parametrize("latitude_deg, bearing_deg", [(0, 90), (45, 0), (-30, 270), (60, 123)])
def test_no_cross_range_without_rotation_or_wind(latitude_deg, bearing_deg):
    flight = threedof.simulate_3dof(
        BASELINE, 65.0, latitude_deg=latitude_deg, bearing_deg=bearing_deg, output_step_s=5.0
    )
    assert np.max(np.abs(flight.cross_range_m)) < 1e-6
    assert flight.attrs["range_m"] == pytest.approx(
        threedof.simulate_3dof(BASELINE, 65.0).attrs["range_m"], rel=1e-8
    )


def test_winds_push_the_way_they_blow():
    calm = threedof.simulate_3dof(BASELINE, 45.0, output_step_s=10.0).attrs
    cross = threedof.simulate_3dof(BASELINE, 45.0, cross_wind_m_s=6.0, output_step_s=10.0).attrs
    head = threedof.simulate_3dof(BASELINE, 45.0, head_wind_m_s=6.0, output_step_s=10.0).attrs
    assert cross["cross_range_m"] > 1.0  # drifts to the right, downwind
    assert head["range_m"] < calm["range_m"]


def test_batch_matches_single_launches():
    # Same scheme and tolerances; steps may differ by rounding, within rtol = 1e-10 (~1 cm).
    elevations = np.array([30.0, 45.0, 65.0, 85.0])
    batch = threedof.simulate_3dof_batch(BASELINE, elevations, rtol=1e-10)
    for elevation, row in zip(elevations, batch.itertuples()):
        single = threedof.simulate_3dof(BASELINE, elevation, rtol=1e-10).attrs
        assert row.apogee_altitude_m == pytest.approx(single["apogee_altitude_m"], abs=0.05)
        assert row.range_m == pytest.approx(single["range_m"], abs=0.05)


def test_table_has_the_shared_columns_and_physical_values():
    flight = threedof.simulate_3dof(HP, 50.0)
    from harp_analysis.trajectory import BASE_COLUMNS

    assert tuple(flight.columns) == BASE_COLUMNS
    assert flight.altitude_m.iloc[0] == 0.0 and abs(flight.altitude_m.iloc[-1]) < 1e-3
    assert flight.mach.iloc[0] == pytest.approx(2022.0 / 340.1, rel=1e-3)
    assert flight.drag_coefficient.iloc[0] == pytest.approx(
        -np.interp(flight.mach.iloc[0], M829.mach, M829.cx0)
    )
    # Drag only removes angular momentum: it never increases along the flight.
    assert np.all(np.diff(flight.specific_angular_momentum_m2_s) <= 1e-6)


def test_escape_or_short_time_ends_cleanly():
    with pytest.warns(ModelValidityWarning, match="did not return"):
        short = threedof.simulate_3dof(BASELINE, 45.0, max_time_s=20.0)
    assert not short.attrs["impact"] and short.time_s.iloc[-1] == pytest.approx(20.0)
    with pytest.warns(ModelValidityWarning):
        escape = threedof.simulate_3dof(BASELINE, 90.0, speed_m_s=15_000.0, max_time_s=500.0)
    assert np.isnan(escape.attrs["apogee_time_s"])


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"elevation_deg": 0.0}, "elevation_deg"),
        ({"elevation_deg": 91.0}, "elevation_deg"),
        ({"elevation_deg": np.nan}, "elevation_deg"),
        ({"speed_m_s": -5.0}, "speed_m_s"),
        ({"latitude_deg": 95.0}, "latitude_deg"),
        ({"bearing_deg": 360.0}, "bearing_deg"),
        ({"atmosphere": "martian"}, "atmosphere"),
        ({"drag_law": "brick"}, "drag_law"),
        ({"rtol": 0.0}, "rtol"),
        ({"output_step_s": 0.0}, "output_step_s"),
        ({"head_wind_m_s": np.inf}, "head_wind_m_s"),
    ],
)
def test_bad_input_is_named(kwargs, name):
    arguments = {"elevation_deg": 45.0} | kwargs
    with pytest.raises((ValueError, TypeError), match=name):
        threedof.simulate_3dof(BASELINE, **arguments)


def test_bad_projectile_is_named():
    with pytest.raises(ValueError, match="projectile 'bullet'"):
        get_projectile("bullet")
    with pytest.raises(TypeError, match="projectile"):
        threedof.simulate_3dof("HP", 45.0)
    from harp_analysis.projectiles import Projectile

    for name in ("mass_kg", "reference_area_m2", "launch_speed_m_s"):
        values = dict(
            name="x",
            mass_kg=1.0,
            reference_area_m2=1.0,
            drag_law=BASELINE_CONE,
            launch_speed_m_s=1.0,
            source="",
        ) | {name: 0.0}
        with pytest.raises(ValueError, match=name):
            Projectile(**values)


# --- drag laws --------------------------------------------------------------------------------
def test_eq_4_8():
    assert BASELINE_CONE(0.0) == pytest.approx(0.091)
    assert BASELINE_CONE(100.0) == pytest.approx(0.014)


def test_m829_zero_yaw_drag_is_minus_cx0_and_holds_outside_the_table():
    law = get_drag_law("m829")
    assert law(np.array(M829.mach)) == pytest.approx(-np.array(M829.cx0))
    assert law(4.5) == pytest.approx(0.5 * (0.69 + 0.543))
    assert law(12.0) == pytest.approx(0.449)  # held, where MATLAB's interp1 returns NaN
    strict = TabulatedDragLaw(M829.mach, tuple(-c for c in M829.cx0), outside="raise")
    with pytest.raises(ValueError, match="mach"):
        strict(12.0)
    with pytest.raises(ValueError, match="mach"):
        law(-1.0)
    with pytest.raises(ValueError, match="mach table"):
        TabulatedDragLaw((0.0, 0.0), (1.0, 1.0))
