"""One launch, described once, flown by every engine.

A :class:`Launch` holds everything about a shot that is not a numerical option of an engine:
the projectile and its muzzle speed (relative to the ground), the gun's elevation and bearing,
the site (latitude, longitude, altitude), the wind, the spin the rifling gives, the atmosphere
with the day's change of density and temperature, and the Earth's rotation. It is validated
once, at construction, and each error names the field. The engines
(:func:`harp_analysis.threedof.simulate_3dof`,
:func:`harp_analysis.sixdof.simulate_6dof`, :func:`harp_analysis.mlt.simulate_mlt`,
:func:`harp_analysis.mks.for_launch`, :func:`harp_analysis.eci.solution_for_launch`,
:func:`harp_analysis.appendix_a.simulate_appendix_a`) take one and add only their own numerical
options, so no engine hides a scenario default: the dissertation's cases are the named
launches below.

Wind: ``cross_wind_m_s`` blows toward the right of the line of fire (positive cross range),
``head_wind_m_s`` against it, both constant with height (Chapter 2 A's "5 m/s cross wind").
The day's air: ``density_change_fraction`` scales the atmosphere's density at every height
(1 + the fraction) and ``temperature_change_k`` warms it by as much at every height (the speed of
sound of :func:`harp_analysis.atmosphere.day_air`), as an artillery met message's ballistic
density and temperature do: Chapter 7 B's "variation in atmospheric density".
An engine whose model has no wind, or no rotating Earth, or launches from sea level only, says
so: a ModelValidityWarning where the model merely leaves out an effect, a ValueError where it
cannot fly the launch at all.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

import numpy as np

from .atmosphere import ATMOSPHERE_NAMES, SOUND_SQUARED_PER_KELVIN, day_air, get_atmosphere
from .projectiles import BASELINE, HP, LP, Projectile
from .validation import ModelValidityWarning, check_choice, check_range, real_number

__all__ = [
    "Launch",
    "HP_CHAPTER_2",
    "LP_CHAPTER_2",
    "chapter_2",
    "baseline_chapter_4",
]


@dataclass(frozen=True)
class Launch:
    """A gun launch: what every engine flies (module docstring). Angles in degrees, as a gun
    is laid; everything else SI."""

    projectile: Projectile
    speed_m_s: float
    elevation_deg: float
    bearing_deg: float = 90.0
    latitude_deg: float = 0.0
    longitude_deg: float = 0.0
    site_altitude_m: float = 0.0
    cross_wind_m_s: float = 0.0
    head_wind_m_s: float = 0.0
    spin_rad_s: float = 0.0
    atmosphere: str = "two_segment"
    rotation_rate_rad_s: float = 0.0
    density_change_fraction: float = 0.0
    temperature_change_k: float = 0.0

    def __post_init__(self):
        if not isinstance(self.projectile, Projectile):
            raise TypeError(
                f"projectile must be a Projectile; got {type(self.projectile).__name__} "
                "(harp_analysis.projectiles.get_projectile turns a name into one)"
            )
        bounds = {
            "speed_m_s": dict(low=0.0, low_inclusive=False, unit="m/s"),
            "elevation_deg": dict(low=0.0, low_inclusive=False, high=90.0, unit="deg"),
            "bearing_deg": dict(low=0.0, high=360.0, high_inclusive=False, unit="deg"),
            "latitude_deg": dict(low=-90.0, high=90.0, unit="deg"),
            "longitude_deg": dict(low=-180.0, high=360.0, unit="deg"),
            "site_altitude_m": dict(low=-500.0, high=10_000.0, unit="m"),
            "cross_wind_m_s": dict(low=-100.0, high=100.0, unit="m/s"),
            "head_wind_m_s": dict(low=-100.0, high=100.0, unit="m/s"),
            "spin_rad_s": dict(),
            "rotation_rate_rad_s": dict(low=-1e-3, high=1e-3, unit="rad/s"),
            # A day's air within these keeps every model's temperature above 120 K.
            "density_change_fraction": dict(low=-0.5, high=0.5),
            "temperature_change_k": dict(low=-60.0, high=60.0, unit="K"),
        }
        for name, limits in bounds.items():
            value = check_range(real_number(getattr(self, name), name), name, **limits)
            object.__setattr__(self, name, value)
        if not isinstance(self.atmosphere, str):
            raise TypeError(f"atmosphere must be a name; got {self.atmosphere!r}")
        check_choice(self.atmosphere, "atmosphere", ATMOSPHERE_NAMES)

    # --- the quantities every engine derives the same way ---------------------------------------
    @property
    def elevation_rad(self) -> float:
        return math.radians(self.elevation_deg)

    @property
    def bearing_rad(self) -> float:
        return math.radians(self.bearing_deg)

    @property
    def latitude_rad(self) -> float:
        return math.radians(self.latitude_deg)

    @property
    def day(self) -> tuple[float, float]:
        """The day's change of the air as :func:`~harp_analysis.atmosphere.day_air` takes it:
        the density factor and gamma R dT (m^2/s^2)."""
        return (
            1.0 + self.density_change_fraction,
            SOUND_SQUARED_PER_KELVIN * self.temperature_change_k,
        )

    def air(self, altitude_m) -> tuple[np.ndarray, np.ndarray]:
        """Density (kg/m^3) and speed of sound (m/s) of the launch's air on its day."""
        model = get_atmosphere(self.atmosphere)
        return day_air(model.density(altitude_m), model.speed_of_sound(altitude_m), *self.day)

    @property
    def surface_density_kg_m3(self) -> float:
        """Air density at the gun (the launch's air at the site's altitude)."""
        return float(self.air(self.site_altitude_m)[0])

    @property
    def launch_mach(self) -> float:
        """Muzzle speed over the speed of sound at the gun."""
        return self.speed_m_s / float(self.air(self.site_altitude_m)[1])

    @property
    def launch_drag_coefficient(self) -> float:
        """Cd0 of the projectile's drag law at the launch Mach number: the one value the MKS
        (eq 3.22) and the rotating-Earth corrections (eq 5.8) take for the whole flight."""
        return float(self.projectile.drag_law(self.launch_mach))

    @property
    def has_day_air(self) -> bool:
        return self.density_change_fraction != 0.0 or self.temperature_change_k != 0.0

    @property
    def has_wind(self) -> bool:
        return self.cross_wind_m_s != 0.0 or self.head_wind_m_s != 0.0

    def require_zero(self, engine: str, *names: str, reason: str) -> None:
        """ValueError naming the first of ``names`` that is not zero: ``engine`` cannot fly it."""
        for name in names:
            if getattr(self, name) != 0.0:
                raise ValueError(
                    f"the {engine} cannot fly launch.{name} = {getattr(self, name):g}: {reason}"
                )

    def warn_ignored(self, engine: str, *names: str, reason: str) -> None:
        """A ModelValidityWarning for each of ``names`` that is not zero: ``engine`` leaves
        that effect out."""
        for name in names:
            if getattr(self, name) != 0.0:
                warnings.warn(
                    f"the {engine} ignores launch.{name} = {getattr(self, name):g}: {reason}",
                    ModelValidityWarning,
                    stacklevel=3,
                )

    def but(self, **changes) -> Launch:
        """A copy with ``changes`` (validated again), e.g. ``launch.but(elevation_deg=60)``."""
        return replace(self, **changes)


def chapter_2(projectile: Projectile, **changes) -> Launch:
    """Chapter 2 A's reference launch of ``projectile`` (Appendix B's case): its muzzle speed
    (2022 m/s for HP and LP) at 50 deg through eqs 2.1-2.2, a 5 m/s cross wind, 10 rad/s of
    spin, a non-rotating Earth."""
    return Launch(
        projectile,
        speed_m_s=projectile.launch_speed_m_s,
        elevation_deg=50.0,
        cross_wind_m_s=5.0,
        spin_rad_s=10.0,
    ).but(**changes)


#: Chapter 2 A's reference launches.
HP_CHAPTER_2 = chapter_2(HP)
LP_CHAPTER_2 = chapter_2(LP)


def baseline_chapter_4(elevation_deg: float, **changes) -> Launch:
    """Chapter 4 B's baseline cone at ``elevation_deg``: 2157 m/s, no wind, no spin, a
    non-rotating Earth, eqs 2.1-2.2 (Chapter 5 adds the rotation and the site)."""
    return Launch(BASELINE, BASELINE.launch_speed_m_s, elevation_deg).but(**changes)
