"""Every FMU (full and variant) through a plain C host (tests/host/fmu_host.c), as a tool vendor's
importer would load it: built with gcc and run natively on binaries/linux64, built with
x86_64-w64-mingw32-gcc and run under wine on binaries/win64, and built with aarch64-linux-gnu-gcc
and run under qemu-aarch64 on the aarch64-linux library of the FMU's FMI 3.0 twin (FMI 2.0 names
no aarch64 platform; the host calls the library's fmi2 functions). Against fmpy's run of the
same DefaultExperiment: bit for bit natively (the same library and maths), within 1e-8 of each
output's range under wine (Windows' maths library rounds some functions differently), within
1e-12 under qemu. Every status must be fmi2OK, and a wrong GUID is refused with a logged message
on both x86_64 platforms.

Wine 8 lacks bcryptprimitives.dll, which Rust's standard library imports (ProcessPrng) and every
Windows 10 and 11 has: the test builds a stand-in (tests/host/bcryptprimitives.c) next to the
host program. An FMU never carries it.
"""
import os
import pathlib
import re
import shutil
import subprocess
import zipfile

import fmpy
import numpy as np
import pytest

from conftest import FMU_DIR, ROOT

HOST = ROOT / "tests" / "host"
FMUS = sorted(FMU_DIR.glob("*.fmu")) + sorted((FMU_DIR / "variants").glob("*.fmu"))
WINE = shutil.which("wine")
MINGW = shutil.which("x86_64-w64-mingw32-gcc")
QEMU = shutil.which("qemu-aarch64")
AARCH64_GCC = shutil.which("aarch64-linux-gnu-gcc")
# Where libc6-arm64-cross puts the aarch64 loader and C library, for qemu-aarch64 -L.
AARCH64_SYSROOT = "/usr/aarch64-linux-gnu"
AARCH64 = "aarch64-linux"
# Each output within this fraction of its range of x86_64's: the same Rust code, but another
# instruction set may contract a multiply and an add into one rounding.
AARCH64_BOUND = 1e-12


@pytest.fixture(scope="module")
def hosts(tmp_path_factory):
    """{platform: command prefix} of the host programs this machine can build and run."""
    directory = tmp_path_factory.mktemp("host")
    native = directory / "fmu_host"
    subprocess.run(["gcc", "-O2", "-Wall", "-Werror", "-o", str(native), str(HOST / "fmu_host.c"), "-ldl"],
                   check=True)
    hosts = {"linux64": [str(native)]}
    if os.environ.get("CI") and not (WINE and MINGW):
        pytest.fail("CI runs the win64 checks: tests/run.sh installs wine and mingw-w64")
    if WINE and MINGW:
        exe = directory / "fmu_host.exe"
        subprocess.run([MINGW, "-O2", "-Wall", "-Werror", "-o", str(exe), str(HOST / "fmu_host.c")], check=True)
        subprocess.run([MINGW, "-O2", "-shared", "-o", str(directory / "bcryptprimitives.dll"),
                        str(HOST / "bcryptprimitives.c"), "-ladvapi32"], check=True)
        hosts["win64"] = [WINE, str(exe)]
    if os.environ.get("CI") and not (QEMU and AARCH64_GCC):
        pytest.fail("CI runs the aarch64 checks: tests/run.sh installs qemu-user and gcc-aarch64-linux-gnu")
    if QEMU and AARCH64_GCC:
        arm = directory / "fmu_host_aarch64"
        subprocess.run([AARCH64_GCC, "-O2", "-Wall", "-Werror", f'-DPLATFORM="{AARCH64}"', "-o", str(arm),
                        str(HOST / "fmu_host.c"), "-ldl"], check=True)
        hosts[AARCH64] = [QEMU, "-L", AARCH64_SYSROOT, str(arm)]
    return hosts


def fmi3_twin(fmu):
    """The FMI 3.0 FMU packed beside an FMI 2.0 one (fmu-out/fmi3/, fmu-out/fmi3/variants/)."""
    relative = fmu.relative_to(FMU_DIR)
    return FMU_DIR / "fmi3" / relative


def wine_environment():
    return {**os.environ, "WINEDEBUG": "-all", "WINEDLLOVERRIDES": "mscoree,mshtml=", "DISPLAY": ""}


def run_host(command, directory, *extra):
    """The host's exit status, standard output and standard error. Both go to files, not pipes:
    wine's background processes inherit a pipe and hold it open for seconds after the host has
    exited, and reading a pipe waits for them."""
    out, err = directory / "host.out", directory / "host.err"
    with open(out, "w") as stdout, open(err, "w") as stderr:
        status = subprocess.run([*command, str(directory), *extra], stdin=subprocess.DEVNULL, stdout=stdout,
                                stderr=stderr, timeout=600, env=wine_environment()).returncode
    return status, out.read_text(), err.read_text()


def read_csv(text):
    lines = text.strip().splitlines()
    names = lines[0].split(",")
    table = np.array([[float(x) for x in line.split(",")] for line in lines[1:]])
    return {name: table[:, i] for i, name in enumerate(names)}


@pytest.fixture(scope="module")
def fmpy_runs():
    runs = {}
    for fmu in FMUS:
        md = fmpy.read_model_description(str(fmu))
        outputs = [v.name for v in md.modelVariables if v.causality == "output" and v.type == "Real"]
        experiment = md.defaultExperiment
        runs[fmu.stem] = fmpy.simulate_fmu(str(fmu), stop_time=float(experiment.stopTime),
                                           output_interval=float(experiment.stepSize), output=outputs)
    return runs


@pytest.mark.parametrize("platform", ["linux64", "win64"])
def test_every_fmu_carries_its_platforms_binary(platform):
    if platform == "win64" and not MINGW:
        pytest.skip("no mingw-w64 here: the FMUs carry linux64 only")
    for fmu in FMUS:
        with zipfile.ZipFile(fmu) as archive:
            extension = "dll" if platform == "win64" else "so"
            assert f"binaries/{platform}/{fmu.stem}.{extension}" in archive.namelist(), fmu.name


@pytest.mark.parametrize("platform", ["linux64", "win64", AARCH64])
@pytest.mark.parametrize("fmu", FMUS, ids=[f.stem for f in FMUS])
def test_the_c_host_runs_the_default_experiment_as_fmpy_does(platform, fmu, hosts, fmpy_runs, tmp_path):
    if platform not in hosts:
        pytest.skip("no wine and mingw-w64 here" if platform == "win64"
                    else "no qemu-user and gcc-aarch64-linux-gnu here")
    with zipfile.ZipFile(fmu) as archive:
        archive.extractall(tmp_path)
    if platform == AARCH64:
        library = f"binaries/{AARCH64}/{fmu.stem}.so"
        with zipfile.ZipFile(fmi3_twin(fmu)) as archive:
            if library not in archive.namelist():
                pytest.skip(f"{fmi3_twin(fmu).name} carries no {AARCH64} library: `friction-fmu build` says why")
            archive.extract(library, tmp_path)
    status, out, err = run_host(hosts[platform], tmp_path)
    assert status == 0, err[-3000:]
    result, reference = read_csv(out), fmpy_runs[fmu.stem]
    assert len(result["time"]) == len(reference)
    for name in reference.dtype.names:
        if platform == "linux64":
            assert np.array_equal(result[name], reference[name]), name
        else:
            scale = np.ptp(reference[name]) or np.max(np.abs(reference[name])) or 1.0
            error = np.max(np.abs(result[name] - reference[name])) / scale
            bound = AARCH64_BOUND if platform == AARCH64 else 1e-8
            assert error <= bound, f"{name}: {error:.1e} of its range"


# A full FMU of each model and a variant FMU of each kind that reads a variant.
UNLOADED = ["LongitudinalFriction", "TransverseFriction", "DryFrictionOscillator", "DriveTrain",
            "variants/Table1Dahl", "variants/Fig8", "variants/OscillatorFig1"]


@pytest.mark.parametrize("fmu", UNLOADED)
def test_loading_and_unloading_a_library_leaks_nothing(fmu, hosts, tmp_path):
    """valgrind's leak check over three cycles of dlopen, a short run, fmi2FreeInstance and dlclose:
    nothing definitely lost (what a library keeps for its live instances goes with the last)."""
    if not shutil.which("valgrind"):
        if os.environ.get("CI"):
            pytest.fail("CI runs the leak check: tests/run.sh installs valgrind")
        pytest.skip("no valgrind here")
    with zipfile.ZipFile(FMU_DIR / f"{fmu}.fmu") as archive:
        archive.extractall(tmp_path)
    done = subprocess.run(["valgrind", "--leak-check=full", "--errors-for-leak-kinds=definite",
                           "--error-exitcode=9", "-q", *hosts["linux64"], str(tmp_path),
                           "--cycles", "3", "--steps", "20"],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]


def guid(fmu):
    return fmpy.read_model_description(str(fmu)).guid


# (FMU, the FMU whose GUID it is given): a made-up GUID, another model's, and, for a variant FMU,
# its own full model's. Each library carries its FMU's model alone and accepts its GUID alone.
WRONG_GUIDS = [
    ("TransverseFriction", None),
    ("LongitudinalFriction", "TransverseFriction"),
    ("DriveTrain", "DryFrictionOscillator"),
    ("variants/Fig8", "TransverseFriction"),
    ("variants/Table1Dahl", "variants/Fig8"),
]


@pytest.mark.parametrize("platform", ["linux64", "win64"])
@pytest.mark.parametrize("fmu, given", WRONG_GUIDS)
def test_a_guid_but_its_own_fmus_is_refused_with_a_logged_message(platform, fmu, given, hosts, tmp_path):
    if platform not in hosts:
        pytest.skip("no wine and mingw-w64 here")
    with zipfile.ZipFile(FMU_DIR / f"{fmu}.fmu") as archive:
        archive.extractall(tmp_path)
    wrong = guid(FMU_DIR / f"{given}.fmu") if given else "{00000000-0000-0000-0000-000000000000}"
    status, _, err = run_host(hosts[platform], tmp_path, "--guid", wrong)
    assert status == 1 and "fmi2Instantiate: NULL" in err, err
    assert f'log host status 3 [logStatusError]: fmi2Instantiate: fmuGUID "{wrong}" matches no model' in err, err


def glibc_versions(library, objdump="objdump"):
    """The GLIBC_x.y symbol versions a library needs, as tuples."""
    dynamic = subprocess.run([objdump, "-T", str(library)], capture_output=True, text=True, check=True).stdout
    return {tuple(int(n) for n in v.split(".")) for v in re.findall(r"GLIBC_([0-9.]+)\)?\s", dynamic)}


@pytest.mark.parametrize("platform", ["linux64", AARCH64])
@pytest.mark.parametrize("fmu", FMUS, ids=[f.stem for f in FMUS])
def test_the_linux_libraries_load_on_glibc_2_17_and_are_stripped(platform, fmu, tmp_path):
    packed = fmu if platform == "linux64" else fmi3_twin(fmu)
    with zipfile.ZipFile(packed) as archive:
        name = f"binaries/{platform}/{fmu.stem}.so"
        if name not in archive.namelist():
            pytest.skip(f"{packed.name} carries no {platform} library: `friction-fmu build` says why")
        library = pathlib.Path(archive.extract(name, tmp_path))
    # The host's objdump reads no aarch64 symbol table: binutils-aarch64-linux-gnu's does.
    objdump = "objdump" if platform == "linux64" else "aarch64-linux-gnu-objdump"
    if not shutil.which(objdump):
        pytest.skip(f"no {objdump} here")
    versions = glibc_versions(library, objdump)
    assert versions and max(versions) <= (2, 17), sorted(versions)[-3:]
    symbols = subprocess.run([objdump, "-t", str(library)], capture_output=True, text=True).stdout
    assert "no symbols" in symbols, symbols[:500]
