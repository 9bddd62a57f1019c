//! The suspended grains of a run without contacts, as a structure of arrays: what the per-step
//! passes of full physics (voidage grid, free update, deposition, next step size) read and write,
//! packed so that each pass streams through memory.
//!
//! Without contacts a grain moves only vertically, only while it is suspended, and once it has
//! settled nothing moves it again. So the run keeps, for its suspended grains only and in
//! ascending grain order, the height, speed and voidage cell that change with every step, and the
//! constants those passes read (diameter, size class, real solid volume, Stokes terminal speed).
//! A grain leaves when it settles: deposition writes it into the [`State`] and drops it. The
//! heights and speeds of the grains still suspended are written back into the [`State`] only when
//! something reads them there ([`Suspension::write_back`]: the records, snapshots, readings,
//! checkpoints, a fault report and the end of the run). Each grain's free update and deposition
//! are those of [`super::step::kernel`], as in the per-grain passes over the [`State`]
//! ([`Stepper::free_update`], [`VoidageGrid::fill`], [`Stepper::deposit_vmax`]), on the same
//! grains in the same order: the results are the same, bit for bit.

use super::setup::Setup;
use super::state::State;
use super::step::kernel::{after_step, bed_rise_m, free_step, on_bed, CellDrag, CellGrain, Limits};
use super::step::{Stepper, INTERRUPT_CHECK_GRAINS};
use super::voidage::VoidageGrid;
use crate::dynamics::terminal::{exponential_near_terminal_lanes, TerminalTable};
use crate::fluid::sphere_volume_m3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// Grains whose terminal-state tables the free update evaluates together
/// ([`exponential_near_terminal_lanes`]).
const LANES: usize = 16;

/// The suspended grains of a run without contacts (see the module doc). SI units.
#[derive(Clone, Debug, Default)]
pub struct Suspension {
    /// Index of each grain in the [`State`], ascending.
    index: Vec<u32>,
    /// Height of each grain's centre, m (ahead of the [`State`] until written back).
    y_m: Vec<f64>,
    /// Vertical velocity of each grain, m/s (ahead of the [`State`] until written back).
    v_m_s: Vec<f64>,
    /// The voidage cell holding each grain ([`VoidageGrid::cell_of`]).
    cell: Vec<u32>,
    /// The kind of each grain (an index into `kinds`).
    kind: Vec<u32>,
    /// The distinct (size class, diameter, weight) of the grains: a few hundred, where the
    /// grains are up to millions.
    kinds: Vec<Kind>,
    /// Entries whose grain has settled ([`GONE`] in `cell`), not yet dropped.
    gone: usize,
    /// Height above the bed surface within which a grain may join the bed in one deposition
    /// pass, m: more than the bed's rise if every grain suspended at the start settled at once.
    reach_m: f64,
    /// Per chunk of [`INTERRUPT_CHECK_GRAINS`] entries, after a free update: the entries within
    /// `reach_m` of the bed surface (ascending), and the largest speed of the others (each the
    /// larger of its speed and its Stokes terminal speed), m/s.
    near_bed: Vec<(Vec<u32>, f64)>,
    /// Per part of the entries ([`Suspension::fill`]), the solid volume of its suspended
    /// grains per voidage cell, m³.
    parts: Vec<Vec<f64>>,
}

/// The entries per part of the voidage fill ([`Suspension::fill`]) in a grid of `cells` cells:
/// at least 2¹⁶, and sixteen per cell so that zeroing and adding the parts (`cells` values
/// each, streamed) costs little beside summing the grains (a scattered add each). A function
/// of the grid only: the same sums whatever the threads.
pub fn fill_part_grains(cells: usize) -> usize {
    (1 << 16).max(16 * cells)
}

/// The constants of the grains of one size class, diameter and weight. SI units.
#[derive(Clone, Copy, Debug)]
struct Kind {
    /// Size class.
    class: usize,
    /// Diameter, m.
    diameter_m: f64,
    /// Real solid volume of one grain (its weight times its volume), m³.
    volume_m3: f64,
    /// Stokes terminal speed ([`Stepper::stokes_speed_m_s`]), m/s.
    stokes_m_s: f64,
}

/// Entries per task of [`Suspension::write_back`].
const WRITE_BACK_GRAINS: usize = 1 << 15;

/// The `cell` of an entry whose grain has settled.
const GONE: u32 = u32::MAX;

impl Suspension {
    /// The suspended grains of `st` in the cells of `grid`, or None if a grain index or a cell
    /// does not fit in 32 bits (the caller then steps the [`State`] itself). Also returns whether
    /// any grain of `st`, suspended or settled, fails the fault test of
    /// [`Stepper::grain_fault`] now (in the cylinder of `setup`): the first step's free update
    /// would have found it (nothing changes a settled grain or a horizontal position afterwards).
    pub fn new(
        st: &State,
        grid: &VoidageGrid,
        stepper: &Stepper,
        setup: &Setup,
    ) -> Option<(Self, bool)> {
        let cells = grid.cells();
        if u32::try_from(st.grains.len()).is_err()
            || cells.cell_of(0.0, f64::INFINITY) >= GONE as usize
        {
            return None;
        }
        let mut me = Self::default();
        let mut suspect = false;
        let mut kinds = std::collections::HashMap::new();
        let mut total_m3 = 0.0;
        for (i, ((gr, &v), &settled)) in st
            .grains
            .iter()
            .zip(&st.velocity_m_s)
            .zip(&st.settled)
            .enumerate()
        {
            suspect |= stepper.is_faulty(gr, v, setup);
            if settled {
                continue;
            }
            me.index.push(i as u32);
            me.y_m.push(gr.y_m);
            me.v_m_s.push(v);
            me.cell.push(cells.cell_of(gr.x_m, gr.y_m) as u32);
            let key = (gr.class, gr.diameter_m.to_bits(), gr.weight.to_bits());
            let kind = *kinds.entry(key).or_insert_with(|| {
                me.kinds.push(Kind {
                    class: gr.class,
                    diameter_m: gr.diameter_m,
                    volume_m3: gr.weight * sphere_volume_m3(gr.diameter_m),
                    stokes_m_s: stepper.stokes_speed_m_s(gr.diameter_m),
                });
                me.kinds.len() - 1
            });
            me.kind.push(u32::try_from(kind).ok()?);
            total_m3 += me.kinds[kind].volume_m3;
        }
        me.reach_m = 1.01 * total_m3 / stepper.bed_area_m2 + 1e-12;
        Some((me, suspect))
    }

    /// The largest speed of the suspended grains, each the larger of its speed and its Stokes
    /// terminal speed, m/s, 0 if none (as [`Stepper::step_with_vmax_s`] finds it).
    pub fn vmax_m_s(&self) -> f64 {
        self.v_m_s
            .iter()
            .zip(&self.kind)
            .zip(&self.cell)
            .filter(|(_, &c)| c != GONE)
            .map(|((v, &k), _)| v.abs().max(self.kinds[k as usize].stokes_m_s))
            .fold(0.0, f64::max)
    }

    /// Number of suspended grains.
    pub fn len(&self) -> usize {
        self.index.len() - self.gone
    }

    /// True when no grain is suspended.
    #[allow(dead_code)] // the pair of `len` (clippy's len_without_is_empty)
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Refills `grid` with the solid volume of the suspended grains: in parallel, each part of
    /// [`fill_part_grains`] consecutive entries sums its grains per cell in grain order, then
    /// [`VoidageGrid::fill_parts`] adds the parts in order. The order of every sum depends on the
    /// grains and the grid only, not on the threads; with one part (up to
    /// [`fill_part_grains`] entries) it is grain order, as [`VoidageGrid::fill`] sums; with
    /// more, a sum's last digits may differ from grain order's.
    pub fn fill(&mut self, grid: &mut VoidageGrid) {
        let cells = grid.cell_count();
        let n = fill_part_grains(cells);
        self.parts
            .resize_with(self.cell.len().div_ceil(n), Vec::new);
        let kinds = &self.kinds;
        let sum = |((solid, cs), ks): ((&mut Vec<f64>, &[u32]), &[u32])| {
            solid.clear();
            solid.resize(cells, 0.0);
            for (&c, &k) in cs.iter().zip(ks) {
                if c != GONE {
                    solid[c as usize] += kinds[k as usize].volume_m3;
                }
            }
        };
        if self.parts.len() > 1 {
            self.parts
                .par_iter_mut()
                .zip(self.cell.par_chunks(n))
                .zip(self.kind.par_chunks(n))
                .for_each(sum);
        } else {
            // One part: on this thread (no hand-over to the pool), the same sums.
            self.parts
                .iter_mut()
                .zip(self.cell.chunks(n))
                .zip(self.kind.chunks(n))
                .for_each(sum);
        }
        grid.fill_parts(&self.parts);
    }

    /// The free update of every suspended grain over `dt_s` ([`free_step`] with [`CellDrag`]) above the
    /// bed surface `floor_m` (a grain reaching it stops on it; deposition then flags it), in
    /// parallel by chunks of [`INTERRUPT_CHECK_GRAINS`] grains, with each grain's new voidage
    /// cell. Returns the grains advanced and whether any now fails the test of
    /// [`Stepper::grain_fault`] in the cylinder of `setup` (after [`Suspension::write_back`], the
    /// fault scan names the first).
    pub fn free_update(
        &mut self,
        stepper: &Stepper,
        grid: &VoidageGrid,
        setup: &Setup,
        floor_m: f64,
        dt_s: f64,
    ) -> (u64, bool) {
        let drag = CellDrag::new(stepper, grid, dt_s);
        let fast = drag.fast;
        let ctx = Update {
            drag,
            kinds: self
                .kinds
                .iter()
                .map(|k| {
                    let table = grid.terminal_table(k.class, k.diameter_m).filter(|_| fast);
                    KindStep {
                        table,
                        dt_over_mass: table.map_or(f64::NAN, |t| dt_s / t.mass_kg),
                        half_d_m: 0.5 * k.diameter_m,
                        top_m: setup.height_m + k.diameter_m,
                        stokes_m_s: k.stokes_m_s,
                    }
                })
                .collect(),
            lim: Limits {
                floor_m,
                speed_bound_m_s: stepper.speed_bound_m_s,
            },
        };
        let suspect = AtomicBool::new(false);
        let n = INTERRUPT_CHECK_GRAINS;
        let chunks = self.index.len().div_ceil(n);
        self.near_bed.resize_with(chunks, Default::default);
        let reach = floor_m + 1e-15 + self.reach_m;
        self.y_m
            .par_chunks_mut(n)
            .zip(self.v_m_s.par_chunks_mut(n))
            .zip(self.cell.par_chunks_mut(n))
            .zip(self.kind.par_chunks(n))
            .zip(self.near_bed.par_iter_mut())
            .for_each(|((((ys, vs), cs), ks), (near, vmax))| {
                near.clear();
                let mut found = Found {
                    near,
                    vmax: 0.0,
                    bad: false,
                };
                let chunk = Chunk {
                    ys,
                    vs,
                    cs,
                    ks,
                    kinds: &self.kinds,
                };
                chunk.update(&ctx, reach, &mut found);
                *vmax = found.vmax;
                if found.bad {
                    suspect.store(true, Ordering::Relaxed);
                }
            });
        (self.len() as u64, suspect.into_inner())
    }

    /// Deposition (as [`Stepper::deposit_vmax`], in ascending grain order), after
    /// [`Suspension::free_update`]: every suspended grain touching the bed surface of `st` joins
    /// the bed, at rest on it, the bed rising by its real volume over `stepper.bed_area_m2`; it
    /// is written into `st` and leaves the suspension. Only the grains the free update found
    /// within reach of the bed are visited. Returns the largest speed of the grains still
    /// suspended (each the larger of its speed and its Stokes terminal speed), m/s, 0 if none,
    /// and whether a grain that joined the bed fails the test of [`Stepper::grain_fault`] there
    /// (the next step's free update would have found it).
    pub fn deposit_vmax(
        &mut self,
        st: &mut State,
        stepper: &Stepper,
        setup: &Setup,
    ) -> (f64, bool) {
        let mut vmax = 0.0f64;
        let mut suspect = false;
        let n = INTERRUPT_CHECK_GRAINS;
        for (chunk, (near, chunk_vmax)) in self.near_bed.iter().enumerate() {
            vmax = vmax.max(*chunk_vmax);
            for &k in near {
                let j = chunk * n + k as usize;
                let kind = self.kinds[self.kind[j] as usize];
                let (y, v, d) = (self.y_m[j], self.v_m_s[j], kind.diameter_m);
                let half_d = 0.5 * d;
                if on_bed(y, half_d, st.bed_height_m) {
                    let i = self.index[j] as usize;
                    let gr = &mut st.grains[i];
                    gr.y_m = st.bed_height_m + half_d;
                    st.velocity_m_s[i] = 0.0;
                    st.settled[i] = true;
                    st.bed_height_m += bed_rise_m(gr.weight, d, stepper.bed_area_m2);
                    suspect |= stepper.is_faulty(&st.grains[i], 0.0, setup);
                    self.cell[j] = GONE;
                    self.gone += 1;
                } else {
                    vmax = vmax.max(v.abs().max(kind.stokes_m_s));
                }
            }
        }
        if self.gone * 16 > self.index.len() {
            self.drop_gone();
        }
        (vmax, suspect)
    }

    /// Drops the entries of settled grains, keeping the order of the others.
    fn drop_gone(&mut self) {
        let mut kept = 0;
        for j in 0..self.index.len() {
            if self.cell[j] == GONE {
                continue;
            }
            self.index[kept] = self.index[j];
            self.y_m[kept] = self.y_m[j];
            self.v_m_s[kept] = self.v_m_s[j];
            self.cell[kept] = self.cell[j];
            self.kind[kept] = self.kind[j];
            kept += 1;
        }
        self.truncate(kept);
        self.gone = 0;
    }

    /// Keeps the first `n` grains.
    fn truncate(&mut self, n: usize) {
        self.index.truncate(n);
        self.y_m.truncate(n);
        self.v_m_s.truncate(n);
        self.cell.truncate(n);
        self.kind.truncate(n);
    }

    /// Writes the heights and speeds of the suspended grains into `st`, in parallel by chunks
    /// of [`WRITE_BACK_GRAINS`] entries: the indices ascend, so each chunk writes its own range
    /// of the state's grains.
    pub fn write_back(&self, st: &mut State) {
        let n = WRITE_BACK_GRAINS;
        let len = self.index.len();
        let mut tasks = Vec::with_capacity(len.div_ceil(n));
        let (mut grains, mut speeds) = (&mut st.grains[..], &mut st.velocity_m_s[..]);
        let mut base = 0;
        for lo in (0..len).step_by(n) {
            let end = self
                .index
                .get(lo + n)
                .map_or(base + grains.len(), |&i| i as usize);
            let (g, g_rest) = std::mem::take(&mut grains).split_at_mut(end - base);
            let (v, v_rest) = std::mem::take(&mut speeds).split_at_mut(end - base);
            tasks.push((lo, base, g, v));
            (grains, speeds, base) = (g_rest, v_rest, end);
        }
        tasks.into_par_iter().for_each(|(lo, base, g, v)| {
            for j in lo..len.min(lo + n) {
                if self.cell[j] != GONE {
                    let i = self.index[j] as usize - base;
                    g[i].y_m = self.y_m[j];
                    v[i] = self.v_m_s[j];
                }
            }
        });
    }
}

/// The constants of one free update ([`Suspension::free_update`]).
struct Update<'a> {
    /// The drag of the step.
    drag: CellDrag<'a>,
    /// What the update reads of each kind ([`KindStep`]).
    kinds: Vec<KindStep<'a>>,
    /// The bed surface and the speed bound.
    lim: Limits,
}

/// What the free update reads of one grain kind, computed once per step: the same operations
/// on the same values as per grain, so the same bits. SI units.
#[derive(Clone, Copy)]
struct KindStep<'a> {
    /// Its terminal-state table, on the fast path ([`Stepper::fast_path`]) when its size class
    /// has one.
    table: Option<&'a TerminalTable>,
    /// The step over the mass, dt/m, s/kg (NaN without a table): one division per kind and step
    /// instead of one per grain.
    dt_over_mass: f64,
    /// Half the diameter, m.
    half_d_m: f64,
    /// The cylinder height plus the diameter, m: a centre above it is a fault.
    top_m: f64,
    /// Stokes terminal speed, m/s.
    stokes_m_s: f64,
}

/// One chunk of the suspended grains' arrays in a free update.
struct Chunk<'a> {
    ys: &'a mut [f64],
    vs: &'a mut [f64],
    cs: &'a mut [u32],
    /// The grains' kinds, and the kinds.
    ks: &'a [u32],
    kinds: &'a [Kind],
}

/// What the free update of one chunk found ([`Chunk::update`]).
struct Found<'a> {
    /// The entries within reach of the bed after the update (ascending).
    near: &'a mut Vec<u32>,
    /// The largest speed of the others, each the larger of its speed and its Stokes terminal
    /// speed, m/s.
    vmax: f64,
    /// Whether any grain now fails the fault test.
    bad: bool,
}

impl Chunk<'_> {
    /// The free update of every grain of the chunk ([`Suspension::free_update`]); `reach` is
    /// the height below which a grain's bottom may touch the bed in this step's deposition, m.
    fn update(self, u: &Update, reach: f64, found: &mut Found) {
        let Chunk {
            ys,
            vs,
            cs,
            ks,
            kinds,
        } = self;
        let len = ys.len();
        let voidage = u.drag.grid.voidages();
        let kind_of = |j: usize| &u.kinds[ks[j] as usize];
        // Grains with a terminal-state table, `LANES` at a time (the same steps as
        // `CellDrag` gives them one by one); the others one by one. A settled
        // entry's lane computes a step that is not used.
        let mut k = 0;
        while k + LANES <= len {
            let lanes: [&KindStep; LANES] = std::array::from_fn(|l| kind_of(k + l));
            let tables = lanes.map(|q| q.table);
            let steps = if u.drag.fast && tables.iter().all(Option::is_some) {
                let tables = tables.map(|t| t.expect("all tables present"));
                exponential_near_terminal_lanes(
                    tables,
                    std::array::from_fn(|l| match cs[k + l] {
                        GONE => 1.0,
                        cell => voidage[cell as usize],
                    }),
                    lanes.map(|q| q.dt_over_mass),
                    tables.map(|t| t.body_force_n),
                    std::array::from_fn(|l| vs[k + l]),
                    u.drag.dt_s,
                )
            } else {
                [None; LANES]
            };
            for (l, step) in steps.into_iter().enumerate() {
                let j = k + l;
                if cs[j] == GONE {
                    continue;
                }
                match step {
                    Some(step) => finish(u, lanes[l], reach, j, step, ys, vs, cs, found),
                    None => {
                        let kind = &kinds[ks[j] as usize];
                        one_grain(u, kind, lanes[l], reach, j, ys, vs, cs, found)
                    }
                }
            }
            k += LANES;
        }
        for j in k..len {
            if cs[j] != GONE {
                let kind = &kinds[ks[j] as usize];
                one_grain(u, kind, kind_of(j), reach, j, ys, vs, cs, found);
            }
        }
    }
}

/// The free update ([`free_step`] with [`CellDrag`]) of entry `j` of kind `kind` (its
/// constants `q`) outside the lanes. Out of line: the lanes cover nearly every grain-step (all
/// but the first step from rest and steps after a large change of voidage, 0.4 % in sample 5).
#[cold]
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn one_grain(
    u: &Update,
    kind: &Kind,
    q: &KindStep,
    reach: f64,
    j: usize,
    ys: &mut [f64],
    vs: &mut [f64],
    cs: &mut [u32],
    found: &mut Found,
) {
    let g = CellGrain {
        diameter_m: kind.diameter_m,
        class: kind.class,
        cell: cs[j] as usize,
    };
    let moved = free_step(&u.drag, &g, ys[j], vs[j], q.half_d_m, q.top_m, u.lim);
    record(u, q, reach, j, moved, ys, vs, cs, found);
}

/// Entry `j` of kind `q` after its step `(v1, dx)` ([`after_step`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn finish(
    u: &Update,
    q: &KindStep,
    reach: f64,
    j: usize,
    step: (f64, f64),
    ys: &mut [f64],
    vs: &mut [f64],
    cs: &mut [u32],
    found: &mut Found,
) {
    let moved = after_step(ys[j], step, q.half_d_m, q.top_m, u.lim);
    record(u, q, reach, j, moved, ys, vs, cs, found);
}

/// Stores entry `j`'s new height and speed, finds its new cell, and lists it in `found` as
/// within `reach` of the bed or counts its speed; records whether it now fails the test of
/// [`Stepper::grain_fault`] (`fault`; its horizontal position, constant, was tested by
/// [`Suspension::new`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn record(
    u: &Update,
    q: &KindStep,
    reach: f64,
    j: usize,
    (y, v, fault): (f64, f64, bool),
    ys: &mut [f64],
    vs: &mut [f64],
    cs: &mut [u32],
    found: &mut Found,
) {
    (ys[j], vs[j]) = (y, v);
    if y.is_finite() {
        cs[j] = u.drag.grid.cell_after(cs[j] as usize, y) as u32;
    }
    if y - q.half_d_m <= reach {
        found.near.push(j as u32);
    } else {
        found.vmax = found.vmax.max(v.abs().max(q.stokes_m_s));
    }
    found.bad |= fault;
}
