"""Derived arrays kept on disk by what they were computed from, as compiled kernels are.

An engine that learns a table from its own flights (:mod:`harp_analysis.engines.calibrated_mks`)
computes it once per user and version of the physics: the arrays are saved in the user's cache
folder beside the compiled kernels (:func:`.kernel_digest.cache_folder`, named by a digest of every
source file the computing module reaches and of the compiler's versions, so an edit to the
physics computes afresh, and every checkout of the same sources shares them), under a
name that is a digest of the key the caller gives (what the table was learned from). Processes
computing the same table at once take turns under a file lock, the later one loading what the
first saved; a file is written to a temporary name and renamed into place, so a reader never
sees half of one. Loaded arrays are read-only.

``HARP_ANALYSIS_STORE=0`` keeps nothing on disk (every table computed afresh in the process).
"""

from __future__ import annotations

import hashlib
import os
import tempfile
from collections.abc import Callable
from pathlib import Path

import numpy as np
from filelock import FileLock

from .kernel_digest import cache_folder

__all__ = ["stored_arrays", "store_enabled"]


def store_enabled() -> bool:
    """Whether tables are kept on disk (``HARP_ANALYSIS_STORE`` unset or not ``0``)."""
    return os.environ.get("HARP_ANALYSIS_STORE", "1") != "0"


def _read_only(arrays: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    for array in arrays.values():
        array.flags.writeable = False
    return arrays


def stored_arrays(
    module_name: str, name: str, key: str, compute: Callable[[], dict[str, np.ndarray]]
) -> tuple[dict[str, np.ndarray], bool]:
    """The arrays ``compute()`` returns (a dict of name to array), kept on disk for
    ``module_name`` under ``name`` and a digest of ``key``; and whether they were loaded, not
    computed. The arrays are read-only."""
    if not store_enabled():
        return _read_only({k: np.asarray(v) for k, v in compute().items()}), False
    folder = cache_folder(module_name) / name
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{hashlib.sha256(key.encode()).hexdigest()[:20]}.npz"
    with FileLock(str(path) + ".lock"):
        if path.is_file():
            with np.load(path) as saved:
                return _read_only({k: saved[k] for k in saved.files}), True
        arrays = {k: np.asarray(v) for k, v in compute().items()}
        handle, temporary = tempfile.mkstemp(dir=folder, suffix=".npz")
        try:
            with os.fdopen(handle, "wb") as file:
                np.savez(file, **arrays)  # type: ignore[arg-type]  # names, not flags
            os.replace(temporary, path)
        except BaseException:
            Path(temporary).unlink(missing_ok=True)
            raise
    return _read_only(arrays), False
