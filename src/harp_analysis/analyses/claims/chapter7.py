"""Quantities behind statements of Chapter 7 that the ledger scores (rows ``ch7.*`` and
``ch7c.*``): the cost of a firing solution by the MKS and by the 3DOF (7 A), a pointing error
against the MKS's error (7 B), the ground-fire miss, a late arrival and the error's growth over
the trajectory (7 C). The firing solutions and pointing errors fly the 3DOF here.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from scipy.optimize import brentq

from ...engines import mks, threedof
from ...foundation import earth
from ...foundation.validation import Bounds, check_choice, finite_scalar, positive_scalar
from ...models.launch import Launch, baseline_chapter_4
from .. import effort
from ..comparisons import BASELINE_ELEVATIONS_DEG, case, chapter_4_launch, launch_error_at_apogee_km

__all__ = [
    "firing_solution",
    "FiringEvaluations",
    "firing_solution_evaluations",
    "SolutionsPerSolve",
    "firing_solutions_per_3dof_solution",
    "position_shift_m",
    "pointing_shift_over_mks_error",
    "mks_impact_miss_km",
    "impact_miss_over_total_error",
    "late_arrival_miss_m",
    "ErrorGrowth",
    "error_growth",
]


# --- Chapter 7 A: firing solutions ----------------------------------------------------------------
def firing_solution(
    method: str = "mks",
    target_range_km: float = 150.0,
    target_altitude_km: float = 100.0,
    elevation_bracket_deg: tuple[float, float] = (45.0, 75.0),
    elevation_tolerance_deg: float = 1e-6,
) -> tuple[float, int, int]:
    """(elevation in deg, solver iterations, right-hand-side evaluations) of the baseline's
    firing solution through a point ``target_altitude_km`` up and ``target_range_km``
    downrange, by Brent's method on the elevation (the bearing is the target's on a
    non-rotating Earth). ``method``: the three-term MKS (each iteration one closed-form
    evaluation, counted as one) or the 3DOF (each iteration a whole adaptive flight)."""
    check_choice(method, "method", ("mks", "3dof"))
    reach = finite_scalar(target_range_km, "target_range_km") * 1e3
    height = finite_scalar(target_altitude_km, "target_altitude_km") * 1e3
    calls: list[int] = []

    def miss(elevation_deg):
        launch = baseline_chapter_4(float(elevation_deg))
        if method == "mks":
            solution = mks.for_launch(launch, warn=False)
            calls.append(1)
            return float(solution.altitude(np.array([reach / earth.RADIUS_M]))[0]) - height
        flight = threedof.simulate_3dof(launch, output_step_s=0.1)
        calls.append(flight.attrs["rhs_evaluations"])
        ranges = flight.ground_range_m.to_numpy()
        up = flight.time_s.to_numpy() <= flight.attrs["apogee_time_s"]
        part = up if ranges[up][-1] >= reach else ~up
        return float(np.interp(reach, ranges[part], flight.altitude_m.to_numpy()[part])) - height

    low, high = elevation_bracket_deg
    elevation = brentq(miss, low, high, xtol=positive_scalar(elevation_tolerance_deg, "tolerance"))
    return float(elevation), len(calls), int(sum(calls))


@dataclasses.dataclass(frozen=True)
class FiringEvaluations:
    """A firing solution's count (:func:`firing_solution`): ``evaluations`` (MKS solutions, or
    the 3DOF's right-hand sides), the solver's iterations and the elevation found."""

    evaluations: int
    iterations: int
    elevation_deg: float

    @property
    def per_iteration(self) -> float:
        return self.evaluations / self.iterations


def firing_solution_evaluations(method: str = "mks", **target) -> FiringEvaluations:
    """Evaluations a firing solution takes (:func:`firing_solution`): MKS solutions for
    ``method="mks"``, the 3DOF's right-hand-side evaluations for ``"3dof"``."""
    elevation, iterations, evaluations = firing_solution(method, **target)
    return FiringEvaluations(iterations if method == "mks" else evaluations, iterations, elevation)


@dataclasses.dataclass(frozen=True)
class SolutionsPerSolve:
    """MKS firing solutions against one 3DOF firing solution, by operations
    (:func:`firing_solutions_per_3dof_solution`)."""

    three_dof_evaluations: int
    operations_per_evaluation: float
    mks_iterations: int
    mks_operations: float  # of one MKS evaluation

    @property
    def three_dof_operations(self) -> float:
        return self.three_dof_evaluations * self.operations_per_evaluation

    @property
    def mks_solution_operations(self) -> float:
        return self.mks_iterations * self.mks_operations

    @property
    def solutions(self) -> float:
        """MKS firing solutions that cost the operations of one 3DOF firing solution."""
        return self.three_dof_operations / self.mks_solution_operations

    @property
    def log10_solutions(self) -> float:
        return math.log10(self.solutions)


def firing_solutions_per_3dof_solution(**target) -> SolutionsPerSolve:
    """How many MKS firing solutions cost the operations of one 3DOF firing solution, as
    ``log10_solutions`` (:func:`firing_solution`; operations per 3DOF evaluation and per MKS
    evaluation from :func:`~harp_analysis.analyses.effort.effort_table`'s counts for HP's flight and
    apogee)."""
    _, iterations, _ = firing_solution("mks", **target)
    three = firing_solution("3dof", **target)[2]
    return SolutionsPerSolve(
        three,
        effort.operations_per_3dof_evaluation(),
        iterations,
        effort.mks_evaluation_operations(),
    )


# --- Chapter 7 B-C: other uncertainties, ground fire ----------------------------------------------
def position_shift_m(
    launch: Launch, elevation_error_mrad: float = 0.0, speed_error_m_s: float = 0.0, at_s=None
) -> float:
    """Distance (m) between the 3DOF positions of ``launch`` and of the launch with its
    elevation raised by ``elevation_error_mrad`` and its speed by ``speed_error_m_s``, at time
    ``at_s`` (default: the unperturbed apogee time)."""
    changed = launch.but(
        elevation_deg=launch.elevation_deg
        + math.degrees(finite_scalar(elevation_error_mrad, "elevation_error_mrad") * 1e-3),
        speed_m_s=launch.speed_m_s + finite_scalar(speed_error_m_s, "speed_error_m_s"),
    )
    flights = [threedof.simulate_3dof(x, output_step_s=0.25) for x in (launch, changed)]
    time = flights[0].attrs["apogee_time_s"] if at_s is None else finite_scalar(at_s, "at_s")
    points = [
        np.array([np.interp(time, f.time_s, f[c]) for c in ("x_m", "y_m", "z_m")]) for f in flights
    ]
    return float(np.linalg.norm(points[1] - points[0]))


def pointing_shift_over_mks_error(
    elevation_deg: float = 45.0, elevation_error_mrad: float = 1.0, speed_error_m_s: float = 0.0
) -> float:
    """Position change at the apogee time from a pointing error (and a muzzle-speed error) over
    the three-term MKS's error at apogee, baseline at ``elevation_deg`` (Ch. 7 B: these
    uncertainties "may end up being much larger" than the MKS's)."""
    shift = position_shift_m(
        baseline_chapter_4(elevation_deg), elevation_error_mrad, speed_error_m_s
    )
    return shift / 1e3 / launch_error_at_apogee_km(chapter_4_launch("baseline", elevation_deg))


def mks_impact_miss_km(
    projectile: str = "baseline", elevation_deg: float = 85.0, **launch_changes
) -> float:
    """|MKS impact range - 3DOF range| (km) of Chapter 4's launch
    (:func:`~harp_analysis.analyses.comparisons.case`): where the MKS puts a ground-fire round
    against where the simulation lands it."""
    flight, solution, _ = case(projectile, elevation_deg, **launch_changes)
    return abs(float(solution.impact_angle) * earth.RADIUS_M - flight.attrs["range_m"]) / 1e3


def impact_miss_over_total_error(
    projectile: str = "baseline", elevation_deg: float = 85.0
) -> float:
    """Ground-fire miss (:func:`mks_impact_miss_km`) over the total position error at the
    3DOF's impact (eq 4.7, geometric reading): what Ch. 7 C calls "slightly misleading"."""
    errors = case(projectile, elevation_deg)[2]
    miss_m = mks_impact_miss_km(projectile, elevation_deg) * 1e3
    return miss_m / float(errors.total_geometric_m.iloc[-1])


# --- Chapter 7 C: timing, the error's growth ------------------------------------------------------
def late_arrival_miss_m(
    speed_m_s: float = 2000.0,
    delay_s: float = 0.5,
    flight_path_angle_deg: float = 0.0,
    gravity_m_s2: float = earth.STANDARD_GRAVITY_M_S2,
) -> float:
    """Distance (m) a body moving at ``speed_m_s`` on a ballistic path covers in ``delay_s``:
    |v dt + g dt^2 / 2| under uniform gravity (over half a second the conic's curvature is
    that of the parabola)."""
    speed = Bounds(low=0.0).scalar(speed_m_s, "speed_m_s")
    delay = Bounds(low=0.0).scalar(delay_s, "delay_s")
    angle = math.radians(finite_scalar(flight_path_angle_deg, "flight_path_angle_deg"))
    g = finite_scalar(gravity_m_s2, "gravity_m_s2")
    horizontal = speed * math.cos(angle) * delay
    vertical = speed * math.sin(angle) * delay - 0.5 * g * delay**2
    return math.hypot(horizontal, vertical)


@dataclasses.dataclass(frozen=True)
class ErrorGrowth:
    """The MKS's error at impact over its error at apogee, smallest over Chapter 4's
    elevations, as printed and with the asymptotic angular momentum taken from the 3DOF's
    apogee (Fig 4.13's correction)."""

    impact_over_apogee: float
    corrected_impact_over_apogee: float
    impact_km: float  # largest over the elevations, as printed
    corrected_impact_km: float  # the same elevation, corrected


def error_growth() -> ErrorGrowth:
    """How the MKS's error grows from apogee to impact (Ch. 7 C: "the minor mismatch of
    predicted angular momentum with reality that causes the error of the projectile to grow
    over the trajectory"), the baseline at 30-85 deg."""

    def ends(momentum_from_apogee: bool) -> np.ndarray:
        rows = []
        for elevation in BASELINE_ELEVATIONS_DEG:
            flight, _, errors = case(
                "baseline", elevation, momentum_from_apogee=momentum_from_apogee
            )
            at_apogee = np.interp(
                flight.attrs["apogee_time_s"], errors.time_s, errors.total_geometric_m
            )
            rows.append((errors.total_geometric_m.iloc[-1], at_apogee))
        return np.array(rows)

    printed, corrected = ends(False), ends(True)
    worst = int(np.argmax(printed[:, 0]))
    return ErrorGrowth(
        float(np.min(printed[:, 0] / printed[:, 1])),
        float(np.min(corrected[:, 0] / corrected[:, 1])),
        float(printed[worst, 0]) / 1e3,
        float(corrected[worst, 0]) / 1e3,
    )
