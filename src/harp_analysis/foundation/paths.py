"""Where things live, resolved once so code works from any working directory.

nbmake runs every notebook from its own folder and users start JupyterLab anywhere, so no
module may rely on the current directory.

- ``HARP_DATA_DIR``: the HARP tables, which ship inside the package
  (``harp_analysis/_data/harp``, a link to the repository's ``data/harp`` in a checkout and a
  copy in an installed wheel), found through :mod:`importlib.resources`. They load wherever the
  package is installed.
- ``ROOT`` and the folders under it (``COMMITTED_FIGURES_DIR``, ``NOTEBOOKS_DIR``,
  ``REGISTRY_DIR``): the repository checkout, found from this file's location (an
  editable install from ``src/``) or the environment variable ``HARP_ANALYSIS_ROOT``. Only the
  figure registry, the ledger and ``make figures`` need them; asking for one without a checkout
  raises a RuntimeError that says how to point at one.
- ``FIGURES_DIR``: where :func:`harp_analysis.reporting.plotting.save_figure` writes. It is
  the folder ``HARP_ANALYSIS_FIGURES_DIR`` names, which ``make figures`` sets to the committed
  ``figures/``; without it, the user's own scratch folder in the system's temporary directory
  (``harp-analysis-figures-<uid>``, readable by its owner only), so running or editing a
  notebook never overwrites the committed figures unless asked to, and users of one machine
  never share it.
"""

from __future__ import annotations

import os
import secrets
import tempfile
from importlib import resources
from pathlib import Path

__all__ = [  # noqa: F822 (the checkout folders are served by __getattr__ below)
    "ROOT",
    "HARP_DATA_DIR",
    "FIGURES_DIR",
    "COMMITTED_FIGURES_DIR",
    "NOTEBOOKS_DIR",
    "REGISTRY_DIR",
    "write_atomically",
]

HARP_DATA_DIR = Path(str(resources.files("harp_analysis") / "_data" / "harp"))


def _find_root() -> Path | None:
    override = os.environ.get("HARP_ANALYSIS_ROOT")
    root = Path(override).resolve() if override else Path(__file__).resolve().parents[3]
    return root if (root / "registry").is_dir() and (root / "data" / "harp").is_dir() else None


_ROOT = _find_root()
_IN_CHECKOUT = {
    "ROOT": lambda root: root,
    "COMMITTED_FIGURES_DIR": lambda root: root / "figures",
    "NOTEBOOKS_DIR": lambda root: root / "notebooks",
    "REGISTRY_DIR": lambda root: root / "registry",
}


def write_atomically(path: Path, write) -> Path:
    """Call ``write(temporary_path)`` and rename the result onto ``path``, so a reader never
    sees a half-written file (a figure, the gallery, the ledger), even if the run is stopped.
    The file gets the mode of any file the user creates (0o666 less the umask), where
    ``tempfile.mkstemp`` would leave it readable by its owner only."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.parent / f".{path.stem}-{secrets.token_hex(8)}{path.suffix}"
    os.close(os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
    try:
        write(temporary)
        os.replace(temporary, path)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise
    return path


def _scratch_figures_dir() -> Path:
    """This user's scratch folder for figures, created readable by its owner only; a folder of
    that name that another user owns is refused (it could be read or replaced by them)."""
    folder = Path(tempfile.gettempdir()) / f"harp-analysis-figures-{os.getuid()}"
    folder.mkdir(mode=0o700, exist_ok=True)
    if folder.lstat().st_uid != os.getuid() or folder.is_symlink():
        raise PermissionError(
            f"the scratch figure folder {folder} belongs to another user (or is a link); "
            "remove it, or set HARP_ANALYSIS_FIGURES_DIR to a folder of your own"
        )
    return folder


def __getattr__(name: str) -> Path:
    if name == "FIGURES_DIR":
        chosen = os.environ.get("HARP_ANALYSIS_FIGURES_DIR")
        return Path(chosen).resolve() if chosen else _scratch_figures_dir()
    if name not in _IN_CHECKOUT:
        raise AttributeError(f"module 'harp_analysis.foundation.paths' has no attribute {name!r}")
    if _ROOT is None:
        raise RuntimeError(
            f"harp_analysis.foundation.paths.{name} needs the repository checkout (registry, "
            "figures, "
            "notebooks), and none was found beside the installed package. Install with "
            "`pip install -e .` from a checkout, or set HARP_ANALYSIS_ROOT to its path."
        )
    return _IN_CHECKOUT[name](_ROOT)
