"""Figures are saved by number, deterministically (two regenerations are byte-identical),
atomically, and as vector PDFs whose fonts are embedded as TrueType (Type 42)."""

import hashlib
import inspect
import io
import re
import zlib
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from fontTools.pens.recordingPen import DecomposingRecordingPen
from fontTools.ttLib import TTFont
from matplotlib import font_manager
from matplotlib.backends import _backend_pdf_ps
from matplotlib.mathtext import MathTextParser

from harp_analysis.foundation import paths
from harp_analysis.reporting import plotting, save_shortcuts


@pytest.fixture
def figures_dir(tmp_path, monkeypatch):
    monkeypatch.setattr(paths, "FIGURES_DIR", tmp_path)
    return tmp_path


def _digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_save_figure_names_file_by_number_and_is_deterministic(figures_dir):
    fig, ax = plotting.new_figure()
    ax.plot(np.arange(10), np.arange(10) ** 2)
    first = _digest(plotting.save_figure(fig, "2.1"))
    second_path = plotting.save_figure(fig, "2.1")
    assert second_path == figures_dir / "fig_2_1.png"
    assert _digest(second_path) == first
    assert b"Software" not in second_path.read_bytes()
    assert b"tIME" not in second_path.read_bytes()  # no PNG time chunk


def test_save_figure_refuses_unregistered_or_fileless_numbers(figures_dir):
    fig, _ = plotting.new_figure()
    with pytest.raises(ValueError, match="'8.1'"):
        plotting.save_figure(fig, "8.1")
    with pytest.raises(ValueError, match="'1.1'.*no output file"):
        plotting.save_figure(fig, "1.1")
    with pytest.raises(TypeError, match="fig must be a matplotlib Figure"):
        plotting.save_figure("figure", "2.1")


def _figure():
    """A line plot as the notebooks draw them: mathtext labels, a legend, minus signs."""
    fig, ax = plotting.new_figure()
    x = np.linspace(0.0, 10.0, 50)
    ax.plot(x, np.sin(x) - 0.5, label=r"$\beta = 0.3$", **plotting.style("3DOF"))
    ax.plot(x, np.cos(x), label=r"$\tau\,v_0$", **plotting.style("MKS", "HP"))
    ax.set_xlabel(r"Range $x$ (km)")
    ax.set_ylabel(r"Elevation $\theta_0$ ($^\circ$)")
    ax.legend()
    return fig


def _pdf_objects(data: bytes) -> dict[int, tuple[bytes, bytes]]:
    """Object number -> (its dictionary, its stream inflated) of a PDF as matplotlib writes it."""
    found = {}
    pattern = rb"(\d+) 0 obj\s*(.*?)(?:\nstream\n(.*?)\nendstream)?\s*endobj"
    for match in re.finditer(pattern, data, re.DOTALL):
        stream = match[3] or b""
        if b"/FlateDecode" in match[2]:
            stream = zlib.decompress(stream)
        found[int(match[1])] = match[2], stream
    return found


def _page(pdf: bytes) -> bytes:
    """The drawing of the PDF's page: its first stream (matplotlib writes the page first)."""
    return next(stream for head, stream in _pdf_objects(pdf).values() if b"/Length" in head)


def _embedded_fonts(pdf: bytes) -> list[TTFont]:
    objects = _pdf_objects(pdf)
    numbers = re.findall(rb"/FontFile2 (\d+) 0 R", pdf)
    return [TTFont(io.BytesIO(objects[int(number)][1])) for number in numbers]


def test_save_figure_pdf_is_deterministic_whatever_the_subset_cache(figures_dir):
    fig = _figure()
    png = plotting.save_figure(fig, "2.1")
    pdf = png.with_suffix(".pdf")
    first = _digest(png), _digest(pdf)
    save_shortcuts.subset_font.cache_clear()  # the fonts subset afresh, then taken from the cache
    for _ in range(2):
        plotting.save_figure(fig, "2.1")
        assert (_digest(png), _digest(pdf)) == first
    for stamp in (b"/Creator", b"/Producer", b"/CreationDate", b"matplotlib"):
        assert stamp not in pdf.read_bytes()


def test_save_figure_pdf_is_vector_with_embedded_truetype_fonts(figures_dir):
    pdf = plotting.save_figure(_figure(), "2.1").with_suffix(".pdf").read_bytes()
    objects = _pdf_objects(pdf)
    dictionaries = b"\n".join(dictionary for dictionary, _ in objects.values())
    assert b"/Subtype /Type3" not in dictionaries  # journals refuse Type 3 fonts
    assert b"/Subtype /Image" not in dictionaries  # nothing rasterised
    fonts = re.findall(rb"/Subtype /CIDFontType2", dictionaries)
    embedded = _embedded_fonts(pdf)
    assert len(fonts) == len(embedded) >= 2  # every font (text, mathtext italics) embedded
    for font in embedded:
        assert {"glyf", "loca", "hmtx", "cmap"} <= set(font.keys())
        assert not {"GSUB", "GPOS"} & set(font.keys())  # the lean subsetting is in force
    assert b" l\n" in _page(pdf) and b" TJ\n" in _page(pdf)  # lines as paths, text as text


def _outlines(font: TTFont, glyph: str):
    pen = DecomposingRecordingPen(font.getGlyphSet())
    font.getGlyphSet()[glyph].draw(pen)
    program = font["glyf"][glyph].program if hasattr(font["glyf"][glyph], "program") else None
    return pen.value, font["hmtx"][glyph], program and program.getBytecode()


def test_lean_subset_embeds_the_glyphs_matplotlib_would():
    path = font_manager.findfont("DejaVu Sans")
    font = font_manager.get_font(path)
    glyphs = {font.get_char_index(ord(c)) for c in "Range (km) −0.5 fiAV°"}
    data = save_shortcuts.subset_font(str(path), path.face_index, frozenset(glyphs))[0]
    with save_shortcuts.lean_glyphs_subset(path, glyphs) as lean:
        # what matplotlib embeds is the cached font, byte for byte (no time stamp added)
        assert _backend_pdf_ps.font_as_file(lean.font).getvalue() == data
        with _backend_pdf_ps.get_glyphs_subset(path, glyphs) as full:
            for glyph in glyphs:
                ours = lean.font.getGlyphOrder()[lean.glyph_index_map[glyph]]
                theirs = full.font.getGlyphOrder()[full.glyph_index_map[glyph]]
                assert _outlines(lean.font, ours) == _outlines(full.font, theirs)
            for table in ("fpgm", "prep", "cvt ", "gasp"):  # the hinting
                assert lean.font[table].compile(lean.font) == full.font[table].compile(full.font)


def _hooks():
    return _backend_pdf_ps.get_glyphs_subset, vars(MathTextParser)["_parse_cached"]


def test_shortcuts_are_checked_against_the_pinned_matplotlib():
    """The private hooks are used with the matplotlib they were read against, and no other."""
    pinned = re.search(r"^matplotlib==(\S+)$", (paths.ROOT / "environment.txt").read_text(), re.M)
    assert pinned and pinned[1] == save_shortcuts.CHECKED_MATPLOTLIB == matplotlib.__version__, (
        "matplotlib changed: re-read backend_pdf's embedTTFType42, "
        "_backend_pdf_ps.get_glyphs_subset and MathTextParser.parse, then update "
        "save_shortcuts.CHECKED_MATPLOTLIB"
    )
    original = _hooks()
    assert list(inspect.signature(original[0]).parameters) == ["fontfile", "glyphs"]
    assert list(inspect.signature(original[1]).parameters) == [
        *("self", "s", "dpi", "prop", "antialiased", "load_glyph_flags")
    ]
    with save_shortcuts.shortcuts():
        assert _backend_pdf_ps.get_glyphs_subset is save_shortcuts.lean_glyphs_subset
        assert vars(MathTextParser)["_parse_cached"] is not original[1]
    assert _hooks() == original


@pytest.mark.parametrize("turned_off", ["by the switch", "by another matplotlib"])
def test_shortcuts_change_no_pixel_and_no_drawing(figures_dir, monkeypatch, turned_off):
    """Saved with matplotlib's own ways (the shortcuts switched off, or under another
    matplotlib) and with the shortcuts: the same PNG, the same PDF page; only the embedded
    fonts are leaner."""
    fig = _figure()
    saved = []
    for on in (False, True):
        with monkeypatch.context() as patch:
            if not on and turned_off == "by the switch":
                patch.setenv(save_shortcuts.SWITCH, "0")
            elif not on:
                patch.setattr(matplotlib, "__version__", "99.0")
            assert save_shortcuts.enabled() is on
            png = plotting.save_figure(fig, "2.1")
            saved.append((png.read_bytes(), png.with_suffix(".pdf").read_bytes()))
    (own_png, own_pdf), (png, pdf) = saved
    assert png == own_png
    assert _page(pdf) == _page(own_pdf)
    assert all("GSUB" in font for font in _embedded_fonts(own_pdf))
    assert not any("GSUB" in font for font in _embedded_fonts(pdf))


def test_save_figure_writes_atomically(figures_dir, monkeypatch):
    fig = _figure()
    png = plotting.save_figure(fig, "2.1")
    pdf = png.with_suffix(".pdf")
    before = pdf.read_bytes()
    savefig = fig.savefig

    def interrupted(target, **keywords):
        if keywords["format"] != "pdf":
            return savefig(target, **keywords)
        Path(target).write_bytes(b"%PDF-1.4 truncated")
        raise KeyboardInterrupt

    monkeypatch.setattr(fig, "savefig", interrupted)
    hooks = _hooks()
    with pytest.raises(KeyboardInterrupt):
        plotting.save_figure(fig, "2.1")
    assert pdf.read_bytes() == before  # the previous figure, whole
    assert sorted(p.name for p in figures_dir.iterdir()) == ["fig_2_1.pdf", "fig_2_1.png"]
    assert _hooks() == hooks  # matplotlib's own, back in place
