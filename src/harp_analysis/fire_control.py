"""Fire control (Chapter 7 A): the gun's elevation and bearing that put a projectile on a point.

The ECI Modified Kepler Solution (:mod:`.eci`) flies the shot in the inertial frame of the gun
at t = 0, the gun at longitude 0; the target, fixed to the Earth, turns with it, so at time t
it lies at its Earth-fixed position turned by omega t about the Earth's axis (longitudes are
taken relative to the gun's). Where the trajectory's radius equals R + the target's altitude
(on its descending branch, or ascending) the trajectory's point is compared with the target's
inertial position at that time of flight: the residual is the east and north miss (m) at the
target. One vectorised MKS over a grid of elevations at the great-circle bearing brackets the
low-angle and high-angle roots (the range at the target's altitude against elevation), and
scipy's least squares refines (elevation, bearing) from each bracket.

:func:`verify_with_3dof` then flies the 3DOF (the launch's own atmosphere and drag law, the
rotating Earth) at the MKS solution, measures its miss, and refines the solution by shooting
with the 3DOF itself: the MKS's 3DOF miss is the model error the text's method accepts.

SI inside (m, s, rad); degrees only in the arguments and fields named ``_deg``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from . import earth, eci, mks, threedof
from .launch import Launch
from .trajectory import TruncatedFlightWarning, launch_frame, rotate_about_axis
from .validation import check_choice, check_range, real_number

__all__ = [
    "TargetPoint",
    "FiringSolution",
    "FiringSolutions",
    "Verification",
    "firing_solutions",
    "verify_with_3dof",
    "great_circle",
    "BRANCHES",
]

BRANCHES = ("descending", "ascending")
#: The bracketing grid of elevations (deg): every half degree, short of the vertical, where
#: the MKS has no angular momentum.
_GRID_STEP_DEG = 0.5
_GRID_TOP_DEG = 89.5
#: The grid leaves out elevations whose beta x decay scale exceeds this: the angular momentum
#: decays to e^-8 of its launch value there, and the closed form's constants cancel
#: (mks.ModifiedKeplerSolution refuses them) long before beta reaches its validity limit 0.25.
_GRID_MAX_DECAY = 8.0
#: How far the refinement may turn the bearing from the great-circle one (rad): the Earth's
#: rotation deflects the shot by far less.
_BEARING_SPAN_RAD = math.radians(30.0)
#: Gauss-Legendre intervals and order of the time of flight (eq 3.32) to the target: converged
#: to well under a microsecond, a fraction of a millimetre of the target's motion.
_TIME_INTERVALS = 16
_TIME_ORDER = 8
#: The miss (m) that stands for a shot that never reaches the target (refinements turn back).
_SHORT_MISS_M = 1e12
#: A 3DOF refinement has converged once it lands this close (m), even if scipy's test of its
#: steps fails: at rtol = 1e-9 the 3DOF's own end point is good to millimetres.
_LANDED_M = 0.01
_CROSSING_ITERATIONS = 100
_CROSSING_TOLERANCE_RAD = 1e-14  # 64 nm of range: the rounding of u allows no better


@dataclass(frozen=True)
class TargetPoint:
    """A point fixed to the Earth: its latitude and longitude (deg), altitude above the
    spherical Earth (m) and, optionally, the time (s after t = 0, now) it must be reached."""

    latitude_deg: float
    longitude_deg: float
    altitude_m: float = 0.0
    arrival_time_s: float | None = None

    def __post_init__(self):
        bounds = {
            "latitude_deg": dict(low=-90.0, high=90.0, unit="deg"),
            "longitude_deg": dict(low=-180.0, high=360.0, unit="deg"),
            "altitude_m": dict(low=0.0, unit="m"),
        }
        for name, limits in bounds.items():
            value = check_range(real_number(getattr(self, name), name), name, **limits)
            object.__setattr__(self, name, value)
        if self.arrival_time_s is not None:
            arrival = real_number(self.arrival_time_s, "arrival_time_s")
            if arrival < 0.0:
                raise ValueError(
                    f"arrival_time_s = {arrival:g} s has already passed: it must be >= 0 "
                    "(seconds after t = 0, now)"
                )
            object.__setattr__(self, "arrival_time_s", arrival)

    def earth_fixed_m(self, gun_longitude_deg: float = 0.0) -> np.ndarray:
        """Position (3,) in the Earth-fixed frame whose x axis points to longitude
        ``gun_longitude_deg`` (the frame of a gun there, at t = 0)."""
        latitude = math.radians(self.latitude_deg)
        longitude = math.radians(self.longitude_deg - gun_longitude_deg)
        up = launch_frame(latitude, longitude, 0.0)[0]
        return (earth.RADIUS_M + self.altitude_m) * up


@dataclass(frozen=True)
class FiringSolution:
    """One root: how to lay the gun, when to fire and how well the MKS does there."""

    elevation_deg: float
    bearing_deg: float
    time_of_flight_s: float
    fire_time_s: float | None  # arrival_time_s - time of flight, if an arrival time is set
    miss_m: float  # residual distance between the MKS trajectory and the target
    beta: float  # eq 3.22 of the ECI launch (eq 6.11)
    leaves_atmosphere: bool  # apogee above mks.SENSIBLE_ATMOSPHERE_M
    mks_solves: int  # MKS trajectories this root's refinement evaluated
    branch: str  # where it meets the target: "descending" or "ascending"

    @property
    def beta_valid(self) -> bool:
        """Whether beta is within the text's validity limit (Ch. 4 B: below 0.25)."""
        return self.beta <= mks.BETA_VALIDITY_LIMIT


@dataclass(frozen=True)
class FiringSolutions:
    """The low-angle and high-angle roots (None where there is none) and, when either is
    missing, ``reason`` saying why; ``mks_solves`` counts every MKS trajectory evaluated."""

    low: FiringSolution | None
    high: FiringSolution | None
    reason: str | None
    mks_solves: int
    maximum_range_m: float  # ground range of the grid's best shot to the target's altitude

    @property
    def roots(self) -> list[FiringSolution]:
        return [root for root in (self.low, self.high) if root is not None]


@dataclass(frozen=True)
class Verification:
    """The 3DOF's check of an MKS firing solution and its shooting refinement."""

    mks_miss_m: float  # the 3DOF fired at the MKS solution, its miss at the target
    elevation_deg: float  # refined by shooting with the 3DOF
    bearing_deg: float
    elevation_change_deg: float  # refined - MKS
    bearing_change_deg: float
    miss_m: float  # the 3DOF's miss at the refined solution
    time_of_flight_s: float  # of the 3DOF at the refined solution
    flights: int  # 3DOF flights the refinement took, the check at the MKS solution included
    converged: bool  # scipy's test of its steps, or landed within _LANDED_M
    message: str


class _Gun:
    """The constants of a gun's ECI MKS launches (eci.correction_for_launch's, computed once)
    and its frame: the ECI MKS puts the gun at longitude 0."""

    def __init__(self, gun: Launch):
        self.launch = gun
        self.latitude_rad = gun.latitude_rad
        self.omega = gun.rotation_rate_rad_s
        self.up = np.ravel(launch_frame(gun.latitude_rad, 0.0, 0.0)[0])
        self.drag_area_m2 = gun.launch_drag_coefficient * gun.projectile.reference_area_m2
        self.surface_density_kg_m3 = mks.gun_density_kg_m3(gun)

    def correction(self, elevation_rad, bearing_rad) -> eci.LaunchCorrection:
        """eci.correction_for_launch of the gun laid at these angles (arrays: many at once)."""
        return eci.launch_correction(
            self.launch.speed_m_s,
            elevation_rad,
            bearing_rad,
            self.latitude_rad,
            drag_area_m2=self.drag_area_m2,
            mass_kg=self.launch.projectile.mass_kg,
            surface_density_kg_m3=self.surface_density_kg_m3,
            rotation_rate_rad_s=self.omega,
        )


def _check_gun(gun) -> Launch:
    if not isinstance(gun, Launch):
        raise TypeError(f"gun must be a harp_analysis.launch.Launch; got {type(gun).__name__}")
    if gun.site_altitude_m != 0.0:
        raise ValueError(
            f"gun.site_altitude_m must be 0 (the ECI MKS launches from r0 = R); "
            f"got {gun.site_altitude_m:g} m"
        )
    return gun


def _check_target(target) -> TargetPoint:
    if not isinstance(target, TargetPoint):
        raise TypeError(f"target must be a TargetPoint; got {type(target).__name__}")
    return target


def _check_bearing_limits(bearing_limits_deg) -> tuple[float, float] | None:
    if bearing_limits_deg is None:
        return None
    if isinstance(bearing_limits_deg, str) or np.shape(bearing_limits_deg) != (2,):
        raise TypeError(
            "bearing_limits_deg must be None or a pair (from, to) of bearings in deg; "
            f"got {bearing_limits_deg!r}"
        )
    first, last = (
        check_range(
            real_number(value, "bearing_limits_deg"),
            "bearing_limits_deg",
            low=0.0,
            high=360.0,
            unit="deg",
        )
        for value in bearing_limits_deg
    )
    return first, last


def _within(bearing_deg: float, limits: tuple[float, float]) -> bool:
    """Whether ``bearing_deg`` lies on the arc turning clockwise from limits[0] to limits[1]."""
    first, last = limits
    return (bearing_deg - first) % 360.0 <= (last - first) % 360.0


def great_circle(gun: Launch, target: TargetPoint) -> tuple[float, float]:
    """The central angle (rad) from the gun to the target and the initial bearing (rad, from
    true north, in [0, 2 pi)) of the great circle between them."""
    lat1, lat2 = gun.latitude_rad, math.radians(target.latitude_deg)
    dlon = math.radians(target.longitude_deg - gun.longitude_deg)
    a = np.ravel(launch_frame(lat1, 0.0, 0.0)[0])
    b = np.ravel(launch_frame(lat2, dlon, 0.0)[0])
    angle = math.atan2(float(np.linalg.norm(np.cross(a, b))), float(a @ b))
    bearing = math.atan2(
        math.sin(dlon) * math.cos(lat2),
        math.cos(lat1) * math.sin(lat2) - math.sin(lat1) * math.cos(lat2) * math.cos(dlon),
    )
    return angle, bearing % (2 * math.pi)


def _crossing_angles(
    solution: mks.ModifiedKeplerSolution, target_radius_m: float, branch: str
) -> np.ndarray:
    """Angular range (m,) where each launch's radius equals ``target_radius_m`` on ``branch``;
    NaN where it escapes or its apogee is below. Newton's iteration on u = 1/r, kept inside
    the branch's bracket by bisection (u is monotonic on each side of the apogee)."""
    apogee = np.where(solution.escapes, 0.0, solution.apogee_angle)
    apogee_radius = np.ravel(solution.radius(apogee[:, None]))
    reached = ~solution.escapes & (apogee_radius > target_radius_m)
    target_u = 1.0 / target_radius_m
    if branch == "descending":  # u rises from the apogee to the impact, at u = 1/R
        low, high = apogee.copy(), np.atleast_1d(solution.impact_angle).astype(float).copy()
        theta, sign = high.copy(), 1.0
    else:  # u falls from the muzzle to the apogee
        low, high = np.zeros_like(apogee), apogee.copy()
        theta, sign = low.copy(), -1.0
    reached &= high > low  # not so at a grazing elevation, where the closed form has no digits
    theta[~reached] = low[~reached] = high[~reached] = 0.0
    for _ in range(_CROSSING_ITERATIONS):
        column = theta[:, None]
        excess = np.ravel(solution.u(column)) - target_u
        slope = np.ravel(solution.du_dtheta(column))
        beyond = sign * excess > 0  # past the crossing
        high = np.where(beyond, theta, high)
        low = np.where(beyond, low, theta)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(excess == 0, theta, theta - excess / slope)
        inside = (step > low) & (step < high)
        new = np.where(inside, step, 0.5 * (low + high))
        done = np.max(np.abs(new - theta)) <= _CROSSING_TOLERANCE_RAD
        theta = new
        if done:
            break
    return np.where(reached, theta, np.nan)


def _times(solution: mks.ModifiedKeplerSolution, theta_rad: np.ndarray) -> np.ndarray:
    """Time of flight (s) to each launch's angle ``theta_rad`` (m,), NaN where it is NaN."""
    finite = np.where(np.isfinite(theta_rad), theta_rad, 0.0)
    fractions = np.linspace(0.0, 1.0, _TIME_INTERVALS + 1)[1:]
    grid = finite[:, None] * fractions
    times = np.atleast_2d(solution.time(grid, _TIME_ORDER))[:, -1]
    return np.where(np.isfinite(theta_rad), times, np.nan)


class _Problem:
    """A gun and a target: the MKS residual and its bookkeeping."""

    def __init__(self, gun: Launch, target: TargetPoint, branch: str):
        self.gun = _Gun(gun)
        self.target = target
        self.branch = branch
        self.target_radius_m = earth.RADIUS_M + target.altitude_m
        self.target_fixed = target.earth_fixed_m(gun.longitude_deg)
        self.solves = 0

    def target_inertial(self, time_s):
        """The target's inertial position(s) (3, n) at ``time_s`` (n,): turned with the Earth."""
        time = np.atleast_1d(time_s)
        fixed = np.repeat(self.target_fixed[:, None], time.size, axis=1)
        return rotate_about_axis(fixed, self.gun.omega * time)

    def flights(self, elevation_rad, bearing_rad):
        """The ECI MKS of launches at ``elevation_rad`` and ``bearing_rad`` (arrays), their
        angles and times to the target's altitude."""
        correction = self.gun.correction(elevation_rad, bearing_rad)
        solution = eci.solution_for(correction, warn=False)
        self.solves += np.size(elevation_rad)
        theta = _crossing_angles(solution, self.target_radius_m, self.branch)
        return correction, solution, theta, _times(solution, theta)

    def residual(self, x):
        """East and north miss (m) at the target of the shot at elevation x[0] (rad) and
        bearing x[1] (rad); NaN if the shot does not reach the target's altitude."""
        correction, solution, theta, time = self.flights(x[0], x[1] % (2 * math.pi))
        if not np.isfinite(theta[0]):
            return np.full(2, np.nan), solution, time[0]
        point = eci.inertial_positions(solution, correction, self.gun.latitude_rad, theta)[0]
        aim = self.target_inertial(time)[:, 0]
        return _east_north(point - aim, aim), solution, time[0]


def _east_north(difference, at) -> np.ndarray:
    """The east and north components of ``difference`` at the point ``at`` (3,)."""
    east = np.array([-at[1], at[0], 0.0])
    east /= np.linalg.norm(east)
    north = np.cross(at / np.linalg.norm(at), east)
    return np.array([difference @ east, difference @ north])


def _grid(problem: _Problem, bearing_rad: float):
    """The bracketing sweep: elevations (rad) and, at each, the trajectory's angular range to
    the target's altitude less the central angle from the gun to the target's position at that
    time (rad; NaN where it does not get there), and whether each escapes."""
    elevation = np.radians(np.arange(_GRID_STEP_DEG, _GRID_TOP_DEG + 1e-9, _GRID_STEP_DEG))
    correction = problem.gun.correction(elevation, bearing_rad)
    usable = (correction.elevation_rad > 0) & (
        correction.beta * correction.decay_scale <= _GRID_MAX_DECAY
    )  # the Earth's turn can tip a grazing shot's inertial velocity below the horizon
    elevation = elevation[usable]
    _, solution, theta, time = problem.flights(elevation, bearing_rad)
    aim = problem.target_inertial(np.nan_to_num(time))
    aim /= np.linalg.norm(aim, axis=0)
    central = np.arctan2(
        np.linalg.norm(np.cross(problem.gun.up, aim.T), axis=1), problem.gun.up @ aim
    )
    return elevation, theta - central, theta, solution.escapes


def _refine(problem: _Problem, start, bounds, limits, arrival_time_s):
    """Least squares on the east and north miss from ``start`` (elevation, bearing; rad)
    within ``bounds``; the FiringSolution, or None and why."""
    first = problem.solves

    def miss(x):
        # a shot that falls short of the target's altitude: a large miss turns the solver back
        return np.nan_to_num(problem.residual(x)[0], nan=_SHORT_MISS_M)

    with np.errstate(invalid="ignore"):
        fit = optimize.least_squares(
            miss, start, bounds=bounds, x_scale=1.0, xtol=1e-12, ftol=1e-12, gtol=1e-12
        )
    residual, solution, time = problem.residual(fit.x)
    if not np.all(np.isfinite(residual)):
        return None, "the refinement left the trajectories that reach the target's altitude"
    elevation_deg = math.degrees(fit.x[0])
    bearing_deg = math.degrees(fit.x[1]) % 360.0
    if limits is not None and not _within(bearing_deg, limits):
        return None, f"bearing {bearing_deg:.3f} deg lies outside bearing_limits_deg {limits}"
    fire_time = None if arrival_time_s is None else arrival_time_s - time
    if fire_time is not None and fire_time < 0:
        return None, (
            f"its time of flight {time:.1f} s exceeds arrival_time_s = {arrival_time_s:g} s"
        )
    apogee = float(solution.apogee_altitude())
    root = FiringSolution(
        elevation_deg=elevation_deg,
        bearing_deg=bearing_deg,
        time_of_flight_s=float(time),
        fire_time_s=None if fire_time is None else float(fire_time),
        miss_m=float(np.hypot(*residual)),
        beta=float(solution.beta[0, 0]),
        leaves_atmosphere=apogee > mks.SENSIBLE_ATMOSPHERE_M,
        mks_solves=problem.solves - first,
        branch=problem.branch,
    )
    return root, None


def firing_solutions(
    gun: Launch,
    target: TargetPoint,
    *,
    bearing_limits_deg: tuple[float, float] | None = None,
    branch: str = "descending",
) -> FiringSolutions:
    """The low-angle and high-angle firing solutions of ``gun`` (a Launch: its projectile,
    speed, site and Earth rotation; its elevation and bearing are ignored) onto ``target``,
    meeting it on the trajectory's ``branch`` ("descending" or "ascending"). The bearing is
    limited to the arc turning clockwise from bearing_limits_deg[0] to [1] if given. A target
    out of reach is a result with no roots and the reason, not an exception."""
    gun = _check_gun(gun)
    target = _check_target(target)
    branch = check_choice(branch, "branch", BRANCHES)
    limits = _check_bearing_limits(bearing_limits_deg)
    gun.warn_ignored("ECI MKS", "cross_wind_m_s", "head_wind_m_s", reason="it has no wind")
    problem = _Problem(gun, target, branch)
    if branch == "ascending" and target.altitude_m == 0.0:
        return FiringSolutions(
            None, None, "the ascending branch meets altitude 0 only at the muzzle", 0, math.nan
        )
    central, bearing = great_circle(gun, target)
    elevation, excess, theta, escapes = _grid(problem, bearing)
    maximum_range = float(np.nanmax(theta, initial=0.0) * earth.RADIUS_M)
    no_root = None
    if escapes.all():
        no_root = "the MKS escapes at every elevation: the muzzle speed exceeds escape speed"
    elif not np.isfinite(excess).any():
        no_root = (
            f"above the maximum altitude: no trajectory reaches {target.altitude_m / 1e3:g} km"
        )
    elif np.nanmax(excess) < 0:
        no_root = (
            f"beyond the maximum range: the target is {central * earth.RADIUS_M / 1e3:.1f} km "
            f"away, the gun reaches about {maximum_range / 1e3:.1f} km at "
            f"{target.altitude_m / 1e3:g} km altitude"
        )
    if no_root is not None:
        return FiringSolutions(None, None, no_root, problem.solves, maximum_range)
    peak = int(np.nanargmax(excess))
    sign = np.sign(excess)
    low_cells = np.flatnonzero((sign[:-1] < 0) & (sign[1:] >= 0))
    high_cells = np.flatnonzero((sign[:-1] >= 0) & (sign[1:] < 0))
    low_cells, high_cells = low_cells[low_cells < peak], high_cells[high_cells >= peak]
    bearing_bounds = (bearing - _BEARING_SPAN_RAD, bearing + _BEARING_SPAN_RAD)
    roots: dict[str, FiringSolution | None] = {}
    reasons = []
    for name, cells, span in (
        ("low", low_cells[-1:], (elevation[0], elevation[peak])),
        ("high", high_cells[:1], (elevation[peak], elevation[-1])),
    ):
        if not cells.size:
            roots[name] = None
            reasons.append(
                f"no {name}-angle root: none between {np.degrees(span[0]):.1f} and "
                f"{np.degrees(span[1]):.1f} deg of elevation reaches the target"
            )
            continue
        cell = int(cells[0])
        # start where the bracket interpolates to zero; stay within a cell of it, on its side
        # of the maximum range so that the two roots cannot merge
        a, b = excess[cell], excess[cell + 1]
        start = elevation[cell] + (elevation[cell + 1] - elevation[cell]) * a / (a - b)
        lower = max(elevation[max(cell - 1, 0)], span[0])
        upper = min(elevation[min(cell + 2, elevation.size - 1)], span[1])
        bounds = ([lower, bearing_bounds[0]], [upper, bearing_bounds[1]])
        roots[name], why = _refine(problem, [start, bearing], bounds, limits, target.arrival_time_s)
        if why is not None:
            reasons.append(f"no {name}-angle root: {why}")
    return FiringSolutions(
        roots["low"], roots["high"], "; ".join(reasons) or None, problem.solves, maximum_range
    )


def verify_with_3dof(
    gun: Launch, target: TargetPoint, solution: FiringSolution, *, rtol: float = 1e-9
) -> Verification:
    """The 3DOF (the gun's own atmosphere, drag law and Earth rotation) fired at the MKS
    ``solution`` and its miss where it crosses the target's altitude on the solution's branch,
    then a shooting refinement of (elevation, bearing) by the 3DOF from there (scipy's root,
    finite differences): how far the MKS solution was from the 3DOF's, and at what cost."""
    gun = _check_gun(gun)
    target = _check_target(target)
    if not isinstance(solution, FiringSolution):
        raise TypeError(f"solution must be a FiringSolution; got {type(solution).__name__}")
    aim = target.earth_fixed_m()  # the 3DOF's Earth-fixed frame has x toward longitude 0
    flights = 0

    def fly(x) -> threedof.Flights:
        nonlocal flights
        flights += 1
        return threedof.fly_3dof(
            gun.but(elevation_deg=math.degrees(x[0]), bearing_deg=math.degrees(x[1]) % 360.0),
            rtol=rtol,
            end_altitude_m=target.altitude_m,
            rising=solution.branch == "ascending",
        )

    def miss(x):
        if not 0.0 < x[0] <= math.pi / 2:  # no such gun: a miss that turns the solver back
            return np.full(2, _SHORT_MISS_M)
        flight = fly(x)
        if not flight.impact[0]:  # never crossed the target's altitude
            return np.full(2, _SHORT_MISS_M)
        return _east_north(flight.end_position_m[:, 0] - aim, aim)

    start = np.radians([solution.elevation_deg, solution.bearing_deg])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", TruncatedFlightWarning)  # a cut-off flight misses
        mks_miss = float(np.hypot(*miss(start)))
        # a step of 1e-7 rad moves the end point by centimetres, far above the 3DOF's noise
        fit = optimize.root(miss, start, method="hybr", options=dict(eps=1e-14, xtol=1e-10))
        final = fly(fit.x)
    residual = _east_north(final.end_position_m[:, 0] - aim, aim)
    elevation, bearing = math.degrees(fit.x[0]), math.degrees(fit.x[1]) % 360.0
    return Verification(
        mks_miss_m=mks_miss,
        elevation_deg=elevation,
        bearing_deg=bearing,
        elevation_change_deg=elevation - solution.elevation_deg,
        bearing_change_deg=(bearing - solution.bearing_deg + 180.0) % 360.0 - 180.0,
        miss_m=float(np.hypot(*residual)) if final.impact[0] else math.inf,
        time_of_flight_s=float(final.time_of_flight_s[0]),
        flights=flights,
        converged=bool(fit.success) or float(np.hypot(*residual)) <= _LANDED_M,
        message=str(fit.message),
    )
