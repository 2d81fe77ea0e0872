"""Regenerated figures match the committed ones to an image tolerance.

`make test` runs this after executing every notebook into a scratch folder, named by
``HARP_ANALYSIS_REGENERATED_FIGURES``; without it the test is skipped. The tolerance is an RMS
difference of 0.5 (of 255) per pixel: the last-bit differences between machines measured
0.001-0.17, while a moved curve or a changed label is several times larger.
"""

import os
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from harp_analysis.foundation import paths
from harp_analysis.reporting import registry

TOLERANCE_RMS = 0.5
REGENERATED = os.environ.get("HARP_ANALYSIS_REGENERATED_FIGURES")
FIGURES = [e for e in registry.load_registry() if e.file.endswith(".png")]


def _pixels(path: Path) -> np.ndarray:
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.int16)


def _rms(old: np.ndarray, new: np.ndarray) -> float:
    """Root-mean-square difference per pixel channel (0-255), as matplotlib's calculate_rms."""
    difference = (old - new).astype(np.float32)
    return float(np.sqrt(np.mean(difference * difference, dtype=np.float64)))


@pytest.mark.skipif(not REGENERATED, reason="set by `make test` after the notebooks run")
@pytest.mark.parametrize("entry", FIGURES, ids=lambda e: e.number)
def test_regenerated_figure_matches_the_committed_one(entry):
    committed = paths.COMMITTED_FIGURES_DIR / entry.file
    regenerated = Path(str(REGENERATED)) / entry.file
    assert regenerated.is_file(), f"{entry.label}: the notebooks did not draw {entry.file}"
    assert regenerated.with_suffix(".pdf").is_file(), f"{entry.label}: no vector PDF"
    old, new = _pixels(committed), _pixels(regenerated)
    assert old.shape == new.shape, (
        f"{entry.label}: size changed {old.shape[:2]} -> {new.shape[:2]}; run `make figures`"
    )
    rms = _rms(old, new)
    assert rms <= TOLERANCE_RMS, (
        f"{entry.label}: differs from figures/{entry.file} by RMS {rms:.3f} > {TOLERANCE_RMS}; "
        "if the change is meant, run `make figures` and commit"
    )
