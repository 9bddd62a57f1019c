//! Validation case (moved from `tests/validation/sphere_drag.rs`, which holds the C_d(Re) laws
//! against Roos & Willmarth's data): a terminal-velocity run with each Newtonian law against the
//! law's own force balance (scenario `scenarios/stokes_single.toml`, resized).

use super::{prepare, scene};
use crate::dynamics::Integrator;
use crate::fluid::newtonian::CdCorrelation;
use crate::scenes::free_settling::{run, RunOptions};
use std::f64::consts::PI;
use std::path::Path;

/// Terminal velocity where ½ C_d(Re) ρ_f (π d²/4) v² = (ρ_p − ρ_f)(π d³/6) g, by bisection on
/// the pure C_d function alone (independent of the crate's solver).
fn force_balance(cd: impl Fn(f64) -> f64, d: f64, rho_p: f64, rho_f: f64, mu: f64, g: f64) -> f64 {
    let w = (rho_p - rho_f) * PI * d.powi(3) / 6.0 * g;
    let drag = |v: f64| 0.5 * cd(rho_f * v * d / mu) * rho_f * PI * d * d / 4.0 * v * v;
    let (mut lo, mut hi) = (0.0, 10.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if drag(mid) < w {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The 2700 kg/m³ sphere of `stokes_single` enlarged to 0.8 mm (Re ≈ 100): with each law, the
/// simulated end velocity equals the law's own force balance within 1e-6, at dt = 1e-4 s and at
/// dt = 0.05 s (several response times per step: the exponential update linearises the law at
/// the backward-Euler end speed and stays stable), and the run reports Re ≈ 100.
#[test]
fn terminal_velocity_with_each_law_matches_its_force_balance() {
    for c in [
        CdCorrelation::SchillerNaumann,
        CdCorrelation::CliftGauvin,
        CdCorrelation::Morrison,
    ] {
        let (key, cd) = (c.key(), |re| c.cd(re));
        let v_ref = force_balance(cd, 8e-4, 2700.0, 1000.0, 1e-3, 9.81);
        for dt in [1e-4, 0.05] {
            let ov: Vec<String> = [
                format!("drag.law={key}"),
                "spheres[0].diameter_m=8e-4".into(),
                "time.end_s=1".into(),
            ]
            .into();
            let p = prepare(Path::new("scenarios/stokes_single.toml"), Some(dt), &ov)
                .expect("scenario loads");
            let opts = RunOptions {
                dt_s: dt,
                integrator: Integrator::Exponential,
                timeseries: false,
            };
            let r = run(scene(&p), &p.spheres, opts).expect("stable").remove(0);
            let v = r.v_simulated_m_s.abs();
            assert!(
                (v / v_ref - 1.0).abs() < 1e-6,
                "{key} dt {dt}: {v} vs {v_ref}"
            );
            assert!(
                (r.v_force_balance_m_s.abs() / v_ref - 1.0).abs() < 1e-9,
                "{key}"
            );
            let re = r.reynolds.expect("Newtonian law");
            assert!(re > 70.0 && re < 130.0, "{key}: Re {re}");
        }
    }
}
