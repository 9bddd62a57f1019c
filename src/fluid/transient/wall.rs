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

/// Largest sphere-to-cylinder diameter ratio d/D at which [`haberman_sayre_factor`] is used:
/// Haberman & Sayre compared their formula with falling-ball measurements up to about 0.8.
pub const HABERMAN_SAYRE_MAX_RATIO: f64 = 0.8;

/// Haberman & Sayre's (1958) factor K ≥ 1 on the drag of a sphere moving along the axis of a
/// circular cylinder, in creeping flow (David Taylor Model Basin Report 1143), λ = d/D:
///
/// K = (1 − 0.75857 λ⁵) / (1 − 2.1050 λ + 2.0865 λ³ − 1.7068 λ⁵ + 0.72603 λ⁶),
///
/// so that the terminal speed is v∞/K. It agrees with Faxén's series
/// K = 1/(1 − 2.10444 λ + 2.08877 λ³ − 0.94813 λ⁵ − 1.372 λ⁶ + 3.87 λ⁸ − 4.19 λ¹⁰) (Happel &
/// Brenner 1965, §7-4) to 2e-4 for λ ≤ 0.15. Range: Re → 0 and 0 ≤ λ ≤
/// [`HABERMAN_SAYRE_MAX_RATIO`]; at finite Re the walls slow a sphere less (Di Felice 1996;
/// Chhabra, Agarwal & Chaudhary 2003), so applying K to the whole drag there overstates the effect.
pub fn haberman_sayre_factor(ratio: f64) -> f64 {
    let l = ratio;
    let (l3, l5) = (l.powi(3), l.powi(5));
    (1.0 - 0.75857 * l5) / (1.0 - 2.1050 * l + 2.0865 * l3 - 1.7068 * l5 + 0.72603 * l5 * l)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Faxén's series (Happel & Brenner 1965, eq. 7-4.28), an independent computation of the
    /// same creeping-flow factor, valid for small λ.
    fn faxen(l: f64) -> f64 {
        1.0 / (1.0 - 2.10444 * l + 2.08877 * l.powi(3) - 0.94813 * l.powi(5) - 1.372 * l.powi(6)
            + 3.87 * l.powi(8)
            - 4.19 * l.powi(10))
    }

    #[test]
    fn haberman_sayre_agrees_with_faxen_at_small_ratio() {
        assert_eq!(haberman_sayre_factor(0.0), 1.0);
        for l in [0.01, 0.05, 0.1, 0.15] {
            let (hs, fx) = (haberman_sayre_factor(l), faxen(l));
            assert!((hs / fx - 1.0).abs() < 2e-4, "λ = {l}: {hs} vs {fx}");
        }
        // Monotone: a wider sphere in the same tube is slowed more.
        let mut last = 1.0;
        for i in 1..=80 {
            let k = haberman_sayre_factor(i as f64 * 0.01);
            assert!(k > last, "λ = {}: {k} ≤ {last}", i as f64 * 0.01);
            last = k;
        }
    }

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
