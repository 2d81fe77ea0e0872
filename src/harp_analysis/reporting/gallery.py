"""The gallery ``figures/README.md``: every figure's status, caption and the ledger rows about
it, and the check that the registry's statuses agree with the ledger.

A figure is "reproduced" only when every ledger row about it reproduces; a drawn figure with a
row that is close or does not reproduce is "drawn, deviates", and the gallery links the rows.
A row tied to a figure by its paragraph but about what the figure cannot draw is exempted from
its status with the reason (the ledger's ``exempt``), and listed as such. The project's own
figures (registry ``extension = true``, numbered X.1, X.2, ...) follow in a section of their
own, "Beyond the dissertation": "drawn, extension", held by the tests their reason names; where
one draws a number the text states, the ledger scores it there too. Reasons and captions quote
the ledger's numbers (:func:`.ledger.quote_rows`), and each figure lists the extension results
measured about it.
"""

from __future__ import annotations

from pathlib import Path

from ..foundation import paths
from .ledger import (
    VERDICTS,
    ClaimResult,
    MeasuredResult,
    bearing_on,
    claims_by_figure,
    evaluate_all,
    load_measurements,
    measurements_by_figure,
    quote_rows,
)
from .registry import DRAWN, STATUSES, RegistryEntry, load_registry

__all__ = [
    "render_gallery",
    "status_problems",
    "reason_text",
    "caption_text",
    "readme_headline",
    "render_readme_headline",
    "README_MARKERS",
    "SHOWN",
]

#: The statuses as the gallery shows them.
SHOWN = {
    "reproduced": "reproduced",
    "deviates": "drawn, deviates",
    "partial": "partial",
    "pending": "pending",
    "not reproducible": "not reproducible",
    "extension": "drawn, extension",
}
_TABLE_HEAD = [
    "| number | title | class | status | notebook | reason |",
    "|---|---|---|---|---|---|",
]


def _rows(results: list[ClaimResult], only_deviating: bool = False) -> str:
    return ", ".join(
        f"[`{r.claim.id}`](CLAIMS.md#{r.claim.id}) ({r.claim.verdict})"
        for r in results
        if not (only_deviating and r.claim.verdict == "reproduces")
    )


def status_problems() -> list[str]:
    """Where a registry status disagrees with the ledger rows about the figure: "reproduced"
    with a row that does not reproduce (a recovered row included: agreement by construction is
    not a reproduction), or "deviates" with none; a reproduced figure that no row speaks about
    without its ``no_number`` (the text states no number about it), or a ``no_number`` on a
    figure that has rows."""
    tied = claims_by_figure()
    problems = []
    for entry in load_registry():
        rows = bearing_on(entry.number, tied.get(entry.number, []))
        problems += _verdict_problems(entry, rows) + _no_number_problems(entry, rows)
    return problems


def _verdict_problems(entry: RegistryEntry, rows: list[ClaimResult]) -> list[str]:
    """Where ``entry``'s status disagrees with the verdicts of ``rows``, the rows bearing on it."""
    deviating = [r for r in rows if r.claim.verdict != "reproduces"]
    if entry.status == "reproduced" and deviating:
        return [f"{entry.label} is 'reproduced' but {_rows(deviating)} do not reproduce"]
    if entry.status == "deviates" and not deviating:
        return [f"{entry.label} is 'deviates' but no ledger row about it deviates"]
    return []


def _no_number_problems(entry: RegistryEntry, rows: list[ClaimResult]) -> list[str]:
    """Where ``entry``'s ``no_number`` is missing (a reproduced figure without ``rows``, the rows
    bearing on it) or stale (a figure with rows)."""
    if entry.status == "reproduced" and not rows and not entry.no_number.strip():
        return [
            f"{entry.label} is 'reproduced' but no ledger row speaks about it: score what "
            "the text states about it, or say in no_number that it states no number"
        ]
    if rows and entry.no_number:
        return [f"{entry.label} has ledger rows, so its no_number is stale"]
    return []


def reason_text(entry: RegistryEntry) -> str:
    """``entry``'s reason as a reader sees it: the ledger's numbers quoted in."""
    return quote_rows(entry.reason)


def caption_text(entry: RegistryEntry) -> str:
    """``entry``'s caption as a reader sees it: the ledger's numbers quoted in."""
    return quote_rows(entry.caption)


def _exempted(entry: RegistryEntry, tied: list[ClaimResult]) -> str:
    """The rows exempted from ``entry``'s status, each with its reason."""
    return " ".join(
        f"Not bearing on it: [`{r.claim.id}`](CLAIMS.md#{r.claim.id}) ({r.claim.verdict}): "
        f"{r.claim.exempt[entry.number]}"
        for r in tied
        if entry.number in r.claim.exempt
    )


def _measured(results: list[MeasuredResult]) -> str:
    return ", ".join(f"[`{r.row.id}`](CLAIMS.md#{r.row.id})" for r in results)


def _line(entry: RegistryEntry, tied: list[ClaimResult], measured: list[MeasuredResult]) -> str:
    notebook = f"[{entry.notebook}](../notebooks/{entry.notebook})" if entry.notebook else ""
    reason = reason_text(entry)
    bearing = bearing_on(entry.number, tied)
    if entry.status in ("deviates", "partial", "extension") and _rows(bearing, True):
        reason = f"{reason} Rows: {_rows(bearing, True)}."
    if _exempted(entry, tied):
        reason = f"{reason} {_exempted(entry, tied)}".strip()
    if measured:
        reason = f"{reason} Extension results: {_measured(measured)}.".strip()
    if entry.no_number:
        reason = f"{reason} No ledger row: {entry.no_number}".strip()
    return (
        f"| {entry.label} | {entry.title} | {entry.figure_class} | "
        f"{SHOWN[entry.status]} | {notebook} | {_cell(reason)} |"
    )


def _cell(text: str) -> str:
    """Text safe inside a Markdown table cell: a literal | would end the cell."""
    return text.replace("|", "\\|").replace("\n", " ")


def render_gallery(target: Path | None = None) -> Path:
    """Write the gallery: every entry with its status, reason and ledger rows, then each drawn
    figure with its caption (PNG shown, vector PDF linked)."""
    target = Path(target) if target else paths.FIGURES_DIR / "README.md"
    tied, measured = claims_by_figure(), measurements_by_figure()
    entries = [e for e in load_registry() if not e.extension]
    extensions = [e for e in load_registry() if e.extension]
    lines = [
        "# Figures of Stutz (2013), regenerated",
        "",
        "Generated by `make figures` from `registry/figures.toml` and the ledger; do not edit by "
        "hand. A figure is *reproduced* when every number the text states about it reproduces "
        "([CLAIMS.md](CLAIMS.md)); *drawn, deviates* when one does not, with the rows linked.",
        "",
        _counted(entries),
        "",
        *_table(entries, tied, measured),
        *_drawn(entries, tied, measured),
    ]
    if extensions:
        lines += [
            "# Beyond the dissertation",
            "",
            "The project's own figures, numbered outside the dissertation's numbering: what the "
            "text's methods make possible but the text does not draw. The figures themselves are "
            "not the text's, so they carry no reproduction status; each is held by the tests its "
            "reason names. Where one draws a number the text does state, the ledger scores that "
            "number (the rows linked, failing ones included), and what the project measures of "
            "its own work is listed as extension results, measured and not scored "
            f"({len(extensions)} figures in all).",
            "",
            *_table(extensions, tied, measured),
            *_drawn(extensions, tied, measured),
        ]
    text = "\n".join(lines)
    return paths.write_atomically(target, lambda path: path.write_text(text))


def _counted(entries: list[RegistryEntry]) -> str:
    """How many of the dissertation's ``entries`` have each status, and how many in all."""
    counts = {
        status: sum(e.status == status for e in entries)
        for status in STATUSES
        if status != "extension"  # the dissertation's figures are never extensions
    }
    shown = ", ".join(f"{n} {SHOWN[status]}" for status, n in counts.items())
    return f"{shown} ({len(entries)} in all)."


def _table(
    entries: list[RegistryEntry],
    tied: dict[str, list[ClaimResult]],
    measured: dict[str, list[MeasuredResult]],
) -> list[str]:
    """The table of ``entries``: a line each, with its status, reason and ledger rows."""
    lines = [_line(e, tied.get(e.number, []), measured.get(e.number, [])) for e in entries]
    return [*_TABLE_HEAD, *lines, ""]


def _drawn(
    entries: list[RegistryEntry],
    tied: dict[str, list[ClaimResult]],
    measured: dict[str, list[MeasuredResult]],
) -> list[str]:
    """A section per drawn figure of ``entries``: its caption, status and image."""
    lines: list[str] = []
    for e in entries:
        if e.status not in DRAWN:
            continue
        if e.file.endswith(".png"):
            shown = f"![{e.label}]({e.file})\n\nVector: [{e.file[:-4]}.pdf]({e.file[:-4]}.pdf)"
        else:
            shown = f"[{e.file}]({e.file})"
        rows = _rows(bearing_on(e.number, tied.get(e.number, [])))
        exempted = _exempted(e, tied.get(e.number, []))
        results = _measured(measured.get(e.number, []))
        lines += [
            f"## {e.label}: {e.title}",
            "",
            f"*{caption_text(e)}*" if e.caption else "",
            "",
            f"Status: {SHOWN[e.status]}. Drawn by `notebooks/{e.notebook}`."
            + (f" Ledger rows: {rows}." if rows else "")
            + (f" {exempted}" if exempted else "")
            + (f" Extension results: {results}." if results else ""),
            "",
            shown,
            "",
        ]
    return lines


#: The lines README.md's headline stands between; :func:`render_readme_headline` writes it.
README_MARKERS = (
    "<!-- headline: written by `make figures` from the registry and the ledger; do not edit -->",
    "<!-- /headline -->",
)


def readme_headline() -> str:
    """What is reproduced, in two paragraphs for README.md: the figures by status and the
    ledger by verdict, counted from the registry and the ledger as they stand."""
    entries = load_registry()
    figures = [e for e in entries if not e.extension]
    status = {s: sum(e.status == s for e in figures) for s in STATUSES}
    verdicts = [r.claim.verdict for r in evaluate_all()]
    verdict = {v: verdicts.count(v) for v in VERDICTS}
    extensions = len(entries) - len(figures)
    return (
        f"**{status['reproduced']} of the dissertation's {len(figures)} figures and tables "
        "reproduced**: drawn from the package, every number the text states about them "
        f"recomputed within its tolerance. {status['deviates']} more are drawn but deviate (a "
        f"number the text states about them does not reproduce; each says which, and why), "
        f"{status['partial']} are partial (a layer whose data the text lacks), "
        + (f"{status['pending']} pending, " if status["pending"] else "")
        + f"and {status['not reproducible']} cannot be drawn from the "
        "text at all (photographs, sketches, models it does not give); "
        f"{extensions} more figures are the project's own, beyond the text "
        "([figures/README.md](figures/README.md)).\n\n"
        f"**{len(verdicts) - verdict['recovered']} of the text's checkable statements scored** "
        f"([figures/CLAIMS.md](figures/CLAIMS.md)): {verdict['reproduces']} reproduce, "
        f"{verdict['close']} are close and {verdict['does not reproduce']} do not reproduce, "
        f"each with the reason found; {verdict['recovered']} more agree only because the "
        "project fitted an input to them (recovered), and "
        f"{len(load_measurements())} extension results measure the project's own work beyond "
        "the text, unscored."
    )


def render_readme_headline(readme: Path | None = None) -> Path:
    """Rewrite README.md's headline (between :data:`README_MARKERS`) with
    :func:`readme_headline`; the rest of the file is left as it is."""
    readme = Path(readme) if readme else paths.ROOT / "README.md"
    text = readme.read_text()
    start, end = README_MARKERS
    if start not in text or end not in text:
        raise ValueError(f"{readme}: no headline markers ({start} ... {end})")
    before, rest = text.split(start, 1)
    _, after = rest.split(end, 1)
    updated = f"{before}{start}\n{readme_headline()}\n{end}{after}"
    return paths.write_atomically(readme, lambda path: path.write_text(updated))
