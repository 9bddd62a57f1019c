//! Wall corrections of the drag on a sphere: the approach to a plane wall (the container bottom).
//!
//! **Brenner (1961)**, *The slow motion of a sphere through a viscous fluid towards a plane
//! surface*, Chem. Eng. Sci. 16:242, exact in Stokes flow (Re → 0): the drag on a sphere of radius
//! R whose centre is at distance h from the wall, moving normal to it, is λ times Stokes' drag,
//!
//! λ = (4/3) sinh α Σ_{n≥1} n(n+1)/((2n−1)(2n+3)) ·
//!     [(2 sinh((2n+1)α) + (2n+1) sinh 2α) / (4 sinh²((n+½)α) − (2n+1)² sinh² α) − 1],
//!
//! α = arcosh(h/R). λ → 1 + 9R/(8h) far from the wall and λ → ∞ at contact. Below a gap
//! δ = h − R of 1e-3 R the series needs thousands of terms; there the lubrication asymptote of
//! Cox & Brenner (1967, Chem. Eng. Sci. 22:1753), λ ≈ R/δ + (1/5) ln(R/δ) + 0.971, is used (the
//! two agree to 1e-3 there). Range: creeping flow; at finite Re the correction is applied to the
//! whole drag, as DEM codes usually do, which overstates it once the Oseen length ν/v is shorter
//! than the gap (ten Cate et al. 2002 discuss this for their sphere; docs/validation/transient.md).

/// Gap (in radii) below which the Cox–Brenner lubrication asymptote replaces Brenner's series.
pub const LUBRICATION_GAP_RADII: f64 = 1e-3;

/// Brenner's factor λ ≥ 1 on the drag of a sphere of radius `radius_m` whose surface is
/// `gap_m` from a plane wall, moving normal to it (module docs). Infinite at contact or overlap.
pub fn brenner_factor(gap_m: f64, radius_m: f64) -> f64 {
    if gap_m <= 0.0 {
        return f64::INFINITY;
    }
    let eps = gap_m / radius_m;
    if eps < LUBRICATION_GAP_RADII {
        return 1.0 / eps + 0.2 * (1.0 / eps).ln() + 0.971;
    }
    let alpha = (1.0 + eps).acosh();
    let (sa, s2a) = (alpha.sinh(), (2.0 * alpha).sinh());
    let mut sum = 0.0;
    for n in 1..100_000 {
        let nf = n as f64;
        let x = (2.0 * nf + 1.0) * alpha;
        if x > 60.0 {
            break;
        }
        let num = 2.0 * x.sinh() + (2.0 * nf + 1.0) * s2a;
        let sh = (0.5 * x).sinh();
        let den = 4.0 * sh * sh - (2.0 * nf + 1.0).powi(2) * sa * sa;
        sum += nf * (nf + 1.0) / ((2.0 * nf - 1.0) * (2.0 * nf + 3.0)) * (num / den - 1.0);
    }
    4.0 / 3.0 * sa * sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brenner_tends_to_the_method_of_reflections_far_away() {
        for h_over_r in [20.0, 50.0] {
            let l = brenner_factor(h_over_r - 1.0, 1.0);
            let far = 1.0 + 9.0 / (8.0 * h_over_r);
            // The next reflection is O((R/h)²) of the first.
            assert!((l - far).abs() < 0.1 * (far - 1.0), "{l} vs {far}");
        }
    }

    /// Brenner's Table 1 (1961): λ = 3.036 at h/R = 1.5431 (α = 1), 1.4129 at h/R = 3.7622
    /// (α = 2), 9.2518 at h/R = 1.1276 (α = 0.5).
    #[test]
    fn brenner_matches_his_table() {
        for (alpha, want) in [(1.0f64, 3.0361), (2.0, 1.4129), (0.5, 9.2518)] {
            let got = brenner_factor(alpha.cosh() - 1.0, 1.0);
            assert!(
                (got / want - 1.0).abs() < 2e-4,
                "α {alpha}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn the_lubrication_asymptote_joins_the_series() {
        let e = LUBRICATION_GAP_RADII;
        let series = brenner_factor(e * 1.0001, 1.0);
        let lub = brenner_factor(e * 0.9999, 1.0);
        assert!((series / lub - 1.0).abs() < 1e-3, "{series} vs {lub}");
        assert_eq!(brenner_factor(0.0, 1.0), f64::INFINITY);
    }
}
