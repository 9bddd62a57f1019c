//! Progress bars on stderr (indicatif), hidden with `--quiet` or when stderr is not a terminal,
//! so that CSV on stdout and logs stay clean.
//!
//! # The time left
//!
//! indicatif's own `{eta}` extrapolates the rate of the first units to the whole bar. A
//! sedimentation bar counts simulated seconds, and the first ones cost the most (short steps
//! while the coarse grains settle and meet; the step then grows to `max_step_s`): a 6 s run
//! showed an ETA of 17 minutes. The bar shows [`Eta`] instead: nothing during a warm-up
//! (the first [`WARMUP_S`] of wall time and [`WARMUP_FRACTION`] of the bar), then the remaining
//! units at the rate of the recent past (the last quarter of the elapsed time, at least 1 s), so
//! that a rate that changes is followed instead of averaged with its start.

use indicatif::{ProgressBar, ProgressState, ProgressStyle};
use std::cell::RefCell;
use std::collections::VecDeque;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Wall time before any time left is shown, s.
pub const WARMUP_S: f64 = 2.0;

/// Fraction of the bar before any time left is shown.
pub const WARMUP_FRACTION: f64 = 0.05;

/// An estimator of the time left from (wall time, position) observations of a bar of known
/// length: the rate over a trailing window, hidden during the warm-up.
#[derive(Clone, Debug, Default)]
pub struct Eta {
    samples: VecDeque<(f64, f64)>,
    len: f64,
}

impl Eta {
    /// An estimator for a bar of `len` units.
    pub fn new(len: f64) -> Self {
        Self {
            samples: VecDeque::new(),
            len,
        }
    }

    /// Records that `pos` units were done after `elapsed_s` of wall time.
    pub fn observe(&mut self, elapsed_s: f64, pos: f64) {
        if let Some(&(t, _)) = self.samples.back() {
            if elapsed_s < t {
                self.samples.clear();
            }
        }
        self.samples.push_back((elapsed_s, pos));
        // Keep the trailing window, plus the one sample just before it (its start).
        let window = self.window_s(elapsed_s);
        while self.samples.len() > 2 && self.samples[1].0 <= elapsed_s - window {
            self.samples.pop_front();
        }
    }

    fn window_s(&self, elapsed_s: f64) -> f64 {
        (0.25 * elapsed_s).max(1.0)
    }

    /// Seconds left, or None during the warm-up or while nothing moves.
    pub fn seconds_left(&self) -> Option<f64> {
        let (&(t0, p0), &(t1, p1)) = (self.samples.front()?, self.samples.back()?);
        if t1 < WARMUP_S || self.len <= 0.0 || p1 < WARMUP_FRACTION * self.len {
            return None;
        }
        let rate = (p1 - p0) / (t1 - t0);
        (rate > 0.0 && rate.is_finite()).then(|| (self.len - p1).max(0.0) / rate)
    }

    /// The time left as the bar shows it: `ETA 12 s`, `ETA 3.5 min`, `ETA 1.2 h`; `ETA …`
    /// during the warm-up.
    pub fn label(&self) -> String {
        match self.seconds_left() {
            None => "ETA …".into(),
            Some(s) if s < 1.0 => "ETA <1 s".into(),
            Some(s) if s < 120.0 => format!("ETA {:.0} s", s),
            Some(s) if s < 7200.0 => format!("ETA {} min", crate::io::fmt::sig(s / 60.0, 2)),
            Some(s) => format!("ETA {} h", crate::io::fmt::sig(s / 3600.0, 2)),
        }
    }
}

impl indicatif::style::ProgressTracker for Eta {
    fn clone_box(&self) -> Box<dyn indicatif::style::ProgressTracker> {
        Box::new(self.clone())
    }

    fn tick(&mut self, state: &ProgressState, _now: Instant) {
        self.len = state.len().unwrap_or(0) as f64;
        self.observe(state.elapsed().as_secs_f64(), state.pos() as f64);
    }

    fn reset(&mut self, _state: &ProgressState, _now: Instant) {
        self.samples.clear();
    }

    fn write(&self, _state: &ProgressState, w: &mut dyn std::fmt::Write) {
        let _ = w.write_str(&self.label());
    }
}

/// A window on the progress of a computation, for a caller that draws its own bar (the Python
/// package draws one in a terminal or a Jupyter notebook). Inside [`Watch::scope`], every
/// progress bar the computation makes on this thread is not drawn on stderr but tracked here;
/// [`Watch::shown`] reads the latest one from any thread.
#[derive(Clone, Debug, Default)]
pub struct Watch(Arc<Mutex<Option<(ProgressBar, String)>>>);

/// What a watched progress bar shows.
#[derive(Clone, Debug, PartialEq)]
pub struct Shown {
    /// What is counted: the scenario's name.
    pub name: String,
    /// Units done.
    pub pos: u64,
    /// Units in all (None while unknown).
    pub len: Option<u64>,
    /// The unit: `s simulated`, `cases`, `repeats`.
    pub unit: String,
    /// Live figures: steps so far, steps per second.
    pub message: String,
}

thread_local! {
    static WATCHING: RefCell<Option<Watch>> = const { RefCell::new(None) };
}

impl Watch {
    /// A watch with nothing to show yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Runs `f` with this watch on the current thread (nested scopes restore the outer one).
    pub fn scope<T>(&self, f: impl FnOnce() -> T) -> T {
        let outer = WATCHING.with(|w| w.replace(Some(self.clone())));
        struct Restore(Option<Watch>);
        impl Drop for Restore {
            fn drop(&mut self) {
                WATCHING.with(|w| *w.borrow_mut() = self.0.take());
            }
        }
        let _restore = Restore(outer);
        f()
    }

    /// The watch of the current thread's [`Watch::scope`], if any (to carry it into a thread
    /// pool's worker).
    pub fn current() -> Option<Watch> {
        WATCHING.with(|w| w.borrow().clone())
    }

    /// The latest bar's state, if a bar was made.
    pub fn shown(&self) -> Option<Shown> {
        let guard = self.0.lock().ok()?;
        let (bar, unit) = guard.as_ref()?;
        Some(Shown {
            name: bar.prefix(),
            pos: bar.position(),
            len: bar.length(),
            unit: unit.clone(),
            message: bar.message().trim_end_matches(',').to_string(),
        })
    }
}

/// The watched bar of `len` units, if the current thread is inside a [`Watch::scope`].
fn watched(len: u64, name: &str, unit: &str) -> Option<ProgressBar> {
    let watch = WATCHING.with(|w| w.borrow().clone())?;
    let bar = ProgressBar::hidden();
    bar.set_length(len);
    bar.set_prefix(name.to_string());
    let unit = unit
        .split(['{', ','])
        .next()
        .unwrap_or("")
        .trim()
        .to_string();
    if let Ok(mut g) = watch.0.lock() {
        *g = Some((bar.clone(), unit));
    }
    Some(bar)
}

/// A bar of `len` units, prefixed by `name`, with a template whose `{pos}`/`{len}` are followed
/// by `unit` (e.g. "cases", "s simulated"); `{msg}` carries live figures (steps, step rate), then
/// the time left ([`Eta`]). Hidden when `quiet` or when stderr is not a terminal; inside a
/// [`Watch::scope`], tracked by the watch and not drawn (whatever `quiet` says).
pub fn bar(len: u64, name: &str, unit: &str, quiet: bool) -> ProgressBar {
    use std::io::IsTerminal;
    if let Some(bar) = watched(len, name, unit) {
        return bar;
    }
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(len);
    let template = format!("{{prefix}} [{{bar:30}}] {{pos}}/{{len}} {unit} {{msg}} {{left}}");
    bar.set_style(
        ProgressStyle::with_template(&template)
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .with_key("left", Eta::new(len as f64))
            .progress_chars("=> "),
    );
    bar.set_prefix(name.to_string());
    bar
}

/// Live figures of a stepping loop for a bar's message: steps so far and steps per second of
/// wall time since `start`.
pub fn step_message(steps: u64, start: std::time::Instant) -> String {
    let rate = steps as f64 / start.elapsed().as_secs_f64().max(1e-9);
    format!("{steps} steps, {} steps/s,", crate::io::fmt::sig(rate, 3))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Feeds `pos(t)` every 0.05 s from `from_s` to `until_s`.
    fn run(eta: &mut Eta, pos: impl Fn(f64) -> f64, from_s: f64, until_s: f64) {
        let mut k = (from_s / 0.05).round() as u32;
        while 0.05 * k as f64 <= until_s + 1e-9 {
            let t = 0.05 * k as f64;
            eta.observe(t, pos(t));
            k += 1;
        }
    }

    #[test]
    fn a_watch_tracks_the_bars_made_in_its_scope_only() {
        let watch = Watch::new();
        let outside = bar(10, "before", "cases,", false);
        outside.inc(1);
        assert_eq!(watch.shown(), None);
        watch.scope(|| {
            let b = bar(40, "sedimentation", "s simulated {msg}", true);
            b.inc(3);
            b.set_message("12 steps, 100 steps/s,");
        });
        let shown = watch.shown().expect("a bar was made in the scope");
        assert_eq!(shown.name, "sedimentation");
        assert_eq!((shown.pos, shown.len), (3, Some(40)));
        assert_eq!(shown.unit, "s simulated");
        assert_eq!(shown.message, "12 steps, 100 steps/s");
        let after = bar(5, "after", "cases", true);
        after.inc(5);
        assert_eq!(watch.shown().unwrap().name, "sedimentation");
    }

    #[test]
    fn steady_progress_gives_the_exact_time_left() {
        let mut eta = Eta::new(100.0);
        run(&mut eta, |t| 10.0 * t, 0.0, 4.0); // 10 units/s: 60 units left at t = 4 s
        let left = eta.seconds_left().unwrap();
        assert!((left - 6.0).abs() < 0.05, "{left}");
        assert_eq!(eta.label(), "ETA 6 s");
    }

    #[test]
    fn nothing_is_shown_during_the_warm_up() {
        let mut eta = Eta::new(100.0);
        run(&mut eta, |t| 10.0 * t, 0.0, 1.5);
        assert_eq!(eta.seconds_left(), None);
        assert_eq!(eta.label(), "ETA …");
        let mut slow = Eta::new(100.0);
        run(&mut slow, |t| 0.01 * t, 0.0, 10.0); // 10 s in, 0.1 % done
        assert_eq!(slow.seconds_left(), None);
    }

    /// The friction of issue 13: the first units are slow (3 % of the bar in 5 s), the rest fast
    /// (97 % in 1 s): a 6 s run. The rate of the early units would predict 160 s of the 1 s left;
    /// the estimator shows nothing while the start is slow, then follows the fast rate.
    #[test]
    fn a_slow_start_does_not_inflate_the_time_left() {
        let pos = |t: f64| {
            if t < 5.0 {
                0.6 * t
            } else {
                3.0 + 97.0 * (t - 5.0).min(1.0)
            }
        };
        let mut eta = Eta::new(100.0);
        run(&mut eta, pos, 0.0, 4.9);
        assert_eq!(eta.seconds_left(), None, "3 % done: still warming up");
        run(&mut eta, pos, 4.95, 5.5);
        let left = eta.seconds_left().unwrap();
        let truth = 0.5;
        assert!(left < 3.0 * truth, "{left} s left shown, {truth} s true");
        let early_rate_estimate = (100.0 - pos(5.5)) / 0.6;
        assert!(early_rate_estimate > 50.0 * truth);
    }
}
