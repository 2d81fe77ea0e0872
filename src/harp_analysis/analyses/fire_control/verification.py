"""The 3DOF's check of an MKS firing solution (Chapter 7 A): :func:`verify_with_3dof` flies the
3DOF (the launch's own atmosphere and drag law, the rotating Earth) at the MKS solution of
:mod:`.firing`, measures its miss, and refines the solution by shooting with the 3DOF itself,
every solution flown together in the compiled batch: the MKS's 3DOF miss is the model error the
text's method accepts.

SI inside (m, s, rad); degrees only in the arguments and fields named ``_deg``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import partial
from typing import overload

import numpy as np

from ...engines import threedof
from ...foundation.sweeps import client_shares, sweep
from ...foundation.validation import check_range, real_number
from ...models.launch import Launch
from .firing import (
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
#: At most this many 3DOF flights per solution in the refinement, and at most this many steps
#: in a row that fail to halve the miss (where the 3DOF has no root near the MKS's).
_MAX_FLIGHTS = 30
_FAILURES = 4
#: Where the 3DOF at the MKS solution falls short of the target's altitude, the elevation is
#: raised by this (rad) up to this many times.
_RAISES = 8
_RAISE_RAD = math.radians(0.25)
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


class _Batch3dof:
    """The 3DOF flown at many (elevation, bearing) pairs of one gun at once, each to its
    target's altitude on its branch: the east and north miss (m) at each target."""

    def __init__(self, gun: Launch, targets: list[TargetPoint], rising: np.ndarray, rtol: float):
        self.layings = threedof.Layings(gun, rtol=rtol)  # the gun validated once, here
        self.aims = np.array([target.earth_fixed_m() for target in targets])  # 3DOF's frame
        self.axes = east_north_axes(self.aims)
        self.altitudes = np.array([target.altitude_m for target in targets])
        self.rising = rising
        self.flights = np.zeros(len(targets), dtype=int)
        self.rhs_evaluations = np.zeros(len(targets), dtype=int)

    def miss(self, x: np.ndarray, which: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The miss (k, 2) of the shots at ``x`` (k, 2; rad) for targets ``which`` (k,), NaN
        where the shot never reaches its target's altitude (quietly: a short shot misses), and
        the times of flight (k,)."""
        flight = self.layings.fly(
            np.clip(x[:, 0], _FLATTEST_RAD, 0.5 * math.pi),
            x[:, 1],
            self.altitudes[which],
            self.rising[which],
        )
        np.add.at(self.flights, which, 1)
        np.add.at(self.rhs_evaluations, which, flight.rhs_evaluations)
        aims = self.aims[which]
        miss = east_north(flight.end_position_m.T - aims, aims, self.axes[which])
        miss[~flight.impact] = np.nan
        return miss, np.where(flight.impact, flight.time_of_flight_s, np.nan)

    def jacobian(self, x, miss, which) -> np.ndarray:
        """Forward differences (k, 2, 2) of the miss at ``x``: two flights each."""
        step = 1e-7  # rad: centimetres at the target, far above the 3DOF's noise at rtol 1e-9
        columns = []
        for k in range(2):
            shifted = x.copy()
            shifted[:, k] += step
            columns.append((self.miss(shifted, which)[0] - miss) / step)
        return np.stack(columns, axis=-1)


def _refine_3dof(
    gun: Launch,
    targets: list[TargetPoint],
    solutions: list[FiringSolution],
    rtol: float,
    tolerance_m: float,
) -> list[Verification]:
    """Newton's method on every solution's (elevation, bearing) with the 3DOF, all solutions
    flown together each iteration: one flight per solution and step, the Jacobian the MKS's
    at its root (its model error is small next to the sensitivities) updated by Broyden's rule
    along each step, differenced by the 3DOF only where a step fails to halve the miss."""
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
    # where the 3DOF at the MKS solution falls short of the target's altitude (the MKS's
    # apogee just above it, the 3DOF's below), raise the elevation until it gets there
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
    size = np.hypot(miss[:, 0], miss[:, 1])
    failures = np.zeros(count, dtype=int)  # steps in a row that did not halve the miss
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
    results = []
    for i, solution in enumerate(solutions):
        elevation, bearing = math.degrees(x[i, 0]), math.degrees(x[i, 1]) % 360.0
        converged = bool(size[i] <= tolerance_m)
        message = (
            f"landed within {tolerance_m:g} m"
            if converged
            else "the 3DOF never reached the target's altitude on the branch near the MKS solution"
            if not np.isfinite(size[i])
            else f"stopped {size[i]:.3g} m from the target after {shots.flights[i]} flights: "
            "no 3DOF root near the MKS's"
        )
        results.append(
            Verification(
                mks_miss_m=float(first[i]) if np.isfinite(first[i]) else math.inf,
                elevation_deg=elevation,
                bearing_deg=bearing,
                elevation_change_deg=elevation - solution.elevation_deg,
                bearing_change_deg=(math.degrees(x[i, 1] - start[i, 1]) + 180.0) % 360.0 - 180.0,
                miss_m=float(size[i]) if np.isfinite(size[i]) else math.inf,
                time_of_flight_s=float(time[i]),
                flights=int(shots.flights[i]),
                converged=converged,
                message=message,
                rhs_evaluations=int(shots.rhs_evaluations[i]),
            )
        )
    return results


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
    One target and solution, or sequences of them (one Verification each, the same answers
    either way); given a Dask ``client``, the solutions are shared out in chunks among its
    workers (:func:`.sweeps.sweep`).

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
        whether it converged and why not.
    """
    gun = check_gun(gun)
    points, single = check_targets(targets)
    chosen = [solutions] if single else list(solutions) if isinstance(solutions, Sequence) else None
    if chosen is None or len(chosen) != len(points):
        raise ValueError(
            "solutions must be one FiringSolution per target "
            f"({len(points)} targets; got {type(solutions).__name__})"
        )
    for index, solution in enumerate(chosen):
        if not isinstance(solution, FiringSolution):
            raise TypeError(
                f"solutions[{index}] must be a FiringSolution; got {type(solution).__name__}"
            )
    tolerance = check_range(
        real_number(tolerance_m, "tolerance_m"), "tolerance_m", low=0.0, low_inclusive=False
    )
    rtol = check_range(real_number(rtol, "rtol"), "rtol", low=0.0, low_inclusive=False, high=1e-3)
    if client is None:
        results = _refine_3dof(gun, points, chosen, rtol, tolerance)
    else:
        refine = partial(_refine_chunk, gun=gun, rtol=rtol, tolerance_m=tolerance)
        chunks = sweep(refine, client_shares(list(zip(points, chosen)), client), client=client)
        results = [result for chunk in chunks for result in chunk]
    return results[0] if single else results


def _refine_chunk(chunk, gun, rtol, tolerance_m) -> list[Verification]:
    """:func:`_refine_3dof` of a chunk of (target, solution) pairs (a Dask worker's share)."""
    targets, solutions = zip(*chunk, strict=True)
    return _refine_3dof(gun, list(targets), list(solutions), rtol, tolerance_m)
