//! The `settle` command line.

use crate::run::{run_files, FileReport, RunRequest};
use crate::scenes::free_settling::output::{rel_error, rel_error_vs_force_balance};
use clap::{Parser, Subcommand};
use std::path::PathBuf;

/// Simulate solid particles settling in Newtonian and Bingham fluids.
///
/// Exit codes: 0 success; 2 bad input (a scenario, an input file or a command-line argument;
/// nothing was run or written); 3 unstable run (nothing was written); 4 I/O or environment (a
/// file or folder could not be read or written); 130 interrupted by Ctrl-C or SIGTERM (a
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
    /// Each run writes summary.csv (one row per body), timeseries.csv (if recorded), probes.csv
    /// (velocities at [measure].velocity_at_s), metrics.csv and terminal_velocity.svg (when
    /// measured velocities exist), and run.toml (effective parameters, version, dt, steps, wall
    /// time). With several files, OUT/combined/ holds the joint summary and metrics.
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
        #[arg(long, allow_negative_numbers = true)]
        dt: Option<f64>,
        /// Override any scenario key, e.g. --set fluid.viscosity_pa_s=0.002 --set physics=ideal-stokes
        /// or --set 'spheres[0].diameter_m=2e-4'. Repeatable.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Print nothing but errors (no progress bar).
        #[arg(long, short)]
        quiet: bool,
        /// Write a checkpoint every SECONDS of wall time (and always when interrupted).
        #[arg(long, value_name = "SECONDS")]
        checkpoint_every: Option<f64>,
        /// Continue the interrupted or killed run whose output folder is DIR (its scenario files
        /// and options come from DIR/checkpoint/request.toml).
        #[arg(long, value_name = "DIR", conflicts_with_all = ["scenarios", "out", "dt", "set"])]
        resume: Option<PathBuf>,
        /// Run even if the cost estimate exceeds 24 h of wall time, 8 GB of memory or 4 GB of
        /// outputs.
        #[arg(long)]
        force: bool,
    },
    /// Benchmarks (wall times and ratios) written to OUT/bench.csv.
    Bench {
        /// Output folder.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Shorter loops and no full sweep (a quick smoke run).
        #[arg(long)]
        quick: bool,
    },
    /// Time-step sensitivity sweep: run every (integrator, dt) and compare.
    ///
    /// Writes OUT/<name>_sweep/sweep.csv (one row per integrator, dt, body and quantity: value,
    /// reference, error against the reference and against the finest stable dt, wall time,
    /// steps, status stable/unstable with the reason), quantity_vs_dt.svg, speed_accuracy.svg and
    /// recommended_dt.csv, and prints the recommended dt beside the Rayleigh-time rule.
    /// Defaults come from the scenario's [sweep] table. Kinds free_settling, drop and funnel_pour
    /// can be swept; other kinds, like bad options, exit 2 before anything is written.
    Sweep(crate::sweep::Args),
    /// Reduce laboratory hydrometer readings by ASTM D422 or D7928 (percent finer vs diameter).
    ///
    /// READINGS.csv holds the test's figures as `# key = value` lines (standard, hydrometer,
    /// dry_mass_g, specific_gravity, meniscus_correction, blank_reading, and for D7928 the
    /// hydrometer's measured h_r1_cm, h_r2_cm, bulb_volume_ml, cylinder_area_cm2), then the
    /// columns time_min (or time_s), reading, temperature_c [, blank_reading]. Writes
    /// OUT/<stem>_reduced/percent_finer.csv, percent_finer.svg and reduce.toml. Bad input (a
    /// missing figure, a reading off the scale, times out of order, a temperature outside the
    /// standard's range) exits 2 naming the file, row and column; nothing is written.
    /// See docs/commands/reduce.md.
    Reduce {
        /// The readings file (CSV).
        readings: PathBuf,
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
}

/// Parses the arguments, runs, and returns the process exit code.
pub fn main() -> i32 {
    let cli = Cli::parse();
    crate::interrupt::install();
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
        } => {
            if let Some(every) = checkpoint_every.filter(|s| !(s.is_finite() && *s > 0.0)) {
                eprintln!(
                    "error: --checkpoint-every {every} is out of range: allowed > 0 s of wall time"
                );
                return crate::error::EXIT_BAD_INPUT;
            }
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
            match run_files(&req) {
                Ok(reports) => {
                    if !quiet {
                        for r in &reports {
                            print_report(r);
                        }
                        if reports.len() > 1 {
                            print_overall(&reports);
                        }
                    }
                    0
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    e.exit_code()
                }
            }
        }
        Command::Bench { out, quick } => {
            let figs = match crate::bench::project_root().and_then(|r| crate::bench::run(&r, quick))
            {
                Ok(f) => f,
                Err(e) => {
                    eprintln!("error: {e}");
                    return e.exit_code();
                }
            };
            for f in &figs {
                println!(
                    "{:<16} {:<34} {:>14.6e} {}",
                    f.benchmark, f.quantity, f.value, f.unit
                );
            }
            let path = out.join("bench.csv");
            if let Err(e) =
                std::fs::create_dir_all(&out).and_then(|_| crate::bench::write(&path, &figs))
            {
                let e = crate::error::Error::Io(path, e);
                eprintln!("error: {e}");
                return e.exit_code();
            }
            println!("-> {}", path.display());
            0
        }
        Command::Sweep(args) => match crate::sweep::main(&args) {
            Ok(()) => 0,
            Err(e) => {
                eprintln!("error: {e}");
                e.exit_code()
            }
        },
        Command::Reduce {
            readings,
            standard,
            hydrometer,
            out,
        } => {
            let req = crate::reduce::Request {
                file: readings,
                standard,
                hydrometer,
                out_dir: out,
            };
            match crate::reduce::run(&req) {
                Ok(r) => {
                    for l in &r.lines {
                        println!("{l}");
                    }
                    for w in &r.warnings {
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
            "all files vs measured: N = {}, mean |err| = {:.1}%, median = {:.1}%, max = {:.1}%, bias = {:+.1}%, within 10%: {:.0}%, within 25%: {:.0}%",
            s.n,
            100.0 * s.mean_abs,
            100.0 * s.median_abs,
            100.0 * s.max_abs,
            100.0 * s.bias,
            100.0 * s.within_10pct,
            100.0 * s.within_25pct
        );
    }
}

fn print_report(r: &FileReport) {
    print_table(r);
    for w in &r.warnings {
        println!("  warning: {w}");
    }
}

fn print_table(r: &FileReport) {
    let s = &r.prepared.scenario;
    if r.results.is_empty() {
        println!(
            "{} ({:.3} s wall) -> {}",
            s.name,
            r.wall_time_s,
            r.out.display()
        );
        for l in &r.lines {
            println!("  {l}");
        }
        return;
    }
    println!(
        "{} ({} bodies, dt = {:e} s, {}, {:.3} s wall) -> {}",
        s.name,
        r.results.len(),
        s.time.dt_s,
        s.time.integrator.name(),
        r.wall_time_s,
        r.out.display()
    );
    println!(
        "  {:<8} {:>9} {:>8} {:>10} {:>11} {:>11} {:>9} {:>10} {:>10}",
        "sphere", "d_mm", "rho", "v_meas", "v_sim", "v_balance", "err", "sim/bal-1", "regime"
    );
    for x in &r.results {
        let sp = &x.case.spec;
        println!(
            "  {:<8} {:>9.4} {:>8.0} {:>10} {:>11.5e} {:>11.5e} {:>9} {:>10.2e} {:>10}",
            x.case.id,
            sp.diameter_m * 1e3,
            sp.density_kg_m3,
            sp.v_measured_m_s
                .map(|v| format!("{v:.4}"))
                .unwrap_or("-".into()),
            x.v_simulated_m_s,
            x.v_force_balance_m_s,
            rel_error(x)
                .map(|e| format!("{:+.1}%", 100.0 * e))
                .unwrap_or("-".into()),
            rel_error_vs_force_balance(x),
            x.regime.label()
        );
    }
    let stats = crate::scenes::free_settling::output::metrics(&r.results);
    if let Some(all) = stats.last() {
        println!(
            "  vs measured: N = {}, mean |err| = {:.1}%, median = {:.1}%, max = {:.1}%, bias = {:+.1}%, within 10%: {:.0}%, within 25%: {:.0}%",
            all.n,
            100.0 * all.mean_abs,
            100.0 * all.median_abs,
            100.0 * all.max_abs,
            100.0 * all.bias,
            100.0 * all.within_10pct,
            100.0 * all.within_25pct
        );
    }
}
