"""Parameter sweeps through an FMU: one simulation per grid point, in parallel.

    python -m friction_fmu.sweep fmu-out/TransverseFriction.fmu \\
        --grid vd=1e-4,5e-4,2e-3 --grid va=0,1e-3,2e-3 --grid f=1e3,3e3 \\
        --set initial=sliding --output FFx_mean --stop-time 150/f --step 1/f
    python -m friction_fmu.sweep --preset fig8            # the paper's Fig. 8 grid
    python -m friction_fmu.sweep ... --scheduler tcp://host:8786   # on a Dask cluster

Points run on the local cores (a process pool, one worker per core) unless a Dask scheduler is
given; both executors get the same task, `runner.run_point`, through the same
concurrent.futures interface. Writes PREFIX.csv (one row per point), PREFIX.svg (heat map) and
PREFIX.json (what was run).
"""
import argparse
import concurrent.futures as cf
import contextlib
import csv
import json
import os
import pathlib
import sys
import time

import fmpy

from . import check, heatmap
from .grid import Output, Plan, Span, load_file, parse_assignment
from .presets import PRESETS
from .progress import Progress
from .runner import FmuSource, run_point


@contextlib.contextmanager
def local_executor(workers):
    with cf.ProcessPoolExecutor(max_workers=workers) as executor:
        yield executor, lambda source: source


@contextlib.contextmanager
def dask_executor(scheduler):
    """A Dask client's concurrent.futures executor. `scheduler` is an address
    (tcp://host:port) or a cluster object (e.g. a LocalCluster). The FMU is scattered to every
    worker once, so tasks carry only a reference to it."""
    from distributed import Client

    with Client(scheduler) as client:
        def ship(source):
            return client.scatter(source, broadcast=True)

        yield client.get_executor(pure=False), ship


def run_sweep(fmu, plan, scheduler=None, workers=None, ship=None, progress=True):
    """Runs every point of `plan`; returns the rows in grid order and a summary of the run.

    `ship` is how the FMU reaches the workers: "path" (a filesystem they share with this
    process; the default on local cores) or "bytes" (the .fmu's content; the default on Dask,
    safe on any cluster)."""
    check.plan(fmpy.read_model_description(fmu), plan)
    ship = ship or ("bytes" if scheduler is not None else "path")
    source = FmuSource.by_bytes(fmu) if ship == "bytes" else FmuSource.by_path(fmu)
    points = plan.points()
    workers = workers or os.cpu_count()
    executor_cm = dask_executor(scheduler) if scheduler is not None else local_executor(workers)
    began = time.perf_counter()
    rows = []
    with executor_cm as (executor, place):
        shipped = place(source)
        bar = Progress(len(points), enabled=progress)
        futures = [executor.submit(run_point, shipped, plan, p) for p in points]
        try:
            for future in cf.as_completed(futures):
                row = future.result()
                rows.append(row)
                bar.advance(failed=row["status"] != "ok")
        finally:
            bar.close()
    rows.sort(key=lambda r: r["point"])
    summary = {
        "fmu": os.path.abspath(fmu),
        "executor": f"dask {scheduler}" if scheduler is not None else f"local, {workers} processes",
        "ship": ship,
        "points": len(points),
        "failed": sum(r["status"] != "ok" for r in rows),
        "wall_time_s": time.perf_counter() - began,
    }
    return rows, summary


def columns(plan):
    return ["point", *plan.grid, *(o.column for o in plan.outputs), "status", "message",
            "wall_time_s"]


def write_csv(path, plan, rows):
    """Floats are written with repr, so the file holds every bit of each number."""
    with open(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=columns(plan), extrasaction="ignore")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: repr(v) if isinstance(v, float) else v for k, v in row.items()})


def units_of(fmu):
    """Unit of every variable that has one, from the modelDescription."""
    md = fmpy.read_model_description(fmu)
    units = {}
    for var in md.modelVariables:
        unit = getattr(var, "unit", None) or getattr(var.declaredType, "unit", None)
        if unit:
            units[var.name] = unit
    return units


def heatmap_units(fmu, plan):
    units = units_of(fmu)
    for output in plan.outputs:
        if output.variable in units:
            units[output.column] = units[output.variable]
    return units


def parse_args(argv):
    p = argparse.ArgumentParser(prog="python -m friction_fmu.sweep", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("fmu", nargs="?", help="the .fmu (a preset brings its own default)")
    p.add_argument("--preset", choices=sorted(PRESETS), help="a stored sweep, e.g. fig8")
    p.add_argument("--grid", action="append", default=[], metavar="NAME=V1,V2,...",
                   help="a grid axis (repeat for more axes)")
    p.add_argument("--grid-file", help="TOML or JSON with grid, set, outputs, stop_time, step")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="a fixed parameter (enumeration items by name or number)")
    p.add_argument("--output", action="append", default=[], metavar="SPEC",
                   help="NAME (value at the stop time) or NAME:mean_last=TIME (mean of the "
                        "samples in the last TIME); TIME is seconds or N/PARAM, e.g. 1/f")
    p.add_argument("--stop-time", help="seconds or N/PARAM (default: DefaultExperiment)")
    p.add_argument("--step", help="communication step, seconds or N/PARAM (default: "
                                  "DefaultExperiment)")
    p.add_argument("--workers", type=int, help="local processes (default: os.cpu_count())")
    p.add_argument("--scheduler", help="Dask scheduler address, e.g. tcp://host:8786")
    p.add_argument("--ship", choices=["bytes", "path"],
                   help="send the FMU as bytes or by path (default: path locally, bytes on Dask)")
    p.add_argument("--out", help="output prefix (default fmu-out/sweeps/sweep)")
    p.add_argument("--x", help="heat map x axis (default: first grid axis)")
    p.add_argument("--y", help="heat map y axis (default: second grid axis)")
    p.add_argument("--color", help="heat map column (default: first output)")
    p.add_argument("--fix", action="append", default=[], metavar="NAME=VALUE",
                   help="pin another grid axis in the heat map instead of faceting it")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    return p.parse_args(argv)


def plan_from_args(args):
    preset = PRESETS[args.preset] if args.preset else {}
    plan = preset["plan"]() if preset else Plan()
    if args.grid_file:
        loaded = load_file(args.grid_file)
        plan.grid.update(loaded.grid)
        plan.fixed.update(loaded.fixed)
        plan.outputs = loaded.outputs or plan.outputs
        plan.stop_time = loaded.stop_time or plan.stop_time
        plan.step = loaded.step or plan.step
    for text in args.grid:
        name, values = parse_assignment(text)
        plan.grid[name] = values
    for text in args.set:
        name, values = parse_assignment(text)
        if len(values) != 1:
            raise SystemExit(f"--set {text}: one value expected (a list is a --grid axis)")
        plan.fixed[name] = values[0]
    if args.output:
        plan.outputs = [Output.parse(o) for o in args.output]
    plan.stop_time = Span.parse(args.stop_time) or plan.stop_time
    plan.step = Span.parse(args.step) or plan.step
    if not plan.grid:
        raise SystemExit("nothing to sweep: give --grid NAME=V1,V2,... or --grid-file")
    if not plan.outputs:
        raise SystemExit("nothing to collect: give --output NAME")
    return plan, preset


def view_from_args(args, preset, plan):
    """Heat map x, y (None with a single axis: one row), color column and pinned axes."""
    view = {**preset.get("heatmap", {}), **{k: v for k, v in
            {"x": args.x, "y": args.y, "color": args.color}.items() if v}}
    fixed = {}
    for text in args.fix:
        name, values = parse_assignment(text)
        if len(values) != 1:
            raise ValueError(f"--fix {text}: one value expected")
        fixed[name] = values[0]
    free = [a for a in plan.grid if a not in fixed]
    x = view.get("x") or next((a for a in free if a != view.get("y")), list(plan.grid)[0])
    y = view.get("y") or next((a for a in free if a != x), None)
    column = view.get("color", plan.outputs[0].column)
    return x, y, column, fixed


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    # every refusal before the sweep starts is one line and a non-zero exit, no traceback
    try:
        plan, preset = plan_from_args(args)
        fmu = args.fmu or preset.get("fmu")
        if fmu is None:
            raise SystemExit("give the FMU to sweep")
        x, y, column, fixed = view_from_args(args, preset, plan)
        check.plan(fmpy.read_model_description(fmu), plan)
        check.view(plan, x, y, column, fixed)
    except (ValueError, OSError) as error:  # OSError: a missing FMU or grid file
        raise SystemExit(f"error: {error}") from None
    prefix = pathlib.Path(args.out or preset.get("out", "fmu-out/sweeps/sweep"))
    prefix.parent.mkdir(parents=True, exist_ok=True)

    rows, summary = run_sweep(fmu, plan, scheduler=args.scheduler, workers=args.workers,
                              ship=args.ship, progress=not args.quiet)
    write_csv(prefix.with_suffix(".csv"), plan, rows)
    svg = heatmap.render(rows, plan.grid, x, y, column, heatmap_units(fmu, plan), fixed,
                         title=preset.get("title"))
    prefix.with_suffix(".svg").write_text(svg)
    summary.update(grid=plan.grid, fixed=plan.fixed, outputs=[o.column for o in plan.outputs],
                   stop_time=str(plan.stop_time or "DefaultExperiment"),
                   step=str(plan.step or "DefaultExperiment"))
    prefix.with_suffix(".json").write_text(json.dumps(summary, indent=2) + "\n")
    run_times = [r["wall_time_s"] for r in rows]
    print(f"{summary['points']} points ({summary['failed']} failed) in "
          f"{summary['wall_time_s']:.2f} s on {summary['executor']}, FMU shipped by "
          f"{summary['ship']}; one run {min(run_times):.3f}-{max(run_times):.3f} s")
    for suffix in (".csv", ".svg", ".json"):
        print(f"wrote {prefix.with_suffix(suffix)}")
    return 1 if summary["failed"] == summary["points"] else 0


if __name__ == "__main__":
    sys.exit(main())
