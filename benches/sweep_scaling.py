#!/usr/bin/env python3
"""How a parameter sweep scales: the same grid with 1 and 2 local worker processes and on a
2-worker Dask LocalCluster, in one run; prints a table of wall times (median of 3) and speed-ups
against 1 local worker.

Run from the repository root after `cargo build --release && target/release/friction-fmu build`:

    .venv/bin/python benches/sweep_scaling.py [--repeats 3] [--periods 150]

The grid is Fig. 8's (`python -m friction_fmu.sweep --preset fig8`: 6 vd x 6 va x 2 f = 72
points), each run `--periods` vibration periods long at the FMU's default tolerance 1e-10 (the
preset's 1e-8 makes runs too short to time). A sweep's wall time counts everything the user
waits for: starting the process pool (or connecting to the already running cluster), shipping
the FMU, every point, collecting the rows. "work" is the sum of the points' own run times: the
serial work, whatever the executor.
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


def timed(fmu, plan, repeats, **executor):
    walls, works = [], []
    for _ in range(repeats):
        rows, summary = run_sweep(fmu, plan, progress=False, **executor)
        assert summary["failed"] == 0, [r["message"] for r in rows if r["status"] != "ok"]
        walls.append(summary["wall_time_s"])
        works.append(sum(r["wall_time_s"] for r in rows))
    return statistics.median(walls), statistics.median(works), len(rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--periods", type=float, default=150.0)
    args = parser.parse_args()

    preset = PRESETS["fig8"]
    plan = preset["plan"]()
    plan.fixed.pop("tolerance")
    plan.stop_time = Span(args.periods, "f")
    fmu = preset["fmu"]

    from distributed import LocalCluster

    results = [("local processes", 1, timed(fmu, plan, args.repeats, workers=1)),
               ("local processes", 2, timed(fmu, plan, args.repeats, workers=2))]
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster:
        results.append(("Dask LocalCluster", 2, timed(fmu, plan, args.repeats, scheduler=cluster)))

    base = results[0][2][0]
    print(f"\n{os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}; "
          f"grid of Fig. 8, {args.periods:g} periods per point; median of {args.repeats}\n")
    print("| points | executor | workers | wall time (s) | work (s) | speed-up |")
    print("|---:|---|---:|---:|---:|---:|")
    for name, workers, (wall, work, points) in results:
        print(f"| {points} | {name} | {workers} | {wall:.2f} | {work:.2f} | {base / wall:.2f}x |")


if __name__ == "__main__":
    main()
