"""Chapter 7 A's counts, built: the MKS trajectories of a firing solution against the 3DOF's
equations of motion (:func:`~harp_analysis.analyses.fire_control.studies.costs.shoot_3dof`, the
iterative 3DOF firing solution alone), a raid's MKS intercepts against one iterative 3DOF intercept,
and one verified firing solution's operations, by default in :func:`.firing.barbados_case`. Counts,
not wall times: the ledger reads them and must come out the same on every machine; the wall times of
the same work are ``benchmarks/bench_fire_control.py``'s.

SI inside (m, s, rad); degrees only in the arguments and fields named ``_deg``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from functools import cache

import numpy as np
from scipy import optimize

from ....engines import threedof
from ....foundation import earth
from ....foundation.validation import check_choice
from ....models.launch import Launch
from ....models.trajectory import EndAltitudeNotCrossedWarning
from ... import effort
from ..firing import (
    BARBADOS_HP,
    BRANCHES,
    TargetPoint,
    barbados_case,
    check_gun,
    check_target,
    east_north,
    firing_solutions,
    great_circle,
)
from ..intercepts import raid, raid_roots, raid_windows
from ..verification import LANDED_M, Verification, verify_with_3dof

__all__ = [
    "shoot_3dof",
    "mks_solves_per_firing_solution",
    "eom_evaluations_per_3dof_firing_solution",
    "SolveCount",
    "RaidComparison",
    "VerifiedSolutionWork",
    "raid_against_3dof_intercept",
    "verified_firing_solution_operations",
]

#: A root the solver returns puts the MKS trajectory this close to the target (m).
_CONVERGED_MISS_M = 1.0
#: The miss (m) that stands for a shot that never reaches the target (refinements turn back).
_SHORT_MISS_M = 1e12


class _Shooting:
    """The 3DOF's shooting solve of (elevation, bearing) onto an Earth-fixed point (scipy's
    root, finite differences), counting its flights and right-hand-side evaluations."""

    def __init__(self, gun: Launch, target: TargetPoint, rising: bool, rtol: float):
        self.gun, self.target, self.rising, self.rtol = gun, target, rising, rtol
        self.aim = target.earth_fixed_m()  # the 3DOF's Earth-fixed frame: x toward longitude 0
        self.flights = 0
        self.rhs_evaluations = 0

    def fly(self, x) -> threedof.Flights:
        flight = threedof.fly_3dof(
            self.gun.but(elevation_deg=math.degrees(x[0]), bearing_deg=math.degrees(x[1]) % 360.0),
            rtol=self.rtol,
            end_altitude_m=self.target.altitude_m,
            rising=self.rising,
        )
        self.flights += 1
        self.rhs_evaluations += int(flight.rhs_evaluations[0])
        return flight

    def miss(self, x) -> np.ndarray:
        """East and north miss (m); a huge one, turning the solver back, where there is no
        such gun or the shot never crosses the target's altitude."""
        if not 0.0 < x[0] <= math.pi / 2:
            return np.full(2, _SHORT_MISS_M)
        flight = self.fly(x)
        if not flight.impact[0]:
            return np.full(2, _SHORT_MISS_M)
        return east_north(flight.end_position_m[:, 0] - self.aim, self.aim)

    def solve(self, start, step_bound: float = 100.0):
        """From ``start`` (elevation, bearing; rad): the miss there, scipy's fit and the flight
        at its end; ``step_bound`` is hybr's ``factor`` (small for a start far from the root)."""
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", EndAltitudeNotCrossedWarning)  # a short shot misses
            first = float(np.hypot(*self.miss(start)))
            # a step of 1e-7 rad moves the end point by centimetres, far above the 3DOF's noise
            fit = optimize.root(
                self.miss,
                start,
                method="hybr",
                options=dict(eps=1e-14, xtol=1e-10, factor=step_bound),
            )
            final = self.fly(fit.x)
        if final.impact[0]:
            miss = float(np.hypot(*east_north(final.end_position_m[:, 0] - self.aim, self.aim)))
        else:
            miss = math.inf
        return first, fit, final, miss

    def verification(self, start, **options) -> Verification:
        """:meth:`solve` from ``start`` (elevation, bearing; rad), reported against it."""
        start_miss, fit, final, miss = self.solve(start, **options)
        elevation, bearing = math.degrees(fit.x[0]), math.degrees(fit.x[1]) % 360.0
        start_elevation, start_bearing = np.degrees(start)
        return Verification(
            mks_miss_m=start_miss,
            elevation_deg=elevation,
            bearing_deg=bearing,
            elevation_change_deg=elevation - float(start_elevation),
            bearing_change_deg=(bearing - float(start_bearing) + 180.0) % 360.0 - 180.0,
            miss_m=miss,
            time_of_flight_s=float(final.time_of_flight_s[0]),
            flights=self.flights,
            converged=bool(fit.success) or miss <= LANDED_M,
            message=str(fit.message),
            rhs_evaluations=self.rhs_evaluations,
        )


def _drag_free_start(gun: Launch, target: TargetPoint, branch: str) -> np.ndarray | None:
    """(elevation, bearing) (rad) of the lowest drag-free conic (eq 3.8, no rotation) from the
    gun at its muzzle speed through the target's radius at its central angle on ``branch``:
    with T = tan(elevation) and k = GM / (R V)^2, u(theta) = 1 / r_t is the quadratic
    k (1 - cos) T^2 - (sin / R) T + k (1 - cos) + cos / R - 1 / r_t = 0. None if out of reach."""
    central, bearing = great_circle(gun, target)
    r0, rt = earth.RADIUS_M, earth.RADIUS_M + target.altitude_m
    k = earth.GM_M3_S2 / (r0 * gun.speed_m_s) ** 2
    a = k * (1 - math.cos(central))
    b = -math.sin(central) / r0
    c = a + math.cos(central) / r0 - 1 / rt
    discriminant = b * b - 4 * a * c
    if a <= 0 or discriminant < 0:
        return None
    for tangent in sorted((-b - s * math.sqrt(discriminant)) / (2 * a) for s in (1, -1)):
        if tangent <= 0:
            continue
        # the conic's apogee angle: u' = 0 where tan(theta) = T / (R c3 - 1), c3 = k (1 + T^2)
        apogee = math.atan2(tangent, r0 * k * (1 + tangent**2) - 1) % math.pi
        if (central < apogee) == (branch == "ascending"):
            return np.array([math.atan(tangent), bearing])
    return None


def shoot_3dof(
    gun: Launch, target: TargetPoint, *, branch: str = "descending", rtol: float = 1e-9
) -> Verification:
    """The iterative 3DOF firing solution alone: shooting (elevation, bearing) with the 3DOF
    from the drag-free conic's elevation at the great-circle bearing, not from the MKS. The
    result's ``mks_miss_m`` and changes are those of that drag-free start; ``rhs_evaluations``
    counts the 3DOF's equations of motion solved. ValueError if the conic cannot reach it."""
    gun = check_gun(gun)
    target = check_target(target)
    branch = check_choice(branch, "branch", BRANCHES)
    start = _drag_free_start(gun, target, branch)
    if start is None:
        raise ValueError(f"target: no drag-free conic reaches it on the {branch} branch")
    shooting = _Shooting(gun, target, branch == "ascending", rtol)
    # bounded steps: drag shortens the drag-free range several-fold, and hybr's default first
    # step from so far off overshoots to the other root or stalls
    return shooting.verification(start, step_bound=0.1)


@dataclass(frozen=True)
class SolveCount:
    """The MKS trajectories of one firing solution (both roots): the search (grid, edges and
    maximum range) and each root's Newton iterations, and the roots."""

    trajectories: int
    search: int
    low_newton: int
    high_newton: int
    low_elevation_deg: float
    low_bearing_deg: float
    high_elevation_deg: float


def mks_solves_per_firing_solution(
    gun: Launch | None = None, target: TargetPoint | None = None
) -> SolveCount:
    """MKS trajectories one firing solution evaluates, both roots and their search, by default
    in :func:`.firing.barbados_case`. Chapter 7 A: "dozens or even hundreds"."""
    gun, target = barbados_case() if gun is None or target is None else (gun, target)
    result = firing_solutions(gun, target)
    if result.low is None or result.high is None:
        raise ValueError(f"target: the case lacks a root ({result.reason})")
    newton = result.low.mks_solves + result.high.mks_solves
    return SolveCount(
        result.mks_solves,
        result.mks_solves - newton,
        result.low.mks_solves,
        result.high.mks_solves,
        result.low.elevation_deg,
        result.low.bearing_deg,
        result.high.elevation_deg,
    )


def eom_evaluations_per_3dof_firing_solution(
    gun: Launch | None = None, target: TargetPoint | None = None, *, rtol: float = 1e-9
) -> Verification:
    """The iterative 3DOF firing solution, whose ``rhs_evaluations`` count the 3DOF's equations
    of motion solved (:func:`~harp_analysis.analyses.fire_control.studies.costs.shoot_3dof` from the
    drag-free conic, every flight of the shooting included) of :func:`.firing.barbados_case` by
    default. Chapter 7 A: "hundreds of thousands or millions of numerical EOM solutions"."""
    gun, target = barbados_case() if gun is None or target is None else (gun, target)
    return shoot_3dof(gun, target, rtol=rtol)


@dataclass(frozen=True)
class RaidComparison:
    """Every MKS intercept of a raid against one converged iterative 3DOF intercept (Chapter 7
    A's claim), by counts."""

    targets: int
    intercepts: int
    feasible: int
    roots: int
    mks_trajectories: int
    three_dof_rhs: int  # right-hand-side evaluations of the one 3DOF intercept
    three_dof_flights: int
    three_dof_miss_m: float
    mks_miss_m: float  # the MKS root's own miss in the 3DOF, before its refinement
    alone_rhs: int  # the 3DOF alone from the drag-free conic (barbados_case, descending)
    alone_flights: int

    @property
    def trajectories_per_intercept(self) -> float:
        return self.mks_trajectories / self.intercepts

    @property
    def log10_counts(self) -> float:
        """log10 of the 3DOF intercept's right-hand sides over the raid's MKS trajectories."""
        return math.log10(self.three_dof_rhs / self.mks_trajectories)


@cache
def raid_against_3dof_intercept(
    gun: Launch = BARBADOS_HP, *, count: int = 100, times: int = 50
) -> RaidComparison:
    """Every MKS intercept of a raid (:func:`.intercepts.raid`'s ``count`` targets, each at
    ``times`` intercept times over its flight, the ascending branch) against one converged
    iterative 3DOF intercept: the first target's middle feasible intercept, refined by the 3DOF
    from its MKS root to a miss under 1 m (:func:`.verification.verify_with_3dof`; from the
    drag-free conic the 3DOF shooting does not converge on this ascending branch, and a start
    from the MKS makes the 3DOF cheaper, against the claim: so the 3DOF alone from the
    drag-free conic, in :func:`.firing.barbados_case`, is counted too). Cached: the ledger
    reads it twice."""
    windows = raid_windows(gun, raid(gun, count), count=times)
    feasible = [item for item in windows[0].intercepts if item.roots]
    if not feasible:
        raise ValueError(f"the first target has no feasible intercept ({windows[0].reason})")
    middle = feasible[len(feasible) // 2]
    assert middle.aim is not None  # a feasible intercept has its point
    shot = verify_with_3dof(gun, middle.aim, middle.roots[0], tolerance_m=_CONVERGED_MISS_M)
    if not shot.converged:  # a count of a failed solve would be no measure of the claim
        raise RuntimeError(f"the iterative 3DOF intercept did not converge: {shot.message}")
    alone = shoot_3dof(*barbados_case())
    return RaidComparison(
        count,
        sum(len(window.intercepts) for window in windows),
        sum(int(window.feasible.sum()) for window in windows),
        len(raid_roots(windows)),
        sum(window.mks_solves for window in windows),
        shot.rhs_evaluations,
        shot.flights,
        shot.miss_m,
        shot.mks_miss_m,
        alone.rhs_evaluations,
        alone.flights,
    )


@dataclass(frozen=True)
class VerifiedSolutionWork:
    """The operations of one firing solution as a gun's computer would run it (Chapter 2's
    "in real time as the gun swings into place"): both MKS roots, then the low root refined by
    the 3DOF to a miss under 1 m, each counted as Fig 4.7 counts
    (:mod:`~harp_analysis.analyses.effort`)."""

    mks_trajectories: int  # both roots and their search
    mks_operations_per_trajectory: float  # one three-term MKS evaluation's, a lower bound
    three_dof_rhs: int
    three_dof_operations_per_rhs: float  # DOP853's share included
    flights: int
    three_dof_miss_m: float
    mks_miss_m: float  # the MKS low root's miss in the 3DOF, before the refinement

    @property
    def mks_operations(self) -> float:
        return self.mks_trajectories * self.mks_operations_per_trajectory

    @property
    def three_dof_operations(self) -> float:
        return self.three_dof_rhs * self.three_dof_operations_per_rhs

    @property
    def operations(self) -> float:
        return self.mks_operations + self.three_dof_operations


def verified_firing_solution_operations(
    gun: Launch | None = None, target: TargetPoint | None = None
) -> VerifiedSolutionWork:
    """The operations of one verified firing solution, by default for
    :func:`.firing.barbados_case`: the MKS trajectories of both roots (each counted as one
    three-term MKS evaluation, Fig 4.7's unit: a lower bound, as a solver's trajectory also
    finds a crossing and its time), then the 3DOF's refinement of the low root to under 1 m."""
    gun, target = barbados_case() if gun is None or target is None else (gun, target)
    low = firing_solutions(gun, target).low
    if low is None:
        raise ValueError("target: the case has no low-angle firing solution")
    shot = verify_with_3dof(gun, target, low, tolerance_m=_CONVERGED_MISS_M)
    return VerifiedSolutionWork(
        mks_solves_per_firing_solution(gun, target).trajectories,
        effort.mks_evaluation_operations(),
        shot.rhs_evaluations,
        effort.operations_per_3dof_evaluation(),
        shot.flights,
        shot.miss_m,
        shot.mks_miss_m,
    )
