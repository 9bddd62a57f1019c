//! `settle sweep`: argument handling, sharding, merging and reporting around [`crate::sweep`].

use crate::contact::rayleigh_time_s;
use crate::dynamics::Integrator;
use crate::output::{num, StagedDir};
use crate::run::{prepare, Prepared, RunError};
use crate::scenario::ScenarioError;
use crate::sweep::{self, Row};
use std::path::{Path, PathBuf};

/// Arguments of `settle sweep` (see `settle sweep --help`).
#[derive(Clone, Debug, Default)]
pub struct SweepArgs {
    /// Scenario files.
    pub scenarios: Vec<PathBuf>,
    /// Explicit dt list, s.
    pub dt: Vec<f64>,
    /// `LO:HI` range.
    pub dt_range: Option<String>,
    /// Steps per decade of the range.
    pub per_decade: u32,
    /// Integrator names.
    pub integrators: Vec<String>,
    /// Tolerance of the recommended dt.
    pub tol: Option<f64>,
    /// Output folder.
    pub out: PathBuf,
    /// `I/N` shard.
    pub shard: Option<String>,
    /// Folders with parts to merge.
    pub merge: Vec<PathBuf>,
    /// `KEY=VALUE` overrides.
    pub overrides: Vec<String>,
    /// Print nothing.
    pub quiet: bool,
}

fn arg_err(msg: String) -> RunError {
    RunError::Scenario(ScenarioError {
        file: PathBuf::from("<command line>"),
        key: None,
        message: msg,
    })
}

fn parse_shard(s: &str) -> Result<(usize, usize), RunError> {
    let bad = || {
        arg_err(format!(
            "--shard `{s}`: expected I/N with 1 ≤ I ≤ N, e.g. 2/8"
        ))
    };
    let (i, n) = s.split_once('/').ok_or_else(bad)?;
    let (i, n): (usize, usize) = (i.parse().map_err(|_| bad())?, n.parse().map_err(|_| bad())?);
    if i == 0 || n == 0 || i > n {
        return Err(bad());
    }
    Ok((i, n))
}

fn integrators(names: &[String], p: &Prepared) -> Result<Vec<Integrator>, RunError> {
    if names.is_empty() {
        let from_file = p
            .scenario
            .sweep
            .as_ref()
            .map(|s| s.integrators.clone())
            .unwrap_or_default();
        return Ok(if from_file.is_empty() {
            Integrator::ALL.to_vec()
        } else {
            from_file
        });
    }
    names
        .iter()
        .map(|n| {
            Integrator::ALL
                .iter()
                .copied()
                .find(|i| i.name() == n.trim())
                .ok_or_else(|| {
                    arg_err(format!(
                        "--integrator `{n}`: allowed explicit, implicit, exponential"
                    ))
                })
        })
        .collect()
}

fn dts(args: &SweepArgs, p: &Prepared) -> Result<Vec<f64>, RunError> {
    let mut v = args.dt.clone();
    if let Some(r) = &args.dt_range {
        let bad = || {
            arg_err(format!(
                "--dt-range `{r}`: expected LO:HI with 0 < LO < HI, e.g. 1e-8:1e-1"
            ))
        };
        let (lo, hi) = r.split_once(':').ok_or_else(bad)?;
        let (lo, hi): (f64, f64) = (
            lo.parse().map_err(|_| bad())?,
            hi.parse().map_err(|_| bad())?,
        );
        if !(lo > 0.0 && hi > lo && hi.is_finite()) || args.per_decade == 0 {
            return Err(bad());
        }
        v.extend(sweep::dt_range(lo, hi, args.per_decade));
    }
    if v.is_empty() {
        v = p
            .scenario
            .sweep
            .as_ref()
            .map(|s| s.dt_s.clone())
            .unwrap_or_default();
    }
    if v.is_empty() {
        return Err(arg_err(format!(
            "{}: no time steps: give --dt, --dt-range, or a [sweep] dt_s list in the scenario",
            p.path.display()
        )));
    }
    for dt in &v {
        if !(*dt > 0.0 && dt.is_finite()) {
            return Err(arg_err(format!(
                "time step {dt} is out of range: allowed dt > 0 s"
            )));
        }
    }
    Ok(v)
}

/// Runs `settle sweep`.
pub fn sweep(args: &SweepArgs) -> Result<(), RunError> {
    if !args.merge.is_empty() {
        return merge(args);
    }
    if args.scenarios.is_empty() {
        return Err(arg_err("give scenario files, or --merge DIR...".into()));
    }
    let prepared: Vec<Prepared> = args
        .scenarios
        .iter()
        .map(|f| prepare(f, None, &args.overrides))
        .collect::<Result<_, _>>()
        .map_err(RunError::Scenario)?;
    let shard = args.shard.as_deref().map(parse_shard).transpose()?;
    for p in &prepared {
        let cases = sweep::grid(&integrators(&args.integrators, p)?, &dts(args, p)?);
        let bar = progress_bar(cases.len(), &p.scenario.name, args.quiet);
        let tick = || bar.inc(1);
        let name = format!("{}_sweep", p.scenario.name);
        let io = |e: std::io::Error| RunError::Io(p.path.clone(), e);
        match shard {
            Some((i, n)) => {
                let part = sweep::shard(&cases, i, n);
                bar.set_length(part.len() as u64);
                let rows = sweep::run_cases_with(p, &part, &tick);
                bar.finish_and_clear();
                let dir = args.out.join(&name);
                std::fs::create_dir_all(&dir).map_err(io)?;
                let file = dir.join(format!("sweep_part_{i}_of_{n}.csv"));
                let tmp = dir.join(format!(".sweep_part_{i}_of_{n}.csv.tmp"));
                sweep::write_rows(&tmp, &rows).map_err(io)?;
                std::fs::rename(&tmp, &file).map_err(io)?;
                if !args.quiet {
                    println!(
                        "{}: shard {i}/{n} ({} rows) -> {}",
                        p.scenario.name,
                        rows.len(),
                        file.display()
                    );
                }
            }
            None => {
                let mut rows = sweep::run_cases_with(p, &cases, &tick);
                bar.finish_and_clear();
                sweep::finish(&mut rows);
                let stage = StagedDir::new(&args.out, &name).map_err(io)?;
                write_results(
                    stage.path("").as_path(),
                    &rows,
                    Some(p),
                    tol(args, Some(p)),
                    args.quiet,
                )
                .map_err(|e| RunError::Other(format!("{}: {e}", p.path.display())))?;
                let dest = stage.commit().map_err(io)?;
                if !args.quiet {
                    println!("  -> {}", dest.display());
                }
            }
        }
    }
    Ok(())
}

/// A progress bar on stderr (cases done, rate, ETA): see [`crate::progress::bar`].
fn progress_bar(len: usize, name: &str, quiet: bool) -> indicatif::ProgressBar {
    crate::progress::bar(len as u64, name, "cases, {per_sec},", quiet)
}

fn tol(args: &SweepArgs, p: Option<&Prepared>) -> f64 {
    args.tol
        .or_else(|| p.and_then(|p| p.scenario.sweep.as_ref().and_then(|s| s.tol)))
        .unwrap_or(0.01)
}

fn merge(args: &SweepArgs) -> Result<(), RunError> {
    let mut rows: Vec<Row> = Vec::new();
    let mut parts = 0;
    for dir in &args.merge {
        let rd = std::fs::read_dir(dir).map_err(|e| RunError::Io(dir.clone(), e))?;
        let mut files: Vec<PathBuf> = rd
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with("sweep_part_") && n.ends_with(".csv"))
            })
            .collect();
        files.sort();
        for f in files {
            rows.extend(sweep::read_rows(&f).map_err(|e| RunError::Io(f.clone(), e))?);
            parts += 1;
        }
    }
    if parts == 0 {
        return Err(arg_err(
            "--merge: no sweep_part_*.csv in the given folders".into(),
        ));
    }
    sweep::finish(&mut rows);
    let prepared = args
        .scenarios
        .first()
        .map(|f| prepare(f, None, &args.overrides))
        .transpose()
        .map_err(RunError::Scenario)?;
    let dest = if args.out == Path::new("out") {
        args.merge[0].clone()
    } else {
        args.out.clone()
    };
    std::fs::create_dir_all(&dest).map_err(|e| RunError::Io(dest.clone(), e))?;
    write_results(
        &dest,
        &rows,
        prepared.as_ref(),
        tol(args, prepared.as_ref()),
        args.quiet,
    )
    .map_err(|e| RunError::Other(format!("{}: {e}", dest.display())))?;
    if !args.quiet {
        println!(
            "merged {parts} parts ({} rows) -> {}",
            rows.len(),
            dest.join("sweep.csv").display()
        );
    }
    Ok(())
}

fn write_results(
    dir: &Path,
    rows: &[Row],
    p: Option<&Prepared>,
    tol: f64,
    quiet: bool,
) -> Result<(), String> {
    sweep::write_rows(&dir.join("sweep.csv"), rows).map_err(|e| e.to_string())?;
    let sums = sweep::summarise(rows);
    let title = p
        .map(|p| p.scenario.name.clone())
        .unwrap_or_else(|| "sweep".into());
    sweep::charts(dir, &title, &sums)?;
    // Rayleigh-time rule (f-EDEM eq. 22) for the first sphere with elastic properties.
    let rayleigh = p.and_then(|p| {
        p.spheres.iter().find_map(|c| {
            Some(rayleigh_time_s(
                c.spec.diameter_m,
                c.spec.density_kg_m3,
                c.spec.youngs_modulus_pa?,
                c.spec.poisson_ratio?,
            ))
        })
    });
    let mut w =
        csv::Writer::from_path(dir.join("recommended_dt.csv")).map_err(|e| e.to_string())?;
    w.write_record([
        "integrator",
        "recommended_dt_s",
        "tol",
        "rayleigh_time_s",
        "rayleigh_20pct_dt_s",
    ])
    .map_err(|e| e.to_string())?;
    if !quiet {
        println!("{title}: {} cases", sums.len());
        println!(
            "  {:<12} {:>10} {:>9} {:>10} {:>9}  max |error vs finest| per quantity",
            "integrator", "dt_s", "status", "wall_s", "steps"
        );
        for s in &sums {
            let errs: Vec<String> = s
                .errors
                .iter()
                .map(|(q, (f, _))| format!("{q}={f:.1e}"))
                .collect();
            println!(
                "  {:<12} {:>10.1e} {:>9} {:>10.4} {:>9}  {}",
                s.integrator,
                s.dt_s,
                if s.stable { "stable" } else { "UNSTABLE" },
                s.wall_time_s,
                s.steps,
                errs.join(" ")
            );
        }
    }
    for integ in Integrator::ALL {
        if !sums.iter().any(|s| s.integrator == integ.name()) {
            continue;
        }
        let rec = sweep::recommended_dt(&sums, integ.name(), tol);
        w.write_record([
            integ.name().to_string(),
            rec.map(num).unwrap_or_default(),
            num(tol),
            rayleigh.map(num).unwrap_or_default(),
            rayleigh.map(|r| num(0.2 * r)).unwrap_or_default(),
        ])
        .map_err(|e| e.to_string())?;
        if !quiet {
            let r = rec
                .map(|d| format!("{d:.1e} s"))
                .unwrap_or_else(|| "none in the grid".into());
            print!(
                "  recommended dt ({}, error vs finest < {tol}): {r}",
                integ.name()
            );
            if let Some(tr) = rayleigh {
                print!(
                    "   [Rayleigh time {tr:.3e} s; 20 % rule {:.3e} s]",
                    0.2 * tr
                );
            }
            println!();
        }
    }
    w.flush().map_err(|e| e.to_string())
}
