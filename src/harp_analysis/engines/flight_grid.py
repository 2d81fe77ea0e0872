"""A gun's flights on a grid, and what engines learned from them share: the gun, its band, the
grid of 3DOF flights and the interpolation between them.

Chapter 7 A and C ask for firing solutions as fast as the MKS and as accurate as the numerical
flights, and name two ways: correction tables learned from 3DOF flights (the calibrated MKS,
:mod:`.calibrated_mks`) and fly-out tables of the flights themselves. Both learn from the same
flights of one gun, here:

- :class:`Gun`: what a table is learned for, a projectile at a site (latitude, site altitude,
  the air's model and temperature, the Earth's rotation); a
  :class:`~harp_analysis.models.launch.Launch` names its gun (:meth:`Gun.of`), and the
  longitude does not matter (the Earth is the same at every longitude).
- :class:`Band`: the launches a table covers, muzzle speeds 0.8-1.15 times the projectile's,
  elevations 15-88 deg, any bearing, days within +-10 % of the air's density;
  :meth:`Band.check` refuses a launch outside it, naming the field and the band (a table is
  never extrapolated).
- :class:`Grid`: the training launches, a tensor grid over elevation, speed, bearing and the
  day's density (nodes closer where the flights change fastest, at low elevations), and
  :func:`fly_grid`, the 3DOF flights over it as positions at fractions of each flight's time
  (:data:`TIME_NODES`, closer near launch and impact) and its time of flight.
- :func:`interpolate`: local tensor-product Lagrange interpolation of values on the grid (cubic
  in elevation and speed, cubic and periodic in bearing, quadratic in the density), vectorised.

SI inside; degrees only in the names that say so.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicSpline

from ..foundation.compiled import jit
from ..foundation.validation import ModelValidityWarning
from ..models.launch import Launch, Launches
from ..models.projectiles import Projectile
from ..models.trajectory import TruncatedFlightWarning
from . import threedof

__all__ = [
    "Gun",
    "Band",
    "Grid",
    "DEFAULT_GRID",
    "TIME_NODES",
    "GridFlights",
    "fly_grid",
    "interpolate",
    "warm_up",
]

_EDGE = np.geomspace(2e-3, 0.1, 8)
#: Fractions of a flight's time at which the grid's flights are kept: closer near launch, where
#: the dense air turns the flight fastest, and near impact, where it slows it.
TIME_NODES = np.unique(
    np.concatenate([[0.0], _EDGE, np.linspace(0.12, 0.88, 16), 1 - _EDGE[::-1], [1.0]])
)


@dataclass(frozen=True)
class Gun:
    """A projectile at a site: what a table is learned for. The muzzle speed of the band is the
    projectile's own (``projectile.launch_speed_m_s``)."""

    projectile: Projectile
    latitude_deg: float = 0.0
    site_altitude_m: float = 0.0
    atmosphere: str = "two_segment"
    rotation_rate_rad_s: float = 0.0
    temperature_change_k: float = 0.0

    @classmethod
    def of(cls, launch: Launch | Launches) -> Gun:
        """The gun ``launch`` is fired from (one site, one Earth rotation, one day's temperature
        for a :class:`~harp_analysis.models.launch.Launches`)."""
        if isinstance(launch, Launch):
            values = {name: getattr(launch, name) for name in _SITE_FIELDS}
        else:
            values = {name: launch.shared(name) for name in _SITE_FIELDS}
        return cls(launch.projectile, atmosphere=launch.atmosphere, **values)

    @property
    def key(self) -> str:
        """What a table of this gun is learned from, as text (the store's key)."""
        return repr(self)

    def launches(self, speed_factor, elevation_deg, bearing_deg, density_change) -> Launches:
        """Launches of this gun (arrays of one shape, flattened), from longitude 0."""
        arrays = np.broadcast_arrays(speed_factor, elevation_deg, bearing_deg, density_change)
        speed, elevation, bearing, density = (np.ravel(a) for a in arrays)
        return Launches(
            self.projectile,
            speed * self.projectile.launch_speed_m_s,
            elevation,
            bearing_deg=bearing,
            latitude_deg=self.latitude_deg,
            site_altitude_m=self.site_altitude_m,
            atmosphere=self.atmosphere,
            rotation_rate_rad_s=self.rotation_rate_rad_s,
            density_change_fraction=density,
            temperature_change_k=self.temperature_change_k,
        )

    def at_nodes(self, axes: tuple[np.ndarray, ...]) -> Launches:
        """Its launches at every node of a grid's ``axes`` (elevation, speed factor, bearing,
        density change), flattened in the axes' order."""
        elevation, speed, bearing, density = np.meshgrid(*axes, indexing="ij")
        return self.launches(speed, elevation, bearing, density)


_SITE_FIELDS = ("latitude_deg", "site_altitude_m", "rotation_rate_rad_s", "temperature_change_k")


@dataclass(frozen=True)
class Band:
    """The launches a table of a gun covers: muzzle speeds as factors of the projectile's, the
    gun's elevations (deg) and the day's density change (a fraction); every bearing."""

    speed_factors: tuple[float, float] = (0.8, 1.15)
    elevations_deg: tuple[float, float] = (15.0, 88.0)
    density_changes: tuple[float, float] = (-0.10, 0.10)

    def check(self, launch: Launch | Launches, gun: Gun, engine: str) -> np.ndarray:
        """``launch``'s coordinates in the band (n, 4): elevation (deg), speed factor, bearing
        (deg) and density change; a ValueError naming the field where it is outside the band or
        from another gun, and a warning for its wind (left out: the table's flights had none).
        """
        _check_gun(Gun.of(launch), gun, engine)
        launch.warn_ignored(
            engine, "cross_wind_m_s", "head_wind_m_s", reason="its flights had no wind"
        )
        nominal = gun.projectile.launch_speed_m_s
        speed = np.ravel(launch.speed_m_s) / nominal
        elevation = np.ravel(launch.elevation_deg)
        density = np.ravel(launch.density_change_fraction)
        for name, values, (low, high), shown in (
            ("speed_m_s", speed, self.speed_factors, lambda v: f"{v * nominal:.6g} m/s"),
            ("elevation_deg", elevation, self.elevations_deg, lambda v: f"{v:g} deg"),
            ("density_change_fraction", density, self.density_changes, lambda v: f"{v:+g}"),
        ):
            outside = np.flatnonzero((values < low - 1e-12) | (values > high + 1e-12))
            if outside.size:
                where = "" if isinstance(launch, Launch) else f"[{outside[0]}]"
                raise ValueError(
                    f"{name}{where} = {shown(values[outside[0]])} lies outside the band the "
                    f"{engine} was learned on, {shown(low)} to {shown(high)}"
                    + (
                        f" ({low:g}-{high:g} x the projectile's {nominal:g} m/s)"
                        if name == "speed_m_s"
                        else ""
                    )
                    + ": a table is never extrapolated; fly the 3DOF there"
                )
        bearing = np.ravel(launch.bearing_deg) % 360.0
        return np.stack(np.broadcast_arrays(elevation, speed, bearing, density), axis=1)


def _check_gun(theirs: Gun, gun: Gun, engine: str) -> None:
    """A ValueError naming the fields where the gun of a launch, ``theirs``, differs from the
    ``gun`` the ``engine`` was learned for."""
    if theirs == gun:
        return
    different = [
        name
        for name in ("projectile", "atmosphere", *_SITE_FIELDS)
        if getattr(theirs, name) != getattr(gun, name)
    ]
    raise ValueError(
        f"the {engine} was learned for another gun: the launch's "
        + ", ".join(f"{name} = {_shown(getattr(theirs, name))}" for name in different)
        + " differ from its "
        + ", ".join(f"{_shown(getattr(gun, name))}" for name in different)
        + " (learn a table for this gun)"
    )


def _shown(value) -> str:
    return value.name if isinstance(value, Projectile) else f"{value!r}"


@dataclass(frozen=True)
class Grid:
    """The training launches: nodes in elevation (deg), speed factor, bearing (deg, periodic,
    equally spaced from 0) and density change. A gun on a still Earth needs one bearing."""

    elevations_deg: tuple[float, ...] = (
        15.0, 16.5, 18.0, 20.0, 22.0, 24.5, 27.0, 30.0, 33.5, 37.0, 41.0, 46.0, 51.0, 57.0,
        63.0, 69.0, 75.0, 80.0, 84.0, 86.5, 88.0,
    )  # fmt: skip
    speed_factors: tuple[float, float] = (0.8, 1.15)
    speed_step: float = 0.09  # the largest step between speed nodes (a factor)
    bearings: int = 12
    density_changes: tuple[float, ...] = (-0.10, 0.0, 0.10)

    def speed_breaks(self, gun: Gun) -> np.ndarray:
        """Speed factors where the launch Mach crosses a breakpoint of the projectile's drag
        table, with the band's ends: across one, every flight's drag changes slope, and so
        does what the flights show (HP's table at Mach 5.0 is its speed factor 0.84). No
        stencil of :func:`interpolate` straddles one."""
        sound = float(np.ravel(gun.launches(1.0, 45.0, 0.0, 0.0).air(gun.site_altitude_m)[1])[0])
        low, high = self.speed_factors
        kinks = np.asarray(getattr(gun.projectile.drag_law, "mach", ()), dtype=float)
        kinks = kinks * sound / gun.projectile.launch_speed_m_s
        inside = kinks[(kinks > low + 1e-9) & (kinks < high - 1e-9)]
        return np.unique(np.concatenate([[low, high], inside]))

    def axes(self, gun: Gun) -> tuple[np.ndarray, ...]:
        """The nodes of each axis for ``gun``: speeds at most :attr:`speed_step` apart and at
        least four between breaks (:meth:`speed_breaks`), one bearing on a still Earth."""
        breaks = self.speed_breaks(gun)
        speeds = [
            np.linspace(low, high, max(4, math.ceil((high - low) / self.speed_step) + 1))
            for low, high in zip(breaks[:-1], breaks[1:])
        ]
        bearings = self.bearings if gun.rotation_rate_rad_s else 1
        return (
            np.array(self.elevations_deg),
            np.unique(np.concatenate(speeds)),
            np.arange(bearings) * 360.0 / bearings,
            np.array(self.density_changes),
        )

    def covers(self, band: Band) -> bool:
        return (
            (self.elevations_deg[0], self.elevations_deg[-1]) == band.elevations_deg
            and self.speed_factors == band.speed_factors
            and (self.density_changes[0], self.density_changes[-1]) == band.density_changes
        )


DEFAULT_GRID = Grid()
#: The output step (s) of the grid's 3DOF flights, interpolated to the time nodes by a cubic
#: spline (its error goes as the step's fourth power: a tenth of a millimetre, where linear
#: interpolation would cut 0.3 m off an apogee).
_STEP_S = 0.5


@dataclass(frozen=True)
class GridFlights:
    """The 3DOF flights of a gun over a grid: each flight's inertial positions (m, the frame
    at longitude 0 at launch) at :data:`TIME_NODES` of its time of flight, that time (s), and
    its apogee's altitude (m) and time (s); arrays shaped by the grid's axes (elevation, speed,
    bearing, density, ...)."""

    axes: tuple[np.ndarray, ...]
    positions_m: np.ndarray = field(repr=False)  # (*grid, nodes, 3)
    time_of_flight_s: np.ndarray = field(repr=False)  # (*grid,)
    apogee_altitude_m: np.ndarray = field(repr=False)  # (*grid,)
    apogee_time_s: np.ndarray = field(repr=False)  # (*grid,)
    rhs_evaluations: int
    seconds: float  # the flights' wall time, measured

    @property
    def flights(self) -> int:
        return int(self.time_of_flight_s.size)


def fly_grid(gun: Gun, grid: Grid = DEFAULT_GRID) -> GridFlights:
    """The 3DOF flights of ``gun`` over ``grid`` (:class:`GridFlights`), each flown whole by
    :func:`.threedof.simulate_3dof` (rtol 1e-9, on the gun's turning Earth and day's air); their
    wall time is measured once the kernels are compiled (one flight flown before)."""
    axes = grid.axes(gun)
    shape = tuple(a.size for a in axes)
    launches = gun.at_nodes(axes)
    positions = np.empty((len(launches), TIME_NODES.size, 3))
    times, apogees, apogee_times = np.empty((3, len(launches)))
    evaluations = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        threedof.simulate_3dof(launches[0], output_step_s=_STEP_S)  # compiled before the clock
        warnings.simplefilter("error", TruncatedFlightWarning)  # a table of landed flights
        start = time.perf_counter()
        for i, launch in enumerate(launches):
            try:
                flight = threedof.simulate_3dof(launch, output_step_s=_STEP_S)
            except TruncatedFlightWarning as cut:
                raise ValueError(
                    f"the gun's launch at {launch.speed_m_s:.6g} m/s and "
                    f"{launch.elevation_deg:g} deg does not land within the 3DOF's flight time: "
                    f"no table can be learned from it ({cut})"
                ) from None
            t = flight.time_s.to_numpy()
            xyz = flight[["x_m", "y_m", "z_m"]].to_numpy()
            positions[i] = CubicSpline(t, xyz, axis=0)(TIME_NODES * t[-1])
            times[i] = t[-1]
            apogees[i], apogee_times[i] = (
                flight.attrs["apogee_altitude_m"],
                flight.attrs["apogee_time_s"],
            )
            evaluations += flight.attrs["rhs_evaluations"]
    seconds = time.perf_counter() - start
    return GridFlights(
        axes,
        positions.reshape(*shape, TIME_NODES.size, 3),
        times.reshape(shape),
        apogees.reshape(shape),
        apogee_times.reshape(shape),
        evaluations,
        seconds,
    )


_PERIODIC = (False, False, True, False)


def _stencil(
    nodes: np.ndarray, x: np.ndarray, periodic: bool, breaks: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Indices (n, k) and Lagrange weights (n, k) of the k = min(4, nodes) nodes around each of
    ``x`` (n,): the two on each side, shifted inward at an edge, or at a break (a node of
    ``breaks``: no stencil straddles one, each segment has four nodes or more); on a periodic
    axis (equally spaced over 360) the neighbours wrap."""
    count = nodes.size
    if count == 1:
        return np.zeros((x.size, 1), dtype=int), np.ones((x.size, 1))
    k = min(4, count)
    if periodic:
        step = 360.0 / count
        first = np.floor(x / step).astype(int) - (k // 2 - 1)
        offsets = first[:, None] + np.arange(k)
        indices = offsets % count
        positions = offsets * step
    else:
        ends = np.searchsorted(nodes, nodes[[0, -1]] if breaks is None else breaks)
        segment = np.clip(np.searchsorted(nodes[ends], x, side="right") - 1, 0, ends.size - 2)
        low, high = ends[segment], ends[segment + 1] - k + 1
        first = np.clip(np.searchsorted(nodes, x, side="right") - k // 2, low, high)
        indices = first[:, None] + np.arange(k)
        positions = nodes[indices]
    weights = np.ones((x.size, k))
    for j in range(k):
        for m in range(k):
            if m != j:
                weights[:, j] *= (x - positions[:, m]) / (positions[:, j] - positions[:, m])
    return indices, weights


def interpolate(
    axes: tuple[np.ndarray, ...],
    values: np.ndarray,
    points: np.ndarray,
    speed_breaks: np.ndarray | None = None,
) -> np.ndarray:
    """``values`` ``(*grid, *shape)``, given at the nodes of ``axes`` (elevation, speed factor,
    bearing, density change), at ``points`` ``(n, 4)``: ``(n, *shape)``, by local tensor-product
    Lagrange interpolation (cubic in each axis of four or more nodes, periodic in bearing, no
    stencil across one of ``speed_breaks``). The stencils are found in numpy, the sum over
    them (a few hundred nodes of a hundred values each) runs compiled."""
    grid = tuple(a.size for a in axes)
    tail = values.shape[len(grid) :]
    flat = np.ascontiguousarray(values.reshape(math.prod(grid), -1))
    strides = np.cumprod((1,) + grid[:0:-1])[::-1]
    count = points.shape[0]
    indices = np.zeros((count, 4, 4), dtype=np.int64)
    weights = np.zeros((count, 4, 4))
    sizes = np.zeros(4, dtype=np.int64)
    for d, a in enumerate(axes):
        index, weight = _stencil(a, points[:, d], _PERIODIC[d], speed_breaks if d == 1 else None)
        sizes[d] = index.shape[1]
        indices[:, d, : sizes[d]] = index * strides[d]
        weights[:, d, : sizes[d]] = weight
    out = np.empty((count, flat.shape[1]))
    _tensor_sum(flat, indices, weights, sizes, out)
    return out.reshape(count, *tail)


@jit
def _tensor_sum(flat, offsets, weights, sizes, out):
    """out[i] = sum over the stencil's nodes of the product of the four axes' weights times
    ``flat``'s row at the sum of their offsets."""
    for i in range(out.shape[0]):
        out[i, :] = 0.0
        for a in range(sizes[0]):
            for b in range(sizes[1]):
                wab = weights[i, 0, a] * weights[i, 1, b]
                oab = offsets[i, 0, a] + offsets[i, 1, b]
                for c in range(sizes[2]):
                    wabc = wab * weights[i, 2, c]
                    oabc = oab + offsets[i, 2, c]
                    for d in range(sizes[3]):
                        w = wabc * weights[i, 3, d]
                        row = oabc + offsets[i, 3, d]
                        for m in range(flat.shape[1]):
                            out[i, m] += w * flat[row, m]


def warm_up() -> None:
    """Compile the interpolation's kernel ahead of use."""
    out = np.empty((1, 1))
    _tensor_sum(np.ones((1, 1)), np.zeros((1, 4, 4), np.int64), np.ones((1, 4, 4)),
                np.ones(4, np.int64), out)  # fmt: skip
