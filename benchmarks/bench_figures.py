"""Cost of saving a figure, PNG and PDF, against the way it was saved before (``python
benchmarks/bench_figures.py``; ``--smoke`` for one quick round that checks what is written).

The figure is one the notebooks would draw: 6.5 in wide, four models' curves with markers,
mathtext labels and a legend. The reference is how
:func:`harp_analysis.reporting.plotting.save_figure` saved before: ``fig.savefig`` to a 300 dpi PNG,
then to a PDF, in the house style (TrueType fonts, no stamps), each through a temporary file,
matplotlib subsetting the fonts and laying mathtext out in each of the save's four drawings. The
package subsets the fonts without the tables a PDF never reads, keeps each subset for glyph sets
that recur, and lays each mathtext string out once per save: timed with its font cache emptied
before every save (a figure of new text) and kept (one whose text was seen before). Printed: the
best time per save of each (interleaved rounds), the ratio to the reference, and the PDFs' sizes;
checked (every run): the PNGs are byte-identical and every PDF embeds its fonts as TrueType, none as
Type 3.
"""

import os
import re
import sys
import tempfile
from pathlib import Path

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
from measure import interleaved_best

from harp_analysis.foundation.paths import write_atomically
from harp_analysis.reporting import plotting, save_shortcuts

matplotlib.use("agg")

NUMBER = "4.11"  # a registered figure: its file name only


def representative_figure():
    fig, ax = plotting.new_figure()
    elevation = np.linspace(20.0, 85.0, 300)
    for k, engine in enumerate(("3DOF", "6DOF", "MLT", "MKS")):
        apogee = 180.0 * np.sin(np.radians(elevation)) ** 2 * (1.0 - 0.04 * k)
        ax.plot(
            elevation, apogee, label=rf"{engine}, $v_0 = 2.1$ km/s", **plotting.style(engine, "HP")
        )
    ax.set_xlabel(r"Gun elevation $\theta_0$ ($^\circ$)")
    ax.set_ylabel(r"Apogee $h_{\max}$ (km)")
    ax.set_title(r"Apogee against elevation, $\beta = 0.31$, $\tau = -0.05$")
    ax.legend()
    return fig


def reference_save(fig, png: Path) -> Path:
    """The way figures were saved before: ``fig.savefig`` to each file, matplotlib's subsetting."""
    metadata = {
        ".png": {"Software": None},
        ".pdf": {"Creator": None, "Producer": None, "CreationDate": None},
    }
    with plt.rc_context(plotting.HOUSE_STYLE):  # type: ignore[arg-type]
        for path, backend in ((png, "agg"), (png.with_suffix(".pdf"), "pdf")):
            write_atomically(
                path,
                lambda target, path=path, backend=backend: fig.savefig(
                    target,
                    dpi=plotting.DPI,
                    metadata=metadata[path.suffix],
                    backend=backend,
                    format=path.suffix[1:],
                ),
            )
    return png


def check_fonts(pdf: Path) -> None:
    """Every font of ``pdf`` embedded as TrueType (CIDFontType2 with a FontFile2), no Type 3."""
    data = pdf.read_bytes()
    fonts = len(re.findall(rb"/Subtype /CIDFontType2", data))
    if b"/Subtype /Type3" in data or not fonts or fonts != data.count(b"/FontFile2"):
        raise AssertionError(f"{pdf.name}: fonts not all embedded as TrueType")


def main(smoke: bool = False) -> None:
    fig = representative_figure()
    with tempfile.TemporaryDirectory() as scratch:
        previous = os.environ.get("HARP_ANALYSIS_FIGURES_DIR")
        os.environ["HARP_ANALYSIS_FIGURES_DIR"] = str(Path(scratch) / "package")
        try:
            reference_png = Path(scratch) / "reference" / "figure.png"
            new_png = plotting.save_figure(fig, NUMBER)
            reference_save(fig, reference_png)

            def afresh():
                save_shortcuts.subset_font.cache_clear()
                plotting.save_figure(fig, NUMBER)

            times = interleaved_best(
                {
                    "reference: fig.savefig PNG, then PDF": lambda: reference_save(
                        fig, reference_png
                    ),
                    "save_figure, fonts subset afresh": afresh,
                    "save_figure, glyph sets seen before": lambda: plotting.save_figure(
                        fig, NUMBER
                    ),
                },
                rounds=1 if smoke else 7,
            )
            if new_png.read_bytes() != reference_png.read_bytes():
                raise AssertionError("the PNG differs from the reference's")
            for pdf in (reference_png.with_suffix(".pdf"), new_png.with_suffix(".pdf")):
                check_fonts(pdf)
            sizes = [
                png.with_suffix(".pdf").stat().st_size / 1e3 for png in (reference_png, new_png)
            ]
        finally:
            if previous is None:
                del os.environ["HARP_ANALYSIS_FIGURES_DIR"]
            else:
                os.environ["HARP_ANALYSIS_FIGURES_DIR"] = previous
    plt.close(fig)
    lean = save_shortcuts.enabled()
    print(
        f"Saving a {plotting.FULL_WIDTH_IN} in wide line plot (PNG {plotting.DPI} dpi + PDF, "
        f"TrueType fonts), best of {1 if smoke else 7} interleaved rounds; matplotlib "
        f"{matplotlib.__version__}, lean subsetting "
        f"{'on' if lean else 'OFF (switched off, or an unchecked release)'}"
    )
    reference = times["reference: fig.savefig PNG, then PDF"]
    print(f"{'case':<40} {'per save (s)':>13} {'vs reference':>13}")
    for name, seconds in times.items():
        print(f"{name:<40} {seconds:>13.3f} {reference / seconds:>12.2f}x")
    print(f"PDF size: reference {sizes[0]:.1f} kB, save_figure {sizes[1]:.1f} kB")
    print("PNG byte-identical to the reference's; every PDF font embedded as TrueType")


if __name__ == "__main__":
    main(smoke="--smoke" in sys.argv)
