"""The bad-input suite (issue 25, item 5): every public entry point, given NaN, infinities,
negative, zero and huge numbers, strings, lists, None, wrong types and values outside a model's
validity, answers with an error naming the argument, a warning naming the reason, or a correct
result: never a silent wrong answer, an obscure error or a hang.

The probes run in one child process (``python tests/test_bad_inputs.py --child START``) whose
address space is capped (``RLIMIT_AS``): a probe that tries to allocate without bound fails
there as a MemoryError, never on the machine. Each probe has ``PROBE_SECONDS`` of wall time
(``signal.alarm``, for Python loops) and a few more before ``faulthandler`` ends the child (for
compiled loops, which no signal interrupts); the parent then records the probe as a hang and
starts a new child from the next one. Each probe's outcome is then one test here.

An outcome is judged by its kind:

- ``Err(pattern)``: a ``ValueError`` or ``TypeError`` (or a subclass, such as ``HarpDataError``),
  an ``IndexError`` for an index or an ``OSError`` for a file, whose message matches ``pattern``,
  which names the argument in the caller's words (a bare ``KeyError`` never counts);
- ``Warned(pattern)``: a warning (``UserWarning`` or a subclass) or such an error matching
  ``pattern``: the input is legal but outside a model's validity, refused or flagged by name;
- ``Ok(check)``: a result for which the expression ``check`` (on ``r``) is true.
"""

# ruff: noqa: E501  (the probe table keeps one probe a line)
from __future__ import annotations

import json
import os
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from harp_analysis.models.atmosphere import ATMOSPHERE_NAMES, get_atmosphere
from harp_analysis.models.launch import BOUNDS, Launch
from harp_analysis.models.projectiles import BASELINE

PROBE_SECONDS = 10  # wall time a probe may take (the slowest correct one takes ~2 s)
_BACKSTOP_SECONDS = 5  # then faulthandler ends the child
_ADDRESS_SPACE_SPARE = 3 * 2**30  # bytes the child may map beyond what its imports took


@dataclass(frozen=True)
class Err:
    pattern: str


@dataclass(frozen=True)
class Warned:
    pattern: str


@dataclass(frozen=True)
class Ok:
    check: str


# The names every probe may use (evaluated in the child).
SETUP = """
import itertools, math
import numpy as np
from harp_analysis.analyses import (
    comparisons,
    error_budget,
    mks_improvement,
    mlt_validation,
    scenarios,
)
from harp_analysis.analyses.fire_control import firing
from harp_analysis.analyses.harp import apogees, appendices, confidence, rounds
from harp_analysis.engines import eci, mks, mks_improved, mlt, sixdof, threedof
from harp_analysis.foundation import sweeps
from harp_analysis.models import atmosphere, projectiles
from harp_analysis.reporting import explorer, registry
from harp_analysis.models.launch import (
    HP_CHAPTER_2,
    LP_CHAPTER_2,
    Launch,
    Launches,
    baseline_chapter_4,
)
from harp_analysis.models.projectiles import BASELINE, HP, LP
nan, inf = math.nan, math.inf
B45 = baseline_chapter_4(45.0)
HP50 = HP_CHAPTER_2.but(cross_wind_m_s=0.0)
GUN, TARGET = firing.barbados_case()
# compiled before any probe runs: an alarm must never interrupt a compiler
from harp_analysis.analyses.fire_control import solver
for warm in (mks, mks_improved, solver, sixdof, mlt):
    warm.warm_up()
threedof.fly_3dof(B45), threedof.fly_3dof(HP_CHAPTER_2), threedof.fly_3dof(GUN)
firing.firing_solutions(GUN, TARGET)
"""

# fmt: off
PROBES: dict[str, tuple[str, Err | Warned | Ok]] = {
    # --- Launch and Launches: every field checked at construction -------------------------
    "launch speed nan": ("Launch(BASELINE, nan, 45.0)", Err("speed_m_s must be finite")),
    "launch speed inf": ("Launch(BASELINE, inf, 45.0)", Err("speed_m_s must be finite")),
    "launch speed negative": ("Launch(BASELINE, -1.0, 45.0)", Err(r"speed_m_s must lie in")),
    "launch speed zero": ("Launch(BASELINE, 0.0, 45.0)", Err(r"speed_m_s must lie in")),
    "launch speed huge": ("Launch(BASELINE, 1e9, 45.0)", Err("speed_m_s must lie in")),
    "launch speed string": ("Launch(BASELINE, '2157', 45.0)", Err("speed_m_s must be a real number")),
    "launch speed list": ("Launch(BASELINE, [2157.0], 45.0)", Err("speed_m_s must be a real number")),
    "launch speed None": ("Launch(BASELINE, None, 45.0)", Err("speed_m_s must be a real number")),
    "launch speed bool": ("Launch(BASELINE, True, 45.0)", Err("speed_m_s must be a real number")),
    "launch elevation zero": ("Launch(BASELINE, 2157.0, 0.0)", Err(r"elevation_deg must lie in \(0, 90\]")),
    "launch elevation above 90": ("Launch(BASELINE, 2157.0, 91.0)", Err("elevation_deg must lie in")),
    "launch bearing 360": ("Launch(BASELINE, 2157.0, 45.0, bearing_deg=360.0)", Err("bearing_deg must lie in")),
    "launch latitude 91": ("Launch(BASELINE, 2157.0, 45.0, latitude_deg=91.0)", Err("latitude_deg must lie in")),
    "launch altitude huge": ("Launch(BASELINE, 2157.0, 45.0, site_altitude_m=1e6)", Err("site_altitude_m must lie in")),
    "launch wind nan": ("Launch(BASELINE, 2157.0, 45.0, cross_wind_m_s=nan)", Err("cross_wind_m_s must be finite")),
    "launch spin huge": ("Launch(HP, 2022.0, 50.0, spin_rad_s=1e300)", Err("spin_rad_s must lie in")),
    "launch rotation huge": ("Launch(BASELINE, 2157.0, 45.0, rotation_rate_rad_s=1.0)", Err("rotation_rate_rad_s must lie in")),
    "launch density change -1": ("Launch(BASELINE, 2157.0, 45.0, density_change_fraction=-1.0)", Err("density_change_fraction must lie in")),
    "launch projectile name": ("Launch('baseline', 2157.0, 45.0)", Err("projectile must be a Projectile")),
    "launch projectile None": ("Launch(None, 2157.0, 45.0)", Err("projectile must be a Projectile")),
    "launch atmosphere unknown": ("Launch(BASELINE, 2157.0, 45.0, atmosphere='mars')", Err("unknown atmosphere 'mars'")),
    "launch atmosphere None": ("Launch(BASELINE, 2157.0, 45.0, atmosphere=None)", Err("atmosphere must be a name")),
    "launch vertical": ("Launch(BASELINE, 2157.0, 90.0)", Ok("r.elevation_deg == 90.0")),
    "launch but string": ("B45.but(elevation_deg='60')", Err("elevation_deg must be a real number")),
    "launch but unknown field": ("B45.but(elevation=60.0)", Err("elevation")),
    "launches nan at index": ("Launches(BASELINE, [2157.0, nan], 45.0)", Err(r"speed_m_s\[1\]|speed_m_s must be finite.*index")),
    "launches empty": ("Launches(BASELINE, [], 45.0)", Err("at least one launch")),
    "launches 2-D": ("Launches(BASELINE, [[2157.0, 2000.0]], 45.0)", Err("1-D")),
    "launches lengths differ": ("Launches(BASELINE, [2157.0, 2000.0], [45.0, 50.0, 55.0])", Err("share one length")),
    "launches strings": ("Launches(BASELINE, ['2157'], 45.0)", Err("speed_m_s must be a real number")),
    "launches from mixed": ("Launches.from_launches([B45, HP_CHAPTER_2])", Err(r"launches\[1\]\.projectile")),
    "launches from string": ("Launches.from_launches('B45')", Err("launches must be a Launch")),
    "launches index out": ("Launches(BASELINE, [2157.0, 2000.0], 45.0)[5]", Err("launch 5 of 2")),
    # --- projectiles ----------------------------------------------------------------------
    "projectile unknown": ("projectiles.get_projectile('XX')", Err("unknown projectile 'XX'")),
    "projectile None": ("projectiles.get_projectile(None)", Err("projectile")),
    "projectile list": ("projectiles.get_projectile(['HP'])", Err("projectile")),
    "projectile mass negative": ("projectiles.Projectile('p', -1.0, 0.01, BASELINE.drag_law, 2000.0, 's')", Err("mass_kg must lie in")),
    "projectile area string": ("projectiles.Projectile('p', 10.0, '0.01', BASELINE.drag_law, 2000.0, 's')", Err("reference_area_m2 must be a real number")),
    "projectile drag law": ("projectiles.Projectile('p', 10.0, 0.01, 0.3, 2000.0, 's')", Err("drag_law must be a drag law")),
    "rigid body of baseline": ("projectiles.check_rigid_body(BASELINE, 'the 6DOF')", Err("has no aero")),
    # --- atmosphere ---------------------------------------------------------------------------
    "density string": ("atmosphere.standard_density('10000')", Err("altitude_m must be a real number")),
    "density nan": ("atmosphere.standard_density(nan)", Err("altitude_m must be finite")),
    "density negative": ("atmosphere.standard_density(-1.0)", Err("altitude_m must lie in")),
    "density above table": ("atmosphere.standard_density(2e6)", Err("altitude_m must lie in")),
    "density None in list": ("atmosphere.standard_density([0.0, None])", Err("altitude_m must be a real number")),
    "density None": ("atmosphere.standard_density(None)", Err("altitude_m must be a real number")),
    "density list": ("atmosphere.standard_density([0.0, 1e4])", Ok("abs(r[0] - 1.225) < 1e-3 and 0.4 < r[1] < 0.42")),
    "sound above 86 km": ("atmosphere.standard_speed_of_sound(90e3)", Err("altitude_m must lie in")),
    "two segment inf": ("atmosphere.two_segment_density(inf)", Err("altitude_m must be finite")),
    "three layer string": ("atmosphere.three_layer_speed_of_sound('1')", Err("altitude_m must be a real number")),
    "exponential k zero": ("atmosphere.exponential_density(0.0, decay_constant_per_m=0.0)", Err("decay_constant_per_m must lie in")),
    "exponential k string": ("atmosphere.exponential_density(0.0, decay_constant_per_m='1e-4')", Err("decay_constant_per_m must be a real number")),
    "exponential rho0 negative": ("atmosphere.exponential_density(0.0, surface_density_kg_m3=-1.0)", Err("surface_density_kg_m3 must lie in")),
    "atmosphere unknown": ("atmosphere.get_atmosphere('mars')", Err("unknown atmosphere 'mars'")),
    "atmosphere list": ("atmosphere.get_atmosphere(['us1976'])", Err("atmosphere")),
    "ceiling step tiny": ("atmosphere.agreement_ceiling('two_segment', 0.1, step_m=1e-9)", Err("step_m = 1e-09 m makes more than")),
    "ceiling tolerance nan": ("atmosphere.agreement_ceiling('two_segment', nan)", Err("relative_tolerance must be finite")),
    "ceiling atmosphere": ("atmosphere.agreement_ceiling('venus', 0.1)", Err("unknown atmosphere 'venus'")),
    "fit definition step": ("atmosphere.FitDefinition(50e3, 1e-6, 'log')", Err("step_m = 1e-06 m makes more than")),
    "model density string": ("atmosphere.get_atmosphere('us1976').density('5')", Err("altitude_m must be a real number")),
    # --- the 3DOF -----------------------------------------------------------------------------
    "3dof launch string": ("threedof.fly_3dof('HP')", Err("launches must be a Launch")),
    "3dof rtol zero": ("threedof.fly_3dof(B45, rtol=0.0)", Err("rtol")),
    "3dof rtol string": ("threedof.fly_3dof(B45, rtol='1e-9')", Err("rtol")),
    "3dof max time nan": ("threedof.fly_3dof(B45, max_time_s=nan)", Err("max_time_s")),
    "3dof max time negative": ("threedof.fly_3dof(B45, max_time_s=-1.0)", Err("max_time_s")),
    "3dof end altitude string": ("threedof.fly_3dof(B45, end_altitude_m='0')", Err("end_altitude_m")),
    "3dof end altitude underground": ("threedof.fly_3dof(B45, end_altitude_m=-150e3)", Err(r"end_altitude_m must lie in \[-500, inf\] m")),
    "3dof end above the apogee": ("threedof.fly_3dof(B45, end_altitude_m=500e3)", Warned(r"never comes down through end_altitude_m = 500 km \(its apogee: 10\d\.\d km\)")),
    "3dof end above the apogee lands": (
        "threedof.fly_3dof(B45, end_altitude_m=500e3)",
        Ok("r.stop_reason[0] == 'ground_before_end' and not r.impact[0] and abs(np.linalg.norm(r.end_position_m[:, 0]) - 6378e3) < 1e-3 and r.time_of_flight_s[0] < 400"),
    ),
    "3dof end never risen through": ("threedof.fly_3dof(B45, end_altitude_m=500e3, rising=True)", Warned("never climbs through end_altitude_m = 500 km")),
    "3dof turn at a step's end": (  # the envelope's map at 270 deg, 140 km, 65 km hung here
        "threedof.fly_3dof(GUN.but(elevation_deg=45.55003258142979, bearing_deg=269.90248245939864), end_altitude_m=65e3)",
        Warned(r"never comes down through end_altitude_m = 65 km \(its apogee: 62.11 km\)"),
    ),
    "3dof batch end above apogees": ("threedof.fly_3dof(Launches(BASELINE, 2157.0, [20.0, 45.0, 10.0]), end_altitude_m=[50e3, 50e3, 50e3])", Warned(r"2 of 3 3DOF flights never cross their end altitude \(launches 0, 2\)")),
    "3dof layings gun string": ("threedof.Layings('B45')", Err("gun must be a harp_analysis.models.launch.Launch")),
    "3dof layings rtol zero": ("threedof.Layings(B45, rtol=0.0)", Err("rtol")),
    "3dof layings elevation zero": ("threedof.Layings(B45).fly(np.array([0.0]), np.array([1.0]), 0.0, False)", Err(r"elevation_rad\[0\] must lie in \(0, pi/2\]")),
    "3dof layings elevation in deg": ("threedof.Layings(B45).fly(np.array([0.5, 45.0]), np.array([1.0, 1.0]), 0.0, False)", Err(r"elevation_rad\[1\] must lie in \(0, pi/2\]; got 45")),
    "3dof layings bearing nan": ("threedof.Layings(B45).fly(np.array([0.5]), np.array([nan]), 0.0, False)", Err("bearing_rad must be finite")),
    "3dof layings lengths": ("threedof.Layings(B45).fly(np.array([0.5, 0.6]), np.array([1.0]), 0.0, False)", Err("elevation_rad and bearing_rad must be arrays of one length")),
    "3dof layings empty": ("threedof.Layings(B45).fly(np.array([]), np.array([]), 0.0, False)", Err("elevation_rad and bearing_rad must be arrays of one length")),
    "3dof layings end string": ("threedof.Layings(B45).fly(np.array([0.5]), np.array([1.0]), '0', False)", Err("end_altitude_m")),
    "3dof layings rising string": ("threedof.Layings(B45).fly(np.array([0.5]), np.array([1.0]), 0.0, 'yes')", Err("rising must be True, False")),
    "3dof layings end never crossed": (
        "threedof.Layings(B45).fly(np.array([0.5]), np.array([1.0]), 500e3, True)",
        Ok("not r.impact[0] and r.stop_reason[0] == 'ground_before_end'"),
    ),
    "3dof layings is fly_3dof": (
        "threedof.Layings(B45).fly(np.radians([30.0, 60.0]), np.radians([10.0, 200.0]), [20e3, 30e3], np.array([True, False]))",
        Ok("all((r.range_m[i], r.time_of_flight_s[i]) == (f.range_m[0], f.time_of_flight_s[0]) for i, f in enumerate([threedof.fly_3dof(B45.but(elevation_deg=30.0, bearing_deg=10.0), end_altitude_m=20e3, rising=True), threedof.fly_3dof(B45.but(elevation_deg=60.0, bearing_deg=200.0), end_altitude_m=30e3)]))"),
    ),
    "3dof output step zero": ("threedof.simulate_3dof(B45, output_step_s=0.0)", Err("output_step_s")),
    "3dof output step tiny": ("threedof.simulate_3dof(B45, output_step_s=1e-9)", Err("output_step_s")),
    "3dof batch string": ("threedof.simulate_3dof_batch('B45')", Err("launches")),
    "3dof at 0.01 deg": (
        "threedof.simulate_3dof(B45.but(elevation_deg=0.01))",
        Ok("r.altitude_m.min() > -1.0 and r.attrs['range_m'] < 1e3"),
    ),
    "3dof at 45 deg": ("threedof.fly_3dof(B45)", Ok("100e3 < r.apogee_altitude_m[0] < 200e3")),
    # --- the 6DOF -----------------------------------------------------------------------------
    "6dof baseline": ("sixdof.simulate_6dof(B45)", Err("has no aero")),
    "6dof launch string": ("sixdof.simulate_6dof('HP')", Err("launch")),
    "6dof density altitude": ("sixdof.simulate_6dof(HP_CHAPTER_2, density_altitude='round')", Err("density_altitude")),
    "6dof output step zero": ("sixdof.simulate_6dof(HP_CHAPTER_2, output_step_s=0.0)", Err("output_step_s")),
    "6dof output step tiny": ("sixdof.simulate_6dof(HP_CHAPTER_2, output_step_s=1e-9)", Err("output_step_s")),
    "6dof max time nan": ("sixdof.simulate_6dof(HP_CHAPTER_2, max_time_s=nan)", Err("max_time_s")),
    "6dof rtol string": ("sixdof.simulate_6dof(HP_CHAPTER_2, rtol='1e-9')", Err("rtol")),
    # --- Modified Linear Theory -----------------------------------------------------------
    "mlt segment zero": ("mlt.simulate_mlt(HP_CHAPTER_2, segment_length_m=0.0)", Err("segment_length_m")),
    "mlt segment nan": ("mlt.simulate_mlt(HP_CHAPTER_2, segment_length_m=nan)", Err("segment_length_m")),
    "mlt segment string": ("mlt.simulate_mlt(HP_CHAPTER_2, segment_length_m='500')", Err("segment_length_m")),
    "mlt segment huge": ("mlt.simulate_mlt(HP_CHAPTER_2, segment_length_m=1e9)", Err("segment_length_m")),
    "mlt segment 1 mm": ("mlt.simulate_mlt(HP_CHAPTER_2, segment_length_m=1e-3)", Err("segment_length_m")),
    "mlt coefficients at": ("mlt.simulate_mlt(HP_CHAPTER_2, coefficients_at='end')", Err("coefficients_at")),
    "mlt gravity": ("mlt.simulate_mlt(HP_CHAPTER_2, gravity='flat earth')", Err("gravity")),
    "mlt baseline": ("mlt.simulate_mlt(B45)", Err("has no aero")),
    "mlt HP 70 deg": ("mlt.simulate_mlt(HP50.but(elevation_deg=70.0))", Warned("MLT|re-entry|valid")),
    "mlt LP 80 deg": ("mlt.simulate_mlt(LP_CHAPTER_2.but(cross_wind_m_s=0.0, elevation_deg=80.0))", Warned("MLT|re-entry|valid")),
    # --- the MKS ------------------------------------------------------------------------------
    "mks n_terms string": ("mks.for_launch(B45, n_terms='3')", Err("n_terms")),
    "mks n_terms zero": ("mks.for_launch(B45, n_terms=0)", Err("n_terms")),
    "mks n_terms fraction": ("mks.for_launch(B45, n_terms=2.5)", Err("n_terms")),
    "mks n_terms nan": ("mks.for_launch(B45, n_terms=nan)", Err("n_terms")),
    "mks n_terms huge": ("mks.for_launch(B45, n_terms=10**9)", Err("n_terms")),
    "mks n_terms list": ("mks.for_launch(B45, n_terms=[3])", Err("n_terms")),
    "mks decay zero": ("mks.for_launch(B45, decay_constant_per_m=0.0)", Err("decay_constant_per_m")),
    "mks decay string": ("mks.for_launch(B45, decay_constant_per_m='1e-4')", Err("decay_constant_per_m")),
    "mks launch string": ("mks.for_launch('B45')", Err("launch")),
    "mks n_points one": ("mks.simulate_mks(B45, n_points=1)", Err("n_points")),
    "mks n_points huge": ("mks.simulate_mks(B45, n_points=10**12)", Err("n_points")),
    "mks n_points string": ("mks.simulate_mks(B45, n_points='400')", Err("n_points")),
    "mks above escape speed": ("mks.for_launch(B45.but(speed_m_s=15e3))", Warned("escape orbit")),
    "mks at 45 deg": ("mks.for_launch(B45, warn=False).apogee_altitude()", Ok("100e3 < r < 200e3")),
    # --- the improved MKS and the ECI MKS -------------------------------------------------
    "improved launch string": ("mks_improved.solve('B45')", Err("launch")),
    "improved n_terms string": ("mks_improved.solve(B45, n_terms='3')", Err("n_terms")),
    "improved calibration": ("mks_improved.solve(B45, calibration=2.0)", Err("calibration")),
    "improved fire-control gun": (
        "mks_improved.solve(firing.BARBADOS_HP.but(elevation_deg=30.845228653704602, "
        "bearing_deg=269.9255856283873))",
        Warned("improved MKS"),
    ),
    "eci model unknown": ("eci.correction_for_launch(B45, model='flat')", Err("unknown model 'flat'")),
    "eci model list": ("eci.correction_for_launch(B45, model=['consistent'])", Err("model")),
    "eci n_terms string": ("eci.correction_for_launch(B45).solution(n_terms='3')", Err("n_terms")),
    "eci launch string": ("eci.correction_for_launch('B45')", Err("launch")),
    "eci mass negative": ("eci.correction_for_launch(B45, mass_kg=-1.0)", Err("mass_kg must lie in")),
    "eci density nan": ("eci.correction_for_launch(B45, surface_density_kg_m3=nan)", Err("surface_density_kg_m3 must be finite")),
    "eci table times unsorted": ("eci.simulate_eci_mks(B45, times_s=[5.0, 1.0])", Err("times_s must be sorted")),
    "eci table times nan": ("eci.simulate_eci_mks(B45, times_s=[nan])", Err("times_s must be finite")),
    "eci table times string": ("eci.simulate_eci_mks(B45, times_s='1')", Err("times_s must be a real number")),
    "eci table points": ("eci.simulate_eci_mks(B45, n_points=10**12)", Err("n_points")),
    "eci table launches": ("eci.simulate_eci_mks(Launches(BASELINE, 2157.0, [45.0, 50.0]))", Err("launch must be a Launch")),
    "eci table flies": ("eci.simulate_eci_mks(B45, times_s=[1e9])", Ok("len(r) == 1 and r.attrs['stop_reason'] == 'impact'")),
    "harp round mass string": ("apogees.round_corrections('yuma', 1800.0, 'heavy', 2.8e-3)", Err("mass_kg must be a real number")),
    "harp round site": ("apogees.round_corrections('mars', 1800.0, 84.0, 2.8e-3)", Err("unknown site 'mars'")),
    # --- fire control -------------------------------------------------------------------------
    "target latitude nan": ("firing.TargetPoint(nan, 0.0)", Err("latitude_deg must be finite")),
    "target latitude string": ("firing.TargetPoint('13', 0.0)", Err("latitude_deg must be a real number")),
    "target altitude negative": ("firing.TargetPoint(13.0, -59.0, altitude_m=-1.0)", Err("altitude_m must lie in")),
    "target arrival past": ("firing.TargetPoint(13.0, -59.0, arrival_time_s=-1.0)", Err("arrival_time_s")),
    "firing target string": ("firing.firing_solutions(GUN, 'target')", Err("target")),
    "firing gun string": ("firing.firing_solutions('gun', TARGET)", Err("gun")),
    "firing branch": ("firing.firing_solutions(GUN, TARGET, branch='up')", Err("branch")),
    "firing bearing limits": ("firing.firing_solutions(GUN, TARGET, bearing_limits_deg=(nan, 10.0))", Err("bearing_limits_deg")),
    "firing empty targets": ("firing.firing_solutions(GUN, [])", Ok("r == []")),
    "firing case": ("firing.firing_solutions(GUN, TARGET)", Ok("r.low is not None or r.reason")),
    "firing target at the gun": ("firing.firing_solutions(GUN, firing.TargetPoint(GUN.latitude_deg, GUN.longitude_deg))", Ok("r.roots == [] and r.reason.startswith('the target is at the gun')")),
    "firing target above the gun": ("firing.firing_solutions(GUN, firing.TargetPoint(GUN.latitude_deg, GUN.longitude_deg, 50e3))", Ok("r.roots == [] and r.reason.startswith('the target is straight above the gun')")),
    "firing target 100 m away": ("firing.firing_solutions(GUN.but(rotation_rate_rad_s=0.0), firing.destination(GUN, 109.0, 100.0))", Ok("'0.0 km' not in r.reason and \"the target's 100 m\" in r.reason")),
    "firing target 1 m away": ("firing.firing_solutions(GUN.but(rotation_rate_rad_s=0.0), firing.destination(GUN, 109.0, 1.0))", Ok("r.roots == [] and 'nan' not in r.reason and 'km' not in r.reason")),
    # --- the error budget ---------------------------------------------------------------------
    "dispersion samples huge": ("error_budget.dispersion(B45, samples=10**12, progress=False)", Err("samples must lie in")),
    "dispersion samples one": ("error_budget.dispersion(B45, samples=1, progress=False)", Err("samples must lie in")),
    "dispersion samples string": ("error_budget.dispersion(B45, samples='64', progress=False)", Err("samples must be a whole number")),
    "dispersion chunk zero": ("error_budget.dispersion(B45, chunk=0, progress=False)", Err("chunk must lie in")),
    "dispersion seed negative": ("error_budget.dispersion(B45, samples=16, seed=-1, progress=False)", Err("seed")),
    "dispersion method": ("error_budget.dispersion(B45, samples=16, method='latin', progress=False)", Err("method")),
    "dispersion uncertainty": ("error_budget.dispersion(B45, ('elevation',), progress=False)", Err(r"uncertainties\[0\]")),
    "dispersion uncertainties string": ("error_budget.dispersion(B45, 'elevation', progress=False)", Err("uncertainties must be a sequence")),
    "dispersion launch string": ("error_budget.dispersion('B45', progress=False)", Err("launch must be a Launch")),
    "one at a time list": ("error_budget.one_at_a_time(B45, list(error_budget.CHAPTER_7B[:1]))", Ok("len(r) == 1")),
    "nominal launch string": ("error_budget.nominal('B45')", Err("launch must be a Launch")),
    "nominal launch list": ("error_budget.nominal([B45])", Err("launch")),
    "sensitivity samples": ("error_budget.sensitivity_indices(B45, base_samples=10**9, progress=False)", Err("base_samples must lie in")),
    "budget launches list": ("error_budget.budget_table([B45], progress=False)", Err("launches must map names")),
    "pointing name": ("error_budget.required_pointing_mrad('a howitzer')", Err("launch_name")),
    "dispersion over error output": ("error_budget.dispersion_over_model_error('range')", Err("output")),
    # --- sweeps -------------------------------------------------------------------------------
    "sweep endless": ("sweeps.sweep(abs, itertools.count(), progress=False)", Err("max_items")),
    "sweep too long": ("sweeps.sweep(abs, range(10**7), progress=False)", Err("max_items")),
    "sweep not iterable": ("sweeps.sweep(abs, 5)", Err("items must be iterable")),
    "sweep not callable": ("sweeps.sweep(3, [1])", Err("function must be callable")),
    "sweep window string": ("sweeps.sweep(abs, [1], window='2')", Err("window")),
    "sweep client": ("sweeps.sweep(abs, [1], client=object())", Err("client must be a Dask client")),
    "chunks huge": ("sweeps.chunks(10**12, 1)", Err("count|max_items")),
    "chunks string": ("sweeps.chunks('10', 2)", Err("count must be a whole number")),
    "sample chunk huge": ("sweeps.sample_chunk(0, 2, range(10**12))", Err("indices|points")),
    "sample chunk dimensions huge": ("sweeps.sample_chunk(0, 10**9, range(10))", Err("dimensions|points")),
    "sample chunk method": ("sweeps.sample_chunk(0, 2, range(4), method='halton')", Err("method")),
    # --- the HARP data ------------------------------------------------------------------------
    "appendix site": ("appendices.load_appendix('mars')", Err("unknown site 'mars'")),
    "appendix site None": ("appendices.load_appendix(None)", Err("site")),
    "appendix site list": ("appendices.load_appendix(['yuma'])", Err("site")),
    "appendix missing file": ("appendices.load_appendix('yuma', path='/nonexistent/e.tsv')", Err("/nonexistent/e.tsv")),
    "appendix path number": ("appendices.load_appendix('yuma', path=5)", Err("path")),
    "speeds site": ("appendices.load_muzzle_speeds('mars')", Err("unknown site 'mars'")),
    "barbados loads": ("appendices.load_barbados()", Ok("len(r) == 23 and r.duplicate_of_earlier_row.sum() == 1")),
    "predicted model": ("apogees.predicted_apogees('yuma', model='flat')", Err("unknown model 'flat'")),
    "predicted drag area nan": ("apogees.predicted_apogees('yuma', drag_area=nan)", Err("drag_area must be finite")),
    "predicted drag area negative": ("apogees.predicted_apogees('yuma', drag_area=-1.0)", Err("drag_area must lie in")),
    "predicted drag area string": ("apogees.predicted_apogees('yuma', drag_area='0.003')", Err("drag_area must be a real number")),
    "predicted drag area list": ("apogees.predicted_apogees('yuma', drag_area=[0.003])", Err("drag_area must be a real number")),
    "drag area model list": ("apogees.drag_area_m2(['dissertation'])", Err("model")),
    "drag area model": ("apogees.drag_area_m2('flat')", Err("unknown model 'flat'")),
    "residual statistic": ("apogees.residual_statistic('yuma', 'median')", Err("statistic")),
    "martlet mass": ("apogees.martlet(-1.0, 1800.0)", Err("mass_kg")),
    "round trajectory round": ("rounds.round_trajectory('barbados', 999)", Err("round 999 is not in")),
    "round trajectory fraction": ("rounds.round_trajectory('barbados', 181.7)", Err("round_number")),
    "round trajectory string": ("rounds.round_trajectory('barbados', '181')", Err("round_number")),
    "round trajectory points": ("rounds.round_trajectory('barbados', 181, n_points=10**12)", Err("n_points")),
    "round trajectory site": ("rounds.round_trajectory('mars', 181)", Err("unknown site 'mars'")),
    "radar track round": ("rounds.load_radar_track('barbados', '181')", Err("round_number")),
    "splash range model": ("rounds.splash_range_km(model='flat')", Err("unknown model 'flat'")),
    "splash error round": ("rounds.splash_error(999)", Err("round_number 999 has no observed splash")),
    "splash error list": ("rounds.splash_error([181])", Err("round_number")),
    "column agreement site": ("apogees.column_agreement('mars')", Err("unknown site 'mars'")),
    # --- HARP with confidence -------------------------------------------------------------
    "bootstrap resamples huge": ("confidence.bootstrap_interval([1.0, 2.0, 4.0], resamples=10**12)", Err("resamples must lie in")),
    "bootstrap resamples few": ("confidence.bootstrap_interval([1.0, 2.0, 4.0], resamples=3)", Err("resamples must lie in")),
    "bootstrap confidence string": ("confidence.bootstrap_interval([1.0, 2.0, 4.0], confidence='0.9')", Err("confidence must be a real number")),
    "bootstrap sample strings": ("confidence.bootstrap_interval(['1', '2', '4'])", Err("sample")),
    "bootstrap sample short": ("confidence.bootstrap_interval([1.0, 2.0])", Err("sample must be 1-D with at least 3")),
    "bootstrap statistic": ("confidence.bootstrap_interval([1.0, 2.0, 4.0], 'median')", Err("statistic")),
    "residual intervals site": ("confidence.residual_intervals('mars')", Err("unknown site 'mars'")),
    "quantisation step negative": ("confidence.uniform_quantisation_std(-1.0)", Err("step must lie in")),
    "scatter budget std negative": ("confidence.scatter_budget('yuma', speed_std_m_s=-1.0)", Err("speed_std_m_s")),
    "surface densities": ("confidence.surface_densities_kg_m3('moon')", Err("densities")),
    # --- Chapter 4's comparisons, the improved MKS's judging, the MLT's validation --------
    "comparison projectile": ("comparisons.chapter_4_launch('XX', 45.0)", Err("unknown projectile 'XX'")),
    "comparison elevation": ("comparisons.chapter_4_launch('baseline', 95.0)", Err("elevation_deg must lie in")),
    "comparison variant": ("comparisons.error_ratio('faster')", Err("unknown variant 'faster'")),
    "comparison variant change": ("comparisons.max_error_change_km('faster')", Err("unknown variant 'faster'")),
    "comparison straighter": ("comparisons.straighter_ratio('faster')", Err("unknown variant 'faster'")),
    "comparison fly n_terms string": ("comparisons.fly(B45, n_terms='3')", Err("n_terms")),
    "comparison fly launch list": ("comparisons.fly([B45])", Err("launch")),
    "improvement earth": ("mks_improvement.judged_rms('mars')", Err("earth")),
    "mlt validation projectile": ("mlt_validation.method_comparison('XX')", Err("projectile")),
    # --- scenarios and the registry -----------------------------------------------------------
    "scenario projectile": ("scenarios.reference_launch('XX')", Err("unknown projectile 'XX'")),
    "scenario projectile list": ("scenarios.reference_launch(['HP'])", Err("projectile")),
    "scenario 3dof launch string": ("scenarios.fly_3dof('HP')", Err("launch")),
    "scenario 3dof launch list": ("scenarios.fly_3dof([HP_CHAPTER_2])", Err("launch")),
    "scenario 3dof step": ("scenarios.fly_3dof(HP_CHAPTER_2, output_step_s=-1.0)", Err("output_step_s")),
    "scenario mlt segment": ("scenarios.fly_mlt(HP_CHAPTER_2, segment_length_m=1e-3)", Err("segment_length_m")),
    "scenario 6dof density altitude": ("scenarios.fly_6dof(HP_CHAPTER_2, density_altitude=['flat'])", Err("density_altitude")),
    "scenario drag ratio": ("scenarios.drag_to_gravity_crossing_altitude_km('HP', ratio=nan)", Err("ratio")),
    "scenario loss altitude": ("scenarios.angular_momentum_loss_share_below('HP', altitude_km='20')", Err("altitude_km must be a real number")),
    "scenario gravity string": ("scenarios.launch_drag_to_gravity('HP', gravity_m_s2='9.8')", Err("gravity_m_s2 must be a real number")),
    "scenario drag to weight": ("scenarios.launch_drag_to_gravity('HP')", Ok("1.0 < r < 1e3")),
    "registry number": ("registry.get_entry('99.9')", Err("'99.9' is not in the figure registry")),
    "registry number None": ("registry.get_entry(None)", Err("number")),
    "registry figure file": ("registry.figure_file('99.9')", Err("'99.9' is not in the figure registry")),
    "registry missing file": ("registry.load_registry('/nonexistent/figures.toml')", Err("/nonexistent/figures.toml")),
    "registry loads": ("registry.get_entry('2.1')", Ok("r.number == '2.1'")),
    # --- the explorer: a model's validity said once -------------------------------------------
    "explorer beta above 0.25": ("explorer.fly(HP_CHAPTER_2)[1]", Ok("[m[:13] for m in r if 'beta' in m] == ['MKS beta = 0.']")),
    "explorer beta above 1": ("explorer.fly(baseline_chapter_4(3.0))[1]", Ok("len([m for m in r if 'beta' in m]) == 1 and any('beta' in m and 'no MKS is shown' in m for m in r)")),
}
# fmt: on


# --- the child: runs the probes from START, one JSON line per probe -------------------------------
def _outcome(expression: str, namespace: dict) -> dict:
    import warnings

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = eval(expression, namespace)
        except Exception as error:  # the outcome under test
            return {"kind": "error", "type": _lineage(type(error)), "message": str(error)}
    record = {
        "kind": "result",
        "warnings": [
            {"type": _lineage(w.category), "message": str(w.message)}
            for w in caught
            if issubclass(w.category, UserWarning)
        ],
    }
    namespace["r"] = result
    return record


def _lineage(kind: type) -> list[str]:
    """The names of ``kind`` and its bases, most derived first."""
    return [cls.__name__ for cls in kind.__mro__]


def _child(start: int) -> None:
    import faulthandler
    import resource
    import signal

    namespace: dict = {}
    exec(SETUP, namespace)
    pages = int(Path("/proc/self/statm").read_text().split()[0])
    limit = pages * os.sysconf("SC_PAGE_SIZE") + _ADDRESS_SPACE_SPARE
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

    class ProbeTimeout(BaseException):
        pass

    def alarm(signum, frame):
        raise ProbeTimeout

    signal.signal(signal.SIGALRM, alarm)
    for index, (name, (expression, expected)) in enumerate(list(PROBES.items())[start:], start):
        print(json.dumps({"start": index}), flush=True)
        faulthandler.dump_traceback_later(PROBE_SECONDS + _BACKSTOP_SECONDS, exit=True)
        signal.alarm(PROBE_SECONDS)
        try:
            record = _outcome(expression, namespace)
            if record["kind"] == "result" and isinstance(expected, Ok):
                check = eval(expected.check, namespace)
                record["check"] = bool(check)
        except ProbeTimeout:
            record = {"kind": "hang"}
        except Exception as error:  # a check that could not be evaluated
            record = {"kind": "result", "check": False, "check_error": repr(error)}
        finally:
            signal.alarm(0)
            faulthandler.cancel_dump_traceback_later()
        record.update(index=index, name=name)
        print(json.dumps(record), flush=True)


# --- the parent ---------------------------------------------------------------------------------
def _run_probes() -> dict[str, dict]:
    """Every probe's outcome, restarting the child after a probe that ended it."""
    outcomes: dict[str, dict] = {}
    names = list(PROBES)
    start = 0
    while start < len(names):
        child = subprocess.run(
            [sys.executable, __file__, "--child", str(start)],
            capture_output=True,
            text=True,
            timeout=len(names) * (PROBE_SECONDS + _BACKSTOP_SECONDS) + 120,
        )
        running = None
        for line in child.stdout.splitlines():
            record = json.loads(line)
            if set(record) == {"start"}:
                running = record["start"]
            else:
                outcomes[record["name"]] = record
                running = None
        if running is None:  # every probe from start reported
            if len(outcomes) < len(names) - start and not outcomes:
                raise RuntimeError(f"the probe child failed to start:\n{child.stderr[-3000:]}")
            break
        outcomes[names[running]] = {"kind": "hang", "stderr": child.stderr[-2000:]}
        start = running + 1
    return outcomes


@pytest.fixture(scope="module")
def outcomes() -> dict[str, dict]:
    return _run_probes()


#: What a named error may be (with a message naming the argument): a bad value or type, an
#: index out of range, a file that is not there. A bare KeyError never is.
_NAMED_ERRORS = {"ValueError", "TypeError", "IndexError", "OSError"}


def _named_error(record: dict, pattern: str) -> bool:
    import re

    return (
        record["kind"] == "error"
        and bool(set(record["type"]) & _NAMED_ERRORS)
        and "KeyError" not in record["type"]
        and re.search(pattern, record["message"]) is not None
    )


def _verdict(record: dict, expected: Err | Warned | Ok) -> str | None:
    """None if ``record`` is what ``expected`` asks; else what went wrong."""
    import re

    if record["kind"] == "hang":
        return "hang"
    if isinstance(expected, Err):
        if _named_error(record, expected.pattern):
            return None
        if record["kind"] == "error":
            return f"obscure: {record['type'][0]}: {record['message'][:300]}"
        return "silent: returned a result"
    if isinstance(expected, Warned):
        if _named_error(record, expected.pattern):
            return None
        if record["kind"] == "result" and any(
            re.search(expected.pattern, w["message"]) for w in record["warnings"]
        ):
            return None
        if record["kind"] == "error":
            return f"obscure: {record['type'][0]}: {record['message'][:300]}"
        return f"silent: no warning matching {expected.pattern!r} ({record['warnings']})"
    if record["kind"] == "error":
        return f"error where a result was due: {record['type'][0]}: {record['message'][:300]}"
    if not record.get("check"):
        return f"wrong result: {expected.check} is false {record.get('check_error', '')}"
    return None


pytestmark = pytest.mark.xdist_group("bad_inputs")  # one child for the whole table


@pytest.mark.parametrize("name", list(PROBES))
def test_probe(outcomes, name):
    expression, expected = PROBES[name]
    problem = _verdict(outcomes[name], expected)
    assert problem is None, f"{expression}: {problem}"


# --- hypothesis: any value of any kind for a Launch field or an altitude -------------------------
_ANY_VALUE = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(),
    st.text(max_size=8),
    st.none(),
    st.booleans(),
    st.lists(st.floats(-1e3, 1e3), max_size=3),
    st.complex_numbers(max_magnitude=1e3),
    st.fractions(),
    st.decimals(allow_nan=True),
    st.floats(allow_nan=True, allow_infinity=True).map(np.float64),
    st.integers(-(2**31), 2**31 - 1).map(np.int32),
)


@settings(max_examples=300, deadline=None)
@given(name=st.sampled_from(sorted(BOUNDS)), value=_ANY_VALUE)
def test_a_launch_field_is_inside_its_bounds_or_refused_by_name(name, value):
    try:
        launch = Launch(BASELINE, 2157.0, 45.0).but(**{name: value})
    except (TypeError, ValueError) as error:
        assert name in str(error)
        return
    field = getattr(launch, name)
    assert type(field) is float and BOUNDS[name].inside(field)
    assert field == float(value) and not isinstance(value, bool | str | list)


@settings(max_examples=100, deadline=None)
@given(value=_ANY_VALUE, model=st.sampled_from(ATMOSPHERE_NAMES))
@example(value=1.4963543110037574e308, model="three_layer")  # its temperature grows to overflow
def test_an_altitude_gives_a_finite_air_or_is_refused_by_name(value, model):
    atmosphere = get_atmosphere(model)
    try:
        density = atmosphere.density(value)
        sound = atmosphere.speed_of_sound(value)
    except (TypeError, ValueError) as error:
        assert "altitude_m" in str(error)
        return
    assert np.all(np.isfinite(density)) and np.all(density >= 0.0)
    assert np.all(np.isfinite(sound)) and np.all(sound > 0.0)


def test_the_verdicts_can_fail():
    """The judge itself: an obscure error, a silent result and a hang are each caught."""
    key_error = {"kind": "error", "type": ["KeyError", "LookupError"], "message": "'x'"}
    assert _verdict(key_error, Err("x")).startswith("obscure")
    assert _verdict({"kind": "result", "warnings": []}, Err("x")).startswith("silent")
    assert _verdict({"kind": "result", "warnings": []}, Warned("x")).startswith("silent")
    assert _verdict({"kind": "hang"}, Ok("True")) == "hang"
    assert _verdict({"kind": "result", "warnings": [], "check": False}, Ok("r")).startswith("wrong")
    unnamed = {"kind": "error", "type": ["ValueError"], "message": "must be finite; got nan"}
    assert _verdict(unnamed, Err("theta_rad")).startswith("obscure")


if __name__ == "__main__" and sys.argv[1:2] == ["--child"]:
    _child(int(sys.argv[2]))
elif __name__ == "__main__":  # a survey: every probe's verdict, as a table
    for probe, record in _run_probes().items():
        verdict = _verdict(record, PROBES[probe][1]) or "ok"
        print(f"{probe:40} {verdict[:150]}")
