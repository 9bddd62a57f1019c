//! Leave-one-suspension-out figures for the law with constants fitted to the spheres: f-EDEM's
//! eq. 19, C_d = a/Re′ + b on 1 ≤ Re′ ≤ 150 (a = 29.12, b = 0.195 in f-EDEM). For each
//! suspension, a and b are refitted by least squares on the (Re′, C_d) points of the other
//! suspensions, and the held-out spheres' terminal velocities are predicted with them.

use super::data::{DataSet, Sphere};
use super::eval::{net_weight, State, G_M_S2};
use crate::fluid::bingham::{cd_from_terminal_velocity, reynolds_bingham, yield_drag_n};
use crate::fluid::sphere_area_m2;

/// The (Re′, C_d) point of a sphere of a Bingham fluid: the published one when the file gives
/// it (f-EDEM Table 3), else eq. 14 and eq. 17 at the measured speed. None for a
/// Herschel–Bulkley fluid.
pub fn point(data: &DataSet, s: &Sphere) -> Option<(f64, f64)> {
    let f = &data.fluids[s.fluid];
    if !f.is_bingham() {
        return None;
    }
    if let (Some(re), Some(cd)) = (s.re_tabulated, s.cd_tabulated) {
        return Some((re, cd));
    }
    Some(at_speed(data, s, s.v_measured_m_s))
}

/// (Re′, C_d) of sphere `i` moving at `v` (eq. 14 and eq. 17), if it is in a Bingham fluid, `v`
/// is positive and finite and C_d is positive.
pub fn re_cd(data: &DataSet, i: usize, v: f64) -> Option<(f64, f64)> {
    let s = &data.spheres[i];
    if !data.fluids[s.fluid].is_bingham() || v <= 0.0 || !v.is_finite() {
        return None;
    }
    let (re, cd) = at_speed(data, s, v);
    (cd > 0.0 && re > 0.0).then_some((re, cd))
}

/// Re′ (eq. 14) and the C_d of eq. 17 of sphere `s` at speed `v`, in its (Bingham) fluid.
fn at_speed(data: &DataSet, s: &Sphere, v: f64) -> (f64, f64) {
    let f = &data.fluids[s.fluid];
    let (ty, eb) = (f.rheogram.yield_stress_pa, f.rheogram.consistency_pa_sn);
    let re = reynolds_bingham(f.density_kg_m3, v, s.diameter_m, ty, eb);
    let cd = cd_from_terminal_velocity(
        s.density_kg_m3,
        f.density_kg_m3,
        s.diameter_m,
        ty,
        v,
        G_M_S2,
    );
    (re, cd)
}

/// Least-squares fit of C_d = a/Re′ + b to the points with 1 ≤ Re′ ≤ 150 (residuals in C_d);
/// None with fewer than two distinct such points.
pub fn fit_eq19(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let p: Vec<(f64, f64)> = points
        .iter()
        .filter(|(re, _)| (1.0..=150.0).contains(re))
        .map(|&(re, cd)| (1.0 / re, cd))
        .collect();
    let n = p.len() as f64;
    let (sx, sy) = p.iter().fold((0.0, 0.0), |a, (x, y)| (a.0 + x, a.1 + y));
    let (mx, my) = (sx / n, sy / n);
    let sxx: f64 = p.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    let sxy: f64 = p.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    if p.len() < 2 || sxx <= 0.0 {
        return None;
    }
    let a = sxy / sxx;
    Some((a, my - a * mx))
}

/// Terminal velocity of f-EDEM's law with eq. 19's middle branch a/Re′ + b, m/s, and whether it
/// moves, is static or is held on a jump. Each branch of eq. 9 is a quadratic in v
/// (see [`crate::fluid::bingham`]); the first branch whose drag reaches the net weight `w_n`
/// inside its speed interval gives the root, a branch starting above it holds the sphere on
/// the jump at its start.
pub fn fedem_speed(a: f64, b: f64, rho_f: f64, d: f64, ty: f64, eb: f64, w_n: f64) -> (f64, State) {
    let area = sphere_area_m2(d);
    let fy = yield_drag_n(d, ty);
    let at = |re: f64| {
        let q = re * eb / d;
        (q + (q * q + 4.0 * rho_f * re * ty).sqrt()) / (2.0 * rho_f)
    };
    let (v1, v150) = (at(1.0), at(150.0));
    // (c0, c1, c2, lo, hi) of F = c0 + c1 v + c2 v² on [lo, hi].
    let branches = [
        (fy + 12.0 * area * ty, 12.0 * area * eb / d, 0.0, 0.0, v1),
        (
            fy + 0.5 * a * area * ty,
            0.5 * a * area * eb / d,
            0.5 * b * rho_f * area,
            v1,
            v150,
        ),
        (fy, 0.0, 0.2 * rho_f * area, v150, f64::INFINITY),
    ];
    for (k, &(c0, c1, c2, lo, hi)) in branches.iter().enumerate() {
        let f_lo = c0 + c1 * lo + c2 * lo * lo;
        if f_lo >= w_n {
            return if k == 0 {
                (0.0, State::Static)
            } else {
                (lo, State::Jump)
            };
        }
        let r = if c2 == 0.0 {
            (w_n - c0) / c1
        } else {
            (-c1 + (c1 * c1 + 4.0 * c2 * (w_n - c0)).sqrt()) / (2.0 * c2)
        };
        if r <= hi {
            return (r, State::Moving);
        }
    }
    (f64::INFINITY, State::Moving)
}

/// A held-out sphere's prediction: (sphere index, predicted velocity m/s, state).
pub type HeldOut = (usize, f64, State);
/// Eq. 19 refitted without one fluid: (held-out fluid index, a, b).
pub type Refit = (usize, f64, f64);

/// Leave-one-suspension-out predictions of f-EDEM's law: (sphere index, predicted velocity m/s,
/// state) for every sphere of a Bingham fluid, and the refitted (a, b) per held-out fluid index.
pub fn loso_fedem(data: &DataSet) -> (Vec<HeldOut>, Vec<Refit>) {
    let mut preds = Vec::new();
    let mut fits = Vec::new();
    for (fi, f) in data.fluids.iter().enumerate() {
        if !f.is_bingham() || !data.spheres.iter().any(|s| s.fluid == fi) {
            continue;
        }
        let pts: Vec<(f64, f64)> = data
            .spheres
            .iter()
            .filter(|s| s.fluid != fi)
            .filter_map(|s| point(data, s))
            .collect();
        let Some((a, b)) = fit_eq19(&pts) else {
            continue;
        };
        fits.push((fi, a, b));
        for (i, s) in data
            .spheres
            .iter()
            .enumerate()
            .filter(|(_, s)| s.fluid == fi)
        {
            let (v, st) = fedem_speed(
                a,
                b,
                f.density_kg_m3,
                s.diameter_m,
                f.rheogram.yield_stress_pa,
                f.rheogram.consistency_pa_sn,
                net_weight(data, s),
            );
            preds.push((i, v, st));
        }
    }
    (preds, fits)
}
