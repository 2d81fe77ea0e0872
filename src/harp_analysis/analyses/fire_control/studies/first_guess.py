"""A better first guess, measured (issue 24 item 4): the improved MKS (Chapter 7 C,
:mod:`.mks_improved`) as the fire-control solver's model, against the ECI MKS the text has.

The 3DOF refinement (:func:`~harp_analysis.analyses.fire_control.verification.verify_with_3dof`)
starts from a model's firing solution; the closer that solution lands when the 3DOF flies it, the
fewer 3DOF flights the refinement needs. The ECI MKS leaves out the drag's decay on the way down and
takes eq 3.11's air at the launch Cd0 all the way up; the improved MKS models both (its module
docstring), at a few ms a solve and some tens of ms a root, where the compiled ECI MKS finds both
roots in well under a ms.

:func:`improved_solution` moves an ECI MKS root to the improved MKS's root: Newton's method on
(elevation, bearing), the residual the east and north miss at the target of the improved MKS
where it crosses the target's radius on the root's branch, turned into the Earth-fixed frame
at its time of flight, the first Jacobian the ECI root's own, updated by Broyden's rule along
each step (the updated one goes on to the 3DOF's refinement, which it spares a few flights
over the envelope against the ECI root's Jacobian). :func:`compare_first_guesses`
flies both models' solutions in the 3DOF over a reachable envelope (two sites, five bearings,
a few downranges, both roots) and counts the 3DOF flights each refinement takes to land within
1 m; :func:`summary` condenses it per model. The whole comparison takes a few seconds (the
improved MKS's solves are most of it).

Frames: the improved MKS's positions are inertial, in the 3DOF's frame (x toward longitude 0
at t = 0, z north); a point reached at time t is fixed to the Earth at that point turned by
-omega t about z (:attr:`.mks_improved.ImprovedSolution.impact_point_m` does the same), where
:meth:`~harp_analysis.analyses.fire_control.firing.TargetPoint.earth_fixed_m` places the target.

SI inside (m, s, rad); degrees only in the arguments and columns named ``_deg``.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import replace

import numpy as np
import pandas as pd
from scipy.optimize import brentq

from ....engines import mks_improved
from ....foundation import earth
from ....foundation.validation import (
    Bounds,
    ModelValidityWarning,
    check_choice,
)
from ....models.launch import Launch
from ....models.sites import YUMA
from ....models.trajectory import rotate_about_axis
from .. import firing
from ..firing import FiringSolution, TargetPoint
from ..verification import verify_with_3dof

__all__ = [
    "MODELS",
    "ROOTS",
    "GUNS",
    "BEARINGS_DEG",
    "DOWNRANGES_M",
    "COLUMNS",
    "FLIGHT_COST_S",
    "improved_miss",
    "improved_solution",
    "compare_first_guesses",
    "summary",
]

MODELS = ("mks", "improved")
ROOTS = ("low", "high")
#: The two guns: Barbados's HP (:data:`~harp_analysis.analyses.fire_control.firing.BARBADOS_HP`) and
#: the same gun at Yuma's latitude (Ch. 6 D) and longitude (about 114.4 deg W).
GUNS: dict[str, Launch] = {
    "Barbados": firing.BARBADOS_HP,
    "Yuma": firing.BARBADOS_HP.but(
        latitude_deg=math.degrees(YUMA.latitude_rad), longitude_deg=-114.4
    ),
}
BEARINGS_DEG = (0.0, 90.0, 150.0, 225.0, 270.0)
DOWNRANGES_M = (60e3, 120e3, 180e3)
#: The improved MKS's Newton stops once its trajectory passes this close to the target (m).
_CONVERGED_MISS_M = 1.0
#: The 3DOF refinement's tolerance in the comparison (m).
_LANDED_M = 1.0
#: A rough wall time of one 3DOF flight in the compiled batch (s), for :func:`summary`'s
#: total: the time a refinement spends is about its flights times this.
FLIGHT_COST_S = 0.5e-3
#: Step halvings Newton's method tries where a step lands further off (or nowhere), its
#: steps at most, and the elevations (rad) it keeps to.
_HALVINGS = 4
_ITERATIONS = 12
_LOWEST_RAD, _HIGHEST_RAD = 1e-6, math.radians(89.9)
#: The columns of :func:`compare_first_guesses`, one row per point, root and model.
COLUMNS = (
    "site",
    "bearing_deg",  # the bearing from the gun along which the point lies
    "downrange_m",  # great-circle distance to the point's foot, on the surface
    "altitude_m",
    "root",  # "low" or "high"
    "model",  # "mks" (the ECI MKS) or "improved" (the improved MKS)
    "elevation_deg",  # the model's firing solution
    "aim_bearing_deg",
    "model_miss_m",  # the model's own miss at its solution
    "model_solves",  # trajectories of the model its root took
    "model_time_s",  # wall time of the model's solve of this root (the improved's: from the MKS's)
    "first_guess_miss_m",  # the 3DOF flown at the model's solution: its miss (NaN: never there)
    "flights",  # 3DOF flights the refinement took to land within 1 m, the first included
    "converged",
    "miss_m",  # the 3DOF's miss at the refined solution
    "refined_elevation_deg",  # the 3DOF's root the refinement found
    "refined_bearing_deg",
    "refine_time_s",  # the refinement's share of its batch's wall time (by flights)
    "in_band",  # the improved MKS's air momentum share within its validity band (both rows)
    "reason",  # why the model has no root (None where it has one)
)


def _check_solution(solution, target: TargetPoint) -> FiringSolution:
    if not isinstance(solution, FiringSolution):
        raise TypeError(f"solution must be a FiringSolution; got {type(solution).__name__}")
    jacobian = solution.jacobian_m_rad
    if jacobian is None or np.shape(jacobian) != (2, 2) or not np.all(np.isfinite(jacobian)):
        raise ValueError(
            "solution.jacobian_m_rad must be the MKS root's finite (2, 2) Jacobian (m/rad); "
            f"got {None if jacobian is None else np.shape(jacobian)}"
        )
    return _check_branch(solution, target)


def _check_branch(solution: FiringSolution, target: TargetPoint) -> FiringSolution:
    if solution.branch == "ascending" and target.altitude_m == 0.0:
        raise ValueError(
            "solution.branch is 'ascending' but target.altitude_m is 0: the ascending branch "
            "meets altitude 0 only at the muzzle"
        )
    return solution


def _crossing(flight: mks_improved.ImprovedSolution, radius_m: float, branch: str):
    """Angular range (rad) where ``flight`` crosses ``radius_m`` on ``branch``, None if its
    apogee stays below it."""
    apogee, impact = float(flight.apogee_angle), float(flight.impact_angle)
    if branch == "descending" and radius_m == flight.radius_m:
        return impact
    excess = float(flight.radius(apogee)) - radius_m
    if excess < 0:
        return None
    low, high = (apogee, impact) if branch == "descending" else (0.0, apogee)
    if excess == 0:
        return apogee
    return float(brentq(lambda theta: float(flight.radius(theta)) - radius_m, low, high))


def _fly(gun: Launch, x, calibration: mks_improved.Calibration):
    """The improved MKS of ``gun`` laid at ``x`` (elevation, bearing; rad), None where it has
    no solution (its re-entry decay without a finite solution, or its march failing)."""
    laid = gun.but(elevation_deg=math.degrees(x[0]), bearing_deg=math.degrees(x[1]) % 360.0)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ModelValidityWarning)  # judged at the root
            return mks_improved.solve(laid, calibration)
    except (ValueError, ArithmeticError):  # its re-entry march can divide by zero, too
        return None


def _residual(flight, target: TargetPoint, branch: str, aim: np.ndarray):
    """(east, north miss (2,), time of flight) of ``flight`` at ``target``, or None."""
    if flight is None:
        return None
    theta = _crossing(flight, earth.RADIUS_M + target.altitude_m, branch)
    if theta is None:
        return None
    when = float(flight.time(theta))
    inertial = flight.positions([when])[0]
    turned = rotate_about_axis(
        inertial[:, None], np.array([-flight.launch.rotation_rate_rad_s * when])
    )
    return firing.east_north(turned[:, 0] - aim, aim), when


def improved_miss(
    gun: Launch,
    target: TargetPoint,
    solution: FiringSolution,
    *,
    calibration: mks_improved.Calibration = mks_improved.UNCALIBRATED,
) -> float:
    """The improved MKS's miss (m) at ``target`` flown at ``solution``'s elevation and bearing
    (where it crosses the target's radius on the solution's branch, Earth-fixed); NaN if it
    never gets there."""
    gun = firing.check_gun(gun)
    target = firing.check_target(target)
    if not isinstance(solution, FiringSolution):
        raise TypeError(f"solution must be a FiringSolution; got {type(solution).__name__}")
    _check_branch(solution, target)
    if not isinstance(calibration, mks_improved.Calibration):
        raise TypeError(f"calibration must be a Calibration; got {type(calibration).__name__}")
    x = np.radians([solution.elevation_deg, solution.bearing_deg])
    found = _residual(_fly(gun, x, calibration), target, solution.branch, target.earth_fixed_m())
    return math.nan if found is None else float(np.hypot(*found[0]))


def improved_solution(
    gun: Launch,
    target: TargetPoint,
    solution: FiringSolution,
    *,
    iterations: int = _ITERATIONS,
    calibration: mks_improved.Calibration = mks_improved.UNCALIBRATED,
) -> FiringSolution | None:
    """The improved MKS's firing solution of ``target``, from the ECI MKS's ``solution`` (a
    root of :func:`~harp_analysis.analyses.fire_control.firing.firing_solutions` for ``gun``):
    Newton's method on (elevation, bearing), at most ``iterations`` steps, the residual the improved
    MKS's east and north miss at the target on the solution's branch, the first Jacobian
    ``solution.jacobian_m_rad`` (Broyden's update along each step; a step that lands further off is
    halved). Stops once the improved MKS passes within 1 m. Returns ``solution`` with the new
    elevation, bearing, time of flight, fire time, miss (the improved MKS's), Jacobian (the updated
    one) and ``mks_solves`` (improved MKS solves taken); ``beta`` and ``leaves_atmosphere`` stay the
    ECI root's. None if it does not converge, or the improved MKS has no solution on the way (its
    re-entry decay diverges on some westward shots). A ModelValidityWarning where the root lies
    outside the improved MKS's band of :func:`.mks_improved.air_momentum_share`."""
    gun = firing.check_gun(gun)
    target = firing.check_target(target)
    solution = _check_solution(solution, target)
    if isinstance(iterations, bool) or not isinstance(iterations, int | np.integer):
        raise TypeError(f"iterations must be an integer; got {type(iterations).__name__}")
    iterations = int(Bounds(low=1).check(iterations, "iterations"))
    if not isinstance(calibration, mks_improved.Calibration):
        raise TypeError(f"calibration must be a Calibration; got {type(calibration).__name__}")
    better, _ = _improve(gun, target, solution, iterations, calibration)
    if better is not None and not _in_band(gun, better):
        low, high = mks_improved.AIR_MOMENTUM_SHARE_RANGE
        warnings.warn(
            "the improved MKS's root lies outside its band of the air's share in the launch's "
            f"angular momentum, ({low:g}, {high:g}] (mks_improved.air_momentum_share)",
            ModelValidityWarning,
            stacklevel=2,
        )
    return better


def _improve(
    gun: Launch,
    target: TargetPoint,
    solution: FiringSolution,
    iterations: int,
    calibration: mks_improved.Calibration,
) -> tuple[FiringSolution | None, str | None]:
    """:func:`improved_solution` of checked arguments, and why not where it is None."""
    aim = target.earth_fixed_m()
    branch = solution.branch
    x = np.radians([solution.elevation_deg, solution.bearing_deg])
    jacobian = np.array(solution.jacobian_m_rad, dtype=float)
    flight = _fly(gun, x, calibration)
    if flight is None:
        return None, "the improved MKS has no solution at the ECI MKS's root"
    found = _residual(flight, target, branch, aim)
    solves = 1
    if found is None:
        return None, "the improved MKS at the ECI MKS's root does not reach the target's altitude"
    miss, when = found
    size = float(np.hypot(*miss))
    for _ in range(iterations):
        if size < _CONVERGED_MISS_M:
            break
        try:
            step = -np.linalg.solve(jacobian, miss)
        except np.linalg.LinAlgError:
            return None, "the Jacobian became singular"
        trial, found, tries = _closer(gun, x, step, size, calibration, target, branch, aim)
        solves += tries
        if found is None:
            return None, (
                f"no step from {size:.3g} m got closer (the improved MKS has no solution or "
                "does not reach the target's altitude there)"
            )
        taken = trial - x
        jacobian += np.outer(found[0] - miss - jacobian @ taken, taken) / float(taken @ taken)
        x, (miss, when) = trial, found
        size = float(np.hypot(*miss))
    if not size < _CONVERGED_MISS_M:
        return None, f"still {size:.3g} m off after {iterations} Newton steps"
    jacobian.flags.writeable = False
    arrival = target.arrival_time_s
    return replace(
        solution,
        elevation_deg=math.degrees(x[0]),
        bearing_deg=math.degrees(x[1]) % 360.0,
        time_of_flight_s=when,
        fire_time_s=None if arrival is None else arrival - when,
        miss_m=size,
        mks_solves=solves,
        jacobian_m_rad=jacobian,
    ), None


def _closer(gun: Launch, x, step, size: float, calibration, target, branch: str, aim):
    """The Newton ``step`` from ``x`` halved (at most ``_HALVINGS`` times), elevation kept in
    the solver's range, until the improved MKS lands closer than ``size`` (m): the point, its
    :func:`_residual` (None where no step got closer) and the solves spent."""
    for tries in range(1, _HALVINGS + 2):
        trial = x + step
        trial[0] = min(max(trial[0], _LOWEST_RAD), _HIGHEST_RAD)
        found = _residual(_fly(gun, trial, calibration), target, branch, aim)
        if found is not None and np.hypot(*found[0]) < size:
            return trial, found, tries
        step = 0.5 * step
    return trial, None, tries


def _in_band(gun: Launch, solution: FiringSolution) -> bool:
    laid = gun.but(elevation_deg=solution.elevation_deg, bearing_deg=solution.bearing_deg)
    low, high = mks_improved.AIR_MOMENTUM_SHARE_RANGE
    return bool(low < mks_improved.air_momentum_share(laid) <= high)


def _check_guns(guns) -> dict[str, Launch]:
    if not isinstance(guns, Mapping) or not guns:
        raise TypeError(f"guns must be a non-empty mapping of site name to Launch; got {guns!r}")
    for name, gun in guns.items():
        if not isinstance(name, str):
            raise TypeError(f"guns' keys must be site names (str); got {name!r}")
        if not isinstance(gun, Launch):
            raise TypeError(f"guns[{name!r}] must be a Launch; got {type(gun).__name__}")
        firing.check_gun(gun)
    return dict(guns)


def _check_values(values, name: str, interval: Bounds) -> list[float]:
    if isinstance(values, str | bytes) or not isinstance(values, Sequence | np.ndarray):
        raise TypeError(f"{name} must be a sequence of numbers; got {type(values).__name__}")
    checked = [interval.number(value, name) for value in values]
    if not checked:
        raise ValueError(f"{name} must not be empty")
    return checked


def _row_points(gun: Launch, bearings, downranges, altitudes):
    points = [
        (bearing, downrange, altitude)
        for bearing in bearings
        for downrange in downranges
        for altitude in altitudes
    ]
    targets = [firing.destination(gun, *point) for point in points]
    return points, targets


def _verify(gun: Launch, entries: list, which: int) -> tuple[list, float]:
    """:func:`~harp_analysis.analyses.fire_control.verification.verify_with_3dof` of the solutions
    ``entry[which]`` of ``entries`` (None where there is none) in one batch, and its wall time
    (s)."""
    chosen = [entry for entry in entries if entry[which] is not None]
    start = time.perf_counter()
    checks = (
        verify_with_3dof(
            gun, [e[1] for e in chosen], [e[which] for e in chosen], tolerance_m=_LANDED_M
        )
        if chosen
        else []
    )
    seconds = time.perf_counter() - start
    by_entry = {id(entry): check for entry, check in zip(chosen, checks)}
    return [by_entry.get(id(entry)) for entry in entries], seconds


def _first_guesses(gun: Launch, points, targets, branch, calibration) -> list[tuple]:
    """Each root of the ECI MKS at each of ``targets`` (``points`` their bearings, downranges
    and altitudes) and the improved MKS's from it (:func:`_improve`), timed: (point, target,
    root name, MKS root, improved root or None, MKS time, improved time, why no improved root)."""
    firing.firing_solutions(gun, targets[:1], branch=branch)  # the kernels loaded
    entries = []
    for point, target in zip(points, targets):
        start = time.perf_counter()
        solutions = firing.firing_solutions(gun, target, branch=branch)
        mks_time = (time.perf_counter() - start) / max(len(solutions.roots), 1)
        for name in ROOTS:
            root = getattr(solutions, name)
            if root is None:
                continue
            start = time.perf_counter()
            better, why = _improve(gun, target, root, _ITERATIONS, calibration)
            own = time.perf_counter() - start
            entries.append((point, target, name, root, better, mks_time, mks_time + own, why))
    return entries


def _check_both(gun: Launch, entries: list) -> tuple[dict, dict, int, float]:
    """Both models' roots of ``entries`` (:func:`_first_guesses`) checked by the 3DOF, one
    batch a model (:func:`_verify`): each model's checks and seconds a flight, and the flights
    and seconds of both."""
    checks, per_flight = {}, {}
    flights, seconds = 0, 0.0
    for model, which in (("mks", 3), ("improved", 4)):
        checks[model], batch = _verify(gun, entries, which)
        count = sum(check.flights for check in checks[model] if check is not None)
        per_flight[model] = batch / max(count, 1)
        flights, seconds = flights + count, seconds + batch
    return checks, per_flight, flights, seconds


def _rows(site: str, gun: Launch, entries: list, checks: dict, per_flight: dict) -> list[dict]:
    """The rows of :func:`compare_first_guesses` of one site's ``entries``, two a root (the
    ECI MKS's, the improved MKS's), and their 3DOF ``checks`` and seconds ``per_flight``."""
    rows = []
    for index, entry in enumerate(entries):
        (bearing, downrange, altitude), _, name, root, better, *times, why = entry
        point = dict(site=site, bearing_deg=bearing, downrange_m=downrange, altitude_m=altitude)
        band = _in_band(gun, root if better is None else better)
        for model, solution, model_time, reason in (
            ("mks", root, times[0], None),
            ("improved", better, times[1], why),
        ):
            row = _row(solution, model_time, checks[model][index], per_flight[model])
            rows.append(
                point | dict(root=name, model=model) | row | dict(in_band=band, reason=reason)
            )
    return rows


#: A model's columns of :func:`compare_first_guesses` from its solution and from the solution's
#: 3DOF check: (column, the attribute it holds, its value where there is none).
_SOLUTION_COLUMNS = (
    ("elevation_deg", "elevation_deg", math.nan),
    ("aim_bearing_deg", "bearing_deg", math.nan),
    ("model_miss_m", "miss_m", math.nan),
    ("model_solves", "mks_solves", 0),
)
_CHECK_COLUMNS = (
    ("first_guess_miss_m", "mks_miss_m", math.nan),
    ("flights", "flights", 0),
    ("converged", "converged", False),
    ("miss_m", "miss_m", math.nan),
    ("refined_elevation_deg", "elevation_deg", math.nan),
    ("refined_bearing_deg", "bearing_deg", math.nan),
)


def _row(solution, model_time: float, check, check_time: float) -> dict:
    """One model's columns of a row of :func:`compare_first_guesses`: its ``solution`` (None
    where it found none), timed ``model_time`` (s), and that solution's 3DOF ``check`` (None
    where there is none), at ``check_time`` (s) a flight."""
    return (
        _columns(solution, _SOLUTION_COLUMNS)
        | _columns(check, _CHECK_COLUMNS)
        | dict(
            model_time_s=model_time,
            refine_time_s=0.0 if check is None else check.flights * check_time,
        )
    )


def _columns(item, columns) -> dict:
    """``columns`` (column, attribute, default) of ``item``, their defaults where it is None."""
    return {
        name: default if item is None else getattr(item, attribute)
        for name, attribute, default in columns
    }


def compare_first_guesses(
    guns: Mapping[str, Launch] = GUNS,
    bearings_deg: Sequence[float] = BEARINGS_DEG,
    downranges_m: Sequence[float] = DOWNRANGES_M,
    altitudes_m: Sequence[float] = (0.0,),
    *,
    branch: str = "descending",
    calibration: mks_improved.Calibration = mks_improved.UNCALIBRATED,
) -> pd.DataFrame:
    """Both models' first guesses over the reachable envelope: for every gun of ``guns`` (site
    name to Launch), every point ``downranges_m`` along each of ``bearings_deg`` at each of
    ``altitudes_m``, met on ``branch``, and each root the ECI MKS finds there, the ECI MKS's
    solution and the improved MKS's (:func:`improved_solution` from it), each flown by the 3DOF
    and refined to land within 1 m
    (:func:`~harp_analysis.analyses.fire_control.verification.verify_with_3dof`, each model's roots
    of a gun in one batch). One row per point, root and model (:data:`COLUMNS`); points out of the
    ECI MKS's reach have none. Where the improved MKS finds no root its row keeps NaN, no flights,
    converged False and the reason. ``model_time_s``: the ECI MKS's single-target solve shared
    between its roots; the improved's, that plus its own Newton's (it starts from the MKS's root).
    ``refine_time_s``: the model's 3DOF batch's wall time shared by flights; ``frame.attrs`` holds
    ``seconds_per_3dof_flight`` (the batches' time over their flights), ``branch`` and
    ``projectiles`` (the guns' projectiles' names)."""
    guns = _check_guns(guns)
    bearings = _check_values(bearings_deg, "bearings_deg", Bounds(0.0, 360.0, unit="deg"))
    downranges = _check_values(downranges_m, "downranges_m", Bounds(low=0.0, low_inclusive=False))
    altitudes = _check_values(altitudes_m, "altitudes_m", Bounds(low=0.0, unit="m"))
    branch = check_choice(branch, "branch", firing.BRANCHES)
    if not isinstance(calibration, mks_improved.Calibration):
        raise TypeError(f"calibration must be a Calibration; got {type(calibration).__name__}")
    mks_improved.warm_up()
    rows = []
    flights = seconds = 0.0
    for site, gun in guns.items():
        points, targets = _row_points(gun, bearings, downranges, altitudes)
        entries = _first_guesses(gun, points, targets, branch, calibration)
        if not entries:
            continue
        checks, per_flight, count, batch = _check_both(gun, entries)
        flights, seconds = flights + count, seconds + batch
        rows += _rows(site, gun, entries, checks, per_flight)
    frame = pd.DataFrame(rows, columns=list(COLUMNS))
    frame.attrs["seconds_per_3dof_flight"] = seconds / flights if flights else math.nan
    frame.attrs["branch"] = branch
    frame.attrs["projectiles"] = sorted({gun.projectile.name for gun in guns.values()})
    return frame


def summary(
    frame: pd.DataFrame, *, by: Sequence[str] = (), flight_cost_s: float = FLIGHT_COST_S
) -> pd.DataFrame:
    """Per model of :func:`compare_first_guesses`'s ``frame`` (and per value of the columns
    ``by``, e.g. ``("root",)``), over the point-roots where both models have a root (the same
    shots for both): how many, the median, 95th percentile and maximum of the 3DOF's miss at
    the first guess (m; infinite where that shot never reaches the target's altitude), the
    mean 3DOF flights to land within 1 m, the share converged, the mean model time (s) and the
    mean total, model time plus flights times ``flight_cost_s`` (s); ``no_root``, the
    point-roots of the whole frame where the model found none."""
    if not isinstance(frame, pd.DataFrame):
        raise TypeError(f"frame must be a pandas DataFrame; got {type(frame).__name__}")
    missing = [name for name in COLUMNS if name not in frame.columns]
    if missing:
        raise ValueError(f"frame lacks the columns {missing} of compare_first_guesses")
    if isinstance(by, str) or not all(name in frame.columns for name in by):
        raise ValueError(f"by must be a sequence of the frame's columns; got {by!r}")
    cost = Bounds(low=0.0).number(flight_cost_s, "flight_cost_s")
    keys = ["site", "bearing_deg", "downrange_m", "altitude_m", "root"]
    found = frame.elevation_deg.notna()
    both = found.groupby([frame[key] for key in keys]).transform("all")
    groups = ["model", *by]
    paired = frame[both].assign(
        total_time_s=lambda f: f.model_time_s + f.flights * cost,
        first_guess_miss_m=lambda f: f.first_guess_miss_m.fillna(math.inf),
    )
    table = paired.groupby(groups, sort=False).agg(
        points=("first_guess_miss_m", "size"),
        median_miss_m=("first_guess_miss_m", "median"),
        p95_miss_m=("first_guess_miss_m", lambda miss: miss.quantile(0.95)),
        max_miss_m=("first_guess_miss_m", "max"),
        mean_flights=("flights", "mean"),
        converged_fraction=("converged", "mean"),
        mean_model_time_s=("model_time_s", "mean"),
        mean_total_time_s=("total_time_s", "mean"),
    )
    no_root = (~found).groupby([frame[name] for name in groups], sort=False).sum()
    return table.assign(no_root=no_root.reindex(table.index).fillna(0).astype(int))
