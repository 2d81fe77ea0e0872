"""Chapter 7 B's error budget: the gun's and the air's uncertainty against the MKS's own error.

Chapter 7 B lists what a fire-control system does not know exactly: where the gun points, the
muzzle speed, the gun's latitude, the moment of fire, the air's density (and, with it, its
temperature) and the wind, and expects that "these uncertainties may end up being much larger
than the uncertainties contained in the simplification assumptions made to make the Modified
Kepler equation solvable". This module puts numbers to both sides for a launch:

- the *dispersion*: the 3DOF (the reference physics) flies the launch with its inputs drawn
  from :data:`CHAPTER_7B` (quasi-Monte Carlo, a scrambled Sobol' sequence mapped through the
  normal quantile), and the spread of the apogee, the impact point and the position at the
  nominal apogee time is measured about the nominal flight;
- the *model error*: the ECI MKS (:mod:`.eci`, the non-rotating MKS where the Earth does not
  turn) of the nominal launch against the 3DOF's nominal flight, for the same three outputs.

Positions are Earth-fixed (the 3DOF's inertial axes at the moment of fire), so a wrong latitude
counts with the gun's own displacement, and a shot fired late by dt is where the punctual one
was dt earlier. Variance-based sensitivity indices (Sobol', via SALib) say which input drives
each output. Every sample runs through :func:`harp_analysis.foundation.sweeps.sweep`, in chunks;
given a Dask client the chunks run on its cluster with identical results.

The sizes of the uncertainties are the text's where it gives one (pointing "down to the
milli-radian"), the data's where the HARP records show a resolution (muzzle speed in steps of
10 ft/s, the site's latitude to the arc second), and otherwise a stated assumption (fire timing,
the day's density and temperature, the wind): each :class:`Uncertainty` carries its basis, and
the one-at-a-time table scales linearly with each size, so a reader can rescale any of them.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace
from functools import partial

import numpy as np
import pandas as pd
from scipy.stats import norm

from ..engines import eci
from ..engines.threedof import fly_3dof
from ..foundation import earth
from ..foundation.caching import cached_copies
from ..foundation.sweeps import SAMPLING_METHODS, chunks, sample_chunk, sweep
from ..foundation.validation import Bounds, check_choice, real_number, whole_number
from ..models.launch import Launch, Launches, baseline_chapter_4, chapter_2
from ..models.projectiles import HP
from ..models.trajectory import launch_frame, rotate_about_axis
from .harp import apogees
from .harp import confidence as harp_confidence
from .harp.appendices import FOOT_M

__all__ = [
    "Uncertainty",
    "CHAPTER_7B",
    "OUTPUTS",
    "representative_launches",
    "martlet_at_barbados",
    "nominal",
    "model_error",
    "flown",
    "Moments",
    "dispersion",
    "MAX_SAMPLES",
    "MIN_SAMPLES",
    "MAX_CHUNK",
    "MAX_BASE_SAMPLES",
    "MIN_BASE_SAMPLES",
    "one_at_a_time",
    "sensitivity_indices",
    "budget_table",
    "COMPARABLE_FACTOR",
    "required_pointing_mrad",
    "representative_budget",
    "median_required_pointing_mrad",
    "dispersion_over_model_error",
    "harp_spread_over_model_error",
    "SpreadOverModelError",
    "harp_spread_interval_over_model_error",
]

_MRAD_DEG = math.degrees(1e-3)
_POINTING = 'Ch. 7 B: pointing "possible down to the milli-radian"'


@dataclass(frozen=True)
class Uncertainty:
    """One input's 1-sigma uncertainty (normal, centred on the nominal launch): ``field`` is the
    :class:`~harp_analysis.models.launch.Launch` field it moves, or ``"fire_time_s"``; ``sd`` is in
    that field's unit; ``basis`` says where the number comes from."""

    name: str
    field: str
    sd: float
    basis: str


#: Chapter 7 B's list, with the sizes this project takes for them (``basis`` says why).
CHAPTER_7B = (
    Uncertainty("elevation", "elevation_deg", _MRAD_DEG, _POINTING),
    Uncertainty("bearing", "bearing_deg", _MRAD_DEG, _POINTING),
    Uncertainty(
        "muzzle speed",
        "speed_m_s",
        apogees.SPEED_STEP_FT_S * FOOT_M,
        "assumed: one step of the HARP muzzle-speed records, 10 ft/s, as a gun's round-to-round "
        "scatter (the records' own rounding is 10/sqrt(12) ft/s; HARP's scatter, Ch. 6, "
        "implies more)",
    ),
    Uncertainty(
        "latitude",
        "latitude_deg",
        1.0 / 3600.0,
        "the resolution of the text's site coordinates, 1 arc second (Ch. 6 C), as 1 sd",
    ),
    Uncertainty("fire time", "fire_time_s", 1e-3, "assumed: 1 ms (the text gives none)"),
    Uncertainty(
        "air density",
        "density_change_fraction",
        0.02,
        "assumed: 2 % day to day at every height (the text gives none)",
    ),
    Uncertainty(
        "air temperature",
        "temperature_change_k",
        5.0,
        "assumed: 5 K at every height (the text gives none)",
    ),
    Uncertainty("cross wind", "cross_wind_m_s", 5.0, "Ch. 2 A's 5 m/s cross wind as the scale"),
    Uncertainty("head wind", "head_wind_m_s", 5.0, "Ch. 2 A's 5 m/s cross wind as the scale"),
)

#: The scalar outputs of a flight that the sensitivity indices explain (m): the apogee altitude,
#: the impact point's displacement along and across the nominal line of fire, and the position
#: at the nominal apogee time displaced along the nominal flight path (its largest component).
OUTPUTS = ("apogee", "impact_downrange", "impact_crossrange", "position_along_track")


def martlet_at_barbados() -> Launch:
    """A Martlet 2C (Mod 2) round fired from the Barbados gun as Chapter 6 models it: 85 deg on
    109T from 13 deg 4' 38'' N on a turning Earth, the distinct rounds' median mass and muzzle
    speed, and the drag of :func:`~harp_analysis.analyses.harp.apogees.martlet` (a constant Cd0 A,
    as the MKS assumes)."""
    rounds = apogees.appendix_rounds("barbados")
    rounds = rounds[~rounds.duplicate_of_earlier_row]
    speed = float(rounds.muzzle_speed_m_s.median())
    martlet = apogees.martlet(float(rounds.mass_kg.median()), speed)
    return apogees.gun_launch("barbados", martlet, speed)


def representative_launches() -> dict[str, Launch]:
    """The issue's representative launches, all on the turning Earth: HP at 50 deg (Chapter 2
    A's launch without its wind, which is an uncertainty here) and the baseline cone at
    Chapter 5's elevations, both fired east from the equator, and the Martlet at Barbados.

    Returns
    -------
    dict of str to Launch
        The launches by name ("HP, 50 deg", "baseline, 45 deg", "Martlet, Barbados", ...).
    """
    east = dict(rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S, bearing_deg=90.0)
    launches = {"HP, 50 deg": chapter_2(HP, cross_wind_m_s=0.0, spin_rad_s=0.0, **east)}
    for elevation in (30.0, 45.0, 65.0, 85.0):
        launches[f"baseline, {elevation:g} deg"] = baseline_chapter_4(elevation, **east)
    launches["Martlet, Barbados"] = martlet_at_barbados()
    return launches


# --- the 3DOF's flights -----------------------------------------------------------------------
def _perturbed(
    launch: Launch, uncertainties, deviations: np.ndarray
) -> tuple[Launches, np.ndarray]:
    """The launches of ``deviations`` (m, d) in units of each uncertainty's sd, and their
    delays of fire (s)."""
    delays = np.zeros(len(deviations))
    fields: dict[str, np.ndarray] = {}
    for u, z in zip(uncertainties, deviations.T):
        if u.field == "fire_time_s":
            delays = delays + z * u.sd
        else:
            fields[u.field] = fields.get(u.field, getattr(launch, u.field)) + z * u.sd
    if "bearing_deg" in fields:
        fields["bearing_deg"] %= 360.0
    copies = Launches.from_launches(launch)[np.zeros(len(deviations), int)]  # one per row
    return copies.but(**fields), delays


def flown(launch: Launch, uncertainties, deviations, at_time_s: float) -> np.ndarray:
    """The 3DOF's outputs for ``launch`` moved by ``deviations`` (m, d) sds of
    ``uncertainties``: rows of the apogee altitude, the Earth-fixed impact point (3) and the
    Earth-fixed position at ``at_time_s`` after the nominal moment of fire (3), in metres."""
    deviations = np.atleast_2d(np.asarray(deviations, dtype=float))
    launches, delays = _perturbed(launch, uncertainties, deviations)
    whole = fly_3dof(launches)
    if not whole.impact.all():
        raise ValueError("a flight of the sample did not come down within the 3DOF's time limit")
    at_time = fly_3dof(launches, max_time_s=at_time_s)
    # fired dt late, it is at t where the punctual round was at t - dt (the Earth-fixed flight
    # is the same): to first order in dt, v dt behind
    position = at_time.end_position_m - at_time.end_velocity_m_s * delays
    return np.column_stack([whole.apogee_altitude_m, whole.end_position_m.T, position.T])


@cached_copies
def nominal(launch: Launch) -> tuple[np.ndarray, float, np.ndarray]:
    """The nominal 3DOF flight's outputs (:func:`flown`), its apogee time, and the unit vectors
    along and across the line of fire at the impact point and along the flight at the apogee
    time (rows: downrange, crossrange, along-track)."""
    apogee_time = float(fly_3dof(_check_launch(launch)).apogee_time_s[0])
    outputs = flown(launch, (), np.zeros((1, 0)), apogee_time)[0]
    impact = outputs[1:4]
    up = impact / np.linalg.norm(impact)
    gun = _gun_position(launch)
    downrange = impact - gun - ((impact - gun) @ up) * up
    downrange /= np.linalg.norm(downrange)
    at_time = fly_3dof(launch, max_time_s=apogee_time)
    along = at_time.end_velocity_m_s[:, 0] / np.linalg.norm(at_time.end_velocity_m_s[:, 0])
    axes = np.array([downrange, np.cross(downrange, up), along])
    return outputs, apogee_time, axes


def _gun_position(launch: Launch) -> np.ndarray:
    up = launch_frame(launch.latitude_rad, math.radians(launch.longitude_deg), 0.0)[0]
    return (earth.RADIUS_M + launch.site_altitude_m) * np.ravel(up)


def _scalar_outputs(launch: Launch, outputs: np.ndarray) -> np.ndarray:
    """:data:`OUTPUTS` of :func:`flown`'s rows, about the nominal flight (m)."""
    reference, _, axes = nominal(launch)
    deviation = outputs - reference
    return np.column_stack(
        [
            deviation[:, 0],
            deviation[:, 1:4] @ axes[0],
            deviation[:, 1:4] @ axes[1],
            deviation[:, 4:7] @ axes[2],
        ]
    )


# --- the model error --------------------------------------------------------------------------
@cached_copies
def model_error(launch: Launch) -> pd.Series:
    """The ECI MKS's error (m) for ``launch`` against the 3DOF: its apogee altitude, its impact
    point (distance between the two impact points on the ground) and its position at the
    3DOF's apogee time (the distance between the two positions at the same time, Chapter 5 C's
    measure), each from the nominal flight of :func:`nominal`.

    Parameters
    ----------
    launch : Launch
        The nominal launch, on the rotating Earth or not.

    Returns
    -------
    pandas.Series
        ``apogee_m``, ``impact_m`` and ``position_m``: the three errors (m).
    """
    reference, apogee_time, _ = nominal(_check_launch(launch))
    flight = eci.simulate_eci_mks(launch, times_s=[apogee_time], warn=False)
    # the rows at the 3DOF's apogee time and at the impact, turned into the Earth's axes
    moments = flight.time_s.to_numpy()
    inertial = flight[["x_m", "y_m", "z_m"]].to_numpy().T
    fixed = rotate_about_axis(inertial, -launch.rotation_rate_rad_s * moments).T
    return pd.Series(
        {
            "apogee_m": abs(flight.attrs["apogee_altitude_m"] - reference[0]),
            "impact_m": float(np.linalg.norm(fixed[-1] - reference[1:4])),
            "position_m": float(np.linalg.norm(fixed[0] - reference[4:7])),
        }
    )


# --- sampling ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class Moments:
    """Count, mean and sum of squared deviations (Chan et al.'s pairwise update) of the rows
    folded in: what a sweep keeps of a million samples."""

    count: int
    mean: np.ndarray
    squares: np.ndarray  # (k, k): sum of outer products of deviations from the mean

    @classmethod
    def of(cls, rows: np.ndarray) -> Moments:
        mean = rows.mean(axis=0)
        deviations = rows - mean
        return cls(len(rows), mean, deviations.T @ deviations)

    def add(self, other: Moments) -> Moments:
        if self.count == 0:
            return other
        count = self.count + other.count
        delta = other.mean - self.mean
        return Moments(
            count,
            self.mean + delta * other.count / count,
            self.squares
            + other.squares
            + np.outer(delta, delta) * self.count * other.count / count,
        )

    @property
    def covariance(self) -> np.ndarray:
        return self.squares / (self.count - 1)


def _fold(state: Moments | None, rows: Moments) -> Moments:
    return rows if state is None else state.add(rows)


def _deviations(unit: np.ndarray) -> np.ndarray:
    """Standard normal deviations of points of the unit cube (the quantile; a scrambled
    sequence never lands on 0 or 1 exactly, the clip guards the floating point)."""
    return norm.ppf(np.clip(unit, 1e-15, 1.0 - 1e-15))


def _chunk_moments(launch, uncertainties, at_time_s, seed, method, indices) -> Moments:
    unit = sample_chunk(seed, len(uncertainties), indices, method)
    outputs = flown(launch, uncertainties, _deviations(unit), at_time_s)
    reference = nominal(launch)[0]
    return Moments.of(np.column_stack([outputs - reference, _scalar_outputs(launch, outputs)]))


#: Flights a dispersion draws at most and at least: above, the sample would take hours and
#: its chunks' index gigabytes; below, the spread's own relative error, 1/sqrt(2 (n - 1)),
#: exceeds 18 % (and one sample has no spread at all).
MAX_SAMPLES = 2**20
MIN_SAMPLES = 16
#: Flights the 3DOF flies at once in one chunk at most (its arrays scale with it).
MAX_CHUNK = 2**14
#: Saltelli base samples at most (each costs d + 2 flights) and at least (SALib's estimators
#: and their bootstrap half-widths are meaningless below).
MAX_BASE_SAMPLES = 2**16
MIN_BASE_SAMPLES = 8


def _check_launch(launch) -> Launch:
    if not isinstance(launch, Launch):
        raise TypeError(f"launch must be a Launch; got {type(launch).__name__}")
    return launch


def _check_uncertainties(uncertainties) -> tuple[Uncertainty, ...]:
    if isinstance(uncertainties, Uncertainty | str | bytes) or not isinstance(
        uncertainties, Iterable
    ):
        raise TypeError(
            f"uncertainties must be a sequence of Uncertainty; got {type(uncertainties).__name__}"
        )
    uncertainties = tuple(uncertainties)
    for position, u in enumerate(uncertainties):
        if not isinstance(u, Uncertainty):
            raise TypeError(f"uncertainties[{position}] must be an Uncertainty; got {u!r:.60}")
        name = f"uncertainties[{position}].sd"
        Bounds(low=0.0).check(real_number(u.sd, name), name)
    return uncertainties


def dispersion(
    launch: Launch,
    uncertainties=CHAPTER_7B,
    *,
    samples: int = 1024,
    seed: int = 0,
    method: str = "sobol",
    chunk: int = 64,
    client=None,
    progress: bool = True,
) -> pd.Series:
    """The 3DOF's spread (m) for ``launch`` under ``uncertainties``, from ``samples`` flights
    (in chunks of ``chunk``, through :func:`~harp_analysis.foundation.sweeps.sweep`, on ``client``'s
    cluster if given): the root-mean-square distance of the apogee altitude, the impact point
    and the position at the nominal apogee time from the nominal flight's, and the standard
    deviation of each of :data:`OUTPUTS` (``sd_<output>_m``). ``samples`` lies within
    [:data:`MIN_SAMPLES`, :data:`MAX_SAMPLES`], ``chunk`` within [1, :data:`MAX_CHUNK`].

    Parameters
    ----------
    launch : Launch
        The nominal launch.
    uncertainties : sequence of Uncertainty
        The inputs drawn and their standard deviations (Chapter 7 B's list by default).
    samples : int
        Flights of the sample.
    seed : int
        The sample's seed: the same seed, the same result, on a cluster or not.
    method : str
        ``"sobol"`` (scrambled Sobol' quasi-Monte Carlo) or ``"random"``.
    chunk : int
        Flights per chunk of the sweep.
    client : dask.distributed.Client, optional
        Runs the chunks on its cluster; None in this process.
    progress : bool
        Show a progress bar.

    Returns
    -------
    pandas.Series
        ``apogee_m``, ``impact_m`` and ``position_m`` (the root-mean-square distances, m) and
        ``sd_<output>_m`` for each of :data:`OUTPUTS`; its name is the number of flights.
    """
    launch = _check_launch(launch)
    uncertainties = _check_uncertainties(uncertainties)
    samples = whole_number(samples, "samples", low=MIN_SAMPLES, high=MAX_SAMPLES)
    chunk = whole_number(chunk, "chunk", low=1, high=MAX_CHUNK)
    check_choice(method, "method", SAMPLING_METHODS)
    if not uncertainties:
        raise ValueError("uncertainties must name at least one input (an sd of 0 is allowed)")
    _, apogee_time, _ = nominal(launch)
    moments = sweep(
        partial(_chunk_moments, launch, uncertainties, apogee_time, seed, method),
        chunks(samples, chunk),
        client=client,
        progress=progress,
        description="error budget",
        reduce=_fold,
        max_items=MAX_SAMPLES,
    )
    variance = np.diag(moments.covariance)
    offset = moments.mean[:7]  # of the flights from the nominal one

    def rms(columns):
        return math.sqrt(variance[columns].sum() + offset[columns] @ offset[columns])

    result = {
        "apogee_m": rms(slice(0, 1)),
        "impact_m": rms(slice(1, 4)),
        "position_m": rms(slice(4, 7)),
    }
    for name, value in zip(OUTPUTS, variance[7:]):
        result[f"sd_{name}_m"] = math.sqrt(value)
    return pd.Series(result, name=moments.count)


def one_at_a_time(launch: Launch, uncertainties=CHAPTER_7B) -> pd.DataFrame:
    """Each input's own 1-sigma effect on :data:`OUTPUTS` (m, signed) and on the miss of the
    impact point and of the position at the nominal apogee time (m): central differences of
    +-1 sd, the others held nominal. Linear in each sd (checked by the tests): a reader may
    rescale a row by another size of its uncertainty."""
    return _one_at_a_time(_check_launch(launch), _check_uncertainties(uncertainties))


@cached_copies
def _one_at_a_time(launch: Launch, uncertainties: tuple[Uncertainty, ...]) -> pd.DataFrame:
    _, apogee_time, _ = nominal(launch)
    d = len(uncertainties)
    deviations = np.vstack([np.eye(d), -np.eye(d)])
    outputs = flown(launch, uncertainties, deviations, apogee_time)
    scalar = _scalar_outputs(launch, outputs)
    half = (scalar[:d] - scalar[d:]) / 2
    impact = np.linalg.norm((outputs[:d, 1:4] - outputs[d:, 1:4]) / 2, axis=1)
    position = np.linalg.norm((outputs[:d, 4:7] - outputs[d:, 4:7]) / 2, axis=1)
    table = pd.DataFrame(half, columns=[f"{name}_m" for name in OUTPUTS])
    table["impact_m"], table["position_m"] = impact, position
    table.index = pd.Index([u.name for u in uncertainties], name="input")
    return table


def sensitivity_indices(
    launch: Launch,
    uncertainties=CHAPTER_7B,
    *,
    base_samples: int = 128,
    seed: int = 0,
    client=None,
    progress: bool = True,
) -> pd.DataFrame:
    """First-order and total Sobol' indices of each input for each of :data:`OUTPUTS`
    (SALib's Saltelli design, ``base_samples`` x (d + 2) flights, and its estimators with
    their 95 % bootstrap half-widths): rows are inputs, columns ``<output>_S1``, ``_ST``,
    ``_S1_conf``, ``_ST_conf``. ``base_samples`` lies within [:data:`MIN_BASE_SAMPLES`,
    :data:`MAX_BASE_SAMPLES`].

    Parameters
    ----------
    launch : Launch
        The nominal launch.
    uncertainties : sequence of Uncertainty
        The inputs and their standard deviations (Chapter 7 B's list by default).
    base_samples : int
        The Saltelli design's base sample N: N x (d + 2) flights for d inputs.
    seed : int
        The design's and the bootstrap's seed.
    client : dask.distributed.Client, optional
        Flies the design on its cluster; None in this process.
    progress : bool
        Show a progress bar.

    Returns
    -------
    pandas.DataFrame
        One row per input; columns ``<output>_S1``, ``<output>_ST``, ``<output>_S1_conf`` and
        ``<output>_ST_conf`` for each of :data:`OUTPUTS`.
    """
    from SALib.analyze import sobol as analyze
    from SALib.sample import sobol as sample

    launch = _check_launch(launch)
    uncertainties = _check_uncertainties(uncertainties)
    base_samples = whole_number(
        base_samples, "base_samples", low=MIN_BASE_SAMPLES, high=MAX_BASE_SAMPLES
    )
    names = [u.name for u in uncertainties]
    problem = {"num_vars": len(names), "names": names, "bounds": [[0.0, 1.0]] * len(names)}
    unit = sample.sample(problem, base_samples, calc_second_order=False, seed=seed)
    _, apogee_time, _ = nominal(launch)
    pieces = sweep(
        partial(_chunk_outputs, launch, uncertainties, apogee_time),
        np.array_split(unit, max(1, len(unit) // 64)),
        client=client,
        progress=progress,
        description="sensitivity",
    )
    scalar = np.vstack(pieces)
    columns = {}
    for k, output in enumerate(OUTPUTS):
        indices = analyze.analyze(
            problem, scalar[:, k], calc_second_order=False, seed=seed, print_to_console=False
        )
        for key in ("S1", "ST", "S1_conf", "ST_conf"):
            columns[f"{output}_{key}"] = indices[key]
    return pd.DataFrame(columns, index=pd.Index(names, name="input"))


def _chunk_outputs(launch, uncertainties, at_time_s, unit) -> np.ndarray:
    return _scalar_outputs(launch, flown(launch, uncertainties, _deviations(unit), at_time_s))


# --- the budget -------------------------------------------------------------------------------
def budget_table(
    launches: dict[str, Launch] | None = None,
    uncertainties=CHAPTER_7B,
    *,
    samples: int = 512,
    seed: int = 0,
    client=None,
    progress: bool = True,
) -> pd.DataFrame:
    """Per launch (rows) and output (apogee, impact point, position at the apogee time): the
    3DOF's dispersion under ``uncertainties`` (:func:`dispersion`), the MKS's model error
    (:func:`model_error`), their ratio, and which dominates (or "comparable", within
    :data:`COMPARABLE_FACTOR`)."""
    launches = representative_launches() if launches is None else launches
    if not isinstance(launches, Mapping):
        raise TypeError(f"launches must map names to Launch; got {type(launches).__name__}")
    rows = []
    for name, launch in launches.items():
        spread = dispersion(
            launch, uncertainties, samples=samples, seed=seed, client=client, progress=progress
        )
        error = model_error(launch)
        for output in ("apogee", "impact", "position"):
            ratio = spread[f"{output}_m"] / error[f"{output}_m"]
            rows.append(
                {
                    "launch": name,
                    "output": output,
                    "dispersion_m": spread[f"{output}_m"],
                    "mks_error_m": error[f"{output}_m"],
                    "ratio": ratio,
                    "dominates": _dominant(ratio),
                }
            )
    return pd.DataFrame(rows).set_index(["launch", "output"])


#: Within this factor of each other the two sides are "comparable": the sizes assumed for the
#: day's air and the fire timing (:data:`CHAPTER_7B`) are not known better than that.
COMPARABLE_FACTOR = 2.0


def _dominant(ratio: float) -> str:
    if ratio >= COMPARABLE_FACTOR:
        return "gun and air"
    return "MKS" if ratio <= 1 / COMPARABLE_FACTOR else "comparable"


def required_pointing_mrad(launch_name: str = "baseline, 45 deg", output: str = "impact") -> float:
    """The pointing uncertainty (mrad, 1 sd in elevation and bearing alike) whose miss equals
    the MKS's model error for the representative launch ``launch_name``: the accuracy below
    which pointing stops mattering next to the MKS's simplifications (Ch. 7 B)."""
    launches = representative_launches()
    check_choice(launch_name, "launch_name", tuple(launches))
    check_choice(output, "output", ("impact", "position"))
    launch = launches[launch_name]
    pointing = tuple(u for u in CHAPTER_7B if u.field in ("elevation_deg", "bearing_deg"))
    per_mrad = one_at_a_time(launch, tuple(replace(u, sd=_MRAD_DEG) for u in pointing))
    miss_per_mrad = math.sqrt((per_mrad[f"{output}_m"] ** 2).sum())
    return float(model_error(launch)[f"{output}_m"] / miss_per_mrad)


def median_required_pointing_mrad(output: str = "position") -> float:
    """:func:`required_pointing_mrad` for ``output``, the median over the representative
    launches."""
    names = representative_launches()
    return float(np.median([required_pointing_mrad(name, output) for name in names]))


@cached_copies
def representative_budget(samples: int = 4096, seed: int = 0) -> pd.DataFrame:
    """:func:`budget_table` of the representative launches (computed once per process)."""
    return budget_table(samples=samples, seed=seed, progress=False)


def dispersion_over_model_error(output: str = "impact") -> float:
    """The median over the representative launches of the 3DOF's dispersion under
    :data:`CHAPTER_7B` over the MKS's model error, for ``output`` ("apogee", "impact" or
    "position"): above 1, the gun and the air outweigh the MKS's simplifications (Ch. 7 B)."""
    check_choice(output, "output", ("apogee", "impact", "position"))
    ratios = representative_budget().xs(output, level="output").ratio
    return float(ratios.median())


def harp_spread_over_model_error(site: str = "barbados") -> float:
    """The standard deviation of ``site``'s HARP apogee residuals (the dissertation model, the
    distinct rounds) over the ECI MKS's apogee error against the 3DOF for the representative
    Martlet round at Barbados (:func:`martlet_at_barbados`): how much larger the experimental
    spread is than the MKS's own error (Ch. 4 A)."""
    spread_m = 1e3 * apogees.residual_statistic(site, "std", include_duplicate=False)
    return float(spread_m / model_error(martlet_at_barbados())["apogee_m"])


@dataclass(frozen=True)
class SpreadOverModelError:
    """A site's residual spread over the MKS's apogee error, the spread with its interval
    (:func:`harp_spread_interval_over_model_error`)."""

    site: str
    spread_m: harp_confidence.Interval  # the residuals' sd and its interval (std_interval)
    model_error_m: float  # the ECI MKS's apogee error for the representative Martlet
    coverage: harp_confidence.Coverage  # the interval's, simulated on the residuals' shape
    coverage_normal: harp_confidence.Coverage  # and on normal data

    @property
    def ratio(self) -> harp_confidence.Interval:
        """The spread over the model error, and its interval's ends over it."""
        return harp_confidence.Interval(*(s / self.model_error_m for s in self.spread_m))


def harp_spread_interval_over_model_error(
    site: str = "barbados", confidence: float = 0.95
) -> SpreadOverModelError:
    """:func:`harp_spread_over_model_error` with the spread's sampling uncertainty: the
    residuals' standard deviation with its ``confidence`` interval
    (:func:`~harp_analysis.analyses.harp.confidence.std_interval`, 22 rounds) over the same model
    error, and how often such an interval holds the truth at a site's rounds
    (:func:`~harp_analysis.analyses.harp.confidence.coverage`)."""
    spread = harp_confidence.residual_intervals(site, confidence=confidence).loc["std"]
    return SpreadOverModelError(
        site,
        harp_confidence.Interval(*(float(spread[f"{x}_m"]) for x in ("estimate", "low", "high"))),
        float(model_error(martlet_at_barbados())["apogee_m"]),
        harp_confidence.coverage("std", "bonett", "residuals", confidence=confidence),
        harp_confidence.coverage("std", "bonett", "normal", confidence=confidence),
    )
