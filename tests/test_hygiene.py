"""Machine hygiene: each user's own scratch folder for figures, and files written with the mode
the user's umask gives any new file (the committed figures are not left readable by one user)."""

import os
import stat
import tempfile

import pytest

from harp_analysis.foundation import paths
from harp_analysis.reporting import plotting


def _mode(path):
    return stat.S_IMODE(path.stat().st_mode)


@pytest.fixture
def temporary_directory(tmp_path, monkeypatch):
    """The system's temporary directory, as tempfile finds it, moved to ``tmp_path``."""
    monkeypatch.delenv("HARP_ANALYSIS_FIGURES_DIR", raising=False)
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    return tmp_path


def test_the_scratch_figure_folder_is_the_user_s_own(temporary_directory):
    folder = paths.FIGURES_DIR
    assert folder == temporary_directory / f"harp-analysis-figures-{os.getuid()}"
    assert folder.is_dir() and _mode(folder) == 0o700
    assert paths.FIGURES_DIR == folder  # found again, not made anew


def test_a_scratch_folder_of_another_user_is_refused(temporary_directory, monkeypatch):
    other = os.getuid() + 1
    (temporary_directory / f"harp-analysis-figures-{other}").mkdir()  # owned by this user
    monkeypatch.setattr(os, "getuid", lambda: other)
    with pytest.raises(PermissionError, match="belongs to another user.*HARP_ANALYSIS_FIGURES_DIR"):
        _ = paths.FIGURES_DIR


@pytest.mark.parametrize("umask", [0o022, 0o002, 0o077], ids=oct)
def test_files_are_written_with_the_user_s_umask(tmp_path, monkeypatch, umask):
    """A new file and a replaced one get 0o666 less the umask, as a file the user creates."""
    monkeypatch.setattr(paths, "FIGURES_DIR", tmp_path)
    target = tmp_path / "table.md"
    previous = os.umask(umask)
    try:
        for text in ("first", "second"):
            paths.write_atomically(target, lambda path, text=text: path.write_text(text))
            assert _mode(target) == 0o666 & ~umask and target.read_text() == text
        fig, _ = plotting.new_figure()
        png = plotting.save_figure(fig, "2.1")
    finally:
        os.umask(previous)
    assert _mode(png) == _mode(png.with_suffix(".pdf")) == 0o666 & ~umask
    assert sorted(path.name for path in tmp_path.iterdir()) == [
        "fig_2_1.pdf",
        "fig_2_1.png",
        "table.md",
    ]  # no temporary file left behind
