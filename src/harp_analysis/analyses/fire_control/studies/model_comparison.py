"""The calibrated MKS's firing solutions against the ECI MKS's, judged by the 3DOF (issue 35,
item 4).

The calibrated MKS (:mod:`harp_analysis.engines.calibrated_mks`) learns its table from the
3DOF flights of a grid of launches; it is judged here on aims it was never calibrated on:
points drawn at random across the gun's envelope (:func:`random_aims`: bearings, downranges
and altitudes, both branches), whose roots lie anywhere between the grid's nodes. Each model's
roots of every aim (:func:`.firing.firing_solutions`, ``model="eci"`` and ``"calibrated"``) are
flown once by the 3DOF to the target's altitude on the root's branch
(:func:`.envelope.three_dof_misses`): the miss is the model error the root carries
(:func:`compare_models`, :func:`summary`). And Chapter 7's raid (:func:`.intercepts.raid`) is
verified from each model's roots (:func:`verified_raid`): the 3DOF flights its refinement
(:func:`.verify_with_3dof`) takes to land each root within a metre, the cost a better root
saves. :func:`calibrated_fire_control` condenses both for the ledger.

SI inside (m, s, rad); degrees only in the arguments and columns named ``_deg``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np
import pandas as pd

from ....foundation import earth
from ....foundation.validation import Bounds, check_choice
from ....models.launch import Launch
from ..envelope import three_dof_misses
from ..firing import (
    BARBADOS_HP,
    BRANCHES,
    MODELS,
    TargetPoint,
    check_gun,
    destination,
    great_circle,
)
from ..firing import firing_solutions as solve
from ..intercepts import raid, raid_roots, raid_windows
from ..verification import verify_with_3dof

__all__ = [
    "DOWNRANGES_M",
    "ALTITUDES_M",
    "COLUMNS",
    "RAID_COLUMNS",
    "random_aims",
    "compare_models",
    "summary",
    "verified_raid",
    "CalibratedFireControl",
    "calibrated_fire_control",
]

#: The aims are drawn uniformly over these downranges along the great circle (m) and
#: altitudes (m), every bearing, either branch: HP from Barbados reaches about 400 km at sea
#: level and 170 km up; an aim beyond its reach has no root and adds none.
DOWNRANGES_M = (5e3, 450e3)
ALTITUDES_M = (0.0, 120e3)
#: The verified raid lands every root this close (m), as benchmarks/bench_fire_control.py's.
_LANDED_M = 1.0
#: The columns of :func:`compare_models`, one row per aim, root and model asked.
COLUMNS = (
    "aim",  # the aim's index in its list
    "bearing_deg",  # from the gun, along which the aim lies
    "downrange_m",  # great-circle distance to the aim's foot, on the surface
    "altitude_m",
    "branch",  # "ascending" or "descending"
    "root",  # "low" or "high"
    "model",  # the model asked for, of firing.MODELS
    "solved_by",  # whose root it is: "calibrated", or "eci" (kept, with the reason)
    "reason",  # why the ECI MKS's root stands for the calibrated MKS's (None otherwise)
    "elevation_deg",
    "aim_bearing_deg",  # the root's bearing
    "time_of_flight_s",  # the model's, to the aim
    "miss_3dof_m",  # the 3DOF flown once at the root: its miss (NaN: never gets there)
)
#: The columns of :func:`verified_raid`, one row per root.
RAID_COLUMNS = ("solved_by", "reason", "first_miss_m", "converged", "flights")


def random_aims(
    gun: Launch = BARBADOS_HP, count: int = 600, seed: int = 35
) -> tuple[list[TargetPoint], list[str]]:
    """``count`` aims from ``gun`` drawn at random (numpy's generator seeded with ``seed``):
    bearing uniform over the circle, downrange over :data:`DOWNRANGES_M`, altitude over
    :data:`ALTITUDES_M`, the branch either at even odds; points fixed to the Earth
    (:func:`.firing.destination`), and their branches. None is a launch of the calibration's
    grid: their roots fall between its nodes."""
    gun = check_gun(gun)
    count = int(Bounds(low=1).number(count, "count"))
    draws = np.random.default_rng(seed)
    bearing = draws.uniform(0.0, 360.0, count)
    downrange = draws.uniform(*DOWNRANGES_M, count)
    altitude = draws.uniform(*ALTITUDES_M, count)
    rising = draws.uniform(size=count) < 0.5
    targets = [destination(gun, *point) for point in zip(bearing, downrange, altitude)]
    return targets, [BRANCHES[int(up)] for up in rising]


def compare_models(
    gun: Launch, targets: list[TargetPoint], branches: list[str], *, rtol: float = 1e-9
) -> pd.DataFrame:
    """Every root of each aim by each model of :data:`.firing.MODELS` (the aims of a branch
    solved together), flown once by the 3DOF to its aim's altitude on its branch (all as one
    batch): one row per aim, root and model (:data:`COLUMNS`); aims out of reach have none.
    ``attrs`` keep the aims' count."""
    gun = check_gun(gun)
    if len(targets) != len(branches):
        raise ValueError(f"one branch per aim: {len(targets)} aims, {len(branches)} branches")
    branches = [check_choice(branch, "branch", BRANCHES) for branch in branches]
    found = []
    for branch in BRANCHES:
        chosen = [i for i, name in enumerate(branches) if name == branch]
        if chosen:
            found += _roots(gun, targets, chosen, branch)
    frame = pd.DataFrame([row for row, _, _ in found], columns=list(COLUMNS))
    if found:
        _, points, roots = zip(*found, strict=True)
        frame["miss_3dof_m"] = three_dof_misses(gun, list(points), list(roots), rtol)[0]
    frame.attrs["aims"] = len(targets)
    return frame


def _roots(gun: Launch, targets: list[TargetPoint], chosen: list[int], branch: str) -> list:
    """Every root by each model of the aims ``chosen`` (indices into ``targets``, all met on
    ``branch``), a model's solved together: (its row of :func:`compare_models`, aim, root)."""
    aims = [targets[i] for i in chosen]
    found = []
    for model in MODELS:
        solved = solve(gun, aims, branch=branch, model=model)
        for index, target, solutions in zip(chosen, aims, solved, strict=True):
            for name in ("low", "high"):
                root = getattr(solutions, name)
                if root is not None:
                    found.append(
                        (_row(gun, index, target, branch, name, model, root), target, root)
                    )
    return found


def _row(gun: Launch, index: int, target: TargetPoint, branch, name, model, root) -> dict:
    """The row of :func:`compare_models` of aim ``index``'s root ``name`` by ``model``, before
    the 3DOF flies it."""
    angle, bearing = great_circle(gun, target)
    return dict(
        aim=index,
        bearing_deg=math.degrees(bearing),
        downrange_m=angle * earth.RADIUS_M,
        altitude_m=target.altitude_m,
        branch=branch,
        root=name,
        model=model,
        solved_by=root.model,
        reason=root.reason,
        elevation_deg=root.elevation_deg,
        aim_bearing_deg=root.bearing_deg,
        time_of_flight_s=root.time_of_flight_s,
    )


def summary(frame: pd.DataFrame) -> pd.DataFrame:
    """Per model asked and whose root it is (:func:`compare_models`'s ``frame``): the roots,
    those whose 3DOF flight never reaches the aim's altitude, and the median, 95th percentile
    and largest 3DOF miss (m) of the rest."""
    reached = frame.assign(reached=np.isfinite(frame.miss_3dof_m.to_numpy(dtype=float)))
    table = reached.groupby(["model", "solved_by"], sort=False).agg(
        roots=("miss_3dof_m", "size"), never_there=("reached", lambda r: int((~r).sum()))
    )
    misses = reached[reached.reached].groupby(["model", "solved_by"], sort=False).miss_3dof_m
    return table.join(
        misses.agg(
            median_miss_m="median",
            p95_miss_m=lambda miss: miss.quantile(0.95),
            max_miss_m="max",
        )
    )


def verified_raid(
    gun: Launch = BARBADOS_HP,
    model: str = "eci",
    *,
    count: int = 100,
    times: int = 50,
    tolerance_m: float = _LANDED_M,
) -> pd.DataFrame:
    """Chapter 7's raid (:func:`.intercepts.raid`'s ``count`` targets at ``times`` intercept
    times each, the ascending branch) solved by ``model`` (:func:`.intercepts.raid_windows`)
    and every root refined by the 3DOF to land within ``tolerance_m``
    (:func:`.verify_with_3dof`, all at once): one row per root (:data:`RAID_COLUMNS`), whose it
    is (and why the ECI MKS's stands, under the calibrated model), the 3DOF's miss at it, and
    whether and in how many flights the refinement landed it."""
    model = check_choice(model, "model", MODELS)
    pairs = raid_roots(raid_windows(gun, raid(gun, count), count=times, model=model))
    aims = []
    for item, _ in pairs:
        assert item.aim is not None  # a feasible intercept has its point
        aims.append(item.aim)
    checks = verify_with_3dof(gun, aims, [root for _, root in pairs], tolerance_m=tolerance_m)
    return pd.DataFrame(
        [
            (root.model, root.reason, check.mks_miss_m, check.converged, check.flights)
            for (_, root), check in zip(pairs, checks, strict=True)
        ],
        columns=list(RAID_COLUMNS),
    )


@dataclass(frozen=True)
class CalibratedFireControl:
    """The calibrated MKS's firing solutions judged by the 3DOF: on random aims
    (:func:`random_aims`) the 3DOF's miss (m) at its roots and at the ECI MKS's roots of the
    same aims, and the verified raid's 3DOF flights per root from each model's roots."""

    aims: int
    roots: int  # every root of the aims under model="calibrated"
    calibrated_roots: int  # those the calibrated MKS gave (the rest keep the ECI MKS's)
    never_there: int  # calibrated roots whose 3DOF flight never reaches the aim's altitude
    median_miss_m: float  # the 3DOF at the calibrated roots
    p95_miss_m: float
    max_miss_m: float
    eci_median_miss_m: float  # the 3DOF at the ECI MKS's roots of the same aims
    eci_p95_miss_m: float
    raid_roots: int  # the verified raid's, under model="calibrated"
    raid_calibrated_roots: int
    raid_calibrated_landed: int  # of those, the roots the 3DOF's refinement landed
    flights_per_root: float  # the calibrated roots the 3DOF landed: its mean flights
    flights_per_root_all: float  # every root it landed, the kept ECI MKS's included
    eci_flights_per_root: float  # the same from the ECI MKS's roots (model="eci")

    @property
    def kept_roots(self) -> int:
        """Roots of the aims where the ECI MKS's stands, with the reason."""
        return self.roots - self.calibrated_roots

    @property
    def raid_kept_roots(self) -> int:
        return self.raid_roots - self.raid_calibrated_roots


@cache
def calibrated_fire_control(
    gun: Launch = BARBADOS_HP, count: int = 600, seed: int = 35
) -> CalibratedFireControl:
    """:class:`CalibratedFireControl` of ``gun`` over ``count`` random aims (``seed``) and
    Chapter 7's raid. Cached: the ledger reads it three times."""
    frame = compare_models(gun, *random_aims(gun, count, seed))
    table = summary(frame)
    own, eci = table.loc[("calibrated", "calibrated")], table.loc[("eci", "eci")]
    raids = {model: verified_raid(gun, model) for model in MODELS}
    calibrated = raids["calibrated"]
    landed = calibrated[calibrated.converged]
    ours = landed[landed.solved_by == "calibrated"]
    return CalibratedFireControl(
        count,
        int(table.loc["calibrated"].roots.sum()),
        int(own.roots),
        int(own.never_there),
        float(own.median_miss_m),
        float(own.p95_miss_m),
        float(own.max_miss_m),
        float(eci.median_miss_m),
        float(eci.p95_miss_m),
        len(calibrated),
        int((calibrated.solved_by == "calibrated").sum()),
        len(ours),
        float(ours.flights.mean()),
        float(landed.flights.mean()),
        float(raids["eci"].flights[raids["eci"].converged].mean()),
    )
