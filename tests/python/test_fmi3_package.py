"""The FMI 3.0 FMUs `friction-fmu build` packs into fmu-out/fmi3/ (and fmi3/variants/): each is
valid against fmpy's FMI 3.0 schema and checks, describes what its FMI 2.0 twin describes, and
carries the same library under FMI 3.0's platform names.

Oracles: the FMI 2.0 FMUs beside them (whose interface other tests pin), read with fmpy; the
FMI 3.0 standard's attributes, read from the XML with ElementTree.
"""
import re
import xml.etree.ElementTree as ET
import zipfile

import attrs
import fmpy
import pytest
from fmpy.simulation import apply_start_values
from fmpy.validation import validate_fmu

from conftest import FMU_DIR, ROOT
from friction_fmu import switches

MODELS = ["LongitudinalFriction", "TransverseFriction", "DryFrictionOscillator", "DriveTrain"]
VARIANT_NAMES = sorted(p.stem for p in (FMU_DIR / "variants").glob("*.fmu"))
# (FMI 2.0 FMU, FMI 3.0 FMU) of every model and every packed variant.
PAIRS = [(FMU_DIR / f"{m}.fmu", FMU_DIR / "fmi3" / f"{m}.fmu") for m in MODELS] + [
    (FMU_DIR / "variants" / f"{v}.fmu", FMU_DIR / "fmi3" / "variants" / f"{v}.fmu")
    for v in VARIANT_NAMES]
IDS = [fmi3.stem for _, fmi3 in PAIRS]
# FMI 2.0's platform folders and FMI 3.0's for the same library.
FOLDERS = {"linux64": "x86_64-linux", "win64": "x86_64-windows"}
# ELF's e_machine of AArch64.
EM_AARCH64 = 183


def members(fmu):
    with zipfile.ZipFile(fmu) as z:
        return {name: z.read(name) for name in z.namelist()}


def root_of(fmu):
    with zipfile.ZipFile(fmu) as z:
        return ET.fromstring(z.read("modelDescription.xml"))


def test_every_fmi2_fmu_has_its_fmi3_twin():
    assert VARIANT_NAMES, "no variant FMUs in fmu-out/variants: run `friction-fmu build variants/*.toml --out fmu-out/variants`"
    for _, fmi3 in PAIRS:
        assert fmi3.exists(), f"{fmi3} is missing: run `friction-fmu build`"


@pytest.mark.parametrize("fmi2,fmi3", PAIRS, ids=IDS)
def test_fmpy_validates_the_fmi3_fmu(fmi2, fmi3):
    """The schema fmpy ships and its checks (one independent variable, unique value
    references, ModelStructure complete); they read the XML only, not the library."""
    assert validate_fmu(str(fmi3)) == []


def unit_of(variable):
    """A Float64's unit, as FMI 3.0 gives it: its own, or its declared type's (ours name it there,
    docs/interoperability.md, "The fmi crate")."""
    declared = variable.declaredType
    return variable.unit or (declared.unit if declared is not None and variable.type == "Float64" else None)


@pytest.mark.parametrize("fmi2,fmi3", PAIRS, ids=IDS)
def test_the_fmi3_description_says_what_the_fmi2_one_says(fmi2, fmi3):
    md2, md3 = fmpy.read_model_description(str(fmi2)), fmpy.read_model_description(str(fmi3))
    assert md3.fmiVersion == "3.0"
    assert md3.instantiationToken == md2.guid
    assert md3.coSimulation.modelIdentifier == md2.coSimulation.modelIdentifier
    assert attrs.asdict(md3.defaultExperiment) == attrs.asdict(md2.defaultExperiment)
    type_of = {"Real": "Float64", "Integer": "Int32"}
    variables3 = [v for v in md3.modelVariables if v.causality != "independent"]
    assert len(variables3) == len(md2.modelVariables)
    for v2, v3 in zip(md2.modelVariables, variables3):
        assert (v3.name, v3.valueReference, v3.causality, v3.variability) == (
            v2.name, v2.valueReference, v2.causality, v2.variability)
        assert v3.type == type_of[v2.type], v2.name
        assert (v3.start, unit_of(v3), v3.min, v3.max, v3.description) == (
            v2.start, v2.unit, v2.min, v2.max, v2.description), v2.name
        if v3.type == "Int32":
            assert (v3.declaredType and v3.declaredType.name) == (
                v2.declaredType and v2.declaredType.name), v2.name
    units = lambda md: {u.name: attrs.asdict(u.baseUnit) for u in md.unitDefinitions}  # noqa: E731
    assert units(md3) == units(md2) | {"s": units(md3)["s"]}
    dependencies = lambda md: [(u.variable.name, sorted(d.name for d in u.dependencies or []))  # noqa: E731
                               for u in md.outputs]
    assert dependencies(md3) == dependencies(md2)
    assert [u.variable.name for u in md3.initialUnknowns] == [
        u.variable.name for u in md2.initialUnknowns]


@pytest.mark.parametrize("fmi2,fmi3", PAIRS, ids=IDS)
def test_the_fmi3_capabilities(fmi2, fmi3):
    cs2, cs3 = root_of(fmi2).find("CoSimulation"), root_of(fmi3).find("CoSimulation")
    for flag in ["canGetAndSetFMUState", "canSerializeFMUState", "providesIntermediateUpdate"]:
        assert cs3.get(flag) == "true", flag
    for flag in ["hasEventMode", "canReturnEarlyAfterIntermediateUpdate"]:
        assert cs3.get(flag) == "false", flag
    for flag in ["canHandleVariableCommunicationStepSize", "maxOutputDerivativeOrder"]:
        assert cs3.get(flag) == cs2.get(flag), flag
    variables = root_of(fmi3).find("ModelVariables")
    (time,) = [v for v in variables if v.get("causality") == "independent"]
    assert (time.tag, time.get("name"), time.get("valueReference"), time.get("declaredType")) == (
        "Float64", "time", "0", "s")
    (seconds,) = [t for t in root_of(fmi3).find("TypeDefinitions") if t.get("name") == "s"]
    assert (seconds.tag, seconds.get("unit")) == ("Float64Type", "s")
    for v in variables:
        continuous_input = v.get("causality") == "input" and v.get("variability") == "continuous"
        assert v.get("intermediateUpdate") == ("true" if continuous_input else None), v.get("name")


@pytest.mark.parametrize("fmi2,fmi3", PAIRS, ids=IDS)
def test_the_fmi3_fmu_carries_the_fmi2_library_and_files(fmi2, fmi3):
    files2, files3 = members(fmi2), members(fmi3)
    identifier = root_of(fmi3).find("CoSimulation").get("modelIdentifier")
    binaries2 = {n for n in files2 if n.startswith("binaries/")}
    assert binaries2, fmi2
    for name in binaries2:
        folder = name.split("/")[1]
        twin = name.replace(f"binaries/{folder}/", f"binaries/{FOLDERS[folder]}/")
        assert files3[twin] == files2[name], twin
    others = lambda files: {n: b for n, b in files.items()  # noqa: E731
                            if not n.startswith("binaries/") and n != "modelDescription.xml"}
    page = "documentation/index.html"
    # The FMI 3.0 page is the FMI 2.0 one with a paragraph on FMI 3.0's names of the functions.
    note = re.compile(rb"<p>This is the FMI 3\.0 FMU;.*?</p>\n", re.DOTALL)
    assert len(note.findall(files3[page])) == 1
    files3[page] = note.sub(b"", files3[page])
    assert others(files3) == others(files2)
    assert not any(n.startswith("binaries/aarch64") for n in files2), "FMI 2.0 names no aarch64"
    aarch64 = files3.get(f"binaries/aarch64-linux/{identifier}.so")
    if aarch64 is not None:
        assert aarch64[:4] == b"\x7fELF" and int.from_bytes(aarch64[18:20], "little") == EM_AARCH64


@pytest.mark.parametrize("model", MODELS)
def test_the_committed_fmi3_descriptions_are_the_packed_ones(model):
    committed = (ROOT / "modelDescription" / "fmi3" / f"{model}.xml").read_bytes()
    assert members(FMU_DIR / "fmi3" / f"{model}.fmu")["modelDescription.xml"] == committed


@pytest.mark.parametrize("fmi2,fmi3", PAIRS, ids=IDS)
def test_the_python_package_reads_the_same_switch_items(fmi2, fmi3):
    md2, md3 = fmpy.read_model_description(str(fmi2)), fmpy.read_model_description(str(fmi3))
    items = lambda md: {v.name: switches.items(v) for v in md.modelVariables  # noqa: E731
                        if switches.items(v) is not None}
    assert items(md3) == items(md2)
    assert items(md2) or fmi2.parent.name == "variants"


class Recorder:
    """Stands in for an FMI 3.0 instance: records which setter fmpy calls."""

    def __init__(self):
        self.calls = []

    def __getattr__(self, name):
        if not name.startswith("set"):
            raise AttributeError(name)
        return lambda vrs, values: self.calls.append((name, list(vrs), list(values)))


@pytest.mark.parametrize("model", MODELS)
def test_fmpy_sets_switches_with_set_int32(model):
    """fmpy's start values (simulate_fmu(start_values=...)) reach a switch through fmi3SetInt32,
    the setter its Int32 type names, and a Real through fmi3SetFloat64."""
    md = fmpy.read_model_description(str(FMU_DIR / "fmi3" / f"{model}.fmu"))
    switch = next(v for v in md.modelVariables if v.declaredType is not None and v.type == "Int32")
    real = next(v for v in md.modelVariables if v.type == "Float64" and v.causality == "parameter")
    fmu = Recorder()
    assert apply_start_values(fmu, md, {switch.name: 2, real.name: 1.5}) == {}
    assert sorted(fmu.calls) == sorted([("setInt32", [switch.valueReference], [2]),
                                        ("setFloat64", [real.valueReference], [1.5])])
