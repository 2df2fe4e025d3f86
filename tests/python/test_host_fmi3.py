"""Every FMU through a plain C FMI 3.0 host (tests/host/fmu_host3.c), compiled against the FMI 3.0
headers, natively with gcc, on the win64 library under wine with mingw, and on the aarch64-linux
library under qemu-aarch64 with aarch64-linux-gnu-gcc: its run of the DefaultExperiment through
fmi3InstantiateCoSimulation .. fmi3DoStep .. fmi3FreeInstance equals the FMI 2.0 host's
(tests/host/fmu_host.c) run of the FMI 2.0 FMU within 1e-12 of each output's range, on the same
platform (aarch64: against x86_64's). Every status must be fmi3OK, every step must end where it was asked to, and
a wrong instantiationToken is refused with a logged message.

The FMU run is fmu-out/fmi3/<name>.fmu where it has been packed; else the FMI 2.0 FMU's own
directory, whose library exports the fmi3 functions too (its GUID is the token).

The FMI 3.0 headers are not part of this repository: the host is compiled against the copy fmpy
(tests/python/requirements.txt) ships in fmpy/c-code, or else the fmi-sys crate's in cargo's
registry (the `fmi` dev-dependency's). They are BSD-2-Clause, (C) Modelica Association Project
"FMI".
"""
import glob
import os
import pathlib
import shutil
import subprocess
import zipfile

import fmpy
import numpy as np
import pytest

from conftest import FMU_DIR, ROOT
from test_host import MINGW, WINE, read_csv, run_host

HOST = ROOT / "tests" / "host"
QEMU = shutil.which("qemu-aarch64")
AARCH64_GCC = shutil.which("aarch64-linux-gnu-gcc")
# Where libc6-arm64-cross puts the aarch64 loader and C library, for qemu-aarch64 -L.
AARCH64_SYSROOT = "/usr/aarch64-linux-gnu"
FMI2_FMUS = sorted(FMU_DIR.glob("*.fmu")) + sorted((FMU_DIR / "variants").glob("*.fmu"))
IDS = [str(f.relative_to(FMU_DIR).with_suffix("")) for f in FMI2_FMUS]
# Under wine and qemu a run costs seconds: the full models and a variant of each kind (the FMI 2.0
# host runs every FMU's win64 and aarch64-linux library, tests/python/test_host.py).
EMULATED_RUNS = ["LongitudinalFriction", "TransverseFriction", "DryFrictionOscillator", "DriveTrain",
             "variants/Fig8", "variants/OscillatorFig1"]


def fmi3_headers():
    """The directory of an installed copy of fmi3FunctionTypes.h and the headers it includes."""
    candidates = [pathlib.Path(fmpy.__file__).parent / "c-code"]
    registry = pathlib.Path(os.environ.get("CARGO_HOME", pathlib.Path.home() / ".cargo")) / "registry" / "src"
    candidates += sorted(pathlib.Path(p) for p in glob.glob(str(registry / "*" / "fmi-sys-*" / "fmi-standard3" / "headers")))
    for candidate in candidates:
        if (candidate / "fmi3FunctionTypes.h").is_file() and (candidate / "fmi3PlatformTypes.h").is_file():
            return candidate
    pytest.fail(f"no FMI 3.0 headers in {[str(c) for c in candidates]}: install fmpy (tests/python/requirements.txt)")


@pytest.fixture(scope="module")
def hosts(tmp_path_factory):
    """{platform: (FMI 2.0 host, FMI 3.0 host)}, each a command prefix, for the platforms this
    machine can build and run."""
    directory = tmp_path_factory.mktemp("host3")
    headers = fmi3_headers()
    native2, native3 = directory / "fmu_host", directory / "fmu_host3"
    subprocess.run(["gcc", "-O2", "-Wall", "-Werror", "-o", str(native2), str(HOST / "fmu_host.c"), "-ldl"],
                   check=True)
    subprocess.run(["gcc", "-O2", "-Wall", "-Wextra", "-Werror", "-I", str(headers), "-o", str(native3),
                    str(HOST / "fmu_host3.c"), "-ldl"], check=True)
    hosts = {"linux": ([str(native2)], [str(native3)])}
    if os.environ.get("CI") and not (WINE and MINGW):
        pytest.fail("CI runs the win64 checks: tests/run.sh installs wine and mingw-w64")
    if WINE and MINGW:
        exe2, exe3 = directory / "fmu_host.exe", directory / "fmu_host3.exe"
        subprocess.run([MINGW, "-O2", "-Wall", "-Werror", "-o", str(exe2), str(HOST / "fmu_host.c")], check=True)
        subprocess.run([MINGW, "-O2", "-Wall", "-Wextra", "-Werror", "-I", str(headers), "-o", str(exe3),
                        str(HOST / "fmu_host3.c")], check=True)
        subprocess.run([MINGW, "-O2", "-shared", "-o", str(directory / "bcryptprimitives.dll"),
                        str(HOST / "bcryptprimitives.c"), "-ladvapi32"], check=True)
        hosts["windows"] = ([WINE, str(exe2)], [WINE, str(exe3)])
    if os.environ.get("CI") and not (QEMU and AARCH64_GCC):
        pytest.fail("CI runs the aarch64 checks: tests/run.sh installs qemu-user and gcc-aarch64-linux-gnu")
    if QEMU and AARCH64_GCC:
        # Against the x86_64 FMI 2.0 host: aarch64 has no FMI 2.0 platform name.
        arm = directory / "fmu_host3_aarch64"
        subprocess.run([AARCH64_GCC, "-O2", "-Wall", "-Wextra", "-Werror", "-I", str(headers), "-o", str(arm),
                        str(HOST / "fmu_host3.c"), "-ldl"], check=True)
        hosts["aarch64"] = ([str(native2)], [QEMU, "-L", AARCH64_SYSROOT, str(arm)])
    return hosts


def extract(fmu, directory):
    directory.mkdir()
    with zipfile.ZipFile(fmu) as archive:
        archive.extractall(directory)
    return directory


def fmi3_twin(fmi2_fmu, tmp_path):
    """The directory the FMI 3.0 host runs: the extracted FMI 3.0 FMU of the same name if it has
    been packed, else the FMI 2.0 FMU's."""
    twin = FMU_DIR / "fmi3" / fmi2_fmu.relative_to(FMU_DIR)
    return extract(twin if twin.exists() else fmi2_fmu, tmp_path / "fmi3")


@pytest.mark.parametrize("platform", ["linux", "windows", "aarch64"])
@pytest.mark.parametrize("fmu", FMI2_FMUS, ids=IDS)
def test_the_fmi3_host_runs_the_default_experiment_as_the_fmi2_host_does(platform, fmu, hosts, tmp_path):
    name = str(fmu.relative_to(FMU_DIR).with_suffix(""))
    if platform not in hosts:
        pytest.skip("no wine and mingw-w64 here" if platform == "windows"
                    else "no qemu-user and gcc-aarch64-linux-gnu here")
    if platform != "linux" and name not in EMULATED_RUNS:
        pytest.skip("emulated: the full models and a variant of each kind")
    host2, host3 = hosts[platform]
    directory3 = fmi3_twin(fmu, tmp_path)
    if platform == "aarch64" and not (directory3 / "binaries" / "aarch64-linux").is_dir():
        pytest.skip("no aarch64-linux library in fmu-out/fmi3: `friction-fmu build` says why")
    status, out2, err = run_host(host2, extract(fmu, tmp_path / "fmi2"))
    assert status == 0, err[-3000:]
    status, out3, err = run_host(host3, directory3)
    assert status == 0, err[-3000:]
    fmi2_run, fmi3_run = read_csv(out2), read_csv(out3)
    assert list(fmi3_run) == list(fmi2_run)
    assert np.array_equal(fmi3_run["time"], fmi2_run["time"])
    for output, want in fmi2_run.items():
        scale = np.ptp(want) or np.max(np.abs(want)) or 1.0
        error = np.max(np.abs(fmi3_run[output] - want)) / scale
        assert error <= 1e-12, f"{name}.{output}: {error:.1e} of its range"


@pytest.mark.parametrize("platform", ["linux", "windows"])
@pytest.mark.parametrize("fmu, given", [("TransverseFriction", None), ("DriveTrain", "DryFrictionOscillator"),
                                        ("variants/Fig8", "TransverseFriction")])
def test_a_token_but_its_own_fmus_is_refused_with_a_logged_message(platform, fmu, given, hosts, tmp_path):
    if platform not in hosts:
        pytest.skip("no wine and mingw-w64 here")
    directory = fmi3_twin(FMU_DIR / f"{fmu}.fmu", tmp_path)
    wrong = fmpy.read_model_description(str(FMU_DIR / f"{given}.fmu")).guid if given else "{00000000-0000-0000-0000-000000000000}"
    status, _, err = run_host(hosts[platform][1], directory, "--token", wrong)
    assert status == 1 and "fmi3InstantiateCoSimulation: NULL" in err, err
    assert (f'log status 3 [logStatusError]: fmi3InstantiateCoSimulation: instantiationToken "{wrong}" matches no model'
            in err), err


@pytest.mark.parametrize("fmu", ["TransverseFriction", "variants/Table1Dahl"])
def test_loading_and_unloading_through_fmi3_leaks_nothing(fmu, hosts, tmp_path):
    """valgrind's leak check over three cycles of dlopen, a short run, fmi3FreeInstance and dlclose."""
    if not shutil.which("valgrind"):
        if os.environ.get("CI"):
            pytest.fail("CI runs the leak check: tests/run.sh installs valgrind")
        pytest.skip("no valgrind here")
    directory = fmi3_twin(FMU_DIR / f"{fmu}.fmu", tmp_path)
    done = subprocess.run(["valgrind", "--leak-check=full", "--errors-for-leak-kinds=definite",
                           "--error-exitcode=9", "-q", *hosts["linux"][1], str(directory),
                           "--cycles", "3", "--steps", "20"],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
