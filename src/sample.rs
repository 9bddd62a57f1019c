//! Soil samples: cumulative grain-size distributions, their discretisation into n_φ diameters
//! (seed 000 §4.4, Fig. 5, eq. 15), and representative grains with statistical weights placed by
//! stratified random sampling (seed Fig. 6).

use crate::error::BadInput;
use crate::fluid::sphere_volume_m3;
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
/// Built by value where code wants one grain whole ([`Grains::grain`]); the grains of a run are
/// held as [`Grains`] (constants) and the state's arrays (what changes).
#[derive(Clone, Copy, Debug, PartialEq)]
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

/// What the grains of one kind share: size class, diameter and statistical weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GrainKind {
    /// Index of the size class.
    pub class: usize,
    /// Diameter, m.
    pub diameter_m: f64,
    /// Number of real grains each grain of the kind represents.
    pub weight: f64,
}

impl GrainKind {
    /// The real solid volume of one grain of the kind (its weight times its volume), m³.
    pub fn volume_m3(&self) -> f64 {
        self.weight * sphere_volume_m3(self.diameter_m)
    }
}

/// The grains of a sample, held once and compactly: per grain its kind (a 4-byte index into a
/// table of a few hundred kinds) and its horizontal position at t = 0, 12 bytes per grain. The
/// heights at t = 0 are not kept: [`Grains::initial_heights_m`] places the grains again (the same
/// random draws, the same numbers), once per run, into the state that updates them.
#[derive(Clone, Debug)]
pub struct Grains {
    /// The kinds (class, diameter, weight): one per size class holding grains.
    pub kinds: Vec<GrainKind>,
    /// The kind of each grain, an index into `kinds`.
    pub kind: Vec<u32>,
    /// Horizontal position of each grain at t = 0, m.
    pub x_m: Vec<f64>,
    /// How the grains were placed, to place them again ([`Grains::initial_heights_m`]).
    placement: Placement,
}

/// The stratified placement of [`Grains`]: the random generator as the shuffle left it, and the
/// rectangle, m.
#[derive(Clone, Debug)]
struct Placement {
    rng: ChaCha8Rng,
    width_m: f64,
    height_m: f64,
}

impl Placement {
    /// Places the grains of kinds `kind` (in order) by stratified random sampling in a √n × √n
    /// grid of cells of the rectangle, calling `f(x, y)` (m) for each, in grain order.
    fn visit(&self, kinds: &[GrainKind], kind: &[u32], mut f: impl FnMut(f64, f64)) {
        let mut rng = self.rng.clone();
        let (width_m, height_m) = (self.width_m, self.height_m);
        let m = (kind.len() as f64).sqrt().ceil() as usize;
        let (cw, ch) = (width_m / m as f64, height_m / m as f64);
        let (cells, n_grains) = (m * m, kind.len());
        for (i, &k) in kind.iter().enumerate() {
            // Spread the grains evenly over all m² cells (the last cells are not left empty).
            let cell = i * cells / n_grains;
            let (cx, cy) = ((cell % m) as f64, (cell / m) as f64);
            let r = 0.5 * kinds[k as usize].diameter_m;
            let x = ((cx + rng.random::<f64>()) * cw).clamp(r, width_m - r);
            let y = ((cy + rng.random::<f64>()) * ch).clamp(r, height_m - r);
            f(x, y);
        }
    }
}

impl Grains {
    /// Number of grains.
    pub fn len(&self) -> usize {
        self.kind.len()
    }

    /// True when there is no grain.
    pub fn is_empty(&self) -> bool {
        self.kind.is_empty()
    }

    /// The kind of grain `i`.
    #[inline(always)]
    pub fn kind_of(&self, i: usize) -> &GrainKind {
        &self.kinds[self.kind[i] as usize]
    }

    /// Diameter of grain `i`, m.
    #[inline(always)]
    pub fn diameter_m(&self, i: usize) -> f64 {
        self.kind_of(i).diameter_m
    }

    /// Grain `i` whole, at (`x_m`, `y_m`) (m).
    #[inline(always)]
    pub fn grain(&self, i: usize, x_m: f64, y_m: f64) -> Grain {
        let k = self.kind_of(i);
        Grain {
            x_m,
            y_m,
            diameter_m: k.diameter_m,
            weight: k.weight,
            class: k.class,
        }
    }

    /// The kinds that hold at least one grain (every kind of a sample made here; a table
    /// filtered by hand may hold more).
    pub fn kinds_present(&self) -> Vec<GrainKind> {
        let mut used = vec![false; self.kinds.len()];
        for &k in &self.kind {
            used[k as usize] = true;
        }
        self.kinds
            .iter()
            .zip(used)
            .filter_map(|(k, u)| u.then_some(*k))
            .collect()
    }

    /// The height of every grain's centre at t = 0, m: the placement made again.
    pub fn initial_heights_m(&self) -> Vec<f64> {
        let mut y = Vec::with_capacity(self.len());
        self.placement
            .visit(&self.kinds, &self.kind, |_, y_m| y.push(y_m));
        y
    }

    /// Every grain whole at t = 0 (tests and small samples: 40 bytes per grain).
    pub fn to_vec(&self) -> Vec<Grain> {
        self.initial_heights_m()
            .into_iter()
            .enumerate()
            .map(|(i, y)| self.grain(i, self.x_m[i], y))
            .collect()
    }
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
) -> Grains {
    let mut kinds = Vec::new();
    let mut kind = Vec::with_capacity(n + classes.len());
    for (i, c) in classes.iter().enumerate() {
        if c.mass_fraction <= 0.0 {
            continue;
        }
        let k = ((n as f64 * c.mass_fraction).round() as usize).max(1);
        let weight = real_count(c, mass_kg, density_kg_m3) / k as f64;
        push_class(&mut kinds, &mut kind, c, i, k, weight);
    }
    place(kinds, kind, width_m, height_m, seed)
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
) -> Grains {
    let mut kinds = Vec::new();
    let mut kind = Vec::with_capacity(real_total(classes, mass_kg, density_kg_m3));
    for (i, c) in classes.iter().enumerate() {
        let k = real_count(c, mass_kg, density_kg_m3).round() as usize;
        push_class(&mut kinds, &mut kind, c, i, k, 1.0);
    }
    place(kinds, kind, width_m, height_m, seed)
}

/// Appends `k` grains of class `c` (index `i`), each of weight `weight`: one kind (none if `k`
/// is 0).
fn push_class(
    kinds: &mut Vec<GrainKind>,
    kind: &mut Vec<u32>,
    c: &SizeClass,
    i: usize,
    k: usize,
    weight: f64,
) {
    if k == 0 {
        return;
    }
    let index = u32::try_from(kinds.len()).expect("fewer than 2³² size classes");
    kinds.push(GrainKind {
        class: i,
        diameter_m: c.diameter_m,
        weight,
    });
    kind.extend(std::iter::repeat_n(index, k));
}

/// Shuffles the grains of kinds `kind` (seeded) and places them by stratified random sampling in
/// a √n × √n grid of cells of the width_m × height_m rectangle ([`Placement::visit`]), keeping
/// their horizontal positions.
fn place(
    kinds: Vec<GrainKind>,
    mut kind: Vec<u32>,
    width_m: f64,
    height_m: f64,
    seed: u64,
) -> Grains {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // The permutation depends on the length only: the same as that of the grains themselves.
    kind.shuffle(&mut rng);
    let placement = Placement {
        rng,
        width_m,
        height_m,
    };
    let mut x_m = Vec::with_capacity(kind.len());
    placement.visit(&kinds, &kind, |x, _| x_m.push(x));
    Grains {
        kinds,
        kind,
        x_m,
        placement,
    }
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
        let g = real_grains(&c, m, rho, 0.0635, 0.457, 7).to_vec();
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
        let g = representative_grains(&c, 20_000, m, rho, 0.0635, 0.457, 7).to_vec();
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
            representative_grains(&c, 20_000, m, rho, 0.0635, 0.457, 7).to_vec()
        );
    }

    /// The grains held once (a kind index and x per grain, the heights placed again) are the
    /// grains the 40-byte-per-grain layout made: the same shuffle (it depends on the count
    /// only), the same draws, bit for bit. The reference is that layout's code, kept here.
    #[test]
    fn compact_grains_are_those_of_the_grain_by_grain_layout() {
        let c = discretize(&sample5(), 220);
        let (m, rho, (w, h), seed) = (0.06 / 180.0, 2500.0, (0.0635, 0.457), 11);
        let n = 5_000;
        let mut old = Vec::new();
        for (i, x) in c.iter().enumerate() {
            if x.mass_fraction <= 0.0 {
                continue;
            }
            let k = ((n as f64 * x.mass_fraction).round() as usize).max(1);
            let weight = real_count(x, m, rho) / k as f64;
            old.extend((0..k).map(|_| Grain {
                x_m: 0.0,
                y_m: 0.0,
                diameter_m: x.diameter_m,
                weight,
                class: i,
            }));
        }
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        old.shuffle(&mut rng);
        let side = (old.len() as f64).sqrt().ceil() as usize;
        let (cw, ch) = (w / side as f64, h / side as f64);
        let (cells, len) = (side * side, old.len());
        for (i, g) in old.iter_mut().enumerate() {
            let cell = i * cells / len;
            let (cx, cy) = ((cell % side) as f64, (cell / side) as f64);
            let r = 0.5 * g.diameter_m;
            g.x_m = ((cx + rng.random::<f64>()) * cw).clamp(r, w - r);
            g.y_m = ((cy + rng.random::<f64>()) * ch).clamp(r, h - r);
        }
        let new = representative_grains(&c, n, m, rho, w, h, seed);
        assert_eq!(new.len(), old.len());
        let bits = |g: &[Grain]| -> Vec<(u64, u64, u64, u64, usize)> {
            g.iter()
                .map(|g| {
                    let b = |x: f64| x.to_bits();
                    (b(g.x_m), b(g.y_m), b(g.diameter_m), b(g.weight), g.class)
                })
                .collect()
        };
        assert_eq!(bits(&new.to_vec()), bits(&old));
        assert_eq!(new.kinds_present(), new.kinds);
    }
}
