//! The console summary of a funnel pour and the engine settings it records in `run.toml`.

use super::{Census, Geometry, Place, RepeatResult};
use crate::engine::EngineSettings;
use crate::io::fmt::{g, short};
use crate::scenario::FunnelPourSpec;
use crate::scenario::Submergence;
use crate::scenes::Prepared;

/// The engine settings of the scene: [`EngineSettings::for_scene`] for the smallest ball and the
/// free-fall speed from the top of the column to the bottom, √(2 g z_top), with the contacts'
/// friction.
pub fn engine_settings(p: &Prepared, f: &FunnelPourSpec) -> EngineSettings {
    let s = &p.common;
    let geo = Geometry::of(f);
    let d_min = p
        .spheres
        .iter()
        .map(|c| c.spec.diameter_m)
        .fold(f64::INFINITY, f64::min);
    let v_max = (2.0 * s.gravity_m_s2 * geo.column_top_z_m).sqrt();
    let mut settings = EngineSettings::for_scene(d_min, v_max);
    settings.friction = f.contacts.friction;
    settings
}

/// The first line: repeats, balls, time step, submergence and wall time (`wall_s` in all, s).
fn header(p: &Prepared, f: &FunnelPourSpec, results: &[RepeatResult], wall_s: f64) -> String {
    let s = &p.common;
    let reps = results.len();
    let mean_wall = results.iter().map(|r| r.wall_time_s).sum::<f64>() / reps as f64;
    format!(
        "funnel pour: {reps} repeat(s) × {} balls, dt = {} s, {} submergence; wall time {} s ({} s per repeat, {} threads)",
        f.funnel.count,
        short(s.time.dt_s),
        match s.submergence {
            Submergence::Full => "full",
            Submergence::Partial => "partial",
        },
        g(wall_s),
        g(mean_wall),
        rayon::current_num_threads()
    )
}

/// The census at `count_time_s` over the repeats that reached it (a range when they differ).
fn at_count_time(n: usize, count_time_s: f64, results: &[RepeatResult]) -> Option<String> {
    let counted: Vec<Census> = results.iter().filter_map(|r| r.census_at_count).collect();
    if counted.is_empty() {
        return None;
    }
    let rng = |f: &dyn Fn(&Census) -> usize| {
        let lo = counted.iter().map(f).min().unwrap_or(0);
        let hi = counted.iter().map(f).max().unwrap_or(0);
        if lo == hi {
            format!("{lo}")
        } else {
            format!("{lo}–{hi}")
        }
    };
    Some(format!(
        "at t = {} s: {} of {n} balls in the paste, {} in the domain (f-EDEM Fig. 20: all 68 balls generated only for dt ≤ 1.04e-5 s)",
        short(count_time_s),
        rng(&|c| c.paste),
        rng(&|c| c.in_domain())
    ))
}

/// Where the balls of every repeat are at the end, summed.
fn at_the_end(n: usize, results: &[RepeatResult]) -> String {
    let finals: Vec<Census> = results.iter().map(|r| r.census()).collect();
    let sum = |f: &dyn Fn(&Census) -> usize| finals.iter().map(f).sum::<usize>();
    format!(
        "at the end: {} of {} balls in the paste; {} still in the funnel, {} falling, {} escaped over the rim ({} beside the cylinder, {} out of the domain), {} lost through a wall",
        sum(&|c| c.paste),
        n * results.len(),
        sum(&|c| c.funnel),
        sum(&|c| c.falling),
        sum(&|c| c.outside + c.away),
        sum(&|c| c.outside),
        sum(&|c| c.away),
        sum(&|c| c.lost)
    )
}

/// The heights of the ball centres in the paste over all repeats (range, 5–95 %, median, cm).
fn z_spread(results: &[RepeatResult]) -> Option<String> {
    let mut zs: Vec<f64> = results
        .iter()
        .flat_map(|r| r.balls.iter())
        .filter(|b| b.place == Place::Paste)
        .map(|b| b.position_m[2])
        .collect();
    if zs.is_empty() {
        return None;
    }
    zs.sort_by(f64::total_cmp);
    let q = |f: f64| zs[((zs.len() - 1) as f64 * f).round() as usize] * 100.0;
    Some(format!(
        "ball centres in the paste at Z = {}–{} cm above the bottom (5–95 %: {}–{} cm, median {} cm; f-EDEM Fig. 21: 8.5–13.5 cm)",
        g(q(0.0)),
        g(q(1.0)),
        g(q(0.05)),
        g(q(0.95)),
        g(q(0.5))
    ))
}

/// How well the balls had settled when the outlet opened, and when the runs ended.
fn settling(results: &[RepeatResult]) -> String {
    let slowest_fill = results
        .iter()
        .map(|r| r.max_speed_at_opening_m_s)
        .fold(0.0, f64::max);
    format!(
        "largest ball speed when the outlet opened: {} m/s; runs ended at t = {}–{} s",
        g(slowest_fill),
        g(results
            .iter()
            .map(|r| r.end_time_s)
            .fold(f64::INFINITY, f64::min)),
        g(results.iter().map(|r| r.end_time_s).fold(0.0, f64::max))
    )
}

/// The summary lines of a funnel pour of the (non-empty) `results`, `wall_s` of wall time in all.
pub fn lines(
    p: &Prepared,
    spec: &FunnelPourSpec,
    results: &[RepeatResult],
    wall_s: f64,
) -> Vec<String> {
    let f = &spec.funnel;
    let mut lines = vec![header(p, spec, results, wall_s)];
    lines.extend(
        f.count_time_s
            .and_then(|tc| at_count_time(f.count, tc, results)),
    );
    lines.push(at_the_end(f.count, results));
    lines.extend(z_spread(results));
    lines.push(settling(results));
    lines
}
