"""Envelope maps (issue 16 item 4): how far the MKS firing solution misses when the 3DOF flies it.

For each intercept point of a map (a downrange distance along a bearing from the gun, along
the great circle, times an altitude above the spherical Earth; the point fixed to the Earth,
met on the trajectory's descending branch) the ECI MKS firing solution
(:func:`~harp_analysis.analyses.fire_control.firing.firing_solutions`) is flown once by the 3DOF on
the rotating Earth, to the target's altitude, and its miss measured: the straight-line distance (m)
from the 3DOF's Earth-fixed end point to the target's
(:meth:`~harp_analysis.analyses.fire_control.firing.TargetPoint.earth_fixed_m`). It is the first
step of :func:`~harp_analysis.analyses.fire_control.verification.verify_with_3dof` without its
shooting refinement, which would be far too slow for a map. Each point's ``outcome``
(:data:`OUTCOMES`) says which of three it is: the 3DOF's miss measured; no MKS firing solution; or
an MKS solution that the 3DOF, fired at it, never brings to the target's altitude (its apogee below
it: the MKS's trajectory of the same launch climbs higher than the 3DOF's), a root the MKS claims
and the 3DOF cannot reach. The last two keep the reason.

The points run through :func:`.sweeps.sweep`, an altitude's row of them at a time (solved
together by the compiled solver, the 3DOF flown at them as one batch): in this process, or on
a Dask cluster.

SI inside (m, s, rad); degrees only in the arguments and columns named ``_deg``.
"""

from __future__ import annotations

import math
import warnings
from functools import partial

import numpy as np
import pandas as pd

from ...engines import threedof
from ...foundation.sweeps import sweep
from ...foundation.validation import Bounds, check_choice, finite_array
from ...models.launch import Launch, Launches
from ...models.trajectory import EndAltitudeNotCrossedWarning
from .firing import destination, firing_solutions

__all__ = [
    "ROOTS",
    "OUTCOMES",
    "MEASURED",
    "NO_SOLUTION",
    "NEVER_THERE",
    "MAP_COLUMNS",
    "miss_map",
    "three_dof_misses",
]

ROOTS = ("low", "high")
#: What a map point's row holds (column ``outcome``): the 3DOF fired at the MKS solution
#: crosses the target's altitude and its miss is measured; the MKS has no firing solution of
#: the root there; the MKS has one, and the 3DOF fired at it never gets to the target's altitude.
MEASURED, NO_SOLUTION, NEVER_THERE = OUTCOMES = (
    "3DOF miss measured",
    "no MKS solution",
    "3DOF never reaches the target's altitude",
)
#: The columns of :func:`miss_map`, one row per intercept point.
MAP_COLUMNS = (
    "map_bearing_deg",  # the bearing from the gun along which the points lie
    "root",  # "low" or "high"
    "downrange_m",  # great-circle distance from the gun to the point's foot, on the surface
    "altitude_m",
    "latitude_deg",  # of the point
    "longitude_deg",
    "elevation_deg",  # the MKS firing solution (NaN where there is none)
    "bearing_deg",
    "time_of_flight_s",  # of the MKS to the point
    "beta",  # of the ECI launch (validity: below 0.25)
    "leaves_atmosphere",
    "mks_miss_m",  # the MKS solution's own residual at the point (fire_control's miss_m)
    "miss_3dof_m",  # the 3DOF flown at the MKS solution: its miss (NaN where it cannot)
    "apogee_3dof_m",  # the 3DOF flown at the MKS solution: its apogee's altitude
    "outcome",  # one of OUTCOMES
    "reason",  # why there is no 3DOF miss: no firing solution, or the 3DOF never got there
)


def three_dof_misses(gun: Launch, targets, solutions, rtol: float) -> tuple[np.ndarray, np.ndarray]:
    """The 3DOF (the gun's atmosphere, drag law and Earth rotation) fired once at each firing
    solution, flown as one batch: the distance (m) from where it crosses its target's altitude
    on the solution's branch to the target, NaN if it never gets there (within the 3DOF's
    time); and the altitude of its apogee (m)."""
    laid = Launches.from_launches([gun]).but(
        elevation_deg=np.array([s.elevation_deg for s in solutions]),
        bearing_deg=np.array([s.bearing_deg for s in solutions]),
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", EndAltitudeNotCrossedWarning)  # NaN below
        flight = threedof.fly_3dof(
            laid,
            rtol=rtol,
            end_altitude_m=np.array([t.altitude_m for t in targets]),
            rising=np.array([s.branch == "ascending" for s in solutions]),
        )
    # the 3DOF's Earth-fixed frame has its x axis toward longitude 0
    aims = np.array([t.earth_fixed_m() for t in targets])
    distance = np.linalg.norm(flight.end_position_m.T - aims, axis=1)
    return np.where(flight.impact, distance, np.nan), flight.apogee_altitude_m


def _points(
    points: list[tuple[float, float]],
    gun: Launch,
    bearing_deg: float,
    roots: tuple[str, ...],
    rtol: float,
) -> list[dict]:
    """The rows of the points ``(downrange_m, altitude_m)``, one per root of ``roots``: its
    firing solution and the 3DOF's miss there, or why there is none (all solved together,
    the 3DOF flights as one batch)."""
    targets = [destination(gun, bearing_deg, downrange, altitude) for downrange, altitude in points]
    rows, flown = [], []
    for (downrange, altitude), target, solutions in zip(
        points, targets, firing_solutions(gun, targets), strict=True
    ):
        for root in roots:
            row, solution = _solved_row(root, downrange, altitude, bearing_deg, target, solutions)
            rows.append(row)
            if solution is not None:
                flown.append((row, target, solution))
    if flown:
        chosen, aims, solved = zip(*flown, strict=True)
        misses, apogees = three_dof_misses(gun, aims, solved, rtol)
        for row, aim, miss, apogee in zip(chosen, aims, misses, apogees, strict=True):
            row.update(miss_3dof_m=miss, apogee_3dof_m=apogee, outcome=MEASURED)
            if not math.isfinite(miss):
                row.update(outcome=NEVER_THERE, reason=_never_there(apogee, aim.altitude_m))
    return rows


def _solved_row(root: str, downrange, altitude, bearing_deg: float, target, solutions):
    """The row of a point's ``root`` before the 3DOF flies it: the firing solution or why
    there is none; and that solution (None where there is none)."""
    row: dict[str, object] = dict.fromkeys(MAP_COLUMNS, math.nan)
    row.update(
        map_bearing_deg=bearing_deg,
        root=root,
        downrange_m=downrange,
        altitude_m=altitude,
        latitude_deg=target.latitude_deg,
        longitude_deg=target.longitude_deg,
        leaves_atmosphere=None,
        outcome=NO_SOLUTION,
        reason=None,
    )
    solution = solutions.low if root == "low" else solutions.high
    if solution is None:
        # the reason names each missing root; keep this root's part
        parts = [p for p in (solutions.reason or "").split("; ") if f"no {root}-angle" in p]
        row["reason"] = parts[0] if parts else solutions.reason
        return row, None
    row.update(
        elevation_deg=solution.elevation_deg,
        bearing_deg=solution.bearing_deg,
        time_of_flight_s=solution.time_of_flight_s,
        beta=solution.beta,
        leaves_atmosphere=solution.leaves_atmosphere,
        mks_miss_m=solution.miss_m,
    )
    return row, solution


def _never_there(apogee_m: float, altitude_m: float) -> str:
    """Why the 3DOF fired at the MKS solution has no miss: its apogee (m) below the target's
    ``altitude_m``, or its flight ended before it fell back to it."""
    return "the 3DOF fired at the MKS solution never reaches the target's altitude: " + (
        f"its apogee, {apogee_m / 1e3:.1f} km, is below the target's {altitude_m / 1e3:g} km"
        if apogee_m < altitude_m
        else "it has not fallen back to it at the end of its flight"
    )


def _check_map(ranges_m, altitudes_m) -> tuple[np.ndarray, np.ndarray]:
    """The map's downrange distances (> 0) and altitudes (>= 0), checked, as flat arrays (m)."""
    ranges = np.ravel(finite_array(ranges_m, "ranges_m"))
    altitudes = np.ravel(finite_array(altitudes_m, "altitudes_m"))
    if ranges.size == 0 or np.any(ranges <= 0):
        raise ValueError("ranges_m must be one or more downrange distances > 0 (m)")
    if altitudes.size == 0 or np.any(altitudes < 0):
        raise ValueError("altitudes_m must be one or more altitudes >= 0 (m)")
    return ranges, altitudes


def miss_map(
    gun: Launch,
    bearing_deg: float,
    ranges_m,
    altitudes_m,
    *,
    root: str = "low",
    rtol: float = 1e-9,
    client=None,
    progress: bool = True,
) -> pd.DataFrame:
    """The MKS firing solution's 3DOF miss over a map of intercept points: every downrange
    distance of ``ranges_m`` (m, along ``bearing_deg`` from ``gun``) at every altitude of
    ``altitudes_m`` (m), met on the descending branch by the ``root`` ("low", "high" or
    "both") solution. A tidy table, one row per point and root (:data:`MAP_COLUMNS`), ranges
    varying fastest, each point's ``outcome`` one of :data:`OUTCOMES`; ``attrs`` keep the gun,
    bearing and root. ``client`` and ``progress`` go to :func:`.sweeps.sweep`."""
    if not isinstance(gun, Launch):
        raise TypeError(
            f"gun must be a harp_analysis.models.launch.Launch; got {type(gun).__name__}"
        )
    root = check_choice(root, "root", (*ROOTS, "both"))
    roots = ROOTS if root == "both" else (root,)
    bearing_deg = Bounds(low=0.0, high=360.0, unit="deg").number(bearing_deg, "bearing_deg")
    ranges, altitudes = _check_map(ranges_m, altitudes_m)
    points = [(float(x), float(h)) for h in altitudes for x in ranges]
    # one altitude's points a chunk: each solved by the compiled solver and flown as one batch
    chunks = [points[start : start + ranges.size] for start in range(0, len(points), ranges.size)]
    rows = sweep(
        partial(_points, gun=gun, bearing_deg=bearing_deg, roots=roots, rtol=rtol),
        chunks,
        client=client,
        progress=progress,
        description=f"miss map, bearing {bearing_deg:g} deg",
    )
    frame = pd.DataFrame([row for chunk in rows for row in chunk], columns=list(MAP_COLUMNS))
    frame.attrs.update(gun=gun, bearing_deg=bearing_deg, root=root, rtol=rtol)
    return frame
