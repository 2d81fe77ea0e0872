"""What Appendix E identifies of the HARP model (issue 26): every combination of the three
choices Chapters 5-6 leave open, each fitted to Appendix E's Error column as the dissertation
model is, with its fit, Barbados' mean residual and round 181's range.

The open choices (:class:`~harp_analysis.engines.eci.EciModel`'s fields, each with the readings the
text allows):

- ``tangent_sine``: the elevation whose sine eq 5.8's straight climb (eq 5.7) uses: ``"gun"``
  (phi_rel, the elevation of Vrel, as printed) or ``"corrected"`` (that of Vrel + omega x r0,
  the velocity V_tangent is added to);
- ``tau_elevation``: eq 6.12's phi: ``"corrected"`` or ``"launch"`` (eq 6.15's V, V_tangent
  included); the text gives eqs 6.11-6.13 one phi and does not say which velocity's it is;
- ``speed_ratio``: the V of eq 5.3's (Vrel/V)^2: ``"corrected"`` (Vrel + omega x r0, Figs 5.1-5.2)
  or ``"launch"`` (eq 6.15's V against its air-relative part).

Everything else stays the dissertation model's (:data:`~harp_analysis.engines.eci.DISSERTATION`):
V_tangent included, beta of eq 6.11 at the gun's 85 deg (Appendix E's Beta column holds it: every
Yuma Beta within print rounding, ``tests/test_harp.py``), the consistent decay. Each combination's
Cd0 A is :func:`~harp_analysis.analyses.harp.apogees.fit_drag_area_to_errors` of its own model, the
least-squares fit that fixes the dissertation model's, and is used unchanged at Barbados, as the
text says.

Noise. Appendix E prints Error in km to two decimals: 10 m steps
(:data:`ERROR_COLUMN_RESOLUTION_M`), so a model that computed every round exactly as the
dissertation did would still miss each printed Error by a rounding error, uniform within half a
step: RMS step / sqrt(12) = 2.9 m. A combination fits within noise when its RMS misfit is
below what rounding alone exceeds with probability :data:`SIGNIFICANCE` over the 22 rounds
(:func:`noise_threshold_km`). A choice is identified when every combination fitting within
noise reads it alike; otherwise Appendix E cannot tell its readings apart, and the spread of a
result over those combinations (:func:`appendix_e_spread`) is the uncertainty the choice leaves.

The Error column is what Fig 6.6 draws: every fit here is in-sample at Yuma.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd
from scipy.stats import norm

from ...engines import eci
from ...foundation.caching import cached_copies
from ...foundation.validation import Bounds, check_choice, probability, real_number, whole_number
from . import apogees
from . import rounds as harp_rounds

__all__ = [
    "OPEN_CHOICES",
    "ERROR_COLUMN_RESOLUTION_M",
    "SIGNIFICANCE",
    "QUANTITIES",
    "combinations",
    "rounding_rms_km",
    "noise_threshold_km",
    "identification_table",
    "choice_table",
    "Spread",
    "appendix_e_spread",
    "ReadingFit",
    "reading_fit",
]

#: The choices the text leaves open and the readings it allows (module docstring).
OPEN_CHOICES = {
    "tangent_sine": ("gun", "corrected"),
    "tau_elevation": ("corrected", "launch"),
    "speed_ratio": ("corrected", "launch"),
}
#: The step of Appendix E's printed Error column (m): two decimals of a km.
ERROR_COLUMN_RESOLUTION_M = 2 * apogees.PRINT_HALF_UNITS["apogee_error_m"]
#: The chance that print rounding alone gives an RMS misfit above the noise threshold.
SIGNIFICANCE = 0.01
#: The results of each combination that :func:`appendix_e_spread` reports.
QUANTITIES = ("barbados_mean_km", "barbados_std_km", "round181_range_km")
_KM = 1e3


def combinations() -> tuple[eci.EciModel, ...]:
    """Every combination of :data:`OPEN_CHOICES`, the dissertation model's other choices kept,
    each named by its readings."""
    models = []
    for readings in itertools.product(*OPEN_CHOICES.values()):
        choices: dict[str, Any] = dict(zip(OPEN_CHOICES, readings))
        choices["name"] = ", ".join(f"{choice}={reading}" for choice, reading in choices.items())
        models.append(dataclasses.replace(eci.DISSERTATION, **choices))
    return tuple(models)


def _is_dissertation(model: eci.EciModel) -> bool:
    return all(getattr(model, c) == getattr(eci.DISSERTATION, c) for c in OPEN_CHOICES)


def rounding_rms_km(resolution_m: float = ERROR_COLUMN_RESOLUTION_M) -> float:
    """RMS (km) of the rounding error of one printed Error: uniform over one print step."""
    step = Bounds(low=0.0, unit="m").check(
        real_number(resolution_m, "resolution_m"), "resolution_m"
    )
    return step / math.sqrt(12) / _KM


def noise_threshold_km(
    rounds: int | None = None,
    significance: float = SIGNIFICANCE,
    resolution_m: float = ERROR_COLUMN_RESOLUTION_M,
) -> float:
    """The RMS misfit (km) that rounding to ``resolution_m`` alone exceeds with probability
    ``significance`` over ``rounds`` rounds (default Appendix E's 22). Each rounding error u is
    uniform in +-h; the mean of u^2 over n rounds has mean h^2/3 and variance (4/45) h^4 / n,
    near normal (central limit), so the threshold is sqrt(h^2/3 (1 + z sqrt(0.8 / n))), z the
    normal quantile of 1 - ``significance``. The fitted Cd0 A only lowers a true model's
    misfit, so the threshold errs towards calling a combination within noise."""
    count = apogees.round_count("yuma") if rounds is None else whole_number(rounds, "rounds", low=1)
    chance = probability(significance, "significance")
    spread = float(norm.ppf(1.0 - chance)) * math.sqrt(0.8 / count)
    return rounding_rms_km(resolution_m) * math.sqrt(max(1.0 + spread, 0.0))


def _row(model: eci.EciModel) -> dict:
    area = apogees.fit_drag_area_to_errors(model)[0]
    yuma = apogees.predicted_apogees("yuma", model, area)
    misfit_km = (yuma.residual_m - yuma.printed_error_m).to_numpy() / _KM
    barbados = apogees.predicted_apogees("barbados", model, area).residual_m / _KM
    return {
        **{choice: getattr(model, choice) for choice in OPEN_CHOICES},
        "dissertation": _is_dissertation(model),
        "drag_area_m2": area,
        "error_rms_km": float(np.sqrt(np.mean(misfit_km**2))),
        "error_max_km": float(np.max(np.abs(misfit_km))),
        "barbados_mean_km": float(barbados.mean()),
        "barbados_std_km": float(barbados.std(ddof=1)),
        "round181_range_km": harp_rounds.splash_range_km("barbados", 181, model, area),
    }


@cached_copies
def _fits() -> pd.DataFrame:
    table = pd.DataFrame([_row(model) for model in combinations()])
    return table.sort_values("error_rms_km", ignore_index=True)


def identification_table(
    resolution_m: float = ERROR_COLUMN_RESOLUTION_M, significance: float = SIGNIFICANCE
) -> pd.DataFrame:
    """One row per combination of :data:`OPEN_CHOICES` (the dissertation model's marked), best
    fit first: its readings, the Cd0 A it fits to Appendix E's Error column (m^2), the RMS and
    largest misfit to that column (km), whether it fits within the noise of an Error column
    printed to ``resolution_m`` (:func:`noise_threshold_km`), and with that Cd0 A Barbados'
    mean and sample standard deviation of the residual over the 23 printed rows (km, as
    Ch. 6 C counts them) and round 181's splash range (km,
    :func:`~harp_analysis.analyses.harp.rounds.splash_range_km`). A copy."""
    table = _fits()
    threshold = noise_threshold_km(significance=significance, resolution_m=resolution_m)
    table.insert(
        table.columns.get_loc("error_max_km") + 1,
        "within_noise",
        table.error_rms_km <= threshold,
    )
    return table


def choice_table(
    resolution_m: float = ERROR_COLUMN_RESOLUTION_M, significance: float = SIGNIFICANCE
) -> pd.DataFrame:
    """Per open choice: the readings of the combinations that fit within noise
    (:func:`identification_table`), whether Appendix E identifies the choice (exactly one
    reading among them), the dissertation model's reading, the RMS misfit (km) of the
    combination differing from the dissertation model's in this choice alone, and the best
    any combination reaches with another reading."""
    table = identification_table(resolution_m, significance)
    fitting = table[table.within_noise]
    rows = {}
    for choice in OPEN_CHOICES:
        own = getattr(eci.DISSERTATION, choice)
        others_kept = np.logical_and.reduce(
            [table[c] == getattr(eci.DISSERTATION, c) for c in OPEN_CHOICES if c != choice]
        )
        readings = sorted(set(fitting[choice]))
        rows[choice] = {
            "readings_within_noise": ", ".join(readings) or "none",
            "identified": len(readings) == 1,
            "dissertation_reading": own,
            "alone_changed_rms_km": float(
                table.error_rms_km[others_kept & (table[choice] != own)].min()
            ),
            "best_other_rms_km": float(table.error_rms_km[table[choice] != own].min()),
        }
    return pd.DataFrame(rows).T


@dataclass(frozen=True)
class Spread:
    """A result over the combinations Appendix E cannot tell apart (km)."""

    quantity: str
    dissertation: float  # the dissertation model's value
    low: float  # lowest and highest over the combinations fitting within noise
    high: float
    nearest: float  # the value among them nearest ``nearest_to`` (the dissertation's if None)
    all_low: float  # lowest and highest over every combination
    all_high: float
    within_noise: int  # how many combinations fit within noise
    combinations: int
    noise_threshold_km: float
    runner_up_rms_km: float  # the best RMS misfit of a combination outside the noise
    runner_up: float  # that combination's value

    @property
    def all_width(self) -> float:
        """How far the open choices move the quantity when Appendix E does not constrain them:
        the highest minus the lowest over every combination."""
        return self.all_high - self.all_low


def appendix_e_spread(
    quantity: str, *, magnitude: bool = False, nearest_to: float | None = None
) -> Spread:
    """The spread of ``quantity`` (one of :data:`QUANTITIES`; its magnitude if ``magnitude``)
    over the combinations fitting Appendix E within noise (the default noise,
    :func:`identification_table`), and over all of them."""
    check_choice(quantity, "quantity", QUANTITIES)
    table = identification_table()
    values = table[quantity].abs() if magnitude else table[quantity]
    fitting = values[table.within_noise]
    if fitting.empty:
        raise ValueError("no combination fits Appendix E's Error column within noise")
    own = float(values[table.dissertation].iloc[0])
    if nearest_to is None:
        nearest = own
    else:
        target = real_number(nearest_to, "nearest_to")
        nearest = float(fitting.iloc[int(np.argmin(np.abs(fitting.to_numpy() - target)))])
    outside = values[~table.within_noise]  # the table is sorted by misfit
    return Spread(
        quantity=f"|{quantity}|" if magnitude else quantity,
        dissertation=own,
        low=float(fitting.min()),
        high=float(fitting.max()),
        nearest=nearest,
        all_low=float(values.min()),
        all_high=float(values.max()),
        within_noise=len(fitting),
        combinations=len(table),
        noise_threshold_km=noise_threshold_km(),
        runner_up_rms_km=float(table.error_rms_km[outside.index[0]]) if len(outside) else math.nan,
        runner_up=float(outside.iloc[0]) if len(outside) else math.nan,
    )


@dataclass(frozen=True)
class ReadingFit:
    """The best fit to Appendix E's Error column of the combinations reading ``choice`` as
    ``reading``."""

    choice: str
    reading: str
    combination: str  # the best one's readings
    error_rms_km: float
    noise_threshold_km: float
    within_noise: bool
    dissertation_rms_km: float


def reading_fit(choice: str, reading: str) -> ReadingFit:
    """How well Appendix E's Error column admits ``reading`` of the open ``choice``: the best
    RMS misfit (km) of every combination that reads it so."""
    check_choice(choice, "choice", OPEN_CHOICES)
    check_choice(reading, "reading", OPEN_CHOICES[choice])
    table = identification_table()
    best = table[table[choice] == reading].iloc[0]  # the table is sorted by misfit
    return ReadingFit(
        choice=choice,
        reading=reading,
        combination=", ".join(f"{c}={best[c]}" for c in OPEN_CHOICES),
        error_rms_km=float(best.error_rms_km),
        noise_threshold_km=noise_threshold_km(),
        within_noise=bool(best.within_noise),
        dissertation_rms_km=float(table.error_rms_km[table.dissertation].iloc[0]),
    )
