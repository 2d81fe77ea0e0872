"""The figure registry: every figure and table of the dissertation, its class and its status.

The registry is ``registry/figures.toml``; :func:`harp_analysis.reporting.gallery.render_gallery`
turns it into ``figures/README.md``. Vocabulary and rules (enforced on load, so a malformed registry
fails loudly, naming the entry):

- ``class``: how the figure can be reproduced at all (``data``, ``schematic``, ``partial``,
  ``not reproducible``), as inventoried in ``shared/FIGURES.md``;
- ``status``: where the project stands (``reproduced``: drawn, and every ledger row about it
  reproduces; ``deviates``: drawn, but a ledger row about it does not; ``partial``,
  ``pending``, ``not reproducible``); every status but ``reproduced`` needs a ``reason``;
- ``caption`` (optional): one line naming the figure's case and model variant;
- ``no_number`` (optional): for a figure no ledger row speaks about, what the text says of it
  and that it states no number to check, so "reproduced" rests on the drawing alone by
  necessity, not by omission (:func:`harp_analysis.reporting.gallery.status_problems` asks for it on
  every reproduced figure without a row, and refuses it on one with rows);
- ``extension`` (optional, default false): the project's own figure, beyond the dissertation,
  numbered outside its numbering (``X.1``, ``X.2``, ... written ``fig_x_1.png``). There is
  nothing in the text to reproduce, so its status is ``extension`` (drawn; its ``reason`` names
  the tests that hold it) or ``pending``, never another, and it needs its caption.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from functools import cache
from pathlib import Path

from ..foundation import paths

__all__ = [
    "RegistryEntry",
    "load_registry",
    "load_toml_rows",
    "get_entry",
    "figure_file",
    "CLASSES",
    "STATUSES",
    "DRAWN",
    "EXTENSION_STATUSES",
    "INDEX_FILES",
]

CLASSES = ("data", "schematic", "partial", "not reproducible")
STATUSES = ("reproduced", "deviates", "partial", "pending", "not reproducible", "extension")
#: The statuses of a drawn figure: it has its notebook and file.
DRAWN = ("reproduced", "deviates", "partial", "extension")
#: The statuses an extension (the project's own figure) may have.
EXTENSION_STATUSES = ("extension", "pending")
#: Files in figures/ that are indexes, not figures.
INDEX_FILES = ("README.md", "CLAIMS.md")
_FIELDS = ("number", "kind", "title", "class", "notebook", "file", "status", "reason")


@dataclass(frozen=True)
class RegistryEntry:
    number: str
    kind: str
    title: str
    figure_class: str
    notebook: str
    file: str
    status: str
    reason: str
    caption: str = ""
    extension: bool = False
    no_number: str = ""  # why no ledger row speaks about it (see the module docstring)

    @property
    def label(self) -> str:
        return self.number if self.kind == "table" else f"Figure {self.number}"


def _entry(raw: dict, position: int, source: Path) -> RegistryEntry:
    where = f"{source.name} entry {position} ({raw.get('number', '?')})"
    _check_fields(raw, where)
    _check_status(raw, where)
    extension = raw.get("extension", False)
    if not isinstance(extension, bool):
        raise ValueError(f"{where}: extension must be true or false; got {extension!r}")
    if extension:
        _check_extension(raw, where)
    elif raw["status"] == "extension":
        raise ValueError(f"{where}: status 'extension' is for extension = true entries only")
    return RegistryEntry(
        raw["number"],
        raw["kind"],
        raw["title"],
        raw["class"],
        raw["notebook"],
        raw["file"],
        raw["status"],
        raw["reason"],
        raw.get("caption", ""),
        extension,
        raw.get("no_number", ""),
    )


def _check_fields(raw: dict, where: str) -> None:
    """Every field known, and the required ones there."""
    missing = [name for name in _FIELDS if name not in raw]
    unknown = set(raw) - {*_FIELDS, "caption", "extension", "no_number"}
    if unknown:
        raise ValueError(f"{where}: unknown field(s) {', '.join(sorted(unknown))}")
    if missing:
        raise ValueError(f"{where}: missing field(s) {', '.join(missing)}")


def _check_status(raw: dict, where: str) -> None:
    """The class and status of the vocabulary, a reason for every status but reproduced, and a
    drawn figure's notebook and file."""
    if raw["class"] not in CLASSES:
        raise ValueError(f"{where}: class {raw['class']!r} is not one of {CLASSES}")
    if raw["status"] not in STATUSES:
        raise ValueError(f"{where}: status {raw['status']!r} is not one of {STATUSES}")
    if raw["status"] != "reproduced" and not raw["reason"].strip():
        raise ValueError(f"{where}: status {raw['status']!r} needs a reason")
    if raw["status"] in DRAWN and not (raw["notebook"] and raw["file"]):
        raise ValueError(f"{where}: a {raw['status']} entry needs its notebook and file")


def _check_extension(raw: dict, where: str) -> None:
    """An extension: numbered X.n, its file fig_x_n, status extension or pending, a caption."""
    number = raw["number"]
    prefix, _, index = number.partition(".")
    if prefix != "X" or not index.isdigit() or index.startswith("0"):
        raise ValueError(f"{where}: an extension is numbered X.1, X.2, ...; got {number!r}")
    if raw["status"] not in EXTENSION_STATUSES:
        raise ValueError(
            f"{where}: an extension has nothing in the dissertation to reproduce; its status "
            f"is one of {EXTENSION_STATUSES}, not {raw['status']!r}"
        )
    expected = f"fig_x_{index}.png"
    if raw["file"] and raw["file"] != expected:
        raise ValueError(f"{where}: extension {number}'s file is {expected!r}; got {raw['file']!r}")
    if raw["status"] == "extension" and not raw.get("caption", "").strip():
        raise ValueError(f"{where}: a drawn extension needs its caption")


def load_toml_rows(path: Path, table: str, build, key: str) -> tuple:
    """Rows ``[[table]]`` of the TOML file ``path``, each made by ``build(raw, position,
    path)``; raises naming the file if two rows share the same ``key`` attribute."""
    with open(path, "rb") as handle:
        rows = tuple(
            build(raw, i, path)
            for i, raw in enumerate(tomllib.load(handle).get(table, []), start=1)
        )
    keys = [getattr(row, key) for row in rows]
    duplicates = sorted({k for k in keys if keys.count(k) > 1})
    if duplicates:
        raise ValueError(f"{path.name}: duplicate {key}s {duplicates}")
    return rows


@cache
def load_registry(path: Path | None = None) -> tuple[RegistryEntry, ...]:
    """All registry entries, in the dissertation's order."""
    path = Path(path) if path else paths.REGISTRY_DIR / "figures.toml"
    return load_toml_rows(path, "item", _entry, "number")


def get_entry(number: str) -> RegistryEntry:
    """The registry entry of figure ``number`` (e.g. ``"2.1"`` or ``"Table 4.1"``)."""
    for entry in load_registry():
        if entry.number == number:
            return entry
    raise ValueError(f"number {number!r} is not in the figure registry (registry/figures.toml)")


def figure_file(number: str) -> Path:
    """Where figure ``number`` is written: ``figures/`` plus the registry's file name."""
    entry = get_entry(number)
    if not entry.file:
        raise ValueError(
            f"number {number!r}: the registry gives no output file "
            f"(status {entry.status!r}: {entry.reason})"
        )
    return paths.FIGURES_DIR / entry.file
