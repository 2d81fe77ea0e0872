"""The figure of the calibrated MKS judged (X.10): reporting on
:mod:`~harp_analysis.analyses.mks_calibration`. It draws from the table the analysis returns and
returns the figure; notebook 09 saves it."""

from __future__ import annotations

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from ...analyses.mks_calibration import MEASURES
from ..plotting import FULL_WIDTH_IN, new_figure, style

__all__ = ["draw_judged_calibration"]

#: Each model as the judged table names it: its label, the house style's key and its marker.
_MODELS = {
    "eci": ("the text's ECI MKS", "MKS", "o"),
    "improved": ("the improved MKS", "improved MKS", "s"),
    "calibrated": ("the calibrated MKS", "calibrated MKS", "^"),
}
_TITLES = {
    "impact_m": "impact point's distance",
    "apogee_m": "apogee altitude's error",
    "time_of_flight_s": "time of flight's error",
}
_UNITS = {"impact_m": "m", "apogee_m": "m", "time_of_flight_s": "s"}


def draw_judged_calibration(judged: pd.DataFrame) -> Figure:
    """Figure X.10: for every judged launch (:func:`~harp_analysis.analyses.mks_calibration.judge`:
    launches never calibrated on), each model's error against the 3DOF, by the launch's elevation,
    one panel per measure, log scale; filled markers on the turning Earth, open on a still one."""
    fig, axes = new_figure(3, 1, figsize=(FULL_WIDTH_IN, 7.4), sharex=True, layout="constrained")
    turning = judged.turning.to_numpy()
    for ax, measure in zip(axes, MEASURES, strict=True):
        for model, (_, key, marker) in _MODELS.items():
            values = np.abs(judged[f"{model}_{measure}"].to_numpy())
            look = {**style(key), "linestyle": "none", "marker": marker, "markersize": 3.5}
            for chosen, face in ((turning, look["color"]), (~turning, "white")):
                ax.plot(judged.elevation_deg[chosen], values[chosen], markerfacecolor=face,
                        **look)  # fmt: skip
        ax.set_yscale("log")
        ax.set_ylabel(f"{_TITLES[measure]} ({_UNITS[measure]})", fontsize=8.5)
        ax.margins(x=0.03, y=0.08)
    axes[-1].set_xlabel("elevation (deg)")
    handles = [
        Line2D([], [], **{**style(key), "linestyle": "none", "marker": marker}, label=label)
        for label, key, marker in _MODELS.values()
    ]
    handles.append(
        Line2D(
            [],
            [],
            color="black",
            linestyle="none",
            marker="o",
            markerfacecolor="white",
            label="open: a still Earth",
        )  # fmt: skip
    )
    fig.legend(handles=handles, loc="outside lower center", ncol=4, fontsize=8)
    return fig
