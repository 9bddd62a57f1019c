//! The `settle` command line.

use crate::run::{run_files, FileReport, RunRequest};
use clap::{Parser, Subcommand};
use std::path::PathBuf;

/// Simulate solid particles settling in Newtonian and Bingham fluids.
///
/// Exit codes, the same in every command: 0 success; 2 bad input, found before any work and
/// nothing written (an argument, an input file that is missing, a folder, given twice or wrong,
/// or an output folder settle may not write: --out a file, a non-empty folder settle did not
/// create, the results of another command or input); 3 unstable run (nothing was written); 4
/// the machine refused (a file could not be read or written: disk, permissions, a read-only
/// --out); 130 interrupted by Ctrl-C or SIGTERM (a
/// sedimentation or funnel-pour run keeps what it simulated, marked interrupted in run.toml; other
/// kinds write nothing of the unfinished run).
#[derive(Parser, Debug)]
#[command(name = "settle", version, about)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run one or more scenario files; results go to OUT/<scenario name>/.
    ///
    /// Each run writes its kind's CSV files and charts (every file is listed in
    /// docs/scenarios/<kind>.md; summary.csv for every kind), report.html (a self-contained page:
    /// scenario, record, validity warnings, results, every chart) and run.toml (effective
    /// scenario, overrides as given, version, dt, steps, wall time, warnings). With several files,
    /// OUT/combined/ holds the joint summary, metrics, charts and report.html.
    /// `settle run OUT/NAME/run.toml` runs the same case again (the --set list and --dt it was
    /// run with are recorded in it, already applied; input files as absolute paths).
    /// Exit codes: 0 success, 2 bad input (nothing written), 3 unstable run (nothing written),
    /// 4 I/O or environment, 130 interrupted.
    ///
    /// OUT/NAME/ is settle's: a rerun replaces the files settle wrote there (listed in its
    /// .settle-run file) and keeps any other; a folder settle did not create is never replaced
    /// (exit 2). The names `checkpoint` and `combined` are reserved.
    ///
    /// Long runs: --checkpoint-every SECONDS saves the state of the sedimentation cylinder and of
    /// each funnel-pour repeat to OUT/checkpoint/ (also on Ctrl-C/SIGTERM, exit 130), and
    /// `settle run --resume OUT` continues with the same outputs as an uninterrupted run.
    Run {
        /// Scenario files (TOML).
        #[arg(required_unless_present = "resume")]
        scenarios: Vec<PathBuf>,
        /// Output folder.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Time step in seconds, overriding time.dt_s of every scenario.
        #[arg(long, allow_hyphen_values = true, value_parser = crate::io::arg::seconds)]
        dt: Option<f64>,
        /// Override any scenario key, e.g. --set fluid.viscosity_pa_s=0.002 --set physics=ideal-stokes
        /// or --set 'spheres[0].diameter_m=2e-4'. Repeatable.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Print nothing but errors (no progress bar).
        #[arg(long, short)]
        quiet: bool,
        /// Write a checkpoint every SECONDS of wall time (and always when interrupted).
        #[arg(long, value_name = "SECONDS", allow_hyphen_values = true,
              value_parser = crate::io::arg::seconds)]
        checkpoint_every: Option<f64>,
        /// Continue the interrupted or killed run whose output folder is DIR (its scenario files
        /// and options come from DIR/checkpoint/request.toml).
        #[arg(long, value_name = "DIR", conflicts_with_all = ["scenarios", "out", "dt", "set"])]
        resume: Option<PathBuf>,
        /// Run even if the cost estimate exceeds 24 h of wall time, 8 GB of memory or 4 GB of
        /// outputs.
        #[arg(long)]
        force: bool,
        /// Submit the run to Slurm as one job that checkpoints on the warning signal before its
        /// time limit, is requeued and resumes (script and log in OUT/; see docs/cluster.md).
        #[arg(long, conflicts_with = "resume")]
        slurm: bool,
        /// Options of the submission (with --slurm).
        #[command(flatten)]
        submit: crate::slurm::Submit,
    },
    /// Benchmarks (wall times and ratios) written to OUT/bench/bench.csv.
    Bench {
        /// Output folder.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Shorter loops and no full sweep (a quick smoke run).
        #[arg(long)]
        quick: bool,
        /// Representative grains of the sedimentation benchmarks (default 20000 with --quick,
        /// else 100000).
        #[arg(long, allow_negative_numbers = true, value_parser = crate::io::arg::count1_usize)]
        grains: Option<usize>,
        /// Only the sedimentation benchmarks (grain-steps per second, stage wall times, peak
        /// memory per grain).
        #[arg(long)]
        sedimentation_only: bool,
    },
    /// Time-step sensitivity sweep: run every (integrator, dt) and compare.
    ///
    /// Writes OUT/<name>_sweep/sweep.csv (one row per integrator, dt, body and quantity: value,
    /// reference, error against the reference and against the finest stable dt, wall time,
    /// steps, status stable/unstable with the reason), quantity_vs_dt.svg, speed_accuracy.svg and
    /// recommended_dt.csv, and prints the recommended dt beside the Rayleigh-time rule.
    /// Defaults come from the scenario's [sweep] table. Kinds free_settling, drop and funnel_pour
    /// can be swept; other kinds, like bad options, exit 2 before anything is written.
    ///
    /// With --vary KEY=GRID (repeatable), a parameter sweep of any scenario key instead, at the
    /// scenario's own dt: OUT/<name>_vary/vary.csv (the varied keys, body, each result with its
    /// unit, status) and a chart <quantity>_vs_<key>.svg of each result against the first key.
    /// A list of words or booleans is a categorical axis, each value passed as --set passes it
    /// (e.g. --vary transient.history=off,basset,mei-adrian compares quasi-steady and history
    /// forces). Every case is validated first: a bad key or value exits 2 with nothing written.
    Sweep(crate::sweep::Args),
    /// Reduce laboratory hydrometer readings by ASTM D422 or D7928, or pipette and
    /// buoyancy-sphere readings by seed 000's eqs. 17 and 22 (percent finer vs diameter).
    ///
    /// READINGS.csv holds the test's figures as `# key = value` lines (standard, hydrometer,
    /// dry_mass_g, specific_gravity, meniscus_correction, blank_reading, and for D7928 the
    /// hydrometer's measured h_r1_cm, h_r2_cm, bulb_volume_ml, cylinder_area_cm2; or
    /// `instrument = pipette | buoyancy-sphere` with its own figures), then the columns
    /// time_min (or time_s), reading (drawn_mass_g, apparent_mass_g), temperature_c
    /// [, blank_reading]. Writes
    /// OUT/<stem>_reduced/percent_finer.csv (also as .xlsx and as AGS4 .ags), percent_finer.svg
    /// and reduce.toml. Bad input (a
    /// missing figure, a reading off the scale, times out of order, a temperature outside the
    /// standard's range) exits 2 naming the file, row and column; nothing is written.
    /// See docs/commands/reduce.md.
    Reduce {
        /// The readings file: CSV (comma or semicolon, decimal point or comma, UTF-8 or
        /// Latin-1), .xlsx or .ods.
        #[arg(required_unless_present = "template")]
        readings: Option<PathBuf>,
        /// Print a readings template to fill in (d7928 or d422) and exit.
        #[arg(long, value_name = "STANDARD", conflicts_with = "readings")]
        template: Option<String>,
        /// d422 or d7928 (overrides the file's `# standard`).
        #[arg(long)]
        standard: Option<String>,
        /// 152H or 151H (overrides the file's `# hydrometer`).
        #[arg(long)]
        hydrometer: Option<String>,
        /// Output folder.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
    /// Every drag law of a yield-stress fluid on spheres with measured terminal velocities.
    ///
    /// By default the 121 spheres of Valentik & Whitmore (1965) in six clay suspensions (f-EDEM
    /// Tables 2-3, built in). Per law (bingham-fedem, bingham-additive, ansley-smith,
    /// wilson-2003, and the last two with Beris et al.'s static criterion): velocity error of the
    /// force-balance terminal velocity (mean, median, max |error|, bias, within 10 % and 25 %),
    /// force error at the measured speed, spheres predicted static or on a jump, and
    /// leave-one-suspension-out figures for f-EDEM's fitted eq. 19. Writes OUT/laws/laws.csv,
    /// predictions.csv, cd_vs_re.svg, parity.svg, error_vs_yield_number.svg.
    /// See docs/commands/laws.md.
    Laws {
        /// A spheres CSV (sphere_id, suspension, diameter_m, density_kg_m3,
        /// v_terminal_measured_m_s [, re_bingham_tabulated, cd_tabulated]); needs --fluids.
        #[arg(requires = "fluids")]
        spheres: Option<PathBuf>,
        /// The fluids CSV of SPHERES (suspension, density_kg_m3, yield_stress_pa, and
        /// plastic_viscosity_pa_s or consistency_pa_sn and flow_index).
        #[arg(long, requires = "spheres")]
        fluids: Option<PathBuf>,
        /// Output folder; results go to OUT/laws/.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
    /// Calibration: fit scenario keys to measurements, or compute a yield stress from slumps.
    ///
    /// `settle fit SCENARIO --fit KEY=LO:HI [--fit ...] --measured M.csv [--set K=V] [--out DIR]`
    /// runs the scenario inside a bounded minimiser (Brent for one key, Nelder-Mead for several)
    /// of chi2 = sum ((model - measured)/sigma)^2. M.csv: file (an output CSV, e.g. summary.csv),
    /// column, row (NAME=VALUE, id=VALUE or a 0-based index), value [, sigma]. Writes
    /// OUT/<name>_fit/: fitted.csv (values, 1-sigma uncertainty, chi2 + 1 interval),
    /// residuals.csv (with d model/d key), objective.csv and objective_vs_<key>.svg (one key),
    /// fit.toml. Bad input (a key that is not a real number, reversed bounds, a measurement the
    /// run does not write, no convergence, a best value on a bound) exits 2 with nothing written.
    /// `settle fit slump --height-mm H --slump-mm S1,S2 --density RHO` prints the yield stress
    /// of slump tests (f-EDEM Appendix I). See docs/commands/fit.md.
    Fit(crate::fit::Args),
    /// Recover the grain-size distribution from one or several instruments' readings.
    ///
    /// Fits settle's forward model (the suspension each size leaves at each reading time, read
    /// through the instrument's exact geometry) to the readings of READINGS.csv (the format of
    /// `settle reduce`; several files: instruments of the same soil): bins even in ln d over the
    /// diameters the readings resolve, w ≥ 0, Σw = 1, Tikhonov smoothing with λ by the
    /// discrepancy principle (or GCV, or a number), a 5–95 % band by Monte Carlo over the
    /// readings' uncertainty and the smoothing prior. Writes OUT/<stem>_inverted/inverted.csv,
    /// misfit.csv, standard.csv, inverted.svg and invert.toml. Bad input exits 2 naming the file
    /// or option; nothing is written. See docs/commands/invert.md.
    Invert {
        /// The readings files (CSV, the format of `settle reduce`).
        #[arg(required = true)]
        readings: Vec<PathBuf>,
        /// Forward model: ideal-stokes (Stokes settling) or full (hindered settling at the
        /// test's concentration).
        #[arg(long, default_value = "ideal-stokes")]
        model: String,
        /// Diameter bins over the resolved range (default: twice the readings, 8–30).
        #[arg(long, allow_negative_numbers = true, value_parser = crate::io::arg::count1_usize)]
        bins: Option<usize>,
        /// Resolved diameter range LO:HI in µm (default: from the readings' times and depths).
        #[arg(long, value_name = "LO:HI", allow_hyphen_values = true)]
        diameters_um: Option<String>,
        /// Smoothing weight λ: discrepancy, gcv or a number ≥ 0.
        #[arg(long, default_value = "discrepancy", allow_negative_numbers = true)]
        lambda: String,
        /// Resolution of the readings in their unit: one for every file or one per file,
        /// comma-separated (default 0.5 g/L hydrometer, 0.001 g pipette, 0.01 g sphere).
        #[arg(long, allow_negative_numbers = true, value_delimiter = ',',
              value_parser = crate::io::arg::reading_unit)]
        resolution: Vec<f64>,
        /// Monte Carlo repeats of the uncertainty band (0: none).
        #[arg(long, default_value_t = 100, allow_negative_numbers = true,
              value_parser = crate::io::arg::count_usize)]
        repeats: usize,
        /// Seed of the Monte Carlo.
        #[arg(long, default_value_t = 1, allow_negative_numbers = true,
              value_parser = crate::io::arg::count)]
        seed: u64,
        /// Also the strict bounds of the curve at each diameter at confidence P (`--bounds`
        /// alone: 0.95; `--bounds=0.99`): its smallest and largest value over every distribution
        /// of the bins, without smoothing, whose χ² is at most the P-quantile of χ² with m
        /// degrees of freedom, m the number of readings (what the readings alone leave open).
        #[arg(long, value_name = "P", num_args = 0..=1, require_equals = true,
              default_missing_value = "0.95", value_parser = crate::io::arg::probability)]
        bounds: Option<f64>,
        /// Output folder.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
}

/// Parses the arguments, runs, and returns the process exit code.
pub fn main() -> i32 {
    let cli = Cli::parse();
    crate::interrupt::install();
    if let Err(e) = preflight(&cli.command) {
        eprintln!("error: {e}");
        return e.exit_code();
    }
    match cli.command {
        Command::Run {
            scenarios,
            out,
            dt,
            set,
            quiet,
            checkpoint_every,
            resume,
            force,
            slurm,
            submit,
        } => {
            let req = RunRequest {
                files: scenarios,
                out_dir: resume.clone().unwrap_or(out),
                dt_s: dt,
                overrides: set,
                checkpoint_every_s: checkpoint_every,
                resume: resume.is_some(),
                force,
                quiet,
            };
            run_command(&req, slurm.then_some(&submit))
        }
        Command::Bench {
            out,
            quick,
            grains,
            sedimentation_only,
        } => bench(
            &out,
            crate::bench::Options {
                quick,
                grains,
                sedimentation_only,
            },
        ),
        Command::Fit(args) => exit_code(crate::fit::main(&args), |lines| {
            for l in &lines {
                println!("{l}");
            }
        }),
        Command::Sweep(args) if args.slurm.is_some() => code(crate::slurm::sweep(&args)),
        Command::Sweep(args) => exit_code(crate::sweep::main(&args), |()| {}),
        Command::Reduce {
            readings,
            template,
            standard,
            hydrometer,
            out,
        } => reduce(readings, template.as_deref(), standard, hydrometer, &out),
        Command::Laws {
            spheres,
            fluids,
            out,
        } => laws(crate::laws::Request {
            files: spheres.zip(fluids),
            out_dir: out,
        }),
        Command::Invert {
            readings,
            model,
            bins,
            diameters_um,
            lambda,
            resolution,
            repeats,
            seed,
            bounds,
            out,
        } => invert(crate::invert::Request {
            files: readings,
            options: crate::invert::InvertOptions {
                model,
                bins,
                diameters_um,
                lambda,
                resolution,
                repeats,
                seed,
                bounds,
            },
            out_dir: out,
        }),
    }
}

/// `settle reduce`: prints the readings template (no readings file), or reduces the readings
/// and writes the results into OUT; the exit code.
fn reduce(
    readings: Option<std::path::PathBuf>,
    template: Option<&str>,
    standard: Option<String>,
    hydrometer: Option<String>,
    out: &std::path::Path,
) -> i32 {
    let Some(readings) = readings else {
        return match crate::reduce::template(template.unwrap_or_default()) {
            Ok(t) => {
                print!("{t}");
                0
            }
            Err(e) => {
                eprintln!("error: {e}");
                e.exit_code()
            }
        };
    };
    let opts = crate::reduce::ReduceOptions {
        standard,
        hydrometer,
    };
    let done = crate::reduce::reduce(readings, &opts).and_then(|r| {
        let dest = r.write(out)?;
        Ok((r.lines(&dest), r.warnings))
    });
    outcome(done, |(lines, warnings)| (lines, warnings))
}

/// `settle run` (or with `--slurm`, its submission): checks `--checkpoint-every`, then runs; the
/// exit code.
fn run_command(req: &RunRequest, slurm: Option<&crate::slurm::Submit>) -> i32 {
    if let Some(every) = req
        .checkpoint_every_s
        .filter(|s| !(s.is_finite() && *s > 0.0))
    {
        eprintln!("error: --checkpoint-every {every} is out of range: allowed > 0 s of wall time");
        return crate::error::EXIT_BAD_INPUT;
    }
    match slurm {
        Some(submit) => code(crate::slurm::run(req, submit)),
        None => run(req),
    }
}

/// The checks of every command before any work ([`crate::io::arg::preflight`]): its input
/// files exist, are files and are given once; its `--out` is a folder one can write in.
fn preflight(command: &Command) -> Result<(), crate::error::Error> {
    use std::path::Path;
    let each = |what: &'static str, files: &'_ [PathBuf]| -> Vec<(&'static str, PathBuf)> {
        files.iter().map(|f| (what, f.clone())).collect()
    };
    let (inputs, out): (Vec<(&str, PathBuf)>, Option<&Path>) = match command {
        Command::Run {
            scenarios,
            out,
            resume,
            ..
        } => (
            each("scenario", scenarios),
            resume.is_none().then_some(out.as_path()),
        ),
        Command::Bench { out, .. } => (Vec::new(), Some(out)),
        Command::Fit(a) => {
            let mut v = each("scenario", a.scenario.as_slice());
            v.extend(each("measurements", a.measured.as_slice()));
            let calibration = a.scenario.is_some();
            (v, calibration.then_some(a.out.as_path()))
        }
        Command::Sweep(a) if a.merge.is_empty() => (
            each("scenario", &a.scenarios),
            Some(a.out.as_deref().unwrap_or(Path::new("out"))),
        ),
        Command::Sweep(_) => (Vec::new(), None),
        Command::Reduce { readings, out, .. } => match readings {
            Some(r) => (each("readings", std::slice::from_ref(r)), Some(out)),
            None => (Vec::new(), None),
        },
        Command::Laws {
            spheres,
            fluids,
            out,
        } => {
            let mut v = each("spheres", spheres.as_slice());
            v.extend(each("fluids", fluids.as_slice()));
            (v, Some(out))
        }
        Command::Invert { readings, out, .. } => (each("readings", readings), Some(out)),
    };
    let inputs: Vec<(&str, &Path)> = inputs.iter().map(|(w, p)| (*w, p.as_path())).collect();
    crate::io::arg::preflight(&inputs, out)
}

/// `settle run`: runs the scenario files, prints their reports; the exit code.
fn run(req: &RunRequest) -> i32 {
    exit_code(run_files(req), |reports| {
        if !req.quiet {
            for r in &reports {
                print_report(r);
            }
            if reports.len() > 1 {
                print_overall(&reports);
            }
        }
    })
}

/// The exit code of a command's result: 0 after `on_ok`, else the error printed and its class.
fn exit_code<T>(result: Result<T, crate::error::Error>, on_ok: impl FnOnce(T)) -> i32 {
    match result {
        Ok(v) => {
            on_ok(v);
            0
        }
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    }
}

/// The exit code a command returned, or its error printed and its class.
fn code(result: Result<i32, crate::error::Error>) -> i32 {
    match result {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    }
}

/// `settle bench`: runs the benchmarks, prints them and writes OUT/bench/bench.csv (a folder
/// of its own, checked before the benchmarks run); the exit code.
fn bench(out: &std::path::Path, opts: crate::bench::Options) -> i32 {
    let owner = crate::io::Owner::new("bench", "the benchmarks");
    let checked = crate::io::owner::check_out_dir(out)
        .and_then(|()| crate::io::owner::check_writable(out))
        .and_then(|()| crate::io::owner::check_owned(&out.join("bench"), &owner));
    if let Err(e) = checked {
        eprintln!("error: {e}");
        return e.exit_code();
    }
    let figs = match crate::bench::project_root().and_then(|r| crate::bench::run(&r, opts)) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("error: {e}");
            return e.exit_code();
        }
    };
    for f in &figs {
        println!(
            "{:<16} {:<34} {:>14} {}",
            f.benchmark,
            f.quantity,
            crate::io::fmt::g(f.value),
            f.unit
        );
    }
    let mut outputs = crate::io::Outputs::new();
    outputs.set_owner(owner);
    let written = crate::bench::to_csv(&figs)
        .map_err(|e| crate::error::Error::Io(out.join("bench"), e))
        .and_then(|bytes| {
            outputs.file("bench.csv", bytes);
            outputs.write_folder(out, "bench")
        });
    match written {
        Ok(dir) => {
            println!("-> {}", dir.join("bench.csv").display());
            0
        }
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    }
}

/// `settle laws`: runs and prints the table; the exit code.
fn laws(req: crate::laws::Request) -> i32 {
    outcome(crate::laws::run(&req), |r| (&r.lines, &[]))
}

/// `settle invert`: runs and prints the summary and warnings; the exit code.
fn invert(req: crate::invert::Request) -> i32 {
    outcome(crate::invert::run(&req), |r| (&r.lines, &r.warnings))
}

/// Prints a command's lines and warnings (`text` picks them from its report) and returns 0, or
/// prints its error and returns the error's exit code.
fn outcome<T>(
    result: Result<T, crate::error::Error>,
    text: impl Fn(&T) -> (&[String], &[String]),
) -> i32 {
    match result {
        Ok(r) => {
            let (lines, warnings) = text(&r);
            for l in lines {
                println!("{l}");
            }
            for w in warnings {
                println!("  warning: {w}");
            }
            0
        }
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    }
}

/// The error statistics over every file of the run (the `all` row of combined/metrics.csv).
fn print_overall(reports: &[FileReport]) {
    let all: Vec<_> = reports
        .iter()
        .flat_map(|r| r.results.iter().cloned())
        .collect();
    if let Some(s) = crate::scenes::free_settling::output::metrics(&all).last() {
        println!(
            "all files {}",
            crate::scenes::free_settling::console::stats_line(s)
        );
    }
}

fn print_report(r: &FileReport) {
    for line in table(r) {
        println!("{line}");
    }
    for w in &r.warnings {
        println!("  warning: {w}");
    }
}

/// The console table of one file's run: a title line, then the kind's result (free settling:
/// one row per sphere with the Reynolds number; drop: entry speed, settling distance and stop
/// time per sphere and fall height; other kinds: their summary lines). Every number in the
/// format of [`crate::io::fmt`].
pub fn table(r: &FileReport) -> Vec<String> {
    use crate::io::fmt::g;
    let s = &r.prepared.common;
    if r.results.is_empty() {
        let mut out = vec![format!(
            "{} ({} s wall) -> {}",
            s.name,
            g(r.wall_time_s),
            r.out.display()
        )];
        out.extend(r.lines.iter().map(|l| format!("  {l}")));
        return out;
    }
    let mut out = vec![format!(
        "{} ({} bodies, dt = {} s, {}, {} s wall) -> {}",
        s.name,
        r.results.len(),
        crate::io::fmt::short(s.time.dt_s),
        s.time.integrator.name(),
        g(r.wall_time_s),
        r.out.display()
    )];
    if let crate::scenario::SceneSpec::FreeSettling(f) = &r.prepared.scene {
        out.extend(crate::scenes::free_settling::console::rows(
            &r.results, f.entry,
        ));
    }
    out
}
