//! The study's progress bar (indicatif; hidden when stderr is not a terminal,
//! where each step and note is printed as a plain line instead).

use super::StudyProgress;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;

/// A progress bar over the study's points.
pub struct StudyBar {
    bar: ProgressBar,
    terminal: bool,
}

impl StudyBar {
    /// A bar on stderr.
    pub fn new() -> Self {
        let bar = ProgressBar::new(0);
        bar.set_style(
            ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} {wide_msg}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        StudyBar { bar, terminal: std::io::stderr().is_terminal() }
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Default for StudyBar {
    fn default() -> Self {
        Self::new()
    }
}

impl StudyProgress for StudyBar {
    fn start(&mut self, steps: u64) {
        self.bar.set_length(steps);
    }

    fn step(&mut self, message: &str) {
        self.bar.inc(1);
        if self.terminal {
            self.bar.set_message(message.to_string());
        } else {
            eprintln!("[{}/{}] {message}", self.bar.position(), self.bar.length().unwrap_or(0));
        }
    }

    fn note(&mut self, message: &str) {
        if self.terminal {
            self.bar.println(message);
        } else {
            eprintln!("{message}");
        }
    }
}
