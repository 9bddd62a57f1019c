//! The two ends of a full block of the free update on AVX-512 ([`super::update`]): the lanes'
//! voidages gathered from their cells, and the end of their step (after-step, fault, bed and
//! cell tests: [`super::update::Block::finish`]) as a few vector operations instead of sixteen
//! lanes one by one. Comparisons, selections and maxima only (no arithmetic but the additions
//! and subtractions of [`after_step`](super::super::step::kernel::after_step), in its order), so
//! the same results as the lane-by-lane code; test `wide_block_end_is_the_lane_by_lane_end`.

use super::block::{BlockEnd, EndConstants, LANES};
use std::arch::x86_64::*;

/// Whether the cell indices `c` may be gathered from a table of `len` entries: every index
/// below `len` (so no [`GONE`](super::update::GONE)), and twice `len` an `i32`.
#[inline]
#[target_feature(enable = "avx512f")]
pub(super) fn gatherable(c: &[u32; LANES], len: usize) -> bool {
    if len == 0 || len >= 1 << 30 {
        return false;
    }
    let n = _mm512_set1_epi32(len as i32);
    (0..LANES / 16).all(|h| {
        // SAFETY: 16 u32 (64 bytes) read from `c` at 16h, in bounds (LANES a multiple of 16).
        let idx = unsafe { _mm512_loadu_si512(c.as_ptr().add(16 * h).cast()) };
        _mm512_cmplt_epu32_mask(idx, n) == u16::MAX
    })
}

/// The voidage of each lane's cell, `voidage[c[l]]`; `c` must pass [`gatherable`] for
/// `voidage.len()`.
#[inline]
#[target_feature(enable = "avx512f")]
pub(super) fn gather(voidage: &[f64], c: &[u32; LANES]) -> [f64; LANES] {
    debug_assert!(gatherable(c, voidage.len()));
    let mut out = [0.0; LANES];
    for h in 0..LANES / 8 {
        // SAFETY: 8 u32 read from `c`, in bounds; every index below voidage.len()
        // ([`gatherable`]); 8 f64 written to `out`, in bounds.
        unsafe {
            let idx = _mm256_loadu_si256(c.as_ptr().add(8 * h).cast());
            let e = _mm512_i32gather_pd::<8>(idx, voidage.as_ptr());
            _mm512_storeu_pd(out.as_mut_ptr().add(8 * h), e);
        }
    }
    out
}

/// What each lane reads of its cell's entry of a kind's table per cell, `at[c[l]][i]` as
/// `out[i][l]`; `c` must pass [`gatherable`] for `at.len()`, which must be below 2²⁸ (the
/// indices 4c + i fit in 32 bits).
#[inline]
#[target_feature(enable = "avx512f")]
pub(super) fn gather_at(at: &[[f64; 4]], c: &[u32; LANES]) -> [[f64; LANES]; 4] {
    debug_assert!(at.len() < 1 << 28 && gatherable(c, at.len()));
    let mut out = [[0.0; LANES]; 4];
    let base = at.as_ptr().cast::<f64>();
    for h in 0..LANES / 8 {
        // SAFETY: 8 u32 read from `c`, in bounds; every index 4c + i < 4 at.len() (`c` passes
        // [`gatherable`]) and below 2³⁰, so the offsets fit an i32 and stay within `at`'s
        // 4 at.len() f64; 8 f64 written to each row of `out`, in bounds.
        unsafe {
            let idx = _mm256_slli_epi32::<2>(_mm256_loadu_si256(c.as_ptr().add(8 * h).cast()));
            for (i, row) in out.iter_mut().enumerate() {
                let at_i = _mm256_add_epi32(idx, _mm256_set1_epi32(i as i32));
                let x = _mm512_i32gather_pd::<8>(at_i, base);
                _mm512_storeu_pd(row.as_mut_ptr().add(8 * h), x);
            }
        }
    }
    out
}

/// The end of a block's step: from the heights `y0` (m) before it, the displacements `dx` (m)
/// and speeds `v1` (m/s) over it, the new heights `y1` (m: [`after_step`]'s, stopping on the
/// bed), and the tests of [`BlockEnd`] against the bounds of the cells `c0` (which must pass
/// [`gatherable`] for `bounds.len()`).
///
/// [`after_step`]: super::super::step::kernel::after_step
#[inline]
#[target_feature(enable = "avx512f")]
pub(super) fn finish(
    k: EndConstants,
    y0: &[f64; LANES],
    dx: &[f64; LANES],
    v1: &[f64; LANES],
    c0: &[u32; LANES],
    bounds: &[(f64, f64)],
    y1: &mut [f64; LANES],
) -> BlockEnd {
    debug_assert!(gatherable(c0, bounds.len()));
    let hd = _mm512_set1_pd(k.half_d_m);
    let floor = _mm512_set1_pd(k.floor_m);
    let on_floor = _mm512_set1_pd(k.floor_m + k.half_d_m);
    let top = _mm512_set1_pd(k.top_m);
    let bound = _mm512_set1_pd(k.speed_bound_m_s);
    let reach = _mm512_set1_pd(k.reach_m);
    let stokes = _mm512_set1_pd(k.stokes_m_s);
    let largest = _mm512_set1_pd(f64::MAX);
    let mut end = BlockEnd {
        left: 0,
        near: 0,
        bad: false,
        vmax: 0.0,
    };
    let mut vmax = _mm512_setzero_pd();
    for h in 0..LANES / 8 {
        // SAFETY: 8 values read from and written to arrays of LANES at 8h; every cell index
        // below bounds.len() < 2^30 ([`gatherable`]), so 2c and 2c + 1 index `bounds` as f64.
        let (v, yn, lo, hi) = unsafe {
            let y = _mm512_add_pd(
                _mm512_loadu_pd(y0.as_ptr().add(8 * h)),
                _mm512_loadu_pd(dx.as_ptr().add(8 * h)),
            );
            // y1 = floor + d/2 where y1 − d/2 ≤ floor (`after_step`).
            let hit = _mm512_cmp_pd_mask::<_CMP_LE_OQ>(_mm512_sub_pd(y, hd), floor);
            let yn = _mm512_mask_blend_pd(hit, y, on_floor);
            _mm512_storeu_pd(y1.as_mut_ptr().add(8 * h), yn);
            let v = _mm512_loadu_pd(v1.as_ptr().add(8 * h));
            let idx = _mm256_loadu_si256(c0.as_ptr().add(8 * h).cast());
            let idx2 = _mm256_slli_epi32::<1>(idx);
            let base = bounds.as_ptr().cast::<f64>();
            let lo = _mm512_i32gather_pd::<8>(idx2, base);
            let hi = _mm512_i32gather_pd::<8>(idx2, base.add(1));
            (v, yn, lo, hi)
        };
        let av = _mm512_abs_pd(v);
        // Not finite (NaN fails the ordered test), faster than the bound, above the top
        // (`vertical_fault`).
        let finite = _mm512_cmp_pd_mask::<_CMP_LE_OQ>(_mm512_abs_pd(yn), largest)
            & _mm512_cmp_pd_mask::<_CMP_LE_OQ>(av, largest);
        let bad = !finite
            | _mm512_cmp_pd_mask::<_CMP_GT_OQ>(av, bound)
            | _mm512_cmp_pd_mask::<_CMP_GT_OQ>(yn, top);
        let near = _mm512_cmp_pd_mask::<_CMP_LE_OQ>(_mm512_sub_pd(yn, hd), reach);
        let inside =
            _mm512_cmp_pd_mask::<_CMP_LE_OQ>(lo, yn) & _mm512_cmp_pd_mask::<_CMP_LT_OQ>(yn, hi);
        // |v|.max(stokes): `max_pd` gives its second operand where either is NaN, as f64::max
        // gives the number (the Stokes speed is one).
        let speed = _mm512_max_pd(av, stokes);
        vmax = _mm512_max_pd(vmax, _mm512_maskz_mov_pd(!near, speed));
        end.bad |= bad != 0;
        end.left |= u32::from(!inside) << (8 * h);
        end.near |= u32::from(near) << (8 * h);
    }
    end.vmax = _mm512_reduce_max_pd(vmax);
    end
}
