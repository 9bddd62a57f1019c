//! Seed 000 Fig. 4: the transient velocity of a grain released from rest in the clear fluid and
//! the time it takes to reach its terminal velocity, per diameter of the sample. Computed with the
//! run's own physics: the drag of the run (Stokes for `ideal-stokes`; Dallavalle at voidage 1,
//! an isolated grain, for full physics, [`crate::fluid::SphereDrag`]) advanced by the exponential
//! integrator of [`crate::dynamics::advance`] under gravity and buoyancy, as a grain of the
//! cylinder is. Files: `transient.csv`/`.svg` (v(t)/v_t of six diameters),
//! `terminal_time.csv`/`.svg` (t_95 and t_99, the times to reach 95 and 99 % of v_t, of every
//! diameter class; the chart also shows the seed's Table 1) and `terminal_time_table1.csv` (seed
//! 000 Table 1 recomputed, [`table1_rows`]).
//!
//! # Seed 000 Table 1 and its inconsistency
//!
//! The seed's Table 1 gives |u̇_tr| = (ρ_p − ρ_f) g φ²/(18 μ) and t_tr from eq. 13,
//! u(t) = (1 − e^(−t/τ)) u_tr with τ = ρ_p φ²/(18 μ) (ρ_p = 2500, ρ_f = 1000 kg/m³,
//! μ = 1e-3 Pa s). The text defines t_tr as the time to 0.99 u_tr, τ ln 100; only the 70 µm row
//! (313.4e-5 s = τ ln 100) follows it. The other five rows (104.0, 26.0, 4.16, 1.04, 0.26 e-5 s)
//! are τ ln 20, the time to 95 %: at 99 % they would read 160.0, 40.0, 6.40, 1.60 and 0.40e-5 s.

use crate::dynamics::{advance, Integrator};
use crate::fluid::newtonian::{reynolds, stokes_response_time_s};
use crate::fluid::{sphere_mass_kg, DragLaw, SphereDrag};
use crate::io::chart::{Chart, Curve, Scale, Series};
use crate::io::fmt::{num, sig_shortest};
use crate::io::{Outputs, Table};
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
    /// Time to reach 0.99 v_t from rest, s (Stokes: τ ln 100).
    pub t99_s: f64,
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
        let (mut t, mut v, mut t95, mut t99) = (0.0, 0.0, f64::NAN, f64::NAN);
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
                if t99.is_nan() && v1 >= 0.99 * vt {
                    t99 = t + dt * (0.99 * vt - v) / (v1 - v);
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
            t99_s: t99,
            curve,
        }
    }
}

/// Seed 000 Table 1 as printed: diameter φ (m), t_tr (s), |u̇_tr| (m/s), and the fraction of
/// u_tr its t_tr is the time to (0.99 for 70 µm as the text says, 0.95 for the other rows).
pub const SEED_TABLE1: [(f64, f64, f64, f64); 6] = [
    (70e-6, 313.4e-5, 400.5e-5, 0.99),
    (50e-6, 104.0e-5, 204.3e-5, 0.95),
    (25e-6, 26.0e-5, 51.09e-5, 0.95),
    (10e-6, 4.16e-5, 8.17e-5, 0.95),
    (5e-6, 1.04e-5, 2.04e-5, 0.95),
    (2.5e-6, 0.26e-5, 0.51e-5, 0.95),
];

/// One row of Table 1 recomputed from eq. 13 with the run's grains and fluid `k`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Table1Row {
    /// Diameter φ, m.
    pub diameter_m: f64,
    /// Eq. 13 (Stokes) terminal velocity (ρ_p − ρ_f) g φ²/(18 μ), m/s.
    pub terminal_m_s: f64,
    /// Eq. 13 time to 95 % of it, τ ln 20, s.
    pub t95_s: f64,
    /// Eq. 13 time to 99 % of it, τ ln 100 (the seed's stated definition of t_tr), s.
    pub t99_s: f64,
    /// The seed's printed t_tr, s.
    pub seed_t_tr_s: f64,
    /// The seed's printed |u̇_tr|, m/s.
    pub seed_terminal_m_s: f64,
    /// The level the seed's t_tr corresponds to: 0.99 or 0.95.
    pub seed_level: f64,
}

/// Seed 000 Table 1 recomputed with eq. 13 for the grains and fluid of `k` (the seed's: ρ_p =
/// 2500, ρ_f = 1000 kg/m³, μ = 1e-3 Pa s), beside the printed values.
pub fn table1_rows(k: &Grains) -> Vec<Table1Row> {
    SEED_TABLE1
        .iter()
        .map(|&(d, t_tr, u_tr, level)| {
            let tau = stokes_response_time_s(d, k.density_kg_m3, k.viscosity_pa_s);
            Table1Row {
                diameter_m: d,
                terminal_m_s: (k.density_kg_m3 - k.fluid_density_kg_m3) * k.gravity_m_s2 * d * d
                    / (18.0 * k.viscosity_pa_s),
                t95_s: tau * 20f64.ln(),
                t99_s: tau * 100f64.ln(),
                seed_t_tr_s: t_tr,
                seed_terminal_m_s: u_tr,
                seed_level: level,
            }
        })
        .collect()
}

/// `terminal_time_table1.csv`: [`table1_rows`] of `k` with the run's own drag law's t_95 and
/// t_99 at the same diameters.
fn table1(k: &Grains) -> Table {
    let rows: Vec<Vec<String>> = table1_rows(k)
        .iter()
        .map(|r| {
            let own = k.transient(r.diameter_m);
            vec![
                num(r.diameter_m),
                num(r.terminal_m_s),
                num(r.t95_s),
                num(r.t99_s),
                num(r.seed_terminal_m_s),
                num(r.seed_t_tr_s),
                num(r.seed_level * 100.0),
                num(own.terminal_m_s),
                num(own.t95_s),
                num(own.t99_s),
            ]
        })
        .collect();
    Table::with_rows(
        "terminal_time_table1.csv",
        [
            "diameter_m",
            "eq13_terminal_velocity_m_s",
            "eq13_t95_s",
            "eq13_t99_s",
            "seed_terminal_velocity_m_s",
            "seed_t_tr_s",
            "seed_t_tr_percent_of_terminal",
            "run_terminal_velocity_m_s",
            "run_t95_s",
            "run_t99_s",
        ],
        rows,
    )
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

/// Adds `transient.csv`/`.svg` (the curves of six of the `diameters_m`),
/// `terminal_time.csv`/`.svg` (t_95 of every diameter) and `terminal_time_table1.csv` to `out`;
/// `name` heads the titles.
pub fn write_all(out: &mut Outputs, name: &str, k: Grains, diameters_m: &[f64]) -> io::Result<()> {
    let mut ds = diameters_m.to_vec();
    ds.sort_by(f64::total_cmp);
    ds.dedup();
    let all: Vec<Transient> = ds.iter().map(|&d| k.transient(d)).collect();
    let shown: Vec<&Transient> = picked(&ds)
        .iter()
        .filter_map(|d| all.iter().find(|t| t.diameter_m == *d))
        .collect();
    write_transient(out, name, &shown)?;
    out.table(terminal_table(&k, &all));
    out.chart(
        "terminal_time.svg",
        &terminal_chart(name, &all, (ds[0], ds[ds.len() - 1])),
    )?;
    out.table(table1(&k));
    Ok(())
}

/// `transient.csv` and `transient.svg`: the velocity from rest of the diameters `shown`.
fn write_transient(out: &mut Outputs, name: &str, shown: &[&Transient]) -> io::Result<()> {
    let mut rows = Vec::new();
    for t in shown {
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
    out.table(Table::with_rows(
        "transient.csv",
        [
            "diameter_m",
            "time_s",
            "time_ms",
            "velocity_m_s",
            "velocity_fraction",
        ],
        rows,
    ));
    let series: Vec<Series> = shown
        .iter()
        .enumerate()
        .map(|(i, t)| Series {
            label: format!(
                "d = {} µm (v_t = {} mm/s)",
                sig_shortest(t.diameter_m * 1e6, 3),
                sig_shortest(t.terminal_m_s * 1e3, 3)
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
    let chart = Chart::new(format!(
        "{name}: velocity from rest in the clear fluid (seed 000 Fig. 4)"
    ))
    .x("time since release, log scale (ms)", Scale::Log)
    .y("velocity / terminal velocity v/v_t (-)", Scale::Linear)
    .all_series(series);
    out.chart("transient.svg", &chart)
}

/// `terminal_time.csv`: the terminal velocity, Reynolds number, response time and times to
/// 95 and 99 % of the terminal velocity of every diameter (`all`) of grains `k`.
fn terminal_table(k: &Grains, all: &[Transient]) -> Table {
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
                num(t.t99_s),
                num(t.response_time_s * 100f64.ln()),
            ]
        })
        .collect();
    Table::with_rows(
        "terminal_time.csv",
        [
            "diameter_m",
            "terminal_velocity_m_s",
            "reynolds",
            "response_time_s",
            "t95_s",
            "t95_stokes_s",
            "t99_s",
            "t99_stokes_s",
        ],
        rows,
    )
}

/// `terminal_time.svg`: the time to 95 % of the terminal velocity of the diameters `all` (about
/// 25 of them), the Stokes times to 95 and 99 %, and seed 000's Table 1 within `range_m` (the
/// smallest and largest diameter, m).
fn terminal_chart(name: &str, all: &[Transient], range_m: (f64, f64)) -> Chart {
    // About 25 of the classes on the chart, so the markers stay apart (all in the CSV).
    let step = (all.len() / 25).max(1);
    Chart::new(format!(
        "{name}: time to reach the terminal velocity (seed 000 Fig. 4)"
    ))
    .x("diameter, log scale (µm)", Scale::Log)
    .y(
        "time to 95 or 99 % of the terminal velocity, log scale (ms)",
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
    .curve(
        Curve::new(
            "Stokes: t_99 = τ ln 100 (seed 000's stated t_tr)",
            all.iter()
                .map(|t| (t.diameter_m * 1e6, t.response_time_s * 100f64.ln() * 1e3))
                .collect(),
        )
        .dashed(),
    )
    .series(Series {
        label: "seed 000 Table 1 t_tr (70 µm: 99 %; the others: 95 %)".into(),
        points: SEED_TABLE1
            .iter()
            .filter(|r| r.0 >= range_m.0 && r.0 <= range_m.1)
            .map(|r| (r.0 * 1e6, r.1 * 1e3))
            .collect(),
        colour: 1,
        filled: false,
        line: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Seed 000 Table 1 from eq. 13 with the seed's grains and water (g = 9.81 m/s²): every
    /// |u̇_tr| and every t_tr truncates to the printed value (within one unit of the last printed
    /// digit above it), t_tr at the level the
    /// row uses: 99 % for 70 µm, 95 % for the others, which at 99 % would be 54 % longer (ln 100 /
    /// ln 20 = 1.537): the seed's inconsistency.
    #[test]
    fn seed_table1_follows_eq13_at_99_percent_for_70_um_and_95_percent_for_the_rest() {
        let k = Grains {
            density_kg_m3: 2500.0,
            fluid_density_kg_m3: 1000.0,
            viscosity_pa_s: 1e-3,
            gravity_m_s2: 9.81,
            stokes: true,
        };
        // One unit of the last printed digit (the table's unit is 1e-5): |u̇_tr|, t_tr. The seed
        // truncates (400.575 is printed 400.5, 204.375 204.3), so the value lies within one
        // unit above the printed one.
        let unit = [
            (0.1, 0.1),
            (0.1, 0.1),
            (0.01, 0.1),
            (0.01, 0.01),
            (0.01, 0.01),
            (0.01, 0.01),
        ];
        let truncates_to = |x: f64, printed: f64, u: f64| {
            let d = x - printed;
            (-1e-12..u * 1e-5).contains(&d)
        };
        for (r, (uu, ut)) in table1_rows(&k).iter().zip(unit) {
            let t = if r.seed_level == 0.99 {
                r.t99_s
            } else {
                r.t95_s
            };
            assert!(
                truncates_to(r.terminal_m_s, r.seed_terminal_m_s, uu),
                "{r:?}"
            );
            assert!(truncates_to(t, r.seed_t_tr_s, ut), "{r:?}");
            // The other level misses the printed value.
            let other = if r.seed_level == 0.99 {
                r.t95_s
            } else {
                r.t99_s
            };
            assert!((other / r.seed_t_tr_s - 1.0).abs() > 0.3, "{r:?}");
        }
        // The run's own Stokes transient gives the same t_99 as eq. 13.
        let t = k.transient(70e-6);
        assert!((t.t99_s / (t.response_time_s * 100f64.ln()) - 1.0).abs() < 1e-3);
    }

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
