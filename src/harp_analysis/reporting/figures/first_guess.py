"""The first-guess figure (issue 24 item 4): reporting on :mod:`.studies.first_guess`'s
comparison of the ECI MKS and the improved MKS as the fire-control solver's model."""

from __future__ import annotations

import numpy as np
import pandas as pd
from matplotlib.artist import Artist
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import MaxNLocator

from ...analyses.fire_control.studies.first_guess import COLUMNS, MODELS, ROOTS
from ..plotting import ENGINE_STYLES, FULL_WIDTH_IN, OKABE_ITO, new_figure

__all__ = ["MODEL_NAMES", "draw_first_guess_comparison"]

#: Each model's name in the legend and its house style (:data:`.plotting.ENGINE_STYLES`).
MODEL_NAMES = {"mks": "ECI MKS", "improved": "improved MKS"}
_STYLES = {"mks": ENGINE_STYLES["MKS"], "improved": ENGINE_STYLES["improved MKS"]}
#: Each root's marker: they read apart without colour.
_ROOT_MARKERS = {"low": "o", "high": "^"}
#: Each model's bar fill in the flights panel: solid and hatched.
_HATCHES = {"mks": "", "improved": "////"}


def _paired(frame: pd.DataFrame) -> pd.DataFrame:
    """The rows of the point-roots where both models have a root (the same shots for both)."""
    keys = ["site", "bearing_deg", "downrange_m", "altitude_m", "root"]
    found = frame.elevation_deg.notna()
    return frame[found.groupby([frame[key] for key in keys]).transform("all")]


def _title(frame: pd.DataFrame) -> str:
    projectiles = ", ".join(frame.attrs.get("projectiles", [])) or "the gun"
    sites = " and ".join(dict.fromkeys(frame.site))
    bearings = ", ".join(f"{b:03.0f}" for b in sorted(frame.bearing_deg.unique()))
    branch = frame.attrs.get("branch", "descending")
    return (
        f"First guesses flown by the 3DOF: {projectiles} from {sites},\n"
        f"bearings {bearings}°T, {branch} branch"
    )


def draw_first_guess_comparison(frame: pd.DataFrame) -> Figure:
    """Two panels of :func:`.studies.first_guess.compare_first_guesses`'s ``frame``, over the
    point-roots where both models have a root: left, the empirical distribution of the 3DOF's
    miss at each model's first guess (log scale; a line per model, its marker the root; a shot
    that never reaches the target's altitude keeps its curve below 1);
    right, the 3DOF flights each refinement took to land within 1 m (a bar per model, hatched
    the improved MKS). The title names the case; the points where the improved MKS found no
    root are counted in the legend."""
    if not isinstance(frame, pd.DataFrame):
        raise TypeError(f"frame must be a pandas DataFrame; got {type(frame).__name__}")
    missing = [name for name in COLUMNS if name not in frame.columns]
    if missing:
        raise ValueError(f"frame lacks the columns {missing} of compare_first_guesses")
    paired = _paired(frame)
    if paired.empty:
        raise ValueError("frame has no point-root where both models have a root")
    fig, (left, right) = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 4.0), layout="constrained")
    _draw_misses(left, paired)
    _draw_flights(right, paired)
    no_root = int(
        frame[(frame.model == "improved") & frame.elevation_deg.isna()]
        .groupby(["site", "bearing_deg", "downrange_m", "altitude_m", "root"])
        .ngroups
    )
    shots = len(paired) // len(MODELS)
    fig.legend(handles=_legend_handles(), loc="outside lower center", ncol=3, fontsize=7.5)
    fig.suptitle(
        f"{_title(frame)}\n{shots} shots where both models have a root; the improved MKS has "
        f"none for {no_root} more",
        fontsize=9,
    )
    return fig


def _draw_misses(ax, paired: pd.DataFrame) -> None:
    """The left panel: per model and root, the empirical distribution of the 3DOF's miss at
    the first guess (log scale); a shot that never reaches the target's altitude keeps its
    curve below 1."""
    for model in MODELS:
        for root in ROOTS:
            rows = paired[(paired.model == model) & (paired.root == root)]
            miss = np.sort(rows.first_guess_miss_m.dropna())  # NaN: the shot never got there
            if not miss.size:
                continue
            share = np.arange(1, miss.size + 1) / len(rows)
            ax.step(
                miss,
                share,
                where="post",
                marker=_ROOT_MARKERS[root],
                markersize=4,
                markerfacecolor="white" if root == "high" else _STYLES[model]["color"],
                **_STYLES[model],
            )
    ax.set_xscale("log")
    ax.set_xlabel(r"3DOF miss at the first guess, $|\Delta \mathbf{r}|$ (m)")
    ax.set_ylabel(r"share of shots, miss $\leq |\Delta \mathbf{r}|$")
    ax.set_ylim(0.0, 1.02)


def _draw_flights(ax, paired: pd.DataFrame) -> None:
    """The right panel: the 3DOF flights each refinement took to land within 1 m, a bar per
    model (hatched the improved MKS) and a vertical line at each model's mean."""
    counts = sorted(paired.flights.unique())
    width = 0.38
    for offset, model in zip((-0.5, 0.5), MODELS):
        flights = paired[paired.model == model].flights
        heights = [int((flights == count).sum()) for count in counts]
        ax.bar(
            np.asarray(counts) + offset * width,
            heights,
            width=width,
            color="white" if model == "improved" else _STYLES[model]["color"],
            edgecolor=_STYLES[model]["color"],
            hatch=_HATCHES[model],
            linewidth=1.0,
        )
        mean = float(flights.mean())
        ax.axvline(mean, linewidth=1.0, **_STYLES[model])
    ax.set_xticks(range(min(counts), max(counts) + 1))
    ax.tick_params(axis="x", labelsize=8)
    ax.set_xlabel(r"3DOF flights to land within 1 m, $n$")
    ax.set_ylabel("shots")
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.grid(axis="x", visible=False)


def _legend_handles() -> list[Artist]:
    """The legend's entries: each model's line, each root's marker, each model's bars."""
    handles: list[Artist] = [
        Line2D([], [], label=MODEL_NAMES[model], linewidth=1.6, **_STYLES[model])
        for model in MODELS
    ]
    handles += [
        Line2D(
            [],
            [],
            marker=_ROOT_MARKERS[root],
            markerfacecolor="white" if root == "high" else OKABE_ITO["grey"],
            color=OKABE_ITO["grey"],
            linestyle="none",
            markersize=4,
            label=f"{root}-angle root",
        )
        for root in ROOTS
    ]
    handles += [
        Patch(
            facecolor="white" if model == "improved" else _STYLES[model]["color"],
            edgecolor=_STYLES[model]["color"],
            hatch=_HATCHES[model],
            label=f"{MODEL_NAMES[model]} flights (vertical line: mean)",
        )
        for model in MODELS
    ]
    return handles
