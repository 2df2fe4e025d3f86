"""DriveTrain coupled to TransverseFriction by a fixed-step Jacobi master on fmpy.

    python -m friction_fmu.couple [--step H] [--stop-time T] [--derivatives | --held] \\
        [--set friction.NAME=VALUE ...] [--set drive.NAME=VALUE ...] [--fmu-dir DIR] [--out PREFIX]

The nut of the drive's lead screw is the far end of the friction model's drive spring:

    DriveTrain.v_nut      -> TransverseFriction.vd_in   (drive_source = input)
    TransverseFriction.Fd -> DriveTrain.F_load

At every communication point t = k H each FMU's output is handed to the other's input, then both
step from t to t + H (Jacobi). With derivatives (the default) the master also passes the outputs'
first derivatives (fmi2GetRealOutputDerivatives -> fmi2SetRealInputDerivatives), so each FMU sees
its input move linearly over the step instead of held: the coupling error then falls as H^2
instead of H.

The default case: the motor is switched on at t = 0 with everything at rest and no support
vibration (friction: drive_source=input, va=0, initial=rest, vd_in=0), 0.04 s at H = 0.1 ms.

Writes PREFIX.csv (one row per communication point, SI units, every number as Python's repr so
it reads back to the same bits), PREFIX.png and PREFIX.svg (nut velocity, Fd and FF against
time). The CSV's columns: time; v_nut, x_nut, i, omega (DriveTrain's outputs); Fd, FF, FFx, FFy,
x, y, W_diss (TransverseFriction's); vd_in and F_load, each input as its FMU saw it at the end of
the step just taken (held: the partner's output at t - H; with derivatives: extrapolated from
t - H over H; at t = 0 its start value), which differ from v_nut and Fd by the coupling error;
with derivatives, dv_nut_dt and dFd_dt, the derivatives passed at t.

Exit status: 0 when the run reached the stop time; 1 when an FMU failed during the run (the files
then hold the run up to the last good point); 2 when the arguments were refused, before anything
ran.
"""
import argparse
import contextlib
import csv
import difflib
import math
import pathlib
import re
import shutil
import sys

import fmpy
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave

from . import check, runner, switches
from .grid import Plan, parse_value
from .sweep import writable

# The coupled case: TransverseFriction's defaults without the vibration, driven from the nut.
FRICTION = {"drive_source": "input", "va": 0.0, "initial": "rest", "vd_in": 0.0}
DRIVE = {}
STOP_TIME = 0.04
STEP = 1e-4
FMU_DIR = pathlib.Path("fmu-out")
OUT = "fmu-out/coupling/drive_friction"
SUFFIXES = (".csv", ".png", ".svg")
MAX_STEPS = check.MAX_STEPS

# The two FMUs by the name a --set gives them, and the variables this master reads or writes:
# a model without them is not the one it couples.
MODELS = {"drive": "DriveTrain", "friction": "TransverseFriction"}
DRIVE_OUTPUTS = ("x_nut", "i", "omega")  # recorded besides v_nut
FRICTION_OUTPUTS = ("FF", "FFx", "FFy", "x", "y", "W_diss")  # recorded besides Fd
NEEDED = {"drive": ("v_nut", "F_load", *DRIVE_OUTPUTS),
          "friction": ("vd_in", "Fd", "drive_source", *FRICTION_OUTPUTS)}
# Each coupled input and the output the master sets it from.
COUPLED = {("friction", "vd_in"): "drive.v_nut", ("drive", "F_load"): "friction.Fd"}

# The CSV's columns. vd_in and F_load are the inputs as the FMU saw them at t, at the end of the
# step it just took (held: the partner's output at t - H; with derivatives: extrapolated from t - H
# over H); they differ from v_nut and Fd at t by the coupling error. The d*_dt columns are the
# derivatives passed at t (with derivatives only).
COLUMNS = ("time", "v_nut", "vd_in", "Fd", "F_load", "FF", "FFx", "FFy", "x", "y", "x_nut", "i",
           "omega", "W_diss")
RATE_COLUMNS = ("dv_nut_dt", "dFd_dt")
STATUS = ["fmi2OK", "fmi2Warning", "fmi2Discard", "fmi2Error", "fmi2Fatal", "fmi2Pending"]


def columns(derivatives):
    return COLUMNS + RATE_COLUMNS if derivatives else COLUMNS


# -- the master ------------------------------------------------------------------------------


class FmuFailed(Exception):
    """An FMI call of one FMU returned fmi2Discard or worse; `said` is what the FMU logged."""

    def __init__(self, fmu, function, status, said):
        self.fmu, self.function, self.status, self.said = fmu, function, status, said
        label = STATUS[status] if 0 <= status < len(STATUS) else f"status {status}"
        super().__init__(f"{fmu}: {function} returned {label}" + (f": {said}" if said else ""))


class CouplingFailed(Exception):
    """An FMU failed: `time` is the communication point (None: while the FMUs were set up, before
    any step), `stepping` whether it was the step from `time` to `time + step`, `rows` the run up
    to the last good point."""

    def __init__(self, failed, time, stepping, step, rows):
        self.failed, self.time, self.stepping, self.rows = failed, time, stepping, rows
        if time is None:
            where = "before the first step"
        elif stepping:
            where = f"at t = {time:.9g} s (the step to {time + step:.9g} s)"
        else:
            where = f"at t = {time:.9g} s"
        super().__init__(f"{where}: {failed}")


class Fmu:
    """One FMU2Slave with its variables by name and its log captured, so that a failure carries
    the FMU's own reason."""

    def __init__(self, path, label):
        self.label = label
        self.md = fmpy.read_model_description(str(path))
        self.vars = {v.name: v for v in self.md.modelVariables}
        self.directory = fmpy.extract(str(path))
        # runner's logger, not one of our own: fmpy's native logger proxy holds a single Python
        # logger for the whole process, so a second one would steal the sweep's messages.
        self.environment = next(runner._ENVIRONMENTS)
        self.messages = runner._MESSAGES[self.environment] = []
        self.slave = None
        try:
            self.slave = FMU2Slave(guid=self.md.guid, unzipDirectory=self.directory,
                                   modelIdentifier=self.md.coSimulation.modelIdentifier,
                                   instanceName=label)
            try:
                self.slave.instantiate(callbacks=runner._callbacks(self.environment))
            except Exception as error:  # fmpy says only "Failed to instantiate model"
                raise FmuFailed(label, "fmi2Instantiate", 3, self.said() or str(error)) from None
        except BaseException:
            self.close()
            raise

    def _call(self, function, *args, **kwargs):
        try:
            return function(*args, **kwargs)
        except FMICallException as error:
            raise FmuFailed(self.label, error.function, error.status, self.said()) from None

    def said(self):
        """The FMU's warnings and errors so far, on one line."""
        texts = [" ".join(text.split()) for status, text in self.messages if status >= 1]
        return " | ".join(dict.fromkeys(texts))

    def warnings(self):
        """The distinct warnings the FMU logged, with how often each came."""
        counts = {}
        for status, text in self.messages:
            if status == 1:
                text = " ".join(text.split())
                counts[text] = counts.get(text, 0) + 1
        return counts

    def vr(self, name):
        return self.vars[name].valueReference

    def set(self, **values):
        """Parameters (and start values of inputs): a switch by item name or number."""
        for name, value in values.items():
            var = self.vars.get(name)
            if var is None:
                raise ValueError(f"{self.label} has no variable {name!r}")
            if isinstance(value, str):
                items = switches.items(var) or {}
                if value not in items:
                    raise ValueError(f"{self.label}.{name} = {value!r}: expected one of "
                                     f"{', '.join(items) or 'a number'}")
                self._call(self.slave.setInteger, [var.valueReference], [items[value]])
            elif var.type == "Integer":
                self._call(self.slave.setInteger, [var.valueReference], [int(value)])
            else:
                self._call(self.slave.setReal, [var.valueReference], [float(value)])

    def start(self, **values):
        self._call(self.slave.setupExperiment, startTime=0.0)
        self.set(**values)
        self._call(self.slave.enterInitializationMode)
        self._call(self.slave.exitInitializationMode)

    def get(self, *names):
        values = self._call(self.slave.getReal, [self.vr(n) for n in names])
        return values[0] if len(names) == 1 else values

    def rate(self, name):
        return self._call(self.slave.getRealOutputDerivatives, [self.vr(name)], [1])[0]

    def give(self, name, value, rate=None):
        """Sets an input; with `rate` it moves linearly over the next step only (FMI 2.0
        fmi2SetRealInputDerivatives), without it it is held."""
        self._call(self.slave.setReal, [self.vr(name)], [value])
        if rate is not None:
            self._call(self.slave.setRealInputDerivatives, [self.vr(name)], [1], [rate])

    def step(self, t, h):
        self._call(self.slave.doStep, t, h)

    def close(self):
        if self.slave is not None:
            if getattr(self.slave, "component", None) is not None:
                # terminate is not allowed after fmi2Error; freeing is, and is all that is left
                with contextlib.suppress(FMICallException):
                    self.slave.terminate()
                self.slave.freeInstance()  # unloads the library too
            else:
                self.slave.freeLibrary()
        runner._MESSAGES.pop(self.environment, None)
        shutil.rmtree(self.directory, ignore_errors=True)


def steps(stop_time, step):
    """The number of communication steps from 0 to `stop_time`. Refuses a stop time that is not
    a whole number of steps (the last point would not be the stop time) and more than MAX_STEPS
    steps (a mistyped time, not a run anyone waits for)."""
    for what, value in (("step", step), ("stop time", stop_time)):
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            raise ValueError(f"{what} {value!r} s: expected a finite number of seconds > 0")
    ratio = stop_time / step
    if ratio > MAX_STEPS:
        raise ValueError(f"stop time {stop_time:g} s at a step of {step:g} s is {ratio:.3g} "
                         f"steps: at most {MAX_STEPS:.0e} are allowed (a shorter stop time or a "
                         "longer step)")
    n = round(ratio)
    # k H in floating point is off by a few ulps of a decimal stop time (0.04 / 1e-4 is
    # 400.00000000000006); anything further is a stop time between two points
    if n < 1 or abs(ratio - n) > 1e-6:
        below, above = math.floor(ratio) * step, math.ceil(ratio) * step
        choices = " or ".join(f"{t:.9g}" for t in (below, above) if t > 0)
        raise ValueError(f"stop time {stop_time:g} s is {ratio:.6g} steps of {step:g} s: "
                         f"expected a whole number of steps (e.g. {choices} s)")
    return n


def exchange(drive, friction, derivatives):
    """The Jacobi exchange at one communication point; returns the outputs at t and what was
    passed to each input, {input: (value, derivative or None)}."""
    v_nut = drive.get("v_nut")
    v_rate = drive.rate("v_nut") if derivatives else None
    friction.give("vd_in", v_nut, v_rate)
    # Fd only after vd_in is set: it feeds through the drive damping, hd (vd_in - x')
    fd = friction.get("Fd")
    fd_rate = friction.rate("Fd") if derivatives else None
    drive.give("F_load", fd, fd_rate)
    # the rest after both inputs, so every value of the row belongs to the same inputs
    outputs = {"v_nut": v_nut, "Fd": fd,
               **dict(zip(DRIVE_OUTPUTS, drive.get(*DRIVE_OUTPUTS))),
               **dict(zip(FRICTION_OUTPUTS, friction.get(*FRICTION_OUTPUTS)))}
    if derivatives:
        outputs.update(dv_nut_dt=v_rate, dFd_dt=fd_rate)
    return outputs, {"vd_in": (v_nut, v_rate), "F_load": (fd, fd_rate)}


def reached(passed, step):
    """Each input at the end of the coming step as its FMU moves it: held, or along the line the
    derivative gives it."""
    return {name: value if rate is None else value + rate * step
            for name, (value, rate) in passed.items()}


def run(step=STEP, derivatives=True, stop_time=STOP_TIME, friction=None, drive=None,
        fmu_dir=FMU_DIR, on_warning=None):
    """The coupled run: one dict a communication point, t = 0 and the stop time included, with
    the keys `columns(derivatives)`. `friction` and `drive` are values set before initialization,
    over FRICTION and DRIVE (switches by item name or number). An FMU that fails raises
    CouplingFailed holding the rows up to the last good point. `on_warning(fmu, text, count)` is
    called for each distinct warning an FMU logged."""
    n = steps(stop_time, step)
    rows = []
    t, stepping = None, False  # where the run is, for the message if an FMU fails
    # both FMUs are freed, and their extracted files removed, however the run ends
    with contextlib.ExitStack() as stack:
        try:
            fmus = {}
            for key, identifier in MODELS.items():
                fmus[key] = Fmu(pathlib.Path(fmu_dir) / f"{identifier}.fmu", identifier)
                stack.callback(fmus[key].close)
            if on_warning is not None:  # before the instances are freed with their logs
                stack.callback(_report_warnings, fmus.values(), on_warning)
            fmus["drive"].start(**{**DRIVE, **(drive or {})})
            fmus["friction"].start(**{**FRICTION, **(friction or {})})
            # what the inputs are at t = 0, before the first exchange: their start values
            seen = {"vd_in": fmus["friction"].get("vd_in"), "F_load": fmus["drive"].get("F_load")}
            for k in range(n + 1):
                t, stepping = k * step, False
                outputs, passed = exchange(fmus["drive"], fmus["friction"], derivatives)
                rows.append({"time": t, **outputs, **seen})
                if k == n:
                    break
                seen = reached(passed, step)
                stepping = True
                fmus["drive"].step(t, step)
                fmus["friction"].step(t, step)
        except FmuFailed as failed:
            raise CouplingFailed(failed, t, stepping, step, _ordered(rows, derivatives)) from None
    return _ordered(rows, derivatives)


def _report_warnings(fmus, on_warning):
    for fmu in fmus:
        for text, count in fmu.warnings().items():
            on_warning(fmu.label, text, count)


def _ordered(rows, derivatives):
    return [{c: row[c] for c in columns(derivatives)} for row in rows]


def couple(step, derivatives, stop_time=STOP_TIME, friction=None, drive=None, fmu_dir=FMU_DIR):
    """The run as rows (t, v_nut, x_nut, Fd, x), for comparing with a reference
    (friction_fmu.coupling_error)."""
    return [(r["time"], r["v_nut"], r["x_nut"], r["Fd"], r["x"])
            for r in run(step, derivatives, stop_time, friction, drive, fmu_dir)]


# -- the command line ------------------------------------------------------------------------


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        # argparse takes "--step -1e-4" for an option named -1e-4 ("expected one argument"):
        # every number, exponent included, is a value, refused by check.positive_seconds with its reason
        self._negative_number_matcher = re.compile(
            r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE)

    def error(self, message):
        # one line and exit status 2, as every other refusal; the usage is one --help away
        raise ValueError(f"{message} (see --help)")



def parse_args(argv):
    p = _Parser(prog="python -m friction_fmu.couple", description=__doc__,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--step", type=check.positive_seconds, default=STEP, metavar="H",
                   help=f"communication step in s (default {STEP:g})")
    p.add_argument("--stop-time", type=check.positive_seconds, default=STOP_TIME, metavar="T",
                   help=f"stop time in s, a whole number of steps (default {STOP_TIME:g})")
    inputs = p.add_mutually_exclusive_group()
    inputs.add_argument("--derivatives", dest="derivatives", action="store_true", default=True,
                        help="pass the outputs' first derivatives with the inputs (default)")
    inputs.add_argument("--held", dest="derivatives", action="store_false",
                        help="hold every input over the step")
    p.add_argument("--set", action="append", default=[], metavar="FMU.NAME=VALUE",
                   help="a parameter of friction (TransverseFriction) or drive (DriveTrain); "
                        "switch items by name or number, e.g. friction.initial=rest")
    p.add_argument("--fmu-dir", default=str(FMU_DIR), metavar="DIR",
                   help=f"directory of DriveTrain.fmu and TransverseFriction.fmu (default "
                        f"{FMU_DIR})")
    p.add_argument("--out", default=OUT, metavar="PREFIX",
                   help=f"writes PREFIX.csv, .png and .svg; a directory (DIR/) holds "
                        f"drive_friction.* (default {OUT})")
    return p.parse_args(argv)


def load_models(fmu_dir):
    """{"drive": md, "friction": md}: the modelDescriptions of the two FMUs in `fmu_dir`, each
    checked to be the model this master couples."""
    if not pathlib.Path(fmu_dir).is_dir():
        said = "not a directory" if pathlib.Path(fmu_dir).exists() else "no such directory"
        raise ValueError(f"--fmu-dir {fmu_dir}: {said} (the FMUs are built into fmu-out/ by "
                         "`friction-fmu build`)")
    models = {}
    for key, identifier in MODELS.items():
        path = pathlib.Path(fmu_dir) / f"{identifier}.fmu"
        if not path.is_file():
            raise ValueError(f"--fmu-dir {fmu_dir}: no {identifier}.fmu in it (the FMUs are "
                             "built into fmu-out/ by `friction-fmu build`)")
        md = check.model_description(str(path))
        cs = md.coSimulation
        if cs is None or cs.modelIdentifier != identifier:
            raise ValueError(f"{path}: not the {identifier} co-simulation FMU (model "
                             f"{md.modelName!r})")
        names = {v.name for v in md.modelVariables}
        missing = [n for n in NEEDED[key] if n not in names]
        if missing:
            raise ValueError(f"{path}: not the {identifier} this master couples: no variable "
                             f"{', '.join(missing)}")
        models[key] = md
    return models


def interpolates(models):
    """Refuses --derivatives on an FMU that cannot take input derivatives or give output ones."""
    for md in models.values():
        cs = md.coSimulation
        if not cs.canInterpolateInputs or (cs.maxOutputDerivativeOrder or 0) < 1:
            raise ValueError(f"--derivatives: {cs.modelIdentifier} does not interpolate inputs "
                             "or give output derivatives (canInterpolateInputs, "
                             "maxOutputDerivativeOrder): run with --held")


def parse_set(text, models):
    """`--set friction.NAME=VALUE` -> ("friction", NAME, value as the FMU takes it), refusing
    what the FMU would refuse (or ignore) before anything runs."""
    target, eq, raw = text.partition("=")
    key, dot, name = target.strip().partition(".")
    name = name.strip()
    if not eq or not dot or not name or not raw.strip():
        raise ValueError(f"--set {text}: expected friction.NAME=VALUE or drive.NAME=VALUE")
    if key not in models:
        raise ValueError(f"--set {text}: {key!r} is not a coupled FMU: friction "
                         "(TransverseFriction) or drive (DriveTrain)")
    md = models[key]
    variables = {v.name: v for v in md.modelVariables}
    parameters = [n for n, v in variables.items() if v.causality == "parameter"]
    var = variables.get(name)
    if var is None:
        near = difflib.get_close_matches(name, list(variables), n=1)
        hint = f" (did you mean {near[0]}?)" if near else ""
        raise ValueError(f"--set {text}: {MODELS[key]} has no variable {name!r}{hint}")
    if (key, name) in COUPLED:
        raise ValueError(f"--set {text}: {name} is the coupled input: the master sets it from "
                         f"{COUPLED[key, name]} at every communication point")
    if var.causality != "parameter":
        article = "an" if var.causality[0] in "aeiou" else "a"
        raise ValueError(f"--set {text}: {name} is {article} {var.causality}; --set takes "
                         f"parameters of {MODELS[key]}: {', '.join(parameters)}")
    try:
        value = typed(var, parse_value(raw))
        check.ranges(md, Plan(fixed={name: value}))
    except ValueError as error:
        raise ValueError(f"--set {text}: {error}") from None
    if key == "friction" and name == "drive_source" and value != switches.items(var)["input"]:
        raise ValueError(f"--set {text}: the friction model follows the nut only with "
                         "drive_source = input")
    return key, name, value


def typed(var, value):
    """`value` (a float or a text) as `var` takes it: a switch's item by name or number, a whole
    number for an Integer, a finite number for a Real."""
    items = switches.items(var)
    if items is not None:
        if isinstance(value, str) and value in items:
            return items[value]
        if isinstance(value, float) and value in items.values():
            return int(value)
        listed = ", ".join(f"{item} ({number})" for item, number in items.items())
        raise ValueError(f"{var.name} = {_shown(value)}: expected one of {listed}")
    if not isinstance(value, float):
        raise ValueError(f"{var.name} = {value!r}: expected a number")
    if not math.isfinite(value):
        raise ValueError(f"{var.name} = {value!r}: expected a finite number")
    if var.type == "Integer":
        if value != int(value):
            raise ValueError(f"{var.name} = {value!r}: expected a whole number")
        return int(value)
    if var.type != "Real":
        raise ValueError(f"{var.name} is a {var.type}: --set takes Real and Integer parameters")
    return value


def _shown(value):
    """A value as given: 3 rather than 3.0, a text quoted."""
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    return repr(value)


def out_paths(out):
    """{suffix: path} of PREFIX.csv, .png and .svg. A directory (one that exists, or any path
    ending in /) holds drive_friction.*; a PREFIX ending in one of the suffixes loses it."""
    prefix = pathlib.Path(out)
    if out.endswith(("/", "\\")) or prefix.is_dir():
        prefix = prefix / pathlib.Path(OUT).name
    elif prefix.suffix in SUFFIXES:
        prefix = prefix.with_suffix("")
    return {suffix: prefix.with_name(prefix.name + suffix) for suffix in SUFFIXES}


def prepare(argv):
    """The checked command line: (args, steps, {"friction": values, "drive": values}, paths).
    Raises ValueError for the first thing wrong."""
    args = parse_args(argv)
    n = steps(args.stop_time, args.step)
    models = load_models(args.fmu_dir)
    if args.derivatives:
        interpolates(models)
    values = {"friction": {}, "drive": {}}
    for text in args.set:
        key, name, value = parse_set(text, models)
        values[key][name] = value
    paths = out_paths(args.out)
    writable(paths, args.out)
    return args, n, values, paths


def write_csv(path, rows, derivatives):
    """Every number with repr: the file reads back to the same bits."""
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(columns(derivatives))
        for row in rows:
            writer.writerow([repr(row[c]) for c in columns(derivatives)])


def describe(args, unit="s", scale=1.0):
    inputs = "with first derivatives" if args.derivatives else "held"
    return f"Jacobi, H = {args.step * scale:g} {unit}, inputs {inputs}"


def write_results(args, rows, paths, stopped=None):
    from .coupling_plot import plot  # matplotlib only once there is something to draw

    write_csv(paths[".csv"], rows, args.derivatives)
    # PREFIX.png and PREFIX.svg, the paths out_paths gave
    plot(rows, paths[".csv"].with_suffix(""), describe(args, "ms", 1e3), stopped=stopped)
    for path in paths.values():
        print(f"wrote {path}")


def main(argv=None):
    """The command; returns its exit status: 0 done, 1 an FMU failed during the run, 2 refused."""
    try:
        args, n, values, paths = prepare(sys.argv[1:] if argv is None else argv)
    except (ValueError, OSError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    print(f"coupling DriveTrain.v_nut -> TransverseFriction.vd_in, TransverseFriction.Fd -> "
          f"DriveTrain.F_load: {n} steps to {args.stop_time:g} s, {describe(args)}; writing "
          f"{paths['.csv']} (and .png, .svg)", flush=True)

    def warn(fmu, text, count):
        print(f"warning: {fmu}: {text}" + (f" ({count} times)" if count > 1 else ""),
              file=sys.stderr)

    try:
        rows = run(args.step, args.derivatives, args.stop_time, values["friction"],
                   values["drive"], args.fmu_dir, on_warning=warn)
    except CouplingFailed as failed:
        if failed.time is None:  # refused while setting up: nothing ran
            print(f"error: {failed}", file=sys.stderr)
            return 2
        print(f"error: {failed}", file=sys.stderr, flush=True)
        write_results(args, failed.rows, paths, stopped=failed.time)
        return 1
    write_results(args, rows, paths)
    return 0


if __name__ == "__main__":
    sys.exit(main())
