//! The pair search of the cylinder's contact stage: a cell list (columns in x, sorted by
//! height) that finds, for one step, every pair of suspended grains whose surface gap can fall
//! below the lubrication cut-off within the step. Grains move only vertically between
//! contacts, so a pair can meet only if their discs overlap horizontally (|Δx| < r₁ + r₂ + h_out),
//! and their vertical separation, monotone over the step, is then smallest at one of its ends
//! (or zero if they cross): the test is exact for the free update of the step, with no travel
//! bound to guess.

use rayon::prelude::*;

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

/// Grains from which [`PairFinder::pairs`] sorts and searches its columns in parallel, and the
/// least each parallel task gets: a small search stays on the calling thread, where it costs
/// less than handing it to the thread pool at every step.
pub const PARALLEL_MIN_GRAINS: usize = 16_384;

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
    ///
    /// From [`PARALLEL_MIN_GRAINS`] grains on, the columns are sorted and searched in parallel
    /// (the result is the same whatever the number of threads). Once an interrupt is requested
    /// ([`crate::interrupt::requested`], checked at each column and every
    /// [`crate::scenes::sedimentation::step::INTERRUPT_CHECK_GRAINS`] grains within one) the
    /// search stops and the list is incomplete: the caller must discard the step.
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
        // Each column sorted (stably: ties keep the binning order) and searched on its own, in
        // parallel from PARALLEL_MIN_GRAINS grains on (each task at least that many grains);
        // the pairs are sorted at the end, so the result does not depend on the order the
        // columns are searched in.
        let binned: usize = self.columns.iter().map(Vec::len).sum();
        let parallel = binned >= PARALLEL_MIN_GRAINS;
        let min_cols = (n_col * PARALLEL_MIN_GRAINS).div_ceil(binned.max(1)).max(1);
        let sort = |col: &mut Vec<u32>| col.sort_by(|a, b| y0(*a).total_cmp(&y0(*b)));
        if parallel {
            self.columns
                .par_iter_mut()
                .with_min_len(min_cols)
                .for_each(sort);
        } else {
            self.columns.iter_mut().for_each(sort);
        }
        // Vertical reach: touching (2 r_max + cut-off) plus the largest relative travel.
        let reach = 2.0 * r_max * (1.0 + 0.5 * outer_fraction) + 2.0 * travel_max;
        let columns = &self.columns;
        // The pairs of grains of column `c` with grains of the same or the next column.
        let search = |c: usize, out: &mut Vec<(usize, usize)>| {
            if crate::interrupt::requested() {
                return;
            }
            let here = &columns[c];
            for (k, &i) in here.iter().enumerate() {
                if (k + 1).is_multiple_of(super::super::step::INTERRUPT_CHECK_GRAINS)
                    && crate::interrupt::requested()
                {
                    return;
                }
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
                if let Some(next) = columns.get(c + 1) {
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
        };
        let mut out = Vec::new();
        if parallel {
            let found: Vec<Vec<(usize, usize)>> = (0..n_col)
                .into_par_iter()
                .with_min_len(min_cols)
                .fold(Vec::new, |mut acc, c| {
                    search(c, &mut acc);
                    acc
                })
                .collect();
            out = found.concat();
        } else {
            for c in 0..n_col {
                search(c, &mut out);
            }
        }
        out.sort_unstable();
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pseudo-random numbers in [0, 1) from `seed` (a 64-bit linear congruential generator).
    fn uniform(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// `n` pseudo-random grains (seed `seed`; every `gap`-th one not in suspension) of radius
    /// 2–35 µm in a box `[width, height]` m, each moving down by up to `drop` m.
    fn grains(
        seed: u64,
        n: usize,
        gap: usize,
        [width, height, drop]: [f64; 3],
    ) -> Vec<Option<Probe>> {
        let mut rnd = uniform(seed);
        (0..n)
            .map(|k| {
                if k % gap == 0 {
                    return None;
                }
                let r = 2e-6 + 33e-6 * rnd();
                let y0 = height * rnd();
                probe(width * rnd(), y0, y0 - drop * rnd(), r)
            })
            .collect()
    }

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
        let probes = grains(12345, 3000, 17, [2e-3, 0.02, 5e-4]);
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
    fn the_parallel_search_finds_the_pairs_of_a_sweep_in_x() {
        // Above PARALLEL_MIN_GRAINS grains (the parallel path), against an independent
        // reference: grains sorted by x, each tested against those within the widest reach.
        let n = PARALLEL_MIN_GRAINS + 4000;
        let probes = grains(987654321, n, 23, [4e-3, 0.05, 2e-4]);
        let mut by_x: Vec<usize> = (0..n).filter(|&i| probes[i].is_some()).collect();
        by_x.sort_by(|&a, &b| probes[a].unwrap().x_m.total_cmp(&probes[b].unwrap().x_m));
        let widest = 2.0 * 35e-6 * 1.05 + 1e-9;
        let mut sweep = Vec::new();
        for (k, &i) in by_x.iter().enumerate() {
            let p = probes[i].unwrap();
            for &j in &by_x[k + 1..] {
                let q = probes[j].unwrap();
                if q.x_m - p.x_m > widest {
                    break;
                }
                if may_meet(&p, &q, 0.1) {
                    sweep.push((i.min(j), i.max(j)));
                }
            }
        }
        sweep.sort_unstable();
        let found = PairFinder::default().pairs(&probes, 4e-3, 0.1);
        assert!(
            sweep.len() > 100,
            "the case must have pairs: {}",
            sweep.len()
        );
        assert_eq!(found, sweep);
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
}
