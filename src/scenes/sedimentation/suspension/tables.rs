//! The tables per voidage cell of the free update's tabulated step: for the kinds with many
//! grains per cell, what the step reads of each cell's voidage, computed once per cell, kind
//! and step rather than once per grain ([`kind_at_voidage`]).

use super::super::voidage::VoidageGrid;
use super::Suspension;
use crate::dynamics::terminal::kind_at_voidage;
use rayon::prelude::*;

/// The entries of a kind per voidage cell from which the free update computes its tabulated
/// step's terminal state once per cell ([`kind_at_voidage`], eight cells at a time) rather
/// than once per grain. A table entry costs about what it saves one grain (1.3 ns per entry
/// and step on 2 threads, measured with tables for every kind at N = 10⁶: sample 5's run 3.7×
/// slower, 114 B per grain), and holds 32 B: from 8 per cell, the tables cost at most 4 B per
/// grain and an eighth of the Horner chains they save. At N = 10⁶ no kind has so many (a few
/// thousand grains each in 7 329 cells); at sample 2's real count most have (4·10⁵ each).
pub const TABLES_PER_CELL: usize = 8;

impl Suspension {
    /// Computes the tables per cell of this step's free update over `dt_s` (s) in `grid`
    /// (`at`: the kinds with a terminal-state table, on the fast path, and at least
    /// `tables_from` entries, by default [`TABLES_PER_CELL`] per cell), in parallel by kind.
    pub(super) fn fill_tables(&mut self, grid: &VoidageGrid, fast: bool, dt_s: f64) {
        let voidage = grid.voidages();
        let min = self
            .tables_from
            .unwrap_or(TABLES_PER_CELL * (voidage.len() + 1));
        self.at.resize_with(self.kinds.len(), Vec::new);
        if self.kind.len() < min.max(1) {
            // No kind has so many (no hand-over to the threads for nothing).
            self.at.iter_mut().for_each(Vec::clear);
            return;
        }
        let kind = &self.kind;
        self.at
            .par_iter_mut()
            .zip(&self.kinds)
            .enumerate()
            .for_each(|(k, (at, q))| {
                at.clear();
                // The entries in kind order: the kind's by bisection.
                let k = k as u32;
                let n = kind.partition_point(|&x| x <= k) - kind.partition_point(|&x| x < k);
                let table = grid.terminal_table(q.class, q.diameter_m);
                let Some(table) = table.filter(|_| fast && n >= min.max(1)) else {
                    return;
                };
                let dt_over_mass = dt_s / table.mass_kg;
                // Eight cells at a time (their Horner chains interleaved), then voidage 1.
                let cells = voidage.len() + 1;
                let e_of = |c: usize| voidage.get(c).copied().unwrap_or(1.0);
                for c0 in (0..cells).step_by(8) {
                    let e: [f64; 8] = std::array::from_fn(|l| e_of(c0 + l));
                    let [ut, kt, ct, h] = kind_at_voidage::<8>(table, e, dt_over_mass);
                    let n = (cells - c0).min(8);
                    at.extend((0..n).map(|l| [ut[l], kt[l], ct[l], h[l]]));
                }
            });
    }
}
