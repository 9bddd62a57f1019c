//! The tables, files and console summary of `settle invert`, in memory.

use super::solve::LambdaRule;
use super::InvertResult;
use crate::error::Error;
use crate::io::chart::{Band, Chart, Curve, Scale, Series};
use crate::io::fmt::clean;
use crate::io::fmt::g;
use crate::io::{Outputs, Table};
use std::path::{Path, PathBuf};

/// The tables and files of `OUT/<name>/`: `inverted.csv`, `misfit.csv`, `standard.csv`,
/// `inverted.svg` and `invert.toml`.
pub fn outputs(r: &InvertResult) -> Result<Outputs, Error> {
    let bounds = r.options.bounds.is_some();
    let rows: Vec<Vec<String>> = r
        .curve
        .iter()
        .map(|c| {
            let mut row = vec![
                clean(c.diameter_m),
                clean(c.percent_finer),
                clean(c.p5),
                clean(c.p95),
            ];
            if bounds {
                let (lo, hi) = c.bounds.map_or((String::new(), String::new()), |(lo, hi)| {
                    (clean(lo), clean(hi))
                });
                row.extend([lo, hi]);
            }
            row
        })
        .collect();
    let mut header = vec![
        "diameter_m",
        "percent_finer",
        "percent_finer_p5",
        "percent_finer_p95",
    ];
    if bounds {
        header.extend(["percent_finer_min", "percent_finer_max"]);
    }
    let mut out = Outputs::new();
    out.table(Table::with_rows("inverted.csv", header, rows));
    let rows: Vec<Vec<String>> = r
        .misfit
        .iter()
        .map(|m| {
            let t = &r.tests[m.file];
            vec![
                t.file.display().to_string(),
                t.probe.name().to_string(),
                clean(m.time_s),
                clean(m.reading),
                clean(m.predicted),
                clean(m.reading - m.predicted),
                clean(m.sigma),
            ]
        })
        .collect();
    out.table(Table::with_rows(
        "misfit.csv",
        [
            "file",
            "instrument",
            "time_s",
            "reading",
            "predicted",
            "residual",
            "sigma",
        ],
        rows,
    ));
    let rows: Vec<Vec<String>> = r
        .standard
        .iter()
        .map(|(k, s)| {
            let t = &r.tests[*k];
            vec![
                t.file.display().to_string(),
                t.probe.name().to_string(),
                clean(s.reading.time_s),
                clean(s.reading.reading),
                clean(s.effective_depth_m),
                clean(s.diameter_m),
                clean(s.percent_finer),
            ]
        })
        .collect();
    out.table(Table::with_rows(
        "standard.csv",
        [
            "file",
            "instrument",
            "time_s",
            "reading",
            "effective_depth_m",
            "diameter_m",
            "percent_finer",
        ],
        rows,
    ));
    out.chart("inverted.svg", &chart(r))
        .map_err(|e| Error::Io(PathBuf::from(&r.name).join("inverted.svg"), e))?;
    out.file("invert.toml", record(r));
    Ok(out)
}

fn chart(r: &InvertResult) -> Chart {
    let um = |d: f64| d * 1e6;
    let mut c = Chart::new(format!(
        "{}: recovered grain-size curve ({} model)",
        r.name.trim_end_matches("_inverted"),
        r.model.name()
    ))
    .x("particle diameter [µm]", Scale::Log)
    .y("percent finer [%]", Scale::Linear)
    .y_range(0.0, 100.0);
    if r.curve.iter().any(|p| p.p95 > p.p5) {
        c = c.band(Band {
            label: "5–95 % band".into(),
            points: r
                .curve
                .iter()
                .map(|p| (um(p.diameter_m), p.p5, p.p95))
                .collect(),
            shade: 0.18,
        });
    }
    let bounds: Vec<(f64, f64, f64)> = r
        .curve
        .iter()
        .filter_map(|p| p.bounds.map(|(lo, hi)| (um(p.diameter_m), lo, hi)))
        .collect();
    if let Some(p) = r.options.bounds.filter(|_| !bounds.is_empty()) {
        c = c.band(Band {
            label: format!(
                "strict bounds, {} % (χ² ≤ {})",
                crate::io::fmt::short(100.0 * p),
                crate::io::fmt::sig_trim(super::solve::chi2_bar(r.misfit.len(), p), 4)
            ),
            points: bounds,
            shade: 0.07,
        });
    }
    c = c.curve(Curve::new(
        "inverted",
        r.curve
            .iter()
            .map(|p| (um(p.diameter_m), p.percent_finer))
            .collect(),
    ));
    for (k, t) in r.tests.iter().enumerate() {
        let pts: Vec<(f64, f64)> = r
            .standard
            .iter()
            .filter(|(f, _)| *f == k)
            .map(|(_, s)| (um(s.diameter_m), s.percent_finer))
            .filter(|(d, _)| *d > 0.0)
            .collect();
        let file = t
            .file
            .file_name()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        c = c.series(Series {
            label: format!("standard reduction: {file}"),
            points: pts,
            colour: k + 1,
            filled: false,
            line: false,
        });
    }
    c
}

fn record(r: &InvertResult) -> String {
    let files: Vec<String> = r
        .inputs
        .iter()
        .map(|f| format!("{:?}", f.display().to_string()))
        .collect();
    let rule_name = match r.lambda_rule {
        LambdaRule::Fixed(_) => "fixed",
        LambdaRule::Discrepancy => "discrepancy",
        LambdaRule::Gcv => "gcv",
    };
    let edges = super::resolved_edges(&r.bins);
    let mut t = format!(
        "# written by settle invert\n[invert]\nsettle_version = \"{}\"\ninputs = [{}]\n\
         model = \"{}\"\nbins = {}\ndiameter_lo_m = {}\ndiameter_hi_m = {}\n\
         lambda_rule = \"{}\"\nlambda = {}\nchi2 = {}\nreadings = {}\niterations = {}\n\
         converged = {}\nrepeats = {}\nseed = {}\nbounds = {}\nwall_time_s = {}\n",
        env!("CARGO_PKG_VERSION"),
        files.join(", "),
        r.model.name(),
        edges.len() - 1,
        clean(edges[0]),
        clean(edges[edges.len() - 1]),
        rule_name,
        clean(r.lambda),
        clean(r.chi2),
        r.misfit.len(),
        r.iterations,
        r.converged,
        r.options.repeats,
        r.options.seed,
        r.options.bounds.is_some(),
        clean(r.wall_time_s),
    );
    if let Some(p) = r.options.bounds {
        t.push_str(&format!(
            "bounds_confidence = {}\nbounds_chi2_max = {}\n",
            clean(p),
            clean(super::solve::chi2_bar(r.misfit.len(), p))
        ));
    }
    t.push_str(&format!(
        "mass_finer_than_range = {}\nmass_coarser_than_range = {}\n",
        clean(r.w[0]),
        clean(r.w[r.w.len() - 1])
    ));
    for test in &r.tests {
        let an = &test.col.analysis;
        t.push_str(&format!(
            "\n[[file]]\npath = {:?}\ninstrument = \"{}\"\nreadings = {}\nresolution = {}\n\
             sigma = {}\ncounting_sigma_max = {}\ncolumn_height_m = {}\nlayers = {}\nc0_kg_m3 = {}\nviscosity_pa_s = {}\n\
             fluid_density_kg_m3 = {}\ngrain_density_kg_m3 = {}\ngravity_m_s2 = {}\n",
            test.file.display().to_string(),
            test.probe.name(),
            test.readings.len(),
            clean(test.resolution),
            clean(test.sigma()),
            clean(test.counting_sigma.iter().copied().fold(0.0, f64::max)),
            clean(test.col.height_m),
            test.col.layers,
            clean(an.c0_kg_m3),
            clean(an.viscosity_pa_s),
            clean(an.fluid_density_kg_m3),
            clean(an.grain_density_kg_m3),
            clean(an.gravity_m_s2),
        ));
        if let Some((d, _)) = &test.input {
            t.push_str(&format!("\n[file.input]\n{}", d.toml()));
        }
    }
    t
}

/// Warnings: χ² well above the number of readings (the model does not explain them within
/// their uncertainty), iterations that did not converge.
pub fn warnings(r: &InvertResult) -> Vec<String> {
    let m = r.misfit.len() as f64;
    let mut w: Vec<String> = r
        .tests
        .iter()
        .filter_map(|t| t.input.as_ref().map(|(_, w)| (t, w)))
        .flat_map(|(t, ws)| ws.iter().map(move |x| format!("{}: {x}", t.file.display())))
        .collect();
    if r.chi2 > 2.0 * m && r.lambda_rule != LambdaRule::Gcv {
        w.extend(super::diagnose::chi2_warning(
            &r.tests, &r.misfit, r.chi2, r.model,
        ));
    }
    if !r.converged {
        w.push(format!(
            "the iterations did not converge to 0.01 points in {}",
            r.iterations
        ));
    }
    let empty = r.curve.iter().filter(|c| c.bounds.is_none()).count();
    if let Some(p) = r.options.bounds.filter(|_| empty > 0) {
        let m = r.misfit.len();
        w.push(format!(
            "--bounds: no distribution of the bins has χ² ≤ {} (the {} % quantile of χ² for \
             {m} readings) at {} of {} diameters, so the strict bounds there are empty (— in \
             the table): the readings scatter more than their resolution allows for this model. \
             Check the readings, give a larger --resolution, or try another --model",
            crate::io::fmt::sig_trim(super::solve::chi2_bar(m, p), 4),
            crate::io::fmt::short(100.0 * p),
            empty,
            r.curve.len()
        ));
    }
    w
}

/// The console summary: a title line (the results written to `out`), then diameter, percent
/// finer and band.
pub fn summary(r: &InvertResult, out: &Path) -> Vec<String> {
    let bounds = r.options.bounds.is_some();
    let mut lines = vec![format!(
        "{} ({} model, {} readings, {} bins, λ = {}, χ² = {}, {} iterations, {} s) -> {}",
        r.inputs
            .iter()
            .map(|f| f.display().to_string())
            .collect::<Vec<_>>()
            .join(" + "),
        r.model.name(),
        r.misfit.len(),
        r.curve.len().saturating_sub(1),
        g(r.lambda),
        g(r.chi2),
        r.iterations,
        g(r.wall_time_s),
        out.display()
    )];
    let mut head = format!(
        "  {:>8} {:>8} {:>8} {:>8}",
        "d_um", "finer_%", "p5_%", "p95_%"
    );
    if bounds {
        head += &format!(" {:>8} {:>8}", "min_%", "max_%");
    }
    lines.push(head);
    for c in &r.curve {
        let mut line = format!(
            "  {:>8} {:>8} {:>8} {:>8}",
            g(c.diameter_m * 1e6),
            g(c.percent_finer),
            g(c.p5),
            g(c.p95)
        );
        if bounds {
            let (lo, hi) = c
                .bounds
                .map_or(("—".into(), "—".into()), |(lo, hi)| (g(lo), g(hi)));
            line += &format!(" {lo:>8} {hi:>8}");
        }
        lines.push(line);
    }
    lines
}
