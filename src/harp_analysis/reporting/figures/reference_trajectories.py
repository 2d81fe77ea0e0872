"""The figures of Chapter 2's reference trajectories (notebook 02, Figs 2.2-2.10), reporting on
:mod:`harp_analysis.analyses.scenarios`.

Each figure takes ``flights``, the flight tables by (projectile name, model), e.g.
``{("HP", "3DOF"): ..., ("LP", "3DOF"): ..., ("HP", "6DOF"): ...}``, drawn in that order; the
figures that compare the atmosphere's altitude (Figs 2.4, 2.8, 2.10) take ``spherical`` too, the
6DOF flights by projectile with the air at the true altitude, as the 3DOF takes it. A model has
its colour and line style, a projectile its marker
(:func:`~harp_analysis.reporting.plotting.style`).
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ...analyses import scenarios
from .. import plotting
from ..plotting import FULL_WIDTH_IN, new_figure

__all__ = [
    "draw_altitude_with_drag_ratio",
    "draw_cross_range",
    "draw_speed",
    "draw_angle_of_attack",
    "draw_range_against_time",
    "draw_swerve",
    "draw_mach_and_drag",
    "draw_lower_atmosphere",
    "draw_angular_momentum",
]

_SINGLE = (FULL_WIDTH_IN, 3.9)  # one panel across the page
_ALL_MODELS = ("3DOF", "6DOF", "MLT")
#: Markers of the models drawn over one another are staggered along the line.
_STAGGER = {"3DOF": 0.0, "6DOF": 0.027, "MLT": 0.053}
#: Fig 2.2's marks: where N = drag / gravity falls through each on the way up.
_DRAG_RATIOS = (10, 1, 0.1, 0.01, 0.001)
#: Fig 2.9's lower atmosphere: below it, almost all the angular momentum is lost.
_LOWER_ATMOSPHERE_M = 20e3


def _look(model: str, name: str) -> dict:
    """The line keywords of ``model`` flying projectile ``name``."""
    return plotting.style(model, name) | {"markevery": (_STAGGER[model], 0.08)}


def _names(flights: dict) -> list[str]:
    """The projectiles of ``flights``, in order."""
    return list(dict.fromkeys(name for name, _ in flights))


def _legend_above(ax, ncols: int = 3) -> None:
    ax.legend(ncols=ncols, loc="lower center", bbox_to_anchor=(0.5, 1.0))


def _draw(ax, flights, x, y, scale_x=1e-3, scale_y=1e-3, models=_ALL_MODELS) -> None:
    """Each of ``flights`` flown by one of ``models``, column ``y`` against ``x``."""
    for (name, model), flight in flights.items():
        if model in models:
            ax.plot(flight[x] * scale_x, flight[y] * scale_y, **_look(model, name),
                    label=f"{name} {model}")  # fmt: skip


def _draw_spherical(ax, spherical, x, y, scale_x=1e-3, scale_y=1e-3) -> None:
    """The 6DOF flights with the air at the true altitude: thin, in the 6DOF's style."""
    for k, flight in enumerate(spherical.values()):
        ax.plot(flight[x] * scale_x, flight[y] * scale_y, **plotting.style("6DOF"), lw=0.9,
                label="6DOF, air at the true altitude" if k == 0 else None)  # fmt: skip


def _one_panel(
    flights,
    y,
    ylabel,
    *,
    spherical=None,
    scale_y=1.0,
    models=_ALL_MODELS,
    x="ground_range_m",
    xlabel="range (km)",
    scale_x=1e-3,
    ncols=3,
) -> Figure:
    """One panel across the page: column ``y`` of ``flights`` (and of ``spherical``, if given)
    against ``x``, the legend above."""
    fig, ax = new_figure(figsize=_SINGLE, layout="constrained")
    _draw(ax, flights, x, y, scale_x=scale_x, scale_y=scale_y, models=models)
    if spherical is not None:
        _draw_spherical(ax, spherical, x, y, scale_x=scale_x, scale_y=scale_y)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    _legend_above(ax, ncols)
    return fig


def draw_altitude_with_drag_ratio(flights: dict) -> Figure:
    """Fig 2.2: altitude against range, with filled marks where the 3DOF's N = drag / gravity
    falls through 10, 1, 0.1, 0.01 and 0.001 on the way up (labels left of the first
    projectile's curve, right of the others')."""
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 4.2), layout="constrained")
    _draw(ax, flights, "ground_range_m", "altitude_m")
    first = _names(flights)[0]
    for name in _names(flights):
        crossings = scenarios.drag_to_gravity_crossings(flights[name, "3DOF"], _DRAG_RATIOS)
        for ratio, row in crossings.iterrows():
            x, y = row.ground_range_m / 1e3, row.altitude_m / 1e3
            ax.plot(x, y, linestyle="none", marker=plotting.PROJECTILE_MARKERS[name], ms=5,
                    color=plotting.ENGINE_STYLES["3DOF"]["color"])  # fmt: skip
            left = name == first
            ax.annotate(f"$N$ = {ratio:g}", (x, y), textcoords="offset points", fontsize=8,
                        xytext=(-8, 2) if left else (5, -9), ha="right" if left else "left",
                        va="center" if left else "top")  # fmt: skip
    ax.set_xlabel("range (km)")
    ax.set_ylabel("altitude (km)")
    ax.set_xlim(left=-30)  # room for the first projectile's labels
    _legend_above(ax)
    return fig


def draw_cross_range(flights: dict) -> Figure:
    """Fig 2.3: cross range (m) against range in the cross wind."""
    return _one_panel(flights, "cross_range_m", "cross range (m)")


def draw_speed(flights: dict, spherical: dict) -> Figure:
    """Fig 2.4: speed against range, with the 6DOF in the air at the true altitude (thin)."""
    return _one_panel(flights, "speed_m_s", "speed (m/s)", spherical=spherical)


def draw_angle_of_attack(flights: dict) -> Figure:
    """Fig 2.5: the 6DOF's and MLT's total angle of attack (deg) against range."""
    return _one_panel(flights, "angle_of_attack_rad", r"total angle of attack $\alpha$ (deg)",
                          scale_y=np.degrees(1.0), models=("6DOF", "MLT"), ncols=4)  # fmt: skip


def draw_range_against_time(flights: dict) -> Figure:
    """Fig 2.6: range against time."""
    return _one_panel(flights, "ground_range_m", "range (km)", scale_y=1e-3, x="time_s",
                          xlabel="time (s)", scale_x=1.0)  # fmt: skip


def draw_angular_momentum(flights: dict, spherical: dict) -> Figure:
    """Fig 2.10: the 3DOF's and 6DOF's specific angular momentum against range, with the 6DOF
    in the air at the true altitude (thin)."""
    return _one_panel(flights, "specific_angular_momentum_m2_s",
                          "specific angular momentum $h$ (km$^2$/s)", spherical=spherical,
                          scale_y=1e-6, models=("3DOF", "6DOF"))  # fmt: skip


def draw_swerve(flights: dict) -> Figure:
    """Fig 2.7: swerve (:func:`~harp_analysis.analyses.scenarios.swerve`: the 6DOF's and MLT's cross
    range minus the 3DOF's at the same time) against range; the lower panel zooms in on every swerve
    but HP's MLT, which runs to kilometres and is marked where it leaves the panel."""
    fig, (top, bottom) = new_figure(2, 1, sharex=True, figsize=(FULL_WIDTH_IN, 5.4),
                                    gridspec_kw={"height_ratios": [1, 1]},
                                    layout="constrained")  # fmt: skip
    swerves = {(name, model): scenarios.swerve(flights[name, model], flights[name, "3DOF"])
               for model in ("6DOF", "MLT") for name in _names(flights)}  # fmt: skip
    for (name, model), swerve in swerves.items():
        for ax in (top, bottom):
            ax.plot(swerve.ground_range_m / 1e3, swerve.swerve_m, **_look(model, name),
                    label=f"{name} {model}")  # fmt: skip
    detail = [swerve.swerve_m for key, swerve in swerves.items() if key != ("HP", "MLT")]
    low = min(s.min() for s in detail)
    high = max(s.max() for s in detail)
    pad = 0.1 * (high - low)
    bottom.set_ylim(low - pad, high + pad)
    hp_mlt = swerves["HP", "MLT"]
    leaves = hp_mlt.ground_range_m[hp_mlt.swerve_m > high + pad].iloc[0] / 1e3
    bottom.annotate("HP MLT: off scale (upper panel)", (leaves, high + pad),
                    xytext=(12, -4), textcoords="offset points", ha="left", va="top", fontsize=8,
                    arrowprops={"arrowstyle": "->", "lw": 0.8})  # fmt: skip
    top.set_ylabel("swerve (m)")
    bottom.set_ylabel("swerve (m), detail")
    bottom.set_xlabel("range (km)")
    _legend_above(top, ncols=4)
    plotting.keep_markers_whole(fig)  # none cut where HP's MLT leaves the detail panel
    return fig


def draw_mach_and_drag(flights: dict, spherical: dict) -> Figure:
    """Fig 2.8: the 3DOF's and 6DOF's Mach number (above) and drag coefficient (below) against
    range, with the 6DOF in the air at the true altitude (thin); HP's yaw drag past apogee
    (:func:`~harp_analysis.analyses.scenarios.yaw_drag_peak`) is marked with its angle of attack."""
    fig, (top, bottom) = new_figure(2, 1, sharex=True, figsize=(FULL_WIDTH_IN, 5.6),
                                    layout="constrained")  # fmt: skip
    for ax, column in ((top, "mach"), (bottom, "drag_coefficient")):
        _draw(ax, flights, "ground_range_m", column, scale_y=1.0, models=("3DOF", "6DOF"))
        _draw_spherical(ax, spherical, "ground_range_m", column, scale_y=1.0)
    bump = scenarios.yaw_drag_peak(flights["HP", "6DOF"])
    alpha = np.degrees(bump.angle_of_attack_rad)
    bottom.annotate(rf"HP 6DOF: yaw drag ($\alpha \approx {alpha:.0f}$°)",
                    (bump.ground_range_m / 1e3, bump.drag_coefficient),
                    xytext=(36, 6), textcoords="offset points", ha="left", va="bottom",
                    fontsize=8, arrowprops={"arrowstyle": "->", "lw": 0.8})  # fmt: skip
    top.set_ylabel("Mach number $M$")
    bottom.set_ylabel("drag coefficient $C_D$")
    bottom.set_xlabel("range (km)")
    _legend_above(top)
    return fig


def draw_lower_atmosphere(flights: dict) -> Figure:
    """Fig 2.9: the 3DOF's and 6DOF's ascent below 20 km with the straight launch line at the
    first projectile's elevation (above); each flight's altitude minus its own launch line's
    (:func:`~harp_analysis.analyses.scenarios.height_over_straight_line_m`, m), where the
    projectiles part (below)."""
    fig, (ax, below) = new_figure(2, 1, sharex=True, figsize=(FULL_WIDTH_IN, 5.4),
                                  gridspec_kw={"height_ratios": [3, 2]},
                                  layout="constrained")  # fmt: skip
    names = _names(flights)
    for name in names:
        for model in ("3DOF", "6DOF"):
            low = scenarios.ascent_below(flights[name, model], _LOWER_ATMOSPHERE_M)
            ax.plot(low.ground_range_m / 1e3, low.altitude_m / 1e3, **_look(model, name),
                    label=f"{name} {model}")  # fmt: skip
            below.plot(low.ground_range_m / 1e3, scenarios.height_over_straight_line_m(low),
                       **_look(model, name))  # fmt: skip
    launch = flights[names[0], "3DOF"].attrs["launch"]
    x_km = np.linspace(0, _LOWER_ATMOSPHERE_M / 1e3 / np.tan(launch.elevation_rad), 2)
    ax.plot(x_km, scenarios.straight_line_altitude_m(x_km, launch.elevation_rad), color="k",
            lw=0.8, label=f"straight line at {launch.elevation_deg:g}°")  # fmt: skip
    below.axhline(0.0, color="k", lw=0.8)
    ax.set_ylabel("altitude (km)")
    below.set_ylabel("altitude minus the\nstraight line (m)")
    below.set_xlabel("range (km)")
    ax.legend()
    return fig
