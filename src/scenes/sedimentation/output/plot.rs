//! Small helpers of the sedimentation charts drawn directly with plotters: time texts with a
//! fixed number of significant digits (issue 13: no float noise, never `-0`; the number rule is
//! [`sig_shortest`]).

use crate::io::fmt::sig_shortest;

/// A time as a lab reads it: `t = 60 s (1 min)`, `t = 90 s (1.5 min)`.
pub fn time_text(time_s: f64) -> String {
    format!(
        "t = {} s ({} min)",
        sig_shortest(time_s, 6),
        sig_shortest(time_s / 60.0, 4)
    )
}

/// A drawing failure as an I/O error of kind `Other` (the caller names the path).
pub fn err(e: impl std::fmt::Display) -> std::io::Error {
    std::io::Error::other(e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_print_as_a_person_writes_them() {
        assert_eq!(time_text(60.0), "t = 60 s (1 min)");
        assert_eq!(time_text(90.0), "t = 90 s (1.5 min)");
        assert_eq!(time_text(900.0), "t = 900 s (15 min)");
    }
}
