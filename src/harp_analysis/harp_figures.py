"""The figures of single HARP rounds (Figs 6.7-6.11): reporting on :mod:`.harp_rounds`."""

from __future__ import annotations

import math

from matplotlib.ticker import MultipleLocator

from . import harp_rounds
from .plotting import FULL_WIDTH_IN, OKABE_ITO, new_figure, style

__all__ = ["draw_round_figure"]

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
    radar points if ``data/harp/radar`` has them, else a note saying they are missing.

    Told apart without colour: the MKS in its engine style (dotted), radar points as black
    markers (one shape per radar), the measured apogee a black dashed line, and where the text
    gives them (round 181) its MKS range (grey cross) and the observed splash (black triangle),
    enlarged in an inset; one legend below both panels, clear of the curves."""
    launch_site, number, row = harp_rounds._round_row(site, round_number)
    trajectory = harp_rounds.round_trajectory(site, number)
    radar = harp_rounds.load_radar_track(site, number)
    fig, (by_time, by_range) = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 3.6))
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
        harp_rounds.TEXT_SPLASH_RANGES_KM.get(number, {}) if launch_site.name == "Barbados" else {}
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
    fig.subplots_adjust(bottom=0.38 if radar is None else 0.30, top=0.88, wspace=0.3)
    fig.legend(
        handles,
        labels,
        loc="upper center",
        bbox_to_anchor=(0.5, 0.2 if radar is None else 0.13),
        ncol=2,
        fontsize=8.5,
        frameon=False,
        handlelength=3,
    )
    if radar is None:
        fig.text(
            0.5,
            0.01,  # on the page, which is the figure: nothing outside it is saved
            f"radar data for round {number} are not in the dissertation "
            "(see data/harp/radar/README.md)",
            ha="center",
            va="bottom",
            color=OKABE_ITO["black"],
            fontsize=9,
            bbox=dict(facecolor="white", edgecolor=OKABE_ITO["grey"]),
        )
    fig.suptitle(
        f"{launch_site.name} round {number}: {row.muzzle_speed_m_s / 1e3:.3f} km/s, "
        f"{math.degrees(launch_site.elevation_rad):.0f}°, bearing "
        f"{math.degrees(launch_site.gun_bearing_rad):03.0f}°T; "
        "ECI Modified Kepler (dissertation model)",
        fontsize=9,
    )
    return fig
