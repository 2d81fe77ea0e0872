"""The claims ledger: every number the dissertation states, recomputed by the package.

The ledger is ``registry/claims.toml``. Each ``[[claim]]`` names the package callable that
computes the project's value (``compute = "module:function"``, with optional ``kwargs``, an
optional ``field`` to read from the result and an optional ``scale`` to the row's unit), so the
value is recomputed on every evaluation and never typed in. Verdicts are checked against the
numbers (:func:`verdict_problems`), so a verdict cannot silently go stale:

- ``reproduces``: the computed value is within ``tolerance`` of the text's;
- ``close``: outside ``tolerance`` but within ``close_tolerance``, with an explanation;
- ``does not reproduce``: outside ``close_tolerance`` (or ``tolerance`` if none), with an
  explanation.

Tolerances are absolute in the row's unit, or relative when ``tolerance_kind = "relative"``.
A claim that is a bound ("less than 1 %", "over 4 degrees") sets ``bound = "upper"`` or
``"lower"``: only a computed value on the wrong side of the text's counts as a deviation.
"""

from __future__ import annotations

import importlib
import math
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

from . import paths
from .registry import load_toml_rows

__all__ = [
    "Claim",
    "ClaimResult",
    "load_claims",
    "evaluate",
    "evaluate_all",
    "verdict_problems",
    "render_claims",
    "VERDICTS",
]

VERDICTS = ("reproduces", "close", "does not reproduce")
_REQUIRED = (
    "id",
    "source",
    "statement",
    "text_value",
    "unit",
    "compute",
    "tolerance",
    "verdict",
    "explanation",
)


@dataclass(frozen=True)
class Claim:
    id: str
    source: str
    statement: str
    text_value: float
    unit: str
    compute: str
    tolerance: float
    verdict: str
    explanation: str
    tolerance_kind: str = "absolute"
    close_tolerance: float | None = None
    kwargs: dict = field(default_factory=dict, hash=False)
    field: str | None = None
    scale: float = 1.0
    bound: str | None = None


@dataclass(frozen=True)
class ClaimResult:
    claim: Claim
    computed: float

    @property
    def deviation(self) -> float:
        """|computed - text| (for a bound, only past it), relative to the text's value when
        the tolerance is relative."""
        difference = self.computed - self.claim.text_value
        difference = {"upper": max(difference, 0.0), "lower": max(-difference, 0.0)}.get(
            self.claim.bound or "", abs(difference)
        )
        if self.claim.tolerance_kind == "relative":
            return difference / abs(self.claim.text_value)
        return difference

    @property
    def within_tolerance(self) -> bool:
        return self.deviation <= self.claim.tolerance


def _claim(raw: dict, position: int, source: Path) -> Claim:
    where = f"{source.name} claim {raw.get('id', '?')!r}"
    missing = [name for name in _REQUIRED if name not in raw]
    if missing:
        raise ValueError(f"{where}: missing field(s) {', '.join(missing)}")
    unknown = set(raw) - set(Claim.__dataclass_fields__)
    if unknown:
        raise ValueError(f"{where}: unknown field(s) {', '.join(sorted(unknown))}")
    if raw["verdict"] not in VERDICTS:
        raise ValueError(f"{where}: verdict {raw['verdict']!r} is not one of {VERDICTS}")
    if raw.get("tolerance_kind", "absolute") not in ("absolute", "relative"):
        raise ValueError(f"{where}: tolerance_kind must be 'absolute' or 'relative'")
    if raw.get("bound") not in (None, "upper", "lower"):
        raise ValueError(f"{where}: bound must be 'upper' or 'lower'")
    if ":" not in raw["compute"]:
        raise ValueError(f"{where}: compute must read 'module:function', got {raw['compute']!r}")
    return Claim(**raw)


@cache
def load_claims(path: Path | None = None) -> tuple[Claim, ...]:
    """Every claim of the ledger, in file order; ids must be unique."""
    path = Path(path) if path else paths.REGISTRY_DIR / "claims.toml"
    return load_toml_rows(path, "claim", _claim, "id")


def evaluate(claim: Claim) -> ClaimResult:
    """Compute the project's value of ``claim`` by calling the package."""
    module_name, _, attribute = claim.compute.partition(":")
    result = getattr(importlib.import_module(module_name), attribute)(**claim.kwargs)
    if claim.field:
        result = getattr(result, claim.field)
    return ClaimResult(claim, float(result) * claim.scale)


def evaluate_all() -> list[ClaimResult]:
    return [evaluate(claim) for claim in load_claims()]


def verdict_problems(result: ClaimResult) -> list[str]:
    """Why ``result``'s verdict does not match its numbers (empty when it does)."""
    claim, problems = result.claim, []
    if not math.isfinite(result.computed):
        return [f"computed value is {result.computed}"]
    if claim.verdict == "reproduces":
        if not result.within_tolerance:
            problems.append(
                f"marked 'reproduces' but deviates by {result.deviation:.4g} "
                f"> tolerance {claim.tolerance:g}"
            )
        return problems
    if not claim.explanation.strip():
        problems.append(f"verdict {claim.verdict!r} needs an explanation")
    if result.within_tolerance:
        problems.append(
            f"marked {claim.verdict!r} but is within tolerance "
            f"({result.deviation:.4g} <= {claim.tolerance:g}): it reproduces"
        )
    if claim.verdict == "close":
        if claim.close_tolerance is None:
            problems.append("verdict 'close' needs a close_tolerance")
        elif result.deviation > claim.close_tolerance:
            problems.append(
                f"marked 'close' but deviates by {result.deviation:.4g} "
                f"> close_tolerance {claim.close_tolerance:g}"
            )
    elif claim.close_tolerance is not None and result.deviation <= claim.close_tolerance:
        problems.append(
            f"marked 'does not reproduce' but is within close_tolerance "
            f"{claim.close_tolerance:g}: it is close"
        )
    return problems


def _number(value: float) -> str:
    return f"{value:.6g}"


def render_claims(target: Path | None = None) -> Path:
    """Write ``figures/CLAIMS.md``: the ledger evaluated now, as a readable table."""
    target = Path(target) if target else paths.FIGURES_DIR / "CLAIMS.md"
    results = evaluate_all()
    counts = {v: sum(r.claim.verdict == v for r in results) for v in VERDICTS}
    lines = [
        "# Claims ledger: the dissertation's numbers, recomputed",
        "",
        "Generated by `make figures` from `registry/claims.toml`; do not edit by hand. Every "
        "computed value comes from the package at generation time; `tests/test_ledger.py` "
        "checks every verdict against it.",
        "",
        ", ".join(f"{n} {verdict}" for verdict, n in counts.items()) + f" ({len(results)} in all).",
        "",
        "| id | source | statement | text | computed | unit | tolerance | verdict | explanation |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in results:
        c = r.claim
        tolerance = (
            f"{c.tolerance:g}" if c.tolerance_kind == "absolute" else f"{c.tolerance:.2%} rel."
        )
        text = {"upper": "< ", "lower": "> "}.get(c.bound or "", "") + _number(c.text_value)
        lines.append(
            f"| `{c.id}` | {c.source} | {c.statement} | {text} | "
            f"{_number(r.computed)} | {c.unit} | {tolerance} | **{c.verdict}** | "
            f"{c.explanation} |"
        )
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text("\n".join(lines) + "\n")
    return target
