#!/usr/bin/env python3
"""How a parameter sweep scales: the same grid with 1 and 2 local worker processes and on a
2-worker Dask LocalCluster, in one run; prints a table of wall times (median of 3) and speed-ups
against 1 local worker.

Run from the repository root after `cargo build --release && target/release/friction-fmu build`:

    .venv/bin/python benches/sweep_scaling.py [--repeats 3] [--periods 150]

The grid is Fig. 8's (`python -m friction_fmu.sweep --preset fig8`: 6 vd x 6 va x 2 f = 72
points), each run `--periods` vibration periods long at tolerance 1e-10 (the preset's and the
FMU's default 1e-8 make runs too short to time). A sweep's wall time counts everything the user
waits for: starting the process pool (or connecting to the already running cluster), shipping
the FMU, every point, collecting the rows. "run" is the sum of the points' own wall times and
"CPU" the sum of their CPU times: the serial work, whatever the executor; when run exceeds CPU,
the workers waited for a core (the machine was busy with other processes too); "cores used" is
CPU / wall time. The setups take turns, repeat after repeat.
"""
import argparse
import os
import pathlib
import statistics
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

from friction_fmu.grid import Span  # noqa: E402
from friction_fmu.presets import PRESETS  # noqa: E402
from friction_fmu.sweep import run_sweep  # noqa: E402


def once(fmu, plan, executor):
    rows, summary = run_sweep(fmu, plan, progress=False, **executor)
    assert summary["failed"] == 0, [r["message"] for r in rows if r["status"] != "ok"]
    return (summary["wall_time_s"], sum(r["wall_time_s"] for r in rows),
            sum(r["cpu_time_s"] for r in rows), len(rows))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--periods", type=float, default=150.0)
    args = parser.parse_args()

    preset = PRESETS["fig8"]
    plan = preset["plan"]()
    plan.fixed["tolerance"] = 1e-10
    plan.fixed["initial"] = "sliding"  # a fixed workload: the transient, periods as asked
    plan.stop_time = Span(args.periods, "f")
    fmu = preset["fmu"]
    load = os.getloadavg()[0]

    from distributed import LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster:
        setups = [("local processes", 1, {"workers": 1}),
                  ("local processes", 2, {"workers": 2}),
                  ("Dask LocalCluster", 2, {"scheduler": cluster})]
        # round-robin, so a change in the machine's other load falls on every setup alike
        samples = {name_workers[:2]: [] for name_workers in setups}
        for _ in range(args.repeats):
            for name, workers, executor in setups:
                samples[name, workers].append(once(fmu, plan, executor))

    medians = {k: [statistics.median(x) for x in zip(*v)] for k, v in samples.items()}
    base = medians["local processes", 1][0]
    print(f"\n{os.cpu_count()} cores, load average {load:.2f} before, "
          f"{os.getloadavg()[0]:.2f} after; "
          f"grid of Fig. 8, {args.periods:g} periods per point; median of {args.repeats}\n")
    print("| points | executor | workers | wall time (s) | run (s) | CPU (s) | cores used "
          "| speed-up |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|")
    for (name, workers), (wall, run, cpu, points) in medians.items():
        print(f"| {points:.0f} | {name} | {workers} | {wall:.2f} | {run:.2f} | {cpu:.2f} "
              f"| {cpu / wall:.2f} | {base / wall:.2f}x |")


if __name__ == "__main__":
    main()
