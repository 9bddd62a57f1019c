//! Contacts and squeeze-film lubrication between representative grains of the sedimentation
//! cylinder ([`crate::scenes::sedimentation`], `physics = "full"`): the pair search
//! ([`PairFinder`]), the clusters of linked pairs ([`clusters`]) and their contact solve in a
//! Rapier 2D world ([`resolve`]).
//!
//! The pair search is a cell list (columns in x, sorted by height) that finds, for one step,
//! every pair of suspended grains whose surface gap can fall below the lubrication cut-off
//! within the step. Grains move only vertically between
//! contacts, so a pair can meet only if their discs overlap horizontally (|Δx| < r₁ + r₂ + h_out),
//! and their vertical separation, monotone over the step, is then smallest at one of its ends
//! (or zero if they cross): the test is exact for the free update of the step, with no travel
//! bound to guess.

use crate::dynamics::{advance, Integrator};
use crate::engine::dim2::{FluidBody, Vector, World};
use crate::engine::{BodyId, EngineSettings};
use crate::fluid::lubrication::{damping_n_s_m, Cutoffs};
use crate::fluid::{sphere_mass_kg, SphereDrag};
use nalgebra::SVector;

/// One grain as the pair search sees it: centre x, height at the start and at the end of the
/// free step, radius (real), all in m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Probe {
    /// Horizontal position, m.
    pub x_m: f64,
    /// Height of the centre at the start of the step, m.
    pub y_start_m: f64,
    /// Height of the centre at the end of the free (contact-less) step, m.
    pub y_end_m: f64,
    /// Radius, m.
    pub radius_m: f64,
}

/// Outer lubrication cut-off of a pair, m: `outer_fraction` × a_eff, a_eff = a₁a₂/(a₁ + a₂).
fn reach_m(a1: f64, a2: f64, outer_fraction: f64) -> f64 {
    outer_fraction * a1 * a2 / (a1 + a2)
}

/// True if the pair's surface gap is below `outer_fraction` × a_eff at some time of the step,
/// for grains moving vertically and monotonically from `y_start_m` to `y_end_m`.
pub fn may_meet(p: &Probe, q: &Probe, outer_fraction: f64) -> bool {
    may_meet_within(p, q, outer_fraction, 0.0)
}

/// [`may_meet`] with the cut-off widened by `extra_m`.
pub fn may_meet_within(p: &Probe, q: &Probe, outer_fraction: f64, extra_m: f64) -> bool {
    let contact =
        p.radius_m + q.radius_m + reach_m(p.radius_m, q.radius_m, outer_fraction) + extra_m;
    let dx = (p.x_m - q.x_m).abs();
    if dx >= contact {
        return false;
    }
    let dy0 = q.y_start_m - p.y_start_m;
    let dy1 = q.y_end_m - p.y_end_m;
    let closest = if dy0 * dy1 <= 0.0 {
        0.0
    } else {
        dy0.abs().min(dy1.abs())
    };
    closest * closest + dx * dx < contact * contact
}

/// Cell list of the pair search: columns of width `column_m` over [0, `width_m`], each holding
/// the indices of its grains sorted by starting height. Rebuilt every step (O(N) binning, and
/// sorting that is nearly linear because grains keep their order from step to step).
#[derive(Clone, Debug, Default)]
pub struct PairFinder {
    columns: Vec<Vec<u32>>,
}

impl PairFinder {
    /// Every pair (i < j) of `probes` (None: grain not in suspension) that may meet within the
    /// step ([`may_meet`]), sorted. `outer_fraction` is the lubrication cut-off h_out/a_eff.
    pub fn pairs(
        &mut self,
        probes: &[Option<Probe>],
        width_m: f64,
        outer_fraction: f64,
    ) -> Vec<(usize, usize)> {
        let (mut r_max, mut travel_max): (f64, f64) = (0.0, 0.0);
        for p in probes.iter().flatten() {
            r_max = r_max.max(p.radius_m);
            travel_max = travel_max.max((p.y_end_m - p.y_start_m).abs());
        }
        if r_max <= 0.0 {
            return Vec::new();
        }
        // A column is at least as wide as the largest possible horizontal reach of a pair, so a
        // grain meets only grains of its own and the neighbouring columns.
        let column = 2.0 * r_max * (1.0 + 0.5 * outer_fraction);
        let n_col = ((width_m / column).floor() as usize).max(1);
        let column = width_m / n_col as f64;
        self.columns.resize_with(n_col, Vec::new);
        self.columns.iter_mut().for_each(Vec::clear);
        for (i, p) in probes.iter().enumerate() {
            if let Some(p) = p {
                let c = ((p.x_m / column).max(0.0) as usize).min(n_col - 1);
                self.columns[c].push(i as u32);
            }
        }
        let y0 = |i: u32| probes[i as usize].expect("binned").y_start_m;
        for col in &mut self.columns {
            col.sort_by(|a, b| y0(*a).total_cmp(&y0(*b)));
        }
        // Vertical reach: touching (2 r_max + cut-off) plus the largest relative travel.
        let reach = 2.0 * r_max * (1.0 + 0.5 * outer_fraction) + 2.0 * travel_max;
        let mut out = Vec::new();
        for c in 0..n_col {
            let here = &self.columns[c];
            for (k, &i) in here.iter().enumerate() {
                let p = probes[i as usize].expect("binned");
                // Same column: grains above i in the sorted order.
                for &j in &here[k + 1..] {
                    let q = probes[j as usize].expect("binned");
                    if q.y_start_m - p.y_start_m > reach {
                        break;
                    }
                    if may_meet(&p, &q, outer_fraction) {
                        out.push((i.min(j) as usize, i.max(j) as usize));
                    }
                }
                // Right-hand column: grains within the reach either way.
                if let Some(next) = self.columns.get(c + 1) {
                    let lo = next.partition_point(|&j| y0(j) < p.y_start_m - reach);
                    for &j in &next[lo..] {
                        let q = probes[j as usize].expect("binned");
                        if q.y_start_m - p.y_start_m > reach {
                            break;
                        }
                        if may_meet(&p, &q, outer_fraction) {
                            out.push((i.min(j) as usize, i.max(j) as usize));
                        }
                    }
                }
            }
        }
        out.sort_unstable();
        out
    }
}

/// Groups of grains linked by pairs (connected components), each sorted, the groups ordered by
/// their first grain.
pub fn clusters(pairs: &[(usize, usize)]) -> Vec<Vec<usize>> {
    use std::collections::HashMap;
    let mut parent: HashMap<usize, usize> = HashMap::new();
    fn find(parent: &mut HashMap<usize, usize>, i: usize) -> usize {
        let mut r = i;
        while let Some(&p) = parent.get(&r) {
            if p == r {
                break;
            }
            r = p;
        }
        // Path compression.
        let mut k = i;
        while k != r {
            let next = parent[&k];
            parent.insert(k, r);
            k = next;
        }
        r
    }
    for &(i, j) in pairs {
        parent.entry(i).or_insert(i);
        parent.entry(j).or_insert(j);
        let (a, b) = (find(&mut parent, i), find(&mut parent, j));
        if a != b {
            parent.insert(a.max(b), a.min(b));
        }
    }
    let keys: Vec<usize> = parent.keys().copied().collect();
    let mut groups: HashMap<usize, Vec<usize>> = HashMap::new();
    for k in keys {
        let r = find(&mut parent, k);
        groups.entry(r).or_default().push(k);
    }
    let mut out: Vec<Vec<usize>> = groups
        .into_values()
        .map(|mut g| {
            g.sort_unstable();
            g
        })
        .collect();
    out.sort_unstable_by_key(|g| g[0]);
    out
}

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
}

/// What the contact solve of one cluster did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Solve {
    /// Rapier steps taken.
    pub rapier_steps: u64,
    /// The engine reported an unstable step (speed above half its cap, or non-finite): the
    /// cluster was advanced by the free update for this step instead.
    pub fallback: bool,
}

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
///    drag inside the contact solve, frictionless discs, walls at x = 0 and B, the bed surface
///    as floor) stepped so that the fastest grain moves at most `travel_per_substep` of the
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
    let probe_at = |k: usize, t: f64| {
        let g = &grains[k];
        Probe {
            x_m: g.x_m,
            y_start_m: g.y_m,
            y_end_m: free(g, sc, g.y_m, g.vy_m_s, t).0,
            radius_m: 0.5 * g.diameter_m,
        }
    };
    // Rapier step size of the contact window: the fastest grain moves at most
    // `travel_per_substep` of the smallest diameter.
    let d_min = grains
        .iter()
        .map(|g| g.diameter_m)
        .fold(f64::INFINITY, f64::min);
    let v_bound = grains
        .iter()
        .map(|g| g.vy_m_s.abs().max(stokes_speed_m_s(g, sc)))
        .fold(0.0, f64::max);
    let travel = sc.travel_per_substep * d_min;
    let h_sub = (travel / v_bound.max(1e-300)).max(1e-12);
    // 1. First time a pair may come within its cut-off plus two Rapier steps of travel (so that
    //    Rapier's narrow phase sees the pair, within its prediction distance, before it is
    //    within the cut-off).
    let margin = 2.0 * travel;
    let meet = |i: usize, j: usize, t: f64| {
        may_meet_within(&probe_at(i, t), &probe_at(j, t), sc.outer_fraction, margin)
    };
    let mut t_c = dt_s;
    for &(i, j) in pairs {
        if meet(i, j, 0.0) {
            t_c = 0.0;
            break;
        }
        let (mut lo, mut hi) = (0.0, t_c);
        if !meet(i, j, hi) {
            continue;
        }
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if meet(i, j, mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        t_c = lo;
    }
    let mut state: Vec<Resolved> = grains
        .iter()
        .map(|g| {
            let (y, v) = free(g, sc, g.y_m, g.vy_m_s, t_c);
            Resolved {
                x_m: g.x_m,
                y_m: y,
                vy_m_s: v,
            }
        })
        .collect();
    if t_c >= dt_s {
        return (state, Solve::default());
    }
    // 2. Contact window in a Rapier world.
    let v_max = grains
        .iter()
        .zip(&state)
        .map(|(g, s)| s.vy_m_s.abs().max(stokes_speed_m_s(g, sc)))
        .fold(0.0, f64::max);
    let mut settings = EngineSettings::for_scene(d_min, v_max);
    settings.friction = 0.0;
    // A small grain squeezed by a large one may move faster than its own terminal speed: the
    // cap (an instability detector) is set well above the cluster's largest terminal speed.
    settings.max_linear_velocity_m_s = settings.max_linear_velocity_m_s.max(40.0 * v_max);
    // Undoing overlaps left by earlier steps is this solve's job, not a fault: the engine's
    // penetration check would send such clusters to the free fallback, which keeps the overlap.
    settings.max_penetration_fraction = 0.0;
    let mut world = World::new(settings, sc.gravity_m_s2);
    world.add_floor(sc.floor_m);
    world.add_wall(Vector::new(0.0, 0.0), Vector::new(1.0, 0.0));
    world.add_wall(Vector::new(sc.width_m, 0.0), Vector::new(-1.0, 0.0));
    let ids: Vec<BodyId> = grains
        .iter()
        .zip(&state)
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
    let radius = |k: usize| 0.5 * grains[k].diameter_m;
    let gap = |w: &World, i: usize, j: usize| {
        (w.position_m(ids[j]) - w.position_m(ids[i])).norm() - radius(i) - radius(j)
    };
    let on_floor =
        |w: &World, k: usize| w.position_m(ids[k])[1] - radius(k) <= sc.floor_m + 1e-3 * radius(k);
    let cut_of = |i: usize, j: usize| {
        let (a, b) = (radius(i), radius(j));
        sc.outer_fraction * a * b / (a + b)
    };
    let mut t = t_c;
    let mut steps = 0u64;
    let mut dampers = Vec::new();
    // A first step of 1e-6 of a Rapier step registers the close pairs (prediction distance
    // floored at the window's margin plus the largest cut-off), so that the first real step
    // already drives them with the effective-mass drag.
    let cut_max = pairs.iter().map(|&(i, j)| cut_of(i, j)).fold(0.0, f64::max);
    world.set_min_prediction_distance_m(margin + cut_max);
    let mut warm = true;
    let mut released = false;
    while t < dt_s * (1.0 - 1e-12) {
        for j in dampers.drain(..) {
            world.remove_pair_damper(j);
        }
        if let Some(cut) = sc.lubrication {
            for &(i, j) in pairs {
                let c = damping_n_s_m(
                    radius(i),
                    radius(j),
                    gap(&world, i, j),
                    sc.viscosity_pa_s,
                    cut,
                );
                if c > 0.0 {
                    dampers.push(world.add_pair_damper(ids[i], ids[j], c));
                }
            }
        }
        // Within the film, the gap may change by at most `film_change_per_step` per Rapier step
        // (the damper's gap is frozen over the step): h ≤ f max(gap, h_in)/|approach speed|.
        let mut h_lub = f64::INFINITY;
        if let Some(cut) = sc.lubrication {
            for &(i, j) in pairs {
                let gap_ij = gap(&world, i, j);
                if gap_ij < cut_of(i, j) {
                    let (pi, pj) = (world.position_m(ids[i]), world.position_m(ids[j]));
                    let n = (pj - pi).normalize();
                    let approach =
                        -(world.velocity_m_s(ids[j]) - world.velocity_m_s(ids[i])).dot(&n);
                    let a_eff = cut_of(i, j) / sc.outer_fraction;
                    if approach > 0.0 {
                        h_lub = h_lub.min(
                            sc.film_change_per_step * gap_ij.max(cut.inner * a_eff) / approach,
                        );
                    }
                }
            }
        }
        let h = if warm { 1e-6 } else { 1.0 } * h_sub.min(h_lub).min(dt_s - t);
        warm = false;
        // The engine refuses a step (states untouched) whose free-flight force would exceed its
        // speed cap: retry smaller.
        let mut h_try = h;
        let mut last = None;
        for _ in 0..20 {
            match world.step(h_try, sc.integrator) {
                Ok(()) => {
                    last = None;
                    break;
                }
                Err(e) => last = Some(e),
            }
            h_try *= 0.25;
        }
        if last.is_some() {
            // The engine reported a speed above half its cap (or a non-finite state): give up
            // the contact solve of this cluster for this step, counted as a fallback.
            let free_only = grains
                .iter()
                .map(|g| {
                    let (y, v) = free(g, sc, g.y_m, g.vy_m_s, dt_s);
                    Resolved {
                        x_m: g.x_m,
                        y_m: y,
                        vy_m_s: v,
                    }
                })
                .collect();
            return (
                free_only,
                Solve {
                    rapier_steps: steps,
                    fallback: true,
                },
            );
        }
        t += h_try;
        steps += 1;
        // 3. Release once no pair is close or may meet on the free paths for the rest.
        let rest = dt_s - t;
        let now: Vec<(f64, f64, f64)> = ids
            .iter()
            .map(|&id| {
                let (p, v) = (world.position_m(id), world.velocity_m_s(id));
                (p[0], p[1], v[1])
            })
            .collect();
        let apart = pairs.iter().all(|&(i, j)| {
            if on_floor(&world, i) || on_floor(&world, j) {
                return true;
            }
            if gap(&world, i, j) < cut_of(i, j) {
                return false;
            }
            let probe = |k: usize| Probe {
                x_m: now[k].0,
                y_start_m: now[k].1,
                y_end_m: free(&grains[k], sc, now[k].1, now[k].2, rest).0,
                radius_m: radius(k),
            };
            !may_meet(&probe(i), &probe(j), sc.outer_fraction)
        });
        if apart || rest <= 0.0 {
            for (k, s) in state.iter_mut().enumerate() {
                let (y, v) = free(&grains[k], sc, now[k].1, now[k].2, rest.max(0.0));
                *s = Resolved {
                    x_m: now[k].0,
                    y_m: y,
                    vy_m_s: v,
                };
            }
            released = true;
            break;
        }
    }
    if !released {
        for (k, s) in state.iter_mut().enumerate() {
            let (p, v) = (world.position_m(ids[k]), world.velocity_m_s(ids[k]));
            *s = Resolved {
                x_m: p[0],
                y_m: p[1],
                vy_m_s: v[1],
            };
        }
    }
    // Inside the walls (Rapier's resting penetration is ~1e-3 d).
    for (k, s) in state.iter_mut().enumerate() {
        let r = radius(k);
        s.x_m = s.x_m.clamp(r, sc.width_m - r);
    }
    (
        state,
        Solve {
            rapier_steps: steps,
            fallback: false,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn probe(x: f64, y0: f64, y1: f64, r: f64) -> Option<Probe> {
        Some(Probe {
            x_m: x,
            y_start_m: y0,
            y_end_m: y1,
            radius_m: r,
        })
    }

    #[test]
    fn finds_exactly_the_pairs_of_a_brute_force_search() {
        // Pseudo-random grains in a 2 mm × 20 mm box, moving down by up to 0.5 mm.
        let mut s = 12345u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let probes: Vec<Option<Probe>> = (0..3000)
            .map(|k| {
                if k % 17 == 0 {
                    return None;
                }
                let r = 2e-6 + 33e-6 * rnd();
                let y0 = 0.02 * rnd();
                probe(2e-3 * rnd(), y0, y0 - 5e-4 * rnd(), r)
            })
            .collect();
        let mut brute = Vec::new();
        for i in 0..probes.len() {
            for j in i + 1..probes.len() {
                if let (Some(p), Some(q)) = (probes[i], probes[j]) {
                    if may_meet(&p, &q, 0.1) {
                        brute.push((i, j));
                    }
                }
            }
        }
        let found = PairFinder::default().pairs(&probes, 2e-3, 0.1);
        assert!(
            brute.len() > 10,
            "the case must have pairs: {}",
            brute.len()
        );
        assert_eq!(found, brute);
    }

    #[test]
    fn crossing_paths_meet_and_side_by_side_grains_do_not() {
        // Big grain above a small one, overtaking it within the step.
        let big = probe(0.0, 1e-3, 0.0, 35e-6).unwrap();
        let small = probe(10e-6, 6e-4, 5.9e-4, 2.5e-6).unwrap();
        assert!(may_meet(&big, &small, 0.1));
        // Same, but horizontally 40 µm apart: they pass each other.
        let small = probe(40e-6, 6e-4, 5.9e-4, 2.5e-6).unwrap();
        assert!(!may_meet(&big, &small, 0.1));
    }

    #[test]
    fn clusters_are_connected_components() {
        let c = clusters(&[(1, 5), (5, 9), (2, 3), (9, 1)]);
        assert_eq!(c, vec![vec![1, 5, 9], vec![2, 3]]);
    }
}
