//! Progress of a long report stage on stderr, so a long report shows it is alive without
//! cluttering stdout (which a user may redirect into a file). On a terminal one bar is redrawn in
//! place; elsewhere (a log file, CI) plain lines, one per tenth of the stage, with no carriage
//! returns or escape codes.

use std::io::{IsTerminal as _, Write as _};

pub struct Progress {
    stage: &'static str,
    total: usize,
    done: usize,
    terminal: bool,
    /// Tenths of the stage already reported as a plain line.
    reported: usize,
}

const WIDTH: usize = 30;

impl Progress {
    /// A stage of `total` items; says that it starts.
    pub fn new(stage: &'static str, total: usize) -> Self {
        let progress = Progress {
            stage,
            total,
            done: 0,
            terminal: std::io::stderr().is_terminal(),
            reported: 0,
        };
        if !progress.terminal {
            eprintln!("{stage}: 0/{total}");
        }
        progress
    }

    /// Marks one more item done; `label` says what ran.
    pub fn tick(&mut self, label: &str) {
        self.done = (self.done + 1).min(self.total);
        if self.terminal {
            self.draw(label);
            return;
        }
        let tenths = 10 * self.done / self.total.max(1);
        if tenths > self.reported {
            self.reported = tenths;
            eprintln!("{}: {}/{} {label}", self.stage, self.done, self.total);
        }
    }

    /// Shows what runs next (on a terminal only: a plain log gets a line per tenth).
    pub fn draw(&self, label: &str) {
        if !self.terminal {
            return;
        }
        let filled = WIDTH * self.done / self.total.max(1);
        let bar: String = "#".repeat(filled) + &" ".repeat(WIDTH - filled);
        // \x1b[K clears what a longer previous label left behind.
        eprint!(
            "\r{} [{bar}] {}/{} {label}\x1b[K",
            self.stage, self.done, self.total
        );
        let _ = std::io::stderr().flush();
    }

    pub fn finish(&self) {
        if self.terminal {
            eprintln!();
        }
    }
}
