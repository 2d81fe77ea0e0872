"""Two shortcuts through matplotlib's saving, each by one of its private functions, in place
only while :func:`.plotting.save_figure` writes.

Saving spends its time in two places that matplotlib offers no setting for. (Writing the PDF in
a thread would gain nothing: the engines' compiled kernels hold the GIL.)

Fonts. Embedding a TrueType (Type 42) font, the PDF backend has fontTools subset it from the
whole file with its layout tables (GSUB, GPOS, GDEF, MATH, kern) and glyph names: ~50 ms a
font, four fonts a figure, nearly half of saving it. A PDF reads none of them: matplotlib has
laid the text out with the full font, the page places every glyph, a CIDToGIDMap finds it by
index and the ToUnicode map gives its text. Subset without them, a font takes ~19 ms, and the
glyph sets that recur (tick digits, the minus sign, mathtext's italics) are subset once per
process. The outlines, advances and hinting embedded are the same (tests/test_figures.py
compares them). The hook: ``_backend_pdf_ps.get_glyphs_subset(fontpath, glyph indices)``,
which ``embedTTFType42`` enters as a context manager, then serialises its ``.font`` (a TTFont)
and reads its ``.glyph_index_map`` (old glyph index -> the subset's). Upstream: the subsetting
came with matplotlib pull request 20391 (Type42 subsetting in PS/PDF), which keeps every table
and has no option to drop any.

Mathtext. Each renderer has a MathTextParser of its own, whose cache is keyed by the parser,
so each of the four drawings of a save (tight box and image, for the PNG and the PDF) lays
every mathtext string out afresh, a few ms each. The layout depends on the parser only by its
output type (raster or vector); within one save (the rcParams fixed) each is laid out once
per output type, size and font. The hook: ``MathTextParser._parse_cached(parser, s, dpi, prop,
antialiased, load_glyph_flags)``, the cached part of ``MathTextParser.parse``. Upstream:
matplotlib issue 20821 (mathtext.MathTextParser is slow), open.

The switch: ``HARP_ANALYSIS_SAVE_SHORTCUTS=0`` turns both off, and they are off under any
matplotlib but the release they were read against (:data:`CHECKED_MATPLOTLIB`, environment.txt's
pin; a test holds the two equal). Off, matplotlib's own ways run: the same PNG and the same PDF
page, with larger fonts embedded, in about 1.4 times the time (benchmarks/bench_figures.py).
"""

from __future__ import annotations

import contextlib
import functools
import io
import os
from types import SimpleNamespace
from typing import Any

import matplotlib
from fontTools import subset
from fontTools.ttLib import TTFont
from matplotlib.backends import _backend_pdf_ps
from matplotlib.mathtext import MathTextParser

__all__ = [
    "CHECKED_MATPLOTLIB",
    "SWITCH",
    "enabled",
    "lean_glyphs_subset",
    "shortcuts",
    "subset_font",
]

#: The matplotlib release whose private functions the shortcuts were read against.
CHECKED_MATPLOTLIB = "3.11.2"
#: The environment variable that turns the shortcuts off when "0".
SWITCH = "HARP_ANALYSIS_SAVE_SHORTCUTS"
_NOT_READ_BY_PDF = ["GSUB", "GPOS", "GDEF", "MATH", "kern", "FFTM"]  # FFTM: FontForge's stamp


def enabled() -> bool:
    """Whether the shortcuts are taken: not switched off, and under the matplotlib checked."""
    return os.environ.get(SWITCH) != "0" and matplotlib.__version__ == CHECKED_MATPLOTLIB


@functools.lru_cache(maxsize=256)
def subset_font(path: str, face_index: int, glyphs: frozenset[int]) -> tuple[bytes, dict]:
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
def lean_glyphs_subset(fontfile, glyphs):
    """:func:`subset_font` in the form of matplotlib's ``get_glyphs_subset``; a fresh TTFont
    each time, as matplotlib closes it, which re-serialises to the same bytes (left to its
    defaults, fontTools would stamp the time of saving into the font's head table)."""
    data, glyph_index_map = subset_font(str(fontfile), fontfile.face_index, frozenset(glyphs))
    with TTFont(io.BytesIO(data), recalcBBoxes=False, recalcTimestamp=False) as font:
        yield SimpleNamespace(font=font, glyph_index_map=glyph_index_map)


@contextlib.contextmanager
def shortcuts():
    """Inside, if :func:`enabled`, PDFs embed their fonts through :func:`lean_glyphs_subset`
    and each mathtext layout is shared by every renderer of its output type."""
    if not enabled():
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

    _backend_pdf_ps.get_glyphs_subset = lean_glyphs_subset
    MathTextParser._parse_cached = parse_once
    try:
        yield
    finally:
        _backend_pdf_ps.get_glyphs_subset = subset_glyphs
        MathTextParser._parse_cached = parse
