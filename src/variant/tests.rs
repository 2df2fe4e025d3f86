//! Variants: a valid one read back value by value, and one test per refusal, each checking
//! that the message names the file, the key and what was expected.

use super::parse;
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

fn refused(text: &str, fragments: &[&str]) {
    let message = match parse("variants/x.toml", text) {
        Ok(_) => panic!("accepted: {text}"),
        Err(message) => message,
    };
    assert!(message.starts_with("variants/x.toml"), "{message}");
    for fragment in fragments {
        assert!(
            message.contains(fragment),
            "{fragment:?} not in {message:?}"
        );
    }
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
    refused(
        &fig4a_with("solver = \"rk4\"", "solver = \"rk4\"\ncolour = 1"),
        &["line 7", "colour", "unknown field", "expected one of"],
    );
    refused(
        &fig4a_with("step = 1e-5", "step = 1e-5\nstepSize = 1e-5"),
        &["stepSize", "unknown field"],
    );
}

#[test]
fn missing_and_mistyped_keys_are_refused() {
    refused(
        &fig4a_with("law = \"split\"\n", ""),
        &["missing field `law`"],
    );
    refused(
        &fig4a_with("law = \"split\"", "law = 3"),
        &["law = 3", "expected a string"],
    );
    refused(
        &fig4a_with("vd = 0.5e-3", "vd = \"fast\""),
        &["key `parameters.vd`", "vd = \"fast\"", "expected a number"],
    );
    refused(
        &fig4a_with("steps_per_period = 400", "steps_per_period = 400.5"),
        &["key `parameters.steps_per_period`", "expected an integer"],
    );
    refused(
        &fig4a_with("body = \"free\"", "body = 2"),
        &["key `parameters.body`", "expected an item name"],
    );
}

#[test]
fn unknown_models_and_names_are_refused() {
    refused(
        &fig4a_with("\"TransverseFriction\"", "\"Transverse\""),
        &[
            "key `model`",
            "unknown model \"Transverse\"",
            "expected one of LongitudinalFriction, TransverseFriction, DryFrictionOscillator",
        ],
    );
    refused(
        &fig4a_with("va = 0.0", "vx = 0.0"),
        &[
            "key `parameters.vx`",
            "no parameter or input \"vx\"",
            "expected one of",
            "vd_in",
        ],
    );
    refused(
        &fig4a_with("[\"vd\", \"kt\"]", "[\"vd\", \"FF\"]"),
        &[
            "key `tunable`",
            "\"FF\" is not a parameter",
            "expected one of",
        ],
    );
    refused(
        &fig4a_with("[\"FFx\", \"Fd\"]", "[\"FFx\", \"vd\"]"),
        &["key `outputs`", "\"vd\" is not an output"],
    );
    refused(
        &fig4a_with("[\"FFx\", \"Fd\"]", "[]"),
        &["key `outputs`", "expected at least one output"],
    );
    refused(
        &fig4a_with("[\"vd\", \"kt\"]", "[\"vd\", \"vd\"]"),
        &["key `tunable`", "listed twice"],
    );
    refused(
        &fig4a_with("va = 0.0", "FF = 0.0"),
        &["key `parameters.FF`", "expected a parameter or an input"],
    );
    refused(
        &fig4a_with("va = 0.0", "solver = \"rk4\""),
        &["key `parameters.solver`", "top-level key `solver`"],
    );
    refused(
        &fig4a_with("name = \"Fig4a\"", "name = \"Fig 4a\""),
        &["key `name`", "expected a letter followed by"],
    );
    refused(
        &fig4a_with("name = \"Fig4a\"", "name = \"TransverseFriction\""),
        &["key `name`", "full model TransverseFriction"],
    );
    // The same file as the full model's on a case-insensitive file system.
    refused(
        &fig4a_with("name = \"Fig4a\"", "name = \"transverseFRICTION\""),
        &[
            "key `name`",
            "up to letter case",
            "case-insensitive file system",
        ],
    );
    for (name, why) in [
        ("int", "is a C keyword: expected another name"),
        ("_", "expected a letter followed by"),
        ("_Fig4a", "expected a letter followed by"),
        ("fmi2Instantiate", "reserved for the FMI functions"),
        ("FMI3x", "reserved for the FMI functions"),
        ("Con", "a device name on Windows"),
        ("lpt1", "a device name on Windows"),
    ] {
        refused(
            &fig4a_with("name = \"Fig4a\"", &format!("name = \"{name}\"")),
            &["key `name`", why],
        );
    }
}

#[test]
fn values_out_of_range_and_unknown_items_are_refused() {
    refused(
        &fig4a_with("va = 0.0", "eta = 1.5"),
        &[
            "key `parameters.eta`",
            "eta = 1.5 is out of range",
            "expected 0 <= eta <= 1",
        ],
    );
    refused(
        &fig4a_with("va = 0.0", "kt = 0"),
        &["key `parameters.kt`", "expected kt > 0"],
    );
    refused(
        &fig4a_with("law = \"split\"", "law = \"viscous\""),
        &[
            "key `law`",
            "\"viscous\" is not an item of SlipLaw",
            "expected one of split, total",
        ],
    );
    refused(
        &fig4a_with("solver = \"rk4\"", "solver = \"euler\""),
        &[
            "key `solver`",
            "expected one of dopri5, rk4, two_phase, radau5, exponential",
        ],
    );
    refused(
        &fig4a_with("body = \"free\"", "body = \"floating\""),
        &["key `parameters.body`", "expected one of free, held"],
    );
}

#[test]
fn an_input_the_configuration_reads_must_be_kept() {
    refused(
        &fig4a_with("body = \"free\"", "drive_source = \"input\""),
        &[
            "key `inputs`",
            "drive_source = input reads vd_in",
            "expected inputs to include \"vd_in\"",
        ],
    );
    refused(
        &fig4a_with("[\"vd\", \"kt\"]", "[\"vd\", \"drive_source\"]"),
        &["key `inputs`", "drive_source is tunable", "\"vd_in\""],
    );
    let kept = fig4a_with("body = \"free\"", "drive_source = \"input\"")
        .replace("inputs = []", "inputs = [\"vd_in\"]");
    assert!(parse("x.toml", &kept).is_ok());
}

#[test]
fn a_bad_experiment_is_refused() {
    refused(
        &fig4a_with("step = 1e-5", "step = 0"),
        &["key `experiment.step`", "expected 0 < step"],
    );
    refused(
        &fig4a_with("stop = 0.016", "stop = 0.0"),
        &["key `experiment.stop`", "expected a finite time > start"],
    );
    // libcosim's clock counts nanoseconds; 1/60 kHz is no whole number of them.
    refused(
        &fig4a_with("step = 1e-5", "step = 1.6666666666666667e-05"),
        &["key `experiment.step`", "whole number of nanoseconds"],
    );
    // 1500 steps of 1e-5 end at 0.015000000000000001, not at 0.015.
    refused(
        &fig4a_with("stop = 0.016", "stop = 0.015"),
        &["key `experiment.step`", "whole number of steps"],
    );
    refused(
        &fig4a_with("step = 1e-5", "step = 1e-5\ntolerance = -1"),
        &[
            "key `experiment.tolerance`",
            "expected a finite tolerance > 0",
        ],
    );
    // A second tolerance beside the solver's is refused; the same one is accepted.
    refused(
        &fig4a_with("step = 1e-5", "step = 1e-5\ntolerance = 1e-6"),
        &[
            "key `experiment.tolerance`",
            "the solver integrates to tolerance = 1e-8",
        ],
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
        &[
            "key `description`",
            "control character",
            "expected printable text",
        ],
    );
    refused(
        &fig4a_with("\"TransverseFriction\"", "\"DriveTrain\""),
        &["key `model`", "unknown model \"DriveTrain\""],
    );
}
