//! Axis ranges, tick positions and tick labels.
//!
//! Ticks are chosen here, not by plotters, so that every label is printed from a known step with
//! exactly the digits the step needs: a 1e-4 step prints `0.0001`, never `9.999999999999999e-5`;
//! a log axis is labelled at decades (`1e-5`, or `0.001` … `1000` when every decade is in that
//! span). A linear axis of positive data starts at zero when the smallest value is at most half
//! the largest; otherwise it spans at least ±10 % of its largest magnitude, so one sphere at
//! 0.0043 m/s never gets an axis from 0.0042 to 0.00432.

use super::Scale;

/// Largest number of significant digits a tick label prints.
pub const MAX_DIGITS: i32 = 6;

/// Smallest span of a linear axis, as a fraction of its largest magnitude (±10 %).
pub const MIN_RELATIVE_SPAN: f64 = 0.2;

/// Fraction of the data span added on each side of a linear axis.
const PAD: f64 = 0.04;

/// An axis as drawn: its range in drawing space (log₁₀ of the value on a log axis), the labelled
/// ticks with their labels, and the positions of the light grid lines between them.
#[derive(Clone, Debug, PartialEq)]
pub struct AxisLayout {
    /// Lower end, drawing space.
    pub lo: f64,
    /// Upper end, drawing space.
    pub hi: f64,
    /// Labelled ticks, drawing space.
    pub ticks: Vec<f64>,
    /// The label of each tick.
    pub labels: Vec<String>,
    /// Light grid lines, drawing space.
    pub minor: Vec<f64>,
    /// Log axis (drawing space is log₁₀ of the value).
    pub log: bool,
}

impl AxisLayout {
    /// The label of the tick at `v` (drawing space), empty if `v` is not a tick.
    pub fn label_at(&self, v: f64) -> String {
        let tol = 1e-9 * (self.hi - self.lo).abs().max(1e-300);
        self.ticks
            .iter()
            .position(|t| (t - v).abs() <= tol)
            .map(|i| self.labels[i].clone())
            .unwrap_or_default()
    }

    /// Maps a data value to drawing space (None: not drawable, e.g. ≤ 0 on a log axis).
    pub fn to_draw(&self, v: f64) -> Option<f64> {
        to_draw(v, self.log)
    }
}

/// A data value in drawing space: itself, or log₁₀ of it on a log axis (None if not finite or,
/// on a log axis, not positive).
pub fn to_draw(v: f64, log: bool) -> Option<f64> {
    if !v.is_finite() || (log && v <= 0.0) {
        return None;
    }
    Some(if log { v.log10() } else { v })
}

/// The layout of an axis holding `values` (data space; non-finite values, and values ≤ 0 on a
/// log axis, are ignored). `fixed` forces the data range; `from_zero` lets a positive linear
/// axis start at zero when its smallest value is at most half its largest, or when its span is
/// under ±10 % (one value, or nearly equal values). Otherwise a linear axis spans at least ±10 %
/// of its largest magnitude.
pub fn layout(
    values: impl Iterator<Item = f64>,
    scale: Scale,
    fixed: Option<(f64, f64)>,
    from_zero: bool,
) -> AxisLayout {
    let log = scale == Scale::Log;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter_map(|v| to_draw(v, log)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if let Some((a, b)) = fixed.and_then(|(a, b)| Some((to_draw(a, log)?, to_draw(b, log)?))) {
        let (lo, hi) = (a.min(b), a.max(b));
        if hi > lo {
            return if log {
                log_ticks(lo, hi)
            } else {
                linear_ticks(lo, hi)
            };
        }
    }
    if lo > hi {
        (lo, hi) = if log { (-1.0, 0.0) } else { (0.0, 1.0) };
    }
    if log {
        let (lo, hi) = widen(lo, hi, 1.0);
        let pad = PAD * (hi - lo);
        log_ticks(lo - pad, hi + pad)
    } else {
        let (lo, hi) = linear_range(lo, hi, from_zero);
        linear_ticks(lo, hi)
    }
}

/// The layout of a categorical axis: category i at i, labelled with its name, the range half a
/// position beyond the first and the last (one category: −0.5 … 0.5).
pub fn categorical(names: &[String]) -> AxisLayout {
    let n = names.len().max(1);
    AxisLayout {
        lo: -0.5,
        hi: n as f64 - 0.5,
        ticks: (0..names.len()).map(|i| i as f64).collect(),
        labels: names.to_vec(),
        minor: Vec::new(),
        log: false,
    }
}

/// `(lo, hi)` widened about its centre to at least `span`.
fn widen(lo: f64, hi: f64, span: f64) -> (f64, f64) {
    if hi - lo >= span {
        return (lo, hi);
    }
    let c = 0.5 * (lo + hi);
    (c - 0.5 * span, c + 0.5 * span)
}

/// A padded linear data range (its lower end at zero when `from_zero` and reasonable).
fn linear_range(lo: f64, hi: f64, from_zero: bool) -> (f64, f64) {
    let narrow = hi - lo < MIN_RELATIVE_SPAN * hi;
    if from_zero && lo >= 0.0 && hi > 0.0 && (lo <= 0.5 * hi || narrow) {
        return (0.0, hi + PAD * hi);
    }
    let mag = lo.abs().max(hi.abs());
    let min_span = if mag > 0.0 {
        MIN_RELATIVE_SPAN * mag
    } else {
        1.0
    };
    let (lo, hi) = widen(lo, hi, min_span);
    let pad = PAD * (hi - lo);
    (lo - pad, hi + pad)
}

/// A nice step for about `target` intervals over `span`: (mantissa 1, 2, 2.5 or 5; exponent).
pub fn nice_step(span: f64, target: f64) -> (f64, i32) {
    let raw = (span / target).max(f64::MIN_POSITIVE);
    let mut e = raw.log10().floor() as i32;
    let f = raw / 10f64.powi(e);
    let m = if f <= 1.0 {
        1.0
    } else if f <= 2.0 {
        2.0
    } else if f <= 2.5 {
        2.5
    } else if f <= 5.0 {
        5.0
    } else {
        e += 1;
        1.0
    };
    (m, e)
}

/// Ticks every nice step (about six intervals) inside `[lo, hi]`.
fn linear_ticks(lo: f64, hi: f64) -> AxisLayout {
    let (m, e) = nice_step(hi - lo, 6.0);
    let step = m * 10f64.powi(e);
    let eps = 1e-9;
    let (k0, k1) = ((lo / step - eps).ceil(), (hi / step + eps).floor());
    let values: Vec<f64> = (k0 as i64..=k1 as i64).map(|k| k as f64 * step).collect();
    // The exponent of the last digit a tick needs: 2.5 × 10^e needs one more.
    let last = if m == 2.5 { e - 1 } else { e };
    let max_abs = values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let sci = !(1e-3..1e6).contains(&max_abs);
    let labels = values.iter().map(|&v| label(v, last, sci)).collect();
    // Light lines: five (or four, for a 2 or 2.5 step) per interval.
    let parts = if m == 1.0 || m == 5.0 { 5.0 } else { 4.0 };
    let minor = (((k0 - 1.0) * parts) as i64..=((k1 + 1.0) * parts) as i64)
        .map(|j| j as f64 * step / parts)
        .filter(|v| *v >= lo && *v <= hi)
        .collect();
    AxisLayout {
        lo,
        hi,
        ticks: values,
        labels,
        minor,
        log: false,
    }
}

/// Ticks of a log axis over `[lo, hi]` (log₁₀ of the values): every decade (every n-th when
/// there are more than 8), and 2 and 5 times each decade when fewer than three decades show.
fn log_ticks(lo: f64, hi: f64) -> AxisLayout {
    let (d0, d1) = (lo.ceil() as i32, hi.floor() as i32);
    let decades = (d1 - d0).max(0);
    let every = (decades + 7) / 8;
    let every = every.max(1);
    let mut values: Vec<(f64, i32)> = Vec::new(); // (mantissa, exponent)
    let mut minor = Vec::new();
    for e in (lo.floor() as i32)..=(hi.ceil() as i32) {
        for m in 1..10 {
            let v = (m as f64).log10() + e as f64;
            if v < lo - 1e-12 || v > hi + 1e-12 {
                continue;
            }
            let labelled = if d1 - d0 < 2 {
                matches!(m, 1 | 2 | 5)
            } else {
                m == 1 && (e - d0) % every == 0
            };
            if labelled {
                values.push((m as f64, e));
            } else if m == 1 || decades <= 6 {
                minor.push(v);
            }
        }
    }
    let sci = values.iter().any(|&(_, e)| !(-3..=4).contains(&e));
    let labels = values
        .iter()
        .map(|&(m, e)| label(m * 10f64.powi(e), e, sci))
        .collect();
    AxisLayout {
        lo,
        hi,
        ticks: values.iter().map(|&(m, e)| m.log10() + e as f64).collect(),
        labels,
        minor,
        log: true,
    }
}

/// The label of tick value `v` whose last needed digit has exponent `last` (e.g. −4 for a 1e-4
/// step): fixed-point with exactly the decimals it needs, or with `sci` a mantissa with the
/// digits it needs and an exponent (`2.5e-5`); `0` for zero (never `-0`); at most
/// [`MAX_DIGITS`] significant digits.
pub fn label(v: f64, last: i32, sci: bool) -> String {
    if v.abs() < 0.5 * 10f64.powi(last) {
        return "0".to_string();
    }
    let lead = v.abs().log10().floor() as i32;
    // Rounding may carry into the next decade (9.99 → 10.0): take the exponent after rounding.
    let lead = if (v.abs() / 10f64.powi(lead) * 10f64.powi(lead - last)).round()
        >= 10f64.powi(lead - last + 1)
    {
        lead + 1
    } else {
        lead
    };
    let digits = (lead - last + 1).clamp(1, MAX_DIGITS);
    // More integer digits than MAX_DIGITS: round the rest away (123456789 → 123457000).
    let q = 10f64.powi(lead - digits + 1);
    let v = if q > 1.0 { (v / q).round() * q } else { v };
    if sci {
        format!("{:.*e}", (digits - 1) as usize, v)
    } else {
        let decimals = (digits - 1 - lead).max(0) as usize;
        format!("{v:.decimals$}")
    }
}

/// `v` printed with `digits` significant digits for a legend or a title (`0.00926`, `1.5e-8`,
/// `1230`), never float noise or `-0`.
pub fn significant(v: f64, digits: i32) -> String {
    if !v.is_finite() {
        return v.to_string();
    }
    if v == 0.0 {
        return "0".to_string();
    }
    let lead = v.abs().log10().floor() as i32;
    let sci = v.abs() < 1e-3 || v.abs() >= 1e6;
    let s = label(v, lead - digits.clamp(1, MAX_DIGITS) + 1, sci);
    // Trailing zeros of a fixed-point number say nothing in a legend: 1.500 → 1.5.
    if !sci && s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lin(lo: f64, hi: f64) -> AxisLayout {
        layout([lo, hi].into_iter(), Scale::Linear, None, false)
    }

    /// Issue 13: the sweep chart printed `9.999999999999999e-5` and `1.0000000000000002e-14`.
    #[test]
    fn a_small_step_prints_its_digits_not_float_noise() {
        assert_eq!(label(1e-4, -4, false), "0.0001");
        assert_eq!(label(0.1 + 0.2, -1, false), "0.3");
        assert_eq!(label(3.0 * 0.1, -1, false), "0.3");
        assert_eq!(label(-1e-17, -1, false), "0");
        assert_eq!(label(2.5e-5, -6, true), "2.5e-5");
        assert_eq!(label(1.0000000000000002e-14, -14, true), "1e-14");
        let a = lin(0.0, 0.0004);
        assert!(a.labels.contains(&"1e-4".to_string()), "{:?}", a.labels);
        let a = lin(0.0, 0.004);
        assert!(a.labels.contains(&"0.001".to_string()), "{:?}", a.labels);
        let a = lin(0.0006, 0.0011);
        assert!(a.labels.contains(&"0.0007".to_string()), "{:?}", a.labels);
        for a in [
            lin(0.0, 0.0006),
            lin(0.0, 0.006),
            lin(2700.0, 8200.0),
            lin(-3.2, 7.7),
        ] {
            for l in &a.labels {
                assert!(
                    l.len() <= 8 && !l.starts_with("-0"),
                    "{l} in {:?}",
                    a.labels
                );
            }
        }
    }

    #[test]
    fn a_log_axis_is_labelled_at_decades() {
        let a = layout([1e-16, 1e-1].into_iter(), Scale::Log, None, false);
        assert!(
            a.labels.iter().all(|l| l.starts_with("1e-")),
            "{:?}",
            a.labels
        );
        assert!(a.labels.len() <= 9, "{:?}", a.labels);
        let a = layout([1e-5, 1e-3].into_iter(), Scale::Log, None, false);
        assert_eq!(a.labels, ["1e-5", "1e-4", "1e-3"]);
        let a = layout([0.02, 3.0].into_iter(), Scale::Log, None, false);
        assert_eq!(a.labels, ["0.02", "0.05", "0.1", "0.2", "0.5", "1", "2"]);
    }

    /// Issue 13: one sphere at 0.0043 m/s got a y axis from 0.0042 to 0.00432.
    #[test]
    fn a_single_value_gets_an_axis_from_zero_or_ten_percent_around_it() {
        let a = layout([0.0043].into_iter(), Scale::Linear, None, true);
        assert_eq!(a.lo, 0.0);
        assert!(a.hi >= 0.0043 && a.hi < 0.006, "{a:?}");
        let a = layout([1000.0, 1001.0].into_iter(), Scale::Linear, None, false);
        assert!(a.lo <= 900.0 && a.hi >= 1100.0, "{a:?}");
        assert!(a.labels.iter().all(|l| l.len() <= 6), "{:?}", a.labels);
    }

    #[test]
    fn legend_numbers_print_significant_digits() {
        assert_eq!(significant(0.009265000000000002, 4), "0.009265");
        assert_eq!(significant(0.0015, 3), "0.0015");
        assert_eq!(significant(1.497872402354501e-15, 3), "1.50e-15");
        assert_eq!(significant(18.8312, 4), "18.83");
        assert_eq!(significant(-0.0, 3), "0");
    }

    #[test]
    fn rounding_up_a_decade_keeps_the_digit_count() {
        assert_eq!(label(9.9999999, -1, false), "10.0");
        assert_eq!(label(1234.5, -1, false), "1234.5");
        assert_eq!(label(1.0e6, 5, true), "1.0e6");
        assert_eq!(label(123456789.0, 0, false), "123457000");
    }
}
