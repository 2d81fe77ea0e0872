"""Figure helpers: one house style, one meaning per colour, one deterministic way to save.

Styles. Series are told apart without colour, and each colour means one thing across the set
(:func:`style`):

- the model or engine has a colour of the Okabe-Ito palette (safe for colour-blind readers)
  and a line style: 3DOF solid blue, 6DOF dashed orange, MLT dash-dot green, MKS dotted
  vermillion (the project's improved MKS sky blue, dash-dot-dotted); a quantity of one model
  (its air, its error, its series length) takes that model's colour; black is measured data and
  the exact references a figure is read against (the 1976 standard atmosphere, a straight
  line, conical-flow values), grey the text's own values and formulas;
- the projectile has a marker: HP circle, LP square, the baseline cone triangle;
- the gun elevation has a shade of reddish purple, light to dark from 30 to 85 deg, and a
  marker of its own; such curves are also labelled directly (:func:`label_lines`).

Saving. :func:`save_figure` writes each figure twice, a vector PDF and a 300 dpi PNG, under
the registry's name, exactly :data:`FULL_WIDTH_IN` wide (the page is the figure's own size,
never a box cropped to the ink: everything drawn must fit it, as constrained layout makes it,
and notes belong in the registry's caption, not around the axes), once :func:`figure_defects`
finds nothing wrong with it (labels over labels or over curves, data clipped silently, ink off
the page), with no software or time stamps, through a temporary file renamed into place: an
interrupted run never leaves a truncated figure. The PDF's fonts are embedded as TrueType
(Type 42), subset without the tables a PDF never reads, and mathtext is laid out once per save
(:func:`_shortcuts`): a save takes about 70 % of the time matplotlib's own ways take
(benchmarks/bench_figures.py).
"""

from __future__ import annotations

import contextlib
import functools
import io
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import matplotlib
import matplotlib.pyplot as plt
from fontTools import subset
from fontTools.ttLib import TTFont
from matplotlib.backends import _backend_pdf_ps
from matplotlib.figure import Figure
from matplotlib.mathtext import MathTextParser
from matplotlib.text import Text
from matplotlib.transforms import Bbox

from ..foundation.paths import write_atomically
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
        marker_only = line.get_linestyle() in ("None", "none", "", " ")
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
    found = []
    for other in _texts(ax) if labels is None else labels:
        if other is not label and box.overlaps(_box(other, renderer)):
            found.append(f"overlaps {_name(other)}")
    for line in ax.lines:
        if not line.get_visible() or line.get_linestyle() in ("None", "none", "", " "):
            continue
        seen = Bbox.intersection(box, ax.bbox) if line.get_clip_on() else box
        path = line.get_transform().transform_path(line.get_path())
        if seen is not None and path.intersects_bbox(seen, filled=False):
            found.append(f"sits over {_name(line)}")
    return found


def _off_the_page(label, renderer) -> bool:
    page = label.figure.bbox.padded(_OVERLAP_TOLERANCE_PT * label.figure.dpi / 72.0)
    box = _box(label, renderer)
    return not (page.contains(box.x0, box.y0) and page.contains(box.x1, box.y1))


def figure_defects(fig) -> list[str]:
    """What a reader would trip on in ``fig``, as drawn: its width other than
    :data:`FULL_WIDTH_IN`; ink off the page; within an axes, two labels (texts, annotations,
    the legend) over one another, or a label over a curve (:func:`label_overlaps`); the labels
    of different panels over one another (:func:`_decorations_overlapping`); data clipped
    silently (:func:`_data_outside_limits`). Empty when there is none."""
    found = []
    if abs(fig.get_figwidth() - FULL_WIDTH_IN) > 1e-9:
        found.append(f"the figure is {fig.get_figwidth():g} in wide, not {FULL_WIDTH_IN:g} in")
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        where = f"axes {ax.get_title() or ax.get_ylabel() or fig.axes.index(ax)!r}"
        labels = _texts(ax)
        for i, label in enumerate(labels):
            if _off_the_page(label, renderer):
                found.append(f"{where}: {_name(label)} runs off the page")
            overlaps = label_overlaps(ax, label, renderer, labels=labels[i + 1 :])
            found += [f"{where}: {_name(label)} {overlap}" for overlap in overlaps]
        found += [f"{where}: {defect}" for defect in _data_outside_limits(ax)]
    for text in fig.texts:
        if text.get_text().strip() and _off_the_page(text, renderer):
            found.append(f"figure text {_name(text)} runs off the page")
    found += _decorations_overlapping(fig, renderer)
    return found


def _decorations_overlapping(fig, renderer) -> list[str]:
    """Labels of different axes, or of the figure, over one another: one panel's axis label
    over its neighbour's, a figure legend or title over an axes' label."""
    owned = [(ax, label) for ax in fig.axes for label in
             (ax.title, ax.xaxis.label, ax.yaxis.label) if label.get_visible() and
             label.get_text().strip()]  # fmt: skip
    owned += [(fig, text) for text in fig.texts if text.get_text().strip()]
    owned += [(fig, legend) for legend in fig.legends]
    found = []
    for i, (owner, label) in enumerate(owned):
        for other_owner, other in owned[i + 1 :]:
            if owner is not other_owner or owner is fig:
                if _box(label, renderer).overlaps(_box(other, renderer)):
                    found.append(f"{_name(label)} overlaps {_name(other)}")
    return found


# Metadata matplotlib would otherwise fill with its version and the time.
_NO_METADATA = {
    ".png": {"Software": None},
    ".pdf": {"Creator": None, "Producer": None, "CreationDate": None},
}


# Saving spends its time in two places that matplotlib offers no setting for; save_figure takes
# a shorter way through each, by two of its private functions (:func:`_shortcuts`). (Writing the
# PDF in a thread would gain nothing: the engines' compiled kernels hold the GIL.)
#
# Fonts. Embedding a TrueType (Type 42) font, the PDF backend has fontTools subset it from the
# whole file with its layout tables (GSUB, GPOS, GDEF, MATH, kern) and glyph names: ~50 ms a
# font, four fonts a figure, nearly half of saving it. A PDF reads none of them: matplotlib has
# laid the text out with the full font, the page places every glyph, a CIDToGIDMap finds it by
# index and the ToUnicode map gives its text. Subset without them, a font takes ~19 ms, and the
# glyph sets that recur (tick digits, the minus sign, mathtext's italics) are subset once per
# process. The outlines, advances and hinting embedded are the same (tests/test_figures.py
# compares them). The hook: `_backend_pdf_ps.get_glyphs_subset(fontpath, glyph indices)`, which
# embedTTFType42 enters as a context manager, then serialises its `.font` (a TTFont) and reads
# its `.glyph_index_map` (old glyph index -> the subset's).
#
# Mathtext. Each renderer has a MathTextParser of its own, whose cache is keyed by the parser,
# so each of the four drawings of a save (tight box and image, for the PNG and the PDF) lays
# every mathtext string out afresh, a few ms each. The layout depends on the parser only by its
# output type (raster or vector); within one save (the rcParams fixed) each is laid out once
# per output type, size and font. The hook: `MathTextParser._parse_cached(parser, s, dpi, prop,
# antialiased, load_glyph_flags)`, the cached part of `MathTextParser.parse`.
#
# Both hooks are in place only while save_figure writes, and only under the matplotlib release
# they were read against, environment.txt's pin (a test holds the two equal); under any other,
# matplotlib's own ways run: slower, as correct.
_CHECKED_MATPLOTLIB = "3.11.2"
_NOT_READ_BY_PDF = ["GSUB", "GPOS", "GDEF", "MATH", "kern", "FFTM"]  # FFTM: FontForge's stamp


@functools.lru_cache(maxsize=256)
def _subset_font(path: str, face_index: int, glyphs: frozenset[int]) -> tuple[bytes, dict]:
    """The TrueType file of font ``path`` cut to ``glyphs`` (and .notdef), and the map of their
    glyph indices into it."""
    options = subset.Options(glyph_names=False, recommended_glyphs=True, font_number=face_index)
    options.drop_tables += _NOT_READ_BY_PDF
    with subset.load_font(path, options) as font:
        subsetter = subset.Subsetter(options=options)
        subsetter.populate(gids=glyphs)
        subsetter.subset(font)
        data = io.BytesIO()
        font.save(data, reorderTables=False)
    return data.getvalue(), subsetter.glyph_index_map


@contextlib.contextmanager
def _lean_glyphs_subset(fontfile, glyphs):
    """:func:`_subset_font` in the form of matplotlib's ``get_glyphs_subset``; a fresh TTFont
    each time, as matplotlib closes it, which re-serialises to the same bytes (left to its
    defaults, fontTools would stamp the time of saving into the font's head table)."""
    data, glyph_index_map = _subset_font(str(fontfile), fontfile.face_index, frozenset(glyphs))
    with TTFont(io.BytesIO(data), recalcBBoxes=False, recalcTimestamp=False) as font:
        yield SimpleNamespace(font=font, glyph_index_map=glyph_index_map)


@contextlib.contextmanager
def _shortcuts():
    """Inside, PDFs embed their fonts through :func:`_lean_glyphs_subset` and each mathtext
    layout is shared by every renderer of its output type (see the comment above)."""
    if matplotlib.__version__ != _CHECKED_MATPLOTLIB:
        yield
        return
    subset_glyphs = _backend_pdf_ps.get_glyphs_subset
    parse = vars(MathTextParser)["_parse_cached"]
    parsed: dict[tuple, Any] = {}

    def parse_once(parser, *arguments):
        key = (parser._output_type, *arguments)
        if key not in parsed:
            parsed[key] = parse(parser, *arguments)
        return parsed[key]

    _backend_pdf_ps.get_glyphs_subset = _lean_glyphs_subset
    MathTextParser._parse_cached = parse_once
    try:
        yield
    finally:
        _backend_pdf_ps.get_glyphs_subset = subset_glyphs
        MathTextParser._parse_cached = parse


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
    with house_style, _shortcuts():
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
