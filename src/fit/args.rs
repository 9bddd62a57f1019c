//! The command line of `settle fit`: its arguments and what it prints.

use super::bound::{bound_from, Bound};
use super::calibrate::{calibrate, FitOptions};
use super::measure::Measured;
use super::output;
use crate::api::Scenario;
use crate::error::Error;
use std::path::{Path, PathBuf};

/// Arguments of `settle fit` (see `settle fit --help`).
#[derive(clap::Args, Clone, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct Args {
    /// Calculators that need no scenario.
    #[command(subcommand)]
    pub calc: Option<Calc>,
    /// The scenario file (TOML) whose keys are fitted.
    #[arg(required = true)]
    pub scenario: Option<PathBuf>,
    /// A real-valued scenario key to fit and its bounds, KEY=LO:HI (LO < HI, in the key's unit),
    /// e.g. fluid.plastic_viscosity_pa_s=0.1:3. Repeatable (Nelder–Mead for several keys).
    #[arg(long = "fit", value_name = "KEY=LO:HI", required = true,
          allow_hyphen_values = true, value_parser = parse_bound)]
    pub fit: Vec<Bound>,
    /// The measurements: a CSV with columns file, column, row, value [, sigma].
    #[arg(long, value_name = "M.csv", required = true)]
    pub measured: Option<PathBuf>,
    /// Override any other scenario key for every run, as in `settle run --set`. Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Output folder; results go to `OUT/<name>_fit/`.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}

/// The calculators of `settle fit`.
#[derive(clap::Subcommand, Clone, Debug)]
pub enum Calc {
    /// The yield stress of a paste from cylinder slump tests (Pashias & Boger 1996; f-EDEM
    /// Appendix I, eqs. A1-A3): prints τ_y per slump and their mean. Writes nothing.
    Slump {
        /// Height H of the cylinder mould, mm.
        #[arg(long, allow_negative_numbers = true, value_parser = crate::io::arg::millimetres)]
        height_mm: f64,
        /// Slump S of each test, mm (comma-separated or repeated), 0 < S < H.
        #[arg(long, value_delimiter = ',', required = true, allow_negative_numbers = true,
              value_parser = crate::io::arg::millimetres)]
        slump_mm: Vec<f64>,
        /// Density of the paste, kg/m³.
        #[arg(long, allow_negative_numbers = true, value_parser = crate::io::arg::kg_per_m3)]
        density: f64,
        /// Gravitational acceleration, m/s².
        #[arg(long, default_value_t = crate::fluid::slump::G_M_S2, allow_negative_numbers = true,
              value_parser = crate::io::arg::m_per_s2)]
        g: f64,
    },
}

/// `--fit KEY=LO:HI` for clap ([`Bound::parse`]'s message).
fn parse_bound(s: &str) -> Result<Bound, String> {
    bound_from(s)
}

/// `settle fit`: the slump calculator, or a calibration; returns the console lines. The
/// scenario is loaded with the `--set` list, the measurements and bounds checked, and the
/// destination `OUT/<name>_fit/` checked before any run ([`crate::run::destination_allowed`]:
/// a folder settle did not make is bad input naming the scenario's `name`); the outputs are
/// written once the fit succeeded ([`super::FitResult::write`]).
pub fn main(args: &Args) -> Result<Vec<String>, Error> {
    if let Some(Calc::Slump {
        height_mm,
        slump_mm,
        density,
        g,
    }) = &args.calc
    {
        return Ok(super::slump(*height_mm, slump_mm, *density, *g)?.lines);
    }
    let (Some(file), Some(measured)) = (&args.scenario, &args.measured) else {
        return Err(Error::bad_argument(
            "--measured",
            Path::new(""),
            "settle fit needs a scenario, --fit and --measured",
        ));
    };
    let out = &args.out;
    for b in &args.fit {
        crate::scenario::refuse_set_of(&args.set, &b.key, "--fit")?;
    }
    let scenario = Scenario::load_with(file, &args.set)?;
    let measured = Measured::File(measured.clone());
    let r = calibrate(
        &scenario,
        &args.fit,
        &measured,
        &FitOptions::default(),
        |folder| {
            crate::io::owner::check_out_dir(out)?;
            let owner = super::calibrate::owner(folder);
            crate::run::destination_allowed(&out.join(folder), file, &owner)
        },
    )?;
    let dest = r.write(out)?;
    Ok(if args.quiet {
        Vec::new()
    } else {
        output::lines(&r.fit, Some(&dest))
    })
}
