//! `--fit KEY=LO:HI`: a key to fit and its bounds.

use crate::error::Error;
use std::path::Path;

/// One `--fit KEY=LO:HI`: a real-valued scenario key and its bounds.
#[derive(Clone, Debug, PartialEq)]
pub struct Bound {
    /// The key, as `--set` takes it.
    pub key: String,
    /// Lower bound, in the key's unit.
    pub lo: f64,
    /// Upper bound, in the key's unit (> lo).
    pub hi: f64,
}

/// What `--fit` allows, for its messages.
pub(crate) const ALLOWED: &str = "allowed KEY=LO:HI with numbers LO < HI, e.g. \
                       fluid.plastic_viscosity_pa_s=0.1:3";

/// Parses `KEY=LO:HI` (finite numbers, LO < HI); the message of `--fit`'s refusal.
pub(crate) fn bound_from(s: &str) -> Result<Bound, String> {
    let (key, range) = s
        .split_once('=')
        .ok_or_else(|| format!("`{s}`: {ALLOWED}"))?;
    let key = key.trim();
    if !crate::scenario::is_key_path(key) {
        return Err(format!("`{key}` is not a scenario key: {ALLOWED}"));
    }
    let num = |t: &str| t.trim().parse::<f64>().ok().filter(|x| x.is_finite());
    if let Some((a, b)) = range.split_once(':') {
        if let Some(p) = [a, b]
            .iter()
            .find_map(|t| crate::io::arg::number_problem(t, "the key's unit"))
        {
            return Err(format!("{p}: {ALLOWED}"));
        }
    }
    let (lo, hi) = range
        .split_once(':')
        .and_then(|(a, b)| Some((num(a)?, num(b)?)))
        .ok_or_else(|| format!("`{range}` is not LO:HI: {ALLOWED}"))?;
    checked(key, lo, hi)
}

/// A bound of `key` from `lo` to `hi`, or why not.
fn checked(key: &str, lo: f64, hi: f64) -> Result<Bound, String> {
    if !crate::scenario::is_key_path(key) {
        return Err(format!("`{key}` is not a scenario key: {ALLOWED}"));
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return Err(format!("`{lo}:{hi}` is not LO:HI: {ALLOWED}"));
    }
    if lo >= hi {
        return Err(format!("bounds {lo}:{hi} are reversed or empty: {ALLOWED}"));
    }
    Ok(Bound {
        key: key.to_string(),
        lo,
        hi,
    })
}

impl Bound {
    /// `--fit KEY=LO:HI`: a scenario key and finite bounds LO < HI. Whether the key exists, is
    /// a real number and allows both bounds is checked by [`super::fit()`] against its scenario. A
    /// malformed text is bad input naming `--fit` and the text, the command line's message.
    pub fn parse(s: &str) -> Result<Self, Error> {
        bound_from(s).map_err(|m| Error::bad_argument("--fit", Path::new(s), m))
    }

    /// The bound `key` from `lo` to `hi`, checked as [`Bound::parse`] checks it.
    pub fn new(key: &str, lo: f64, hi: f64) -> Result<Self, Error> {
        checked(key, lo, hi)
            .map_err(|m| Error::bad_argument("--fit", Path::new(&format!("{key}={lo}:{hi}")), m))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `--fit KEY=LO:HI`: a key path and finite bounds LO < HI; each refusal names `--fit`, the
    /// text and what is allowed.
    #[test]
    fn bounds_parse_and_refuse() {
        let b = Bound::parse(" fluid.yield_stress_pa = 10 : 40").unwrap();
        assert_eq!(
            (b.key.as_str(), b.lo, b.hi),
            ("fluid.yield_stress_pa", 10.0, 40.0)
        );
        assert_eq!(Bound::new("fluid.yield_stress_pa", 10.0, 40.0).unwrap(), b);
        for (text, says) in [
            ("fluid.yield_stress_pa", "allowed KEY=LO:HI"),
            ("fluid yield=1:2", "is not a scenario key"),
            ("fluid.yield_stress_pa=1", "is not LO:HI"),
            ("fluid.yield_stress_pa=1:inf", "is not a finite number"),
            ("fluid.yield_stress_pa=1:1e400", "out of range"),
            (
                "fluid.yield_stress_pa=3:0.1",
                "bounds 3:0.1 are reversed or empty",
            ),
        ] {
            let m = Bound::parse(text).unwrap_err().to_string();
            assert!(m.starts_with(&format!("{text}: key `--fit`: ")), "{m}");
            assert!(m.contains(says), "{text}: {m}");
        }
        let m = Bound::new("k", 2.0, 2.0).unwrap_err().to_string();
        assert!(
            m.starts_with("k=2:2: key `--fit`: bounds 2:2 are reversed"),
            "{m}"
        );
        assert!(Bound::new("k", f64::NAN, 2.0).is_err());
    }
}
