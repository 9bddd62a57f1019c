//! `settle bench`: wall-time benchmarks written to CSV (never timed tests). Ratios come from one
//! run on one machine: our integrator step against the analytic floor, large against small dt.

use crate::dynamics::{advance, Integrator};
use crate::error::Error;
use crate::fluid::{sphere_mass_kg, DragLaw, SphereDrag};
use crate::run::prepare;
use crate::scenes::free_settling::{self, RunOptions};
use crate::scenes::Prepared;
use nalgebra::Vector3;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// One benchmark figure.
#[derive(Clone, Debug)]
pub struct Figure {
    /// Benchmark name.
    pub benchmark: String,
    /// What was measured.
    pub quantity: String,
    /// Value.
    pub value: f64,
    /// Unit.
    pub unit: String,
}

fn fig(b: &str, q: &str, v: f64, u: &str) -> Figure {
    Figure {
        benchmark: b.into(),
        quantity: q.into(),
        value: v,
        unit: u.into(),
    }
}

/// The project folder holding `scenarios/` (the benchmarks run its scenario files): the current
/// directory if it holds them, else the folder this binary was built from. An I/O or
/// environment error naming both if neither does.
pub fn project_root() -> Result<PathBuf, Error> {
    let probe = Path::new("scenarios/valentik_susp1.toml");
    let cwd = std::env::current_dir().unwrap_or_else(|_| PathBuf::from("."));
    let built = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    for root in [&cwd, &built] {
        if root.join(probe).is_file() {
            return Ok(root.clone());
        }
    }
    Err(Error::Io(
        cwd.join(probe),
        std::io::Error::new(
            std::io::ErrorKind::NotFound,
            format!(
                "the benchmark scenarios are neither here nor in {} (the source folder settle \
                 was built from)",
                built.display()
            ),
        ),
    ))
}

fn valentik(root: &Path) -> Result<Vec<Prepared>, Error> {
    (1..=6)
        .map(|n| {
            prepare(
                &root.join(format!("scenarios/valentik_susp{n}.toml")),
                None,
                &[],
            )
            .map_err(Error::BadInput)
        })
        .collect()
}

/// The free-settling scene of `p`, or a bad input naming its kind (the benchmarks of free
/// spheres load free-settling and drop scenarios).
fn spheres_scene(p: &Prepared) -> Result<free_settling::Scene<'_>, Error> {
    free_settling::Scene::of(p).ok_or_else(|| {
        Error::bad_input(
            &p.path,
            Some("kind"),
            format!(
                "`{}`: allowed kind = \"free_settling\" or \"drop\"",
                p.common.kind.name()
            ),
        )
    })
}

fn run_all(ps: &[Prepared], dt: f64, integ: Integrator) -> Result<(f64, u64), Error> {
    let t0 = Instant::now();
    let mut steps = 0;
    for p in ps {
        let opts = RunOptions {
            dt_s: dt,
            integrator: integ,
            timeseries: false,
        };
        let r = free_settling::run(spheres_scene(p)?, &p.spheres, opts)
            .map_err(|u| Error::Unstable(p.path.clone(), u))?;
        steps += r.iter().map(|x| x.steps).sum::<u64>();
    }
    Ok((t0.elapsed().as_secs_f64(), steps))
}

/// Runs the benchmarks of `opts`; `root` is the project folder (for the scenario files).
pub fn run(root: &Path, opts: Options) -> Result<Vec<Figure>, Error> {
    let quick = opts.quick;
    let mut out = Vec::new();
    if opts.sedimentation_only {
        sedimentation(root, quick, opts.grains, &mut out)?;
        return Ok(out);
    }
    stokes_step(quick, &mut out);
    bingham_step(quick, &mut out);
    let ps = valentik(root)?;
    valentik_dt(&ps, quick, &mut out)?;
    paste_drops(root, &mut out)?;
    sedimentation(root, quick, opts.grains, &mut out)?;
    transient_step(root, quick, &mut out)?;
    if !quick {
        valentik_sweep(&ps, &mut out)?;
    }
    Ok(out)
}

/// Step cost of the exponential integrator against the analytic floor.
fn stokes_step(quick: bool, out: &mut Vec<Figure>) {
    let n = if quick { 1_000_000 } else { 20_000_000 };
    // 1. Integrator step cost against the analytic floor (Stokes sphere of f-EDEM Table 1).
    let d = 1e-4;
    let drag = SphereDrag::new(
        DragLaw::Stokes {
            viscosity_pa_s: 1e-3,
        },
        d,
        1000.0,
    );
    let m = sphere_mass_kg(d, 2700.0);
    let w = Vector3::new(0.0, 0.0, -(m - sphere_mass_kg(d, 1000.0)) * 9.81);
    let dt = 1e-5;
    let t0 = Instant::now();
    let mut v = Vector3::zeros();
    for _ in 0..n {
        v = advance(Integrator::Exponential, &drag, m, &w, black_box(&v), dt).velocity_m_s;
    }
    black_box(v);
    let ours = t0.elapsed().as_secs_f64() / n as f64 * 1e9;
    let (vt, tau) = (
        -w.z / (3.0 * std::f64::consts::PI * 1e-3 * d),
        m / (3.0 * std::f64::consts::PI * 1e-3 * d),
    );
    let e = (-dt / tau).exp();
    let t0 = Instant::now();
    let mut s = 0.0f64;
    let mut x = 0.0f64;
    for _ in 0..n {
        let s1 = vt + (black_box(s) - vt) * e;
        x += vt * dt + (s - vt) * tau * (1.0 - e);
        s = s1;
    }
    black_box((s, x));
    let floor = t0.elapsed().as_secs_f64() / n as f64 * 1e9;
    out.push(fig("stokes_step", "exponential_step_ns", ours, "ns"));
    out.push(fig("stokes_step", "analytic_floor_step_ns", floor, "ns"));
    out.push(fig("stokes_step", "ratio_ours_to_floor", ours / floor, "-"));
}

/// Step cost of the exponential integrator on a Bingham sphere.
fn bingham_step(quick: bool, out: &mut Vec<Figure>) {
    let n = if quick { 1_000_000 } else { 20_000_000 };
    // 2. Bingham step cost (Newton solve of the set-valued implicit equation + exponential).
    let drag_b = SphereDrag::new(
        DragLaw::Bingham {
            yield_stress_pa: 30.5,
            plastic_viscosity_pa_s: 0.0131,
        },
        0.0254,
        1280.0,
    );
    let mb = sphere_mass_kg(0.0254, 6142.0);
    let wb = Vector3::new(0.0, 0.0, -(mb - sphere_mass_kg(0.0254, 1280.0)) * 9.81);
    let t0 = Instant::now();
    let mut v = Vector3::zeros();
    for _ in 0..n {
        v = advance(
            Integrator::Exponential,
            &drag_b,
            mb,
            &wb,
            black_box(&v),
            1e-4,
        )
        .velocity_m_s;
    }
    black_box(v);
    out.push(fig(
        "bingham_step",
        "exponential_step_ns",
        t0.elapsed().as_secs_f64() / n as f64 * 1e9,
        "ns",
    ));
}

/// The 121 Valentik spheres at the default dt, and large against small dt.
fn valentik_dt(ps: &[Prepared], quick: bool, out: &mut Vec<Figure>) -> Result<(), Error> {
    // 3. All 121 Valentik spheres, default dt (1e-3 s), and large against small dt.
    let (wall, steps) = run_all(ps, 1e-3, Integrator::Exponential)?;
    out.push(fig("valentik_121", "wall_time_dt_1e-3_s", wall, "s"));
    out.push(fig("valentik_121", "steps_dt_1e-3", steps as f64, "steps"));
    let (w_big, _) = run_all(ps, 1e-1, Integrator::Exponential)?;
    let small = if quick { 1e-4 } else { 1e-5 };
    let (w_small, s_small) = run_all(ps, small, Integrator::Exponential)?;
    out.push(fig("valentik_121", "wall_time_dt_1e-1_s", w_big, "s"));
    out.push(fig(
        "valentik_121",
        &format!("wall_time_dt_{small:e}_s"),
        w_small,
        "s",
    ));
    out.push(fig(
        "valentik_121",
        &format!("steps_dt_{small:e}"),
        s_small as f64,
        "steps",
    ));
    out.push(fig(
        "valentik_121",
        "ratio_small_dt_to_large_dt_wall",
        w_small / w_big.max(1e-9),
        "-",
    ));

    Ok(())
}

/// The 18 paste drops at the recommended dt against f-EDEM's.
fn paste_drops(root: &Path, out: &mut Vec<Figure>) -> Result<(), Error> {
    // 4. Paste drops: 18 balls, dt = 1e-3 s (the recommended step) against f-EDEM's 5e-6 s.
    let paste_file = root.join("scenarios/paste_single_ball.toml");
    let paste = prepare(&paste_file, None, &[]).map_err(Error::BadInput)?;
    for dt in [1e-3, 5e-6] {
        let t0 = Instant::now();
        let opts = RunOptions {
            dt_s: dt,
            integrator: Integrator::Exponential,
            timeseries: false,
        };
        let r = free_settling::run(spheres_scene(&paste)?, &paste.spheres, opts)
            .map_err(|u| Error::Unstable(paste_file.clone(), u))?;
        let steps: u64 = r.iter().map(|x| x.steps).sum();
        out.push(fig(
            "paste_18_drops",
            &format!("wall_time_dt_{dt:e}_s"),
            t0.elapsed().as_secs_f64(),
            "s",
        ));
        out.push(fig(
            "paste_18_drops",
            &format!("steps_dt_{dt:e}"),
            steps as f64,
            "steps",
        ));
    }

    Ok(())
}

/// What `settle bench` runs.
#[derive(Clone, Copy, Debug, Default)]
pub struct Options {
    /// Shorter loops and no full sweep (a quick smoke run).
    pub quick: bool,
    /// Representative grains of the sedimentation benchmarks (default 20 000 with `quick`, else
    /// 100 000).
    pub grains: Option<usize>,
    /// Only the sedimentation benchmarks.
    pub sedimentation_only: bool,
}

/// Peak and current resident set size of this process, bytes (`VmHWM`, `VmRSS` of
/// /proc/self/status; None where there is no /proc).
fn rss_bytes() -> Option<(f64, f64)> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let kb = |key: &str| -> Option<f64> {
        let line = s.lines().find(|l| l.starts_with(key))?;
        line.split_whitespace().nth(1)?.parse::<f64>().ok()
    };
    Some((kb("VmHWM:")? * 1024.0, kb("VmRSS:")? * 1024.0))
}

/// CPU time of this process so far (user + system, all threads), s: fields 14 and 15 of
/// /proc/self/stat in clock ticks of 1/100 s (USER_HZ). None where there is no /proc.
fn cpu_time_s() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/stat").ok()?;
    let rest = s.rsplit_once(") ")?.1;
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// Resets the peak resident set size of this process to the current one (Linux ≥ 4.0: `5` to
/// /proc/self/clear_refs). False where that is not possible.
fn reset_peak_rss() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// The sedimentation cylinder, sample 5, 1440 min, at `grains` representative grains (default
/// 20 000 quick, 100 000 otherwise): ideal-Stokes, full physics without contacts, and (not
/// quick) full physics as the scenario has it (contacts and lubrication). Each gives its wall
/// time, the grain-steps of the free update per second (of the free update's own wall time and
/// of the whole run's), the wall time of every stage of the step loop, and the peak resident
/// set size over the run per grain (the peak is reset before the setup; no snapshots).
fn sedimentation(
    root: &Path,
    quick: bool,
    grains: Option<usize>,
    out: &mut Vec<Figure>,
) -> Result<(), Error> {
    // 5. Sedimentation cylinder, sample 5, 1440 min.
    let n = grains.unwrap_or(if quick { 20_000 } else { 100_000 });
    for (label, physics, contacts) in [
        ("ideal-stokes", "ideal-stokes", None),
        ("full-nocontacts", "full", Some(false)),
        ("full", "full", Some(true)),
    ] {
        if quick && label == "full" {
            continue;
        }
        let mut ov = vec![
            format!("physics={physics}"),
            format!("sample.particles={n}"),
            "sample.snapshot_times_s=[]".to_string(),
        ];
        if contacts == Some(false) {
            ov.push("sample.contacts=false".into());
            ov.push("sample.lubrication=false".into());
        }
        let name = format!("sedimentation_sample5_{label}");
        sedimentation_case(root, &name, &ov, contacts == Some(true), out)?;
    }
    Ok(())
}

/// One run of [`sedimentation`] with the overrides `ov`, its figures under `name` (with the
/// contact statistics if `contacts`).
fn sedimentation_case(
    root: &Path,
    name: &str,
    ov: &[String],
    contacts: bool,
    out: &mut Vec<Figure>,
) -> Result<(), Error> {
    let p = prepare(&root.join("scenarios/sedimentation_sample5.toml"), None, ov)
        .map_err(Error::BadInput)?;
    let peak_reset = reset_peak_rss();
    let rss0 = rss_bytes();
    let su = crate::scenes::sedimentation::setup(&p)?;
    let cpu0 = cpu_time_s();
    let t0 = Instant::now();
    let st = crate::scenes::sedimentation::simulate(
        &su,
        crate::scenes::sedimentation::State::initial(&su),
        &[],
        &mut (),
    );
    let wall = t0.elapsed().as_secs_f64();
    let cpu = cpu0.zip(cpu_time_s()).map(|(c0, c1)| c1 - c0);
    let rss1 = rss_bytes();
    let ng = su.grains.len() as f64;
    sedimentation_figures(name, ng, &st, wall, cpu, out);
    if let (true, Some((_, before)), Some((peak, _))) = (peak_reset, rss0, rss1) {
        out.push(fig(name, "peak_rss_bytes", peak, "B"));
        out.push(fig(name, "peak_rss_bytes_per_grain", peak / ng, "B/grain"));
        out.push(fig(
            name,
            "peak_rss_above_start_bytes_per_grain",
            (peak - before) / ng,
            "B/grain",
        ));
    }
    if contacts {
        let c = &st.contacts;
        out.push(fig(name, "contact_pairs", c.pairs as f64, "pairs"));
        out.push(fig(
            name,
            "contact_grains_handed",
            c.grains as f64,
            "grains",
        ));
        out.push(fig(
            name,
            "contact_rapier_steps",
            c.rapier_steps as f64,
            "steps",
        ));
        out.push(fig(name, "contact_wall_time_s", c.wall_s, "s"));
    }
    Ok(())
}

/// The time figures of a run of [`sedimentation`] of `ng` grains ending in `st`, after `wall`
/// seconds of wall time and `cpu` of CPU time (where known).
fn sedimentation_figures(
    name: &str,
    ng: f64,
    st: &crate::scenes::sedimentation::State,
    wall: f64,
    cpu: Option<f64>,
    out: &mut Vec<Figure>,
) {
    let sg = &st.stages;
    out.push(fig(name, "grains", ng, "grains"));
    out.push(fig(name, "wall_time_1440min_s", wall, "s"));
    if let Some(cpu) = cpu {
        // On a shared machine the wall time counts the other processes too.
        out.push(fig(name, "cpu_time_1440min_s", cpu, "s"));
        // The suspended grain-steps per CPU second of the whole run (every stage, all
        // threads): what load on a shared machine changes least.
        let per_cpu = sg.grain_steps as f64 / cpu.max(1e-9);
        out.push(fig(
            name,
            "run_grain_steps_per_cpu_s",
            per_cpu,
            "grain-steps/CPU-s",
        ));
    }
    out.push(fig(name, "steps", st.steps as f64, "steps"));
    // N × steps: the grain-steps of an update that visits every grain at every step (the
    // figure of issue 17's 5.5e7 grain-steps/s).
    let all = ng * st.steps as f64 / wall.max(1e-9);
    out.push(fig(
        name,
        "all_grains_times_steps_per_s",
        all,
        "grain-steps/s",
    ));
    let gs = sg.grain_steps as f64;
    out.push(fig(name, "free_update_grain_steps", gs, "grain-steps"));
    let per_update = gs / sg.free_update_s.max(1e-9);
    out.push(fig(
        name,
        "free_update_grain_steps_per_s",
        per_update,
        "grain-steps/s",
    ));
    let per_wall = gs / wall.max(1e-9);
    out.push(fig(
        name,
        "run_grain_steps_per_s",
        per_wall,
        "grain-steps/s",
    ));
    for (q, v) in [
        ("stage_step_size_s", sg.step_size_s),
        ("stage_voidage_s", sg.voidage_s),
        ("stage_free_update_s", sg.free_update_s),
        ("stage_fault_scan_s", sg.fault_scan_s),
        ("stage_contacts_s", sg.contacts_s),
        ("stage_deposit_events_s", sg.deposit_events_s),
    ] {
        out.push(fig(name, q, v, "s"));
    }
}

/// The cost of the transient forces on a free body's step (issue 16): ten Cate's E4 sphere
/// (Schiller–Naumann drag, exponential integrator) falling in a deep column (no bottom, no wall
/// factor) for 10 s at dt = 1e-5 s (quick: 1e-4 s), quasi-steady against added mass + the
/// history force (Basset, Mei & Adrian at the terminal Re, at the current Re; the last includes
/// building its table of fits), measured back to back in one run (two alternating
/// rounds, the faster of each).
fn transient_step(root: &Path, quick: bool, out: &mut Vec<Figure>) -> Result<(), Error> {
    let dt = if quick { 1e-4 } else { 1e-5 };
    let file = root.join("scenarios/ten_cate_e4.toml");
    let time = |history: Option<&str>| -> Result<(f64, u64, usize), Error> {
        let mut ov = vec![
            "container.height_m=1000".to_string(),
            "time.end_s=10".to_string(),
            "transient.wall=off".to_string(),
        ];
        match history {
            Some("mei-adrian-current") => {
                ov.push("transient.history=mei-adrian".to_string());
                ov.push("transient.history_reynolds=current".to_string());
            }
            Some(h) => ov.push(format!("transient.history={h}")),
            None => ov.push("transient.added_mass=false".to_string()),
        }
        let p = prepare(&file, Some(dt), &ov).map_err(Error::BadInput)?;
        let states = match history {
            Some(_) => free_settling::history_states(spheres_scene(&p)?, &p.spheres).unwrap_or(0),
            None => 2,
        };
        let opts = RunOptions {
            dt_s: dt,
            integrator: Integrator::Exponential,
            timeseries: false,
        };
        let t0 = Instant::now();
        let r = free_settling::run(spheres_scene(&p)?, &p.spheres, opts)
            .map_err(|u| Error::Unstable(file.clone(), u))?;
        let wall = t0.elapsed().as_secs_f64();
        Ok((wall, r.iter().map(|x| x.steps).sum(), states))
    };
    // Two rounds, alternating, the faster of each (warm caches, less noise from the machine).
    let mut best = [(f64::INFINITY, 0u64, 0usize); 4];
    let cases = [
        None,
        Some("basset"),
        Some("mei-adrian"),
        Some("mei-adrian-current"),
    ];
    for _ in 0..2 {
        for (i, h) in cases.into_iter().enumerate() {
            let r = time(h)?;
            if r.0 < best[i].0 {
                best[i] = r;
            }
        }
    }
    let [(w_qs, n_qs, _), (w_b, n_b, s_b), (w_m, n_m, s_m), (w_c, n_c, _)] = best;
    let b = "transient_free_body";
    out.push(fig(b, &format!("steps_dt_{dt:e}"), n_qs as f64, "steps"));
    out.push(fig(
        b,
        "quasi_steady_step_ns",
        w_qs / n_qs as f64 * 1e9,
        "ns",
    ));
    let per_step_qs = w_qs / n_qs as f64;
    let history = [
        ("basset", Some(s_b), w_b / n_b as f64),
        ("mei_adrian", Some(s_m), w_m / n_m as f64),
        ("mei_adrian_current_re", None, w_c / n_c as f64),
    ];
    for (name, states, per_step) in history {
        if let Some(states) = states {
            out.push(fig(b, &format!("{name}_states"), states as f64, "states"));
        }
        out.push(fig(b, &format!("{name}_step_ns"), per_step * 1e9, "ns"));
        out.push(fig(
            b,
            &format!("ratio_{name}_to_quasi_steady"),
            per_step / per_step_qs,
            "-",
        ));
    }
    Ok(())
}

/// The full Valentik sweep.
fn valentik_sweep(ps: &[Prepared], out: &mut Vec<Figure>) -> Result<(), Error> {
    // 6. The full Valentik sweep: 6 scenarios × 10 dt (1e-5 … 3e-1 s) × 3 integrators.
    let t0 = Instant::now();
    let mut cases = 0;
    for p in ps {
        let sw = p.common.sweep.as_ref().ok_or_else(|| {
            Error::bad_input(
                &p.path,
                Some("sweep"),
                "missing: the benchmark sweeps its dt",
            )
        })?;
        let grid = crate::sweep::grid(&Integrator::ALL, &sw.dt_s);
        cases += grid.len();
        let mut rows = crate::sweep::run_cases(p, &grid)?;
        crate::sweep::finish(&mut rows);
    }
    out.push(fig("valentik_sweep", "cases", cases as f64, "cases"));
    out.push(fig(
        "valentik_sweep",
        "wall_time_s",
        t0.elapsed().as_secs_f64(),
        "s",
    ));
    Ok(())
}

/// The figures as the bytes of `bench.csv` (`benchmark,quantity,value,unit`).
pub fn to_csv(figs: &[Figure]) -> std::io::Result<Vec<u8>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(["benchmark", "quantity", "value", "unit"])
        .map_err(std::io::Error::other)?;
    for f in figs {
        w.write_record([
            f.benchmark.clone(),
            f.quantity.clone(),
            format!("{}", f.value),
            f.unit.clone(),
        ])
        .map_err(std::io::Error::other)?;
    }
    w.into_inner()
        .map_err(|e| std::io::Error::other(e.to_string()))
}
