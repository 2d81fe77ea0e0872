"""The fly-out tables' figure (X.9): reporting on :mod:`.flyout_comparison`, the fly-out table
against the calibrated MKS learned from the same 3DOF flights."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.ticker import FuncFormatter

from ...analyses.flyout_comparison import COLUMNS, GUNS, METHODS, TARGETS_M
from ..plotting import ENGINE_STYLES, FULL_WIDTH_IN, OKABE_ITO, PROJECTILE_MARKERS, new_figure

__all__ = ["METHOD_NAMES", "draw_flyout_comparison"]

#: Each method's name in the legend, its engine's label (:data:`.plotting.ENGINE_STYLES`).
METHOD_NAMES = {"calibrated_mks": "calibrated MKS", "flyout_table": "fly-out table"}
#: Each method's markers: filled for the calibrated MKS, open for the fly-out table, so that
#: they read apart without colour; the marker's shape is the projectile's.
_FILLED = {"calibrated_mks": True, "flyout_table": False}
_ROWS = (
    ("impact_rms_m", "impact point,\nRMS miss (m)"),
    ("apogee_rms_m", "apogee altitude,\nRMS error (m)"),
)


def _plain(value: float, _=None) -> str:
    return f"{value:g}"


def _twos_and_fives(value: float, _=None) -> str:
    """A minor tick's label where its leading digit is 2 or 5 (a log axis of a decade or
    less is read between its powers of ten)."""
    return _plain(value) if f"{value:e}"[0] in "25" else ""


def _look(method: str, gun: str) -> dict:
    colour = ENGINE_STYLES[METHOD_NAMES[method]]["color"]
    return {
        **ENGINE_STYLES[METHOD_NAMES[method]],
        "marker": PROJECTILE_MARKERS[GUNS[gun].projectile.name],
        "markersize": 5,
        "markerfacecolor": colour if _FILLED[method] else "white",
    }


def draw_flyout_comparison(frame: pd.DataFrame, targets_m: Sequence[float] = TARGETS_M) -> Figure:
    """Figure X.9 from :func:`.flyout_comparison.comparison`'s ``frame``: a column per gun, a
    row per error (the impact point's root-mean-square miss, the apogee altitude's), each
    against the 3DOF flights the tables learn from (log-log), both methods, a point per grid;
    in the impact row the accuracies ``targets_m`` as grey dotted lines; on top, the table's
    size (MB, the fly-out table's: 103 numbers a flight; the calibrated MKS keeps 105)."""
    if not isinstance(frame, pd.DataFrame):
        raise TypeError(f"frame must be a pandas DataFrame; got {type(frame).__name__}")
    missing = [name for name in COLUMNS if name not in frame.columns]
    if missing:
        raise ValueError(f"frame lacks the columns {missing} of flyout_comparison.comparison")
    guns = list(dict.fromkeys(frame.gun))
    fig, axes = new_figure(
        len(_ROWS),
        len(guns),
        figsize=(FULL_WIDTH_IN, 5.6),
        layout="constrained",
        sharex="col",
        squeeze=False,
    )
    table = frame[frame.method == "flyout_table"]
    per_flight = float(np.median(table.nbytes / table.flights))
    for column, gun in enumerate(guns):
        rows = frame[frame.gun == gun]
        for row, (measure, label) in enumerate(_ROWS):
            ax = axes[row, column]
            _draw_errors(ax, rows, gun, measure, targets_m)
            if column == 0:
                ax.set_ylabel(label)
            if row == len(_ROWS) - 1:
                ax.set_xlabel("3DOF flights in the table")
        top = axes[0, column].secondary_xaxis(
            "top",
            functions=(lambda f: f * per_flight / 1e6, lambda mb: mb * 1e6 / per_flight),
        )
        top.set_xlabel(f"{gun}\ntable size (MB)")
    handles = _legend_handles()
    fig.legend(handles=handles, loc="outside lower center", ncols=len(handles))
    return fig


def _draw_errors(
    ax, rows: pd.DataFrame, gun: str, measure: str, targets_m: Sequence[float]
) -> None:
    """One panel: ``gun``'s error ``measure`` of each method against the 3DOF flights its
    table learned from (``rows``, the gun's), log-log; the impact's with ``targets_m``."""
    for method in METHODS:
        mine = rows[rows.method == method].sort_values("flights")
        ax.plot(mine.flights, mine[measure], **_look(method, gun))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.yaxis.set_major_formatter(FuncFormatter(_plain))
    ax.yaxis.set_minor_formatter(FuncFormatter(_twos_and_fives))
    if measure == "impact_rms_m":
        for target in targets_m:
            ax.axhline(target, color=OKABE_ITO["grey"], linestyle=":", linewidth=1.0)


def _legend_handles() -> list[Line2D]:
    """A line per method, saying which markers are its."""
    return [
        Line2D(
            [],
            [],
            label=f"{METHOD_NAMES[method]} ({'filled' if _FILLED[method] else 'open'} markers)",
            **ENGINE_STYLES[METHOD_NAMES[method]],
        )
        for method in METHODS
    ]
