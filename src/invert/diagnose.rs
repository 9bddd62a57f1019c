//! What to say when the model cannot explain the readings (issue 26, item 8): χ² well above
//! the number of readings m names the files whose readings it misses, the readings that miss
//! most (time and misfit in σ), and what to change, by what the σ of those readings is made of.
//!
//! A run's readings files carry the counting noise of the representative grains
//! (`counting_sigma`, [`crate::instruments::counting`]), which `settle invert` adds to the
//! resolution. Where the misfits are of the size of that counting σ the run had too few
//! grains for the readings' precision (more grains: σ ∝ 1/√N); where they are many counting σ
//! the forward model misses something of the run (another `--model`, or the figures). A
//! laboratory file (no counting σ) is told to check its figures, `--resolution` and the model.

use super::options::Model;
use super::problem::Test;
use super::Misfit;
use crate::io::fmt::g;

/// A file's share of χ²: (index of the file, its χ², its readings, its worst readings as
/// (time s, misfit in σ), the median of |misfit| over the counting σ, if it has one).
struct FileFit {
    file: usize,
    chi2: f64,
    m: usize,
    worst: Vec<(f64, f64)>,
    misfit_over_counting: Option<f64>,
}

fn file_fits(tests: &[Test], misfit: &[Misfit]) -> Vec<FileFit> {
    let mut out = Vec::new();
    let mut row = 0;
    for (k, t) in tests.iter().enumerate() {
        let rows = &misfit[row..row + t.readings.len()];
        row += t.readings.len();
        let z: Vec<(f64, f64)> = rows
            .iter()
            .map(|x| (x.time_s, (x.reading - x.predicted) / x.sigma))
            .collect();
        let chi2 = z.iter().map(|(_, z)| z * z).sum();
        let mut worst: Vec<(f64, f64)> = z.iter().copied().filter(|(_, z)| z.abs() > 2.0).collect();
        worst.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
        worst.truncate(4);
        let mut ratio: Vec<f64> = rows
            .iter()
            .zip(&t.counting_sigma)
            .filter(|(_, c)| **c > 0.0)
            .map(|(x, c)| (x.reading - x.predicted).abs() / c)
            .collect();
        ratio.sort_by(f64::total_cmp);
        out.push(FileFit {
            file: k,
            chi2,
            m: t.readings.len(),
            worst,
            misfit_over_counting: (!ratio.is_empty()).then(|| ratio[ratio.len() / 2]),
        });
    }
    out
}

/// What to change for a file that the model misses.
fn advice(f: &FileFit, model: Model) -> String {
    let other = match model {
        Model::IdealStokes => "try --model full (hindered settling)",
        Model::Full => {
            "the full model has no contacts: compare with a run without them \
             (sample.contacts = false)"
        }
    };
    match f.misfit_over_counting {
        None => format!(
            "check the file's figures (dry_mass_g, specific_gravity, the instrument's depth and \
             size) and give a --resolution as coarse as the readings really are{}",
            match model {
                Model::IdealStokes => ", or try --model full (hindered settling)",
                Model::Full => "",
            }
        ),
        Some(x) if x <= 3.0 => format!(
            "its misfits are {} times its readings' counting σ (the noise of the run's \
             representative grains, already included): a run with more grains \
             (sample.particles; σ falls as 1/√N) reads more precisely, and the model is then \
             tested more strictly",
            g(x)
        ),
        Some(x) => format!(
            "its misfits are {} times its readings' counting σ, so more grains will not help: \
             the forward model misses something of the run: {other}, or leave this file out",
            g(x)
        ),
    }
}

/// The warning for χ² > 2 m (None when the readings are explained): per file that the model
/// misses (its own χ² above twice its readings), its χ², the readings that miss most, and what
/// to change.
pub fn chi2_warning(tests: &[Test], misfit: &[Misfit], chi2: f64, model: Model) -> Option<String> {
    let m = misfit.len();
    if chi2 <= 2.0 * m as f64 {
        return None;
    }
    let mut fits = file_fits(tests, misfit);
    fits.sort_by(|a, b| (b.chi2 / b.m as f64).total_cmp(&(a.chi2 / a.m as f64)));
    let mut parts: Vec<String> = fits
        .iter()
        .filter(|f| f.chi2 > 2.0 * f.m as f64)
        .map(|f| {
            let worst: Vec<String> = f
                .worst
                .iter()
                .map(|(t, z)| format!("t = {} min ({}σ)", g(t / 60.0), g(*z)))
                .collect();
            format!(
                "{}: χ² = {} for its {} readings, worst {}; {}",
                tests[f.file].file.display(),
                g(f.chi2),
                f.m,
                if worst.is_empty() {
                    "none beyond 2σ (many small misfits)".to_string()
                } else {
                    worst.join(", ")
                },
                advice(f, model)
            )
        })
        .collect();
    if parts.is_empty() {
        parts
            .push("no single file stands out: check the figures, the model or --resolution".into());
    }
    Some(format!(
        "χ² = {} for {m} readings: the model does not explain the readings within their \
         uncertainty. {}",
        g(chi2),
        parts.join(". ")
    ))
}
