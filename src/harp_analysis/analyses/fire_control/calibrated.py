"""Firing solutions by the calibrated MKS (issue 35, item 4): Chapter 7 C's remedy for the MKS's
miss, a table learned from the gun's 3DOF flights (:mod:`harp_analysis.engines.calibrated_mks`),
put under Chapter 7 A's fire control.

The compiled ECI MKS solver (:mod:`.solver`) keeps the search: it brackets every root of a
target (low and high, the bearing free near the vertical) and lands on the ECI MKS's.
:func:`refine` then moves every root at once onto the calibrated MKS's, by Newton's method on
(elevation, bearing): the residual is the east and north miss (m) at the target of the
calibrated flight where it crosses the target's altitude on the root's branch
(:meth:`.CalibratedSolution.crossing`, fixed to the Earth), every root's flight one
:class:`.CalibratedSolution` of :class:`~harp_analysis.models.launch.Launches` per step; the
first Jacobian is the ECI root's, updated by Broyden's rule along each step, and a step that
lands further off (or nowhere) is taken again with the Jacobian differenced afresh where the
root stands, then halved. At the calibrated root the calibrated MKS's own Jacobian is taken by
forward differences (two evaluations more), so that the 3DOF's refinement
(:func:`.verify_with_3dof`), which starts from it, steps well the first time.

Where the calibrated flight at the ECI MKS's root never reaches the target's altitude (the
MKS climbs higher than the 3DOF, whose path the table learns), the elevation is raised a
quarter of a degree at a time until it does, as the 3DOF's refinement does. A root the
calibrated MKS cannot give keeps the ECI MKS's, and says why: its elevation outside the band
the table was learned on (:data:`.calibrated_mks.BAND`, 15-88 deg), its flight never reaching
the target's altitude on the branch, or Newton's method stopping off the target. A
gun outside the band itself (its muzzle speed, its day's air) is refused by name
(:func:`calibration`).

SI inside (m, s, rad).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ...engines import calibrated_mks, eci
from ...models.launch import Launch, Launches

__all__ = ["CONVERGED_M", "Refined", "calibration", "refine"]

#: Newton's method stops once the calibrated flight passes this close to the target (m): far
#: inside what the table knows of the 3DOF (tens of metres), so the root is the model's own,
#: and above the crossing's rounding (a tenth of a millimetre in altitude, more along a shallow
#: crossing).
CONVERGED_M = 0.01
#: Newton's steps at most, and the halvings of a step in a row after which a root stops.
_ITERATIONS = 20
_HALVINGS = 5
#: The forward difference (rad) of the calibrated MKS's Jacobian at its root: a step of
#: metres at the target, wide of the crossing's micrometres and narrow next to the table's
#: nodes (degrees apart).
_DIFFERENCE_RAD = 1e-6
#: Where the calibrated flight at the ECI MKS's root never gets to the target's altitude (its
#: apogee, the 3DOF's, below the ECI MKS's), the elevation is raised by this (rad) up to this
#: many times, as the 3DOF's refinement does: in steps small enough that the first elevation
#: that gets there lies below the maximum range's (a low root stays low), up to 4 deg (the
#: ECI MKS's low roots to aims a few tens of kilometres up lie up to 3 deg below the
#: calibrated MKS's).
_RAISE_RAD = math.radians(0.25)
_RAISES = 16
_LOWEST_RAD, _HIGHEST_RAD = (math.radians(value) for value in calibrated_mks.BAND.elevations_deg)


class Refined(NamedTuple):
    """Each root's (k,) calibrated firing solution, or where ``reasons`` gives why not (the
    ECI MKS's root to be kept), what Newton's method reached."""

    x: np.ndarray  # (k, 2): elevation and bearing (rad)
    miss_m: np.ndarray  # the calibrated flight's miss at the target
    time_of_flight_s: np.ndarray  # to its crossing of the target's altitude
    jacobian_m_rad: np.ndarray  # (k, 2, 2): d(east, north miss)/d(elevation, bearing)
    beta: np.ndarray  # eq 3.22 of the ECI launch at the root (eq 6.11)
    apogee_altitude_m: np.ndarray  # the calibrated flight's
    evaluations: np.ndarray  # calibrated MKS flights evaluated, per root
    reasons: list[str | None]


def calibration(gun: Launch) -> calibrated_mks.Calibration:
    """The calibration of ``gun`` (:func:`.calibrated_mks.calibration_for`, learned on first
    use), its elevation and bearing ignored; a ValueError naming the field where its muzzle
    speed or its day's air lies outside the band the calibrated MKS learns."""
    laid = gun.but(elevation_deg=math.degrees(0.5 * (_LOWEST_RAD + _HIGHEST_RAD)))
    return calibrated_mks.calibration_for(laid)


class _Shots:
    """The calibrated MKS of one gun laid at many (elevation, bearing) pairs at once, each to
    its target's altitude on its branch: the east and north miss (m) at each target."""

    def __init__(self, gun: Launch, aims_m, axes, altitudes_m, rising):
        self.launches = Launches.from_launches([gun])
        self.calibration = calibration(gun)
        self.aims, self.axes = aims_m, axes
        self.altitudes, self.rising = altitudes_m, rising
        self.evaluations = np.zeros(len(aims_m), dtype=int)

    def solution(self, x: np.ndarray) -> calibrated_mks.CalibratedSolution:
        laid = self.launches.but(
            elevation_deg=np.degrees(x[:, 0]), bearing_deg=np.degrees(x[:, 1]) % 360.0
        )
        return calibrated_mks.CalibratedSolution(laid, self.calibration)

    def miss(self, x: np.ndarray, which: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The miss (k, 2) of the shots at ``x`` (k, 2; rad) for targets ``which`` (k,), NaN
        where the flight never crosses its target's altitude on its branch, and the times of
        flight (k,) to the crossing."""
        time, point = self.solution(x).crossing(self.altitudes[which], self.rising[which])
        np.add.at(self.evaluations, which, 1)
        aims = self.aims[which]
        return np.einsum("kij,kj->ki", self.axes[which], point - aims), time

    def jacobian(self, x: np.ndarray, miss: np.ndarray, which: np.ndarray) -> np.ndarray:
        """Forward differences (k, 2, 2) of the miss at ``x`` (backward in elevation at the
        band's top): two evaluations each."""
        columns = []
        for k in range(2):
            step = np.full(len(which), _DIFFERENCE_RAD)
            if k == 0:
                step[x[:, 0] + step > _HIGHEST_RAD] *= -1.0
            shifted = x.copy()
            shifted[:, k] += step
            columns.append((self.miss(shifted, which)[0] - miss) / step[:, None])
        return np.stack(columns, axis=-1)


def refine(
    gun: Launch,
    aims_m: np.ndarray,
    axes: np.ndarray,
    altitudes_m: np.ndarray,
    rising: np.ndarray,
    x: np.ndarray,
    jacobian: np.ndarray,
) -> Refined:
    """Every ECI MKS root moved onto the calibrated MKS's, all at once (the module's method).

    Parameters
    ----------
    gun : Launch
        The gun: its calibration (:func:`calibration`) is learned on first use.
    aims_m : numpy.ndarray
        (k, 3): each root's target, fixed to the Earth in the 3DOF's frame
        (:meth:`.firing.TargetPoint.earth_fixed_m`).
    axes : numpy.ndarray
        (k, 2, 3): the unit vectors east and north at each target.
    altitudes_m, rising : numpy.ndarray
        (k,): each target's altitude, and whether its root meets it on the way up.
    x, jacobian : numpy.ndarray
        (k, 2) and (k, 2, 2): each ECI MKS root's elevation and bearing (rad) and its
        Jacobian (m/rad).

    Returns
    -------
    Refined
        The calibrated roots, or why not.
    """
    count = len(x)
    shots = _Shots(gun, aims_m, axes, altitudes_m, rising)
    start = np.array(x, dtype=float)
    x = start.copy()
    x[:, 0] = np.clip(x[:, 0], _LOWEST_RAD, _HIGHEST_RAD)
    jacobian = np.array(jacobian, dtype=float)
    everyone = np.arange(count)
    miss, time = shots.miss(x, everyone)
    for _ in range(_RAISES):
        short = everyone[~np.isfinite(miss[:, 0]) & (x[:, 0] < _HIGHEST_RAD)]
        if not short.size:
            break
        x[short, 0] = np.minimum(x[short, 0] + _RAISE_RAD, _HIGHEST_RAD)
        miss[short], time[short] = shots.miss(x[short], short)
    size = np.hypot(miss[:, 0], miss[:, 1])
    reached = np.isfinite(size)
    scale = np.ones(count)  # the share of Newton's step a root takes: halved where one failed
    fresh = np.zeros(count, dtype=bool)  # its Jacobian differenced where it stands
    for _ in range(_ITERATIONS):
        which = everyone[reached & (size > CONVERGED_M) & (scale > 0.5**_HALVINGS)]
        if not which.size:
            break
        step = _newton_steps(jacobian[which], miss[which])
        trial = x[which] + scale[which, None] * step
        trial[:, 0] = np.clip(trial[:, 0], _LOWEST_RAD, _HIGHEST_RAD)
        taken = trial - x[which]
        new_miss, new_time = shots.miss(trial, which)
        new_size = np.hypot(new_miss[:, 0], new_miss[:, 1])
        # Broyden's update along every step that got there, closer or not
        norm = np.sum(taken * taken, axis=1)
        usable = np.isfinite(new_size) & (norm > 0)
        change = new_miss - miss[which] - np.einsum("kij,kj->ki", jacobian[which], taken)
        jacobian[which[usable]] += (
            np.einsum("ki,kj->kij", change, taken)[usable] / norm[usable, None, None]
        )
        better = new_size < size[which]  # False where it never got there (NaN)
        kept = which[better]
        x[kept], miss[kept], time[kept], size[kept] = (
            trial[better],
            new_miss[better],
            new_time[better],
            new_size[better],
        )
        scale[kept], fresh[kept] = 1.0, False
        # a step that failed: the Jacobian differenced afresh, then the step halved
        failed = which[~better]
        scale[failed[fresh[failed]]] *= 0.5
        _difference(shots, jacobian, x, miss, failed[~fresh[failed]])
        fresh[failed] = True
    landed = reached & (size <= CONVERGED_M)
    _difference(shots, jacobian, x, miss, everyone[landed & ~fresh])
    solution = shots.solution(x)
    np.add.at(shots.evaluations, everyone, 1)
    reasons = [
        None if landed[i] else _why(start[i], x[i], size[i], reached[i], rising[i])
        for i in range(count)
    ]
    return Refined(
        x,
        size,
        time,
        jacobian,
        np.ravel(eci.correction_for_launch(solution.launch).beta),
        np.atleast_1d(solution.apogee_altitude_m),
        shots.evaluations,
        reasons,
    )


def _difference(shots: _Shots, jacobian, x, miss, which: np.ndarray) -> None:
    """``jacobian`` (k, 2, 2) of the roots ``which`` differenced afresh where they stand
    (:meth:`_Shots.jacobian`), in place, where each neighbour gets to the target's altitude."""
    if which.size:
        fresh = shots.jacobian(x[which], miss[which], which)
        whole = np.isfinite(fresh).all(axis=(1, 2))
        jacobian[which[whole]] = fresh[whole]


def _newton_steps(jacobian: np.ndarray, miss: np.ndarray) -> np.ndarray:
    """-J^-1 miss of every root (k, 2) by Cramer's rule; zero where J (k, 2, 2) is singular."""
    (a, b), (c, d) = jacobian[:, 0].T, jacobian[:, 1].T
    with np.errstate(invalid="ignore", divide="ignore"):
        step = -np.stack([d * miss[:, 0] - b * miss[:, 1], a * miss[:, 1] - c * miss[:, 0]], 1)
        step /= (a * d - b * c)[:, None]
    return np.where(np.isfinite(step), step, 0.0)


def _why(start: np.ndarray, x: np.ndarray, size: float, reached: bool, rising: bool) -> str:
    """Why the calibrated MKS gave no root from the ECI MKS's at ``start`` (rad), Newton's
    method having reached ``x`` ``size`` m off (``reached``: its first flight crossed the
    target's altitude)."""
    low, high = calibrated_mks.BAND.elevations_deg
    for edge, below, word in ((_LOWEST_RAD, True, "below"), (_HIGHEST_RAD, False, "above")):
        outside = start[0] < edge if below else start[0] > edge
        if outside or abs(x[0] - edge) < 1e-9:
            return (
                f"the {calibrated_mks.ENGINE} puts the root {word} {math.degrees(edge):g} deg "
                f"of elevation (the ECI MKS's: {math.degrees(start[0]):.2f} deg), outside the "
                f"band its table was learned on ({low:g}-{high:g} deg)"
            )
    if not reached:
        way = "climbs" if rising else "comes down"
        return (
            f"the {calibrated_mks.ENGINE} flown at the ECI MKS's root, and up to "
            f"{math.degrees(_RAISES * _RAISE_RAD):g} deg above it, never {way} through the "
            "target's altitude (its apogee lies below it)"
        )
    return (
        f"Newton's method on the {calibrated_mks.ENGINE} stopped {size:.3g} m from the target: "
        "no calibrated root near the ECI MKS's"
    )
