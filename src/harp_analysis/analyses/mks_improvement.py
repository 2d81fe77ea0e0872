"""The better MKS judged (Chapter 7 C, issue 17): its one coefficient fitted on one set of
launches, the dissertation's MKS and the improved one judged against the 3DOF on a disjoint set,
and error maps over bearing x elevation x latitude on the rotating Earth.

The error measures are those of :mod:`.rotating`: positions at the 3DOF's output times while both
are in flight (the distance between the two at the same time), the maximum over the flight and
the value at the 3DOF's apogee; and at the end, the impact point's miss (Earth-fixed), its range
and its time against the 3DOF's.

The split is structural: :func:`fit` takes the training launches and nothing else, and the
judging set (:data:`JUDGING`) shares no launch with the training set (:data:`TRAINING`): other
elevations, other projectiles (HP and LP, without Chapter 2's wind and spin, which no MKS
models), and rotating-Earth launches at bearings and latitudes off the training grid. The
baseline's still-Earth elevations sit between the training ones (an interpolation); HP, LP and
the rotating-Earth launches are the harder test, and :func:`judged_rms` reports them
apart.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from functools import cache, partial

import numpy as np
import pandas as pd
from scipy.optimize import minimize_scalar

from ..engines import eci, mks, mks_improved
from ..engines.mks_improved import Calibration
from ..engines.threedof import fly_3dof, simulate_3dof
from ..foundation import earth
from ..foundation.caching import cached_copies
from ..foundation.sweeps import sweep
from ..foundation.validation import ModelValidityWarning, check_choice
from ..models.launch import Launch, baseline_chapter_4, chapter_2
from ..models.projectiles import BASELINE, HP, LP
from ..models.trajectory import rotate_about_axis
from . import error_budget
from .comparisons import BASELINE_ELEVATIONS_DEG

__all__ = [
    "TRAINING",
    "JUDGING",
    "LaunchErrors",
    "launch_errors",
    "fit",
    "calibration",
    "judge",
    "asymptote_errors",
    "MAP_BEARINGS_DEG",
    "MAP_ELEVATIONS_DEG",
    "MAP_LATITUDES_DEG",
    "error_map",
    "impact_time_error_s",
    "judged_rms",
    "map_shares",
    "error_differences_m",
    "BROAD_SPEEDS_M_S",
    "BROAD_ELEVATIONS_DEG",
    "BROAD_MEASURES",
    "BROAD_SPLITS",
    "broad_projectiles",
    "BroadLaunch",
    "broad_launches",
    "broad_judgement",
    "broad_errors",
    "BroadImprovement",
    "broad_improvement",
    "broad_band_shares",
]

_SPIN = earth.ROTATION_RATE_RAD_S


def _rotating(elevation_deg: float, latitude_deg: float, bearing_deg: float) -> Launch:
    return baseline_chapter_4(
        elevation_deg,
        latitude_deg=latitude_deg,
        bearing_deg=bearing_deg,
        rotation_rate_rad_s=_SPIN,
    )


def _still_air(projectile, elevation_deg: float) -> Launch:
    """Chapter 2 A's launch of HP or LP at ``elevation_deg`` without its wind and spin."""
    return chapter_2(projectile, elevation_deg=elevation_deg, cross_wind_m_s=0.0, spin_rad_s=0.0)


#: The fit's launches: the baseline cone at 30-75 deg, non-rotating (eqs 2.1-2.2), and fired
#: east and west from the equator and 45 deg N at 30 and 45 deg.
TRAINING: tuple[Launch, ...] = (
    *(baseline_chapter_4(e) for e in (30.0, 45.0, 60.0, 75.0)),
    *(_rotating(e, lat, brg) for lat in (0.0, 45.0) for brg in (90.0, 270.0) for e in (30.0, 45.0)),
)
#: The judging launches, none of them in :data:`TRAINING`: the baseline at the elevations
#: between and beyond, HP and LP, and the rotating Earth off the training grid.
JUDGING: tuple[Launch, ...] = (
    *(baseline_chapter_4(e) for e in (35.0, 50.0, 65.0, 80.0, 85.0)),
    *(_still_air(p, e) for p in (HP, LP) for e in (40.0, 50.0, 70.0)),
    _rotating(35.0, 13.1, 109.0),  # Barbados' latitude, its firing bearing
    _rotating(50.0, -30.0, 45.0),
    _rotating(65.0, 60.0, 180.0),
    _rotating(80.0, 32.9, 200.0),
    _rotating(40.0, -15.0, 330.0),
    _rotating(85.0, 20.0, 0.0),
)


@cached_copies
def _flight(launch: Launch) -> pd.DataFrame:
    """The 3DOF's table of ``launch`` (0.25 s rows), computed once."""
    return simulate_3dof(launch, output_step_s=0.25)


@dataclass(frozen=True)
class LaunchErrors:
    """One MKS against the 3DOF: position errors (m) while both fly, and the impact's."""

    max_error_m: float
    apogee_error_m: float
    impact_miss_m: float
    impact_range_error_m: float
    impact_time_error_s: float
    rms_error_m: float


def launch_errors(
    launch: Launch, solution: mks_improved.ImprovedSolution, flight: pd.DataFrame | None = None
) -> LaunchErrors:
    """``solution`` (of ``launch``) against the 3DOF's ``flight`` of ``launch`` (flown and
    kept for the next caller if not given)."""
    flight = _flight(launch) if flight is None else flight
    time = flight.time_s.to_numpy()
    both = time <= solution.impact_time_s
    simulated = flight[["x_m", "y_m", "z_m"]].to_numpy()[both]
    error = np.linalg.norm(simulated - solution.positions(time[both]), axis=1)
    apogee_time = flight.attrs["apogee_time_s"]
    end = flight[["x_m", "y_m", "z_m"]].to_numpy()[-1:].T  # inertial; Earth-fixed below
    impact = rotate_about_axis(
        end, np.array([-flight.attrs["time_of_flight_s"] * launch.rotation_rate_rad_s])
    )[:, 0]
    return LaunchErrors(
        max_error_m=float(error.max()),
        apogee_error_m=float(np.interp(apogee_time, time[both], error)),
        impact_miss_m=float(np.linalg.norm(solution.impact_point_m - impact)),
        impact_range_error_m=solution.impact_range_m[0] - flight.attrs["range_m"],
        impact_time_error_s=solution.impact_time_s - flight.attrs["time_of_flight_s"],
        rms_error_m=float(np.sqrt(np.mean(error**2))),
    )


def _training_cost(launches: tuple[Launch, ...], calibration: Calibration) -> float:
    """Mean square of the RMS position errors over ``launches`` (m^2)."""
    errors = [
        launch_errors(launch, mks_improved.solve(launch, calibration)).rms_error_m
        for launch in launches
    ]
    return float(np.mean(np.square(errors)))


def fit(training: tuple[Launch, ...]) -> Calibration:
    """The calibration that makes the improved MKS closest to the 3DOF on ``training`` (the only
    launches it sees): ``reentry_scale`` by a bounded 1-D minimisation of the mean square RMS
    position error over them."""
    training = tuple(training)
    if not training or not all(isinstance(launch, Launch) for launch in training):
        raise TypeError("training must be a non-empty sequence of Launch")
    return Calibration(
        reentry_scale=_minimise(lambda x: _training_cost(training, Calibration(reentry_scale=x)))
    )


def _minimise(cost) -> float:
    """Argmin of ``cost`` over the factors 0.5-1.5 (to 1e-4)."""
    result = minimize_scalar(cost, bounds=(0.5, 1.5), method="bounded", options={"xatol": 1e-4})
    return float(result.x)


@cache
def calibration() -> Calibration:
    """:func:`fit` of :data:`TRAINING`, computed once.

    Returns
    -------
    Calibration
        The improved MKS's re-entry scale fitted on the training launches, for
        :func:`harp_analysis.engines.mks_improved.solve`.
    """
    return fit(TRAINING)


def _row(launch: Launch, variant: str, fitted: Calibration) -> dict:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)  # beta > 0.25 for LP
        solution = mks_improved.flight(launch, variant, fitted)
    errors = launch_errors(launch, solution)
    return {
        "projectile": launch.projectile.name,
        "elevation_deg": launch.elevation_deg,
        "latitude_deg": launch.latitude_deg,
        "bearing_deg": launch.bearing_deg,
        "rotating": launch.rotation_rate_rad_s != 0.0,
        # the dissertation's eq 3.22 beta (ECI where the Earth turns): the text's validity
        "beta": float(mks_improved.dissertation(launch).ascent.beta[0, 0]),
        "variant": variant,
        **{name: getattr(errors, name) for name in LaunchErrors.__dataclass_fields__},
    }


def judge(launches: tuple[Launch, ...] = JUDGING) -> pd.DataFrame:
    """Both variants against the 3DOF on ``launches`` (the judging set by default), one row per
    launch and variant, with the calibration fitted on :data:`TRAINING`; ``beta`` is the
    dissertation's MKS beta of the launch (the text holds its MKS valid to
    :data:`~harp_analysis.engines.mks.BETA_VALIDITY_LIMIT`)."""
    fitted = calibration()
    return pd.DataFrame(
        [_row(launch, variant, fitted) for launch in launches for variant in mks_improved.VARIANTS]
    )


def asymptote_errors(launches: tuple[Launch, ...] = JUDGING) -> pd.DataFrame:
    """h_inf / h - 1 of both variants, h the 3DOF's angular momentum at its apogee (above the
    air: Fig 4.12's measure), one row per launch."""
    fitted = calibration()
    rows = []
    for launch in launches:
        flight = _flight(launch)
        h = np.interp(
            flight.attrs["apogee_time_s"], flight.time_s, flight.specific_angular_momentum_m2_s
        )
        row = {
            "projectile": launch.projectile.name,
            "elevation_deg": launch.elevation_deg,
            "latitude_deg": launch.latitude_deg,
            "bearing_deg": launch.bearing_deg,
        }
        for variant in mks_improved.VARIANTS:
            solution = mks_improved.flight(launch, variant, fitted)
            row[variant] = float(solution.ascent.h_inf[0, 0] / h - 1)
        rows.append(row)
    return pd.DataFrame(rows)


#: The map's grid: continuous bearing, elevation and latitude, coarsely sampled.
MAP_BEARINGS_DEG = tuple(float(b) for b in np.arange(0.0, 360.0, 30.0))
MAP_ELEVATIONS_DEG = tuple(float(e) for e in np.linspace(30.0, 85.0, 8))
MAP_LATITUDES_DEG = (-60.0, -30.0, 0.0, 30.0, 60.0)


def _map_point(point: tuple[float, float, float], fitted: Calibration) -> dict:
    """Both variants' impact miss and max position error at one (bearing, elevation, latitude)."""
    bearing, elevation, latitude = point
    launch = _rotating(elevation, latitude, bearing)
    flight = simulate_3dof(launch, output_step_s=0.25)  # not kept: the map has hundreds
    row = {
        "bearing_deg": bearing,
        "elevation_deg": elevation,
        "latitude_deg": latitude,
        "air_momentum_share": mks_improved.air_momentum_share(launch),
    }
    for variant in mks_improved.VARIANTS:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ModelValidityWarning)  # the share column says
                solution = mks_improved.flight(launch, variant, fitted)
            errors = launch_errors(launch, solution, flight)
        except ValueError:  # a variant that cannot fly the launch (its error names why)
            row[f"{variant}_impact_miss_m"] = row[f"{variant}_max_error_m"] = np.nan
            continue
        row[f"{variant}_impact_miss_m"] = errors.impact_miss_m
        row[f"{variant}_max_error_m"] = errors.max_error_m
    return row


@cached_copies
def error_map(
    bearings_deg: tuple[float, ...] = MAP_BEARINGS_DEG,
    elevations_deg: tuple[float, ...] = MAP_ELEVATIONS_DEG,
    latitudes_deg: tuple[float, ...] = MAP_LATITUDES_DEG,
    progress: bool = True,
) -> pd.DataFrame:
    """The baseline cone on the rotating Earth over the grid, one row per point: the impact miss
    and the max position error (m) of the dissertation's MKS and the improved one (NaN where a
    variant cannot fly the launch), and the air's share of the angular momentum
    (:func:`~harp_analysis.engines.mks_improved.air_momentum_share`; beyond its limit the improved
    one warns)."""
    points = [(b, e, lat) for lat in latitudes_deg for e in elevations_deg for b in bearings_deg]
    rows = sweep(
        partial(_map_point, fitted=calibration()),
        points,
        progress=progress,
        description="MKS error map",
    )
    return pd.DataFrame(rows)


def impact_time_error_s(elevations_deg: tuple[float, ...] = BASELINE_ELEVATIONS_DEG) -> float:
    """The median magnitude (s) of the dissertation MKS's impact-time error against the 3DOF
    for Chapter 4 B's baseline cone at ``elevations_deg`` (non-rotating): how late or early the
    text's MKS arrives at a ground target (Ch. 7 C)."""
    errors = [
        launch_errors(launch, mks_improved.dissertation(launch)).impact_time_error_s
        for launch in map(baseline_chapter_4, elevations_deg)
    ]
    return float(np.median(np.abs(errors)))


def judged_rms(earth: str = "both") -> pd.DataFrame:
    """The root-mean-square of each :class:`LaunchErrors` field over the judging set, or its
    launches on the ``"turning"`` or ``"still"`` Earth: one row per variant."""
    check_choice(earth, "earth", ("both", "turning", "still"))
    judged = judge()
    if earth != "both":
        judged = judged[judged.rotating == (earth == "turning")]
    measures = list(LaunchErrors.__dataclass_fields__)
    return judged.groupby("variant")[measures].agg(lambda v: float(np.sqrt(np.mean(v**2))))


def map_shares(
    error_map: pd.DataFrame, measures: tuple[str, ...] = ("impact_miss_m", "max_error_m")
) -> pd.Series:
    """What :func:`error_map` (or :func:`broad_judgement`) says, as shares of its points: where
    the improved MKS has the smaller magnitude of each of ``measures``, over all points, inside
    its validity band (:data:`~harp_analysis.engines.mks_improved.AIR_MOMENTUM_SHARE_RANGE`, drawn
    from the map) and outside it, with the points inside and those where it has no solution."""
    low, high = mks_improved.AIR_MOMENTUM_SHARE_RANGE
    inside = (error_map.air_momentum_share > low) & (error_map.air_momentum_share <= high)
    shares: dict[str, float] = {"points": len(error_map), "inside": int(inside.sum())}
    for measure in measures:
        better = np.abs(error_map[f"improved_{measure}"]) < np.abs(
            error_map[f"dissertation_{measure}"]
        )
        shares[f"better_{measure}"] = float(better.mean())
        shares[f"better_{measure}_inside"] = float(better[inside].mean())
        shares[f"better_{measure}_outside"] = float(better[~inside].mean())
    shares["unsolved"] = int(error_map[f"improved_{measures[0]}"].isna().sum())
    return pd.Series(shares)


def error_differences_m(error_map: pd.DataFrame) -> pd.DataFrame:
    """The improved MKS's error minus the dissertation's (m; negative: the improved one is
    nearer the 3DOF) at each :func:`error_map` point, for the impact miss and the largest error
    in flight: a measure that near-zero errors cannot blow up, as a ratio does where the text's
    MKS misses by metres by luck. NaN where the improved MKS has no solution."""
    return pd.DataFrame(
        {
            measure: error_map[f"improved_{measure}"] - error_map[f"dissertation_{measure}"]
            for measure in ("impact_miss_m", "max_error_m")
        }
    )


# --- the broad judging set (issue 26) ------------------------------------------------------------
BROAD_SPEEDS_M_S = (1500.0, 2000.0, 2500.0, 3000.0, 3500.0)
BROAD_ELEVATIONS_DEG = (20.0, 35.0, 50.0, 65.0, 85.0)
#: Signed errors of the MKS against the 3DOF (MKS minus 3DOF; the impact miss is a distance).
BROAD_MEASURES = ("apogee_error_m", "impact_range_error_m", "impact_time_error_s", "impact_miss_m")
#: How :func:`broad_errors` groups the launches: the text's validity (eq 3.22's beta at most
#: mks.BETA_VALIDITY_LIMIT, "inside", or not), the improved MKS's own beta warning
#: (mks_improved.MAX_JUDGED_BETA), the Earth, the day's air, the projectile.
BROAD_SPLITS = ("all", "validity", "warning", "earth", "air", "projectile")
_AIRS = ("standard", "told", "untold")
_BROAD_SEED = 26
_BROAD_LATITUDES_DEG = (-60.0, 60.0)


def broad_projectiles() -> dict:
    """The broad set's projectiles by name: HP and LP (Chapter 2), the baseline cone (Chapter
    4) and the Martlet 2C as Chapter 6 flies it from Barbados (a constant Cd0 A)."""
    martlet = error_budget.martlet_at_barbados().projectile
    return {"HP": HP, "LP": LP, "baseline": BASELINE, "Martlet": martlet}


@dataclass(frozen=True)
class BroadLaunch:
    """One launch of the broad set: what the 3DOF flies (``flown``, its day's air included),
    what the MKS is given (``told``: the same, or without the day's air), and its labels."""

    projectile: str
    flown: Launch
    told: Launch
    earth: str  # "still" or "turning"
    air: str  # "standard", "told" or "untold"


def broad_launches(
    speeds_m_s: tuple[float, ...] = BROAD_SPEEDS_M_S,
    elevations_deg: tuple[float, ...] = BROAD_ELEVATIONS_DEG,
    projectiles: tuple[str, ...] = ("HP", "LP", "baseline", "Martlet"),
    seed: int = _BROAD_SEED,
) -> tuple[BroadLaunch, ...]:
    """Every projectile x speed x elevation on the still and on the turning Earth, each in the
    standard air and on one day's air told and not told to the MKS. A turning-Earth launch's
    latitude (uniform in -60..60 deg) and bearing (uniform) and each launch's day (density
    change and temperature change, normal at
    :data:`~harp_analysis.analyses.error_budget.CHAPTER_7B`'s sds) are drawn from ``seed``, one per
    projectile x speed x elevation x Earth, in that order."""
    chosen = broad_projectiles()
    sizes = {u.field: u.sd for u in error_budget.CHAPTER_7B}
    rng = np.random.default_rng(seed)
    launches = []
    for name in projectiles:
        for speed in speeds_m_s:
            for elevation in elevations_deg:
                for turning in (False, True):
                    latitude, bearing = rng.uniform(*_BROAD_LATITUDES_DEG), rng.uniform(0, 360)
                    standard = Launch(chosen[name], speed, elevation)
                    if turning:
                        standard = standard.but(
                            latitude_deg=latitude, bearing_deg=bearing, rotation_rate_rad_s=_SPIN
                        )
                    day = standard.but(
                        **{
                            field: rng.normal(0.0, sizes[field])
                            for field in ("density_change_fraction", "temperature_change_k")
                        }
                    )
                    earth_name = "turning" if turning else "still"
                    launches += [
                        BroadLaunch(name, standard, standard, earth_name, "standard"),
                        BroadLaunch(name, day, day, earth_name, "told"),
                        BroadLaunch(name, day, standard, earth_name, "untold"),
                    ]
    return tuple(launches)


def _mks_errors(solution: mks_improved.ImprovedSolution, flights, index: int) -> dict:
    return {
        "apogee_error_m": solution.apogee_altitude_m - flights.apogee_altitude_m[index],
        "impact_range_error_m": solution.impact_range_m[0] - flights.range_m[index],
        "impact_time_error_s": solution.impact_time_s - flights.time_of_flight_s[index],
        "impact_miss_m": float(
            np.linalg.norm(solution.impact_point_m - flights.end_position_m[:, index])
        ),
    }


def _judged_row(entry: BroadLaunch, flights, index: int, fitted: Calibration) -> dict:
    told = entry.told
    beta = float(eci.correction_for_launch(told).solution(warn=False).beta.flat[0])
    row = {
        "projectile": entry.projectile,
        "speed_m_s": told.speed_m_s,
        "elevation_deg": told.elevation_deg,
        "latitude_deg": told.latitude_deg,
        "bearing_deg": told.bearing_deg,
        "earth": entry.earth,
        "air": entry.air,
        "density_change_fraction": entry.flown.density_change_fraction,
        "temperature_change_k": entry.flown.temperature_change_k,
        "beta": beta,
        "validity": "inside" if beta <= mks.BETA_VALIDITY_LIMIT else "outside",
        "warning": "warned" if beta > mks_improved.MAX_JUDGED_BETA else "quiet",
        "air_momentum_share": mks_improved.air_momentum_share(told),
    }
    for variant in mks_improved.VARIANTS:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ModelValidityWarning)  # the columns say
                errors = _mks_errors(mks_improved.flight(told, variant, fitted), flights, index)
        except ValueError:  # no re-entry solution (its error names why)
            errors = dict.fromkeys(BROAD_MEASURES, np.nan)
        row |= {f"{variant}_{measure}": value for measure, value in errors.items()}
    return row


@cached_copies
def broad_judgement(
    speeds_m_s: tuple[float, ...] = BROAD_SPEEDS_M_S,
    elevations_deg: tuple[float, ...] = BROAD_ELEVATIONS_DEG,
    projectiles: tuple[str, ...] = ("HP", "LP", "baseline", "Martlet"),
    seed: int = _BROAD_SEED,
) -> pd.DataFrame:
    """Both variants against the 3DOF on :func:`broad_launches`, one row per launch: its
    labels, eq 3.22's beta of the launch the MKS is given (the dissertation's ECI MKS's) with
    its ``validity`` and ``warning`` groups (:data:`BROAD_SPLITS`), the air's share of its
    angular momentum, and each variant's :data:`BROAD_MEASURES` as ``<variant>_<measure>``
    (NaN where a variant has no solution). The 3DOF flies each projectile and Earth as one
    compiled batch; the calibration is :func:`calibration`'s."""
    launches = broad_launches(speeds_m_s, elevations_deg, projectiles, seed)
    fitted = calibration()
    rows: list[dict | None] = [None] * len(launches)
    groups: dict[tuple, list[int]] = {}
    for index, entry in enumerate(launches):
        groups.setdefault((entry.projectile, entry.earth), []).append(index)
    for indices in groups.values():
        flights = fly_3dof([launches[i].flown for i in indices])
        if not flights.impact.all():
            raise RuntimeError("a broad-set 3DOF flight did not land within its time limit")
        for position, index in enumerate(indices):
            rows[index] = _judged_row(launches[index], flights, position, fitted)
    return pd.DataFrame(rows)


def _solved(judged: pd.DataFrame) -> pd.Series:
    """Launches where both variants have a solution: the pairs compared."""
    return judged[[f"{v}_{BROAD_MEASURES[0]}" for v in mks_improved.VARIANTS]].notna().all(axis=1)


def _rms(values: np.ndarray) -> float:
    """Root-mean-square of ``values`` (NaN if there are none)."""
    return float(np.sqrt(np.mean(values**2))) if values.size else math.nan


def broad_errors(split: str = "all", judged: pd.DataFrame | None = None) -> pd.DataFrame:
    """Root-mean-square and median magnitude of each variant's :data:`BROAD_MEASURES` over the
    broad set's launches that both variants solve (``judged``, :func:`broad_judgement` by
    default), grouped by ``split`` (:data:`BROAD_SPLITS`): index (group, variant), columns
    ``<measure>_rms``, ``<measure>_median``, ``launches`` and ``unsolved`` (the group's
    launches the improved MKS has no solution for, left out of both variants' statistics)."""
    check_choice(split, "split", BROAD_SPLITS)
    judged = broad_judgement() if judged is None else judged
    groups = judged.assign(all="all")[split]
    solved = _solved(judged)
    rows = {}
    for group in sorted(groups.unique()):
        members = judged[(groups == group) & solved]
        for variant in mks_improved.VARIANTS:
            row = {}
            for measure in BROAD_MEASURES:
                values = np.abs(members[f"{variant}_{measure}"].to_numpy())
                row[f"{measure}_rms"] = _rms(values)
                row[f"{measure}_median"] = float(np.median(values)) if values.size else np.nan
            row["launches"] = len(members)
            row["unsolved"] = int(((groups == group) & ~solved).sum())
            rows[group, variant] = row
    return pd.DataFrame(rows).T.rename_axis([split, "variant"])


@dataclass(frozen=True)
class BroadImprovement:
    """One measure and statistic of the improved MKS over the dissertation's on a subset of
    the broad set (:func:`broad_improvement`)."""

    measure: str
    statistic: str
    improved: float  # in the measure's unit
    dissertation: float
    launches: int  # both variants solved
    unsolved: int  # the improved MKS has no solution
    better_share: float  # of the launches, where the improved MKS's magnitude is smaller

    @property
    def ratio(self) -> float:
        return self.improved / self.dissertation


def broad_improvement(
    measure: str = "impact_range_error_m",
    statistic: str = "rms",
    *,
    validity: str = "all",
    earth: str = "both",
    air: str = "all",
    judged: pd.DataFrame | None = None,
) -> BroadImprovement:
    """``statistic`` ("rms" or "median" of the magnitude) of ``measure`` on the broad set's
    launches of the given text ``validity`` ("inside", "outside" or "all"), ``earth``
    ("still", "turning" or "both") and day's ``air`` ("standard", "told", "untold" or "all"),
    the improved MKS's and the dissertation's, over the launches both solve (``judged``,
    :func:`broad_judgement` by default)."""
    check_choice(measure, "measure", BROAD_MEASURES)
    check_choice(statistic, "statistic", ("rms", "median"))
    check_choice(validity, "validity", ("all", "inside", "outside"))
    check_choice(earth, "earth", ("both", "still", "turning"))
    check_choice(air, "air", ("all", *_AIRS))
    judged = broad_judgement() if judged is None else judged
    chosen = np.ones(len(judged), dtype=bool)
    for column, value, every in (("validity", validity, "all"), ("earth", earth, "both")):
        if value != every:
            chosen &= judged[column] == value
    if air != "all":
        chosen &= judged.air == air
    solved = _solved(judged)
    members = judged[chosen & solved]
    magnitude = {v: np.abs(members[f"{v}_{measure}"].to_numpy()) for v in mks_improved.VARIANTS}
    reduce = _rms if statistic == "rms" else np.median
    return BroadImprovement(
        measure,
        statistic,
        float(reduce(magnitude["improved"])),
        float(reduce(magnitude["dissertation"])),
        len(members),
        int((chosen & ~solved).sum()),
        float(np.mean(magnitude["improved"] < magnitude["dissertation"])),
    )


def broad_band_shares() -> pd.Series:
    """:func:`map_shares` of the broad set's turning-Earth launches (none an error-map point;
    on the still Earth the air carries nothing and every launch is inside the band), for the
    impact miss and the impact range: the validity band checked on launches it was not drawn
    from."""
    judged = broad_judgement()
    turning = judged[judged.earth == "turning"].reset_index(drop=True)
    return map_shares(turning, ("impact_miss_m", "impact_range_error_m"))
