"""The total position error between a simulation and the Modified Kepler Solution (eqs 4.4-4.7).

The simulation is sampled in time and the MKS is a function of the angular range, so Chapter 4 A
compares them at the simulation's angular range theta_i of each time step:

- eq 4.4, radial error: eps_r = r_sim - r_MKS(theta_i);
- eq 4.5, along-track error: eps_theta = (t_MKS(theta_i) - t_sim) |V|, the time the MKS takes
  to reach theta_i beyond the simulation's, times the simulation's speed;
- eq 4.6, the direction of the track, Phi;
- eq 4.7, eps_total = sqrt((eps_r + eps_theta cos Phi)^2 + (eps_theta sin Phi)^2).

Read closely, eqs 4.6 and 4.7 do not describe the geometry of Fig 4.5. Eq 4.6 as printed is
atan of r [(1/r_i - c3) sin(theta) - tan(phi_i)/r_i cos(theta)]: the derivative of the
*drag-free* Kepler solution (no driving terms), with the sign of its cos(theta) term flipped
(-r du/dtheta = r [(1/r0 - c3) sin(theta) + tan(phi0)/r0 cos(theta)] for u = c1 sin + c2 cos + c3).
And eq 4.7 composes the errors with cos and sin swapped: an along-track displacement eps_theta
along a path climbing at Phi above the horizontal has radial component eps_theta sin(Phi) and
horizontal component eps_theta cos(Phi). Three measures are therefore computed:

``total_printed``
    eqs 4.6-4.7 exactly as printed (r_i, phi_i the launch radius and elevation, c3 the MKS's);
``total_geometric``
    the reading that matches Fig 4.5: Phi the MKS's own flight-path angle atan(-u'/u) at
    theta_i (eq 3.28) and sqrt((eps_r + eps_theta sin Phi)^2 + (eps_theta cos Phi)^2);
``direct``
    the distance between the simulation's position and the MKS's at the same time (the MKS
    angle at t_sim found by inverting eq 3.32), including the simulation's cross range.

The geometric reading agrees with the direct distance to first order in the errors; the
figures use it (notebook 04 shows all three for Fig 4.6).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..engines.mks import ModifiedKeplerSolution
from ..foundation import earth

__all__ = ["position_errors"]


def position_errors(simulation: pd.DataFrame, solution: ModifiedKeplerSolution) -> pd.DataFrame:
    """Eqs 4.4-4.7 and the direct distance between a simulation table (the columns of
    :mod:`.trajectory`) and a single-launch MKS, row by row up to the simulation's impact."""
    if not solution.single:
        raise ValueError("solution must describe a single launch")
    flight = simulation[simulation.ground_range_m >= 0]
    theta = flight.ground_range_m.to_numpy() / earth.RADIUS_M
    r_sim = flight.altitude_m.to_numpy() + earth.RADIUS_M
    t_sim = flight.time_s.to_numpy()
    r_mks = solution.radius(theta)
    eps_r = r_sim - r_mks  # eq 4.4
    t_mks = solution.time(np.maximum.accumulate(theta))
    eps_theta = (t_mks - t_sim) * flight.speed_m_s.to_numpy()  # eq 4.5

    r0, phi0, c3 = solution.radius_m[0, 0], solution.elevation_rad[0, 0], solution.c3[0, 0]
    phi_printed = np.arctan(
        r_mks * (1 / r0 - c3) * np.sin(theta) - r_mks * np.tan(phi0) / r0 * np.cos(theta)
    )  # eq 4.6 as printed
    total_printed = np.hypot(
        eps_r + eps_theta * np.cos(phi_printed), eps_theta * np.sin(phi_printed)
    )  # eq 4.7 as printed
    phi = solution.flight_path_angle(theta)
    total_geometric = np.hypot(eps_r + eps_theta * np.sin(phi), eps_theta * np.cos(phi))

    # The MKS at the simulation's times: invert t(theta) on a fine grid of its own.
    grid = np.linspace(0.0, solution.impact_angle, 4001)
    theta_at_t = np.interp(t_sim, solution.time(grid), grid)
    r_at_t = solution.radius(theta_at_t)
    cross = flight.cross_range_m.to_numpy() / earth.RADIUS_M
    sim_xyz = r_sim * np.array(
        [np.cos(cross) * np.cos(theta), np.cos(cross) * np.sin(theta), np.sin(cross)]
    )
    mks_xyz = r_at_t * np.array([np.cos(theta_at_t), np.sin(theta_at_t), 0 * theta_at_t])
    return pd.DataFrame(
        {
            "time_s": t_sim,
            "theta_rad": theta,
            "radial_error_m": eps_r,
            "along_track_error_m": eps_theta,
            "phi_printed_rad": phi_printed,
            "phi_mks_rad": phi,
            "total_printed_m": total_printed,
            "total_geometric_m": total_geometric,
            "direct_m": np.linalg.norm(sim_xyz - mks_xyz, axis=0),
        }
    )
