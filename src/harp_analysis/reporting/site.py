"""The documentation site (``make docs``, issue 28): its generated pages, its notebooks run once,
and the check of the HTML Sphinx builds from them.

``make docs`` runs three steps:

1. ``python -m harp_analysis.reporting.site sources build/docs/source`` assembles the tree
   Sphinx reads: the hand-written pages of ``docs/`` (``conf.py``, ``_templates`` and
   ``_static`` stay there, read with ``sphinx-build -c docs``), the chapter notebooks 01-08
   run once (:func:`run_notebooks`), the committed figures, and the pages written here from the
   registry and the ledger (:func:`write_pages`, from the Jinja2 templates of
   ``docs/_templates/pages``): the gallery, a page per figure, the ledger, the HARP data's
   provenance, the benchmark results and the list of curated names;
2. ``sphinx-build -W -n`` builds the HTML, every warning an error;
3. ``python -m harp_analysis.reporting.site check build/docs/html`` checks every internal
   link, anchor and image of the built pages, and that none loads anything from outside
   (:func:`.link_check.check_site`).

What takes minutes is done once and cached in ``build/docs/cache`` under a digest of what it
depends on (:func:`digest`): the ledger's evaluation (:func:`evaluated_ledger`, about 1.5 min,
every trajectory its rows fly), each notebook's run, and the benchmarks' output. A cache
entry is reused only while the package's sources, the data, the registry, the pinned
environment and (for a notebook or the benchmarks) the file itself are unchanged.
``HARP_ANALYSIS_DOCS_EXECUTE=0`` leaves the notebooks unrun (their pages show the code without
outputs) and ``HARP_ANALYSIS_DOCS_BENCHMARKS`` is ``full`` (``make benchmark``'s sizes),
``smoke`` (the tests' tiny sizes, seconds) or ``off``: for iterating on the site's pages.

The explorer (notebook 00) is a Voila app: its page shows how to open it and a screenshot,
and its notebook is not run here.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import platform
import re
import shutil
import subprocess
import sys
import time
from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass, replace
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from ..foundation import paths
from .build import execute_notebook
from .gallery import SHOWN, caption_text, reason_text
from .ledger import VERDICTS, evaluate_all, evaluate_measurements, known_to, printed_digits
from .link_check import check_site, html_pages
from .registry import DRAWN, RegistryEntry, load_registry

__all__ = [
    "LedgerRow",
    "chapter_of",
    "digest",
    "evaluated_ledger",
    "run_notebooks",
    "run_benchmarks",
    "write_pages",
    "assemble",
    "main",
    "CHAPTER_NOTEBOOKS",
    "EXPLORER_NOTEBOOK",
    "LEDGER_COLUMNS",
    "TEMPLATES",
    "THUMBNAIL_WIDTH_PX",
]

#: The explorer's notebook: a Voila app, shown by a screenshot and never run by the site.
EXPLORER_NOTEBOOK = "00_explorer.ipynb"
#: The chapter notebooks, each a page of the site, in order (every notebook but the explorer).
CHAPTER_NOTEBOOKS = "[0-9][0-9]_*.ipynb"
#: The templates of the generated pages (Jinja2 writing Markdown), under the checkout: the prose
#: and layout are there, what they show is gathered here (:func:`write_pages`). Sphinx never
#: reads them as pages: ``docs/_templates`` is not copied to the source tree, and ``.j2`` is no
#: source suffix.
TEMPLATES = Path("docs/_templates/pages")
#: The ledger page's columns and their shares of its width (%): every row reads whole in the
#: window, the explanation (the reason behind a verdict) the widest.
LEDGER_COLUMNS = (
    ("id", 9),
    ("chapter", 5),
    ("source", 6),
    ("statement", 14),
    ("text", 5),
    ("computed", 6),
    ("unit", 4),
    ("tolerance", 6),
    ("verdict", 7),
    ("figures", 5),
    ("computed by", 9),
    ("explanation", 24),
)
#: The width of the gallery's thumbnails (px): twice what it shows of them, so that they stay
#: sharp on a high-density screen.
THUMBNAIL_WIDTH_PX = 360
#: Folders of docs/ that stay there (read by sphinx-build -c docs), and files never copied.
_CONFIGURATION = {"conf.py", "_templates", "_static", "__pycache__"}


# --- what a cache entry depends on ----------------------------------------------------------


def _files(root: Path, patterns: Iterable[str]) -> list[Path]:
    found = {path for pattern in patterns for path in root.glob(pattern) if path.is_file()}
    return sorted(path for path in found if "__pycache__" not in path.parts)


def digest(*extra: Path) -> str:
    """A short hash of everything a cached result depends on: the package's sources, the HARP
    data, the registry, the pinned environment, and the files ``extra`` (a notebook, the
    benchmarks), each by its path relative to the checkout and its bytes."""
    root = paths.ROOT
    files = [
        *_files(root, ("src/harp_analysis/**/*.py", "data/harp/**/*", "registry/*")),
        root / "environment.txt",
        *extra,
    ]
    hasher = hashlib.sha256()
    for path in files:
        try:
            name = path.resolve().relative_to(root.resolve()).as_posix()
        except ValueError:
            name = path.name
        hasher.update(name.encode() + b"\0" + path.read_bytes() + b"\0")
    return hasher.hexdigest()[:16]


def _cached_json(cache: Path, name: str, key: str, compute) -> Any:
    """``compute()``, or what it returned last under the same ``key`` (a JSON file in
    ``cache``; older entries of ``name`` are removed)."""
    target = cache / f"{name}-{key}.json"
    if target.is_file():
        return json.loads(target.read_text())
    value = compute()
    for stale in cache.glob(f"{name}-*.json"):
        stale.unlink()
    paths.write_atomically(target, lambda path: path.write_text(json.dumps(value, indent=1)))
    return value


# --- the ledger, evaluated once ---------------------------------------------------------------


@dataclass(frozen=True)
class LedgerRow:
    """One evaluated ledger row as the site shows it: the claim's fields, the computed value as
    CLAIMS.md prints it, the explanation with its quoted numbers filled in."""

    id: str
    chapter: str
    source: str
    statement: str
    text: str
    computed: str
    unit: str
    tolerance: str
    verdict: str
    explanation: str
    figures: tuple[str, ...]
    module: str  # the module and function that compute it
    function: str
    kind: str = "claim"  # or "extension": an extension result, measured, with no verdict


def chapter_of(source: str) -> str:
    """The chapter a ledger row's ``source`` cites: "Chapter 4" for "Ch. 4 B, eq 4.8" or
    "Table 4.1", "Appendices" for "Appendix E"."""
    found = re.search(r"\bCh\.\s*(\d+)", source) or re.search(
        r"\b(?:Table|Fig(?:ure)?\.?|eqs?\.?)\s*(\d+)\.", source
    )
    if found:
        return f"Chapter {found.group(1)}"
    if re.search(r"\bAppendi(?:x|ces)\b", source):
        return "Appendices"
    return "Other"


def _tolerance(value: float | None, kind: str) -> str:
    if value is None:
        return ""
    return f"{value:g}" if kind == "absolute" else f"{value:.2%} rel."


#: What the ledger page shows in the verdict column of an extension result.
EXTENSION_RESULT = "extension result"


def _evaluate() -> list[dict]:
    rows = []
    for result in evaluate_all():
        claim = result.claim
        module, _, function = claim.compute.partition(":")
        bound = {"upper": "< ", "lower": "> "}.get(claim.bound or "", "")
        fitted = f"Fitted to {claim.fitted_to}. " if claim.fitted_to else ""
        tolerance = _tolerance(claim.tolerance, claim.tolerance_kind)
        if claim.close_tolerance is not None:
            tolerance += f"; close: {_tolerance(claim.close_tolerance, claim.tolerance_kind)}"
        row = LedgerRow(
            id=claim.id,
            chapter=chapter_of(claim.source),
            source=claim.source,
            statement=claim.statement,
            text=f"{bound}{claim.text_value:.6g}",
            computed=f"{result.computed:.{printed_digits(result)}g}{known_to(result)}",
            unit=claim.unit,
            tolerance=tolerance,
            verdict=claim.verdict,
            explanation=(fitted + result.explanation).strip(),
            figures=claim.figures,
            module=module,
            function=function,
        )
        rows.append(asdict(row))
    for measured in evaluate_measurements():
        row_of = measured.row
        module, _, function = row_of.compute.partition(":")
        rows.append(
            asdict(
                LedgerRow(
                    id=row_of.id,
                    chapter=chapter_of(row_of.source),
                    source=row_of.source,
                    statement=row_of.statement,
                    text="",
                    computed=f"{measured.computed:.{printed_digits(measured)}g}",
                    unit=row_of.unit,
                    tolerance="",
                    verdict=EXTENSION_RESULT,
                    explanation=measured.explanation,
                    figures=row_of.figures,
                    module=module,
                    function=function,
                    kind="extension",
                )
            )
        )
    return rows


def quoted_registry(cache: Path | None = None) -> list[RegistryEntry]:
    """The registry with each reason and caption as a reader sees them, the ledger's numbers
    quoted in (:func:`.gallery.reason_text`); cached in ``cache`` like the ledger, whose rows
    they quote."""

    def quoted() -> dict[str, list[str]]:
        return {e.number: [reason_text(e), caption_text(e)] for e in load_registry()}

    texts = _cached_json(cache, "registry", digest(), quoted) if cache else quoted()
    return [
        replace(e, reason=texts[e.number][0], caption=texts[e.number][1]) for e in load_registry()
    ]


def evaluated_ledger(cache: Path) -> list[LedgerRow]:
    """Every ledger row evaluated (:func:`harp_analysis.reporting.ledger.evaluate_all`), once per
    version of the package, data and registry: cached in ``cache``."""
    rows = _cached_json(cache, "ledger", digest(), _evaluate)
    return [LedgerRow(**{**row, "figures": tuple(row["figures"])}) for row in rows]


# --- the notebooks, run once ------------------------------------------------------------------


def run_notebooks(
    notebooks: list[Path], cache: Path, jobs: int = 2, timeout_s: int = 1200
) -> dict[Path, Path]:
    """Each notebook of ``notebooks`` run once in a fresh kernel from its own folder (as
    ``make figures`` runs them, ``jobs`` at a time), its figures saved to a scratch folder in
    ``cache``, never to the committed ``figures/``: the executed notebook of each, cached in
    ``cache`` under :func:`digest` of it, so an unchanged notebook of an unchanged package is
    not run again. A failing cell fails the build (nbclient's CellExecutionError)."""
    folder = cache / "notebooks"
    folder.mkdir(parents=True, exist_ok=True)
    executed = {path: folder / f"{path.stem}-{digest(path)}.ipynb" for path in notebooks}
    pending = [path for path in notebooks if not executed[path].is_file()]
    for path in notebooks:  # earlier runs of the same notebooks
        for stale in folder.glob(f"{path.stem}-*.ipynb"):
            if stale != executed[path]:
                stale.unlink()
    figures_dir = cache / "figures"
    figures_dir.mkdir(parents=True, exist_ok=True)

    def run(path: Path) -> tuple[Path, float]:
        return path, execute_notebook(path, figures_dir, timeout_s, executed_path=executed[path])

    # The later chapters' notebooks are the longer ones: started first, they end with the rest.
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        for path, seconds in pool.map(run, pending[::-1]):
            print(f"{seconds:6.1f} s  ran {path.name}", flush=True)
    return executed


# --- the benchmarks, run once -----------------------------------------------------------------


def run_benchmarks(cache: Path, mode: str = "full") -> dict:
    """The output of every ``benchmarks/bench_*.py``, run as ``make benchmark`` runs it (``mode``
    ``full``) or in its smoke mode (``smoke``: tiny sizes, timings not meaningful), with the
    machine and the date: cached in ``cache`` as long as the package and the benchmarks are
    unchanged. A benchmark that fails fails the build."""
    scripts = sorted((paths.ROOT / "benchmarks").glob("bench_*.py"))
    helpers = sorted((paths.ROOT / "benchmarks").glob("*.py"))

    def compute() -> dict:
        outputs = {}
        for script in scripts:
            command = [sys.executable, str(script), *(["--smoke"] if mode == "smoke" else [])]
            start = time.perf_counter()
            run = subprocess.run(
                command, cwd=paths.ROOT, capture_output=True, text=True, check=False
            )
            if run.returncode:
                raise RuntimeError(f"{script.name} failed ({run.returncode}):\n{run.stderr}")
            seconds = time.perf_counter() - start
            print(f"{seconds:6.1f} s  ran {script.name} ({mode})", flush=True)
            outputs[script.name] = {"seconds": seconds, "output": run.stdout}
        return {
            "mode": mode,
            "date": datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
            "machine": f"{platform.machine()}, {os.cpu_count()} cores, Python "
            f"{platform.python_version()}, {platform.system()}",
            "benchmarks": outputs,
        }

    return _cached_json(cache, f"benchmarks-{mode}", digest(*helpers), compute)


# --- the generated pages ----------------------------------------------------------------------

_PUNCTUATION = re.compile(r"([\\`*_{}\[\]<>()#+!|$~^&-])")


def _md(text: str) -> str:
    """``text`` as literal Markdown inline text: every character MyST could read as markup
    escaped (CommonMark lets any ASCII punctuation be escaped; "-" or "1." alone would start a
    list), line breaks folded."""
    escaped = _PUNCTUATION.sub(r"\\\1", " ".join(text.split()))
    return re.sub(r"^(\d+)([.)])", r"\1\\\2", escaped)


def _slug(number: str) -> str:
    """The page name of figure or table ``number``: "figure-2-1", "table-4-1", "figure-x-3"."""
    kind = "table" if number.startswith("Table") else "figure"
    bare = number.removeprefix("Table").strip()
    return f"{kind}-{bare.lower().replace('.', '-')}"


def _badge(status: str) -> str:
    """A registry status as a coloured badge with its words (site.css: ``status-badge``)."""
    return f"[{_md(SHOWN[status])}]{{.status-badge .status-{status.replace(' ', '-')}}}"


def _counted(
    values: Iterable[str], names: Sequence[str] | Mapping[str, str], every: bool = False
) -> str:
    """How many of ``values`` are each of ``names``, in their order ("3 reproduces, 1 close"),
    each shown as ``names`` maps it (:data:`SHOWN`) or as it is; one with none is left out
    unless ``every``."""
    counts = Counter(values)
    shown = names if isinstance(names, Mapping) else {name: name for name in names}
    return ", ".join(f"{counts[n]} {shown[n]}" for n in shown if every or counts[n])


def _pages_environment() -> Any:
    """The Jinja2 environment of :data:`TEMPLATES`: whole lines kept as written (a block tag's
    line left out), no escaping (the pages are Markdown; :func:`_md` escapes text where a
    template asks), an undefined name an error."""
    import jinja2

    environment = jinja2.Environment(
        loader=jinja2.FileSystemLoader(paths.ROOT / TEMPLATES),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
        trim_blocks=True,
        lstrip_blocks=True,
        autoescape=False,
    )
    environment.filters |= {
        "md": _md,
        "slug": _slug,
        "badge": _badge,
        "counted": _counted,
        "thumbnail_name": _thumbnail_name,
    }
    environment.globals |= {
        "SHOWN": SHOWN,
        "VERDICTS": VERDICTS,
        "DRAWN": DRAWN,
        "LEDGER_COLUMNS": LEDGER_COLUMNS,
    }
    return environment


def _data_files() -> list[Path]:
    """The HARP data's files the provenance page offers for download."""
    harp = paths.ROOT / "data" / "harp"
    return [*sorted(harp.glob("*.tsv")), harp / "SHA256SUMS"]


def _tied(rows: list[LedgerRow]) -> dict[str, list[LedgerRow]]:
    """The rows of ``rows`` about each figure, by its number."""
    tied: dict[str, list[LedgerRow]] = {}
    for row in rows:
        for number in row.figures:
            tied.setdefault(number, []).append(row)
    return tied


def _shared_context(
    rows: list[LedgerRow], chapter_pages: dict[str, str], entries: list[RegistryEntry]
) -> dict[str, Any]:
    """What every page's template is given: the registry's ``entries`` (``dissertation`` and
    ``extensions``, and the ``registry`` by number), the ledger's ``rows`` (``claims``, scored,
    and ``measured``, the extension results; ``tied``, those about each figure by its number)
    and the ``chapters`` (each notebook's page)."""
    return {
        "entries": entries,
        "dissertation": [e for e in entries if not e.extension],
        "extensions": [e for e in entries if e.extension],
        "registry": {e.number: e for e in entries},
        "claims": [row for row in rows if row.kind == "claim"],
        "measured": [row for row in rows if row.kind == "extension"],
        "tied": _tied(rows),
        "chapters": chapter_pages,
    }


def _pages(
    rows: list[LedgerRow],
    chapter_pages: dict[str, str],
    benchmarks: dict | None,
    entries: list[RegistryEntry],
) -> dict[str, str]:
    """Each generated page's text by its name in the source tree, rendered from
    :data:`TEMPLATES`, each given :func:`_shared_context` and what it alone shows."""
    import harp_analysis

    from ..analyses.error_budget import CHAPTER_7B

    shared = _shared_context(rows, chapter_pages, entries)
    tied = shared["tied"]
    environment = _pages_environment()

    def render(template: str, **context: Any) -> str:
        return environment.get_template(template).render(**shared, **context)

    harp = paths.ROOT / "data" / "harp"
    pages = {
        f"gallery/{_slug(e.number)}.md": render(
            "figure.md.j2", entry=e, rows=tied.get(e.number, [])
        )
        for e in entries
    }
    return pages | {
        "gallery/index.md": render("gallery.md.j2"),
        "ledger.md": render("ledger.md.j2"),
        "_generated/summary.md": render("summary.md.j2"),
        "_generated/extensions.md": render("extensions.md.j2"),
        "_generated/uncertainties.md": render("uncertainties.md.j2", uncertainties=CHAPTER_7B),
        "benchmarks.md": render("benchmarks.md.j2", results=benchmarks),
        "api/curated.md": render(
            "curated.md.j2",
            names=harp_analysis.__all__,
            modules=harp_analysis._API,
            version=harp_analysis.__version__,
        ),
        "chapters/index.md": render("chapters.md.j2"),
        "provenance/index.md": render(
            "provenance.md.j2",
            readme=(harp / "README.md").read_text(),
            files=[path.name for path in _data_files()],
        ),
        "provenance/radar.md": (harp / "radar" / "README.md").read_text(),
    }


def _copy_if_changed(source: Path, target: Path) -> None:
    """Copy ``source`` to ``target`` unless it holds the same bytes already, so that Sphinx
    reads again only the pages that changed."""
    if target.is_file() and target.read_bytes() == source.read_bytes():
        return
    target.parent.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(source, target)


def _write_if_changed(target: Path, text: str) -> None:
    if target.is_file() and target.read_text() == text:
        return
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(text)


def write_pages(
    target: Path,
    rows: list[LedgerRow],
    chapter_pages: dict[str, str],
    benchmarks: dict | None,
    entries: list[RegistryEntry] | None = None,
) -> list[Path]:
    """Write the generated pages into the source tree ``target``: the gallery and a page per
    registry entry, the ledger, the landing page's summary, the list of extensions, the
    provenance of the HARP data (its README, its radar note, the files for download), the
    benchmarks, the curated names; ``chapter_pages`` maps each notebook to its page's name;
    ``entries``, the registry as :func:`quoted_registry` gives it (by default, quoted now)."""
    entries = quoted_registry() if entries is None else entries
    pages = _pages(rows, chapter_pages, benchmarks, entries)
    for name, text in pages.items():
        _write_if_changed(target / name, text)
    for path in _data_files():
        _copy_if_changed(path, target / "provenance" / "data" / path.name)
    return [target / name for name in pages]


def _thumbnail_name(figure: str) -> str:
    """The name of the gallery's thumbnail of figure file ``figure``: another name than the
    figure's, which Sphinx would otherwise rename on copying both to the site's images."""
    return figure.removesuffix(".png") + "-thumbnail.png"


def _thumbnail(figure: Path, cache: Path) -> Path:
    """A copy of the committed figure ``figure`` :data:`THUMBNAIL_WIDTH_PX` wide, in 256
    colours, for the gallery (about 15 kB where the figure is about 170 kB: the gallery loads
    under 1 MB, not 10): cached in ``cache`` under a digest of the figure's bytes."""
    from PIL import Image

    data = figure.read_bytes()
    target = cache / f"{figure.stem}-{hashlib.sha256(data).hexdigest()[:16]}.png"
    if target.is_file():
        return target
    for stale in cache.glob(f"{figure.stem}-*.png"):
        stale.unlink()
    with Image.open(figure) as image:
        small = image.convert("RGB")
    small.thumbnail((THUMBNAIL_WIDTH_PX, small.height), Image.Resampling.LANCZOS)
    small = small.quantize(256, dither=Image.Dither.NONE)
    return paths.write_atomically(target, lambda path: small.save(path, "PNG", optimize=True))


def _figures_for_site(target: Path, cache: Path) -> None:
    """The committed figures the gallery shows (PNG, PDF for download, tables), and the
    gallery's thumbnails of the PNG ones (made once per figure, kept in ``cache``)."""
    for path in sorted(paths.COMMITTED_FIGURES_DIR.iterdir()):
        if path.suffix in (".png", ".pdf") or (path.suffix == ".md" and path.name != "README.md"):
            if path.name != "CLAIMS.md":
                _copy_if_changed(path, target / "figures" / path.name)
        if path.suffix == ".png":
            thumbnail = _thumbnail(path, cache)
            _copy_if_changed(
                thumbnail, target / "gallery" / "thumbnails" / _thumbnail_name(path.name)
            )


def _copy_hand_written(docs: Path, target: Path) -> None:
    """The hand-written pages of ``docs`` (not its configuration, :data:`_CONFIGURATION`) and
    the root files a page includes (CHANGELOG.md, CITATION.cff), copied into ``target``."""
    for path in sorted(docs.rglob("*")):
        relative = path.relative_to(docs)
        if path.is_file() and not _CONFIGURATION & set(relative.parts):
            _copy_if_changed(path, target / relative)
    for name in ("CHANGELOG.md", "CITATION.cff"):
        _copy_if_changed(paths.ROOT / name, target / "_root" / name)


def _notebooks_and_ledger(
    notebooks: list[Path], cache: Path, execute: bool, jobs: int
) -> tuple[dict[Path, Path], list[LedgerRow]]:
    """Each notebook as executed (:func:`run_notebooks`; as it is unless ``execute``) and the
    evaluated ledger: the ledger in this process while the notebooks run in their kernels."""
    start = time.perf_counter()
    with ThreadPoolExecutor(max_workers=1) as background:
        running = background.submit(run_notebooks, notebooks, cache, jobs) if execute else None
        rows = evaluated_ledger(cache)
        executed = running.result() if running else {path: path for path in notebooks}
    print(f"{time.perf_counter() - start:6.1f} s  notebooks and ledger", flush=True)
    return executed, rows


def _chapters_for_site(target: Path, executed: dict[Path, Path]) -> dict[str, str]:
    """The notebooks of ``executed`` (each notebook: its executed copy) as the chapters' pages
    of ``target``, any other left from an earlier build (renamed or removed) taken out: each
    notebook's name mapped to its page's."""
    chapters = target / "chapters"
    for notebook, run in executed.items():
        _copy_if_changed(run, chapters / notebook.name)
    for stale in chapters.glob("*.ipynb"):
        if stale.name not in {notebook.name for notebook in executed}:
            stale.unlink()
    return {notebook.name: f"/chapters/{notebook.stem}" for notebook in executed}


def assemble(
    target: Path,
    docs: Path | None = None,
    execute: bool = True,
    benchmarks: str = "full",
    cache: Path | None = None,
    jobs: int = 2,
) -> None:
    """Assemble the source tree of the site in ``target`` (see the module docstring): the
    hand-written pages of ``docs``, the chapter notebooks (run once and cached if ``execute``),
    the committed figures, the root files a page includes (CHANGELOG.md, CITATION.cff) and the
    generated pages."""
    cache = Path(cache) if cache else target.parent / "cache"
    cache.mkdir(parents=True, exist_ok=True)
    _copy_hand_written(Path(docs) if docs else paths.ROOT / "docs", target)
    _figures_for_site(target, cache / "thumbnails")
    notebooks = [
        path
        for path in sorted(paths.NOTEBOOKS_DIR.glob(CHAPTER_NOTEBOOKS))
        if path.name != EXPLORER_NOTEBOOK
    ]
    executed, rows = _notebooks_and_ledger(notebooks, cache, execute, jobs)
    chapter_pages = _chapters_for_site(target, executed)
    results = None if benchmarks == "off" else run_benchmarks(cache, benchmarks)
    write_pages(target, rows, chapter_pages, results, quoted_registry(cache))


# --- command line -----------------------------------------------------------------------------


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(dest="command", required=True)
    sources = commands.add_parser("sources", help="assemble the source tree Sphinx reads")
    sources.add_argument("target", type=Path)
    sources.add_argument("--jobs", type=int, default=2, help="notebooks run at once")
    check = commands.add_parser("check", help="check the built HTML's links and images")
    check.add_argument("site", type=Path)
    args = parser.parse_args(argv)
    if args.command == "sources":
        execute = os.environ.get("HARP_ANALYSIS_DOCS_EXECUTE", "1") != "0"
        benchmarks = os.environ.get("HARP_ANALYSIS_DOCS_BENCHMARKS", "full")
        if benchmarks not in ("full", "smoke", "off"):
            parser.error("HARP_ANALYSIS_DOCS_BENCHMARKS is full, smoke or off")
        assemble(args.target, execute=execute, benchmarks=benchmarks, jobs=args.jobs)
        return 0
    problems = check_site(args.site)
    for problem in problems:
        print(problem)
    pages = len(list(html_pages(args.site)))
    print(
        f"{pages} pages checked: {len(problems)} problems"
        if problems
        else f"{pages} pages "
        "checked: every internal link, anchor and image is there, nothing loaded from outside"
    )
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
