"""The fire-control figures (X.1, X.2): reporting on :mod:`.envelope`'s miss maps; and the
calibrated MKS's roots against the ECI MKS's (:mod:`.studies.model_comparison`), drawn in
notebook 07."""

from __future__ import annotations

from typing import Any

import numpy as np
import pandas as pd
from matplotlib.lines import Line2D

from ...analyses.fire_control import envelope
from ...engines import mks
from ..plotting import FULL_WIDTH_IN, OKABE_ITO, new_figure, style

__all__ = ["MISS_CLASSES", "draw_miss_map", "draw_model_comparison"]

#: Miss classes (low, high in m, label, marker, shade): a marker and a shade of grey each
#: (darker, larger miss), so they read without colour; a decade each, metres to 100 km.
MISS_CLASSES = (
    (0.0, 10.0, "below 10 m", "o", "#F0F0F0"),
    (10.0, 100.0, "10 to 100 m", "v", "#D4D4D4"),
    (100.0, 1e3, "0.1 to 1 km", "p", "#B0B0B0"),
    (1e3, 1e4, "1 to 10 km", "s", "#8C8C8C"),
    (1e4, 1e5, "10 to 100 km", "^", "#4D4D4D"),
    (1e5, np.inf, "100 km or more", "D", OKABE_ITO["black"]),
)
#: A root the MKS claims and the 3DOF fired at it never brings to the target's altitude
#: (:data:`~harp_analysis.analyses.fire_control.envelope.NEVER_THERE`): worse than any miss, black
#: as the largest; its marker and size (a star reads small at the others' size).
NEVER_THERE_LOOK = ("*", OKABE_ITO["black"], 8.0)
_SIZE = 5.5
#: The firing elevation's contours (deg) drawn over each map.
ELEVATION_STEP_DEG = 10.0
_NONE: dict[str, Any] = dict(
    marker="x", color=OKABE_ITO["grey"], linestyle="none", markersize=3.5, mew=0.7
)


def _elevation_contours(ax, rows: pd.DataFrame) -> None:
    """Dotted, labelled contours of the root's firing elevation over the points it exists at."""
    solved = rows[np.isfinite(rows.elevation_deg)]
    if len(solved) < 3 or solved.downrange_m.nunique() < 2 or solved.altitude_m.nunique() < 2:
        return
    low, high = solved.elevation_deg.min(), solved.elevation_deg.max()
    levels = (
        np.arange(np.ceil(low / ELEVATION_STEP_DEG), np.floor(high / ELEVATION_STEP_DEG) + 1)
        * ELEVATION_STEP_DEG
    )
    if not levels.size:
        return
    lines = ax.tricontour(
        solved.downrange_m / 1e3,
        solved.altitude_m / 1e3,
        solved.elevation_deg,
        levels=levels,
        colors=OKABE_ITO["black"],
        linestyles=":",
        linewidths=0.8,
    )
    ax.clabel(lines, fmt=lambda value: f"{value:.0f}°", fontsize=6.5, inline_spacing=2)


def _marks(ax, x, y, chosen, valid, marker: str, shade: str, size: float = _SIZE) -> None:
    """The points ``chosen`` in ``marker`` and ``shade``: filled and edged in black where
    ``valid`` (beta within the MKS's validity), open in the shade where not."""
    for filled in (True, False):
        points = chosen & (valid == filled)
        ax.plot(
            x[points],
            y[points],
            marker=marker,
            linestyle="none",
            markersize=size,
            color=shade,
            mec=OKABE_ITO["black"] if filled else shade,
            mew=0.6 if filled else 1.3,
            mfc=shade if filled else "white",
        )


def draw_miss_map(maps: pd.DataFrame, bearings_deg, root: str, site: str):
    """Figures X.1 and X.2: one panel per bearing of
    :func:`~harp_analysis.analyses.fire_control.envelope.miss_map`'s rows for ``root`` ("low" or
    "high"), each intercept point marked by its outcome
    (:data:`~harp_analysis.analyses.fire_control.envelope.OUTCOMES`): the class of the 3DOF's miss
    at the MKS solution, a star where the 3DOF fired at it never reaches the target's altitude (with
    its legend entry only if a point is one), open where beta exceeds the MKS's validity, a cross
    where there is no solution; the firing elevation's contours over the points; ``site`` names the
    gun."""
    fig, axes = new_figure(
        1,
        len(bearings_deg),
        figsize=(FULL_WIDTH_IN, 3.9),
        sharex=True,
        sharey=True,
        layout="constrained",
    )
    chosen = maps[maps.root == root]
    for ax, bearing in zip(np.atleast_1d(axes), bearings_deg):
        # margins about the grid, which the contours' limits would otherwise hold at its edges,
        # cutting the outer rows and columns of markers in half
        ax.use_sticky_edges = False
        rows = chosen[chosen.map_bearing_deg == bearing]
        x, y = rows.downrange_m / 1e3, rows.altitude_m / 1e3
        miss = rows.miss_3dof_m.to_numpy()
        valid = (rows.beta <= mks.BETA_VALIDITY_LIMIT).to_numpy()
        unsolved = (rows.outcome == envelope.NO_SOLUTION).to_numpy()
        ax.plot(x[unsolved], y[unsolved], **_NONE)
        for low, high, _, marker, shade in MISS_CLASSES:
            _marks(ax, x, y, (miss >= low) & (miss < high), valid, marker, shade)
        _marks(ax, x, y, (rows.outcome == envelope.NEVER_THERE).to_numpy(), valid,
               *NEVER_THERE_LOOK)  # fmt: skip
        _elevation_contours(ax, rows)
        ax.set_title(f"bearing {bearing:03.0f}°T", fontsize=9)
        ax.set_xlabel("downrange (km)")
    np.atleast_1d(axes)[0].set_ylabel("intercept altitude (km)")
    handles = [
        Line2D(
            [],
            [],
            marker=m,
            color=s,
            mec=OKABE_ITO["black"],
            mew=0.6,
            linestyle="none",
            markersize=_SIZE,
            label=f"3DOF miss {label}",
        )  # fmt: skip
        for _, _, label, m, s in MISS_CLASSES
    ]
    if (chosen.outcome == envelope.NEVER_THERE).any():
        marker, shade, size = NEVER_THERE_LOOK
        handles.append(Line2D([], [], marker=marker, color=shade, mec=OKABE_ITO["black"], mew=0.6,
                              linestyle="none", markersize=size,
                              label=envelope.NEVER_THERE))  # fmt: skip
    handles += [
        Line2D(
            [],
            [],
            marker="o",
            color=MISS_CLASSES[1][4],
            mfc="white",
            mew=1.3,
            linestyle="none",
            markersize=_SIZE,
            label=r"open: $\beta > 0.25$ (beyond the MKS's validity)",
        ),  # fmt: skip
        Line2D([], [], label=f"no {root}-angle firing solution", **_NONE),
        Line2D(
            [],
            [],
            color=OKABE_ITO["black"],
            linestyle=":",
            linewidth=0.8,
            label=f"firing elevation (every {ELEVATION_STEP_DEG:g}°)",
        ),
    ]
    fig.legend(handles=handles, loc="outside lower center", ncol=2, fontsize=7.5)
    fig.suptitle(f"{root}-angle ECI MKS solution flown by the 3DOF:\n{site}", fontsize=9)
    return fig


#: The models of :func:`draw_model_comparison`: (model asked, whose roots, label, engine style).
_MODELS = (
    ("eci", "eci", "ECI MKS (the text's)", "ECI MKS"),
    ("calibrated", "calibrated", "calibrated MKS", "calibrated MKS"),
)
#: Flights a root above this are drawn together in its last bar.
_MOST_FLIGHTS = 10


def draw_model_comparison(misses: pd.DataFrame, raids: dict[str, pd.DataFrame]):
    """Left: the share of roots (cumulative) whose 3DOF flight misses the aim by less than a
    distance, for the ECI MKS's roots and the calibrated MKS's own (``misses``:
    :func:`.studies.model_comparison.compare_models`; roots whose flight never gets there left out).
    Right: the 3DOF flights the verified raid takes to land each root, for each model's roots
    it lands (``raids``: :func:`.studies.model_comparison.verified_raid` by model)."""
    fig, (left, right) = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 2.8), layout="constrained")
    for model, whose, label, engine in _MODELS:
        rows = misses[(misses.model == model) & (misses.solved_by == whose)]
        miss = np.sort(rows.miss_3dof_m.dropna().to_numpy(dtype=float))
        share = np.arange(1, miss.size + 1) / miss.size
        left.step(miss, share, where="post", label=f"{label}, {miss.size} roots", **style(engine))
    left.set(xscale="log", xlabel="3DOF miss at the root (m)", ylabel="share of roots")
    left.set_ylim(0.0, 1.0)
    left.legend(loc="lower right", fontsize=7)
    bins = np.arange(1, _MOST_FLIGHTS + 1)
    width = 0.4
    for k, (model, whose, label, engine) in enumerate(_MODELS):
        frame = raids[model]
        landed = frame[frame.converged & (frame.solved_by == whose)]
        flights = np.minimum(landed.flights.to_numpy(), _MOST_FLIGHTS)
        counts = np.array([(flights == n).sum() for n in bins]) / max(len(landed), 1)
        right.bar(
            bins + (k - 0.5) * width,
            counts,
            width=width,
            color=style(engine)["color"],
            hatch="///" if k else None,
            edgecolor=OKABE_ITO["black"],
            linewidth=0.5,
            label=f"{label}: {landed.flights.mean():.2f} a root",
        )
    right.set_xticks(bins, [*map(str, bins[:-1]), f"{_MOST_FLIGHTS}+"])
    right.set(xlabel="3DOF flights to land within the tolerance", ylabel="share of roots landed")
    right.legend(loc="upper right", fontsize=7)
    return fig
