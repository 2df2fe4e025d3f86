//! A one-line progress bar on stderr, redrawn in place, so a long report shows it is alive
//! without cluttering stdout (which a user may redirect into a file).

use std::io::Write as _;

pub struct Progress {
    total: usize,
    done: usize,
}

const WIDTH: usize = 30;

impl Progress {
    pub fn new(total: usize) -> Self {
        Progress { total, done: 0 }
    }

    /// Marks one more item done and redraws the bar with `label` (what runs next).
    pub fn tick(&mut self, label: &str) {
        self.done = (self.done + 1).min(self.total);
        self.draw(label);
    }

    pub fn draw(&self, label: &str) {
        let filled = WIDTH * self.done / self.total.max(1);
        let bar: String = "#".repeat(filled) + &" ".repeat(WIDTH - filled);
        // \x1b[K clears what a longer previous label left behind.
        eprint!("\r[{bar}] {}/{} {label}\x1b[K", self.done, self.total);
        let _ = std::io::stderr().flush();
    }

    pub fn finish(&self) {
        eprintln!();
    }
}
