//! The forward model of `settle invert` (`src/instruments/forward/`).
//!
//! Ideal Stokes: the unit fields summed with the weights are `instruments::ideal_field` of the
//! bins' cumulative curve (1e-9 kg/m³); every unit field starts uniform at c₀ (1 − ρ_f/ρ_p); a
//! bin's mass is conserved in a tall column while its grains are suspended (1e-6 relative).
//!
//! Hindered (Dallavalle + Di Felice, the scene's `physics = "full"` without contacts):
//! - as c₀ → 0 it is settling at the isolated Dallavalle speed (the analytic limiting diameter of
//!   each depth), which at small Re is 1/0.96 of Stokes' (0.5 % at 2 µm);
//! - mass is conserved exactly, bed included, and every bin's (tracers too) follows its
//!   sub-diameters' bulk speeds;
//! - one size: a single front at the Di Felice hindered terminal speed at the initial voidage
//!   (an independent bisection of the scene's drag law), the bulk at c₀ below it and the bed at
//!   b = c₀ v t/(P ρ_p − c₀);
//! - two sizes: the fine size above the coarse front is denser by the jump condition
//!   c⁺ (s − v⁺) = c⁻ (s − v⁻);
//! - against the simulation (`settle run`, contacts and lubrication off, samples 4 and 2): every
//!   reading of the hydrometer, the sphere and the pipette in `instruments.csv` is the same
//!   instrument on the forward field of the input curve within 3σ (the run's own 1σ) plus the
//!   model tolerance stated at [`MODEL_TOL_PERCENT`].

use crate::common::{read_csv_records, settle, tmp};
use settle::fluid::{DragLaw, SphereDrag};
use settle::instruments::forward::hindered::{Hindered, SUB_DIAMETER_STEP};
use settle::instruments::forward::speed::terminal_speed_m_s;
use settle::instruments::forward::{field_of, fields_for, unit_fields, Bins, Column, Settling};
use settle::instruments::{ideal_field, Analysis};
use std::f64::consts::PI;
use std::path::Path;

const H: f64 = 0.457;
const HINDERED: Settling = Settling::Hindered {
    voidage_cell_m: 0.002,
};

fn analysis(c0: f64) -> Analysis {
    Analysis {
        viscosity_pa_s: 1e-3,
        grain_density_kg_m3: 2500.0,
        fluid_density_kg_m3: 1000.0,
        gravity_m_s2: 9.81,
        c0_kg_m3: c0,
    }
}

fn column(height_m: f64, layers: usize, c0: f64) -> Column {
    Column {
        height_m,
        layers,
        analysis: analysis(c0),
    }
}

/// Sample 4 of data/sedimentation_samples.csv as bins: its curve is log-linear between points.
fn sample4() -> (Bins, Vec<f64>) {
    (
        Bins {
            edges_m: vec![2.5e-6, 25e-6, 35e-6, 70e-6],
        },
        vec![0.05, 0.92, 0.03],
    )
}

fn excess(an: &Analysis) -> f64 {
    an.c0_kg_m3 * (1.0 - an.fluid_density_kg_m3 / an.grain_density_kg_m3)
}

#[test]
fn ideal_unit_fields_sum_to_the_ideal_field() {
    let col = column(H, 4000, 41.5);
    let bins = Bins::log_spaced(1e-6, 1e-4, 40);
    // A curve with a gap and mass coarser than the last edge.
    let w: Vec<f64> = (0..40)
        .map(|j| {
            if (10..14).contains(&j) {
                0.0
            } else {
                0.9 / 36.0
            }
        })
        .collect();
    let times = [1e-3, 60.0, 600.0, 3600.0, 86400.0];
    let units = unit_fields(&col, Settling::IdealStokes, &bins, &w, &times);
    for (u, &t) in units.iter().zip(&times) {
        let got = field_of(&col, u, &w);
        let want = ideal_field(&col.analysis, H, 4000, t, |d| bins.cumulative(&w, d));
        let worst = got
            .density_kg_m3
            .iter()
            .zip(&want.density_kg_m3)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-9, "t = {t}: {worst}");
    }
}

#[test]
fn every_unit_field_starts_uniform() {
    let col = column(H, 500, 41.5);
    let (bins, w) = sample4();
    for settling in [Settling::IdealStokes, HINDERED] {
        let u = &unit_fields(&col, settling, &bins, &w, &[0.0])[0];
        for row in u {
            for x in row {
                assert!(
                    (x - excess(&col.analysis)).abs() < 1e-12,
                    "{settling:?}: {x}"
                );
            }
        }
    }
}

#[test]
fn ideal_mass_is_conserved_while_suspended() {
    // A bottomless column 100 m tall: in [0, H] each bin keeps excess × (H − ⟨v⟩ t), its grains
    // having crossed y = H at their mean Stokes speed ⟨v⟩ = (ρ_p − ρ_f) g ⟨d²⟩/(18 μ), with
    // ⟨d²⟩ = (b² − a²)/(2 ln(b/a)) for a log-uniform bin [a, b].
    let col = column(100.0, 20_000, 41.5);
    let (bins, w) = sample4();
    let t = 600.0;
    let u = &unit_fields(&col, Settling::IdealStokes, &bins, &w, &[t])[0];
    let h = 100.0 / 20_000.0;
    for (j, row) in u.iter().enumerate() {
        let (a, b) = (bins.edges_m[j], bins.edges_m[j + 1]);
        let d2 = (b * b - a * a) / (2.0 * (b / a).ln());
        let v = 1500.0 * 9.81 * d2 / 18e-3;
        let m: f64 = row.iter().sum::<f64>() * h;
        let want = excess(&col.analysis) * (100.0 - v * t);
        assert!((m / want - 1.0).abs() < 1e-6, "bin {j}: {m} vs {want}");
    }
}

/// The diameter whose isolated Dallavalle speed is `v`, m (bisection in ln d).
fn diameter_of_speed(an: &Analysis, v: f64) -> f64 {
    let (mut lo, mut hi) = (1e-8f64.ln(), 1e-2f64.ln());
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if terminal_speed_m_s(an, mid.exp(), 1.0) < v {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (0.5 * (lo + hi)).exp()
}

#[test]
fn hindered_tends_to_isolated_dallavalle_settling_as_c0_vanishes() {
    let col = column(H, 4000, 1e-9);
    let an = col.analysis;
    let (bins, w) = sample4();
    let times = [120.0, 900.0];
    let units = unit_fields(&col, HINDERED, &bins, &w, &times);
    let h = H / 4000.0;
    for (u, &t) in units.iter().zip(&times) {
        for (j, row) in u.iter().enumerate() {
            // Cumulative excess above each depth, against the analytic one (a bin present below
            // the depth where its coarsest grains have gone), in 1 cm windows: the sub-diameters
            // (1 % apart) make a staircase of the analytic ramp, whose window means agree to a
            // fraction of a step.
            let mut cum = 0.0;
            let mut exact = 0.0;
            for (k, x) in row.iter().enumerate() {
                cum += x * h;
                let y = (k as f64 + 0.5) * h;
                let d = diameter_of_speed(&an, y / t);
                exact += excess(&an) * bins.fraction_finer(j, d) * h;
                if (k + 1) % 87 == 0 {
                    let tol = 0.005 * 0.0087 * excess(&an) + 1e-3 * exact;
                    assert!(
                        (cum - exact).abs() <= tol * (k + 1) as f64 / 87.0,
                        "bin {j} t {t} y {y}: {cum} vs {exact}"
                    );
                }
            }
        }
    }
    // Dallavalle's 0.96: at small Re the isolated speed is Stokes' / 0.96, so a fine bin's field
    // at t is the ideal one at t / 0.96.
    let fine = Bins {
        edges_m: vec![1e-6, 2e-6, 3e-6],
    };
    let st = (2500.0 - 1000.0) * 9.81 * 4e-12 / 18e-3;
    assert!((terminal_speed_m_s(&an, 2e-6, 1.0) / st * 0.96 - 1.0).abs() < 5e-3);
    let t = 20_000.0;
    let hind = &unit_fields(&col, HINDERED, &fine, &[0.5, 0.5], &[t])[0];
    let ideal = &unit_fields(&col, Settling::IdealStokes, &fine, &[0.5, 0.5], &[t / 0.96])[0];
    for j in 0..2 {
        let (a, b): (f64, f64) = (hind[j].iter().sum(), ideal[j].iter().sum());
        assert!((a / b - 1.0).abs() < 2e-3, "bin {j}: {a} vs {b}");
    }
}
