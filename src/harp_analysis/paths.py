"""Where things live in the repository, resolved once so code works from any working directory.

nbmake runs every notebook from its own folder and users start JupyterLab anywhere, so no
module may rely on the current directory. The repository root is found from this file's
location (the package is installed in editable mode from ``src/``); set the environment
variable ``HARP_ANALYSIS_ROOT`` to point elsewhere, for example at a checkout when the
package was installed without ``-e``.
"""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["ROOT", "DATA_DIR", "HARP_DATA_DIR", "FIGURES_DIR", "NOTEBOOKS_DIR", "REGISTRY_DIR"]


def _find_root() -> Path:
    override = os.environ.get("HARP_ANALYSIS_ROOT")
    root = Path(override).resolve() if override else Path(__file__).resolve().parents[2]
    if not (root / "data" / "harp").is_dir():
        raise RuntimeError(
            f"harp_analysis cannot find its repository at {root} (no data/harp folder there). "
            "Install the package with `pip install -e .` from a checkout, or set "
            "HARP_ANALYSIS_ROOT to the checkout's path."
        )
    return root


ROOT = _find_root()
DATA_DIR = ROOT / "data"
HARP_DATA_DIR = DATA_DIR / "harp"
FIGURES_DIR = Path(os.environ.get("HARP_ANALYSIS_FIGURES_DIR", ROOT / "figures")).resolve()
NOTEBOOKS_DIR = ROOT / "notebooks"
REGISTRY_DIR = ROOT / "registry"
