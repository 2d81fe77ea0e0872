"""The projectiles of the dissertation: HP and LP (Chapter 2 A, Appendix B) and the baseline cone
(Chapter 4 B), with the conflicts between the text and Appendix B's code recorded.

HP and LP ("heavy" and "light" projectile) share the M829 aerodynamics of Appendix B. The text
and the code disagree on their inertias and LP's diameter:

- the text gives HP roll and pitch inertias 0.00853 and 6.20934 kg m^2; Appendix B's code, which
  is the HP run (mass 15.66 kg, d = 0.0395 m), instead scales LP's inertias by mass and diameter
  squared, ``(15.66/5.029) (0.0395/0.0256)^2 [0.00033, 0.24021]`` = 0.002447 and 1.7808 kg m^2.
  :data:`HP` uses the code's values (the run that made the figures); :data:`HP_TEXT` the text's.
  A pitch inertia of 6.2 kg m^2 would need a 2.2 m long rod of 15.66 kg, while 1.78 kg m^2 fits
  a penetrator of about 1.2 m;
- the code's scaling divides by an LP diameter of 0.0256 m; the text says 26.8 mm. :data:`LP`
  follows the text (its diameter sets the reference area), :data:`LP_APPENDIX_B` the code's;
- the code carries a commented-out mass "4.894" next to 15.66; it is not used.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..foundation.validation import Bounds, check_choice, real_number
from .drag import BASELINE_CONE, M829, AeroTables, DragLaw

__all__ = [
    "Projectile",
    "HP",
    "HP_TEXT",
    "LP",
    "LP_APPENDIX_B",
    "BASELINE",
    "get_projectile",
    "check_rigid_body",
    "PROJECTILE_NAMES",
]

_SCALE_LP_TO_HP = (15.66 / 5.029) * (0.0395 / 0.0256) ** 2  # Appendix B's inertia scaling


@dataclass(frozen=True)
class Projectile:
    """Mass properties, reference area, drag and nominal launch speed of a projectile.

    Parameters
    ----------
    name : str
        Its name (:data:`PROJECTILE_NAMES` for the dissertation's).
    mass_kg : float
        Mass (kg).
    reference_area_m2 : float
        The area its drag coefficient refers to (m^2).
    drag_law : DragLaw
        Its zero-yaw drag coefficient against Mach (:mod:`harp_analysis.models.drag`).
    launch_speed_m_s : float
        The nominal muzzle speed the text gives it (m/s).
    source : str
        Where the values come from in the dissertation.
    diameter_m, roll_inertia_kg_m2, pitch_inertia_kg_m2 : float, optional
        Diameter (m) and moments of inertia (kg m^2) of a rigid body; the point-mass engines
        need none of them.
    aero : AeroTables, optional
        The aerodynamic coefficient tables the 6DOF and MLT fly (Appendix B's M829); None for
        a point mass.
    """

    name: str
    mass_kg: float
    reference_area_m2: float
    drag_law: DragLaw
    launch_speed_m_s: float
    source: str
    diameter_m: float | None = None
    roll_inertia_kg_m2: float | None = None
    pitch_inertia_kg_m2: float | None = None
    aero: AeroTables | None = None

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name:
            raise TypeError(f"name must be a non-empty string; got {self.name!r}")
        for name in ("mass_kg", "reference_area_m2", "launch_speed_m_s"):
            value = Bounds(low=0.0, low_inclusive=False).check(
                real_number(getattr(self, name), name), name
            )
            object.__setattr__(self, name, value)
        for name in ("diameter_m", "roll_inertia_kg_m2", "pitch_inertia_kg_m2"):
            if getattr(self, name) is not None:
                value = Bounds(low=0.0, low_inclusive=False).check(
                    real_number(getattr(self, name), name), name
                )
                object.__setattr__(self, name, value)
        if not callable(self.drag_law) or not hasattr(self.drag_law, "evaluate"):
            raise TypeError(
                f"drag_law must be a drag law of harp_analysis.models.drag (callable, with "
                "evaluate); "
                f"got {self.drag_law!r}"
            )
        if self.aero is not None and not isinstance(self.aero, AeroTables):
            raise TypeError(f"aero must be AeroTables or None; got {type(self.aero).__name__}")

    @property
    def launch_energy_j(self) -> float:
        """Kinetic energy at the nominal launch speed (J)."""
        return 0.5 * self.mass_kg * self.launch_speed_m_s**2


def _m829_round(name, mass_kg, diameter_m, roll, pitch, source) -> Projectile:
    return Projectile(
        name,
        mass_kg,
        math.pi / 4 * diameter_m**2,
        M829.zero_yaw_drag(),
        2022.0,
        source,
        diameter_m,
        roll,
        pitch,
        M829,
    )


HP = _m829_round(
    "HP",
    15.66,
    0.0395,
    _SCALE_LP_TO_HP * 0.00033,
    _SCALE_LP_TO_HP * 0.24021,
    "Ch. 2 A mass and diameter; inertias as Appendix B's code scales them",
)
HP_TEXT = _m829_round(
    "HP_text",
    15.66,
    0.0395,
    0.00853,
    6.20934,
    "Ch. 2 A: mass, diameter and inertias as the text states them",
)
LP = _m829_round("LP", 5.029, 0.0268, 0.00033, 0.24021, "Ch. 2 A, as the text states it")
LP_APPENDIX_B = _m829_round(
    "LP_appendix_b",
    5.029,
    0.0256,
    0.00033,
    0.24021,
    "Ch. 2 A with the 0.0256 m diameter of Appendix B's inertia scaling",
)
BASELINE = Projectile(
    "baseline",
    11.6,
    0.008,
    BASELINE_CONE,
    2157.0,
    "Ch. 4 B: 4 deg half-angle cone, 11.6 kg, base area 0.008 m^2, eq 4.8",
)

_PROJECTILES = {p.name: p for p in (HP, HP_TEXT, LP, LP_APPENDIX_B, BASELINE)}
PROJECTILE_NAMES = tuple(_PROJECTILES)


def get_projectile(name: str) -> Projectile:
    """The projectile called ``name`` (one of :data:`PROJECTILE_NAMES`).

    Parameters
    ----------
    name : str
        One of :data:`PROJECTILE_NAMES` (``"HP"``, ``"LP"``, ``"baseline"``, ...).

    Returns
    -------
    Projectile
        Its mass properties, reference area, drag law and nominal launch speed.
    """
    return _PROJECTILES[check_choice(name, "projectile", _PROJECTILES)]


def check_rigid_body(projectile, needed_by: str) -> Projectile:
    """``projectile`` if it carries what a rigid-body method (6DOF, MLT) needs: aerodynamic
    tables, a diameter and roll and pitch inertias; otherwise a named error."""
    if not isinstance(projectile, Projectile):
        raise TypeError(f"projectile must be a Projectile; got {type(projectile).__name__}")
    missing = [
        name
        for name in ("aero", "diameter_m", "roll_inertia_kg_m2", "pitch_inertia_kg_m2")
        if getattr(projectile, name) is None
    ]
    if missing:
        raise ValueError(
            f"projectile {projectile.name!r} has no {', '.join(missing)}: "
            f"{needed_by} needs aerodynamic tables, a diameter and roll and pitch "
            "inertias"
        )
    return projectile
