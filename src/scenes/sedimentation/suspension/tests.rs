//! The end of a full block of the free update, lane by lane and on AVX-512, against each
//! lane's own [`after_step`] and the tests of `record` (what the per-grain loop does).

use super::super::step::kernel::{after_step, Limits};
use super::update::{Block, BlockEnd, EndConstants, LANES};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A column of `rows` cells of 1 mm each, [lo, hi) in m.
fn column(rows: usize) -> Vec<(f64, f64)> {
    (0..rows)
        .map(|r| (r as f64 * 1e-3, (r + 1) as f64 * 1e-3))
        .collect()
}

/// Random blocks with the cases the tests must tell apart: heights on a cell's bounds, a grain
/// reaching the floor, within reach of the bed, above the top, speeds not finite or beyond the
/// bound.
fn blocks(bounds: &[(f64, f64)], seed: u64) -> Vec<(Block, EndConstants)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let k = EndConstants {
        half_d_m: 5e-5,
        top_m: 0.0995,
        floor_m: 2e-3,
        speed_bound_m_s: 0.5,
        reach_m: 2.5e-3,
        stokes_m_s: 1e-3,
    };
    (0..400)
        .map(|_| {
            let mut b = Block {
                j0: 0,
                y0: [0.0; LANES],
                c0: [0; LANES],
                v1: [0.0; LANES],
                dx: [0.0; LANES],
            };
            for l in 0..LANES {
                let c = rng.random_range(0..bounds.len());
                let (lo, hi) = bounds[c];
                b.c0[l] = c as u32;
                b.y0[l] = rng.random_range(lo..hi);
                b.v1[l] = -rng.random_range(0.0..2e-3);
                b.dx[l] = b.v1[l] * 0.5;
                match rng.random_range(0..12) {
                    0 => b.dx[l] = lo - b.y0[l],
                    1 => b.dx[l] = hi - b.y0[l],
                    2 => b.dx[l] = -b.y0[l],
                    3 => b.dx[l] = k.reach_m + k.half_d_m - b.y0[l],
                    4 => b.dx[l] = 0.2,
                    5 => b.v1[l] = f64::NAN,
                    6 => b.v1[l] = f64::NEG_INFINITY,
                    7 => b.v1[l] = -0.6,
                    8 => b.dx[l] = f64::NAN,
                    _ => {}
                }
            }
            (b, k)
        })
        .collect()
}

/// Each lane alone: [`after_step`], then the tests of `record` and `store`.
fn lane_by_lane(b: &Block, k: EndConstants, bounds: &[(f64, f64)]) -> (BlockEnd, [f64; LANES]) {
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
    let mut y1 = [0.0; LANES];
    for l in 0..LANES {
        let (y, v, bad) = after_step(b.y0[l], (b.v1[l], b.dx[l]), k.half_d_m, k.top_m, lim);
        y1[l] = y;
        end.bad |= bad;
        if y - k.half_d_m <= k.reach_m {
            end.near |= 1 << l;
        } else {
            end.vmax = end.vmax.max(v.abs().max(k.stokes_m_s));
        }
        let (lo, hi) = bounds[b.c0[l] as usize];
        if !(lo <= y && y < hi) {
            end.left |= 1 << l;
        }
    }
    (end, y1)
}

#[test]
fn block_end_is_each_lane_alone() {
    let bounds = column(100);
    let (mut faults, mut left, mut near) = (0, 0, 0);
    for (b, k) in blocks(&bounds, 1) {
        let mut y1 = [0.0; LANES];
        let end = b.end(k, &bounds, &mut y1);
        let (want, want_y1) = lane_by_lane(&b, k, &bounds);
        assert_eq!(end, want);
        assert_eq!(y1.map(f64::to_bits), want_y1.map(f64::to_bits));
        faults += usize::from(end.bad);
        left += end.left.count_ones();
        near += end.near.count_ones();
    }
    // The cases occur (400 blocks of 32 lanes, each case in about 1 lane of 12).
    assert!(
        faults > 100 && left > 1000 && near > 1000,
        "{faults} {left} {near}"
    );
}

#[cfg(target_arch = "x86_64")]
#[test]
fn wide_block_end_is_the_lane_by_lane_end() {
    if !std::arch::is_x86_feature_detected!("avx512f") {
        eprintln!("no AVX-512 on this processor: the wide block end is never used here");
        return;
    }
    let bounds = column(100);
    for (b, k) in blocks(&bounds, 2) {
        // SAFETY: the processor has AVX-512F (checked above).
        assert!(unsafe { super::wide::gatherable(&b.c0, bounds.len()) });
        let (mut y1, mut y1_wide) = ([0.0; LANES], [0.0; LANES]);
        let end = b.end(k, &bounds, &mut y1);
        // SAFETY: as above; every cell below bounds.len().
        let wide =
            unsafe { super::wide::finish(k, &b.y0, &b.dx, &b.v1, &b.c0, &bounds, &mut y1_wide) };
        assert_eq!(wide, end);
        assert_eq!(y1_wide.map(f64::to_bits), y1.map(f64::to_bits));
    }
    let mut c = [3u32; LANES];
    // SAFETY: as above.
    assert!(!unsafe { super::wide::gatherable(&c, 3) });
    c[LANES - 1] = u32::MAX;
    // SAFETY: as above.
    assert!(!unsafe { super::wide::gatherable(&c, 100) });
    let voidage: Vec<f64> = (0..100).map(|i| 0.5 + i as f64 * 1e-3).collect();
    let c: [u32; LANES] = std::array::from_fn(|l| (l * 3) as u32);
    // SAFETY: as above; every index below 100.
    let e = unsafe { super::wide::gather(&voidage, &c) };
    assert_eq!(e, c.map(|i| voidage[i as usize]));
    // A kind's table per cell: each of its four readings of each lane's cell.
    let at: Vec<[f64; 4]> = (0..100)
        .map(|i| std::array::from_fn(|r| (i * 4 + r) as f64 + 0.5))
        .collect();
    // SAFETY: as above; every index below 100.
    let read = unsafe { super::wide::gather_at(&at, &c) };
    for (r, row) in read.iter().enumerate() {
        assert_eq!(*row, c.map(|i| at[i as usize][r]));
    }
}
