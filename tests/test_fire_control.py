"""Fire control against closed forms (the vacuum conic), the exact vacuum case on a rotating
Earth, the 3DOF itself, and bad input."""

import dataclasses
import math
import re
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import optimize

from harp_analysis.analyses.fire_control.firing import (
    FiringSolution,
    TargetPoint,
    destination,
    firing_solutions,
)
from harp_analysis.analyses.fire_control.intercepts import raid_windows
from harp_analysis.analyses.fire_control.verification import verify_with_3dof
from harp_analysis.engines import eci, kepler, threedof
from harp_analysis.foundation import earth
from harp_analysis.models.launch import Launch
from harp_analysis.models.projectiles import HP
from harp_analysis.models.sites import BARBADOS
from harp_analysis.models.trajectory import EndAltitudeNotCrossedWarning

SPEED = HP.launch_speed_m_s
VACUUM = Launch(HP, SPEED, 45.0, atmosphere="vacuum")
ROTATING = Launch(
    HP,
    SPEED,
    45.0,
    latitude_deg=math.degrees(BARBADOS.latitude_rad),
    longitude_deg=-59.6,  # Barbados
    rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
)


def _destination(gun: Launch, bearing_deg, distance_m, altitude_m=0.0, **kwargs) -> TargetPoint:
    """The point ``distance_m`` along the great circle from the gun (spherical trigonometry)."""
    lat1, angle = gun.latitude_rad, distance_m / earth.RADIUS_M
    bearing = math.radians(bearing_deg)
    lat2 = math.asin(
        math.sin(lat1) * math.cos(angle) + math.cos(lat1) * math.sin(angle) * math.cos(bearing)
    )
    dlon = math.atan2(
        math.sin(bearing) * math.sin(angle) * math.cos(lat1),
        math.cos(angle) - math.sin(lat1) * math.sin(lat2),
    )
    return TargetPoint(
        math.degrees(lat2), gun.longitude_deg + math.degrees(dlon), altitude_m, **kwargs
    )


# --- vacuum, non-rotating: the closed-form conic ------------------------------------------------
def _conic_u(elevation_rad, range_angle_rad):
    """Eq 3.8 from the surface: u(Theta) with h = R V cos(phi), u(0) = 1/R, u'(0) = -tan/R."""
    r0 = earth.RADIUS_M
    c3 = earth.GM_M3_S2 / (r0 * SPEED * math.cos(elevation_rad)) ** 2
    return (
        c3
        + (1 / r0 - c3) * math.cos(range_angle_rad)
        - math.tan(elevation_rad) / r0 * math.sin(range_angle_rad)
    )


def _maximum_range_elevation():
    fit = optimize.minimize_scalar(
        lambda phi: -kepler.ballistic_conic(SPEED, phi).range_angle_rad,
        bounds=(0.1, 1.4),
        method="bounded",
        options=dict(xatol=1e-12),
    )
    return fit.x, float(-fit.fun)


@pytest.mark.parametrize("distance_km, altitude_m", [(20.0, 0.0), (250.0, 0.0), (250.0, 30e3)])
def test_vacuum_matches_the_closed_form_conic(distance_km, altitude_m):
    best, _ = _maximum_range_elevation()
    angle = distance_km * 1e3 / earth.RADIUS_M
    target = TargetPoint(0.0, math.degrees(angle), altitude_m)

    def miss(phi):
        return _conic_u(phi, angle) - 1 / (earth.RADIUS_M + altitude_m)

    low = optimize.brentq(miss, 1e-3, best, xtol=1e-15)
    high = optimize.brentq(miss, best, math.pi / 2 - 1e-6, xtol=1e-15)
    result = firing_solutions(VACUUM, target)
    assert result.reason is None
    assert result.low.elevation_deg == pytest.approx(math.degrees(low), abs=1e-6)
    assert result.high.elevation_deg == pytest.approx(math.degrees(high), abs=1e-6)
    for root in result.roots:
        assert root.bearing_deg == pytest.approx(90.0, abs=1e-9)  # due east along the equator
        assert root.beta == 0.0 and root.beta_valid
        assert root.miss_m < 1e-3
    if distance_km == 20.0 and altitude_m == 0.0:  # near flat: complementary angles
        assert result.low.elevation_deg + result.high.elevation_deg == pytest.approx(90, abs=0.1)


def test_vacuum_roots_merge_at_the_maximum_range_and_vanish_beyond_it():
    best, range_angle = _maximum_range_elevation()
    near = firing_solutions(VACUUM, TargetPoint(0.0, math.degrees(0.995 * range_angle)))
    assert near.low.elevation_deg < math.degrees(best) < near.high.elevation_deg
    assert near.high.elevation_deg - near.low.elevation_deg < 10.0
    beyond = firing_solutions(VACUUM, TargetPoint(0.0, math.degrees(1.01 * range_angle)))
    assert beyond.low is None and beyond.high is None
    assert "maximum range" in beyond.reason


# --- rotating Earth -----------------------------------------------------------------------------
@pytest.fixture(scope="module")
def rotating_vacuum():
    gun = ROTATING.but(atmosphere="vacuum")
    target = _destination(gun, 40.0, 150e3)
    return gun, target, firing_solutions(gun, target)


def test_rotating_vacuum_mks_is_exact_against_the_3dof(rotating_vacuum):
    """Without air the ECI MKS is the inertial Kepler conic: the 3DOF lands on the target."""
    gun, target, result = rotating_vacuum
    for root in result.roots:
        check = verify_with_3dof(gun, target, root)
        assert check.mks_miss_m < 1e-3
        assert abs(check.elevation_change_deg) < 1e-8 and abs(check.bearing_change_deg) < 1e-8


def test_the_ascending_root_meets_the_turning_target_on_the_public_eci_path():
    """Rebuild the MKS with eci.correction_for_launch, find where it rises through the target's
    radius with brentq, and compare with the target turned by omega t."""
    target = _destination(ROTATING, 120.0, 60e3, altitude_m=40e3)
    result = firing_solutions(ROTATING, target, branch="ascending")
    assert result.roots
    for root in result.roots:
        launch = ROTATING.but(elevation_deg=root.elevation_deg, bearing_deg=root.bearing_deg)
        correction = eci.correction_for_launch(launch)
        solution = correction.solution(warn=False)
        radius = earth.RADIUS_M + target.altitude_m
        theta = optimize.brentq(
            lambda t: solution.radius(t)[0] - radius,
            0.0,
            float(solution.apogee_angle),
            xtol=1e-15,
        )
        time = float(solution.time(np.linspace(0, theta, 400)[1:])[-1])
        assert time == pytest.approx(root.time_of_flight_s, rel=1e-9)
        point = eci.inertial_positions(solution, correction, ROTATING.latitude_rad, [theta])[0]
        # the MKS's frame has the gun at longitude 0; the target turns east by omega t
        lat = math.radians(target.latitude_deg)
        lon = math.radians(target.longitude_deg - ROTATING.longitude_deg)
        lon += earth.ROTATION_RATE_RAD_S * time
        aim = radius * np.array(
            [math.cos(lat) * math.cos(lon), math.cos(lat) * math.sin(lon), math.sin(lat)]
        )
        assert np.linalg.norm(point - aim) < 1e-3


@pytest.fixture(scope="module")
def hp_targets():
    surface = _destination(ROTATING, 60.0, 150e3)
    aloft = _destination(ROTATING, 60.0, 150e3, altitude_m=30e3)
    return [(target, firing_solutions(ROTATING, target)) for target in (surface, aloft)]


def test_the_refined_solution_lands_the_3dof_on_the_target(hp_targets):
    for target, result in hp_targets:
        assert result.low is not None and result.high is not None, result.reason
        for root in result.roots:
            check = verify_with_3dof(ROTATING, target, root)
            assert check.converged, check.message
            flight = threedof.fly_3dof(
                ROTATING.but(elevation_deg=check.elevation_deg, bearing_deg=check.bearing_deg),
                end_altitude_m=target.altitude_m,
            )
            assert flight.impact[0]
            distance = np.linalg.norm(flight.end_position_m[:, 0] - target.earth_fixed_m())
            assert distance < 1.0
            # the MKS's own miss is reported, finite, and smaller than the range itself
            assert 0.0 < check.mks_miss_m < 150e3
            assert check.flights >= 3


def test_the_batched_refinement_lands_every_root_and_gives_the_one_by_one_answers():
    """Every root of targets in all four quadrants, aloft and at sea level, refined together:
    each lands the 3DOF (flown again, directly) within the tolerance of its target, in a few
    flights (the MKS's Jacobian stands in for differences), and each is what refining it
    alone gives."""
    targets = [
        _destination(ROTATING, bearing, distance, altitude_m=altitude)
        for bearing in (30.0, 120.0, 210.0, 300.0)
        for distance, altitude in ((80e3, 0.0), (160e3, 20e3))
    ]
    pairs = [
        (target, root)
        for target, result in zip(targets, firing_solutions(ROTATING, targets))
        for root in result.roots
    ]
    assert len(pairs) == 2 * len(targets)
    aims, roots = zip(*pairs)
    together = verify_with_3dof(ROTATING, list(aims), list(roots), tolerance_m=1.0)
    for target, root, check in zip(aims, roots, together, strict=True):
        assert check.converged, check.message
        flight = threedof.fly_3dof(
            ROTATING.but(elevation_deg=check.elevation_deg, bearing_deg=check.bearing_deg),
            end_altitude_m=target.altitude_m,
        )
        assert np.linalg.norm(flight.end_position_m[:, 0] - target.earth_fixed_m()) < 1.0
        assert 2 <= check.flights <= 12
        alone = verify_with_3dof(ROTATING, target, root, tolerance_m=1.0)
        assert alone.elevation_deg == check.elevation_deg
        assert alone.flights == check.flights


def test_a_solution_the_3dof_falls_short_of_is_raised_quietly_onto_the_target():
    """80 km out and 20 km up, the MKS's low root tops out above the target and the 3DOF's
    (19.9 km) below it: that shot never comes down through 20 km, a miss the refinement
    expects (no warning of it reaches the caller), and raising the elevation lands it."""
    target = _destination(ROTATING, 109.0, 80e3, altitude_m=20e3)
    low = firing_solutions(ROTATING, target).low
    with pytest.warns(EndAltitudeNotCrossedWarning, match=r"its apogee: 19\.\d+ km"):
        threedof.fly_3dof(
            ROTATING.but(elevation_deg=low.elevation_deg, bearing_deg=low.bearing_deg),
            end_altitude_m=20e3,
        )
    with warnings.catch_warnings():
        warnings.simplefilter("error", EndAltitudeNotCrossedWarning)
        check = verify_with_3dof(ROTATING, target, low)
    assert check.mks_miss_m == math.inf and check.converged and check.elevation_change_deg > 0


def test_a_newton_step_past_the_vertical_is_flown_at_it_and_the_branch_searched():
    """A first Jacobian that all but ignores the elevation (the Barbados case's low root's, its
    elevation column shrunk 10^4 times) sends Newton's first step far past the vertical: the
    gun is laid at 90 deg, never beyond, and the Jacobian differenced there, zero (a step of
    either angle flies the same shot), ends Newton's method without a step (numpy raised
    LinAlgError on it before); the search of the branch, on the MKS root's side of the maximum
    range, then lands it on the root the true Jacobian leads to."""
    gun, target = barbados_case()
    low = firing_solutions(gun, target).low
    jacobian = low.jacobian_m_rad.copy()
    jacobian[:, 0] *= 1e-4
    check = verify_with_3dof(gun, target, dataclasses.replace(low, jacobian_m_rad=jacobian))
    assert check.converged, check
    expected = verify_with_3dof(gun, target, low).elevation_deg
    assert check.elevation_deg == pytest.approx(expected, abs=1e-4), check


def test_fire_time_is_the_arrival_time_less_the_time_of_flight():
    target = _destination(ROTATING, 60.0, 150e3)
    timed = firing_solutions(ROTATING, TargetPoint(**{**target.__dict__, "arrival_time_s": 400}))
    assert timed.low.fire_time_s == pytest.approx(400 - timed.low.time_of_flight_s, abs=1e-9)
    late = firing_solutions(ROTATING, TargetPoint(**{**target.__dict__, "arrival_time_s": 200}))
    assert late.low is not None and late.high is None  # the lob takes longer than 200 s
    assert "arrival_time_s" in late.reason


# --- unreachable targets: results with reasons --------------------------------------------------
def test_unreachable_targets_say_why():
    far = firing_solutions(ROTATING, _destination(ROTATING, 60.0, 3000e3))
    assert far.roots == [] and "maximum range" in far.reason
    high = firing_solutions(ROTATING, _destination(ROTATING, 60.0, 50e3, altitude_m=2000e3))
    assert high.roots == [] and "maximum altitude" in high.reason
    target = _destination(ROTATING, 60.0, 150e3)
    fenced = firing_solutions(ROTATING, target, bearing_limits_deg=(180.0, 300.0))
    assert fenced.roots == [] and "bearing_limits_deg" in fenced.reason
    wrapped = firing_solutions(ROTATING, target, bearing_limits_deg=(300.0, 90.0))
    assert len(wrapped.roots) == 2
    escaping = firing_solutions(VACUUM.but(speed_m_s=12e3), TargetPoint(0.0, 5.0))
    assert escaping.roots == [] and "escape" in escaping.reason


@pytest.mark.parametrize("branch", ["descending", "ascending"])
def test_a_target_at_the_gun_or_straight_above_it_says_why_it_has_no_solution(branch):
    """No great-circle bearing leads from the gun to a point at it, along which the solver
    searches: a result with that reason (not "reaches 0.0 km, beyond the target's 0.0 km"),
    and the other targets of the batch keep their answers."""
    here = TargetPoint(ROTATING.latitude_deg, ROTATING.longitude_deg)
    above = TargetPoint(ROTATING.latitude_deg, ROTATING.longitude_deg, altitude_m=50e3)
    elsewhere = _destination(ROTATING, 60.0, 60e3, altitude_m=30e3)
    results = firing_solutions(ROTATING, [here, above, elsewhere], branch=branch)
    for result, where in zip(results, ["at the gun (0 m", "straight above the gun, 50.0 km up"]):
        assert result.roots == [] and result.reason.startswith(f"the target is {where}"), result
        assert "great-circle bearing" in result.reason
    assert results[2] == firing_solutions(ROTATING, elsewhere, branch=branch)
    assert results[2].roots


def test_a_target_metres_from_the_gun_is_quoted_in_metres():
    """A short range's reasons quote its metres (the lob of the vertical shot falls back
    about a kilometre away), never "0.0 km", and a root the search lost never "nan m"."""
    still = ROTATING.but(rotation_rate_rad_s=0.0)
    close = firing_solutions(still, _destination(still, 60.0, 100.0))
    assert close.high is None and "beyond the target's 100 m" in close.reason, close.reason
    assert re.search(r"still reaches \d{3} m,", close.reason), close.reason
    closer = firing_solutions(still, destination(still, 109.0, 1.0))  # the low root's Newton
    assert "km" not in closer.reason and "nan" not in closer.reason, closer.reason  # can't start


# --- bad input: refused by name -----------------------------------------------------------------
def test_bad_input_is_refused_by_name():
    target = TargetPoint(1.0, 1.0)
    with pytest.raises(ValueError, match="arrival_time_s"):
        TargetPoint(1.0, 1.0, arrival_time_s=-1.0)
    with pytest.raises(TypeError, match="gun"):
        firing_solutions("HP", target)
    with pytest.raises(ValueError, match="site_altitude_m"):
        firing_solutions(VACUUM.but(site_altitude_m=100.0), target)
    with pytest.raises(TypeError, match="target"):
        firing_solutions(VACUUM, (1.0, 1.0))
    with pytest.raises(ValueError, match="branch"):
        firing_solutions(VACUUM, target, branch="up")
    with pytest.raises(ValueError, match="bearing_limits_deg"):
        firing_solutions(VACUUM, target, bearing_limits_deg=(0.0, 400.0))
    with pytest.raises(TypeError, match="bearing_limits_deg"):
        firing_solutions(VACUUM, target, bearing_limits_deg=90.0)
    with pytest.raises(TypeError, match="solution"):
        verify_with_3dof(VACUUM, target, None)
    with pytest.raises(TypeError, match=r"targets\[1\]"):
        firing_solutions(VACUUM, [target, "x"])
    root = firing_solutions(VACUUM, target).low
    assert isinstance(root, FiringSolution)
    with pytest.raises(ValueError, match="one FiringSolution per target"):
        verify_with_3dof(VACUUM, [target, target], [root])
    with pytest.raises(ValueError, match="tolerance_m"):
        verify_with_3dof(VACUUM, target, root, tolerance_m=0.0)
    with pytest.raises(TypeError, match="targets"):
        raid_windows(VACUUM, "raid")
    with pytest.raises(ValueError, match="end_altitude_m"):
        threedof.fly_3dof(VACUUM, end_altitude_m=[1.0, 2.0])
    with pytest.raises(TypeError, match="rising"):
        threedof.fly_3dof(VACUUM, rising="yes")


_ILLEGAL = {
    "latitude_deg": st.floats().filter(lambda v: not -90.0 <= v <= 90.0),
    "longitude_deg": st.floats().filter(lambda v: not -180.0 <= v <= 360.0),
    "altitude_m": st.floats().filter(lambda v: not v >= 0.0 or math.isinf(v)),
    "arrival_time_s": st.floats().filter(lambda v: not v >= 0.0 or math.isinf(v)),
}


@settings(max_examples=60, deadline=None)
@given(data=st.data(), name=st.sampled_from(sorted(_ILLEGAL)))
def test_target_fields_are_refused_by_name(data, name):
    value = data.draw(st.one_of(_ILLEGAL[name], st.text(max_size=3), st.booleans()))
    fields = dict(latitude_deg=10.0, longitude_deg=20.0, altitude_m=0.0, arrival_time_s=None)
    with pytest.raises((TypeError, ValueError), match=name):
        TargetPoint(**{**fields, name: value})


def test_points_from_earth_fixed_positions_are_the_points_that_give_them():
    """TargetPoint.from_earth_fixed inverts earth_fixed_m, for a gun at any longitude, keeps
    each arrival time, and gives None for a point below the ground."""
    gun_longitude = -59.6
    points = [
        TargetPoint(13.1, -57.9, 20e3),
        TargetPoint(-62.0, 170.0, 0.0),
        TargetPoint(89.0, 5.0),
    ]
    fixed = np.array([p.earth_fixed_m(gun_longitude) for p in points]).T
    below = 0.5 * fixed[:, :1]  # halfway to the Earth's centre
    found = TargetPoint.from_earth_fixed(
        np.hstack([fixed, below]), [10.0, 20.0, 30.0, 40.0], gun_longitude
    )
    assert found[-1] is None
    for point, back, arrival in zip(points, found, (10.0, 20.0, 30.0), strict=False):
        assert back.latitude_deg == pytest.approx(point.latitude_deg, abs=1e-9)
        assert back.longitude_deg == pytest.approx(point.longitude_deg, abs=1e-9)
        assert back.altitude_m == pytest.approx(point.altitude_m, abs=1e-6)
        assert back.arrival_time_s == arrival
    with pytest.raises(ValueError, match="arrival_times_s"):
        TargetPoint.from_earth_fixed(fixed, [10.0, -1.0, 30.0])
    with pytest.raises(ValueError, match="positions_m"):
        TargetPoint.from_earth_fixed(fixed[:, :2].T, [10.0, 20.0])


# --- part 2: Kepler targets and intercepts ------------------------------------------------------
from scipy.integrate import solve_ivp  # noqa: E402

from harp_analysis.analyses.fire_control.firing import BARBADOS_HP, barbados_case  # noqa: E402
from harp_analysis.analyses.fire_control.intercepts import (  # noqa: E402
    KeplerTarget,
    intercept,
    intercept_window,
    raid,
)
from harp_analysis.analyses.fire_control.studies.costs import shoot_3dof  # noqa: E402
from harp_analysis.models.trajectory import rotate_about_axis  # noqa: E402


def _two_body(t, y):
    return np.r_[y[3:], -earth.GM_M3_S2 * y[:3] / np.linalg.norm(y[:3]) ** 3]


def test_kepler_propagation_and_fall_match_the_integrated_two_body_problem():
    target = raid(count=3)[1]
    ground = target.ground_time_s

    def lands(t, y):
        return np.linalg.norm(y[:3]) - earth.RADIUS_M

    lands.terminal = True
    times = np.linspace(0.0, 0.99 * ground, 9)
    reference = solve_ivp(
        _two_body,
        (0.0, 2 * ground),
        np.r_[target.position_m, target.velocity_m_s],
        method="DOP853",
        rtol=1e-13,
        atol=1e-9,
        t_eval=times,
        events=lands,
    )
    assert np.abs(reference.y[:3] - target.position_at(times)).max() < 1e-3
    assert reference.t_events[0][0] == pytest.approx(ground, abs=1e-6)
    assert target.position_at(5.0).shape == (3,)


@pytest.mark.parametrize("altitude_fraction", [0.3, 0.7])
def test_the_vacuum_intercept_meets_the_target_in_the_3dof(altitude_fraction):
    """Without air the ECI MKS is exact: the 3DOF, fired at the intercept's fire time, crosses
    the target's point within metres at the intercept time."""
    gun = BARBADOS_HP.but(atmosphere="vacuum")
    target = raid(gun, count=5)[2]
    window = intercept_window(gun, target, count=20)
    feasible = [item for item in window.intercepts if item.roots]
    assert feasible, window.reason
    item = feasible[int(altitude_fraction * (len(feasible) - 1))]
    for root in item.roots:
        flight = threedof.fly_3dof(
            gun.but(elevation_deg=root.elevation_deg, bearing_deg=root.bearing_deg),
            end_altitude_m=item.aim.altitude_m,
            rising=True,
        )
        # the 3DOF's end point is Earth-fixed (x toward longitude 0): at the intercept time T
        # it lies in the inertial frame turned by omega T, whichever moment the gun fired
        fire, when = root.fire_time_s, item.intercept_time_s
        end = rotate_about_axis(flight.end_position_m, [gun.rotation_rate_rad_s * when])[:, 0]
        aim = rotate_about_axis(  # the target's inertial point, in the 3DOF's frame
            target.position_at(item.intercept_time_s)[:, None],
            [math.radians(gun.longitude_deg)],
        )[:, 0]
        arrival = fire + flight.time_of_flight_s[0]
        speed = np.linalg.norm(target.velocity_m_s) + flight.impact_speed_m_s[0]
        assert np.linalg.norm(end - aim) + abs(arrival - item.intercept_time_s) * speed < 5.0


def test_an_intercept_needing_a_shot_before_now_is_no_solution():
    target = raid(count=5)[2]
    early = intercept(BARBADOS_HP, target, 0.2 * target.ground_time_s)
    assert early.roots == [] and early.reason
    window = intercept_window(BARBADOS_HP, target, count=30)
    first = next(item for item in window.intercepts if item.aim and item.aim.altitude_m < 60e3)
    late = intercept(BARBADOS_HP, target, first.intercept_time_s)
    for root in late.roots:
        assert root.fire_time_s >= 0.0
    landed = intercept(BARBADOS_HP, target, target.ground_time_s + 1.0)
    assert landed.aim is None and "ground" in landed.reason
    with pytest.raises(ValueError, match="intercept_time_s"):
        intercept(BARBADOS_HP, target, -1.0)
    with pytest.raises(TypeError, match="target"):
        intercept(BARBADOS_HP, "raid", 10.0)
    with pytest.raises(ValueError, match="position_m"):
        KeplerTarget([1.0, 0.0, 0.0], [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="velocity_m_s"):
        KeplerTarget([earth.RADIUS_M, 0.0, 0.0], [0.0, 12e3, 0.0])


def test_fire_before_now_is_refused_with_the_reason():
    target = raid(count=5)[2]
    window = intercept_window(BARBADOS_HP, target, count=30)
    feasible = [item for item in window.intercepts if item.roots]
    # the same point, reached by the same shots, but due sooner than any flight can get there
    aim = feasible[0].aim
    due = min(root.time_of_flight_s for root in feasible[0].roots) / 2
    hurried = firing_solutions(
        BARBADOS_HP, TargetPoint(**{**aim.__dict__, "arrival_time_s": due}), branch="ascending"
    )
    assert hurried.roots == [] and "before t = 0" in hurried.reason


def test_the_window_is_ordered_and_its_fire_times_feasible():
    window = intercept_window(BARBADOS_HP, raid(count=5)[2], count=30)
    assert window.reason is None
    assert window.earliest_intercept_s <= window.latest_intercept_s
    assert 0.0 <= window.first_fire_s <= window.last_fire_s
    assert window.time_to_fire_s >= 0.0
    for item in window.intercepts:
        for root in item.roots:
            assert root.fire_time_s + root.time_of_flight_s == pytest.approx(item.intercept_time_s)


def test_the_3dof_alone_lands_on_the_target_from_the_drag_free_conic():
    gun, target = barbados_case()
    shot = shoot_3dof(gun, target)
    assert shot.converged, shot.message
    flight = threedof.fly_3dof(
        gun.but(elevation_deg=shot.elevation_deg, bearing_deg=shot.bearing_deg)
    )
    assert np.linalg.norm(flight.end_position_m[:, 0] - target.earth_fixed_m()) < 1.0
    # drag shortens the range: the drag-free start is far off, and the gun must be raised
    assert shot.mks_miss_m > 10e3 and shot.elevation_change_deg > 0
    assert shot.rhs_evaluations > shot.flights
