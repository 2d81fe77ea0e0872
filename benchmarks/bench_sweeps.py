"""The sweep's speed-up from one Dask worker to two, measured in the same run (``make
benchmark``).

The work: a Monte Carlo of 3DOF flights of Chapter 4's baseline cone, its elevation drawn
uniformly in 20-85 deg from a seeded Philox stream
(:func:`harp_analysis.foundation.sweeps.sample_chunk`), flown in chunks by
:func:`harp_analysis.engines.threedof.fly_3dof`. The same sweep runs in this process and on local
clusters of one and of two worker processes (one thread each; the workers load the compiled kernels
before the timing starts). So does a sweep of idle waits, which needs no CPU: its speed-up is the
scheduling's alone, whatever else the machine is running. The reference is the sweep in this
process: the same flights, chunks and seeds, one after the other; every cluster's run must return
its apogees bit for bit (checked). Printed: the best wall time of each (interleaved rounds), the
speed-ups of two workers over one, whether every run returned the same apogees, and the load average
before the run. ``--smoke``: a few small chunks, one round, clusters of threads in this process, to
check every path.
"""

import logging
import os
import time
from contextlib import ExitStack
from functools import partial

import numpy as np
from distributed import Client
from measure import agree, interleaved_best, smoke_requested

from harp_analysis.engines import threedof
from harp_analysis.foundation import sweeps
from harp_analysis.models.launch import baseline_chapter_4

SEED = 1965
FLIGHTS, CHUNK, ROUNDS = 20_000, 1_000, 3
WAIT_S = 0.1  # an idle chunk: the speed-up of the scheduling alone
LOWEST_DEG, HIGHEST_DEG = 20.0, 85.0
BASELINE = baseline_chapter_4(45.0)


def apogees_m(seed: int, indices: range) -> np.ndarray:
    """One chunk of the Monte Carlo: the apogee altitudes (m) of its flights."""
    fractions = sweeps.sample_chunk(seed, 1, indices, method="random")[:, 0]
    elevations = LOWEST_DEG + (HIGHEST_DEG - LOWEST_DEG) * fractions
    launches = [BASELINE.but(elevation_deg=e) for e in elevations]
    return threedof.fly_3dof(launches).apogee_altitude_m


def started_client(workers: int, processes: bool = True) -> tuple[Client, float]:
    """The client of a new local cluster of ``workers`` processes (or threads of this process,
    which start in a fraction of the time) closed with the client, its workers' kernels loaded,
    and the seconds it took to get there."""
    start = time.perf_counter()
    client = Client(
        n_workers=workers,
        threads_per_worker=1,
        processes=processes,
        dashboard_address=":0",
        silence_logs=logging.ERROR,
    )
    client.run(apogees_m, SEED, range(2))  # each worker loads the compiled kernels
    return client, time.perf_counter() - start


def main(smoke: bool = False) -> None:
    logging.getLogger("distributed").setLevel(logging.ERROR)  # its closing chatter too
    load = os.getloadavg()[0]
    flights_count, chunk, rounds = (200, 50, 1) if smoke else (FLIGHTS, CHUNK, ROUNDS)
    items = sweeps.chunks(flights_count, chunk)
    work = partial(apogees_m, SEED)
    sweeps.sweep(work, items[:1], progress=False)  # this process loads the kernels too
    waits = [WAIT_S / 10 if smoke else WAIT_S] * len(items)
    with ExitStack() as open_clients:
        started, flights, idle = {}, {}, {}
        for workers in (0, 1, 2):
            client = None
            if workers:
                client, started[workers] = started_client(workers, processes=not smoke)
                open_clients.enter_context(client)
            name = f"Dask, {workers} worker{'s' * (workers > 1)}" if workers else "in process"
            flights[name] = partial(sweeps.sweep, work, items, client=client, progress=False)
            idle[name] = partial(sweeps.sweep, time.sleep, waits, client=client, progress=False)
        results = {name: np.concatenate(run()) for name, run in flights.items()}
        times = interleaved_best(flights, rounds=rounds)
        idle_times = interleaved_best(idle, rounds=rounds)

    reference = results["in process"]
    for name, apogees in results.items():
        agree(f"{name}'s apogees against the sweep in process", apogees - reference, 0.0)
    print(
        f"sweep: {flights_count:,} 3DOF flights of the baseline cone, elevation uniform in "
        f"{LOWEST_DEG:g}-{HIGHEST_DEG:g} deg (Philox), {len(items)} chunks of {chunk:,}; "
        f"and {len(items)} idle waits of {waits[0]:g} s (no CPU: the scheduling alone). "
        "Reference: the same sweep in this process"
    )
    print(
        f"best of {rounds} interleaved rounds on {os.cpu_count()} cores, load average "
        f"{load:.1f} before the run (another process's load slows the flights)"
    )
    print(f"{'':16} {'flights (s)':>12} {'flights/s':>10} {'same apogees':>13} {'waits (s)':>10}")
    for name, seconds in times.items():
        same = "yes" if np.array_equal(results[name], reference) else "NO"
        print(
            f"{name:16} {seconds:>12.2f} {flights_count / seconds:>10,.0f} {same:>13} "
            f"{idle_times[name]:>10.2f}"
        )
    one, two = "Dask, 1 worker", "Dask, 2 workers"
    print(
        f"speed-up, two workers over one: flights {times[one] / times[two]:.2f}x, "
        f"waits {idle_times[one] / idle_times[two]:.2f}x (ideal 2x; the flights need two idle "
        "cores)"
    )
    print(
        "cluster start, kernels loaded: "
        + ", ".join(f"{workers} worker(s) {seconds:.1f} s" for workers, seconds in started.items())
    )
    print(f"mean apogee {reference.mean() / 1e3:.2f} km over {reference.size:,} flights")


if __name__ == "__main__":
    main(smoke=smoke_requested())
