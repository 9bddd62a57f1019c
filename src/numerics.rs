//! Bracketing root finders shared by the physics and the commands: bisection
//! ([`bisect`], [`try_bisect`]) and Newton's method safeguarded by a bracket
//! ([`safeguarded_newton`]). No domain types.
//!
//! Each caller keeps its own stopping rule (a number of halvings, a width, machine precision;
//! for Newton a closure), so that moving a hand-written loop here changes no result: the
//! midpoint is always `0.5 * (lo + hi)`, and the rule is checked where the loops checked it.
//! Sources: bisection, e.g. Press et al., *Numerical Recipes* (3rd ed., 2007) §9.1; Newton's
//! method with a bisection safeguard ("rtsafe"), ibid. §9.4.

/// When [`bisect`] stops halving early (it always stops after [`Bisection::halvings`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stop {
    /// Never early: every halving is made.
    Never,
    /// Once |hi − lo| ≤ the width (checked before each halving, also before the first).
    Width(f64),
    /// Once |hi − lo| < the width (checked before each halving, also before the first).
    WidthBelow(f64),
    /// Once the midpoint rounds to one of the ends (machine precision).
    Adjacent,
}

/// The iteration rule of [`bisect`]: at most `halvings` halvings, fewer by `stop`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bisection {
    /// The most halvings made.
    pub halvings: usize,
    /// The early stop.
    pub stop: Stop,
}

impl Bisection {
    /// Exactly `halvings` halvings.
    pub fn halvings(halvings: usize) -> Self {
        Self {
            halvings,
            stop: Stop::Never,
        }
    }

    /// At most `halvings` halvings, stopping early by `stop`.
    pub fn until(stop: Stop, halvings: usize) -> Self {
        Self { halvings, stop }
    }

    fn done(&self, lo: f64, hi: f64) -> bool {
        match self.stop {
            Stop::Never => false,
            Stop::Width(w) => (hi - lo).abs() <= w,
            Stop::WidthBelow(w) => (hi - lo).abs() < w,
            Stop::Adjacent => {
                let mid = 0.5 * (lo + hi);
                mid == lo || mid == hi
            }
        }
    }
}

/// Bisection of the bracket (`lo`, `hi`) of a predicate that holds at `lo` and not at `hi`
/// (`lo` may be above `hi`): each halving evaluates `toward_hi` at the midpoint
/// m = (lo + hi)/2 and moves `lo` to m where it holds, `hi` to m where it does not. Returns the
/// final (lo, hi); the caller picks its answer from them (e.g. the midpoint).
pub fn bisect(
    lo: f64,
    hi: f64,
    rule: Bisection,
    mut toward_hi: impl FnMut(f64) -> bool,
) -> (f64, f64) {
    let r: Result<_, std::convert::Infallible> = try_bisect(lo, hi, rule, |m| Ok(toward_hi(m)));
    r.unwrap_or_else(|e| match e {})
}

/// [`bisect`] with a fallible predicate: its first error stops the search and is returned.
pub fn try_bisect<E>(
    mut lo: f64,
    mut hi: f64,
    rule: Bisection,
    mut toward_hi: impl FnMut(f64) -> Result<bool, E>,
) -> Result<(f64, f64), E> {
    let mut left = rule.halvings;
    while left > 0 && !rule.done(lo, hi) {
        let mid = 0.5 * (lo + hi);
        if toward_hi(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
        left -= 1;
    }
    Ok((lo, hi))
}

/// One evaluation of [`safeguarded_newton`], as its stopping rule sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iterate<S> {
    /// The point evaluated.
    pub at: f64,
    /// The residual there (increasing in x).
    pub residual: f64,
    /// The slope the caller gave there.
    pub slope: f64,
    /// What else the caller's evaluation returned.
    pub extra: S,
    /// The bracket after this evaluation.
    pub lo: f64,
    /// The bracket after this evaluation.
    pub hi: f64,
    /// The next point: Newton's step from `at` if it falls strictly inside the bracket, else
    /// the bracket's midpoint; `at` itself when the residual is exactly 0.
    pub next: f64,
    /// Whether `next` is Newton's step.
    pub newton: bool,
}

/// How [`safeguarded_newton`] ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonEnd<S> {
    /// The last evaluation (None if `max_iter` is 0).
    pub last: Option<Iterate<S>>,
    /// Whether the stopping rule fired (false: zero residual or out of iterations).
    pub stopped: bool,
    /// The next iterate after the last evaluation (`start` if there was none): the answer of a
    /// loop that steps before it tests.
    pub x: f64,
}

/// Newton's method on a residual r(x) increasing across the bracket [`lo`, `hi`], from
/// `start`, safeguarded by bisection: each evaluation `eval(x)` = (r, slope, extra) narrows the
/// bracket (r > 0: hi = x, else lo = x), takes Newton's step x − r/slope if it is finite and
/// strictly inside the bracket, else the midpoint, and stops when r = 0 exactly, when
/// `done(&iterate)` holds (after the step is computed), or after `max_iter` evaluations.
/// A slope that should refuse Newton's step may be given as NaN.
pub fn safeguarded_newton<S: Copy>(
    mut lo: f64,
    mut hi: f64,
    start: f64,
    max_iter: usize,
    mut eval: impl FnMut(f64) -> (f64, f64, S),
    done: impl Fn(&Iterate<S>) -> bool,
) -> NewtonEnd<S> {
    let mut x = start;
    let mut last = None;
    for _ in 0..max_iter {
        let (r, slope, extra) = eval(x);
        let mut it = Iterate {
            at: x,
            residual: r,
            slope,
            extra,
            lo,
            hi,
            next: x,
            newton: false,
        };
        if r == 0.0 {
            return NewtonEnd {
                last: Some(it),
                stopped: false,
                x,
            };
        }
        if r > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let step = x - r / slope;
        it.newton = step > lo && step < hi && step.is_finite();
        it.next = if it.newton { step } else { 0.5 * (lo + hi) };
        (it.lo, it.hi) = (lo, hi);
        let stop = done(&it);
        x = it.next;
        last = Some(it);
        if stop {
            return NewtonEnd {
                last,
                stopped: true,
                x,
            };
        }
    }
    NewtonEnd {
        last,
        stopped: false,
        x,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisection_of_the_square_root_of_two() {
        let (lo, hi) = bisect(0.0, 2.0, Bisection::until(Stop::Adjacent, 200), |x| {
            x * x < 2.0
        });
        assert!(lo < hi && lo * lo < 2.0 && hi * hi >= 2.0);
        assert!((0.5 * (lo + hi) - 2f64.sqrt()).abs() <= 2.0 * f64::EPSILON);
    }

    #[test]
    fn bisection_counts_its_halvings_and_stops_at_the_width() {
        let mut n = 0;
        let (lo, hi) = bisect(0.0, 1.0, Bisection::halvings(10), |x| {
            n += 1;
            x < 0.3
        });
        assert_eq!(n, 10);
        assert_eq!(hi - lo, 1.0 / 1024.0);
        assert!(lo < 0.3 && 0.3 <= hi);
        let mut n = 0;
        let (lo, hi) = bisect(0.0, 1.0, Bisection::until(Stop::Width(0.25), 100), |x| {
            n += 1;
            x < 0.3
        });
        assert_eq!((n, lo, hi), (2, 0.25, 0.5));
        // Already narrow enough: no halving at all.
        let (lo, hi) = bisect(
            0.0,
            0.1,
            Bisection::until(Stop::Width(0.25), 100),
            |_| panic!(),
        );
        assert_eq!((lo, hi), (0.0, 0.1));
        // A strict width: 0.25 is not below 0.25, so one more halving.
        let (lo, hi) = bisect(
            0.0,
            1.0,
            Bisection::until(Stop::WidthBelow(0.25), 100),
            |x| x < 0.3,
        );
        assert_eq!((lo, hi), (0.25, 0.375));
    }

    #[test]
    fn bisection_with_the_ends_reversed_and_an_error() {
        // The predicate holds at lo = 3 (above the root of x² = 4) and not at hi = 0.
        let (lo, hi) = bisect(3.0, 0.0, Bisection::until(Stop::Width(1e-12), 200), |x| {
            x * x > 4.0
        });
        assert!((0.5 * (lo + hi) - 2.0).abs() < 1e-12 && lo > hi);
        let r = try_bisect(0.0, 1.0, Bisection::halvings(50), |x| {
            if x < 0.2 {
                Err("too low")
            } else {
                Ok(false)
            }
        });
        assert_eq!(r, Err("too low"));
    }

    #[test]
    fn newton_converges_quadratically_and_bisects_where_newton_would_leave() {
        // r = x³ − 8 on [0, 10] from x = 10: Newton steps stay inside; 8 steps from 10 to 2.
        let end = safeguarded_newton(
            0.0,
            10.0,
            10.0,
            200,
            |x| (x * x * x - 8.0, 3.0 * x * x, ()),
            |it| (it.next - it.at).abs() <= 4.0 * f64::EPSILON * it.at,
        );
        assert!((end.x - 2.0).abs() <= 4.0 * f64::EPSILON, "{end:?}");
        // A slope of NaN refuses every Newton step: pure bisection, 1 halving per evaluation.
        let mut n = 0;
        let end = safeguarded_newton(
            0.0,
            1.0,
            0.5,
            200,
            |x| {
                n += 1;
                (x - 0.3, f64::NAN, ())
            },
            |it| it.hi - it.lo <= 1e-3,
        );
        let last = end.last.unwrap();
        assert!(
            !last.newton && end.stopped && last.hi - last.lo <= 1e-3,
            "{end:?}"
        );
        assert!(last.lo <= 0.3 && 0.3 <= last.hi && n == 10, "{n}");
    }

    #[test]
    fn newton_stops_at_an_exact_root_and_after_its_evaluations() {
        let end = safeguarded_newton(0.0, 4.0, 1.0, 200, |x| (x - 1.0, 1.0, 7), |_| false);
        assert_eq!((end.x, end.stopped), (1.0, false));
        assert_eq!(end.last.unwrap().extra, 7);
        let end = safeguarded_newton(
            0.0,
            4.0,
            3.0,
            2,
            |x| (x.exp() - 2.0, f64::NAN, ()),
            |_| false,
        );
        // Two bisections from 3: 3 → 1.5 → 0.75.
        assert_eq!((end.x, end.stopped), (0.75, false));
        assert!(
            safeguarded_newton(0.0, 1.0, 0.5, 0, |x| (x, 1.0, ()), |_| true)
                .last
                .is_none()
        );
    }
}
