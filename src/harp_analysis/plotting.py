"""Figure helpers: one house style and one deterministic way to save a figure by its number."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
from matplotlib.figure import Figure

from .registry import figure_file

__all__ = ["HOUSE_STYLE", "DPI", "new_figure", "save_figure", "save_table"]

DPI = 150
HOUSE_STYLE: dict[str, Any] = {
    "figure.figsize": (6.4, 4.4),
    "font.family": "DejaVu Sans",  # bundled with matplotlib: identical glyphs on every machine
    "font.size": 10,
    "axes.grid": True,
    "grid.alpha": 0.35,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "legend.frameon": False,
    "lines.linewidth": 1.6,
    "savefig.dpi": DPI,
    "savefig.bbox": "tight",
    "path.simplify": False,
}
# PNG metadata keys matplotlib would otherwise fill with its version string.
_NO_METADATA = {"Software": None}


def new_figure(nrows: int = 1, ncols: int = 1, **kwargs):
    """``plt.subplots`` in the house style; returns ``(fig, axes)``."""
    with plt.rc_context(HOUSE_STYLE):  # type: ignore[arg-type]  # keys checked at run time
        return plt.subplots(nrows, ncols, **kwargs)


def save_figure(fig, number: str) -> Path:
    """Save ``fig`` as dissertation figure ``number`` (e.g. ``"2.1"`` -> ``figures/fig_2_1.png``).

    The file name comes from the figure registry, so only registered figures can be saved.
    Rendered by Agg whatever the interactive backend (JupyterLab's inline one included), at a
    fixed dpi, with no software or time stamps: saving the same figure twice gives
    byte-identical files.
    """
    if not isinstance(fig, Figure):
        raise TypeError(f"fig must be a matplotlib Figure; got {type(fig).__name__}")
    path = figure_file(number)
    path.parent.mkdir(parents=True, exist_ok=True)
    with plt.rc_context(HOUSE_STYLE):  # type: ignore[arg-type]  # keys checked at run time
        fig.savefig(path, dpi=DPI, metadata=_NO_METADATA, backend="agg")
    return path


def save_table(frame, number: str, note: str = "") -> Path:
    """Save ``frame`` as dissertation table ``number`` (e.g. ``"Table 4.1"``): a Markdown table
    under the file name the registry gives, numbers to five significant figures."""
    from .registry import get_entry

    path = figure_file(number)
    header = "| | " + " | ".join(map(str, frame.columns)) + " |"
    lines = [
        f"# {number}: {get_entry(number).title}",
        "",
        note,
        "",
        header,
        "|---" * (len(frame.columns) + 1) + "|",
    ]
    for index, row in frame.iterrows():
        cells = (f"{value:.5g}" if isinstance(value, float) else str(value) for value in row)
        lines.append(f"| {index} | " + " | ".join(cells) + " |")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n")
    return path
