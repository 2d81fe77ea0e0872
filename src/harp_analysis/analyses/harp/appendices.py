"""Load the HARP apogee tables of Stutz (2013), Appendix D (Barbados) and E (Yuma), in SI units.

The files in ``data/harp`` keep the printed values and units; this module converts them at load
time. Column meanings, units and quirks of the tables are described in ``data/harp/README.md``.

Every loader checks on load, raising :class:`HarpDataError` naming the file, line and column:

- the header, the number of fields and the syntax of every number (plain decimal notation;
  ``nan``, ``inf``, ``1_000`` and surrounding spaces are refused), and that there is at least one
  data row;
- that every value lies within :data:`PLAUSIBLE_RANGES` (wide physical limits, in the file's
  printed units, so that a value typed in the wrong unit fails: an apogee in metres, a mass in
  pounds, an angle in radians, a muzzle speed in m/s in the ft/s file), and each corrected
  azimuth within :data:`AZIMUTH_TURN_DEG` of its site's gun bearing;
- the file's SHA-256 against the ``SHA256SUMS`` beside it (see :func:`load_appendix`);
  ``verify=False`` skips this check only.
"""

from __future__ import annotations

import hashlib
import math
import os
import re
from pathlib import Path
from typing import NamedTuple

import pandas as pd

from ...foundation.paths import HARP_DATA_DIR
from ...models.sites import LaunchSite, get_site

__all__ = [
    "HarpDataError",
    "load_appendix",
    "load_barbados",
    "load_yuma",
    "load_muzzle_speeds",
    "verify_checksums",
    "MUZZLE_SPEEDS_FILE",
    "PLAUSIBLE_RANGES",
    "AZIMUTH_TURN_DEG",
    "Bounds",
]

#: Derived data beside the transcription: each round's exact muzzle speed (data/harp/README.md).
MUZZLE_SPEEDS_FILE = "muzzle_speeds.tsv"
_SPEED_COLUMNS = ("site", "round", "vo_ft_s")
_CHECKSUMS_FILE = "SHA256SUMS"

_KM = 1e3
_DEG = math.pi / 180
#: The international foot; the HARP records give muzzle speeds in ft/s.
FOOT_M = 0.3048


class HarpDataError(ValueError):
    """A HARP data file is malformed or does not match its recorded checksum."""


class Bounds(NamedTuple):
    """Plausible values of one file column, in the file's printed unit."""

    low: float
    high: float
    unit: str
    reason: str
    low_inclusive: bool = False
    high_inclusive: bool = False

    def __contains__(self, value: object) -> bool:
        if not isinstance(value, float | int):
            return False
        above = value >= self.low if self.low_inclusive else value > self.low
        below = value <= self.high if self.high_inclusive else value < self.high
        return above and below

    def __str__(self) -> str:
        opening, closing = "[" if self.low_inclusive else "(", "]" if self.high_inclusive else ")"
        return f"{opening}{self.low:g}, {self.high:g}{closing} {self.unit}".rstrip()


_INF = math.inf
#: File column -> wide physical plausibility limits, in the printed unit, each with its reason.
#: Not fitted to the data: a value outside is a typo or a wrong unit, never a surprising round.
PLAUSIBLE_RANGES: dict[str, Bounds] = {
    "round": Bounds(1, _INF, "", "round numbers count from 1", low_inclusive=True),
    "error_km": Bounds(-100, 100, "km", "an apogee difference; a value in metres exceeds it"),
    "apogee_km": Bounds(10, 500, "km", "gun-launched apogees; an apogee in metres (122000) fails"),
    "mass_kg": Bounds(50, 150, "kg", "Martlet 2C rounds are ~77-85 kg; pounds (~185) fail"),
    "vo_km_s": Bounds(1, 5, "km/s", "hypersonic gun muzzle speeds; a speed in m/s or ft/s fails"),
    "mach": Bounds(1, 20, "", "supersonic: Vo's limits over a 250-350 m/s speed of sound"),
    "mu_deg": Bounds(
        1,
        30,
        "deg",
        "the Earth's rotation (0.39-0.45 km/s at both sites) turns a ~2 km/s launch by 10-15 deg; "
        "an angle in radians (< 0.53) fails",
        True,
        True,
    ),
    "beta": Bounds(0, 5, "", "a positive dimensionless drag parameter (eq. 6.11), printed ~0.2"),
    "v_tangent_km_s": Bounds(0, 6, "km/s", "a speed no larger than the launch speed", True),
    "corrected_elevation_deg": Bounds(
        10, 90, "deg", "an apogee shot's elevation (70-75 deg here); radians (< 1.6) fail", True
    ),
    "corrected_velocity_km_s": Bounds(0, 6, "km/s", "Vo plus < 0.47 km/s of Earth rotation"),
    "corrected_azimuth_deg": Bounds(0, 360, "deg", "a bearing from true north", True, True),
    "li_km2_s": Bounds(0, 40_000, "km2/s", "|V| r0 cos(phi) <= 6 km/s x 6400 km; m2/s fails"),
    "delta_apogee_km": Bounds(-100, 100, "km", "an apogee difference, as error_km"),
    "vo_ft_s": Bounds(
        3281, 16_404, "ft/s", "vo_km_s's 1-5 km/s; a HARP speed in m/s (1600-2200) or km/s fails"
    ),
}


class _Column(NamedTuple):
    loaded_name: str
    scale: float | None  # factor from the file's unit to SI; None for the integer round number


# File column name -> loaded column; shared by both appendices.
#: How far a corrected azimuth may lie from its site's gun bearing: the Earth's rotation turns
#: the bearing by about the misalignment angle (at most mu_deg's 30 deg).
AZIMUTH_TURN_DEG = 30.0


def _azimuth_bounds(site: LaunchSite) -> Bounds:
    """The corrected azimuths plausible at ``site``: a bearing in radians (0-6.3) fails."""
    bearing = math.degrees(site.gun_bearing_rad)
    return Bounds(
        bearing - AZIMUTH_TURN_DEG,
        bearing + AZIMUTH_TURN_DEG,
        "deg",
        f"within {AZIMUTH_TURN_DEG:g} deg of {site.name}'s gun bearing {bearing:g} deg true, "
        "which the Earth's rotation turns by about mu; a bearing in radians fails",
        True,
        True,
    )


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

_INTEGER = re.compile(r"[0-9]+", re.ASCII)
_DECIMAL = re.compile(r"[+-]?([0-9]+(\.[0-9]*)?|\.[0-9]+)([eE][+-]?[0-9]+)?", re.ASCII)
_SHA256 = re.compile(r"[0-9a-fA-F]{64}", re.ASCII)


# --- checksums -----------------------------------------------------------------------------------
def _read_checksums(sums_path: Path) -> dict[str, str]:
    """``SHA256SUMS`` (``sha256sum`` format) as file name -> lower-case hex digest, in file order;
    blank lines are skipped, anything else malformed raises naming the line."""
    try:
        text = sums_path.read_bytes().decode("utf-8")
    except UnicodeDecodeError:
        raise HarpDataError(f"{sums_path}: not UTF-8 text") from None
    listed: dict[str, str] = {}
    for number, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        where = f"{sums_path} line {number}"
        parts = line.split(maxsplit=1)
        if len(parts) != 2:
            raise HarpDataError(
                f"{where}: malformed line {line!r}, expected '<64 hex digits>  <file name>'"
            )
        digest, name = parts[0], parts[1].rstrip().removeprefix("*")
        if not _SHA256.fullmatch(digest):
            raise HarpDataError(
                f"{where}: {digest!r} is not a SHA-256 digest (64 hex digits, got "
                f"{len(digest)} characters)"
            )
        if not name:
            raise HarpDataError(f"{where}: malformed line {line!r}, no file name")
        if name in listed:
            raise HarpDataError(f"{where}: {name} is listed twice")
        listed[name] = digest.lower()
    return listed


def _check_digest(path: Path, data: bytes, packaged: bool) -> None:
    """Compare ``data`` (the bytes of ``path``) with its entry in ``SHA256SUMS`` beside it.

    A package file (``packaged``) must be listed; any other file is checked only if listed."""
    sums_path = path.parent / _CHECKSUMS_FILE
    opt_out = "pass verify=False to load it unchecked"
    if not sums_path.is_file():
        if packaged:
            raise HarpDataError(
                f"{path}: no {_CHECKSUMS_FILE} beside the package's data file to verify it "
                f"against (damaged install?); reinstall the package, or {opt_out}"
            )
        return
    expected = _read_checksums(sums_path).get(path.name)
    if expected is None:
        if packaged:
            raise HarpDataError(
                f"{path}: not listed in {sums_path}; add its checksum "
                f"(sha256sum {path.name} >> {_CHECKSUMS_FILE}), or {opt_out}"
            )
        return
    actual = hashlib.sha256(data).hexdigest()
    if actual != expected:
        raise HarpDataError(
            f"{path}: SHA-256 {actual} does not match {sums_path} ({expected}): the file was "
            f"edited after its checksum was recorded. If the edit is intended, record it "
            f"(cd {path.parent} && sha256sum *.tsv > {_CHECKSUMS_FILE}); otherwise restore the "
            f"file, or {opt_out}"
        )


def _read_text(path: Path, packaged: bool, verify: bool) -> str:
    """The text of ``path``, checked against its checksum first if ``verify``.

    The bytes hashed are the bytes parsed, so the check costs one SHA-256 of a few kB per load
    and no second read; no cache is needed (nor can a stale one let an edit through)."""
    data = path.read_bytes()
    if verify:
        _check_digest(path, data, packaged)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise HarpDataError(f"{path}: not UTF-8 text (byte {error.start})") from None


# --- parsing -------------------------------------------------------------------------------------
def _read_rows(path: Path, text: str, columns: tuple[str, ...]) -> list[tuple[int, list[str]]]:
    """The data rows of tab-separated ``text`` with header ``columns`` as (line number, fields);
    '#' lines are comments. Raises unless there is a header and at least one data row."""
    rows, header_seen = [], False
    for number, line in enumerate(text.splitlines(), start=1):
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
        rows.append((number, fields))
    if not header_seen:
        raise HarpDataError(f"{path}: no header line")
    if not rows:
        raise HarpDataError(f"{path}: header but no data rows")
    return rows


def _parse_number(
    text: str, column: str, where: str, plausible: Bounds | None = None
) -> float | int:
    """The value of one field in the file's unit, checked against ``plausible`` (by default
    the column's :data:`PLAUSIBLE_RANGES`)."""
    integer = column == "round"
    try:
        if not (_INTEGER if integer else _DECIMAL).fullmatch(text):
            raise ValueError(text)
        value = int(text) if integer else float(text)
    except ValueError:  # also int()'s limit on the number of digits
        raise HarpDataError(f"{where}, column {column!r}: could not parse {text!r}") from None
    plausible = plausible or PLAUSIBLE_RANGES[column]
    if not math.isfinite(value) or value not in plausible:
        raise HarpDataError(
            f"{where}, column {column!r}: {text!r} is outside the plausible range {plausible} "
            f"({plausible.reason})"
        )
    return value


def _path(path) -> Path:
    if not isinstance(path, str | os.PathLike):
        raise TypeError(f"path must be a file path (a str or a Path); got {type(path).__name__}")
    return Path(path)


def _to_si(value: float | int, column: str) -> float | int:
    scale = _COLUMNS[column].scale
    return value if scale is None else value * scale


def load_appendix(
    site: str | LaunchSite, path: str | Path | None = None, *, verify: bool = True
) -> pd.DataFrame:
    """Appendix D ("barbados") or E ("yuma") as a DataFrame in SI units, rows in printed order.

    ``path`` reads another file with the same layout instead of the one in ``data/harp``.
    Besides the converted table columns the frame has ``site``, ``source_line`` (1-based line in
    the file) and ``duplicate_of_earlier_row`` (True where the round number already appeared).

    Raises :class:`HarpDataError` naming the file, line and column for a malformed file, a file
    with no data rows or a value outside :data:`PLAUSIBLE_RANGES`. With ``verify`` (the default)
    the file's SHA-256 is checked against ``SHA256SUMS`` in its folder: the package's own file
    (``path=None``) must be listed there and match, so an edited file raises; a file of your own
    is checked only if its folder has a ``SHA256SUMS`` that lists it (as a copy of ``data/harp``
    does). ``verify=False`` skips the checksum, not the other checks.
    """
    launch_site = get_site(site)
    file_name, columns = _LAYOUTS[launch_site.key]
    packaged = path is None
    path = HARP_DATA_DIR / file_name if path is None else _path(path)
    plausible = dict(PLAUSIBLE_RANGES, corrected_azimuth_deg=_azimuth_bounds(launch_site))
    rows, line_numbers = [], []
    for number, fields in _read_rows(path, _read_text(path, packaged, verify), columns):
        where = f"{path} line {number}"
        rows.append(
            [_to_si(_parse_number(t, c, where, plausible[c]), c) for c, t in zip(columns, fields)]
        )
        line_numbers.append(number)
    frame = pd.DataFrame(rows, columns=[_COLUMNS[c].loaded_name for c in columns])
    frame["site"] = launch_site.name
    frame["duplicate_of_earlier_row"] = frame["round_number"].duplicated()
    frame["source_line"] = line_numbers
    return frame


def load_barbados(*, verify: bool = True) -> pd.DataFrame:
    """Appendix D, Barbados, as :func:`load_appendix` reads it.

    Parameters
    ----------
    verify : bool
        Check the file's SHA-256 against ``SHA256SUMS`` (the other checks are always made).

    Returns
    -------
    pandas.DataFrame
        One row per printed row in SI units, the duplicated round 181 flagged in
        ``duplicate_of_earlier_row``.
    """
    return load_appendix("barbados", verify=verify)


def load_yuma(*, verify: bool = True) -> pd.DataFrame:
    """Appendix E, Yuma; see :func:`load_appendix`."""
    return load_appendix("yuma", verify=verify)


def load_muzzle_speeds(
    site: str | LaunchSite, path: str | Path | None = None, *, verify: bool = True
) -> pd.DataFrame:
    """The exact muzzle speeds of ``site``'s rounds recovered from the appendix's columns
    (derived data, ``data/harp/muzzle_speeds.tsv``; method in
    :func:`~harp_analysis.analyses.harp.apogees.recover_muzzle_speeds`): ``round_number``,
    ``speed_ft_s`` and ``muzzle_speed_m_s`` (x 0.3048), one row per round.

    Checks as :func:`load_appendix` (``path``, ``verify``, :data:`PLAUSIBLE_RANGES`); besides, the
    ``site`` field must be a site's lower-case name, a round may appear once per site, and the
    file must hold at least one row for ``site``."""
    launch_site = get_site(site)
    packaged = path is None
    path = HARP_DATA_DIR / MUZZLE_SPEEDS_FILE if path is None else _path(path)
    rows = []
    for number, fields in _read_rows(path, _read_text(path, packaged, verify), _SPEED_COLUMNS):
        where = f"{path} line {number}"
        if fields[0] not in _LAYOUTS:
            raise HarpDataError(
                f"{where}, column 'site': {fields[0]!r} is not one of {list(_LAYOUTS)}"
            )
        rows.append(
            (
                fields[0],
                _parse_number(fields[1], "round", where),
                _parse_number(fields[2], "vo_ft_s", where),
            )
        )
    frame = pd.DataFrame(rows, columns=["site", "round_number", "speed_ft_s"])
    frame = frame[frame.site == launch_site.key].drop(columns="site")
    if frame.empty:
        raise HarpDataError(f"{path}: no rows for site {launch_site.key!r}")
    if frame.round_number.duplicated().any():
        raise HarpDataError(f"{path}: a {launch_site.name} round is listed twice")
    frame["muzzle_speed_m_s"] = frame.speed_ft_s * FOOT_M
    return frame.reset_index(drop=True)


def verify_checksums(directory: str | Path = HARP_DATA_DIR) -> list[str]:
    """Check each file listed in ``directory/SHA256SUMS``; return the names, or raise naming one.

    A malformed ``SHA256SUMS`` line (not ``<64 hex digits>  <name>``) raises naming the line."""
    directory = Path(directory)
    sums_path = directory / _CHECKSUMS_FILE
    if not sums_path.is_file():
        raise HarpDataError(f"{directory}: no {_CHECKSUMS_FILE} file")
    listed = _read_checksums(sums_path)
    if not listed:
        raise HarpDataError(f"{sums_path}: lists no files")
    for name, expected in listed.items():
        try:
            actual = hashlib.sha256((directory / name).read_bytes()).hexdigest()
        except FileNotFoundError:
            raise HarpDataError(
                f"{name}: listed in {_CHECKSUMS_FILE} but missing from {directory}"
            ) from None
        if actual != expected:
            raise HarpDataError(
                f"{name}: SHA-256 {actual} does not match {_CHECKSUMS_FILE} ({expected})"
            )
    return list(listed)
