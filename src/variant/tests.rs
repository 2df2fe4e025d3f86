//! Variants: a valid one read back value by value, and the refusals, each checked to name the
//! file, the key and the kind of error.

use super::{parse, Refused};
use crate::error::Kind;
use crate::models::transverse::table::vr;
use crate::variables::variable::Causality;

const FIG4A: &str = r#"
name = "Fig4a"
model = "TransverseFriction"
description = "no vibration"
law = "split"
solver = "rk4"
tunable = ["vd", "kt"]
inputs = []
outputs = ["FFx", "Fd"]
[parameters]
va = 0.0
vd = 0.5e-3
steps_per_period = 400
body = "free"
[experiment]
start = 0.0
stop = 0.016
step = 1e-5
"#;

/// FIG4A with `from` replaced by `to` (which must occur).
fn fig4a_with(from: &str, to: &str) -> String {
    assert!(FIG4A.contains(from), "{from}");
    FIG4A.replacen(from, to, 1)
}

/// The refusal of `text` as variants/x.toml, checked to be about `key` (None: the file as a
/// whole) and of `kind`.
fn refused(text: &str, key: Option<&str>, kind: Kind) -> Refused {
    let refused = match parse("variants/x.toml", text) {
        Ok(_) => panic!("accepted: {text}"),
        Err(refused) => refused,
    };
    assert_eq!(refused.file, "variants/x.toml", "{refused}");
    assert_eq!(refused.key.as_deref(), key, "{refused}");
    assert_eq!(refused.error.kind, kind, "{refused}");
    refused
}

/// A refusal says the file, the key, what was found and what was expected, in that order.
#[test]
fn a_refusal_says_the_file_the_key_what_was_found_and_what_was_expected() {
    let eta = refused(
        &fig4a_with("va = 0.0", "eta = 1.5"),
        Some("parameters.eta"),
        Kind::Value { name: "eta" },
    );
    assert_eq!(
        eta.to_string(),
        "variants/x.toml: key `parameters.eta`: eta = 1.5 is out of range: expected 0 <= eta <= 1 (no unit)"
    );
}

/// Oracle: the file's own values and the model table's defaults.
#[test]
fn a_valid_file_gives_its_values_and_keeps_what_it_lists() {
    let variant = parse("fig4a.toml", FIG4A).unwrap();
    assert_eq!(variant.name, "Fig4a");
    assert_eq!(variant.model.table.model_identifier, "TransverseFriction");
    assert_eq!(variant.values.real(vr::VA), 0.0);
    assert_eq!(variant.values.real(vr::VD), 0.5e-3);
    assert_eq!(variant.values.integer(vr::STEPS_PER_PERIOD), 400);
    assert_eq!(variant.values.item(vr::SOLVER), "rk4");
    assert_eq!(variant.values.item(vr::SLIP_LAW), "split");
    assert_eq!(variant.values.real(vr::KT), 6.286e7);
    assert_eq!(variant.kept, vec![vr::KT, vr::VD, vr::FFX, vr::FD]);
    assert_eq!(variant.experiment.stop, 0.016);
    // Not given: it states the tolerance the solver integrates to (the model's default).
    assert_eq!(variant.experiment.tolerance, Some(1e-8));
    let scope = variant.scope();
    assert!(scope.exposes(vr::VD) && scope.exposes(vr::FFX));
    assert!(scope.fixes(vr::VA) && scope.fixes(vr::VD_IN) && scope.fixes(vr::FF));
    // Every variable is either kept or fixed, outputs aside.
    let fixed = variant.fixed();
    for v in variant.model.table.variables {
        let in_fixed = fixed.iter().any(|(f, _)| f.name == v.name);
        let kept = variant.kept.contains(&v.value_reference);
        assert!(
            kept != in_fixed || v.causality == Causality::Output,
            "{}",
            v.name
        );
    }
}

/// Oracle: the FMI rule that the GUID identifies the XML; the XML lists exactly the kept
/// variables, with the file's start values and experiment.
#[test]
fn the_trimmed_xml_lists_the_kept_variables_and_hashes_to_its_guid() {
    let variant = parse("fig4a.toml", FIG4A).unwrap();
    let (guid, xml) = variant.model_description();
    assert_eq!(xml.matches("<ScalarVariable ").count(), 4);
    for name in ["vd", "kt", "FFx", "Fd"] {
        assert!(xml.contains(&format!("name=\"{name}\"")), "{name}");
    }
    assert!(xml.contains("start=\"5e-4\""));
    assert!(!xml.contains("name=\"va\"") && !xml.contains("SlipLaw"));
    assert!(xml.contains("stopTime=\"0.016\"") && xml.contains("tolerance=\"0.00000001\""));
    assert!(xml.contains("modelIdentifier=\"Fig4a\""));
    // Fd depends on vd_in in the full model; hidden, it is no dependency here.
    assert!(xml.contains("<Unknown index=\"4\" dependencies=\"\"/>"));
    // The GUID changes with a kept start value, with a hidden value (which the XML does not
    // show) and with the model, and with nothing else.
    for (from, to) in [
        ("vd = 0.5e-3", "vd = 0.6e-3"),
        ("steps_per_period = 400", "steps_per_period = 401"),
    ] {
        let other = parse("fig4a.toml", &fig4a_with(from, to)).unwrap();
        assert_ne!(other.model_description().0, guid, "{to}");
    }
    let hidden_changed = parse("fig4a.toml", &fig4a_with("va = 0.0", "va = 1e-3")).unwrap();
    assert_eq!(
        hidden_changed
            .model_description()
            .1
            .replace(&hidden_changed.model_description().0, ""),
        xml.replace(&guid, "")
    );
    assert_ne!(hidden_changed.model_description().0, guid);
    let commented = parse("fig4a.toml", &format!("{FIG4A}# a comment\n")).unwrap();
    assert_eq!(commented.model_description().0, guid);
}

#[test]
fn unknown_keys_are_refused() {
    let colour = refused(
        &fig4a_with("solver = \"rk4\"", "solver = \"rk4\"\ncolour = 1"),
        None,
        Kind::Refused,
    );
    // TOML's own message, placed on its line.
    assert!(
        colour.error.found.starts_with("line 7 (`colour = 1`)"),
        "{colour}"
    );
    refused(
        &fig4a_with("step = 1e-5", "step = 1e-5\nstepSize = 1e-5"),
        None,
        Kind::Refused,
    );
}

#[test]
fn missing_and_mistyped_keys_are_refused() {
    refused(&fig4a_with("law = \"split\"\n", ""), None, Kind::Refused);
    refused(
        &fig4a_with("law = \"split\"", "law = 3"),
        None,
        Kind::Refused,
    );
    for (from, to, name) in [
        ("vd = 0.5e-3", "vd = \"fast\"", "vd"),
        (
            "steps_per_period = 400",
            "steps_per_period = 400.5",
            "steps_per_period",
        ),
        ("body = \"free\"", "body = 2", "body"),
    ] {
        refused(
            &fig4a_with(from, to),
            Some(&format!("parameters.{name}")),
            Kind::Value { name },
        );
    }
}

#[test]
fn unknown_models_and_names_are_refused() {
    let model = refused(
        &fig4a_with("\"TransverseFriction\"", "\"Transverse\""),
        Some("model"),
        Kind::Value { name: "model" },
    );
    assert_eq!(
        model.error.expected,
        "one of LongitudinalFriction, TransverseFriction, DryFrictionOscillator"
    );
    for (from, to, key) in [
        ("va = 0.0", "vx = 0.0", "parameters.vx"),
        ("[\"vd\", \"kt\"]", "[\"vd\", \"FF\"]", "tunable"),
        ("[\"FFx\", \"Fd\"]", "[\"FFx\", \"vd\"]", "outputs"),
        ("[\"FFx\", \"Fd\"]", "[]", "outputs"),
        ("[\"vd\", \"kt\"]", "[\"vd\", \"vd\"]", "tunable"),
        ("va = 0.0", "FF = 0.0", "parameters.FF"),
        ("va = 0.0", "solver = \"rk4\"", "parameters.solver"),
    ] {
        refused(&fig4a_with(from, to), Some(key), Kind::Refused);
    }
    // Not a C identifier, a full model's name (in any letter case: the same file on a
    // case-insensitive file system), a C keyword, the FMI functions' prefix, a Windows device.
    for name in [
        "Fig 4a",
        "TransverseFriction",
        "transverseFRICTION",
        "int",
        "_",
        "_Fig4a",
        "fmi2Instantiate",
        "FMI3x",
        "Con",
        "lpt1",
    ] {
        refused(
            &fig4a_with("name = \"Fig4a\"", &format!("name = \"{name}\"")),
            Some("name"),
            Kind::Value { name: "name" },
        );
    }
}

#[test]
fn values_out_of_range_and_unknown_items_are_refused() {
    for (from, to, key, name) in [
        ("va = 0.0", "eta = 1.5", "parameters.eta", "eta"),
        ("va = 0.0", "kt = 0", "parameters.kt", "kt"),
        ("law = \"split\"", "law = \"viscous\"", "law", "slip_law"),
        ("solver = \"rk4\"", "solver = \"euler\"", "solver", "solver"),
        (
            "body = \"free\"",
            "body = \"floating\"",
            "parameters.body",
            "body",
        ),
    ] {
        refused(&fig4a_with(from, to), Some(key), Kind::Value { name });
    }
}

#[test]
fn an_input_the_configuration_reads_must_be_kept() {
    refused(
        &fig4a_with("body = \"free\"", "drive_source = \"input\""),
        Some("inputs"),
        Kind::Combination,
    );
    refused(
        &fig4a_with("[\"vd\", \"kt\"]", "[\"vd\", \"drive_source\"]"),
        Some("inputs"),
        Kind::Combination,
    );
    let kept = fig4a_with("body = \"free\"", "drive_source = \"input\"")
        .replace("inputs = []", "inputs = [\"vd_in\"]");
    assert!(parse("x.toml", &kept).is_ok());
}

#[test]
fn a_bad_experiment_is_refused() {
    for (from, to, key, name) in [
        ("step = 1e-5", "step = 0", "experiment.step", "step"),
        ("stop = 0.016", "stop = 0.0", "experiment.stop", "stop"),
        // libcosim's clock counts nanoseconds; 1/60 kHz is no whole number of them.
        (
            "step = 1e-5",
            "step = 1.6666666666666667e-05",
            "experiment.step",
            "step",
        ),
        // 1500 steps of 1e-5 end at 0.015000000000000001, not at 0.015.
        ("stop = 0.016", "stop = 0.015", "experiment.step", "step"),
        (
            "step = 1e-5",
            "step = 1e-5\ntolerance = -1",
            "experiment.tolerance",
            "tolerance",
        ),
    ] {
        refused(&fig4a_with(from, to), Some(key), Kind::Value { name });
    }
    // A second tolerance beside the solver's is refused; the same one is accepted.
    refused(
        &fig4a_with("step = 1e-5", "step = 1e-5\ntolerance = 1e-6"),
        Some("experiment.tolerance"),
        Kind::Combination,
    );
    assert!(parse(
        "fig4a.toml",
        &fig4a_with("step = 1e-5", "step = 1e-5\ntolerance = 1e-8")
    )
    .is_ok());
}

/// Oracle: the format: a description must be XML-safe, and only models with a friction law
/// are trimmed (DriveTrain has none).
#[test]
fn control_characters_and_models_without_a_law_are_refused() {
    refused(
        &fig4a_with(
            "description = \"no vibration\"",
            "description = \"no\\u0001vibration\"",
        ),
        Some("description"),
        Kind::Value {
            name: "description",
        },
    );
    refused(
        &fig4a_with("\"TransverseFriction\"", "\"DriveTrain\""),
        Some("model"),
        Kind::Value { name: "model" },
    );
}
