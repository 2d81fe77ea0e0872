"""The dissertation's tables built by the package, each computed value beside the text's (the
ledger's rows, registry/claims.toml); notebooks save them with
:func:`~harp_analysis.reporting.plotting.save_table`."""

from __future__ import annotations

import pandas as pd

from ..analyses import comparisons, scenarios
from . import ledger

__all__ = ["DRAG_TO_WEIGHT_THRESHOLDS", "table_4_1"]

#: The drag/weight ratios Table 4.1's printed "drag = weight" altitudes may mean.
DRAG_TO_WEIGHT_THRESHOLDS = (0.001, 0.01)
_DAGGER = "\u2020 "


def _note(claims: dict[str, ledger.ClaimResult], name: str) -> str:
    """The ledger rows of projectile ``name`` whose value is not the text's, with their
    verdicts; a dagger marks the large deviations ("does not reproduce"), and for the "drag =
    weight" altitude the threshold whose crossing lies nearest the printed value is named."""
    parts = []
    for claim_id, result in claims.items():
        verdict = result.claim.verdict
        if not claim_id.endswith(f".{name.lower()}") or verdict == "reproduces":
            continue
        part = (_DAGGER if verdict == "does not reproduce" else "") + f"{claim_id} ({verdict})"
        if ".drag_equals_weight." in claim_id:
            nearest = min(DRAG_TO_WEIGHT_THRESHOLDS, key=lambda n: abs(
                scenarios.drag_to_gravity_crossing_altitude_km(name, n) - result.claim.text_value
            ))  # fmt: skip
            part += f": the text's altitude is where drag = {nearest:g} weight"
        parts.append(part)
    return "; ".join(parts)


def table_4_1(projectiles=("HP", "LP", "baseline")) -> pd.DataFrame:
    """Table 4.1 for ``projectiles``: the drag/weight at launch, the altitude where drag = weight
    (and where drag falls to :data:`DRAG_TO_WEIGHT_THRESHOLDS` of the weight) and the MKS's
    beta, each beside the text's value, and a note naming the ledger rows (``table4.1.*``) whose
    computed value is not the text's (``_note()``)."""
    claims = {result.claim.id: result for result in ledger.evaluate_all("table4.1.")}

    def text(key: str, name: str) -> float:
        return claims[f"table4.1.{key}.{name.lower()}"].claim.text_value

    rows = {
        name: {
            "drag/weight at launch (text)": text("n0", name),
            "drag/weight at launch": scenarios.launch_drag_to_gravity(name),
            "altitude where drag = weight, km (text)": text("drag_equals_weight", name),
            "altitude where drag = weight, km": scenarios.drag_to_gravity_crossing_altitude_km(
                name
            ),
            **{
                f"altitude where drag = {n:g} weight, km": (
                    scenarios.drag_to_gravity_crossing_altitude_km(name, n)
                )
                for n in DRAG_TO_WEIGHT_THRESHOLDS
            },
            "MKS beta (text)": text("beta", name),
            "MKS beta": comparisons.mks_beta(name),
            "note": _note(claims, name),
        }
        for name in projectiles
    }
    return pd.DataFrame.from_dict(rows, orient="index")
