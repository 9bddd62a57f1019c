//! The threshold search: the given angles, then bisection of the bracket they make.

use super::{simulate_tilt, TiltError, TiltOutcome, TiltSetup};
use crate::numerics::{try_bisect, Bisection, Stop};

/// The runs of a threshold search.
#[derive(Clone, Debug, PartialEq)]
pub struct TiltSearch {
    /// Every run, the given angles and the bisection's, sorted by angle.
    pub runs: Vec<TiltOutcome>,
    /// Final bracket (largest sticking angle, smallest sliding angle), degrees; `None` when the
    /// given angles do not contain a sticking angle below a sliding one.
    pub bracket: Option<(f64, f64)>,
}

impl TiltSearch {
    /// Threshold angle: the middle of the bracket, degrees.
    pub fn threshold_deg(&self) -> Option<f64> {
        self.bracket.map(|(lo, hi)| 0.5 * (lo + hi))
    }
}

/// The tilt runs at `angles_deg` and, when they bracket the threshold (a sticking angle below a
/// sliding one), its bisection until the bracket is at most `tolerance_deg` wide.
pub fn tilt_threshold(
    t: &TiltSetup,
    angles_deg: &[f64],
    tolerance_deg: f64,
) -> Result<TiltSearch, TiltError> {
    let mut runs = angles_deg
        .iter()
        .map(|&a| simulate_tilt(t, a))
        .collect::<Result<Vec<_>, _>>()?;
    let hi = runs
        .iter()
        .filter(|r| r.slides)
        .map(|r| r.angle_deg)
        .fold(f64::INFINITY, f64::min);
    let lo = runs
        .iter()
        .filter(|r| !r.slides && r.angle_deg < hi)
        .map(|r| r.angle_deg)
        .fold(f64::NEG_INFINITY, f64::max);
    let bracket = if lo.is_finite() && hi.is_finite() {
        let rule = Bisection::until(Stop::Width(tolerance_deg), usize::MAX);
        Some(try_bisect(lo, hi, rule, |mid| {
            let mut r = simulate_tilt(t, mid)?;
            r.bisection = true;
            let sticks = !r.slides;
            runs.push(r);
            Ok::<bool, TiltError>(sticks)
        })?)
    } else {
        None
    };
    runs.sort_by(|a, b| a.angle_deg.total_cmp(&b.angle_deg));
    Ok(TiltSearch { runs, bracket })
}
