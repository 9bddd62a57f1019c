//! The one number format of human output (console tables, summary lines, warnings): a fixed
//! number of significant digits, plain decimals between 1e-3 and 1e6 and `1.234e-5` outside,
//! never `-0`, never an exponent `e0`, never float noise such as `9.999999999999999e-5`.
//!
//! CSV files keep [`crate::io::num`] (shortest round-trip form: no digit is lost); this module is
//! for what a person reads.

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
}
