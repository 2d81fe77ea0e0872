"""Single HARP rounds (Chapter 6 E, Figs 6.7-6.11): the ECI Modified Kepler trajectory of one
round as an observer on the rotating Earth sees it, the slot for its radar track, and its figure.

Trajectory. The round flies :func:`harp_analysis.engines.eci.simulate_eci_mks` from its appendix row
(mass, muzzle speed) and its site (latitude, gun bearing, 85 deg, surface density) with the
Martlet's Cd0 A of :func:`~harp_analysis.analyses.harp.apogees.drag_area_m2` and the model of
:func:`~harp_analysis.analyses.harp.apogees.predicted_apogees` (by default V_tangent included,
``decay="consistent"``), so its peak is that apogee. The MKS angular range theta is inertial: it
lies in the plane of the launch "up" and the corrected inertial azimuth (~95 deg at Barbados for the
109 deg gun). The inertial position r(theta) (cos theta up + sin theta d_azimuth) at time t(theta)
is turned into the Earth-fixed frame by a rotation of -omega t about the polar axis, and its ranges
are measured from the launch site on the Earth's surface.

Range "as measured by the radar". Ch. 6 E: "the range displayed is the relative range between
the original launch location and the current position of the projectile as is measured by the
radar". It is read here as the horizontal distance over the ground from the gun to the point
below the projectile on the rotating Earth (``radar_range_m`` = ``ground_range_m``): a slant
range could not be plotted against altitude as in Figs 6.7-6.11 (it is never below the
altitude), an inertial range would put round 181 ~157 km out instead of the text's ~40 km, and
the splash range the text compares with is a triangulated distance on the sea. A radar's
horizontal range slant x cos(elevation) in its tangent plane, (R + h) sin(theta_E), differs from
the arc R theta_E by about h theta_E: under 0.5 km at apogee, zero at the splash.

Round 181 (:func:`splash_range_km`): the Earth-fixed ground range at the MKS impact. The Earth's
rotation dominates it: the inertial arc R theta is several times the ground range, most of it
the site's own eastward travel omega R cos(lat) t during the ~320 s flight, so the range depends
strongly on how much horizontal speed the model's decay takes from the inertial angular
momentum. The ledger row ``ch6.round181.range`` gives each model's range against the text's
MKS 39.6 km and the observed splash 41.1 km (:data:`TEXT_SPLASH_RANGES_KM`).

Radar tracks are not in the dissertation (it cites the HARP reports [11, 12]). Their file schema
is in ``data/harp/radar/README.md``; :func:`load_radar_track` returns None when a round has no
file, and no values are ever invented.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd

from ...engines import eci
from ...foundation import earth
from ...foundation.paths import HARP_DATA_DIR
from ...foundation.validation import whole_number
from ...models.sites import LaunchSite, get_site
from ...models.trajectory import launch_frame, rotate_about_axis
from . import apogees
from .appendices import HarpDataError

__all__ = [
    "RADAR_DIR",
    "RADAR_NAMES",
    "TEXT_SPLASH_RANGES_KM",
    "round_row",
    "round_trajectory",
    "splash_range_km",
    "splash_error",
    "load_radar_track",
]

RADAR_DIR = HARP_DATA_DIR / "radar"
#: Ch. 6 B: the MPS-19 at the gun, the M-33 (assumed on Trinidad).
RADAR_NAMES = ("MPS-19", "M-33")
_RADAR_HEADER = ("time_s", "altitude_km", "range_km", "radar")
#: Ch. 6 E on round 181: the ECI MKS range the text computed and the triangulated splash (km).
TEXT_SPLASH_RANGES_KM = {181: {"text's MKS": 39.6, "observed splash": 41.1}}
_KM = 1e3


def round_row(site: str | LaunchSite, round_number: int):
    """The site, the round's number and its row of the appendix
    (:func:`~harp_analysis.analyses.harp.apogees.appendix_rounds`); a ValueError naming the round if
    the site's table has no such round."""
    launch_site = get_site(site)
    number = whole_number(round_number, "round_number", low=1)
    table = apogees.appendix_rounds(launch_site)
    rows = table[table.round_number == number]
    if rows.empty:
        raise ValueError(f"round {number} is not in the {launch_site.name} apogee table")
    return launch_site, number, rows.iloc[0]


def round_trajectory(
    site: str | LaunchSite,
    round_number: int,
    n_points: int = 400,
    *,
    model: str | eci.EciModel = "dissertation",
    drag_area_m2: float | None = None,
) -> pd.DataFrame:
    """The ECI MKS of ``round_number`` fired from ``site`` (its table,
    :func:`~harp_analysis.engines.eci.simulate_eci_mks`, in the site's air), launch to impact at
    ``n_points`` equal steps of angular range and the apogee: ``time_s``, ``altitude_m``,
    ``inertial_range_m`` (R theta), and on the rotating Earth ``ground_range_m`` (surface arc from
    the gun), ``downrange_m`` and ``cross_range_m`` (along and right of the gun bearing) and
    ``radar_range_m`` (= the ground range; module docstring). ``model`` and its Cd0 A (or
    ``drag_area_m2``) as in :func:`~harp_analysis.analyses.harp.apogees.predicted_apogees`, whose
    default it shares; the round flies its recovered exact muzzle speed. ValueError for a round not
    in the site's appendix."""
    launch_site, _, row = round_row(site, round_number)
    name = eci.get_model(model).name
    area = apogees.drag_area_m2(model) if drag_area_m2 is None else drag_area_m2
    speed = float(row.muzzle_speed_m_s)
    launch = apogees.gun_launch(launch_site, apogees.martlet(row.mass_kg, speed, name, area), speed)
    flight = eci.simulate_eci_mks(
        launch,
        model=model,
        n_points=n_points,
        surface_density_kg_m3=launch_site.surface_density_kg_m3,
        warn=False,
    )
    # the positions, inertial, turned into the Earth's axes at each time
    time = flight.time_s.to_numpy()
    inertial = flight[["x_m", "y_m", "z_m"]].to_numpy()
    fixed = np.column_stack(rotate_about_axis(inertial.T, -launch.rotation_rate_rad_s * time))
    up = np.ravel(launch_frame(launch_site.latitude_rad, 0.0, 0.0)[0])
    radius = flight.altitude_m.to_numpy() + earth.RADIUS_M
    ground = earth.RADIUS_M * np.arccos(np.clip(fixed @ up / radius, -1.0, 1.0))
    swept = np.arctan2(np.linalg.norm(np.cross(inertial, up), axis=1), inertial @ up)
    return pd.DataFrame(
        {
            "time_s": time,
            "altitude_m": flight.altitude_m.to_numpy(),
            "inertial_range_m": earth.RADIUS_M * swept,
            "ground_range_m": ground,
            "downrange_m": flight.ground_range_m.to_numpy(),
            "cross_range_m": flight.cross_range_m.to_numpy(),
            "radar_range_m": ground,
        }
    )


def splash_range_km(
    site: str | LaunchSite = "barbados",
    round_number: int = 181,
    model: str | eci.EciModel = "dissertation",
    drag_area_m2: float | None = None,
) -> float:
    """Ground range (km) on the rotating Earth at the MKS impact of ``round_number`` under
    ``model`` with its Cd0 A (or ``drag_area_m2``); for Barbados round 181 the text gives
    39.6 km (MKS) and 41.1 km (observed splash); module docstring."""
    trajectory = round_trajectory(site, round_number, model=model, drag_area_m2=drag_area_m2)
    return float(trajectory.ground_range_m.iloc[-1]) / _KM


def splash_error(
    round_number: int = 181, relative: bool = False, model: str = "dissertation"
) -> float:
    """Observed splash range of a Barbados round (Ch. 6 E: 41.1 km for round 181) minus the ECI
    MKS's (:func:`splash_range_km`), km, or as a share of the observed range."""
    try:
        observed = TEXT_SPLASH_RANGES_KM[round_number]["observed splash"]
    except (KeyError, TypeError):  # TypeError: an unhashable round_number
        raise ValueError(
            f"round_number {round_number!r} has no observed splash in the text; "
            f"it gives one for rounds {sorted(TEXT_SPLASH_RANGES_KM)}"
        ) from None
    error = observed - splash_range_km("barbados", round_number, model)
    return error / observed if relative else error


# --- radar tracks --------------------------------------------------------------------------------
def _radar_path(site, round_number):
    return RADAR_DIR / f"{get_site(site).key}_round_{round_number}.csv"


def _radar_field(text, column, where):
    if column == "radar":
        if text.strip() not in RADAR_NAMES:
            raise HarpDataError(f"{where}, column 'radar': {text!r} is not one of {RADAR_NAMES}")
        return text.strip()
    try:
        value = float(text)
    except ValueError:
        raise HarpDataError(f"{where}, column {column!r}: could not parse {text!r}") from None
    if not math.isfinite(value) or value < 0:
        raise HarpDataError(f"{where}, column {column!r}: {text!r} is not a finite number >= 0")
    return value


def _radar_row(fields: list[str], where: str) -> list:
    """A data line's ``fields``, one per column of the header, each parsed
    (:func:`_radar_field`)."""
    if len(fields) != len(_RADAR_HEADER):
        column = _RADAR_HEADER[min(len(fields), len(_RADAR_HEADER) - 1)]
        raise HarpDataError(
            f"{where}, column {column!r}: expected {len(_RADAR_HEADER)} fields, got {len(fields)}"
        )
    return [_radar_field(t, c, where) for c, t in zip(_RADAR_HEADER, fields)]


def _read_radar(path: Path) -> pd.DataFrame:
    rows, lines, provenance, header_seen = [], [], [], False
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        if line.startswith("#"):
            provenance.append(line[1:].strip())
            continue
        if not line.strip():
            continue
        fields = line.split(",")
        where = f"{path} line {number}"
        if not header_seen:
            if tuple(f.strip() for f in fields) != _RADAR_HEADER:
                raise HarpDataError(
                    f"{where}: header {fields} does not match {list(_RADAR_HEADER)}"
                )
            header_seen = True
            continue
        rows.append(_radar_row(fields, where))
        lines.append(number)
    if not header_seen:
        raise HarpDataError(f"{path}: no header line")
    if not any(p.lower().startswith("source:") for p in provenance):
        raise HarpDataError(f"{path}: no '# source:' provenance comment")
    frame = pd.DataFrame(rows, columns=list(_RADAR_HEADER))
    frame = pd.DataFrame(
        {
            "time_s": frame.time_s.astype(float),
            "altitude_m": frame.altitude_km.astype(float) * _KM,
            "range_m": frame.range_km.astype(float) * _KM,
            "radar": frame.radar,
            "source_line": lines,
        }
    )
    frame.attrs["provenance"] = "\n".join(provenance)
    return frame


def load_radar_track(site: str | LaunchSite, round_number: int) -> pd.DataFrame | None:
    """The radar track of ``round_number`` from ``site`` in SI (``time_s``, ``altitude_m``,
    ``range_m``, ``radar``, ``source_line``; the file's comments in ``attrs["provenance"]``),
    or None if ``data/harp/radar`` has no file for it. HarpDataError names the file, line and
    column of a malformed row."""
    path = _radar_path(site, whole_number(round_number, "round_number", low=1))
    return _read_radar(path) if path.is_file() else None
