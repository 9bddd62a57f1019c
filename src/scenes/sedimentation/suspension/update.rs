//! The free update of the packed suspension's grains ([`super::Suspension::free_update`]),
//! chunk by chunk: runs of one kind on vectors ([`Chunk::update`]), the rare others one by one.

use super::super::step::kernel::{after_step, free_step, CellDrag, CellGrain, Limits};
#[cfg(doc)]
use super::super::step::Stepper;
pub(super) use super::block::{BlockEnd, EndConstants, LANES};
#[cfg(target_arch = "x86_64")]
use super::wide;
#[cfg(doc)]
use crate::dynamics::terminal::kind_at_voidage;
use crate::dynamics::terminal::{
    exponential_near_terminal_kind_at, exponential_near_terminal_kind_saturated, SaturatedSteps,
    TerminalTable,
};

/// The `cell` of an entry whose grain has settled.
pub(super) const GONE: u32 = u32::MAX;

/// The constants of the grains of one size class, diameter and weight. SI units.
#[derive(Clone, Copy, Debug)]
pub(super) struct Kind {
    /// Size class.
    pub(super) class: usize,
    /// Diameter, m.
    pub(super) diameter_m: f64,
    /// Real solid volume of one grain (its weight times its volume), m³.
    pub(super) volume_m3: f64,
    /// The same in the quanta of the voidage grid's sums
    /// ([`SolidQuanta`](super::super::voidage::SolidQuanta)).
    pub(super) volume_q: i128,
    /// Stokes terminal speed ([`Stepper::stokes_speed_m_s`]), m/s.
    pub(super) stokes_m_s: f64,
}

/// The constants of one free update ([`super::Suspension::free_update`]).
pub(super) struct Update<'a> {
    /// The drag of the step.
    pub(super) drag: CellDrag<'a>,
    /// What the update reads of each kind ([`KindStep`]).
    pub(super) kinds: Vec<KindStep<'a>>,
    /// The bed surface and the speed bound.
    pub(super) lim: Limits,
}

/// What the free update reads of one grain kind, computed once per step: the same operations
/// on the same values as per grain, so the same bits. SI units.
#[derive(Clone, Copy)]
pub(super) struct KindStep<'a> {
    /// Its index among the kinds.
    pub(super) kind: u32,
    /// Its terminal-state table, on the fast path ([`Stepper::fast_path`]) when its size class
    /// has one.
    pub(super) table: Option<&'a TerminalTable>,
    /// What its tabulated step reads of each voidage cell ([`kind_at_voidage`], one entry
    /// per cell and one at voidage 1 for the settled lanes), where computed for this step.
    pub(super) at: Option<&'a [[f64; 4]]>,
    /// The step over the mass, dt/m, s/kg (NaN without a table): one division per kind and step
    /// instead of one per grain.
    pub(super) dt_over_mass: f64,
    /// Half the diameter, m.
    pub(super) half_d_m: f64,
    /// The cylinder height plus the diameter, m: a centre above it is a fault.
    pub(super) top_m: f64,
    /// Stokes terminal speed, m/s.
    pub(super) stokes_m_s: f64,
}

/// One chunk of the suspended grains' arrays in a free update.
pub(super) struct Chunk<'a> {
    pub(super) ys: &'a mut [f64],
    pub(super) vs: &'a mut [f64],
    pub(super) cs: &'a mut [u32],
    /// The grains' kinds, and the kinds.
    pub(super) ks: &'a [u32],
    pub(super) kinds: &'a [Kind],
}

/// What the free update of one chunk found ([`Chunk::update`]).
pub(super) struct Found<'a> {
    /// The entries within reach of the bed after the update (ascending).
    pub(super) near: &'a mut Vec<u32>,
    /// The grains that changed cell: (cell before the step, cell after it, kind).
    pub(super) moved: &'a mut Vec<(u32, u32, u32)>,
    /// The largest speed of the others, each the larger of its speed and its Stokes terminal
    /// speed, m/s.
    pub(super) vmax: f64,
    /// Whether any grain now fails the fault test.
    pub(super) bad: bool,
}

impl Chunk<'_> {
    /// The free update of every grain of the chunk ([`super::Suspension::free_update`]);
    /// `reach` is the height below which a grain's bottom may touch the bed in this step's
    /// deposition, m.
    ///
    /// The entries are in kind order ([`super::Suspension::new`]), so the chunk is a few runs of
    /// one kind each: `LANES` neighbouring grains of a run share one terminal-state table
    /// ([`exponential_near_terminal_kind_saturated`]: its coefficients read once, the lanes
    /// computed as vectors, on the widest vectors the processor has: [`Chunk::update`] picks
    /// the build); a run's last grains (fewer than `LANES`) on blocks of a quarter or half as
    /// many lanes ([`Tail`]). Every grain's update is the same operations as [`CellDrag`] gives
    /// it alone.
    #[inline(always)]
    fn update_any<const WIDE: bool>(self, u: &Update, reach: f64, found: &mut Found) {
        let Chunk {
            ys,
            vs,
            cs,
            ks,
            kinds,
        } = self;
        let voidage = u.drag.grid.voidages();
        let bounds = u.drag.grid.cell_bounds();
        let cells = voidage.len().min(bounds.len());
        debug_assert!(ks.is_sorted(), "the entries are in kind order");
        let len = ys.len();
        let mut a = 0;
        while a < len {
            let k = ks[a];
            // The kinds ascend (kind order): the run's end by bisection, not a scan.
            let b = a + ks[a..].partition_point(|&x| x <= k);
            let (q, kind) = (&u.kinds[k as usize], &kinds[k as usize]);
            let Some(table) = q.table else {
                for j in a..b {
                    if cs[j] != GONE {
                        one_grain(u, kind, q, reach, j, ys, vs, cs, found);
                    }
                }
                a = b;
                continue;
            };
            let mut j0 = a;
            while j0 + LANES <= b {
                let (y0, c0, v0) = load(j0, ys, cs, vs);
                // AVX-512: the voidages gathered, and the end of the step on vectors, when
                // every lane holds a suspended grain (`wide`).
                #[cfg(target_arch = "x86_64")]
                // SAFETY: WIDE only in `update_avx512`, whose processor has AVX-512F.
                let wide = WIDE && unsafe { wide::gatherable(&c0, cells) };
                #[cfg(not(target_arch = "x86_64"))]
                let wide = false;
                let step = block_step::<WIDE>(u, q, table, &c0, v0, wide);
                let all_ok = (0..LANES).all(|l| step.ok[l]);
                if all_ok && (0..LANES).all(|l| c0[l] != GONE) {
                    let (v1, dx) = (step.velocity_m_s, step.displacement_m);
                    let block = Block { j0, y0, c0, v1, dx };
                    block.finish(u, q, reach, wide, ys, vs, cs, found);
                } else {
                    let (at, grains) = ((j0, LANES), (&mut *ys, &mut *vs, &mut *cs));
                    lanes_end(u, (kind, q), reach, at, (&y0, &c0), &step, grains, found);
                }
                j0 += LANES;
            }
            // The run's last grains (fewer than `LANES`) on blocks of a quarter or half as
            // many lanes: fewer lanes computed for nothing (17 to 31: 16, then the rest).
            while j0 < b {
                let n = (b - j0).min(LANES / 2);
                let t = Tail {
                    j0,
                    n,
                    kind,
                    q,
                    table,
                };
                if n <= LANES / 4 {
                    t.update::<{ LANES / 4 }>(u, reach, ys, vs, cs, found);
                } else {
                    t.update::<{ LANES / 2 }>(u, reach, ys, vs, cs, found);
                }
                j0 += n;
            }
            a = b;
        }
    }

    /// [`Chunk::update_any`] built for the widest vectors this processor has (AVX-512, AVX2,
    /// else the build's baseline), chosen at run time. Additions, multiplications and divisions
    /// are rounded alike on every width (nothing is fused into a multiply-add), so every build
    /// gives the same bits.
    pub(super) fn update(self, u: &Update, reach: f64, found: &mut Found) {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx512f") {
                // SAFETY: the processor has AVX-512F (checked just above).
                return unsafe { self.update_avx512(u, reach, found) };
            }
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: the processor has AVX2 (checked just above).
                return unsafe { self.update_avx2(u, reach, found) };
            }
        }
        self.update_any::<false>(u, reach, found)
    }

    /// [`Chunk::update_any`] on AVX-512 vectors.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f")]
    fn update_avx512(self, u: &Update, reach: f64, found: &mut Found) {
        self.update_any::<true>(u, reach, found)
    }

    /// [`Chunk::update_any`] on AVX2 vectors.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn update_avx2(self, u: &Update, reach: f64, found: &mut Found) {
        self.update_any::<false>(u, reach, found)
    }
}

/// The saturated tabulated step of a block of grains of the kind `q` (whose table is `table`)
/// in the cells `c0` at the speeds `v0` (m/s), as [`lanes_step`] computes it, with what each
/// lane reads gathered on AVX-512 vectors where `WIDE` and the cells are in the table per cell
/// or, without one, in the grid (`wide`: they pass [`wide::gatherable`](super::wide) for it).
/// The same bits either way.
#[inline(always)]
fn block_step<const WIDE: bool>(
    u: &Update,
    q: &KindStep,
    table: &TerminalTable,
    c0: &[u32; LANES],
    v0: [f64; LANES],
    wide: bool,
) -> SaturatedSteps<LANES> {
    #[cfg(target_arch = "x86_64")]
    if WIDE {
        let (dt_m, dt) = (q.dt_over_mass, u.drag.dt_s);
        match q.at {
            // SAFETY: `WIDE` only in `update_avx512`, whose processor has AVX-512F; the cells
            // pass `gatherable` for the table, shorter than 2²⁸ entries (`gather_at`).
            Some(at) if at.len() < 1 << 28 && unsafe { wide::gatherable(c0, at.len()) } => {
                let read = unsafe { wide::gather_at(at, c0) };
                return exponential_near_terminal_kind_at::<LANES>(table, read, dt_m, v0, dt);
            }
            None if wide => {
                // SAFETY: AVX-512F as above; `wide`: the cells pass `gatherable` for the grid.
                let e0 = unsafe { wide::gather(u.drag.grid.voidages(), c0) };
                return exponential_near_terminal_kind_saturated::<LANES>(table, e0, dt_m, v0, dt);
            }
            _ => {}
        }
    }
    let _ = wide;
    lanes_step(u, q, table, c0, v0)
}

/// The saturated tabulated step of `L` grains of the kind `q` (whose table is `table`) in the
/// cells `c0` at the speeds `v0` (m/s), each lane's reading loaded alone: from the kind's table
/// per cell where it has one ([`kind_at_voidage`]; its last entry, at voidage 1, for a settled
/// lane), else from the lane's voidage (1 for a settled lane).
#[inline(always)]
fn lanes_step<const L: usize>(
    u: &Update,
    q: &KindStep,
    table: &TerminalTable,
    c0: &[u32; L],
    v0: [f64; L],
) -> SaturatedSteps<L> {
    let (dt_m, dt) = (q.dt_over_mass, u.drag.dt_s);
    if let Some(at) = q.at {
        let last = at.len() - 1;
        let mut read = [[0.0; L]; 4];
        for l in 0..L {
            let r = at[(c0[l] as usize).min(last)];
            for (i, x) in r.into_iter().enumerate() {
                read[i][l] = x;
            }
        }
        exponential_near_terminal_kind_at::<L>(table, read, dt_m, v0, dt)
    } else {
        let voidage = u.drag.grid.voidages();
        let mut e0 = [0.0; L];
        for l in 0..L {
            e0[l] = if c0[l] == GONE {
                1.0
            } else {
                voidage[c0[l] as usize]
            };
        }
        exponential_near_terminal_kind_saturated::<L>(table, e0, dt_m, v0, dt)
    }
}

/// A full block of [`LANES`] entries from `j0` whose grains are all suspended and all took
/// the saturated step ([`exponential_near_terminal_kind_saturated`]): their heights `y0` (m)
/// and cells `c0` before it, their speeds `v1` (m/s) and displacements `dx` (m) over it.
pub(super) struct Block {
    pub(super) j0: usize,
    pub(super) y0: [f64; LANES],
    pub(super) c0: [u32; LANES],
    pub(super) v1: [f64; LANES],
    pub(super) dx: [f64; LANES],
}

/// The heights, cells and speeds of the [`LANES`] entries from `j0`. Plain loops (not
/// `array::from_fn` or `map`, which may be left out of line, built for the baseline).
#[inline(always)]
fn load(
    j0: usize,
    ys: &[f64],
    cs: &[u32],
    vs: &[f64],
) -> ([f64; LANES], [u32; LANES], [f64; LANES]) {
    let (mut y0, mut c0, mut v0) = ([0.0; LANES], [0u32; LANES], [0.0; LANES]);
    let (y, c, v) = (
        &ys[j0..j0 + LANES],
        &cs[j0..j0 + LANES],
        &vs[j0..j0 + LANES],
    );
    for l in 0..LANES {
        (y0[l], c0[l], v0[l]) = (y[l], c[l], v[l]);
    }
    (y0, c0, v0)
}

/// The last `n` entries of a run of one kind from `j0` (`n` ≤ L < [`LANES`]: kind `kind`,
/// its constants `q` and terminal-state table `table`), stepped on blocks of `L` lanes: the
/// same operations lane by lane as a block of [`LANES`], so the same bits.
struct Tail<'a> {
    j0: usize,
    n: usize,
    kind: &'a Kind,
    q: &'a KindStep<'a>,
    table: &'a TerminalTable,
}

impl Tail<'_> {
    /// The free update of the tail's grains ([`Chunk::update_any`] lane by lane).
    #[inline(always)]
    fn update<const L: usize>(
        self,
        u: &Update,
        reach: f64,
        ys: &mut [f64],
        vs: &mut [f64],
        cs: &mut [u32],
        found: &mut Found,
    ) {
        let Tail {
            j0,
            n,
            kind,
            q,
            table,
        } = self;
        let (mut y0, mut c0, mut v0) = ([0.0; L], [0u32; L], [0.0; L]);
        for l in 0..L {
            let j = j0 + l.min(n - 1);
            (y0[l], c0[l], v0[l]) = (ys[j], cs[j], vs[j]);
        }
        let step = lanes_step::<L>(u, q, table, &c0, v0);
        lanes_end::<L>(
            u,
            (kind, q),
            reach,
            (j0, n),
            (&y0, &c0),
            &step,
            (ys, vs, cs),
            found,
        );
    }
}

/// The end of the step `step` of the `n` lanes from `j0` of a block of `L` lanes of kind `q`
/// (constants `kind`), from the heights `y0` (m) and cells `c0` before it, lane by lane:
/// [`after_step`] and the tests of [`record`] without a branch, stored ([`store`]), the lanes
/// outside the saturated step's range stepped alone ([`one_grain`]), the settled lanes left.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn lanes_end<const L: usize>(
    u: &Update,
    (kind, q): (&Kind, &KindStep),
    reach: f64,
    (j0, n): (usize, usize),
    (y0, c0): (&[f64; L], &[u32; L]),
    step: &SaturatedSteps<L>,
    (ys, vs, cs): (&mut [f64], &mut [f64], &mut [u32]),
    found: &mut Found,
) {
    let (v1, dx) = (&step.velocity_m_s, &step.displacement_m);
    let (mut y1, mut fault, mut near) = ([0.0; L], [false; L], [false; L]);
    let mut vmax = 0.0f64;
    for l in 0..L {
        (y1[l], _, fault[l]) = after_step(y0[l], (v1[l], dx[l]), q.half_d_m, q.top_m, u.lim);
        near[l] = y1[l] - q.half_d_m <= reach;
        let counted = step.ok[l] && !near[l] && c0[l] != GONE && l < n;
        vmax = vmax.max(if counted {
            v1[l].abs().max(q.stokes_m_s)
        } else {
            0.0
        });
    }
    found.vmax = found.vmax.max(vmax);
    for l in 0..n {
        let j = j0 + l;
        if c0[l] == GONE {
            continue;
        }
        if !step.ok[l] {
            one_grain(u, kind, q, reach, j, ys, vs, cs, found);
            continue;
        }
        store(u, q, j, (y1[l], v1[l], fault[l]), ys, vs, cs, found);
        if near[l] {
            found.near.push(j as u32);
        }
    }
}

/// The constants of the end of a block of kind `q` ([`EndConstants`]).
#[inline(always)]
fn block_constants(u: &Update, q: &KindStep, reach: f64) -> EndConstants {
    EndConstants {
        half_d_m: q.half_d_m,
        top_m: q.top_m,
        floor_m: u.lim.floor_m,
        speed_bound_m_s: u.lim.speed_bound_m_s,
        reach_m: reach,
        stokes_m_s: q.stokes_m_s,
    }
}

impl Block {
    /// The end of the block's step of kind `q` ([`Block::end`], or [`wide::finish`] where
    /// `wide`: only in the AVX-512 build, for cells that pass [`wide::gatherable`]), stored
    /// ([`Block::apply`]).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn finish(
        self,
        u: &Update,
        q: &KindStep,
        reach: f64,
        wide: bool,
        ys: &mut [f64],
        vs: &mut [f64],
        cs: &mut [u32],
        found: &mut Found,
    ) {
        let bounds = u.drag.grid.cell_bounds();
        let k = block_constants(u, q, reach);
        let mut y1 = [0.0; LANES];
        #[cfg(target_arch = "x86_64")]
        // SAFETY: `wide` only in the AVX-512 build, whose processor has AVX-512F, and where
        // the cells pass `gatherable` (`voidage` and `bounds` have one entry per cell).
        let end = if wide {
            unsafe { wide::finish(k, &self.y0, &self.dx, &self.v1, &self.c0, bounds, &mut y1) }
        } else {
            self.end(k, bounds, &mut y1)
        };
        #[cfg(not(target_arch = "x86_64"))]
        let end = {
            let _ = wide;
            self.end(k, bounds, &mut y1)
        };
        self.apply(u, q.kind, &end, &y1, ys, vs, cs, found);
    }

    /// The end of the block's step lane by lane ([`after_step`] and the tests of [`record`]):
    /// the new heights into `y1`, and what [`BlockEnd`] lists, against the cells' `bounds`.
    /// The same as [`wide::finish`], which does it on vectors.
    #[inline(always)]
    pub(super) fn end(
        &self,
        k: EndConstants,
        bounds: &[(f64, f64)],
        y1: &mut [f64; LANES],
    ) -> BlockEnd {
        let lim = Limits {
            floor_m: k.floor_m,
            speed_bound_m_s: k.speed_bound_m_s,
        };
        let mut end = BlockEnd {
            left: 0,
            near: 0,
            bad: false,
            vmax: 0.0,
        };
        for l in 0..LANES {
            let bad;
            (y1[l], _, bad) = after_step(
                self.y0[l],
                (self.v1[l], self.dx[l]),
                k.half_d_m,
                k.top_m,
                lim,
            );
            let near = y1[l] - k.half_d_m <= k.reach_m;
            if !near {
                end.vmax = end.vmax.max(self.v1[l].abs().max(k.stokes_m_s));
            }
            let (lo, hi) = bounds[self.c0[l] as usize];
            let inside = lo <= y1[l] && y1[l] < hi;
            end.bad |= bad;
            end.left |= u32::from(!inside) << l;
            end.near |= u32::from(near) << l;
        }
        end
    }

    /// Stores the block's new heights `y1` and speeds, the new cells of the grains (of kind
    /// `kind`) that left theirs, and what `end` found into `found` (the entries near the bed
    /// in ascending order): what [`store`] and [`record`] do lane by lane.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn apply(
        &self,
        u: &Update,
        kind: u32,
        end: &BlockEnd,
        y1: &[f64; LANES],
        ys: &mut [f64],
        vs: &mut [f64],
        cs: &mut [u32],
        found: &mut Found,
    ) {
        let j0 = self.j0;
        ys[j0..j0 + LANES].copy_from_slice(y1);
        vs[j0..j0 + LANES].copy_from_slice(&self.v1);
        found.vmax = found.vmax.max(end.vmax);
        found.bad |= end.bad;
        let mut left = end.left;
        while left != 0 {
            let l = left.trailing_zeros() as usize;
            left &= left - 1;
            move_cell(u, kind, j0 + l, y1[l], cs, found);
        }
        let mut near = end.near;
        while near != 0 {
            let l = near.trailing_zeros() as usize;
            near &= near - 1;
            found.near.push((j0 + l) as u32);
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

/// Stores entry `j`'s new height and speed, finds its new cell, and lists it in `found` as
/// within `reach` of the bed or counts its speed; records whether it now fails the test of
/// [`Stepper::grain_fault`] (`fault`; its horizontal position, constant, was tested by
/// [`super::Suspension::new`]).
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
    store(u, q, j, (y, v, fault), ys, vs, cs, found);
    if y - q.half_d_m <= reach {
        found.near.push(j as u32);
    } else {
        found.vmax = found.vmax.max(v.abs().max(q.stokes_m_s));
    }
}

/// Stores entry `j`'s new height and speed, finds its new cell, and records whether it now
/// fails the fault test (what [`record`] and the lanes of [`Chunk::update_any`] share); a
/// grain that changed cell is listed in `found.moved`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn store(
    u: &Update,
    q: &KindStep,
    j: usize,
    (y, v, fault): (f64, f64, bool),
    ys: &mut [f64],
    vs: &mut [f64],
    cs: &mut [u32],
    found: &mut Found,
) {
    (ys[j], vs[j]) = (y, v);
    move_cell(u, q.kind, j, y, cs, found);
    found.bad |= fault;
}

/// Finds the new cell of entry `j` (of kind `kind`) at height `y` (m; none if not finite) and,
/// if it changed, stores it and lists the grain in `found.moved` (what [`store`] and
/// [`Block::apply`] share).
#[inline(always)]
fn move_cell(u: &Update, kind: u32, j: usize, y: f64, cs: &mut [u32], found: &mut Found) {
    if !y.is_finite() {
        return;
    }
    let (old, new) = (cs[j], u.drag.grid.cell_after(cs[j] as usize, y) as u32);
    if new != old {
        cs[j] = new;
        found.moved.push((old, new, kind));
    }
}
