"""What every benchmark measures with: best times (interleaved, so a busy machine slows every
case alike), peak memory, a target's verdict, the cold start of a fresh process, the wall and
CPU time of a command (:func:`run_timed`), and the check that a reference computes what the
package does (every benchmark's smoke mode asserts it)."""

import math
import os
import resource
import subprocess
import sys
import tempfile
import time
import tracemalloc

import numpy as np


def interleaved_best(functions: dict, rounds: int = 5, number: int = 1) -> dict:
    """Best time (s) per call of each function over ``rounds`` rounds that call each in turn,
    ``number`` times in a row."""
    best = dict.fromkeys(functions, math.inf)
    for _ in range(rounds):
        for name, function in functions.items():
            start = time.perf_counter()
            for _ in range(number):
                function()
            best[name] = min(best[name], (time.perf_counter() - start) / number)
    return best


def best_of(function, repeat: int = 5, number: int = 1) -> float:
    """Best of ``repeat`` timings of ``number`` calls of ``function``, per call (s)."""
    return interleaved_best({"": function}, repeat, number)[""]


def peak_memory_bytes(function) -> int:
    """The peak of the memory allocated while ``function`` runs, as tracemalloc sees it: Python's
    and numpy's, not what compiled kernels allocate themselves (their arrays, scratch)."""
    tracemalloc.start()
    function()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak


def verdict(value: float, target: float) -> str:
    return "met" if value <= target else f"missed by {value / target:.2f}x"


def run_timed(command: list[str], **keywords) -> tuple[subprocess.CompletedProcess, float, float]:
    """``subprocess.run(command, **keywords)``, its wall seconds, and the CPU seconds of every
    process it ran (user and system)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    completed = subprocess.run(command, **keywords)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return completed, wall, cpu


def cold_start_s(code: str) -> float:
    """Seconds that ``code`` (which prints them last) takes in a fresh process whose compiled
    kernels start from an empty cache."""
    with tempfile.TemporaryDirectory() as empty:
        env = dict(os.environ, HARP_ANALYSIS_KERNEL_CACHE=empty)
        result = subprocess.run(
            [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=False
        )
    if result.returncode:
        raise RuntimeError(f"the cold-start process failed:\n{result.stderr}")
    return float(result.stdout.split()[-1])


def agree(what: str, difference, tolerance: float) -> float:
    """The largest magnitude of ``difference`` (a number or an array), or AssertionError naming
    ``what`` if it exceeds ``tolerance`` or is not finite: a benchmark's reference must compute
    what the package computes, to a stated accuracy."""
    largest = float(np.max(np.abs(difference)))
    if not largest <= tolerance:
        raise AssertionError(f"{what}: differs by {largest:.3g}, beyond {tolerance:.3g}")
    return largest


def smoke_requested() -> bool:
    """Whether the command line asks for the smoke mode (``--smoke``): tiny sizes, one round,
    no cold start, the references' agreement checked."""
    return "--smoke" in sys.argv[1:]
