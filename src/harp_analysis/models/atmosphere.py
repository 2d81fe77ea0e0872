"""Atmospheric density and speed of sound: the models of Chapters 2 A and 3 B and Appendices A
and B.

Five models, each vectorised over altitude (m above the spherical Earth's surface) and exposed
through one interface, :class:`AtmosphereModel`, so the simulations can take any of them by name
(:func:`get_atmosphere`):

``us1976``
    The 1976 US Standard Atmosphere [47], the reference. Densities come from the maintained
    ``ussa1976`` package (a full implementation of NASA-TM-X-74335, 0 to 1000 km), tabulated once
    every 25 m and interpolated linearly in log-density (relative interpolation error below
    1e-6, 1e-5 across the 86 km junction of the standard's two parts).
``two_segment``
    The multi-stage fit of eqs 2.1 and 2.2 as coded in Appendix B (the 6DOF).
``three_layer``
    The three-layer model inside the Appendix A 3DOF (NASA Glenn's "Earth Atmosphere Model").
``exponential``
    rho0 exp(-k a) of eq 3.11, the model behind the Modified Kepler Solution.
``vacuum``
    No air at all, to switch drag off in checks against closed-form orbits.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from typing import Any, Literal

import numpy as np

from ..foundation.compiled import formula, jit, select
from ..foundation.validation import Bounds, check_choice, real_array, real_number

__all__ = [
    "DRY_AIR_GAS_CONSTANT_J_KG_K",
    "SOUND_SQUARED_PER_KELVIN",
    "SEA_LEVEL_DENSITY_KG_M3",
    "TEXT_DECAY_CONSTANT_PER_M",
    "TEXT_R_SQUARED",
    "AtmosphereModel",
    "get_atmosphere",
    "ATMOSPHERE_NAMES",
    "standard_density",
    "standard_speed_of_sound",
    "two_segment_density",
    "two_segment_speed_of_sound",
    "three_layer_density",
    "three_layer_speed_of_sound",
    "exponential_density",
    "agreement_ceiling",
    "MAX_GRID_POINTS",
    "FitDefinition",
    "ExponentialFit",
    "fit_exponential",
    "FIT_DEFINITIONS",
    "LITERAL_FIT_DEFINITION",
    "literal_fit",
    "model_r_squared",
    "text_model_r_squared",
    "fit_definition_table",
    "day_air",
]

SEA_LEVEL_DENSITY_KG_M3 = 1.225  # US Standard Atmosphere 1976; Chapter 3 B's rho0
TEXT_DECAY_CONSTANT_PER_M = 0.117e-3  # Chapter 3 B: k = 0.117 /km
TEXT_R_SQUARED = 0.994  # Chapter 3 B: the "optimized coefficient of determination" of that k
_HEAT_CAPACITY_RATIO = 1.4
#: The 1976 standard's specific gas constant of dry air (J/(kg K)).
DRY_AIR_GAS_CONSTANT_J_KG_K = 287.05287
#: gamma R of dry air: a^2 = gamma R T (m^2/s^2 per kelvin).
SOUND_SQUARED_PER_KELVIN = _HEAT_CAPACITY_RATIO * DRY_AIR_GAS_CONSTANT_J_KG_K
_GAS_CONSTANT_J_KG_K = 287.0  # as Appendix A writes it (the standard's is 287.05287)

# The reference table: ussa1976 is exact but slow to call per point, so tabulate once.
_STANDARD_TOP_M = 1_000_000.0
_STANDARD_STEP_M = 25.0


#: Points of a grid from the surface that a function of this module builds at most (about
#: 80 MB of floats): a step far below the top would otherwise allocate until memory runs out.
MAX_GRID_POINTS = 10**7


def _positive(value, name: str, unit: str = "") -> float:
    """A number > 0, strictly (a string such as "10000" is refused, not read)."""
    return Bounds(low=0.0, low_inclusive=False, unit=unit).check(real_number(value, name), name)


def _grid_step(top_m: float, step_m: float, name: str = "step_m") -> float:
    """``step_m``, refused naming ``name`` if a grid to ``top_m`` would exceed
    :data:`MAX_GRID_POINTS`."""
    if top_m / step_m > MAX_GRID_POINTS:
        raise ValueError(
            f"{name} = {step_m:g} m makes more than {MAX_GRID_POINTS:g} points up to "
            f"{top_m:g} m; take a step of at least {top_m / MAX_GRID_POINTS:g} m"
        )
    return step_m


#: Where the Earth's gravity stops holding a body against the Sun's (its Hill sphere's radius,
#: m): no air model means anything beyond, and the formulas' temperatures, growing with height,
#: overflow far above it.
_HILL_SPHERE_M = 1.5e9


def _altitudes(altitude_m, *, ceiling_m: float | None = None) -> np.ndarray:
    altitude = real_array(altitude_m, "altitude_m")
    high = _HILL_SPHERE_M if ceiling_m is None else ceiling_m
    return Bounds(low=0.0, high=high, unit="m").check(altitude, "altitude_m")


@cache
def _standard_table() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    import ussa1976  # imported lazily: it pulls in xarray

    grid = np.arange(0.0, _STANDARD_TOP_M + _STANDARD_STEP_M, _STANDARD_STEP_M)
    table = ussa1976.compute(z=grid, variables=["rho", "t"])
    return grid, np.log(table["rho"].values), table["t"].values


def standard_density(altitude_m) -> np.ndarray:
    """Density of the 1976 US Standard Atmosphere (kg/m^3) at geometric altitude 0 to 1000 km.

    Reference model of Figs 2.1 and 3.2. Agrees with the printed NASA tables to their four
    significant figures up to 90 km; at 100 km the ``ussa1976`` implementation is 0.15 % above
    the printed 5.604e-7 kg/m^3 (see ``tests/test_atmosphere.py``).

    Parameters
    ----------
    altitude_m : float or array_like
        Geometric altitude (m), 0 to 1000 km.

    Returns
    -------
    numpy.ndarray
        Density (kg/m^3), of the shape of ``altitude_m``.
    """
    return _standard_density(_altitudes(altitude_m, ceiling_m=_STANDARD_TOP_M))


def _standard_density(a):
    grid, log_density, _ = _standard_table()
    return _table_density(a, grid, log_density)


@formula
def _table_density(a, grid, log_density):
    return np.exp(np.interp(a, grid, log_density))


def standard_speed_of_sound(altitude_m) -> np.ndarray:
    """Speed of sound sqrt(gamma R T) of the 1976 standard (m/s), defined by it up to 86 km."""
    return _standard_speed_of_sound(_altitudes(altitude_m, ceiling_m=86_000.0))


def _standard_speed_of_sound(a):
    grid, _, temperature = _standard_table()
    return _table_speed_of_sound(a, grid, temperature)


@formula
def _table_speed_of_sound(a, grid, temperature):
    return np.sqrt(SOUND_SQUARED_PER_KELVIN * np.interp(a, grid, temperature))


# --- Eqs 2.1 and 2.2, as coded in Appendix B -------------------------------------------------
# The typeset eq 2.2 writes the speed of sound as 14.9390 sqrt(518 - 0.01170 a); Appendix B's
# code has 518.4 (sea-level temperature in degrees Rankine). We follow the code: 518.4 also
# makes the two segments' speeds of sound meet at 10.769 km (295.93 m/s, eq 2.1's constant).
_SEGMENT_BREAK_M = 10_769.0


def two_segment_density(altitude_m) -> np.ndarray:
    """Density (kg/m^3) of the two-segment model, eqs 2.1 (above 10.769 km) and 2.2 (below)."""
    return _two_segment_density(_altitudes(altitude_m))


@formula
def _two_segment_density(a):
    lower = 1.22581 * (1.0 - 0.00002257 * np.minimum(a, _SEGMENT_BREAK_M)) ** 4.256
    upper = 0.37454745 * np.exp(-0.00015682 * (a - _SEGMENT_BREAK_M))
    return select(a > _SEGMENT_BREAK_M, upper, lower)


def two_segment_speed_of_sound(altitude_m) -> np.ndarray:
    """Speed of sound (m/s) of eqs 2.1 and 2.2 with Appendix B's constant 518.4 (see above)."""
    return _two_segment_speed_of_sound(_altitudes(altitude_m))


@formula
def _two_segment_speed_of_sound(a):
    lower = 14.9390 * np.sqrt(518.4 - 0.01170 * np.minimum(a, _SEGMENT_BREAK_M))
    return select(a > _SEGMENT_BREAK_M, 295.92987, lower)


# --- Appendix A's three layers (NASA Glenn "Earth Atmosphere Model", metric) -----------------
@formula
def _three_layer_state(a):
    """Temperature (K) and pressure (kPa) exactly as Appendix A computes them: troposphere
    below 11 km, lower stratosphere to 25 km, upper stratosphere above."""
    a_km = a / 1000.0
    temperature = select(
        a_km < 11.0,
        288.14 - 6.49 * a_km,
        select(a_km < 25.0, -56.46 + 273.1, 141.89 + 2.99 * a_km),
    )
    pressure = select(
        a_km < 11.0,
        101.29 * (temperature / 288.08) ** 5.256,
        select(
            a_km < 25.0,
            22.65 * np.exp(1.73 - 0.157 * a_km),
            2.488 * (temperature / 216.6) ** -11.388,
        ),
    )
    return temperature, pressure


def three_layer_density(altitude_m) -> np.ndarray:
    """Density (kg/m^3) of Appendix A's atmosphere: p / (0.2869 T), p in kPa."""
    return _three_layer_density(_altitudes(altitude_m))


@formula
def _three_layer_density(a):
    temperature, pressure = _three_layer_state(a)
    return pressure / (0.2869 * temperature)


def three_layer_speed_of_sound(altitude_m) -> np.ndarray:
    """Speed of sound (m/s) of Appendix A: sqrt(1.4 * 287 * T)."""
    return _three_layer_speed_of_sound(_altitudes(altitude_m))


@formula
def _three_layer_speed_of_sound(a):
    temperature, _ = _three_layer_state(a)
    return np.sqrt(_HEAT_CAPACITY_RATIO * _GAS_CONSTANT_J_KG_K * temperature)


def exponential_density(
    altitude_m,
    decay_constant_per_m: float = TEXT_DECAY_CONSTANT_PER_M,
    surface_density_kg_m3: float = SEA_LEVEL_DENSITY_KG_M3,
) -> np.ndarray:
    """rho0 exp(-k a) of eq 3.11 (kg/m^3); k in 1/m (the text's 0.117 /km is 1.17e-4 /m)."""
    k = _positive(decay_constant_per_m, "decay_constant_per_m", "1/m")
    rho0 = _positive(surface_density_kg_m3, "surface_density_kg_m3", "kg/m^3")
    return rho0 * np.exp(-k * _altitudes(altitude_m))


@formula
def _text_exponential_density(a):
    return SEA_LEVEL_DENSITY_KG_M3 * np.exp(-TEXT_DECAY_CONSTANT_PER_M * a)


def _no_density(a):
    return 0.0 * a


@dataclass(frozen=True)
class AtmosphereModel:
    """A named density and speed-of-sound pair, the pluggable atmosphere of the simulations.

    ``density`` and ``speed_of_sound`` check their altitudes like the module's functions;
    ``density_kernel`` and ``sound_kernel`` are the unchecked formulas that integration loops
    call (they accept slightly negative altitudes, which an integrator may probe at impact).
    """

    name: str
    density_kernel: Callable[[Any], Any]  # float or array in, the same out
    sound_kernel: Callable[[Any], Any]
    source: str
    ceiling_m: float | None = None
    sound_ceiling_m: float | None = None
    #: Altitudes (m) where the formulas jump or kink; integrators step onto them.
    breakpoints_m: tuple[float, ...] = ()
    #: The model's number in compiled loops (:func:`air`).
    code: int = -1

    def density(self, altitude_m) -> np.ndarray:
        return self.density_kernel(_altitudes(altitude_m, ceiling_m=self.ceiling_m))

    def speed_of_sound(self, altitude_m) -> np.ndarray:
        return self.sound_kernel(_altitudes(altitude_m, ceiling_m=self.sound_ceiling_m))

    def table(self) -> np.ndarray:
        """What :func:`air` needs besides the altitude: the 1976 standard's grid (m), log
        density and temperature (K) as rows (3, k); a placeholder (3, 2) for the formulas."""
        if self.code == US1976:
            return np.array(_standard_table())
        return np.zeros((3, 2))


@formula
def day_air(density, sound, density_factor, sound_squared_change):
    """The day's air from a model's: the density times ``density_factor`` (1 + the day's
    relative change) and the speed of sound of air warmer by dT at every height,
    sqrt(a^2 + gamma R dT) (``sound_squared_change`` = gamma R dT). An artillery met message's
    "ballistic density" and "ballistic temperature" are such height-uniform changes."""
    return density * density_factor, np.sqrt(sound * sound + sound_squared_change)


# Compiled loops choose the model by number; each runs the formulas above.
US1976, TWO_SEGMENT, THREE_LAYER, EXPONENTIAL, VACUUM = range(5)


@jit(inline=True)
def air(code, altitude_m, table):
    """Density (kg/m^3) and speed of sound (m/s) at ``altitude_m`` (one number) of the model
    numbered ``code`` (:attr:`AtmosphereModel.code`), for compiled loops; ``table`` is the
    model's :meth:`AtmosphereModel.table`. Unchecked, like the kernels."""
    if code == US1976:
        return (
            _table_density(altitude_m, table[0], table[1]),
            _table_speed_of_sound(altitude_m, table[0], table[2]),
        )
    if code == THREE_LAYER:
        return (
            _three_layer_density(altitude_m),
            _three_layer_speed_of_sound(altitude_m),
        )
    sound = _two_segment_speed_of_sound(altitude_m)
    if code == TWO_SEGMENT:
        return _two_segment_density(altitude_m), sound
    if code == EXPONENTIAL:
        return _text_exponential_density(altitude_m), sound
    if code == VACUUM:
        return 0.0, sound
    raise ValueError("unknown atmosphere code: only the registered models are compiled")


_MODELS = {
    model.name: model
    for model in (
        AtmosphereModel(
            "us1976",
            _standard_density,
            _standard_speed_of_sound,
            "US Standard Atmosphere 1976 [47] via ussa1976",
            _STANDARD_TOP_M,
            86_000.0,
            (11_000.0, 20_000.0, 32_000.0, 47_000.0, 51_000.0, 71_000.0, 86_000.0),
            code=US1976,
        ),
        AtmosphereModel(
            "two_segment",
            _two_segment_density,
            _two_segment_speed_of_sound,
            "eqs 2.1-2.2 as coded in Appendix B",
            breakpoints_m=(_SEGMENT_BREAK_M,),
            code=TWO_SEGMENT,
        ),
        AtmosphereModel(
            "three_layer",
            _three_layer_density,
            _three_layer_speed_of_sound,
            "Appendix A",
            breakpoints_m=(11_000.0, 25_000.0),
            code=THREE_LAYER,
        ),
        # Eq 3.11 defines only a density; where a simulation needs Mach with it (Fig 4.15) the
        # speed of sound of the simulation's own two-segment model is kept.
        AtmosphereModel(
            "exponential",
            _text_exponential_density,
            _two_segment_speed_of_sound,
            "eq 3.11 with k = 0.117 /km; speed of sound of eqs 2.1-2.2",
            code=EXPONENTIAL,
        ),
        # No air: drag off, for checks against the closed-form Kepler orbit.
        AtmosphereModel(
            "vacuum",
            _no_density,
            _two_segment_speed_of_sound,
            "no air (density zero); speed of sound of eqs 2.1-2.2 for Mach",
            code=VACUUM,
        ),
    )
}
ATMOSPHERE_NAMES = tuple(_MODELS)


def get_atmosphere(name: str) -> AtmosphereModel:
    """The atmosphere model called ``name`` (one of :data:`ATMOSPHERE_NAMES`).

    Parameters
    ----------
    name : str
        One of :data:`ATMOSPHERE_NAMES` (``"us1976"``, ``"two_segment"``, ...).

    Returns
    -------
    AtmosphereModel
        The model: its density and speed of sound against altitude, compiled.
    """
    return _MODELS[check_choice(name, "atmosphere", _MODELS)]


def agreement_ceiling(
    atmosphere: str,
    relative_tolerance: float,
    *,
    top_m: float = 150_000.0,
    step_m: float = 10.0,
) -> float:
    """Highest altitude (m) up to which the model ``atmosphere`` stays within
    ``relative_tolerance`` of the 1976 standard's density at every point of a ``step_m`` grid
    from the surface: the range over which the model "holds". ``top_m`` if it never departs."""
    density = get_atmosphere(atmosphere).density
    tolerance = _positive(relative_tolerance, "relative_tolerance")
    top_m = _positive(top_m, "top_m", "m")
    step_m = _grid_step(top_m, _positive(step_m, "step_m", "m"))
    grid = np.arange(0.0, top_m + step_m, step_m)
    outside = np.abs(density(grid) / standard_density(grid) - 1.0) > tolerance
    return float(grid[np.argmax(outside)] - step_m) if outside.any() else top_m


# --- The fit of k (Chapter 3 B, Fig 3.2) ------------------------------------------------------
@dataclass(frozen=True)
class FitDefinition:
    """One way to fit rho0 exp(-k a) to the standard atmosphere and score it with R^2.

    The text says only that k "was found by optimizing the coefficient of determination between
    the exponential model and the NASA Standard Atmosphere data", with rho0 = 1.225 kg/m^3. The
    unstated choices are: the altitude range and grid, whether rho0 is held at 1.225 or fitted,
    and whether R^2 (and so the least-squares fit that maximises it) is taken on the densities
    themselves (``linear``) or on their logarithms (``log``).
    """

    top_m: float
    step_m: float
    space: Literal["linear", "log"]
    rho0_free: bool = False

    def __post_init__(self):
        _positive(self.top_m, "top_m", "m")
        Bounds(high=self.top_m, unit="m").check(_positive(self.step_m, "step_m", "m"), "step_m")
        _grid_step(self.top_m, self.step_m)
        check_choice(self.space, "space", ("linear", "log"))

    def altitudes_m(self) -> np.ndarray:
        return np.arange(0.0, self.top_m + self.step_m / 2, self.step_m)

    def describe(self) -> str:
        rho0 = "rho0 fitted" if self.rho0_free else "rho0 = 1.225 kg/m^3 fixed"
        return (
            f"0-{self.top_m / 1e3:g} km every {self.step_m / 1e3:g} km, "
            f"R^2 of {'density' if self.space == 'linear' else 'log density'}, {rho0}"
        )


@dataclass(frozen=True)
class ExponentialFit:
    """Result of :func:`fit_exponential`: k, rho0 and the R^2 of the fit's own definition."""

    definition: FitDefinition
    decay_constant_per_m: float
    surface_density_kg_m3: float
    r_squared: float

    @property
    def decay_constant_per_km(self) -> float:
        return self.decay_constant_per_m * 1e3


def model_r_squared(
    definition: FitDefinition,
    decay_constant_per_m: float,
    surface_density_kg_m3: float = SEA_LEVEL_DENSITY_KG_M3,
) -> float:
    """R^2 of the model rho0 exp(-k a) against the 1976 standard, on ``definition``'s grid and
    in its space (density or log density)."""
    altitude = definition.altitudes_m()
    observed = standard_density(altitude)
    model = surface_density_kg_m3 * np.exp(-decay_constant_per_m * altitude)
    if definition.space == "log":
        observed, model = np.log(observed), np.log(model)
    residual = np.sum((observed - model) ** 2)
    return float(1.0 - residual / np.sum((observed - observed.mean()) ** 2))


def fit_exponential(definition: FitDefinition) -> ExponentialFit:
    """Least-squares fit of eq 3.11 to the 1976 standard under ``definition``.

    Least squares in the space where R^2 is computed is exactly the maximisation of that R^2
    (the total sum of squares does not depend on the model), so this is the text's "optimised
    coefficient of determination" for the chosen space. Log space is a linear regression;
    linear space a nonlinear least-squares fit started from the text's k.
    """
    from scipy.optimize import curve_fit

    altitude = definition.altitudes_m()
    observed = standard_density(altitude)
    rho0 = SEA_LEVEL_DENSITY_KG_M3
    if definition.space == "log" and definition.rho0_free:
        slope, intercept = np.polyfit(altitude, np.log(observed), 1)
        k, rho0 = -slope, float(np.exp(intercept))
    elif definition.space == "log":
        k = -np.sum(altitude * np.log(observed / rho0)) / np.sum(altitude**2)
    elif definition.rho0_free:
        (k, rho0), _ = curve_fit(
            lambda a, k, r: r * np.exp(-k * a),
            altitude,
            observed,
            p0=(TEXT_DECAY_CONSTANT_PER_M, rho0),
        )
    else:
        (k,), _ = curve_fit(
            lambda a, k: rho0 * np.exp(-k * a), altitude, observed, p0=(TEXT_DECAY_CONSTANT_PER_M,)
        )
    return ExponentialFit(
        definition, float(k), float(rho0), model_r_squared(definition, float(k), float(rho0))
    )


#: The definitions compared in notebook 01 (altitude range x grid x space x rho0).
FIT_DEFINITIONS = tuple(
    FitDefinition(top_km * 1e3, step_km * 1e3, space, rho0_free)
    for space in ("linear", "log")
    for rho0_free in (False, True)
    for top_km in (20, 30, 50, 86, 100)
    for step_km in (1, 5)
)

#: The literal reading of Chapter 3 B: rho0 held at the stated 1.225 kg/m^3, R^2 of the
#: densities themselves, over the whole 0-100 km of Figs 2.1 and 3.2 on a 1 km grid.
LITERAL_FIT_DEFINITION = FitDefinition(100e3, 1e3, "linear", False)


def literal_fit() -> ExponentialFit:
    """The fit under :data:`LITERAL_FIT_DEFINITION`, the one the ledger compares with the text."""
    return fit_exponential(LITERAL_FIT_DEFINITION)


def text_model_r_squared(top_m: float = 100e3) -> float:
    """R^2 of the text's own model (k = 0.117 /km, rho0 = 1.225) under the literal definition,
    over 0 to ``top_m``."""
    definition = FitDefinition(top_m, LITERAL_FIT_DEFINITION.step_m, "linear", False)
    return model_r_squared(definition, TEXT_DECAY_CONSTANT_PER_M)


def fit_definition_table(definitions=FIT_DEFINITIONS):
    """A pandas table of k (1/km) and R^2 for each fit definition."""
    import pandas as pd

    rows = []
    for definition in definitions:
        fit = fit_exponential(definition)
        rows.append(
            {
                "altitudes": f"0-{definition.top_m / 1e3:g} km",
                "grid_km": definition.step_m / 1e3,
                "R2_space": definition.space,
                "rho0": "fitted" if definition.rho0_free else "1.225 fixed",
                "rho0_kg_m3": fit.surface_density_kg_m3,
                "k_per_km": fit.decay_constant_per_km,
                "R2": fit.r_squared,
            }
        )
    return pd.DataFrame(rows)
