//! Our solvers against compiled peers on the same equations, at equal error on what a user
//! reads (FFx_mean, FT_mean, the amplitude). Prints markdown; run with
//! `cargo run --release --manifest-path benches/compiled_peers/Cargo.toml`.
//!
//! Peers: SUNDIALS CVODE (BDF and Adams, Debian's libsundials-dev), diffsol 0.18 (bdf and the
//! SDIRK esdirk34) and ode_solvers 0.6 (Dopri5 and Dop853), all on the project's right-hand
//! sides (src/problem.rs). Ours run through the models' step functions, as the FMUs run them.
//! CPU time of the running thread; each setting's median of [`REPEATS`] runs, the settings of
//! one case taken in turn in every round, so the machine's drift spreads over all of them.
//!
//! Ours in scene T also runs through the library the FMU carries (`fmu` profile, without
//! link-time optimisation), loaded with dlopen and driven by fmi2 calls, one fmi2DoStep a
//! period ([`fmu_library`]: build it first with
//! `cargo build --profile fmu -p friction-fmu-binary --examples` in the main crate); its rows
//! are marked "FMU library" and that is the one that counts. Its counts are its in-process
//! twin's (the same steps).
//!
//! Arguments, if any, pick cases by position (0-6, in the order of `main`); with
//! `PEERS_VERBOSE` set, every setting's error and time is printed to stderr as it is first run.

mod cases;
mod cvode;
mod dop853;
mod fmu_library;
mod peers;
mod problem;

use cases::{Case, Knob};
use friction_fmu::cpu_clock::time_cpu;
use std::io::Write;

/// Timed runs per setting (their median is taken).
const REPEATS: usize = 5;
/// A run longer than this (s of CPU) is a solver's last setting: tighter ones are not run.
const CAP: f64 = 0.6;
/// Settings stop once two in a row are below this error: the 1e-9 column is then bracketed.
const FLOOR: f64 = 2e-10;
/// A run longer than this (s of CPU) is not repeated: its one run is its time (the explicit
/// peers and CVODE's Adams on the stiff contact, bound by their stability, take seconds).
const ONCE: f64 = 1.0;
/// A timed sample repeats a short run until it lasts this long (s), for the clock's sake.
const SAMPLE: f64 = 2e-3;
/// The errors the ratios are read at.
const ERRORS: [f64; 6] = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9];

struct Point {
    curve: usize,
    knob: Knob,
    error: f64,
    /// The largest error of this setting and every tighter one of its solver: a setting whose
    /// error happens to land low does not stand for its neighbours (benches/transverse.py
    /// reads its table the same way).
    worst: f64,
    rhs: u64,
    reps: u32,
    times: Vec<f64>,
    /// Timed once only (longer than [`ONCE`]).
    once: bool,
}

impl Point {
    fn median(&self) -> f64 {
        let mut t = self.times.clone();
        t.sort_by(f64::total_cmp);
        t[t.len() / 2]
    }
}

/// A solver's CPU time at an error, read off its work-precision curve.
#[derive(Clone, Copy, Debug)]
enum Cost {
    /// Interpolated between two settings (log-log).
    Exactly(f64),
    /// Its most accurate setting is less accurate: at least that setting's time.
    AtLeast(f64),
    /// Its least accurate setting is more accurate: at most that setting's time.
    AtMost(f64),
    Nothing,
}

/// The settings no other setting beats in both error and time, most accurate first.
fn frontier(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut sorted: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(e, t)| e.is_finite() && *e > 0.0 && *t > 0.0)
        .collect();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut out: Vec<(f64, f64)> = Vec::new();
    for p in sorted {
        if out.last().is_none_or(|last| p.1 < last.1) {
            out.push(p);
        }
    }
    out
}

fn time_at(front: &[(f64, f64)], e: f64) -> Cost {
    let (Some(first), Some(last)) = (front.first(), front.last()) else {
        return Cost::Nothing;
    };
    if e < first.0 {
        return Cost::AtLeast(first.1);
    }
    if e > last.0 {
        return Cost::AtMost(last.1);
    }
    let x = e.ln();
    for w in front.windows(2) {
        let (a, b) = (w[0], w[1]);
        if a.0 <= e && e <= b.0 {
            let f = if b.0 > a.0 {
                (x - a.0.ln()) / (b.0.ln() - a.0.ln())
            } else {
                0.0
            };
            return Cost::Exactly((a.1.ln() + f * (b.1.ln() - a.1.ln())).exp());
        }
    }
    Cost::Exactly(first.1)
}

/// The right-hand sides a solver takes at error `e`, interpolated (log-log) between the same
/// settings as its time (its (error, time) frontier); None outside them.
fn rhs_at(points: &[(f64, f64, f64)], e: f64) -> Option<f64> {
    let pairs: Vec<(f64, f64)> = points.iter().map(|p| (p.0, p.1)).collect();
    let front = frontier(&pairs);
    let rhs = |q: (f64, f64)| {
        points
            .iter()
            .find(|p| p.0 == q.0 && p.1 == q.1)
            .map(|p| p.2)
            .unwrap_or(f64::NAN)
    };
    front.windows(2).find_map(|w| {
        let (a, b) = (w[0], w[1]);
        (a.0 <= e && e <= b.0).then(|| {
            let f = if b.0 > a.0 {
                (e.ln() - a.0.ln()) / (b.0.ln() - a.0.ln())
            } else {
                0.0
            };
            (rhs(a).ln() + f * (rhs(b).ln() - rhs(a).ln())).exp()
        })
    })
}

/// peer / ours as a table cell: `>` a lower bound, `<` an upper one.
fn ratio(peer: Cost, ours: Cost) -> String {
    match (peer, ours) {
        (Cost::Exactly(p), Cost::Exactly(o)) => format!("{:.2}", p / o),
        (Cost::AtLeast(p), Cost::Exactly(o) | Cost::AtMost(o)) => format!("> {:.2}", p / o),
        (Cost::Exactly(p), Cost::AtMost(o)) => format!("> {:.2}", p / o),
        (Cost::AtMost(p), Cost::Exactly(o)) => format!("< {:.2}", p / o),
        (Cost::Nothing, _) => "fails".into(),
        (_, Cost::AtLeast(_)) => "ours n/r".into(),
        _ => "?".into(),
    }
}

fn short(e: f64) -> String {
    format!("{e:.0e}")
}

struct Measured {
    points: Vec<Point>,
    failures: Vec<(usize, Knob, String)>,
}

fn measure(case: &Case) -> Measured {
    let mut points = Vec::new();
    let mut failures = Vec::new();
    // The first round: which settings to run (and each one's error), and how many runs make a
    // timed sample.
    for (ci, curve) in case.curves.iter().enumerate() {
        if curve.absent.is_some() {
            continue;
        }
        let mut below = 0;
        for &knob in &curve.knobs {
            let (out, seconds) = time_cpu(|| (curve.run)(knob));
            let out = match out {
                Ok(o) if o.value.is_finite() => o,
                other => {
                    let why = match other {
                        Ok(o) => format!("non-finite reading {}", o.value),
                        Err(e) => e,
                    };
                    failures.push((ci, knob, why));
                    // Failures at loose settings are common (diffsol's Newton on the stiff
                    // contact), so tighter ones are tried: only the time limit stops them.
                    if seconds > CAP {
                        break;
                    }
                    continue;
                }
            };
            let error = ((out.value - case.reference) / case.reference).abs();
            if std::env::var_os("PEERS_VERBOSE").is_some() {
                eprintln!("{} {knob}: error {error:.2e}, {seconds:.2e} s", curve.name);
            }
            points.push(Point {
                curve: ci,
                knob,
                error,
                worst: error,
                rhs: out.rhs,
                reps: (SAMPLE / seconds.max(1e-9)).ceil().clamp(1.0, 1e4) as u32,
                times: if seconds > ONCE {
                    vec![seconds]
                } else {
                    Vec::new()
                },
                once: seconds > ONCE,
            });
            below = if error < FLOOR { below + 1 } else { 0 };
            if below >= 2 || seconds > CAP {
                break;
            }
        }
        eprint!(".");
    }
    // The library reports no counts: a run through it takes the steps of its in-process twin
    // (the same code; their readings agree to the bit, checked here).
    for k in 0..points.len() {
        let curve = &case.curves[points[k].curve];
        if !curve.via_library {
            continue;
        }
        let twin = curve.name.trim_end_matches(cases::LIBRARY_SUFFIX);
        let found = points
            .iter()
            .find(|q| case.curves[q.curve].name == twin && q.knob == points[k].knob)
            .map(|q| (q.rhs, q.error));
        if let Some((rhs, error)) = found {
            points[k].rhs = rhs;
            if error != points[k].error {
                eprintln!(
                    "{} {}: error {:.3e} in-process, {:.3e} through the library",
                    twin, points[k].knob, error, points[k].error
                );
            }
        }
    }
    for k in (0..points.len()).rev() {
        if let Some(next) = points.get(k + 1) {
            if next.curve == points[k].curve {
                points[k].worst = points[k].error.max(next.worst);
            }
        }
    }
    // The timed rounds, every setting of the case in turn in each.
    for _ in 0..REPEATS {
        for p in points.iter_mut().filter(|p| !p.once) {
            let run = &case.curves[p.curve].run;
            let (out, seconds) = time_cpu(|| {
                for _ in 0..p.reps {
                    std::hint::black_box(run(p.knob).ok());
                }
            });
            std::hint::black_box(out);
            p.times.push(seconds / f64::from(p.reps));
        }
        eprint!("+");
    }
    eprintln!();
    Measured { points, failures }
}

/// The fastest of `ats` (name, time) at one error, as (name, bound).
fn fastest<'a>(ats: &[(&'a str, Cost)]) -> Option<(&'a str, Cost)> {
    let value = |a: Cost| match a {
        Cost::Exactly(t) | Cost::AtMost(t) => Some(t),
        _ => None,
    };
    let best = ats
        .iter()
        .filter_map(|&(n, a)| value(a).map(|t| (n, a, t)))
        .min_by(|a, b| a.2.total_cmp(&b.2))
        .map(|(n, a, _)| (n, a));
    best.or_else(|| {
        ats.iter()
            .filter_map(|&(n, a)| match a {
                Cost::AtLeast(t) => Some((n, a, t)),
                _ => None,
            })
            .min_by(|a, b| a.2.total_cmp(&b.2))
            .map(|(n, a, _)| (n, a))
    })
}

/// One case: its reference, the ratio table, the summary row, then every setting measured.
fn report(case: &Case, m: &Measured, out: &mut impl Write, summary: &mut Vec<String>) {
    let w = |out: &mut dyn Write, s: String| writeln!(out, "{s}").expect("stdout");
    w(out, format!("\n## {}\n", case.title));
    w(
        out,
        format!("Reading: {}. {}.\n", case.quantity, case.reference_note),
    );
    let curve_points = |ci: usize| -> Vec<(f64, f64)> {
        m.points
            .iter()
            .filter(|p| p.curve == ci)
            .map(|p| (p.worst, p.median()))
            .collect()
    };
    let triples = |ours: bool, ci: Option<usize>| -> Vec<(f64, f64, f64)> {
        m.points
            .iter()
            .filter(|p| match ci {
                Some(c) => p.curve == c,
                None => case.curves[p.curve].ours == ours,
            })
            .map(|p| (p.worst, p.median(), p.rhs as f64))
            .collect()
    };
    let ours_all: Vec<(f64, f64)> = m
        .points
        .iter()
        .filter(|p| case.curves[p.curve].ours)
        .map(|p| (p.worst, p.median()))
        .collect();
    let ours = frontier(&ours_all);
    let header: Vec<String> = ERRORS.iter().map(|&e| format!("at {}", short(e))).collect();
    w(
        out,
        format!(
            "| CPU time / ours at equal error | {} |",
            header.join(" | ")
        ),
    );
    w(out, format!("|---|{}", "---|".repeat(ERRORS.len())));
    // Ours (in-process, or through the FMU's library): the CPU time at each error on the
    // frontier `ours` of the curves `pick` selects, and which solver gives it.
    let our_cells = |pick: fn(&cases::Curve) -> bool, ours: &[(f64, f64)]| -> Vec<String> {
        ERRORS
            .iter()
            .map(|&e| {
                let best = case
                    .curves
                    .iter()
                    .enumerate()
                    .filter(|(_, c)| pick(c))
                    .map(|(ci, c)| (c.name.as_str(), time_at(&frontier(&curve_points(ci)), e)))
                    .collect::<Vec<_>>();
                let name = |n: &str| {
                    n.trim_start_matches("ours ")
                        .trim_end_matches(cases::LIBRARY_SUFFIX)
                        .to_string()
                };
                match (time_at(ours, e), fastest(&best)) {
                    (Cost::Exactly(t), Some((n, _))) => format!("{t:.2e} s ({})", name(n)),
                    (Cost::AtMost(t), Some((n, _))) => format!("<= {t:.2e} s ({})", name(n)),
                    (Cost::AtLeast(t), _) => format!("n/r (>= {t:.2e} s)"),
                    _ => "-".into(),
                }
            })
            .collect()
    };
    let ours_cells = our_cells(|c| c.ours, &ours);
    w(
        out,
        format!(
            "| **ours** (CPU s, best of our solvers) | {} |",
            ours_cells.join(" | ")
        ),
    );
    // Ours through the FMU's library, where the case runs it.
    let library_all: Vec<(f64, f64)> = m
        .points
        .iter()
        .filter(|p| case.curves[p.curve].via_library)
        .map(|p| (p.worst, p.median()))
        .collect();
    let library = frontier(&library_all);
    let has_library = !library.is_empty();
    if has_library {
        let cells = our_cells(|c| c.via_library, &library);
        w(
            out,
            format!(
                "| **ours, FMU library** (CPU s; `fmu` profile, fmi2 calls) | {} |",
                cells.join(" | ")
            ),
        );
    }
    for c in case.curves.iter().filter(|c| c.via_library) {
        if let Some(why) = &c.absent {
            w(
                out,
                format!(
                    "| {} | {} |",
                    c.name,
                    vec![why.as_str(); ERRORS.len()].join(" | ")
                ),
            );
        }
    }
    let mut peer_ats: Vec<Vec<(&str, Cost)>> = vec![Vec::new(); ERRORS.len()];
    let mut cvode_bdf: Vec<Cost> = vec![Cost::Nothing; ERRORS.len()];
    for (ci, curve) in case.curves.iter().enumerate() {
        if curve.ours || curve.via_library {
            continue;
        }
        if let Some(why) = &curve.absent {
            w(
                out,
                format!(
                    "| {} | {} |",
                    curve.name,
                    vec![why.as_str(); ERRORS.len()].join(" | ")
                ),
            );
            continue;
        }
        let front = frontier(&curve_points(ci));
        let cells: Vec<String> = ERRORS
            .iter()
            .enumerate()
            .map(|(k, &e)| {
                let at = time_at(&front, e);
                peer_ats[k].push((curve.name.as_str(), at));
                if curve.name == "CVODE BDF" {
                    cvode_bdf[k] = at;
                }
                ratio(at, time_at(&ours, e))
            })
            .collect();
        w(out, format!("| {} | {} |", curve.name, cells.join(" | ")));
    }
    for q in &case.quoted {
        // Their settings are listed loosest first: the same worst-of-tighter reading.
        let mut points = q.points.clone();
        for k in (0..points.len().saturating_sub(1)).rev() {
            points[k].0 = points[k].0.max(points[k + 1].0);
        }
        let front = frontier(&points);
        let cells: Vec<String> = ERRORS
            .iter()
            .map(|&e| ratio(time_at(&front, e), time_at(&ours, e)))
            .collect();
        w(out, format!("| {} | {} |", q.name, cells.join(" | ")));
    }
    let fastest_cells: Vec<String> = peer_ats
        .iter()
        .enumerate()
        .map(|(k, ats)| match fastest(ats) {
            Some((name, at)) => format!("{} ({name})", ratio(at, time_at(&ours, ERRORS[k]))),
            None => "-".into(),
        })
        .collect();
    w(
        out,
        format!(
            "| **fastest compiled peer / ours** | {} |",
            fastest_cells.join(" | ")
        ),
    );
    let library_cells: Vec<String> = peer_ats
        .iter()
        .enumerate()
        .map(|(k, ats)| match fastest(ats) {
            Some((name, at)) => format!("{} ({name})", ratio(at, time_at(&library, ERRORS[k]))),
            None => "-".into(),
        })
        .collect();
    if has_library {
        w(
            out,
            format!(
                "| **fastest compiled peer / ours, FMU library** | {} |",
                library_cells.join(" | ")
            ),
        );
    }
    // Where the ratio comes from: the fastest peer's right-hand sides over ours, and its CPU
    // time per right-hand side over ours (the two multiply to the ratio).
    let ours_rhs = triples(true, None);
    let split: Vec<String> = peer_ats
        .iter()
        .enumerate()
        .map(|(k, ats)| {
            let e = ERRORS[k];
            let Some((name, Cost::Exactly(t))) = fastest(ats) else {
                return "-".into();
            };
            let Some(ci) = case.curves.iter().position(|c| c.name == name) else {
                return "-".into();
            };
            match (
                rhs_at(&triples(false, Some(ci)), e),
                rhs_at(&ours_rhs, e),
                time_at(&ours, e),
            ) {
                (Some(p), Some(o), Cost::Exactly(to)) => {
                    format!("{:.2} x {:.2}", p / o, (t / p) / (to / o))
                }
                _ => "-".into(),
            }
        })
        .collect();
    w(
        out,
        format!(
            "| fastest peer's RHS evaluations / ours x its CPU per RHS / ours | {} |",
            split.join(" | ")
        ),
    );
    summary.push(format!(
        "| {} | {} |",
        case.title.split(',').next().unwrap_or(""),
        fastest_cells.join(" | ")
    ));
    if has_library {
        summary.push(format!(
            "| {}, FMU library | {} |",
            case.title.split(',').next().unwrap_or(""),
            library_cells.join(" | ")
        ));
    }
    if case.title.contains("kt x 1000") {
        let cells: Vec<String> = cvode_bdf
            .iter()
            .enumerate()
            .map(|(k, &at)| ratio(at, time_at(&ours, ERRORS[k])))
            .collect();
        summary.push(format!(
            "| {}: CVODE BDF / ours | {} |",
            case.title.split(',').next().unwrap_or(""),
            cells.join(" | ")
        ));
    }
    w(out, String::new());
    w(
        out,
        format!("Every setting run (CPU s: median of {REPEATS}, with the least and the most):\n"),
    );
    w(out, "| solver | setting | rel. error | worst at this or tighter | CPU s | min-max | RHS evals | ns per RHS |".into());
    w(out, "|---|---|---|---|---|---|---|---|".into());
    for p in &m.points {
        let lo = p.times.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = p.times.iter().copied().fold(0.0, f64::max);
        w(
            out,
            format!(
                "| {} | {} | {:.2e} | {:.2e} | {:.3e} | {} | {} | {:.0} |",
                case.curves[p.curve].name,
                p.knob,
                p.error,
                p.worst,
                p.median(),
                if p.once {
                    "one run".to_string()
                } else {
                    format!("{lo:.2e}-{hi:.2e}")
                },
                p.rhs,
                p.median() / p.rhs.max(1) as f64 * 1e9
            ),
        );
    }
    for (ci, knob, e) in &m.failures {
        w(
            out,
            format!(
                "| {} | {} | failed: {} | | | | | |",
                case.curves[*ci].name,
                knob,
                e.replace('|', "/")
            ),
        );
    }
}

fn main() {
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let mut summary = Vec::new();
    writeln!(
        out,
        "# Compiled peers: CPU time at equal error, peer / ours\n\nCPU time of the running thread; each setting's median of {REPEATS} runs, the settings of a case alternating in each round. A setting's error is the largest of its own and its solver's tighter settings' (a setting that happens to land low does not stand for its neighbours). Ratios are read at each error on log-log work-precision curves (each solver's settings that no other of its settings beats in both that error and time); `>`/`<`: a bound, where a curve does not reach that error (`> r`: the peer's most accurate setting is less accurate and took r times ours; `< r`: its least accurate is more accurate); `n/r`: not reached. Ours: the best of our solvers at each error."
    )
    .expect("stdout");
    // scipy's Radau on scene T, 0.05 s from steady sliding, from benches/transverse_results.md
    // (Part 2): (rel. error, CPU s), measured by benches/transverse.py in its own process.
    let scipy_split: &[(f64, f64)] = &[(5.25e-7, 5.559), (3.62e-8, 7.377), (2.30e-7, 10.041)];
    let scipy_total: &[(f64, f64)] = &[(1.19e-7, 3.379), (3.95e-9, 5.578), (3.19e-10, 9.584)];
    let scipy_split_stiff: &[(f64, f64)] = &[(5.37e-6, 0.866), (2.54e-8, 1.246), (3.81e-8, 1.795)];
    let builders: Vec<Box<dyn Fn() -> Case>> = vec![
        Box::new(|| cases::transverse("split", 1.0, scipy_split)),
        Box::new(|| cases::transverse("total", 1.0, scipy_total)),
        Box::new(|| cases::transverse("split", 1000.0, scipy_split_stiff)),
        Box::new(|| cases::transverse("total", 1000.0, &[])),
        Box::new(cases::longitudinal),
        Box::new(cases::oscillator_trigonometric),
        Box::new(cases::oscillator_exact),
    ];
    // Arguments, if any, pick the cases whose builders' positions (0-6) they name.
    let picked: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    for (k, build) in builders.iter().enumerate() {
        if !picked.is_empty() && !picked.contains(&k) {
            continue;
        }
        eprintln!("case {k}");
        let (case, seconds) = time_cpu(build);
        eprint!("{} (reference {seconds:.1} s) ", case.title);
        let m = measure(&case);
        report(&case, &m, &mut out, &mut summary);
        out.flush().expect("stdout");
    }
    writeln!(
        out,
        "\n## Summary: the fastest compiled peer's CPU time over ours at equal error\n"
    )
    .expect("stdout");
    let header: Vec<String> = ERRORS.iter().map(|&e| format!("at {}", short(e))).collect();
    writeln!(out, "| case | {} |", header.join(" | ")).expect("stdout");
    writeln!(out, "|---|{}", "---|".repeat(ERRORS.len())).expect("stdout");
    for row in summary {
        writeln!(out, "{row}").expect("stdout");
    }
}
