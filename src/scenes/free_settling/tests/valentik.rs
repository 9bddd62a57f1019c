//! Validation case: Valentik & Whitmore (1965) spheres in six clay suspensions, as reproduced by
//! f-EDEM §4.1. Data: `data/valentik_whitmore_1965_*.csv` (f-EDEM Tables 2 and 3);
//! scenarios: `scenarios/valentik_susp1.toml` … `valentik_susp6.toml`.

use super::{prepare, scene};
use crate::fluid::bingham::{cd_from_terminal_velocity, reynolds_bingham};
use crate::scenario::RheologyModel;
use crate::scenes::free_settling::{run, RunOptions, SphereResult, StopReason};
use std::collections::HashMap;
use std::path::Path;

#[derive(serde::Deserialize)]
struct Suspension {
    suspension: u32,
    density_kg_m3: f64,
    plastic_viscosity_pa_s: f64,
    yield_stress_pa: f64,
}

#[derive(serde::Deserialize)]
struct Sphere {
    sphere_id: String,
    suspension: u32,
    diameter_m: f64,
    density_kg_m3: f64,
    v_terminal_measured_m_s: f64,
    re_bingham_tabulated: f64,
    cd_tabulated: Option<f64>,
}

fn suspensions() -> HashMap<u32, Suspension> {
    csv::Reader::from_path("data/valentik_whitmore_1965_suspensions.csv")
        .unwrap()
        .deserialize::<Suspension>()
        .map(|r| {
            let r = r.unwrap();
            (r.suspension, r)
        })
        .collect()
}

/// Half a unit of the last printed digit of a tabulated value (its rounding interval).
fn half_ulp_printed(x: f64, decimals: i32) -> f64 {
    let _ = x;
    0.5 * 10f64.powi(-decimals)
}

/// Every row of Table 3 reproduces its tabulated Re' (eq. 18) and C_d (eq. 17) from the Table 2
/// properties of its suspension, within the rounding of the printed velocity and the printed
/// value: Re' to ±(half a unit of its last digit + 1.2 % for the rounded velocity), C_d likewise.
#[test]
fn every_sphere_reproduces_its_tabulated_re_and_cd() {
    let susp = suspensions();
    let rows: Vec<Sphere> = csv::Reader::from_path("data/valentik_whitmore_1965_spheres.csv")
        .unwrap()
        .deserialize()
        .map(|r| r.unwrap())
        .collect();
    assert_eq!(rows.len(), 121);
    let mut counts = [0usize; 7];
    let mut worst: f64 = 0.0;
    for r in &rows {
        counts[r.suspension as usize] += 1;
        let s = &susp[&r.suspension];
        let re = reynolds_bingham(
            s.density_kg_m3,
            r.v_terminal_measured_m_s,
            r.diameter_m,
            s.yield_stress_pa,
            s.plastic_viscosity_pa_s,
        );
        let tol_re = half_ulp_printed(r.re_bingham_tabulated, 2) + 0.012 * r.re_bingham_tabulated;
        assert!(
            (re - r.re_bingham_tabulated).abs() <= tol_re,
            "{}: Re' {re} vs {}",
            r.sphere_id,
            r.re_bingham_tabulated
        );
        worst = worst.max((re / r.re_bingham_tabulated - 1.0).abs());
        if let Some(cd_tab) = r.cd_tabulated {
            let cd = cd_from_terminal_velocity(
                r.density_kg_m3,
                s.density_kg_m3,
                r.diameter_m,
                s.yield_stress_pa,
                r.v_terminal_measured_m_s,
                9.81,
            );
            let tol = half_ulp_printed(cd_tab, 2) + 0.005 * cd_tab;
            assert!(
                (cd - cd_tab).abs() <= tol,
                "{}: C_d {cd} vs {cd_tab}",
                r.sphere_id
            );
        }
    }
    assert_eq!(&counts[1..], &[27, 16, 18, 17, 19, 24]);
    assert!(worst < 0.01, "worst Re' deviation {worst}");
}

#[test]
fn scenario_fluids_match_table2() {
    let susp = suspensions();
    for n in 1..=6u32 {
        let path = format!("scenarios/valentik_susp{n}.toml");
        let p = prepare(Path::new(&path), None, &[]).unwrap();
        let s = &susp[&n];
        assert_eq!(
            p.rheology,
            RheologyModel::Bingham {
                plastic_viscosity_pa_s: s.plastic_viscosity_pa_s,
                yield_stress_pa: s.yield_stress_pa,
            },
            "{path}"
        );
        assert_eq!(p.common.fluid_density_kg_m3, s.density_kg_m3, "{path}");
        assert!(p.spheres.iter().all(|c| c.spec.suspension == Some(n)));
    }
}

fn run_all(dt: f64) -> Vec<SphereResult> {
    let mut out = Vec::new();
    for n in 1..=6 {
        let p = prepare(
            Path::new(&format!("scenarios/valentik_susp{n}.toml")),
            Some(dt),
            &[],
        )
        .unwrap();
        let opts = RunOptions {
            dt_s: dt,
            integrator: p.common.time.integrator,
            timeseries: true,
        };
        out.extend(run(scene(&p), &p.spheres, opts).unwrap());
    }
    out
}

/// Acceptance: each simulated terminal velocity agrees with its own force-balance solution
/// within 0.5 %, spheres held on a jump of eq. 19 included, and no time series chatters (the
/// velocity of a sphere released from rest never decreases).
#[test]
fn terminal_velocities_agree_with_the_force_balance_without_chatter() {
    let res = run_all(1e-3);
    assert_eq!(res.len(), 121);
    let mut jumps = 0;
    for r in &res {
        let fb = r.v_force_balance_m_s;
        let err = if fb == 0.0 {
            r.v_simulated_m_s
        } else {
            r.v_simulated_m_s / fb - 1.0
        };
        assert!(
            err.abs() < 0.005,
            "{}: {} vs balance {fb}",
            r.case.id,
            r.v_simulated_m_s
        );
        if r.force_balance_at_jump {
            jumps += 1;
            assert_eq!(r.regime.label(), "jump", "{}", r.case.id);
        }
        assert!(
            matches!(r.stop, StopReason::Steady | StopReason::Static),
            "{}: {:?}",
            r.case.id,
            r.stop
        );
        for w in r.samples.windows(2) {
            assert!(
                w[1].velocity_m_s >= w[0].velocity_m_s * (1.0 - 1e-12),
                "{}: velocity drops at t = {}",
                r.case.id,
                w[1].time_s
            );
        }
    }
    assert!(jumps > 0, "some spheres sit on a jump of eq. 19");
}

/// Regression against stored reference: the overall error figures quoted in `docs/validation/valentik.md`.
#[test]
fn overall_error_against_measurements_is_as_documented() {
    let res = run_all(1e-3);
    let stats = crate::scenes::free_settling::output::metrics(&res);
    let all = stats.last().unwrap();
    assert_eq!(all.group, "all");
    assert_eq!(all.n, 121);
    let reference: toml::Table = std::fs::read_to_string("data/valentik_reference_metrics.toml")
        .unwrap()
        .parse()
        .unwrap();
    let get = |k: &str| reference["all"][k].as_float().unwrap();
    assert!(
        (all.mean_abs - get("mean_abs_rel_error")).abs() < 1e-3,
        "mean {}",
        all.mean_abs
    );
    assert!(
        (all.median_abs - get("median_abs_rel_error")).abs() < 1e-3,
        "median {}",
        all.median_abs
    );
    assert!(
        (all.bias - get("bias_rel_error")).abs() < 1e-3,
        "bias {}",
        all.bias
    );
}
