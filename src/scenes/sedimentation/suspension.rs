//! The suspended grains of a run without contacts, as a structure of arrays: what the per-step
//! passes of full physics (voidage grid, free update, deposition, next step size) read and write,
//! packed so that each pass streams through memory.
//!
//! Without contacts a grain moves only vertically, only while it is suspended, and once it has
//! settled nothing moves it again. So the run keeps, for its suspended grains only, the height,
//! speed and voidage cell that change with every step, and the constants those passes read
//! (diameter, size class, real solid volume, Stokes terminal speed) once per grain kind. The
//! grains are held in kind order (ascending grain index within a kind), so that the free update
//! takes neighbouring grains of one kind together, on vectors (issue 28). A grain leaves when it
//! settles: deposition writes it into the [`State`] and drops it. The heights and speeds of the
//! grains still suspended are written back into the [`State`] only when something reads them
//! there ([`Suspension::write_back`]: the records, snapshots, readings, checkpoints, a fault
//! report and the end of the run). Each grain's free update and deposition are those of
//! [`super::step::kernel`], as in the per-grain passes over the [`State`]
//! ([`Stepper::free_update`], [`VoidageGrid::fill`], [`Stepper::deposit_vmax`]): deposition
//! visits its grains in grain order, and the voidage sums are exact (the same in any order,
//! [`SolidQuanta`](super::voidage::SolidQuanta)), so the results are the same, bit for bit.

use super::setup::Setup;
use super::state::State;
use super::step::kernel::{bed_rise_m, on_bed, CellDrag, Limits};
use super::step::Stepper;
use super::voidage::VoidageGrid;
#[cfg(doc)]
use crate::dynamics::terminal::kind_at_voidage;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use sums::{move_volumes, Touched};
use update::{Chunk, Found, Kind, KindStep, Update, GONE};

mod block;
mod sums;
mod tables;
#[cfg(test)]
mod tests;
mod update;
#[cfg(target_arch = "x86_64")]
mod wide;

/// Entries per task of the free update ([`Suspension::free_update`]) of `len` entries: about
/// a quarter of each thread's share, so that the threads stay busy when few grains are left
/// suspended (late in a run), between 2¹¹ and 2¹⁴ (a task holds long runs of one kind, and its
/// bookkeeping is small beside its grains). The results do not depend on it.
fn update_chunk_grains(len: usize) -> usize {
    (len / (4 * rayon::current_num_threads().max(1))).clamp(1 << 11, 1 << 14)
}

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
    /// Per chunk of `chunk` entries, after a free update: the entries within
    /// `reach_m` of the bed surface (ascending), and the largest speed of the others (each the
    /// larger of its speed and its Stokes terminal speed), m/s.
    near_bed: Vec<(Vec<u32>, f64)>,
    /// Per chunk of the last free update, the grains that changed cell (cell before the
    /// step, cell after it, kind), not yet in `sums_q`.
    moved: Vec<Vec<(u32, u32, u32)>>,
    /// The solid volume of the suspended grains per voidage cell, in quanta
    /// ([`SolidQuanta`](super::voidage::SolidQuanta)), once a fill has summed it: kept exact
    /// from step to step by the grains that change cell or settle (integers: the same as a
    /// sum afresh).
    sums_q: Option<Vec<i128>>,
    /// The cells whose sums changed since the last fill, while few.
    touched: Touched,
    /// Entries per chunk of the last free update ([`update_chunk_grains`]).
    chunk: usize,
    /// Deposition's lists, kept from step to step (no allocation per step): the entries
    /// within reach (gap above the bed, m; the bed's rise if it joins, m; entry), and those
    /// that may join (grain index, entry).
    near_scratch: Vec<(f64, f64, u32)>,
    may_join: Vec<(u32, u32)>,
    /// Per kind, what its tabulated step reads of each voidage cell in this step
    /// ([`kind_at_voidage`], the last entry at voidage 1), for the kinds with at least
    /// `tables_from` entries; empty for the others.
    at: Vec<Vec<[f64; 4]>>,
    /// The fewest entries of a kind for which the free update reads its tabulated step from a
    /// table per cell, computed once per cell and step, rather than per grain; `None`:
    /// [`TABLES_PER_CELL`](tables::TABLES_PER_CELL) per cell of the grid. The results are the
    /// same either way.
    tables_from: Option<usize>,
    /// The fewest entries within reach of the bed that deposition lists and sums in parallel;
    /// `None`: [`DEPOSIT_PAR_MIN`]. The results are the same either way.
    deposit_par_from: Option<usize>,
}

/// The entries within reach of the bed from which deposition lists and sums them in parallel
/// (fewer: the hand-over to the threads would cost more than it saves).
const DEPOSIT_PAR_MIN: usize = 1 << 16;

/// The entries per part of the voidage fill ([`Suspension::fill`]) of `len` entries in a grid
/// of `cells` cells on `threads` threads: one part per thread, each of at least 2¹⁴ entries and
/// two per cell, so that zeroing and adding the parts (`cells` values each, streamed) costs
/// little beside summing the grains (a scattered add each). The sums are exact integers, the
/// same whatever the parts.
pub fn fill_part_grains(cells: usize, len: usize, threads: usize) -> usize {
    len.div_ceil(threads.max(1)).max(1 << 14).max(2 * cells)
}

impl Suspension {
    /// The suspended grains of `st` in the cells of `grid`, or None if a grain index or a cell
    /// does not fit in 32 bits (the caller then steps the [`State`] itself, left as it was).
    /// Takes the speeds of `st` (their array becomes the suspended grains', compacted in place:
    /// no second copy; [`Suspension::into_state`] gives them back): `st.velocity_m_s` is empty
    /// while the suspension lives, every settled grain being at rest. Also returns whether
    /// any grain of `st`, suspended or settled, fails the fault test of
    /// [`Stepper::grain_fault`] now (in the cylinder of `setup`): the first step's free update
    /// would have found it (nothing changes a settled grain or a horizontal position afterwards).
    pub fn new(
        st: &mut State,
        grid: &VoidageGrid,
        stepper: &Stepper,
        setup: &Setup,
    ) -> Option<(Self, bool)> {
        let cells = grid.cells();
        let grains = &setup.grains;
        if u32::try_from(st.len()).is_err() || cells.cell_of(0.0, f64::INFINITY) >= GONE as usize {
            return None;
        }
        let kinds = &grains.kinds;
        let mut me = Self {
            kinds: kinds
                .iter()
                .map(|k| Kind {
                    class: k.class,
                    diameter_m: k.diameter_m,
                    volume_m3: k.volume_m3(),
                    volume_q: grid.quanta().of(k.volume_m3()),
                    stokes_m_s: stepper.stokes_speed_m_s(k.diameter_m),
                })
                .collect(),
            ..Self::default()
        };
        let n = st.settled.iter().filter(|&&s| !s).count();
        me.index.reserve_exact(n);
        me.y_m.reserve_exact(n);
        me.cell.reserve_exact(n);
        me.kind.reserve_exact(n);
        let mut speeds = std::mem::take(&mut st.velocity_m_s);
        let mut suspect = false;
        let mut total_m3 = 0.0;
        for (i, (&y, &settled)) in st.y_m.iter().zip(&st.settled).enumerate() {
            let (x, v) = (st.x_m(grains, i), speeds[i]);
            suspect |= stepper.is_faulty(&grains.grain(i, x, y), v, setup);
            if settled {
                continue;
            }
            let kind = grains.kind[i];
            // Entry k = index.len() ≤ i: its slot is read already.
            speeds[me.index.len()] = v;
            me.index.push(i as u32);
            me.y_m.push(y);
            me.cell.push(0); // found by `order_by_kind`
            me.kind.push(kind);
            total_m3 += me.kinds[kind as usize].volume_m3;
        }
        speeds.truncate(me.index.len());
        me.v_m_s = speeds;
        me.reach_m = 1.01 * total_m3 / stepper.bed_area_m2 + 1e-12;
        me.order_by_kind(|j| cells.cell_of(st.x_m(grains, j), st.y_m[j]) as u32);
        Some((me, suspect))
    }

    /// Puts the entries in kind order, ascending grain index within a kind, in place: each
    /// entry's place (a counting sort by kind) is held in `cell` for the while, and every swap
    /// puts one entry in its place; then each entry's cell is found again (`cell_of`, from its
    /// grain's index): no memory beyond the entries'.
    fn order_by_kind(&mut self, cell_of: impl Fn(usize) -> u32) {
        let mut next = vec![0u32; self.kinds.len() + 1];
        for &k in &self.kind {
            next[k as usize + 1] += 1;
        }
        for k in 1..next.len() {
            next[k] += next[k - 1];
        }
        let place = &mut self.cell;
        for (p, &k) in place.iter_mut().zip(&self.kind) {
            let slot = &mut next[k as usize];
            *p = *slot;
            *slot += 1;
        }
        for j in 0..place.len() {
            loop {
                let d = place[j] as usize;
                if d == j {
                    break;
                }
                place.swap(j, d);
                self.index.swap(j, d);
                self.y_m.swap(j, d);
                self.v_m_s.swap(j, d);
                self.kind.swap(j, d);
            }
        }
        for (c, &i) in self.cell.iter_mut().zip(&self.index) {
            *c = cell_of(i as usize);
        }
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

    /// Refills `grid` with the solid volume of the suspended grains. The first time, in
    /// parallel: each part of [`fill_part_grains`] consecutive entries sums its grains per cell,
    /// then the parts are added. Afterwards from the sums kept up to date by the free update
    /// (a grain that changed cell moves its volume) and deposition (a grain that settled takes
    /// it away). Every sum is exact (integer quanta), so the same in any order, any cut into
    /// parts and any sequence of such changes, as [`VoidageGrid::fill`] sums in grain order.
    pub fn fill(&mut self, grid: &mut VoidageGrid) {
        if let Some(sums) = &mut self.sums_q {
            let t = &mut self.touched;
            move_volumes(sums, &mut self.moved, &self.kinds, t);
            // Only the cells listed, if the grid is as this suspension's last fill left it.
            if t.all || !grid.fill_sums_at(sums, &t.cells, t.stamp) {
                grid.fill_sums(sums);
            }
            t.reset(grid);
            return;
        }
        let cells = grid.cell_count();
        let n = fill_part_grains(cells, self.cell.len(), rayon::current_num_threads());
        let mut parts: Vec<Vec<i128>> = vec![Vec::new(); self.cell.len().div_ceil(n)];
        let kinds = &self.kinds;
        let sum = |((solid, cs), ks): ((&mut Vec<i128>, &[u32]), &[u32])| {
            solid.clear();
            solid.resize(cells, 0);
            for (&c, &k) in cs.iter().zip(ks) {
                if c != GONE {
                    solid[c as usize] += kinds[k as usize].volume_q;
                }
            }
        };
        if parts.len() > 1 {
            parts
                .par_iter_mut()
                .zip(self.cell.par_chunks(n))
                .zip(self.kind.par_chunks(n))
                .for_each(sum);
        } else {
            // One part: on this thread (no hand-over to the pool), the same sums.
            parts
                .iter_mut()
                .zip(self.cell.chunks(n))
                .zip(self.kind.chunks(n))
                .for_each(sum);
        }
        let mut sums = vec![0i128; cells];
        for p in parts.iter().filter(|p| !p.is_empty()) {
            for (x, &v) in sums.iter_mut().zip(p) {
                *x += v;
            }
        }
        grid.fill_sums(&sums);
        self.touched.reset(grid);
        self.sums_q = Some(sums);
        // Already in the cells just summed.
        self.moved.iter_mut().for_each(Vec::clear);
    }

    /// The free update of every suspended grain over `dt_s` ([`free_step`] with [`CellDrag`])
    /// above the bed surface `floor_m` (a grain reaching it stops on it; deposition then flags
    /// it), in parallel by chunks of [`update_chunk_grains`] grains, with each grain's new
    /// voidage cell (a grain that changed cell is listed for the next fill's sums). Returns the
    /// grains advanced and whether any now fails the test of [`Stepper::grain_fault`] in the
    /// cylinder of `setup` (after [`Suspension::write_back`], the fault scan names the first).
    ///
    /// [`free_step`]: super::step::kernel::free_step
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
        self.fill_tables(grid, fast, dt_s);
        let at = &self.at;
        let ctx = Update {
            drag,
            kinds: self
                .kinds
                .iter()
                .enumerate()
                .map(|(i, k)| {
                    let table = grid.terminal_table(k.class, k.diameter_m).filter(|_| fast);
                    KindStep {
                        kind: i as u32,
                        table,
                        at: Some(&at[i][..]).filter(|a| !a.is_empty()),
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
        let n = update_chunk_grains(self.index.len());
        self.chunk = n;
        let chunks = self.index.len().div_ceil(n);
        self.near_bed.resize_with(chunks, Default::default);
        // Grains moved by an update not followed by a fill: into the sums first.
        match &mut self.sums_q {
            Some(sums) => move_volumes(sums, &mut self.moved, &self.kinds, &mut self.touched),
            None => self.moved.iter_mut().for_each(Vec::clear),
        }
        self.moved.resize_with(chunks, Default::default);
        let reach = floor_m + 1e-15 + self.reach_m;
        self.y_m
            .par_chunks_mut(n)
            .zip(self.v_m_s.par_chunks_mut(n))
            .zip(self.cell.par_chunks_mut(n))
            .zip(self.kind.par_chunks(n))
            .zip(self.near_bed.par_iter_mut())
            .zip(self.moved.par_iter_mut())
            .for_each(|(((((ys, vs), cs), ks), (near, vmax)), moved)| {
                near.clear();
                let mut found = Found {
                    near,
                    moved,
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

    /// Every path of the free update and deposition taken however few the grains: every
    /// kind's tabulated step from its table per cell (by default from
    /// [`TABLES_PER_CELL`](tables::TABLES_PER_CELL) entries per cell), deposition's lists and
    /// sums in parallel (by default from [`DEPOSIT_PAR_MIN`] entries). The results are the
    /// same: for the tests that show it.
    pub fn every_path(&mut self) {
        self.tables_from = Some(0);
        self.deposit_par_from = Some(1);
    }

    /// Deposition (as [`Stepper::deposit_vmax`], in ascending grain order), after
    /// [`Suspension::free_update`]: every suspended grain touching the bed surface of `st` joins
    /// the bed, at rest on it, the bed rising by its real volume over `stepper.bed_area_m2`; its
    /// height and settled flag are written into `st` (its speed, 0, when the suspension ends)
    /// and it leaves the suspension. Only the grains the free update found
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
        let n = self.chunk;
        // The entries within reach: (gap above the bed, rise of the bed if it joins, entry).
        let bed0 = st.bed_height_m;
        let mut near = std::mem::take(&mut self.near_scratch);
        near.clear();
        for (_, chunk_vmax) in &self.near_bed {
            vmax = vmax.max(*chunk_vmax);
        }
        // In parallel where many (late in a run most grains are within reach), in chunk order.
        let (kinds, kind, y_m) = (&self.kinds, &self.kind, &self.y_m);
        let entry = |chunk: usize, k: u32| {
            let j = chunk * n + k as usize;
            let kind = &kinds[kind[j] as usize];
            let gap = y_m[j] - 0.5 * kind.diameter_m - bed0;
            (gap, kind.volume_m3 / stepper.bed_area_m2, j as u32)
        };
        let par_min = self.deposit_par_from.unwrap_or(DEPOSIT_PAR_MIN).max(1);
        let many = self.near_bed.iter().map(|(l, _)| l.len()).sum::<usize>() >= par_min;
        if many {
            let lists = self.near_bed.par_iter().map(|(l, _)| l).enumerate();
            near.par_extend(lists.flat_map_iter(|(c, l)| l.iter().map(move |&k| entry(c, k))));
        } else {
            let lists = self.near_bed.iter().map(|(l, _)| l).enumerate();
            near.extend(lists.flat_map(|(c, l)| l.iter().map(move |&k| entry(c, k))));
        }
        // Only a grain within the rise of the bed that the grains able to join could make can
        // join (the bed rises only as grains join): that bound, with ample margin for rounding,
        // found by adding such grains until none is added. The others are visited for their
        // speeds only; the possible ones in grain order (the entries are in kind order), as
        // the per-grain pass visits them, so the same grains join in the same order.
        // In parallel where many: the rise's rounding depends on how the sum is cut, but the
        // bound's 1 % margin covers it, and a grain beyond the true bound cannot join whatever
        // the bound.
        let within = |limit: f64| {
            let part = |s: &[(f64, f64, u32)]| {
                s.iter()
                    .filter(|x| x.0 <= limit)
                    .fold((0.0, 0), |(r, c), x| (r + x.1, c + 1))
            };
            if near.len() < par_min {
                return part(&near);
            }
            near.par_chunks(par_min.div_ceil(4))
                .map(part)
                .reduce(|| (0.0, 0), |a, b| (a.0 + b.0, a.1 + b.1))
        };
        let mut limit = 1e-15 + 1e-12;
        let mut count = usize::MAX;
        for _ in 0..16 {
            let (rise, c) = within(limit);
            limit = 1e-15 + 1e-12 + 1.01 * rise;
            if c == count {
                break;
            }
            count = c;
        }
        if count != within(limit).1 {
            limit = f64::INFINITY;
        }
        let mut may_join = std::mem::take(&mut self.may_join);
        may_join.clear();
        for &(gap, _, j) in &near {
            if gap <= limit {
                may_join.push((self.index[j as usize], j));
            } else {
                let kind = &self.kinds[self.kind[j as usize] as usize];
                vmax = vmax.max(self.v_m_s[j as usize].abs().max(kind.stokes_m_s));
            }
        }
        // Ascending runs (one per kind of each chunk): the stable sort merges them.
        may_join.sort();
        for &(_, j) in &may_join {
            let j = j as usize;
            let kind = self.kinds[self.kind[j] as usize];
            let (y, v, d) = (self.y_m[j], self.v_m_s[j], kind.diameter_m);
            let half_d = 0.5 * d;
            if on_bed(y, half_d, st.bed_height_m) {
                let i = self.index[j] as usize;
                let y = st.bed_height_m + half_d;
                st.y_m[i] = y;
                st.settled[i] = true;
                let grain = setup.grains.grain(i, st.x_m(&setup.grains, i), y);
                st.bed_height_m += bed_rise_m(grain.weight, d, stepper.bed_area_m2);
                suspect |= stepper.is_faulty(&grain, 0.0, setup);
                if let Some(sums) = &mut self.sums_q {
                    sums[self.cell[j] as usize] -= kind.volume_q;
                    self.touched.note(1, [self.cell[j]]);
                }
                self.cell[j] = GONE;
                self.gone += 1;
            } else {
                vmax = vmax.max(v.abs().max(kind.stokes_m_s));
            }
        }
        (self.near_scratch, self.may_join) = (near, may_join);
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

    /// Writes the heights of the suspended grains into `st`, in parallel: the state's grains
    /// are cut in one range per thread, and each thread writes the entries whose grains are in
    /// its range (the entries are in kind order, so a range's grains are anywhere among them).
    /// Copies only: the same heights whatever the threads. Their speeds stay here
    /// ([`Suspension::speeds_m_s`]).
    pub fn write_back(&self, st: &mut State) {
        let per = st.y_m.len().div_ceil(rayon::current_num_threads()).max(1);
        st.y_m
            .par_chunks_mut(per)
            .enumerate()
            .for_each(|(c, heights)| {
                let lo = c * per;
                for ((&i, &y), &cell) in self.index.iter().zip(&self.y_m).zip(&self.cell) {
                    if let Some(h) = (i as usize)
                        .checked_sub(lo)
                        .and_then(|k| heights.get_mut(k))
                    {
                        if cell != GONE {
                            *h = y;
                        }
                    }
                }
            });
    }

    /// The vertical velocity of every one of the `n` grains of the state, m/s: a suspended
    /// grain's from here, 0 for a settled one (at rest in the bed). A new array of `n` speeds,
    /// for what reads the state's speeds while the suspension holds them (a checkpoint, the
    /// fault scan).
    pub fn speeds_m_s(&self, n: usize) -> Vec<f64> {
        let mut v = vec![0.0; n];
        for (j, &i) in self.index.iter().enumerate() {
            if self.cell[j] != GONE {
                v[i as usize] = self.v_m_s[j];
            }
        }
        v
    }

    /// Ends the suspension: writes the heights of the suspended grains into `st` and gives it
    /// back every grain's speed ([`Suspension::speeds_m_s`]), spread in place over the array of
    /// speeds [`Suspension::new`] took from `st` (which still has room for every grain): no
    /// new array of speeds (two of flags, a byte per grain), so the end of a run needs no more
    /// memory than its steps.
    pub fn into_state(self, st: &mut State) {
        self.write_back(st);
        let Self {
            index,
            mut v_m_s,
            cell,
            ..
        } = self;
        let n = st.len();
        let len = index.len();
        v_m_s.resize(n, 0.0);
        // Entry j's speed goes to slot index[j]: follow each chain of entries whose slot holds
        // another entry not yet moved. `moved`: the entry first at j has left; `set`: slot j
        // holds its grain's speed.
        let (mut moved, mut set) = (vec![false; len], vec![false; n]);
        for j in 0..len {
            if moved[j] {
                continue;
            }
            moved[j] = true;
            let mut carry = (index[j] as usize, v_m_s[j], cell[j] == GONE);
            loop {
                let (slot, v, gone) = carry;
                let next = (slot < len && !moved[slot])
                    .then(|| (index[slot] as usize, v_m_s[slot], cell[slot] == GONE));
                v_m_s[slot] = if gone { 0.0 } else { v };
                set[slot] = true;
                match next {
                    Some(c) => {
                        moved[slot] = true;
                        carry = c;
                    }
                    None => break,
                }
            }
        }
        for (v, &s) in v_m_s.iter_mut().zip(&set) {
            if !s {
                *v = 0.0;
            }
        }
        st.velocity_m_s = v_m_s;
    }
}
