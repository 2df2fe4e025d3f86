#!/usr/bin/env python3
"""What one fmi2DoStep costs at a small communication step, beside a trivial FMU's.

Each FMU is loaded through ctypes in this one process, instantiated at its defaults, and advanced
by CALLS doSteps of h (1e-6 s unless --step says otherwise) at t = i h, as a master computes its
points; the CPU time of the process (time.process_time) over those calls, divided by their
number, is the cost per call. The FMUs take turns, a fresh instance each run, and each one's
median over the runs is printed with the median of its difference from the trivial FMU's time
in the same run (short runs taken in turn, paired, so that a machine whose speed drifts with
other work shifts both). What the trivial FMU costs is what the call itself costs from Python
through ctypes (argument conversion, the call, its checks), so the difference is what our model
and FMI layer add. A second table does the same with every output read by fmi2GetReal after
each step, as a master that records the outputs does.

The trivial FMU is the Dahlquist FMU of the Modelica Association's Reference FMUs (FMI 2.0,
co-simulation): its doStep checks its arguments and, its fixed solver step being 0.1 s, does
no integration at h = 1e-6 s. It is not part of this project: build it outside this tree with
gcc and cmake from the public sources of the Reference FMUs (the modelica/Reference-FMUs
repository, checked out in ./Reference-FMUs here):

    cmake -S Reference-FMUs -B /tmp/reference-fmus -DFMI_VERSION=2 -DCMAKE_BUILD_TYPE=Release
    cmake --build /tmp/reference-fmus --target Dahlquist
    # -> /tmp/reference-fmus/fmus/Dahlquist.fmu
    #    (and /tmp/reference-fmus/temp/Dahlquist/binaries/linux64/Dahlquist.so)

Then, from the repository root, after `cargo run --release` (or `friction-fmu build`) has packed
fmu-out/:

    .venv/bin/python benches/per_call.py /tmp/reference-fmus/fmus/Dahlquist.fmu
        [--fmu fmu-out/LongitudinalFriction.fmu ...] [--step 1e-6] [--calls 5000] [--runs 21]
        [--set tolerance=1e-6 ...]

--set gives a parameter of ours a value other than its default, in every FMU of ours that has
it (the trivial FMU keeps its defaults).

The trivial FMU's path may be its .fmu, the folder it was unpacked into, or its shared library
inside such a folder (binaries/linux64/Dahlquist.so, modelDescription.xml two folders up).
Linux (linux64 binaries) only.
"""
import argparse
import ctypes
import pathlib
import statistics
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
import zipfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
MODELS = ["LongitudinalFriction", "TransverseFriction", "DryFrictionOscillator", "DriveTrain"]

# The logger is variadic in C; ctypes cannot define one, so this one takes the first variadic
# argument as a pointer, where the x86-64 System V convention puts it: an FMU that logs with the
# format "%s" passes its message there.
LOGGER = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p,
                          ctypes.c_char_p, ctypes.c_void_p)
ALLOCATE = ctypes.CFUNCTYPE(ctypes.c_void_p, ctypes.c_size_t, ctypes.c_size_t)
FREE = ctypes.CFUNCTYPE(None, ctypes.c_void_p)
STEP_FINISHED = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_int)


class Callbacks(ctypes.Structure):
    _fields_ = [("logger", LOGGER), ("allocateMemory", ALLOCATE), ("freeMemory", FREE),
                ("stepFinished", STEP_FINISHED), ("componentEnvironment", ctypes.c_void_p)]


messages = []


@LOGGER
def _log(_env, _name, status, category, message, argument):
    if message == b"%s" and argument:
        message = ctypes.string_at(argument)
    messages.append((status, (category or b"").decode(), (message or b"").decode(errors="replace")))


_libc = ctypes.CDLL(None)
_libc.calloc.restype = ctypes.c_void_p
_libc.calloc.argtypes = [ctypes.c_size_t, ctypes.c_size_t]
_libc.free.argtypes = [ctypes.c_void_p]
CALLBACKS = Callbacks(_log, ALLOCATE(_libc.calloc), FREE(_libc.free), STEP_FINISHED(0), None)


class Fmu:
    """One FMU's library with the FMI 2.0 functions this benchmark calls."""

    def __init__(self, path, scratch):
        path = pathlib.Path(path)
        if path.suffix == ".fmu":
            root = pathlib.Path(tempfile.mkdtemp(dir=scratch))
            with zipfile.ZipFile(path) as z:
                z.extractall(root)
        elif path.is_dir():
            root = path
        else:
            root = path.resolve().parents[2]
        md = ET.parse(root / "modelDescription.xml").getroot()
        self.guid = md.get("guid")
        self.name = md.find("CoSimulation").get("modelIdentifier")
        self.outputs = [int(v.get("valueReference")) for v in md.iter("ScalarVariable")
                        if v.get("causality") == "output" and v.find("Real") is not None]
        # name -> (value reference, whether it is Real), for --set.
        self.variables = {v.get("name"): (int(v.get("valueReference")), v.find("Real") is not None)
                          for v in md.iter("ScalarVariable")}
        self.start_values = {}
        library = path if path.suffix == ".so" else root / "binaries" / "linux64" / f"{self.name}.so"
        self.root = root
        self.label = self.name
        self.path = path
        lib = ctypes.CDLL(str(library))
        self.instantiate = lib.fmi2Instantiate
        self.instantiate.restype = ctypes.c_void_p
        self.instantiate.argtypes = [ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p,
                                     ctypes.c_char_p, ctypes.POINTER(Callbacks), ctypes.c_int,
                                     ctypes.c_int]
        self.setup = lib.fmi2SetupExperiment
        self.setup.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_double, ctypes.c_double,
                               ctypes.c_int, ctypes.c_double]
        self.enter = lib.fmi2EnterInitializationMode
        self.enter.argtypes = [ctypes.c_void_p]
        self.exit = lib.fmi2ExitInitializationMode
        self.exit.argtypes = [ctypes.c_void_p]
        self.do_step = lib.fmi2DoStep
        self.do_step.argtypes = [ctypes.c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_int]
        self.get_real = lib.fmi2GetReal
        self.get_real.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint32), ctypes.c_size_t,
                                  ctypes.POINTER(ctypes.c_double)]
        self.set_real = lib.fmi2SetReal
        self.set_real.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint32), ctypes.c_size_t,
                                  ctypes.POINTER(ctypes.c_double)]
        self.set_integer = lib.fmi2SetInteger
        self.set_integer.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint32),
                                     ctypes.c_size_t, ctypes.POINTER(ctypes.c_int)]
        self.free = lib.fmi2FreeInstance
        self.free.argtypes = [ctypes.c_void_p]
        self.free.restype = None

    def start(self):
        resources = (self.root / "resources").resolve().as_uri().encode()
        c = self.instantiate(b"per_call", 1, self.guid.encode(), resources,
                             ctypes.byref(CALLBACKS), 0, 0)
        if not c:
            raise SystemExit(f"{self.name}: fmi2Instantiate failed: {messages[-3:]}")
        statuses = [self.setup(c, 0, 0.0, 0.0, 0, 0.0), self.enter(c)]
        for name, value in self.start_values.items():
            vr, real = self.variables[name]
            if real:
                setter, number = self.set_real, (ctypes.c_double * 1)(value)
            else:
                setter, number = self.set_integer, (ctypes.c_int * 1)(round(value))
            statuses.append(setter(c, (ctypes.c_uint32 * 1)(vr), 1, number))
        statuses.append(self.exit(c))
        if any(status > 1 for status in statuses):
            raise SystemExit(f"{self.name}: initialisation failed: {messages[-3:]}")
        return c

    def run(self, points, read):
        """CPU seconds per doStep over `points` ((t, h) pairs), a fresh instance."""
        c = self.start()
        do_step = self.do_step
        n = len(self.outputs)
        vrs = (ctypes.c_uint32 * n)(*self.outputs)
        values = (ctypes.c_double * n)()
        get_real = self.get_real
        try:
            started = time.process_time()
            if read:
                for t, h in points:
                    if do_step(c, t, h, 1) > 1 or get_real(c, vrs, n, values) > 1:
                        raise SystemExit(f"{self.name}: failed at t = {t}: {messages[-3:]}")
            else:
                for t, h in points:
                    if do_step(c, t, h, 1) > 1:
                        raise SystemExit(f"{self.name}: fmi2DoStep failed at t = {t}: {messages[-3:]}")
            return (time.process_time() - started) / len(points)
        finally:
            self.free(c)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("trivial", help="the Dahlquist FMU (.fmu, unpacked folder, or its .so)")
    parser.add_argument("--fmu", action="append",
                        help="an FMU of ours (repeat; default: fmu-out/<Model>.fmu for each model)")
    parser.add_argument("--step", type=float, default=1e-6, help="communication step h (s)")
    parser.add_argument("--calls", type=int, default=5000, help="doSteps per run")
    parser.add_argument("--runs", type=int, default=21, help="runs per FMU (median taken)")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="a parameter of ours, in every FMU of ours that has it (repeat)")
    args = parser.parse_args()
    if args.runs < 1 or args.calls < 1:
        parser.error("--runs and --calls must be >= 1")
    ours = args.fmu or [str(ROOT / "fmu-out" / f"{m}.fmu") for m in MODELS]

    with tempfile.TemporaryDirectory() as scratch:
        trivial = Fmu(args.trivial, scratch)
        fmus = [trivial] + [Fmu(p, scratch) for p in ours]
        for setting in args.set:
            name, _, value = setting.partition("=")
            for fmu in fmus[1:]:
                if name in fmu.variables:
                    fmu.start_values[name] = float(value)
        names = [f.name for f in fmus]
        for fmu in fmus:
            # FMUs of one model from two builds (before and after a change) by their folders.
            if names.count(fmu.name) > 1:
                fmu.label = f"{fmu.name} ({fmu.path.resolve().parent.name})"
        points = [(i * args.step, (i + 1) * args.step - i * args.step) for i in range(args.calls)]
        settings = f", ours with {', '.join(args.set)}" if args.set else ", each at its defaults"
        print(f"fmi2DoStep at h = {args.step:g} s, {args.calls} calls a run from t = 0{settings}; "
              f"CPU time of the process (time.process_time), median of {args.runs} alternating "
              f"runs; Python {sys.version.split()[0]}, ctypes.\n")
        for read in (False, True):
            times = [[] for _ in fmus]
            for run in range(args.runs):
                # Each run in another order, so that a drift of the machine's speed is shared.
                shift = run % len(fmus)
                for i in list(range(len(fmus)))[shift:] + list(range(len(fmus)))[:shift]:
                    times[i].append(fmus[i].run(points, read))
            what = "fmi2DoStep, then fmi2GetReal of every output" if read else "fmi2DoStep alone"
            print(f"{what}:\n")
            print("| model | CPU us per call | minus the trivial FMU's (us) | that difference's quartiles (us) |")
            print("|---|---|---|---|")
            for fmu, t in zip(fmus, times):
                differences = sorted((a - b) * 1e6 for a, b in zip(t, times[0]))
                quartiles = statistics.quantiles(differences, n=4) if len(t) > 1 else differences * 3
                print(f"| {fmu.label} | {statistics.median(t) * 1e6:.3f} | "
                      f"{statistics.median(differences):+.3f} | "
                      f"{quartiles[0]:+.3f} to {quartiles[2]:+.3f} |")
            print()
        warnings = [m for m in messages if m[0] == 1]
        if warnings:
            print(f"{len(warnings)} warnings logged, the first: {warnings[0][2]}")


if __name__ == "__main__":
    main()
