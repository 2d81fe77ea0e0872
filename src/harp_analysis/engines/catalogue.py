"""The engines in one place: a record per engine, and one ``fly(launch, engine="3dof")``.

As py-ballisticcalc's engines share one protocol and one test suite, every engine here flies a
:class:`~harp_analysis.models.launch.Launch` to the trajectory table of
:mod:`harp_analysis.models.trajectory` (the same columns, the same metadata in ``frame.attrs``),
and its :class:`Engine` record says what else a caller needs to know: its label, what it models
(wind, a rotating Earth, the day's air), whether its table has every column, whether it flies a
batch of launches at once, which projectiles it takes, the option that sets its numerical
accuracy, and what Fig 4.7 counts of its work. ``tests/test_engines.py`` runs its physics suite
over :data:`ENGINES`; the explorer offers its engines and :mod:`harp_analysis.analyses.effort`
counts them from here.

====================  =====  ========  ========  ==========  =====  ==========  ====================
engine                wind   rotating  day's     full table  batch  rigid body  tolerance
                             Earth     air
====================  =====  ========  ========  ==========  =====  ==========  ====================
``3dof``              yes    yes       yes       yes         yes    no          ``rtol``
``6dof``              yes    no        no        yes         no     yes         ``rtol``
``mlt``               yes    no        no        yes         no     yes         ``segment_length_m``
``mks``               no     no        yes       yes         no     no          ``n_terms``
``eci_mks``           no     yes       yes       yes         no     no          ``n_terms``
``calibrated_mks``    no     yes       yes [2]_  yes         no     no          ``grid``
``flyout_table``      no     yes       yes [2]_  yes         no     no          ``grid``
``appendix_a``        no     yes [1]_  yes       no          no     no          ``dt_s``
====================  =====  ========  ========  ==========  =====  ==========  ====================

.. [1] with the macro's printed rotation terms (:mod:`.appendix_a`); its listing runs with them off.
.. [2] the day's density within the band it was learned on (+-10 %), at the gun's temperature:
   :mod:`.calibrated_mks` and :mod:`.flyout_table` learn a table per gun from its 3DOF flights
   and refuse a launch outside it by name.

What an engine does not model it says: a wind or a day's air left out is a
:class:`~harp_analysis.foundation.validation.ModelValidityWarning` naming the field; a rotating
Earth it cannot fly is a ValueError naming ``rotation_rate_rad_s``. The MKS's many launches at once
(:func:`.mks.for_launch`, :func:`.eci.correction_for_launch`) are one closed-form solution, not
flights; the improved MKS (:mod:`.mks_improved`) has no trajectory table and is not listed.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from types import MappingProxyType

import pandas as pd

from ..foundation.counting import Counted
from ..foundation.validation import check_choice
from ..models.launch import Launch
from . import appendix_a, calibrated_mks, eci, flyout_table, mks, mlt, sixdof, threedof

__all__ = ["Engine", "ENGINES", "ENGINE_NAMES", "get_engine", "fly"]


@dataclass(frozen=True)
class Engine:
    """One engine: how to fly it and what it models.

    ``fly(launch, **options)`` returns the shared trajectory table; ``options`` are the
    engine's own keywords (``tolerance`` among them; Appendix A's ``dt_s`` has no default, as
    the text prints none). ``fly_batch(launches, **options)``, where there is one, flies a
    :class:`~harp_analysis.models.launch.Launches` in one compiled call, a row per launch with
    the metadata of the tables it would return one by one. ``counted(launch)`` is what Fig 4.7
    counts of the engine's work (:mod:`harp_analysis.foundation.counting`): the functions one
    evaluation of its right-hand side runs (the 3DOF, the 6DOF), or every function its segment
    loop calls (MLT); None where the count is not of the engine's own code (the MKS's apogee is
    counted as straight-line code in :mod:`harp_analysis.analyses.effort`)."""

    name: str  # the key of ENGINES, and fly()'s engine=
    label: str  # as frame.attrs["engine"] names it, and as figures and the explorer show it
    summary: str  # what it is, in a line
    fly: Callable[..., pd.DataFrame]
    tolerance: str  # the option that sets its numerical accuracy: tighter, closer to converged
    # What it models, each off unless its row says so:
    wind: bool = False  # flies the launch's head and cross wind
    rotating_earth: bool = False  # flies a launch on the turning Earth (rotation_rate_rad_s)
    day_air: bool = False  # flies the day's density and temperature change
    full_table: bool = True  # every column of trajectory.BASE_COLUMNS (all but Appendix A's)
    rigid_body: bool = False  # needs Appendix B's projectile (aerodynamic tables and inertias)
    fly_batch: Callable[..., pd.DataFrame] | None = None
    counted: Callable[[Launch], tuple[Counted, ...]] | None = None

    @property
    def batch(self) -> bool:
        """Whether it flies many launches in one call (:attr:`fly_batch`)."""
        return self.fly_batch is not None


_ENGINES = (
    Engine(
        "3dof",
        "3DOF",
        "point mass, Appendix A's physics, adaptive DOP853 with events (compiled)",
        threedof.simulate_3dof,
        "rtol",
        wind=True,
        rotating_earth=True,
        day_air=True,
        fly_batch=threedof.simulate_3dof_batch,
        counted=threedof.counted_functions,
    ),
    Engine(
        "6dof",
        "6DOF",
        "Appendix B's rigid finned projectile, in the no-roll frame (DOP853)",
        sixdof.simulate_6dof,
        "rtol",
        wind=True,
        rigid_body=True,
        counted=sixdof.counted_functions,
    ),
    Engine(
        "mlt",
        "MLT",
        "Modified Linear Theory, reconstructed: closed-form segments of the 6DOF's equations",
        mlt.simulate_mlt,
        "segment_length_m",
        wind=True,
        rigid_body=True,
        counted=mlt.counted_functions,
    ),
    Engine(
        "mks",
        "MKS",
        "the Modified Kepler Solution (eq 3.30) on a non-rotating Earth, closed form",
        mks.simulate_mks,
        "n_terms",
        day_air=True,
    ),
    Engine(
        "eci_mks",
        "ECI MKS",
        "the MKS on the rotating Earth (Chapter 5's inertial-frame correction), closed form",
        eci.simulate_eci_mks,
        "n_terms",
        rotating_earth=True,
        day_air=True,
    ),
    Engine(
        "calibrated_mks",
        "calibrated MKS",
        "the ECI MKS corrected by a table learned from the gun's 3DOF flights (Chapter 7 C)",
        calibrated_mks.simulate_calibrated_mks,
        "grid",
        rotating_earth=True,
        day_air=True,
    ),
    Engine(
        "flyout_table",
        "fly-out table",
        "the gun's 3DOF flights over a grid, interpolated directly (Chapter 7 A's fly-out table)",
        flyout_table.simulate_flyout_table,
        "grid",
        rotating_earth=True,
        day_air=True,
    ),
    Engine(
        "appendix_a",
        "Appendix A macro",
        "Appendix A's own fixed-step numerics, to explain artefacts of the original figures",
        appendix_a.simulate_appendix_a,
        "dt_s",
        rotating_earth=True,
        day_air=True,
        full_table=False,
    ),
)
#: Every engine by name, in the order above.
ENGINES = MappingProxyType({engine.name: engine for engine in _ENGINES})
ENGINE_NAMES = tuple(ENGINES)


def get_engine(name: str) -> Engine:
    """The engine called ``name`` (one of :data:`ENGINE_NAMES`); a ValueError naming them.

    Parameters
    ----------
    name : str
        One of :data:`ENGINE_NAMES`.

    Returns
    -------
    Engine
        The engine's record: its label, its flight, what it models.
    """
    return ENGINES[check_choice(name, "engine", ENGINES)]


def fly(launch: Launch, engine: str = "3dof", **options) -> pd.DataFrame:
    """``launch`` flown by ``engine`` (one of :data:`ENGINE_NAMES`) with the engine's own
    keyword ``options``, as the shared trajectory table of :mod:`harp_analysis.models.trajectory`
    (``fly(HP_CHAPTER_2, "6dof", rtol=1e-10)``).

    Parameters
    ----------
    launch : Launch
        The launch to fly.
    engine : str
        One of :data:`ENGINE_NAMES`.
    **options
        The engine's own keyword options (its tolerance, output step, ...).

    Returns
    -------
    pandas.DataFrame
        The trajectory table of :mod:`harp_analysis.models.trajectory`, one row per output
        time in SI units, with the shared metadata in ``frame.attrs``.
    """
    return get_engine(engine).fly(launch, **options)
