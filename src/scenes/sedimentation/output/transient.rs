//! Seed 000 Fig. 4: the transient velocity of a grain released from rest in the clear fluid and
//! the time it takes to reach its terminal velocity, per diameter of the sample. Computed with the
//! run's own physics: the drag of the run (Stokes for `ideal-stokes`; Dallavalle at voidage 1,
//! an isolated grain, for full physics, [`crate::fluid::SphereDrag`]) advanced by the exponential
//! integrator of [`crate::dynamics::advance`] under gravity and buoyancy, as a grain of the
//! cylinder is. Files: `transient.csv`/`.svg` (v(t)/v_t of six diameters) and
//! `terminal_time.csv`/`.svg` (t_95, the time to reach 95 % of v_t, of every diameter class).

use super::plot::sig;
use crate::dynamics::{advance, Integrator};
use crate::fluid::newtonian::{reynolds, stokes_response_time_s};
use crate::fluid::{sphere_mass_kg, DragLaw, SphereDrag};
use crate::io::chart::{scatter_svg, Chart, Curve, Scale, Series};
use crate::io::{num, StagedDir};
use nalgebra::SVector;
use std::io;

/// The fluid and grains of the transient.
#[derive(Clone, Copy, Debug)]
pub struct Grains {
    /// Grain density ρ_p, kg/m³.
    pub density_kg_m3: f64,
    /// Fluid density ρ_f, kg/m³.
    pub fluid_density_kg_m3: f64,
    /// Viscosity μ, Pa s.
    pub viscosity_pa_s: f64,
    /// Gravity g, m/s².
    pub gravity_m_s2: f64,
    /// Stokes drag only (`ideal-stokes`) instead of Dallavalle at voidage 1.
    pub stokes: bool,
}

/// The transient of one diameter.
#[derive(Clone, Debug, PartialEq)]
pub struct Transient {
    /// Diameter d, m.
    pub diameter_m: f64,
    /// Terminal velocity v_t of the drag law's force balance, m/s.
    pub terminal_m_s: f64,
    /// Stokes response time τ = ρ_p d² / (18 μ), s.
    pub response_time_s: f64,
    /// Time to reach 0.95 v_t from rest, s (Stokes: τ ln 20).
    pub t95_s: f64,
    /// (time, velocity) from rest, s and m/s, at 41 log-spaced times from 0.01 τ to 10 τ.
    pub curve: Vec<(f64, f64)>,
}

impl Grains {
    /// The drag of a grain of diameter `d_m`.
    fn drag(&self, d_m: f64) -> SphereDrag {
        let law = if self.stokes {
            DragLaw::Stokes {
                viscosity_pa_s: self.viscosity_pa_s,
            }
        } else {
            DragLaw::Dallavalle {
                viscosity_pa_s: self.viscosity_pa_s,
                voidage: 1.0,
            }
        };
        SphereDrag::new(law, d_m, self.fluid_density_kg_m3)
    }

    /// Releases a grain of diameter `d_m` from rest and follows it to 10 τ in steps of τ/200
    /// (landing on the curve's times).
    pub fn transient(&self, d_m: f64) -> Transient {
        let drag = self.drag(d_m);
        let m = sphere_mass_kg(d_m, self.density_kg_m3);
        let w = (m - sphere_mass_kg(d_m, self.fluid_density_kg_m3)) * self.gravity_m_s2;
        let vt = drag.balance_speed(w).speed_m_s;
        let tau = stokes_response_time_s(d_m, self.density_kg_m3, self.viscosity_pa_s);
        let times: Vec<f64> = (0..=40)
            .map(|j| tau * 10f64.powf(-2.0 + 3.0 * j as f64 / 40.0))
            .collect();
        let (mut t, mut v, mut t95) = (0.0, 0.0, f64::NAN);
        let mut curve = Vec::with_capacity(times.len());
        for &next in &times {
            while t < next {
                let dt = (tau / 200.0).min(next - t);
                let v1 = advance::<1>(
                    Integrator::Exponential,
                    &drag,
                    m,
                    &SVector::from([w]),
                    &SVector::from([v]),
                    dt,
                )
                .velocity_m_s[0];
                if t95.is_nan() && v1 >= 0.95 * vt {
                    t95 = t + dt * (0.95 * vt - v) / (v1 - v);
                }
                (t, v) = (t + dt, v1);
            }
            curve.push((t, v));
        }
        Transient {
            diameter_m: d_m,
            terminal_m_s: vt,
            response_time_s: tau,
            t95_s: t95,
            curve,
        }
    }
}

/// Six diameters of `diameters_m` (sorted ascending), log-evenly spread from the smallest to
/// the largest.
pub fn picked(diameters_m: &[f64]) -> Vec<f64> {
    let n = diameters_m.len();
    if n <= 6 {
        return diameters_m.to_vec();
    }
    let (d0, d1) = (diameters_m[0], diameters_m[n - 1]);
    let mut out: Vec<f64> = (0..6)
        .map(|i| {
            let target = d0 * (d1 / d0).powf(i as f64 / 5.0);
            *diameters_m
                .iter()
                .min_by(|a, b| {
                    (*a / target)
                        .ln()
                        .abs()
                        .total_cmp(&(*b / target).ln().abs())
                })
                .unwrap_or(&d0)
        })
        .collect();
    out.dedup();
    out
}

/// Writes `transient.csv`/`.svg` (the curves of six of the `diameters_m`) and
/// `terminal_time.csv`/`.svg` (t_95 of every diameter) into `stage`; `name` heads the titles.
pub fn write_all(stage: &StagedDir, name: &str, k: Grains, diameters_m: &[f64]) -> io::Result<()> {
    let dir = |f: &str| stage.path(f);
    let mut ds = diameters_m.to_vec();
    ds.sort_by(f64::total_cmp);
    ds.dedup();
    let all: Vec<Transient> = ds.iter().map(|&d| k.transient(d)).collect();
    let shown: Vec<&Transient> = picked(&ds)
        .iter()
        .filter_map(|d| all.iter().find(|t| t.diameter_m == *d))
        .collect();
    let mut rows = Vec::new();
    for t in &shown {
        for &(time, v) in &t.curve {
            rows.push(vec![
                num(t.diameter_m),
                num(time),
                num(time * 1e3),
                num(v),
                num(v / t.terminal_m_s),
            ]);
        }
    }
    crate::io::write_csv(
        &dir("transient.csv"),
        &[
            "diameter_m",
            "time_s",
            "time_ms",
            "velocity_m_s",
            "velocity_fraction",
        ],
        &rows,
    )?;
    let rows: Vec<Vec<String>> = all
        .iter()
        .map(|t| {
            vec![
                num(t.diameter_m),
                num(t.terminal_m_s),
                num(reynolds(
                    k.fluid_density_kg_m3,
                    t.terminal_m_s,
                    t.diameter_m,
                    k.viscosity_pa_s,
                )),
                num(t.response_time_s),
                num(t.t95_s),
                num(t.response_time_s * 20f64.ln()),
            ]
        })
        .collect();
    crate::io::write_csv(
        &dir("terminal_time.csv"),
        &[
            "diameter_m",
            "terminal_velocity_m_s",
            "reynolds",
            "response_time_s",
            "t95_s",
            "t95_stokes_s",
        ],
        &rows,
    )?;
    let series: Vec<Series> = shown
        .iter()
        .enumerate()
        .map(|(i, t)| Series {
            label: format!(
                "d = {} µm (v_t = {} mm/s)",
                sig(t.diameter_m * 1e6, 3),
                sig(t.terminal_m_s * 1e3, 3)
            ),
            points: t
                .curve
                .iter()
                .map(|&(time, v)| (time * 1e3, v / t.terminal_m_s))
                .collect(),
            colour: i,
            filled: true,
            line: true,
        })
        .collect();
    scatter_svg(
        &dir("transient.svg"),
        &format!("{name}: velocity from rest in the clear fluid (seed 000 Fig. 4)"),
        "time since release, log scale (ms)",
        "velocity / terminal velocity v/v_t (-)",
        Scale::Log,
        Scale::Linear,
        &series,
    )?;
    // About 25 of the classes on the chart, so the markers stay apart (all in the CSV).
    let step = (all.len() / 25).max(1);
    Chart::new(format!(
        "{name}: time to reach the terminal velocity (seed 000 Fig. 4)"
    ))
    .x("diameter, log scale (µm)", Scale::Log)
    .y(
        "time to 95 % of the terminal velocity, log scale (ms)",
        Scale::Log,
    )
    .series(Series {
        label: "time to 95 % of v_t (the run's drag and integrator)".into(),
        points: all
            .iter()
            .step_by(step)
            .map(|t| (t.diameter_m * 1e6, t.t95_s * 1e3))
            .collect(),
        colour: 0,
        filled: true,
        line: false,
    })
    .curve(Curve::new(
        "Stokes: t_95 = τ ln 20, τ = ρ_p d²/(18 μ)",
        all.iter()
            .map(|t| (t.diameter_m * 1e6, t.response_time_s * 20f64.ln() * 1e3))
            .collect(),
    ))
    .svg(&dir("terminal_time.svg"))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Under Stokes drag v(t) = v_t (1 − e^{−t/τ}): t_95 = τ ln 20 and v_t = d²(ρ_p − ρ_f)g/(18μ).
    #[test]
    fn a_stokes_grain_reaches_95_percent_at_tau_ln_20() {
        let k = Grains {
            density_kg_m3: 2500.0,
            fluid_density_kg_m3: 1000.0,
            viscosity_pa_s: 1e-3,
            gravity_m_s2: 9.81,
            stokes: true,
        };
        let t = k.transient(50e-6);
        let tau = 2500.0 * 50e-6 * 50e-6 / 18e-3;
        let vt = 50e-6 * 50e-6 * 1500.0 * 9.81 / 18e-3;
        assert!((t.terminal_m_s / vt - 1.0).abs() < 1e-9);
        assert!(
            (t.t95_s / (tau * 20f64.ln()) - 1.0).abs() < 1e-3,
            "{}",
            t.t95_s
        );
        let (t_end, v_end) = *t.curve.last().unwrap();
        assert!((t_end / (10.0 * tau) - 1.0).abs() < 1e-9);
        assert!((v_end / vt - (1.0 - (-10.0f64).exp())).abs() < 1e-6);
        assert_eq!(picked(&[1.0, 2.0, 3.0]), vec![1.0, 2.0, 3.0]);
        let ds: Vec<f64> = (0..100).map(|i| 1e-6 * 1.05f64.powi(i)).collect();
        let p = picked(&ds);
        assert_eq!((p.len(), p[0], p[5]), (6, ds[0], ds[99]));
    }
}
