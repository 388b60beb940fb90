//! Progress bars for steps a person waits for: on standard error, only when it is a
//! terminal, never with `--quiet`, and only once a step has run for about a second (a
//! fast step shows nothing). Rates print with one decimal ("13.1/s"), bytes in binary units.

use std::fmt::Write as _;
use std::io::IsTerminal;
use std::thread;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};

/// How long a step runs before its bar appears.
const SHOW_AFTER: Duration = Duration::from_secs(1);

/// What a bar counts.
#[derive(Debug, Clone, Copy)]
pub enum Unit {
    /// Bytes of a file.
    Bytes,
    /// Things, named in the plural ("segments", "rows").
    Items(&'static str),
}

/// Whether bars may show: `false` with `--quiet` or when standard error is not a terminal.
#[derive(Debug, Clone, Copy)]
pub struct Progress {
    shown: bool,
    quiet: bool,
}

impl Progress {
    /// Bars unless `quiet`, and only on a terminal.
    pub fn new(quiet: bool) -> Self {
        Self {
            shown: !quiet && std::io::stderr().is_terminal(),
            quiet,
        }
    }

    /// Whether `--quiet` asked for silence: advisories (not errors) are not printed either.
    pub fn quiet(self) -> bool {
        self.quiet
    }

    /// A bar of `len` units for the step `what` ("reading maze.json"), appearing after
    /// [`SHOW_AFTER`] if the step is still running. `finish_and_clear` it when done.
    pub fn bar(self, what: impl Into<String>, len: u64, unit: Unit) -> ProgressBar {
        self.later(Some(len), style(unit), what.into())
    }

    /// A spinner with the time taken, for a step whose length is unknown.
    pub fn spinner(self, what: impl Into<String>) -> ProgressBar {
        let style =
            ProgressStyle::with_template("{spinner} {msg} ({elapsed})").expect("a valid template");
        self.later(None, style, what.into())
    }

    /// A hidden bar that shows after [`SHOW_AFTER`] unless finished by then.
    fn later(self, len: Option<u64>, style: ProgressStyle, what: String) -> ProgressBar {
        if !self.shown {
            return ProgressBar::hidden();
        }
        let bar = ProgressBar::with_draw_target(len, ProgressDrawTarget::hidden())
            .with_style(style)
            .with_message(what);
        let later = bar.downgrade();
        thread::spawn(move || {
            thread::sleep(SHOW_AFTER);
            if let Some(bar) = later.upgrade().filter(|bar| !bar.is_finished()) {
                bar.set_draw_target(ProgressDrawTarget::stderr());
                bar.enable_steady_tick(Duration::from_millis(200));
            }
        });
        bar
    }
}

/// A progress bar that the core's long steps tell ([`crate::progress::Progress`]): the
/// core counts, the bar shows.
pub struct Told<'a>(pub &'a ProgressBar);

impl crate::progress::Progress for Told<'_> {
    fn set_length(&self, steps: u64) {
        self.0.set_length(steps);
    }

    fn advance(&self, steps: u64) {
        self.0.inc(steps);
    }
}

/// The bar's look for `unit`.
fn style(unit: Unit) -> ProgressStyle {
    let template = match unit {
        Unit::Bytes => "{msg} [{bar:30}] {binary_bytes}/{binary_total_bytes}, {rate}, eta {eta}",
        Unit::Items(_) => "{msg} [{bar:30}] {human_pos}/{human_len} {unit}, {rate}, eta {eta}",
    };
    ProgressStyle::with_template(template)
        .expect("a valid template")
        .progress_chars("=> ")
        .with_key(
            "rate",
            move |state: &ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = w.write_str(&rate(unit, state.per_sec()));
            },
        )
        .with_key(
            "unit",
            move |_: &ProgressState, w: &mut dyn std::fmt::Write| {
                if let Unit::Items(name) = unit {
                    let _ = w.write_str(name);
                }
            },
        )
}

/// A rate with sensible precision: one decimal, bytes in MiB.
fn rate(unit: Unit, per_second: f64) -> String {
    let mut text = String::new();
    match unit {
        Unit::Bytes => {
            let _ = write!(text, "{:.1} MiB/s", per_second / (1024.0 * 1024.0));
        }
        Unit::Items(_) => {
            let _ = write!(text, "{}/s", human(per_second));
        }
    }
    text
}

/// `13.1`, `4.2k`, `1.3M`: one decimal, thousands and millions abbreviated.
fn human(value: f64) -> String {
    if value >= 1e6 {
        format!("{:.1}M", value / 1e6)
    } else if value >= 1e4 {
        format!("{:.1}k", value / 1e3)
    } else {
        format!("{value:.1}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_have_one_decimal() {
        assert_eq!(rate(Unit::Items("lines"), 13.0734), "13.1/s");
        assert_eq!(rate(Unit::Items("rows"), 41_234.5), "41.2k/s");
        assert_eq!(rate(Unit::Items("rows"), 2_345_678.0), "2.3M/s");
        assert_eq!(rate(Unit::Bytes, 3.0 * 1024.0 * 1024.0 + 1.0), "3.0 MiB/s");
    }

    #[test]
    fn quiet_or_piped_bars_stay_hidden() {
        let bar = Progress::new(true).bar("reading", 10, Unit::Bytes);
        assert!(bar.is_hidden());
        bar.inc(5);
        assert_eq!(bar.position(), 5);
    }
}
