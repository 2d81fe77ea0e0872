"""HARP with confidence (issue 17): how sure the apogee residuals of :mod:`.apogees` are, how much
of their scatter the known input uncertainties explain, the Martlet's Cd0 A fitted to both sites
with its uncertainty, and whether the Barbados drag transfers to Yuma once each site's air
follows its temperature.

Conventions of :mod:`.apogees`: the distinct rounds (Barbados 22 of Appendix D's 23 printed rows,
Yuma 22), residual = measured - predicted apogee, the ECI MKS of the ``"dissertation"`` model
by default. SI inside (m, kg, m/s, m^2).

Intervals of the residuals' mean and standard deviation are closed forms whose coverage at
the sites' 22 rounds is simulated (:func:`coverage`, :func:`coverage_table`): the mean's is
Student's t interval (exact for normal data), the standard deviation's Bonett's (2006,
Comput. Stat. Data Anal. 50, 775-782: the log of the variance with a kurtosis-based standard
error and the small-sample factor n / (n - z)), which needs no normality. The BCa bootstrap
interval of the standard deviation covers well below its nominal 95 % at n = 22 (the
statistic's skewed, kurtosis-driven sampling distribution is what BCa corrects only to second
order), which is why it is no longer used there. The fits and transfers (sections 3 and 4) keep
bootstrap intervals (:func:`scipy.stats.bootstrap`, BCa), deterministic given ``seed``: their
statistics have no closed form; at n = 22 a BCa interval of a mean covers a little below
nominal, as :func:`coverage_table` shows.

Surface density. :mod:`.apogees` flies each site at ``sites.LaunchSite.surface_density_kg_m3``:
Barbados at the 1976 standard's 1.225 kg/m^3 (Ch. 6 C), Yuma at the text's 1.14 kg/m^3
(Ch. 6 D, an evening average of the NCDC record, not given). No per-round density (or
temperature, pressure, humidity) exists anywhere in the dissertation. Each appendix's Mach
column gives one speed of sound per site
(:func:`~harp_analysis.analyses.harp.apogees.speed_of_sound`), hence one air temperature
(:func:`~harp_analysis.analyses.harp.apogees.air_temperature_k`): Yuma about 10 K colder.
``densities="site"`` keeps the text's two values; ``densities="temperature"`` keeps the anchor
site's value and gives the other site the density of the same surface pressure at its own
temperature (rho ~ 1/T). rho0 and Cd0 A enter the ECI MKS only as their product (eqs 5.8, 6.11), so
a fitted Cd0 A absorbs the anchor's value and a transfer depends only on the ratio of the two
densities.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
import pandas as pd
from scipy import stats
from scipy.stats import bootstrap

from ...engines import eci
from ...foundation.caching import cached_copies
from ...foundation.validation import (
    Bounds,
    check_choice,
    probability,
    real_array,
    real_number,
    whole_number,
)
from ...models.sites import LaunchSite, get_site
from . import apogees
from .appendices import FOOT_M

__all__ = [
    "RESAMPLES",
    "MAX_RESAMPLES",
    "SPEED_RECORD_STEP_M_S",
    "MASS_RECORD_STEP_KG",
    "Interval",
    "uniform_quantisation_std",
    "bootstrap_interval",
    "INTERVAL_METHODS",
    "COVERAGE_DISTRIBUTIONS",
    "mean_interval",
    "std_interval",
    "Coverage",
    "coverage",
    "coverage_table",
    "site_rounds",
    "residual_intervals",
    "residual_interval_table",
    "apogee_sensitivities",
    "ScatterBudget",
    "scatter_budget",
    "scatter_budget_table",
    "surface_densities_kg_m3",
    "DragAreaFit",
    "fit_drag_area",
    "drag_area_interval",
    "drag_area_fit_table",
    "Transfer",
    "transfer",
    "transfer_table",
    "apogee_density_ratio",
]

SITES = ("barbados", "yuma")
#: Bootstrap resamples by default (scipy's default).
RESAMPLES = 9999
#: Bootstrap resamples at most: scipy holds them all at once (22 rounds x 8 bytes each).
MAX_RESAMPLES = 10**5
#: The muzzle-speed records' step: the recovered speeds are whole multiples of it (harp).
SPEED_RECORD_STEP_M_S = apogees.SPEED_STEP_FT_S * FOOT_M
#: The appendices' masses are whole half pounds of 0.4536 kg (data/harp/README.md).
MASS_RECORD_STEP_KG = 0.5 * 0.4536
_FIT_STEP = 1e-4  # relative step of d apogee / d Cd0 A (the apogees carry ~1e-7 m of rounding)
# The fit ends when Cd0 A moves by less than this share of the change that would shift the
# residuals by their own rms, i.e. far below its statistical uncertainty.
_FIT_TOLERANCE = 1e-6
_FIT_ITERATIONS = 30


class Interval(NamedTuple):
    """An estimate and its confidence interval (low, high), in the quantity's unit."""

    estimate: float
    low: float
    high: float

    @property
    def contains_zero(self) -> bool:
        """Whether 0 lies in [low, high]."""
        return self.low <= 0.0 <= self.high


def uniform_quantisation_std(step: float) -> float:
    """Standard deviation of a value known only to the nearest multiple of ``step``: uniform
    over +- step / 2, sd = step / sqrt(12)."""
    return Bounds(low=0.0).check(real_number(step, "step"), "step") / math.sqrt(12.0)


def _check_bootstrap(confidence, resamples, seed):
    confidence = probability(confidence, "confidence")
    for value, name, low in ((resamples, "resamples", 1), (seed, "seed", 0)):
        if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < low:
            raise ValueError(f"{name} must be a whole number >= {low}; got {value!r}")
    fewest = math.ceil(2.0 / (1.0 - confidence))  # a resample in each tail
    if not fewest <= resamples <= MAX_RESAMPLES:
        raise ValueError(
            f"resamples must lie in [{fewest}, {MAX_RESAMPLES}] for a {confidence:g} interval "
            f"(each tail holds a resample; above, the resamples take gigabytes); got {resamples}"
        )


def _bootstrap(samples, statistic, confidence, resamples, seed) -> Interval:
    """BCa interval of ``statistic(*samples, axis=-1)``, each sample resampled on its own."""
    _check_bootstrap(confidence, resamples, seed)
    result = bootstrap(
        samples,
        statistic,
        confidence_level=confidence,
        n_resamples=resamples,
        method="BCa",
        vectorized=True,
        axis=-1,
        rng=np.random.default_rng(seed),
    )
    estimate = float(statistic(*samples, axis=-1))
    return Interval(
        estimate, float(result.confidence_interval.low), float(result.confidence_interval.high)
    )


# --- the distinct rounds and their predictions ---------------------------------------------------
@cached_copies
def _rounds(site: str | LaunchSite) -> pd.DataFrame:
    table = apogees.appendix_rounds(site)
    return table[~table.duplicate_of_earlier_row].reset_index(drop=True)


def _apogees_m(
    site, drag_area_m2, model, surface_density_kg_m3=None, speed_m_s=None, mass_kg=None
) -> np.ndarray:
    """Predicted apogees (m) of ``site``'s distinct rounds by the ECI MKS of :mod:`.apogees`,
    with any input replaced (arrays broadcast against the rounds: a (k, 1) ``drag_area_m2``
    gives k rows)."""
    site = get_site(site)
    rounds = _rounds(site)
    arrays = np.broadcast_arrays(
        rounds.muzzle_speed_m_s.to_numpy() if speed_m_s is None else speed_m_s,
        rounds.mass_kg.to_numpy() if mass_kg is None else mass_kg,
        drag_area_m2,
        site.surface_density_kg_m3 if surface_density_kg_m3 is None else surface_density_kg_m3,
    )
    speed, mass, area, density = (np.ravel(array) for array in arrays)
    rounds = apogees.round_corrections(
        site, speed, mass, area, model, surface_density_kg_m3=density
    )
    apogee = rounds.solution(warn=False).apogee_altitude("eq_6_4")
    return np.reshape(apogee, arrays[0].shape)


def _residuals_m(site: str | LaunchSite, model: str) -> np.ndarray:
    frame = apogees.predicted_apogees(site, model)
    return frame.residual_m[~frame.duplicate_of_earlier_row].to_numpy()


# --- 1. intervals of the residual mean and standard deviation ------------------------------------
_STATISTICS = {
    "mean": lambda sample, axis=-1: np.mean(sample, axis=axis),
    "std": lambda sample, axis=-1: np.std(sample, ddof=1, axis=axis),
}


def bootstrap_interval(
    sample,
    statistic: str = "mean",
    *,
    confidence: float = 0.95,
    resamples: int = RESAMPLES,
    seed: int = 0,
) -> Interval:
    """BCa bootstrap interval of the ``"mean"`` or sample standard deviation (``"std"``,
    ddof = 1) of a 1-D ``sample``, in its unit."""
    check_choice(statistic, "statistic", _STATISTICS)
    values = real_array(sample, "sample")
    if values.ndim != 1 or values.size < 3:
        raise ValueError(f"sample must be 1-D with at least 3 values; got shape {values.shape}")
    return _bootstrap((values,), _STATISTICS[statistic], confidence, resamples, seed)


def residual_intervals(
    site: str, model: str = "dissertation", confidence: float = 0.95
) -> pd.DataFrame:
    """Mean and sample standard deviation (rows) of ``site``'s distinct-round apogee residuals
    under ``model``, with their intervals (:func:`mean_interval`, :func:`std_interval`):
    columns ``estimate_m``, ``low_m``, ``high_m``."""
    residuals = _residuals_m(site, model)
    rows = {
        "mean": mean_interval(residuals, confidence),
        "std": std_interval(residuals, confidence),
    }
    return pd.DataFrame(rows, index=["estimate_m", "low_m", "high_m"]).T


def residual_interval_table(model: str = "dissertation", confidence: float = 0.95) -> pd.DataFrame:
    """:func:`residual_intervals` of both sites, indexed by (site, statistic)."""
    return pd.concat(
        {site: residual_intervals(site, model, confidence) for site in SITES},
        names=["site", "statistic"],
    )


# --- 1b. the intervals' coverage at the sites' sample size ---------------------------------------
#: The intervals each statistic can be given; the first is the one :func:`residual_intervals`
#: uses ("bca": :func:`bootstrap_interval`; "chi2": normal theory's, exact for normal data only).
INTERVAL_METHODS = {"mean": ("t", "bca"), "std": ("bonett", "chi2", "bca")}
#: What :func:`coverage` draws from, each with a known mean and standard deviation: normal;
#: uniform (light-tailed: the residuals' kurtosis is 1.7 at Barbados and 2.0 at Yuma, the
#: uniform's 1.8, the normal's 3); gamma of shape 4 (skewness 1, a skewed case); and the
#: residuals themselves, each site's distinct rounds centred and scaled to unit variance and
#: pooled (44 values drawn with replacement: the residuals' own shape).
COVERAGE_DISTRIBUTIONS = ("normal", "uniform", "gamma", "residuals")
_GAMMA_SHAPE = 4.0


def _t_limits(samples: np.ndarray, confidence: float) -> tuple[np.ndarray, ...]:
    """Student's t interval of the mean of each row of ``samples`` (..., n)."""
    size = samples.shape[-1]
    mean = samples.mean(axis=-1)
    half = stats.t.ppf((1 + confidence) / 2, size - 1) * samples.std(ddof=1, axis=-1)
    half = half / math.sqrt(size)
    return mean, mean - half, mean + half


def _bonett_limits(samples: np.ndarray, confidence: float) -> tuple[np.ndarray, ...]:
    """Bonett's interval of the standard deviation of each row of ``samples`` (..., n): the
    variance's log +- z se, se = c sqrt((kurtosis - (n-3)/n) / (n-1)), the kurtosis taken about
    a mean trimmed by 1 / (2 sqrt(n - 4)) of each tail, and c s^2 for s^2 (c = n / (n - z))."""
    size = samples.shape[-1]
    z = stats.norm.ppf((1 + confidence) / 2)
    factor = size / (size - z)
    trimmed = stats.trim_mean(samples, 1 / (2 * math.sqrt(size - 4)), axis=-1)
    variance = samples.var(ddof=1, axis=-1)
    kurtosis = (
        size * np.sum((samples - trimmed[..., None]) ** 4, axis=-1) / ((size - 1) * variance) ** 2
    )
    spread = z * factor * np.sqrt(np.maximum(kurtosis - (size - 3) / size, 0.0) / (size - 1))
    centre = np.log(factor * variance)
    return np.sqrt(variance), np.exp((centre - spread) / 2), np.exp((centre + spread) / 2)


def _chi2_limits(samples: np.ndarray, confidence: float) -> tuple[np.ndarray, ...]:
    """Normal theory's interval of the standard deviation: (n-1) s^2 / sigma^2 is chi-square."""
    dof = samples.shape[-1] - 1
    std = samples.std(ddof=1, axis=-1)
    tails = stats.chi2.ppf([(1 + confidence) / 2, (1 - confidence) / 2], dof)
    return std, std * np.sqrt(dof / tails[0]), std * np.sqrt(dof / tails[1])


_CLOSED_FORMS = {("mean", "t"): _t_limits, ("std", "bonett"): _bonett_limits}
_CLOSED_FORMS[("std", "chi2")] = _chi2_limits


def _closed_form(sample, statistic: str, method: str, confidence: float) -> Interval:
    confidence = probability(confidence, "confidence")
    values = real_array(sample, "sample")
    if values.ndim != 1 or values.size < 5:
        raise ValueError(f"sample must be 1-D with at least 5 values; got shape {values.shape}")
    return Interval(*(float(x) for x in _CLOSED_FORMS[statistic, method](values, confidence)))


def mean_interval(sample, confidence: float = 0.95) -> Interval:
    """Student's t interval of the mean of a 1-D ``sample`` (at least 5 values), in its unit."""
    return _closed_form(sample, "mean", "t", confidence)


def std_interval(sample, confidence: float = 0.95) -> Interval:
    """Bonett's interval of the standard deviation (the estimate: ddof = 1) of a 1-D
    ``sample`` (at least 5 values), in its unit (module docstring)."""
    return _closed_form(sample, "std", "bonett", confidence)


@dataclass(frozen=True)
class Coverage:
    """How often an interval held the true value in :func:`coverage`'s simulation."""

    statistic: str
    method: str
    distribution: str
    size: int  # values in each sample
    trials: int
    confidence: float  # the nominal coverage
    covered: float  # the share of trials whose interval held the true value

    @property
    def standard_error(self) -> float:
        """The binomial Monte Carlo standard error of :attr:`covered`."""
        return math.sqrt(self.covered * (1 - self.covered) / self.trials)


def _draws(distribution: str, rng: np.random.Generator, shape: tuple[int, int]):
    """Samples of ``distribution`` (:data:`COVERAGE_DISTRIBUTIONS`) and its true mean and sd."""
    if distribution == "normal":
        return rng.normal(0.0, 1.0, shape), 0.0, 1.0
    if distribution == "uniform":
        return rng.uniform(-math.sqrt(3.0), math.sqrt(3.0), shape), 0.0, 1.0
    if distribution == "gamma":  # scale 1 / sqrt(shape): unit sd
        scale = 1 / math.sqrt(_GAMMA_SHAPE)
        return rng.gamma(_GAMMA_SHAPE, scale, shape), _GAMMA_SHAPE * scale, 1.0
    pooled = np.concatenate([_standardised(site) for site in SITES])
    return rng.choice(pooled, size=shape), 0.0, 1.0


def site_rounds() -> int:
    """The distinct rounds of a site: 22 at each (tests/test_harp_confidence.py)."""
    return len(_rounds(SITES[0]))


def _standardised(site: str) -> np.ndarray:
    residuals = _residuals_m(site, "dissertation")
    return (residuals - residuals.mean()) / residuals.std()


@cached_copies
def coverage(
    statistic: str = "std",
    method: str = "bonett",
    distribution: str = "normal",
    *,
    size: int | None = None,
    trials: int = 4000,
    confidence: float = 0.95,
    resamples: int = 999,
    seed: int = 0,
) -> Coverage:
    """The share of ``trials`` samples of ``size`` values drawn from ``distribution``
    (:data:`COVERAGE_DISTRIBUTIONS`) whose ``method`` interval (:data:`INTERVAL_METHODS`) of
    ``statistic`` holds the distribution's true value; ``size`` defaults to a site's distinct
    rounds (:func:`site_rounds`). ``"bca"`` is :func:`bootstrap_interval`'s with ``resamples``,
    all trials in one call of scipy's bootstrap (which resamples every trial with the same
    indices: the trials stay independent, their data being so). Deterministic given ``seed``."""
    check_choice(statistic, "statistic", INTERVAL_METHODS)
    check_choice(method, "method", INTERVAL_METHODS[statistic])
    check_choice(distribution, "distribution", COVERAGE_DISTRIBUTIONS)
    confidence = probability(confidence, "confidence")
    size = site_rounds() if size is None else whole_number(size, "size", low=5)
    trials = whole_number(trials, "trials", low=1)
    samples, true_mean, true_std = _draws(distribution, np.random.default_rng(seed), (trials, size))
    truth = true_mean if statistic == "mean" else true_std
    if method == "bca":
        _check_bootstrap(confidence, resamples, seed)
        result = bootstrap(
            (samples,),
            _STATISTICS[statistic],
            confidence_level=confidence,
            n_resamples=resamples,
            method="BCa",
            vectorized=True,
            axis=-1,
            batch=max(1, 2_000_000 // (trials * size)),  # resamples held at once: ~16 MB
            rng=np.random.default_rng(seed),
        )
        low, high = result.confidence_interval
    else:
        _, low, high = _CLOSED_FORMS[statistic, method](samples, confidence)
    covered = float(np.mean((low <= truth) & (truth <= high)))
    return Coverage(statistic, method, distribution, size, trials, confidence, covered)


@cached_copies
def coverage_table(
    size: int | None = None,
    trials: int = 4000,
    confidence: float = 0.95,
    seed: int = 0,
) -> pd.DataFrame:
    """:func:`coverage` of every statistic's every method (rows) on every distribution
    (columns), at ``size`` values a sample (default :func:`site_rounds`)."""
    rows = {
        (statistic, method): {
            distribution: coverage(
                statistic,
                method,
                distribution,
                size=size,
                trials=trials,
                confidence=confidence,
                seed=seed,
            ).covered
            for distribution in COVERAGE_DISTRIBUTIONS
        }
        for statistic, methods in INTERVAL_METHODS.items()
        for method in methods
    }
    return pd.DataFrame(rows).T.rename_axis(["statistic", "method"])


# --- 2. the scatter the known input uncertainties explain ----------------------------------------
def apogee_sensitivities(
    site: str | LaunchSite,
    model: str = "dissertation",
    speed_step_m_s: float = SPEED_RECORD_STEP_M_S / 2,
    mass_step_kg: float = MASS_RECORD_STEP_KG / 2,
    density_step: float = 0.01,
) -> pd.DataFrame:
    """Per distinct round of ``site``: the central-difference slope of its predicted apogee
    (``model`` with its own Cd0 A and the site's density) against muzzle speed
    (``speed_m_per_m_s``), mass (``mass_m_per_kg``) and the relative surface density
    (``density_m_per_relative``, m per unit d rho / rho), and each input's nonlinearity at its
    step, |A(x+h) + A(x-h) - 2 A(x)| / |A(x+h) - A(x-h)|: the second-order change against the
    first, small where a linear propagation holds. The steps default to half the records'
    quantisation step (speed, mass) and 1 % of the density."""
    site, model = get_site(site), eci.get_model(model).name
    rounds = _rounds(site)
    speed, mass = rounds.muzzle_speed_m_s.to_numpy(), rounds.mass_kg.to_numpy()
    density = site.surface_density_kg_m3
    inputs = {  # name: (step, unit of the slope, the changed input)
        "speed": (
            _positive(speed_step_m_s, "speed_step_m_s"),
            "m_per_m_s",
            lambda change: {"speed_m_s": speed + change},
        ),
        "mass": (
            _positive(mass_step_kg, "mass_step_kg"),
            "m_per_kg",
            lambda change: {"mass_kg": mass + change},
        ),
        "density": (
            _positive(density_step, "density_step"),
            "m_per_relative",
            lambda change: {"surface_density_kg_m3": density * (1 + change)},
        ),
    }
    area = apogees.drag_area_m2(model)
    nominal = _apogees_m(site, area, model)
    frame = pd.DataFrame({"round_number": rounds.round_number})
    for name, (step, unit, changed) in inputs.items():
        up, down = (_apogees_m(site, area, model, **changed(sign * step)) for sign in (1, -1))
        frame[f"{name}_{unit}"] = (up - down) / (2 * step)
        frame[f"{name}_nonlinearity"] = np.abs(up + down - 2 * nominal) / np.abs(up - down)
    return frame


def _positive(value, name):
    return Bounds(low=0.0, low_inclusive=False).check(real_number(value, name), name)


@dataclass(frozen=True)
class ScatterBudget:
    """One site's residual scatter against the inputs' uncertainties (:func:`scatter_budget`)."""

    site: str
    observed_std_m: Interval  # the residuals' sample sd and its interval (std_interval)
    explained_std_m: float  # the apogee sd the given input uncertainties produce
    explained_fraction: Interval  # explained / observed variance, at the sd's interval
    implied_speed_std_m_s: Interval  # the muzzle-speed sd that alone explains the rest
    implied_density_std: Interval  # the relative surface-density sd that alone explains the rest


def scatter_budget(
    site: str | LaunchSite,
    model: str = "dissertation",
    speed_std_m_s: float = uniform_quantisation_std(SPEED_RECORD_STEP_M_S),
    mass_std_kg: float = uniform_quantisation_std(MASS_RECORD_STEP_KG),
    density_std: float = 0.0,
    confidence: float = 0.95,
) -> ScatterBudget:
    """How much of ``site``'s residual variance (distinct rounds, ``model``) independent input
    errors of the given standard deviations explain, propagated linearly through each round's
    :func:`apogee_sensitivities` (the explained variance is their mean over the rounds), and
    what the rest implies.

    What is known: the muzzle speeds are records to 10 ft/s and the masses whole half pounds,
    so by default each is uniform over its quantisation step (sd step / sqrt(12)). The text
    gives no accuracy for the probe or radar muzzle speeds (Ch. 6 B: radar from 4-10 s after
    launch, smear cameras "prone to poor readings") nor any day's air: no per-round density
    exists, so ``density_std`` is 0 unless one is assumed. The implied sds are what the
    scatter implies, not data: the muzzle-speed sd (m/s) alone, or the relative surface-density
    sd alone, that would add the unexplained variance (0 where nothing is left), at the
    observed sd and at its interval's ends."""
    site, model = get_site(site), eci.get_model(model).name
    slopes = apogee_sensitivities(site, model)
    speed_slope2 = np.mean(slopes.speed_m_per_m_s**2)
    density_slope2 = np.mean(slopes.density_m_per_relative**2)
    explained = (
        speed_slope2 * _nonnegative(speed_std_m_s, "speed_std_m_s") ** 2
        + np.mean(slopes.mass_m_per_kg**2) * _nonnegative(mass_std_kg, "mass_std_kg") ** 2
        + density_slope2 * _nonnegative(density_std, "density_std") ** 2
    )
    observed = std_interval(_residuals_m(site, model), confidence)

    def implied(slope2):  # high sd -> high implied sd
        return Interval(*(math.sqrt(max(s**2 - explained, 0.0) / slope2) for s in observed))

    fraction = Interval(
        *(explained / s**2 for s in (observed.estimate, observed.high, observed.low))
    )
    return ScatterBudget(
        site.key,
        observed,
        math.sqrt(explained),
        fraction,
        implied(speed_slope2),
        implied(density_slope2),
    )


def _nonnegative(value, name):
    return Bounds(low=0.0).check(real_number(value, name), name)


def scatter_budget_table(model: str = "dissertation", confidence: float = 0.95) -> pd.DataFrame:
    """:func:`scatter_budget` of both sites with the default (quantisation) uncertainties, one
    row per site; each interval as ``<name>``, ``<name>_low``, ``<name>_high``."""
    rows = {}
    for site in SITES:
        budget = scatter_budget(site, model, confidence=confidence)
        row: dict[str, float] = {"explained_std_m": budget.explained_std_m}
        for name in (
            "observed_std_m",
            "explained_fraction",
            "implied_speed_std_m_s",
            "implied_density_std",
        ):
            row |= _flat(name, getattr(budget, name))
        rows[site] = row
    return pd.DataFrame(rows).T


def _flat(name: str, interval: Interval) -> dict[str, float]:
    return {name: interval.estimate, f"{name}_low": interval.low, f"{name}_high": interval.high}


# --- 3. Cd0 A fitted to the apogees --------------------------------------------------------------
def surface_densities_kg_m3(densities: str = "site", anchor: str = "barbados") -> dict[str, float]:
    """Each site's surface density (kg/m^3): the text's (``"site"``, those :mod:`.apogees` flies),
    or (``"temperature"``) ``anchor``'s with the other site's at the same surface pressure and
    its own Mach-column temperature, rho = rho_anchor T_anchor / T (module docstring)."""
    check_choice(densities, "densities", ("site", "temperature"))
    anchor = get_site(anchor).key
    values = {site: get_site(site).surface_density_kg_m3 for site in SITES}
    if densities == "site":
        return values
    temperature = {
        site: apogees.air_temperature_k(apogees.speed_of_sound(site)[0]) for site in SITES
    }
    return {site: values[anchor] * temperature[anchor] / temperature[site] for site in SITES}


def _site_names(sites: str | Iterable[str]) -> tuple[str, ...]:
    names = (sites,) if isinstance(sites, str) else tuple(sites)
    names = tuple(get_site(site).key for site in names)
    if not names or len(set(names)) != len(names):
        raise ValueError(f"sites must name one or both sites once each; got {sites!r}")
    return names


def _residuals_and_slopes(site, index, area, density, model):
    """Residuals (k, n) of the rounds ``index`` (k, n) of ``site`` at Cd0 A ``area`` (k,) and
    their slopes d residual / d Cd0 A (forward difference)."""
    measured = _rounds(site).apogee_m.to_numpy()[index]
    step = area[:, None] * _FIT_STEP
    predicted, shifted = (
        np.take_along_axis(_apogees_m(site, a, model, density), index, axis=-1)
        for a in (area[:, None], area[:, None] + step)
    )
    return measured - predicted, (predicted - shifted) / step


def _linearised(samples, area, densities, model, per_site_offset):
    """All resampled residuals and slopes side by side; with ``per_site_offset`` each site's
    centred, which removes its offset exactly (a linear parameter: Frisch-Waugh-Lovell)."""
    parts = [
        _residuals_and_slopes(site, index, area, densities[site], model)
        for site, index in samples.items()
    ]
    if per_site_offset:
        parts = [tuple(x - x.mean(axis=-1, keepdims=True) for x in part) for part in parts]
    residual, slope = (np.concatenate(x, axis=-1) for x in zip(*parts))
    return residual, slope


def _fit_areas(samples, densities, model, per_site_offset, start) -> np.ndarray:
    """Cd0 A (k,) of least squares for k resamples at once, by Gauss-Newton from ``start``;
    ``samples`` maps each site to (k, n) indices of its distinct rounds."""
    area = np.full(next(iter(samples.values())).shape[0], start)
    for _ in range(_FIT_ITERATIONS):
        residual, slope = _linearised(samples, area, densities, model, per_site_offset)
        curvature = np.sum(slope**2, axis=-1)
        step = -np.sum(residual * slope, axis=-1) / curvature
        area = area + step
        if np.all(np.abs(step) <= _FIT_TOLERANCE * np.sqrt(np.sum(residual**2, -1) / curvature)):
            return area
    raise RuntimeError(f"the Cd0 A fit did not converge in {_FIT_ITERATIONS} iterations")


@dataclass(frozen=True)
class DragAreaFit:
    """Cd0 A (m^2) fitted to the distinct rounds' apogees (:func:`fit_drag_area`)."""

    sites: tuple[str, ...]
    drag_area_m2: float
    standard_uncertainty_m2: float  # sqrt(s^2 / (J^T J)), s^2 = residual variance
    residual_std_m: float  # s, with n - p degrees of freedom
    rounds: int
    site_offsets_m: dict[str, float] = field(default_factory=dict)  # with per_site_offset


def fit_drag_area(
    sites: str | Iterable[str] = SITES,
    *,
    per_site_offset: bool = False,
    densities: str = "site",
    anchor: str = "barbados",
    model: str = "dissertation",
) -> DragAreaFit:
    """Least-squares Cd0 A of the apogee residuals (measured - predicted, ``model``) of the
    distinct rounds of ``sites`` (one or both), each site at
    :func:`surface_densities_kg_m3` (``densities``, ``anchor``).
    Its standard uncertainty is the linearised one, s^2 (J^T J)^-1 with s^2 the residual sum of
    squares over n - p and J the residuals' slopes.

    ``per_site_offset`` adds a free mean residual per site, a bias (the site's muzzle-speed
    calibration, air, apogee method) the drag is then not asked to absorb: Cd0 A is fitted only
    to how the residuals vary with each round's drag sensitivity within a site, which is the
    fairer comparison if the sites differ by an offset, at the price of a much weaker
    constraint."""
    sites = _site_names(sites)
    model = eci.get_model(model).name
    rho = surface_densities_kg_m3(densities, anchor)
    samples = {site: np.arange(len(_rounds(site)))[None] for site in sites}
    area = _fit_areas(samples, rho, model, per_site_offset, apogees.drag_area_m2(model))
    residual, slope = _linearised(samples, area, rho, model, per_site_offset)
    parameters = 1 + per_site_offset * len(sites)
    variance = float(np.sum(residual**2)) / (residual.size - parameters)
    offsets = {}
    if per_site_offset:
        offsets = {
            site: float(np.mean(_residuals_and_slopes(site, index, area, rho[site], model)[0]))
            for site, index in samples.items()
        }
    return DragAreaFit(
        sites,
        float(area[0]),
        math.sqrt(variance / float(np.sum(slope**2))),
        math.sqrt(variance),
        residual.size,
        offsets,
    )


def _flattened(statistic):
    """A statistic of (k, n) index arrays as scipy's bootstrap calls it: any leading shape."""

    def wrapped(*indices, axis=-1):
        lead = np.shape(indices[0])[:-1]
        flat = [np.reshape(index, (-1, np.shape(index)[-1])) for index in indices]
        return np.reshape(statistic(*flat), lead)

    return wrapped


def drag_area_interval(
    sites: str | Iterable[str] = SITES,
    *,
    per_site_offset: bool = False,
    densities: str = "site",
    anchor: str = "barbados",
    model: str = "dissertation",
    confidence: float = 0.95,
    resamples: int = RESAMPLES,
    seed: int = 0,
) -> Interval:
    """BCa bootstrap interval of :func:`fit_drag_area`'s Cd0 A (m^2), resampling the rounds
    within each site."""
    sites = _site_names(sites)
    model = eci.get_model(model).name
    rho = surface_densities_kg_m3(densities, anchor)
    start = fit_drag_area(
        sites, per_site_offset=per_site_offset, densities=densities, anchor=anchor, model=model
    ).drag_area_m2

    @_flattened
    def fitted(*indices):
        return _fit_areas(dict(zip(sites, indices)), rho, model, per_site_offset, start)

    rounds = tuple(np.arange(len(_rounds(site))) for site in sites)
    return _bootstrap(rounds, fitted, confidence, resamples, seed)


def drag_area_fit_table(
    densities: str = "site",
    model: str = "dissertation",
    confidence: float = 0.95,
    resamples: int = RESAMPLES,
    seed: int = 0,
) -> pd.DataFrame:
    """Cd0 A (m^2) fitted to each site alone, to both, and to both with a per-site offset: the
    estimate, its linearised standard uncertainty, its bootstrap interval, the residual sd, the
    fitted offsets (NaN where none is fitted) and its ratio to the Cd0 A ``model`` predicts
    with (:func:`~harp_analysis.analyses.harp.apogees.drag_area_m2`; the dissertation's is the one
    Appendix E's errors fix)."""
    cases = {
        "barbados": (("barbados",), False),
        "yuma": (("yuma",), False),
        "joint": (SITES, False),
        "joint, per-site offsets": (SITES, True),
    }
    rows = {}
    for name, (sites, offset) in cases.items():
        fit = fit_drag_area(sites, per_site_offset=offset, densities=densities, model=model)
        interval = drag_area_interval(
            sites,
            per_site_offset=offset,
            densities=densities,
            model=model,
            confidence=confidence,
            resamples=resamples,
            seed=seed,
        )
        rows[name] = {
            "drag_area_m2": fit.drag_area_m2,
            "standard_uncertainty_m2": fit.standard_uncertainty_m2,
            "low_m2": interval.low,
            "high_m2": interval.high,
            "residual_std_m": fit.residual_std_m,
            **{f"offset_{site}_m": fit.site_offsets_m.get(site, math.nan) for site in SITES},
            "ratio_to_model": fit.drag_area_m2 / apogees.drag_area_m2(model),
        }
    return pd.DataFrame(rows).T


# --- 4. the drag of one site at the other ---------------------------------------------------------
@dataclass(frozen=True)
class Transfer:
    """Cd0 A fitted at ``fit_site`` flown at ``predict_site`` (:func:`transfer`)."""

    fit_site: str
    predict_site: str
    densities: str
    fit_density_kg_m3: float
    predict_density_kg_m3: float
    drag_area_m2: float
    mean_residual_m: Interval  # at predict_site, bootstrapped over both sites' rounds

    @property
    def holds(self) -> bool:
        """Whether zero lies inside the transferred mean residual's interval."""
        return self.mean_residual_m.contains_zero


def transfer(
    fit_site: str = "barbados",
    predict_site: str = "yuma",
    densities: str = "temperature",
    model: str = "dissertation",
    confidence: float = 0.95,
    resamples: int = RESAMPLES,
    seed: int = 0,
) -> Transfer:
    """Fit Cd0 A to ``fit_site``'s rounds alone (:func:`fit_drag_area`), fly ``predict_site``'s
    rounds with it and report their mean residual. With ``densities="temperature"`` the fit
    site keeps its density and the other follows its Mach-column temperature at the same
    pressure; with ``"site"`` both keep the text's. The interval resamples both sites' rounds,
    so it carries the fitted drag's uncertainty as well as the predicted site's scatter; the
    transfer holds if it contains zero."""
    fit_site, predict_site = _site_names((fit_site, predict_site))
    model = eci.get_model(model).name
    rho = surface_densities_kg_m3(densities, anchor=fit_site)
    start = fit_drag_area(
        (fit_site,), densities=densities, anchor=fit_site, model=model
    ).drag_area_m2

    @_flattened
    def mean_residual(fit_index, predict_index):
        area = _fit_areas({fit_site: fit_index}, rho, model, False, start)
        residual = _residuals_and_slopes(
            predict_site, predict_index, area, rho[predict_site], model
        )[0]
        return residual.mean(axis=-1)

    rounds = tuple(np.arange(len(_rounds(site))) for site in (fit_site, predict_site))
    return Transfer(
        fit_site,
        predict_site,
        densities,
        rho[fit_site],
        rho[predict_site],
        start,
        _bootstrap(rounds, mean_residual, confidence, resamples, seed),
    )


def transfer_table(
    model: str = "dissertation",
    confidence: float = 0.95,
    resamples: int = RESAMPLES,
    seed: int = 0,
) -> pd.DataFrame:
    """:func:`transfer` both ways under both density choices, one row each."""
    rows = []
    for fit_site, predict_site in (SITES, SITES[::-1]):
        for densities in ("site", "temperature"):
            result = transfer(fit_site, predict_site, densities, model, confidence, resamples, seed)
            rows.append(
                {
                    "fit_site": fit_site,
                    "predict_site": predict_site,
                    "densities": densities,
                    "fit_density_kg_m3": result.fit_density_kg_m3,
                    "predict_density_kg_m3": result.predict_density_kg_m3,
                    "drag_area_m2": result.drag_area_m2,
                    **_flat("mean_residual_m", result.mean_residual_m),
                    "holds": result.holds,
                }
            )
    return pd.DataFrame(rows)


def apogee_density_ratio(
    model: str = "dissertation",
    confidence: float = 0.95,
    resamples: int = RESAMPLES,
    seed: int = 0,
) -> Interval:
    """The Yuma-to-Barbados surface-density ratio the apogees imply for one Martlet drag: the
    product rho0 Cd0 A fitted at Yuma alone over that at Barbados alone (only the product
    enters the ECI MKS), with its BCa interval resampling each site's rounds. A transfer holds
    for any pair of densities with this ratio; compare the Mach columns' T_barbados / T_yuma
    (:func:`surface_densities_kg_m3`) and the text's 1.14 / 1.225."""
    model = eci.get_model(model).name
    rho = surface_densities_kg_m3("site")
    start = {site: fit_drag_area((site,), model=model).drag_area_m2 for site in SITES}

    @_flattened
    def ratio(*indices):
        product = {
            site: rho[site] * _fit_areas({site: index}, rho, model, False, start[site])
            for site, index in zip(SITES, indices)
        }
        return product["yuma"] / product["barbados"]

    rounds = tuple(np.arange(len(_rounds(site))) for site in SITES)
    return _bootstrap(rounds, ratio, confidence, resamples, seed)
