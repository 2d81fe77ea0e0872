"""The documentation site (``make docs``, issue 28): its generated pages, its notebooks run once,
and the check of the HTML Sphinx builds from them.

``make docs`` runs three steps:

1. ``python -m harp_analysis.reporting.site sources build/docs/source`` assembles the tree
   Sphinx reads: the hand-written pages of ``docs/`` (``conf.py``, ``_templates`` and
   ``_static`` stay there, read with ``sphinx-build -c docs``), the chapter notebooks 01-08
   run once (:func:`run_notebooks`), the committed figures, and the pages written here from the
   registry and the ledger (:func:`write_pages`): the gallery, a page per figure, the ledger,
   the HARP data's provenance, the benchmark results and the list of curated names;
2. ``sphinx-build -W -n`` builds the HTML, every warning an error;
3. ``python -m harp_analysis.reporting.site check build/docs/html`` checks every internal
   link, anchor and image of the built pages, and that none loads anything from outside
   (:func:`check_site`).

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
from collections.abc import Iterable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass, replace
from datetime import UTC, datetime
from html.parser import HTMLParser
from pathlib import Path
from typing import Any
from urllib.parse import unquote, urlsplit

from ..foundation import paths
from .build import execute_notebook
from .gallery import caption_text, reason_text
from .ledger import VERDICTS, evaluate_all, evaluate_measurements, known_to, printed_digits
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
    "check_site",
    "main",
    "CHAPTER_NOTEBOOKS",
    "EXPLORER_NOTEBOOK",
    "LEDGER_COLUMNS",
    "THUMBNAIL_WIDTH_PX",
]

#: The explorer's notebook: a Voila app, shown by a screenshot and never run by the site.
EXPLORER_NOTEBOOK = "00_explorer.ipynb"
#: The chapter notebooks, each a page of the site, in order (every notebook but the explorer).
CHAPTER_NOTEBOOKS = "[0-9][0-9]_*.ipynb"
#: The statuses as the gallery shows them (as figures/README.md).
SHOWN = {
    "reproduced": "reproduced",
    "deviates": "drawn, deviates",
    "partial": "partial",
    "pending": "pending",
    "not reproducible": "not reproducible",
    "extension": "drawn, extension",
}
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


#: The front matter of a page without the theme's column of its contents: the gallery and each
#: figure's page give the figures that width.
_WITHOUT_CONTENTS = ("---", "html_theme.sidebar_secondary.remove: true", "---")


def _badge(status: str) -> str:
    """A registry status as a coloured badge with its words (site.css: ``status-badge``)."""
    return f"[{_md(SHOWN[status])}]{{.status-badge .status-{status.replace(' ', '-')}}}"


def _claim_label(claim_id: str) -> str:
    return f"claim-{claim_id}"


def _row_link(row: LedgerRow) -> str:
    return f"{{ref}}`{row.id} <{_claim_label(row.id)}>`"


def _function_link(row: LedgerRow) -> str:
    return f"{{py:obj}}`{row.function} <{row.module}.{row.function}>`"


def _figure_link(number: str, entries: dict[str, RegistryEntry]) -> str:
    entry = entries.get(number)
    label = entry.label if entry else number
    return f"{{doc}}`{label} </gallery/{_slug(number)}>`" if entry else _md(label)


def _regenerate(entry: RegistryEntry) -> str:
    if entry.kind == "table" or " " in entry.number:
        return f'.venv/bin/python -m harp_analysis.reporting.build --figure "{entry.number}"'
    return f"make figures FIG={entry.number}"


def _rows_table(rows: list[LedgerRow]) -> list[str]:
    """A figure page's ledger rows: each linked to its row of the ledger and to the API entry of
    the function that computes it."""
    lines = [
        ":::{list-table}",
        ":header-rows: 1",
        ":class: ledger-rows",
        "",
        "* - row",
        "  - the text states",
        "  - text",
        "  - computed",
        "  - unit",
        "  - verdict",
        "  - computed by",
    ]
    for row in rows:
        lines += [
            f"* - {_row_link(row)}",
            f"  - {_md(row.statement)}",
            f"  - {_md(row.text)}",
            f"  - {_md(row.computed)}",
            f"  - {_md(row.unit)}",
            f"  - **{row.verdict}**",
            f"  - {_function_link(row)}",
        ]
    return [*lines, ":::"]


def _figure_page(entry: RegistryEntry, rows: list[LedgerRow], chapter_pages: dict[str, str]) -> str:
    lines = [
        *_WITHOUT_CONTENTS,
        f"({_slug(entry.number)})=",
        f"# {entry.label}: {_md(entry.title)}",
        "",
    ]
    drawn = entry.status in DRAWN and entry.file
    text_caption = [
        "::::{container} text-caption",
        "**The dissertation's caption**" if not entry.extension else "**The project's figure**",
        "",
        f"*{_md(entry.title)}*",
        "",
        f"Status: {_badge(entry.status)} (class: {entry.figure_class}).",
        "",
        _md(entry.reason) if entry.reason else "",
        "",
        f"No ledger row: {_md(entry.no_number)}" if entry.no_number else "",
        "::::",
    ]
    if drawn and entry.file.endswith(".png"):
        pdf = entry.file[:-4] + ".pdf"
        shown = [  # scaled to the page's width, so Sphinx links it to the full-size image
            f":::{{figure}} ../figures/{entry.file}",
            f":alt: {entry.label} as the project draws it",
            ":class: project-figure",
            ":width: 100%",
            "",
            _md(entry.caption) if entry.caption else f"{entry.label}, as the project draws it.",
            ":::",
            "",
            f"Click the figure for its full size; vector: {{download}}`{pdf} <../figures/{pdf}>`",
        ]
    elif drawn:  # a table, written as Markdown
        shown = [f":::{{include}} ../figures/{entry.file}", ":heading-offset: 1", ":::"]
    else:
        shown = ["*Not drawn: see the status.*"]
    lines += [
        ":::::{container} figure-pair",
        "::::{container} project-side",
        *shown,
        "::::",
        "",
        *text_caption,
        ":::::",
        "",
    ]
    if entry.notebook:
        chapter = chapter_pages.get(entry.notebook)
        where = f"{{doc}}`{chapter}`" if chapter else f"`notebooks/{entry.notebook}`"
        lines += [
            f"Drawn by {where} (`notebooks/{entry.notebook}`). To regenerate it into `figures/`:",
            "",
            "```sh",
            _regenerate(entry),
            "```",
            "",
        ]
    lines += ["## Ledger rows about it", ""]
    if rows:
        counts = Counter(row.verdict for row in rows)
        lines += [
            ", ".join(f"{counts[v]} {v}" for v in VERDICTS if counts[v]) + ". Each row links "
            "to its line of the {doc}`ledger </ledger>` (the explanation, the tolerance) and "
            "to the function that computes it.",
            "",
            *_rows_table(rows),
        ]
    else:
        lines += ["No ledger row speaks about it."]
    return "\n".join(lines) + "\n"


def _gallery_index(
    entries: list[RegistryEntry], tied: dict[str, list[LedgerRow]], pages: list[str]
) -> str:
    dissertation = [e for e in entries if not e.extension]
    extensions = [e for e in entries if e.extension]
    counts = Counter(e.status for e in dissertation)
    lines = [
        *_WITHOUT_CONTENTS,
        "# Gallery",
        "",
        "Every figure and table of the dissertation, with the text's own caption, the project's "
        "figure, its status and the ledger rows about it (each linked to its value, its "
        "verdict and the function that computes it). A figure is *reproduced* when every "
        "number the text states about it reproduces, *drawn, deviates* when one does not. "
        "Generated from `registry/figures.toml` and the evaluated ledger.",
        "",
        ", ".join(f"{counts[s]} {SHOWN[s]}" for s in SHOWN if counts[s])
        + f" ({len(dissertation)} in "
        f"all); {len(extensions)} figures of the project's own beyond the dissertation.",
        "",
        "```{toctree}",
        ":hidden:",
        "",
        *pages,
        "```",
        "",
    ]
    groups = (("The dissertation", dissertation), ("Beyond the dissertation", extensions))
    for title, group in groups:
        lines += [
            f"## {title}",
            "",
            ":::{list-table}",
            ":header-rows: 1",
            ":class: gallery-table",
            ":widths: 24 37 20 19",
            "",
            "* - figure",
            "  - caption",
            "  - status",
            "  - ledger rows",
        ]
        for e in group:
            counts = Counter(row.verdict for row in tied.get(e.number, []))
            verdicts = ", ".join(f"{counts[v]} {v}" for v in VERDICTS if counts[v])
            if e.status in DRAWN and e.file.endswith(".png"):
                shown = (
                    f"[![{e.label}](thumbnails/{_thumbnail_name(e.file)})]({_slug(e.number)}.md)"
                )
            else:
                shown = "*a table*" if e.status in DRAWN else "*not drawn*"
            lines += [
                f"* - {shown}",
                "",
                f"    {{doc}}`{e.label} <{_slug(e.number)}>`",
                f"  - {_md(e.title if not e.extension else e.caption or e.title)}",
                f"  - {_badge(e.status)}",
                f"  - {verdicts}",
            ]
        lines += [":::", ""]
    return "\n".join(lines)


def _ledger_page(all_rows: list[LedgerRow], entries: dict[str, RegistryEntry]) -> str:
    rows = [row for row in all_rows if row.kind == "claim"]
    extensions = [row for row in all_rows if row.kind == "extension"]
    counts = Counter(row.verdict for row in rows)
    lines = [
        "# The ledger",
        "",
        "The dissertation's checkable statements, each recomputed by the package function "
        "named beside it, with its tolerance and an honest verdict; generated from "
        "`registry/claims.toml`, evaluated when the site was built (as `figures/CLAIMS.md`). "
        "Statements the text makes without data for a computation are listed, with the reason, "
        "in `registry/no_data.md`.",
        "",
        "- **reproduces**: the computed value lies within the tolerance of the text's (for a "
        "bound, on the stated side of it).",
        "- **close**: outside the tolerance but within the close tolerance; the explanation "
        "says why.",
        "- **does not reproduce**: outside the close tolerance; the explanation gives the best "
        "reason found.",
        "- **recovered**: within the tolerance, of a value fitted to the very number it is "
        "scored against: evidence that the fit holds, not that the text reproduces.",
        "",
        f"{len(rows)} rows: " + ", ".join(f"{counts[v]} {v}" for v in VERDICTS) + ". "
        "Filter by chapter and verdict, or sort by a column (click its heading); the row's id "
        "is its link.",
        "",
        ":::{list-table}",
        ":header-rows: 1",
        ":class: ledger-table",
        f":widths: {' '.join(str(width) for _, width in LEDGER_COLUMNS)}",
        "",
        f"* - {LEDGER_COLUMNS[0][0]}",
        *(f"  - {name}" for name, _ in LEDGER_COLUMNS[1:]),
    ]
    for row in rows:
        figures = ", ".join(_figure_link(number, entries) for number in row.figures)
        lines += [
            f"* - ({_claim_label(row.id)})=",
            "",
            f"    `{row.id}`",
            f"  - {row.chapter}",
            f"  - {_md(row.source)}",
            f"  - {_md(row.statement)}",
            f"  - {_md(row.text)}",
            f"  - {_md(row.computed)}",
            f"  - {_md(row.unit)}",
            f"  - {_md(row.tolerance)}",
            f"  - {row.verdict}",
            f"  - {figures}",
            f"  - {_function_link(row)}",
            f"  - {_md(row.explanation)}",
        ]
    lines += [
        ":::",
        "",
        "## Extension results: measured, not scored",
        "",
        "What the project measures of its own work beyond the text (its improved MKS, readings "
        "resting on input sizes or hypotheses the text does not give): each answers a passage "
        "of the text but states nothing the text claims, so it carries no verdict, only its "
        f"measured value ({len(extensions)} results).",
        "",
        ":::{list-table}",
        ":header-rows: 1",
        ":class: extension-table",
        ":widths: 16 28 10 46",
        "",
        "* - id",
        "  - what is measured",
        "  - measured",
        "  - explanation",
    ]
    for row in extensions:
        lines += [
            f"* - ({_claim_label(row.id)})=",
            "",
            f"    `{row.id}`",
            f"  - {_md(row.statement)} (answers {_md(row.source)}; {_function_link(row)})",
            f"  - {_md(row.computed)} {_md(row.unit)}",
            f"  - {_md(row.explanation)}",
        ]
    return "\n".join([*lines, ":::", ""])


def _summary(entries: list[RegistryEntry], all_rows: list[LedgerRow]) -> str:
    """The landing page's generated part: what is reproduced, what deviates, the ledger's
    verdicts."""
    rows = [row for row in all_rows if row.kind == "claim"]
    dissertation = [e for e in entries if not e.extension]
    counts = Counter(e.status for e in dissertation)
    verdicts = Counter(row.verdict for row in rows)

    def listed(status: str, with_reason: bool) -> list[str]:
        return [
            f"- {{doc}}`{e.label} </gallery/{_slug(e.number)}>` ({_md(e.title)})"
            + (f": {_md(e.reason)}" if with_reason and e.reason else "")
            for e in dissertation
            if e.status == status
        ]

    return "\n".join(
        [
            f"Of the dissertation's {len(dissertation)} figures and tables, "
            + ", ".join(f"{counts[s]} {SHOWN[s]}" for s in SHOWN if counts[s])
            + f". Of the {len(rows)} rows of the {{doc}}`ledger </ledger>` (the text's "
            "checkable statements, each recomputed by the package), "
            + ", ".join(f"{verdicts[v]} {v}" for v in VERDICTS)
            + f"; and {len(all_rows) - len(rows)} extension results, the project's own "
            "measurements beyond the text, unscored.",
            "",
            "### Reproduced",
            "",
            *listed("reproduced", False),
            "",
            "### Drawn, deviating from the text",
            "",
            *listed("deviates", True),
            "",
            "### Partial, and not reproducible",
            "",
            *listed("partial", True),
            *listed("not reproducible", True),
            "",
        ]
    )


def _extension_list(entries: list[RegistryEntry]) -> str:
    return "\n".join(
        f"- {{doc}}`{e.label} </gallery/{_slug(e.number)}>`: {_md(e.caption or e.title)}"
        for e in entries
        if e.extension
    )


def _uncertainties() -> str:
    """The error budget's uncertainties (:data:`harp_analysis.analyses.error_budget.CHAPTER_7B`)
    as a table: each input, its standard deviation and its basis."""
    from ..analyses.error_budget import CHAPTER_7B

    lines = [
        ":::{list-table}",
        ":header-rows: 1",
        "",
        "* - input",
        "  - the launch's field",
        "  - 1 sd",
        "  - basis",
    ]
    for u in CHAPTER_7B:
        lines += [
            f"* - {_md(u.name)}",
            f"  - `{u.field}`",
            f"  - {u.sd:.4g}",
            f"  - {_md(u.basis)}",
        ]
    return "\n".join([*lines, ":::", ""])


def _benchmarks_page(results: dict | None) -> str:
    lines = [
        "# Benchmarks",
        "",
        "Each `benchmarks/bench_*.py` times an engine against a reference measured in the same "
        "run, and says what that reference computes and how accurately (`make benchmark` runs "
        "them all; `make test` runs each in a short smoke mode, asserting no time).",
        "",
    ]
    if not results:
        not_run = "*Not run for this build* (`HARP_ANALYSIS_DOCS_BENCHMARKS=off`)."
        return "\n".join([*lines, not_run, ""])
    mode = {
        "full": "at `make benchmark`'s sizes",
        "smoke": "in the smoke mode: tiny sizes, one round (the timings mean little)",
    }[results["mode"]]
    lines += [
        f"The output below is of one run {mode}, on {results['date']}, on the machine that "
        f"built this site ({results['machine']}); the numbers are those of that run.",
        "",
    ]
    for name, run in results["benchmarks"].items():
        lines += [
            f"## {name}",
            "",
            f"{run['seconds']:.0f} s in all.",
            "",
            "```text",
            run["output"].rstrip().replace("```", "'''"),
            "```",
            "",
        ]
    return "\n".join(lines)


def _curated_page() -> str:
    import harp_analysis

    lines = [
        "# The curated names",
        "",
        "`harp_analysis.__all__`: the names a user starts from, importable from the package "
        "itself (`from harp_analysis import simulate_3dof`), each imported on first use. Each "
        "is documented in the module that defines it:",
        "",
    ]
    for name in harp_analysis.__all__:
        if name == "__version__":
            lines.append(f"- `__version__`: `{harp_analysis.__version__}`, this site's version")
            continue
        module = harp_analysis._API[name]
        where = f"harp_analysis.{module}"
        lines.append(f"- {{py:obj}}`{name} <{where}.{name}>` ({{mod}}`{where}`)")
    return "\n".join([*lines, ""])


def _chapters_index(pages: list[str]) -> str:
    return "\n".join(
        [
            "# The chapters",
            "",
            "The reproduction read like a paper: one page per notebook, run once when the site "
            "was built, with its figures and numbers in place (each notebook imports the "
            "package, draws and explains; the physics lives in the package).",
            "",
            "```{toctree}",
            ":maxdepth: 1",
            "",
            *pages,
            "```",
            "",
        ]
    )


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
    by_number = {e.number: e for e in entries}
    tied: dict[str, list[LedgerRow]] = {}
    for row in rows:
        for number in row.figures:
            tied.setdefault(number, []).append(row)
    pages: dict[str, str] = {}
    figure_pages = []
    for e in entries:
        pages[f"gallery/{_slug(e.number)}.md"] = _figure_page(
            e, tied.get(e.number, []), chapter_pages
        )
        figure_pages.append(_slug(e.number))
    pages["gallery/index.md"] = _gallery_index(entries, tied, figure_pages)
    pages["ledger.md"] = _ledger_page(rows, by_number)
    pages["_generated/summary.md"] = _summary(entries, rows)
    pages["_generated/extensions.md"] = _extension_list(entries)
    pages["_generated/uncertainties.md"] = _uncertainties()
    pages["benchmarks.md"] = _benchmarks_page(benchmarks)
    pages["api/curated.md"] = _curated_page()
    pages["chapters/index.md"] = _chapters_index(list(chapter_pages.values()))
    harp = paths.ROOT / "data" / "harp"
    readme = (harp / "README.md").read_text()
    data_files = sorted(p.name for p in harp.glob("*.tsv")) + ["SHA256SUMS"]
    pages["provenance/index.md"] = (
        readme.replace("](radar/README.md)", "](radar.md)")
        + "\n\n## The files\n\n"
        + "\n".join(f"- {{download}}`{name} <data/{name}>`" for name in data_files)
        + "\n\n```{toctree}\n:hidden:\n\nradar\n```\n"
    )
    pages["provenance/radar.md"] = (harp / "radar" / "README.md").read_text()
    written = []
    for name, text in pages.items():
        _write_if_changed(target / name, text)
        written.append(target / name)
    for name in data_files:
        _copy_if_changed(harp / name, target / "provenance" / "data" / name)
    return written


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
    docs = Path(docs) if docs else paths.ROOT / "docs"
    cache = Path(cache) if cache else target.parent / "cache"
    cache.mkdir(parents=True, exist_ok=True)
    for path in sorted(docs.rglob("*")):
        relative = path.relative_to(docs)
        if path.is_file() and not _CONFIGURATION & set(relative.parts):
            _copy_if_changed(path, target / relative)
    for name in ("CHANGELOG.md", "CITATION.cff"):
        _copy_if_changed(paths.ROOT / name, target / "_root" / name)
    _figures_for_site(target, cache / "thumbnails")
    notebooks = [
        path
        for path in sorted(paths.NOTEBOOKS_DIR.glob(CHAPTER_NOTEBOOKS))
        if path.name != EXPLORER_NOTEBOOK
    ]
    start = time.perf_counter()
    with ThreadPoolExecutor(max_workers=1) as background:
        # the ledger in this process while the notebooks run in their kernels
        running = background.submit(run_notebooks, notebooks, cache, jobs) if execute else None
        rows = evaluated_ledger(cache)
        executed = running.result() if running else {path: path for path in notebooks}
    print(f"{time.perf_counter() - start:6.1f} s  notebooks and ledger", flush=True)
    chapter_pages = {}
    for path in notebooks:
        _copy_if_changed(executed[path], target / "chapters" / path.name)
        chapter_pages[path.name] = f"/chapters/{path.stem}"
    results = None if benchmarks == "off" else run_benchmarks(cache, benchmarks)
    write_pages(target, rows, chapter_pages, results, quoted_registry(cache))
    expected = {target / "chapters" / path.name for path in notebooks}
    for stale in (target / "chapters").glob("*.ipynb"):  # a notebook renamed or removed
        if stale not in expected:
            stale.unlink()


# --- the check of the built site --------------------------------------------------------------


class _Page(HTMLParser):
    """The ids, links and resources of one HTML page."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.ids: set[str] = set()
        self.links: list[str] = []
        self.resources: list[tuple[str, str]] = []  # (tag, url)

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = {name: value for name, value in attrs if value is not None}
        for name in ("id", "name") if tag == "a" else ("id",):
            if name in values:
                self.ids.add(values[name])
        if tag == "a" and "href" in values:
            self.links.append(values["href"])
        if tag in ("img", "script", "iframe", "source", "embed", "audio", "video"):
            if "src" in values:
                self.resources.append((tag, values["src"]))
        if tag == "link" and "href" in values:
            self.resources.append((tag, values["href"]))
        if tag == "object" and "data" in values:
            self.resources.append((tag, values["data"]))
        for srcset in (values.get("srcset"),):
            if srcset:
                for part in srcset.split(","):
                    self.resources.append((tag, part.split()[0]))


_CSS_URL = re.compile(r"""url\(\s*['"]?([^'")]+)['"]?\s*\)|@import\s+['"]([^'"]+)['"]""")


def _external(url: str) -> bool:
    parts = urlsplit(url)
    return bool(parts.scheme and parts.scheme not in ("data", "file")) or url.startswith("//")


def check_site(site: Path) -> list[str]:
    """What is wrong with the built site in ``site``: every link of every page to another page
    of the site must reach an existing file and, with a fragment, an element with that id; every
    image, script and stylesheet must be there; no page or stylesheet may load anything from
    outside (a CDN, a web font), so that the site works offline. Links out of the site (``http``,
    ``mailto``) are allowed but never followed. Empty when all is well."""
    site = Path(site).resolve()
    pages: dict[Path, _Page] = {}
    for path in sorted(site.rglob("*.html")):
        if path.relative_to(site).parts[0] == "_static":
            continue  # the theme's templates copied as they are (webpack-macros.html), no page
        parser = _Page()
        parser.feed(path.read_text(errors="replace"))
        pages[path.resolve()] = parser
    problems = []
    if not pages:
        return [f"{site}: no HTML page"]

    def resolve(base: Path, url: str) -> tuple[Path, str]:
        parts = urlsplit(url)
        target = (base.parent / unquote(parts.path)).resolve() if parts.path else base
        if target.is_dir():
            target = target / "index.html"
        return target, unquote(parts.fragment)

    for path, page in pages.items():
        name = path.relative_to(site).as_posix()
        for url in page.links:
            if _external(url) or url.startswith(("mailto:", "javascript:")):
                continue
            target, fragment = resolve(path, url)
            if not target.is_file():
                problems.append(f"{name}: link {url!r} reaches no file")
            elif fragment and target.suffix == ".html" and fragment not in pages[target].ids:
                problems.append(f"{name}: link {url!r} reaches no element id={fragment!r}")
        for tag, url in page.resources:
            if _external(url):
                problems.append(f"{name}: <{tag}> loads {url!r} from outside the site")
                continue
            if url.startswith("data:"):
                continue
            target, _ = resolve(path, url)
            if not target.is_file():
                problems.append(f"{name}: <{tag}> {url!r} is missing")
    for css in sorted(site.rglob("*.css")):
        for match in _CSS_URL.finditer(css.read_text(errors="replace")):
            url = match.group(1) or match.group(2)
            if url.startswith(("data:", "#")):
                continue
            if _external(url):
                problems.append(f"{css.relative_to(site)}: loads {url!r} from outside the site")
            elif not (css.parent / unquote(urlsplit(url).path)).is_file():
                problems.append(f"{css.relative_to(site)}: {url!r} is missing")
    return problems


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
    pages = sum(p.relative_to(args.site).parts[0] != "_static" for p in args.site.rglob("*.html"))
    print(
        f"{pages} pages checked: {len(problems)} problems"
        if problems
        else f"{pages} pages "
        "checked: every internal link, anchor and image is there, nothing loaded from outside"
    )
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
