"""Computational effort per apogee (Fig 4.7): floating-point operations counted from the source
by one rule for every method, next to the wall time measured on this machine.

The counting rule, applied to the code that each method runs per evaluation:

- every arithmetic operator (+ - * / and unary minus) is 1 operation, and so is a comparison
  or a min/max/clip/where (one select per element); ``x ** 2`` is 1 and ``x ** 3`` 2;
- sqrt is 1 (one hardware instruction);
- exp, log, sin, cos, tan, their inverses and a general power are 10 (a libm call);
- a table lookup (bisect, np.interp) is 10;
- the operations are counted statically from each function's abstract syntax tree, per
  element: a numpy expression over a trajectory's state costs what the same scalar code would;
  a vector operation counts once, numpy's (3, n) expression as compiled code's
  ``compiled.vector(x, y, z)`` of its components (their costliest), and the formulas shared
  by numpy and compiled code count the same in both;
- branches: a function counts along its costliest path. Of an ``if`` (or a conditional
  expression) the costlier branch counts, a branch that leaves the block (return, raise,
  break, continue) competing with the other branch and everything after it. An upper bound
  where the cheaper branch runs: MLT's ``_phi`` counts its 18-term series (44 operations, 176
  complex-weighted) in every call, also in the quarter of HP's calls (1 km segments) that take
  the exponential (18, 72 weighted): MLT's count is about 7 % high;
- loops: a ``for`` loop's body, or a comprehension's element (and its conditions), counts once
  per item. ``range`` with constant bounds and a module-level tuple or list constant are sized
  from the code; any other iterable is sized by the caller (``trips``, keyed by the iterable's
  source text), and a loop nobody sized, or a ``while`` loop, is an error rather than a
  guess. A function defined inside another counts where it is called, once per call;
- complex arithmetic: a function that runs in complex numbers counts each of its operations
  :data:`COMPLEX_WEIGHT` = 4 times (a complex add is 2 real operations, a product 6, a real
  times a complex 2, a quotient about 11: 4 stands for their mix), transcendentals included:
  cmath.exp is 40 (a real exp, cos and sin and two products would be 32) and cmath.sqrt 4
  (hypot, a real sqrt and about 5 operations would be 7).

Which functions an engine's work runs, which of them compute in complex numbers and how long
their unsized loops are, the engine declares (its record's ``counted`` in
:mod:`harp_analysis.engines.catalogue`, a tuple of
:class:`~harp_analysis.foundation.counting.Counted`); this module applies the rule to them.

What the branch rule changes in the 3DOF and 6DOF: the rigid body's ``air_altitude`` and the
3DOF's ``_air_velocity`` have branches of different cost (1 fewer each when only the costlier
counts): the 6DOF's right-hand side is 300 operations (its coefficient interpolation 2 per each
of the table's 9 columns), the 3DOF's 80 (81; 4 of them the day's air of
:func:`.atmosphere.day_air`, which the 6DOF leaves out). In MLT the loop is ``_phi``'s series
(the 18 terms of phi_3, a constant of :mod:`harp_analysis.engines.mlt`); complex-weighted are
``_phi`` (also where ``_scalar_solution`` calls it on a real argument) and
``_epicyclic_solution``, while ``propagate_segment``, real but for 6 complex operations (about
14 real ones), counts at weight 1.

An integration costs its right-hand side times the evaluations it made, plus the scheme's own
arithmetic per step (DOP853: combining 13 stage derivatives per state, the two error
estimates and the step control), counted analytically in :func:`dop853_step_flops`. The MKS
apogee is eqs 3.22, 3.27, 4.8 and 6.4-6.10 evaluated once: :func:`mks_apogee_flops` counts the
straight-line code :func:`mks_apogee` that computes it.

How many evaluations an adaptive integration makes depends on rounding, so the counts of the
integrations are good to a few per cent, not to their last digit. A DOP853 error estimate at
rtol 1e-9 is a sum of stage derivatives that cancel to about 1e-7 of their size: the order in
which a code adds them, or one unit in the last place of an exp, moves the step sizes in their
eighth digit and can turn an accepted step into a rejected one. HP's 3DOF at 50 deg made
1,070 evaluations in the compiled kernel, 1,130 in numpy's vectorised code (its BLAS summation
order), and 1,202 if the kernel summed the error estimate in reverse order: its count is good to
about 6 % (0.03 in log10). How the integrator meets the air's breakpoint and the drag table's
kinks matters more: it made 856 once it carried its steps across the breakpoint, and 904, nine
times as accurate, once its steps also ended on the table's Mach nodes
(:mod:`harp_analysis.engines.threedof`). The 6DOF's moved
from 24,974 to 25,031 when its right-hand side was compiled (libm's exp for numpy's; one unit
in the last place of the density alone does the same): 0.3 %.

MLT (:func:`mlt_flops`) costs every call that MLT's segment loop
(:data:`harp_analysis.engines.mlt.SEGMENT_LOOP`) makes, times the called function's own count, plus
the loop's own operations once per segment. The calls are counted while the flight runs (a profile
hook, like an integrator's count of its evaluations) and the count stops where the loop ends. Per
segment, with the coefficients at its ``"middle"``, that is: ``segment_coefficients`` twice (at the
start, and at the middle of the first pass), each with its rotation, wind, gravity, air and
coefficient table; ``propagate_segment`` three times (the first pass to the end and to the middle
in ``_solve_segment``, the second pass to the end in the loop), each with two ``_scalar_solution``
and one ``_epicyclic_solution``, so four ``_phi``; two more ``_rotation`` for the trapezoid mean;
the impact check ``_altitude``; and, in every segment up to the apogee's, ``_radial_velocity``,
which propagates to the segment's end once more (the state the second pass just computed). The
apogee's segment adds the radial velocity at its start, the brentq evaluations and the apogee
state; the last segment the brentq evaluations of the impact (one propagation each; brentq's own
arithmetic, about 10 operations per iteration, is not counted). For HP with 1 km segments that is
about 4,800 operations a segment, half of them in ``_phi``.

Output is not counted for any method: the table's rows (the 3DOF's Hermite samples, the 6DOF's
dense-output samples, MLT's one propagation per row, all after its segment loop), nor MLT's
validity diagnostics. Events are counted where locating them costs right-hand sides or
propagations: the 6DOF's evaluations include scipy's 3 per step that build each step's
interpolant, which locates its events (and samples its rows), about 18 % of them; MLT's
radial-velocity checks and root-finding propagations are counted. The 3DOF locates its events
on its Hermite interpolant, whose arithmetic is not counted, and the 3DOF's and 6DOF's event
functions' own operations are not (about 40 and 90 per step, 2 % and 1 % of a step), while
MLT's ``_altitude`` and ``_radial_velocity`` bodies (14 a segment, 0.3 %) are. MLT's validity
check of each segment (:data:`harp_analysis.engines.mlt.DIAGNOSTICS`) is not counted, nor any
call made within it.
"""

from __future__ import annotations

import ast
import inspect
import math
import sys
import textwrap
import time
from collections import Counter
from typing import Any

import numpy as np
import pandas as pd

from ..engines import catalogue, mks, mlt
from ..foundation import earth
from ..foundation.caching import cached_copies
from ..foundation.counting import Counted
from ..models import atmosphere

__all__ = [
    "COMPLEX_WEIGHT",
    "count_flops",
    "dop853_step_flops",
    "mks_apogee",
    "mks_apogee_flops",
    "mlt_flops",
    "effort_table",
    "orders_of_magnitude",
    "operations_per_3dof_evaluation",
    "mks_evaluation_operations",
    "best_time",
]

COMPLEX_WEIGHT = 4  # real operations per operation on complex numbers (module docstring)

_TRANSCENDENTAL = {
    "exp",
    "log",
    "log10",
    "sin",
    "cos",
    "tan",
    "arcsin",
    "arccos",
    "arctan",
    "asin",
    "acos",
    "atan",
    "atan2",
    "arctan2",
    "power",
    "pow",
}
_SELECT = {"minimum", "maximum", "min", "max", "clip", "where", "select", "abs", "fabs"}
_LOOKUP = {"bisect_right", "bisect_left", "interp", "searchsorted"}


class _Counter(ast.NodeVisitor):
    """Operations of one syntax tree, each times ``scale`` (the complex weight, times the trips
    of the loops around it)."""

    def __init__(self, weight, trips, names, local_names, nested=()):
        self.flops = 0
        self.scale = weight
        self.trips = trips
        self.names = names  # the function's module globals
        self.local_names = local_names  # its parameters and locals, which shadow them
        self.nested = {node.name: node for node in nested}  # functions defined inside it

    def add(self, operations):
        self.flops += operations * self.scale

    def visit_BinOp(self, node):
        if isinstance(node.op, ast.Pow):
            exponent = node.right
            small = isinstance(exponent, ast.Constant) and exponent.value in (2, 3)
            self.add(exponent.value - 1 if small else 10)
        else:
            self.add(1)
        self.generic_visit(node)

    def visit_UnaryOp(self, node):
        self.add(isinstance(node.op, ast.USub))
        self.generic_visit(node)

    def visit_Compare(self, node):
        self.add(len(node.ops))
        self.generic_visit(node)

    def visit_Call(self, node):
        name = (
            node.func.attr if isinstance(node.func, ast.Attribute) else getattr(node.func, "id", "")
        )
        if name == "vector":  # compiled code's 3-vector, one operation per component's form
            self.flops += max(self.measure(lambda a=arg: self.visit(a)) for arg in node.args)
            return
        self.add(
            10
            if name in _TRANSCENDENTAL or name in _LOOKUP
            else 1
            if name in _SELECT or name in ("sqrt", "hypot")
            else 0
        )
        self.generic_visit(node)
        if isinstance(node.func, ast.Name) and node.func.id in self.nested:
            self.block(self.nested[node.func.id].body)  # inlined where it is called

    def visit_FunctionDef(self, node):
        pass  # a nested function counts where it is called (visit_Call)

    def measure(self, visit) -> int:
        """Operations that ``visit()`` adds, kept apart from the total."""
        outer, self.flops = self.flops, 0
        visit()
        cost, self.flops = self.flops, outer
        return cost

    def block(self, statements):
        """A statement list along its costliest path: of an ``if``, the costlier branch, where
        a branch that ends (return, raise, break, continue) competes with the other branch and
        the statements after it."""
        for index, statement in enumerate(statements):
            if not isinstance(statement, ast.If):
                self.visit(statement)
                continue
            self.visit(statement.test)
            rest = statements[index + 1 :]
            body_ends, else_ends = _ends(statement.body), _ends(statement.orelse)
            if not (body_ends or else_ends):
                self.flops += max(
                    self.measure(lambda: self.block(statement.body)),
                    self.measure(lambda: self.block(statement.orelse)),
                )
                continue
            body = statement.body + ([] if body_ends else rest)
            other = statement.orelse + ([] if else_ends else rest)
            self.flops += max(
                self.measure(lambda: self.block(body)), self.measure(lambda: self.block(other))
            )
            return

    def visit_If(self, node):  # an if that no statement list of block() holds
        self.block([node])

    def visit_IfExp(self, node):
        self.visit(node.test)
        self.flops += max(
            self.measure(lambda: self.visit(node.body)),
            self.measure(lambda: self.visit(node.orelse)),
        )

    def length(self, iterable) -> int:
        """Items of a loop's ``iterable``: given in ``trips``, or read from the code."""
        text = ast.unparse(iterable)
        if text in self.trips:
            return self.trips[text]
        trips = _constant_range(iterable)
        if trips is not None:
            return trips
        if (
            isinstance(iterable, ast.Name)
            and iterable.id not in self.local_names
            and isinstance(self.names.get(iterable.id), (tuple, list))
        ):
            return len(self.names[iterable.id])
        raise ValueError(f"a loop over {text!r} of unknown length: give it in trips")

    def visit_For(self, node):
        self.visit(node.iter)
        outer = self.scale
        self.scale *= self.length(node.iter)
        self.block(node.body)
        self.scale = outer
        self.block(node.orelse)

    visit_AsyncFor = visit_For

    def visit_While(self, node):
        raise ValueError("a while loop's trips are not known from the code")

    def comprehension(self, node, elements):
        outer = self.scale
        for generator in node.generators:
            self.visit(generator.iter)  # once per item of the generators before it
            self.scale *= self.length(generator.iter)
            for condition in generator.ifs:
                self.visit(condition)
        for element in elements:
            self.visit(element)
        self.scale = outer

    def visit_ListComp(self, node):
        self.comprehension(node, [node.elt])

    visit_SetComp = visit_GeneratorExp = visit_ListComp

    def visit_DictComp(self, node):
        self.comprehension(node, [node.key, node.value])


def _constant_range(iterable) -> int | None:
    """Items of ``range(...)`` of constant arguments (no keywords), or None for any other
    ``iterable``."""
    if (
        isinstance(iterable, ast.Call)
        and getattr(iterable.func, "id", "") == "range"
        and not iterable.keywords
        and all(isinstance(a, ast.Constant) for a in iterable.args)
    ):
        bounds = [int(a.value) for a in iterable.args if isinstance(a, ast.Constant)]  # type: ignore[arg-type]
        return len(range(*bounds))
    return None


def _ends(statements) -> bool:
    """Whether a statement list always leaves its block (return, raise, break, continue)."""
    if not statements:
        return False
    last = statements[-1]
    return isinstance(last, (ast.Return, ast.Raise, ast.Break, ast.Continue)) or (
        isinstance(last, ast.If) and _ends(last.body) and _ends(last.orelse)
    )


def _python(function):
    """The Python function behind a compiled one (numba keeps it as ``py_func``)."""
    return getattr(function, "py_func", function)


def _function_tree(function):
    tree = ast.parse(textwrap.dedent(inspect.getsource(_python(function))))
    body = tree.body[0]
    if (
        body.body
        and isinstance(body.body[0], ast.Expr)
        and isinstance(getattr(body.body[0], "value", None), ast.Constant)
    ):
        body.body = body.body[1:]  # the docstring is not arithmetic
    return body


def _count(function, weight=1, trips=None, part=None) -> int:
    """Operations of ``function``'s statements, or of the loop ``part(tree)`` picks from its
    tree (its test and body: one iteration)."""
    tree = _function_tree(function)
    function = _python(function)
    code = function.__code__
    nested = [
        node for node in ast.walk(tree) if isinstance(node, ast.FunctionDef) and node is not tree
    ]
    counter = _Counter(
        weight,
        dict(trips or {}),
        function.__globals__,
        set(code.co_varnames) | set(code.co_cellvars),
        nested,
    )
    if part is None:
        counter.block(tree.body)
    else:
        test, body = part(tree)
        counter.visit(test)
        counter.block(body)
    return counter.flops


def count_flops(*functions, weight: int = 1, trips: dict | None = None) -> int:
    """Operations per call of ``functions`` together, by the module's rule (their own bodies,
    not the functions they call: list every function an evaluation runs). ``weight`` is the
    real operations per operation (:data:`COMPLEX_WEIGHT` for a function in complex numbers);
    ``trips`` maps a loop's iterable, as source text, to its number of items where the code
    does not say (module docstring)."""
    return sum(_count(function, weight, trips) for function in functions)


def dop853_step_flops(n_states: int) -> int:
    """DOP853's own arithmetic per step for ``n_states`` states: each of stages 2-12 combines
    the previous s stage derivatives (2 s operations per state), the solution 12 (24), the two
    error estimates 13 each (52), the error norm (4 per state) and ~30 scalar operations of
    step control."""
    per_state = sum(2 * s for s in range(1, 12)) + 24 + 52 + 4
    return per_state * n_states + 30


def counted_flops(counted: Counted) -> int:
    """Operations per call of one function an engine declares (:mod:`.counting`): its own
    body, at :data:`COMPLEX_WEIGHT` if it computes in complex numbers, its loops sized by the
    engine's trips."""
    weight = COMPLEX_WEIGHT if counted.complex_numbers else 1
    return count_flops(counted.function, weight=weight, trips=dict(counted.trips))


def evaluation_flops(engine: catalogue.Engine, launch) -> int:
    """Operations of one evaluation of ``engine``'s right-hand side for ``launch``: every
    function it declares (:attr:`harp_analysis.engines.catalogue.Engine.counted`), once each."""
    if engine.counted is None:
        raise ValueError(f"the {engine.label} declares no functions to count")
    return sum(counted_flops(counted) for counted in engine.counted(launch))


def mks_apogee(
    speed_m_s,
    elevation_rad,
    cd0,
    mass_kg,
    area_m2,
    k_per_m=atmosphere.TEXT_DECAY_CONSTANT_PER_M,
    rho0=atmosphere.SEA_LEVEL_DENSITY_KG_M3,
    r0=earth.RADIUS_M,
    gm=earth.GM_M3_S2,
):
    """Apogee altitude (m) of the three-term MKS in straight-line code (eqs 3.22, 3.27, 6.13,
    6.14, 6.6-6.10, 6.4, 6.5), the operations Fig 4.7 counts. Same result as
    :class:`harp_analysis.engines.mks.ModifiedKeplerSolution` (tests/test_effort.py)."""
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


@cached_copies
def _mlt_costs(launch) -> dict:
    """Own operations per call of each function MLT's segment loop runs for ``launch``, by code
    object (:func:`harp_analysis.engines.mlt.counted_functions`)."""
    counted = catalogue.get_engine("mlt").counted
    assert counted is not None  # MLT declares its segment loop's functions
    return {entry.function.__code__: counted_flops(entry) for entry in counted(launch)}


def _segment_loop(tree) -> tuple:
    """The test and body of MLT's loop over segments (in
    :data:`harp_analysis.engines.mlt.SEGMENT_LOOP`)."""
    loop = next(node for node in ast.walk(tree) if isinstance(node, ast.While))
    return loop.test, loop.body


def _mlt_run(launch, **flight) -> tuple[Counter, pd.DataFrame]:
    """One MLT flight and the calls of every Python function that its segment loop made (by
    code object; a profile hook), leaving out the diagnostics and what runs after the loop
    (the output rows)."""
    simulate = mlt.SEGMENT_LOOP.__code__
    diagnostics = {function.__code__ for function in mlt.DIAGNOSTICS}  # not counted
    loop_test, loop_body = _segment_loop(_function_tree(mlt.SEGMENT_LOOP))
    first = simulate.co_firstlineno + loop_test.lineno - 1
    last = simulate.co_firstlineno + loop_body[-1].end_lineno - 1
    calls: Counter = Counter()

    def hook(frame, event, arg):
        if event != "call":
            return
        outer = frame.f_back
        while outer is not None and outer.f_code is not simulate:
            if outer.f_code in diagnostics:
                return
            outer = outer.f_back
        if outer is not None and first <= outer.f_lineno <= last:
            calls[frame.f_code] += 1

    previous = sys.getprofile()
    sys.setprofile(hook)
    try:
        table = mlt.simulate_mlt(launch, **flight)
    finally:
        sys.setprofile(previous)
    return calls, table


def _mlt_count(launch, **flight) -> tuple[int, pd.DataFrame]:
    calls, table = _mlt_run(launch, **flight)
    if launch.atmosphere != "two_segment":
        raise ValueError(
            "MLT's operations are counted in the two-segment atmosphere only (Fig 4.7's; "
            "the 1976 standard's kernels call helpers that the count does not see)"
        )
    loop = _count(mlt.SEGMENT_LOOP, part=_segment_loop)
    flops = sum(calls[code] * cost for code, cost in _mlt_costs(launch).items())
    return flops + table.attrs["steps"] * loop, table


def mlt_flops(launch, **flight) -> int:
    """Operations of one MLT flight of ``launch`` (keyword arguments of
    :func:`harp_analysis.engines.mlt.simulate_mlt`, in the two-segment atmosphere) to impact, by the
    module's rule: every call its segment loop makes times the called function's own count,
    plus the loop's own operations per segment; the output rows and the validity diagnostics
    are not counted."""
    return _mlt_count(launch, **flight)[0]


def best_time(function, repeat: int = 5, number: int = 1) -> float:
    """Best of ``repeat`` timings of ``number`` calls of ``function``, per call (s)."""
    best = math.inf
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in range(number):
            function()
        best = min(best, (time.perf_counter() - start) / number)
    return best


@cached_copies
def effort_table(elevation_deg: float = 50.0, timed: bool = True) -> pd.DataFrame:
    """FLOPs and wall time per apogee of HP at ``elevation_deg``, and each apogee's difference
    from the 6DOF's: 6DOF, 3DOF, MKS (three terms, straight-line code; and vectorised over a
    million launches) and Modified Linear Theory (1 km segments, coefficients at each
    segment's middle, the 6DOF's spherical density altitude). The simulations fly to impact,
    as the figure's methods do; the MKS evaluates the apogee alone. ``timed=False``
    leaves the wall times NaN: the counts (the ledger's) need no timing."""
    from ..models.launch import HP_CHAPTER_2

    launch = HP_CHAPTER_2.but(elevation_deg=elevation_deg)
    rigid, point_mass, linear_theory = map(catalogue.get_engine, ("6dof", "3dof", "mlt"))
    six = rigid.fly(launch, density_altitude="spherical")
    three = point_mass.fly(launch)
    six_rhs = evaluation_flops(rigid, launch)
    # scipy's DOP853 with dense output: 2 evaluations to start, 12 per step attempt and 3 more
    # per accepted step for the interpolant its events are found on.
    six_attempts = (six.attrs["rhs_evaluations"] - 2 - 3 * six.attrs["steps"]) / 12
    six_flops = six.attrs["rhs_evaluations"] * six_rhs + six_attempts * dop853_step_flops(12)
    three_flops = three.attrs["rhs_evaluations"] * evaluation_flops(
        point_mass, launch
    ) + three.attrs["rhs_evaluations"] / 12 * dop853_step_flops(6)
    mlt_flight: dict[str, Any] = dict(
        density_altitude="spherical",
        segment_length_m=mlt.SEGMENT_LENGTH_M,
        coefficients_at="middle",
    )
    linear_flops, linear = _mlt_count(launch, **mlt_flight)
    projectile = launch.projectile
    inputs = (
        launch.speed_m_s,
        launch.elevation_rad,
        launch.launch_drag_coefficient,
        projectile.mass_kg,
        projectile.reference_area_m2,
        atmosphere.TEXT_DECAY_CONSTANT_PER_M,
        mks.gun_density_kg_m3(launch),  # rho0 of eq 3.11, as mks.for_launch takes it
    )
    many = np.full(1_000_000, launch.elevation_rad)
    lookup = 14  # Cd0 from the M829 table: one lookup and the linear interpolation

    def seconds(function, **repeats):  # wall time only when asked: the counts do not need it
        return best_time(function, **repeats) if timed else math.nan

    rows = [
        (
            rigid.label,
            six_flops,
            seconds(lambda: rigid.fly(launch, density_altitude="spherical"), repeat=2),
            six.attrs["apogee_altitude_m"],
        ),
        (
            point_mass.label,
            three_flops,
            seconds(lambda: point_mass.fly(launch)),
            three.attrs["apogee_altitude_m"],
        ),
        (
            linear_theory.label,
            linear_flops,
            seconds(lambda: linear_theory.fly(launch, **mlt_flight)),
            linear.attrs["apogee_altitude_m"],
        ),
        (
            "MKS (3 terms)",
            mks_apogee_flops() + lookup,
            seconds(lambda: mks_apogee(*inputs), number=1000),
            float(mks_apogee(*inputs)),
        ),
        (
            "MKS, a million launches at once (per launch)",
            mks_apogee_flops() + lookup,
            seconds(lambda: mks_apogee(inputs[0], many, *inputs[2:]), repeat=3) / many.size,
            float(mks_apogee(*inputs)),
        ),
    ]
    table = pd.DataFrame(rows, columns=["method", "flops", "seconds", "apogee_m"])
    table["apogee_difference_m"] = (table.apogee_m - six.attrs["apogee_altitude_m"]).abs()
    return table.set_index("method")


def orders_of_magnitude(method: str, than: str = "MKS (3 terms)") -> float:
    """log10 of the operation count of ``method`` over ``than``'s (Ch. 4 A, Fig 4.7);
    ``method`` and ``than`` are rows of :func:`effort_table` ("6DOF", "3DOF", "MLT",
    "MKS (3 terms)", ...)."""
    flops = effort_table(timed=False).flops
    return float(np.log10(flops[method] / flops[than]))


def operations_per_3dof_evaluation() -> float:
    """Operations of one 3DOF evaluation with its share of DOP853's arithmetic: Fig 4.7's count
    of HP's flight (:func:`effort_table`) over the flight's right-hand-side evaluations."""
    from ..models.launch import HP_CHAPTER_2

    flops = effort_table(timed=False).flops["3DOF"]
    return float(flops) / catalogue.get_engine("3dof").fly(HP_CHAPTER_2).attrs["rhs_evaluations"]


def mks_evaluation_operations() -> float:
    """Operations of one three-term MKS evaluation as Fig 4.7 counts it (an apogee, its
    constants included: :func:`effort_table`)."""
    return float(effort_table(timed=False).flops["MKS (3 terms)"])
