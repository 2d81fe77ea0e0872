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

With ``model="calibrated"`` each root the ECI MKS finds is then moved onto the calibrated
MKS's (:mod:`.calibrated`: the ECI MKS corrected by a table learned from the gun's 3DOF
flights, :mod:`harp_analysis.engines.calibrated_mks`), which lands tens of metres from where the
3DOF does instead of kilometres; the text's ECI MKS stays the default.

The rest of Chapter 7 A lives beside it: :mod:`.verification` flies the 3DOF at a solution and
refines it by shooting, :mod:`.intercepts` meets ballistic targets and raids, and
:mod:`.studies.costs` counts and times both against the text's claims.

SI inside (m, s, rad); degrees only in the arguments and fields named ``_deg``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import overload

import numpy as np

from ...engines import eci, mks
from ...foundation import earth
from ...foundation.validation import Bounds, check_choice, finite_array, real_number
from ...models.launch import Launch
from ...models.projectiles import HP
from ...models.sites import BARBADOS
from ...models.trajectory import launch_frame
from . import calibrated, solver

__all__ = [
    "TargetPoint",
    "FiringSolution",
    "FiringSolutions",
    "firing_solutions",
    "great_circle",
    "east_north",
    "east_north_axes",
    "BRANCHES",
    "MODELS",
    "AT_GUN_M",
    "destination",
    "BARBADOS_HP",
    "barbados_case",
]

BRANCHES = ("descending", "ascending")
#: The models a firing solution can come from: the text's ECI MKS (:mod:`.solver`), or the
#: calibrated MKS (:mod:`.calibrated`), from the ECI MKS's roots.
MODELS = ("eci", "calibrated")
#: A target closer to the gun than this along the ground (m) is at the gun, or straight above
#: it: far closer than any shot is aimed (the 3DOF refinement lands within a centimetre), and
#: where the great-circle bearing from the gun, along which the solver searches, is lost.
AT_GUN_M = 1e-3


@dataclass(frozen=True)
class TargetPoint:
    """A point fixed to the Earth: its latitude and longitude (deg), altitude above the
    spherical Earth (m) and, optionally, the time (s after t = 0, now) it must be reached.

    Parameters
    ----------
    latitude_deg, longitude_deg : float
        Where it is (deg north, deg east).
    altitude_m : float
        Its height above the spherical Earth (m, >= 0).
    arrival_time_s : float, optional
        When the projectile must reach it (s after t = 0, now; >= 0); None for any time.
    """

    latitude_deg: float
    longitude_deg: float
    altitude_m: float = 0.0
    arrival_time_s: float | None = None

    def __post_init__(self):
        bounds = {
            "latitude_deg": Bounds(low=-90.0, high=90.0, unit="deg"),
            "longitude_deg": Bounds(low=-180.0, high=360.0, unit="deg"),
            "altitude_m": Bounds(low=0.0, unit="m"),
        }
        for name, interval in bounds.items():
            object.__setattr__(self, name, interval.number(getattr(self, name), name))
        if self.arrival_time_s is not None:
            arrival = real_number(self.arrival_time_s, "arrival_time_s")
            if arrival < 0.0:
                raise ValueError(
                    f"arrival_time_s = {arrival:g} s has already passed: it must be >= 0 "
                    "(seconds after t = 0, now)"
                )
            object.__setattr__(self, "arrival_time_s", arrival)

    @classmethod
    def _of_valid(cls, latitude_deg, longitude_deg, altitude_m, arrival_time_s) -> TargetPoint:
        """A point of fields known valid (computed, not given), unchecked."""
        point = cls.__new__(cls)
        for name, value in zip(
            cls.__dataclass_fields__,
            (latitude_deg, longitude_deg, altitude_m, arrival_time_s),
            strict=True,
        ):
            object.__setattr__(point, name, value)
        return point

    @classmethod
    def from_earth_fixed(
        cls, positions_m, arrival_times_s, gun_longitude_deg: float = 0.0
    ) -> list[TargetPoint | None]:
        """The points at the Earth-fixed ``positions_m`` (3, n), in the frame of
        :meth:`earth_fixed_m` for a gun at ``gun_longitude_deg``, each to be reached at its time
        of ``arrival_times_s`` (n,; s after t = 0): that method's inverse for many points at
        once, None for a point below the ground."""
        fixed = finite_array(positions_m, "positions_m")
        times = np.atleast_1d(finite_array(arrival_times_s, "arrival_times_s"))
        if fixed.ndim != 2 or fixed.shape[0] != 3 or times.shape != fixed.shape[1:]:
            raise ValueError(
                f"positions_m must be (3, n) and arrival_times_s (n,); got {fixed.shape} "
                f"and {times.shape}"
            )
        if np.any(times < 0.0):
            raise ValueError("arrival_times_s must be >= 0 (seconds after t = 0, now)")
        radius = np.linalg.norm(fixed, axis=0)
        latitude = np.degrees(np.arcsin(np.clip(fixed[2] / radius, -1.0, 1.0)))
        longitude = (
            np.degrees(np.arctan2(fixed[1], fixed[0])) + gun_longitude_deg + 180
        ) % 360 - 180
        return [
            cls._of_valid(lat, lon, r - earth.RADIUS_M, t) if r >= earth.RADIUS_M else None
            for lat, lon, r, t in zip(
                latitude.tolist(), longitude.tolist(), radius.tolist(), times.tolist(), strict=True
            )
        ]

    def earth_fixed_m(self, gun_longitude_deg: float = 0.0) -> np.ndarray:
        """Position (3,) in the Earth-fixed frame whose x axis points to longitude
        ``gun_longitude_deg`` (the frame of a gun there, at t = 0)."""
        latitude = math.radians(self.latitude_deg)
        longitude = math.radians(self.longitude_deg - gun_longitude_deg)
        up = launch_frame(latitude, longitude, 0.0)[0]
        return (earth.RADIUS_M + self.altitude_m) * np.ravel(up)


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
    #: d(east, north miss)/d(elevation, bearing) (m/rad) of the MKS at the root, (2, 2)
    #: read-only: the 3DOF refinement's first Jacobian
    jacobian_m_rad: np.ndarray | None = field(default=None, compare=False, repr=False)
    #: the model whose root it is, of :data:`MODELS`: "eci" (the text's ECI MKS) or
    #: "calibrated" (the calibrated MKS); time of flight, miss, beta and apogee are its
    model: str = "eci"
    #: where the calibrated MKS was asked for and this is the ECI MKS's root, why
    reason: str | None = None

    @property
    def beta_valid(self) -> bool:
        """Whether beta is within the text's validity limit (Ch. 4 B: below 0.25)."""
        return self.beta <= mks.BETA_VALIDITY_LIMIT


@dataclass(frozen=True)
class FiringSolutions:
    """The low-angle and high-angle roots (None where there is none) and, when either is
    missing, ``reason`` saying why; ``mks_solves`` counts every MKS trajectory evaluated.
    "Low" is the root of the lower gun elevation, where the range grows with elevation; "high"
    the other, past the maximum range."""

    low: FiringSolution | None
    high: FiringSolution | None
    reason: str | None
    mks_solves: int  # the calibrated MKS's flights included, where it was asked for
    #: the greatest Earth-fixed ground range (m) toward the target, at its altitude, that the
    #: search found (the maximum range where it had to search for it)
    maximum_range_m: float

    @property
    def roots(self) -> list[FiringSolution]:
        return [root for root in (self.low, self.high) if root is not None]


class _Gun:
    """A gun as the compiled solver reads it (:mod:`.solver`): speed, latitude, and what
    its ECI correction (:func:`eci.correction_for_launch`) makes of its projectile and air:
    Cd0 A, mass, eq 3.11's rho0 at the gun, k and the Earth's rotation; and the ECI model's
    flags. The solver lays the gun at its own elevations and bearings."""

    def __init__(self, gun: Launch, model: eci.EciModel = eci.CONSISTENT):
        self.launch = gun
        laid = eci.correction_for_launch(gun, model)
        self.numbers = np.array(
            [
                gun.speed_m_s,
                gun.latitude_rad,
                laid.drag_area_m2,
                laid.mass_kg,
                laid.surface_density_kg_m3,
                laid.decay_constant_per_m,
                laid.rotation_rate_rad_s,
            ]
        )
        self.flags = (*model.flags, model.decay == "consistent")


def check_gun(gun) -> Launch:
    """``gun`` if it is a Launch from the Earth's surface (the ECI MKS's r0 = R), else a
    TypeError or ValueError naming it."""
    if not isinstance(gun, Launch):
        raise TypeError(
            f"gun must be a harp_analysis.models.launch.Launch; got {type(gun).__name__}"
        )
    if gun.site_altitude_m != 0.0:
        raise ValueError(
            f"gun.site_altitude_m must be 0 (the ECI MKS launches from r0 = R); "
            f"got {gun.site_altitude_m:g} m"
        )
    return gun


def check_target(target) -> TargetPoint:
    """``target`` if it is a TargetPoint, else a TypeError naming it."""
    if not isinstance(target, TargetPoint):
        raise TypeError(f"target must be a TargetPoint; got {type(target).__name__}")
    return target


def check_targets(targets) -> tuple[list[TargetPoint], bool]:
    """``targets`` (one TargetPoint or a sequence of them) as a list, and whether it was one."""
    if isinstance(targets, TargetPoint):
        return [targets], True
    if isinstance(targets, str | bytes) or not isinstance(targets, Sequence | np.ndarray):
        raise TypeError(
            f"targets must be a TargetPoint or a sequence of them; got {type(targets).__name__}"
        )
    for index, target in enumerate(targets):
        if not isinstance(target, TargetPoint):
            raise TypeError(f"targets[{index}] must be a TargetPoint; got {type(target).__name__}")
    return list(targets), False


def check_bearing_limits(bearing_limits_deg) -> tuple[float, float] | None:
    """``bearing_limits_deg`` as a pair (from, to) of bearings in [0, 360] deg, or None; else
    an error naming it."""
    if bearing_limits_deg is None:
        return None
    if isinstance(bearing_limits_deg, str) or np.shape(bearing_limits_deg) != (2,):
        raise TypeError(
            "bearing_limits_deg must be None or a pair (from, to) of bearings in deg; "
            f"got {bearing_limits_deg!r}"
        )
    first, last = (
        Bounds(low=0.0, high=360.0, unit="deg").number(value, "bearing_limits_deg")
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


def east_north(difference, at, axes=None) -> np.ndarray:
    """The east and north components (..., 2) of ``difference`` (..., 3) at the points ``at``
    (..., 3), whose :func:`east_north_axes` are ``axes`` if given."""
    # products summed as they always were: the flights scipy's shooting from the drag-free
    # conic counts (costs.shoot_3dof, a ledger row) move with the last bit of the miss
    axes = east_north_axes(at) if axes is None else axes
    return np.stack([np.sum(difference * axes[..., k, :], -1) for k in range(2)], axis=-1)


def east_north_axes(at) -> np.ndarray:
    """The unit vectors east and north (..., 2, 3) at the points ``at`` (..., 3)."""
    east = np.stack([-at[..., 1], at[..., 0], np.zeros_like(at[..., 0])], axis=-1)
    east /= np.linalg.norm(east, axis=-1, keepdims=True)
    north = np.cross(at / np.linalg.norm(at, axis=-1, keepdims=True), east)
    return np.stack([east, north], axis=-2)


def _elevation_deg(elevation_rad: float) -> str:
    return f"{math.degrees(elevation_rad):.2f} deg"


def _distance(metres: float) -> str:
    """A distance for a message: in km to 0.1 km, or in m to three digits below 1 km."""
    return f"{metres / 1e3:.1f} km" if abs(metres) >= 999.5 else f"{metres:.3g} m"


def _missing(status: int, side: int, search: np.ndarray, row) -> str:
    """Why root ``side`` (0 low, 1 high) of a target is missing, from the solver's ``status``
    and ``search``; every range quoted is Earth-fixed ground range along the great circle."""
    name = ("low", "high")[side]
    peak, reach, lowest, lowest_m, highest, highest_m, distance_m = search
    if status == solver.BELOW_LOWEST:
        searched = "searched" if lowest <= solver.LOWEST_ELEVATION_RAD else "can fly"
        return (
            f"no low-angle root: the lowest elevation the MKS {searched} to it, "
            f"{_elevation_deg(lowest)}, already reaches {_distance(lowest_m)}, beyond the "
            f"target's {_distance(distance_m)}"
        )
    if status == solver.ABOVE_HIGHEST:
        searched = "searched" if highest >= solver.HIGHEST_ELEVATION_RAD else "can fly"
        return (
            f"no high-angle root: the highest elevation the MKS {searched} to it, "
            f"{_elevation_deg(highest)}, still reaches {_distance(highest_m)}, beyond the "
            f"target's {_distance(distance_m)}"
        )
    if not math.isfinite(row[3]):  # Newton's method found no usable MKS trajectory to start
        return (
            f"no {name}-angle root: the MKS has no usable trajectory where the search found "
            "it (a root the search lost)"
        )
    return (
        f"no {name}-angle root: the refinement stopped {row[3]:.3g} m from the target "
        "(a root the search lost)"
    )


def _at_gun(target: TargetPoint, distance_m: float) -> str | None:
    """Why a target at the gun (closer than :data:`AT_GUN_M` along the ground) has no firing
    solution; None for any other."""
    if distance_m >= AT_GUN_M:
        return None
    where = (
        "at the gun"
        if target.altitude_m == 0.0
        else f"straight above the gun, {_distance(target.altitude_m)} up"
    )
    return (
        f"the target is {where} ({distance_m:.3g} m from it along the ground): there is no "
        "great-circle bearing from the gun to it, along which the solver searches"
    )


def _solutions(
    gun: Launch,
    targets: list[TargetPoint],
    branch: str,
    limits: tuple[float, float] | None,
    model: str = "eci",
    eci_model: eci.EciModel = eci.CONSISTENT,
) -> list[FiringSolutions]:
    """Every target's FiringSolutions, solved in one call of the compiled solver, and for the
    calibrated ``model`` every root found moved onto the calibrated MKS's at once."""
    laid = _Gun(gun, eci_model)
    count = len(targets)
    latitude = np.radians([target.latitude_deg for target in targets])
    longitude = np.radians([target.longitude_deg - gun.longitude_deg for target in targets])
    altitude = np.array([target.altitude_m for target in targets], dtype=float)
    descending = np.full(count, branch == "descending")
    roots, status, search, counts = solver.solve(
        laid.numbers, laid.flags, latitude, longitude, altitude, descending
    )
    degenerate = [_degenerate(target, search[i, 6], branch) for i, target in enumerate(targets)]
    usable = np.array([why is None for why in degenerate], dtype=bool)
    solved = (status == solver.FOUND) & usable[:, None]
    models = np.full(status.shape, "eci", dtype=object)
    notes = np.full(status.shape, None, dtype=object)
    if model == "calibrated" and solved.any():
        roots, counts = roots.copy(), counts.copy()
        _calibrate(gun, targets, branch, roots, solved, counts, models, notes)
    return [
        _target_solutions(
            target,
            degenerate[i],
            roots[i],
            status[i],
            search[i],
            int(counts[i]),
            models[i],
            notes[i],
            branch,
            limits,
        )
        for i, target in enumerate(targets)
    ]


def _target_solutions(
    target, degenerate, rows, status, search, count, models, notes, branch, limits
) -> FiringSolutions:
    """One target's FiringSolutions from the solver's ``rows``, ``status`` and ``search`` and
    its ``count`` of MKS trajectories; ``degenerate``, why it has none whatever the model (else
    None), ``models`` and ``notes`` whose root each is (:func:`_root`)."""
    if degenerate is not None:
        return FiringSolutions(None, None, degenerate, count, math.nan)
    reason = _out_of_reach(status, search, target, branch)
    if reason is not None:
        return FiringSolutions(None, None, reason, count, search[1])
    found, reasons = _roots(rows, status, search, target, branch, limits, models, notes)
    return FiringSolutions(found[0], found[1], "; ".join(reasons) or None, count, search[1])


def _out_of_reach(status, search, target: TargetPoint, branch: str) -> str | None:
    """Why neither root of ``target`` exists where the solver's ``status`` (2,) gives one
    reason for both (no trajectory gets there, every one escapes, beyond the maximum range);
    else None."""
    both = int(status[0]) if status[0] == status[1] else -1
    return {
        solver.NO_TRAJECTORY: (
            f"above the maximum altitude: no MKS trajectory between "
            f"{_elevation_deg(solver.LOWEST_ELEVATION_RAD)} and "
            f"{_elevation_deg(solver.HIGHEST_ELEVATION_RAD)} of elevation reaches "
            f"{target.altitude_m / 1e3:g} km on the {branch} branch"
        ),
        solver.ALL_ESCAPE: (
            "the MKS escapes at every elevation: the muzzle speed exceeds escape speed"
        ),
        solver.BEYOND_RANGE: (
            f"beyond the maximum range: the target is {_distance(search[6])} away along "
            f"the ground, the gun reaches at most {_distance(search[1])} toward it at "
            f"{target.altitude_m / 1e3:g} km altitude (at "
            f"{_elevation_deg(search[0])}; Earth-fixed ground ranges)"
        ),
    }.get(both)


def _roots(
    rows, status, search, target: TargetPoint, branch: str, limits, models, notes
) -> tuple[list[FiringSolution | None], list[str]]:
    """The low and high FiringSolution (None where there is none) of one target from the
    solver's ``rows``, ``status`` and ``search`` and whose root each is (``models``,
    ``notes``: :func:`_root`), and why each missing one is missing."""
    found: list[FiringSolution | None] = []
    reasons = []
    for side in range(2):
        if status[side] != solver.FOUND:
            found.append(None)
            reasons.append(_missing(status[side], side, search, rows[side]))
            continue
        root, why = _root(rows[side], target, branch, limits, models[side], notes[side])
        found.append(root)
        if why is not None:
            reasons.append(f"no {('low', 'high')[side]}-angle root: {why}")
    return found, reasons


def _degenerate(target: TargetPoint, distance_m: float, branch: str) -> str | None:
    """Why ``target``, ``distance_m`` from the gun along the ground, has no firing solution on
    ``branch`` whatever the model (at the gun, or on the ground on the way up); else None."""
    muzzle = branch == "ascending" and target.altitude_m == 0.0
    return _at_gun(target, distance_m) or (
        "the ascending branch meets altitude 0 only at the muzzle" if muzzle else None
    )


def _calibrate(gun, targets, branch, roots, solved, counts, models, notes) -> None:
    """The solver's ``roots`` (n, 2, fields) where ``solved`` moved onto the calibrated MKS's
    (:func:`.calibrated.refine`, all at once), in place: elevation, bearing, time of flight,
    miss, beta, apogee and Jacobian its own, its flights added to the evaluations and to
    ``counts`` (n,); ``models`` and ``notes`` (n, 2) say whose root each is, and why the ECI
    MKS's is kept where it is."""
    target, side = np.nonzero(solved)
    aims = np.array([targets[i].earth_fixed_m() for i in target])
    rows = roots[target, side]
    refined = calibrated.refine(
        gun,
        aims,
        east_north_axes(aims),
        np.array([targets[i].altitude_m for i in target], dtype=float),
        np.full(target.size, branch == "ascending"),
        rows[:, :2],
        rows[:, 7:11].reshape(-1, 2, 2),
    )
    moved = np.array([why is None for why in refined.reasons])
    rows[moved, :2] = refined.x[moved]
    rows[moved, 2] = refined.time_of_flight_s[moved]
    rows[moved, 3] = refined.miss_m[moved]
    rows[moved, 4] = refined.beta[moved]
    rows[moved, 5] = refined.apogee_altitude_m[moved]
    rows[moved, 7:11] = refined.jacobian_m_rad[moved].reshape(-1, 4)
    rows[:, 6] += refined.evaluations
    roots[target, side] = rows
    np.add.at(counts, target, refined.evaluations)
    models[target[moved], side[moved]] = "calibrated"
    notes[target, side] = refined.reasons


def _root(
    row, target: TargetPoint, branch: str, limits, model: str = "eci", note: str | None = None
) -> tuple[FiringSolution | None, str | None]:
    """The FiringSolution of a solver's root ``row`` (:data:`.solver.SOLUTION_FIELDS`) by
    ``model`` (``note``: why the ECI MKS's root stands for the calibrated MKS's), or None and
    why where the bearing limits or the arrival time rule it out."""
    elevation, bearing, time, miss, beta, apogee, evaluations = row[:7]
    bearing_deg = math.degrees(bearing) % 360.0
    if limits is not None and not _within(bearing_deg, limits):
        return None, f"bearing {bearing_deg:.3f} deg lies outside bearing_limits_deg {limits}"
    arrival = target.arrival_time_s
    fire_time = None if arrival is None else arrival - time
    if fire_time is not None and fire_time < 0:
        return None, (
            f"its time of flight {time:.1f} s exceeds arrival_time_s = {arrival:g} s: "
            "it would have to be fired before t = 0"
        )
    jacobian = row[7:11].reshape(2, 2).copy()
    jacobian.flags.writeable = False
    return FiringSolution(
        elevation_deg=math.degrees(elevation),
        bearing_deg=bearing_deg,
        time_of_flight_s=float(time),
        fire_time_s=None if fire_time is None else float(fire_time),
        miss_m=float(miss),
        beta=float(beta),
        leaves_atmosphere=bool(apogee > mks.SENSIBLE_ATMOSPHERE_M),
        mks_solves=int(evaluations),
        branch=branch,
        jacobian_m_rad=jacobian,
        model=model,
        reason=note,
    ), None


@overload
def firing_solutions(
    gun: Launch,
    targets: TargetPoint,
    *,
    bearing_limits_deg: tuple[float, float] | None = None,
    branch: str = "descending",
    model: str = "eci",
) -> FiringSolutions: ...
@overload
def firing_solutions(
    gun: Launch,
    targets: Sequence[TargetPoint],
    *,
    bearing_limits_deg: tuple[float, float] | None = None,
    branch: str = "descending",
    model: str = "eci",
) -> list[FiringSolutions]: ...
def firing_solutions(gun, targets, *, bearing_limits_deg=None, branch="descending", model="eci"):
    """The low-angle and high-angle firing solutions of ``gun`` (a Launch: its projectile,
    speed, site and Earth rotation; its elevation and bearing are ignored) onto ``targets``
    (one TargetPoint, or a sequence of them: one result each, solved together by the compiled
    solver of :mod:`.solver`, the same answers either way), meeting each on the
    trajectory's ``branch`` ("descending" or "ascending"). The bearing is limited to the arc
    turning clockwise from bearing_limits_deg[0] to [1] if given. A target out of reach, or at
    the gun (closer than :data:`AT_GUN_M` along the ground), is a result with no roots and the
    reason, not an exception. ``model="calibrated"`` moves every root onto the calibrated MKS's
    (:mod:`.calibrated`; its table learned for the gun on first use, a few seconds), keeping
    the ECI MKS's root, with the reason, where it has none (:attr:`FiringSolution.reason`).

    Parameters
    ----------
    gun : Launch
        The gun: projectile, muzzle speed, site and the Earth's rotation (its elevation and
        bearing are what is solved).
    targets : TargetPoint or list of TargetPoint
        The points to reach.
    bearing_limits_deg : (float, float), optional
        The arc of bearings (deg from true north, clockwise from the first to the second)
        the gun may take.
    branch : str
        ``"descending"`` or ``"ascending"``: where the trajectory meets the target.
    model : str
        ``"eci"`` (the text's ECI MKS) or ``"calibrated"`` (the calibrated MKS, from the ECI
        MKS's roots; a gun outside the band it learns, its muzzle speed 0.8-1.15 of the
        projectile's and its day's density within 10 %, is refused by name).

    Returns
    -------
    FiringSolutions or list of FiringSolutions
        The low-angle and high-angle roots of each target (None where there is none, with
        the reason), one result per target if ``targets`` is a sequence.
    """
    gun = check_gun(gun)
    points, single = check_targets(targets)
    branch = check_choice(branch, "branch", BRANCHES)
    limits = check_bearing_limits(bearing_limits_deg)
    model = check_choice(model, "model", MODELS)
    if model == "calibrated":
        calibrated.calibration(gun)  # the gun refused by name outside the band
    results = _solutions(gun, points, branch, limits, model)
    return results[0] if single else results


#: Barbados's gun (Ch. 6: latitude 13 deg 4' 38" N, its longitude about 59.6 deg W), HP at its
#: muzzle speed on the rotating Earth in the 3DOF's two-segment air.
BARBADOS_HP = Launch(
    HP,
    HP.launch_speed_m_s,
    45.0,
    latitude_deg=math.degrees(BARBADOS.latitude_rad),
    longitude_deg=-59.6,
    rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
)


def destination(
    gun: Launch, bearing_deg: float, downrange_m: float, altitude_m: float = 0.0
) -> TargetPoint:
    """The point ``downrange_m`` along the surface from ``gun`` (its latitude and longitude)
    on the great circle leaving it at ``bearing_deg`` from true north, ``altitude_m`` up.

    Parameters
    ----------
    gun : Launch
        The gun whose latitude and longitude the point is measured from.
    bearing_deg : float
        The bearing leaving the gun (deg from true north).
    downrange_m : float
        The distance along the surface (m), at most half the Earth's circumference.
    altitude_m : float
        The point's altitude above the spherical Earth (m).

    Returns
    -------
    TargetPoint
        The point, fixed to the Earth.
    """
    bearing = math.radians(real_number(bearing_deg, "bearing_deg"))
    distance = Bounds(low=0.0).number(downrange_m, "downrange_m")
    if distance > math.pi * earth.RADIUS_M:
        raise ValueError(
            f"downrange_m = {distance:g} m goes past the antipode "
            f"({math.pi * earth.RADIUS_M:.0f} m along the surface)"
        )
    angle = distance / earth.RADIUS_M
    up, along, _ = launch_frame(gun.latitude_rad, math.radians(gun.longitude_deg), bearing)
    point = math.cos(angle) * np.ravel(up) + math.sin(angle) * np.ravel(along)
    latitude = math.degrees(math.asin(float(np.clip(point[2], -1.0, 1.0))))
    longitude = (math.degrees(math.atan2(point[1], point[0])) + 180.0) % 360.0 - 180.0
    return TargetPoint(latitude, longitude, altitude_m)


def barbados_case() -> tuple[Launch, TargetPoint]:
    """Chapter 7's counting case: HP from Barbados at the point 150 km down the gun's bearing
    (109 deg, Ch. 6) at sea level.

    Returns
    -------
    gun : Launch
        HP at its Chapter 2 muzzle speed from Barbados on the rotating Earth
        (:data:`BARBADOS_HP`).
    target : TargetPoint
        The point 150 km down the gun's bearing, at sea level.
    """
    gun = BARBADOS_HP
    return gun, destination(gun, math.degrees(BARBADOS.gun_bearing_rad), 150e3)
