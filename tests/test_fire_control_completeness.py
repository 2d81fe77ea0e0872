"""Every root, labelled consistently, every reason true (issue 24 item 2): the compiled firing
solver against a dense reference scan of the same ECI MKS.

The reference is written here in numpy, apart from the solver's kernels: the MKS of every
elevation of a fine grid (0.05 deg) at the great-circle bearing, its crossing of the target's
radius on the branch by bisection, its time of flight by Gauss-Legendre on 64 equal
intervals, the crossing turned back into the Earth-fixed frame and its signed angle along the
great circle from the gun toward the target less the target's. Each sign change between
usable neighbours is a root of the problem at that bearing; the solver's roots (at their own
bearings, which the Earth's turn deflects) must match them one for one, low below high, with
every bearing quadrant, both sites' latitudes, targets near grazing and near the maximum
range, at sea level and aloft, on both branches.
"""

import math
import warnings

import numpy as np
import pytest

from harp_analysis.analyses.fire_control import firing as fire_control
from harp_analysis.analyses.fire_control import solver as firing_solver
from harp_analysis.engines import eci
from harp_analysis.foundation import earth
from harp_analysis.models.launch import Launch, Launches
from harp_analysis.models.projectiles import HP
from harp_analysis.models.sites import BARBADOS, YUMA
from harp_analysis.models.trajectory import launch_frame, rotate_about_axis

STEP_DEG = 0.05
ELEVATIONS_RAD = np.radians(
    np.arange(
        math.degrees(firing_solver.LOWEST_ELEVATION_RAD),
        math.degrees(firing_solver.HIGHEST_ELEVATION_RAD) + 1e-9,
        STEP_DEG,
    )
)
GUNS = {
    site.name: Launch(
        HP,
        HP.launch_speed_m_s,
        45.0,
        latitude_deg=math.degrees(site.latitude_rad),
        longitude_deg=longitude,
        rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
    )
    for site, longitude in ((BARBADOS, -59.6), (YUMA, -114.4))
}
BEARINGS_DEG = (40.0, 160.0, 200.0, 270.0, 320.0)  # every quadrant, and due west


def _reference_excess(gun: Launch, target, branch: str, elevations_rad=ELEVATIONS_RAD):
    """The along-track excess (rad) of every elevation of ``elevations_rad`` at the
    great-circle bearing, NaN where the MKS has no usable trajectory to the target's radius."""
    central, bearing = fire_control.great_circle(gun, target)
    launches = Launches.from_launches([gun])
    correction = eci.correction_for_launch(
        launches.but(elevation_deg=np.degrees(elevations_rad), bearing_deg=math.degrees(bearing))
    )
    usable = (
        (correction.elevation_rad > 0)
        & (correction.beta * correction.decay_scale <= firing_solver.MAX_DECAY)
        # within 0.01 deg of the inertial vertical the closed form's constants cancel
        & (correction.elevation_rad < math.radians(89.99))
    )
    excess = np.full(elevations_rad.size, np.nan)
    if not usable.any():
        return excess
    index = np.flatnonzero(usable)
    correction = eci.correction_for_launch(
        launches.but(
            elevation_deg=np.degrees(elevations_rad[index]), bearing_deg=math.degrees(bearing)
        )
    )
    solution = correction.solution(warn=False)
    radius = earth.RADIUS_M + target.altitude_m
    apogee = np.where(solution.escapes, 0.0, solution.apogee_angle)
    reached = ~solution.escapes & (np.ravel(solution.radius(apogee[:, None])) > radius)
    if branch == "descending":
        low, high = apogee.copy(), np.where(reached, solution.impact_angle, apogee)
        rises = True  # u rises through 1/radius between apogee and impact
    else:
        low, high = np.zeros_like(apogee), apogee.copy()
        rises = False
    reached &= (high > low) & (apogee > 0)  # not so at the inertial vertical (h0 nearly 0)
    for _ in range(50):  # bisection, to 1e-15 of the angle: the reference needs no speed
        middle = 0.5 * (low + high)
        u = np.ravel(solution.u(middle[:, None]))
        beyond = (u > 1 / radius) if rises else (u < 1 / radius)
        high, low = np.where(beyond, middle, high), np.where(beyond, low, middle)
    theta = np.where(reached, 0.5 * (low + high), 0.0)
    grid = theta[:, None] * np.linspace(0.0, 1.0, 33)[1:]
    time = solution.time(grid, 8)[:, -1]
    up = np.ravel(launch_frame(gun.latitude_rad, 0.0, 0.0)[0])
    velocity = correction.velocity_m_s
    along = velocity - (up @ velocity) * up[:, None]
    along /= np.linalg.norm(along, axis=0)
    r = np.ravel(solution.radius(theta[:, None]))
    inertial = r * (np.cos(theta) * up[:, None] + np.sin(theta) * along)
    fixed = rotate_about_axis(inertial, -gun.rotation_rate_rad_s * time)
    axis = np.ravel(launch_frame(gun.latitude_rad, 0.0, bearing)[1])
    angle = np.arctan2(axis @ fixed, up @ fixed) - central
    excess[index] = np.where(reached, angle, np.nan)
    return excess


def _reference_scan(gun: Launch, target, branch: str):
    """The excess over ELEVATIONS_RAD with the usable elevations' edges, each found by
    bisection between the grid points it lies between, inserted in order."""
    excess = _reference_excess(gun, target, branch)
    usable = np.isfinite(excess)
    elevations, values = list(ELEVATIONS_RAD), list(excess)
    edges = np.flatnonzero(usable[1:] != usable[:-1])
    if edges.size:  # all edges bisected together
        inside = np.where(usable[edges + 1], edges + 1, edges)
        low, high = (
            ELEVATIONS_RAD[np.where(usable[edges + 1], edges, edges + 1)],
            ELEVATIONS_RAD[inside],
        )
        for _ in range(26):
            middle = 0.5 * (low + high)
            found = np.isfinite(_reference_excess(gun, target, branch, middle))
            high, low = np.where(found, middle, high), np.where(found, low, middle)
        elevations += list(high)
        values += list(_reference_excess(gun, target, branch, high))
    order = np.argsort(elevations)
    return np.array(elevations)[order], np.array(values)[order]


def _sign_changes(elevations, excess):
    """Elevations (rad) where the excess changes sign between usable neighbours: rising (the
    range passing the target as the elevation grows) and falling."""
    a, b = excess[:-1], excess[1:]
    both = np.isfinite(a) & np.isfinite(b)
    rising = elevations[:-1][both & (a < 0) & (b >= 0)]
    falling = elevations[:-1][both & (a >= 0) & (b < 0)]
    return rising, falling


def _targets(site: str):
    """(site, gun, target, branch): every bearing, near grazing (5 km), short, mid and long,
    just inside and just beyond the reference's own maximum range, at sea level and aloft."""
    cases = []
    for gun in (GUNS[site],):
        for bearing in BEARINGS_DEG:
            for altitude, branches in ((0.0, ("descending",)), (30e3, BRANCHES)):
                for branch in branches:
                    far = fire_control.destination(gun, bearing, 600e3, altitude)
                    excess = _reference_excess(gun, far, branch)
                    reach = (np.nanmax(excess) + 600e3 / earth.RADIUS_M) * earth.RADIUS_M
                    for distance in (5e3, 40e3, 0.5 * reach, 0.999 * reach, 1.01 * reach):
                        target = fire_control.destination(gun, bearing, distance, altitude)
                        cases.append((site, gun, target, branch))
    return cases


BRANCHES = fire_control.BRANCHES


@pytest.mark.parametrize("site", list(GUNS))
def test_every_root_is_found_and_labelled_and_every_reason_is_true(site):
    cases = _targets(site)
    for branch in BRANCHES:
        chosen = [case for case in cases if case[3] == branch]
        gun = chosen[0][1]
        targets = [case[2] for case in chosen]
        results = fire_control.firing_solutions(gun, targets, branch=branch)
        for target, result in zip(targets, results, strict=True):
            elevations, excess = _reference_scan(gun, target, branch)
            rising, falling = _sign_changes(elevations, excess)
            where = f"{site} {branch} {target}: {result}"
            central, bearing = fire_control.great_circle(gun, target)
            distance = central * earth.RADIUS_M
            reach = (np.nanmax(excess, initial=-np.inf) * earth.RADIUS_M) + distance
            # the reference's maximum range decides whether there are roots; near it (within
            # the cross-track deflection's effect on the range) either answer is right
            margin = abs(reach - distance) < 20.0
            if not margin:
                assert (result.low is not None) == bool(rising.size), where
                assert (result.high is not None) == bool(falling.size), where
            usable = np.isfinite(excess).any()
            peak = math.degrees(elevations[np.nanargmax(excess)]) if usable else math.nan
            for root, changes, side in ((result.low, rising, 1), (result.high, falling, -1)):
                if root is None or not changes.size:
                    continue
                turned = abs((root.bearing_deg - math.degrees(bearing) + 180) % 360 - 180)
                if turned < 5.0:  # the root near the great circle, where the scan looks
                    nearest = np.min(np.abs(np.radians(root.elevation_deg) - changes))
                    assert nearest < math.radians(0.5), where
                assert root.miss_m < 1.0, where
                # low below the maximum range's elevation, high above it, whatever the bearing
                assert side * (peak - root.elevation_deg) > -0.1, where
            if result.low is not None and result.high is not None:
                assert result.low.elevation_deg < result.high.elevation_deg, where
            _assert_reason_true(result, excess, distance, reach, where)


def _assert_reason_true(result, excess, distance_m, reach_m, where):
    """Every reason's quoted ranges are the Earth-fixed ground ranges the reference finds."""
    reason = result.reason or ""
    if "beyond the maximum range" in reason:
        assert reach_m < distance_m + 20.0, where
        assert abs(result.maximum_range_m - reach_m) < 50.0, where
        assert f"{distance_m / 1e3:.1f} km away" in reason, where
    if "already reaches" in reason:  # the low root would lie below the usable elevations
        first = np.flatnonzero(np.isfinite(excess))[0]
        assert excess[first] > -20.0 / earth.RADIUS_M, where
    if "still reaches" in reason:
        last = np.flatnonzero(np.isfinite(excess))[-1]
        assert excess[last] > -20.0 / earth.RADIUS_M, where
    assert "refinement stopped" not in reason, where  # no root lost by the refinement


def test_one_target_or_many_give_the_same_answers():
    gun = GUNS["Barbados"]
    targets = [
        fire_control.destination(gun, bearing, distance)
        for bearing in BEARINGS_DEG
        for distance in (5e3, 100e3, 300e3)
    ]
    together = fire_control.firing_solutions(gun, targets)
    for target, many in zip(targets, together, strict=True):
        one = fire_control.firing_solutions(gun, target)
        assert one == many


def test_westward_shots_through_the_inertial_vertical_keep_both_roots():
    """The issue's case: west from Barbados, where the Earth's turn tips the inertial launch
    past the vertical at high elevation; the low root must be found and labelled low."""
    gun = GUNS["Barbados"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = fire_control.firing_solutions(gun, fire_control.destination(gun, 270.0, 150e3))
    assert result.low is not None and result.high is not None, result
    assert result.low.elevation_deg < 45.0 < result.high.elevation_deg
