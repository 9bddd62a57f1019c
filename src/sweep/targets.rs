//! What can be swept and what each case yields. Free settling and drops (each sphere alone:
//! terminal velocity or settling distance, and the probed velocities, against their analytic or
//! force-balance references) and the funnel pour (ball census and height range of the first
//! repeat, no reference). Other kinds have no dt-sensitive quantity defined here and are
//! refused before anything runs.

use super::plan::Case;
use super::table::{rel, Row, Status};
use crate::error::Error;
use crate::scenario::{FreeSettlingSpec, FunnelPourSpec, SceneSpec};
use crate::scenes::free_settling::{self, Halt, RunOptions, SphereResult};
use crate::scenes::Prepared;
use std::time::Instant;

/// How the cases of a scenario run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target<'a> {
    /// Every sphere alone ([`free_settling::run_scene_cases`]): kinds `free_settling` and
    /// `drop`, of this spec.
    Spheres(&'a FreeSettlingSpec),
    /// The first repeat of a funnel pour ([`crate::scenes::funnel_pour::run_repeat`]), of this spec.
    FunnelPour(&'a FunnelPourSpec),
}

impl<'a> Target<'a> {
    /// The target of a prepared scenario, or a bad input (exit 2) naming its file and kind.
    pub fn of(p: &'a Prepared) -> Result<Self, Error> {
        match &p.scene {
            SceneSpec::FreeSettling(f) => Ok(Self::Spheres(f)),
            SceneSpec::FunnelPour(f) => Ok(Self::FunnelPour(f)),
            _ => Err(Error::bad_input(
                &p.path,
                Some("kind"),
                format!(
                    "a scenario of kind `{}` cannot be swept; kinds that can: {}; nothing was written",
                    p.scene.kind_name(),
                    crate::scenario::sweepable_names().join(", ")
                ),
            )),
        }
    }

    /// Runs one case and returns its rows (without `error_vs_finest`).
    pub fn run_case(self, p: &Prepared, c: &Case) -> Vec<Row> {
        match self {
            Self::Spheres(f) => spheres_case(p, f, c),
            Self::FunnelPour(f) => funnel_case(p, f, c),
        }
    }
}

/// A row of `c` with no body, quantity or value yet.
fn blank(c: &Case, status: Status, reason: String, wall_time_s: f64) -> Row {
    Row {
        integrator: c.integrator,
        dt_s: c.dt_s,
        status,
        reason,
        wall_time_s,
        steps: 0,
        body: String::new(),
        quantity: String::new(),
        value: f64::NAN,
        reference: f64::NAN,
        error_vs_reference: f64::NAN,
        error_vs_finest: f64::NAN,
    }
}

/// The measured quantities of one sphere: (name, value, reference).
fn quantities(r: &SphereResult) -> Vec<(String, f64, f64)> {
    if r.case.fall_height_m.is_some() {
        return vec![(
            "settling_distance_m".to_string(),
            r.final_bottom_depth_m,
            f64::NAN,
        )];
    }
    let mut q = vec![(
        "terminal_velocity_m_s".to_string(),
        r.v_simulated_m_s,
        r.v_force_balance_m_s,
    )];
    for (t, v, a) in &r.probes {
        q.push((format!("velocity_at_{t}s_m_s"), *v, a.unwrap_or(f64::NAN)));
    }
    q
}

/// Whether a quantity of [`Target::run_case`] comes with a reference value (analytic or force
/// balance, where the scene has one): the terminal velocity and the probed velocities.
pub fn has_reference(quantity: &str) -> bool {
    quantity == "terminal_velocity_m_s" || quantity.starts_with("velocity_at_")
}

/// One case of a free-settling or drop sweep: every sphere alone at the case's dt.
fn spheres_case(p: &Prepared, f: &FreeSettlingSpec, c: &Case) -> Vec<Row> {
    let opts = RunOptions {
        dt_s: c.dt_s,
        integrator: c.integrator,
        timeseries: false,
    };
    let t0 = Instant::now();
    let sc = free_settling::Scene {
        common: &p.common,
        spec: f,
    };
    let res = match free_settling::run_scene_cases(sc, &p.spheres, opts) {
        Ok(r) => Ok(r),
        Err(Halt::Unstable(u)) => Err(u),
        // The caller discards every row of an interrupted sweep.
        Err(Halt::Interrupted) => return Vec::new(),
    };
    let wall = t0.elapsed().as_secs_f64();
    match res {
        Ok(results) => results
            .iter()
            .flat_map(|r| {
                quantities(r).into_iter().map(|(q, v, refv)| Row {
                    steps: r.steps,
                    body: r.case.id.clone(),
                    quantity: q,
                    value: v,
                    reference: refv,
                    error_vs_reference: rel(v, refv),
                    ..blank(c, Status::Stable, String::new(), wall)
                })
            })
            .collect(),
        Err(u) => {
            // The same bodies and quantities as a stable case, with NaN values.
            let probes: Vec<String> = f
                .measure
                .as_ref()
                .map(|m| {
                    m.velocity_at_s
                        .iter()
                        .map(|t| format!("velocity_at_{t}s_m_s"))
                        .collect()
                })
                .unwrap_or_default();
            p.spheres
                .iter()
                .flat_map(|s| {
                    let names: Vec<String> = if s.fall_height_m.is_some() {
                        vec!["settling_distance_m".into()]
                    } else {
                        std::iter::once("terminal_velocity_m_s".to_string())
                            .chain(probes.iter().cloned())
                            .collect()
                    };
                    let reason = u.to_string();
                    names.into_iter().map(move |q| Row {
                        body: s.id.clone(),
                        quantity: q,
                        ..blank(c, Status::Unstable, reason.clone(), wall)
                    })
                })
                .collect()
        }
    }
}

/// One case of a funnel-pour sweep (f-EDEM Fig. 20): the first repeat (seed `repeats.seed`) at
/// the case's dt and integrator; quantities: balls in the paste and in the domain at
/// `funnel.count_time_s`, balls lost through a wall, and the lowest and highest final ball
/// centre, m. No reference value: errors are against the finest stable dt only.
fn funnel_case(p: &Prepared, f: &FunnelPourSpec, c: &Case) -> Vec<Row> {
    const QUANTITIES: [&str; 5] = [
        "balls_in_paste_at_count",
        "balls_in_domain_at_count",
        "balls_lost",
        "z_min_m",
        "z_max_m",
    ];
    // The case's step and integrator in the typed time the scene reads (its record, not
    // written by a sweep, keeps the scenario's).
    let mut q = p.clone();
    q.common.time.dt_s = c.dt_s;
    q.common.time.integrator = c.integrator;
    let t0 = Instant::now();
    let res = crate::scenes::funnel_pour::run_repeat(&q, f, 0, f.repeats.seed);
    let wall = t0.elapsed().as_secs_f64();
    let row = |status, reason: String, steps, quantity: &str, value| Row {
        steps,
        body: "all".to_string(),
        quantity: quantity.to_string(),
        value,
        ..blank(c, status, reason, wall)
    };
    match res {
        Ok(r) => {
            let census = r.census_at_count.unwrap_or_else(|| r.census());
            let (z0, z1) = r.z_range_m().unwrap_or((f64::NAN, f64::NAN));
            let values = [
                census.paste as f64,
                census.in_domain() as f64,
                census.lost as f64,
                z0,
                z1,
            ];
            QUANTITIES
                .iter()
                .zip(values)
                .map(|(name, v)| row(Status::Stable, String::new(), r.steps, name, v))
                .collect()
        }
        Err(e) => QUANTITIES
            .iter()
            .map(|name| row(Status::Unstable, e.to_string(), 0, name, f64::NAN))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_registry_says_which_kinds_have_a_target() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        for k in crate::scenario::KINDS {
            let p = crate::run::prepare(&root.join("scenarios").join(k.example), None, &[])
                .unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(Target::of(&p).is_ok(), k.sweepable, "{}", k.name);
        }
    }
}
