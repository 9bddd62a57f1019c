//! The charts of free-settling and drop runs, and of several-file runs (`OUT/combined/`):
//!
//! - `velocity.svg`: v(t) of every sphere from the recorded time series, with the analytic
//!   Stokes curve v(t) = v_t + (v₀ − v_t) e^(−t/τ) where the law is Stokes (f-EDEM Figs. 5–6;
//!   the constants are the run's own: v_t from the force balance, τ = m/(3π μ d), no added mass),
//!   and the measured v(t) of `[reference]` as hollow markers;
//! - `gap.svg` (with `reference.gap_csv` and a container): the gap between each sphere's lowest
//!   point and the container bottom against time, with the measured gap (ten Cate et al. 2002,
//!   Fig. 5a);
//! - `cd_re.svg` and `cd_re.csv`: drag coefficient against the Bingham Reynolds number Re′, the
//!   points of the measured velocities (f-EDEM Table 3, by eqs. 17–18), the simulated ones and
//!   eq. 19 (f-EDEM Fig. 1);
//! - `parity.svg` (combined): simulated against measured terminal velocity of every sphere, with
//!   the parity line and ±10 % and ±25 % bands (f-EDEM Figs. 9–11 in one picture);
//! - `terminal_velocity.svg` (per run: [`terminal_velocity_chart`]; combined: one such panel per
//!   suspension, like f-EDEM Fig. 11 a–f): terminal velocity against sphere density, one colour
//!   and shape per diameter, measured hollow and simulated filled.

use super::SphereResult;
use crate::fluid::bingham::{cd_fedem, cd_from_terminal_velocity, reynolds_bingham};
use crate::io::chart::ticks::significant;
use crate::io::chart::{Band, Chart, Curve, Marker, Scale, Series};
use crate::io::fmt::opt;
use crate::io::Table;
use crate::scenario::inputs::MeasuredCurves;
use crate::scenario::{Common, RheologyModel};
use std::collections::BTreeMap;

/// Most points drawn per time-series line of `velocity.svg` (`timeseries.csv` keeps them all).
const LINE_POINTS: usize = 2000;

/// Markers shown on each time-series line of `velocity.svg` (the line goes through every sample).
const MARKERS_PER_LINE: usize = 12;

/// `velocity.svg`: velocity against time of every sphere with recorded samples, and the
/// analytic Stokes curve of each sphere that has one (released at `v0_m_s`). With transient forces
/// (`exact` = Some(name of the solution)), the analytic curve is the recorded exact column
/// (`velocity_analytic_m_s`: the Boussinesq–Basset closed form, or the exponential approach with
/// added mass) instead. The measured v(t) of `measured` (`[reference]`), if any, is drawn as
/// hollow markers named by its source. None when no sphere has samples.
pub fn velocity_chart(
    title: &str,
    results: &[SphereResult],
    v0_m_s: f64,
    exact: Option<&str>,
    measured: Option<&MeasuredCurves>,
) -> Option<Chart> {
    let mut chart = Chart::new(title)
        .x("time t (s)", Scale::Linear)
        .x_from_zero(true)
        .y("settling velocity v, downward (m/s)", Scale::Linear);
    let mut any = false;
    for (i, r) in results.iter().enumerate() {
        if r.samples.is_empty() {
            continue;
        }
        any = true;
        // At most ~LINE_POINTS points per line (the last kept): a picture, not the data.
        let every = r.samples.len().div_ceil(LINE_POINTS).max(1);
        let last = r.samples.len() - 1;
        let points: Vec<(f64, f64)> = r
            .samples
            .iter()
            .enumerate()
            .filter(|(k, _)| k % every == 0 || *k == last)
            .map(|(_, s)| (s.time_s, s.velocity_m_s))
            .collect();
        let t_end = points.last().map_or(0.0, |p| p.0);
        chart = chart.series_thinned(
            Series {
                label: format!("{}, simulated", r.case.id),
                points,
                colour: i,
                filled: true,
                line: true,
            },
            MARKERS_PER_LINE,
        );
        if let Some(name) = exact {
            let curve: Vec<(f64, f64)> = r
                .samples
                .iter()
                .filter_map(|s| Some((s.time_s, s.velocity_analytic_m_s?)))
                .collect();
            if !curve.is_empty() {
                let label = format!("{}, {name}", r.case.id);
                chart = chart.curve(Curve::new(label, curve).dashed());
            }
        } else if let Some(vt) = r.v_analytic_m_s {
            let tau = r.response_time_s;
            let curve = (0..=200)
                .map(|k| {
                    let t = t_end * k as f64 / 200.0;
                    (t, vt + (v0_m_s - vt) * (-t / tau).exp())
                })
                .collect();
            let law = if v0_m_s == 0.0 {
                "v_t (1 − e^(−t/τ))".to_string()
            } else {
                format!(
                    "v_t + (v₀ − v_t) e^(−t/τ), v₀ = {} m/s",
                    significant(v0_m_s, 4)
                )
            };
            chart = chart.curve(
                Curve::new(
                    format!(
                        "{}, analytic Stokes {law}: v_t = {} m/s, τ = {} s",
                        r.case.id,
                        significant(vt, 4),
                        significant(tau, 4)
                    ),
                    curve,
                )
                .dashed(),
            );
        }
    }
    if let Some(m) = measured.filter(|m| !m.velocity.is_empty()) {
        chart = chart.series(measured_series(&m.source, &m.velocity, results.len()));
    }
    any.then_some(chart)
}

/// The measured points of a `[reference]` curve: hollow markers without a line, labelled with
/// the source and the number of points.
fn measured_series(source: &str, points: &[(f64, f64)], colour: usize) -> Series {
    Series {
        label: format!("measured ({} points): {source}", points.len()),
        points: points.to_vec(),
        colour,
        filled: false,
        line: false,
    }
}

/// `gap.svg`: the gap between each sphere's lowest point and the bottom of a container of
/// fluid height `height_m` (h − depth − d/2, as `gap_to_bottom_m` of `timeseries.csv`) against
/// time, with the measured gap of `measured` as hollow markers (like ten Cate et al. 2002,
/// Fig. 5a). None without a measured gap or recorded samples.
pub fn gap_chart(
    title: &str,
    results: &[SphereResult],
    height_m: f64,
    measured: &MeasuredCurves,
) -> Option<Chart> {
    if measured.gap.is_empty() || results.iter().all(|r| r.samples.is_empty()) {
        return None;
    }
    let mut chart = Chart::new(title)
        .x("time t (s)", Scale::Linear)
        .x_from_zero(true)
        .y("gap between sphere and bottom (m)", Scale::Linear);
    for (i, r) in results.iter().enumerate() {
        let every = r.samples.len().div_ceil(LINE_POINTS).max(1);
        let points: Vec<(f64, f64)> = r
            .samples
            .iter()
            .step_by(every)
            .chain(r.samples.last())
            .map(|s| {
                (
                    s.time_s,
                    height_m - s.depth_m - 0.5 * r.case.spec.diameter_m,
                )
            })
            .collect();
        if points.is_empty() {
            continue;
        }
        let label = format!("{}, simulated", r.case.id);
        let line = Series::sorted_line(label, points, i);
        chart = chart.series_thinned(line, MARKERS_PER_LINE);
    }
    chart = chart.series(measured_series(
        &measured.source,
        &measured.gap,
        results.len(),
    ));
    Some(chart)
}

/// Re′ and C_d of one sphere, from its measured and its simulated terminal velocity.
#[derive(Clone, Debug, PartialEq)]
pub struct CdRe {
    /// Sphere id.
    pub sphere_id: String,
    /// Suspension number, if given.
    pub suspension: Option<u32>,
    /// Re′ at the measured velocity (f-EDEM eq. 18), if measured.
    pub re_measured: Option<f64>,
    /// C_d from the measured velocity (f-EDEM eq. 17), if measured and moving.
    pub cd_measured: Option<f64>,
    /// Re′ at the simulated terminal velocity, if it moves.
    pub re_simulated: Option<f64>,
    /// C_d from the simulated terminal velocity (eq. 17), if it moves.
    pub cd_simulated: Option<f64>,
}

/// The Re′–C_d points of a Bingham run (empty for other fluids). C_d comes from the force balance
/// at the velocity (f-EDEM eq. 17, the scenario's gravity), Re′ from eq. 18, as the validation
/// of Table 3 computes them.
pub fn cd_re_points(s: &Common, results: &[SphereResult]) -> Vec<CdRe> {
    let RheologyModel::Bingham {
        plastic_viscosity_pa_s: eta,
        yield_stress_pa: tau_y,
    } = s.rheology
    else {
        return Vec::new();
    };
    let rho_f = s.fluid_density_kg_m3;
    let at = |r: &SphereResult, v: f64| {
        let sp = &r.case.spec;
        let re = reynolds_bingham(rho_f, v, sp.diameter_m, tau_y, eta);
        let cd = cd_from_terminal_velocity(
            sp.density_kg_m3,
            rho_f,
            sp.diameter_m,
            tau_y,
            v,
            s.gravity_m_s2,
        );
        (re, cd)
    };
    results
        .iter()
        .map(|r| {
            let moving = |v: &f64| v.is_finite() && *v > 0.0;
            let meas = r.case.spec.v_measured_m_s.filter(moving).map(|v| at(r, v));
            let sim = Some(r.v_simulated_m_s).filter(moving).map(|v| at(r, v));
            CdRe {
                sphere_id: r.case.id.clone(),
                suspension: r.case.spec.suspension,
                re_measured: meas.map(|m| m.0),
                cd_measured: meas.map(|m| m.1),
                re_simulated: sim.map(|m| m.0),
                cd_simulated: sim.map(|m| m.1),
            }
        })
        .collect()
}

/// `cd_re.csv`: per sphere, Re′ and C_d from the measured and the simulated velocity, and
/// eq. 19 at the simulated Re′ (dimensionless).
pub fn cd_re_table(points: &[CdRe]) -> Table {
    let rows: Vec<Vec<String>> = points
        .iter()
        .map(|p| {
            vec![
                p.sphere_id.clone(),
                p.suspension.map(|x| x.to_string()).unwrap_or_default(),
                opt(p.re_measured),
                opt(p.cd_measured),
                opt(p.re_simulated),
                opt(p.cd_simulated),
                opt(p.re_simulated.map(cd_fedem)),
            ]
        })
        .collect();
    Table::with_rows(
        "cd_re.csv",
        [
            "sphere_id",
            "suspension",
            "re_bingham_measured",
            "cd_measured",
            "re_bingham_simulated",
            "cd_simulated",
            "cd_eq19_at_simulated",
        ],
        rows,
    )
}

/// `cd_re.svg`: C_d against Re′, log–log: the points of the measured velocities (hollow),
/// the simulated ones (filled) and eq. 19 (like f-EDEM Fig. 1).
pub fn cd_re_chart(title: &str, points: &[CdRe]) -> Chart {
    let pairs = |re: fn(&CdRe) -> Option<f64>, cd: fn(&CdRe) -> Option<f64>| -> Vec<(f64, f64)> {
        points
            .iter()
            .filter_map(|p| Some((re(p)?, cd(p)?)))
            .filter(|(r, c)| *r > 0.0 && *c > 0.0)
            .collect()
    };
    let meas = pairs(|p| p.re_measured, |p| p.cd_measured);
    let sim = pairs(|p| p.re_simulated, |p| p.cd_simulated);
    let (lo, hi) = meas
        .iter()
        .chain(&sim)
        .fold((f64::INFINITY, 0.0f64), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let (lo, hi) = if lo <= hi {
        (lo / 1.5, hi * 1.5)
    } else {
        (0.1, 1000.0)
    };
    // Eq. 19 is discontinuous at Re′ = 1 and 150: sample each side of the jumps.
    let mut xs: Vec<f64> = (0..=240)
        .map(|k| lo * (hi / lo).powf(k as f64 / 240.0))
        .collect();
    xs.extend(
        [1.0 - 1e-9, 1.0, 150.0 - 1e-9, 150.0]
            .iter()
            .filter(|x| **x > lo && **x < hi),
    );
    xs.sort_by(f64::total_cmp);
    let curve = xs.iter().map(|&x| (x, cd_fedem(x))).collect();
    let mut chart = Chart::new(title)
        .x("Bingham Reynolds number Re′ (-)", Scale::Log)
        .y("drag coefficient C_d (-)", Scale::Log);
    if !meas.is_empty() {
        chart = chart.series(Series {
            label: format!(
                "from measured velocities ({} spheres; f-EDEM Table 3)",
                meas.len()
            ),
            points: meas,
            colour: 0,
            filled: false,
            line: false,
        });
    }
    let n_static = points.iter().filter(|p| p.cd_simulated.is_none()).count();
    let still = if n_static > 0 {
        format!(", {n_static} held by the yield stress not shown")
    } else {
        String::new()
    };
    chart
        .series_marked(
            Series {
                label: format!("simulated ({} spheres{still})", sim.len()),
                points: sim,
                colour: 3,
                filled: true,
                line: false,
            },
            Marker::Diamond,
        )
        .curve(Curve::new(
            "f-EDEM eq. 19: 24/Re′ (Re′ < 1), 29.12/Re′ + 0.195 (≤ 150), 0.4",
            curve,
        ))
}

/// Spheres grouped by suspension (0 when none; the suspension number is the colour index, the
/// same in every chart): (measured (density, v), simulated (density, v),
/// parity (measured v, simulated v)).
type BySuspension = BTreeMap<u32, [Vec<(f64, f64)>; 3]>;

fn by_suspension(results: &[&SphereResult]) -> BySuspension {
    let mut out = BySuspension::new();
    for r in results {
        let sp = &r.case.spec;
        let e = out.entry(sp.suspension.unwrap_or(0)).or_default();
        if let Some(m) = sp.v_measured_m_s {
            e[0].push((sp.density_kg_m3, m));
            e[2].push((m, r.v_simulated_m_s));
        }
        e[1].push((sp.density_kg_m3, r.v_simulated_m_s));
    }
    out
}

fn suspension_name(k: u32) -> String {
    if k == 0 {
        "no suspension".to_string()
    } else {
        format!("suspension {k}")
    }
}

/// `parity.svg`: simulated against measured terminal velocity of every measured sphere,
/// log–log, one colour and shape per suspension, with the parity line and ±10 % and ±25 % bands.
/// Spheres the simulation holds at rest (v = 0) cannot show on log axes: the legend counts them.
/// None when no sphere is measured.
pub fn parity_chart(title: &str, results: &[&SphereResult]) -> Option<Chart> {
    let groups = by_suspension(results);
    let shown = |p: &&(f64, f64)| p.0 > 0.0 && p.1 > 0.0 && p.0.is_finite() && p.1.is_finite();
    let all: Vec<(f64, f64)> = groups
        .values()
        .flat_map(|g| g[2].iter().filter(shown).copied())
        .collect();
    if all.is_empty() {
        return None;
    }
    let lo = all
        .iter()
        .map(|p| p.0.min(p.1))
        .fold(f64::INFINITY, f64::min)
        / 1.4;
    let hi = all.iter().map(|p| p.0.max(p.1)).fold(0.0, f64::max) * 1.4;
    let line = |k: f64| -> Vec<(f64, f64, f64)> {
        (0..=60)
            .map(|i| lo * (hi / lo).powf(i as f64 / 60.0))
            .map(|x| (x, (x * (1.0 - k)).max(lo), (x * (1.0 + k)).min(hi)))
            .collect()
    };
    let mut chart = Chart::new(title)
        .x("measured terminal velocity (m/s)", Scale::Log)
        .y("simulated terminal velocity (m/s)", Scale::Log)
        .x_range(lo, hi)
        .y_range(lo, hi)
        .size(700, 600)
        .band(Band {
            label: "within ±25 %".into(),
            points: line(0.25),
            shade: 0.08,
        })
        .band(Band {
            label: "within ±10 %".into(),
            points: line(0.10),
            shade: 0.18,
        })
        .curve(Curve::new(
            "parity: simulated = measured",
            vec![(lo, lo), (hi, hi)],
        ));
    for (k, g) in &groups {
        let pts: Vec<(f64, f64)> = g[2].iter().filter(shown).copied().collect();
        if g[2].is_empty() {
            continue;
        }
        let hidden = g[2].len() - pts.len();
        let within = |tol: f64| {
            pts.iter()
                .filter(|p| (p.1 / p.0 - 1.0).abs() <= tol)
                .count()
        };
        let mut label = format!(
            "{} ({} spheres: {} within ±10 %, {} within ±25 %",
            suspension_name(*k),
            g[2].len(),
            within(0.10),
            within(0.25)
        );
        if hidden > 0 {
            label.push_str(&format!("; {hidden} at rest not shown"));
        }
        label.push(')');
        chart = chart.series(Series {
            label,
            points: pts,
            colour: *k as usize,
            filled: true,
            line: false,
        });
    }
    Some(chart)
}

/// Terminal velocity against sphere density, one colour and shape per diameter: measured
/// (hollow) and simulated (filled, joined by density), like one panel of f-EDEM Fig. 11.
pub fn terminal_velocity_chart(title: &str, results: &[&SphereResult]) -> Chart {
    type Points = Vec<(f64, f64)>;
    let mut by_d: BTreeMap<u64, (Points, Points)> = BTreeMap::new();
    for r in results {
        let key = (r.case.spec.diameter_m * 1e6).round() as u64;
        let e = by_d.entry(key).or_default();
        if let Some(m) = r.case.spec.v_measured_m_s {
            e.0.push((r.case.spec.density_kg_m3, m));
        }
        e.1.push((r.case.spec.density_kg_m3, r.v_simulated_m_s));
    }
    let mut chart = Chart::new(title)
        .x("sphere density (kg/m³)", Scale::Linear)
        .y("terminal velocity (m/s)", Scale::Linear);
    for (i, (d_um, (meas, sim))) in by_d.into_iter().enumerate() {
        let d_mm = d_um as f64 / 1000.0;
        if !meas.is_empty() {
            chart = chart.series(Series {
                label: format!("d = {d_mm} mm, measured"),
                points: meas,
                colour: i,
                filled: false,
                line: false,
            });
        }
        chart = chart.series(Series::sorted_line(
            format!("d = {d_mm} mm, simulated"),
            sim,
            i,
        ));
    }
    chart
}

/// The panels of the combined `terminal_velocity.svg`: one per suspension (drawn two per row,
/// like f-EDEM Fig. 11 a–f), terminal velocity against sphere density, one colour and shape
/// per diameter, measured hollow and simulated filled. None when no sphere is measured.
pub fn combined_terminal_panels(results: &[&SphereResult]) -> Option<Vec<Chart>> {
    if results.iter().all(|r| r.case.spec.v_measured_m_s.is_none()) {
        return None;
    }
    let mut groups: BTreeMap<u32, Vec<&SphereResult>> = BTreeMap::new();
    for r in results {
        groups
            .entry(r.case.spec.suspension.unwrap_or(0))
            .or_default()
            .push(r);
    }
    let panels: Vec<Chart> = groups
        .iter()
        .map(|(k, g)| {
            let n = g.len();
            terminal_velocity_chart(&format!("{} ({n} spheres)", suspension_name(*k)), g)
                .size(560, 400)
        })
        .collect();
    Some(panels)
}
