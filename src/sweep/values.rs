//! The values of `settle sweep`'s options, parsed: each parser refuses a bad value with what is
//! allowed ([`BadValue`], printed by clap after the option's name, exit 2).

use std::fmt;

/// A command-line value outside its allowed range; clap prints it after the option's name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BadValue {
    /// What is allowed, e.g. `0 < TOL ≤ 1`.
    pub allowed: &'static str,
}

impl fmt::Display for BadValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "allowed {}", self.allowed)
    }
}

impl std::error::Error for BadValue {}

/// The allowed values of `--dt`.
pub const DT_ALLOWED: &str = "a time step dt > 0 s (finite), e.g. 1e-3";
/// The allowed values of `--dt-range`.
pub const RANGE_ALLOWED: &str = "LO:HI with 0 < LO < HI (s, finite), e.g. 1e-8:1e-1";
const SHARD_ALLOWED: &str = "I/N with 1 ≤ I ≤ N, e.g. 2/8";
/// The allowed range of `--tol`: a relative error, above 0 (0 would admit no step) and at most
/// 1 (100 %, beyond which the comparison means nothing); as `[sweep] tol` in a scenario.
pub const TOL_ALLOWED: &str = "0 < TOL ≤ 1 (a relative error against the finest stable dt)";

fn positive_s(s: &str) -> Option<f64> {
    s.trim().parse::<f64>().ok().filter(|x| is_dt(*x))
}

/// Whether `x` is a time step `--dt` accepts: finite and > 0, s.
pub fn is_dt(x: f64) -> bool {
    x > 0.0 && x.is_finite()
}

/// Whether `x` is a tolerance `--tol` accepts ([`TOL_ALLOWED`]).
pub fn is_tol(x: f64) -> bool {
    x > 0.0 && x <= 1.0
}

/// Parses one `--dt` value: a finite time step > 0, s.
pub fn parse_dt(s: &str) -> Result<f64, BadValue> {
    positive_s(s).ok_or(BadValue {
        allowed: DT_ALLOWED,
    })
}

/// Parses `--dt-range LO:HI`.
pub fn parse_dt_range(s: &str) -> Result<DtRange, BadValue> {
    let bad = BadValue {
        allowed: RANGE_ALLOWED,
    };
    let (lo, hi) = s.split_once(':').ok_or(bad)?;
    match (positive_s(lo), positive_s(hi)) {
        (Some(lo_s), Some(hi_s)) if lo_s < hi_s => Ok(DtRange { lo_s, hi_s }),
        _ => Err(bad),
    }
}

/// Parses `--shard I/N`.
pub fn parse_shard(s: &str) -> Result<Shard, BadValue> {
    let bad = BadValue {
        allowed: SHARD_ALLOWED,
    };
    let (i, n) = s.split_once('/').ok_or(bad)?;
    let (index, count): (usize, usize) = (
        i.trim().parse().map_err(|_| bad)?,
        n.trim().parse().map_err(|_| bad)?,
    );
    if index == 0 || index > count {
        return Err(bad);
    }
    Ok(Shard { index, count })
}

/// Parses `--tol`: a relative error in (0, 1], see [`TOL_ALLOWED`].
pub fn parse_tol(s: &str) -> Result<f64, BadValue> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|t| is_tol(*t))
        .ok_or(BadValue {
            allowed: TOL_ALLOWED,
        })
}

/// `--shard I/N`: slice `index` (1-based) of `count`, 1 ≤ index ≤ count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which slice, 1-based.
    pub index: usize,
    /// How many slices.
    pub count: usize,
}

/// `--dt-range LO:HI`: the smallest and largest time step, 0 < lo_s < hi_s < ∞, s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DtRange {
    /// Smallest time step, s.
    pub lo_s: f64,
    /// Largest time step, s.
    pub hi_s: f64,
}
