use super::*;
use crate::error::Kind;

/// The integral over `[0, t_end]` of what `scheme` gives for `input` sampled every `h`, less the
/// integral of `input` itself.
fn integral_error(scheme: InputScheme, input: impl Fn(f64) -> f64, h: f64, t_end: f64) -> f64 {
    let mut x = Extrapolator::default();
    let steps = (t_end / h).round() as usize;
    let mut given = 0.0;
    for k in 0..steps {
        let t = k as f64 * h;
        given += x.ramp(scheme, t, input(t), h).integral(0.0, h);
    }
    // The exact integral of the test inputs below, t^3 / 4 + t^2 / 2.
    given - (t_end.powi(4) / 4.0 + t_end.powi(2) / 2.0)
}

fn cubic(t: f64) -> f64 {
    t * t * t + t
}

#[test]
fn held_gives_the_value_and_the_masters_derivative() {
    let mut x = Extrapolator::default();
    assert_eq!(
        x.ramp(InputScheme::Held, 0.0, 2.0, 0.1),
        Ramp {
            value: 2.0,
            rate: 0.0
        }
    );
    x.set_derivative(3.0);
    assert_eq!(x.pending_rate(), 3.0);
    assert_eq!(x.ramp(InputScheme::Held, 0.1, 2.5, 0.1).rate, 3.0);
    assert_eq!(x.ramp(InputScheme::Held, 0.2, 2.5, 0.1).rate, 0.0);
}

#[test]
fn extrapolated_continues_a_line_exactly_over_uneven_steps() {
    let line = |t: f64| 1.0 - 2.0 * t;
    let mut x = Extrapolator::default();
    let times = [0.0, 0.1, 0.25, 0.3, 0.7];
    // The first step knows one value: held.
    assert_eq!(
        x.ramp(InputScheme::Extrapolated, 0.0, line(0.0), 0.1).rate,
        0.0
    );
    for pair in times[1..].windows(2) {
        let (t, next) = (pair[0], pair[1]);
        let ramp = x.ramp(InputScheme::Extrapolated, t, line(t), next - t);
        assert_eq!(ramp.value, line(t));
        assert!((ramp.at(next - t) - line(next)).abs() < 1e-15, "{ramp:?}");
    }
}

#[test]
fn the_integral_is_second_order_extrapolated_and_third_order_corrected() {
    let errors = |scheme| [0.1, 0.05, 0.025].map(|h| integral_error(scheme, cubic, h, 1.0).abs());
    let held = errors(InputScheme::Held);
    let extrapolated = errors(InputScheme::Extrapolated);
    let corrected = errors(InputScheme::Corrected);
    for k in 0..2 {
        let order = |e: [f64; 3]| (e[k] / e[k + 1]).log2();
        assert!((0.9..1.1).contains(&order(held)), "{held:?}");
        assert!(
            (1.9..2.1).contains(&order(extrapolated)),
            "{extrapolated:?}"
        );
        assert!((2.9..3.1).contains(&order(corrected)), "{corrected:?}");
    }
    assert!(
        corrected[2] < 0.05 * extrapolated[2],
        "{corrected:?} {extrapolated:?}"
    );
}

#[test]
fn corrected_makes_up_a_quadratics_integral_to_round_off_from_the_third_value_on() {
    let quadratic = |t: f64| 3.0 * t * t - t + 0.5;
    let antiderivative = |t: f64| t * t * t - 0.5 * t * t + 0.5 * t;
    let times = [0.0, 0.1, 0.15, 0.3, 0.32, 0.5, 0.9, 1.0];
    let mut x = Extrapolator::default();
    let mut given = 0.0;
    for pair in times.windows(2) {
        let (t, next) = (pair[0], pair[1]);
        given += x
            .ramp(InputScheme::Corrected, t, quadratic(t), next - t)
            .integral(0.0, next - t);
    }
    // What the model is still owed at the last point, settled there.
    x.record(1.0, quadratic(1.0));
    let exact = antiderivative(1.0) - antiderivative(0.0);
    // The first step's trapezoid is all that is off: by h^3 u'' / 12 with h = 0.1.
    let first_step = 0.1f64.powi(3) * 6.0 / 12.0;
    assert!(
        (given + x.debt - exact - first_step).abs() < 1e-14,
        "{}",
        given + x.debt - exact
    );
}

#[test]
fn a_masters_derivative_takes_precedence_and_clears_the_debt() {
    let mut x = Extrapolator::default();
    for k in 0..4 {
        let t = k as f64 * 0.1;
        x.ramp(InputScheme::Corrected, t, cubic(t), 0.1);
    }
    assert_ne!(x.debt, 0.0);
    x.set_derivative(-1.0);
    let ramp = x.ramp(InputScheme::Corrected, 0.4, cubic(0.4), 0.1);
    assert_eq!(
        ramp,
        Ramp {
            value: cubic(0.4),
            rate: -1.0
        }
    );
    assert_eq!(x.debt, 0.0);
}

#[test]
fn going_back_without_a_restored_state_restarts_the_history() {
    let mut x = Extrapolator::default();
    x.ramp(InputScheme::Extrapolated, 0.0, 0.0, 0.1);
    x.ramp(InputScheme::Extrapolated, 0.1, 1.0, 0.1);
    let ramp = x.ramp(InputScheme::Extrapolated, 0.05, 5.0, 0.1);
    assert_eq!(
        ramp,
        Ramp {
            value: 5.0,
            rate: 0.0
        }
    );
}

#[test]
fn a_saved_history_goes_on_to_the_same_bits() {
    let mut x = Extrapolator::default();
    for k in 0..5 {
        let t = k as f64 * 0.1;
        x.ramp(InputScheme::Corrected, t, cubic(t), 0.1);
    }
    x.set_derivative(0.25);
    let mut saved = Vec::new();
    x.save(&mut saved);
    assert_eq!(saved.len(), SAVED);
    let mut y = Extrapolator::default();
    y.restore(&saved).unwrap();
    assert_eq!(x, y);
    for k in 5..8 {
        let t = k as f64 * 0.1;
        let (a, b) = (
            x.ramp(InputScheme::Corrected, t, cubic(t), 0.1),
            y.ramp(InputScheme::Corrected, t, cubic(t), 0.1),
        );
        assert_eq!(
            (a.value.to_bits(), a.rate.to_bits()),
            (b.value.to_bits(), b.rate.to_bits())
        );
    }
    saved[6] = 1.5;
    assert_eq!(y.restore(&saved).unwrap_err().kind, Kind::State);
}

#[test]
fn the_one_mode_loop_grows_past_each_schemes_critical_z() {
    for scheme in [
        InputScheme::Held,
        InputScheme::Extrapolated,
        InputScheme::Corrected,
    ] {
        let z = stability::critical(scheme);
        assert!(stability::growth(scheme, 0.98 * z) < 1.0, "{scheme:?}");
        assert!(stability::growth(scheme, 1.02 * z) > 1.0, "{scheme:?}");
        // Held's amplification is |1 - z|.
        assert!((stability::growth(InputScheme::Held, 3.5) - 2.5).abs() < 1e-12);
        // The bound read back from the growth at twice it.
        let growth = stability::growth(scheme, 2.0 * z);
        let bound = stability::largest_stable_steps(scheme, 1e-3, growth)(scheme);
        assert!((bound - 0.5e-3).abs() < 1e-9, "{scheme:?}: {bound}");
    }
}

/// A value sequence that oscillates with the step and grows is found once, with its growth; a
/// smooth rise, or an oscillation that decays, is not.
#[test]
fn the_watch_finds_a_growing_oscillation_once() {
    let run = |value: &dyn Fn(f64) -> f64| {
        let mut x = Extrapolator::default();
        let mut found = vec![];
        for k in 0..60 {
            let t = k as f64 * 0.01;
            x.ramp(InputScheme::Corrected, t, value(k as f64), 0.01);
            if let Some(message) = x.instability("vd_in", InputScheme::Corrected) {
                found.push((k, message));
            }
        }
        found
    };
    let growing = run(&|k| 1.0 + 1e-6 * 1.3f64.powf(k) * (2.0 * k).cos());
    assert_eq!(growing.len(), 1, "{growing:?}");
    let (_, message) = &growing[0];
    assert!(
        message.contains("input_scheme = corrected: vd_in"),
        "{message}"
    );
    let growth: f64 = message
        .split("grows ")
        .nth(1)
        .and_then(|rest| rest.split('-').next())
        .and_then(|number| number.parse().ok())
        .unwrap();
    assert!((growth - 1.3).abs() < 0.05, "{message}");
    assert!(run(&|k| (0.1 * k).exp()).is_empty());
    assert!(run(&|k| 0.9f64.powf(k) * (2.0 * k).cos()).is_empty());
    assert!(run(&|k| (0.05 * k).sin()).is_empty());
}

#[test]
fn a_line_that_would_overflow_holds() {
    let mut x = Extrapolator::default();
    let next = 1.0 + f64::EPSILON;
    x.ramp(InputScheme::Corrected, 0.0, 0.0, 1.0);
    x.ramp(InputScheme::Corrected, 1.0, -1e300, f64::EPSILON);
    let ramp = x.ramp(InputScheme::Corrected, next, 1e300, 1.0);
    assert_eq!(
        ramp,
        Ramp {
            value: 1e300,
            rate: 0.0
        }
    );
}
