"""Load the HARP apogee tables of Stutz (2013), Appendix D (Barbados) and E (Yuma), in SI units.

The files in ``data/harp`` keep the printed values and units; this module converts them at load
time. Column meanings, units and quirks of the tables are described in ``data/harp/README.md``.
"""

from __future__ import annotations

import hashlib
import math
from pathlib import Path
from typing import NamedTuple

import pandas as pd

from .paths import HARP_DATA_DIR
from .sites import get_site

__all__ = [
    "HarpDataError",
    "load_appendix",
    "load_barbados",
    "load_yuma",
    "load_muzzle_speeds",
    "verify_checksums",
    "MUZZLE_SPEEDS_FILE",
]

#: Derived data beside the transcription: each round's exact muzzle speed (data/harp/README.md).
MUZZLE_SPEEDS_FILE = "muzzle_speeds.tsv"
_SPEED_COLUMNS = ("site", "round", "vo_ft_s")

_KM = 1e3
_DEG = math.pi / 180
#: The international foot; the HARP records give muzzle speeds in ft/s.
FOOT_M = 0.3048


class HarpDataError(ValueError):
    """A HARP data file is malformed or does not match its recorded checksum."""


class _Column(NamedTuple):
    loaded_name: str
    scale: float | None  # factor from the file's unit to SI; None for the integer round number


# File column name -> loaded column; shared by both appendices.
_COLUMNS = {
    "round": _Column("round_number", None),
    "error_km": _Column("apogee_error_m", _KM),
    "apogee_km": _Column("apogee_m", _KM),
    "mass_kg": _Column("mass_kg", 1.0),
    "vo_km_s": _Column("muzzle_speed_m_s", _KM),
    "mach": _Column("mach", 1.0),
    "mu_deg": _Column("misalignment_angle_rad", _DEG),
    "beta": _Column("beta", 1.0),
    "v_tangent_km_s": _Column("tangent_speed_m_s", _KM),
    "corrected_elevation_deg": _Column("corrected_elevation_rad", _DEG),
    "corrected_velocity_km_s": _Column("corrected_speed_m_s", _KM),
    "corrected_azimuth_deg": _Column("corrected_azimuth_rad", _DEG),
    "li_km2_s": _Column("initial_angular_momentum_m2_s", _KM**2),
    "delta_apogee_km": _Column("delta_apogee_m", _KM),
}

# Site -> (file name, file columns in printed order).
_LAYOUTS = {
    "barbados": (
        "appendix_d_barbados.tsv",
        (
            "round",
            "apogee_km",
            "mass_kg",
            "vo_km_s",
            "mach",
            "mu_deg",
            "v_tangent_km_s",
            "corrected_elevation_deg",
            "corrected_velocity_km_s",
            "corrected_azimuth_deg",
            "beta",
            "li_km2_s",
        ),
    ),
    "yuma": (
        "appendix_e_yuma.tsv",
        (
            "round",
            "error_km",
            "apogee_km",
            "mass_kg",
            "vo_km_s",
            "mach",
            "mu_deg",
            "beta",
            "v_tangent_km_s",
            "corrected_elevation_deg",
            "corrected_velocity_km_s",
            "corrected_azimuth_deg",
            "li_km2_s",
            "delta_apogee_km",
        ),
    ),
}


def _parse_field(text: str, column: str) -> float | int:
    scale = _COLUMNS[column].scale
    if scale is None:
        return int(text)
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(text)
    return value * scale


def _read_table(path: Path, columns: tuple[str, ...]) -> tuple[list[list[float | int]], list[int]]:
    """Parse a tab-separated file with header ``columns``; '#' lines are comments."""
    rows, line_numbers, header_seen = [], [], False
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        if line.startswith("#"):
            continue
        fields = line.split("\t")
        where = f"{path} line {number}"
        if not header_seen:
            if tuple(fields) != columns:
                raise HarpDataError(
                    f"{where}: header {fields} does not match expected {list(columns)}"
                )
            header_seen = True
            continue
        if len(fields) < len(columns):
            raise HarpDataError(
                f"{where}, column {columns[len(fields)]!r}: missing field "
                f"(expected {len(columns)} fields, got {len(fields)})"
            )
        if len(fields) > len(columns):
            raise HarpDataError(
                f"{where}, column {columns[-1]!r}: extra fields after the last column "
                f"(expected {len(columns)} fields, got {len(fields)})"
            )
        row = []
        for column, text in zip(columns, fields):
            try:
                row.append(_parse_field(text, column))
            except ValueError:
                raise HarpDataError(
                    f"{where}, column {column!r}: could not parse {text!r}"
                ) from None
        rows.append(row)
        line_numbers.append(number)
    if not header_seen:
        raise HarpDataError(f"{path}: no header line")
    return rows, line_numbers


def load_appendix(site: str, path: str | Path | None = None) -> pd.DataFrame:
    """Appendix D ("barbados") or E ("yuma") as a DataFrame in SI units, rows in printed order.

    ``path`` reads another file with the same layout instead of the one in ``data/harp``.
    Besides the converted table columns the frame has ``site``, ``source_line`` (1-based line in
    the file) and ``duplicate_of_earlier_row`` (True where the round number already appeared).
    """
    launch_site = get_site(site)
    file_name, columns = _LAYOUTS[launch_site.name.lower()]
    path = Path(path) if path is not None else HARP_DATA_DIR / file_name
    rows, line_numbers = _read_table(path, columns)
    frame = pd.DataFrame(rows, columns=[_COLUMNS[c].loaded_name for c in columns])
    frame["site"] = launch_site.name
    frame["duplicate_of_earlier_row"] = frame["round_number"].duplicated()
    frame["source_line"] = line_numbers
    return frame


def load_barbados() -> pd.DataFrame:
    """Appendix D, Barbados; see :func:`load_appendix`."""
    return load_appendix("barbados")


def load_yuma() -> pd.DataFrame:
    """Appendix E, Yuma; see :func:`load_appendix`."""
    return load_appendix("yuma")


def load_muzzle_speeds(site: str, path: str | Path | None = None) -> pd.DataFrame:
    """The exact muzzle speeds of ``site``'s rounds recovered from the appendix's columns
    (derived data, ``data/harp/muzzle_speeds.tsv``; method in :func:`harp.recover_muzzle_speeds`):
    ``round_number``, ``speed_ft_s`` and ``muzzle_speed_m_s`` (x 0.3048), one row per round."""
    launch_site = get_site(site)
    path = Path(path) if path is not None else HARP_DATA_DIR / MUZZLE_SPEEDS_FILE
    rows, numbers = [], []
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        if line.startswith("#"):
            continue
        fields = line.split("\t")
        where = f"{path} line {number}"
        if len(fields) != len(_SPEED_COLUMNS):
            raise HarpDataError(
                f"{where}: expected {len(_SPEED_COLUMNS)} fields, got {len(fields)}"
            )
        if not numbers and not rows:
            if tuple(fields) != _SPEED_COLUMNS:
                raise HarpDataError(
                    f"{where}: header {fields} does not match {list(_SPEED_COLUMNS)}"
                )
            numbers.append(number)
            continue
        try:
            rows.append((fields[0], int(fields[1]), float(fields[2])))
        except ValueError:
            raise HarpDataError(f"{where}: could not parse {fields!r}") from None
        if not math.isfinite(rows[-1][2]) or rows[-1][2] <= 0:
            raise HarpDataError(f"{where}, column 'vo_ft_s': {fields[2]!r} is not a positive speed")
    frame = pd.DataFrame(rows, columns=["site", "round_number", "speed_ft_s"])
    frame = frame[frame.site == launch_site.name.lower()].drop(columns="site")
    if frame.round_number.duplicated().any():
        raise HarpDataError(f"{path}: a {launch_site.name} round is listed twice")
    frame["muzzle_speed_m_s"] = frame.speed_ft_s * FOOT_M
    return frame.reset_index(drop=True)


def verify_checksums(directory: str | Path = HARP_DATA_DIR) -> list[str]:
    """Check each file listed in ``directory/SHA256SUMS``; return the names, or raise naming one."""
    directory = Path(directory)
    names = []
    for line in (directory / "SHA256SUMS").read_text(encoding="utf-8").splitlines():
        expected, name = line.split(maxsplit=1)
        name = name.lstrip("*")
        try:
            actual = hashlib.sha256((directory / name).read_bytes()).hexdigest()
        except FileNotFoundError:
            raise HarpDataError(
                f"{name}: listed in SHA256SUMS but missing from {directory}"
            ) from None
        if actual != expected:
            raise HarpDataError(f"{name}: SHA-256 {actual} does not match SHA256SUMS ({expected})")
        names.append(name)
    return names
