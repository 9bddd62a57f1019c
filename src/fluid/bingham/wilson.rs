//! Wilson, Horsley, Kealy, Reizes & Horsley (2003): the fall of a sphere in a non-Newtonian
//! fluid computed as in a Newtonian fluid of an *equivalent* viscosity read off the rheogram. It
//! needs only the rheogram, so it serves Herschel–Bulkley fluids τ = τ_y + K γ̇ⁿ (Bingham: n = 1,
//! K = η_B) as well.
//!
//! **Wilson et al.'s method** (forward: from the sphere to its velocity), as implemented here:
//! 1. the mean surface stress of a sphere of net weight W, τ̄_s = W/(π d²) = Δρ g d/6;
//! 2. the reference stress τ_r = 0.3 τ̄_s, its shear rate γ̇_r on the rheogram (τ(γ̇_r) = τ_r),
//!    and the equivalent viscosity μ_eq = τ_r/γ̇_r (the secant of the rheogram at τ_r);
//! 3. the fall velocity of the same sphere in a Newtonian fluid of viscosity μ_eq, here from the
//!    Clift–Gauvin standard drag curve C_N: ½ C_N(ρ_f V d/μ_eq) ρ_f A V² = W.
//!
//! The method has no answer when τ_r ≤ τ_y (no shear rate on the rheogram), i.e. for a yield
//! number τ_y/(Δρ g d) ≥ 0.3/6 = 0.05: that is this law's static limit, a static resistance
//! π d² τ_y/0.3 ≈ 10.5 d² τ_y (close to Beris et al.'s 0.048, [`super::beris`]).
//!
//! **As a drag law F(v)** (what settle needs, for any speed): F(v) is the net weight W that the
//! method above makes fall at exactly v, so the law's terminal velocity is Wilson et al.'s at any
//! Reynolds number. With x = γ̇_r d/(0.9 v) the method's step 3 reads C_N Re/24 = x, where
//! Re = ρ_f v d/μ_eq = 0.9 ρ_f v² x/τ(0.9 x v/d); this has one root x ≥ 1 (solved here by
//! bracketed regula falsi), and
//!
//! F(v) = π d² τ(0.9 x v/d)/0.3.
//!
//! In creeping flow (C_N = 24/Re) x = 1: F = (π d²/0.3) τ(0.9 v/d), i.e. the secant viscosity at
//! γ̇ = 0.9 v/d; in a Newtonian fluid (τ_y = 0, n = 1) μ_eq = K at every stress and F is the
//! Newtonian Clift–Gauvin drag exactly. As v → 0, F → π d² τ_y/0.3.
//!
//! Source: Wilson, K. C., Horsley, R. R., Kealy, T., Reizes, J. A. & Horsley, M. (2003). Direct
//! prediction of fall velocities in non-Newtonian materials. *Int. J. Miner. Process.* 71:17–30.
//! The paper itself could not be consulted here (no page or equation number can be given). What
//! was checked, and against what:
//! - the reference stress 0.3 τ̄_s, and that the method cannot be used when τ_y ≥ 0.3 τ̄_s: the
//!   abstract of Shokrollahzadeh, A. (2015), *Terminal settling velocity of a sphere in a
//!   non-Newtonian fluid*, MSc thesis, University of Alberta, p. ii ("if the fluid yield stress
//!   is larger than the reference shear stress proposed by this method (0.3τ ≤ τ_y), the
//!   correlation cannot be used"). An earlier version of this module read the secant viscosity
//!   at τ̄_s itself (factor 1, static limit Y = 1/6); that was a recollection and is corrected.
//! - τ̄_s = W/(π d²) (the net weight over the sphere's area) and the secant definition of μ_eq are
//!   from recollection; they make the Newtonian case exact and the static limit Y = 0.05
//!   consistent with the thesis's "0.3 τ̄_s ≤ τ_y" (not checked against the paper's equations).
//! - NOT included, because it could not be checked: any further correction of the paper for
//!   shear-thinning fluids above creeping flow, and the paper's own Newtonian curve (V* against
//!   Re*, for which the Clift–Gauvin curve stands in). Not checked against the paper's worked
//!   examples either.

use super::additive::cd_re_clift_gauvin;
use std::f64::consts::PI;

/// Wilson et al.'s reference stress as a fraction of the mean surface stress: τ_r = 0.3 τ̄_s.
pub const WILSON_REFERENCE_FRACTION: f64 = 0.3;

/// Herschel–Bulkley shear stress, Pa: τ = τ_y + K γ̇ⁿ (Bingham for n = 1, K = η_B).
pub fn herschel_bulkley_stress_pa(
    yield_stress_pa: f64,
    consistency_pa_sn: f64,
    flow_index: f64,
    shear_rate_hz: f64,
) -> f64 {
    yield_stress_pa + consistency_pa_sn * shear_rate_hz.max(0.0).powf(flow_index)
}

/// Mean surface stress of a sphere of diameter `d_m` whose net weight is carried by its
/// surface, Pa: τ̄_s = W/(π d²) = Δρ g d/6 (Wilson et al. 2003).
pub fn mean_surface_stress_pa(density_difference_kg_m3: f64, g_m_s2: f64, d_m: f64) -> f64 {
    density_difference_kg_m3 * g_m_s2 * d_m / 6.0
}

/// Secant viscosity of the Herschel–Bulkley rheogram at shear stress `stress_pa`, Pa s: τ/γ̇ with
/// γ̇ = ((τ − τ_y)/K)^(1/n). Infinite at or below the yield stress.
pub fn secant_viscosity_at_stress_pa_s(
    yield_stress_pa: f64,
    consistency_pa_sn: f64,
    flow_index: f64,
    stress_pa: f64,
) -> f64 {
    if stress_pa <= yield_stress_pa {
        return f64::INFINITY;
    }
    let rate = ((stress_pa - yield_stress_pa) / consistency_pa_sn).powf(1.0 / flow_index);
    stress_pa / rate
}

/// Wilson et al.'s equivalent viscosity of a sphere with mean surface stress `mean_stress_pa`,
/// Pa s: the secant viscosity at the reference stress 0.3 τ̄_s (infinite when 0.3 τ̄_s ≤ τ_y,
/// where the method has no answer).
pub fn equivalent_viscosity_pa_s(
    yield_stress_pa: f64,
    consistency_pa_sn: f64,
    flow_index: f64,
    mean_stress_pa: f64,
) -> f64 {
    secant_viscosity_at_stress_pa_s(
        yield_stress_pa,
        consistency_pa_sn,
        flow_index,
        WILSON_REFERENCE_FRACTION * mean_stress_pa,
    )
}

/// Root x ≥ 1 of C_N(Re(x)) Re(x)/24 = x, Re(x) = 0.9 ρ_f v² x/τ(0.9 x v/d) (module doc), for
/// v > 0. The left side is at least 1 at x = 1 and grows more slowly than x (τ grows with x), so
/// the root is bracketed by doubling x and found by regula falsi (Illinois variant) to rounding.
fn reference_rate_ratio(
    fluid_density_kg_m3: f64,
    d_m: f64,
    yield_stress_pa: f64,
    consistency_pa_sn: f64,
    flow_index: f64,
    v: f64,
) -> f64 {
    let f = |x: f64| {
        let tau = herschel_bulkley_stress_pa(
            yield_stress_pa,
            consistency_pa_sn,
            flow_index,
            0.9 * x * v / d_m,
        );
        let re = 0.9 * fluid_density_kg_m3 * v * v * x / tau;
        cd_re_clift_gauvin(re) / 24.0 - x
    };
    let (mut a, mut fa) = (1.0, f(1.0));
    if fa <= 0.0 {
        return 1.0;
    }
    let (mut b, mut fb) = (2.0, f(2.0));
    let mut doublings = 0;
    while fb > 0.0 && doublings < 2000 {
        a = b;
        fa = fb;
        b *= 2.0;
        fb = f(b);
        doublings += 1;
    }
    let mut side = 0;
    let mut c = b;
    for _ in 0..200 {
        c = b - fb * (b - a) / (fb - fa);
        if !(c > a && c < b) {
            c = 0.5 * (a + b);
        }
        let fc = f(c);
        if fc == 0.0 || (b - a) <= 4.0 * f64::EPSILON * b {
            break;
        }
        if fc > 0.0 {
            a = c;
            fa = fc;
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        } else {
            b = c;
            fb = fc;
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        }
        if fc.abs() <= 1e-15 * c {
            break;
        }
    }
    c
}

/// Drag magnitude of Wilson et al.'s law at speed `speed_m_s` ≥ 0, N: the net weight their
/// method makes fall at that speed, F = π d² τ(0.9 x v/d)/0.3 with x the root of the module
/// doc (x = 1 in creeping flow). At v = 0 the static resistance π d² τ_y/0.3.
pub fn wilson_drag_n(
    fluid_density_kg_m3: f64,
    d_m: f64,
    yield_stress_pa: f64,
    consistency_pa_sn: f64,
    flow_index: f64,
    speed_m_s: f64,
) -> f64 {
    let v = speed_m_s.max(0.0);
    if v == 0.0 {
        return wilson_static_resistance_n(d_m, yield_stress_pa);
    }
    let x = reference_rate_ratio(
        fluid_density_kg_m3,
        d_m,
        yield_stress_pa,
        consistency_pa_sn,
        flow_index,
        v,
    );
    let tau_r = herschel_bulkley_stress_pa(
        yield_stress_pa,
        consistency_pa_sn,
        flow_index,
        0.9 * x * v / d_m,
    );
    PI * d_m * d_m * tau_r / WILSON_REFERENCE_FRACTION
}

/// Static resistance of Wilson et al.'s law, N: π d² τ_y/0.3 ≈ 10.47 d² τ_y (the sphere moves
/// when its reference stress 0.3 τ̄_s exceeds the yield stress, i.e. τ_y/(Δρ g d) < 0.05).
pub fn wilson_static_resistance_n(d_m: f64, yield_stress_pa: f64) -> f64 {
    PI * d_m * d_m * yield_stress_pa / WILSON_REFERENCE_FRACTION
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::bingham::net_weight_n;
    use crate::fluid::newtonian::cd_clift_gauvin;
    use crate::fluid::sphere_area_m2;
    use crate::numerics::{bisect, Bisection};

    /// Wilson et al.'s method run forward, independently of the law: τ̄_s from the weight, μ_eq
    /// at 0.3 τ̄_s, then the Newtonian (Clift–Gauvin) terminal velocity by bisection on V.
    fn forward_velocity(rho_f: f64, rho_p: f64, d: f64, g: f64, ty: f64, k: f64, n: f64) -> f64 {
        let w = net_weight_n(d, rho_p, rho_f, g);
        let ts = mean_surface_stress_pa(rho_p - rho_f, g, d);
        let mu = equivalent_viscosity_pa_s(ty, k, n, ts);
        let drag =
            |v: f64| 0.5 * cd_clift_gauvin(rho_f * v * d / mu) * rho_f * sphere_area_m2(d) * v * v;
        let mut hi = 1.0_f64;
        while drag(hi) < w {
            hi *= 2.0;
        }
        let (lo, hi) = bisect(0.0, hi, Bisection::halvings(200), |v| drag(v) < w);
        0.5 * (lo + hi)
    }

    #[test]
    fn newtonian_fluid_gives_the_newtonian_drag_at_every_speed() {
        // τ_y = 0, n = 1: μ_eq = K at any stress, so F is the Clift–Gauvin drag.
        let (rho, d, k) = (1000.0, 0.01, 0.05);
        for v in [1e-6, 1e-3, 0.1, 1.0, 10.0] {
            let f = wilson_drag_n(rho, d, 0.0, k, 1.0, v);
            let re = rho * v * d / k;
            let want = 0.5 * cd_clift_gauvin(re) * rho * sphere_area_m2(d) * v * v;
            assert!((f / want - 1.0).abs() < 1e-12, "v = {v}: {f} vs {want}");
        }
    }

    #[test]
    fn terminal_velocity_is_wilsons_method_run_forward() {
        // Bingham clay (Valentik & Whitmore suspension 1) and a Herschel–Bulkley paste, from
        // creeping flow to Re_eq of order 10²: where the law balances the weight, the speed is
        // the one Wilson et al.'s forward procedure gives.
        let g = 9.81;
        for (rho_f, rho_p, d, ty, k, n) in [
            (1280.0, 6450.0, 0.0159, 30.5, 0.0131, 1.0),
            (1280.0, 7800.0, 0.0254, 30.5, 0.0131, 1.0),
            (1280.0, 11300.0, 0.0571, 30.5, 0.0131, 1.0),
            (1800.0, 7800.0, 0.01, 20.0, 40.0, 0.5),
            (1800.0, 7800.0, 0.02, 20.0, 2.0, 0.5),
        ] {
            assert!(ty / ((rho_p - rho_f) * g * d) < 0.05, "a moving sphere");
            let v = forward_velocity(rho_f, rho_p, d, g, ty, k, n);
            let w = net_weight_n(d, rho_p, rho_f, g);
            let f = wilson_drag_n(rho_f, d, ty, k, n, v);
            assert!(v > 0.0);
            assert!(
                (f / w - 1.0).abs() < 1e-9,
                "d = {d}, n = {n}: F/W = {}",
                f / w
            );
        }
    }

    #[test]
    fn creeping_flow_uses_the_secant_viscosity_at_0_9_v_over_d() {
        // Re_eq ≪ 1: x = 1, F = (π d²/0.3) τ(0.9 v/d) = 3π μ_sec(0.9 v/d) d v.
        let (rho, d, ty, k, n) = (1800.0, 0.005, 20.0, 40.0, 0.5);
        let v = 1e-5;
        let f = wilson_drag_n(rho, d, ty, k, n, v);
        let rate = 0.9 * v / d;
        let mu = herschel_bulkley_stress_pa(ty, k, n, rate) / rate;
        assert!((f / (3.0 * PI * mu * d * v) - 1.0).abs() < 1e-6, "{f}");
    }

    #[test]
    fn static_limit_is_yield_number_0_05() {
        let (rho, d, ty, k, n) = (1280.0, 0.019, 30.5, 0.0131, 1.0);
        let f0 = wilson_drag_n(rho, d, ty, k, n, 0.0);
        assert!((f0 / wilson_static_resistance_n(d, ty) - 1.0).abs() < 1e-12);
        assert!((f0 / (d * d * ty) - 10.472).abs() < 1e-3);
        // The drag is continuous at rest and increases with speed.
        assert!((wilson_drag_n(rho, d, ty, k, n, 1e-12) / f0 - 1.0).abs() < 1e-9);
        let mut prev = f0;
        for i in 1..3000 {
            let f = wilson_drag_n(rho, d, ty, k, n, i as f64 * 1e-3);
            assert!(f > prev, "v = {}", i as f64 * 1e-3);
            prev = f;
        }
        // The weight at the static resistance has τ_y/(Δρ g d) = 0.05: 0.3 τ̄_s = τ_y.
        let drho = ty / (0.05 * 9.81 * d);
        let w = net_weight_n(d, rho + drho, rho, 9.81);
        assert!((w / f0 - 1.0).abs() < 1e-12);
        let ts = mean_surface_stress_pa(drho, 9.81, d);
        assert!(equivalent_viscosity_pa_s(ty, k, n, ts).is_infinite());
    }
}
