//! The solid volume per voidage cell of the packed suspension between fills: the grains that
//! changed cell move theirs ([`move_volumes`]), and the cells whose sums changed are listed
//! ([`Touched`]) so that a fill reads those alone while they are few.

use super::super::voidage::VoidageGrid;
use super::update::Kind;
use rayon::prelude::*;

/// The voidage cells whose sums changed since the last fill ([`super::Suspension::fill`]), listed
/// while they are at most `limit` (a quarter of the cells: reading the list costs less than
/// reading every cell), else `all` (the list emptied); `stamp`: the grid's after that fill
/// ([`VoidageGrid::stamp`]).
#[derive(Clone, Debug, Default)]
pub(super) struct Touched {
    pub(super) cells: Vec<u32>,
    pub(super) all: bool,
    limit: usize,
    pub(super) stamp: u64,
}

impl Touched {
    /// None changed since the fill that left `grid` as it is.
    pub(super) fn reset(&mut self, grid: &VoidageGrid) {
        self.cells.clear();
        self.all = false;
        self.limit = grid.cell_count() / 4;
        self.stamp = grid.stamp();
    }

    /// Notes the `extra` cells of `cells`, or gives up listing if they make too many.
    pub(super) fn note(&mut self, extra: usize, cells: impl IntoIterator<Item = u32>) {
        if self.all || self.cells.len() + extra > self.limit {
            self.all = true;
            self.cells.clear();
        } else {
            self.cells.extend(cells);
        }
    }
}

/// Moves the volume of each grain of `moved` (cell before, cell after, kind: per chunk of a
/// free update) in the sums per cell `sums` (quanta), notes the cells in `touched`, and empties
/// `moved`: from 2¹⁴ grains in parallel, each thread the cells of one range (every list read
/// by each; exact integers, so the same sums however cut), fewer on this thread.
pub(super) fn move_volumes(
    sums: &mut [i128],
    moved: &mut [Vec<(u32, u32, u32)>],
    kinds: &[Kind],
    touched: &mut Touched,
) {
    let count: usize = moved.iter().map(Vec::len).sum();
    if count == 0 {
        return;
    }
    let list = moved.iter().flatten().flat_map(|&(old, new, _)| [old, new]);
    touched.note(2 * count, list);
    let add = |(p, range): (usize, &mut [i128]), part: usize| {
        let (lo, hi) = (p * part, p * part + range.len());
        for &(old, new, k) in moved.iter().flatten() {
            let q = kinds[k as usize].volume_q;
            let (old, new) = (old as usize, new as usize);
            if (lo..hi).contains(&old) {
                range[old - lo] -= q;
            }
            if (lo..hi).contains(&new) {
                range[new - lo] += q;
            }
        }
    };
    if count < 1 << 14 {
        // Few: on this thread (no hand-over to the pool), every cell one range.
        let all = sums.len();
        add((0, sums), all);
    } else {
        let part = sums.len().div_ceil(rayon::current_num_threads()).max(1);
        sums.par_chunks_mut(part)
            .enumerate()
            .for_each(|x| add(x, part));
    }
    moved.iter_mut().for_each(Vec::clear);
}
