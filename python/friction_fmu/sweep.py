"""Parameter sweeps through an FMU: one simulation per grid point, in parallel.

    python -m friction_fmu.sweep fmu-out/TransverseFriction.fmu \\
        --grid vd=1e-4,5e-4,2e-3 --grid va=0,1e-3,2e-3 --grid f=1e3,3e3 \\
        --set initial=sliding --output FFx_mean --stop-time 150/f --step 1/f
    python -m friction_fmu.sweep --preset fig8            # the paper's Fig. 8 grid
    python -m friction_fmu.sweep ... --scheduler local:4  # on a Dask LocalCluster of 4 workers
    python -m friction_fmu.sweep ... --scheduler tcp://host:8786   # on a Dask cluster

Points run on the local cores (a process pool, one worker per core) unless a Dask scheduler is
given; both executors get the same task, `runner.run_point`, through the same
concurrent.futures interface. Writes PREFIX.csv (one row per point), PREFIX.png and PREFIX.svg
(the plot: a line against a single grid axis, a heat map over two) and PREFIX.json (what was
run). Exit status: 0 when every point ran, 1 when any failed, 2 when the
arguments were refused (before any point ran).
"""
import argparse
import concurrent.futures as cf
import contextlib
import csv
import json
import os
import pathlib
import sys
import tempfile
import time
from dataclasses import dataclass

from . import check
from .grid import Output, Plan, Span, load_file, parse_assignment
from .presets import PRESETS
from .progress import Progress
from .runner import RAN, FmuSource, run_point

CONNECT_TIMEOUT = 10.0  # seconds; Dask's own default, 30 s, is long to wait for a typo
SUFFIXES = (".csv", ".png", ".svg", ".json")


# More local processes than this per CPU only add memory and start-up time: the points are
# CPU-bound.
WORKERS_PER_CPU = 4


def max_workers():
    """The most local processes --workers takes."""
    return WORKERS_PER_CPU * (os.cpu_count() or 1)


def _die_with_parent(parent):
    """A pool process's initializer: on Linux the kernel ends it (SIGTERM) when the sweep that
    started it (`parent`, a process id) dies, however it dies, instead of leaving it to run its
    queue out alone."""
    if sys.platform.startswith("linux"):
        import ctypes
        import signal

        pr_set_pdeathsig = 1
        ctypes.CDLL(None, use_errno=True).prctl(pr_set_pdeathsig, signal.SIGTERM)
        if os.getppid() != parent:
            os._exit(1)  # the sweep died before the signal was asked for


@contextlib.contextmanager
def local_executor(workers):
    with cf.ProcessPoolExecutor(max_workers=workers, initializer=_die_with_parent,
                                initargs=(os.getpid(),)) as executor:
        yield executor, lambda source: source


def local_cluster_size(scheduler):
    """N of `local[:N]` (default: the number of CPUs); None for any other scheduler."""
    if not isinstance(scheduler, str) or scheduler.partition(":")[0] != "local":
        return None
    _, colon, count = scheduler.partition(":")
    if not colon:
        return os.cpu_count()
    if not count.isdigit() or int(count) < 1:
        raise ValueError(f"--scheduler {scheduler}: expected local or local:N, N >= 1 workers")
    if int(count) > max_workers():
        raise ValueError(f"--scheduler {scheduler}: expected at most {max_workers()} worker "
                         f"processes ({WORKERS_PER_CPU} per CPU; the points are CPU-bound, so "
                         "more only take memory)")
    return int(count)


def require_distributed(scheduler):
    """Refuses a Dask scheduler where Dask's `distributed` is not installed, in a line instead
    of the import's traceback."""
    try:
        import distributed  # noqa: F401
    except ImportError:
        raise ValueError(f"--scheduler {scheduler} needs Dask's distributed, which is not "
                         "installed here: pip install -e 'python[dask]'") from None


def executor_label(scheduler, workers):
    size = local_cluster_size(scheduler)
    if size is not None:
        return f"a Dask LocalCluster of {size} worker{'s' * (size != 1)}"
    if scheduler is not None:
        return f"dask {scheduler}"
    return f"local, {workers} process{'es' * (workers != 1)}"


@contextlib.contextmanager
def dask_executor(scheduler, connect_timeout=CONNECT_TIMEOUT):
    """A Dask client's concurrent.futures executor. `scheduler` is an address
    (tcp://host:port), `local[:N]` (a LocalCluster of N worker processes, started here and
    closed with the executor) or a cluster object. The FMU is scattered to every worker once,
    so tasks carry only a reference to it."""
    from distributed import LocalCluster

    size = local_cluster_size(scheduler)
    with contextlib.ExitStack() as stack:
        if size is not None:
            # one thread a worker, as in the local pool: a point holds its core to the end.
            # The workers are spawned with this process's sys.path, so they import this
            # package from where it does, with no PYTHONPATH set.
            scheduler = stack.enter_context(LocalCluster(
                n_workers=size, threads_per_worker=1, processes=True, dashboard_address=None))
        client = stack.enter_context(_client(scheduler, connect_timeout))

        def ship(source):
            return client.scatter(source, broadcast=True)

        yield client.get_executor(pure=False), ship


def _client(scheduler, timeout):
    from distributed import Client

    try:
        return Client(scheduler, timeout=timeout)
    except OSError:  # Dask retries until the timeout, then says only that it timed out
        raise ValueError(f"--scheduler {scheduler}: no Dask scheduler answered within "
                         f"{timeout:g} s (--connect-timeout)") from None
    except ValueError as error:  # an address Dask cannot parse
        raise ValueError(f"--scheduler {scheduler}: {error}") from None


def run_sweep(fmu, plan, scheduler=None, workers=None, ship=None, progress=True,
              connect_timeout=CONNECT_TIMEOUT):
    """Runs every point of `plan`; returns the rows in grid order and a summary of the run.
    Raises ValueError before any point runs when the plan cannot run on the FMU or the Dask
    scheduler does not answer within `connect_timeout` seconds.

    `ship` is how the FMU reaches the workers: "path" (a filesystem they share with this
    process; the default on local cores) or "bytes" (the .fmu's content; the default on Dask,
    safe on any cluster)."""
    md = check.model_description(fmu)
    check.plan(md, plan)
    check.times(md, plan)
    ship = ship or ("bytes" if scheduler is not None else "path")
    source = FmuSource.by_bytes(fmu) if ship == "bytes" else FmuSource.by_path(fmu)
    points = plan.points()
    # no more processes than points to run
    workers = min(workers or os.cpu_count(), len(points))
    executor_cm = (dask_executor(scheduler, connect_timeout) if scheduler is not None
                   else local_executor(workers))
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
                bar.advance(failed=row["status"] not in RAN)
        finally:
            bar.close()
    rows.sort(key=lambda r: r["point"])
    summary = {
        "fmu": os.path.abspath(fmu),
        "executor": executor_label(scheduler, workers),
        "ship": ship,
        "points": len(points),
        "failed": sum(r["status"] not in RAN for r in rows),
        "warned": sum(r["status"] == "warning" for r in rows),
        "wall_time_s": time.perf_counter() - began,
    }
    return rows, summary


def columns(plan):
    return ["point", *plan.grid, *(o.column for o in plan.outputs), "status", "message",
            "wall_time_s"]


def out_paths(out, model):
    """{suffix: path} of the four files of `--out PREFIX`: PREFIX.csv, .png, .svg and .json. A
    directory (one that exists, or any path ending in /) holds MODEL-sweep.*; a PREFIX ending in
    one of the four suffixes loses it, and any other dot is kept (run.f2.5 -> run.f2.5.csv)."""
    prefix = pathlib.Path(out)
    if out.endswith(("/", os.sep)) or prefix.is_dir():
        prefix = prefix / f"{model}-sweep"
    elif prefix.suffix in SUFFIXES:
        prefix = prefix.with_suffix("")
    return {suffix: prefix.with_name(prefix.name + suffix) for suffix in SUFFIXES}


def writable(paths, out):
    """Creates the files' directory and writes a scratch file in it, so that a sweep is
    refused up front rather than run to the end and then lost."""
    directory = paths[".csv"].parent
    if directory.exists() and not directory.is_dir():
        raise ValueError(f"--out {out}: {directory} is a file, not a directory")
    try:
        directory.mkdir(parents=True, exist_ok=True)
        tempfile.TemporaryFile(dir=directory).close()
    except OSError as error:
        raise ValueError(f"--out {out}: cannot write in {directory} ({error.strerror})") from None
    for path in paths.values():
        if path.is_dir() or (path.exists() and not os.access(path, os.W_OK)):
            raise ValueError(f"--out {out}: cannot write {path}")


def write_csv(path, plan, rows):
    """Floats are written with repr, so the file holds every bit of each number."""
    with open(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=columns(plan), extrasaction="ignore")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: repr(v) if isinstance(v, float) else v for k, v in row.items()})


def units_of(md):
    """Unit of every variable that has one, from the modelDescription."""
    units = {}
    for var in md.modelVariables:
        unit = getattr(var, "unit", None) or getattr(var.declaredType, "unit", None)
        if unit:
            units[var.name] = unit
    return units


def plot_units(md, plan):
    units = units_of(md)
    for output in plan.outputs:
        if output.variable in units:
            units[output.column] = units[output.variable]
    return units


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        # one line and exit status 2, as every other refusal (main prints it); the usage is
        # one --help away
        raise ValueError(f"{message} (see --help)")


def _count(text):
    if not text.strip().isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"{text!r}: expected a whole number >= 1")
    return int(text)


def _workers(text):
    count = _count(text)
    if count > max_workers():
        raise argparse.ArgumentTypeError(
            f"{text!r}: expected at most {max_workers()} local processes ({WORKERS_PER_CPU} per "
            f"CPU; the points are CPU-bound, so more only take memory)")
    return count



def parse_args(argv):
    p = _Parser(prog="python -m friction_fmu.sweep", description=__doc__,
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
    p.add_argument("--workers", type=_workers, help="local processes (default: os.cpu_count())")
    p.add_argument("--scheduler", help="Dask: local[:N] starts a LocalCluster of N workers "
                                       "(default: os.cpu_count()), or a scheduler address, "
                                       "e.g. tcp://host:8786")
    p.add_argument("--connect-timeout", type=check.positive_seconds, default=CONNECT_TIMEOUT,
                   metavar="SECONDS", help="how long to wait for the Dask scheduler "
                                           f"(default {CONNECT_TIMEOUT:g})")
    p.add_argument("--ship", choices=["bytes", "path"],
                   help="send the FMU as bytes or by path (default: path locally, bytes on Dask)")
    p.add_argument("--out", help="output prefix, or a directory (DIR/ writes "
                                 "DIR/MODEL-sweep.*); default fmu-out/sweeps/sweep")
    p.add_argument("--x", help="the plot's x axis (default: first grid axis)")
    p.add_argument("--y", help="heat map y axis (default: second grid axis; with one axis the "
                               "plot is a line)")
    p.add_argument("--color", help="the column plotted (default: first output)")
    p.add_argument("--fix", action="append", default=[], metavar="NAME=VALUE",
                   help="pin another grid axis in the plot instead of faceting it")
    p.add_argument("--quiet", action="store_true", help="no start line or progress")
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
    on_command_line = set()
    for text in args.grid:
        name, values = parse_assignment(text)
        if name in on_command_line:
            raise ValueError(f"--grid {text}: {name} is already an axis (one --grid a name, "
                             "with all its values: --grid NAME=V1,V2,...)")
        on_command_line.add(name)
        plan.grid[name] = values
    for text in args.set:
        name, values = parse_assignment(text)
        if len(values) != 1:
            raise ValueError(f"--set {text}: one value expected (a list is a --grid axis)")
        plan.fixed[name] = values[0]
    if args.output:
        plan.outputs = [Output.parse(o) for o in args.output]
    plan.stop_time = Span.parse(args.stop_time) or plan.stop_time
    plan.step = Span.parse(args.step) or plan.step
    if not plan.grid:
        raise ValueError("nothing to sweep: give --grid NAME=V1,V2,... or --grid-file")
    if not plan.outputs:
        raise ValueError("nothing to collect: give --output NAME")
    return plan, preset


def view_from_args(args, preset, plan):
    """The plot's x, y (None with a single free axis: a line plot), column and pinned axes."""
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


@dataclass
class Command:
    """A checked command line: what to run, on what, and where its files go."""

    args: argparse.Namespace
    plan: Plan
    preset: dict
    fmu: str
    md: object  # fmpy's ModelDescription
    view: tuple  # the plot's x, y, column, pinned axes
    workers: int
    paths: dict


def prepare(argv):
    """The command line, checked from its syntax to the output directory; raises ValueError
    (or OSError, for a missing file) for the first thing wrong."""
    args = parse_args(argv)
    plan, preset = plan_from_args(args)
    fmu = args.fmu or preset.get("fmu")
    if fmu is None:
        raise ValueError("give the FMU to sweep")
    md = check.model_description(fmu)
    view = view_from_args(args, preset, plan)
    check.plan(md, plan)
    check.ranges(md, plan)  # before times: an N/PARAM by a PARAM out of range means nothing
    check.times(md, plan)
    check.view(plan, *view)
    if args.workers is not None and args.scheduler is not None:
        raise ValueError("--workers sizes the local process pool: with --scheduler, give "
                         "local:N or size the cluster")
    local_cluster_size(args.scheduler)  # refuses a malformed local:N
    if args.scheduler is not None:
        require_distributed(args.scheduler)
    out = args.out or preset.get("out", "fmu-out/sweeps/sweep")
    paths = out_paths(out, pathlib.Path(fmu).stem)
    writable(paths, out)
    return Command(args, plan, preset, fmu, md, view, args.workers or os.cpu_count(), paths)


def write_results(command, rows, summary):
    plan, paths = command.plan, command.paths
    write_csv(paths[".csv"], plan, rows)
    from . import sweep_plot  # matplotlib only once there is something to draw

    sweep_plot.write(paths[".csv"].with_suffix(""), rows, plan.grid, *command.view[:3],
                     plot_units(command.md, plan), command.view[3],
                     title=command.preset.get("title"), solver=plan.fixed.get("solver"))
    summary.update(grid=plan.grid, fixed=plan.fixed, outputs=[o.column for o in plan.outputs],
                   stop_time=str(plan.stop_time or "DefaultExperiment"),
                   step=str(plan.step or "DefaultExperiment"))
    paths[".json"].write_text(json.dumps(summary, indent=2) + "\n")
    run_times = [r["wall_time_s"] for r in rows]
    warned = f", {summary['warned']} with a warning (see the CSV)" if summary["warned"] else ""
    print(f"{summary['points']} points ({summary['failed']} failed{warned}) in "
          f"{summary['wall_time_s']:.2f} s on {summary['executor']}, FMU shipped by "
          f"{summary['ship']}; one run {min(run_times):.3f}-{max(run_times):.3f} s")
    for path in paths.values():
        print(f"wrote {path}")


def main(argv=None):
    """The command; returns its exit status: 0 every point ran, 1 some failed, 2 refused."""
    # every refusal is one line on stderr and exit status 2, before any point runs
    try:
        command = prepare(sys.argv[1:] if argv is None else argv)
        args = command.args
        if not args.quiet:  # before the pool or the cluster starts, which takes seconds
            print(f"sweeping {command.md.modelName}: {len(command.plan.points())} points on "
                  f"{executor_label(args.scheduler, command.workers)}, writing "
                  f"{command.paths['.csv']} (and .png, .svg, .json)", file=sys.stderr, flush=True)
        # connects to the Dask scheduler before any point runs: no answer is a refusal too
        rows, summary = run_sweep(command.fmu, command.plan, scheduler=args.scheduler,
                                  workers=command.workers, ship=args.ship,
                                  progress=not args.quiet, connect_timeout=args.connect_timeout)
    except (ValueError, OSError) as error:  # OSError: a missing FMU or grid file
        print(f"error: {error}", file=sys.stderr)
        return 2
    write_results(command, rows, summary)
    return 1 if summary["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
