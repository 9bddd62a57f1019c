//! Every number format of settle, in one place. Each rule is one function; where two outputs
//! print numbers differently, they call two functions here (no file defines its own).
//!
//! For a person (console tables, summary lines, warnings, charts, reports):
//! - [`sig`] / [`g`] / [`g_opt`]: `digits` significant digits, plain decimals in [1e-3, 1e6),
//!   `1.234e-5` outside (`0.1000`, `2.500e6`);
//! - [`sig_trim`] / [`short`]: [`sig`] without trailing zeros (`0.3`, `9.19e7`, `1e-4`);
//! - [`sig_plain`]: always plain decimals, as many as the magnitude asks (`-0.00000000000100`);
//! - [`sig_shortest`]: rounded to `digits`, then the shortest plain form (`0.3`, `1230`);
//! - [`g_whole`]: [`g`] of chart legends: whole numbers as integers (`4`, `1.235e5`);
//! - [`pct`]: a signed percentage (`+1.52%`).
//!
//! For a file (CSV, TOML):
//! - [`num`] / [`opt`]: shortest round-trip form; no digit is lost;
//! - [`clean`]: [`num`] of the value rounded to 12 significant digits (no float noise);
//! - [`clean_reading`]: [`num`] of the value rounded to 10 significant digits, 0 below 1e-9.
//!
//! All of them print zero (and −0) as `0`, never `-0`.

/// Significant digits of console tables and summary lines.
pub const DIGITS: usize = 4;

/// `x` with `digits` significant digits (at least 1): `0.1000`, `1.547`, `373.2`, `1.248e-5`,
/// `2.500e6`. Zero (also −0, and any value that rounds to zero) is `0`; NaN is `NaN`; ±∞ is
/// `inf`/`-inf`. Plain decimals when the rounded value lies in [1e-3, 1e6), else exponent form.
pub fn sig(x: f64, digits: usize) -> String {
    if x.is_nan() {
        return "NaN".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf" } else { "-inf" }.into();
    }
    if x == 0.0 {
        return "0".into();
    }
    let digits = digits.max(1);
    // The exponent of the value once rounded to `digits` (9.9996 → 1.000e1).
    let sci = format!("{:.*e}", digits - 1, x);
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    if (-3..6).contains(&exp) {
        let decimals = (digits as i32 - 1 - exp).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{mantissa}e{exp}")
    }
}

/// [`sig`] with [`DIGITS`] significant digits.
pub fn g(x: f64) -> String {
    sig(x, DIGITS)
}

/// [`g`] of an optional value; `-` when absent.
pub fn g_opt(x: Option<f64>) -> String {
    x.map(g).unwrap_or_else(|| "-".into())
}

/// An input or a constant as it was written: up to 6 significant digits, trailing zeros
/// dropped (`1e-5`, `105`, `57.1`, `0.5`); for a scenario's own figures in titles and warnings.
pub fn short(x: f64) -> String {
    sig_trim(x, 6)
}

/// [`sig`] with the trailing zeros of the fraction dropped: `0.1547`, `9.19e7`, `0.3`, `1e-4`;
/// for report tables and titles, where a trailing zero says nothing.
pub fn sig_trim(x: f64, digits: usize) -> String {
    let s = sig(x, digits);
    let (body, exp) = match s.split_once('e') {
        Some((b, e)) => (b.to_string(), format!("e{e}")),
        None => (s.clone(), String::new()),
    };
    let body = if body.contains('.') {
        body.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        body
    };
    format!("{body}{exp}")
}

/// A signed relative difference as a percentage with `digits` significant digits: `+1.523%`,
/// `-0.04100%`, `0%` (no sign for zero).
pub fn pct(fraction: f64, digits: usize) -> String {
    let s = sig(100.0 * fraction, digits);
    if fraction > 0.0 && fraction.is_finite() && s != "0" {
        format!("+{s}%")
    } else {
        format!("{s}%")
    }
}

/// `x` with `n` significant digits in plain decimals, never an exponent: the number of
/// decimals is `n − 1 − ⌊log10 |x|⌋` of the unrounded value (at least 0), so `0.66` (4) →
/// `0.6600`, `1252` (4) → `1252`, `-1e-12` (3) → `-0.00000000000100`, `9.9996` (4) → `10.000`.
/// Zero, and any value that prints as zero, is `0`; ±∞ and NaN print as `inf`, `-inf`, `NaN`.
/// For the console and chart texts of `settle reduce`.
pub fn sig_plain(x: f64, n: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x.is_finite() {
            "0".into()
        } else {
            format!("{x}")
        };
    }
    let mag = x.abs().log10().floor() as i32;
    let decimals = (n as i32 - 1 - mag).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        "0".into()
    } else {
        s
    }
}

/// `v` rounded to `digits` significant digits (at least 1), then printed in Rust's shortest
/// plain form: no trailing zeros and never an exponent: `0.30000000000000004` (4) → `0.3`,
/// `1234.5` (3) → `1230`, `-0.0` → `0`, `-9.99999999e-6` (3) → `-0.00001`. ±∞ and NaN print as
/// `inf`, `-inf`, `NaN`. For the ticks and time texts of the sedimentation charts.
pub fn sig_shortest(v: f64, digits: usize) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == 0.0 {
        return "0".into();
    }
    format!("{}", rounded(v, digits))
}

/// A number of a chart legend with 4 significant digits: like [`g`], but a whole number below
/// 1e5 prints as an integer, and the exponent form starts at 1e5: `0.004630`, `12.50`, `4`,
/// `1.250e-6`, `1.235e5`; zero (also −0) is `0`, NaN is `NaN`.
pub fn g_whole(x: f64) -> String {
    if x.is_nan() {
        return "NaN".into();
    }
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    if x.fract() == 0.0 && a < 1e5 {
        return format!("{}", x as i64);
    }
    if (1e-3..1e5).contains(&a) {
        let d = (3 - a.log10().floor() as i32).max(0) as usize;
        format!("{x:.d$}")
    } else {
        format!("{x:.3e}")
    }
}

/// A number for a CSV file: the shortest form that reads back to the same `f64` (no digit is
/// lost), in exponent form outside [1e-4, 1e7): `0.5`, `1.25e-7`, `3e9`; −0 is `0` (the velocity
/// of a sphere at rest, −0·v, reads as a sign a person looks for meaning in).
pub fn num(x: f64) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    let a = x.abs();
    if a != 0.0 && a.is_finite() && !(1e-4..1e7).contains(&a) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// [`num`] of an optional number; empty when absent.
pub fn opt(x: Option<f64>) -> String {
    x.map(num).unwrap_or_default()
}

/// A computed number for a CSV or TOML file: [`num`] of `x` rounded to 12 significant digits,
/// so that float noise of the arithmetic does not show (`0.1629 − 0.00164 × 39` → `0.09894`,
/// not `0.09893999999999999`; `55e-6 × 1e6` → `55`). For the files of `reduce` and `invert`.
pub fn clean(x: f64) -> String {
    if !x.is_finite() {
        return num(x);
    }
    num(rounded(x, 12))
}

/// A simulated instrument reading or figure for `readings.csv`: [`num`] of `x` rounded to 10
/// significant digits, and `0` below 1e-9 in magnitude (the bisection's noise of a reading of
/// clear fluid): `1e-10` → `0`, `1.00000000004` → `1`.
pub fn clean_reading(x: f64) -> String {
    if x.abs() < 1e-9 {
        return "0".into();
    }
    num(rounded(x, 10))
}

/// `x` rounded to `digits` significant digits (at least 1), through its decimal exponent form
/// (`{:.*e}`, then parsed back); `x` itself if that fails.
fn rounded(x: f64, digits: usize) -> f64 {
    format!("{:.*e}", digits.max(1) - 1, x).parse().unwrap_or(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn significant_digits_in_plain_and_exponent_form() {
        assert_eq!(sig(0.1, 4), "0.1000");
        assert_eq!(sig(0.154686, 4), "0.1547");
        assert_eq!(sig(1.24795, 4), "1.248");
        assert_eq!(sig(373.18, 4), "373.2");
        assert_eq!(sig(9.999999999999999e-5, 4), "1.000e-4");
        assert_eq!(sig(1.0000000000000002e-14, 3), "1.00e-14");
        assert_eq!(sig(2.5e6, 4), "2.500e6");
        assert_eq!(sig(123456.0, 4), "123456");
        assert_eq!(sig(9.9996, 4), "10.00");
        assert_eq!(sig(-0.0012345, 3), "-0.00123");
    }

    #[test]
    fn zero_has_no_sign_and_no_exponent() {
        for x in [0.0, -0.0] {
            assert_eq!(sig(x, 4), "0");
        }
        for x in [1.0, 1.5, 0.001, 999_999.0, -3.0] {
            let s = sig(x, 4);
            assert!(!s.contains("e0") && !s.starts_with("-0"), "{x} → {s}");
        }
        assert_eq!(pct(0.0, 3), "0%");
        assert_eq!(pct(-0.0, 3), "0%");
        assert_eq!(pct(0.01523, 3), "+1.52%");
        assert_eq!(pct(-0.5, 3), "-50.0%");
        assert_eq!(sig(f64::NAN, 4), "NaN");
        assert_eq!(short(1e-5), "1e-5");
        assert_eq!(short(100.0 * 0.016), "1.6");
        assert_eq!(short(0.105 * 1e3), "105");
        assert_eq!(short(-0.0), "0");
    }

    #[test]
    fn plain_shortest_and_legend_forms() {
        assert_eq!(sig_plain(0.66, 4), "0.6600");
        assert_eq!(sig_plain(1252.0, 4), "1252");
        assert_eq!(sig_plain(-1e-12, 3), "-0.00000000000100");
        assert_eq!(sig_plain(-0.0004, 1), "-0.0004");
        assert_eq!(sig_plain(-0.0, 3), "0");
        assert_eq!(sig_shortest(0.1 + 0.2, 4), "0.3");
        assert_eq!(sig_shortest(1234.5, 3), "1230");
        assert_eq!(sig_shortest(-0.0, 3), "0");
        assert_eq!(sig_shortest(-1e-5 * 0.999_999_999, 3), "-0.00001");
        assert_eq!(g_whole(0.00463), "0.004630");
        assert_eq!(g_whole(12.5), "12.50");
        assert_eq!(g_whole(4.0), "4");
        assert_eq!(g_whole(-0.0), "0");
        assert_eq!(g_whole(1.25e-6), "1.250e-6");
        assert_eq!(g_whole(123456.0), "1.235e5");
        assert_eq!(sig_trim(0.15468578413257608, 4), "0.1547");
        assert_eq!(sig_trim(9.999999999999999e-5, 4), "1e-4");
        assert_eq!(sig_trim(99999.96, 4), "100000");
    }

    /// Issue 13: CSVs carried `-0`. Every number still reads back to the same value.
    #[test]
    fn numbers_round_trip_and_zero_has_no_sign() {
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(0.0), "0");
        for x in [1.5, -2.25e-7, 3.0e9, 1e-4, 9_999_999.0, -0.1, f64::NAN] {
            let back: f64 = num(x).parse().unwrap();
            assert!(
                back == x || (x.is_nan() && back.is_nan()),
                "{x} → {}",
                num(x)
            );
        }
        assert_eq!(num(1.25e-7), "1.25e-7");
        assert_eq!(num(0.5), "0.5");
        assert_eq!(opt(None), "");
    }

    #[test]
    fn file_numbers_drop_float_noise() {
        assert_eq!(clean(0.1629 - 0.00164 * 39.0), "0.09894");
        assert_eq!(clean(55e-6 * 1e6), "55");
        assert_eq!(clean(-0.0), "0");
        assert_eq!(clean(f64::INFINITY), "inf");
        assert_eq!(clean_reading(1e-10), "0");
        assert_eq!(clean_reading(-5e-10), "0");
        assert_eq!(clean_reading(1.000_000_000_04), "1");
        assert_eq!(clean_reading(0.1 + 0.2), "0.3");
    }

    /// Human and file numbers: significant digits without `-0`, files without float noise.
    #[test]
    fn numbers_print_without_noise() {
        assert_eq!(sig_plain(0.66, 4), "0.6600");
        assert_eq!(sig_plain(1252.0, 4), "1252");
        assert_eq!(sig_plain(-1e-12, 3), "-0.00000000000100");
        assert_eq!(sig_plain(-0.0004, 1), "-0.0004");
        assert_eq!(sig_plain(-0.0, 3), "0");
        assert_eq!(clean(0.1629 - 0.00164 * 39.0), "0.09894");
        assert_eq!(clean(55e-6 * 1e6), "55");
        assert_eq!(clean(-0.0), "0");
    }
}
