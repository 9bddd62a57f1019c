//! The force hook on Rapier gives the free engine's answer: the f-EDEM Stokes sphere and the
//! Valentik–Whitmore spheres stepped through a Rapier world (`engine = "rapier"`) match the
//! analytic solution and the free integrator.

use super::{prepare, scene};
use crate::dynamics::Integrator;
use crate::scenes::free_settling::{run, run_rapier, RunOptions};
use std::path::Path;

fn opts(dt: f64) -> RunOptions {
    RunOptions {
        dt_s: dt,
        integrator: Integrator::Exponential,
        timeseries: false,
    }
}

#[test]
fn stokes_sphere_through_rapier_matches_the_analytic_solution_in_2d_and_3d() {
    for dim in ["2", "3"] {
        let p = prepare(
            Path::new("scenarios/stokes_single.toml"),
            None,
            &["engine=rapier".into(), format!("dimension={dim}")],
        )
        .unwrap();
        for dt in [1e-5, 1e-3, 1e-2] {
            let r = run_rapier(scene(&p), &p.spheres, opts(dt))
                .unwrap()
                .remove(0);
            let err = r.max_velocity_error_rel.unwrap();
            assert!(err < 1e-6, "{dim}D dt {dt}: max rel velocity error {err}");
            let vt = r.v_analytic_m_s.unwrap();
            assert!(
                (r.v_simulated_m_s / vt - 1.0).abs() < 1e-6,
                "{dim}D dt {dt}"
            );
        }
    }
}

#[test]
fn valentik_spheres_through_rapier_equal_the_free_engine() {
    let p = prepare(Path::new("scenarios/valentik_susp1.toml"), None, &[]).unwrap();
    let free = run(scene(&p), &p.spheres, opts(1e-3)).unwrap();
    let rapier = run_rapier(scene(&p), &p.spheres, opts(1e-3)).unwrap();
    for (a, b) in free.iter().zip(&rapier) {
        assert_eq!(a.case.id, b.case.id);
        let rel =
            (a.v_simulated_m_s - b.v_simulated_m_s).abs() / a.v_simulated_m_s.abs().max(1e-12);
        assert!(
            rel < 1e-9,
            "{}: free {} vs rapier {}",
            a.case.id,
            a.v_simulated_m_s,
            b.v_simulated_m_s
        );
        assert_eq!(a.regime, b.regime, "{}", a.case.id);
    }
}
