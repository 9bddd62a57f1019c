//! Progress bars on stderr (indicatif), hidden with `--quiet` or when stderr is not a terminal,
//! so that CSV on stdout and logs stay clean.

use indicatif::{ProgressBar, ProgressStyle};

/// A bar of `len` units, prefixed by `name`, with a template whose `{pos}`/`{len}` are followed
/// by `unit` (e.g. "cases", "s simulated"); `{msg}` carries live figures (steps, step rate).
/// Hidden when `quiet` or when stderr is not a terminal.
pub fn bar(len: u64, name: &str, unit: &str, quiet: bool) -> ProgressBar {
    use std::io::IsTerminal;
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(len);
    let template = format!("{{prefix}} [{{bar:30}}] {{pos}}/{{len}} {unit} {{msg}} ETA {{eta}}");
    bar.set_style(
        ProgressStyle::with_template(&template)
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.set_prefix(name.to_string());
    bar
}

/// Live figures of a stepping loop for a bar's message: steps so far and steps per second of
/// wall time since `start`.
pub fn step_message(steps: u64, start: std::time::Instant) -> String {
    let rate = steps as f64 / start.elapsed().as_secs_f64().max(1e-9);
    format!("{steps} steps, {rate:.0} steps/s,")
}
