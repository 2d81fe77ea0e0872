"""Figure helpers: one house style, one meaning per colour, one deterministic way to save.

Styles. Series are told apart without colour, and each colour means one thing across the set
(:func:`style`):

- the model or engine has a colour of the Okabe-Ito palette (safe for colour-blind readers)
  and a line style: 3DOF solid blue, 6DOF dashed orange, MLT dash-dot green, MKS dotted
  vermillion (the project's improved MKS sky blue, dash-dot-dotted; the calibrated MKS
  vermillion and the fly-out table blue, both dashed, their dashes their own); a quantity of
  one model (its air, its error, its series length) takes that model's colour; black is
  measured data and the exact references a figure is read against (the 1976 standard
  atmosphere, a straight line, conical-flow values), grey the text's own values and formulas;
- the projectile has a marker: HP circle, LP square, the baseline cone triangle;
- the gun elevation has a shade of reddish purple, light to dark from 30 to 85 deg, and a
  marker of its own; such curves are also labelled directly (:func:`label_lines`).

Saving. :func:`save_figure` writes each figure twice, a vector PDF and a 300 dpi PNG, under
the registry's name, exactly :data:`FULL_WIDTH_IN` wide (the page is the figure's own size,
never a box cropped to the ink: everything drawn must fit it, as constrained layout makes it,
and notes belong in the registry's caption, not around the axes), once :func:`figure_defects`
finds nothing wrong with it (labels over labels or over curves, data clipped silently, any
text off the page, markers cut by the axes' edge), with no software or time stamps, through a
temporary file renamed into place: an interrupted run never leaves a truncated figure. The
PDF's fonts are embedded as TrueType (Type 42), subset without the tables a PDF never reads, and
mathtext is laid out once per save (:mod:`.save_shortcuts`, which says how to turn both off): a
save takes about 70 % of the time matplotlib's own ways take (benchmarks/bench_figures.py).
"""

from __future__ import annotations

import contextlib
import functools
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import lines as mlines
from matplotlib.figure import Figure
from matplotlib.markers import MarkerStyle
from matplotlib.path import Path as MplPath
from matplotlib.text import Text
from matplotlib.transforms import Bbox, IdentityTransform

from ..foundation.paths import write_atomically
from . import save_shortcuts
from .registry import figure_file

__all__ = [
    "HOUSE_STYLE",
    "DPI",
    "FULL_WIDTH_IN",
    "COLUMN_WIDTH_IN",
    "OKABE_ITO",
    "ENGINE_STYLES",
    "PROJECTILE_MARKERS",
    "style",
    "elevation_style",
    "label_lines",
    "keep_markers_whole",
    "new_figure",
    "figure_defects",
    "label_overlaps",
    "save_figure",
    "save_table",
]

DPI = 300
#: A journal page's text width and a column's (inches).
FULL_WIDTH_IN, COLUMN_WIDTH_IN = 6.5, 3.4
HOUSE_STYLE: dict[str, Any] = {
    "figure.figsize": (FULL_WIDTH_IN, 4.2),
    "font.family": "DejaVu Sans",  # bundled with matplotlib: identical glyphs on every machine
    "mathtext.fontset": "dejavusans",
    "font.size": 10,
    "legend.fontsize": 8.5,
    "axes.grid": True,
    "grid.alpha": 0.35,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "legend.frameon": False,
    "lines.linewidth": 1.6,
    "savefig.dpi": DPI,
    "savefig.bbox": "standard",  # the page is the figure: FULL_WIDTH_IN wide, whatever it holds
    "path.simplify": False,
    "pdf.fonttype": 42,  # TrueType in the PDF: editable text
}
#: Okabe and Ito's colour-blind-safe palette.
OKABE_ITO = {
    "black": "#000000",
    "orange": "#E69F00",
    "sky blue": "#56B4E9",
    "bluish green": "#009E73",
    "yellow": "#F0E442",
    "blue": "#0072B2",
    "vermillion": "#D55E00",
    "reddish purple": "#CC79A7",
    "grey": "#7F7F7F",
}
#: Each model's colour and line style, the same in every figure.
ENGINE_STYLES: dict[str, dict[str, Any]] = {
    "3DOF": {"color": OKABE_ITO["blue"], "linestyle": "-"},
    "6DOF": {"color": OKABE_ITO["orange"], "linestyle": "--"},
    "MLT": {"color": OKABE_ITO["bluish green"], "linestyle": "-."},
    "MKS": {"color": OKABE_ITO["vermillion"], "linestyle": ":"},
    # the project's improved MKS (harp_analysis.engines.mks_improved), beside the text's
    "improved MKS": {"color": OKABE_ITO["sky blue"], "linestyle": (0, (6, 2, 1, 2, 1, 2))},
    # the learned tables of a gun: the MKS corrected by the 3DOF's flights takes the MKS's
    # colour, the 3DOF's flights tabulated the 3DOF's; both dashed, their own dashes
    "calibrated MKS": {"color": OKABE_ITO["vermillion"], "linestyle": (0, (5, 2))},
    "fly-out table": {"color": OKABE_ITO["blue"], "linestyle": (0, (9, 2, 2, 2))},
    "measured": {"color": OKABE_ITO["black"], "linestyle": "none", "marker": "o"},
    "text": {"color": OKABE_ITO["grey"], "linestyle": "none", "marker": "x"},
}
PROJECTILE_MARKERS = {"HP": "o", "LP": "s", "baseline": "^"}
_ELEVATION_MARKERS = ("o", "s", "^", "D", "v", "P")
_PURPLES = ("#E7B5D3", "#CC79A7", "#9B4D7C", "#5E2A4B", "#3A1A2E", "#1F0E18")


def style(
    engine: str | None = None, projectile: str | None = None, every: int | None = None
) -> dict:
    """Line keywords for a series: the ``engine``'s colour and line style, the
    ``projectile``'s marker (every ``every`` points; default about a dozen per line)."""
    keywords: dict[str, Any] = {}
    if engine is not None:
        key = "MKS" if engine.startswith("MKS") or engine.startswith("ECI") else engine
        keywords.update(ENGINE_STYLES[key])
    if projectile is not None:
        keywords.update(
            marker=PROJECTILE_MARKERS[projectile],
            markersize=4,
            markevery=every or 0.08,
            markerfacecolor="none",
        )
    return keywords


def elevation_style(elevation_deg: float, elevations_deg) -> dict:
    """Keywords for the curve of ``elevation_deg`` among ``elevations_deg``: a shade of one hue
    (darker, higher) and a marker of its own, so it reads in grey and without colour."""
    order = sorted(elevations_deg).index(elevation_deg)
    shades = _PURPLES[: max(len(elevations_deg), 2)]
    return {
        "color": shades[order],
        "marker": _ELEVATION_MARKERS[order],
        "markersize": 4,
        "markevery": 0.1,
    }


def label_lines(ax, lines, labels, *, at: float = 0.85, fontsize: float = 8.0):
    """Label each of ``lines`` directly, next to the point ``at`` (0-1) along its data."""
    for line, label in zip(lines, labels):
        x, y = line.get_xdata(), line.get_ydata()
        if len(x) == 0:
            continue
        i = min(int(at * (len(x) - 1)), len(x) - 1)
        ax.annotate(
            label,
            (x[i], y[i]),
            textcoords="offset points",
            xytext=(3, 3),
            color=line.get_color(),
            fontsize=fontsize,
        )


def new_figure(nrows: int = 1, ncols: int = 1, **kwargs):
    """``plt.subplots`` in the house style, which stays in force for what is drawn on the
    figure afterwards (legends, lines); returns ``(fig, axes)``. The page :func:`save_figure`
    writes is the figure's own size, so what is drawn must fit it: ``layout="constrained"``
    fits the axes' labels, ticks and legends (a figure laid out by hand, ``subplots_adjust``,
    must fit them itself; :func:`figure_defects` finds ink off the page)."""
    plt.rcParams.update(HOUSE_STYLE)  # type: ignore[arg-type]  # keys checked at run time
    return plt.subplots(nrows, ncols, **kwargs)


#: How far (points) ink may overlap before :func:`figure_defects` calls it a defect: the
#: antialiased edge of a glyph or line, not a visible overlap.
_OVERLAP_TOLERANCE_PT = 0.5


def _texts(ax) -> list:
    """The labels drawn inside or beside ``ax``: its texts and annotations with text, and its
    legend."""
    texts = [t for t in ax.texts if t.get_visible() and t.get_text().strip()]
    legend = ax.get_legend()
    return texts + ([legend] if legend is not None and legend.get_visible() else [])


def _name(artist) -> str:
    if hasattr(artist, "get_text"):
        return repr(artist.get_text().replace("\n", " "))
    if hasattr(artist, "get_label") and not artist.get_label().startswith("_"):
        return f"{type(artist).__name__} {artist.get_label()!r}"
    return type(artist).__name__


def _markers_only(line) -> bool:
    return line.get_linestyle() in ("None", "none", "", " ")  # as matplotlib spells "none"


def _shrunk(box, points: float, dpi: float):
    pad = points * dpi / 72.0
    return box.padded(-pad) if box.width > 2 * pad and box.height > 2 * pad else box


def _data_outside_limits(ax) -> list[str]:
    """Series ``ax`` clips silently: a line drawn wholly outside the axes' limits, or a point
    of a marker-only series (one shown only by its markers) outside them."""
    found = []
    view = ax.viewLim
    for line in ax.lines:
        if not line.get_visible() or len(line.get_xydata()) == 0:
            continue
        if line.get_transform() != ax.transData:  # axes or mixed coordinates (axhline): inside
            continue
        points = ax.transScale.transform(line.get_xydata())
        limits = ax.transScale.transform([[view.x0, view.y0], [view.x1, view.y1]])
        low, high = limits.min(axis=0), limits.max(axis=0)
        finite = points[(points == points).all(axis=1)]
        inside = ((finite >= low) & (finite <= high)).all(axis=1)
        marker_only = _markers_only(line)
        if len(finite) and not inside.any():
            found.append(f"{_name(line)} lies wholly outside the axes' limits")
        elif marker_only and not inside.all():
            found.append(
                f"{_name(line)}: {int((~inside).sum())} of its points outside the axes' limits"
            )
    return found


def _box(label, renderer):
    """The box of ``label``'s ink: a text's own (an annotation's would hold its arrow too)."""
    extent = Text.get_window_extent if isinstance(label, Text) else type(label).get_window_extent
    return _shrunk(extent(label, renderer), _OVERLAP_TOLERANCE_PT, label.figure.dpi)


def label_overlaps(ax, label, renderer, *, labels=None) -> list[str]:
    """What ``label`` (a text, annotation or legend of ``ax``, laid out by ``renderer``) lies
    over: each of ``labels`` (default: every other label of ``ax``) whose box overlaps its box,
    and each curve of ``ax`` whose visible (clipped) part crosses it, as phrases."""
    box = _box(label, renderer)
    found = [
        f"overlaps {_name(other)}"
        for other in (_texts(ax) if labels is None else labels)
        if other is not label and box.overlaps(_box(other, renderer))
    ]
    return found + [f"sits over {_name(line)}" for line in _curves_crossing(ax, box)]


def _curves_crossing(ax, box) -> list:
    """The curves of ``ax`` whose visible part (within the axes, unless unclipped) crosses
    ``box`` (display points); markers alone are no curve."""
    crossing = []
    for line in ax.lines:
        if not line.get_visible() or _markers_only(line):
            continue
        seen = Bbox.intersection(box, ax.bbox) if line.get_clip_on() else box
        path = line.get_transform().transform_path(line.get_path())
        if seen is not None and path.intersects_bbox(seen, filled=False):
            crossing.append(line)
    return crossing


def _off_the_page(label, renderer) -> bool:
    figure = label.get_figure(root=True)
    page = figure.bbox.padded(_OVERLAP_TOLERANCE_PT * figure.dpi / 72.0)
    box = _box(label, renderer)
    return not (page.contains(box.x0, box.y0) and page.contains(box.x1, box.y1))


@contextlib.contextmanager
def _recording_texts() -> Iterator[list[Text]]:
    """Inside, every text drawn with something to show (tick labels, axis labels, titles,
    legends' entries, annotations, contour labels) is appended to the list yielded: exactly
    what a drawing shows, where a text's own settings cannot tell (a tick outside the limits,
    an annotation whose point is clipped, an axes switched off)."""
    drawn: list[Text] = []
    draw = Text.draw

    @functools.wraps(draw)
    def recorded(text, renderer):
        draw(text, renderer)
        if text.get_visible() and text.get_text().strip():
            drawn.append(text)

    Text.draw = recorded  # type: ignore[method-assign, assignment]  # restored below
    try:
        yield drawn
    finally:
        Text.draw = draw  # type: ignore[method-assign]


def _axes_name(ax) -> str:
    """An axes as messages name it: by its title, else its y label, else its place."""
    name = " ".join((ax.get_title() or ax.get_ylabel()).split("\n"))
    return f"axes {name!r}" if name else f"axes {ax.get_figure(root=True).axes.index(ax)}"


def _text_roles(fig) -> dict[int, str]:
    """What each text of ``fig`` that is part of something is (by ``id``): an axes' "x label",
    "y tick label", "title", a legend's "legend entry", with its axes' name, for messages."""
    roles = {}
    for ax in fig.axes:
        where = _axes_name(ax)
        roles[id(ax.title)] = f"{where}: title"
        for letter, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
            roles[id(axis.label)] = f"{where}: {letter} label"
            roles[id(axis.offsetText)] = f"{where}: {letter} axis's offset"
            for tick in [*axis.majorTicks, *axis.minorTicks]:
                roles.update(dict.fromkeys((id(tick.label1), id(tick.label2)),
                                           f"{where}: {letter} tick label"))  # fmt: skip
    for legend in [*(ax.get_legend() for ax in fig.axes), *fig.legends]:
        if legend is not None:
            roles.update(dict.fromkeys(map(id, legend.texts), "legend entry"))
            roles[id(legend.get_title())] = "legend title"
    return roles


def _texts_off_the_page(fig, drawn, renderer) -> list[str]:
    """Each of the ``drawn`` texts of ``fig``, and each legend, not wholly on the page, named
    by what it is (:func:`_text_roles`): a y label longer than the axes is tall, a tick label
    past the page's edge."""
    roles = _text_roles(fig)
    found = []
    for text in drawn:
        if _off_the_page(text, renderer):
            role = roles.get(id(text)) or (
                f"{_axes_name(text.axes)}: text" if text.axes is not None else "figure text"
            )
            found.append(f"{role} {_name(text)} runs off the page")
    legends = [ax.get_legend() for ax in fig.axes] + fig.legends
    for legend in legends:
        if legend is not None and legend.get_visible() and _off_the_page(legend, renderer):
            found.append(f"a legend of {len(legend.texts)} entries runs off the page")
    return found


def _marked(line) -> np.ndarray:
    """The indices of ``line``'s points that carry a marker: every finite one, or those
    ``markevery`` picks, as matplotlib subsamples them when it draws the line."""
    centres = line.get_transform().transform(line.get_xydata())
    finite = np.isfinite(centres).all(axis=1)
    if line.get_markevery() is None:
        return np.flatnonzero(finite)
    # matplotlib's own subsampling, as Line2D.draw's (a private function of matplotlib.lines)
    kept = mlines._mark_every_path(  # type: ignore[attr-defined]
        line.get_markevery(), MplPath(centres), IdentityTransform(), line.axes
    ).vertices
    return np.flatnonzero(finite & (centres[:, None, :] == kept[None]).all(axis=2).any(axis=1))


def _cut_markers(line, renderer) -> tuple[np.ndarray, np.ndarray]:
    """The indices of ``line``'s points that carry a marker the axes may cut (:func:`_marked`;
    none if it has no markers or is not clipped), and which of those markers its axes cut: their
    centre within their own half-size of the axes' edge, inside or out, so that they show in
    part."""
    marker = MarkerStyle(line.get_marker())
    drawn = np.asarray(marker.get_path().vertices).size  # none for "None", "" and " "
    if not line.get_visible() or not line.get_clip_on() or not drawn:
        return np.array([], dtype=int), np.array([], dtype=bool)
    marked = _marked(line)
    centres = line.get_transform().transform(line.get_xydata()[marked])
    # the marker's ink about its centre (pixels): its outline at the marker's size, and half its
    # edge's width, less the lint's tolerance
    shape = marker.get_path().get_extents(marker.get_transform())
    size = renderer.points_to_pixels(line.get_markersize())
    edge = renderer.points_to_pixels(line.get_markeredgewidth()) / 2.0
    tolerance = renderer.points_to_pixels(_OVERLAP_TOLERANCE_PT)
    low = centres + size * np.array([shape.x0, shape.y0]) - edge + tolerance
    high = centres + size * np.array([shape.x1, shape.y1]) + edge - tolerance
    box = line.axes.bbox
    seen = ((high > [box.x0, box.y0]) & (low < [box.x1, box.y1])).all(axis=1)
    whole = ((low >= [box.x0, box.y0]) & (high <= [box.x1, box.y1])).all(axis=1)
    return marked, seen & ~whole


def _markers_cut(ax, renderer) -> list[str]:
    """Series whose markers ``ax`` cuts (``_cut_markers()``): data points on the axes' limits
    (the axes need margins, or limits that take the markers in), or a curve's marker where it
    leaves the axes (:func:`keep_markers_whole`). A marker wholly outside is not cut but hidden
    (``_data_outside_limits()`` says where that is a defect)."""
    found = []
    for line in ax.lines:
        marked, cut = _cut_markers(line, renderer)
        if cut.any():
            x, y = line.get_xydata()[marked[cut][0]]
            found.append(
                f"{_name(line)}: {int(cut.sum())} of its markers cut by the axes' edge, the "
                f"first at ({x:.4g}, {y:.4g}) (the axes need margins)"
            )
    return found


def keep_markers_whole(fig, lines=None) -> None:
    """Leave out of each of ``lines`` (curves marked every few points, as laid out in ``fig``;
    default every curve of ``fig`` with markers) the markers its axes would cut
    (``_cut_markers()``): where a curve leaves the axes, or runs along an axis, its line goes
    to the edge and its markers stop short of it. Call it once the figure is laid out (its
    limits, labels and legends set). Not for a series of markers only, whose every marker is a
    datum (ValueError if given one): its axes need margins."""
    if lines is None:
        lines = [line for ax in fig.axes for line in ax.lines if not _markers_only(line)]
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    for line in lines:
        if _markers_only(line):
            raise ValueError(f"{_name(line)} is markers only: give its axes margins instead")
        marked, cut = _cut_markers(line, renderer)
        if cut.any():
            line.set_markevery(marked[~cut].tolist())


def figure_defects(fig) -> list[str]:
    """What a reader would trip on in ``fig``, as drawn: its width other than
    :data:`FULL_WIDTH_IN`; any text (tick labels, axis labels of one line or more, titles,
    legends, annotations) off the page (``_texts_off_the_page()``); within an axes, two
    labels (texts, annotations, the legend) over one another, or a label over a curve
    (:func:`label_overlaps`); markers cut by the axes' edge (``_markers_cut()``); the labels
    of different panels over one another (``_decorations_overlapping()``); data clipped
    silently (``_data_outside_limits()``). Empty when there is none."""
    found = []
    if abs(fig.get_figwidth() - FULL_WIDTH_IN) > 1e-9:
        found.append(f"the figure is {fig.get_figwidth():g} in wide, not {FULL_WIDTH_IN:g} in")
    with _recording_texts() as drawn:
        fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    found += _texts_off_the_page(fig, drawn, renderer)
    for ax in fig.axes:
        where = _axes_name(ax)
        labels = _texts(ax)
        for i, label in enumerate(labels):
            overlaps = label_overlaps(ax, label, renderer, labels=labels[i + 1 :])
            found += [f"{where}: {_name(label)} {overlap}" for overlap in overlaps]
        found += [f"{where}: {defect}" for defect in _data_outside_limits(ax)]
        found += [f"{where}: {defect}" for defect in _markers_cut(ax, renderer)]
    found += _decorations_overlapping(fig, renderer)
    return found


def _decorations_overlapping(fig, renderer) -> list[str]:
    """Labels of different axes, or of the figure, over one another: one panel's axis label
    over its neighbour's, a figure legend or title over an axes' label."""
    owned = _decorations(fig)
    found = []
    for i, (owner, label) in enumerate(owned):
        for other_owner, other in owned[i + 1 :]:
            if owner is not other_owner or owner is fig:
                if _box(label, renderer).overlaps(_box(other, renderer)):
                    found.append(f"{_name(label)} overlaps {_name(other)}")
    return found


def _decorations(fig) -> list[tuple]:
    """Each label shown around the panels, with its owner: the axes' titles and axis labels,
    the figure's texts and legends."""
    owned = [(ax, label) for ax in fig.axes for label in
             (ax.title, ax.xaxis.label, ax.yaxis.label) if label.get_visible() and
             label.get_text().strip()]  # fmt: skip
    owned += [(fig, text) for text in fig.texts if text.get_text().strip()]
    owned += [(fig, legend) for legend in fig.legends]
    return owned


# Metadata matplotlib would otherwise fill with its version and the time.
_NO_METADATA = {
    ".png": {"Software": None},
    ".pdf": {"Creator": None, "Producer": None, "CreationDate": None},
}


def save_figure(fig, number: str) -> Path:
    """Save ``fig`` as figure ``number`` (e.g. ``"2.1"`` -> ``figures/fig_2_1.png`` and
    ``fig_2_1.pdf``); returns the PNG's path.

    The file name comes from the figure registry, so only registered figures can be saved,
    and only if :func:`figure_defects` finds none (it raises ``ValueError`` naming them).
    Rendered by Agg (PNG, 300 dpi) and the PDF backend whatever the interactive backend, with
    no software or time stamps: saving the same figure twice gives byte-identical files.
    """
    if not isinstance(fig, Figure):
        raise TypeError(f"fig must be a matplotlib Figure; got {type(fig).__name__}")
    png = figure_file(number)
    defects = figure_defects(fig)
    if defects:
        raise ValueError(f"figure {number} is not fit to print: " + "; ".join(defects))
    house_style = plt.rc_context(HOUSE_STYLE)  # type: ignore[arg-type]  # keys checked at run time
    with house_style, save_shortcuts.shortcuts():
        for path, backend in ((png, "agg"), (png.with_suffix(".pdf"), "pdf")):
            write_atomically(
                path,
                lambda target, path=path, backend=backend: fig.savefig(
                    target,
                    dpi=DPI,
                    metadata=_NO_METADATA[path.suffix],
                    backend=backend,
                    format=path.suffix[1:],
                ),
            )
    return png


def save_table(frame, number: str, note: str = "") -> Path:
    """Save ``frame`` as dissertation table ``number`` (e.g. ``"Table 4.1"``): a Markdown table
    under the file name the registry gives, numbers to five significant figures."""
    from .registry import get_entry

    path = figure_file(number)
    header = "| | " + " | ".join(map(str, frame.columns)) + " |"
    lines = [
        f"# {number}: {get_entry(number).title}",
        "",
        note,
        "",
        header,
        "|---" * (len(frame.columns) + 1) + "|",
    ]
    for index, row in frame.iterrows():
        cells = (f"{value:.5g}" if isinstance(value, float) else str(value) for value in row)
        lines.append(f"| {index} | " + " | ".join(cells) + " |")
    text = "\n".join(lines) + "\n"
    return write_atomically(path, lambda target: target.write_text(text))
