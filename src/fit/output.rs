//! The outputs of a fit, in memory ([`Outputs`]); the command line writes them into
//! `OUT/<name>_fit/`, staged and committed only when all are written:
//!
//! | file | content |
//! |---|---|
//! | `fitted.csv` | per key: value, bounds, 1σ uncertainty (curvature), Δχ² = 1 interval (one key) |
//! | `residuals.csv` | per measurement: measured, σ, model, residual, normalised residual, ∂model/∂key |
//! | `objective.csv`, `objective_vs_<key>.svg` | one key: χ² at every value run |
//! | `fit.toml` | the request, the method, runs, χ², the fitted values |

use super::problem::Fit;
use crate::error::Error;
use crate::io::chart::{Chart, Curve, Scale, Series};
use crate::io::fmt::{g, g_opt, short};
use crate::io::fmt::{num, opt};
use crate::io::{Outputs, Table};
use serde::Serialize;
use std::path::Path;

#[derive(Serialize)]
struct FitToml<'a> {
    fit: Meta<'a>,
    keys: Vec<KeyToml<'a>>,
}

#[derive(Serialize)]
struct Meta<'a> {
    settle_version: &'a str,
    scenario_file: String,
    measured_file: String,
    /// The `--set` list applied to every run.
    set: &'a [String],
    /// The time step given apart from the `--set` list (the library's `Scenario::with_dt`).
    #[serde(skip_serializing_if = "Option::is_none")]
    dt_s: Option<f64>,
    method: &'a str,
    runs: usize,
    measurements: usize,
    chi2: f64,
    /// χ² = Σ ((model − measured)/σ)²; σ = 1 in the column's unit where none was given.
    sigma_given: bool,
}

#[derive(Serialize)]
struct KeyToml<'a> {
    key: &'a str,
    value: f64,
    lower_bound: f64,
    upper_bound: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    uncertainty: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    profile_low: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    profile_high: Option<f64>,
}

/// The last part of a key, for file names and axis labels: `fluid.plastic_viscosity_pa_s` →
/// `plastic_viscosity_pa_s`, `spheres[0].diameter_m` → `diameter_m`.
fn short_key(key: &str) -> &str {
    key.rsplit('.').next().unwrap_or(key)
}

/// What the fit was asked: the scenario file, the measurements file (or table), the overrides
/// applied to every run and the time step given apart from them.
pub struct Request<'a> {
    pub scenario: &'a Path,
    pub measured: &'a Path,
    pub set: &'a [String],
    pub dt_s: Option<f64>,
}

/// The outputs of `fit`: `fitted.csv`, `residuals.csv`, for one key `objective.csv` and its
/// chart, and `fit.toml`.
pub fn outputs(req: &Request<'_>, fit: &Fit) -> Result<Outputs, Error> {
    let io = |e: std::io::Error| Error::Io(req.measured.to_path_buf(), e);
    let mut out = Outputs::new();
    let keys: Vec<&str> = fit.bounds.iter().map(|b| b.key.as_str()).collect();
    // fitted.csv
    let (plo, phi) = fit.profile.unwrap_or((None, None));
    let rows: Vec<Vec<String>> = fit
        .bounds
        .iter()
        .enumerate()
        .map(|(j, b)| {
            vec![
                b.key.clone(),
                num(fit.values[j]),
                num(b.lo),
                num(b.hi),
                opt(fit.sigma[j]),
                opt(if j == 0 { plo } else { None }),
                opt(if j == 0 { phi } else { None }),
            ]
        })
        .collect();
    let header = [
        "key",
        "value",
        "lower_bound",
        "upper_bound",
        "uncertainty_1sigma",
        "profile_low",
        "profile_high",
    ];
    out.table(Table::with_rows("fitted.csv", header, rows));
    out.table(residuals(fit, &keys));
    // objective.csv and its chart (one key)
    if fit.bounds.len() == 1 {
        let key = keys[0];
        let rows: Vec<Vec<String>> = fit
            .objective
            .iter()
            .map(|(x, c)| vec![num(*x), num(*c)])
            .collect();
        out.table(Table::with_rows("objective.csv", [key, "chi2"], rows));
        out.chart(
            format!("objective_vs_{}.svg", short_key(key)),
            &objective_chart(fit),
        )
        .map_err(io)?;
    }
    let sigma_given = fit.measured.iter().all(|m| m.sigma.is_some());
    let toml_doc = FitToml {
        fit: Meta {
            settle_version: env!("CARGO_PKG_VERSION"),
            scenario_file: req.scenario.display().to_string(),
            measured_file: req.measured.display().to_string(),
            set: req.set,
            dt_s: req.dt_s,
            method: fit.method,
            runs: fit.runs,
            measurements: fit.measured.len(),
            chi2: fit.chi2,
            sigma_given,
        },
        keys: fit
            .bounds
            .iter()
            .enumerate()
            .map(|(j, b)| KeyToml {
                key: &b.key,
                value: fit.values[j],
                lower_bound: b.lo,
                upper_bound: b.hi,
                uncertainty: fit.sigma[j],
                profile_low: if j == 0 { plo } else { None },
                profile_high: if j == 0 { phi } else { None },
            })
            .collect(),
    };
    let text = toml::to_string(&toml_doc).map_err(|e| io(std::io::Error::other(e)))?;
    out.file("fit.toml", text);
    Ok(out)
}

/// residuals.csv: each measurement against the model, with its sensitivity to each key.
fn residuals(fit: &Fit, keys: &[&str]) -> Table {
    let mut header: Vec<String> = [
        "file",
        "column",
        "row",
        "measured",
        "sigma",
        "model",
        "residual",
        "normalised_residual",
    ]
    .map(String::from)
    .to_vec();
    header.extend(keys.iter().map(|k| format!("sensitivity_per_{k}")));
    let rows: Vec<Vec<String>> = fit
        .measured
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let r = fit.model[i] - m.value;
            let mut row = vec![
                m.file.clone(),
                m.column.clone(),
                m.row.clone(),
                num(m.value),
                opt(m.sigma),
                num(fit.model[i]),
                num(r),
                num(r / m.sigma_or_one()),
            ];
            row.extend(fit.jacobian[i].iter().map(|d| num(*d)));
            row
        })
        .collect();
    Table::with_rows("residuals.csv", header, rows)
}

/// χ² against the key: every run (markers) and the fitted value (a dashed vertical line).
fn objective_chart(fit: &Fit) -> Chart {
    let key = &fit.bounds[0].key;
    let unit = crate::sweep::vary::unit_of(key);
    let x = fit.values[0];
    let top = fit.objective.iter().map(|p| p.1).fold(0.0_f64, f64::max);
    Chart::new("settle fit: objective against the fitted key")
        .x(format!("{} [{unit}]", short_key(key)), Scale::Linear)
        .y("χ² = Σ ((model − measured)/σ)² [-]", Scale::Linear)
        .y_from_zero(true)
        .series(Series::sorted_line("runs".into(), fit.objective.clone(), 0))
        .curve(Curve::new(format!("fitted {}", short(x)), vec![(x, 0.0), (x, top)]).dashed())
}

/// The console lines: the fitted values with their uncertainty, χ², and per measurement the
/// model, the residual and the sensitivity; the first ends `-> FOLDER` when `dest` is where
/// the outputs went.
pub fn lines(fit: &Fit, dest: Option<&Path>) -> Vec<String> {
    let mut head = format!(
        "fit ({}, {} runs, chi2 = {})",
        fit.method,
        fit.runs,
        g(fit.chi2)
    );
    if let Some(d) = dest {
        head.push_str(&format!(" -> {}", d.display()));
    }
    let mut out = vec![head];
    for (j, b) in fit.bounds.iter().enumerate() {
        let unit = match crate::sweep::vary::unit_of(&b.key) {
            "-" => String::new(),
            u => format!(" {u}"),
        };
        let mut l = format!(
            "  {} = {}{unit} (+/- {} from the curvature",
            b.key,
            g(fit.values[j]),
            g_opt(fit.sigma[j])
        );
        if let (0, Some((lo, hi))) = (j, fit.profile) {
            l.push_str(&format!("; chi2 + 1 at {} .. {}", g_opt(lo), g_opt(hi)));
        }
        l.push(')');
        out.push(l);
    }
    for (i, m) in fit.measured.iter().enumerate() {
        let sens: Vec<String> = fit
            .bounds
            .iter()
            .enumerate()
            .map(|(j, b)| format!("d/d{} = {}", short_key(&b.key), g(fit.jacobian[i][j])))
            .collect();
        out.push(format!(
            "  {}: measured {}, model {}, residual {}, {}",
            m.label(),
            g(m.value),
            g(fit.model[i]),
            g(fit.model[i] - m.value),
            sens.join(", ")
        ));
    }
    out
}
