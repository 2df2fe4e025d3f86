//! friction-fmu: builds the FMUs and prints what they compute beside the papers.
//!
//!   friction-fmu build [--out DIR]   pack every model into DIR/<Model>.fmu (default fmu-out) and
//!                                    DIR/fmi3/<Model>.fmu (FMI 3.0), and the drive-coupled
//!                                    system into DIR/DriveFriction.ssp
//!   friction-fmu build FILE.toml... [--out DIR]
//!                                    pack each variant into DIR/<name>.fmu: the model's
//!                                    library with only the variables the file keeps; the FMI
//!                                    3.0 FMU into DIR/fmi3/<name>.fmu, or for a DIR named
//!                                    variants, into fmi3/variants beside it
//!   friction-fmu run [--out DIR]     build, pack the shipped variants/*.toml into
//!                                    DIR/variants (and DIR/fmi3/variants), then print each scene's tables beside the
//!                                    papers' and write figures into DIR/figures (the default
//!                                    command)
//!   friction-fmu report [--out DIR]  error against run time of every solver of every scene:
//!                                    DIR/<scene>.md tables and DIR/<scene>.png/.svg plots
//!                                    (default DIR: fmu-out/report); variants against the
//!                                    full models in DIR/trimmed.md; then prints the stability
//!                                    matrix
//!
//! Figures are written as data (DIR/<name>.csv and .json) and drawn into .png and .svg beside
//! it by the Python package, with .venv's interpreter when it has matplotlib
//! (report::figure::draw).

use friction_fmu::package::Standard;
use friction_fmu::{models, package, report, variant};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::OnceLock;

const USAGE: &str = "usage: friction-fmu [build [VARIANT.toml...]|run|report] [--out DIR] [--version]\n  (no command: run)\n  build   pack every model into DIR/<Model>.fmu and DIR/fmi3/<Model>.fmu (FMI 3.0) (default DIR: fmu-out) and the drive-coupled system into DIR/DriveFriction.ssp\n          or, given variants, each into DIR/<name>.fmu with only the variables it keeps, and into DIR/fmi3/<name>.fmu (for a DIR named variants: fmi3/variants beside it)\n  run     build, pack variants/*.toml into DIR/variants, then print the scenes' tables beside the papers' and write figures into DIR/figures\n  report  error against run time of every solver: DIR/<scene>.md and DIR/<scene>.png/.svg (default DIR: fmu-out/report), variants against the full models: DIR/trimmed.md, then the stability matrix\n  figures are written as data (.csv, .json) and drawn into .png and .svg by .venv/bin/python -m friction_fmu.figures DIR";

/// The FMU libraries of every model and platform whose toolchain is installed, built from the
/// source tree this program was built from. What the platforms not built lack is kept for the
/// end of the output ([`NOT_BUILT`]).
fn libraries() -> Result<Vec<package::Library>, String> {
    let built =
        package::platforms::libraries(Path::new(env!("CARGO_MANIFEST_DIR")), variant::trimmable)?;
    if let Some(report) = built.missing.report() {
        let _ = NOT_BUILT.set(report);
    }
    Ok(built.libraries)
}

/// Which platforms [`libraries`] could not build and the command that adds them: the last
/// thing the main command prints, where a user sees it.
static NOT_BUILT: OnceLock<String> = OnceLock::new();

/// Where the FMI 3.0 FMUs of the FMI 2.0 ones in `out` go: `out/fmi3`, except that a directory
/// named `variants` (as `run` writes) pairs with `fmi3/variants` beside it, so that
/// `fmu-out/variants` and `fmu-out/fmi3/variants` hold the same variants.
fn fmi3_dir(out: &Path) -> PathBuf {
    match (out.parent(), out.file_name()) {
        (Some(parent), Some(name)) if name == "variants" => parent.join("fmi3").join(name),
        _ => out.join("fmi3"),
    }
}

/// Packs variants, for FMI 2.0 into `out` and FMI 3.0 into [`fmi3_dir`]; all are checked
/// before any library is built or FMU written. `libraries`: those already built, if any.
fn build_variants(
    files: &[PathBuf],
    out: &Path,
    libraries: Option<&[package::Library]>,
) -> Result<(), String> {
    let variants = files
        .iter()
        .map(|file| variant::read(file))
        .collect::<Result<Vec<_>, _>>()?;
    for (i, variant) in variants.iter().enumerate() {
        // One letter case apart is the same file on Windows' and macOS's file systems.
        let same = |s: &variant::Variant| s.name.eq_ignore_ascii_case(&variant.name);
        if let Some(other) = variants[..i].iter().position(same) {
            return Err(format!(
                "{} and {} both name their FMU \"{}\" (up to letter case): expected one FMU per name",
                files[other].display(),
                files[i].display(),
                variant.name
            ));
        }
    }
    let built;
    let libraries = match libraries {
        Some(libraries) => libraries,
        None => {
            built = self::libraries()?;
            &built
        }
    };
    for variant in &variants {
        for (standard, dir) in [
            (Standard::Fmi2, out.to_path_buf()),
            (Standard::Fmi3, fmi3_dir(out)),
        ] {
            let path = package::pack_variant_for(standard, variant, libraries, &dir)
                .map_err(|e| format!("packing {}: {e}", variant.name))?;
            println!("wrote {}", path.display());
        }
    }
    Ok(())
}

fn build(out: &Path, libraries: &[package::Library]) -> Result<(), String> {
    for model in models::MODELS {
        let id = model.table.model_identifier;
        for (standard, dir) in [
            (Standard::Fmi2, out.to_path_buf()),
            (Standard::Fmi3, fmi3_dir(out)),
        ] {
            let path = package::pack_for(standard, id, libraries, &dir)
                .map_err(|e| format!("packing {id}: {e}"))?;
            println!("wrote {}", path.display());
        }
    }
    let path = package::ssp::write(out).map_err(|e| format!("packing the system: {e}"))?;
    println!("wrote {}", path.display());
    let path = package::osp::write(out)
        .map_err(|e| format!("writing the system for libcosim's ECCO: {e}"))?;
    println!("wrote {}", path.display());
    for path in package::refresh_committed_xml()
        .map_err(|e| format!("{}: {e}", package::COMMITTED_XML_DIR))?
    {
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// The variants shipped in `variants/` (one per figure and table of the papers), when run from
/// the source tree.
fn shipped_variants() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir("variants")
        .map(|dir| {
            dir.filter_map(|entry| entry.ok().map(|e| e.path()))
                .filter(|path| path.extension().is_some_and(|ext| ext == "toml"))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}

fn run(out: &Path) -> Result<(), String> {
    let libraries = libraries()?;
    build(out, &libraries)?;
    let files = shipped_variants();
    if !files.is_empty() {
        build_variants(&files, &out.join("variants"), Some(&libraries))?;
    }
    let figures = out.join("figures");
    std::fs::create_dir_all(&figures).map_err(|e| format!("{}: {e}", figures.display()))?;
    println!();
    report::longitudinal::print_tables(&mut std::io::stdout()).map_err(|e| e.to_string())?;
    println!();
    report::transverse::print_summary(&figures).map_err(|e| e.to_string())?;
    println!();
    report::oscillator::print_summary(&figures).map_err(|e| e.to_string())?;
    println!();
    report::figure::draw(&figures)
}

fn work_precision(out: &Path) -> Result<(), String> {
    for path in report::work_precision::write_all(&report::cases::all(), out)? {
        println!("wrote {}", path.display());
    }
    // Drawn before the long stages that follow; a failed drawing is reported at the end, the
    // data being on disk already.
    let drawn = report::figure::draw(out);
    if let Err(message) = &drawn {
        eprintln!("friction-fmu: {message}");
    }
    let (path, table) = report::trimmed::write(out)?;
    println!("\n{table}wrote {}", path.display());
    stability()?;
    drawn.map_err(|_| "the report's figures were not drawn (the message above says why)".into())
}

/// The stability matrix runs the FMUs through the in-process driver, built where it is.
#[cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]
fn stability() -> Result<(), String> {
    println!("\nStability matrix: every solver at the stiff and extreme cases\n");
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get());
    let progress = std::sync::Mutex::new(None);
    let rows = report::stability::matrix(threads, &|row, total| {
        let mut progress = progress.lock().unwrap_or_else(|e| e.into_inner());
        progress
            .get_or_insert_with(|| report::progress::Progress::new("stability matrix", total))
            .tick(&format!("{} {} {}", row.model, row.solver, row.extreme));
    });
    if let Some(progress) = progress.into_inner().unwrap_or_else(|e| e.into_inner()) {
        progress.finish();
    }
    report::stability::print(&rows, &mut std::io::stdout()).map_err(|e| e.to_string())
}

#[cfg(not(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64")
)))]
fn stability() -> Result<(), String> {
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut command = "run";
    let mut out = None;
    let mut files = Vec::new();
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "build" => command = "build",
            "run" => command = "run",
            "report" => command = "report",
            "--out" if i + 1 < args.len() => {
                out = Some(PathBuf::from(&args[i + 1]));
                i += 1;
            }
            "--out" => {
                eprintln!("--out needs a directory\n{USAGE}");
                return ExitCode::from(2);
            }
            "-h" | "--help" => {
                println!("{USAGE}");
                return ExitCode::SUCCESS;
            }
            "-V" | "--version" => {
                println!("friction-fmu {}", env!("CARGO_PKG_VERSION"));
                return ExitCode::SUCCESS;
            }
            file if command == "build" && !file.starts_with('-') => {
                files.push(PathBuf::from(file));
            }
            other => {
                eprintln!("unknown argument {other:?}\n{USAGE}");
                return ExitCode::from(2);
            }
        }
        i += 1;
    }
    let result = match command {
        "build" if !files.is_empty() => build_variants(
            &files,
            &out.unwrap_or_else(|| PathBuf::from("fmu-out")),
            None,
        ),
        "build" => libraries().and_then(|libraries| {
            build(&out.unwrap_or_else(|| PathBuf::from("fmu-out")), &libraries)
        }),
        // Not the tracked report/ (the published tables): a plain run leaves the checkout clean.
        "report" => work_precision(&out.unwrap_or_else(|| PathBuf::from("fmu-out/report"))),
        _ => run(&out.unwrap_or_else(|| PathBuf::from("fmu-out"))),
    };
    let code = match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("friction-fmu: {message}");
            ExitCode::FAILURE
        }
    };
    if let Some(report) = NOT_BUILT.get() {
        eprintln!("\nfriction-fmu: {report}");
    }
    code
}
