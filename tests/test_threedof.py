"""The 3DOF simulation against independent physics: closed-form Kepler orbits in vacuum,
conservation laws, symmetry, scipy's own integrator, and convergence under refinement."""

import dataclasses
import math
import warnings

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from harp_analysis.engines import kepler, threedof
from harp_analysis.foundation import earth
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models import trajectory
from harp_analysis.models.atmosphere import two_segment_speed_of_sound
from harp_analysis.models.drag import BASELINE_CONE, M829, TabulatedDragLaw, get_drag_law
from harp_analysis.models.launch import Launch, Launches, baseline_chapter_4
from harp_analysis.models.projectiles import BASELINE, HP, Projectile, get_projectile

#: Chapter 4 B's baseline cone at 2157 m/s and 45 deg, no wind, two-segment air.
BASELINE_45 = Launch(BASELINE, 2157.0, 45.0)


@pytest.fixture(scope="module")
def vacuum_flight():
    return threedof.simulate_3dof(Launch(BASELINE, 2157.0, 45.0, atmosphere="vacuum"), rtol=1e-12)


def test_vacuum_flight_is_the_closed_form_kepler_orbit(vacuum_flight):
    conic = kepler.ballistic_conic(2157.0, np.radians(45.0))
    attrs = vacuum_flight.attrs
    assert attrs["apogee_altitude_m"] == pytest.approx(conic.apogee_altitude_m, rel=1e-6)
    assert attrs["range_m"] == pytest.approx(conic.ground_range_m, rel=1e-6)
    assert attrs["time_of_flight_s"] == pytest.approx(conic.time_of_flight_s, rel=1e-6)
    assert attrs["apogee_time_s"] == pytest.approx(conic.time_to_apogee_s, rel=1e-6)


@pytest.mark.parametrize("elevation_deg", [1e-4, 1e-3, 0.01, 0.1])
def test_a_grazing_shot_lands_where_the_conic_meets_the_ground(elevation_deg):
    # It rises micrometres to metres within its first step; a shot that starts on the ground
    # must still be seen to fall back through it, not fly on underground (issue 25).
    launch = Launch(BASELINE, 2157.0, elevation_deg, atmosphere="vacuum")
    conic = kepler.ballistic_conic(2157.0, np.radians(elevation_deg))
    flight = threedof.simulate_3dof(launch)
    flights = threedof.fly_3dof([launch])
    assert flight.attrs["impact"] and bool(flights.impact[0])
    assert flight.altitude_m.min() > -1e-6
    # positions are integrated to rtol 1e-9 of the Earth's radius (6 mm): a rise of 0.7 um at
    # 1e-4 deg lands within centimetres
    assert flight.attrs["range_m"] == pytest.approx(conic.ground_range_m, rel=1e-3, abs=0.03)
    assert flights.range_m[0] == pytest.approx(conic.ground_range_m, rel=1e-3, abs=0.03)


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
    launch = Launch(
        BASELINE,
        2157.0,
        60.0,
        latitude_deg=0.0,
        bearing_deg=90.0,
        atmosphere="vacuum",
        rotation_rate_rad_s=omega,
    )
    flight = threedof.simulate_3dof(launch, rtol=1e-12)
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


def test_raised_site_in_vacuum_flies_the_conic_from_its_radius():
    """From a site 1000 m up the flight is the Kepler conic of radius R + 1000 m, back down to
    that radius; energy is conserved along it."""
    flight = threedof.simulate_3dof(
        Launch(BASELINE, 2157.0, 45.0, site_altitude_m=1000.0, atmosphere="vacuum"), rtol=1e-12
    )
    conic = kepler.ballistic_conic(2157.0, np.radians(45.0), radius_m=earth.RADIUS_M + 1000.0)
    attrs = flight.attrs
    assert flight.altitude_m.iloc[0] == pytest.approx(1000.0, abs=1e-6)
    assert abs(flight.altitude_m.iloc[-1] - 1000.0) < 1e-3
    assert attrs["apogee_altitude_m"] == pytest.approx(conic.apogee_altitude_m, rel=1e-6)
    assert attrs["range_m"] == pytest.approx(conic.ground_range_m, rel=1e-6)
    assert attrs["time_of_flight_s"] == pytest.approx(conic.time_of_flight_s, rel=1e-6)
    assert attrs["apogee_time_s"] == pytest.approx(conic.time_to_apogee_s, rel=1e-6)
    radius = flight.altitude_m + earth.RADIUS_M
    energy = 0.5 * flight.speed_m_s**2 - earth.GM_M3_S2 / radius
    assert np.ptp(energy) / abs(energy.mean()) < 1e-9


def test_raised_site_in_air_lands_back_at_the_site_altitude():
    raised = threedof.simulate_3dof(BASELINE_45.but(site_altitude_m=1000.0), output_step_s=5.0)
    assert raised.altitude_m.iloc[0] == pytest.approx(1000.0, abs=1e-6)
    assert abs(raised.altitude_m.iloc[-1] - 1000.0) < 1e-3
    assert raised.attrs["stop_reason"] == "impact"
    # Thinner air at the gun: it flies higher than the same shot from sea level.
    sea_level = threedof.simulate_3dof(BASELINE_45, output_step_s=5.0)
    assert raised.attrs["apogee_altitude_m"] > sea_level.attrs["apogee_altitude_m"] + 1000.0


@pytest.fixture(scope="module")
def baseline_flights():
    return {rtol: threedof.simulate_3dof(BASELINE_45, rtol=rtol) for rtol in (1e-8, 1e-10, 1e-12)}


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
    from harp_analysis.models.atmosphere import get_atmosphere

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
    launch = Launch(BASELINE, 2157.0, 65.0, latitude_deg=latitude_deg, bearing_deg=bearing_deg)
    flight = threedof.simulate_3dof(launch, output_step_s=5.0)
    assert np.max(np.abs(flight.cross_range_m)) < 1e-6
    assert flight.attrs["range_m"] == pytest.approx(
        threedof.simulate_3dof(Launch(BASELINE, 2157.0, 65.0)).attrs["range_m"], rel=1e-8
    )


def test_winds_push_the_way_they_blow():
    calm = threedof.simulate_3dof(BASELINE_45, output_step_s=10.0).attrs
    cross = threedof.simulate_3dof(BASELINE_45.but(cross_wind_m_s=6.0), output_step_s=10.0).attrs
    head = threedof.simulate_3dof(BASELINE_45.but(head_wind_m_s=6.0), output_step_s=10.0).attrs
    assert cross["cross_range_m"] > 1.0  # drifts to the right, downwind
    assert head["range_m"] < calm["range_m"]


def test_batch_matches_single_launches():
    # Same scheme and tolerances; steps may differ by rounding, within rtol = 1e-10 (~1 cm).
    elevations = np.array([30.0, 45.0, 65.0, 85.0])
    launches = [BASELINE_45.but(elevation_deg=elevation) for elevation in elevations]
    batch = threedof.simulate_3dof_batch(launches, rtol=1e-10)
    assert batch.elevation_deg.tolist() == elevations.tolist()
    assert batch.stop_reason.tolist() == ["impact"] * len(elevations)
    for launch, row in zip(launches, batch.itertuples()):
        single = threedof.simulate_3dof(launch, rtol=1e-10).attrs
        assert row.apogee_altitude_m == pytest.approx(single["apogee_altitude_m"], abs=0.05)
        assert row.range_m == pytest.approx(single["range_m"], abs=0.05)


def test_batch_of_one_launch_is_accepted():
    batch = threedof.simulate_3dof_batch(BASELINE_45, rtol=1e-10)
    single = threedof.simulate_3dof(BASELINE_45, rtol=1e-10).attrs
    assert len(batch) == 1
    assert batch.range_m[0] == pytest.approx(single["range_m"], abs=0.05)


@pytest.mark.parametrize(
    "changes, name",
    [
        ({"projectile": HP}, "projectile"),
        (
            {"projectile": dataclasses.replace(BASELINE, drag_law=get_drag_law("m829"))},
            "projectile",
        ),
        ({"atmosphere": "vacuum"}, "atmosphere"),
        ({"rotation_rate_rad_s": earth.ROTATION_RATE_RAD_S}, "rotation_rate_rad_s"),
        ({"site_altitude_m": 1000.0}, "site_altitude_m"),
    ],
)
def test_batch_refuses_launches_that_cannot_share_it(changes, name):
    with pytest.raises(ValueError, match=rf"launches\[1\]\.{name}"):
        threedof.simulate_3dof_batch([BASELINE_45, BASELINE_45.but(**changes)])


def test_batch_refuses_an_empty_list_and_non_launches():
    with pytest.raises(ValueError, match="at least one Launch"):
        threedof.simulate_3dof_batch([])
    with pytest.raises(TypeError, match=r"launches\[1\] must be a Launch"):
        threedof.simulate_3dof_batch([BASELINE_45, 60.0])
    for misuse in (BASELINE, "HP", 45.0):
        with pytest.raises(TypeError, match="Launch"):
            threedof.simulate_3dof_batch(misuse)


def test_table_has_the_shared_columns_and_physical_values():
    launch = Launch(HP, 2022.0, 50.0)
    flight = threedof.simulate_3dof(launch)

    assert tuple(flight.columns) == trajectory.BASE_COLUMNS
    assert flight.altitude_m.iloc[0] == 0.0 and abs(flight.altitude_m.iloc[-1]) < 1e-3
    assert flight.mach.iloc[0] == pytest.approx(2022.0 / 340.1, rel=1e-3)
    assert flight.mach.iloc[0] == pytest.approx(launch.launch_mach, rel=1e-12)
    assert flight.drag_coefficient.iloc[0] == pytest.approx(
        -np.interp(flight.mach.iloc[0], M829.mach, M829.cx0)
    )
    assert flight.drag_coefficient.iloc[0] == pytest.approx(launch.launch_drag_coefficient)
    # Drag only removes angular momentum: it never increases along the flight.
    assert np.all(np.diff(flight.specific_angular_momentum_m2_s) <= 1e-6)


def test_metadata_of_a_flight_that_lands(baseline_flights):
    flight = baseline_flights[1e-8]
    attrs = flight.attrs
    assert set(trajectory.METADATA_KEYS) <= set(attrs)
    assert attrs["engine"] == "3DOF" and attrs["launch"] == BASELINE_45
    assert attrs["impact"] is True and attrs["stop_reason"] == "impact"
    assert attrs["stop_reason"] in trajectory.STOP_REASONS
    assert attrs["rhs_evaluations"] > attrs["steps"] > 0
    assert attrs["time_of_flight_s"] == flight.time_s.iloc[-1]
    assert attrs["range_m"] == flight.ground_range_m.iloc[-1]
    assert attrs["cross_range_m"] == flight.cross_range_m.iloc[-1]
    assert attrs["impact_speed_m_s"] == flight.speed_m_s.iloc[-1]
    assert 0 < attrs["apogee_time_s"] < attrs["time_of_flight_s"]
    # The apogee event lies between rows 0.5 s apart: above the highest row by < g (0.25 s)^2 / 2.
    assert 0.0 <= attrs["apogee_altitude_m"] - flight.altitude_m.max() < 0.31
    with warnings.catch_warnings():
        warnings.simplefilter("error", trajectory.TruncatedFlightWarning)
        threedof.simulate_3dof(BASELINE_45, output_step_s=10.0)


def test_escape_or_short_time_ends_cleanly():
    assert issubclass(trajectory.TruncatedFlightWarning, ModelValidityWarning)
    with pytest.warns(trajectory.TruncatedFlightWarning, match="did not return"):
        short = threedof.simulate_3dof(BASELINE_45, max_time_s=20.0)
    assert not short.attrs["impact"] and short.time_s.iloc[-1] == pytest.approx(20.0)
    assert set(trajectory.METADATA_KEYS) <= set(short.attrs)
    assert short.attrs["stop_reason"] == "max_time"
    assert short.attrs["time_of_flight_s"] == pytest.approx(20.0)
    with pytest.warns(trajectory.TruncatedFlightWarning):
        escape = threedof.simulate_3dof(Launch(BASELINE, 15_000.0, 90.0), max_time_s=500.0)
    assert np.isnan(escape.attrs["apogee_time_s"])
    assert escape.attrs["stop_reason"] == "max_time"
    with pytest.warns(trajectory.TruncatedFlightWarning, match="1 of 2"):
        batch = threedof.simulate_3dof_batch(
            [BASELINE_45.but(elevation_deg=85.0), BASELINE_45.but(elevation_deg=5.0)],
            max_time_s=60.0,
        )
    assert batch.stop_reason.tolist() == ["max_time", "impact"]
    assert batch.impact.tolist() == [False, True]


@pytest.mark.parametrize(
    "changes, name",
    [
        ({"elevation_deg": 0.0}, "elevation_deg"),
        ({"elevation_deg": 91.0}, "elevation_deg"),
        ({"elevation_deg": np.nan}, "elevation_deg"),
        ({"speed_m_s": -5.0}, "speed_m_s"),
        ({"latitude_deg": 95.0}, "latitude_deg"),
        ({"bearing_deg": 360.0}, "bearing_deg"),
        ({"atmosphere": "martian"}, "atmosphere"),
        ({"head_wind_m_s": np.inf}, "head_wind_m_s"),
        ({"density_change_fraction": -0.7}, "density_change_fraction"),
        ({"temperature_change_k": 100.0}, "temperature_change_k"),
    ],
)
def test_bad_launch_is_named(changes, name):
    arguments = {"projectile": BASELINE, "speed_m_s": 2157.0, "elevation_deg": 45.0} | changes
    with pytest.raises((ValueError, TypeError), match=name):
        Launch(**arguments)
    with pytest.raises((ValueError, TypeError), match=name):
        BASELINE_45.but(**changes)  # validated again


def test_bad_drag_law_override_is_named():
    # A drag-law override is a projectile override; a name is not a drag law.
    with pytest.raises(TypeError, match="drag_law"):
        Launch(dataclasses.replace(BASELINE, drag_law="brick"), 2157.0, 45.0)


@pytest.mark.parametrize(
    "options, name",
    [
        ({"rtol": 0.0}, "rtol"),
        ({"output_step_s": 0.0}, "output_step_s"),
        ({"max_time_s": -1.0}, "max_time_s"),
        ({"rtol": np.nan}, "rtol"),
    ],
)
def test_bad_numerical_option_is_named(options, name):
    with pytest.raises((ValueError, TypeError), match=name):
        threedof.simulate_3dof(BASELINE_45, **options)


def test_bad_projectile_is_named():
    with pytest.raises(ValueError, match="projectile 'bullet'"):
        get_projectile("bullet")
    with pytest.raises(TypeError, match="projectile"):
        Launch("HP", 2022.0, 45.0)
    # The pre-Launch calls are refused, naming what is wanted.
    for misuse in ("HP", BASELINE, [BASELINE_45], None):
        with pytest.raises(TypeError, match="launch must be a Launch"):
            threedof.simulate_3dof(misuse)
    with pytest.raises(TypeError, match="positional argument"):
        threedof.simulate_3dof("HP", 45.0)
    for old in ("elevation_deg", "speed_m_s", "atmosphere", "cross_wind_m_s", "drag_law"):
        with pytest.raises(TypeError, match=old):
            threedof.simulate_3dof(BASELINE_45, **{old: 1.0})

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


# --- Launch construction, fuzzed ----------------------------------------------------------------
#: The documented bounds of each numeric Launch field: (low, high, low closed, high closed).
LAUNCH_BOUNDS = {
    "speed_m_s": (0.0, math.inf, False, True),
    "elevation_deg": (0.0, 90.0, False, True),
    "bearing_deg": (0.0, 360.0, True, False),
    "latitude_deg": (-90.0, 90.0, True, True),
    "longitude_deg": (-180.0, 360.0, True, True),
    "site_altitude_m": (-500.0, 10_000.0, True, True),
    "cross_wind_m_s": (-100.0, 100.0, True, True),
    "head_wind_m_s": (-100.0, 100.0, True, True),
    "spin_rad_s": (-math.inf, math.inf, True, True),
    "rotation_rate_rad_s": (-1e-3, 1e-3, True, True),
    "density_change_fraction": (-0.5, 0.5, True, True),
    "temperature_change_k": (-60.0, 60.0, True, True),
}

_FUZZ_VALUES = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(min_value=-400.0, max_value=400.0),
    st.floats(min_value=-2e-3, max_value=2e-3),
    st.integers(),
    st.floats(allow_nan=True, allow_infinity=True).map(np.float64),
    st.text(max_size=5),
    st.none(),
    st.booleans(),
)


@settings(max_examples=200, deadline=None)
@given(name=st.sampled_from(sorted(LAUNCH_BOUNDS)), value=_FUZZ_VALUES)
@example(name="speed_m_s", value=2**1000)
@example(name="elevation_deg", value="50")
@example(name="bearing_deg", value=360.0)
@example(name="rotation_rate_rad_s", value=True)
def test_launch_fields_are_finite_and_in_bounds_or_named(name, value):
    arguments = {"projectile": BASELINE, "speed_m_s": 2157.0, "elevation_deg": 45.0}
    try:
        launch = Launch(**(arguments | {name: value}))
    except (TypeError, ValueError) as error:
        assert name in str(error)
        return
    low, high, low_closed, high_closed = LAUNCH_BOUNDS[name]
    field = getattr(launch, name)
    assert type(field) is float and math.isfinite(field)
    assert field == float(value) and not isinstance(value, bool | str)
    assert (low <= field) if low_closed else (low < field)
    assert (field <= high) if high_closed else (field < high)


@pytest.mark.parametrize("value", [10**400, -(10**400)], ids=["+1e400", "-1e400"])
def test_launch_field_beyond_the_float_range_is_named(value):
    with pytest.raises(ValueError, match="spin_rad_s"):
        Launch(BASELINE, 2157.0, 45.0, spin_rad_s=value)


def test_a_warmer_day_lowers_the_mach_number_as_the_speed_of_sound_of_warmer_air():
    """a^2 = gamma R T: 30 K warmer air at every height (the launch's speed of sound and the
    flight's Mach column both follow; the Mach-dependent Cd then changes the flight)."""
    warm = BASELINE_45.but(temperature_change_k=30.0)
    gamma_r = 1.4 * 287.05287
    for altitude_m in (0.0, 20e3):
        sound = two_segment_speed_of_sound(altitude_m)
        assert warm.air(altitude_m)[1] == pytest.approx(np.sqrt(sound**2 + gamma_r * 30.0))
    assert warm.launch_mach == pytest.approx(
        2157.0 / np.sqrt(two_segment_speed_of_sound(0.0) ** 2 + gamma_r * 30.0)
    )
    table = threedof.simulate_3dof(warm, output_step_s=5.0)
    air_speed = table.mach * np.sqrt(
        two_segment_speed_of_sound(table.altitude_m.clip(0)) ** 2 + gamma_r * 30.0
    )
    speed = table.speed_m_s
    assert np.allclose(air_speed, speed, rtol=1e-9)  # no wind: the air speed is the speed


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


@pytest.mark.parametrize("rising", [False, True])
def test_a_flight_can_end_where_it_crosses_an_altitude(rising):
    """fly_3dof ends on the way down (or up) through end_altitude_m: there the radius is
    R + that altitude; a rising crossing ends the flight before its apogee, a falling one after
    it, at the time the full flight passes that altitude."""
    flights = threedof.fly_3dof(BASELINE_45, end_altitude_m=30e3, rising=rising)
    radius = np.linalg.norm(flights.end_position_m[:, 0])
    assert flights.impact[0]
    assert radius - earth.RADIUS_M == pytest.approx(30e3, abs=1e-4)
    assert np.isnan(flights.apogee_time_s[0]) == rising
    table = threedof.simulate_3dof(BASELINE_45, output_step_s=0.01)
    climbing = table.time_s < table.attrs["apogee_time_s"]
    half = table[climbing if rising else ~climbing]
    height = half.altitude_m if rising else -half.altitude_m  # increasing, for np.interp
    crossing = np.interp(30e3 if rising else -30e3, height, half.time_s)
    assert flights.time_of_flight_s[0] == pytest.approx(crossing, abs=1e-3)


@pytest.mark.parametrize("rising", [False, True])
def test_an_end_altitude_the_flight_never_crosses_ends_it_at_the_ground(rising):
    """Asked to end 500 km up, far above its apogee, a flight never crosses that altitude: it
    ends where it would anyway, back at the site's altitude (the same range and time as the
    plain flight), not underground at max_time_s, and warns, quoting its apogee."""
    plain = threedof.fly_3dof(BASELINE_45)
    way = "climbs" if rising else "comes down"
    with pytest.warns(trajectory.EndAltitudeNotCrossedWarning) as caught:
        flights = threedof.fly_3dof(BASELINE_45, end_altitude_m=500e3, rising=rising)
    (message,) = [str(w.message) for w in caught]
    apogee_km = plain.apogee_altitude_m[0] / 1e3
    assert f"never {way} through end_altitude_m = 500 km (its apogee: {apogee_km:.4g} km)" in (
        message
    )
    assert not flights.impact[0] and flights.stop_reason[0] == "ground_before_end"
    assert np.linalg.norm(flights.end_position_m[:, 0]) == pytest.approx(earth.RADIUS_M, abs=1e-3)
    assert flights.range_m[0] == pytest.approx(plain.range_m[0], abs=1e-3)
    assert flights.time_of_flight_s[0] == pytest.approx(plain.time_of_flight_s[0], abs=1e-6)
    assert flights.apogee_altitude_m[0] == pytest.approx(plain.apogee_altitude_m[0], abs=1e-3)


@pytest.mark.parametrize("rising", [False, True])
def test_a_grazing_shot_asked_to_end_above_it_lands_where_it_would(rising):
    """A shot 0.01 deg above the horizon rises millimetres and falls back within its first
    step: the ground must still be seen, not crossed twice unseen."""
    launch = Launch(BASELINE, 2157.0, 0.01, atmosphere="vacuum")
    conic = kepler.ballistic_conic(2157.0, np.radians(0.01))
    with pytest.warns(trajectory.EndAltitudeNotCrossedWarning):
        flights = threedof.fly_3dof(launch, end_altitude_m=1e3, rising=rising)
    assert flights.stop_reason[0] == "ground_before_end"
    assert flights.range_m[0] == pytest.approx(conic.ground_range_m, rel=1e-3, abs=0.03)


def test_a_flight_that_tops_out_just_above_its_end_altitude_rises_through_it():
    """However little its apogee clears its end altitude, a flight asked to end where it rises
    through it does, before its apogee, at that altitude; a millimetre above the apogee it
    never does. The apogee is the same launch's, flown down to the ground. (A step over the
    apogee sags tens of metres below it: stepped over unseen, such crossings came out as shots
    that never got there, and fire control's ascending roots near grazing were lost.)"""
    launch = BASELINE_45.but(elevation_deg=20.0)
    plain = threedof.fly_3dof(launch)
    top, top_time = plain.apogee_altitude_m[0], plain.apogee_time_s[0]
    clearances = np.geomspace(1e-3, 200.0, 60)  # m below the apogee
    with warnings.catch_warnings():
        warnings.simplefilter("error", trajectory.EndAltitudeNotCrossedWarning)
        flights = threedof.fly_3dof(
            [launch] * clearances.size, end_altitude_m=top - clearances, rising=True
        )
    assert flights.impact.all(), clearances[~flights.impact]
    radii = np.linalg.norm(flights.end_position_m, axis=0)
    assert radii - earth.RADIUS_M == pytest.approx(top - clearances, abs=1e-4)
    assert (flights.time_of_flight_s < top_time).all()
    with pytest.warns(trajectory.EndAltitudeNotCrossedWarning, match="never climbs"):
        above = threedof.fly_3dof(launch, end_altitude_m=top + 1e-3, rising=True)
    assert not above.impact[0]


def test_a_batch_names_the_launches_that_never_cross_their_end_altitude():
    """Per launch: the 20 deg shot (apogee about 20 km) never comes down through 50 km, the
    70 deg one never climbs through 500 km; the others end at their crossings as if flown
    alone, and the warning counts and names the two."""
    elevations = [20.0, 45.0, 70.0, 85.0]
    ends = np.array([50e3, 50e3, 500e3, 150e3])
    rising = np.array([False, False, True, True])
    launches = [BASELINE_45.but(elevation_deg=e) for e in elevations]
    with pytest.warns(trajectory.EndAltitudeNotCrossedWarning) as caught:
        flights = threedof.fly_3dof(launches, end_altitude_m=ends, rising=rising)
    (message,) = [str(w.message) for w in caught]
    assert message.startswith("2 of 4 3DOF flights never cross their end altitude (launches 0, 2)")
    assert "launch 0 never comes down through end_altitude_m = 50 km" in message
    assert "launch 2 never climbs through end_altitude_m = 500 km" in message
    assert flights.stop_reason.tolist() == ["ground_before_end", "impact"] * 2
    for i in (1, 3):
        alone = threedof.fly_3dof(launches[i], end_altitude_m=ends[i], rising=rising[i])
        assert flights.range_m[i] == alone.range_m[0]
        assert flights.time_of_flight_s[i] == alone.time_of_flight_s[0]
    radii = np.linalg.norm(flights.end_position_m[:, [0, 2]], axis=0)
    assert radii == pytest.approx(earth.RADIUS_M, abs=1e-3)


def test_an_end_altitude_below_the_site_is_reached_below_it():
    """From a gun 1 km up, a target at sea level lies below the site: the flight comes down
    through the site's altitude and on to the target's (the ground there is not the site's),
    while a flight asked to rise through sea level never can and ends at the site's altitude."""
    raised = BASELINE_45.but(site_altitude_m=1e3)
    with warnings.catch_warnings():
        warnings.simplefilter("error", trajectory.EndAltitudeNotCrossedWarning)
        low = threedof.fly_3dof(raised, end_altitude_m=0.0)
    site = threedof.fly_3dof(raised)
    assert low.impact[0] and low.stop_reason[0] == "impact"
    assert np.linalg.norm(low.end_position_m[:, 0]) == pytest.approx(earth.RADIUS_M, abs=1e-3)
    assert low.range_m[0] > site.range_m[0] and low.time_of_flight_s[0] > site.time_of_flight_s[0]
    with pytest.warns(trajectory.EndAltitudeNotCrossedWarning, match="site's altitude, 1000 m"):
        up = threedof.fly_3dof(raised, end_altitude_m=0.0, rising=True)
    assert up.stop_reason[0] == "ground_before_end"
    assert up.range_m[0] == pytest.approx(site.range_m[0], abs=1e-3)


def test_an_end_altitude_below_any_ground_is_refused_by_name():
    with pytest.raises(ValueError, match=r"end_altitude_m must lie in \[-500, inf\] m"):
        threedof.fly_3dof(BASELINE_45, end_altitude_m=-150e3)
    with pytest.raises(ValueError, match="end_altitude_m"):
        threedof.fly_3dof([BASELINE_45, BASELINE_45], end_altitude_m=[0.0, -1e3])


def test_a_step_cut_at_the_density_jump_carries_the_flight_across():
    """The two-segment air's density jumps by 0.05 % at 10.769 km. A step cut short of it is
    carried across, so the next flies the far side's formulas from its first stage: the
    baseline cone at 45 deg takes 484 evaluations, as the benchmark's lean reference does
    (one layer per step, steps cut on the jump). Starting the next step on the near side cost
    686: its first stage's O(h) error was rejected away, and steps of microseconds grew back."""
    flight = threedof.fly_3dof(baseline_chapter_4(45.0))
    assert flight.rhs_evaluations[0] <= 500
    steps = threedof.simulate_3dof(baseline_chapter_4(45.0)).attrs["steps"]
    assert steps <= 35  # 47 when steps of microseconds grew back twice


def test_a_flight_through_the_drag_tables_nodes_converges_at_the_default_tolerance():
    """Cd(Mach) of Appendix B's table turns at each node (Mach 1, 1.5, ... 8). The step
    control's error estimate assumes a smooth right-hand side and misses the turn, so a step
    across a node must end on it. Convergence: HP rounds at random from Barbados on the
    rotating Earth, flown at the default rtol 1e-9, agree with rtol 1e-12 to 5 cm of apogee and
    20 cm of range (without steps ended on the nodes, 0.6 m and 1.8 m on 300 such launches)."""
    rng = np.random.default_rng(1)
    launches = Launches(
        HP,
        rng.uniform(1000.0, 2200.0, 60),
        rng.uniform(20.0, 88.0, 60),
        bearing_deg=109.0,
        latitude_deg=13.077,
        rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
    )
    default, tight = threedof.fly_3dof(launches), threedof.fly_3dof(launches, rtol=1e-12)
    assert np.max(np.abs(default.apogee_altitude_m - tight.apogee_altitude_m)) < 0.05
    assert np.max(np.abs(default.range_m - tight.range_m)) < 0.2
