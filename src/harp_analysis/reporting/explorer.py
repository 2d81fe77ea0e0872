"""The explorer (notebook 00, and the web page of ``make explore``): one launch, set with
controls, flown by the MKS and the 3DOF at once, the 6DOF and MLT on request.

The logic lives here, the notebook only displays :class:`Explorer`: :class:`Settings` (what
the controls hold, plain numbers), :func:`launch_for` (the
:class:`~harp_analysis.models.launch.Launch` they describe, or a clear error), :func:`fly` (each
engine's trajectory, its apogee, range and time of flight, its distance from the 3DOF at the same
time, and the models' validity messages), :func:`draw` (the figure as PNG bytes) and the two HTML
views. :class:`Explorer` lays them out as ipywidgets; every control change flies the launch again
(the MKS and the 3DOF take milliseconds, drawing a tenth of a second), and bad input shows as a
message, never as a traceback. Messages name a field by its control's label and unit
(:data:`LABELS`,
:func:`in_readers_words`), never by the code's name; the models' validity warnings are all
recorded and shown, never silenced.

The 3DOF, the 6DOF and MLT are the engines of :mod:`harp_analysis.engines.catalogue`, under its
labels (the 6DOF and MLT are its engines for Appendix B's rigid bodies). The MKS here is the text's
(Chapter 5's ECI MKS where the Earth turns, its table
:func:`harp_analysis.engines.eci.simulate_eci_mks`), the improved one and the calibrated one
(:func:`harp_analysis.engines.calibrated_mks.simulate_calibrated_mks`) on request; the HARP
presets fly the Martlet as Chapter 6 models it
(:func:`harp_analysis.analyses.harp.apogees.martlet`), with Yuma's thinner air as the day's density
change.

The calibrated MKS learns a table for each gun (projectile, latitude, atmosphere, day's
temperature, turning Earth or not) from its 3DOF flights the first time it is asked for it: a
second or two on a still Earth, several on a turning one (up to half a minute on a busy
machine), said in a message while it learns. The table is kept on disk and, in the kernel,
for the last 16 guns (:func:`~harp_analysis.engines.calibrated_mks.calibration_for`): at most
about 7 MB each where the Earth turns, under 1 MB where it does not, so a page's kernel grows by
130 MB at most (measured). A launch outside the table's band is refused in the controls' words
before any table is learned (``_check_calibrated_band()``), never extrapolated.
"""

from __future__ import annotations

import html
import io
import math
import re
import warnings
from dataclasses import dataclass, replace
from functools import cache

import matplotlib
import numpy as np
import pandas as pd
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ..analyses import mks_improvement
from ..analyses.harp import apogees
from ..engines import calibrated_mks, catalogue, eci, flight_grid, mks, mks_improved
from ..foundation import earth
from ..foundation.validation import Bounds, ModelValidityWarning
from ..models.atmosphere import ATMOSPHERE_NAMES, SEA_LEVEL_DENSITY_KG_M3
from ..models.drag import ExponentialDragLaw
from ..models.launch import BOUNDS, HP_CHAPTER_2, LP_CHAPTER_2, Launch, baseline_chapter_4
from ..models.projectiles import BASELINE, HP, LP, Projectile
from ..models.sites import BARBADOS, YUMA, LaunchSite
from ..models.trajectory import launch_frame, rotate_about_axis, surface_ranges
from .plotting import HOUSE_STYLE, OKABE_ITO, style

__all__ = [
    "PROJECTILES",
    "ENGINES",
    "Settings",
    "Flown",
    "LABELS",
    "SLIDERS",
    "in_readers_words",
    "presets",
    "preset",
    "launch_for",
    "fly",
    "draw",
    "summary_html",
    "messages_html",
    "Explorer",
]

PROJECTILES = ("HP", "LP", "baseline", "Martlet", "custom")
#: The engine every other is measured against, flown always.
_REFERENCE = catalogue.get_engine("3dof")
#: The catalogue's engines for Appendix B's projectiles (HP and LP), flown on request.
_RIGID_BODY = {engine.label: engine for engine in catalogue.ENGINES.values() if engine.rigid_body}
#: The calibrated MKS's label, its engine's.
_CALIBRATED = calibrated_mks.ENGINE
#: The engines in the order they are drawn: the 3DOF and the MKS always, the rest on request. The
#: MKS is the text's, the improved MKS Chapter 7 C's (:mod:`.mks_improved`, sampled here) and the
#: calibrated MKS the text's corrected by a table learned from the gun's 3DOF flights
#: (:mod:`.calibrated_mks`); the others are the catalogue's, under its labels.
ENGINES = (_REFERENCE.label, "MKS", "improved MKS", _CALIBRATED, *_RIGID_BODY)
#: The other views of the same launch, by the checkbox (:class:`Settings` field) that asks for
#: each.
_VIEWS = {"improved_mks": "improved MKS", "calibrated_mks": _CALIBRATED}
#: Beyond this beta no MKS is shown: the three-term series of its driving function at launch,
#: e^{-2 beta} (eq 3.30), is then 1 against 0.135 (at the text's 0.25, 3 % off).
MKS_SHOWN_BETA = 1.0
#: The atmosphere models as the control names them.
ATMOSPHERE_LABELS = {
    "us1976": "1976 US standard",
    "two_segment": "eqs 2.1-2.2 (Ch. 2)",
    "three_layer": "three layers (App. A)",
    "exponential": "eq 3.11, k = 0.117/km",
    "vacuum": "vacuum",
}
#: Each control's label: what the reader sees, and what every message calls the field.
LABELS = {
    "projectile": "Projectile",
    "speed_m_s": "Muzzle speed (m/s)",
    "elevation_deg": "Elevation (deg)",
    "bearing_deg": "Bearing (deg T)",
    "latitude_deg": "Latitude (deg)",
    "rotating": "The Earth turns",
    "cross_wind_m_s": "Cross wind (m/s)",
    "head_wind_m_s": "Head wind (m/s)",
    "atmosphere": "Atmosphere",
    "density_change_percent": "Day's density (%)",
    "temperature_change_k": "Day's temperature (K)",
    "spin_rad_s": "Spin (rad/s)",
    "mass_kg": "Mass (kg)",
    "diameter_m": "Diameter (m)",
    "drag_area_m2": "Cd0 A (m^2)",
    "improved_mks": "Also the improved MKS",
    "calibrated_mks": "Also the calibrated MKS",
}
#: The fields a slider moves (min, max, step); the number box beside it holds the value.
SLIDERS = {
    "speed_m_s": (200.0, 4000.0, 1.0),
    "elevation_deg": (1.0, 89.5, 0.5),
    "bearing_deg": (0.0, 359.0, 1.0),
    "latitude_deg": (-89.0, 89.0, 0.1),
    "cross_wind_m_s": (-30.0, 30.0, 0.5),
    "head_wind_m_s": (-30.0, 30.0, 0.5),
    "density_change_percent": (-20.0, 20.0, 0.5),
    "temperature_change_k": (-30.0, 30.0, 1.0),
}
#: The Launch's field behind each numeric control, and the control's unit over the field's.
_LAUNCH_FIELDS = {
    "speed_m_s": ("speed_m_s", 1.0),
    "elevation_deg": ("elevation_deg", 1.0),
    "latitude_deg": ("latitude_deg", 1.0),
    "cross_wind_m_s": ("cross_wind_m_s", 1.0),
    "head_wind_m_s": ("head_wind_m_s", 1.0),
    "density_change_percent": ("density_change_fraction", 100.0),
    "temperature_change_k": ("temperature_change_k", 1.0),
    "spin_rad_s": ("spin_rad_s", 1.0),
}
#: Code names a message may carry (the engines name the Launch's fields) and the reader's
#: words for them, with the factor from the field's unit to the control's.
_READERS_WORDS = {
    **{field: (LABELS[name], scale) for name, (field, scale) in _LAUNCH_FIELDS.items()},
    "bearing_deg": (LABELS["bearing_deg"], 1.0),
    "rotation_rate_rad_s": ("the Earth's rotation (rad/s)", 1.0),
    "atmosphere": (LABELS["atmosphere"], 1.0),
    "mass_kg": (LABELS["mass_kg"], 1.0),
    "diameter_m": (LABELS["diameter_m"], 1.0),
    "reference_area_m2": ("the reference area (m^2)", 1.0),
    "launch_speed_m_s": (LABELS["speed_m_s"], 1.0),
    "elevation_rad": (LABELS["elevation_deg"], 180.0 / math.pi),
    "theta_rad": ("the angular range (rad)", 1.0),
    "max_time_s": ("the flight's time limit (s)", 1.0),
    "h_inf": ("h∞", 1.0),
}
_CODE_NAME = re.compile(
    r"\b(launch\.|projectile\.)?(" + "|".join(_READERS_WORDS) + r")\b(?: = ([-+.\deEinfa]+))?"
)
#: Code names that are English words too ("the sensible atmosphere"): a field's name only as
#: one's (``launch.atmosphere``) or with its value.
_ALSO_WORDS = {"atmosphere"}
_NAMED = {"HP": HP, "LP": LP, "baseline": BASELINE}
_DRAW_DPI = 90
#: The 3DOF's output step (s): the distance of each MKS from it is measured at its rows.
_STEP_S = 0.5
#: A message wraps at the width of the views, long words and code included.
_WRAPPING = ' style="overflow-wrap: anywhere; white-space: normal; margin: 0.3em 0"'
#: Cd0 A is shown to four significant digits: the drag tables and the Martlet's fit hold no
#: more.
_DRAG_AREA_DIGITS = 4


@dataclass(frozen=True)
class Settings:
    """What the explorer's controls hold (SI, angles in degrees). ``mass_kg``, ``diameter_m``
    and ``drag_area_m2`` (Cd0 A) describe the Martlet (mass only) and a custom projectile;
    ``measured_apogee_m`` is a HARP round's, shown beside the engines'."""

    projectile: str = "HP"
    speed_m_s: float = HP.launch_speed_m_s
    elevation_deg: float = 50.0
    bearing_deg: float = 90.0
    latitude_deg: float = 0.0
    rotating: bool = False
    cross_wind_m_s: float = 0.0
    head_wind_m_s: float = 0.0
    atmosphere: str = "two_segment"
    density_change_percent: float = 0.0
    temperature_change_k: float = 0.0
    spin_rad_s: float = 0.0
    mass_kg: float = 80.0
    diameter_m: float = 0.1
    drag_area_m2: float = 2.5e-3
    improved_mks: bool = False
    calibrated_mks: bool = False
    measured_apogee_m: float | None = None


def _from_launch(launch: Launch, projectile: str, **extra) -> Settings:
    return Settings(
        projectile=projectile,
        speed_m_s=launch.speed_m_s,
        elevation_deg=launch.elevation_deg,
        bearing_deg=launch.bearing_deg,
        latitude_deg=launch.latitude_deg,
        rotating=launch.rotation_rate_rad_s != 0.0,
        cross_wind_m_s=launch.cross_wind_m_s,
        head_wind_m_s=launch.head_wind_m_s,
        atmosphere=launch.atmosphere,
        spin_rad_s=launch.spin_rad_s,
        mass_kg=launch.projectile.mass_kg,
        **extra,
    )


def _harp_round(site: LaunchSite, round_number: int) -> Settings:
    """A HARP round as Chapter 6 flies it: the Martlet of the round's mass and muzzle speed at
    85 deg on the site's bearing and latitude, the Earth turning, the site's surface density as
    the day's change of the 1.225 kg/m^3 sea-level air."""
    rounds = apogees.appendix_rounds(site)
    row = rounds[rounds.round_number == round_number].iloc[0]
    density_change = site.surface_density_kg_m3 / SEA_LEVEL_DENSITY_KG_M3 - 1.0
    return Settings(
        projectile="Martlet",
        speed_m_s=float(row.muzzle_speed_m_s),
        elevation_deg=math.degrees(site.elevation_rad),
        bearing_deg=math.degrees(site.gun_bearing_rad),
        latitude_deg=math.degrees(site.latitude_rad),
        rotating=True,
        density_change_percent=100.0 * density_change,
        mass_kg=float(row.mass_kg),
        measured_apogee_m=float(row.apogee_m),
    )


def presets() -> dict[str, Settings]:
    """The dissertation's cases by name: Chapter 2 A's HP and LP, Chapter 4 B's baseline cone
    at its four elevations, and every distinct HARP round of Appendices D and E."""
    cases = {
        "Chapter 2 A: HP": _from_launch(HP_CHAPTER_2, "HP"),
        "Chapter 2 A: LP": _from_launch(LP_CHAPTER_2, "LP"),
    }
    for elevation in (30.0, 45.0, 65.0, 85.0):
        cases[f"Chapter 4 B: baseline, {elevation:g} deg"] = _from_launch(
            baseline_chapter_4(elevation), "baseline"
        )
    for site in (BARBADOS, YUMA):
        rounds = apogees.appendix_rounds(site)
        for number in rounds.round_number[~rounds.duplicate_of_earlier_row]:
            name = f"HARP {site.name}: round {number}"
            cases[name] = _harp_round(site, int(number))
    return cases


def preset(name: str) -> Settings:
    """The preset called ``name`` (:func:`presets`), or a ValueError naming it and the known
    ones."""
    cases = presets()
    if name not in cases:
        raise ValueError(f"no preset is called {name!r}; the presets are: {', '.join(cases)}")
    return cases[name]


@cache
def _typical_martlet_mass_kg() -> float:
    """The median mass of the distinct Barbados rounds (Appendix D)."""
    rounds = apogees.appendix_rounds("barbados")
    return float(rounds.mass_kg[~rounds.duplicate_of_earlier_row].median())


def _positive(value, name: str, unit: str) -> float:
    return Bounds(low=0.0, low_inclusive=False, unit=unit).number(value, LABELS[name])


def _projectile(settings: Settings) -> Projectile:
    if settings.projectile in _NAMED:
        return _NAMED[settings.projectile]
    if settings.projectile not in PROJECTILES:
        raise ValueError(f"{LABELS['projectile']} must be one of {', '.join(PROJECTILES)}")
    mass = _positive(settings.mass_kg, "mass_kg", "kg")
    if settings.projectile == "Martlet":
        return apogees.martlet(mass, settings.speed_m_s)
    diameter = _positive(settings.diameter_m, "diameter_m", "m")
    drag_area = Bounds(low=0.0, unit="m^2").number(settings.drag_area_m2, LABELS["drag_area_m2"])
    area = math.pi * diameter**2 / 4
    return Projectile(
        "custom",
        mass,
        area,
        ExponentialDragLaw(0.0, 0.0, drag_area / area),  # Cd0 A / A, constant
        settings.speed_m_s,
        "the explorer's custom projectile: constant Cd0 A",
        diameter_m=diameter,
    )


def _check_controls(settings: Settings) -> None:
    """Each numeric control inside its Launch field's bounds, in the control's own unit and
    words (the day's density in percent, not the Launch's fraction)."""
    for name, (field, scale) in _LAUNCH_FIELDS.items():
        bounds = BOUNDS[field]
        in_control_unit = replace(bounds, low=bounds.low * scale, high=bounds.high * scale)
        in_control_unit.number(getattr(settings, name), LABELS[name])
    Bounds().number(settings.bearing_deg, LABELS["bearing_deg"])  # any bearing, wrapped


def launch_for(settings: Settings) -> Launch:
    """The launch the controls describe; ValueError or TypeError naming what is wrong by the
    control's label."""
    _check_controls(settings)
    return Launch(
        _projectile(settings),
        settings.speed_m_s,
        settings.elevation_deg,
        bearing_deg=settings.bearing_deg % 360.0,
        latitude_deg=settings.latitude_deg,
        cross_wind_m_s=settings.cross_wind_m_s,
        head_wind_m_s=settings.head_wind_m_s,
        spin_rad_s=settings.spin_rad_s,
        atmosphere=settings.atmosphere,
        rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S if settings.rotating else 0.0,
        density_change_fraction=settings.density_change_percent / 100.0,
        temperature_change_k=settings.temperature_change_k,
    )


def in_readers_words(text: str) -> str:
    """``text`` with every code name of a field (``launch.cross_wind_m_s = 5``) replaced by
    the control's label and the value in the control's unit ("Cross wind (m/s)" = 5)."""

    def words(match: re.Match) -> str:
        owner, name, value = match.groups()
        label, scale = _READERS_WORDS[name]
        if value is None:
            return match.group(0) if name in _ALSO_WORDS and owner is None else f'"{label}"'
        try:
            return f'"{label}" = {float(value) * scale:g}'
        except ValueError:
            return f'"{label}" = {value}'

    return _CODE_NAME.sub(words, text)


# --- flying ---------------------------------------------------------------------------------
@dataclass
class Flown:
    """One engine's flight of the launch: its path (time, ground range, altitude; m, s), its
    apogee, range and time of flight, and its distance from the 3DOF at the same times."""

    engine: str
    path: pd.DataFrame
    apogee_m: float
    apogee_time_s: float
    range_m: float
    time_of_flight_s: float
    error_to_3dof: pd.DataFrame | None = None  # time_s, distance_m
    beta: float | None = None  # the MKS's (eq 3.22, with Chapter 5's decay scale)


def _from_table(engine: str, table: pd.DataFrame) -> Flown:
    attrs = table.attrs
    return Flown(
        engine,
        table[["time_s", "ground_range_m", "altitude_m"]].reset_index(drop=True),
        attrs["apogee_altitude_m"],
        attrs["apogee_time_s"],
        attrs["range_m"],
        attrs["time_of_flight_s"],
    )


def _eci_mks(launch: Launch, three: pd.DataFrame) -> Flown:
    """The text's MKS (the ECI MKS's table), with its distance from the 3DOF at its times."""
    table = eci.simulate_eci_mks(launch)
    at_3dof = eci.simulate_eci_mks(launch, times_s=three.time_s, warn=False).iloc[:-1]
    position = ["x_m", "y_m", "z_m"]
    distance = np.linalg.norm(
        three[position].to_numpy()[: len(at_3dof)] - at_3dof[position].to_numpy(), axis=1
    )
    return replace(
        _from_table("MKS", table),
        error_to_3dof=pd.DataFrame({"time_s": at_3dof.time_s.to_numpy(), "distance_m": distance}),
        beta=table.attrs["beta"] * table.attrs["decay_scale"],
    )


def _improved_mks(launch: Launch, three: pd.DataFrame) -> Flown:
    """The improved MKS, sampled in time, with its distance from the 3DOF."""
    solution = mks_improved.solve(launch, mks_improvement.calibration())
    if not math.isfinite(solution.impact_time_s):
        raise ValueError("its asymptotic orbit escapes: there is no apogee or impact")
    times = np.linspace(0.0, solution.impact_time_s, 400)
    inertial = solution.positions(times)
    fixed = rotate_about_axis(inertial.T, -launch.rotation_rate_rad_s * times).T
    up, downrange = _launch_axes(launch)
    ground, _ = surface_ranges(fixed, up, downrange)
    path = pd.DataFrame(
        {
            "time_s": times,
            "ground_range_m": ground,
            "altitude_m": np.linalg.norm(inertial, axis=1) - earth.RADIUS_M,
        }
    )
    return Flown(
        "improved MKS",
        path,
        solution.apogee_altitude_m,
        solution.apogee_time_s,
        solution.impact_range_m[0],
        solution.impact_time_s,
        _distance_to_3dof(three, solution.impact_time_s, solution.positions),
        float(solution.ascent.beta[0, 0] * solution.ascent.decay_scale[0, 0]),
    )


def _calibrated_mks(launch: Launch, three: pd.DataFrame) -> Flown:
    """The calibrated MKS (its table, :func:`.calibrated_mks.simulate_calibrated_mks`), with its
    distance from the 3DOF; its gun's table learned on first use (seconds), refused first
    where it would not hold (``_check_calibrated_band()``)."""
    _check_calibrated_band(launch)
    calibration = calibrated_mks.calibration_for(launch)
    table = calibrated_mks.simulate_calibrated_mks(launch, calibration=calibration)
    solution = calibrated_mks.CalibratedSolution(launch, calibration)
    return replace(
        _from_table(_CALIBRATED, table),
        error_to_3dof=_distance_to_3dof(three, solution.time_of_flight_s, solution.positions),
    )


#: The slack :meth:`.flight_grid.Band.check` allows at the band's edges, in the band's units (a
#: speed factor, degrees, a fraction).
_BAND_SLACK = 1e-12


def _check_calibrated_band(launch: Launch) -> None:
    """A ValueError in the controls' words and units where the calibrated MKS would not hold,
    checked before its gun's table is learned (the engine learns it, seconds, before it checks
    the band): ``launch`` outside the band the table covers
    (:data:`.calibrated_mks.BAND`, checked again by the engine), or the band's longest flight
    (its fastest and steepest, on its thinnest day, eastward) not back on the ground within
    the 3DOF's time limit: the table would learn flights cut short."""
    band = calibrated_mks.BAND
    nominal = launch.projectile.launch_speed_m_s
    edges = {  # the band's edges, and their factor to the Launch field's unit
        "speed_m_s": (band.speed_factors, nominal),
        "elevation_deg": (band.elevations_deg, 1.0),
        "density_change_percent": (band.density_changes, 1.0),
    }
    for name, ((low, high), to_field) in edges.items():
        field, scale = _LAUNCH_FIELDS[name]
        inside = Bounds(
            low=(low - _BAND_SLACK) * to_field * scale,
            high=(high + _BAND_SLACK) * to_field * scale,
            unit=BOUNDS[field].unit,
        )
        try:
            inside.number(getattr(launch, field) * scale, LABELS[name])
        except ValueError as error:
            raise ValueError(
                f"outside the band of launches its table covers: {error} (a table is never "
                "extrapolated)"
            ) from None
    longest = flight_grid.Gun.of(launch).launches(
        band.speed_factors[1], band.elevations_deg[1], 90.0, band.density_changes[0]
    )[0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        flight = _REFERENCE.fly(longest, output_step_s=_STEP_S)
    if not flight.attrs["impact"]:
        raise ValueError(
            f'the longest flight of its band ("{LABELS["speed_m_s"]}" = {longest.speed_m_s:g}, '
            f'"{LABELS["elevation_deg"]}" = {band.elevations_deg[1]:g}, '
            f'"{LABELS["density_change_percent"]}" = {100 * band.density_changes[0]:g}) is not '
            f"back on the ground within the 3DOF's {flight.attrs['time_of_flight_s']:g} s: its "
            "table learns only from whole flights"
        )


def _distance_to_3dof(three: pd.DataFrame, time_of_flight_s: float, positions) -> pd.DataFrame:
    """An MKS's distance from the 3DOF (its table ``three``) at the 3DOF's times within the
    MKS's flight; ``positions`` gives the MKS's (k, 3) at times (k,), in the 3DOF's frame."""
    both = three[three.time_s <= time_of_flight_s]
    times = both.time_s.to_numpy()
    distance = np.linalg.norm(both[["x_m", "y_m", "z_m"]].to_numpy() - positions(times), axis=1)
    return pd.DataFrame({"time_s": times, "distance_m": distance})


def _launch_axes(launch: Launch) -> tuple[np.ndarray, np.ndarray]:
    up, downrange, _ = launch_frame(
        launch.latitude_rad, math.radians(launch.longitude_deg), launch.bearing_rad
    )
    return np.ravel(up), np.ravel(downrange)


def fly(launch: Launch, engines=ENGINES[:2]) -> tuple[dict[str, Flown], list[str]]:
    """Each of ``engines`` (:data:`ENGINES`; the 3DOF always, as the reference) flown on
    ``launch``, and the messages for the reader (in the controls' words): every validity
    warning the engines raise, whether the flight leaves the sensible atmosphere, and why an
    engine could not fly it."""
    flown: dict[str, Flown] = {}
    messages: list[str] = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        three = _REFERENCE.fly(launch, output_step_s=_STEP_S)
        flown[_REFERENCE.label] = _from_table(_REFERENCE.label, three)
        for engine in engines:
            if engine == _REFERENCE.label:
                continue
            if engine not in ENGINES:
                raise ValueError(f"engines must be among {', '.join(ENGINES)}; got {engine!r}")
            try:
                flown[engine] = _fly_beside_3dof(engine, launch, three)
            except (ValueError, TypeError, ArithmeticError) as error:
                messages.append(in_readers_words(f"The {engine} cannot fly this launch: {error}"))
    hidden_beta = _hide_mks_beyond_shown_beta(flown)
    _add_warnings(messages, caught, hidden_beta, calibrated_shown=_CALIBRATED in flown)
    messages += _atmosphere_messages(flown[_REFERENCE.label].apogee_m)
    return flown, messages


def _fly_beside_3dof(engine: str, launch: Launch, three: pd.DataFrame) -> Flown:
    """``engine`` (of :data:`ENGINES`, not the 3DOF) flown on ``launch``; an MKS is compared
    with the 3DOF's table ``three``."""
    if engine in _RIGID_BODY:
        return _from_table(engine, _RIGID_BODY[engine].fly(launch))
    if engine == "MKS":
        return _eci_mks(launch, three)
    if engine == _CALIBRATED:
        return _calibrated_mks(launch, three)
    return _improved_mks(launch, three)


def _hide_mks_beyond_shown_beta(flown: dict[str, Flown]) -> float | None:
    """The MKS's beta if it is beyond :data:`MKS_SHOWN_BETA`, where the MKS and the improved
    MKS are then removed from ``flown``; else None."""
    beta = flown["MKS"].beta if "MKS" in flown else None
    if beta is not None and beta > MKS_SHOWN_BETA:
        for engine in ("MKS", "improved MKS"):
            flown.pop(engine, None)
        return beta
    return None


def _add_warnings(
    messages: list[str], caught, hidden_beta: float | None, *, calibrated_shown: bool
) -> None:
    """Append to ``messages`` each of the models' own warnings ``caught`` (not numpy's
    arithmetic on the way), in the reader's words and once; where the MKS was hidden for its
    ``hidden_beta``, say why once, after its own high-drag warning if it raised one."""
    not_shown = (
        f"beyond beta = {MKS_SHOWN_BETA:g} the three-term series of the drag's driving function "
        "(eq 3.30) is off by a factor of seven or more, so no MKS is shown"
        + (
            " but the calibrated one, whose table learned what the series misses from this "
            "gun's 3DOF flights"
            if calibrated_shown
            else ""
        )
    )
    hidden = hidden_beta is not None
    for warning in caught:
        text = in_readers_words(str(warning.message))
        if hidden and issubclass(warning.category, mks.HighDragWarning):  # its beta: one message
            text, hidden = f"{text}; {not_shown}", False
        if not issubclass(warning.category, RuntimeWarning) and text not in messages:
            messages.append(text)
    if hidden:  # the MKS's beta (eq 3.22) within its limit, this one (its decay's) not
        messages.append(f"MKS beta x decay scale = {hidden_beta:.2f}: {not_shown}.")


def _atmosphere_messages(apogee_m: float) -> list[str]:
    """Why the MKS's assumptions fail for a flight whose 3DOF apogee is ``apogee_m``: it
    reaches none, or stays in the sensible atmosphere (empty when neither)."""
    if not math.isfinite(apogee_m):
        return [
            "The 3DOF reaches no apogee within its time limit: at this speed the round escapes "
            "the Earth or is still climbing; the MKS's numbers then describe an orbit, not a shot."
        ]
    if apogee_m < mks.SENSIBLE_ATMOSPHERE_M:
        return [
            f"The flight never leaves the sensible atmosphere (3DOF apogee {apogee_m / 1e3:.1f} "
            f"km, below {mks.SENSIBLE_ATMOSPHERE_M / 1e3:g} km): the MKS assumes a flight that "
            "spends most of its time above the air (Chapter 3 B)."
        ]
    return []


# --- the views ------------------------------------------------------------------------------
def draw(flown: dict[str, Flown]) -> bytes:
    """PNG of the altitude against ground range of every engine, and each MKS's distance
    from the 3DOF at the same time along the flight."""
    with matplotlib.rc_context(HOUSE_STYLE):  # type: ignore[arg-type]  # keys checked at run time
        figure = Figure(figsize=(9.0, 3.6))
        FigureCanvasAgg(figure)
        path_axes, error_axes = figure.subplots(1, 2)
        for engine in ENGINES:
            if engine not in flown:
                continue
            one = flown[engine]
            look = style(engine)
            path_axes.plot(
                one.path.ground_range_m / 1e3, one.path.altitude_m / 1e3, label=engine, **look
            )
            if one.error_to_3dof is not None:
                error_axes.plot(
                    one.error_to_3dof.time_s,
                    one.error_to_3dof.distance_m / 1e3,
                    label=f"{engine}'s distance",
                    **look,
                )
        path_axes.set_xlabel("ground range (km)")
        path_axes.set_ylabel("altitude (km)")
        path_axes.set_ylim(bottom=0.0)
        if path_axes.lines:
            path_axes.legend(loc="upper right", fontsize=8)
        else:  # a launch that cannot be flown: nothing of an earlier one stays up
            path_axes.text(
                0.5,
                0.5,
                "nothing to draw: see the messages",
                ha="center",
                transform=path_axes.transAxes,
                color=OKABE_ITO["grey"],
            )
        error_axes.set_xlabel("time (s)")
        error_axes.set_ylabel("distance from the 3DOF (km)")
        if error_axes.lines:
            error_axes.legend(loc="upper left", fontsize=8)
        else:
            error_axes.text(
                0.5,
                0.5,
                "no MKS to compare",
                ha="center",
                transform=error_axes.transAxes,
                color=OKABE_ITO["grey"],
            )
        figure.tight_layout()
        buffer = io.BytesIO()
        figure.savefig(buffer, format="png", dpi=_DRAW_DPI)
    return buffer.getvalue()


def summary_html(flown: dict[str, Flown], measured_apogee_m: float | None = None) -> str:
    """The numbers as an HTML table: apogee, its time, range and time of flight per engine
    (and a HARP round's measured apogee, as printed), to the metre and the tenth of a second."""
    rows = "".join(
        f"<tr><td>{engine}</td><td>{one.apogee_m / 1e3:.3f}</td><td>{one.apogee_time_s:.1f}</td>"
        f"<td>{one.range_m / 1e3:.3f}</td><td>{one.time_of_flight_s:.1f}</td></tr>"
        for engine in ENGINES
        if (one := flown.get(engine)) is not None
    )
    if measured_apogee_m is not None:
        rows += f"<tr><td>measured (HARP)</td><td>{measured_apogee_m / 1e3:.2f}</td>" + (
            "<td></td>" * 3 + "</tr>"
        )
    return (
        "<table><thead><tr><th>engine</th><th>apogee (km)</th><th>apogee time (s)</th>"
        "<th>range (km)</th><th>time of flight (s)</th></tr></thead>"
        f"<tbody>{rows}</tbody></table>"
    )


def messages_html(messages: list[str]) -> str:
    """The messages as an HTML list (escaped), or a note that there are none."""
    if not messages:
        return f"<p{_WRAPPING}>No validity warnings.</p>"
    items = "".join(f"<li>{html.escape(text)}</li>" for text in messages)
    return f"<ul{_WRAPPING}>{items}</ul>"


# --- the widgets ----------------------------------------------------------------------------
class Explorer:
    """The explorer's widgets (``.widget``), their controls by the :class:`Settings` field they
    set (``.controls``), and its views: ``.plot`` (an Image), ``.summary`` and ``.messages``
    (HTML). Every control flies the launch again; ``.rigid_body`` (a button) adds the 6DOF and
    MLT to the current launch. CSS classes ``harp-*`` name the parts for a browser.

    The controls hold values exactly: each field of :data:`SLIDERS` is a number box
    (``.controls``), with a slider beside it (``.sliders``) that moves it by its step. A
    browser's slider shows the box's value snapped to its step and sends that back; such an
    echo (within half a step of the box, after the slider's range clamps it) is not the
    reader's move and changes nothing, so a preset flies as named until the reader edits."""

    def __init__(self, preset_name: str = "Chapter 2 A: HP"):
        self._presets = presets()
        self.settings = preset(preset_name)
        self._holding = False
        self._rigid_body = False
        self._calibrated_gun: flight_grid.Gun | None = None  # the last the calibrated MKS flew
        self.last_flown: dict[str, Flown] = {}
        self._make_widgets(preset_name)
        self._name_parts()
        for name, slider in self.sliders.items():
            self._couple(slider, self.controls[name])
        self._show(self.settings)
        for name, control in self.controls.items():
            # another MKS is another view of the same launch, not another launch
            control.observe(self.update if name in _VIEWS else self._changed, names="value")
        self.preset.observe(self._preset_chosen, names="value")
        self.rigid_body.on_click(self._fly_rigid_body)
        self.widget = self._laid_out()
        self.update()

    def _make_widgets(self, preset_name: str) -> None:
        """The preset's dropdown, the sliders, the controls, the button and the views."""
        import ipywidgets as w

        style = {"description_width": "150px"}
        layout = dict(style=style, layout=w.Layout(width="380px"))
        self.preset = w.Dropdown(
            options=["(your own)", *self._presets],
            value=preset_name,
            description="Dissertation case",
            **layout,
        )
        self.sliders = {
            name: w.FloatSlider(
                min=low,
                max=high,
                step=step,
                description=LABELS[name],
                readout=False,
                continuous_update=True,
                style=style,
                layout=w.Layout(width="290px"),
            )
            for name, (low, high, step) in SLIDERS.items()
        }
        boxes = {name: w.FloatText(layout=w.Layout(width="86px")) for name in SLIDERS}
        self.controls = {
            "projectile": w.Dropdown(
                options=PROJECTILES, description=LABELS["projectile"], **layout
            ),
            "speed_m_s": boxes["speed_m_s"],
            "elevation_deg": boxes["elevation_deg"],
            "bearing_deg": boxes["bearing_deg"],
            "latitude_deg": boxes["latitude_deg"],
            "rotating": w.Checkbox(description=LABELS["rotating"], **layout),
            "cross_wind_m_s": boxes["cross_wind_m_s"],
            "head_wind_m_s": boxes["head_wind_m_s"],
            "atmosphere": w.Dropdown(
                options=[(ATMOSPHERE_LABELS.get(name, name), name) for name in ATMOSPHERE_NAMES],
                description=LABELS["atmosphere"],
                **layout,
            ),
            "density_change_percent": boxes["density_change_percent"],
            "temperature_change_k": boxes["temperature_change_k"],
            **{
                name: w.FloatText(description=LABELS[name], **layout)
                for name in ("spin_rad_s", "mass_kg", "diameter_m", "drag_area_m2")
            },
            **{name: w.Checkbox(description=LABELS[name], **layout) for name in _VIEWS},
        }
        self.rigid_body = w.Button(
            description=f"Fly the {' and '.join(_RIGID_BODY)} too", layout=w.Layout(width="380px")
        )
        self.plot = w.Image(format="png", layout=w.Layout(max_width="100%"))
        self.summary = w.HTML(layout=w.Layout(width="100%"))
        self.messages = w.HTML(layout=w.Layout(width="100%"))

    def _name_parts(self) -> None:
        """The CSS classes ``harp-*`` that name each widget for a browser."""
        for widget, name in (
            (self.preset, "preset"),
            (self.plot, "plot"),
            (self.summary, "summary"),
            (self.messages, "messages"),
            (self.rigid_body, "rigid-body"),
        ):
            widget.add_class(f"harp-{name}")
        for name, control in self.controls.items():
            control.add_class(f"harp-{name}")
        for name, slider in self.sliders.items():
            slider.add_class(f"harp-{name}-slider")

    def _laid_out(self):
        """The whole explorer: the controls (each slider beside its box) beside the views."""
        import ipywidgets as w

        rows = [
            w.HBox([self.sliders[name], control]) if name in self.sliders else control
            for name, control in self.controls.items()
        ]
        controls = w.VBox([self.preset, *rows, self.rigid_body])
        views = w.VBox(
            [self.plot, self.summary, self.messages],
            layout=w.Layout(flex="1 1 420px", max_width="820px", min_width="0"),
        )
        widget = w.HBox([controls, views], layout=w.Layout(flex_flow="row wrap"))
        widget.add_class("harp-explorer")
        return widget

    @staticmethod
    def _couple(slider, box) -> None:
        """The slider follows the box; a move of the slider (not its echo) sets the box."""

        def moved(change) -> None:
            held = min(max(box.value, slider.min), slider.max)
            if math.isfinite(held) and abs(change["new"] - held) <= slider.step / 2:
                return  # the box's value, snapped to the slider's step: no move
            box.value = change["new"]

        def typed(change) -> None:
            if math.isfinite(change["new"]):
                slider.value = change["new"]  # clamped to the slider's range

        slider.observe(moved, names="value")
        box.observe(typed, names="value")

    # what the controls show and hold
    def _show(self, settings: Settings) -> None:
        self._holding = True
        try:
            for name, control in self.controls.items():
                control.value = getattr(settings, name)
            custom = settings.projectile == "custom"
            self.controls["diameter_m"].disabled = not custom
            self.controls["drag_area_m2"].disabled = not custom
            self.controls["mass_kg"].disabled = settings.projectile not in ("custom", "Martlet")
            self.rigid_body.disabled = settings.projectile not in ("HP", "LP")  # Appendix B's data
        finally:
            self._holding = False

    def _describe(self, launch: Launch) -> None:
        """Fill the fields a named projectile fixes (shown greyed out) with its values: mass,
        diameter (the reference area's; 0 for the Martlet, whose the text does not give) and
        Cd0 A at the launch Mach number, to its meaningful digits. A custom projectile starts
        from them."""
        if self.settings.projectile == "custom":
            return
        projectile = launch.projectile
        diameter = projectile.diameter_m or math.sqrt(4 * projectile.reference_area_m2 / math.pi)
        drag_area = launch.launch_drag_coefficient * projectile.reference_area_m2
        self._holding = True
        try:
            self.controls["mass_kg"].value = projectile.mass_kg
            self.controls["diameter_m"].value = (
                0.0 if self.settings.projectile == "Martlet" else diameter
            )
            self.controls["drag_area_m2"].value = float(f"{drag_area:.{_DRAG_AREA_DIGITS}g}")
        finally:
            self._holding = False

    def _read(self) -> Settings:
        values = {name: control.value for name, control in self.controls.items()}
        measured = self.settings.measured_apogee_m if self.preset.value in self._presets else None
        return replace(self.settings, **values, measured_apogee_m=measured)

    def _changed(self, change) -> None:
        if self._holding:
            return
        if change["owner"] is self.controls["projectile"]:
            named = _NAMED.get(change["new"])
            if named:
                mass = named.mass_kg
            elif change["new"] == "Martlet" and change["old"] in _NAMED:
                mass = _typical_martlet_mass_kg()  # not an HP's 15.7 kg
            else:
                mass = self.settings.mass_kg
            settings = replace(self._read(), mass_kg=mass)
            if settings.diameter_m <= 0:  # from the Martlet, whose diameter the text lacks
                settings = replace(settings, diameter_m=Settings.diameter_m)
            self._show(settings)
        self._holding = True
        try:
            self.preset.value = "(your own)"  # the controls no longer show a dissertation case
        finally:
            self._holding = False
        self._rigid_body = False
        self.update()

    def _preset_chosen(self, change) -> None:
        if self._holding or change["new"] not in self._presets:
            return
        views = {name: self.controls[name].value for name in _VIEWS}  # the reader's: kept
        self.settings = replace(self._presets[change["new"]], **views)
        self._show(self.settings)
        self._rigid_body = False
        self.update()

    def _fly_rigid_body(self, _button=None) -> None:
        self._rigid_body = True
        self.update()

    def _say_what_is_learned(self, launch: Launch, engines: list[str]) -> None:
        """A message while a view learns what it needs first (seconds): the improved MKS its
        fit, once; the calibrated MKS the table of a gun other than the last one it flew. The
        message is then replaced by the flight's: it only flashes where the table is loaded
        (milliseconds, learned before) or the launch refused."""
        learning = []
        if "improved MKS" in engines and not mks_improvement.calibration.cache_info().currsize:
            learning.append(
                "Fitting the improved MKS on its training launches (once, a few seconds)."
            )
        if _CALIBRATED in engines and (gun := flight_grid.Gun.of(launch)) != self._calibrated_gun:
            flights = math.prod(axis.size for axis in flight_grid.DEFAULT_GRID.axes(gun))
            learning.append(
                f"Finding the calibrated MKS's table for this gun: learned from its {flights} "
                "3DOF flights the first time (seconds, up to half a minute where the Earth "
                "turns), kept in memory and on disk after. Another projectile (the Martlet's "
                "and a custom one's muzzle speed included), latitude, atmosphere, day's "
                "temperature, or the Earth turning or not, is another gun."
            )
        if learning:
            self.messages.value = messages_html(learning)

    def update(self, _change=None) -> None:
        """Fly the launch the controls describe and show it; a message, never a traceback."""
        self.settings = self._read()
        engines = [
            *ENGINES[:2],
            *(view for name, view in _VIEWS.items() if getattr(self.settings, name)),
        ]
        if self._rigid_body:
            engines += list(_RIGID_BODY)
        try:
            launch = launch_for(self.settings)
            self._say_what_is_learned(launch, engines)
            flown, messages = fly(launch, engines)
        except (ValueError, TypeError, ArithmeticError) as error:
            self.last_flown = {}
            self.plot.value = draw({})  # no trajectory of an earlier launch left standing
            self.summary.value = ""
            self.messages.value = messages_html([f"This launch cannot be flown: {error}"])
            return
        self._describe(launch)
        if _CALIBRATED in flown:
            self._calibrated_gun = flight_grid.Gun.of(launch)
        self.last_flown = flown
        self.plot.value = draw(flown)
        self.summary.value = summary_html(flown, self.settings.measured_apogee_m)
        self.messages.value = messages_html(messages)
