"""The calibrated MKS judged (issue 35): on launches it was never calibrated on, against the
text's ECI MKS and the project's improved MKS, every one measured against the 3DOF.

Guns are drawn at random: each of HP, LP and the baseline cone at two sites on the turning Earth
(latitudes uniform in -50..50 deg) and one on a still Earth; each gun's calibration is learned on
its own grid of 3DOF flights (:mod:`harp_analysis.engines.calibrated_mks`). Launches are drawn
at random across the band it covers (:data:`~harp_analysis.engines.calibrated_mks.BAND`: muzzle
speeds 0.8-1.15 of the projectile's, elevations 15-88 deg, any bearing, the day's density within
+-10 %), never at the grid's nodes: a draw that falls within a hair of a node on every axis is
drawn again (the chance is nil; the check makes the claim true by construction). Each launch
is flown by the 3DOF (the truth, rtol 1e-9), the calibrated MKS, the ECI MKS (three terms, the
one door) and the improved MKS (:func:`.mks_improvement.calibration`); the errors are the
impact point's distance (Earth-fixed), the apogee altitude's and the time of flight's. A
judgement is computed once per version of the physics (a minute: 360 3DOF flights and each
model at each launch, one by one), then kept in memory and on disk
(:func:`harp_analysis.foundation.stored.stored_arrays`, by its guns, count and seed).

SI inside; degrees only in the names that say so.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..engines import calibrated_mks, eci, mks_improved, threedof
from ..engines.flight_grid import DEFAULT_GRID, Gun
from ..foundation import earth
from ..foundation.caching import cached_copies
from ..foundation.stored import stored_arrays
from ..foundation.validation import ModelValidityWarning, whole_number
from ..models.launch import Launch
from ..models.projectiles import get_projectile
from ..models.trajectory import rotate_about_axis
from . import mks_improvement

__all__ = [
    "MODELS",
    "MEASURES",
    "judging_guns",
    "judging_launches",
    "judge",
    "Accuracy",
    "accuracy",
]

#: The models judged against the 3DOF, as the table's columns name them.
MODELS = ("calibrated", "eci", "improved")
#: The errors measured of each: impact point (m), apogee altitude (m), time of flight (s).
MEASURES = ("impact_m", "apogee_m", "time_of_flight_s")
_PROJECTILES = ("HP", "LP", "baseline")
_SEED = 35


def judging_guns(seed: int = _SEED) -> tuple[Gun, ...]:
    """Each projectile at two random sites on the turning Earth (latitude uniform in -50..50
    deg) and at one on a still Earth (latitude 0), in that order."""
    rng = np.random.default_rng(seed)
    guns = []
    for name in _PROJECTILES:
        projectile = get_projectile(name)
        for _ in range(2):
            latitude = float(rng.uniform(-50.0, 50.0))
            guns.append(
                Gun(
                    projectile, latitude_deg=latitude, rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S
                )
            )
        guns.append(Gun(projectile))
    return tuple(guns)


def _on_a_node(values: np.ndarray, axes: tuple[np.ndarray, ...]) -> bool:
    """Whether (elevation, speed factor, bearing, density change) lies within a hair of a grid
    node on every axis."""
    return all(np.min(np.abs(axis - value)) < 1e-6 for axis, value in zip(axes, values))


def judging_launches(gun: Gun, count: int, seed: int) -> tuple[Launch, ...]:
    """``count`` launches of ``gun`` drawn uniformly across its band, from random longitudes,
    none at a node of the calibration's grid."""
    band = calibrated_mks.BAND
    axes = DEFAULT_GRID.axes(gun)
    rng = np.random.default_rng(seed)
    launches: list[Launch] = []
    while len(launches) < count:
        draw = np.array(
            [
                rng.uniform(*band.elevations_deg),
                rng.uniform(*band.speed_factors),
                rng.uniform(0.0, 360.0),
                rng.uniform(*band.density_changes),
            ]
        )
        if _on_a_node(draw, axes):
            continue
        elevation, speed, bearing, density = draw
        launches.append(
            Launch(
                gun.projectile,
                speed * gun.projectile.launch_speed_m_s,
                elevation,
                bearing_deg=bearing,
                latitude_deg=gun.latitude_deg,
                longitude_deg=float(rng.uniform(-180.0, 180.0)),
                rotation_rate_rad_s=gun.rotation_rate_rad_s,
                density_change_fraction=density,
            )
        )
    return tuple(launches)


def _earth_fixed(inertial: np.ndarray, launch: Launch, time_s: float) -> np.ndarray:
    return rotate_about_axis(
        np.asarray(inertial, dtype=float)[:, None],
        np.array([-launch.rotation_rate_rad_s * time_s]),
    )[:, 0]


def _errors(launch: Launch, truth, model: str, fitted) -> dict:
    """The errors of ``model`` on ``launch`` against the 3DOF's flight ``truth``."""
    impact = _earth_fixed(
        truth[["x_m", "y_m", "z_m"]].to_numpy()[-1], launch, truth.time_s.iloc[-1]
    )
    if model == "calibrated":
        calibrated = calibrated_mks.CalibratedSolution(launch)
        point, apogee = calibrated.impact_point_m, calibrated.apogee_altitude_m
        time = calibrated.time_of_flight_s
    elif model == "eci":
        table = eci.simulate_eci_mks(launch, warn=False)
        end = table[["x_m", "y_m", "z_m"]].to_numpy()[-1]
        time = table.attrs["time_of_flight_s"]
        point, apogee = _earth_fixed(end, launch, time), table.attrs["apogee_altitude_m"]
    else:
        try:
            improved = mks_improved.solve(launch, fitted)
        except ValueError:  # no re-entry solution (mks_improvement's broad judgement)
            return dict.fromkeys(MEASURES, math.nan)
        point, apogee, time = (
            improved.impact_point_m,
            improved.apogee_altitude_m,
            improved.impact_time_s,
        )
    return {
        "impact_m": float(np.linalg.norm(np.asarray(point) - impact)),
        "apogee_m": float(apogee - truth.attrs["apogee_altitude_m"]),
        "time_of_flight_s": float(time - truth.attrs["time_of_flight_s"]),
    }


@cached_copies
def judge(
    per_gun: int = 40, seed: int = _SEED, guns: tuple[Gun, ...] | None = None
) -> pd.DataFrame:
    """Every judged launch (``per_gun`` for each of ``guns``, :func:`judging_guns` by default),
    a row each: the gun, the launch and each model's errors (``<model>_<measure>``), and each
    gun's calibration cost when it was judged (``calibration_s``, 0 where it was loaded from
    disk; ``calibration_flights``). Computed once, kept in memory and on disk."""
    count = whole_number(per_gun, "per_gun", low=1, high=10_000)
    chosen = judging_guns(seed) if guns is None else tuple(guns)
    key = repr((tuple(gun.key for gun in chosen), count, seed))

    def compute() -> dict[str, np.ndarray]:
        frame = _judged(chosen, count, seed)
        return {column: np.asarray(frame[column].tolist()) for column in frame.columns}

    arrays, _ = stored_arrays(__name__, "judged", key, compute)
    return pd.DataFrame({column: array.copy() for column, array in arrays.items()})


def _judged(guns: tuple[Gun, ...], count: int, seed: int) -> pd.DataFrame:
    fitted = mks_improvement.calibration()
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        for index, gun in enumerate(guns):
            calibration = calibrated_mks.calibration_for(gun.launches(1.0, 45.0, 0.0, 0.0))
            for launch in judging_launches(gun, count, seed + 1 + index):
                truth = threedof.simulate_3dof(launch, output_step_s=1.0)
                row = {
                    "projectile": gun.projectile.name,
                    "latitude_deg": gun.latitude_deg,
                    "turning": bool(gun.rotation_rate_rad_s),
                    "speed_factor": launch.speed_m_s / gun.projectile.launch_speed_m_s,
                    "elevation_deg": launch.elevation_deg,
                    "bearing_deg": launch.bearing_deg,
                    "density_change": launch.density_change_fraction,
                    "calibration_s": calibration.seconds,
                    "calibration_flights": calibration.flights,
                }
                for model in MODELS:
                    for measure, value in _errors(launch, truth, model, fitted).items():
                        row[f"{model}_{measure}"] = value
                rows.append(row)
    return pd.DataFrame(rows)


@dataclass(frozen=True)
class Accuracy:
    """One model's errors over the judged launches against the ECI MKS's on the same ones."""

    model: str
    measure: str
    launches: int
    rms: float
    p95: float
    eci_rms: float
    eci_p95: float

    @property
    def rms_ratio(self) -> float:
        return self.rms / self.eci_rms

    @property
    def p95_ratio(self) -> float:
        return self.p95 / self.eci_p95


def accuracy(
    measure: str = "impact_m",
    model: str = "calibrated",
    per_gun: int = 40,
    seed: int = _SEED,
    guns: tuple[Gun, ...] | None = None,
) -> Accuracy:
    """RMS and 95th percentile of |error| of ``model`` for ``measure`` over :func:`judge`'s
    launches that both it and the ECI MKS solve, and the ECI MKS's on the same launches."""
    if measure not in MEASURES:
        raise ValueError(f"measure must be one of {MEASURES}; got {measure!r}")
    if model not in MODELS:
        raise ValueError(f"model must be one of {MODELS}; got {model!r}")
    judged = judge(per_gun, seed, guns)
    mine = judged[f"{model}_{measure}"].abs().to_numpy()
    theirs = judged[f"eci_{measure}"].abs().to_numpy()
    solved = np.isfinite(mine) & np.isfinite(theirs)
    mine, theirs = mine[solved], theirs[solved]
    return Accuracy(
        model,
        measure,
        int(solved.sum()),
        float(np.sqrt(np.mean(mine**2))),
        float(np.percentile(mine, 95)),
        float(np.sqrt(np.mean(theirs**2))),
        float(np.percentile(theirs, 95)),
    )
