"""Quantities behind statements of Chapter 2 that the ledger scores (rows ``ch2.*`` and
``atm.two_segment.continuous_break``): the order of Appendix A's scheme, HP's inertia, the
angle of attack, Mach number, drag coefficient, speed, turn and angular momentum of the
reference flights (2 B), the share of the range gravity dominates, the Earth's GM, the density
fit's break, and what the Earth's rotation moves (2 A). The rotation's and Appendix A's flights
are flown here.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import constants

from ...engines import appendix_a, threedof
from ...foundation import earth
from ...foundation.validation import Bounds, check_choice, finite_scalar, positive_scalar
from ...models import trajectory
from ...models.atmosphere import two_segment_density
from ...models.launch import Launch, baseline_chapter_4
from ...models.projectiles import HP, LP
from .. import scenarios
from ..scenarios import fly_3dof

__all__ = [
    "observed_order",
    "appendix_a_convergence_order",
    "similar_inertia_kg_m2",
    "max_angle_of_attack_below_deg",
    "mach_over_speed_ratio_max",
    "ascent_change_below",
    "heavy_over_light",
    "gravity_dominant_share",
    "TEXT_EARTH_MASS_KG",
    "text_gm_over_appendix_gm",
    "two_segment_break_jump",
    "momentum_loss",
    "momentum_loss_ratio",
    "rotation_impact_shift_km",
    "rotation_shift_growth",
    "nonrotating_spread_m",
]


def observed_order(coarse: float, medium: float, fine: float) -> float:
    """Observed order of convergence p of a result computed with steps h, h/2 and h/4:
    log2((coarse - medium) / (medium - fine)) (the error goes as h^p)."""
    values = [finite_scalar(v, name) for v, name in ((coarse, "coarse"), (medium, "medium"))]
    values.append(finite_scalar(fine, "fine"))
    first, second = values[0] - values[1], values[1] - values[2]
    if first == 0.0 or second == 0.0 or (first > 0) != (second > 0):
        return float("nan")
    return math.log2(first / second)


def appendix_a_convergence_order(
    elevation_deg: float = 45.0, dt_s: float = 0.1, atmosphere: str = "three_layer"
) -> float:
    """Observed order of Appendix A's scheme (Ch. 2 A: "a custom written 2nd order 3DOF
    simulation"): the baseline's apogee height flown by the macro with steps ``dt_s``,
    ``dt_s``/2 and ``dt_s``/4 (:func:`observed_order`)."""
    launch = baseline_chapter_4(elevation_deg, atmosphere=atmosphere)
    step = positive_scalar(dt_s, "dt_s", "s")
    apogees = [
        appendix_a.simulate_appendix_a(launch, step / 2**n).attrs["apogee_altitude_m"]
        for n in range(3)
    ]
    return observed_order(*apogees)


def similar_inertia_kg_m2(axis: str = "pitch") -> float:
    """HP's roll or pitch inertia (kg m^2) if HP were LP scaled up geometrically (same shape,
    same density): LP's stated inertia times s^5, s = (m_HP / m_LP)^(1/3) (mass goes as s^3,
    inertia as mass times length^2). Ch. 2 A gives HP 6.20934 (pitch) and 0.00853 (roll)."""
    check_choice(axis, "axis", ("roll", "pitch"))
    scale = (HP.mass_kg / LP.mass_kg) ** (1.0 / 3.0)
    inertia = LP.pitch_inertia_kg_m2 if axis == "pitch" else LP.roll_inertia_kg_m2
    if inertia is None:
        raise ValueError(f"LP carries no {axis} inertia")
    return inertia * scale**5


def max_angle_of_attack_below_deg(projectile: str = "HP", altitude_km: float = 30.0) -> float:
    """Largest total angle of attack (deg) of Chapter 2 A's 6DOF flight while below
    ``altitude_km``, on the way up and on the way down (Fig 2.5)."""
    flight = scenarios.reference_6dof(projectile)
    low = flight.altitude_m < finite_scalar(altitude_km, "altitude_km") * 1e3
    return float(np.degrees(flight.angle_of_attack_rad[low].max()))


def mach_over_speed_ratio_max(projectile: str = "HP") -> float:
    """Largest (Mach / launch Mach) / (speed / launch speed) on the way up of Chapter 2 A's 3DOF
    flight (Fig 2.8): how much more slowly the Mach number falls than the speed."""
    ascent = scenarios.ascent(scenarios.reference_3dof(projectile))
    mach = ascent.mach.to_numpy() / ascent.mach.iloc[0]
    speed = ascent.speed_m_s.to_numpy() / ascent.speed_m_s.iloc[0]
    return float(np.max(mach / speed))


def ascent_change_below(
    projectile: str = "HP",
    quantity: str = "drag_coefficient",
    altitude_km: float = 20.0,
    atmosphere: str = "two_segment",
) -> float:
    """Change of a quantity over the ascent of Chapter 2 A's 3DOF flight (5 m/s cross wind) up
    to ``altitude_km``:

    - ``"drag_coefficient"``: largest |Cd / Cd0 - 1| (Fig 2.8);
    - ``"speed"``: 1 - V / V0 at the altitude (the speed lost);
    - ``"turn"``: launch flight-path angle minus the one at the altitude (deg), the curvature
      of Fig 2.9's path in the lower atmosphere.
    """
    check_choice(quantity, "quantity", ("drag_coefficient", "speed", "turn"))
    top = finite_scalar(altitude_km, "altitude_km") * 1e3
    launch = scenarios.reference_launch(projectile).but(atmosphere=atmosphere)
    ascent = scenarios.ascent(fly_3dof(launch))
    low = ascent[ascent.altitude_m <= top]
    if quantity == "drag_coefficient":
        cd = low.drag_coefficient.to_numpy()
        return float(np.max(np.abs(cd / cd[0] - 1.0)))
    heights = ascent.altitude_m.to_numpy()
    if quantity == "speed":
        return float(1.0 - np.interp(top, heights, ascent.speed_m_s) / ascent.speed_m_s.iloc[0])
    angle = ascent.flight_path_angle_rad.to_numpy()
    return math.degrees(angle[0] - float(np.interp(top, heights, angle)))


def heavy_over_light(quantity: str = "drag_coefficient", altitude_km: float = 20.0) -> float:
    """:func:`ascent_change_below` of HP over LP's (Ch. 2 B: the heavier projectile "slows down
    much less" and "shows less curvature")."""
    return ascent_change_below("HP", quantity, altitude_km) / ascent_change_below(
        "LP", quantity, altitude_km
    )


def gravity_dominant_share(projectile: str = "HP", ratio: float = 1.0) -> float:
    """Share of Chapter 2 A's ground range flown with drag under ``ratio`` times gravity (N <
    ``ratio``, Fig 2.2): "gravity is the dominant force over the vast majority of the
    trajectory"."""
    limit = Bounds(low=0.0, low_inclusive=False).scalar(ratio, "ratio")
    flight = scenarios.reference_3dof(projectile)
    n = flight.drag_to_gravity.to_numpy()
    steps = np.diff(flight.ground_range_m.to_numpy())
    below = 0.5 * (n[1:] + n[:-1]) < limit
    return float(steps[below].sum() / flight.attrs["range_m"])


#: Ch. 2 A: the Earth's mass (kg).
TEXT_EARTH_MASS_KG = 5.972e24


def text_gm_over_appendix_gm(earth_mass_kg: float = TEXT_EARTH_MASS_KG) -> float:
    """G M with Ch. 2 A's Earth mass and CODATA 2018's G (scipy.constants) over Appendices A and
    B's GM = 398600.4418 km^3/s^2."""
    return constants.G * finite_scalar(earth_mass_kg, "earth_mass_kg") / earth.GM_M3_S2


def two_segment_break_jump(break_m: float = 10_769.0, offset_m: float = 1e-3) -> float:
    """Relative jump of eqs 2.1-2.2's density across their break: rho just above over rho just
    below, minus 1 (0 for a continuous fit)."""
    at = finite_scalar(break_m, "break_m")
    step = positive_scalar(offset_m, "offset_m", "m")
    above, below = two_segment_density(np.array([at + step, at - step]))
    return float(above / below - 1.0)


def momentum_loss(projectile: str = "HP", part: str = "ascent", altitude_km: float = 20.0) -> float:
    """Relative loss of specific angular momentum of Chapter 2 A's 3DOF flight (Fig 2.10):
    over the whole ascent (``"ascent"``), or on the way down from ``altitude_km`` to impact
    (``"reentry"``)."""
    check_choice(part, "part", ("ascent", "reentry"))
    flight = scenarios.reference_3dof(projectile)
    momentum = flight.specific_angular_momentum_m2_s.to_numpy()
    if part == "ascent":
        ascent = scenarios.ascent(flight).specific_angular_momentum_m2_s.to_numpy()
        return float(1.0 - ascent[-1] / ascent[0])
    down = flight.time_s.to_numpy() > flight.attrs["apogee_time_s"]
    heights = flight.altitude_m.to_numpy()[down][::-1]
    start = np.interp(
        finite_scalar(altitude_km, "altitude_km") * 1e3, heights, momentum[down][::-1]
    )
    return float(1.0 - momentum[-1] / start)


def momentum_loss_ratio(
    numerator: str = "LP", denominator: str = "HP", part: str = "ascent"
) -> float:
    """:func:`momentum_loss` of ``numerator`` over ``denominator``'s."""
    return momentum_loss(numerator, part) / momentum_loss(denominator, part)


def _earth_fixed_impact_m(launch: Launch) -> tuple[np.ndarray, float]:
    """Impact point (Earth-fixed, m) and range (m) of the 3DOF flight of ``launch``."""
    flight = threedof.simulate_3dof(launch, output_step_s=1.0)
    inertial = flight[["x_m", "y_m", "z_m"]].to_numpy()[-1]
    turned = launch.rotation_rate_rad_s * flight.attrs["time_of_flight_s"]
    return trajectory.rotate_about_axis(inertial, -turned), flight.attrs["range_m"]


def rotation_impact_shift_km(
    speed_m_s: float = 2157.0,
    elevation_deg: float = 45.0,
    latitude_deg: float = 45.0,
    bearing_deg: float = 0.0,
    relative: bool = False,
    atmosphere: str = "two_segment",
) -> float:
    """Distance (km) between the impact points of the baseline fired on a rotating and on a
    non-rotating Earth (3DOF, Earth-fixed): the Coriolis and centrifugal correction of Ch. 2 A;
    over the non-rotating range if ``relative``."""
    launch = baseline_chapter_4(
        elevation_deg,
        speed_m_s=speed_m_s,
        latitude_deg=latitude_deg,
        bearing_deg=bearing_deg,
        atmosphere=atmosphere,
    )
    still, reach = _earth_fixed_impact_m(launch)
    turning, _ = _earth_fixed_impact_m(launch.but(rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S))
    shift = float(np.linalg.norm(turning - still))
    return shift / reach if relative else shift / 1e3


def rotation_shift_growth(
    low_speed_m_s: float = 800.0,
    high_speed_m_s: float = 2157.0,
    elevation_deg: float = 45.0,
    latitude_deg: float = 45.0,
    bearing_deg: float = 0.0,
) -> float:
    """The rotation's impact shift as a share of the range at ``high_speed_m_s`` over that at
    ``low_speed_m_s`` (:func:`rotation_impact_shift_km`): "more pronounced as the projectile
    velocities and range increase" (Ch. 2 A)."""
    shifts = [
        rotation_impact_shift_km(v, elevation_deg, latitude_deg, bearing_deg, relative=True)
        for v in (high_speed_m_s, low_speed_m_s)
    ]
    return shifts[0] / shifts[1]


def nonrotating_spread_m(
    elevation_deg: float = 45.0,
    rotation_rate_rad_s: float = 0.0,
    latitudes_deg=(0.0, 30.0, 60.0, 85.0),
    bearings_deg=(0.0, 90.0, 200.0, 315.0),
) -> float:
    """Largest spread (m) of the baseline's apogee height and range over launch latitudes and
    bearings (3DOF): zero on Ch. 2 A's non-rotating Earth, where "it is unimportant where the
    launch point is located or what bearing it is launched"."""
    apogees, ranges = [], []
    for latitude in latitudes_deg:
        for bearing in bearings_deg:
            flight = threedof.simulate_3dof(
                baseline_chapter_4(
                    elevation_deg,
                    latitude_deg=latitude,
                    bearing_deg=bearing,
                    rotation_rate_rad_s=rotation_rate_rad_s,
                ),
                output_step_s=10.0,
            )
            apogees.append(flight.attrs["apogee_altitude_m"])
            ranges.append(flight.attrs["range_m"])
    return float(max(np.ptp(apogees), np.ptp(ranges)))
