"""One launch, described once, flown by every engine.

A :class:`Launch` holds everything about a shot that is not a numerical option of an engine:
the projectile and its muzzle speed (relative to the ground), the gun's elevation and bearing,
the site (latitude, longitude, altitude), the wind, the spin the rifling gives, the atmosphere
with the day's change of density and temperature, and the Earth's rotation. It is validated
once, at construction, and each error names the field. The engines
(:func:`harp_analysis.engines.threedof.simulate_3dof`,
:func:`harp_analysis.engines.sixdof.simulate_6dof`, :func:`harp_analysis.engines.mlt.simulate_mlt`,
:func:`harp_analysis.engines.mks.for_launch`,
:func:`harp_analysis.engines.eci.correction_for_launch`,
:func:`harp_analysis.engines.eci.simulate_eci_mks`,
:func:`harp_analysis.engines.appendix_a.simulate_appendix_a`) take one and add only their own
numerical options, so no engine hides a scenario default: the dissertation's cases are the named
launches below.

Wind: ``cross_wind_m_s`` blows toward the right of the line of fire (positive cross range),
``head_wind_m_s`` against it, both constant with height (Chapter 2 A's "5 m/s cross wind").
The day's air: ``density_change_fraction`` scales the atmosphere's density at every height
(1 + the fraction) and ``temperature_change_k`` warms it by as much at every height (the speed of
sound of :func:`harp_analysis.models.atmosphere.day_air`), as an artillery met message's ballistic
density and temperature do: Chapter 7 B's "variation in atmospheric density".
An engine whose model has no wind, or no rotating Earth, or launches from sea level only, says
so: a ModelValidityWarning where the model merely leaves out an effect, a ValueError where it
cannot fly the launch at all.
"""

from __future__ import annotations

import math
import numbers
import warnings
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..foundation.validation import (
    Bounds,
    ModelValidityWarning,
    check_choice,
)
from .atmosphere import ATMOSPHERE_NAMES, SOUND_SQUARED_PER_KELVIN, day_air, get_atmosphere
from .projectiles import BASELINE, HP, LP, Projectile

__all__ = [
    "Launch",
    "Launches",
    "BOUNDS",
    "HP_CHAPTER_2",
    "LP_CHAPTER_2",
    "chapter_2",
    "baseline_chapter_4",
]


#: Every numeric field of a launch and where it must lie; the others are the projectile and
#: the atmosphere's name.
#: The upper bounds of speed and spin hold every physical launch with a wide margin (guns reach
#: ~3 km/s, escape speed is 11.2 km/s and the engines warn beyond it; rifle bullets spin at
#: ~2e4 rad/s): a value beyond is a typo or a wrong unit, which no engine should fly.
BOUNDS = {
    "speed_m_s": Bounds(low=0.0, low_inclusive=False, high=1e5, unit="m/s"),
    "elevation_deg": Bounds(low=0.0, low_inclusive=False, high=90.0, unit="deg"),
    "bearing_deg": Bounds(low=0.0, high=360.0, high_inclusive=False, unit="deg"),
    "latitude_deg": Bounds(low=-90.0, high=90.0, unit="deg"),
    "longitude_deg": Bounds(low=-180.0, high=360.0, unit="deg"),
    "site_altitude_m": Bounds(low=-500.0, high=10_000.0, unit="m"),
    "cross_wind_m_s": Bounds(low=-100.0, high=100.0, unit="m/s"),
    "head_wind_m_s": Bounds(low=-100.0, high=100.0, unit="m/s"),
    "spin_rad_s": Bounds(low=-1e5, high=1e5, unit="rad/s"),
    "rotation_rate_rad_s": Bounds(low=-1e-3, high=1e-3, unit="rad/s"),
    # A day's air within these keeps every model's temperature above 120 K.
    "density_change_fraction": Bounds(low=-0.5, high=0.5),
    "temperature_change_k": Bounds(low=-60.0, high=60.0, unit="K"),
}


def _check_projectile(projectile) -> None:
    if not isinstance(projectile, Projectile):
        raise TypeError(
            f"projectile must be a Projectile; got {type(projectile).__name__} "
            "(harp_analysis.models.projectiles.get_projectile turns a name into one)"
        )


def _check_atmosphere(atmosphere) -> None:
    if not isinstance(atmosphere, str):
        raise TypeError(f"atmosphere must be a name; got {atmosphere!r}")
    check_choice(atmosphere, "atmosphere", ATMOSPHERE_NAMES)


def _check_member(position: int, launch, first: Launch) -> None:
    """A TypeError unless ``launch``, at ``position`` of launches flown together, is a
    :class:`Launch`; a ValueError unless it shares the projectile and atmosphere of the
    ``first``."""
    if not isinstance(launch, Launch):
        raise TypeError(f"launches[{position}] must be a Launch; got {type(launch).__name__}")
    for name in ("projectile", "atmosphere"):
        if getattr(launch, name) != getattr(first, name):
            raise ValueError(
                f"launches[{position}].{name} differs from launches[0]'s: launches "
                "flown together share one projectile and atmosphere"
            )


class _LaunchAir:
    """The air of a launch's day, the same for one launch (numbers) and many (arrays)."""

    atmosphere: str
    density_change_fraction: Any
    temperature_change_k: Any

    @property
    def day(self) -> tuple:
        """The day's change of the air as :func:`~harp_analysis.models.atmosphere.day_air` takes it:
        the density factor and gamma R dT (m^2/s^2)."""
        return (
            1.0 + self.density_change_fraction,
            SOUND_SQUARED_PER_KELVIN * self.temperature_change_k,
        )

    def air(self, altitude_m) -> tuple[np.ndarray, np.ndarray]:
        """Density (kg/m^3) and speed of sound (m/s) of the launch's air on its day."""
        model = get_atmosphere(self.atmosphere)
        return day_air(model.density(altitude_m), model.speed_of_sound(altitude_m), *self.day)


@dataclass(frozen=True)
class Launch(_LaunchAir):
    """A gun launch: what every engine flies (module docstring). Angles in degrees, as a gun
    is laid; everything else SI. Each field is validated here (:data:`BOUNDS`), and an error
    names it.

    Parameters
    ----------
    projectile : Projectile
        What the gun fires (:data:`~harp_analysis.models.projectiles.HP`, ``LP``,
        ``BASELINE``, or :func:`~harp_analysis.models.projectiles.get_projectile` of a name).
    speed_m_s : float
        Muzzle speed relative to the ground (m/s).
    elevation_deg : float
        The gun's elevation above the horizontal, in (0, 90] deg.
    bearing_deg : float
        The line of fire, from true north (90 is east).
    latitude_deg, longitude_deg : float
        The gun's site (deg north, deg east).
    site_altitude_m : float
        The site's height above sea level (m).
    cross_wind_m_s, head_wind_m_s : float
        The wind toward the right of the line of fire and against it (m/s), constant with
        height.
    spin_rad_s : float
        The spin the rifling gives (rad/s; the rigid-body engines fly it).
    atmosphere : str
        The air's model, one of :data:`~harp_analysis.models.atmosphere.ATMOSPHERE_NAMES`
        (eqs 2.1-2.2's ``"two_segment"`` by default).
    rotation_rate_rad_s : float
        The Earth's rotation rate (rad/s): 0 for the non-rotating Earth of Chapters 2-4,
        :data:`harp_analysis.foundation.earth.ROTATION_RATE_RAD_S` for Chapter 5's.
    density_change_fraction, temperature_change_k : float
        The day's air: the density scaled by 1 + the fraction and the air warmed by as many
        kelvin, at every height.
    """

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
        _check_projectile(self.projectile)
        for name, bounds in BOUNDS.items():
            object.__setattr__(self, name, bounds.number(getattr(self, name), name))
        _check_atmosphere(self.atmosphere)

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
        """A copy with ``changes`` (validated again), e.g. ``launch.but(elevation_deg=60)``.

        Parameters
        ----------
        **changes
            New values of fields, by name (the class's Parameters).

        Returns
        -------
        Launch
            The changed copy; this launch is left as it is.
        """
        return replace(self, **changes)


class Launches(_LaunchAir):
    """Many launches of one projectile through one atmosphere, as arrays: the batch the engines
    fly at once (:func:`harp_analysis.engines.mks.for_launch`,
    :func:`harp_analysis.engines.eci.correction_for_launch`,
    :func:`harp_analysis.engines.threedof.fly_3dof`,
    :func:`harp_analysis.engines.threedof.simulate_3dof_batch`,
    :func:`harp_analysis.engines.mks_improved.solve`).

    The fields are :class:`Launch`'s, each a number (shared by every launch) or a 1-D array, all
    broadcast to one length n; they are validated once, here, and each error names the field and
    the index of its first bad value. The fields are read-only arrays (n,). Indexing gives a
    :class:`Launch` (an integer) or a :class:`Launches` (a slice, a mask or indices); iterating
    gives every :class:`Launch`; :meth:`from_launches` turns a sequence of them into one.
    Quantities derived from a field that every launch shares are computed once.

    Parameters
    ----------
    projectile : Projectile
        What every launch fires.
    speed_m_s, elevation_deg, bearing_deg : float or array_like
        The shot, as :class:`Launch`'s: a number for every launch or an array of one per
        launch, as is each field below but the atmosphere.
    latitude_deg, longitude_deg, site_altitude_m : float or array_like
        The site.
    cross_wind_m_s, head_wind_m_s, spin_rad_s : float or array_like
        The wind and the spin.
    atmosphere : str
        The air every launch flies through.
    rotation_rate_rad_s, density_change_fraction, temperature_change_k : float or array_like
        The Earth's rotation and the day's air.
    """

    def __init__(
        self,
        projectile: Projectile,
        speed_m_s,
        elevation_deg,
        bearing_deg=90.0,
        latitude_deg=0.0,
        longitude_deg=0.0,
        site_altitude_m=0.0,
        cross_wind_m_s=0.0,
        head_wind_m_s=0.0,
        spin_rad_s=0.0,
        atmosphere: str = "two_segment",
        rotation_rate_rad_s=0.0,
        density_change_fraction=0.0,
        temperature_change_k=0.0,
    ):
        _check_projectile(projectile)
        _check_atmosphere(atmosphere)
        given = locals()  # the numeric fields by name (and the others)
        fields = {name: bounds.array(given[name], name) for name, bounds in BOUNDS.items()}
        shapes = {name: array.shape for name, array in fields.items()}
        try:
            shape = np.broadcast_shapes(*shapes.values())
        except ValueError:
            arrays = ", ".join(f"{name} {shape}" for name, shape in shapes.items() if shape)
            raise ValueError(
                f"the fields of Launches must share one length; got {arrays}"
            ) from None
        if len(shape) > 1:
            raise ValueError(f"the fields of Launches must be numbers or 1-D arrays; got {shapes}")
        if shape == (0,):
            raise ValueError("Launches must hold at least one launch")
        self._store(projectile, atmosphere, fields, shape[0] if shape else 1)

    def _store(self, projectile: Projectile, atmosphere: str, fields: dict, count: int) -> None:
        """Keep valid ``fields`` (numbers or arrays (count,), owned by no one else)."""
        self.projectile, self.atmosphere = projectile, atmosphere
        self._shared: dict[str, float] = {}
        for name, array in fields.items():
            if array.ndim == 0 or array.size == 1 or not np.any(array != array.flat[0]):
                self._shared[name] = float(array.flat[0])
            setattr(self, name, np.broadcast_to(array, (count,)))  # a read-only view

    @classmethod
    def _of_valid(cls, projectile: Projectile, atmosphere: str, fields: dict) -> Launches:
        """Launches of fields known valid (arrays of launches already checked), unchecked."""
        launches = cls.__new__(cls)
        launches._store(projectile, atmosphere, fields, len(next(iter(fields.values()))))
        return launches

    # the fields, for type checkers (set in __init__)
    speed_m_s: np.ndarray
    elevation_deg: np.ndarray
    bearing_deg: np.ndarray
    latitude_deg: np.ndarray
    longitude_deg: np.ndarray
    site_altitude_m: np.ndarray
    cross_wind_m_s: np.ndarray
    head_wind_m_s: np.ndarray
    spin_rad_s: np.ndarray
    rotation_rate_rad_s: np.ndarray
    density_change_fraction: np.ndarray
    temperature_change_k: np.ndarray

    @classmethod
    def from_launches(cls, launches) -> Launches:
        """The launches of a sequence of :class:`Launch` sharing one projectile and atmosphere
        (a :class:`Launch` or a :class:`Launches` is taken as it is)."""
        if isinstance(launches, Launches):
            return launches
        if isinstance(launches, Launch):
            launches = [launches]
        if isinstance(launches, str | bytes) or not isinstance(launches, Iterable):
            raise TypeError(
                "launches must be a Launch, a Launches or a sequence of Launch; "
                f"got {type(launches).__name__}"
            )
        launches = list(launches)
        if not launches:
            raise ValueError("launches must hold at least one Launch")
        first = launches[0]
        for position, launch in enumerate(launches):
            _check_member(position, launch, first)
        columns = np.array([[getattr(one, name) for name in BOUNDS] for one in launches]).T
        return cls._of_valid(first.projectile, first.atmosphere, dict(zip(BOUNDS, columns)))

    def __len__(self) -> int:
        return self.speed_m_s.size

    def __repr__(self) -> str:
        return f"Launches({len(self)} of {self.projectile.name}, {self.atmosphere!r})"

    def _fields(self, index=slice(None)) -> dict:
        return {name: getattr(self, name)[index] for name in BOUNDS}

    def __getitem__(self, index):
        if isinstance(index, numbers.Integral) and not isinstance(index, bool):
            if not -len(self) <= index < len(self):
                raise IndexError(f"launch {index} of {len(self)}")
            one = {name: float(value) for name, value in self._fields(index).items()}
            return Launch(self.projectile, atmosphere=self.atmosphere, **one)
        fields = {name: np.array(values, ndmin=1) for name, values in self._fields(index).items()}
        if not len(fields["speed_m_s"]):
            raise IndexError(f"no launch of {len(self)} at {index!r}")
        return Launches._of_valid(self.projectile, self.atmosphere, fields)

    def __iter__(self) -> Iterator[Launch]:
        return (self[i] for i in range(len(self)))

    def but(self, **changes) -> Launches:
        """A copy with ``changes`` (validated again), e.g. ``launches.but(elevation_deg=60)``.

        Parameters
        ----------
        **changes
            New values of fields, by name (the class's Parameters): a number for every launch
            or an array of one per launch.

        Returns
        -------
        Launches
            The changed copy; these launches are left as they are.
        """
        fields = dict(self._fields(), projectile=self.projectile, atmosphere=self.atmosphere)
        unknown = set(changes) - set(fields)
        if unknown:
            raise TypeError(f"Launches has no field {sorted(unknown)[0]!r}")
        return Launches(**{**fields, **changes})

    def shared(self, name: str, *, reason: str = "") -> float:
        """The value of field ``name`` that every launch shares; a ValueError naming the first
        launch that differs (and ``reason``) if they do not."""
        if name not in self._shared:
            values = getattr(self, name)
            index = int(np.flatnonzero(values != values[0])[0])
            raise ValueError(
                f"launches[{index}].{name} = {values[index]:g} differs from launches[0]'s "
                f"{values[0]:g}: {reason or f'these launches must share one {name}'}"
            )
        return self._shared[name]

    def compact(self, name: str) -> np.ndarray:
        """Field ``name`` as (1,) if every launch shares it, else (n,): what a computation that
        broadcasts needs, so shared quantities are computed once."""
        if name in self._shared:
            return np.array([self._shared[name]])
        return getattr(self, name)

    @property
    def day(self) -> tuple:
        """:attr:`Launch.day` of each launch, computed once where they share it."""
        return (
            1.0 + self.compact("density_change_fraction"),
            SOUND_SQUARED_PER_KELVIN * self.compact("temperature_change_k"),
        )

    def _each(self, values) -> np.ndarray:
        return np.broadcast_to(values, (len(self),))

    @property
    def elevation_rad(self) -> np.ndarray:
        return self._each(np.radians(self.compact("elevation_deg")))

    @property
    def bearing_rad(self) -> np.ndarray:
        return self._each(np.radians(self.compact("bearing_deg")))

    @property
    def latitude_rad(self) -> np.ndarray:
        return self._each(np.radians(self.compact("latitude_deg")))

    @property
    def surface_density_kg_m3(self) -> np.ndarray:
        """:attr:`Launch.surface_density_kg_m3` of each launch."""
        return self._each(self.air(self.compact("site_altitude_m"))[0])

    @property
    def launch_mach(self) -> np.ndarray:
        """:attr:`Launch.launch_mach` of each launch."""
        sound = self.air(self.compact("site_altitude_m"))[1]
        return self._each(self.compact("speed_m_s") / sound)

    @property
    def launch_drag_coefficient(self) -> np.ndarray:
        """:attr:`Launch.launch_drag_coefficient` of each launch."""
        sound = self.air(self.compact("site_altitude_m"))[1]
        return self._each(self.projectile.drag_law(self.compact("speed_m_s") / sound))

    def require_zero(self, engine: str, *names: str, reason: str) -> None:
        """:meth:`Launch.require_zero` for every launch, naming the first that is not zero."""
        for name in names:
            if self._shared.get(name) != 0.0:
                index = int(np.flatnonzero(getattr(self, name))[0])
                raise ValueError(
                    f"the {engine} cannot fly launches.{name}[{index}] = "
                    f"{getattr(self, name)[index]:g}: {reason}"
                )

    def warn_ignored(self, engine: str, *names: str, reason: str) -> None:
        """:meth:`Launch.warn_ignored` once for every field ``names`` not zero somewhere."""
        for name in names:
            if self._shared.get(name) != 0.0:
                values = getattr(self, name)
                nonzero = np.flatnonzero(values)
                warnings.warn(
                    f"the {engine} ignores launches.{name} in {nonzero.size} of {values.size} "
                    f"launches (first [{nonzero[0]}] = {values[nonzero[0]]:g}): {reason}",
                    ModelValidityWarning,
                    stacklevel=3,
                )


def chapter_2(projectile: Projectile, **changes) -> Launch:
    """Chapter 2 A's reference launch of ``projectile`` (Appendix B's case): its muzzle speed
    (2022 m/s for HP and LP) at 50 deg through eqs 2.1-2.2, a 5 m/s cross wind, 10 rad/s of
    spin, a non-rotating Earth.

    Parameters
    ----------
    projectile : Projectile
        HP or LP (or any projectile, at its own muzzle speed).
    **changes
        Fields of :class:`Launch` to change (as :meth:`Launch.but`).

    Returns
    -------
    Launch
        The launch, validated.
    """
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
    non-rotating Earth, eqs 2.1-2.2 (Chapter 5 adds the rotation and the site).

    Parameters
    ----------
    elevation_deg : float
        The gun's elevation (deg).
    **changes
        Fields of :class:`Launch` to change (as :meth:`Launch.but`).

    Returns
    -------
    Launch
        The launch, validated.
    """
    return Launch(BASELINE, BASELINE.launch_speed_m_s, elevation_deg).but(**changes)
