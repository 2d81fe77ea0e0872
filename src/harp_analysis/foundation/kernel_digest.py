"""What decides a compiled kernel's machine code, as one digest: the folder it is cached in.

A kernel's folder (:func:`cache_folder`) is named by a digest of the contents of every source
file of the package the kernel's module reaches, import by import (a formula it calls from
another module counts), and of the versions that compile it (numba's, llvmlite's, Python's, and
the CPU's name and features as numba sees them). Neither the files' paths nor their modification
times count: every checkout, worktree, virtual environment and CI run of the same sources and
versions on a machine shares the one folder. The folders live in the user's cache folder,
``$XDG_CACHE_HOME/harp-analysis/kernels`` (``~/.cache/harp-analysis/kernels`` if
``XDG_CACHE_HOME`` is unset); ``HARP_ANALYSIS_KERNEL_CACHE`` names another folder to keep them in
(``NUMBA_CACHE_DIR``, if set and it is not, puts them in its ``harp-analysis/kernels``). A folder
no version uses any more is never read again, and may be deleted.

This is the package's own code, not numba's, because numba keys its cache by the compiled
function's file alone, its path and modification time: a change to a formula imported from
another module goes unnoticed (numba issue 1833, open since 2016), and each checkout compiles
afresh. :mod:`.numba_cache` tells numba to use these folders; :mod:`.stored` keeps tables
derived from the engines beside them, under the same digest.
"""

from __future__ import annotations

import ast
import hashlib
import os
import sys
from functools import cache
from pathlib import Path

import llvmlite
import numba

__all__ = ["cache_folder", "cache_root"]

_PACKAGE = Path(__file__).parents[1]  # the package's root folder
_PACKAGE_NAME = __name__.partition(".")[0]


def _imported(source: Path) -> frozenset[Path]:
    """The package's source files that ``source`` imports (``from . import x``, ``from .x
    import y``, ``import harp_analysis.x``), constants included: numba bakes them in."""
    return _imported_as_of(source, *_stamp(source))


def _stamp(source: Path) -> tuple[int, int]:
    status = source.stat()
    return status.st_mtime_ns, status.st_size


@cache
def _imported_as_of(source: Path, mtime_ns: int, size: int) -> frozenset[Path]:
    """:func:`_imported` of ``source`` as it was at that modification time and size (a file
    is parsed once per version, not once per compiled function). A relative import is resolved
    against the folder of ``source`` itself (``from ..models import drag`` in a subpackage), an
    absolute one against the package's root: either way every module a kernel reaches counts."""
    found: set[Path] = set()
    for node in ast.walk(ast.parse(source.read_text())):
        if isinstance(node, ast.ImportFrom):
            found.update(_imported_from(source, node))
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith(f"{_PACKAGE_NAME}."):
                    found.update(_module_files(_PACKAGE, alias.name.partition(".")[2], []))
    return frozenset(found)


def _imported_from(source: Path, node: ast.ImportFrom) -> list[Path]:
    """The package's source files that ``node``, a ``from ... import ...`` of ``source``,
    imports: none if it imports from another package."""
    module = node.module or ""
    if node.level:
        base = source.parent
        for _ in range(node.level - 1):
            base = base.parent
    elif module == _PACKAGE_NAME or module.startswith(f"{_PACKAGE_NAME}."):
        base, module = _PACKAGE, module.removeprefix(_PACKAGE_NAME).lstrip(".")
    else:  # another package's
        return []
    return _module_files(base, module, [alias.name for alias in node.names])


def _module_files(base: Path, module: str, names: list[str]) -> list[Path]:
    """The source files of ``module`` (dotted, below ``base``; empty: ``base`` itself) and of
    those of ``names`` that are its submodules: a module's file or a subpackage's
    ``__init__.py``."""
    folder = base.joinpath(*module.split(".")) if module else base
    candidates = [folder.with_suffix(".py"), folder / "__init__.py"] if module else []
    for name in names:
        candidates += [folder / f"{name}.py", folder / name / "__init__.py"]
    return [path for path in candidates if path.is_file()]


def _sources(module_name: str) -> list[Path]:
    """The package's source files that ``module_name`` reaches, import by import."""
    seen: set[Path] = set()
    pending = [Path(str(sys.modules[module_name].__file__))]
    while pending:
        source = pending.pop()
        if source not in seen:
            seen.add(source)
            pending.extend(_imported(source))
    return sorted(seen)


def cache_root() -> Path:
    """The folder that holds the kernels' folders: ``HARP_ANALYSIS_KERNEL_CACHE`` if set, else
    ``harp-analysis/kernels`` in ``NUMBA_CACHE_DIR`` if that is set, else in the user's cache
    folder (``XDG_CACHE_HOME``, by default ``~/.cache``)."""
    if chosen := os.environ.get("HARP_ANALYSIS_KERNEL_CACHE"):
        return Path(chosen)
    root = os.environ.get("NUMBA_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME")
    return Path(root or Path.home() / ".cache") / "harp-analysis" / "kernels"


def cache_folder(module_name: str) -> Path:
    """Where the compiled kernels of ``module_name`` are kept: in :func:`cache_root`, in a
    folder named by a digest of the module's name, of the contents of every source file of the
    package that the module reaches, as they are now (an edit to any of them, or a reload after
    one, compiles afresh), and of ``_toolchain()`` (another numba, llvmlite, Python or CPU
    compiles afresh). Where the files are, and when they were written, does not count."""
    sources = tuple(_sources(module_name))
    stamps = tuple(_stamp(source) for source in sources)
    return cache_root() / _digest(module_name, sources, stamps, _toolchain())


@cache
def _toolchain() -> str:
    """What compiles the kernels, as numba sees it: numba's, llvmlite's and Python's versions,
    and the target (numba's "magic tuple": the triple, the CPU's name and its features, with
    ``NUMBA_CPU_NAME`` and ``NUMBA_CPU_FEATURES`` applied), which numba also keys its index by."""
    from numba.core.registry import cpu_target

    python = f"{sys.implementation.cache_tag}{sys.abiflags} {sys.version}"
    target = cpu_target.target_context.codegen().magic_tuple()
    return repr((numba.__version__, llvmlite.__version__, python, target))


@cache
def _digest(module_name: str, sources: tuple[Path, ...], stamps: tuple, toolchain: str) -> str:
    """The digest of ``module_name``, of ``sources`` at these modification times and sizes
    (read once each; each named by its path in the package, the times not hashed) and of
    ``toolchain``."""
    digest = hashlib.sha256(f"{module_name}\n{toolchain}\n".encode())
    for name, source in sorted((_name_in_package(source), source) for source in sources):
        content = source.read_bytes()
        digest.update(f"{name}\n{len(content)}\n".encode() + content)
    return digest.hexdigest()[:16]


def _name_in_package(source: Path) -> str:
    """``source``'s path within the package (``engines/mks.py``), or its name if outside it (a
    module of the caller's that compiles kernels with :func:`.compiled.jit`)."""
    return (
        source.relative_to(_PACKAGE).as_posix() if source.is_relative_to(_PACKAGE) else source.name
    )
