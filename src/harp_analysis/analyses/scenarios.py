"""The reference flights of Chapter 2 and the quantities the text states about them.

Chapter 2 A: HP and LP launched at 50 deg and 2022 m/s through the two-segment atmosphere of
eqs 2.1-2.2 with a 5 m/s cross wind, simulated in 3DOF, 6DOF and Modified Linear Theory (MLT);
Table 4.1 adds the baseline cone. Flights are cached, so the notebook and the claims ledger
share one run of each.
Functions take projectile names (see :data:`harp_analysis.models.projectiles.PROJECTILE_NAMES`) so
the ledger can call them with plain arguments.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..engines.mlt import simulate_mlt
from ..engines.sixdof import simulate_6dof
from ..engines.threedof import simulate_3dof
from ..foundation import earth
from ..foundation.caching import cached_copies
from ..foundation.validation import Bounds, check_choice, real_number
from ..models.launch import Launch, chapter_2
from ..models.projectiles import get_projectile

__all__ = [
    "reference_launch",
    "fly_3dof",
    "fly_6dof",
    "fly_mlt",
    "reference_3dof",
    "reference_6dof",
    "reference_mlt",
    "RIGID_BODY_METHODS",
    "rigid_body_flight",
    "max_distance_m",
    "max_position_difference_km",
    "swerve",
    "yaw_drag_peak",
    "angle_of_attack_at_apogee_deg",
    "launch_drag_to_gravity",
    "drag_to_gravity_crossing_altitude_km",
    "drag_to_gravity_crossings",
    "angular_momentum_loss_share_below",
    "angular_momentum_change_above",
    "launch_energy_mj",
    "ascent",
    "ascent_below",
    "straight_line_altitude_m",
    "height_over_straight_line_m",
    "loss_share_below",
]

_FINE_STEP_S = 0.01


def reference_launch(projectile: str) -> Launch:
    """Chapter 2 A's launch of ``projectile`` (:func:`harp_analysis.models.launch.chapter_2`)."""
    return chapter_2(get_projectile(projectile))


@cached_copies
def fly_3dof(launch: Launch, output_step_s: float = _FINE_STEP_S) -> pd.DataFrame:
    """The 3DOF flight of ``launch`` at ``output_step_s``, computed once per launch."""
    return simulate_3dof(launch, output_step_s=output_step_s)


@cached_copies
def fly_6dof(launch: Launch, density_altitude: str = "flat") -> pd.DataFrame:
    """The 6DOF flight of ``launch`` (Appendix B's port; air density at the flat-frame
    altitude unless ``density_altitude="spherical"``), computed once per launch."""
    return simulate_6dof(launch, density_altitude=density_altitude)


@cached_copies
def fly_mlt(
    launch: Launch,
    density_altitude: str = "flat",
    segment_length_m: float = 1000.0,
    coefficients_at: str = "middle",
) -> pd.DataFrame:
    """The MLT flight of ``launch`` (:mod:`.mlt`), computed once per launch and options."""
    return simulate_mlt(
        launch,
        density_altitude=density_altitude,
        segment_length_m=segment_length_m,
        coefficients_at=coefficients_at,
    )


def reference_3dof(
    projectile: str, cross_wind_m_s: float = 5.0, output_step_s: float = _FINE_STEP_S
) -> pd.DataFrame:
    """The 3DOF flight of ``projectile`` in Chapter 2 A's conditions (Fig 4.8 and Table 4.1
    fly the same launch "with no wind": ``cross_wind_m_s=0``)."""
    launch = reference_launch(projectile).but(cross_wind_m_s=cross_wind_m_s)
    return fly_3dof(launch, output_step_s)


def launch_energy_mj(projectile: str) -> float:
    """Kinetic energy at the nominal launch speed (MJ), Chapters 2 A and 4 B."""
    return get_projectile(projectile).launch_energy_j / 1e6


def launch_drag_to_gravity(
    projectile: str, atmosphere: str = "two_segment", gravity_m_s2: float | None = None
) -> float:
    """Drag over weight at the muzzle (Table 4.1): 1/2 rho0 V0^2 Cd(Ma0) A / (m g).

    ``gravity_m_s2`` defaults to the simulations' GM/R^2 (9.7987 m/s^2).
    """
    launch = reference_launch(projectile).but(atmosphere=atmosphere)
    p = launch.projectile
    g = (
        earth.surface_gravity_m_s2()
        if gravity_m_s2 is None
        else _positive(gravity_m_s2, "gravity_m_s2")
    )
    drag = (
        0.5
        * launch.surface_density_kg_m3
        * launch.speed_m_s**2
        * launch.launch_drag_coefficient
        * p.reference_area_m2
    )
    return float(drag / (p.mass_kg * g))


def _positive(value, name: str) -> float:
    return Bounds(low=0.0, low_inclusive=False).check(real_number(value, name), name)


def _altitude_km(altitude_km, flight: pd.DataFrame) -> float:
    """``altitude_km`` from the ground to below ``flight``'s apogee (the interval's top), or an
    error naming it."""
    apogee_km = flight.attrs["apogee_altitude_m"] / 1e3
    return Bounds(low=0.0, high=apogee_km, high_inclusive=False, unit="km").check(
        real_number(altitude_km, "altitude_km"), "altitude_km"
    )


def ascent(flight: pd.DataFrame) -> pd.DataFrame:
    """The rows of ``flight`` up to its apogee."""
    return flight[flight.time_s <= flight.attrs["apogee_time_s"]]


def ascent_below(flight: pd.DataFrame, altitude_m: float) -> pd.DataFrame:
    """The rows of ``flight``'s ascent below ``altitude_m``: the lower atmosphere of Figs 2.9,
    3.3, 4.14 and 4.16."""
    rising = ascent(flight)
    return rising[rising.altitude_m < altitude_m]


def straight_line_altitude_m(ground_range_m, elevation_rad: float):
    """Altitude (m) of the straight launch line at ``ground_range_m``: eq 3.16's
    a = theta r0 tan(phi0), with the angular range theta = ground range / r0."""
    return ground_range_m * np.tan(elevation_rad)


def height_over_straight_line_m(flight: pd.DataFrame) -> pd.Series:
    """``flight``'s altitude minus its straight launch line's (:func:`straight_line_altitude_m`
    at its launch elevation) at the same range (m; negative below the line): Fig 2.9's lower
    panel."""
    elevation_rad = flight.attrs["launch"].elevation_rad
    return flight.altitude_m - straight_line_altitude_m(flight.ground_range_m, elevation_rad)


def loss_share_below(flight: pd.DataFrame, altitude_km: float = 20.0) -> float:
    """Share of ``flight``'s ascent loss of specific angular momentum spent below
    ``altitude_km``."""
    rising = ascent(flight)
    altitude_km = _altitude_km(altitude_km, flight)
    momentum = rising.specific_angular_momentum_m2_s.to_numpy()
    at = np.interp(altitude_km * 1e3, rising.altitude_m, momentum)
    return float((momentum[0] - at) / (momentum[0] - momentum[-1]))


def drag_to_gravity_crossing_altitude_km(projectile: str, ratio: float = 1.0) -> float:
    """Altitude (km) where N = drag/gravity falls through ``ratio`` on the way up (Table 4.1's
    "altitude where drag = weight" is ``ratio = 1``)."""
    ratio = _positive(ratio, "ratio")
    rising = ascent(reference_3dof(projectile, cross_wind_m_s=0.0))
    i = _first_below(rising, ratio)
    if i == 0:
        return float("nan")
    n, a = rising.drag_to_gravity.to_numpy(), rising.altitude_m.to_numpy()
    return float(np.interp(np.log(ratio), np.log(n[[i, i - 1]]), a[[i, i - 1]]) / 1e3)


def _first_below(rising: pd.DataFrame, ratio: float) -> int:
    """Position of the first row of the ascent ``rising`` where N = drag/gravity is below
    ``ratio``; 0 if it never is, or already is at the muzzle (no crossing)."""
    below = np.flatnonzero(rising.drag_to_gravity.to_numpy() < ratio)
    return int(below[0]) if below.size else 0


def drag_to_gravity_crossings(flight: pd.DataFrame, ratios) -> pd.DataFrame:
    """The first row of ``flight``'s ascent where N = drag/gravity has fallen below each of
    ``ratios`` (Fig 2.2's marks), indexed by the ratio; a ratio N does not cross on the way up
    is left out."""
    rising = ascent(flight)
    rows = {ratio: _first_below(rising, _positive(ratio, "ratio")) for ratio in ratios}
    crossed = {ratio: i for ratio, i in rows.items() if i}
    return rising.iloc[list(crossed.values())].set_axis(pd.Index(list(crossed), name="ratio"))


def angular_momentum_loss_share_below(projectile: str, altitude_km: float = 20.0) -> float:
    """Share of the ascent's loss of specific angular momentum spent below ``altitude_km``."""
    return loss_share_below(reference_3dof(projectile), altitude_km)


def angular_momentum_change_above(projectile: str, altitude_km: float = 40.0) -> float:
    """Relative change of specific angular momentum while the flight is above ``altitude_km``
    (the "approximately constant" stretch of Fig 2.10)."""
    flight = reference_3dof(projectile)
    above = flight.altitude_m > _altitude_km(altitude_km, flight) * 1e3
    momentum = flight.specific_angular_momentum_m2_s[above]
    return float((momentum.max() - momentum.min()) / momentum.max())


def reference_6dof(projectile: str, density_altitude: str = "flat") -> pd.DataFrame:
    """The 6DOF flight of ``projectile`` in Chapter 2 A's conditions (:func:`fly_6dof`)."""
    return fly_6dof(reference_launch(projectile), density_altitude)


def reference_mlt(projectile: str, density_altitude: str = "flat") -> pd.DataFrame:
    """The MLT flight of ``projectile`` in Chapter 2 A's conditions (:func:`fly_mlt`, its
    default segments)."""
    return fly_mlt(reference_launch(projectile), density_altitude)


RIGID_BODY_METHODS = ("6DOF", "MLT")


def rigid_body_flight(method: str, projectile: str, density_altitude: str = "flat") -> pd.DataFrame:
    """The cached reference flight of a rigid-body ``method`` (:data:`RIGID_BODY_METHODS`)."""
    check_choice(method, "method", RIGID_BODY_METHODS)
    return (reference_6dof if method == "6DOF" else reference_mlt)(projectile, density_altitude)


def _launch_axes(flight: pd.DataFrame, six_dof: bool) -> np.ndarray:
    """Earth-centred positions (n, 3) on the axes (up, downrange, right) at the launch point.

    3DOF launches from latitude 0, longitude 0 eastward: up = x, downrange = y, right = -z.
    The 6DOF's and MLT's flat frame has x downrange, y right, z down, the Earth's centre at
    z = +R.
    """
    if six_dof:
        return np.column_stack([earth.RADIUS_M - flight.z_m, flight.x_m, flight.y_m])
    return np.column_stack([flight.x_m, flight.y_m, -flight.z_m])


def max_distance_m(
    a: pd.DataFrame, b: pd.DataFrame, *, a_three_dof: bool = False, b_three_dof: bool = False
) -> float:
    """Largest distance (m) between flights ``a`` and ``b`` at ``a``'s times inside both (each
    a 6DOF/MLT flat-frame table, or a 3DOF table when flagged)."""
    a = a[a.time_s <= b.time_s.iloc[-1]]
    pb = _launch_axes(b, six_dof=not b_three_dof)
    at = np.column_stack([np.interp(a.time_s, b.time_s, pb[:, i]) for i in range(3)])
    return float(np.max(np.linalg.norm(_launch_axes(a, six_dof=not a_three_dof) - at, axis=1)))


def max_position_difference_km(
    projectile: str, density_altitude: str = "flat", method: str = "6DOF"
) -> float:
    """Largest distance (km) between the 3DOF's position and a rigid-body ``method``'s at the
    same time."""
    return (
        max_distance_m(
            rigid_body_flight(method, projectile, density_altitude),
            reference_3dof(projectile),
            b_three_dof=True,
        )
        / 1e3
    )


def swerve(rigid_body: pd.DataFrame, three_dof: pd.DataFrame) -> pd.DataFrame:
    """Fig 2.7: a rigid-body flight's cross range minus the 3DOF's at the same time, against
    range."""
    three, six = three_dof, rigid_body[rigid_body.time_s <= three_dof.time_s.iloc[-1]]
    cross3 = np.interp(six.time_s, three.time_s, three.cross_range_m)
    return pd.DataFrame(
        {
            "time_s": six.time_s,
            "ground_range_m": six.ground_range_m,
            "swerve_m": six.cross_range_m - cross3,
        }
    )


def yaw_drag_peak(flight: pd.DataFrame) -> pd.Series:
    """The row of a 6DOF ``flight`` where its drag coefficient peaks before the rise near impact
    (in the first 90 % of its range): for HP, the yaw drag of the large angle of attack past
    apogee (Fig 2.8)."""
    early = flight[flight.ground_range_m < 0.9 * flight.ground_range_m.iloc[-1]]
    return flight.loc[early.drag_coefficient.idxmax()]


def angle_of_attack_at_apogee_deg(projectile: str) -> float:
    """Total angle of attack (deg) of the 6DOF reference flight at apogee (Ch. 4 A)."""
    flight = reference_6dof(projectile)
    return float(
        np.degrees(
            np.interp(flight.attrs["apogee_time_s"], flight.time_s, flight.angle_of_attack_rad)
        )
    )
