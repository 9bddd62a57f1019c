//! The ranges in which the laws settle uses were validated, with their sources, and the warning
//! texts a run prints (and writes to `run.toml [run] warnings`) when it leaves them. Pure: the
//! scenes gather their figures and call these functions.
//!
//! | law | validated range | source |
//! |---|---|---|
//! | Stokes drag, F = 3π η v d | Re = ρ_f v d / η < 0.5 | issue 13 (Re ≈ 0.5); seed 000 §4.2 allows Re < 1 for its Stokes drag and one-way coupling, but the drag is then already ~9 % too small at Re = 0.5 and ~15 % at Re = 1 (Schiller–Naumann correction 0.15 Re^0.687), so settle warns from 0.5 |
//! | Schiller–Naumann C_d | Re < 800 | Schiller & Naumann (1933), via Clift, Grace & Weber (1978) ch. 5 |
//! | Clift–Gauvin C_d | Re < 3·10⁵ | Clift & Gauvin (1971), via Clift, Grace & Weber (1978) ch. 5 |
//! | Morrison C_d | Re ≤ 10⁶ | Morrison (2013), *An Introduction to Fluid Mechanics*, ch. 8 |
//! | f-EDEM's Bingham drag (eq. 9, 14, 19) | sphere density 1314–8135 kg/m³, diameter 8–57.1 mm | f-EDEM §5 (conclusions, l. 504–505): "the applicable particle density obtained by this study ranges from 1314 to 8135 kg/m³ and the particle diameter ranges from 8 to 57.1 mm" |
//! | one-way coupling (the grains do not move the fluid) | volume concentration < 1.6 %, mass concentration < 4 % | seed 000 §4.2: "the volume and mass concentrations must be lower than 1.6% and 4% respectively" |
//!
//! Percent finer above 100 % is not a law outside its range but the counting noise of the
//! representative grains: [`percent_finer_sd`].

/// Largest particle Reynolds number of Stokes' law: 0.5, where Stokes' drag is 9 % below the
/// standard drag curve (Schiller–Naumann factor 1 + 0.15 Re^0.687); seed 000 §4.2 allows Re < 1
/// (15 % below).
pub const STOKES_RE_MAX: f64 = 0.5;

/// Sphere densities of f-EDEM's validated Bingham drag, kg/m³ (f-EDEM §5, l. 504–505).
pub const BINGHAM_FEDEM_DENSITY_KG_M3: (f64, f64) = (1314.0, 8135.0);

/// Sphere diameters of f-EDEM's validated Bingham drag, m (8–57.1 mm, f-EDEM §5, l. 504–505).
pub const BINGHAM_FEDEM_DIAMETER_M: (f64, f64) = (0.008, 0.0571);

/// Largest solid volume concentration of one-way coupling (seed 000 §4.2: 1.6 %).
pub const ONE_WAY_VOLUME_FRACTION_MAX: f64 = 0.016;

/// Largest solid mass concentration (solid mass / suspension mass) of one-way coupling
/// (seed 000 §4.2: 4 %).
pub const ONE_WAY_MASS_FRACTION_MAX: f64 = 0.04;

/// Relative slack on range ends, so that a value written as the end itself (8 mm as 0.008 m)
/// is inside.
const EDGE: f64 = 1e-9;

use crate::fluid::newtonian::CdCorrelation;
use crate::io::fmt::{g, short};

/// The warning for Stokes drag used above [`STOKES_RE_MAX`], or None. `spheres` holds
/// (id, Reynolds number at the sphere's largest terminal velocity, simulated or force balance)
/// of every sphere run with Stokes drag.
pub fn stokes_warning(spheres: &[(String, f64)]) -> Option<String> {
    let above: Vec<&(String, f64)> = spheres
        .iter()
        .filter(|(_, re)| *re > STOKES_RE_MAX)
        .collect();
    let (id, re) = above.iter().max_by(|a, b| a.1.total_cmp(&b.1))?;
    Some(format!(
        "Stokes drag used above its range Re < {} (9 % too little drag at 0.5; seed 000 §4.2 allows Re < 1): {} of {} sphere(s) above, largest Re = {} (sphere {id}, at its \
         simulated or force-balance terminal velocity); Stokes' law then underestimates the drag and overestimates the velocity; use drag.law = \"dallavalle\"",
        short(STOKES_RE_MAX),
        above.len(),
        spheres.len(),
        g(*re),
    ))
}

/// The warning for a C_d correlation used above its stated Reynolds number range
/// ([`CdCorrelation::re_max`]), or None. `spheres` holds (id, Reynolds number at the sphere's
/// terminal velocity) of every sphere run with that correlation.
pub fn correlation_warning(cd: CdCorrelation, spheres: &[(String, f64)]) -> Option<String> {
    let above: Vec<&(String, f64)> = spheres
        .iter()
        .filter(|(_, re)| *re > cd.re_max() * (1.0 + EDGE))
        .collect();
    let (id, re) = above.iter().max_by(|a, b| a.1.total_cmp(&b.1))?;
    Some(format!(
        "{} drag coefficient used above its stated range Re ≤ {}: {} of {} sphere(s) above, largest Re = {} (sphere {id}, at its \
         simulated terminal velocity); the correlation is extrapolated there",
        cd.label(),
        short(cd.re_max()),
        above.len(),
        spheres.len(),
        g(*re),
    ))
}

/// Whether a value lies in `[lo, hi]` (ends included, with a relative slack of 1e-9).
fn inside(x: f64, (lo, hi): (f64, f64)) -> bool {
    x >= lo * (1.0 - EDGE) && x <= hi * (1.0 + EDGE)
}

/// The warning for f-EDEM's Bingham drag used on spheres outside its validated density
/// ([`BINGHAM_FEDEM_DENSITY_KG_M3`]) or diameter ([`BINGHAM_FEDEM_DIAMETER_M`]) range, or None.
/// `spheres` holds (id, density kg/m³, diameter m).
pub fn bingham_fedem_warning(spheres: &[(String, f64, f64)]) -> Option<String> {
    let out: Vec<String> = spheres
        .iter()
        .filter(|(_, rho, d)| {
            !inside(*rho, BINGHAM_FEDEM_DENSITY_KG_M3) || !inside(*d, BINGHAM_FEDEM_DIAMETER_M)
        })
        .map(|(id, rho, d)| format!("{id} ({} kg/m³, {} mm)", short(*rho), short(d * 1e3)))
        .collect();
    if out.is_empty() {
        return None;
    }
    const SHOWN: usize = 5;
    let more = if out.len() > SHOWN {
        format!(" and {} more", out.len() - SHOWN)
    } else {
        String::new()
    };
    Some(format!(
        "f-EDEM's Bingham drag used outside its validated range (sphere density {}–{} kg/m³, diameter {}–{} mm; f-EDEM §5): \
         {} of {} sphere(s): {}{more}",
        short(BINGHAM_FEDEM_DENSITY_KG_M3.0),
        short(BINGHAM_FEDEM_DENSITY_KG_M3.1),
        short(BINGHAM_FEDEM_DIAMETER_M.0 * 1e3),
        short(BINGHAM_FEDEM_DIAMETER_M.1 * 1e3),
        out.len(),
        spheres.len(),
        out[..out.len().min(SHOWN)].join(", "),
    ))
}

/// Solid mass concentration of a suspension, solid mass / suspension mass, from its solid
/// volume fraction `c` and the densities: c ρ_p / (c ρ_p + (1 − c) ρ_f).
pub fn mass_fraction(volume_fraction: f64, grain_kg_m3: f64, fluid_kg_m3: f64) -> f64 {
    let solid = volume_fraction * grain_kg_m3;
    solid / (solid + (1.0 - volume_fraction) * fluid_kg_m3)
}

/// The warning for a suspension too concentrated for one-way coupling (seed 000 §4.2: volume
/// concentration < [`ONE_WAY_VOLUME_FRACTION_MAX`], mass concentration <
/// [`ONE_WAY_MASS_FRACTION_MAX`]), or None. `volume_fraction` is the initial (homogeneous)
/// solid volume fraction; the densities are kg/m³.
pub fn one_way_coupling_warning(
    volume_fraction: f64,
    grain_kg_m3: f64,
    fluid_kg_m3: f64,
) -> Option<String> {
    let mass = mass_fraction(volume_fraction, grain_kg_m3, fluid_kg_m3);
    if volume_fraction <= ONE_WAY_VOLUME_FRACTION_MAX && mass <= ONE_WAY_MASS_FRACTION_MAX {
        return None;
    }
    Some(format!(
        "one-way coupling beyond its range (seed 000 §4.2: volume concentration < {} %, mass concentration < {} %): \
         the initial suspension has {} % by volume and {} % by mass; the grains' effect on the water (return flow, \
         hindered settling beyond the voidage factor) is not modelled",
        short(100.0 * ONE_WAY_VOLUME_FRACTION_MAX),
        short(100.0 * ONE_WAY_MASS_FRACTION_MAX),
        crate::io::fmt::sig(100.0 * volume_fraction, 3),
        crate::io::fmt::sig(100.0 * mass, 3),
    ))
}

/// 1σ of a percent-finer reading w made from `n` representative grains counted in the
/// instrument's volume, %.
///
/// The grains are placed independently, each in the instrument's volume with probability p
/// (the volume's share of the suspension): the count is binomial, n ~ B(N, p), of mean N p and
/// variance N p (1 − p). The reading is proportional to the count, w = w̄ n / (N p), so
/// σ_w = w̄ √((1 − p)/(N p)); with the count itself as the estimate of N p,
///
/// σ_w = w √((1 − p) / n)   (→ w / √n, the Poisson limit, for a small volume, p ≪ 1).
///
/// Grains of unequal weight (mass) m_i replace n by the effective count (Σ m_i)² / Σ m_i²,
/// which is how the instruments compute their `sd_percent` (√Σ m_i² against Σ m_i). Infinite
/// for n = 0.
pub fn percent_finer_sd(percent_finer: f64, n: f64, share_p: f64) -> f64 {
    if n <= 0.0 {
        return f64::INFINITY;
    }
    percent_finer.abs() * ((1.0 - share_p).max(0.0) / n).sqrt()
}

/// One reading above 100 %: instrument, time (s), percent finer (%), its 1σ (%).
pub type OverReading = (String, f64, f64, f64);

/// The explanation of percent-finer readings above 100 %, or None when there are none: the
/// noise of the grain count ([`percent_finer_sd`]), each reading with its time in minutes, its
/// 1σ, the effective number of grains it counted, n = (w/σ)² (the inverse of the Poisson
/// limit), and how many σ it lies above 100 %. `grains` is the number of representative grains
/// of the run.
pub fn percent_finer_above_100_warning(readings: &[OverReading], grains: usize) -> Option<String> {
    let over: Vec<&OverReading> = readings.iter().filter(|r| r.2 > 100.0).collect();
    if over.is_empty() {
        return None;
    }
    let list: Vec<String> = over
        .iter()
        .map(|(name, t, w, sd)| {
            format!(
                "{name} {} % at {} min (1σ = {} %, n ≈ {:.0} grains, {}σ above 100 %)",
                crate::io::fmt::sig(*w, 4),
                short(t / 60.0),
                crate::io::fmt::sig(*sd, 2),
                (w / sd).powi(2),
                crate::io::fmt::sig((w - 100.0) / sd, 2),
            )
        })
        .collect();
    let beyond = over.iter().any(|(_, _, w, sd)| (w - 100.0) > 3.0 * sd);
    Some(format!(
        "percent finer above 100 % in {} reading(s): {}. With {grains} representative grains an instrument counts few of them \
         in its volume: a reading of n grains has the counting noise 1σ = w √((1 − p)/n) ≈ w/√n (binomial/Poisson), \
         so readings scatter about 100 % before the coarse grains have passed; {}; more grains (sample.particles) \
         reduce it as 1/√N",
        over.len(),
        list.join(", "),
        if beyond {
            "at least one lies more than 3σ above 100 %, more than the noise explains"
        } else {
            "every one lies within 3σ of 100 %, as the noise explains"
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stokes_warns_only_above_its_range() {
        assert_eq!(stokes_warning(&[("a".into(), 0.49)]), None);
        let w = stokes_warning(&[("a".into(), 0.5), ("b".into(), 3.7e6)]).unwrap();
        assert!(w.contains("1 of 2") && w.contains("3.700e6") && w.contains("sphere b"));
        assert!(w.contains("drag.law = \"dallavalle\""), "{w}");
    }

    #[test]
    fn correlations_warn_only_above_their_stated_range() {
        let sn = CdCorrelation::SchillerNaumann;
        assert_eq!(correlation_warning(sn, &[("a".into(), 800.0)]), None);
        let w = correlation_warning(sn, &[("a".into(), 10.0), ("b".into(), 1200.0)]).unwrap();
        assert!(
            w.starts_with("Schiller–Naumann (1933)") && w.contains("Re ≤ 800"),
            "{w}"
        );
        assert!(
            w.contains("1 of 2") && w.contains("sphere b") && w.contains("1200"),
            "{w}"
        );
        assert_eq!(
            correlation_warning(CdCorrelation::CliftGauvin, &[("b".into(), 1200.0)]),
            None
        );
        let w = correlation_warning(CdCorrelation::Morrison, &[("c".into(), 2e6)]).unwrap();
        assert!(w.contains("Re ≤ 1e6:"), "{w}");
    }

    #[test]
    fn bingham_range_ends_are_inside() {
        let ok = [("lo".into(), 1314.0, 0.008), ("hi".into(), 8135.0, 0.0571)];
        assert_eq!(bingham_fedem_warning(&ok), None);
        let w = bingham_fedem_warning(&[("x".into(), 8135.0, 0.005)]).unwrap();
        assert!(w.contains("x (8135 kg/m³, 5 mm)"), "{w}");
        assert!(bingham_fedem_warning(&[("y".into(), 1200.0, 0.01)]).is_some());
    }

    #[test]
    fn one_way_limits() {
        assert_eq!(one_way_coupling_warning(0.01, 2500.0, 1000.0), None);
        // 1.66 % by volume (60 g of 2500 kg/m³ grains in the 1.447 L cylinder).
        let w = one_way_coupling_warning(0.0166, 2500.0, 1000.0).unwrap();
        assert!(w.contains("1.66 % by volume"), "{w}");
        // Mass concentration alone: 1.5 % by volume of 5000 kg/m³ grains is 7.1 % by mass.
        assert!(one_way_coupling_warning(0.015, 5000.0, 1000.0).is_some());
        let m = mass_fraction(0.015, 5000.0, 1000.0);
        assert!((m - 75.0 / (75.0 + 985.0)).abs() < 1e-12);
    }

    /// The 1σ formula against a direct computation of the binomial spread: N grains each in the
    /// volume with probability p; the reading is 100 n/(N p). A seeded generator, 20 000 draws.
    #[test]
    fn percent_finer_sd_matches_a_monte_carlo_of_the_count() {
        let (grains, p) = (2000usize, 0.02);
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let draws = 20_000;
        let readings: Vec<f64> = (0..draws)
            .map(|_| {
                let n = (0..grains).filter(|_| uniform() < p).count();
                100.0 * n as f64 / (grains as f64 * p)
            })
            .collect();
        let mean = readings.iter().sum::<f64>() / draws as f64;
        let var = readings.iter().map(|w| (w - mean).powi(2)).sum::<f64>() / (draws - 1) as f64;
        let predicted = percent_finer_sd(100.0, grains as f64 * p, p);
        // Standard error of a sample σ over 20 000 draws: σ/√(2·20 000) ≈ 0.5 %.
        assert!(
            (var.sqrt() / predicted - 1.0).abs() < 0.02,
            "Monte Carlo σ {} vs formula {predicted}",
            var.sqrt()
        );
        assert!((mean - 100.0).abs() < 0.2, "{mean}");
        // Poisson limit.
        assert!((percent_finer_sd(100.0, 25.0, 0.0) - 20.0).abs() < 1e-12);
        assert!(percent_finer_sd(100.0, 0.0, 0.0).is_infinite());
    }

    #[test]
    fn above_100_is_explained_only_when_present() {
        assert_eq!(
            percent_finer_above_100_warning(&[("pipette".into(), 30.0, 99.0, 3.0)], 5000),
            None
        );
        let w = percent_finer_above_100_warning(
            &[
                ("pipette".into(), 30.0, 104.9, 3.5),
                ("hydrometer".into(), 120.0, 99.0, 1.0),
            ],
            5000,
        )
        .unwrap();
        assert!(
            w.contains("1 reading(s)") && w.contains("pipette 104.9 % at 0.5 min"),
            "{w}"
        );
        assert!(
            w.contains("1σ = 3.5 %, n ≈ 898 grains, 1.4σ above 100 %"),
            "{w}"
        );
        assert!(w.contains("within 3σ"), "{w}");
    }
}
