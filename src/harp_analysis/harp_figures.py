"""The figures of single HARP rounds (Figs 6.7-6.11): reporting on :mod:`.harp_rounds`."""

from __future__ import annotations

from . import harp_rounds
from .plotting import new_figure

__all__ = ["draw_round_figure"]


def draw_round_figure(site: str, round_number: int):
    """Figs 6.7-6.11: altitude against time and against radar range, the ECI MKS curve and the
    radar points if ``data/harp/radar`` has them, else a note saying they are missing."""
    launch_site, number, row = harp_rounds._round_row(site, round_number)
    trajectory = harp_rounds.round_trajectory(site, number)
    radar = harp_rounds.load_radar_track(site, number)
    fig, (by_time, by_range) = new_figure(1, 2, figsize=(10.0, 4.4))
    altitude_km = trajectory.altitude_m / 1e3
    by_time.plot(trajectory.time_s, altitude_km, label="ECI Modified Kepler")
    by_range.plot(trajectory.radar_range_m / 1e3, altitude_km, label="ECI Modified Kepler")
    if radar is None:
        fig.subplots_adjust(bottom=0.28)
        fig.text(
            0.5,
            0.03,
            f"radar data for round {number} are not in the dissertation\n"
            "(see data/harp/radar/README.md)",
            ha="center",
            va="bottom",
            color="darkred",
            fontsize=11,
            bbox=dict(facecolor="white", edgecolor="darkred"),
        )
    else:
        for name, points in radar.groupby("radar"):
            by_time.plot(points.time_s, points.altitude_m / 1e3, "o", ms=3, label=f"{name} radar")
            by_range.plot(
                points.range_m / 1e3, points.altitude_m / 1e3, "o", ms=3, label=f"{name} radar"
            )
    for axes in (by_time, by_range):
        axes.axhline(
            row.apogee_m / 1e3,
            color="0.3",
            ls=":",
            lw=1.2,
            label=f"measured apogee {row.apogee_m / 1e3:.0f} km",
        )
    if launch_site.name == "Barbados":
        for (label, range_km), marker in zip(
            harp_rounds.TEXT_SPLASH_RANGES_KM.get(number, {}).items(), "v^"
        ):
            by_range.plot(
                range_km,
                0.0,
                marker,
                color="k",
                ms=8,
                clip_on=False,
                label=f"{label} {range_km:.1f} km",
            )
    by_time.set(xlabel="time (s)", ylabel="altitude (km)")
    by_range.set(xlabel="range from the gun (km)", ylabel="altitude (km)")
    for axes in (by_time, by_range):
        axes.legend(loc="lower center")
    fig.suptitle(f"{launch_site.name} round {number}: radar data and ECI Modified Kepler solution")
    return fig
