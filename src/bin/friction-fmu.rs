//! friction-fmu: builds the FMUs and prints what they compute beside the papers.
//!
//!   friction-fmu build [--out DIR]   pack every model into DIR/<Model>.fmu (default fmu-out)
//!   friction-fmu run [--out DIR]     build, then print each scene's tables beside the papers'
//!                                    and write figures into DIR/figures (the default command)

use friction_fmu::{package, report, scenes};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const USAGE: &str = "usage: friction-fmu [build|run] [--out DIR]\n  build  pack every model into DIR/<Model>.fmu (default DIR: fmu-out)\n  run    build, then print the scenes' tables beside the papers' and write figures into DIR/figures";

fn build(out: &Path) -> Result<(), String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot locate this program: {e}"))?;
    let dir = exe.parent().ok_or("this program has no directory")?;
    let library = package::library_beside(dir);
    if !library.exists() {
        return Err(format!(
            "{} is missing: build the library first (cargo build --release)",
            library.display()
        ));
    }
    for model in scenes::MODELS {
        let path = package::pack(model.table.model_identifier, &library, out)
            .map_err(|e| format!("packing {}: {e}", model.table.model_identifier))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

fn run(out: &Path) -> Result<(), String> {
    build(out)?;
    let figures = out.join("figures");
    std::fs::create_dir_all(&figures).map_err(|e| format!("{}: {e}", figures.display()))?;
    println!();
    report::longitudinal::print_tables(&mut std::io::stdout()).map_err(|e| e.to_string())?;
    println!();
    report::transverse::print_summary(&figures).map_err(|e| e.to_string())?;
    println!();
    report::oscillator::print_summary(&figures).map_err(|e| e.to_string())?;
    println!("\nfigures in {}", figures.display());
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut command = "run";
    let mut out = PathBuf::from("fmu-out");
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "build" | "run" => command = if args[i] == "build" { "build" } else { "run" },
            "--out" if i + 1 < args.len() => {
                out = PathBuf::from(&args[i + 1]);
                i += 1;
            }
            "-h" | "--help" => {
                println!("{USAGE}");
                return ExitCode::SUCCESS;
            }
            other => {
                eprintln!("unknown argument {other:?}\n{USAGE}");
                return ExitCode::from(2);
            }
        }
        i += 1;
    }
    let result = if command == "build" {
        build(&out)
    } else {
        run(&out)
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("friction-fmu: {message}");
            ExitCode::FAILURE
        }
    }
}
