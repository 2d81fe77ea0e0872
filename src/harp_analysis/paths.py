"""Where things live, resolved once so code works from any working directory.

nbmake runs every notebook from its own folder and users start JupyterLab anywhere, so no
module may rely on the current directory.

- ``HARP_DATA_DIR``: the HARP tables, which ship inside the package
  (``harp_analysis/_data/harp``, a link to the repository's ``data/harp`` in a checkout and a
  copy in an installed wheel), found through :mod:`importlib.resources`. They load wherever the
  package is installed.
- ``ROOT`` and the folders under it (``COMMITTED_FIGURES_DIR``, ``NOTEBOOKS_DIR``,
  ``REGISTRY_DIR``, ``DATA_DIR``): the repository checkout, found from this file's location (an
  editable install from ``src/``) or the environment variable ``HARP_ANALYSIS_ROOT``. Only the
  figure registry, the ledger and ``make figures`` need them; asking for one without a checkout
  raises a RuntimeError that says how to point at one.
- ``FIGURES_DIR``: where :func:`harp_analysis.plotting.save_figure` writes. It is the folder
  ``HARP_ANALYSIS_FIGURES_DIR`` names, which ``make figures`` sets to the committed ``figures/``;
  without it, a scratch folder in the system's temporary directory, so running or editing a
  notebook never overwrites the committed figures unless asked to.
"""

from __future__ import annotations

import os
import tempfile
from importlib import resources
from pathlib import Path

__all__ = [  # noqa: F822 (the checkout folders are served by __getattr__ below)
    "ROOT",
    "DATA_DIR",
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
    root = Path(override).resolve() if override else Path(__file__).resolve().parents[2]
    return root if (root / "registry").is_dir() and (root / "data" / "harp").is_dir() else None


_ROOT = _find_root()
_IN_CHECKOUT = {
    "ROOT": lambda root: root,
    "DATA_DIR": lambda root: root / "data",
    "COMMITTED_FIGURES_DIR": lambda root: root / "figures",
    "NOTEBOOKS_DIR": lambda root: root / "notebooks",
    "REGISTRY_DIR": lambda root: root / "registry",
}


def write_atomically(path: Path, write) -> Path:
    """Call ``write(temporary_path)`` and rename the result onto ``path``, so a reader never
    sees a half-written file (a figure, the gallery, the ledger), even if the run is stopped."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(
        dir=path.parent, prefix=f".{path.stem}-", suffix=path.suffix
    )
    os.close(handle)
    try:
        write(Path(temporary))
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    return path


def __getattr__(name: str) -> Path:
    if name == "FIGURES_DIR":
        chosen = os.environ.get("HARP_ANALYSIS_FIGURES_DIR")
        scratch = Path(tempfile.gettempdir()) / "harp-analysis-figures"
        return Path(chosen).resolve() if chosen else scratch
    if name not in _IN_CHECKOUT:
        raise AttributeError(f"module 'harp_analysis.paths' has no attribute {name!r}")
    if _ROOT is None:
        raise RuntimeError(
            f"harp_analysis.paths.{name} needs the repository checkout (registry, figures, "
            "notebooks), and none was found beside the installed package. Install with "
            "`pip install -e .` from a checkout, or set HARP_ANALYSIS_ROOT to its path."
        )
    return _IN_CHECKOUT[name](_ROOT)
