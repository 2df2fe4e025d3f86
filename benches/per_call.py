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

--standard 3 times, in the same runs, each FMU of ours through FMI 3.0 beside FMI 2.0: its
fmi3DoStep (after fmi3InstantiateCoSimulation, fmi3EnterInitializationMode and
fmi3ExitInitializationMode; its four output arguments point to variables made once a run) beside
its fmi2DoStep, and the Reference FMUs' FMI 3.0 Dahlquist beside their FMI 2.0 one, with the same
points. Each run visits the models in another order, a model's two standards one after the other
(which first alternates from run to run). For each model it prints the median cost of either
standard, the median of the runs' differences FMI 3 minus FMI 2, and that difference less
Dahlquist's in the same run (what our FMI 3 boundary costs more than our FMI 2 one beyond what
the call's own arguments cost ctypes more). The FMI 3.0 Dahlquist is built as above with
-DFMI_VERSION=3 (binaries/x86_64-linux):

    cmake -S Reference-FMUs -B /tmp/reference-fmus-fmi3 -DFMI_VERSION=3 -DCMAKE_BUILD_TYPE=Release
    cmake --build /tmp/reference-fmus-fmi3 --target Dahlquist
    .venv/bin/python benches/per_call.py /tmp/reference-fmus/fmus/Dahlquist.fmu --standard 3 \
        --trivial3 /tmp/reference-fmus-fmi3/fmus/Dahlquist.fmu [--fmu3 ...]

Our FMI 3.0 FMUs are fmu-out/fmi3/<Model>.fmu where they exist (binaries/x86_64-linux); where
they do not, and for every --fmu given without --fmu3, the FMI 3.0 functions of the FMI 2.0
FMU's own library, which exports both (instantiationToken: the FMI 2.0 GUID). --fmu3 (repeat)
names them, in the order of the FMI 2.0 ones.
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

# FMI 3.0's logger is not variadic: (instanceEnvironment, status, category, message).
LOG_MESSAGE = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_int, ctypes.c_char_p,
                               ctypes.c_char_p)


@LOG_MESSAGE
def _log3(_env, status, category, message):
    messages.append((status, (category or b"").decode(), (message or b"").decode(errors="replace")))


_unpacked = {}


def unpack(path, scratch):
    """The folder an FMU was unpacked into: a .fmu once per path (so that its FMI 2.0 and FMI 3.0
    sides load the same library), a folder as it is, a library's folder two levels up."""
    path = pathlib.Path(path)
    if path.suffix == ".fmu":
        key = path.resolve()
        if key not in _unpacked:
            _unpacked[key] = pathlib.Path(tempfile.mkdtemp(dir=scratch))
            with zipfile.ZipFile(path) as z:
                z.extractall(_unpacked[key])
        return _unpacked[key]
    if path.is_dir():
        return path
    return path.resolve().parents[2]


class Fmu:
    """One FMU's library with the FMI 2.0 functions this benchmark calls."""

    def __init__(self, path, scratch):
        path = pathlib.Path(path)
        root = unpack(path, scratch)
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


class Fmu3:
    """One FMU's library with the FMI 3.0 functions this benchmark calls: an FMI 3.0 FMU's, or an
    FMI 2.0 FMU's of ours, whose library exports both (its GUID is the instantiationToken)."""

    def __init__(self, path, scratch):
        path = pathlib.Path(path)
        root = unpack(path, scratch)
        md = ET.parse(root / "modelDescription.xml").getroot()
        self.name = md.find("CoSimulation").get("modelIdentifier")
        # name -> (value reference, setter's type), for --set; outputs' value references.
        self.variables = {}
        self.outputs = []
        if md.get("fmiVersion", "").startswith("2."):
            self.token = md.get("guid")
            platform = "linux64"
            for v in md.iter("ScalarVariable"):
                vr = int(v.get("valueReference"))
                if v.find("Real") is not None:
                    kind = "Float64"
                    if v.get("causality") == "output":
                        self.outputs.append(vr)
                elif v.find("Integer") is not None:
                    # A switch (an Integer of a declared type here) is an Enumeration in FMI 3.0.
                    kind = "Int64" if v.find("Integer").get("declaredType") else "Int32"
                elif v.find("Enumeration") is not None:
                    kind = "Int64"
                else:
                    kind = "Boolean"
                self.variables[v.get("name")] = (vr, kind)
        else:
            self.token = md.get("instantiationToken")
            platform = "x86_64-linux"
            kinds = {"Float64": "Float64", "Int32": "Int32", "Enumeration": "Int64",
                     "Int64": "Int64", "Boolean": "Boolean"}
            for v in md.find("ModelVariables"):
                if v.get("valueReference") is None:
                    continue
                vr = int(v.get("valueReference"))
                if v.tag == "Float64" and v.get("causality") == "output":
                    self.outputs.append(vr)
                if v.tag in kinds:
                    self.variables[v.get("name")] = (vr, kinds[v.tag])
        self.start_values = {}
        library = path if path.suffix == ".so" else root / "binaries" / platform / f"{self.name}.so"
        self.root = root
        self.label = self.name
        self.path = path
        lib = ctypes.CDLL(str(library))
        self.instantiate = lib.fmi3InstantiateCoSimulation
        self.instantiate.restype = ctypes.c_void_p
        self.instantiate.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p,
                                     ctypes.c_bool, ctypes.c_bool, ctypes.c_bool, ctypes.c_bool,
                                     ctypes.POINTER(ctypes.c_uint32), ctypes.c_size_t,
                                     ctypes.c_void_p, LOG_MESSAGE, ctypes.c_void_p]
        self.enter = lib.fmi3EnterInitializationMode
        self.enter.argtypes = [ctypes.c_void_p, ctypes.c_bool, ctypes.c_double, ctypes.c_double,
                               ctypes.c_bool, ctypes.c_double]
        self.exit = lib.fmi3ExitInitializationMode
        self.exit.argtypes = [ctypes.c_void_p]
        self.do_step = lib.fmi3DoStep
        # The flag as a byte and the four output pointers as addresses: what ctypes converts
        # fastest (POINTER(c_bool) arguments and c_bool cost it about 1 us more a call here).
        self.do_step.argtypes = [ctypes.c_void_p, ctypes.c_double, ctypes.c_double,
                                 ctypes.c_uint8] + [ctypes.c_void_p] * 4
        self.get_real = lib.fmi3GetFloat64
        self.get_real.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint32),
                                  ctypes.c_size_t, ctypes.POINTER(ctypes.c_double),
                                  ctypes.c_size_t]
        self.setters = {}
        for kind, ctype in (("Float64", ctypes.c_double), ("Int32", ctypes.c_int32),
                            ("Int64", ctypes.c_int64), ("Boolean", ctypes.c_bool)):
            setter = getattr(lib, f"fmi3Set{kind}")
            setter.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint32), ctypes.c_size_t,
                               ctypes.POINTER(ctype), ctypes.c_size_t]
            self.setters[kind] = (setter, ctype)
        self.free = lib.fmi3FreeInstance
        self.free.argtypes = [ctypes.c_void_p]
        self.free.restype = None

    def start(self):
        resources = self.root / "resources"
        # FMI 3.0 gives the resources as a path ending in a separator, NULL where there are none.
        resources = (str(resources.resolve()) + "/").encode() if resources.is_dir() else None
        c = self.instantiate(b"per_call", self.token.encode(), resources, False, False, False,
                             False, None, 0, None, _log3, None)
        if not c:
            raise SystemExit(f"{self.name}: fmi3InstantiateCoSimulation failed: {messages[-3:]}")
        statuses = [self.enter(c, False, 0.0, 0.0, False, 0.0)]
        for name, value in self.start_values.items():
            vr, kind = self.variables[name]
            setter, ctype = self.setters[kind]
            number = (ctype * 1)(value if kind == "Float64" else round(value))
            statuses.append(setter(c, (ctypes.c_uint32 * 1)(vr), 1, number, 1))
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
        flags = (ctypes.c_bool * 3)()  # eventHandlingNeeded, terminateSimulation, earlyReturn
        last_time = ctypes.c_double()
        event, terminate, early = (ctypes.addressof(flags) + i for i in range(3))
        last = ctypes.addressof(last_time)
        try:
            started = time.process_time()
            if read:
                for t, h in points:
                    if (do_step(c, t, h, 1, event, terminate, early, last) > 1
                            or get_real(c, vrs, n, values, n) > 1):
                        raise SystemExit(f"{self.name}: failed at t = {t}: {messages[-3:]}")
            else:
                for t, h in points:
                    if do_step(c, t, h, 1, event, terminate, early, last) > 1:
                        raise SystemExit(f"{self.name}: fmi3DoStep failed at t = {t}: {messages[-3:]}")
            elapsed = time.process_time() - started
            if any(flags):
                raise SystemExit(f"{self.name}: fmi3DoStep asked to terminate or returned early")
            return elapsed / len(points)
        finally:
            self.free(c)


def interleaved(groups, runs, points, read):
    """Each FMU's CPU seconds a call in every run, by id: each run visits the groups in another
    order, the FMUs of a group one after the other, in the reverse order every other run."""
    times = {id(fmu): [] for group in groups for fmu in group}
    for run in range(runs):
        # Each run in another order, so that a drift of the machine's speed is shared.
        shift = run % len(groups)
        for group in groups[shift:] + groups[:shift]:
            for fmu in (group if run % 2 == 0 else group[::-1]):
                times[id(fmu)].append(fmu.run(points, read))
    return times


def quartiles_of(differences):
    return statistics.quantiles(differences, n=4) if len(differences) > 1 else differences * 3


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
    parser.add_argument("--standard", choices=["2", "3"], default="2",
                        help="3: each FMU through FMI 3.0 beside FMI 2.0, in the same runs")
    parser.add_argument("--trivial3", help="with --standard 3: the FMI 3.0 Dahlquist FMU")
    parser.add_argument("--fmu3", action="append",
                        help="with --standard 3: an FMI 3.0 FMU of ours, in the order of --fmu "
                             "(repeat; default: fmu-out/fmi3/<Model>.fmu where it exists, "
                             "otherwise the FMI 2.0 FMU's library)")
    args = parser.parse_args()
    if args.runs < 1 or args.calls < 1:
        parser.error("--runs and --calls must be >= 1")
    three = args.standard == "3"
    if three and not args.trivial3:
        parser.error("--standard 3 needs --trivial3, the FMI 3.0 Dahlquist FMU")
    ours = args.fmu or [str(ROOT / "fmu-out" / f"{m}.fmu") for m in MODELS]
    if three:
        if args.fmu3:
            if len(args.fmu3) != len(ours):
                parser.error(f"--fmu3 given {len(args.fmu3)} times for {len(ours)} FMI 2.0 FMUs")
            ours3 = args.fmu3
        elif args.fmu:
            ours3 = ours
        else:
            ours3 = []
            for m, p in zip(MODELS, ours):
                fmi3 = ROOT / "fmu-out" / "fmi3" / f"{m}.fmu"
                ours3.append(str(fmi3) if fmi3.exists() else p)

    with tempfile.TemporaryDirectory() as scratch:
        trivial = Fmu(args.trivial, scratch)
        fmus = [trivial] + [Fmu(p, scratch) for p in ours]
        groups = [[fmu] for fmu in fmus]
        if three:
            # Loaded after the FMI 2.0 ones, so that an FMI 2.0 FMU's .fmu is unpacked once.
            for group, path in zip(groups, [args.trivial3] + ours3):
                group.append(Fmu3(path, scratch))
        for setting in args.set:
            name, _, value = setting.partition("=")
            for group in groups[1:]:
                for fmu in group:
                    if name in fmu.variables:
                        fmu.start_values[name] = float(value)
        names = [f.name for f in fmus]
        for group in groups:
            # FMUs of one model from two builds (before and after a change) by their folders.
            if names.count(group[0].name) > 1:
                for fmu in group:
                    fmu.label = f"{fmu.name} ({group[0].path.resolve().parent.name})"
        points = [(i * args.step, (i + 1) * args.step - i * args.step) for i in range(args.calls)]
        settings = f", ours with {', '.join(args.set)}" if args.set else ", each at its defaults"
        called = "fmi2DoStep and fmi3DoStep" if three else "fmi2DoStep"
        print(f"{called} at h = {args.step:g} s, {args.calls} calls a run from t = 0{settings}; "
              f"CPU time of the process (time.process_time), median of {args.runs} alternating "
              f"runs; Python {sys.version.split()[0]}, ctypes.\n")
        if three:
            for group in groups:
                same = group[1].root == group[0].root and group[1].token == group[0].guid
                print(f"{group[0].label}: FMI 2.0 {group[0].path}, FMI 3.0 {group[1].path}"
                      + (" (its FMI 3.0 functions)" if same else ""))
            print()
        for read in (False, True):
            times = interleaved(groups, args.runs, points, read)
            if three:
                what = ("each doStep, then the getter (fmi2GetReal, fmi3GetFloat64) of every output"
                        if read else "doStep alone")
                print(f"{what}:\n")
                print("| model | FMI 2: CPU us per call | FMI 3: CPU us per call "
                      "| FMI 3 minus FMI 2, median (quartiles), us "
                      "| the same less Dahlquist's in its run, median (quartiles), us |")
                print("|---|---|---|---|---|")
                d2, d3 = times[id(groups[0][0])], times[id(groups[0][1])]
                for fmu2, fmu3 in groups:
                    t2, t3 = times[id(fmu2)], times[id(fmu3)]
                    cells = []
                    for differences in ([(a - b) * 1e6 for a, b in zip(t3, t2)],
                                        [(a - b - (c - d)) * 1e6
                                         for a, b, c, d in zip(t3, t2, d3, d2)]):
                        q = quartiles_of(sorted(differences))
                        cells.append(f"{statistics.median(differences):+.3f} "
                                     f"({q[0]:+.3f} to {q[2]:+.3f})")
                    if fmu2 is trivial:
                        cells[1] = ""
                    print(f"| {fmu2.label} | {statistics.median(t2) * 1e6:.3f} | "
                          f"{statistics.median(t3) * 1e6:.3f} | {cells[0]} | {cells[1]} |")
                print()
                continue
            what = "fmi2DoStep, then fmi2GetReal of every output" if read else "fmi2DoStep alone"
            print(f"{what}:\n")
            print("| model | CPU us per call | minus the trivial FMU's (us) | that difference's quartiles (us) |")
            print("|---|---|---|---|")
            t0 = times[id(trivial)]
            for fmu in fmus:
                t = times[id(fmu)]
                differences = sorted((a - b) * 1e6 for a, b in zip(t, t0))
                quartiles = quartiles_of(differences)
                print(f"| {fmu.label} | {statistics.median(t) * 1e6:.3f} | "
                      f"{statistics.median(differences):+.3f} | "
                      f"{quartiles[0]:+.3f} to {quartiles[2]:+.3f} |")
            print()
        warnings = [m for m in messages if m[0] == 1]
        if warnings:
            print(f"{len(warnings)} warnings logged, the first: {warnings[0][2]}")


if __name__ == "__main__":
    main()
