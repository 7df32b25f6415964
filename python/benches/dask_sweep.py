"""Throughput of a sweep through the package: raceway.sweep (threads) against
raceway.dask.sweep (a LocalCluster of worker processes), same sweep, one run.

    python python/benches/dask_sweep.py [SWEEP.toml] [--workers 2]

Prints, for each executor, the points, the CPU time of the processes that computed them
(getrusage: user + system of this process for the threads, of the worker processes for
Dask; every thread, so the scene checks, summaries and row files count too), the runs' own
thread CPU time (the table's cpu_s column), the wall time, points per CPU second and per wall
second, and the load average. Wall-time ratios are only comparable within one run of this
script.
"""

import argparse
import os
import resource
import time

import raceway
import raceway.dask


def cpu_s():
    """CPU time of this process (all its threads), s."""
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def report(name, table, cpu, wall):
    n = len(table)
    print(
        f"{name:<28} {n:5d} points  {cpu:7.3f} s process CPU  "
        f"{table['cpu_s'].sum():6.3f} s in the runs  {wall:7.3f} s wall  "
        f"{n / cpu:6.1f} points/CPU s  {n / wall:6.1f} points/wall s  "
        f"load average {os.getloadavg()[0]:.1f}"
    )


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("sweep", nargs="?", default="examples/sweeps/bench-qs-1000.toml")
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args()
    from distributed import Client, LocalCluster

    for jobs in (1, a.workers):
        t, c = time.perf_counter(), cpu_s()
        table = raceway.sweep(a.sweep, jobs=jobs)
        report(f"raceway.sweep jobs={jobs}", table, cpu_s() - c, time.perf_counter() - t)
    with LocalCluster(
        n_workers=a.workers, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, Client(cluster) as client:
        c0 = sum(client.run(cpu_s).values())
        t = time.perf_counter()
        table = raceway.dask.sweep(a.sweep, client)
        wall = time.perf_counter() - t
        cpu = sum(client.run(cpu_s).values()) - c0
        report(f"raceway.dask.sweep workers={a.workers}", table, cpu, wall)


if __name__ == "__main__":
    main()
