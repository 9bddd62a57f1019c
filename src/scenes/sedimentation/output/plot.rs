//! Small helpers of the sedimentation charts drawn directly with plotters: tick and time texts
//! with a fixed number of significant digits (issue 13: no float noise, never `-0`).

/// `v` printed with at most `digits` significant digits and no trailing zeros: `0.30000000000000004`
/// → `0.3`, `1234.5` (3 digits) → `1230`, `-0.0` → `0`.
pub fn sig(v: f64, digits: usize) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == 0.0 {
        return "0".into();
    }
    let rounded: f64 = format!("{:.*e}", digits.max(1) - 1, v).parse().unwrap_or(v);
    format!("{rounded}")
}

/// A time as a lab reads it: `t = 60 s (1 min)`, `t = 90 s (1.5 min)`.
pub fn time_text(time_s: f64) -> String {
    format!("t = {} s ({} min)", sig(time_s, 6), sig(time_s / 60.0, 4))
}

/// A drawing failure as an I/O error of kind `Other` (the caller names the path).
pub fn err(e: impl std::fmt::Display) -> std::io::Error {
    std::io::Error::other(e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_and_times_print_as_a_person_writes_them() {
        assert_eq!(sig(0.1 + 0.2, 4), "0.3");
        assert_eq!(sig(1234.5, 3), "1230");
        assert_eq!(sig(-0.0, 3), "0");
        assert_eq!(sig(-1e-5 * 0.999_999_999, 3), "-0.00001");
        assert_eq!(time_text(60.0), "t = 60 s (1 min)");
        assert_eq!(time_text(90.0), "t = 90 s (1.5 min)");
        assert_eq!(time_text(900.0), "t = 900 s (15 min)");
    }
}
