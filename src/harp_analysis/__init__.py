"""harp-analysis: a validated reproduction of Stutz (2013), the Modified Kepler Solution for
hypersonic projectiles launched into space, and its check against the HARP 16-inch gun data.

SI units throughout the package (m, s, kg, rad) unless a module's first line says otherwise.

The names a user starts from are importable here (``from harp_analysis import Launch,
simulate_3dof``): a launch and the text's named ones, the projectiles and sites, each engine's
flight, the firing solutions and the warnings the models give. Each is imported on first use,
so ``import harp_analysis`` starts no compiler; everything else lives in its module
(``harp_analysis.harp``, ``harp_analysis.error_budget``, ...).
"""

# ruff: noqa: F401  (the TYPE_CHECKING imports name the lazy attributes for type checkers)
from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

#: Public name -> the module that defines it.
_API = {
    # launches
    "Launch": "launch",
    "Launches": "launch",
    "chapter_2": "launch",
    "baseline_chapter_4": "launch",
    "HP_CHAPTER_2": "launch",
    "LP_CHAPTER_2": "launch",
    # projectiles and sites
    "Projectile": "projectiles",
    "HP": "projectiles",
    "LP": "projectiles",
    "BASELINE": "projectiles",
    "get_projectile": "projectiles",
    "BARBADOS": "sites",
    "YUMA": "sites",
    "get_site": "sites",
    "get_atmosphere": "atmosphere",
    # the engines, one flight each, all returning the shared trajectory table
    "simulate_3dof": "threedof",
    "fly_3dof": "threedof",
    "simulate_6dof": "sixdof",
    "simulate_mlt": "mlt",
    "simulate_mks": "mks",
    "simulate_appendix_a": "appendix_a",
    # fire control
    "TargetPoint": "fire_control",
    "destination": "fire_control",
    "firing_solutions": "fire_control",
    # what the models warn of
    "ModelValidityWarning": "validation",
    "TruncatedFlightWarning": "trajectory",
}

__all__ = ["__version__", *_API]

if TYPE_CHECKING:  # for type checkers and editors; at run time each name is imported lazily
    from .appendix_a import simulate_appendix_a
    from .atmosphere import get_atmosphere
    from .fire_control import TargetPoint, destination, firing_solutions
    from .launch import HP_CHAPTER_2, LP_CHAPTER_2, Launch, Launches, baseline_chapter_4, chapter_2
    from .mks import simulate_mks
    from .mlt import simulate_mlt
    from .projectiles import BASELINE, HP, LP, Projectile, get_projectile
    from .sites import BARBADOS, YUMA, get_site
    from .sixdof import simulate_6dof
    from .threedof import fly_3dof, simulate_3dof
    from .trajectory import TruncatedFlightWarning
    from .validation import ModelValidityWarning


def __getattr__(name: str) -> Any:
    """A public name imported from its module on first use (PEP 562); a submodule as usual."""
    module = _API.get(name)
    if module is None:
        raise AttributeError(f"module 'harp_analysis' has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_API})
