"""``make figures``: execute every notebook headless, then render the gallery and the ledger.

Notebooks run in memory from their own folder (as nbmake runs them) and are never rewritten,
so the committed notebooks stay free of outputs. Figures land in ``HARP_ANALYSIS_FIGURES_DIR``
(``make figures`` sets it to the committed ``figures/``) through
:func:`harp_analysis.reporting.plotting.save_figure`, and so do the gallery and the evaluated
ledger.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from ..foundation import paths
from .gallery import render_gallery, render_readme_headline
from .ledger import render_claims
from .registry import get_entry

__all__ = ["notebooks", "notebooks_for", "execute_notebook", "main"]


def notebooks() -> list[Path]:
    """Every notebook of the project, in chapter order."""
    return sorted(paths.NOTEBOOKS_DIR.glob("*.ipynb"))


def execute_notebook(
    path: Path,
    figures_dir: Path | None = None,
    timeout_s: int = 600,
    executed_path: Path | None = None,
) -> float:
    """Run notebook ``path`` in a fresh kernel from its own folder; return the seconds it took.

    ``figures_dir`` redirects :func:`~harp_analysis.reporting.plotting.save_figure` for this run
    (a relative folder is read from the current one, not from the notebook's, where the kernel
    runs); ``executed_path``, if given, receives the notebook with its outputs (the
    documentation site's).
    """
    import nbformat
    from nbclient import NotebookClient

    environment = dict(os.environ)
    if figures_dir:
        environment["HARP_ANALYSIS_FIGURES_DIR"] = str(Path(figures_dir).resolve())
    start = time.perf_counter()
    notebook = nbformat.read(path, as_version=4)
    client = NotebookClient(
        notebook,
        timeout=timeout_s,
        kernel_name="python3",
        resources={"metadata": {"path": str(path.parent)}},
    )
    client.execute(env=environment)  # passed on to the kernel manager's start_kernel
    if executed_path is not None:
        paths.write_atomically(executed_path, lambda target: nbformat.write(notebook, target))
    return time.perf_counter() - start


def notebooks_for(numbers: list[str]) -> list[Path]:
    """The notebooks that draw figures ``numbers`` (registry numbers, e.g. "4.11")."""
    chosen = set()
    for number in numbers:
        entry = get_entry(number)
        if not entry.notebook:
            raise ValueError(f"figure {number!r} is drawn by no notebook ({entry.status})")
        chosen.add(paths.NOTEBOOKS_DIR / entry.notebook)
    return sorted(chosen)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jobs", type=int, default=2, help="notebooks run at once (default 2)")
    parser.add_argument(
        "--figure",
        action="append",
        default=[],
        help="regenerate only this figure's notebook (repeatable), e.g. 4.11",
    )
    args = parser.parse_args(argv)
    chosen = notebooks_for(args.figure) if args.figure else notebooks()
    # The later chapters' notebooks are the longer ones: started first, they end with the rest.
    longest_first = chosen[::-1]
    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        timings = dict(zip(longest_first, pool.map(execute_notebook, longest_first)))
    for path in chosen:
        seconds = timings[path]
        print(f"{seconds:6.1f} s  {path.name}")
    for written in (render_gallery(), render_claims()):
        print(f"wrote {written}")
    if paths.FIGURES_DIR.resolve() == paths.COMMITTED_FIGURES_DIR.resolve():
        print(f"wrote {render_readme_headline()}")  # the headline counts what was committed
    return 0


if __name__ == "__main__":
    sys.exit(main())
