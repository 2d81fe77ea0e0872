"""Computational effort per apogee (Fig 4.7): floating-point operations counted from the source
by one rule for every method, next to the wall time measured on this machine.

The counting rule, applied to the code that each method runs per evaluation:

- every arithmetic operator (+ - * / and unary minus) is 1 operation, and so is a comparison
  or a min/max/clip/where (one select per element); ``x ** 2`` is 1 and ``x ** 3`` 2;
- sqrt is 1 (one hardware instruction);
- exp, log, sin, cos, tan, their inverses and a general power are 10 (a libm call);
- a table lookup (bisect, np.interp) is 10;
- the operations are counted statically from each function's abstract syntax tree, per
  element: a numpy expression over a trajectory's state costs what the same scalar code would.

An integration costs its right-hand side times the evaluations it made, plus the scheme's own
arithmetic per step (DOP853: combining 13 stage derivatives per state, the two error
estimates and the step control), counted analytically in :func:`dop853_step_flops`. The MKS
apogee is eqs 3.22, 3.27, 4.8 and 6.4-6.10 evaluated once: :func:`mks_apogee_flops` counts the
straight-line code :func:`mks_apogee` that computes it.
"""

from __future__ import annotations

import ast
import inspect
import math
import textwrap
import time
from functools import cache

import numpy as np
import pandas as pd

from . import atmosphere, drag, earth, threedof
from .sixdof import simulate_6dof

__all__ = ["count_flops", "dop853_step_flops", "mks_apogee", "mks_apogee_flops",
           "effort_table", "orders_of_magnitude", "best_time"]

_TRANSCENDENTAL = {"exp", "log", "log10", "sin", "cos", "tan", "arcsin", "arccos", "arctan",
                   "asin", "acos", "atan", "atan2", "arctan2", "power", "pow"}
_SELECT = {"minimum", "maximum", "min", "max", "clip", "where", "abs", "fabs"}
_LOOKUP = {"bisect_right", "bisect_left", "interp", "searchsorted"}


class _Counter(ast.NodeVisitor):
    def __init__(self):
        self.flops = 0

    def visit_BinOp(self, node):
        if isinstance(node.op, ast.Pow):
            exponent = node.right
            small = isinstance(exponent, ast.Constant) and exponent.value in (2, 3)
            self.flops += exponent.value - 1 if small else 10
        else:
            self.flops += 1
        self.generic_visit(node)

    def visit_UnaryOp(self, node):
        self.flops += isinstance(node.op, ast.USub)
        self.generic_visit(node)

    def visit_Compare(self, node):
        self.flops += len(node.ops)
        self.generic_visit(node)

    def visit_Call(self, node):
        name = node.func.attr if isinstance(node.func, ast.Attribute) else getattr(
            node.func, "id", "")
        self.flops += (10 if name in _TRANSCENDENTAL or name in _LOOKUP
                       else 1 if name in _SELECT or name in ("sqrt", "hypot") else 0)
        self.generic_visit(node)


def count_flops(*functions) -> int:
    """Operations per call of ``functions`` together, by the module's rule (their own bodies,
    not the functions they call: list every function an evaluation runs)."""
    total = 0
    for function in functions:
        tree = ast.parse(textwrap.dedent(inspect.getsource(function)))
        body = tree.body[0]
        if body.body and isinstance(body.body[0], ast.Expr) and isinstance(
                getattr(body.body[0], "value", None), ast.Constant):
            body.body = body.body[1:]  # the docstring is not arithmetic
        counter = _Counter()
        counter.visit(body)
        total += counter.flops
    return total


def dop853_step_flops(n_states: int) -> int:
    """DOP853's own arithmetic per step for ``n_states`` states: each of stages 2-12 combines
    the previous s stage derivatives (2 s operations per state), the solution 12 (24), the two
    error estimates 13 each (52), the error norm (4 per state) and ~30 scalar operations of
    step control."""
    per_state = sum(2 * s for s in range(1, 12)) + 24 + 52 + 4
    return per_state * n_states + 30


def mks_apogee(speed_m_s, elevation_rad, cd0, mass_kg, area_m2,
               k_per_m=atmosphere.TEXT_DECAY_CONSTANT_PER_M, rho0=1.225, r0=earth.RADIUS_M,
               gm=earth.GM_M3_S2):
    """Apogee altitude (m) of the three-term MKS in straight-line code (eqs 3.22, 3.27, 6.13,
    6.14, 6.6-6.10, 6.4, 6.5), the operations Fig 4.7 counts. Same result as
    :class:`harp_analysis.mks.ModifiedKeplerSolution` (tests/test_effort.py)."""
    sin_phi, cos_phi = np.sin(elevation_rad), np.cos(elevation_rad)
    beta = cd0 * rho0 * area_m2 / (2 * k_per_m * mass_kg * sin_phi)
    tau = k_per_m * r0 * sin_phi / cos_phi
    h_inf = speed_m_s * r0 * cos_phi * np.exp(-beta)
    c3 = gm / (h_inf * h_inf)
    c4 = -2 * beta * c3 / (1 + tau * tau)
    c5 = 2 * beta * beta * c3 / (1 + 4 * tau * tau)
    c1 = -sin_phi / (cos_phi * r0) + tau * c4 + 2 * tau * c5
    c2 = 1 / r0 - c3 - c4 - c5
    # At theta = atan(c1/c2), with c1 and c2 both negative on a suborbital flight,
    # c1 sin(theta) + c2 cos(theta) = -sqrt(c1^2 + c2^2).
    decay = np.exp(-tau * np.arctan(c1 / c2))
    u = c3 - np.sqrt(c1 * c1 + c2 * c2) + c4 * decay + c5 * decay * decay
    return 1 / u - r0


def mks_apogee_flops() -> int:
    return count_flops(mks_apogee)


def best_time(function, repeat: int = 5, number: int = 1) -> float:
    """Best of ``repeat`` timings of ``number`` calls of ``function``, per call (s)."""
    best = math.inf
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in range(number):
            function()
        best = min(best, (time.perf_counter() - start) / number)
    return best


@cache
def effort_table(elevation_deg: float = 50.0) -> pd.DataFrame:
    """FLOPs and wall time per apogee of HP at ``elevation_deg``, and each apogee's difference
    from the 6DOF's: 6DOF, 3DOF, MKS (three terms, straight-line code; and vectorised over a
    million launches). Modified Linear Theory is not in the package yet (issue #7)."""
    from .projectiles import HP
    from .scenarios import REFERENCE_CROSSWIND_M_S

    six = simulate_6dof(HP, elevation_deg=elevation_deg, crosswind_m_s=REFERENCE_CROSSWIND_M_S,
                        density_altitude="spherical")
    three = threedof.simulate_3dof(HP, elevation_deg, cross_wind_m_s=REFERENCE_CROSSWIND_M_S)
    six_flops = (six.attrs["n_rhs"] * count_flops(*_sixdof_functions())
                 + six.attrs["n_rhs"] / 12 * dop853_step_flops(12))
    three_flops = (three.attrs["rhs_evaluations"] * count_flops(*_threedof_functions())
                   + three.attrs["rhs_evaluations"] / 12 * dop853_step_flops(6))
    elevation = math.radians(elevation_deg)
    sound = float(atmosphere.get_atmosphere("two_segment").speed_of_sound(0.0))
    cd0 = float(HP.drag_law(HP.launch_speed_m_s / sound))
    inputs = (HP.launch_speed_m_s, elevation, cd0, HP.mass_kg, HP.reference_area_m2)
    many = np.full(1_000_000, elevation)
    lookup = 14  # Cd0 from the M829 table: one lookup and the linear interpolation
    rows = [
        ("6DOF", six_flops, best_time(lambda: simulate_6dof(HP, elevation_deg=elevation_deg),
                                     repeat=2), six.attrs["apogee_altitude_m"]),
        ("3DOF", three_flops, best_time(lambda: threedof.simulate_3dof(HP, elevation_deg)),
         three.attrs["apogee_altitude_m"]),
        ("MKS (3 terms)", mks_apogee_flops() + lookup,
         best_time(lambda: mks_apogee(*inputs), number=1000), float(mks_apogee(*inputs))),
        ("MKS, a million launches at once (per launch)", mks_apogee_flops() + lookup,
         best_time(lambda: mks_apogee(inputs[0], many, *inputs[2:]), repeat=3) / many.size,
         float(mks_apogee(*inputs))),
    ]
    table = pd.DataFrame(rows, columns=["method", "flops", "seconds", "apogee_m"])
    table["apogee_difference_m"] = (table.apogee_m - six.attrs["apogee_altitude_m"]).abs()
    return table.set_index("method")


def _threedof_functions():
    dynamics = threedof._Dynamics
    return (dynamics.acceleration, dynamics.forces, dynamics.air_velocity,
            atmosphere._two_segment_density, atmosphere._two_segment_speed_of_sound,
            drag.TabulatedDragLaw.evaluate)


def _sixdof_functions():
    from .sixdof import RigidBodyModel as M
    return (M.no_roll, M.aero_no_roll, M.air, M.coefficients,
            atmosphere._two_segment_density, atmosphere._two_segment_speed_of_sound)


def orders_of_magnitude(method: str, than: str = "MKS (3 terms)") -> float:
    """log10 of the operation count of ``method`` over ``than``'s (Ch. 4 A, Fig 4.7)."""
    flops = effort_table().flops
    return float(np.log10(flops[method] / flops[than]))
