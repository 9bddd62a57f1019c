//! One repeat of the pour, as named stages: build the world (`initial_repeat`), then step by
//! step open the outlet, step the world, track wall breaches and record the census
//! (`RepeatRun::advance`), until the end time or until every ball in play has rested; with
//! checkpoints (`Checkpoints`) and resumption ([`run_repeat_with`]). [`simulate_with`] runs the
//! repeats in parallel.

use super::census::{Ball, Census, Place, RepeatResult, Sample};
use super::placement::place_balls;
use super::setup::Geometry;
use crate::dynamics::Unstable;
use crate::engine::{dim3, BodyId, EngineSettings};
use crate::error::Error;
use crate::scenario::FunnelPourSpec;
use crate::scenes::{Prepared, RunContext};
use rapier3d_f64::prelude::ColliderHandle;
use std::time::Instant;

/// Time over which every ball must stay slower than `rest_speed_m_s` before a run stops early, s.
pub const REST_WINDOW_S: f64 = 0.05;
/// Default interval of the time series when `record.every_s` is not set, s.
pub const DEFAULT_RECORD_EVERY_S: f64 = 0.01;

/// Everything a repeat needs to continue from where it is: saved in its checkpoint (part
/// `repeat<i>`, see [`crate::checkpoint`]). The field order is the checkpoint's format.
#[derive(serde::Serialize, serde::Deserialize)]
struct RepeatState {
    world: dim3::World,
    ids: Vec<BodyId>,
    diameters: Vec<f64>,
    plug: ColliderHandle,
    /// Positions at the end of the last step (for the wall-breach test).
    prev: Vec<[f64; 3]>,
    /// Balls that went through a wall.
    breached: Vec<bool>,
    samples: Vec<Sample>,
    census_at_count: Option<Census>,
    max_speed_at_opening: f64,
    /// Step since which every ball in play is slower than the rest speed.
    rest_since: Option<u64>,
    /// Steps taken.
    k: u64,
    /// Wall time spent before the last resumption, s.
    wall_before_s: f64,
}

/// How a repeat ended.
pub enum RepeatOutcome {
    /// It ran to its end.
    Done(RepeatResult),
    /// Ctrl-C/SIGTERM stopped it (its state is in the checkpoint, if checkpoints are on).
    Interrupted,
}

/// Runs repeat `index` (seed `seed`) of a funnel pour from its start.
pub fn run_repeat(
    p: &Prepared,
    f: &FunnelPourSpec,
    index: usize,
    seed: u64,
) -> Result<RepeatResult, Error> {
    match run_repeat_with(p, f, index, seed, &RunContext::default())? {
        RepeatOutcome::Done(r) => Ok(r),
        RepeatOutcome::Interrupted => Err(Error::InterruptedUnwritten(p.path.clone())),
    }
}

/// Centre of body `id`, m.
fn position(world: &dim3::World, id: BodyId) -> [f64; 3] {
    let x = world.position_m(id);
    [x[0], x[1], x[2]]
}

/// The state of repeat `index` (seed `seed`) at t = 0: the world built, the balls placed.
fn initial_repeat(p: &Prepared, f: &FunnelPourSpec, seed: u64) -> Result<RepeatState, Error> {
    let s = &p.common;
    let ct = &f.contacts;
    let geo = Geometry::of(f);
    let g = s.gravity_m_s2;
    let n = f.funnel.count;
    let specs: Vec<_> = (0..n)
        .map(|i| &p.spheres[i % p.spheres.len()].spec)
        .collect();
    let diameters: Vec<f64> = specs.iter().map(|sp| sp.diameter_m).collect();
    let d_min = diameters.iter().copied().fold(f64::INFINITY, f64::min);
    let centres = place_balls(&geo, &diameters, seed)
        .map_err(|e| Error::bad_input(&p.path, Some("funnel.column_height_m"), e.to_string()))?;

    // Free fall from the top of the column to the bottom bounds every speed of the scene.
    let v_max = (2.0 * g * geo.column_top_z_m).sqrt();
    let mut settings = EngineSettings::for_scene(d_min, v_max);
    settings.friction = ct.friction;
    let mut world = dim3::World::new(settings, g);
    world.add_floor(0.0);
    let plug = super::setup::add_walls(&mut world, &geo, ct.restitution, ct.friction);
    let ids: Vec<_> = specs
        .iter()
        .zip(&centres)
        .map(|(sp, x)| {
            world.add_sphere(dim3::FluidBody::at_rest(
                dim3::Vector::new(x[0], x[1], x[2]),
                sp.diameter_m,
                sp.density_kg_m3,
                s.sphere_drag(sp.diameter_m),
                g,
            ))
        })
        .collect();
    world.set_restitution_law(ct.restitution_law());
    world.set_rolling_resistance(ct.rolling_resistance);
    world.set_added_mass_coefficient(s.added_mass_coefficient());
    world.set_free_surface(dim3::FreeSurface {
        height_m: geo.paste_height_m,
        radius_m: Some(geo.cylinder_radius_m),
        submergence: s.submergence,
    });

    let prev: Vec<[f64; 3]> = ids.iter().map(|&id| position(&world, id)).collect();
    Ok(RepeatState {
        breached: vec![false; n],
        prev,
        world,
        ids,
        diameters,
        plug,
        samples: Vec::new(),
        census_at_count: None,
        max_speed_at_opening: 0.0,
        rest_since: None,
        k: 0,
        wall_before_s: 0.0,
    })
}

/// The step schedule of a repeat, from the scenario. Step k ends at t = (k − n_fill) dt.
#[derive(Clone, Copy, Debug)]
struct Schedule {
    /// Time step, s.
    dt_s: f64,
    /// Steps of the fill (balls settling on the plug); the outlet opens before step n_fill + 1.
    n_fill: u64,
    /// Steps after the opening, at most.
    n_run: u64,
    /// The step at `funnel.count_time_s`, if set.
    count_step: Option<u64>,
    /// Steps between two rows of the time series.
    every: u64,
    /// Steps every ball in play must stay slower than `rest_speed_m_s` to stop early.
    rest_steps: u64,
    /// Rest speed, m/s.
    rest_speed_m_s: f64,
}

impl Schedule {
    fn of(p: &Prepared, spec: &FunnelPourSpec) -> Self {
        let s = &p.common;
        let f = &spec.funnel;
        let dt = s.time.dt_s;
        let n_fill = (f.fill_time_s / dt).round() as u64;
        Self {
            dt_s: dt,
            n_fill,
            n_run: (s.time.end_s / dt).round().max(1.0) as u64,
            count_step: f.count_time_s.map(|tc| n_fill + (tc / dt).round() as u64),
            every: ((s.record.every_s.unwrap_or(DEFAULT_RECORD_EVERY_S) / dt).round() as u64)
                .max(1),
            rest_steps: (REST_WINDOW_S / dt).round() as u64,
            rest_speed_m_s: f.rest_speed_m_s,
        }
    }

    /// Time at the end of step `k`, s (negative during the fill).
    fn time_s(&self, k: u64) -> f64 {
        (k as f64 - self.n_fill as f64) * self.dt_s
    }
}

/// A repeat being run: its state, schedule and the fixed data to observe its balls.
struct RepeatRun<'a> {
    p: &'a Prepared,
    index: usize,
    seed: u64,
    geo: Geometry,
    schedule: Schedule,
    ids: Vec<BodyId>,
    diameters: Vec<f64>,
    state: RepeatState,
}

impl<'a> RepeatRun<'a> {
    fn new(
        p: &'a Prepared,
        f: &FunnelPourSpec,
        index: usize,
        seed: u64,
        state: RepeatState,
    ) -> Self {
        Self {
            p,
            index,
            seed,
            geo: Geometry::of(f),
            schedule: Schedule::of(p, f),
            ids: state.ids.clone(),
            diameters: state.diameters.clone(),
            state,
        }
    }

    fn finished(&self) -> bool {
        self.state.k >= self.schedule.n_fill + self.schedule.n_run
    }

    /// Places of the balls and the largest speed of those still in play (in the paste, falling
    /// or in the funnel: balls that escaped over the rim do not hold the run).
    fn observe(&self) -> (Vec<Place>, f64) {
        let world = &self.state.world;
        let mut vmax: f64 = 0.0;
        let places = self
            .ids
            .iter()
            .zip(&self.diameters)
            .zip(&self.state.breached)
            .map(|((&id, &d), &lost)| {
                let place = if lost {
                    Place::Lost
                } else {
                    self.geo.place(&position(world, id), d)
                };
                if matches!(place, Place::Paste | Place::Falling | Place::Funnel) {
                    vmax = vmax.max(world.velocity_m_s(id).norm());
                }
                place
            })
            .collect();
        (places, vmax)
    }

    /// Marks the balls that went through a wall during the last step (or turned non-finite) and
    /// remembers the positions for the next step.
    fn track_breaches(&mut self) {
        let st = &mut self.state;
        for ((&id, &d), (from, lost)) in self
            .ids
            .iter()
            .zip(&self.diameters)
            .zip(st.prev.iter_mut().zip(st.breached.iter_mut()))
        {
            let to = position(&st.world, id);
            *lost = *lost || self.geo.breached(from, &to, d) || !to.iter().all(|c| c.is_finite());
            *from = to;
        }
    }

    /// The engine's fault, named with the repeat.
    fn unstable(&self, mut u: Unstable) -> Error {
        u.body = format!("repeat {} (seed {}) {}", self.index, self.seed, u.body);
        Error::Unstable(self.p.path.clone(), u)
    }

    /// One step: opens the outlet after the fill, steps the world, tracks breaches and records.
    /// Returns true when every ball in play has rested long enough to stop.
    fn advance(&mut self) -> Result<bool, Error> {
        let sch = self.schedule;
        if self.state.k == sch.n_fill {
            self.state.max_speed_at_opening = self.observe().1;
            let plug = self.state.plug;
            self.state.world.remove_fixed_collider(plug);
        }
        let integrator = self.p.common.time.integrator;
        if let Err(u) = self.state.world.step(sch.dt_s, integrator) {
            return Err(self.unstable(u));
        }
        self.state.k += 1;
        self.track_breaches();
        Ok(self.record())
    }

    /// Records the step just taken: a time-series row every `every` steps, the census at the
    /// count time, and the rest test after it. Returns true when the run may stop.
    fn record(&mut self) -> bool {
        let sch = self.schedule;
        let k = self.state.k;
        let sample_now = k.is_multiple_of(sch.every);
        let count_now = sch.count_step == Some(k);
        let after_count = sch.count_step.is_none_or(|c| k >= c) && k > sch.n_fill;
        if !(sample_now || count_now || after_count) {
            return false;
        }
        let (places, vmax) = self.observe();
        let census = Census::of(places.iter().copied());
        let st = &mut self.state;
        if sample_now {
            st.samples.push(Sample {
                time_s: sch.time_s(k),
                census,
                max_speed_m_s: vmax,
            });
        }
        if count_now {
            st.census_at_count = Some(census);
        }
        if after_count {
            if vmax < sch.rest_speed_m_s {
                let since = *st.rest_since.get_or_insert(k);
                return k - since >= sch.rest_steps;
            }
            st.rest_since = None;
        }
        false
    }

    /// The result of the repeat as it stands, `wall_s` of wall time spent since the last
    /// resumption.
    fn result(mut self, wall_s: f64) -> RepeatResult {
        let places = self.observe().0;
        let world = &self.state.world;
        let balls = self
            .ids
            .iter()
            .zip(&self.diameters)
            .zip(places)
            .map(|((&id, &d), place)| Ball {
                diameter_m: d,
                position_m: position(world, id),
                speed_m_s: world.velocity_m_s(id).norm(),
                place,
            })
            .collect();
        RepeatResult {
            index: self.index,
            seed: self.seed,
            balls,
            census_at_count: self.state.census_at_count,
            max_speed_at_opening_m_s: self.state.max_speed_at_opening,
            end_time_s: self.schedule.time_s(self.state.k),
            steps: self.state.k,
            wall_time_s: self.state.wall_before_s + wall_s,
            samples: std::mem::take(&mut self.state.samples),
        }
    }
}

/// The checkpoint parts of one repeat: `repeat<i>` (its state) and `repeat<i>.done` (its
/// result), when `ctx` has checkpoints.
struct Checkpoints<'a> {
    p: &'a Prepared,
    ctx: &'a RunContext,
    part: String,
    done_part: String,
}

/// Where a repeat starts when resumed.
enum Resumed {
    /// Already finished.
    Done(RepeatResult),
    /// From its saved state.
    From(Box<RepeatState>),
}

impl<'a> Checkpoints<'a> {
    fn new(p: &'a Prepared, ctx: &'a RunContext, index: usize) -> Self {
        Self {
            p,
            ctx,
            part: format!("repeat{index}"),
            done_part: format!("repeat{index}.done"),
        }
    }

    /// The saved result or state of the repeat, when resuming with checkpoints.
    fn resume(&self) -> Result<Option<Resumed>, Error> {
        let (Some(c), true) = (&self.ctx.checkpoints, self.ctx.resume) else {
            return Ok(None);
        };
        let name = &self.p.common.name;
        if let Some(r) = c.load::<RepeatResult>(name, &self.done_part)? {
            return Ok(Some(Resumed::Done(r)));
        }
        Ok(c.load::<RepeatState>(name, &self.part)?
            .map(|st| Resumed::From(Box::new(st))))
    }

    /// Saves the state, its wall time including the `wall_s` spent since the last resumption.
    fn save(&self, state: &mut RepeatState, wall_s: f64) -> Result<(), Error> {
        if let Some(c) = &self.ctx.checkpoints {
            let before = state.wall_before_s;
            state.wall_before_s += wall_s;
            let r = c.save(&self.p.common.name, &self.part, &*state);
            state.wall_before_s = before;
            r.map_err(|e| Error::Io(self.p.path.clone(), e))?;
        }
        Ok(())
    }

    /// Saves the result of the finished repeat.
    fn save_done(&self, result: &RepeatResult) -> Result<(), Error> {
        if let Some(c) = &self.ctx.checkpoints {
            c.save(&self.p.common.name, &self.done_part, result)
                .map_err(|e| Error::Io(self.p.path.clone(), e))?;
        }
        Ok(())
    }
}

/// [`run_repeat`] with checkpoints and resumption as `ctx` says: continues from the repeat's
/// checkpoint when resuming, saves its state every checkpoint period and when interrupted, and
/// saves its result (part `repeat<i>.done`) once finished, so that a resumed run does not redo
/// it.
pub fn run_repeat_with(
    p: &Prepared,
    f: &FunnelPourSpec,
    index: usize,
    seed: u64,
    ctx: &RunContext,
) -> Result<RepeatOutcome, Error> {
    let wall = Instant::now();
    let checkpoints = Checkpoints::new(p, ctx, index);
    let state = match checkpoints.resume()? {
        Some(Resumed::Done(r)) => return Ok(RepeatOutcome::Done(r)),
        Some(Resumed::From(st)) => *st,
        None => initial_repeat(p, f, seed)?,
    };
    let mut run = RepeatRun::new(p, f, index, seed, state);
    let mut timer = ctx.checkpoints.as_ref().map(|c| c.timer());
    while !run.finished() {
        if crate::interrupt::requested() {
            checkpoints.save(&mut run.state, wall.elapsed().as_secs_f64())?;
            return Ok(RepeatOutcome::Interrupted);
        }
        if timer.as_mut().is_some_and(|t| t.due()) {
            checkpoints.save(&mut run.state, wall.elapsed().as_secs_f64())?;
        }
        if run.advance()? {
            break;
        }
    }
    let result = run.result(wall.elapsed().as_secs_f64());
    checkpoints.save_done(&result)?;
    Ok(RepeatOutcome::Done(result))
}

/// Runs every repeat of a funnel pour in parallel (rayon); results in repeat order.
#[cfg(test)]
pub fn simulate(p: &Prepared, f: &FunnelPourSpec) -> Result<Vec<RepeatResult>, Error> {
    let (results, interrupted) = simulate_with(p, f, &RunContext::default())?;
    if interrupted {
        return Err(Error::InterruptedUnwritten(p.path.clone()));
    }
    Ok(results)
}

/// [`simulate`] with checkpoints, resumption and progress as `ctx` says. Returns the finished
/// repeats in repeat order, and whether Ctrl-C/SIGTERM stopped some (they are then missing).
pub fn simulate_with(
    p: &Prepared,
    f: &FunnelPourSpec,
    ctx: &RunContext,
) -> Result<(Vec<RepeatResult>, bool), Error> {
    use rayon::prelude::*;
    let r = &f.repeats;
    let bar = crate::progress::bar(r.count as u64, &p.common.name, "repeats,", ctx.quiet);
    let outcomes: Vec<RepeatOutcome> = (0..r.count)
        .into_par_iter()
        .map(|i| {
            let o = run_repeat_with(p, f, i, r.seed.wrapping_add(i as u64), ctx);
            bar.inc(1);
            o
        })
        .collect::<Result<_, _>>()?;
    bar.finish_and_clear();
    let mut interrupted = false;
    let mut results = Vec::new();
    for o in outcomes {
        match o {
            RepeatOutcome::Done(r) => results.push(r),
            RepeatOutcome::Interrupted => interrupted = true,
        }
    }
    Ok((results, interrupted))
}
