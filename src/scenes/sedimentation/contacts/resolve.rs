//! The contact solve of one cluster of grains over one step, in a Rapier 2D world (see
//! [`resolve`]).

use super::pairs::{may_meet, may_meet_within, Probe};
use crate::contact::RestitutionLaw;
use crate::dynamics::{advance, Integrator};
use crate::engine::dim2::{FluidBody, Vector, World};
use crate::engine::{BodyId, EngineSettings};
use crate::fluid::lubrication::{damping_n_s_m, Cutoffs};
use crate::fluid::{sphere_mass_kg, SphereDrag};
use crate::numerics::{bisect, Bisection};
use nalgebra::SVector;

/// A grain handed to the contact solve, at the start of the step. SI units.
#[derive(Clone, Copy, Debug)]
pub struct ClusterGrain {
    /// Centre, m.
    pub x_m: f64,
    /// Height of the centre, m.
    pub y_m: f64,
    /// Vertical velocity, m/s.
    pub vy_m_s: f64,
    /// Diameter, m.
    pub diameter_m: f64,
    /// Drag bound to the grain and its fluid (voidage included).
    pub drag: SphereDrag,
}

/// What the contact solve needs of the scene. SI units.
#[derive(Clone, Copy, Debug)]
pub struct ContactScene {
    /// Width B (walls at x = 0 and x = B), m.
    pub width_m: f64,
    /// Height of the floor (the bed surface), m.
    pub floor_m: f64,
    /// Grain density, kg/m³.
    pub density_kg_m3: f64,
    /// Fluid density, kg/m³ (buoyancy).
    pub fluid_density_kg_m3: f64,
    /// Gravity, m/s².
    pub gravity_m_s2: f64,
    /// Fluid viscosity for the squeeze film, Pa s.
    pub viscosity_pa_s: f64,
    /// Lubrication cut-offs (outer: also the pair-search reach); None: no lubrication.
    pub lubrication: Option<Cutoffs>,
    /// Outer reach of the pair search, h_out/a_eff.
    pub outer_fraction: f64,
    /// Integrator of the free parts of the step.
    pub integrator: Integrator,
    /// Largest travel of the fastest grain per Rapier step, in diameters of the cluster's
    /// smallest grain (the engine keeps overlaps below ~1 % of d up to ~0.1–0.5 d per step).
    pub travel_per_substep: f64,
    /// Largest relative change of a squeeze film's gap over one Rapier step (the damper uses
    /// the gap at the start of the step: a first-order error in this fraction).
    pub film_change_per_step: f64,
    /// Coulomb friction coefficient of every collider (grains, walls, bed); `[contacts]`
    /// `friction`, 0 without it.
    pub friction: f64,
    /// Restitution of every contact; `[contacts]` `restitution` (and its speed dependence), 0
    /// without it.
    pub restitution: RestitutionLaw,
}

/// What the contact solve of one cluster did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Solve {
    /// Rapier steps taken.
    pub rapier_steps: u64,
    /// The engine reported an unstable step (speed above half its cap, or non-finite): the
    /// cluster was advanced by the free update for this step instead.
    pub fallback: bool,
    /// An interrupt was requested during the solve ([`crate::interrupt::requested`], checked
    /// every [`RAPIER_STEPS_PER_INTERRUPT_CHECK`] Rapier steps): the solve stopped early and its
    /// result is incomplete; the caller must discard the step.
    pub interrupted: bool,
}

/// Rapier steps of one cluster's contact solve between two checks for an interrupt request.
pub const RAPIER_STEPS_PER_INTERRUPT_CHECK: u64 = 64;

/// A grain at the end of the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Resolved {
    /// Centre, m.
    pub x_m: f64,
    /// Height of the centre, m.
    pub y_m: f64,
    /// Vertical velocity, m/s (the horizontal one is dropped: see [`resolve`]).
    pub vy_m_s: f64,
}

fn net_weight_n(g: &ClusterGrain, sc: &ContactScene) -> f64 {
    -(sphere_mass_kg(g.diameter_m, sc.density_kg_m3)
        - sphere_mass_kg(g.diameter_m, sc.fluid_density_kg_m3))
        * sc.gravity_m_s2
}

/// Free vertical motion of a grain over `t` from (y, v): (y, v) at the end, the floor a stop.
fn free(g: &ClusterGrain, sc: &ContactScene, y: f64, v: f64, t: f64) -> (f64, f64) {
    if t <= 0.0 {
        return (y, v);
    }
    let m = sphere_mass_kg(g.diameter_m, sc.density_kg_m3);
    let w = SVector::<f64, 1>::new(net_weight_n(g, sc));
    let st = advance(sc.integrator, &g.drag, m, &w, &SVector::<f64, 1>::new(v), t);
    let y1 = (y + st.displacement_m[0]).max(sc.floor_m + 0.5 * g.diameter_m);
    (y1, st.velocity_m_s[0])
}

/// Stokes terminal speed of a grain, m/s (an upper bound of its settling speed).
fn stokes_speed_m_s(g: &ClusterGrain, sc: &ContactScene) -> f64 {
    crate::fluid::newtonian::stokes_terminal_velocity_m_s(
        g.diameter_m,
        sc.density_kg_m3,
        sc.fluid_density_kg_m3,
        sc.viscosity_pa_s,
        sc.gravity_m_s2,
    )
}

/// Resolves one cluster of grains linked by close `pairs` (indices into `grains`) over a step
/// `dt_s`, and returns their states at its end and what the solve did ([`Solve`]).
///
/// 1. **Free approach**: every grain moves exactly (vertically, as outside contacts) up to the
///    first time t_c at which a pair may come within its lubrication cut-off, widened by two
///    Rapier steps of travel (bisection on the
///    exact free paths, [`may_meet`]).
/// 2. **Contact window**: from t_c the cluster is a Rapier 2D world ([`World`]: effective-mass
///    drag inside the contact solve, discs with the scene's Coulomb friction and restitution
///    (`[contacts]`; frictionless and perfectly inelastic without it), walls at x = 0 and B,
///    the bed surface as floor) stepped so that the fastest grain moves at most `travel_per_substep` of the
///    smallest diameter per Rapier step. Before every Rapier step, each pair with a gap below
///    h_out gets the squeeze-film damper c = 6πμ a_eff²/max(h, h_in) along its line of centres
///    ([`World::add_pair_damper`], implicit in the solve), and the step is also cut so that
///    no film changes by more than `film_change_per_step` of its gap. The window opens two Rapier steps of
///    travel before the cut-off, and starts with a step of 1e-6 of a Rapier step with the
///    prediction distance floored at that margin, so that the narrow phase sees the pair (and
///    the engine drives it with the effective-mass drag) before it is close.
/// 3. **Release**: once no pair is within its cut-off and none may meet again on the free paths
///    over the rest of the step (grains on the floor excepted: they join the bed), the grains go
///    back to the exact vertical update for the rest of the step. Their horizontal velocity is
///    dropped: it relaxes within the Stokes time ρ_p d²/(18μ) ≤ 0.7 ms (70 µm), far below the
///    steps of the run.
///
/// Limits: each call builds a new world, so a contact lasting over several calls restarts
/// without its horizontal velocity, from positions clamped inside the walls; sampled at 1 ms, a
/// grain wedged against a wall was overrun that way (the tests sample by independent solves
/// from t = 0 instead). The squeeze-film approach runs 5–8 % fast even with fine film steps.
pub fn resolve(
    grains: &[ClusterGrain],
    pairs: &[(usize, usize)],
    sc: &ContactScene,
    dt_s: f64,
) -> (Vec<Resolved>, Solve) {
    let sub = Substep::of(grains, sc);
    // 1. Free approach up to the first time a pair may come within its cut-off plus two Rapier
    //    steps of travel (so that Rapier's narrow phase sees the pair, within its prediction
    //    distance, before it is within the cut-off).
    let margin = 2.0 * sub.travel_m;
    let t_c = first_contact_time(grains, pairs, sc, dt_s, margin);
    let mut state = free_all(grains, sc, t_c);
    if t_c >= dt_s {
        return (state, Solve::default());
    }
    // 2. Contact window in a Rapier world.
    let mut w = Window::new(grains, pairs, sc, &state, sub.d_min_m);
    w.register_close_pairs(margin);
    let mut t = t_c;
    let mut steps = 0u64;
    let mut warm = true;
    let mut released = false;
    while t < dt_s * (1.0 - 1e-12) {
        w.set_dampers();
        let h = if warm { 1e-6 } else { 1.0 } * sub.h_m.min(w.film_step_limit_s()).min(dt_s - t);
        warm = false;
        let Some(h_done) = w.step_with_retries(h) else {
            // The engine reported a speed above half its cap (or a non-finite state): give up
            // the contact solve of this cluster for this step, counted as a fallback.
            let solve = Solve {
                rapier_steps: steps,
                fallback: true,
                interrupted: false,
            };
            return (free_all(grains, sc, dt_s), solve);
        };
        t += h_done;
        steps += 1;
        if steps.is_multiple_of(RAPIER_STEPS_PER_INTERRUPT_CHECK) && crate::interrupt::requested() {
            let solve = Solve {
                rapier_steps: steps,
                fallback: false,
                interrupted: true,
            };
            return (state, solve);
        }
        // 3. Release once no pair is close or may meet on the free paths for the rest.
        if let Some(end) = w.try_release(dt_s - t) {
            state = end;
            released = true;
            break;
        }
    }
    if !released {
        state = w.current();
    }
    // Inside the walls (Rapier's resting penetration is ~1e-3 d).
    for (k, s) in state.iter_mut().enumerate() {
        let r = w.radius(k);
        s.x_m = s.x_m.clamp(r, sc.width_m - r);
    }
    let solve = Solve {
        rapier_steps: steps,
        fallback: false,
        interrupted: false,
    };
    (state, solve)
}

/// Rapier step size of a contact window: the fastest grain moves at most
/// `travel_per_substep` of the smallest diameter.
struct Substep {
    /// Smallest diameter of the cluster, m.
    d_min_m: f64,
    /// Largest travel per Rapier step, m.
    travel_m: f64,
    /// Rapier step, s.
    h_m: f64,
}

impl Substep {
    fn of(grains: &[ClusterGrain], sc: &ContactScene) -> Self {
        let d_min = grains
            .iter()
            .map(|g| g.diameter_m)
            .fold(f64::INFINITY, f64::min);
        let v_bound = grains
            .iter()
            .map(|g| g.vy_m_s.abs().max(stokes_speed_m_s(g, sc)))
            .fold(0.0, f64::max);
        let travel = sc.travel_per_substep * d_min;
        Self {
            d_min_m: d_min,
            travel_m: travel,
            h_m: (travel / v_bound.max(1e-300)).max(1e-12),
        }
    }
}

/// First time within the step at which a pair may come within its cut-off widened by
/// `margin_m` (bisection on the exact free paths, [`may_meet_within`]); `dt_s` if none does.
fn first_contact_time(
    grains: &[ClusterGrain],
    pairs: &[(usize, usize)],
    sc: &ContactScene,
    dt_s: f64,
    margin_m: f64,
) -> f64 {
    let probe_at = |k: usize, t: f64| {
        let g = &grains[k];
        Probe {
            x_m: g.x_m,
            y_start_m: g.y_m,
            y_end_m: free(g, sc, g.y_m, g.vy_m_s, t).0,
            radius_m: 0.5 * g.diameter_m,
        }
    };
    let meet = |i: usize, j: usize, t: f64| {
        may_meet_within(
            &probe_at(i, t),
            &probe_at(j, t),
            sc.outer_fraction,
            margin_m,
        )
    };
    // A pair within reach at the start makes the answer 0 whatever the others: tested for
    // every pair before any bisection (the same answer as testing pair by pair, without the
    // bisections of the pairs before it).
    if pairs.iter().any(|&(i, j)| meet(i, j, 0.0)) {
        return 0.0;
    }
    let mut t_c = dt_s;
    for &(i, j) in pairs {
        if !meet(i, j, t_c) {
            continue;
        }
        t_c = bisect(0.0, t_c, Bisection::halvings(40), |t| !meet(i, j, t)).0;
    }
    t_c
}

/// Every grain moved freely from the start of the step over `t`.
fn free_all(grains: &[ClusterGrain], sc: &ContactScene, t: f64) -> Vec<Resolved> {
    grains
        .iter()
        .map(|g| {
            let (y, v) = free(g, sc, g.y_m, g.vy_m_s, t);
            Resolved {
                x_m: g.x_m,
                y_m: y,
                vy_m_s: v,
            }
        })
        .collect()
}

/// The contact window of one cluster: its Rapier world and the grains' bodies in it.
struct Window<'a> {
    grains: &'a [ClusterGrain],
    pairs: &'a [(usize, usize)],
    sc: &'a ContactScene,
    world: World,
    ids: Vec<BodyId>,
    dampers: Vec<rapier2d_f64::prelude::ImpulseJointHandle>,
}

impl<'a> Window<'a> {
    /// The Rapier world (walls at x = 0 and B, the bed surface as floor) holding the grains at
    /// `state`, with the scene's friction and restitution.
    fn new(
        grains: &'a [ClusterGrain],
        pairs: &'a [(usize, usize)],
        sc: &'a ContactScene,
        state: &[Resolved],
        d_min_m: f64,
    ) -> Self {
        let v_max = grains
            .iter()
            .zip(state)
            .map(|(g, s)| s.vy_m_s.abs().max(stokes_speed_m_s(g, sc)))
            .fold(0.0, f64::max);
        let mut settings = EngineSettings::for_scene(d_min_m, v_max);
        settings.friction = sc.friction;
        // A small grain squeezed by a large one may move faster than its own terminal speed:
        // the cap (an instability detector) is set well above the cluster's largest terminal
        // speed.
        settings.max_linear_velocity_m_s = settings.max_linear_velocity_m_s.max(40.0 * v_max);
        // Undoing overlaps left by earlier steps is this solve's job, not a fault: the engine's
        // penetration check would send such clusters to the free fallback, which keeps the
        // overlap.
        settings.max_penetration_fraction = 0.0;
        let mut world = World::new(settings, sc.gravity_m_s2);
        world.add_floor(sc.floor_m);
        world.add_wall(Vector::new(0.0, 0.0), Vector::new(1.0, 0.0));
        world.add_wall(Vector::new(sc.width_m, 0.0), Vector::new(-1.0, 0.0));
        let ids: Vec<BodyId> = grains
            .iter()
            .zip(state)
            .map(|(g, s)| {
                let mut b = FluidBody::at_rest(
                    Vector::new(s.x_m, s.y_m),
                    g.diameter_m,
                    sc.density_kg_m3,
                    g.drag,
                    sc.gravity_m_s2,
                );
                b.velocity_m_s = Vector::new(0.0, s.vy_m_s);
                world.add_sphere(b)
            })
            .collect();
        // Every collider exists now (the world's default restitution is 0).
        if sc.restitution != RestitutionLaw::constant(0.0) {
            world.set_restitution_law(sc.restitution);
        }
        Self {
            grains,
            pairs,
            sc,
            world,
            ids,
            dampers: Vec::new(),
        }
    }

    fn radius(&self, k: usize) -> f64 {
        0.5 * self.grains[k].diameter_m
    }

    fn gap(&self, i: usize, j: usize) -> f64 {
        let w = &self.world;
        (w.position_m(self.ids[j]) - w.position_m(self.ids[i])).norm()
            - self.radius(i)
            - self.radius(j)
    }

    fn on_floor(&self, k: usize) -> bool {
        self.world.position_m(self.ids[k])[1] - self.radius(k)
            <= self.sc.floor_m + 1e-3 * self.radius(k)
    }

    /// The lubrication cut-off of a pair, h_out = f a_eff, m.
    fn cut_of(&self, i: usize, j: usize) -> f64 {
        let (a, b) = (self.radius(i), self.radius(j));
        self.sc.outer_fraction * a * b / (a + b)
    }

    /// A first step of 1e-6 of a Rapier step registers the close pairs (prediction distance
    /// floored at the window's margin plus the largest cut-off), so that the first real step
    /// already drives them with the effective-mass drag.
    fn register_close_pairs(&mut self, margin_m: f64) {
        let cut_max = self
            .pairs
            .iter()
            .map(|&(i, j)| self.cut_of(i, j))
            .fold(0.0, f64::max);
        self.world.set_min_prediction_distance_m(margin_m + cut_max);
    }

    /// Replaces the squeeze-film dampers: c = 6πμ a_eff²/max(h, h_in) on every pair within
    /// h_out ([`damping_n_s_m`]).
    fn set_dampers(&mut self) {
        for j in self.dampers.drain(..) {
            self.world.remove_pair_damper(j);
        }
        let Some(cut) = self.sc.lubrication else {
            return;
        };
        for &(i, j) in self.pairs {
            let c = damping_n_s_m(
                self.radius(i),
                self.radius(j),
                self.gap(i, j),
                self.sc.viscosity_pa_s,
                cut,
            );
            if c > 0.0 {
                let d = self.world.add_pair_damper(self.ids[i], self.ids[j], c);
                self.dampers.push(d);
            }
        }
    }

    /// Within the film, the gap may change by at most `film_change_per_step` per Rapier step
    /// (the damper's gap is frozen over the step): h ≤ f max(gap, h_in)/|approach speed|, s.
    fn film_step_limit_s(&self) -> f64 {
        let mut h_lub = f64::INFINITY;
        let Some(cut) = self.sc.lubrication else {
            return h_lub;
        };
        let w = &self.world;
        for &(i, j) in self.pairs {
            let gap_ij = self.gap(i, j);
            if gap_ij < self.cut_of(i, j) {
                let (pi, pj) = (w.position_m(self.ids[i]), w.position_m(self.ids[j]));
                let n = (pj - pi).normalize();
                let approach = -(w.velocity_m_s(self.ids[j]) - w.velocity_m_s(self.ids[i])).dot(&n);
                let a_eff = self.cut_of(i, j) / self.sc.outer_fraction;
                if approach > 0.0 {
                    h_lub = h_lub.min(
                        self.sc.film_change_per_step * gap_ij.max(cut.inner * a_eff) / approach,
                    );
                }
            }
        }
        h_lub
    }

    /// One Rapier step of `h` s. The engine refuses a step (states untouched) whose free-flight
    /// force would exceed its speed cap: it is retried at a quarter, up to 20 times. Returns the
    /// step taken, or None if every try was refused.
    fn step_with_retries(&mut self, h: f64) -> Option<f64> {
        let mut h_try = h;
        for _ in 0..20 {
            if self.world.step(h_try, self.sc.integrator).is_ok() {
                return Some(h_try);
            }
            h_try *= 0.25;
        }
        None
    }

    /// The grains as they are in the world.
    fn current(&self) -> Vec<Resolved> {
        self.ids
            .iter()
            .map(|&id| {
                let (p, v) = (self.world.position_m(id), self.world.velocity_m_s(id));
                Resolved {
                    x_m: p[0],
                    y_m: p[1],
                    vy_m_s: v[1],
                }
            })
            .collect()
    }

    /// The grains at the end of the step, moved freely over the `rest_s` left, if no pair is
    /// within its cut-off and none may meet again on the free paths (grains on the floor
    /// excepted: they join the bed), or if no time is left; None while the contact goes on.
    fn try_release(&self, rest_s: f64) -> Option<Vec<Resolved>> {
        let now = self.current();
        let sc = self.sc;
        // Each grain's free path over the rest, computed once (a grain may be in several
        // pairs) and reused for the end state: `free` is the same for `rest_s` and
        // `rest_s.max(0.0)` (no motion for t ≤ 0).
        let mut paths: Vec<Option<(f64, f64)>> = vec![None; now.len()];
        let mut path = |k: usize| {
            *paths[k]
                .get_or_insert_with(|| free(&self.grains[k], sc, now[k].y_m, now[k].vy_m_s, rest_s))
        };
        let mut apart = true;
        for &(i, j) in self.pairs {
            if self.on_floor(i) || self.on_floor(j) {
                continue;
            }
            if self.gap(i, j) < self.cut_of(i, j) {
                apart = false;
                break;
            }
            let probe = |k: usize, y_end_m: f64| Probe {
                x_m: now[k].x_m,
                y_start_m: now[k].y_m,
                y_end_m,
                radius_m: self.radius(k),
            };
            let (pi, pj) = (probe(i, path(i).0), probe(j, path(j).0));
            if may_meet(&pi, &pj, sc.outer_fraction) {
                apart = false;
                break;
            }
        }
        if !(apart || rest_s <= 0.0) {
            return None;
        }
        let end = (0..now.len())
            .map(|k| {
                let (y, v) = path(k);
                Resolved {
                    x_m: now[k].x_m,
                    y_m: y,
                    vy_m_s: v,
                }
            })
            .collect();
        Some(end)
    }
}
