//! Soil samples: cumulative grain-size distributions, their discretisation into n_φ diameters
//! (seed 000 §4.4, Fig. 5, eq. 15), and representative grains with statistical weights placed by
//! stratified random sampling (seed Fig. 6).

use crate::error::BadInput;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;
use std::path::Path;

/// A cumulative distribution: percent finer by mass, piecewise linear in log₁₀ d.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution {
    /// (diameter m, percent finer %) points, ascending in diameter.
    pub points: Vec<(f64, f64)>,
}

impl Distribution {
    /// Percent finer (0–100) at diameter `d_m`, linear in log d between points, 0 below the
    /// first and 100 above the last.
    pub fn percent_finer(&self, d_m: f64) -> f64 {
        let p = &self.points;
        if d_m < p[0].0 {
            return 0.0;
        }
        for w in p.windows(2) {
            let ((d0, f0), (d1, f1)) = (w[0], w[1]);
            if d_m <= d1 {
                let f = (d_m / d0).ln() / (d1 / d0).ln();
                return f0 + f * (f1 - f0);
            }
        }
        100.0
    }

    /// Smallest and largest diameter of the distribution, m.
    pub fn range_m(&self) -> (f64, f64) {
        (self.points[0].0, self.points[self.points.len() - 1].0)
    }

    /// Reads sample `sample` from a CSV with columns `sample, diameter_m, percent_finer` (no
    /// range checks beyond those of a distribution: the scenario layer's reader,
    /// `scenario::inputs::read_sample`, checks every row). Errors name the file and the row.
    pub fn load(path: &Path, sample: u32) -> Result<Self, BadInput> {
        let mut rdr = csv::ReaderBuilder::new()
            .comment(Some(b'#'))
            .from_path(path)
            .map_err(|e| BadInput::new(path, None, format!("cannot read the file: {e}")))?;
        let mut points = Vec::new();
        for (i, rec) in rdr.records().enumerate() {
            let row = format!("row {}", i + 2);
            let rec = rec.map_err(|e| BadInput::new(path, Some(&row), e.to_string()))?;
            let f = |k: usize| -> Result<f64, BadInput> {
                rec.get(k)
                    .and_then(|s| s.trim().parse::<f64>().ok())
                    .ok_or_else(|| {
                        BadInput::new(
                            path,
                            Some(&row),
                            format!("column {} is not a number", k + 1),
                        )
                    })
            };
            if f(0)? as u32 == sample {
                points.push((f(1)?, f(2)?));
            }
        }
        if points.len() < 2 {
            return Err(BadInput::new(
                path,
                None,
                format!("fewer than two points for sample {sample}"),
            ));
        }
        let ok = points
            .windows(2)
            .all(|w| w[1].0 > w[0].0 && w[1].1 >= w[0].1)
            && points
                .iter()
                .all(|p| p.0 > 0.0 && (0.0..=100.0).contains(&p.1));
        if !ok {
            return Err(BadInput::new(
                path,
                None,
                format!("sample {sample}: diameters must increase, percent finer must not decrease and stay within 0–100"),
            ));
        }
        Ok(Self { points })
    }
}

/// One discrete diameter of a sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SizeClass {
    /// Diameter φ_n, m.
    pub diameter_m: f64,
    /// Mass fraction of the sample carried by this diameter, (w_n − w_{n−1})/100.
    pub mass_fraction: f64,
}

/// Discretises a distribution into `n` log-spaced diameters φ_n (seed Fig. 5): the weight of φ_n
/// is w_n − w_{n−1}, with w_n the percent finer at the mid-size (φ_n + φ_{n+1})/2 and w_n = 100
/// for the largest.
pub fn discretize(dist: &Distribution, n: usize) -> Vec<SizeClass> {
    let (d0, d1) = dist.range_m();
    let phi: Vec<f64> = (0..n)
        .map(|i| d0 * (d1 / d0).powf(i as f64 / (n - 1) as f64))
        .collect();
    let mut prev = 0.0;
    phi.iter()
        .enumerate()
        .map(|(i, &d)| {
            let w = if i + 1 < n {
                dist.percent_finer(0.5 * (d + phi[i + 1]))
            } else {
                100.0
            };
            let c = SizeClass {
                diameter_m: d,
                mass_fraction: (w - prev) / 100.0,
            };
            prev = w;
            c
        })
        .collect()
}

/// Number of real grains of a class in a sample of mass `mass_kg` (seed eq. 15):
/// n = 6 m (w_n − w_{n−1}) / (100 ρ_p π φ_n³).
pub fn real_count(class: &SizeClass, mass_kg: f64, density_kg_m3: f64) -> f64 {
    6.0 * mass_kg * class.mass_fraction / (density_kg_m3 * PI * class.diameter_m.powi(3))
}

/// A representative grain: one simulated body standing for `weight` real grains of its class.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Grain {
    /// Horizontal position in the B × H rectangle, m (0 at the left wall).
    pub x_m: f64,
    /// Height of the centre above the bottom, m.
    pub y_m: f64,
    /// Diameter, m.
    pub diameter_m: f64,
    /// Number of real grains it represents.
    pub weight: f64,
    /// Index of its size class.
    pub class: usize,
}

/// `n` representative grains of a sample of mass `mass_kg` (the modelled part, e.g. 1/180 of the
/// cylinder's): each class with mass gets max(1, round(n × mass fraction)) grains of equal
/// weight, so every grain stands for about the same mass. Grains are shuffled (seeded) and placed
/// by stratified random sampling in a √n × √n grid of cells of the rectangle's aspect ratio.
pub fn representative_grains(
    classes: &[SizeClass],
    n: usize,
    mass_kg: f64,
    density_kg_m3: f64,
    width_m: f64,
    height_m: f64,
    seed: u64,
) -> Vec<Grain> {
    let mut grains = Vec::with_capacity(n + classes.len());
    for (i, c) in classes.iter().enumerate() {
        if c.mass_fraction <= 0.0 {
            continue;
        }
        let k = ((n as f64 * c.mass_fraction).round() as usize).max(1);
        let weight = real_count(c, mass_kg, density_kg_m3) / k as f64;
        push_class(&mut grains, c, i, k, weight);
    }
    place(grains, width_m, height_m, seed)
}

/// The number of real grains of a sample of mass `mass_kg` over `classes`: Σ round(nᵢ) of
/// [`real_count`] (what [`real_grains`] makes).
pub fn real_total(classes: &[SizeClass], mass_kg: f64, density_kg_m3: f64) -> usize {
    classes
        .iter()
        .map(|c| real_count(c, mass_kg, density_kg_m3).round() as usize)
        .sum()
}

/// Every real grain of a sample of mass `mass_kg` (the modelled part), each of weight 1
/// (`sample.particles = "real"`): class i gets round(nᵢ) grains ([`real_count`], seed eq. 15),
/// so the mass simulated differs from `mass_kg` only by that rounding (below half a grain per
/// class). Shuffled and placed as [`representative_grains`] places them.
pub fn real_grains(
    classes: &[SizeClass],
    mass_kg: f64,
    density_kg_m3: f64,
    width_m: f64,
    height_m: f64,
    seed: u64,
) -> Vec<Grain> {
    let mut grains = Vec::with_capacity(real_total(classes, mass_kg, density_kg_m3));
    for (i, c) in classes.iter().enumerate() {
        let k = real_count(c, mass_kg, density_kg_m3).round() as usize;
        push_class(&mut grains, c, i, k, 1.0);
    }
    place(grains, width_m, height_m, seed)
}

/// Appends `k` grains of class `c` (index `i`), each of weight `weight`, at the origin.
fn push_class(grains: &mut Vec<Grain>, c: &SizeClass, i: usize, k: usize, weight: f64) {
    grains.extend((0..k).map(|_| Grain {
        x_m: 0.0,
        y_m: 0.0,
        diameter_m: c.diameter_m,
        weight,
        class: i,
    }));
}

/// Shuffles `grains` (seeded) and places them by stratified random sampling in a √n × √n grid
/// of cells of the width_m × height_m rectangle.
fn place(mut grains: Vec<Grain>, width_m: f64, height_m: f64, seed: u64) -> Vec<Grain> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    grains.shuffle(&mut rng);
    let m = (grains.len() as f64).sqrt().ceil() as usize;
    let (cw, ch) = (width_m / m as f64, height_m / m as f64);
    let (cells, n_grains) = (m * m, grains.len());
    for (i, g) in grains.iter_mut().enumerate() {
        // Spread the grains evenly over all m² cells (the last cells are not left empty).
        let cell = i * cells / n_grains;
        let (cx, cy) = ((cell % m) as f64, (cell / m) as f64);
        let r = 0.5 * g.diameter_m;
        g.x_m = ((cx + rng.random::<f64>()) * cw).clamp(r, width_m - r);
        g.y_m = ((cy + rng.random::<f64>()) * ch).clamp(r, height_m - r);
    }
    grains
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample5() -> Distribution {
        Distribution {
            points: vec![(2.5e-6, 0.0), (70e-6, 100.0)],
        }
    }

    #[test]
    fn percent_finer_is_linear_in_log_d() {
        let d = sample5();
        let mid = (2.5e-6f64 * 70e-6).sqrt();
        assert!((d.percent_finer(mid) - 50.0).abs() < 1e-9);
        assert_eq!(d.percent_finer(1e-6), 0.0);
        assert_eq!(d.percent_finer(1e-4), 100.0);
    }

    #[test]
    fn discretisation_conserves_mass_and_follows_the_curve() {
        let d = sample5();
        let c = discretize(&d, 220);
        assert_eq!(c.len(), 220);
        let total: f64 = c.iter().map(|x| x.mass_fraction).sum();
        assert!((total - 1.0).abs() < 1e-12);
        // Cumulative mass at a class equals the curve at its upper mid-size.
        let mut cum = 0.0;
        for i in 0..219 {
            cum += c[i].mass_fraction;
            let mid = 0.5 * (c[i].diameter_m + c[i + 1].diameter_m);
            assert!((cum * 100.0 - d.percent_finer(mid)).abs() < 1e-9);
        }
    }

    #[test]
    fn eq15_counts_reproduce_the_mass() {
        let c = discretize(&sample5(), 220);
        let (m, rho) = (0.06 / 180.0, 2500.0);
        let mass: f64 = c
            .iter()
            .map(|x| real_count(x, m, rho) * rho * PI * x.diameter_m.powi(3) / 6.0)
            .sum();
        assert!((mass / m - 1.0).abs() < 1e-12);
    }

    /// `particles = "real"`: every grain has weight 1, class i holds round(nᵢ) grains (seed eq.
    /// 15), and the mass differs from the sample's only by that rounding (at most half a grain
    /// of each class). A sample of 1.3e-5 kg of sample 5 in the 1/180 wedges: ~23 000 grains.
    #[test]
    fn real_grains_are_every_grain_at_weight_one() {
        let c = discretize(&sample5(), 220);
        let (m, rho) = (1.3e-5 / 180.0, 2500.0);
        let g = real_grains(&c, m, rho, 0.0635, 0.457, 7);
        assert_eq!(g.len(), real_total(&c, m, rho));
        assert!(g.len() > 10_000, "{}", g.len());
        assert!(g.iter().all(|x| x.weight == 1.0));
        let mut per_class = vec![0usize; c.len()];
        for x in &g {
            per_class[x.class] += 1;
            assert!(x.x_m > 0.0 && x.x_m < 0.0635 && x.y_m > 0.0 && x.y_m < 0.457);
        }
        let mut slack = 0.0;
        for (i, k) in per_class.iter().enumerate() {
            assert_eq!(*k, real_count(&c[i], m, rho).round() as usize, "class {i}");
            slack += 0.5 * rho * PI * c[i].diameter_m.powi(3) / 6.0;
        }
        let mass: f64 = g
            .iter()
            .map(|x| rho * PI * x.diameter_m.powi(3) / 6.0)
            .sum();
        assert!(
            (mass - m).abs() <= slack,
            "{mass} kg against {m} kg ± {slack}"
        );
    }

    #[test]
    fn representative_grains_carry_the_mass_and_fill_the_rectangle() {
        let c = discretize(&sample5(), 220);
        let (m, rho) = (0.06 / 180.0, 2500.0);
        let g = representative_grains(&c, 20_000, m, rho, 0.0635, 0.457, 7);
        let mass: f64 = g
            .iter()
            .map(|x| x.weight * rho * PI * x.diameter_m.powi(3) / 6.0)
            .sum();
        assert!((mass / m - 1.0).abs() < 1e-12);
        // Rounding per class: within half a grain per class of N.
        assert!(
            (g.len() as f64 - 20_000.0).abs() <= 0.5 * c.len() as f64,
            "{}",
            g.len()
        );
        // Stratified: each horizontal tenth of the height holds 10 % of the grains (±1 %).
        // Regression: grains filled the √n × √n cells row by row and left the top rows empty
        // (the top tenth held 1781 of 2000 grains).
        for k in 0..10 {
            let n = g
                .iter()
                .filter(|x| ((x.y_m / 0.0457) as usize).min(9) == k)
                .count();
            assert!(
                (n as f64 / g.len() as f64 - 0.1).abs() < 0.01,
                "band {k}: {n}"
            );
        }
        // Same seed, same grains.
        assert_eq!(
            g,
            representative_grains(&c, 20_000, m, rho, 0.0635, 0.457, 7)
        );
    }
}
