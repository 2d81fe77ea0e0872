"""Fly-out tables compared (issue 35, item 3): Chapter 7 A's table of numerical flights against
the calibrated MKS, learned from the very same flights, as the cells shrink.

Chapter 7 A: "The use of fly-out tables or look-up tables of potential positions of the
projectile and missile based upon numerical simulations is also a possible method to develop
intercept solutions. [...] As the size of the discrete volume is decreased to increase accuracy,
the number of simulations and size of the tables increase to an unreasonable size."

Both tables here are of one gun (:mod:`harp_analysis.engines.flight_grid`), learned from its
3DOF flights over a grid of launches (elevation, muzzle speed, bearing, the day's density): the
fly-out table (:mod:`harp_analysis.engines.flyout_table`) interpolates the flights themselves,
the calibrated MKS (:mod:`harp_analysis.engines.calibrated_mks`) what the ECI MKS misses of
them. Each grid of :func:`grid_at` is flown once and both tables are built from those flights
(the same flights, counted once for both; the fly-out table holds 103 numbers a flight, the
calibrated MKS 105 with its apogee's two, so their bytes follow the flights). Each is judged
on launches drawn at random across the band (:func:`judging_launches`, seeded, none a node of
any grid) against the 3DOF flown at them: the distance of the Earth-fixed
impact point, the apogee altitude and the time of flight, root-mean-square and 95th percentile.
:func:`comparison` tabulates it per gun, grid and method with the build's wall time (the
flights', measured once, and each method's own) and the table's bytes; :func:`size_needed`
reads off the flights and bytes each method needs for an accuracy, by log-log interpolation on
the measured curve (never beyond it), and :func:`size_growth` how many times more flights a
tenfold accuracy takes.

The guns (:data:`GUNS`): HP from Barbados
(:data:`~harp_analysis.analyses.fire_control.firing.BARBADOS_HP`), its drag table's breakpoints and
all, and the baseline cone (Chapter 4 B, eq 4.8's smooth drag law, 2157 m/s) from Yuma's latitude;
both on the turning Earth in eqs 2.1-2.2 air. HP's flights change slope where the launch Mach
crosses a breakpoint of its table, which the grid's speed nodes follow
(:meth:`.flight_grid.Grid.speed_breaks`), and also where the Mach the round regains as the air cools
on its way up (a local maximum below 10.8 km) touches one, a kink along a curve in elevation and
speed that no tensor grid follows; both tables converge more slowly for HP there.

The comparison flies about a hundred thousand 3DOF flights, a few minutes once; it is kept in
memory and on disk (:func:`harp_analysis.foundation.stored.stored_arrays`, by its inputs and
the version of the physics), so the notebook and the ledger read it.

SI inside; degrees only in the names that say so.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.interpolate import PchipInterpolator

from ..engines import calibrated_mks, flyout_table
from ..engines.flight_grid import DEFAULT_GRID, Grid, Gun, fly_grid
from ..engines.learned import LearnedSolution, LearnedTable
from ..engines.threedof import fly_3dof
from ..foundation import earth
from ..foundation.caching import cached_copies
from ..foundation.stored import stored_arrays
from ..foundation.validation import Bounds, ModelValidityWarning, check_choice, real_number
from ..models.launch import Launch, Launches
from ..models.projectiles import BASELINE
from ..models.sites import YUMA
from .fire_control.firing import BARBADOS_HP

__all__ = [
    "GUNS",
    "METHODS",
    "SCALES",
    "JUDGED_LAUNCHES",
    "SEED",
    "TARGETS_M",
    "COLUMNS",
    "grid_at",
    "judging_launches",
    "comparison",
    "SizeNeeded",
    "size_needed",
    "SizeGrowth",
    "size_growth",
]

#: The guns compared: HP from Barbados, and the baseline cone from Yuma's latitude (its
#: longitude about 114.4 deg W), both on the turning Earth.
GUNS: dict[str, Launch] = {
    "HP, Barbados": BARBADOS_HP,
    "baseline cone, Yuma": Launch(
        BASELINE,
        BASELINE.launch_speed_m_s,
        45.0,
        latitude_deg=math.degrees(YUMA.latitude_rad),
        longitude_deg=-114.4,
        rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
    ),
}
#: The two tables, by their names in the engines' catalogue: how each is built from a gun's
#: flights and how it solves launches.
METHODS: dict[str, tuple[Callable[..., LearnedTable], Callable[..., LearnedSolution]]] = {
    "calibrated_mks": (calibrated_mks.calibrate, calibrated_mks.CalibratedSolution),
    "flyout_table": (flyout_table.tabulate, flyout_table.FlyoutSolution),
}
#: The grids' scales (:func:`grid_at`): cells shrink as 1/scale along elevation, speed and
#: bearing; 1 is the engines' default grid.
SCALES = (0.25, 0.35, 0.5, 0.7, 1.0, 1.4, 2.0)
#: Launches judged per gun, and the seed they are drawn with.
JUDGED_LAUNCHES = 400
SEED = 35
#: Impact-point accuracies (root-mean-square, m) whose table sizes are read off.
TARGETS_M = (1000.0, 300.0, 100.0)
#: The columns of :func:`comparison`, one row per gun, scale and method.
COLUMNS = (
    "gun",
    "scale",
    "method",
    "flights",  # 3DOF flights of the grid, the same for both methods
    "rhs_evaluations",  # their right-hand-side evaluations
    "flight_s",  # the flights' wall time (s), measured once, shared
    "build_s",  # the flights' wall time and the method's own (s)
    "nbytes",  # the table's values (bytes)
    "impact_rms_m",  # distance of the Earth-fixed impact point from the 3DOF's
    "impact_p95_m",
    "apogee_rms_m",  # apogee altitude's error
    "apogee_p95_m",
    "tof_rms_s",  # time of flight's error
    "tof_p95_s",
)
_ERRORS = COLUMNS[8:]


def grid_at(scale: float) -> Grid:
    """The grid of ``scale``: the default grid's (:data:`.flight_grid.DEFAULT_GRID`) with
    cells 1/``scale`` its size, its elevation nodes resampled along the default's spacing
    (closer at both ends, a monotone cubic through the default's 21 nodes by their index),
    ``20 scale`` steps; the largest speed step 0.09/``scale``; ``12 scale`` bearings (at
    least four); the density's three nodes (their quadratic's error, a few metres, below every
    grid's). Scale 1 is the default grid itself."""
    scale = Bounds(low=0.1, high=4.0).check(real_number(scale, "scale"), "scale")
    default = np.array(DEFAULT_GRID.elevations_deg)
    steps = max(3, round((default.size - 1) * scale))
    spacing = PchipInterpolator(np.linspace(0.0, 1.0, default.size), default)
    elevations = spacing(np.linspace(0.0, 1.0, steps + 1))
    elevations[[0, -1]] = default[[0, -1]]
    return Grid(
        elevations_deg=tuple(float(e) for e in np.round(elevations, 6)),
        speed_step=DEFAULT_GRID.speed_step / scale,
        bearings=max(4, round(DEFAULT_GRID.bearings * scale)),
    )


def judging_launches(gun: Launch, count: int = JUDGED_LAUNCHES, seed: int = SEED) -> Launches:
    """``count`` launches of ``gun`` drawn uniformly across the tables' band (elevation, speed
    factor, bearing, density change; :data:`.calibrated_mks.BAND`), seeded, from ``gun``'s
    longitude: random draws, never a grid's node."""
    band = calibrated_mks.BAND
    draw = np.random.default_rng(seed).uniform
    speed = draw(*band.speed_factors, count)
    elevation = draw(*band.elevations_deg, count)
    bearing = draw(0.0, 360.0, count)
    density = draw(*band.density_changes, count)
    launches = Gun.of(gun).launches(speed, elevation, bearing, density)
    return launches.but(longitude_deg=gun.longitude_deg)


def _errors(solution, reference) -> dict[str, float]:
    impact = np.linalg.norm(solution.impact_point_m - reference.end_position_m.T, axis=1)
    apogee = np.abs(solution.apogee_altitude_m - reference.apogee_altitude_m)
    tof = np.abs(solution.time_of_flight_s - reference.time_of_flight_s)
    values = {}
    for name, errors in (("impact", impact), ("apogee", apogee), ("tof", tof)):
        unit = "s" if name == "tof" else "m"
        values[f"{name}_rms_{unit}"] = float(np.sqrt(np.mean(errors**2)))
        values[f"{name}_p95_{unit}"] = float(np.percentile(errors, 95))
    return values


def _compare(guns: tuple[str, ...], scales: tuple[float, ...], count: int, seed: int):
    rows = []
    for name in guns:
        gun = GUNS[name]
        judged = judging_launches(gun, count, seed)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ModelValidityWarning)
            reference = fly_3dof(judged)
        for scale in scales:
            grid = grid_at(scale)
            flights = fly_grid(Gun.of(gun), grid)
            for method, (build, solve) in METHODS.items():
                table = build(Gun.of(gun), grid, flights=flights)
                rows.append(
                    dict(
                        gun=name,
                        scale=scale,
                        method=method,
                        flights=table.flights,
                        rhs_evaluations=table.rhs_evaluations,
                        flight_s=flights.seconds,
                        build_s=table.seconds,
                        nbytes=table.nbytes,
                        **_errors(solve(judged, table), reference),
                    )
                )
    return pd.DataFrame(rows, columns=list(COLUMNS))


@cached_copies
def comparison(
    guns: tuple[str, ...] = tuple(GUNS),
    scales: tuple[float, ...] = SCALES,
    count: int = JUDGED_LAUNCHES,
    seed: int = SEED,
) -> pd.DataFrame:
    """Both tables of each of ``guns`` (names of :data:`GUNS`) built from the same 3DOF flights
    over :func:`grid_at` each of ``scales`` and judged on ``count`` launches drawn with
    ``seed`` (:func:`judging_launches`) against the 3DOF: one row per gun, scale and method
    (:data:`COLUMNS`). Computed once (a few minutes), kept in memory and on disk."""
    for name in guns:
        check_choice(name, "gun", GUNS)
    key = repr((tuple(Gun.of(GUNS[name]).key for name in guns), scales, count, seed))

    def compute() -> dict[str, np.ndarray]:
        frame = _compare(guns, tuple(scales), count, seed)
        arrays = {column: frame[column].to_numpy() for column in COLUMNS[3:]}
        return {
            **arrays,
            "gun": np.array([guns.index(g) for g in frame.gun]),
            "scale": frame.scale.to_numpy(),
            "method": np.array([list(METHODS).index(m) for m in frame.method]),
        }

    arrays, _ = stored_arrays(__name__, "comparisons", key, compute)
    return pd.DataFrame(
        {
            "gun": [guns[i] for i in arrays["gun"]],
            "scale": arrays["scale"],
            "method": [list(METHODS)[i] for i in arrays["method"]],
            **{column: arrays[column] for column in COLUMNS[3:]},
        },
        columns=list(COLUMNS),
    )


@dataclass(frozen=True)
class SizeNeeded:
    """The table a method needs for an accuracy (:func:`size_needed`): its 3DOF flights, bytes
    and build time (s), by log-log interpolation between the two grids of the measured curve
    that bracket the accuracy (NaN where no grid reaches it; the finest's numbers kept), and
    the other method's for the same accuracy, with their ratio (this over the other)."""

    gun: str
    method: str
    measure: str
    target: float
    flights: float
    nbytes: float
    build_s: float
    other_flights: float
    other_nbytes: float
    ratio: float  # flights over the other method's
    finest_flights: int  # the largest grid measured, and what it reached
    finest_error: float
    other_finest_error: float

    @property
    def megabytes(self) -> float:
        return self.nbytes / 1e6

    @property
    def other_megabytes(self) -> float:
        return self.other_nbytes / 1e6


def _needed(rows: pd.DataFrame, measure: str, target: float) -> tuple[float, float, float]:
    """Flights, bytes and build seconds where the measured curve of ``rows`` (one method of one
    gun, coarse to fine) first falls to ``target``: log-log interpolation between the grids
    that bracket it; the coarsest's where it is already there; NaN where none gets there."""
    rows = rows.sort_values("flights")
    error = rows[measure].to_numpy()
    reached = np.flatnonzero(error <= target)
    if not reached.size:
        return math.nan, math.nan, math.nan
    i = reached[0]
    if i == 0:
        first = rows.iloc[0]
        return float(first["flights"]), float(first["nbytes"]), float(first["build_s"])
    share = math.log(error[i - 1] / target) / math.log(error[i - 1] / error[i])
    low, high = rows.iloc[i - 1], rows.iloc[i]
    return tuple(  # type: ignore[return-value]
        float(math.exp(math.log(low[k]) + share * (math.log(high[k]) - math.log(low[k]))))
        for k in ("flights", "nbytes", "build_s")
    )


def size_needed(
    gun: str = "HP, Barbados",
    method: str = "flyout_table",
    target: float = 300.0,
    measure: str = "impact_rms_m",
    *,
    frame: pd.DataFrame | None = None,
) -> SizeNeeded:
    """The 3DOF flights, bytes and build time ``method`` (a name of :data:`METHODS`) needs for
    ``gun`` (a name of :data:`GUNS`) to bring ``measure`` (a column of :data:`COLUMNS`, an error)
    to ``target``, read off the measured curve of ``frame`` (:func:`comparison` by default),
    and the other method's for the same."""
    check_choice(gun, "gun", GUNS)
    check_choice(method, "method", METHODS)
    check_choice(measure, "measure", _ERRORS)
    target = Bounds(low=0.0, low_inclusive=False).check(real_number(target, "target"), "target")
    frame = comparison() if frame is None else frame
    other = next(name for name in METHODS if name != method)
    mine, theirs = (frame[(frame.gun == gun) & (frame.method == m)] for m in (method, other))
    flights, nbytes, seconds = _needed(mine, measure, target)
    other_flights, other_nbytes, _ = _needed(theirs, measure, target)
    finest, other_finest = (rows.sort_values("flights").iloc[-1] for rows in (mine, theirs))
    return SizeNeeded(
        gun,
        method,
        measure,
        target,
        flights,
        nbytes,
        seconds,
        other_flights,
        other_nbytes,
        flights / other_flights,
        int(finest.flights),
        float(finest[measure]),
        float(other_finest[measure]),
    )


@dataclass(frozen=True)
class SizeGrowth:
    """How a method's table grows for a finer accuracy (:func:`size_growth`): the flights it
    needs at each of two accuracies and their ratio, and the other method's."""

    gun: str
    method: str
    coarse: SizeNeeded
    fine: SizeNeeded
    factor: float  # flights for the fine accuracy over those for the coarse
    other_factor: float


def size_growth(
    gun: str = "HP, Barbados",
    method: str = "flyout_table",
    coarse_m: float = 1000.0,
    fine_m: float = 100.0,
    *,
    frame: pd.DataFrame | None = None,
) -> SizeGrowth:
    """How many times the flights ``method`` needs for ``gun`` grow from an impact-point
    accuracy of ``coarse_m`` to ``fine_m`` (root-mean-square, m; :func:`size_needed`), and the
    other method's: the text's "as the size of the discrete volume is decreased to increase
    accuracy, the number of simulations [...] increase", measured."""
    frame = comparison() if frame is None else frame
    coarse = size_needed(gun, method, coarse_m, frame=frame)
    fine = size_needed(gun, method, fine_m, frame=frame)
    return SizeGrowth(
        gun,
        method,
        coarse,
        fine,
        fine.flights / coarse.flights,
        fine.other_flights / coarse.other_flights,
    )
