"""What engines learned from a gun's 3DOF flights share beyond the flights (:mod:`.flight_grid`):
the table and its store, and everything a learned path answers.

The calibrated MKS (:mod:`.calibrated_mks`) and the fly-out table (:mod:`.flyout_table`) each
learn a table from the same flights of one gun over a grid, and each gives from it a launch's
path at fractions of its flight. What follows from there is the same for both:

- :class:`LearnedTable`: values at every node of the grid's axes, a row per node interpolated
  together (:meth:`LearnedTable.at`, :func:`.flight_grid.interpolate`, after the band's check),
  and what learning them cost (3DOF flights, their right-hand sides, seconds) and weighs
  (:attr:`LearnedTable.nbytes`);
- :func:`stored_table`: a table computed once per gun, grid and version of the physics, kept in
  memory by its engine and on disk (:mod:`harp_analysis.foundation.stored`), read-only;
- :func:`gun_axes`: the gun's up, downrange and right at launch, axes that turn smoothly with
  the launch, in which both tables hold their positions, and :func:`turned`, about the
  Earth's axis;
- :class:`LearnedSolution`: the outputs of a path given at fractions of each flight (inertial
  positions and velocities at longitude 0): the time of flight, the apogee (the largest
  radius), the Earth-fixed impact point and its ranges, where the path crosses an altitude
  (:meth:`LearnedSolution.crossing`), positions at given times, and
  :meth:`LearnedSolution.trajectory`, the engines' shared trajectory table.

SI inside.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, fields
from functools import cached_property
from typing import Any, TypeVar

import numpy as np
import pandas as pd

from ..foundation import earth
from ..foundation.stored import stored_arrays
from ..foundation.validation import finite_array, whole_number
from ..models.launch import Launch, Launches
from ..models.trajectory import MAX_ROWS, describe, launch_frame, rotate_about_axis, surface_ranges
from .flight_grid import Band, Grid, GridFlights, Gun, fly_grid, interpolate

__all__ = [
    "LearnedTable",
    "stored_table",
    "joined",
    "split",
    "gun_of",
    "learned_flights",
    "gun_axes",
    "turned",
    "LearnedSolution",
]


@dataclass(frozen=True, kw_only=True)
class LearnedTable:
    """What an engine learned of one gun's 3DOF flights over a grid: ``values`` ``(*grid, m)``, a
    row at each node of the grid's axes (elevation, speed factor, bearing, density change),
    read-only; the flights it was learned from, their right-hand-side evaluations and the
    seconds learning took (measured; 0 where it was loaded from disk). Engines add their own
    fields (numbers or arrays, kept on disk with the rest by :func:`stored_table`)."""

    gun: Gun
    band: Band
    grid: Grid
    values: np.ndarray = field(repr=False)
    flights: int
    rhs_evaluations: int
    seconds: float
    loaded: bool = False  # from the disk store, not computed in this process
    axes: tuple[np.ndarray, ...] = field(init=False, repr=False)
    speed_breaks: np.ndarray = field(init=False, repr=False)  # no interpolation across one

    def __post_init__(self):
        object.__setattr__(self, "axes", tuple(np.array(a) for a in self.grid.axes(self.gun)))
        object.__setattr__(self, "speed_breaks", self.grid.speed_breaks(self.gun))
        for array in (*self.axes, self.speed_breaks, self.values):
            array.flags.writeable = False  # shared by every caller of the engine's table

    @property
    def nbytes(self) -> int:
        """The table's size (bytes): its values, what an engine keeps and reads."""
        return int(self.values.nbytes)

    def at(self, launch: Launch | Launches, engine: str) -> np.ndarray:
        """The values (n, m) at each of ``launch``'s points, interpolated; a launch outside the
        band or of another gun refused by name (:meth:`.flight_grid.Band.check`)."""
        points = self.band.check(launch, self.gun, engine)
        return interpolate(self.axes, self.values, points, self.speed_breaks)


Table = TypeVar("Table", bound=LearnedTable)
#: What the engine gives a stored table again rather than the store.
_GIVEN = ("gun", "band", "grid", "loaded")


def stored_table(
    kind: type[Table],
    module_name: str,
    gun: Gun,
    grid: Grid,
    band: Band,
    learn: Callable[[], Table],
) -> Table:
    """The table ``learn()`` computes for ``gun`` over ``grid``, kept on disk for
    ``module_name`` (:func:`harp_analysis.foundation.stored.stored_arrays`, by the gun and the
    grid): its values, cost and the fields ``kind`` adds; ``seconds`` 0 and ``loaded`` where
    it was read from disk."""
    names = [f.name for f in fields(kind) if f.init and f.name not in _GIVEN]

    def compute() -> dict[str, np.ndarray]:
        table = learn()
        return {name: np.asarray(getattr(table, name)) for name in names}

    arrays, loaded = stored_arrays(module_name, "tables", f"{gun.key} {grid!r}", compute)
    kept: dict[str, Any] = {
        name: arrays[name] if arrays[name].ndim else arrays[name].item() for name in names
    }
    if loaded:
        kept["seconds"] = 0.0
    return kind(gun=gun, band=band, grid=grid, loaded=loaded, **kept)


def joined(numbers: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """The learned rows (n, j + 3 nodes) of ``n`` flights: numbers each ((n,) or (n, j)) and
    its vectors at the time nodes (n, nodes, 3), as both engines keep them."""
    count = vectors.shape[0]
    return np.concatenate([numbers.reshape(count, -1), vectors.reshape(count, -1)], axis=1)


def split(values: np.ndarray, numbers: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """The numbers (...; or (..., j) for ``numbers`` = j > 1) and the vectors at the time nodes
    (..., nodes, 3) of rows (..., m) made by :func:`joined`."""
    vectors = values[..., numbers:].reshape(*values.shape[:-1], -1, 3)
    return (values[..., 0] if numbers == 1 else values[..., :numbers]), vectors


def gun_of(launch: Launch | Launches, grid: Grid) -> Gun:
    """The gun ``launch`` is fired from (:meth:`.flight_grid.Gun.of`), for a table over
    ``grid``; a TypeError naming the argument that is neither."""
    if not isinstance(launch, Launch | Launches):
        raise TypeError(f"launch must be a Launch or Launches; got {type(launch).__name__}")
    if not isinstance(grid, Grid):
        raise TypeError(f"grid must be a flight_grid.Grid; got {type(grid).__name__}")
    return Gun.of(launch)


def learned_flights(
    gun: Gun, grid: Grid, band: Band, flights: GridFlights | None = None
) -> GridFlights:
    """The 3DOF flights a table of ``gun`` over ``grid`` learns from: ``flights`` where they
    were flown already (another engine's table of the same grid learns from the same ones),
    else :func:`.flight_grid.fly_grid`'s. A ValueError where the grid does not span ``band``
    or ``flights`` were flown over other nodes."""
    if not grid.covers(band):
        raise ValueError(f"grid: its axes do not span the band {band}")
    if flights is None:
        return fly_grid(gun, grid)
    if not isinstance(flights, GridFlights):
        raise TypeError(f"flights must be flight_grid.GridFlights; got {type(flights).__name__}")
    axes = grid.axes(gun)
    if len(flights.axes) != len(axes) or not all(
        a.shape == b.shape and np.array_equal(a, b) for a, b in zip(flights.axes, axes)
    ):
        raise ValueError("flights: flown over other nodes than the grid's for this gun")
    return flights


def gun_axes(launch: Launch | Launches) -> np.ndarray:
    """(n, 3, 3): each launch's up, downrange and right at launch, at longitude 0 (rows)."""
    latitude = np.ravel(launch.latitude_rad)
    up, downrange, _ = launch_frame(latitude, 0.0 * latitude, np.ravel(launch.bearing_rad))
    right = np.cross(downrange.T, up.T)
    return np.stack([np.broadcast_to(up.T, right.shape), downrange.T, right], axis=1)


def turned(vectors: np.ndarray, angle_rad: np.ndarray) -> np.ndarray:
    """``vectors`` (..., 3) turned by ``angle_rad`` (...) about the Earth's axis (z)."""
    flat = rotate_about_axis(vectors.reshape(-1, 3).T, np.ravel(angle_rad))
    return flat.T.reshape(vectors.shape)


#: Illinois' method of :meth:`LearnedSolution.crossing` stops within this of the altitude (m:
#: the radius's rounding, through an inverted time, is micrometres), or once its bracket is
#: this narrow (a fraction of the flight: a picosecond of 300 s), or after this many steps.
_FALSI_M = 1e-4
_FALSI_WIDTH = 1e-15
_FALSI_ITERATIONS = 60


def _falsi(function, low, f_low, high, f_high, active) -> np.ndarray:
    """Row by row, where ``function`` (of points (n,): values (n,)) vanishes in [low, high],
    its values at the ends ``f_low`` and ``f_high`` of opposite signs (or one of them zero),
    by Illinois' method (regula falsi, the value at an end kept twice in a row halved), every
    row ``active`` at once, to :data:`_FALSI_M` of the value or :data:`_FALSI_WIDTH` of the
    bracket; an inactive row's answer is its ``low`` where ``f_low`` vanishes, else its
    ``high``."""
    low, high, f_low, f_high = (np.array(a, dtype=float) for a in (low, high, f_low, f_high))
    point = np.where(np.abs(f_low) <= _FALSI_M, low, high)
    active = active & (np.abs(f_low) > _FALSI_M) & (np.abs(f_high) > _FALSI_M)
    kept = np.zeros(low.shape, dtype=int)  # the end kept last: -1 the low one, +1 the high one
    for _ in range(_FALSI_ITERATIONS):
        if not active.any():
            break
        with np.errstate(invalid="ignore", divide="ignore"):
            trial = (low * f_high - high * f_low) / (f_high - f_low)
        inside = (trial - low) * (trial - high) < 0
        point = np.where(active, np.where(inside, trial, 0.5 * (low + high)), point)
        value = function(point)
        upper = np.sign(value) == np.sign(f_high)  # the point replaces the high end
        keeps = np.where(upper, -1, 1)
        halved = np.where(kept == keeps, 0.5, 1.0)
        low, f_low, high, f_high = (
            np.where(active, new, old)
            for new, old in (
                (np.where(upper, low, point), low),
                (np.where(upper, halved * f_low, value), f_low),
                (np.where(upper, point, high), high),
                (np.where(upper, value, halved * f_high), f_high),
            )
        )
        kept = np.where(active, keeps, kept)
        active &= (np.abs(value) > _FALSI_M) & (np.abs(high - low) > _FALSI_WIDTH)
    return point


class LearnedSolution:
    """A learned engine's flight of one launch or many
    (:class:`~harp_analysis.models.launch.Launches`): numbers for a single Launch, arrays (n,)
    for many; positions in the 3DOF's frame (inertial, the axes the Earth has at launch, the
    launch's longitude included).

    An engine's solution sets :attr:`ENGINE` (its label), ``_time_of_flight`` (n,) and gives
    ``_at_fractions()`` and ``_velocities()`` (inertial, at longitude 0) and
    ``_apogee_guess()``, where the search for the apogee starts (or its own ``_apogees``);
    ``_learned`` holds its table's values at the launches."""

    ENGINE = ""
    _time_of_flight: np.ndarray

    def __init__(self, launch: Launch | Launches, table: LearnedTable):
        self.launch = launch
        self.table = table
        self.single = isinstance(launch, Launch)
        self._learned = table.at(launch, self.ENGINE)
        self._longitude = np.radians(np.ravel(launch.longitude_deg))
        self._rotation = float(table.gun.rotation_rate_rad_s)

    def _at_fractions(self, fraction: np.ndarray) -> np.ndarray:
        """Inertial positions (n, k, 3) at fractions (n, k) of each flight, at longitude 0."""
        raise NotImplementedError

    def _velocities(self, fraction: np.ndarray) -> np.ndarray:
        """Inertial velocities (n, k, 3) at fractions (n, k) of each flight, at longitude 0."""
        raise NotImplementedError

    def _apogee_guess(self) -> np.ndarray:
        """A fraction (n,) of each flight near its apogee, where the search starts."""
        raise NotImplementedError

    def _out(self, values: np.ndarray):
        return float(values[0]) if self.single else values

    @property
    def time_of_flight_s(self):
        """Time of flight (s)."""
        return self._out(self._time_of_flight)

    def _turned(self, inertial: np.ndarray, times: np.ndarray) -> np.ndarray:
        """Positions (n, k, 3) at longitude 0 turned to the launch's longitude, less the Earth's
        turn by ``times`` (n, k) where ``times`` is given (Earth-fixed), in the Earth's axes at
        launch."""
        return turned(inertial, self._longitude[:, None] - self._rotation * times)

    @property
    def impact_point_m(self) -> np.ndarray:
        """The impact point fixed to the Earth (3,) or (n, 3), in the Earth's axes at launch."""
        ends = self._at_fractions(np.ones((self._time_of_flight.size, 1)))
        fixed = self._turned(ends, self._time_of_flight[:, None])[:, 0]
        return fixed[0] if self.single else fixed

    @property
    def impact_range_m(self):
        """(ground range, cross range) of the impact on the turning Earth (m)."""
        latitude = np.ravel(self.launch.latitude_rad)
        up, downrange, _ = launch_frame(
            latitude, self._longitude, np.ravel(self.launch.bearing_rad)
        )
        points = np.reshape(self.impact_point_m, (-1, 3))
        ground, cross = surface_ranges(points, up.T, downrange.T)
        return (self._out(np.atleast_1d(ground)), self._out(np.atleast_1d(cross)))

    @cached_property
    def _apogees(self) -> tuple[np.ndarray, np.ndarray]:
        """Apogee altitude (m) and its fraction of the flight: the largest radius on a grid of
        fractions about ``_apogee_guess()``, the grid narrowed about its best point four
        times (each a quarter of the last), then the parabola through the best three."""
        rows = np.arange(self._time_of_flight.size)
        centre = self._apogee_guess()
        low, high = np.clip(centre - 0.15, 0.0, 1.0), np.clip(centre + 0.15, 0.0, 1.0)
        for points in (61, 9, 9, 9, 9):
            grid = low[:, None] + (high - low)[:, None] * np.linspace(0.0, 1.0, points)
            radius = np.linalg.norm(self._at_fractions(grid), axis=-1)
            best = np.clip(np.argmax(radius, axis=1), 1, points - 2)
            low, high = grid[rows, best - 1], grid[rows, best + 1]
        left, middle, right = (radius[rows, best + k] for k in (-1, 0, 1))
        curvature = np.minimum(left - 2 * middle + right, -1e-300)
        shift = np.clip(0.5 * (left - right) / curvature, -1.0, 1.0)
        step = 0.5 * (high - low)
        return middle - 0.25 * (left - right) * shift - earth.RADIUS_M, grid[
            rows, best
        ] + shift * step

    @property
    def apogee_altitude_m(self):
        """Apogee altitude (m)."""
        return self._out(self._apogees[0])

    @property
    def apogee_time_s(self):
        """Time of the apogee (s)."""
        return self._out(self._apogees[1] * self._time_of_flight)

    def crossing(self, altitude_m, rising=False) -> tuple:
        """Where each flight's path crosses ``altitude_m`` (m; one for every launch or (n,))
        on its way up where ``rising`` (a bool, or (n,)), else on its way down: the time (s)
        and the point fixed to the Earth ((3,) or (n, 3), in the Earth's axes at launch, as
        :attr:`impact_point_m`). Illinois' method (regula falsi, an end kept twice in a row
        halved) on the radius, bracketed by launch and apogee or apogee and impact, to a tenth
        of a millimetre. NaN where the path at the apogee's time stays below the altitude
        (where the apogee is learned apart from the path, as the calibrated MKS's is, the
        path's top lies within metres of :attr:`apogee_altitude_m`). On the way down to the
        ground (altitude 0), or to an altitude below the impact's, it is the impact
        (:attr:`impact_point_m` at :attr:`time_of_flight_s`): the flight ends there, its
        altitude within metres of 0 (what the interpolation leaves).

        Parameters
        ----------
        altitude_m : float or numpy.ndarray
            The altitude crossed (m above the spherical Earth), >= 0.
        rising : bool or numpy.ndarray
            Crossed on the way up (before the apogee), not the way down.

        Returns
        -------
        time_s : float or numpy.ndarray
            When it crosses (s after launch).
        point_m : numpy.ndarray
            Where, fixed to the Earth (m), (3,) or (n, 3).
        """
        count = self._time_of_flight.size
        altitude = np.broadcast_to(finite_array(altitude_m, "altitude_m"), (count,))
        if np.any(altitude < 0):
            raise ValueError("altitude_m must be >= 0 (m above the spherical Earth)")
        up = np.asarray(rising)
        if up.dtype != bool:
            raise TypeError(f"rising must be True, False or an array of them; got {rising!r:.80}")
        up = np.broadcast_to(up, (count,))
        top = self._apogees[1]

        def excess(fraction: np.ndarray) -> np.ndarray:
            radius = np.linalg.norm(self._at_fractions(fraction[:, None])[:, 0], axis=-1)
            return radius - earth.RADIUS_M - altitude

        end = np.where(up, 0.0, 1.0)  # launch, or impact
        f_top, f_end = excess(top), excess(end)
        reached = f_top >= 0
        fraction = _falsi(
            excess,
            np.where(up, end, top),
            np.where(up, f_end, f_top),
            np.where(up, top, end),
            np.where(up, f_top, f_end),
            reached & (up | ((f_end < 0) & (altitude > 0))),  # else launch or impact
        )
        fraction[~reached] = np.nan
        found = np.isfinite(fraction)
        fraction = np.where(found, fraction, 1.0)
        time = fraction * self._time_of_flight
        point = self._turned(self._at_fractions(fraction[:, None]), time[:, None])[:, 0]
        time[~found], point[~found] = np.nan, np.nan
        return self._out(time), point[0] if self.single else point

    def positions(self, time_s) -> np.ndarray:
        """Inertial positions (k, 3) of a single launch at ``time_s`` (k,) within the flight, in
        the 3DOF's frame (the launch's longitude included)."""
        if not self.single:
            raise TypeError("positions: a single launch's; index the launches for one")
        times = np.atleast_1d(finite_array(time_s, "time_s"))
        tof = float(self.time_of_flight_s)
        if np.any(times < 0) or np.any(times > tof * (1 + 1e-12)):
            raise ValueError(f"time_s must lie within the flight, 0 to {tof:.6g} s")
        inertial = self._at_fractions((times / tof)[None, :])
        return self._turned(inertial, np.zeros((1, times.size)))[0]

    def trajectory(self, n_points: int, **extra) -> pd.DataFrame:
        """A single launch's flight as the engines' trajectory table
        (:mod:`harp_analysis.models.trajectory`), launch to impact at ``n_points`` equal steps
        of time, in the 3DOF's frame on the rotating Earth (as :func:`.eci.simulate_eci_mks`):
        the velocity is the path's own; Mach is the speed relative to the air, which turns
        with the Earth; the drag coefficient the projectile's at that Mach, and drag/gravity in
        the launch's day air. No right-hand side is evaluated; ``extra`` goes to
        ``frame.attrs``."""
        count = whole_number(n_points, "n_points", low=3, high=MAX_ROWS)
        launch = self.launch
        if not isinstance(launch, Launch):
            raise TypeError(
                f"launch must be a Launch; got {type(launch).__name__} (a trajectory table "
                "is one launch's; a solution of Launches gives their numbers as arrays)"
            )
        times = np.linspace(0.0, float(self.time_of_flight_s), count)
        fractions = np.linspace(0.0, 1.0, count)[None, :]
        inertial = self._at_fractions(fractions)[0]
        velocity = self._velocities(fractions)[0]
        turned = self._turned(inertial[None], np.zeros((1, count)))[0]
        fixed = self._turned(inertial[None], times[None])[0]
        radius = np.linalg.norm(inertial, axis=1)
        altitude = radius - earth.RADIUS_M
        air_velocity = velocity - self._rotation * np.stack(
            [-inertial[:, 1], inertial[:, 0], 0.0 * inertial[:, 2]], axis=1
        )
        air_speed = np.linalg.norm(air_velocity, axis=1)
        speed = np.linalg.norm(velocity, axis=1)
        density, sound = launch.air(np.maximum(altitude, 0.0))
        mach = air_speed / sound
        projectile = launch.projectile
        cd = projectile.drag_law(mach)
        drag = 0.5 * density * cd * projectile.reference_area_m2 * air_speed**2
        up, downrange, _ = launch_frame(
            launch.latitude_rad, math.radians(launch.longitude_deg), launch.bearing_rad
        )
        ground, cross = surface_ranges(fixed, np.ravel(up), np.ravel(downrange))
        momentum = np.linalg.norm(np.cross(inertial, velocity), axis=1)
        frame = pd.DataFrame(
            {
                "time_s": times,
                "x_m": turned[:, 0],
                "y_m": turned[:, 1],
                "z_m": turned[:, 2],
                "altitude_m": altitude,
                "ground_range_m": ground,
                "cross_range_m": cross,
                "speed_m_s": speed,
                "mach": mach,
                "drag_coefficient": cd,
                "drag_to_gravity": drag / (projectile.mass_kg * earth.GM_M3_S2 / radius**2),
                "specific_angular_momentum_m2_s": momentum,
                "flight_path_angle_rad": np.arcsin(
                    np.clip(np.sum(velocity * inertial, axis=1) / (speed * radius), -1.0, 1.0)
                ),
            }
        )
        apogee_altitude = float(self.apogee_altitude_m)
        apogee_time = float(self.apogee_time_s)
        apogee_ground = float(np.interp(apogee_time, times, ground))
        return describe(
            frame,
            engine=self.ENGINE,
            launch=launch,
            apogee=(apogee_time, apogee_altitude, apogee_ground),
            impact=True,
            rhs_evaluations=0,
            steps=0,
            max_time_s=math.inf,
            **extra,
        )
