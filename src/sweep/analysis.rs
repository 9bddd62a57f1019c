//! What a sweep table says: per-case summaries, the recommended dt of each integrator, and the
//! Rayleigh-time rule of thumb it is printed beside.

use super::table::{integrator_rank, Row, Status};
use crate::contact::rayleigh_time_s;
use crate::dynamics::Integrator;
use crate::scenes::Prepared;
use std::collections::BTreeMap;

/// Per (integrator, dt): status, wall time, and the largest |error| over bodies for each quantity.
#[derive(Clone, Debug)]
pub struct CaseSummary {
    /// Integrator.
    pub integrator: Integrator,
    /// Time step, s.
    pub dt_s: f64,
    /// Stable?
    pub stable: bool,
    /// Wall time, s.
    pub wall_time_s: f64,
    /// Total steps over bodies.
    pub steps: u64,
    /// quantity → (max |error vs finest|, max |error vs reference|), relative.
    pub errors: BTreeMap<String, (f64, f64)>,
    /// Why the case is unstable (the first body's report); empty for a stable case.
    pub reason: String,
}

/// Summarises rows per case, in row order (integrator order, dt descending).
pub fn summarise(rows: &[Row]) -> Vec<CaseSummary> {
    let mut map: BTreeMap<(usize, u64), CaseSummary> = BTreeMap::new();
    for r in rows {
        let key = (integrator_rank(r.integrator), r.dt_s.to_bits());
        let e = map.entry(key).or_insert_with(|| CaseSummary {
            integrator: r.integrator,
            dt_s: r.dt_s,
            stable: r.status == Status::Stable,
            wall_time_s: r.wall_time_s,
            steps: 0,
            errors: BTreeMap::new(),
            reason: String::new(),
        });
        if e.reason.is_empty() && r.status != Status::Stable {
            e.reason = r.reason.clone();
        }
        e.steps += r.steps;
        let q = e
            .errors
            .entry(r.quantity.clone())
            .or_insert((0.0, f64::NAN));
        let fin = r.error_vs_finest.abs();
        if fin.is_finite() {
            q.0 = q.0.max(fin);
        }
        let re = r.error_vs_reference.abs();
        if re.is_finite() {
            q.1 = if q.1.is_nan() { re } else { q.1.max(re) };
        }
    }
    let mut v: Vec<CaseSummary> = map.into_values().collect();
    v.sort_by(|a, b| {
        integrator_rank(a.integrator)
            .cmp(&integrator_rank(b.integrator))
            .then(b.dt_s.total_cmp(&a.dt_s))
    });
    v
}

/// Largest stable dt of `integrator` whose error against the finest is under `tol` for every
/// quantity (and every smaller dt too, so the answer is not a lucky cancellation), s.
pub fn recommended_dt(summaries: &[CaseSummary], integrator: Integrator, tol: f64) -> Option<f64> {
    let mut cases: Vec<&CaseSummary> = summaries
        .iter()
        .filter(|s| s.integrator == integrator)
        .collect();
    cases.sort_by(|a, b| a.dt_s.total_cmp(&b.dt_s));
    let mut best = None;
    for c in cases {
        let ok = c.stable && c.errors.values().all(|(f, _)| *f <= tol);
        if !ok {
            break;
        }
        best = Some(c.dt_s);
    }
    best
}

/// Whether a recommended `dt_s` of `integrator` is verified: a finer stable dt of the grid
/// confirms it. The finest stable dt is the reference of every error, so its own error is 0 by
/// construction and says nothing about it.
pub fn verified(summaries: &[CaseSummary], integrator: Integrator, dt_s: f64) -> bool {
    summaries
        .iter()
        .any(|s| s.integrator == integrator && s.stable && s.dt_s < dt_s)
}

/// Rayleigh time of the first sphere with elastic properties (f-EDEM eq. 22, see
/// [`rayleigh_time_s`]), s; `None` without one.
pub fn rayleigh_time_of(p: &Prepared) -> Option<f64> {
    p.spheres.iter().find_map(|c| {
        Some(rayleigh_time_s(
            c.spec.diameter_m,
            c.spec.density_kg_m3,
            c.spec.youngs_modulus_pa?,
            c.spec.poisson_ratio?,
        ))
    })
}

/// The DEM rule printed beside the recommended dt: dt = 20 % of the Rayleigh time (the usual
/// rule takes 10–20 %, see [`rayleigh_time_s`]).
pub const RAYLEIGH_FRACTION: f64 = 0.2;
