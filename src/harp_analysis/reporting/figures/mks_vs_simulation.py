"""The figures of Chapter 4 (notebook 04), the Modified Kepler Solution against the
simulations, reporting on :mod:`harp_analysis.analyses.comparisons`: the models side by side
(Figs 4.1-4.4), the error's geometry and series length (Figs 4.5, 4.6), the computational effort
(Fig 4.7), three projectiles (Fig 4.8), the cone's drag (Fig 4.9), the baseline cone at several
elevations (Figs 4.10, 4.12, 4.14, 4.16) and the MKS's error for it (Figs 4.11-4.18), with their
direct labels and off-scale marks.

Every figure is :data:`~harp_analysis.reporting.plotting.FULL_WIDTH_IN` wide; what it needs said
beyond its labels is in its registry caption (registry/figures.toml), never in a note around the
axes.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.ticker import FixedFormatter, FixedLocator

from ...analyses import comparisons, scenarios
from ...engines import mks
from ...foundation import earth
from ...models import taylor_maccoll as tm
from ...models.drag import BASELINE_CONE
from ...models.launch import Launch
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
    "draw_error_geometry",
    "draw_error_by_terms",
    "draw_effort",
    "draw_wall_time",
    "draw_three_projectiles",
    "draw_cone_drag",
    "draw_baseline_trajectories",
    "draw_asymptotic_momentum_error",
    "draw_straight_lines",
    "draw_drag_coefficient_against_altitude",
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
    against column ``x``, in the engine's style (:func:`~harp_analysis.reporting.plotting.style`);
    returns the figure."""
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.6), layout="constrained")
    for label, table in models.items():
        ax.plot(table[x] * scale_x, table[y] * scale_y, label=label, **plotting.style(label))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncols=len(models))
    return fig


def direct_labels(ax, lines, labels, at=0.85, offsets=None):
    """:func:`~harp_analysis.reporting.plotting.label_lines`, each label boxed in its line's colour
    (black text, which reads on the palest shade too), optionally moved: ``offsets`` maps a label to
    its ``(dx, dy)`` in points and its horizontal alignment."""
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
    ``_LABEL_PLACES`` about its point where it lies over no other label and no curve
    (:func:`~harp_analysis.reporting.plotting.label_overlaps`); one that fits nowhere stays where it
    was put first, for :func:`~harp_analysis.reporting.plotting.save_figure` to refuse."""
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
    :func:`~harp_analysis.analyses.comparisons.case`), on the text's 0-4 km axis; a star at each
    3DOF apogee.

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
        line, label, error_at_apogee = _error_curve(axes, elevation, elevations_deg, lower, variant)
        lines.append(line)
        at_apogee.append(error_at_apogee)
        if label is not None:
            labels.append(label)
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
    plotting.keep_markers_whole(fig)  # none cut where the errors start, near 0, or leave the axis
    return fig


def _error_curve(axes, elevation: float, elevations_deg, lower: str | None, variant: dict):
    """One elevation's curve of :func:`error_figure` on its ``axes``: the error with a star at
    the 3DOF apogee, named by a direct label or, off the axis, by its note; the lower panel's
    curve. Returns the line, its direct label (None when off the axis) and its error at the
    apogee (km)."""
    ax = axes[0, 0]
    flight, _, errors = comparisons.case("baseline", elevation, **variant)
    x, y = errors.theta_rad * earth.RADIUS_M / 1e3, errors.total_geometric_m / 1e3
    look = plotting.elevation_style(elevation, elevations_deg)
    (line,) = ax.plot(x, y, label=f"{elevation:g} deg", **look)
    k = int(np.argmin(np.abs(errors.time_s - flight.attrs["apogee_time_s"])))
    ax.plot(x.iloc[k], y.iloc[k], color=line.get_color(), **_APOGEE)
    label = None
    if y.max() > ERROR_TOP_KM:  # named by its off-scale note instead
        mark_off_scale(ax, x, y, ERROR_TOP_KM, f"{elevation:g} deg")
    else:
        direct_labels(ax, [line], [f"{elevation:g} deg"], at=1.0)
        label = ax.texts[-1]
    if lower == "detail":
        axes[1, 0].plot(x, y, **look)
        axes[1, 0].plot(x.iloc[k], y.iloc[k], color=line.get_color(), **_APOGEE)
    elif lower == "cross range":
        axes[1, 0].plot(flight.ground_range_m / 1e3, flight.cross_range_m, **look)
    return line, label, y.iloc[k]


def draw_error_geometry(launch: Launch) -> Figure:
    """Fig 4.5: the geometry of the total position error (eqs 4.4-4.7) of ``launch``'s MKS at
    the 3DOF's apogee (:func:`~harp_analysis.analyses.comparisons.fly`): at the simulation's angular
    range theta_i, the radial error eps_r and the along-track error eps_theta (the time lag times
    the speed), which combine along the MKS's flight-path angle Phi."""
    flight, solution, errors = comparisons.fly(launch)
    i = int(np.argmin(np.abs(errors.time_s - flight.attrs["apogee_time_s"])))
    row = errors.iloc[i]
    r_sim = flight.altitude_m.iloc[i] + earth.RADIUS_M
    r_mks = solution.radius(row.theta_rad).item()
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 4.6), layout="constrained")
    horizontal, vertical = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    track = np.cos(row.phi_mks_rad) * horizontal + np.sin(row.phi_mks_rad) * vertical
    mks_point = np.array([0.0, (r_mks - earth.RADIUS_M) / 1e3])
    sim_point = np.array([0.0, (r_sim - earth.RADIUS_M) / 1e3])
    lag = mks_point - row.along_track_error_m / 1e3 * track  # the MKS at the simulation's time
    mks_colour, sim_colour = plotting.style("MKS")["color"], plotting.style("3DOF")["color"]
    mks_label = rf"MKS at $\theta_i$ (altitude {(r_mks - earth.RADIUS_M) / 1e3:.2f} km)"
    ax.plot(*mks_point, "o", ms=7, color=mks_colour, label=mks_label)
    ax.plot(*sim_point, "s", ms=7, color=sim_colour, label=r"3DOF at $t_i$")
    ax.plot(*lag, "^", ms=7, mfc="none", mew=1.5, color=mks_colour, label=r"MKS at $t_i$")
    for start, end, ls, lw in ((mks_point, sim_point, "-", 1.0), (mks_point, lag, "--", 1.0),
                               (lag, sim_point, "-", 2.0)):  # fmt: skip
        arrow = dict(arrowstyle="-|>", color=OKABE_ITO["black"], ls=ls, lw=lw, shrinkA=4, shrinkB=4)
        ax.annotate("", end, start, arrowprops=arrow)
    ax.annotate(rf"$\varepsilon_r$ = {row.radial_error_m / 1e3:.2f} km",
                (mks_point + sim_point) / 2, xytext=(-6, 0), textcoords="offset points",
                ha="right", va="center", fontsize=9)  # fmt: skip
    ax.annotate(rf"$\varepsilon_\theta$ = {row.along_track_error_m / 1e3:.2f} km",
                (mks_point + lag) / 2, xytext=(0, -8), textcoords="offset points", ha="center",
                va="top", fontsize=9)  # fmt: skip
    ax.annotate(f"total, eq 4.7 = {row.total_geometric_m / 1e3:.2f} km", (sim_point + lag) / 2,
                xytext=(8, -4), textcoords="offset points", ha="left", va="top",
                fontsize=9)  # fmt: skip
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(r"along the horizontal at $\theta_i$ (km)")
    ax.set_ylabel("altitude (km)")
    ax.set_title(rf"{launch.projectile.name} at apogee, $t_i$ = {row.time_s:.1f} s, "
                 rf"$\Phi$ = {np.degrees(row.phi_mks_rad):.2f} deg", fontsize=9)  # fmt: skip
    ax.legend(loc="lower right", fontsize=8)
    return fig


#: Fig 4.6's series lengths and their looks (every series is the MKS's error, in its colour).
_TERM_STYLES: dict[int, dict[str, Any]] = {
    1: dict(ls="--"),
    2: dict(ls="-."),
    3: dict(ls="-", lw=2.2),
    4: dict(ls=":", lw=1.2, marker="s", ms=4, mfc="none", markevery=0.12),
    5: dict(ls=":", lw=1.2, marker="D", ms=4, mfc="none", markevery=(0.06, 0.12)),
}
#: Fig 4.6's three measures of the three-term error and their looks.
_MEASURES: dict[str, tuple[str, dict[str, Any]]] = {
    "total_geometric_m": ("eq 4.7, geometric", dict(lw=2.2)),
    "total_printed_m": ("eqs 4.6-4.7, printed", dict(ls="--")),
    "direct_m": ("direct, equal time", dict(ls=":", lw=2.2)),
}
_TERMS_TOP_KM = 8.0


def draw_error_by_terms(launch: Launch) -> Figure:
    """Fig 4.6: the total position error (eq 4.7, geometric reading) of ``launch``'s MKS
    against the 3DOF with 1 to 5 series terms (left); for three terms, eqs 4.6-4.7 as printed,
    their geometric reading and the direct distance at the same time (right)."""
    fig, (left, right) = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 3.4), layout="constrained")
    colour = plotting.ENGINE_STYLES["MKS"]["color"]
    for n, look in _TERM_STYLES.items():
        errors = comparisons.fly(launch, n_terms=n)[2]
        left.plot(errors.time_s, errors.total_geometric_m / 1e3,
                  label=f"{n} term{'s' * (n > 1)}", color=colour, **look)  # fmt: skip
    errors = comparisons.fly(launch)[2]
    for column, (label, look) in _MEASURES.items():
        right.plot(errors.time_s, errors[column] / 1e3, label=label, color=colour, **look)
    # the note left of the exit: the right is the axes' edge
    mark_off_scale(right, errors.time_s, errors.total_printed_m / 1e3, _TERMS_TOP_KM, "printed",
                   xytext=(-24, -4), ha="right")  # fmt: skip
    left.set_ylabel(TOTAL_ERROR_LABEL)
    right.set_ylabel("position error, three terms (km)")
    for ax, where in ((left, "upper left"), (right, "lower right")):
        ax.set_xlabel("time (s)")
        ax.set_ylim(0, _TERMS_TOP_KM)
        ax.legend(loc=where, fontsize=8)
    plotting.keep_markers_whole(fig)  # none cut on the time axis, where every error starts
    return fig


#: Fig 4.7: the reference differs from itself by 0 m, which a log axis cannot hold: it gets a
#: slot of its own at the axis's left end, ticked "0" and cut off by a break mark.
_REFERENCE, _REFERENCE_X, _BREAK_X = "6DOF", 0.15, 0.4
_EFFORT_MARKERS = {"6DOF": "p", "3DOF": "o", "MLT": "s", "MKS (3 terms)": "D"}
#: The methods whose operations Fig 4.7 counts (the vectorised MKS's count is the MKS's).
_COUNTED = ("6DOF", "3DOF", "MLT", "MKS (3 terms)")


def _effort_figure(table, column: str, label: str, methods) -> Figure:
    """``table``'s (:func:`~harp_analysis.analyses.effort.effort_table`) ``column`` of each of
    ``methods`` against its apogee difference from the 6DOF, both on log axes."""
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.8), layout="constrained")
    ax.set_xscale("log")
    ax.set_yscale("log")
    for method in methods:
        y, colour = table[column][method], plotting.style(method)["color"]
        x = _REFERENCE_X if method == _REFERENCE else table.apogee_difference_m[method]
        ax.plot(x, y, _EFFORT_MARKERS.get(method, "v"), ms=8, color=colour)
        ax.annotate(f"{method}: reference (0 m)" if method == _REFERENCE else method, (x, y),
                    textcoords="offset points", xytext=(7, 4), fontsize=8)  # fmt: skip
    decades = [10.0**k for k in range(5)]
    ax.set_xlim(0.1, 5e4)
    ax.xaxis.set_major_locator(FixedLocator([_REFERENCE_X, *decades]))
    ax.xaxis.set_major_formatter(FixedFormatter(["0", *(f"$10^{{{k}}}$" for k in range(5))]))
    ax.xaxis.set_minor_locator(FixedLocator([m * d for d in decades for m in range(2, 10)
                                             if m * d < 5e4]))  # fmt: skip
    ax.xaxis.set_minor_formatter(FixedFormatter([]))
    ax.annotate("//", (_BREAK_X, 0), xycoords=("data", "axes fraction"), ha="center",
                va="center", fontsize=11, annotation_clip=False,
                bbox=dict(fc="white", ec="none", pad=0.5))  # fmt: skip
    ax.set_xlabel("apogee difference from the 6DOF (m)")
    ax.set_ylabel(f"{label}\n(simulations to impact, MKS at apogee)", fontsize=9)
    return fig


def draw_effort(table) -> Figure:
    """Fig 4.7: floating-point operations of each method of ``table``
    (:func:`~harp_analysis.analyses.effort.effort_table`) against its apogee difference from the
    6DOF."""
    return _effort_figure(table, "flops", "floating-point operations", _COUNTED)


def draw_wall_time(table) -> Figure:
    """Fig 4.7 measured in wall time on this machine instead: every method of ``table``
    (:func:`~harp_analysis.analyses.effort.effort_table`), the vectorised MKS too (not saved: it
    changes from run to run)."""
    return _effort_figure(table, "seconds", "wall time on this machine (s)", table.index)


def draw_three_projectiles(elevation_deg: float) -> Figure:
    """Fig 4.8: altitude against range of HP, LP and the baseline cone at ``elevation_deg``
    without wind, the 3DOF's and the three-term MKS's."""
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.8), layout="constrained")
    for name in ("HP", "LP", "baseline"):
        flight, solution, _ = comparisons.case(name, elevation_deg, cross_wind_m_s=0.0)
        angles = np.linspace(0, solution.impact_angle, 400)
        ax.plot(flight.ground_range_m / 1e3, flight.altitude_m / 1e3, label=f"{name}, 3DOF",
                **plotting.style("3DOF", name))  # fmt: skip
        ax.plot(earth.RADIUS_M * angles / 1e3, solution.altitude(angles) / 1e3,
                label=f"{name}, MKS", **plotting.style("MKS", name))  # fmt: skip
    ax.set_xlabel("range (km)")
    ax.set_ylabel("altitude (km)")
    ax.legend(ncols=3, fontsize=8, loc="upper center", bbox_to_anchor=(0.5, 1.18))
    return fig


def draw_cone_drag() -> Figure:
    """Fig 4.9: the baseline cone's drag coefficient from conical flow (Taylor-Maccoll,
    :mod:`~harp_analysis.models.taylor_maccoll`) in Appendix C's normalisation and in the
    free stream's, against Mach, with the text's eq 4.8 (grey) and its form fitted to Appendix
    C's values (black)."""
    grid = tm.EQ_4_8_MACH_GRID
    fine = np.linspace(grid[0], grid[-1], 300)
    fit = tm.baseline_fit()
    appendix_c = tm.cone_drag_coefficient(grid, normalisation="appendix_c")
    free_stream = tm.cone_drag_coefficient(grid)
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.6), layout="constrained")
    ax.plot(grid, appendix_c, "o", ms=5, color=OKABE_ITO["black"],
            label="Taylor-Maccoll, Appendix C's normalisation")  # fmt: skip
    ax.plot(grid, free_stream, "s", ms=4, mfc="none", color=OKABE_ITO["black"],
            label="Taylor-Maccoll, free-stream dynamic pressure")  # fmt: skip
    ax.plot(fine, BASELINE_CONE(fine), "-", lw=1, color=OKABE_ITO["grey"],
            label=r"eq 4.8 (text): $0.077\,e^{-0.38\,Ma} + 0.014$")  # fmt: skip
    ax.plot(fine, fit.law(fine), "--", color=OKABE_ITO["black"],
            label=rf"fit: ${fit.a:.4f}\,e^{{{fit.b:.3f}\,Ma}} + {fit.c:.4f}$, "
            rf"$R^2$ = {fit.r_squared:.4f}")  # fmt: skip
    ax.set_xlabel(r"Mach number $Ma$")
    ax.set_ylabel(r"drag coefficient $C_D$ (base area)")
    ax.set_ylim(0, 1.08 * max(appendix_c.max(), free_stream.max()))  # every point on the axis
    ax.legend(fontsize=8)
    return fig


def _elevation_names(elevations_deg) -> list[str]:
    return [f"{e:g} deg" for e in elevations_deg]


def draw_baseline_trajectories(elevations_deg) -> Figure:
    """Fig 4.10: the three-term MKS trajectories of the baseline cone at ``elevations_deg``."""
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.8), layout="constrained")
    launches = [comparisons.chapter_4_launch("baseline", e) for e in elevations_deg]
    solutions = mks.for_launch(launches)
    names = _elevation_names(elevations_deg)
    lines = []
    for k, (elevation, name) in enumerate(zip(elevations_deg, names)):
        angles = np.linspace(0, solutions.impact_angle[k], 400)
        (line,) = ax.plot(earth.RADIUS_M * angles / 1e3,
                          solutions.altitude(angles[None, :])[k] / 1e3, label=name,
                          **plotting.elevation_style(elevation, elevations_deg))  # fmt: skip
        lines.append(line)
    direct_labels(ax, lines, names, at=0.5, offsets=dict.fromkeys(names, ((0, 6), "center")))
    ax.set_xlabel("range (km)")
    ax.set_ylabel("altitude (km)")
    ax.legend(title="elevation")
    return fig


#: Fig 4.12's elevations (deg).
_MOMENTUM_ELEVATIONS_DEG = np.arange(30.0, 86.0, 5.0)


def draw_asymptotic_momentum_error(elevations_deg=_MOMENTUM_ELEVATIONS_DEG) -> Figure:
    """Fig 4.12: the MKS's asymptotic angular momentum over the 3DOF's at apogee, minus 1 (%),
    for the baseline cone at ``elevations_deg``
    (:func:`~harp_analysis.analyses.comparisons.asymptotic_momentum_error`)."""
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.4), layout="constrained")
    errors = [100 * comparisons.asymptotic_momentum_error("baseline", e) for e in elevations_deg]
    ax.plot(elevations_deg, errors, "o-", color=plotting.ENGINE_STYLES["MKS"]["color"], ms=5)
    ax.axhline(0, color=OKABE_ITO["black"], lw=0.8)  # a reference line: black (grey is the text's)
    ax.set_xlabel("elevation (deg)")
    ax.set_ylabel(r"$(h_\infty^\mathrm{MKS} - h_\mathrm{apogee}^\mathrm{3DOF})\,/\,"
                  r"h_\mathrm{apogee}^\mathrm{3DOF}$ (%)")  # fmt: skip
    return fig


#: The tops of Fig 4.14's and Fig 4.16's lower atmospheres.
_STRAIGHT_LINES_TOP_M, _DRAG_TOP_M = 30e3, 45e3


def draw_straight_lines(elevations_deg) -> Figure:
    """Fig 4.14: altitude against angular range below 30 km on the way up, the 3DOF's flight of
    the baseline cone at each of ``elevations_deg`` (solid) and its straight line of eq 3.16
    (dotted, :func:`~harp_analysis.analyses.scenarios.straight_line_altitude_m`)."""
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.8), layout="constrained")
    lines = []
    for elevation in elevations_deg:
        flight = comparisons.case("baseline", elevation)[0]
        low = scenarios.ascent_below(flight, _STRAIGHT_LINES_TOP_M)
        angle = low.ground_range_m / earth.RADIUS_M
        (line,) = ax.plot(angle * 1e3, low.altitude_m / 1e3,
                          **plotting.elevation_style(elevation, elevations_deg))  # fmt: skip
        lines.append(line)
        straight_m = scenarios.straight_line_altitude_m(low.ground_range_m, np.radians(elevation))
        ax.plot(angle * 1e3, straight_m / 1e3, ":", color=line.get_color())
    direct_labels(ax, lines, _elevation_names(elevations_deg), at=1.0)
    ax.set_xlabel(r"angular range $\theta$ (mrad)")
    ax.set_ylabel("altitude (km)")
    ax.set_ylim(0, _STRAIGHT_LINES_TOP_M / 1e3)
    ax.legend([Line2D([], [], color=OKABE_ITO["black"], marker="o", ms=4),
               Line2D([], [], color=OKABE_ITO["black"], ls=":")],
              ["3DOF", r"straight line, eq 3.16: $a = \theta\, r_0 \tan\phi_0$"],
              loc="lower right")  # fmt: skip
    plotting.keep_markers_whole(fig)  # none cut at the gun, where every line starts
    return fig


def draw_drag_coefficient_against_altitude(elevations_deg) -> Figure:
    """Fig 4.16: the 3DOF's drag coefficient against altitude up to 45 km on the way up, for
    the baseline cone at ``elevations_deg``, with 20 km marked."""
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.8), layout="constrained")
    lines = []
    for elevation in elevations_deg:
        up = scenarios.ascent_below(comparisons.case("baseline", elevation)[0], _DRAG_TOP_M)
        (line,) = ax.plot(up.drag_coefficient, up.altitude_m / 1e3,
                          **plotting.elevation_style(elevation, elevations_deg))  # fmt: skip
        lines.append(line)
    names = _elevation_names(elevations_deg)
    # the two highest elevations end close together: the highest is labelled on its left
    direct_labels(ax, lines, names, at=1.0, offsets={
        n: ((-5, 0), "right") if k == len(names) - 1 else ((5, 0), "left")
        for k, n in enumerate(names)})  # fmt: skip
    ax.axhline(20, color=OKABE_ITO["black"], lw=0.8, ls=":")
    ax.annotate("20 km", (1, 20), xycoords=("axes fraction", "data"), xytext=(-2, 3),
                textcoords="offset points", ha="right", fontsize=8)  # fmt: skip
    ax.set_xlabel(r"drag coefficient $C_D$")
    ax.set_ylabel("altitude (km)")
    return fig
