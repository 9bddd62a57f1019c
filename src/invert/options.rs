//! The options of `settle invert`: the forward model, [`InvertOptions`] (as given, its defaults
//! the command line's), the command line's [`Request`], and their check ([`options`]), which
//! refuses a bad option naming it with the command line's message.

use super::solve::LambdaRule;
use crate::error::Error;
use crate::instruments::forward::Settling;
use std::path::{Path, PathBuf};

/// The forward model of an inversion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Model {
    /// Stokes settling from t = 0 (what the standard reductions assume).
    IdealStokes,
    /// Dallavalle drag with the Di Felice voidage factor at the test's concentration
    /// (hindered settling; no contacts).
    Full,
}

impl Model {
    /// Parses `ideal-stokes` / `full`.
    pub fn parse(s: &str) -> Option<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "ideal-stokes" | "ideal_stokes" | "stokes" => Some(Self::IdealStokes),
            "full" => Some(Self::Full),
            _ => None,
        }
    }

    /// Its name.
    pub fn name(self) -> &'static str {
        match self {
            Self::IdealStokes => "ideal-stokes",
            Self::Full => "full",
        }
    }

    pub(super) fn settling(self) -> Settling {
        match self {
            Self::IdealStokes => Settling::IdealStokes,
            Self::Full => Settling::Hindered {
                voidage_cell_m: 0.002,
            },
        }
    }
}

/// The confidence of `--bounds` given alone: the strict bounds hold every distribution that
/// explains the readings at this level, so the true curve lies inside them at every diameter
/// with this probability when the readings' σ are right (Stark 1992).
pub const DEFAULT_BOUNDS_CONFIDENCE: f64 = 0.95;

/// The options of `settle invert` (its defaults those of the command line), as given: `invert`
/// checks them and refuses a bad one as [`Error::BadInput`] naming the option (`--model`,
/// `--lambda`, ...) with the command line's message.
#[derive(Clone, Debug, PartialEq)]
pub struct InvertOptions {
    /// `--model`: `ideal-stokes` (default) or `full`.
    pub model: String,
    /// `--bins`: resolved diameter bins, 2–200 (None: twice the readings, 8–30).
    pub bins: Option<usize>,
    /// `--diameters-um LO:HI`: the resolved range, µm (None: from the readings).
    pub diameters_um: Option<String>,
    /// `--lambda`: a number ≥ 0, `discrepancy` (default) or `gcv`.
    pub lambda: String,
    /// `--resolution`: the readings' resolution in their unit, one for every file or one per
    /// file in order (empty: each instrument's default).
    pub resolution: Vec<f64>,
    /// `--repeats`: Monte Carlo repeats of the band (0: no band; default 100).
    pub repeats: usize,
    /// `--seed` of the Monte Carlo (ChaCha8; default 1).
    pub seed: u64,
    /// `--bounds[=P]`: also the strict bounds of the curve at each edge at confidence P,
    /// 0 < P < 1 (`--bounds` alone: [`DEFAULT_BOUNDS_CONFIDENCE`]): every distribution of the
    /// bins with χ² at most the P-quantile of χ² with m degrees of freedom
    /// ([`super::solve::chi2_bar`], [`super::solve::Linear::strict_bounds`]). None: no bounds.
    pub bounds: Option<f64>,
}

impl Default for InvertOptions {
    fn default() -> Self {
        Self {
            model: "ideal-stokes".into(),
            bins: None,
            diameters_um: None,
            lambda: "discrepancy".into(),
            resolution: Vec::new(),
            repeats: 100,
            seed: 1,
            bounds: None,
        }
    }
}

/// What `settle invert` is asked to do on the command line: the files, the options and the
/// output folder (`run`).
#[derive(Clone, Debug)]
pub struct Request {
    /// The readings files (one test of one soil each, any instrument).
    pub files: Vec<PathBuf>,
    /// The options (`--model`, `--bins`, …).
    pub options: InvertOptions,
    /// Output folder; results go to `out_dir/<stem of the first file>_inverted/`.
    pub out_dir: PathBuf,
}

impl Default for Request {
    fn default() -> Self {
        Self {
            files: Vec::new(),
            options: InvertOptions::default(),
            out_dir: PathBuf::from("out"),
        }
    }
}

/// The options, checked: (model, λ rule, resolved range in m).
pub(super) type Options = (Model, LambdaRule, Option<(f64, f64)>);

/// Checks `opts` for `files` readings.
pub(super) fn options(opts: &InvertOptions, files: usize) -> Result<Options, Error> {
    let here = Path::new(&opts.model);
    let model = Model::parse(&opts.model).ok_or_else(|| {
        Error::bad_argument(
            "--model",
            here,
            "unknown model; allowed: ideal-stokes, full",
        )
    })?;
    let lambda = match opts.lambda.trim().to_ascii_lowercase().as_str() {
        "discrepancy" => LambdaRule::Discrepancy,
        "gcv" => LambdaRule::Gcv,
        s => match s.parse::<f64>() {
            Ok(x) if x.is_finite() && x >= 0.0 => LambdaRule::Fixed(x),
            _ => {
                let why = crate::io::arg::number_problem(s, "")
                    .map(|p| format!("{p}; "))
                    .unwrap_or_default();
                return Err(Error::bad_argument(
                    "--lambda",
                    Path::new(&opts.lambda),
                    format!("{why}allowed: discrepancy, gcv or a number ≥ 0"),
                ));
            }
        },
    };
    let range = match &opts.diameters_um {
        None => None,
        Some(s) => {
            let bad = |m: &str| Error::bad_argument("--diameters-um", Path::new(s), m.to_string());
            let (a, b) = s
                .split_once(':')
                .ok_or_else(|| bad("expected LO:HI in µm, e.g. 2:75"))?;
            for t in [a, b] {
                if let Some(p) = crate::io::arg::number_problem(t, "µm") {
                    return Err(bad(&format!(
                        "{p}; allowed LO:HI in µm, 0 < LO < HI, e.g. 2:75"
                    )));
                }
            }
            let (a, b): (f64, f64) = (
                a.trim().parse().unwrap_or_default(),
                b.trim().parse().unwrap_or_default(),
            );
            if !(a.is_finite() && b.is_finite() && a > 0.0) {
                return Err(bad("allowed: 0 < LO < HI (µm)"));
            }
            if a >= b {
                return Err(bad("reversed or empty range: LO must be below HI (µm)"));
            }
            Some((a * 1e-6, b * 1e-6))
        }
    };
    if let Some(p) = opts.bounds.filter(|p| !(*p > 0.0 && *p < 1.0)) {
        return Err(Error::bad_argument(
            "--bounds",
            Path::new(&crate::io::fmt::short(p)),
            "the confidence of the strict bounds: allowed 0 < P < 1, e.g. --bounds=0.95",
        ));
    }
    if let Some(n) = opts.bins.filter(|&n| !(2..=200).contains(&n)) {
        return Err(Error::bad_argument(
            "--bins",
            Path::new(&n.to_string()),
            "allowed: 2–200",
        ));
    }
    if !(opts.resolution.len() <= 1 || opts.resolution.len() == files) {
        return Err(Error::bad_argument(
            "--resolution",
            Path::new(
                &opts
                    .resolution
                    .iter()
                    .map(|r| crate::io::fmt::short(*r))
                    .collect::<Vec<_>>()
                    .join(","),
            ),
            format!(
                "{} values for {files} readings file{}: give one resolution for every file or \
                 one per file",
                opts.resolution.len(),
                if files == 1 { "" } else { "s" }
            ),
        ));
    }
    if let Some(r) = opts
        .resolution
        .iter()
        .find(|r| !(r.is_finite() && **r > 0.0))
    {
        return Err(Error::bad_argument(
            "--resolution",
            Path::new(&r.to_string()),
            "allowed: > 0 (in the readings' unit)",
        ));
    }
    if files == 0 {
        return Err(Error::bad_argument(
            "READINGS.csv",
            Path::new(""),
            "no readings file given",
        ));
    }
    Ok((model, lambda, range))
}
