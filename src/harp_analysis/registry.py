"""The figure registry: every figure and table of the dissertation, its class and its status.

The registry is ``registry/figures.toml``; :func:`harp_analysis.gallery.render_gallery` turns it
into ``figures/README.md``. Vocabulary and rules (enforced on load, so a malformed registry fails
loudly, naming the entry):

- ``class``: how the figure can be reproduced at all (``data``, ``schematic``, ``partial``,
  ``not reproducible``), as inventoried in ``shared/FIGURES.md``;
- ``status``: where the project stands (``reproduced``: drawn, and every ledger row about it
  reproduces; ``deviates``: drawn, but a ledger row about it does not; ``partial``,
  ``pending``, ``not reproducible``); every status but ``reproduced`` needs a ``reason``;
- ``caption`` (optional): one line naming the figure's case and model variant.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from functools import cache
from pathlib import Path

from . import paths

__all__ = [
    "RegistryEntry",
    "load_registry",
    "load_toml_rows",
    "get_entry",
    "figure_file",
    "CLASSES",
    "STATUSES",
    "INDEX_FILES",
]

CLASSES = ("data", "schematic", "partial", "not reproducible")
STATUSES = ("reproduced", "deviates", "partial", "pending", "not reproducible")
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

    @property
    def label(self) -> str:
        return self.number if self.kind == "table" else f"Figure {self.number}"


def _entry(raw: dict, position: int, source: Path) -> RegistryEntry:
    where = f"{source.name} entry {position} ({raw.get('number', '?')})"
    missing = [name for name in _FIELDS if name not in raw]
    unknown = set(raw) - {*_FIELDS, "caption"}
    if unknown:
        raise ValueError(f"{where}: unknown field(s) {', '.join(sorted(unknown))}")
    if missing:
        raise ValueError(f"{where}: missing field(s) {', '.join(missing)}")
    if raw["class"] not in CLASSES:
        raise ValueError(f"{where}: class {raw['class']!r} is not one of {CLASSES}")
    if raw["status"] not in STATUSES:
        raise ValueError(f"{where}: status {raw['status']!r} is not one of {STATUSES}")
    if raw["status"] != "reproduced" and not raw["reason"].strip():
        raise ValueError(f"{where}: status {raw['status']!r} needs a reason")
    drawn = ("reproduced", "deviates", "partial")
    if raw["status"] in drawn and not (raw["notebook"] and raw["file"]):
        raise ValueError(f"{where}: a {raw['status']} entry needs its notebook and file")
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
    )


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
