"""Drawing helpers of Chapter 4's figures (notebook 04): the models side by side
(Figs 4.1-4.4), the MKS's error for the baseline cone at several elevations (Figs 4.11-4.18),
direct labels and off-scale marks.

Every figure is :data:`~harp_analysis.reporting.plotting.FULL_WIDTH_IN` wide; what it needs said
beyond its labels is in its registry caption (registry/figures.toml), never in a note around the
axes.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.lines import Line2D

from ...analyses import comparisons
from ...foundation import earth
from .. import plotting
from ..plotting import FULL_WIDTH_IN, OKABE_ITO, new_figure

__all__ = [
    "TOTAL_ERROR_LABEL",
    "ERROR_TOP_KM",
    "compare_models",
    "direct_labels",
    "mark_off_scale",
    "place_clear",
    "error_figure",
]

TOTAL_ERROR_LABEL = "total position error, eq 4.7 (km)"
#: The error figures' axis, as the text's: a curve that leaves it is marked, with its maximum.
ERROR_TOP_KM = 4.0
_APOGEE: dict[str, Any] = dict(
    marker="*", ms=8, mec=OKABE_ITO["black"], mew=0.7, ls="none", zorder=5
)


def compare_models(models: dict, x: str, y: str, *, scale_x=1e-3, scale_y=1e-3, xlabel="",
                   ylabel=""):  # fmt: skip
    """One panel with each of ``models`` (name -> its flight table) drawn as column ``y``
    against column ``x``, in the engine's style (:func:`plotting.style`); returns the figure."""
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.6), layout="constrained")
    for label, table in models.items():
        ax.plot(table[x] * scale_x, table[y] * scale_y, label=label, **plotting.style(label))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncols=len(models))
    return fig


def direct_labels(ax, lines, labels, at=0.85, offsets=None):
    """:func:`plotting.label_lines`, each label boxed in its line's colour (black text, which
    reads on the palest shade too), optionally moved: ``offsets`` maps a label to its
    ``(dx, dy)`` in points and its horizontal alignment."""
    start = len(ax.texts)
    plotting.label_lines(ax, lines, labels, at=at)
    for text, line, label in zip(ax.texts[start:], lines, labels):
        text.set_color(OKABE_ITO["black"])
        text.set_bbox(dict(boxstyle="round,pad=0.2", fc="white", ec=line.get_color(), lw=0.8,
                           alpha=0.9))  # fmt: skip
        if offsets and label in offsets:
            (dx, dy), ha = offsets[label]
            text.xyann = (dx, dy)
            text.set_ha(ha)


#: Where :func:`place_clear` tries a direct label, in order: (offset in points, alignment).
_LABEL_PLACES = (((3, 3), "left"), ((-3, 3), "right"), ((3, -3), "left"), ((-3, -3), "right"))


def place_clear(fig, ax, labels) -> None:
    """Move each of ``labels`` (direct labels of ``ax``, annotations) to the first of
    :data:`_LABEL_PLACES` about its point where it lies over no other label and no curve
    (:func:`plotting.label_overlaps`); one that fits nowhere stays where it was put first,
    for :func:`plotting.save_figure` to refuse."""
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    for label in labels:
        for offset, ha in (*_LABEL_PLACES, _LABEL_PLACES[0]):
            label.xyann = offset
            label.set_ha(ha)
            label.set_va("bottom" if offset[1] > 0 else "top")
            if not plotting.label_overlaps(ax, label, renderer):
                break


def mark_off_scale(ax, x, y, top, name, *, xytext=(8, -10), ha="left"):
    """If the curve (x, y) leaves the axis at ``top``, say so where it leaves, with its maximum:
    the note stands to the right of the exit (``xytext`` points, ``ha``), clear of a curve that
    rises into it from the left."""
    x, y = np.asarray(x), np.asarray(y)
    if y.max() <= top:
        return
    exit_x = x[np.argmax(y > top)]
    ax.annotate(f"{name} off scale: max {y.max():.1f} km", (exit_x, top), xytext=xytext,
                textcoords="offset points", ha=ha, va="top", fontsize=8,
                arrowprops=dict(arrowstyle="-|>", color=OKABE_ITO["black"], lw=0.8))  # fmt: skip


def error_figure(elevations_deg, *, lower: str | None = None, **variant):
    """The three-term MKS's total position error (eq 4.7, geometric reading) against the 3DOF
    for the baseline cone at ``elevations_deg`` (``variant``: keywords of
    :func:`comparisons.case`), on the text's 0-4 km axis; a star at each 3DOF apogee.

    ``lower`` adds a panel beneath: ``"detail"``, the same errors up to their largest value at
    the apogees times 2.5, where the errors before re-entry can be read; ``"cross range"``,
    the 3DOF's cross range, which the in-plane eq 4.7 leaves out (the MKS is planar)."""
    tall = lower is not None
    fig, axes = new_figure(2 if tall else 1, 1, sharex=True, squeeze=False, layout="constrained",
                           figsize=(FULL_WIDTH_IN, 5.6 if tall else 3.8),
                           gridspec_kw={"height_ratios": [3, 2] if tall else [1]})  # fmt: skip
    ax = axes[0, 0]
    lines, labels, at_apogee = [], [], []
    for elevation in elevations_deg:
        flight, _, errors = comparisons.case("baseline", elevation, **variant)
        x, y = errors.theta_rad * earth.RADIUS_M / 1e3, errors.total_geometric_m / 1e3
        look = plotting.elevation_style(elevation, elevations_deg)
        (line,) = ax.plot(x, y, label=f"{elevation:g} deg", **look)
        lines.append(line)
        k = int(np.argmin(np.abs(errors.time_s - flight.attrs["apogee_time_s"])))
        at_apogee.append(y.iloc[k])
        ax.plot(x.iloc[k], y.iloc[k], color=line.get_color(), **_APOGEE)
        if y.max() > ERROR_TOP_KM:  # named by its off-scale note instead
            mark_off_scale(ax, x, y, ERROR_TOP_KM, f"{elevation:g} deg")
        else:
            direct_labels(ax, [line], [f"{elevation:g} deg"], at=1.0)
            labels.append(ax.texts[-1])
        if lower == "detail":
            axes[1, 0].plot(x, y, **look)
            axes[1, 0].plot(x.iloc[k], y.iloc[k], color=line.get_color(), **_APOGEE)
        elif lower == "cross range":
            axes[1, 0].plot(flight.ground_range_m / 1e3, flight.cross_range_m, **look)
    ax.set_ylabel(TOTAL_ERROR_LABEL)
    ax.set_ylim(0, ERROR_TOP_KM)
    handles = [*lines, Line2D([], [], color=OKABE_ITO["grey"], **_APOGEE)]
    ax.legend(handles, [*(f"{e:g} deg" for e in elevations_deg), "3DOF apogee"],
              loc="lower center", bbox_to_anchor=(0.5, 1.0), ncols=len(handles),
              fontsize=8)  # fmt: skip
    if lower == "detail":
        axes[1, 0].set_ylim(0, 2.5 * max(at_apogee))
        axes[1, 0].set_ylabel("total position\nerror, near apogee (km)")
    elif lower == "cross range":
        axes[1, 0].set_ylabel("3DOF cross range (m),\nnot in eq 4.7")
    axes[-1, 0].set_xlabel("range (km)")
    place_clear(fig, ax, labels)
    return fig
