"""The figures of Chapter 6: the apogee residuals of every round (Figs 6.5, 6.6), reporting on
:mod:`harp_analysis.analyses.harp.apogees`, and single HARP rounds (Figs 6.7-6.11), reporting on
:mod:`harp_analysis.analyses.harp.rounds`."""

from __future__ import annotations

import math

import numpy as np
from matplotlib.patches import Patch
from matplotlib.ticker import MultipleLocator

from ...analyses.harp import apogees, rounds
from ..plotting import FULL_WIDTH_IN, OKABE_ITO, new_figure, style

__all__ = ["draw_residual_figure", "draw_round_figure"]

#: The residual bars' fill: a neutral grey, no model's colour, light enough for Appendix E's
#: black marks on it.
_BAR_GREY = "#A6A6A6"


def draw_residual_figure(site: str):
    """Figs 6.5 and 6.6: measured minus predicted apogee per round of ``site``
    (:func:`~harp_analysis.analyses.harp.apogees.predicted_apogees`, the dissertation model), the
    mean (dashed) and the mean +- 1 std (band); a row that repeats an earlier one hatched and white,
    and where the appendix prints its own Error (Yuma), a black dash on each bar."""
    frame = apogees.predicted_apogees(site)
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.8), layout="constrained")
    x = np.arange(len(frame))
    duplicate = frame.duplicate_of_earlier_row.to_numpy()
    bars = ax.bar(x, frame.residual_m / 1e3, color=_BAR_GREY, edgecolor="k", lw=0.6, zorder=2)
    for bar, repeated in zip(bars, duplicate):
        if repeated:  # told apart by its hatching, not its shade
            bar.set_facecolor("white")
            bar.set_hatch("////")
    mean, std = apogees.residual_statistic(site, "mean"), apogees.residual_statistic(site, "std")
    handles = [
        ax.axhline(mean, color="k", lw=1.2, ls="--", label=f"mean {mean:.2f} km"),
        ax.axhspan(mean - std, mean + std, color="0.88", zorder=0,
                   label=f"mean $\\pm$ 1 std ({std:.2f} km)"),
    ]  # fmt: skip
    if duplicate.any():
        handles.append(
            Patch(facecolor="white", edgecolor="k", hatch="////",
                  label=f"round {frame.round_number[duplicate].iloc[0]}'s second (duplicated) row")
        )  # fmt: skip
    if "printed_error_m" in frame:
        printed = dict(ls="none", marker="_", color="k", ms=13, mew=2.5, zorder=3)
        handles += ax.plot(x, frame.printed_error_m / 1e3, label="Appendix E's printed Error",
                           **printed)  # fmt: skip
    ax.set_xticks(x, frame.round_number, rotation=90, fontsize=8)
    ax.set_xlim(-0.7, len(frame) - 0.3)
    ax.set_xlabel("round")
    ax.set_ylabel("measured $-$ predicted\napogee (km)")
    ax.set_title(f"{site.capitalize()} Martlet 2C rounds: ECI Modified Kepler, dissertation model",
                 fontsize=9)  # fmt: skip
    fig.legend(handles=handles, fontsize=8, loc="outside lower center", ncol=2)
    return fig


#: Each radar's marker (black, the "measured" colour): filled circle, open square.
_RADAR_MARKERS = {"MPS-19": dict(marker="o"), "M-33": dict(marker="s", markerfacecolor="none")}


def _splash_style(label: str) -> dict:
    """The observed splash is a measurement (black, filled down-triangle); the text's MKS range
    is the text's value (grey cross), as :func:`plotting.style` gives them."""
    if "observed" in label:
        return {**style("measured"), "marker": "v", "markersize": 8}
    return {**style("text"), "markersize": 9, "markeredgewidth": 2.0}


def draw_round_figure(site: str, round_number: int):
    """Figs 6.7-6.11: altitude against time and against radar range, the ECI MKS curve and the
    radar points if ``data/harp/radar`` has them (the caption says they are not in the
    dissertation).

    Told apart without colour: the MKS in its engine style (dotted), radar points as black
    markers (one shape per radar), the measured apogee a black dashed line, and where the text
    gives them (round 181) its MKS range (grey cross) and the observed splash (black triangle),
    enlarged in an inset; one legend below both panels, clear of the curves."""
    launch_site, number, row = rounds.round_row(site, round_number)
    trajectory = rounds.round_trajectory(site, number)
    radar = rounds.load_radar_track(site, number)
    fig, (by_time, by_range) = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 3.6), layout="constrained")
    altitude_km = trajectory.altitude_m / 1e3
    mks = {**style("MKS"), "lw": 2.2}
    by_time.plot(trajectory.time_s, altitude_km, label="ECI Modified Kepler", **mks)
    by_range.plot(trajectory.radar_range_m / 1e3, altitude_km, label="ECI Modified Kepler", **mks)
    if radar is not None:
        for name, points in radar.groupby("radar"):
            look = {**style("measured"), "markersize": 4, **_RADAR_MARKERS.get(name, {})}
            by_time.plot(points.time_s, points.altitude_m / 1e3, label=f"{name} radar", **look)
            by_range.plot(
                points.range_m / 1e3, points.altitude_m / 1e3, label=f"{name} radar", **look
            )
    for axes in (by_time, by_range):
        axes.axhline(
            row.apogee_m / 1e3,
            color=OKABE_ITO["black"],
            ls="--",
            lw=1.0,
            label=f"measured apogee {row.apogee_m / 1e3:.0f} km",
        )
        axes.set_ylim(bottom=0.0, top=1.12 * max(row.apogee_m, trajectory.altitude_m.max()) / 1e3)
    splashes = (
        rounds.TEXT_SPLASH_RANGES_KM.get(number, {}) if launch_site.name == "Barbados" else {}
    )
    if splashes:  # the splash markers sit a marker's width apart: enlarged in an inset
        zoom = by_range.inset_axes([0.25, 0.13, 0.44, 0.36])
        zoom.plot(trajectory.radar_range_m / 1e3, altitude_km, **mks)
        for label, range_km in splashes.items():
            look = _splash_style(label)
            by_range.plot(
                range_km,
                0.0,
                clip_on=False,
                zorder=5,
                label=f"{label} range {range_km:.1f} km",
                **{**look, "markersize": 0.7 * look["markersize"]},
            )
            zoom.plot(range_km, 0.0, clip_on=False, zorder=5, **look)
        ends = [*splashes.values(), float(trajectory.radar_range_m.iloc[-1]) / 1e3]
        zoom.set_xlim(math.floor(min(ends)) - 1.0, math.ceil(max(ends)) + 1.0)
        zoom.set_ylim(0.0, 8.0)
        zoom.xaxis.set_major_locator(MultipleLocator(2.0))
        zoom.yaxis.set_major_locator(MultipleLocator(4.0))
        zoom.tick_params(labelsize=8, pad=1)
        zoom.grid(True, alpha=0.35)
        by_range.indicate_inset_zoom(zoom, edgecolor=OKABE_ITO["grey"])
    by_time.set(xlabel="time (s)", ylabel="altitude (km)")
    by_range.set(xlabel="range from the gun (km)", ylabel="altitude (km)")
    by_time.set_xlim(left=0.0)
    by_range.set_xlim(left=0.0)
    # One legend under both panels, clear of the curves (the range panel holds every entry).
    handles, labels = by_range.get_legend_handles_labels()
    fig.legend(
        handles,
        labels,
        loc="outside lower center",
        ncol=2,
        fontsize=8.5,
        frameon=False,
        handlelength=3,
    )
    fig.suptitle(
        f"{launch_site.name} round {number}: {row.muzzle_speed_m_s / 1e3:.3f} km/s, "
        f"{math.degrees(launch_site.elevation_rad):.0f}°, bearing "
        f"{math.degrees(launch_site.gun_bearing_rad):03.0f}°T; "
        "ECI Modified Kepler (dissertation model)",
        fontsize=9,
    )
    return fig
