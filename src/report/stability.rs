//! The stability matrix (stiff and extreme cases): every
//! solver of every scene against each extreme the model has a parameter for, run through the
//! exported fmi2* functions as a master would (src/importer.rs), with the outcome of each run.
//!
//! Each case is short (a few periods, or a few thousand communication steps); the long run is
//! 1e6 vibration periods in scene L (at 1 Hz, communication steps of 1e4 periods, coarse
//! settings) and 1e4 periods in T and O, whose solvers cost more per period.

mod run;

pub use run::{print, run, Outcome, Row};

pub use crate::models::stability::Value;

#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    pub model: &'static str,
    /// The `solver` item; "-" for cases whose friction law has a closed form (no solver).
    pub solver: &'static str,
    /// What is extreme, as the table shows it.
    pub extreme: &'static str,
    pub params: Vec<(&'static str, Value)>,
    pub step: f64,
    pub steps: u64,
}

use Value::Item;

/// The `solver` items of a model, in the order of its table.
pub fn solvers(model: &str) -> Vec<&'static str> {
    crate::models::model(model)
        .and_then(|m| {
            let var = m.table.by_name("solver")?;
            let crate::variables::variable::Kind::Switch { type_name, .. } = var.kind else {
                return None;
            };
            m.table.enum_type(type_name)
        })
        .map(|e| e.items.iter().map(|(name, _)| *name).collect())
        .unwrap_or_default()
}

/// Every case: scene x solver x extreme, plus scene O's exact law (no solver) and scene L's
/// Coulomb law (closed form) at each of their extremes.
pub fn cases() -> Vec<Case> {
    let mut cases = Vec::new();
    for descriptor in crate::models::MODELS {
        let model = descriptor.table.model_identifier;
        let stability = &descriptor.stability;
        let extremes = stability.extremes;
        let mut menu: Vec<(&str, Option<(&str, &str)>)> =
            solvers(model).into_iter().map(|s| (s, None)).collect();
        if let Some(law) = stability.fixed_law {
            menu.push(("-", Some(law)));
        }
        // Where a closed form's long run covers 1e6 periods (scene L), the 1e4-period run is
        // for the ODE solvers alone.
        let closed_form_runs_long = extremes.iter().any(|e| e.0 == "1e6 periods");
        for (solver, law) in menu {
            for &(extreme, params, step, steps) in extremes {
                // An extreme of another law (LuGre's vs) does not apply to a fixed law's row.
                if law.is_some() && params.iter().any(|(name, _)| *name == "law") {
                    continue;
                }
                // The long run: 1e6 periods where the scheme is closed-form per sub-step
                // (exponential, a fixed law), 1e4 where an ODE solver resolves each period.
                let closed_form = matches!(solver, "exponential" | "-");
                let long = match extreme {
                    "1e6 periods" => closed_form,
                    "1e4 periods" => !(closed_form && closed_form_runs_long),
                    _ => true,
                };
                if !long {
                    continue;
                }
                let mut all: Vec<(&str, Value)> = stability.base.to_vec();
                if solver != "-" {
                    all.push(("solver", Item(solver)));
                }
                if let Some((name, item)) = law {
                    all.push((name, Item(item)));
                }
                all.extend_from_slice(params);
                cases.push(Case {
                    model,
                    solver: law.map_or(solver, |(_, item)| item),
                    extreme,
                    params: all,
                    step,
                    steps,
                });
            }
        }
    }
    cases
}

/// Runs every case on `threads` threads; rows in the order of [`cases`]. `done` hears of each
/// row as it completes, with the number of cases (for progress).
pub fn matrix(threads: usize, done: &(dyn Fn(&Row, usize) + Sync)) -> Vec<Row> {
    let cases = cases();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let mut rows: Vec<Option<Row>> = vec![None; cases.len()];
    let slots = std::sync::Mutex::new(&mut rows);
    std::thread::scope(|scope| {
        for _ in 0..threads.max(1) {
            scope.spawn(|| loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(case) = cases.get(i) else { break };
                let row = run(case);
                done(&row, cases.len());
                slots.lock().unwrap_or_else(|e| e.into_inner())[i] = Some(row);
            });
        }
    });
    rows.into_iter().flatten().collect()
}
