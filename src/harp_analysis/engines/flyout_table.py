"""The fly-out table: a gun's 3DOF flights over a grid, interpolated directly, Chapter 7 A's
alternative to the MKS ("The use of fly-out tables or look-up tables of potential positions of
the projectile and missile based upon numerical simulations is also a possible method").

The text expects such tables to grow "to an unreasonable size" as their cells shrink;
:mod:`harp_analysis.analyses.flyout_comparison` measures how large they grow against the
calibrated MKS (:mod:`.calibrated_mks`), learned from the very same flights. Both are tables of
one gun (:mod:`.flight_grid`: elevations 15-88 deg, muzzle speeds 0.8-1.15 of the
projectile's, every bearing, the day's density within +-10 %, a launch outside refused by
name); where the calibrated MKS keeps what the MKS misses, this table keeps the flights
themselves:

- at each node of the grid, the 3DOF's time of flight and its positions at
  :data:`.flight_grid.TIME_NODES` of it, fixed to the Earth (the path seen from the gun, on the
  turning Earth) and along the gun's up, downrange and right at launch, less the launch point.
  The inertial path would not do: the Earth's turn carries it east, 450 m/s at Barbados, a
  drift of about a hundred kilometres that swings round with the bearing, and a cubic across
  twelve bearings misses its sine by about 0.2 %, some 130 m at the impact of a 45 deg shot
  of HP (5 m fixed to the Earth, where only the Coriolis and centrifugal pushes vary with
  the bearing);
- between the grid's nodes, local cubic interpolation in each input, periodic in bearing
  (:func:`.flight_grid.interpolate`), as the calibrated MKS interpolates its own table;
- between the time nodes, the not-a-knot cubic spline through the 34 positions, in the fraction
  of the flight: the path is curved, and a straight line between nodes 9 s apart cuts an
  apogee of HP by 50-300 m; the spline keeps to the 3DOF's path within 7 m anywhere (the last
  tenth of the flight, where the air brakes it hardest) and to its apogee within 2 cm.
  Positions and velocities at the nodes (cubic Hermite) would halve the path's error for twice
  the table. The velocity is the spline's derivative with the Earth's turn added.

A table is computed once per gun and version of the physics, kept in memory and on disk
(:func:`table_for`, :func:`.learned.stored_table`); its cost is reported
(:attr:`FlyoutTable.seconds`, :attr:`.learned.LearnedTable.nbytes`).

SI inside; degrees only in the names that say so.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import pandas as pd
from scipy.interpolate import CubicSpline

from ..foundation import earth
from ..models.launch import Launch, Launches
from .flight_grid import DEFAULT_GRID, TIME_NODES, Band, Grid, GridFlights, Gun
from .learned import (
    LearnedSolution,
    LearnedTable,
    gun_axes,
    gun_of,
    joined,
    learned_flights,
    split,
    stored_table,
    turned,
)

__all__ = [
    "FlyoutTable",
    "FlyoutSolution",
    "BAND",
    "tabulate",
    "table_for",
    "simulate_flyout_table",
    "ENGINE",
]

ENGINE = "fly-out table"
#: The launches a table covers (:class:`.flight_grid.Band`).
BAND = Band()
_NODES = TIME_NODES.size
#: The not-a-knot cubic spline through the time nodes as weights on them: the spline of each
#: flight's positions is these weights times its positions (it is linear in them).
_SPLINE = CubicSpline(TIME_NODES, np.eye(_NODES), axis=0)


@dataclass(frozen=True, kw_only=True)
class FlyoutTable(LearnedTable):
    """The 3DOF flights of one gun over a grid as a table: at each node of the grid's axes
    (elevation, speed factor, bearing, density change), the time of flight (s) and the
    positions (m) at :data:`.flight_grid.TIME_NODES` of it, fixed to the Earth, along the gun's
    up, downrange and right at launch, less the launch point (``values``, one row per node,
    :func:`.learned.joined`: the time, then the positions)."""


def tabulate(
    gun: Gun, grid: Grid = DEFAULT_GRID, band: Band = BAND, flights: GridFlights | None = None
) -> FlyoutTable:
    """The fly-out table of ``gun`` over ``grid``: its 3DOF flights
    (:func:`.flight_grid.fly_grid`, or ``flights`` where they were flown already) fixed to the
    Earth and along the gun's axes. Its ``seconds``: the flights' and its own. No caching (see
    :func:`table_for`)."""
    flights = learned_flights(gun, grid, band, flights)
    start = time.perf_counter()
    shape = flights.time_of_flight_s.shape
    launches = gun.at_nodes(flights.axes)
    tof = flights.time_of_flight_s.ravel()
    inertial = flights.positions_m.reshape(-1, _NODES, 3)
    fixed = turned(inertial, -gun.rotation_rate_rad_s * TIME_NODES * tof[:, None])
    local = np.einsum("nkj,naj->nka", fixed, gun_axes(launches))
    local[..., 0] -= earth.RADIUS_M
    return FlyoutTable(
        gun=gun,
        band=band,
        grid=grid,
        values=joined(tof, local).reshape(*shape, -1),
        flights=flights.flights,
        rhs_evaluations=flights.rhs_evaluations,
        seconds=flights.seconds + time.perf_counter() - start,
    )


@lru_cache(maxsize=16)
def _table(gun: Gun, grid: Grid) -> FlyoutTable:
    return stored_table(FlyoutTable, __name__, gun, grid, BAND, lambda: tabulate(gun, grid))


def table_for(launch: Launch | Launches, grid: Grid = DEFAULT_GRID) -> FlyoutTable:
    """The fly-out table of ``launch``'s gun (:meth:`.flight_grid.Gun.of`) over ``grid``: its
    3DOF flights flown the first time (a few seconds, :attr:`FlyoutTable.seconds`), then kept
    in memory and on disk for every later call and process (read-only arrays).

    Parameters
    ----------
    launch : Launch or Launches
        A launch of the gun (its projectile, site, air model and Earth rotation).
    grid : Grid
        The launches flown (:class:`.flight_grid.Grid`): the table's resolution.

    Returns
    -------
    FlyoutTable
        The gun's flights as a table, and what flying them cost.
    """
    return _table(gun_of(launch, grid), grid)


class FlyoutSolution(LearnedSolution):
    """The fly-out table's flight of one launch or many
    (:class:`~harp_analysis.models.launch.Launches`): the time of flight and the positions at
    the time nodes interpolated at each launch, the spline in time between them
    (:class:`.learned.LearnedSolution`: numbers for a single Launch, arrays (n,) for many;
    positions in the 3DOF's frame).

    Parameters
    ----------
    launch : Launch or Launches
        Launches of one gun (projectile, site, air model and Earth rotation), within the band
        the table covers (:data:`BAND`).
    table : FlyoutTable, optional
        The flights to interpolate; by default the gun's (:func:`table_for`, flown on first
        use).
    """

    ENGINE = ENGINE

    def __init__(self, launch: Launch | Launches, table: FlyoutTable | None = None):
        super().__init__(launch, table_for(launch) if table is None else table)
        self._time_of_flight, self._local = split(self._learned)
        self._axes = gun_axes(launch)

    def _fixed(self, fraction: np.ndarray, derivative: int = 0) -> np.ndarray:
        """Earth-fixed positions (n, k, 3) at fractions (n, k) of each flight, at longitude 0,
        or (``derivative`` 1) their rate per fraction of the flight."""
        local = np.einsum("nks,nsa->nka", _SPLINE(fraction, derivative), self._local)
        if not derivative:
            local[..., 0] += earth.RADIUS_M
        return np.einsum("nka,naj->nkj", local, self._axes)

    def _at_fractions(self, fraction: np.ndarray) -> np.ndarray:
        return turned(
            self._fixed(fraction), self._rotation * fraction * self._time_of_flight[:, None]
        )

    def _velocities(self, fraction: np.ndarray) -> np.ndarray:
        """The Earth-fixed path's rate, with the Earth's turn omega x r added, turned."""
        fixed = self._fixed(fraction)
        rate = self._fixed(fraction, 1) / self._time_of_flight[:, None, None]
        spin = self._rotation * np.stack([-fixed[..., 1], fixed[..., 0], 0.0 * fixed[..., 2]], -1)
        return turned(rate + spin, self._rotation * fraction * self._time_of_flight[:, None])

    def _apogee_guess(self) -> np.ndarray:
        """The time node of the largest radius."""
        radius = np.linalg.norm(self._local + [earth.RADIUS_M, 0.0, 0.0], axis=-1)
        return TIME_NODES[np.argmax(radius, axis=1)]


def simulate_flyout_table(
    launch: Launch,
    *,
    grid: Grid = DEFAULT_GRID,
    table: FlyoutTable | None = None,
    n_points: int = 400,
) -> pd.DataFrame:
    """The fly-out table's flight of ``launch`` as the engines' trajectory table
    (:meth:`.learned.LearnedSolution.trajectory`), launch to impact at ``n_points`` equal steps
    of time, in the 3DOF's frame on the rotating Earth. The velocity is the spline's
    derivative with the Earth's turn. No right-hand side is evaluated.

    Parameters
    ----------
    launch : Launch
        A launch of a gun within the band of :data:`BAND`.
    grid : Grid
        The launches the gun's table was flown over (its resolution: the engine's tolerance
        option), when ``table`` is not given.
    table : FlyoutTable, optional
        The flights to interpolate; by default the gun's over ``grid`` (:func:`table_for`).
    n_points : int
        Rows, at equal steps of time from launch to impact.

    Returns
    -------
    pandas.DataFrame
        The trajectory table, one row per output time in SI units, with the shared metadata in
        ``frame.attrs`` (and ``table_flights``, the 3DOF flights of the table).
    """
    solution = FlyoutSolution(launch, table or table_for(launch, grid))
    return solution.trajectory(n_points, table_flights=solution.table.flights)
