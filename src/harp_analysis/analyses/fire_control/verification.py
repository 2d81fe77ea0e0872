"""The 3DOF's check of an MKS firing solution (Chapter 7 A):
:func:`~harp_analysis.analyses.fire_control.verification.verify_with_3dof` flies the 3DOF (the
launch's own atmosphere and drag law, the rotating Earth) at the MKS solution of :mod:`.firing`,
measures its miss, and refines the solution by shooting with the 3DOF itself, every solution flown
together in the compiled batch: the MKS's 3DOF miss is the model error the text's method accepts.

The refinement is Newton's method on (elevation, bearing), the MKS's Jacobian at its root
updated by Broyden's rule, which lands most roots in a few flights. It stalls where the miss is
far from linear: near the grazing elevation, where the 3DOF's apogee just reaches the target's
altitude and the crossing moves as the square root of the elevation above it (below it there is
no crossing at all), and near the descending branch's maximum range, where its two roots merge.
There the 3DOF's branch is searched, root by root (``_search()``): at a bearing, the grazing
elevation is solved on the apogee, on the descending branch the maximum range found, and the
crossing's distance from the gun solved onto the target's by Brent's method in the square root
of the elevation above the foot of the part of the branch where it is monotone; then the
bearing is turned to put the crossing on the target's azimuth from the gun, and again until the
shot lands. A root is reported missing only where the 3DOF shows it missing, its reach quoted.
On the descending branch the search keeps to the side of the 3DOF's maximum range where the
MKS's root lies (its elevation below or above the 3DOF's of the maximum range); a root Newton's
method lands is not searched, whichever side it lands on.

SI inside (m, s, rad); degrees only in the arguments and fields named ``_deg``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache, partial
from typing import NamedTuple, overload

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ...engines import threedof
from ...foundation import earth
from ...foundation.sweeps import client_shares, sweep
from ...foundation.validation import Bounds
from ...models.launch import Launch
from ...models.trajectory import launch_axes, surface_range
from . import solver
from .firing import (
    BRANCHES,
    FiringSolution,
    TargetPoint,
    check_gun,
    check_targets,
    east_north,
    east_north_axes,
)

__all__ = ["Verification", "verify_with_3dof", "LANDED_M"]

#: The 3DOF refinement stops once every solution lands this close (m): at rtol = 1e-9 the
#: 3DOF's own end point is good to millimetres.
LANDED_M = 0.01
#: Newton's method takes at most this many 3DOF flights per solution, and at most this many
#: steps in a row that fail to halve the miss, before the branch is searched instead.
_MAX_FLIGHTS = 30
_FAILURES = 4
#: Where the 3DOF at the MKS solution falls short of the target's altitude, the elevation is
#: raised by this (rad) up to this many times.
_RAISES = 8
_RAISE_RAD = math.radians(0.25)
#: The branch search: the elevations it searches (rad; the MKS solver's) and the bearings it
#: tries at most. Brent's method solves the grazing elevation to _GRAZING_RAD (the 3DOF's apogee
#: is good to tenths of a millimetre, a nanoradian of elevation), a root to _ROOT_WIDTH in the
#: square root of the elevation (rad) above its bracket's foot (a tenth of a millimetre along
#: the track, below the 3DOF's own millimetres) and the maximum range to _PEAK_RAD.
_LOWEST_RAD, _HIGHEST_RAD = solver.LOWEST_ELEVATION_RAD, solver.HIGHEST_ELEVATION_RAD
_PASSES = 6
_GRAZING_RAD = 1e-9
_ROOT_WIDTH = 1e-10
_PEAK_RAD = 1e-5
#: A flight flown for its apogee ends this far below the target's altitude (m), falling: past
#: the apogee of every shot the grazing elevation's solve flies, without the fall to the ground.
_BELOW_M = 1e3
#: No shot is flown flatter than this (rad): the 3DOF's elevations lie in (0, 90] deg.
_FLATTEST_RAD = math.radians(1e-9)


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
    converged: bool  # landed within the tolerance
    message: str
    rhs_evaluations: int = 0  # of the 3DOF's equations of motion, over all its flights


class _Shot(NamedTuple):
    """One 3DOF shot at a target where it crossed the target's altitude on its branch: its
    laying (rad), east and north miss (m), time of flight (s), the ground distances from the gun
    (m, along the great circle) of its crossing (NaN where it never got there) and of the
    target, and the turn of the bearing (rad) that puts the crossing on the target's azimuth
    from the gun."""

    elevation_rad: float
    bearing_rad: float
    miss_m: tuple[float, float]
    time_s: float
    range_m: float
    aim_range_m: float
    turn_rad: float

    @property
    def excess_m(self) -> float:
        """How much farther from the gun than the target (m) the shot crosses its altitude."""
        return self.range_m - self.aim_range_m

    @property
    def missed_by_m(self) -> float:
        """How far from the target the shot crosses its altitude (m)."""
        return math.hypot(*self.miss_m)


class _Batch3dof:
    """The 3DOF flown at many (elevation, bearing) pairs of one gun at once, each to its
    target's altitude on its branch: the east and north miss (m) at each target; and one shot
    at a time for the branch search, with its apogee."""

    def __init__(self, gun: Launch, targets: list[TargetPoint], rising: np.ndarray, rtol: float):
        self.layings = threedof.Layings(gun, rtol=rtol)  # the gun validated once, here
        self.site = gun.latitude_rad, math.radians(gun.longitude_deg)
        self.aims = np.array([target.earth_fixed_m() for target in targets])  # 3DOF's frame
        self.axes = east_north_axes(self.aims)
        self.altitudes = np.array([target.altitude_m for target in targets])
        self.rising = rising
        self.flights = np.zeros(len(targets), dtype=int)
        self.rhs_evaluations = np.zeros(len(targets), dtype=int)

    def fly(self, elevation, bearing, which, end_m=None, rising=None) -> threedof.Flights:
        """The flights at ``elevation`` and ``bearing`` (k,; rad) for targets ``which`` (k,),
        each to its target's altitude on its branch, or to ``end_m`` (k,) rising where
        ``rising`` (k,) if given; quietly (a short shot never crosses its end altitude)."""
        flight = self.layings.fly(
            np.clip(elevation, _FLATTEST_RAD, 0.5 * math.pi),
            bearing,
            self.altitudes[which] if end_m is None else end_m,
            self.rising[which] if rising is None else rising,
        )
        np.add.at(self.flights, which, 1)
        np.add.at(self.rhs_evaluations, which, flight.rhs_evaluations)
        return flight

    def miss(self, x: np.ndarray, which: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The miss (k, 2) of the shots at ``x`` (k, 2; rad) for targets ``which`` (k,), NaN
        where the shot never reaches its target's altitude (a short shot misses), and the times
        of flight (k,)."""
        flight = self.fly(x[:, 0], x[:, 1], which)
        return self.miss_of(flight, which), np.where(flight.impact, flight.time_of_flight_s, np.nan)

    def miss_of(self, flight: threedof.Flights, which: np.ndarray) -> np.ndarray:
        """The east and north miss (k, 2) of ``flight`` at targets ``which``, NaN where it
        never reached its target's altitude."""
        aims = self.aims[which]
        miss = east_north(flight.end_position_m.T - aims, aims, self.axes[which])
        miss[~flight.impact] = np.nan
        return miss

    def jacobian(self, x, miss, which) -> np.ndarray:
        """Forward differences (k, 2, 2) of the miss at ``x``: two flights each."""
        step = 1e-7  # rad: centimetres at the target, far above the 3DOF's noise at rtol 1e-9
        columns = []
        for k in range(2):
            shifted = x.copy()
            shifted[:, k] += step
            columns.append((self.miss(shifted, which)[0] - miss) / step)
        return np.stack(columns, axis=-1)

    def shot(self, elevation: float, bearing: float, i: int) -> _Shot:
        """The shot at ``elevation`` and ``bearing`` (rad) at target ``i``, on its branch."""
        which = np.array([i])
        flight = self.fly(np.array([elevation]), np.array([bearing]), which)
        reached = bool(flight.impact[0])
        up, downrange, _ = launch_axes(*self.site, bearing)
        aim = surface_range(tuple(self.aims[i]), up, downrange)
        crossing = flight.range_m[0], flight.cross_range_m[0]
        turn = _azimuth(*aim) - _azimuth(*crossing)
        east, north = self.miss_of(flight, which)[0]
        return _Shot(
            elevation,
            bearing,
            (float(east), float(north)),
            float(flight.time_of_flight_s[0]) if reached else math.nan,
            _from_gun(*crossing) if reached else math.nan,
            _from_gun(*aim),
            float((turn + math.pi) % (2 * math.pi) - math.pi) if reached else math.nan,
        )

    def apogee_m(self, elevation: float, bearing: float, i: int) -> float:
        """The apogee's altitude (m) of the shot at ``elevation`` and ``bearing`` (rad) at
        target ``i``, flown past it (to :data:`_BELOW_M` under the target's altitude, falling,
        or to the ground)."""
        end = np.array([max(self.altitudes[i] - _BELOW_M, 0.0)])
        falling = np.array([False])
        flight = self.fly(np.array([elevation]), np.array([bearing]), np.array([i]), end, falling)
        return float(flight.apogee_altitude_m[0])


def _azimuth(range_m, cross_range_m):
    """The azimuth (rad) from the gun, from its line of fire to the right, of the point of the
    ground ``range_m`` along the line and ``cross_range_m`` to its right (surface ranges)."""
    return np.arctan2(np.tan(cross_range_m / earth.RADIUS_M), np.sin(range_m / earth.RADIUS_M))


def _from_gun(range_m: float, cross_range_m: float) -> float:
    """The ground distance (m, along the great circle) from the gun of the point of the ground
    ``range_m`` along its line of fire and ``cross_range_m`` to its right (surface ranges)."""
    along, across = range_m / earth.RADIUS_M, cross_range_m / earth.RADIUS_M
    return earth.RADIUS_M * math.atan2(
        math.hypot(math.cos(across) * math.sin(along), math.sin(across)),
        math.cos(across) * math.cos(along),
    )


# --- the search of the 3DOF's branch, where Newton's method stalls ------------------------------
def _km(metres: float) -> str:
    return f"{metres / 1e3:.3f} km"


def _search(
    shots: _Batch3dof, i: int, bearing: float, mks_elevation: float, tolerance_m: float
) -> tuple[_Shot, str | None]:
    """The 3DOF's root of target ``i`` on its branch, searched from ``bearing`` (rad): at each
    bearing the elevation solved (:func:`_on_bearing`), then the bearing turned to put the
    crossing on the target's azimuth from the gun, until the shot lands or the turn would move
    the crossing less than a quarter of the tolerance (where the root is missing, less than a
    tenth of the shortfall). The last shot, and why the root is missing (None where found)."""
    for _ in range(_PASSES):
        shot, reason = _on_bearing(shots, i, bearing, mks_elevation, 0.25 * tolerance_m)
        across = abs(shot.turn_rad * shot.range_m)  # how far the turn moves the crossing (m)
        enough = 0.1 * abs(shot.excess_m) if reason else 0.25 * tolerance_m
        if shot.missed_by_m <= tolerance_m or not across > enough:
            break
        bearing += shot.turn_rad
    return shot, reason


def _on_bearing(
    shots: _Batch3dof, i: int, bearing: float, mks_elevation: float, within_m: float
) -> tuple[_Shot, str | None]:
    """The 3DOF's root of target ``i`` on its branch at ``bearing`` (rad), or the shot that
    shows it missing and why. From the branch's foot (:func:`_grazing`) up, the crossing's
    distance falls on the ascending branch; on the descending one it rises to the maximum range
    (:func:`_peak`) and falls beyond it, and the root is sought on the side of it where
    ``mks_elevation`` (rad), the MKS's root, lies (:func:`_solve` between the ends of that part
    of the branch, to ``within_m`` along it)."""
    altitude, rising = shots.altitudes[i], bool(shots.rising[i])

    @cache  # each shot flown once
    def shoot(elevation: float) -> _Shot:
        return shots.shot(elevation, bearing, i)

    def missing(why: str, where: str, shot: _Shot) -> tuple[_Shot, str]:
        return shot, _missing(why, where, shot, altitude, rising)

    top = shoot(_HIGHEST_RAD)
    highest = f"{math.degrees(_HIGHEST_RAD):.2f} deg, the highest elevation searched"
    if math.isnan(top.range_m):
        apogee = shots.apogee_m(_HIGHEST_RAD, bearing, i)
        return top, (
            f"the 3DOF never reaches the aim's altitude, {altitude / 1e3:g} km: at {highest}, "
            f"its apogee is {_km(apogee)}"
        )
    at_foot, grazing = _at_foot(shoot, _grazing(shots, i, bearing))
    if rising:
        if at_foot.excess_m < 0:
            return missing("the aim lies beyond the ascending branch's reach", grazing, at_foot)
        low, high = at_foot, top
    else:
        peak = _peak(shoot, at_foot.elevation_rad)
        if peak.excess_m < 0:
            where = f"{math.degrees(peak.elevation_rad):.3f} deg, its maximum range"
            return missing("the aim lies beyond the descending branch's reach", where, peak)
        low, high = (at_foot, peak) if mks_elevation < peak.elevation_rad else (peak, top)
        if low is at_foot and at_foot.excess_m > 0:
            return missing("no low-angle 3DOF root", grazing, at_foot)
    if high is top and top.excess_m > 0:
        return missing(f"the aim lies short of the {BRANCHES[rising]} branch", highest, top)
    return _solve(shoot, low, high, within_m), None


def _missing(why: str, where: str, shot: _Shot, altitude: float, rising: bool) -> str:
    """Why a root is missing (``why``), shown by ``shot`` at ``where``: how far from the gun
    the 3DOF crosses the target's ``altitude`` (m) there, and how far the aim is."""
    way = "crosses" if rising else "comes down through"
    against = (
        f"at most {_km(shot.range_m)} from the gun, the aim {_km(shot.aim_range_m)}"
        if shot.excess_m < 0
        else f"{_km(shot.range_m)} from the gun already, the aim {_km(shot.aim_range_m)}"
    )
    return f"{why}: at {where}, the 3DOF {way} {altitude / 1e3:g} km {against}"


def _at_foot(shoot, foot: float) -> tuple[_Shot, str]:
    """The shot at the branch's ``foot`` (rad; :func:`_grazing`), raised by doubling steps
    where its clearance is below the 3DOF's resolution of the crossing, and where it is for a
    message."""
    at_foot, rise = shoot(foot), 1e-9
    while math.isnan(at_foot.range_m):
        at_foot, rise = shoot(min(foot + rise, _HIGHEST_RAD)), 2.0 * rise
    if foot == _LOWEST_RAD:
        return at_foot, f"{math.degrees(foot):.2f} deg, the lowest elevation searched"
    return at_foot, f"the grazing elevation {math.degrees(at_foot.elevation_rad):.4f} deg"


def _grazing(shots: _Batch3dof, i: int, bearing: float) -> float:
    """The foot of target ``i``'s branch at ``bearing`` (rad), where the highest elevation
    searched reaches the target's altitude: the grazing elevation, the lowest at which the
    3DOF's apogee reaches it (Brent's method on the apogee less the altitude, which rises with
    the elevation), or the lowest elevation searched where that reaches it already."""

    @cache  # Brent's method flies its ends again
    def clearance(elevation: float) -> float:
        return shots.apogee_m(elevation, bearing, i) - shots.altitudes[i]

    if clearance(_LOWEST_RAD) >= 0:
        return _LOWEST_RAD
    return brentq(clearance, _LOWEST_RAD, _HIGHEST_RAD, xtol=_GRAZING_RAD)


def _peak(shoot, foot: float) -> _Shot:
    """The shot of the descending branch's maximum range, above its ``foot`` (rad): Brent's
    bounded search, to :data:`_PEAK_RAD`."""
    found = minimize_scalar(
        lambda elevation: -shoot(elevation).range_m,
        bounds=(foot, _HIGHEST_RAD),
        method="bounded",
        options={"xatol": _PEAK_RAD},
    )
    return shoot(found.x)


def _solve(shoot, low: _Shot, high: _Shot, within_m: float) -> _Shot:
    """The shot between ``low`` and ``high``, whose crossings lie either side of the target
    along the bearing, that crosses within ``within_m`` of the target's distance: Brent's method
    in the square root of the elevation above ``low``'s, in which the crossing's distance is
    smooth (above grazing it moves as that square root), stopped by a crossing that close."""
    base, top = low.elevation_rad, math.sqrt(high.elevation_rad - low.elevation_rad)
    flown = {0.0: low, top: high}  # the shots by the square root, the ends known

    def excess(s: float) -> float:
        if s not in flown:
            flown[s] = shoot(base + s * s)
        return flown[s].excess_m if abs(flown[s].excess_m) > within_m else 0.0

    brentq(excess, 0.0, top, xtol=_ROOT_WIDTH)
    return min(flown.values(), key=lambda shot: abs(shot.excess_m))


# --- the refinement -----------------------------------------------------------------------------
def _newton(shots: _Batch3dof, x, miss, time, jacobian, tolerance_m: float) -> None:
    """Newton's method on each solution's (elevation, bearing) ``x`` (k, 2; rad), in place with
    its ``miss`` (k, 2), ``time`` (k,) and ``jacobian`` (k, 2, 2): one flight per solution and
    step, the Jacobian updated by Broyden's rule along each step, differenced by the 3DOF only
    where a step fails to halve the miss, until each lands within ``tolerance_m`` or stalls."""
    everyone = np.arange(x.shape[0])
    size = np.hypot(miss[:, 0], miss[:, 1])
    failures = np.zeros(x.shape[0], dtype=int)  # steps in a row that did not halve the miss
    active = np.isfinite(size) & (size > tolerance_m)
    while active.any():
        which = everyone[active & (shots.flights < _MAX_FLIGHTS) & (failures < _FAILURES)]
        if not which.size:
            break
        # a singular Jacobian has no step (differenced at the vertical, where a step of either
        # angle flies the same shot, it is zero)
        regular = np.linalg.det(jacobian[which]) != 0.0
        step = np.zeros((which.size, 2))
        with np.errstate(invalid="ignore", divide="ignore"):
            step[regular] = -np.linalg.solve(
                jacobian[which][regular], miss[which][regular][..., None]
            )[..., 0]
        step[~np.isfinite(step)] = 0.0
        trial = x[which] + step
        trial[:, 0] = np.clip(trial[:, 0], _FLATTEST_RAD, 0.5 * math.pi)
        step = trial - x[which]
        new_miss, new_time = shots.miss(trial, which)
        new_size = np.hypot(new_miss[:, 0], new_miss[:, 1])
        landed = np.isfinite(new_size)
        # Broyden's update along the step, where the shot got there
        change = new_miss - miss[which]
        predicted = np.einsum("kij,kj->ki", jacobian[which], step)
        norm = np.sum(step * step, axis=1)
        update = np.where(
            (landed & (norm > 0))[:, None, None],
            np.einsum("ki,kj->kij", change - predicted, step)
            / np.maximum(norm, 1e-300)[:, None, None],
            0.0,
        )
        jacobian[which] += np.nan_to_num(update)
        # a shot that never got there: half the step next time, from the same point
        accepted = which[landed]
        x[accepted], miss[accepted], time[accepted] = (
            trial[landed],
            new_miss[landed],
            new_time[landed],
        )
        worse = landed & (new_size > 0.5 * size[which]) & (new_size > tolerance_m)
        stalled = which[worse]
        failures[which] = np.where(worse | ~landed, failures[which] + 1, 0)
        size[accepted] = new_size[landed]
        if stalled.size:
            jacobian[stalled] = shots.jacobian(x[stalled], miss[stalled], stalled)
        failed = which[~landed]
        if failed.size:
            jacobian[failed] *= 2.0  # halves the next step
        active = np.isfinite(size) & (size > tolerance_m)


def _refine_3dof(
    gun: Launch,
    targets: list[TargetPoint],
    solutions: list[FiringSolution],
    rtol: float,
    tolerance_m: float,
) -> list[Verification]:
    """Every solution refined by the 3DOF: Newton's method from the MKS's root (its Jacobian
    there, its model error small next to the sensitivities), all flown together each
    iteration, then the search of the branch for each solution it leaves unlanded."""
    count = len(targets)
    shots = _Batch3dof(gun, targets, np.array([s.branch == "ascending" for s in solutions]), rtol)
    x = np.radians([[s.elevation_deg, s.bearing_deg] for s in solutions])
    start = x.copy()
    everyone = np.arange(count)
    miss, time = shots.miss(x, everyone)
    first = np.hypot(miss[:, 0], miss[:, 1])
    jacobian = np.array(
        [
            np.full((2, 2), np.nan) if s.jacobian_m_rad is None else s.jacobian_m_rad
            for s in solutions
        ]
    )
    _get_there(shots, x, miss, time, jacobian)
    _newton(shots, x, miss, time, jacobian, tolerance_m)
    reasons: list[str | None] = [None] * count
    for i in everyone[~(np.hypot(miss[:, 0], miss[:, 1]) <= tolerance_m)]:
        shot, reasons[i] = _search(shots, i, x[i, 1], start[i, 0], tolerance_m)
        x[i], miss[i], time[i] = (shot.elevation_rad, shot.bearing_rad), shot.miss_m, shot.time_s
    size = np.hypot(miss[:, 0], miss[:, 1])
    return [
        _verification(
            solution, x[i], start[i], first[i], size[i], time[i], reasons[i], shots, i, tolerance_m
        )
        for i, solution in enumerate(solutions)
    ]


def _get_there(shots: _Batch3dof, x, miss, time, jacobian) -> None:
    """Newton's start, in place: where the 3DOF at the MKS solution falls short of the
    target's altitude (the MKS's apogee just above it, the 3DOF's below), the elevation raised
    until it gets there; the Jacobian differenced by the 3DOF where the solution has none."""
    everyone = np.arange(x.shape[0])
    for _ in range(_RAISES):
        short = everyone[~np.isfinite(miss[:, 0])]
        if not short.size:
            break
        x[short, 0] = np.minimum(x[short, 0] + _RAISE_RAD, 0.5 * math.pi)
        miss[short], time[short] = shots.miss(x[short], short)
    unknown = ~np.isfinite(jacobian).all(axis=(1, 2)) & np.isfinite(miss[:, 0])
    if unknown.any():
        which = everyone[unknown]
        jacobian[which] = shots.jacobian(x[which], miss[which], which)


def _verification(
    solution: FiringSolution, x, start, first, size, time, reason, shots, i, tolerance_m
) -> Verification:
    """The Verification of ``solution`` (index ``i`` of the batch ``shots``), refined to
    ``x`` (rad) from ``start`` with the 3DOF's miss ``first`` (m) there and ``size`` at the
    end, arriving at ``time`` (s); ``reason``, why its root is missing (None where it is not,
    or not shown so)."""
    elevation, bearing = math.degrees(x[0]), math.degrees(x[1]) % 360.0
    converged = bool(size <= tolerance_m)
    message = (
        f"landed within {tolerance_m:g} m"
        if converged
        else reason
        or f"stopped {size:.3g} m from the target after {shots.flights[i]} flights: the "
        "3DOF's crossing settles no closer on its branch"
    )
    return Verification(
        mks_miss_m=float(first) if np.isfinite(first) else math.inf,
        elevation_deg=elevation,
        bearing_deg=bearing,
        elevation_change_deg=elevation - solution.elevation_deg,
        bearing_change_deg=(math.degrees(x[1] - start[1]) + 180.0) % 360.0 - 180.0,
        miss_m=float(size) if np.isfinite(size) else math.inf,
        time_of_flight_s=float(time),
        flights=int(shots.flights[i]),
        converged=converged,
        message=message,
        rhs_evaluations=int(shots.rhs_evaluations[i]),
    )


@overload
def verify_with_3dof(
    gun: Launch,
    targets: TargetPoint,
    solutions: FiringSolution,
    *,
    rtol: float = 1e-9,
    tolerance_m: float = LANDED_M,
    client=None,
) -> Verification: ...
@overload
def verify_with_3dof(
    gun: Launch,
    targets: Sequence[TargetPoint],
    solutions: Sequence[FiringSolution],
    *,
    rtol: float = 1e-9,
    tolerance_m: float = LANDED_M,
    client=None,
) -> list[Verification]: ...
def verify_with_3dof(gun, targets, solutions, *, rtol=1e-9, tolerance_m=LANDED_M, client=None):
    """The 3DOF (the gun's own atmosphere, drag law and Earth rotation) fired at each MKS
    firing solution and its miss where it crosses its target's altitude on the solution's
    branch, then refined by shooting with the 3DOF until it lands within ``tolerance_m``: every
    solution flown together in the compiled batch, one flight per solution and Newton step,
    the MKS's own Jacobian at the root (updated by Broyden's rule) in place of differences.
    Where Newton's method stalls or the shot falls short of the altitude, the 3DOF's branch is
    searched (the module's description): a root is reported missing only where the 3DOF
    shows it so, with its reason (the aim beyond the branch's reach, the reach quoted). One
    target and solution, or sequences of them (one Verification each, the same answers either
    way); given a Dask ``client``, the solutions are shared out in chunks among its workers
    (:func:`.sweeps.sweep`).

    Parameters
    ----------
    gun : Launch
        The gun the solutions are for (its own elevation and bearing are not used).
    targets : TargetPoint or sequence of TargetPoint
        The points aimed at.
    solutions : FiringSolution or sequence of FiringSolution
        One MKS firing solution per target (a root of :func:`.firing_solutions`).
    rtol : float
        The 3DOF integrator's relative tolerance.
    tolerance_m : float
        The refinement stops once the 3DOF lands this close to its target (m).
    client : dask.distributed.Client, optional
        Shares the solutions out among its workers; None flies them in this process.

    Returns
    -------
    Verification or list of Verification
        For each solution: the 3DOF's miss at the MKS solution, the refined elevation and
        bearing and their change, the refined miss and time of flight, the flights it took,
        whether it converged and why not; a root the 3DOF lacks ends at the shot that shows it
        missing (at the grazing elevation, the maximum range or an end of the elevations
        searched).
    """
    gun = check_gun(gun)
    points, single = check_targets(targets)
    chosen = _check_solutions(solutions, single, len(points))
    tolerance = Bounds(low=0.0, low_inclusive=False).number(tolerance_m, "tolerance_m")
    rtol = Bounds(low=0.0, high=1e-3, low_inclusive=False).number(rtol, "rtol")
    if client is None:
        results = _refine_3dof(gun, points, chosen, rtol, tolerance)
    else:
        refine = partial(_refine_chunk, gun=gun, rtol=rtol, tolerance_m=tolerance)
        chunks = sweep(refine, client_shares(list(zip(points, chosen)), client), client=client)
        results = [result for chunk in chunks for result in chunk]
    return results[0] if single else results


def _check_solutions(solutions, single: bool, count: int) -> list[FiringSolution]:
    """``solutions`` as a list, checked to be one FiringSolution for each of ``count`` targets
    (one, not in a sequence, where ``single``)."""
    chosen = [solutions] if single else list(solutions) if isinstance(solutions, Sequence) else None
    if chosen is None or len(chosen) != count:
        raise ValueError(
            "solutions must be one FiringSolution per target "
            f"({count} targets; got {type(solutions).__name__})"
        )
    for index, solution in enumerate(chosen):
        if not isinstance(solution, FiringSolution):
            raise TypeError(
                f"solutions[{index}] must be a FiringSolution; got {type(solution).__name__}"
            )
    return chosen


def _refine_chunk(chunk, gun, rtol, tolerance_m) -> list[Verification]:
    """:func:`_refine_3dof` of a chunk of (target, solution) pairs (a Dask worker's share)."""
    targets, solutions = zip(*chunk, strict=True)
    return _refine_3dof(gun, list(targets), list(solutions), rtol, tolerance_m)
