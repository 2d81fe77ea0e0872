"""harp-analysis: a validated reproduction of Stutz (2013), the Modified Kepler Solution for
hypersonic projectiles launched into space, and its check against the HARP 16-inch gun data.

SI units throughout the package (m, s, kg, rad) unless a module's first line says otherwise.

The names a user starts from are importable here (``from harp_analysis import Launch,
simulate_3dof``): a launch and the text's named ones, the projectiles and sites, each engine's
flight and ``fly(launch, engine="3dof")`` with the engines' records (``get_engine``), the firing
solutions and the warnings the models give. Each is imported on first use,
so ``import harp_analysis`` starts no compiler; everything else lives in its module
(``harp_analysis.analyses.harp.apogees``, ``harp_analysis.analyses.error_budget``, ...).
"""

# ruff: noqa: F401  (the TYPE_CHECKING imports name the lazy attributes for type checkers)
from __future__ import annotations

import importlib
from importlib import metadata as _metadata
from typing import TYPE_CHECKING, Any

try:  # the one source of the version is pyproject.toml, read from the installed metadata
    __version__ = _metadata.version("harp-analysis")
except _metadata.PackageNotFoundError:  # a checkout on sys.path that was never installed
    __version__ = "0+unknown"

#: Public name -> the module that defines it.
_API = {
    # launches
    "Launch": "models.launch",
    "Launches": "models.launch",
    "chapter_2": "models.launch",
    "baseline_chapter_4": "models.launch",
    "HP_CHAPTER_2": "models.launch",
    "LP_CHAPTER_2": "models.launch",
    # projectiles and sites
    "Projectile": "models.projectiles",
    "HP": "models.projectiles",
    "LP": "models.projectiles",
    "BASELINE": "models.projectiles",
    "get_projectile": "models.projectiles",
    "BARBADOS": "models.sites",
    "YUMA": "models.sites",
    "get_site": "models.sites",
    "get_atmosphere": "models.atmosphere",
    # the engines, one flight each, all returning the shared trajectory table; any by its name
    "fly": "engines.catalogue",
    "get_engine": "engines.catalogue",
    "simulate_3dof": "engines.threedof",
    "fly_3dof": "engines.threedof",
    "simulate_6dof": "engines.sixdof",
    "simulate_mlt": "engines.mlt",
    "simulate_mks": "engines.mks",
    "simulate_eci_mks": "engines.eci",
    "simulate_appendix_a": "engines.appendix_a",
    # fire control
    "TargetPoint": "analyses.fire_control.firing",
    "destination": "analyses.fire_control.firing",
    "firing_solutions": "analyses.fire_control.firing",
    # what the models warn of
    "ModelValidityWarning": "foundation.validation",
    "TruncatedFlightWarning": "models.trajectory",
    "EndAltitudeNotCrossedWarning": "models.trajectory",
}

__all__ = ["__version__", *_API]

if TYPE_CHECKING:  # for type checkers and editors; at run time each name is imported lazily
    from .analyses.fire_control.firing import TargetPoint, destination, firing_solutions
    from .engines.appendix_a import simulate_appendix_a
    from .engines.catalogue import fly, get_engine
    from .engines.eci import simulate_eci_mks
    from .engines.mks import simulate_mks
    from .engines.mlt import simulate_mlt
    from .engines.sixdof import simulate_6dof
    from .engines.threedof import fly_3dof, simulate_3dof
    from .foundation.validation import ModelValidityWarning
    from .models.atmosphere import get_atmosphere
    from .models.launch import (
        HP_CHAPTER_2,
        LP_CHAPTER_2,
        Launch,
        Launches,
        baseline_chapter_4,
        chapter_2,
    )
    from .models.projectiles import BASELINE, HP, LP, Projectile, get_projectile
    from .models.sites import BARBADOS, YUMA, get_site
    from .models.trajectory import EndAltitudeNotCrossedWarning, TruncatedFlightWarning


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
