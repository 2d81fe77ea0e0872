"""HARP apogees (Chapter 6 C and D): the ECI Modified Kepler Solution of every Martlet 2C round
of Appendices D (Barbados) and E (Yuma), the appendices' derived columns recomputed, and the
drag area, speed of sound and residual statistics behind them.

Muzzle speeds. The appendices print Vo to 0.01 km/s, too coarse for an apogee (0.14 km per m/s).
The HARP records gave speeds in ft/s: for every round exactly one whole multiple of 10 ft/s
inside the printed Vo's rounding interval reproduces the printed mu (2 decimals of a degree, which
pins Vo to a few ft/s) within print rounding (:func:`recover_muzzle_speeds`). Those speeds are
kept as derived data beside the transcription (``data/harp/muzzle_speeds.tsv``) and every model
flies them.

Models (:data:`harp_analysis.engines.eci.MODELS`), each with the drag area it fits itself:

- ``"dissertation"`` (default): the text's own pipeline, recovered from Appendix E's Error
  column, which fixes the dissertation's predicted apogee of every Yuma round. V_tangent of
  eq 5.8 climbs at the corrected elevation; beta of eq 6.11 at the gun's 85 deg; tau at the
  corrected elevation; (Vrel/V)^2 of eq 5.3 with the launch velocity; the decay carries
  cos mu (Vrel/V)^2. Cd0 A is the one value that reproduces the Error column
  (:func:`fit_drag_area_to_errors`), used unchanged at Barbados as the text says. It is the
  default because Figs 6.5 and 6.6 and the text's statistics are this model's results: a
  reproduction draws what the dissertation computed, and the other models are compared with it.
  Every other reading of the three choices that set its predictions (eq 5.8's sine, tau's
  elevation, eq 5.3's V), each fitted to the same column, and which of them Appendix E tells
  apart: :mod:`.identification`.
- ``"consistent"``: the project's reading (eqs 5.8 and 6.11-6.15 as printed, the decay made
  consistent with eq 3.23), Cd0 A from Appendix D's Beta column read as eq 6.11 at the launch
  elevation of the same model.
- ``"printed_columns"``: what the appendices' corrected columns describe (no V_tangent, eq 6.14
  as printed), Cd0 A from Appendix D's Beta column likewise.

Residuals are measured minus predicted apogee, Appendix E's sign convention.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from typing import overload

import numpy as np
import pandas as pd
from scipy.optimize import brentq, minimize_scalar

from ...engines import eci
from ...foundation import earth
from ...foundation.caching import cached_copies
from ...foundation.validation import Bounds, check_choice, probability, real_number
from ...models.atmosphere import SOUND_SQUARED_PER_KELVIN
from ...models.drag import ExponentialDragLaw
from ...models.launch import Launch, Launches
from ...models.projectiles import Projectile
from ...models.sites import LaunchSite, get_site
from .appendices import FOOT_M, MUZZLE_SPEEDS_FILE, HarpDataError, load_appendix, load_muzzle_speeds

__all__ = [
    "gun_launch",
    "round_corrections",
    "SPEED_STEP_FT_S",
    "PRINT_HALF_UNITS",
    "recover_muzzle_speeds",
    "appendix_rounds",
    "launch_corrections",
    "drag_area_m2",
    "fitted_site",
    "fit_drag_area_to_errors",
    "beta_column_drag_area",
    "drag_area_table",
    "speed_of_sound",
    "martlet",
    "air_temperature_k",
    "predicted_apogees",
    "appendix_columns",
    "column_agreement",
    "residual_statistic",
    "residual_table",
    "error_column_misfit_km",
    "drag_transfer_gap",
]

#: The resolution of the HARP muzzle-speed records (ft/s).
SPEED_STEP_FT_S = 10.0
#: Half a unit of the last printed digit of each derived column, in the loaded SI units.
PRINT_HALF_UNITS = {
    "mach": 0.005,
    "misalignment_angle_rad": math.radians(0.005),
    "tangent_speed_m_s": 5.0,
    "corrected_elevation_rad": math.radians(0.005),
    "corrected_speed_m_s": 5.0,
    "corrected_azimuth_rad": math.radians(0.005),
    "beta": 0.005,
    "initial_angular_momentum_m2_s": 5e3,
    "apogee_error_m": 5.0,
    "delta_apogee_m": 5.0,
}
_SPEED_HALF_UNIT_M_S = 5.0  # the appendices print Vo to 0.01 km/s
_TOLERANCE_KM = 0.02  # the Cd0 A interval of Appendix E's Error column: every round this close


@overload
def gun_launch(site: str | LaunchSite, projectile: Projectile, speed_m_s: float) -> Launch: ...
@overload
def gun_launch(
    site: str | LaunchSite, projectile: Projectile, speed_m_s: np.ndarray
) -> Launches: ...
def gun_launch(site, projectile, speed_m_s):
    """``projectile`` fired at ``speed_m_s`` (m/s; an array: one launch each) from ``site``'s
    gun as Chapter 6 lays it: 85 deg along the gun's bearing from the site's latitude, the
    Earth turning; eqs 2.1-2.2's air (the ECI MKS takes the site's, :func:`round_corrections`)."""
    site = get_site(site)
    laid = Launches(
        projectile,
        speed_m_s,
        math.degrees(site.elevation_rad),
        bearing_deg=math.degrees(site.gun_bearing_rad),
        latitude_deg=math.degrees(site.latitude_rad),
        rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
    )
    return laid if np.ndim(speed_m_s) else laid[0]


#: The projectile of :func:`round_corrections`'s launches: the Martlet 2C (Mod 2) by name only,
#: its numbers units, for none is read: each round's mass and the model's (or a fit's) Cd0 A
#: are given to the ECI correction in place of the projectile's, and the launches carry the
#: rounds' own muzzle speeds.
_MARTLET_BY_NAME = Projectile(
    "Martlet 2C (Mod 2), mass and Cd0 A given per round",
    1.0,
    1.0,
    ExponentialDragLaw(0.0, 0.0, 1.0),
    1.0,
    "Ch. 6 and Appendices D-E: each round's mass, each model's Cd0 A",
)


def round_corrections(
    site: str | LaunchSite,
    speed_m_s,
    mass_kg,
    drag_area_m2,
    model: str | eci.EciModel = "dissertation",
    surface_density_kg_m3=None,
) -> eci.LaunchCorrection:
    """The ECI corrections (:func:`~harp_analysis.engines.eci.correction_for_launch`, under
    ``model``) of Martlet rounds fired from ``site``'s gun (:func:`gun_launch`) at ``speed_m_s``
    (m/s), each of ``mass_kg`` with Cd0 A ``drag_area_m2`` (m^2), in the site's air or at
    ``surface_density_kg_m3``: numbers or 1-D arrays, one per round, broadcasting together."""
    site = get_site(site)
    if surface_density_kg_m3 is None:
        surface_density_kg_m3 = site.surface_density_kg_m3
    speed, mass, area, density = np.broadcast_arrays(
        speed_m_s, mass_kg, drag_area_m2, surface_density_kg_m3
    )
    return eci.correction_for_launch(
        gun_launch(site, _MARTLET_BY_NAME, speed),
        model,
        mass_kg=mass,
        drag_area_m2=area,
        surface_density_kg_m3=density,
    )


def _distinct(table):
    return table[~table.duplicate_of_earlier_row].reset_index(drop=True)


# --- muzzle speeds -------------------------------------------------------------------------------
def recover_muzzle_speeds(site: str | LaunchSite) -> pd.DataFrame:
    """Each distinct round's muzzle speed, recovered from its printed columns.

    Candidates are the whole multiples of :data:`SPEED_STEP_FT_S` inside the printed Vo's rounding
    interval (+- 0.005 km/s); each is launched through the rotating-Earth correction
    (Vrel + omega x r0, which mu depends on and the drag does not) and the one whose mu lies
    closest to the printed mu is kept. Returns ``round_number``, ``speed_ft_s``,
    ``muzzle_speed_m_s``, ``mu_misfit`` (its |mu - printed| in half-units of the last printed
    digit) and ``runner_up_misfit`` (the next candidate's): a kept misfit <= 1 and a runner-up
    > 1 make the speed unique."""
    site = get_site(site)
    rounds = _distinct(load_appendix(site))
    half_unit = PRINT_HALF_UNITS["misalignment_angle_rad"]
    rows = []
    for row in rounds.itertuples():
        low = math.ceil((row.muzzle_speed_m_s - 5.0) / FOOT_M / SPEED_STEP_FT_S)
        high = math.floor((row.muzzle_speed_m_s + 5.0) / FOOT_M / SPEED_STEP_FT_S)
        candidates_ft_s = np.arange(low, high + 1) * SPEED_STEP_FT_S
        launch = round_corrections(site, candidates_ft_s * FOOT_M, row.mass_kg, 0.0, eci.CONSISTENT)
        misfit = np.abs(launch.misalignment_rad - row.misalignment_angle_rad) / half_unit
        order = np.argsort(misfit)
        rows.append(
            (row.round_number, candidates_ft_s[order[0]], misfit[order[0]], misfit[order[1]])
        )
    frame = pd.DataFrame(
        rows, columns=["round_number", "speed_ft_s", "mu_misfit", "runner_up_misfit"]
    )
    frame.insert(2, "muzzle_speed_m_s", frame.speed_ft_s * FOOT_M)
    return frame


@cached_copies
def _appendix_rounds(site: LaunchSite) -> pd.DataFrame:
    table = load_appendix(site)
    speeds = load_muzzle_speeds(site)
    exact = dict(zip(speeds.round_number, speeds.muzzle_speed_m_s))
    missing = sorted(set(table.round_number) - set(exact))
    if missing:
        raise ValueError(f"no recovered muzzle speed for {site.key} rounds {missing}")
    recovered = table.round_number.map(exact)
    wrong = (recovered - table.muzzle_speed_m_s).abs() > _SPEED_HALF_UNIT_M_S * (1 + 1e-9)
    if wrong.any():
        row = table[wrong].iloc[0]
        raise HarpDataError(
            f"{MUZZLE_SPEEDS_FILE}: {site.key} round {row.round_number}'s "
            f"{recovered[wrong].iloc[0] / FOOT_M:g} ft/s does not round to the "
            f"{row.muzzle_speed_m_s / 1e3:.2f} km/s of the appendix's line {row.source_line} "
            "(a speed in the wrong unit, or another round's?)"
        )
    return table.assign(
        printed_muzzle_speed_m_s=table.muzzle_speed_m_s,
        muzzle_speed_m_s=recovered,
    )


def appendix_rounds(site: str | LaunchSite) -> pd.DataFrame:
    """The appendix of ``site`` as printed (every row,
    :func:`~harp_analysis.analyses.harp.appendices.load_appendix`), with ``muzzle_speed_m_s`` the
    recovered exact speed and ``printed_muzzle_speed_m_s`` the printed one. A copy: editing it
    changes nothing else."""
    return _appendix_rounds(get_site(site))


def launch_corrections(
    site: str | LaunchSite,
    model: str | eci.EciModel = "dissertation",
    drag_area: float | None = None,
) -> eci.LaunchCorrection:
    """The launch correction of every printed row of ``site`` under ``model`` with its own
    Cd0 A (or ``drag_area``)."""
    site = get_site(site)
    model = eci.get_model(model)
    rounds = appendix_rounds(site)
    area = _check_drag_area(drag_area)
    area = drag_area_m2(model.name) if area is None else area
    return round_corrections(
        site, rounds.muzzle_speed_m_s.to_numpy(), rounds.mass_kg.to_numpy(), area, model
    )


def _check_drag_area(drag_area) -> float | None:
    """``drag_area`` (Cd0 A, m^2) as a float > 0, or None (the model's own)."""
    if drag_area is None:
        return None
    return Bounds(low=0.0, low_inclusive=False, unit="m^2").check(
        real_number(drag_area, "drag_area"), "drag_area"
    )


# --- drag area -----------------------------------------------------------------------------------
def beta_column_drag_area(
    site: str | LaunchSite, model: str | eci.EciModel = "dissertation"
) -> tuple[float, float, float]:
    """Cd0 A (m^2) from ``site``'s printed Beta column read as ``model`` reads it: (central,
    lowest, highest value every printed Beta allows). The central value is the middle of that
    interval, so every printed Beta rounds back; when no single Cd0 A does, it is the least-squares
    value and the bounds are NaN."""
    site, model = get_site(site), eci.get_model(model)
    rounds = _distinct(appendix_rounds(site))
    printed = rounds.beta.to_numpy()

    def beta_per_area(area):
        """beta column / Cd0 A: constant, except through V_tangent's turn of the elevation."""
        return (
            round_corrections(
                site, rounds.muzzle_speed_m_s.to_numpy(), rounds.mass_kg.to_numpy(), area, model
            ).beta_column
            / area
        )

    def solve(target):  # the Cd0 A that gives each row ``target``, by fixed-point iteration
        area = target / beta_per_area(np.full_like(target, 2.8e-3))
        for _ in range(50):
            area, previous = target / beta_per_area(area), area
            if np.max(np.abs(area - previous)) < 1e-15:
                break
        return area

    half = PRINT_HALF_UNITS["beta"]
    low, high = float(np.max(solve(printed - half))), float(np.min(solve(printed + half)))
    if low <= high:
        return (low + high) / 2, low, high
    best = minimize_scalar(
        lambda a: np.sum((a * beta_per_area(a) - printed) ** 2),
        bounds=(1e-4, 1e-2),
        method="bounded",
        options={"xatol": 1e-12},
    ).x
    return float(best), math.nan, math.nan


def _yuma_error_misfit_m(drag_area, model):
    predicted = predicted_apogees("yuma", model, drag_area)
    return (predicted.residual_m - predicted.printed_error_m).to_numpy()


@cache
def fit_drag_area_to_errors(
    model: str | eci.EciModel = "dissertation",
) -> tuple[float, float, float]:
    """Cd0 A (m^2) that Appendix E's Error column implies through ``model`` (the dissertation
    model's own, or any other reading of the open choices, :mod:`.identification`):
    (least squares, lowest, highest value keeping every Yuma round within 0.02 km; NaN bounds
    when no Cd0 A does)."""
    model = eci.get_model(model)
    best = minimize_scalar(
        lambda area: np.sum(_yuma_error_misfit_m(area, model) ** 2),
        bounds=(2.0e-3, 4.0e-3),
        method="bounded",
        options={"xatol": 1e-11},
    ).x

    def margin(area):
        return np.max(np.abs(_yuma_error_misfit_m(area, model))) - _TOLERANCE_KM * 1e3

    if margin(best) > 0:
        return float(best), math.nan, math.nan
    step = 1e-5 * best
    return (
        float(best),
        brentq(margin, best - 100 * step, best, xtol=1e-12),
        brentq(margin, best, best + 100 * step, xtol=1e-12),
    )


def drag_area_m2(model: str | eci.EciModel = "dissertation") -> float:
    """The Martlet's Cd0 A (m^2) each model predicts with (module docstring): the dissertation
    model's from Appendix E's Error column, the others' from Appendix D's Beta column."""
    return _drag_area_m2(eci.get_model(model).name)


def fitted_site(model: str | eci.EciModel = "dissertation") -> str | None:
    """The site whose apogees ``model``'s drag area was fitted to, whose residual statistics
    are then recovered, not predicted: Yuma for the dissertation model (Appendix E's Error
    column), none for the others (Appendix D's Beta column, not an apogee)."""
    return "yuma" if eci.get_model(model).name == "dissertation" else None


@cache
def _drag_area_m2(model: str) -> float:
    if model == "dissertation":
        return fit_drag_area_to_errors()[0]
    return beta_column_drag_area("barbados", model)[0]


def drag_area_table() -> pd.DataFrame:
    """Cd0 A (m^2) per question: each site's Beta column under each model's reading (central
    value and interval), and the Error column under the dissertation model (least squares and
    the interval keeping every round within 0.02 km)."""
    rows = {}
    for model in eci.MODELS:
        for site in ("barbados", "yuma"):
            rows[f"{site} Beta column, {model}"] = beta_column_drag_area(site, model)
    rows["yuma Error column, dissertation"] = fit_drag_area_to_errors()
    return pd.DataFrame(rows, index=["fitted", "low", "high"]).T


def martlet(
    mass_kg: float,
    launch_speed_m_s: float,
    model: str = "dissertation",
    drag_area: float | None = None,
) -> Projectile:
    """A Martlet 2C (Mod 2) round as Chapter 6 flies it, for the simulations: a point mass of
    ``mass_kg`` with ``model``'s constant drag area Cd0 A (:func:`drag_area_m2`), or
    ``drag_area`` (m^2), the MKS's assumption. The text gives neither the Martlet's reference
    area nor how its drag changes with Mach; only the product Cd0 A enters a flight whose Cd is
    constant, so the reference area is Cd0 A and Cd is 1."""
    own = drag_area is None
    return Projectile(
        f"Martlet 2C (Mod 2), {mass_kg:.4g} kg",
        mass_kg,
        drag_area_m2(model) if drag_area is None else drag_area,
        ExponentialDragLaw(0.0, 0.0, 1.0),
        launch_speed_m_s,
        "Ch. 6 and Appendices D-E: "
        + (f"the {model} model's Cd0 A" if own else "a given Cd0 A")
        + ", constant",
    )


def speed_of_sound(site: str | LaunchSite) -> tuple[float, float, float]:
    """The speed of sound a (m/s) behind the Mach column, Mach = Vo/a with the exact speeds:
    (central, lowest, highest a every printed Mach allows). The central value is the middle of
    that interval in 1/a (the least-squares value when the interval is empty): a least-squares
    fit can fall outside it, where some printed Mach would not round back."""
    rounds = _distinct(appendix_rounds(site))
    speed, mach = rounds.muzzle_speed_m_s.to_numpy(), rounds.mach.to_numpy()
    half = PRINT_HALF_UNITS["mach"]
    low, high = float(np.max(speed / (mach + half))), float(np.min(speed / (mach - half)))
    if low > high:
        return float(speed @ speed / (mach @ speed)), math.nan, math.nan
    return 2 / (1 / low + 1 / high), low, high


def air_temperature_k(speed_of_sound_m_s: float) -> float:
    """The air temperature (K) of dry air with this speed of sound, a^2 / (gamma R)."""
    return speed_of_sound_m_s**2 / SOUND_SQUARED_PER_KELVIN


# --- apogees -------------------------------------------------------------------------------------
@cached_copies
def _predicted(site, model, drag_area):
    table = appendix_rounds(site)
    launch = launch_corrections(site, model, drag_area)
    predicted = np.atleast_1d(launch.solution(warn=False).apogee_altitude("eq_6_4"))
    frame = pd.DataFrame(
        {
            "round_number": table.round_number,
            "measured_apogee_m": table.apogee_m,
            "predicted_apogee_m": predicted,
            "residual_m": table.apogee_m - predicted,
            "duplicate_of_earlier_row": table.duplicate_of_earlier_row,
        }
    )
    if "apogee_error_m" in table:
        frame["printed_error_m"] = table.apogee_error_m
    return frame


def predicted_apogees(
    site: str | LaunchSite,
    model: str | eci.EciModel = "dissertation",
    drag_area: float | None = None,
) -> pd.DataFrame:
    """Measured and predicted apogee (eqs 6.4-6.5) of every printed row of ``site``'s appendix
    (the duplicated Barbados round 181 kept and flagged), residual = measured - predicted, and
    for Yuma the printed Error. ``model`` names one of :data:`~harp_analysis.engines.eci.MODELS` or
    is an :class:`~harp_analysis.engines.eci.EciModel`; ``drag_area`` (Cd0 A, m^2) defaults to a
    named model's own (:func:`drag_area_m2`). A copy.

    Parameters
    ----------
    site : str or LaunchSite
        "barbados" (Appendix D) or "yuma" (Appendix E), or the site.
    model : str or EciModel
        The model of the launch corrections: "dissertation", "consistent" or
        "printed_columns" (:data:`~harp_analysis.engines.eci.MODELS`), or one of your own.
    drag_area : float, optional
        Cd0 A (m^2); None for the model's own.

    Returns
    -------
    pandas.DataFrame
        One row per printed row: ``round_number``, ``measured_apogee_m``,
        ``predicted_apogee_m``, ``residual_m``, ``duplicate_of_earlier_row`` and, for Yuma,
        ``printed_error_m``.
    """
    return _predicted(get_site(site), eci.get_model(model), _check_drag_area(drag_area))


def residual_statistic(
    site: str | LaunchSite,
    statistic: str = "mean",
    include_duplicate: bool = True,
    model: str = "dissertation",
) -> float:
    """Mean, its magnitude ("abs_mean") or sample standard deviation ("std") in km of the
    apogee residuals of ``site`` under ``model``."""
    check_choice(statistic, "statistic", ("mean", "abs_mean", "std"))
    frame = predicted_apogees(site, model)
    if not include_duplicate:
        frame = frame[~frame.duplicate_of_earlier_row]
    residual = frame.residual_m / 1e3
    if statistic == "std":
        return float(residual.std(ddof=1))
    return float(abs(residual.mean()) if statistic == "abs_mean" else residual.mean())


def residual_table() -> pd.DataFrame:
    """Residual mean and sample standard deviation (km) for each model and site, over every
    printed row and over the distinct rounds (Barbados' round 181 once), with each model's
    Cd0 A."""
    rows = []
    for model in eci.MODELS:
        for site in ("barbados", "yuma"):
            for include in (True, False):
                rows.append(
                    {
                        "model": model,
                        "site": site,
                        "rows": "all printed" if include else "distinct rounds",
                        "mean_km": residual_statistic(site, "mean", include, model),
                        "std_km": residual_statistic(site, "std", include, model),
                        "drag_area_m2": drag_area_m2(model),
                    }
                )
    return pd.DataFrame(rows)


def error_column_misfit_km() -> float:
    """Largest |recomputed - printed| Error (km) of Appendix E's 22 rounds, dissertation model."""
    frame = predicted_apogees("yuma", "dissertation")
    return float(np.max(np.abs(frame.residual_m - frame.printed_error_m))) / 1e3


def drag_transfer_gap() -> float:
    """How far (relative) the Cd0 A behind Appendix E's errors lies outside the interval that
    Appendix D's Beta column allows under the same (dissertation) reading; 0 if inside."""
    used = drag_area_m2("dissertation")
    _, low, high = beta_column_drag_area("barbados", "dissertation")
    return max(low / used - 1.0, used / high - 1.0, 0.0)


# --- the appendices' derived columns -------------------------------------------------------------
def appendix_columns(site: str | LaunchSite, model: str = "dissertation") -> pd.DataFrame:
    """The derived columns of Appendix D or E recomputed from each round's mass and exact
    muzzle speed and the site under ``model`` (its own Cd0 A), named as the loaded appendix,
    one row per distinct round in printed order: Mach (with the site's fitted speed of sound),
    mu, V tangent, the corrected elevation, speed and azimuth of Vrel + omega x r0, Beta as the
    model reads the column, Li (eq 6.13 of the corrected velocity) and, for Yuma, Error and
    delta apogee (measured - predicted)."""
    site = get_site(site)
    rounds = _distinct(appendix_rounds(site))
    launch = launch_corrections(site, model)
    distinct = ~appendix_rounds(site).duplicate_of_earlier_row.to_numpy()
    columns = {
        "round_number": rounds.round_number,
        "mach": rounds.muzzle_speed_m_s / speed_of_sound(site)[0],
        "misalignment_angle_rad": launch.misalignment_rad[distinct],
        "tangent_speed_m_s": launch.tangent_speed_m_s[distinct],
        "corrected_elevation_rad": launch.corrected_elevation_rad[distinct],
        "corrected_speed_m_s": launch.corrected_speed_m_s[distinct],
        "corrected_azimuth_rad": launch.corrected_azimuth_rad[distinct],
        "beta": launch.beta_column[distinct],
        "initial_angular_momentum_m2_s": eci.initial_angular_momentum(
            launch.corrected_speed_m_s, launch.corrected_elevation_rad
        )[distinct],
    }
    if "apogee_error_m" in rounds:
        residual = predicted_apogees(site, model).residual_m.to_numpy()[distinct]
        columns |= {"apogee_error_m": residual, "delta_apogee_m": residual}
    return pd.DataFrame(columns)


def column_agreement(site: str | LaunchSite, model: str = "dissertation") -> pd.DataFrame:
    """Per derived column: the largest |computed - printed| in half-units of the last printed
    digit (<= 1 is within print rounding), the round where it occurs, and how many rounds lie
    within print rounding."""
    site = get_site(site)
    printed = _distinct(appendix_rounds(site))
    computed = appendix_columns(site, model)
    rows = {}
    for column in computed.columns.drop("round_number"):
        misfit = np.abs(computed[column] - printed[column]).to_numpy() / PRINT_HALF_UNITS[column]
        worst = int(np.argmax(misfit))
        rows[column] = {
            "worst_half_units": misfit[worst],
            "worst_round": int(printed.round_number[worst]),
            "rounds_within": int(np.sum(misfit <= 1.0)),
            "rounds": len(misfit),
        }
    return pd.DataFrame(rows).T


# --- Further Chapter 5-6 statements (the sweep's rows) --------------------------------------------
__all__ += [
    "round_count",
    "site_difference_p_value",
    "site_equivalence_p_value",
    "SiteDifference",
    "site_mean_difference",
    "bearing_from_east_deg",
    "mach_column_temperature_difference_k",
]


def round_count(site: str | LaunchSite, distinct: bool = True) -> int:
    """Rounds in ``site``'s appendix: distinct round numbers, or every printed row."""
    table = appendix_rounds(site)
    return int(len(_distinct(table)) if distinct else len(table))


def _site_samples(quantity: str, model: str) -> list[np.ndarray]:
    """Barbados' and Yuma's distinct rounds: apogee residuals under ``model`` (m) or recovered
    muzzle speeds (m/s)."""
    check_choice(quantity, "quantity", ("residual", "muzzle_speed"))
    samples = []
    for site in ("barbados", "yuma"):
        if quantity == "residual":
            frame = predicted_apogees(site, model)
            samples.append(frame.residual_m[~frame.duplicate_of_earlier_row].to_numpy())
        else:
            samples.append(_distinct(appendix_rounds(site)).muzzle_speed_m_s.to_numpy())
    return samples


def site_difference_p_value(quantity: str = "residual", model: str = "dissertation") -> float:
    """Two-sided p-value of Welch's t-test that the Barbados and Yuma means are equal, over the
    distinct rounds: the apogee residuals under ``model`` (``quantity="residual"``) or the
    recovered muzzle speeds (``"muzzle_speed"``). A small value says the sites differ; a large
    one does not say they agree (:func:`site_equivalence_p_value` does)."""
    from scipy.stats import ttest_ind

    return float(ttest_ind(*_site_samples(quantity, model), equal_var=False).pvalue)


def site_equivalence_p_value(
    quantity: str = "residual",
    *,
    margin: float,
    relative: bool = False,
    model: str = "dissertation",
) -> float:
    """p-value of the two one-sided Welch tests (TOST) that the Barbados and Yuma means differ
    by less than ``margin`` (m or m/s; a share of the two sites' mean if ``relative``): the
    larger of the p-values against a difference of -margin and of +margin. A small value shows
    the sites equivalent within the margin, which no test of a difference can."""
    from scipy.stats import ttest_ind

    barbados, yuma = _site_samples(quantity, model)
    width = Bounds(low=0.0, low_inclusive=False).check(real_number(margin, "margin"), "margin")
    if relative:
        width *= abs(np.mean(np.concatenate([barbados, yuma])))
    above = ttest_ind(barbados + width, yuma, equal_var=False, alternative="greater").pvalue
    below = ttest_ind(barbados - width, yuma, equal_var=False, alternative="less").pvalue
    return float(max(above, below))


@dataclass(frozen=True)
class SiteDifference:
    """Yuma's mean minus Barbados', over the distinct rounds, with its Welch interval
    (:func:`site_mean_difference`); in m, m/s, or a share of the two sites' mean."""

    estimate: float
    low: float
    high: float
    confidence: float
    barbados_mean: float
    barbados_std: float
    yuma_mean: float
    yuma_std: float
    barbados_rounds: int
    yuma_rounds: int


def site_mean_difference(
    quantity: str = "residual",
    *,
    relative: bool = False,
    model: str = "dissertation",
    confidence: float = 0.90,
) -> SiteDifference:
    """Yuma's mean minus Barbados' of the apogee residuals under ``model`` (m) or the recovered
    muzzle speeds (m/s), over the distinct rounds, with its ``confidence`` interval by Welch's t
    (unequal variances); a share of the two sites' mean if ``relative``. The 90 % interval is
    the two one-sided tests' at the 5 % level: the sites are shown equivalent within a margin
    exactly when it lies inside +-margin (:func:`site_equivalence_p_value`), shown to differ by
    more when it lies outside, and neither when it straddles the margin."""
    from scipy.stats import ttest_ind

    barbados, yuma = _site_samples(quantity, model)
    level = probability(confidence, "confidence")
    interval = ttest_ind(yuma, barbados, equal_var=False).confidence_interval(level)
    unit = float(abs(np.mean(np.concatenate([barbados, yuma])))) if relative else 1.0
    return SiteDifference(
        float(np.mean(yuma) - np.mean(barbados)) / unit,
        float(interval.low) / unit,
        float(interval.high) / unit,
        level,
        float(np.mean(barbados)),
        float(np.std(barbados, ddof=1)),
        float(np.mean(yuma)),
        float(np.std(yuma, ddof=1)),
        len(barbados),
        len(yuma),
    )


def bearing_from_east_deg(site: str | None = None) -> float:
    """Angle (deg) between a site's gun bearing and due east (090T); the larger of the two
    sites' by default."""
    sites = ("barbados", "yuma") if site is None else (site,)
    return max(abs(math.degrees(get_site(s).gun_bearing_rad) - 90.0) for s in sites)


def mach_column_temperature_difference_k(site: str = "yuma", reference: str = "barbados") -> float:
    """Air temperature behind ``site``'s Mach column minus that behind ``reference``'s (K),
    each a^2 / (gamma R) of :func:`speed_of_sound`."""
    return air_temperature_k(speed_of_sound(site)[0]) - air_temperature_k(
        speed_of_sound(reference)[0]
    )
