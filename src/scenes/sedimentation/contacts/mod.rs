//! Contacts and squeeze-film lubrication between representative grains of the sedimentation
//! cylinder (`physics = "full"`): the pair search ([`PairFinder`]), the clusters of linked pairs
//! ([`clusters`](mod@clusters)), their contact solve in a Rapier 2D world ([`resolve`](fn@resolve)), and the stage of the
//! step that chains them ([`ContactStage`]).

pub mod clusters;
pub mod pairs;
pub mod resolve;

pub use clusters::clusters;
pub use pairs::{PairFinder, Probe};
pub use resolve::{resolve, ClusterGrain, ContactScene, Resolved, Solve};

use super::setup::{Setup, CONTACT_FILM_CHANGE_PER_STEP, CONTACT_TRAVEL_PER_SUBSTEP};
use super::state::State;
use super::step::{StepStart, Stepper};
use super::voidage::VoidageGrid;
use crate::fluid::lubrication::Cutoffs;
use crate::sample::Grains;
use crate::scenario::SampleSpec;
use rayon::prelude::*;
use std::collections::HashMap;
// Re-exported for the unit tests only.

/// The contact stage of a run: its pair finder (reused from step to step) and the constant part
/// of its [`ContactScene`].
pub struct ContactStage {
    finder: PairFinder,
    scene: ContactScene,
}

/// How a contact stage ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StageEnd {
    /// Every cluster resolved (or none to resolve); `moved`: there were close pairs.
    Done {
        /// At least one close pair was found.
        moved: bool,
    },
    /// An interrupt was requested: the grains are back at the start of the step.
    Interrupted,
}

impl ContactStage {
    /// The stage of sample `sm` in the cylinder of `setup`, with the step constants `k`.
    pub fn new(sm: &SampleSpec, setup: &Setup, k: &Stepper) -> Self {
        Self {
            finder: PairFinder::default(),
            scene: ContactScene {
                width_m: setup.width_m,
                floor_m: 0.0,
                density_kg_m3: k.grain_density_kg_m3,
                fluid_density_kg_m3: k.fluid_density_kg_m3,
                gravity_m_s2: k.gravity_m_s2,
                viscosity_pa_s: k.viscosity_pa_s,
                lubrication: sm.lubrication_on().then_some(Cutoffs {
                    inner: sm.lubrication_inner_cutoff,
                    outer: sm.lubrication_outer_cutoff,
                }),
                outer_fraction: sm.lubrication_outer_cutoff,
                integrator: k.integrator,
                travel_per_substep: CONTACT_TRAVEL_PER_SUBSTEP,
                film_change_per_step: CONTACT_FILM_CHANGE_PER_STEP,
                friction: setup.contacts.friction,
                restitution: setup.contacts.restitution,
            },
        }
    }

    /// After the free update of a step `dt_s` from `start`: finds the close
    /// pairs, groups them in clusters and re-does each cluster from the start of the step in its
    /// own Rapier world (in parallel), the grains' drag from `grid`; updates the contact
    /// statistics. `grains` are the setup's grains of `st`; a grain a contact moves across gets
    /// its horizontal position in the state ([`State::own_x`]). On an interrupt request the
    /// grains go back to the start of the step (a resumed run re-does it) and the stage says so.
    pub fn run(
        &mut self,
        st: &mut State,
        grains: &Grains,
        start: &StepStart,
        grid: &VoidageGrid,
        dt_s: f64,
    ) -> StageEnd {
        let t0 = std::time::Instant::now();
        let probes: Vec<Option<Probe>> = (st.y_m.iter().zip(&st.settled).zip(&start.y_m))
            .enumerate()
            .map(|(i, ((&y, &settled), &y0))| {
                (!settled).then(|| Probe {
                    x_m: st.x_m(grains, i),
                    y_start_m: y0,
                    y_end_m: y,
                    radius_m: 0.5 * grains.diameter_m(i),
                })
            })
            .collect();
        let pairs = self
            .finder
            .pairs(&probes, self.scene.width_m, self.scene.outer_fraction);
        if crate::interrupt::requested() {
            start.rewind(st);
            return StageEnd::Interrupted;
        }
        let groups = clusters(&pairs);
        let group_pairs = pairs_by_cluster(&groups, &pairs);
        let scene = ContactScene {
            floor_m: st.bed_height_m,
            ..self.scene
        };
        let (state, y0s, v0s) = (&*st, &start.y_m, &start.v_m_s);
        let results: Vec<(Vec<Resolved>, Solve)> = groups
            .par_iter()
            .zip(&group_pairs)
            .map(|(grp, gp)| {
                if crate::interrupt::requested() {
                    let interrupted = Solve {
                        interrupted: true,
                        ..Solve::default()
                    };
                    return (Vec::new(), interrupted);
                }
                let members: Vec<ClusterGrain> = grp
                    .iter()
                    .map(|&i| {
                        let (x, d) = (state.x_m(grains, i), grains.diameter_m(i));
                        ClusterGrain {
                            x_m: x,
                            y_m: y0s[i],
                            vy_m_s: v0s[i],
                            diameter_m: d,
                            drag: grid.drag_at(d, x, y0s[i]),
                        }
                    })
                    .collect();
                resolve(&members, gp, &scene, dt_s)
            })
            .collect();
        if results.iter().any(|(_, n)| n.interrupted) {
            start.rewind(st);
            return StageEnd::Interrupted;
        }
        if !groups.is_empty() {
            st.own_x(grains);
        }
        for (grp, (res, n)) in groups.iter().zip(results) {
            st.contacts.rapier_steps += n.rapier_steps;
            st.contacts.fallbacks += u64::from(n.fallback);
            for (&i, r) in grp.iter().zip(res) {
                st.x_m[i] = r.x_m;
                st.y_m[i] = r.y_m;
                st.velocity_m_s[i] = r.vy_m_s;
            }
        }
        let cs = &mut st.contacts;
        cs.pairs += pairs.len() as u64;
        cs.grains += groups.iter().map(Vec::len).sum::<usize>() as u64;
        cs.max_pairs_per_step = cs.max_pairs_per_step.max(pairs.len());
        cs.steps_with_pairs += u64::from(!pairs.is_empty());
        cs.wall_s += t0.elapsed().as_secs_f64();
        StageEnd::Done {
            moved: !pairs.is_empty(),
        }
    }
}

/// The pairs of each cluster, as indices into the cluster's sorted grains.
fn pairs_by_cluster(groups: &[Vec<usize>], pairs: &[(usize, usize)]) -> Vec<Vec<(usize, usize)>> {
    let mut local: HashMap<usize, (usize, usize)> = HashMap::new();
    for (c, grp) in groups.iter().enumerate() {
        for (k, &i) in grp.iter().enumerate() {
            local.insert(i, (c, k));
        }
    }
    let mut group_pairs: Vec<Vec<(usize, usize)>> = vec![Vec::new(); groups.len()];
    for &(i, j) in pairs {
        let (c, a) = local[&i];
        group_pairs[c].push((a, local[&j].1));
    }
    group_pairs
}
