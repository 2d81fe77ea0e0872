"""The figures of Chapter 5 (Figs 5.1-5.11): reporting on :mod:`.eci` and :mod:`.rotating`.

The schematics (Figs 5.1-5.3, 5.10, 5.11) draw the computed launch vectors in top (east,
north) and side (east, up) views, km/s; each vector has one look in every schematic, black or
dark grey with a line style of its own (no model's colour: they are not models), so they read
in grey. Figs 5.4-5.9 draw the ECI MKS's distance from the rotating-Earth 3DOF at equal time,
one curve per gun elevation in the house's elevation shades, each labelled beside itself.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import FancyArrowPatch
from matplotlib.transforms import Bbox

from ...analyses import rotating
from ...engines.eci import LaunchCorrection
from ...models.launch import Launch, baseline_chapter_4
from ...models.trajectory import launch_frame
from ..plotting import FULL_WIDTH_IN, OKABE_ITO, elevation_style, keep_markers_whole, new_figure

__all__ = [
    "VECTOR_STYLES",
    "SCHEMATICS",
    "local_components",
    "draw_launch_schematic",
    "draw_east_west",
    "TOP_KM",
    "draw_distance_at_equal_time",
    "label_beside_curves",
]

_DARK_GREY = "#4D4D4D"  # a vector that is neither a model nor a measurement
#: One look per vector in every schematic, told apart by line style and width.
VECTOR_STYLES: dict[str, dict[str, Any]] = {
    "vrel": dict(color=OKABE_ITO["black"], linestyle="-", lw=1.6),
    "surface": dict(color=_DARK_GREY, linestyle=":", lw=2.0),
    "corrected": dict(color=OKABE_ITO["black"], linestyle="--", lw=1.5),
    "tangent": dict(color=_DARK_GREY, linestyle="-.", lw=1.8),
    "corrections": dict(color=_DARK_GREY, linestyle=(0, (5, 1.5, 1, 1.5, 1, 1.5)), lw=1.8),
    "final": dict(color=OKABE_ITO["black"], linestyle="-", lw=3.0),
    "drag": dict(color=_DARK_GREY, linestyle=(0, (1, 1)), lw=1.4),
}
_VIEWS = {
    "top": ((0, 1), "east (km/s)", "north (km/s)"),
    "side": ((0, 2), "east (km/s)", "up (km/s)"),
}
_V_REL, _V_TAN, _OMEGA_R0 = r"$V_\mathrm{rel}$", r"$V_\mathrm{tangent}$", r"$\omega \times r_0$"


def local_components(vector, latitude_rad: float) -> np.ndarray:
    """(east, north, up) components of an inertial vector at longitude 0."""
    up, north, east = launch_frame(latitude_rad, 0.0, 0.0)
    return np.array([vector @ np.ravel(east), vector @ np.ravel(north), vector @ np.ravel(up)])


def _arrow(ax, start, vec, plane, kind: str, head: str = "-|>"):
    """Draw ``vec`` (east, north, up; km/s) from ``start`` projected on ``plane`` (two
    indices); returns its tip."""
    s = (float(start[plane[0]]), float(start[plane[1]]))
    e = (s[0] + float(vec[plane[0]]), s[1] + float(vec[plane[1]]))
    look = VECTOR_STYLES[kind]
    ax.add_patch(
        FancyArrowPatch(s, e, arrowstyle=head, color=look["color"], lw=look["lw"],
                        linestyle=look["linestyle"], shrinkA=0, shrinkB=0, mutation_scale=12,
                        zorder=3)
    )  # fmt: skip
    ax.update_datalim([s, e])
    return e


def _vector_handles(entries) -> list[Line2D]:
    """Legend samples of the vectors ``entries``, a list of (kind, label)."""
    return [
        Line2D([], [], color=VECTOR_STYLES[k]["color"], linestyle=VECTOR_STYLES[k]["linestyle"],
               lw=VECTOR_STYLES[k]["lw"], label=label)
        for k, label in entries
    ]  # fmt: skip


def _finish(ax, xlabel: str, ylabel: str) -> None:
    ax.plot(0, 0, "k.", zorder=4)
    ax.autoscale_view()
    ax.margins(0.12)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)


def _vectors(correction: LaunchCorrection, latitude_rad: float) -> dict[str, np.ndarray]:
    """The schematics' vectors (east, north, up; km/s) of one launch correction."""
    vrel = local_components(np.ravel(correction.relative_m_s), latitude_rad) / 1e3
    surface = local_components(np.ravel(correction.surface_m_s), latitude_rad) / 1e3
    final = local_components(np.ravel(correction.velocity_m_s), latitude_rad) / 1e3
    return {"vrel": vrel, "surface": surface, "corrected": vrel + surface, "final": final}


def _draw_surface(ax, v, plane, view) -> None:
    _arrow(ax, np.zeros(3), v["vrel"], plane, "vrel")
    _arrow(ax, v["vrel"], v["surface"], plane, "surface")
    _arrow(ax, np.zeros(3), v["corrected"], plane, "corrected")


def _draw_misalignment(ax, v, plane, view) -> None:
    vrel, corrected = v["vrel"], v["corrected"]
    _arrow(ax, np.zeros(3), vrel, plane, "vrel")
    _arrow(ax, np.zeros(3), corrected, plane, "corrected")
    # the drag: a direction only, along -Vrel, drawn at a fixed share of the panel's vectors
    shown = np.array([[w[plane[0]], w[plane[1]]] for w in (vrel, corrected)])
    along = -np.array([vrel[plane[0]], vrel[plane[1]]])
    drag = np.zeros(3)
    drag[list(plane)] = 0.35 * np.linalg.norm(shown, axis=1).max() * along / np.linalg.norm(along)
    _arrow(ax, np.zeros(3), drag, plane, "drag", head="->")
    # mu: the arc between the two directions in space, at 45 % of |Vrel|, projected
    a, b = vrel / np.linalg.norm(vrel), corrected / np.linalg.norm(corrected)
    angle = math.acos(np.clip(a @ b, -1.0, 1.0))
    t = np.linspace(0.0, 1.0, 50)[:, None]
    arc = (np.sin((1 - t) * angle) * a + np.sin(t * angle) * b) / math.sin(angle)
    arc *= 0.45 * np.linalg.norm(vrel)
    if view == "side":  # nearly the plane of the two vectors (in the top view they foreshorten)
        ax.plot(arc[:, plane[0]], arc[:, plane[1]], color="k", lw=1.0, zorder=4)
        middle = arc[len(arc) // 2]
        ax.annotate(rf"$\mu$ = {math.degrees(angle):.1f}°", (middle[plane[0]], middle[plane[1]]),
                    textcoords="offset points", xytext=(14, -4), fontsize=9, ha="left",
                    va="center", bbox=dict(facecolor="white", edgecolor="none", pad=1))  # fmt: skip


def _draw_inertial(ax, v, plane, view) -> None:
    tangent = v["final"] - v["corrected"]
    _arrow(ax, np.zeros(3), v["vrel"], plane, "vrel")
    _arrow(ax, v["vrel"], v["surface"], plane, "surface")
    _arrow(ax, v["corrected"], tangent, plane, "tangent")
    _arrow(ax, np.zeros(3), v["final"], plane, "final")
    if view == "side":  # enlarge the tip, where V_tangent closes the sum
        ends = np.array([[w[plane[0]], w[plane[1]]] for w in (v["corrected"], v["final"])])
        centre, half = ends.mean(axis=0), 0.09
        inset = ax.inset_axes([0.58, 0.06, 0.40, 0.40])
        _arrow(inset, v["vrel"], v["surface"], plane, "surface")
        _arrow(inset, v["corrected"], tangent, plane, "tangent")
        _arrow(inset, np.zeros(3), v["final"], plane, "final")
        inset.set_xlim(centre[0] - half, centre[0] + half)
        inset.set_ylim(centre[1] - half, centre[1] + half)
        inset.set_aspect("equal")
        inset.set_xticks([])
        inset.set_yticks([])
        inset.set_title("tip, enlarged", fontsize=8, pad=2)
        ax.indicate_inset_zoom(inset, edgecolor=OKABE_ITO["grey"])


#: The schematics of one launch's correction: figure -> (what it draws, its legend's vectors).
SCHEMATICS = {
    "5.1": (
        _draw_surface,
        [("vrel", _V_REL + " (gun)"), ("surface", _OMEGA_R0 + " (eq 6.16)"),
         ("corrected", _V_REL + " + " + _OMEGA_R0)],
    ),
    "5.2": (
        _draw_misalignment,
        [("vrel", _V_REL + " (gun; the air-relative velocity)"),
         ("corrected", _V_REL + " + " + _OMEGA_R0),
         ("drag", "drag direction, " + r"$-V_\mathrm{rel}$ (not to scale)")],
    ),
    "5.3": (
        _draw_inertial,
        [("vrel", _V_REL + " (gun)"), ("surface", _OMEGA_R0 + ", from its tip"),
         ("tangent", _V_TAN + " (eq 5.8), to scale, from that tip"),
         ("final", r"$V$ (eq 6.15), from the origin")],
    ),
}  # fmt: skip


def draw_launch_schematic(
    number: str, correction: LaunchCorrection, latitude_rad: float, case: str
):
    """Figs 5.1-5.3 (:data:`SCHEMATICS`): top and side views of ``correction``'s vectors at
    ``latitude_rad``, titled ``case``, one legend below both."""
    draw, entries = SCHEMATICS[number]
    vectors = _vectors(correction, latitude_rad)
    fig, axes = new_figure(1, 2, figsize=(FULL_WIDTH_IN, 4.2), layout="constrained")
    for ax, (view, (plane, xlabel, ylabel)) in zip(axes, _VIEWS.items()):
        draw(ax, vectors, plane, view)
        _finish(ax, xlabel, ylabel)
        ax.set_title(f"{view} view", fontsize=9)
    fig.legend(handles=_vector_handles(entries), loc="outside lower center", ncol=2, fontsize=8,
               handlelength=3)  # fmt: skip
    fig.suptitle(case, fontsize=9)
    return fig


def draw_east_west(shot: Launch, correction: LaunchCorrection):
    """Figs 5.10 and 5.11: the side view of ``shot``'s V_rel, the corrections from its tip and
    the inertial V (eq 6.15) from the origin."""
    vectors = _vectors(correction, shot.latitude_rad)
    vrel, final = vectors["vrel"], vectors["final"]
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.8), layout="constrained")
    _arrow(ax, np.zeros(3), vrel, (0, 2), "vrel")
    _arrow(ax, vrel, final - vrel, (0, 2), "corrections")
    _arrow(ax, np.zeros(3), final, (0, 2), "final")
    _finish(ax, "east (km/s)", "up (km/s)")
    entries = [
        ("vrel", _V_REL + f" (gun, {shot.elevation_deg:g}°)"),
        ("corrections", _OMEGA_R0 + " + " + _V_TAN + r", from the tip of $V_\mathrm{rel}$"),
        ("final", rf"$V$ (eq 6.15), {math.degrees(float(correction.elevation_rad)):.1f}°"),
    ]
    fig.legend(handles=_vector_handles(entries), loc="outside lower center", ncol=2, fontsize=8,
               handlelength=3)  # fmt: skip
    fig.suptitle(
        f"{shot.projectile.name} cone, {shot.speed_m_s / 1e3:.3f} km/s at {shot.elevation_deg:g}°, "
        f"bearing {shot.bearing_deg:03.0f}°T, latitude {shot.latitude_deg:g}°",
        fontsize=9,
    )
    return fig


#: The directions :func:`label_beside_curves` tries a label in about a point: every 45°.
_DIRECTIONS = [(math.cos(a), math.sin(a)) for a in np.linspace(0.0, 2 * math.pi, 9)[:-1]]
#: Its gaps between a point and the label's near edge, in label heights.
_GAPS = (0.4, 0.8, 1.4)


def label_beside_curves(ax, lines, labels, obstacles_px=(), *, fontsize: float = 8.5) -> list:
    """Label each of ``lines`` beside itself: of the places just off its points (eight
    directions, three gaps) whose text box crosses no curve, leaves the axes nowhere and
    covers no placed label nor ``obstacles_px`` (display points, e.g. markers), the one where
    its own curve is nearest relative to the nearest other curve, so that a label cannot be
    read as another curve's. Returns the texts. Call it once the axes are laid out."""
    renderer = ax.figure.canvas.get_renderer()
    paths = [line.get_transform().transform_path(line.get_path()) for line in lines]
    curves = [ax.transData.transform(np.column_stack(line.get_data())) for line in lines]
    marker_px = 1.5 * fontsize * ax.figure.dpi / 72.0  # a marker of about 11-13 pt
    taken = [Bbox.from_bounds(x - marker_px / 2, y - marker_px / 2, marker_px, marker_px)
             for x, y in obstacles_px]  # fmt: skip
    texts = []
    for k, label in enumerate(labels):
        text = ax.text(0.0, 0.0, label, ha="center", va="center", fontsize=fontsize, zorder=6,
                       color=OKABE_ITO["black"])  # fmt: skip
        size = text.get_window_extent(renderer)
        others = np.concatenate([c for j, c in enumerate(curves) if j != k] or [np.empty((0, 2))])
        cx, cy, box = _place_beside(ax, curves[k], others, paths, taken, size.width, size.height)
        taken.append(box)
        text.set_position(ax.transData.inverted().transform((cx, cy)))
        texts.append(text)
    return texts


def _place_beside(ax, own, others, paths, taken, width: float, height: float):
    """Where :func:`label_beside_curves` puts a ``width`` by ``height`` label of curve ``own``
    (display points), among curves ``others``: its centre and box. The places are tried
    about every 80th point of ``own``; one nowhere clear (:func:`_clear`) is the curve's
    middle, as a last resort."""
    best, best_score = None, np.inf
    step = max(len(own) // 80, 1)
    for x, y in own[::step]:
        for dx, dy in _DIRECTIONS:
            for gap in _GAPS:
                cx = x + dx * (gap * height + width / 2)
                cy = y + dy * (gap * height + height / 2)
                box = Bbox.from_bounds(cx - width / 2, cy - height / 2, width, height)
                if not _clear(ax, box, paths, taken):
                    continue
                near = np.hypot(*(own - (cx, cy)).T).min()
                other = np.hypot(*(others - (cx, cy)).T).min() if len(others) else np.inf
                if near / other < best_score:
                    best, best_score = (cx, cy, box), near / other
    if best is None:
        mx, my = own[len(own) // 2]
        best = (mx, my, Bbox.from_bounds(mx, my, 0.0, 0.0))
    return best


def _clear(ax, box, paths, taken) -> bool:
    """Whether ``box`` lies within ``ax``, crosses none of ``paths`` and covers none of
    ``taken`` (boxes, display points)."""
    return (
        ax.bbox.contains(box.x0, box.y0)
        and ax.bbox.contains(box.x1, box.y1)
        and not any(path.intersects_bbox(box, filled=False) for path in paths)
        and not any(box.overlaps(other) for other in taken)
    )


#: The distance axis of Figs 5.4-5.9 (km): the same in every figure.
TOP_KM = 4.0
_OFF_SCALE: dict[str, Any] = dict(
    marker=r"$\uparrow$", color=OKABE_ITO["black"], markersize=11, linestyle="none"
)


def draw_distance_at_equal_time(latitude_deg: float, bearing_deg: float):
    """Figs 5.4-5.9: the ECI MKS's distance from the rotating-Earth 3DOF at equal time against
    the 3DOF's ground range (:func:`~harp_analysis.analyses.rotating.case`), the baseline cone at
    :data:`~harp_analysis.analyses.rotating.ELEVATIONS_DEG`, each curve labelled beside itself; a
    star at the 3DOF's apogee; a curve that leaves the :data:`TOP_KM` axis is marked with an arrow
    where it does, its maximum in the legend."""
    elevations = rotating.ELEVATIONS_DEG
    fig, ax = new_figure(figsize=(FULL_WIDTH_IN, 3.6), layout="constrained")
    lines, marks, handles = [], [], []  # marks: the stars and arrows, which labels avoid
    for elevation in elevations:
        flight, _, errors = rotating.case(latitude_deg, bearing_deg, elevation)
        x, y = errors.ground_range_m.to_numpy() / 1e3, errors.error_m.to_numpy() / 1e3
        (line,) = ax.plot(x, y, label=f"{elevation:g}°", **elevation_style(elevation, elevations))
        lines.append(line)
        handles.append(line)
        k = np.argmin(np.abs(errors.time_s.to_numpy() - flight.attrs["apogee_time_s"]))
        ax.plot(x[k], y[k], "*", ms=11, mfc=line.get_color(), mec="k", mew=0.8, zorder=5)
        marks.append((x[k], y[k]))
        above = np.flatnonzero(y > TOP_KM)
        if len(above):  # the curve leaves the axis: mark where, give its maximum
            ax.plot(x[above[0]], TOP_KM, clip_on=False, zorder=6, **_OFF_SCALE)
            marks.append((x[above[0]], TOP_KM))
            handles.append(
                Line2D([], [], **_OFF_SCALE,
                       label=f"{elevation:g}° leaves the axis;\nits maximum {y.max():.1f} km")
            )  # fmt: skip
    handles.append(
        Line2D([], [], ls="none", marker="*", ms=11, mfc="w", mec="k", label="3DOF apogee")
    )
    ax.set_ylim(0, TOP_KM)
    ax.set_xlim(left=0)
    ax.set_xlabel("3DOF ground range (km)")
    ax.set_ylabel("distance from the 3DOF\nat equal time (km)")
    speed = baseline_chapter_4(elevations[0]).speed_m_s
    ax.set_title(f"baseline cone, {speed:.0f} m/s, latitude {latitude_deg:g}°, "
                 f"bearing {bearing_deg:03.0f}°T", fontsize=9, pad=12)  # fmt: skip
    fig.legend(handles=handles, title="gun elevation", title_fontsize=8, fontsize=8,
               loc="outside right upper")  # fmt: skip
    fig.canvas.draw()  # the layout fixes the axes' place, which the labels are placed in
    label_beside_curves(ax, lines, [f"{e:g}°" for e in elevations], ax.transData.transform(marks))
    keep_markers_whole(fig, lines)  # none cut where the distances start, near 0, or leave the axis
    return fig
