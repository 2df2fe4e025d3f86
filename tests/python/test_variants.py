"""Variants (variants/*.toml) packed by `friction-fmu build FILE.toml`: each FMU lists exactly
what its file keeps, with the file's start values and experiment; it computes what the full FMU
computes with the same values; it refuses what it hides; and a bad or tampered file is refused
with a message.

Oracles: the variants themselves (read here with tomllib, independently of the Rust parser)
and the full FMUs in fmu-out/ run with the same values.
"""
import os
import pathlib
import subprocess
import tomllib

import fmpy
import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

import conftest
from conftest import ROOT, Slave, fmu_path
from friction_fmu import switches

# The command the FMUs were packed with: tests/run.sh names the one its cargo test built.
BINARY = pathlib.Path(os.environ.get("FRICTION_FMU_BIN", ROOT / "target" / "release" / "friction-fmu"))
VARIANTS = sorted((ROOT / "variants").glob("*.toml"))
LAW_PARAMETER = {"LongitudinalFriction": "law", "TransverseFriction": "slip_law",
                 "DryFrictionOscillator": "law"}
# Communication steps simulated per comparison: enough for every figure's transient to show,
# few enough to keep the file fast.
COMPARED_STEPS = 300


def build(*arguments):
    assert BINARY.exists(), f"{BINARY} is missing: run `cargo build --release` first"
    return subprocess.run([str(BINARY), "build", *map(str, arguments)], capture_output=True,
                          text=True, cwd=ROOT)


@pytest.fixture(scope="module")
def packed(tmp_path_factory):
    """Every shipped variant packed into one temporary directory: {file stem: (variant, fmu)}."""
    out = tmp_path_factory.mktemp("variants")
    result = build(*VARIANTS, "--out", out)
    assert result.returncode == 0, result.stderr
    packed = {}
    for file in VARIANTS:
        variant = tomllib.loads(file.read_text())
        path = out / f"{variant['name']}.fmu"
        assert f"wrote {path}" in result.stdout
        packed[file.stem] = (variant, path)
    return packed


def kept_names(variant):
    return variant.get("tunable", []) + variant.get("inputs", []) + variant["outputs"]


def start_of(variant, name):
    """The start value the file gives a kept variable (law and solver by their top-level keys)."""
    law = LAW_PARAMETER[variant["model"]]
    if name == law:
        return variant["law"]
    if name == "solver":
        return variant["solver"]
    return variant["parameters"][name]


def item_value(md, name, item):
    return switches.value(md, name, item)


def full_start_values(variant):
    """Every value the file sets, as start values of the full FMU (items by their integers)."""
    md = fmpy.read_model_description(fmu_path(variant["model"]))
    values = dict(variant.get("parameters", {}))
    values[LAW_PARAMETER[variant["model"]]] = variant["law"]
    values["solver"] = variant["solver"]
    return {name: item_value(md, name, v) if isinstance(v, str) else v
            for name, v in values.items()}


def test_every_figure_and_table_has_a_variant():
    """Oracle: the papers' list: paper L Tables 1-3 (Coulomb and Dahl columns of Table 1),
    paper T Fig. 4a-8, paper O Fig. 1-4."""
    names = {tomllib.loads(f.read_text())["name"] for f in VARIANTS}
    expected = ({"Table1Dahl", "Table1Coulomb", "Table2", "Table3"}
                | {f"Fig{n}" for n in ["4a", "4b", "5", "6", "7", "8"]}
                | {f"OscillatorFig{n}" for n in range(1, 5)})
    assert names == expected


@pytest.mark.parametrize("stem", [f.stem for f in VARIANTS])
def test_model_description_keeps_exactly_what_the_file_lists(packed, stem):
    """Oracle: the variant read with tomllib, and the full model's variable order; fmpy's
    validator checks the rest of the XML (ModelStructure indices, declared types, units)."""
    variant, path = packed[stem]
    assert validate_fmu(str(path)) == []
    md = fmpy.read_model_description(str(path))
    assert md.coSimulation.modelIdentifier == variant["name"]
    assert md.description == variant["description"]
    assert [v.name for v in md.modelVariables] == [
        v.name for v in fmpy.read_model_description(fmu_path(variant["model"])).modelVariables
        if v.name in kept_names(variant)]
    assert len(md.modelVariables) == len(kept_names(variant))
    for var in md.modelVariables:
        if var.causality == "output":
            assert var.start is None
            continue
        expected = start_of(variant, var.name)
        if switches.items(var) is not None:
            assert var.start == str(item_value(md, var.name, expected)), var.name
        else:
            assert float(var.start) == float(expected), var.name
    experiment = variant["experiment"]
    assert float(md.defaultExperiment.startTime) == experiment["start"]
    assert float(md.defaultExperiment.stopTime) == experiment["stop"]
    assert float(md.defaultExperiment.stepSize) == experiment["step"]
    # The experiment's tolerance is the one the solver integrates to.
    solver_tolerance = {"LongitudinalFriction": "tolerance", "TransverseFriction": "tolerance",
                        "DryFrictionOscillator": "rtol"}[variant["model"]]
    if solver_tolerance in variant["parameters"]:
        expected = variant["parameters"][solver_tolerance]
    else:  # the model's default
        full = fmpy.read_model_description(fmu_path(variant["model"]))
        expected = next(v.start for v in full.modelVariables if v.name == solver_tolerance)
    assert float(md.defaultExperiment.tolerance) == float(expected)


@pytest.mark.parametrize("stem", [f.stem for f in VARIANTS])
def test_trimmed_fmu_computes_what_the_full_fmu_computes(packed, stem):
    """Oracle: the full FMU with every value the variant sets. A tunable parameter is moved
    off its start value in both (down, so Table 1's vc stays below va: above it S is 0 and only
    round-off is left to compare), so the check also covers the kept interface."""
    variant, path = packed[stem]
    experiment = variant["experiment"]
    step = experiment["step"]
    stop = min(experiment["stop"], experiment["start"] + COMPARED_STEPS * step)
    changed = {}
    for name in variant.get("tunable", [])[:1]:
        value = start_of(variant, name)
        if isinstance(value, float) and value != 0.0:
            changed[name] = 0.8 * value
    trimmed = fmpy.simulate_fmu(str(path), start_values=changed, stop_time=stop,
                                output_interval=step, output=variant["outputs"])
    full = fmpy.simulate_fmu(fmu_path(variant["model"]),
                             start_values={**full_start_values(variant), **changed},
                             start_time=experiment["start"], stop_time=stop,
                             output_interval=step, output=variant["outputs"])
    assert len(trimmed) == len(full) >= min(COMPARED_STEPS, (stop - experiment["start"]) / step)
    np.testing.assert_array_equal(trimmed["time"], full["time"])
    for name in variant["outputs"]:
        scale = np.max(np.abs(full[name]))
        assert scale > 0, name
        difference = np.max(np.abs(trimmed[name] - full[name]))
        # A variant that skips hidden work (a fixed va = 0, an unread mean) may take other solver
        # steps: equal to the solver's tolerance, far below this bound; otherwise to round-off.
        assert difference <= 1e-6 * scale, (name, difference, scale)


# Paper L (Leus & Gutowski 2008): Table 1 Dahl column (vc, FT_mean), Tables 2 and 3 (kt in
# N/um, FT_mean); the paper prints 3 significant digits, so within 1 %.
TABLE_1_DAHL = [(0.324, 0.0196), (0.264, 0.0196), (0.230, 0.0181), (0.199, 0.0156),
                (0.146, 0.0109), (0.095, 0.0066)]
TABLE_2 = [(0.030, 0.0186), (0.056, 0.0181), (0.120, 0.0172), (0.240, 0.0160), (0.480, 0.0148),
           (0.960, 0.0139)]
TABLE_3 = [(0.030, 0.0127), (0.056, 0.0109), (0.120, 0.00877), (0.240, 0.00783),
           (0.480, 0.00754), (0.960, 0.00742)]
FC = 0.1 * 0.02 * 9.81
VA = 0.264


@pytest.mark.parametrize("stem, tunable, rows, scale", [
    ("table1_dahl", "vc", TABLE_1_DAHL, 1.0),
    ("table1_coulomb", "vc", [(vc, FC * (2 / np.pi) * np.arcsin(min(vc / VA, 1.0)))
                              for vc, _ in TABLE_1_DAHL], 1.0),
    ("table2", "kt", TABLE_2, 1e6),
    ("table3", "kt", TABLE_3, 1e6),
])
def test_packed_tables_reproduce_the_paper(packed, stem, tunable, rows, scale):
    """Oracles: paper L's Tables 1-3 (Dahl, within 1 %) and the Coulomb closed form
    FT_mean = FC (2/pi) asin(vc/va) (within 1e-6), run with each variant FMU's own experiment."""
    variant, path = packed[stem]
    tolerance = 1e-6 if stem.endswith("coulomb") else 1e-2
    for x, expected in rows:
        result = fmpy.simulate_fmu(str(path), start_values={tunable: x * scale},
                                   output=["FT_mean"])
        assert result["FT_mean"][-1] == pytest.approx(expected, rel=tolerance), (x, expected)


def test_fmu_state_of_a_trimmed_fmu_round_trips(packed):
    """Oracle: the run itself; a serialised state restored later replays the same outputs."""
    s = slave(packed["fig8"][1])
    s.initialize(stop_time=0.05)
    period = 1 / 3000
    for i in range(5):
        s.fmu.doStep(i * period, period)
    state = s.fmu.deSerializeFMUstate(s.fmu.serializeFMUstate(s.fmu.getFMUstate()))
    first = []
    for i in range(5, 10):
        s.fmu.doStep(i * period, period)
        first.append(s.get("FFx_mean")[0])
    s.fmu.setFMUstate(state)
    again = []
    for i in range(5, 10):
        s.fmu.doStep(i * period, period)
        again.append(s.get("FFx_mean")[0])
    assert again == first and first[-1] > 0
    s.free()


def slave(path, instance_name="variant"):
    """A conftest.Slave on a variant FMU (registered under its name so Slave finds it)."""
    md = fmpy.read_model_description(str(path))
    conftest._UNZIPPED[md.coSimulation.modelIdentifier] = (fmpy.extract(str(path)), md)
    return Slave(md.coSimulation.modelIdentifier, instance_name)


def refused(s, call, *fragments):
    with pytest.raises(FMICallException) as error:
        call()
    assert error.value.status == 3  # fmi2Error
    for fragment in fragments:
        assert fragment in s.last_message(), (fragment, s.last_message())


def test_hidden_value_references_are_refused_like_unknown_ones(packed):
    """Oracle: the full model's table (va, FFy, vd_in exist there) and the variant's interface."""
    full = fmpy.read_model_description(fmu_path("TransverseFriction"))
    vr = {v.name: v.valueReference for v in full.modelVariables}
    s = slave(packed["fig4a"][1])
    refused(s, lambda: s.fmu.setReal([vr["va"]], [1e-3]),
            f"fmi2SetReal: unknown value reference {vr['va']}: Fig4a has no variable with it")
    refused(s, lambda: s.fmu.setInteger([vr["slip_law"]], [2]),
            f"unknown value reference {vr['slip_law']}: Fig4a has no variable")
    s.initialize(stop_time=1e-3)
    refused(s, lambda: s.fmu.getReal([vr["FFy"]]),
            f"fmi2GetReal: unknown value reference {vr['FFy']}: Fig4a has no variable with it")
    refused(s, lambda: s.fmu.getReal([vr["FFx"], vr["va"]]), f"unknown value reference {vr['va']}")
    refused(s, lambda: s.fmu.getReal([vr["vd_in"]]), f"unknown value reference {vr['vd_in']}")
    s.fmu.doStep(0.0, 1e-4)
    assert s.get("FFx")[0] > 0.0
    s.free()


def test_reset_restores_the_variant_values(packed):
    """Oracle: the variant's vd (5e-4), not the full model's start; va stays hidden at 0."""
    variant, path = packed["fig4a"]
    s = slave(path)
    s.fmu.setReal([s.vr["vd"]], [1e-3])
    s.initialize(stop_time=1e-3)
    assert s.get("vd") == [1e-3]
    s.fmu.reset()
    s.initialize(stop_time=1e-3)
    assert s.get("vd") == [variant["parameters"]["vd"]]
    s.free()


def instantiation_log(path, directory):
    """Instantiates the FMU unzipped in `directory`; returns the log if it was refused."""
    md = fmpy.read_model_description(str(path))
    name = md.coSimulation.modelIdentifier
    conftest._UNZIPPED[name] = (str(directory), md)
    with pytest.raises(Exception, match="Failed to instantiate"):
        Slave(name)
    return list(conftest._LOGS.values())[-1]


def test_tampered_or_missing_variant_resource_is_refused(packed, tmp_path):
    """Oracle: the GUID hashes the interface and every value the variant fixes; a variant.toml that
    describes another interface (vd's start changed) or runs other hidden values (mu changed)
    or none at all cannot be instantiated, and the log says why. A comment may change."""
    variant, path = packed["fig4a"]
    directory = pathlib.Path(fmpy.extract(str(path), unzipdir=str(tmp_path / "fmu")))
    resource = directory / "resources" / "variant.toml"
    text = resource.read_text()
    for old, new in [("vd = 5e-4", "vd = 6e-4"), ("mu = 0.178", "mu = 0.5")]:
        assert old in text
        resource.write_text(text.replace(old, new))
        log = instantiation_log(path, directory)
        assert any(status == 3 and "fmi2Instantiate" in m
                   and "describes an interface with GUID" in m for status, _, m in log), (new, log)
    resource.write_text(text + "# a comment changes nothing the FMU runs\n")
    md = fmpy.read_model_description(str(path))
    conftest._UNZIPPED[md.coSimulation.modelIdentifier] = (str(directory), md)
    Slave(md.coSimulation.modelIdentifier).free()  # accepted from the edited directory
    resource.unlink()
    log = instantiation_log(path, directory)
    assert any("there is no variant" in m and "variant.toml" in m for _, _, m in log), log
    resource.write_text(text)
    s = slave(path)  # the original file is accepted again
    s.free()


def test_a_variant_library_is_its_models_and_runs_the_variant_it_is_handed(packed, tmp_path):
    """docs/platforms.md: a variant FMU's library is the same bytes for every variant of its
    model, so Table2's runs Table3 handed Table3's GUID and resources, and refuses Table3's GUID
    with Table2's resources, whose variant hashes to another."""
    (_, table2), (_, table3) = packed["table2"], packed["table3"]
    two = pathlib.Path(fmpy.extract(str(table2), unzipdir=str(tmp_path / "two")))
    three = pathlib.Path(fmpy.extract(str(table3), unzipdir=str(tmp_path / "three")))
    platform = "linux64" if os.name == "posix" else "win64"
    suffix = ".so" if os.name == "posix" else ".dll"
    library_two = two / "binaries" / platform / f"Table2{suffix}"
    library_three = three / "binaries" / platform / f"Table3{suffix}"
    assert library_two.read_bytes() == library_three.read_bytes()
    library_three.write_bytes(library_two.read_bytes())
    md = fmpy.read_model_description(str(table3))
    conftest._UNZIPPED["Table3"] = (str(three), md)
    Slave("Table3").free()  # Table2's library, Table3's files
    (three / "resources" / "variant.toml").write_text(
        (two / "resources" / "variant.toml").read_text())
    log = instantiation_log(table3, three)
    assert any(status == 3 and "describes an interface with GUID" in m
               for status, _, m in log), log


def test_a_plain_absolute_resource_path_is_taken_like_its_file_uri(packed, monkeypatch):
    """Some importers pass fmuResourceLocation as a plain path (FMI 1.0's habit); a variant FMU,
    which reads resources/variant.toml, runs from it as from the file: URI."""
    variant, path = packed["fig4a"]
    monkeypatch.setattr(pathlib.PurePath, "as_uri", lambda self: str(self))
    s = slave(path, "plain path")
    s.initialize()
    s.fmu.doStep(0.0, variant["experiment"]["step"])
    s.free()


@pytest.mark.parametrize("change, fragments", [
    (("solver = \"dopri5\"", "solver = \"dopri5\"\ncolour = 1"), ["unknown field `colour`"]),
    (("eta = 0.71", "eta = 1.5"), ["key `parameters.eta`", "expected 0 <= eta <= 1"]),
    (("law = \"split\"", "law = \"viscous\""), ["key `law`", "expected one of split, total"]),
    (("vd = 5e-4", "vd_x = 5e-4"), ["key `parameters.vd_x`", "expected one of"]),
    (("inputs = []", "inputs = []  # unchanged control"), None),
])
def test_bad_variant_fails_the_build_with_its_message(tmp_path, change, fragments):
    """Oracle: the format (docs/variants.md, src/variant): the build exits non-zero, names the file and
    the key, and writes no FMU; the unchanged control file builds."""
    text = (ROOT / "variants" / "fig4a.toml").read_text()
    assert change[0] in text
    file = tmp_path / "bad.toml"
    file.write_text(text.replace(change[0], change[1], 1))
    result = build(file, "--out", tmp_path / "out")
    if fragments is None:
        assert result.returncode == 0, result.stderr
        return
    assert result.returncode != 0
    assert str(file) in result.stderr
    for fragment in fragments:
        assert fragment in result.stderr, (fragment, result.stderr)
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


@pytest.mark.parametrize("name", ["int", "fmi2Instantiate", "transversefriction", "NUL"])
def test_a_name_no_importer_or_file_system_can_take_is_refused(tmp_path, name):
    text = (ROOT / "variants" / "fig4a.toml").read_text().replace('name = "Fig4a"', f'name = "{name}"', 1)
    file = tmp_path / "bad.toml"
    file.write_text(text)
    result = build(file, "--out", tmp_path / "out")
    assert result.returncode != 0 and "key `name`" in result.stderr, result.stderr
    assert not (tmp_path / "out").exists()


def test_two_variants_whose_names_differ_only_in_letter_case_are_refused(tmp_path):
    """On Windows' and macOS's file systems Fig4a.fmu and FIG4A.fmu are one file."""
    text = (ROOT / "variants" / "fig4a.toml").read_text()
    (tmp_path / "a.toml").write_text(text)
    (tmp_path / "b.toml").write_text(text.replace('name = "Fig4a"', 'name = "FIG4A"', 1))
    result = build(tmp_path / "a.toml", tmp_path / "b.toml", "--out", tmp_path / "out")
    assert result.returncode != 0
    assert 'both name their FMU "FIG4A" (up to letter case)' in result.stderr, result.stderr
    assert not (tmp_path / "out").exists()
