"""The launch the ledger's computations of Chapters 1, 3 and 4 share: Chapter 4's launch
without wind or spin (:func:`~harp_analysis.analyses.claims.launches.no_wind`)."""

from __future__ import annotations

from ...models.launch import Launch
from ..comparisons import chapter_4_launch

__all__ = [
    "no_wind",
]


def no_wind(projectile: str, elevation_deg: float) -> Launch:
    """Chapter 4's launch of ``projectile`` without wind or spin: a planar flight, the one the
    drag-free conic and Fig 4.8 ("with no wind") compare with."""
    return chapter_4_launch(projectile, elevation_deg).but(
        cross_wind_m_s=0.0, head_wind_m_s=0.0, spin_rad_s=0.0
    )
