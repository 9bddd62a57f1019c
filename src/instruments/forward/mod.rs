//! The forward model of a sedimentation test: the suspension density field that a size
//! distribution leaves at a time, for the instruments of [`crate::instruments`] to read. It is
//! what `settle invert` fits to laboratory (or simulated) readings.
//!
//! The distribution is a set of mass fractions `w` over diameter [`Bins`]: within a bin the
//! mass is spread uniformly in ln d (so the cumulative curve is piecewise linear in log
//! diameter, as a grain-size chart draws it). The suspension starts homogeneous at the
//! concentration c₀ of the test (dry mass over suspension volume).
//!
//! The field is linear in `w` for a given settling of each size: [`unit_fields`] gives the
//! excess density ρ − ρ_f that one unit of mass fraction of each bin leaves in each layer at each
//! time, and [`field_of`] sums them. Under ideal Stokes settling ([`Settling::IdealStokes`]) the
//! unit fields do not depend on the distribution (seed 000 eq. 16: a grain of diameter d has
//! left every depth y < v_St(d) t); under hindered settling the speeds depend on the local
//! solid fraction, i.e. on the distribution itself, so the unit fields are computed for a
//! reference distribution `w_ref` and the caller iterates.

pub mod hindered;
pub mod speed;

use super::{Analysis, LayeredField};
use rayon::prelude::*;

/// The column of suspension the instruments read: its height, the layers of the field and the
/// conversions of the test (μ, ρ_p, ρ_f, g, c₀).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Column {
    /// Height of the suspension H (free surface to the cylinder's bottom), m.
    pub height_m: f64,
    /// Layers of equal thickness over the height (the fields' resolution; 4000 in the
    /// sedimentation scenes).
    pub layers: usize,
    /// Viscosity, densities, gravity and the initial concentration c₀.
    pub analysis: Analysis,
}

/// Diameter bins, m: bin j holds the grains of diameter in [edges[j], edges[j+1]], spread
/// uniformly in ln d. Strictly increasing and positive.
#[derive(Clone, Debug, PartialEq)]
pub struct Bins {
    /// Bin edges, m (at least two, strictly increasing, > 0).
    pub edges_m: Vec<f64>,
}

impl Bins {
    /// `n` bins evenly spaced in ln d between `lo_m` and `hi_m`.
    pub fn log_spaced(lo_m: f64, hi_m: f64, n: usize) -> Self {
        let (a, b) = (lo_m.ln(), hi_m.ln());
        Self {
            edges_m: (0..=n)
                .map(|k| (a + (b - a) * k as f64 / n as f64).exp())
                .collect(),
        }
    }

    /// Number of bins.
    pub fn len(&self) -> usize {
        self.edges_m.len().saturating_sub(1)
    }

    /// No bins.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Fraction (0–1) of bin j's mass finer than `d_m` (log-uniform within the bin).
    pub fn fraction_finer(&self, j: usize, d_m: f64) -> f64 {
        let (a, b) = (self.edges_m[j], self.edges_m[j + 1]);
        if d_m <= a {
            0.0
        } else if d_m >= b {
            1.0
        } else {
            (d_m / a).ln() / (b / a).ln()
        }
    }

    /// The cumulative curve F(d) (fraction finer, 0–1 of the whole specimen) of the mass
    /// fractions `w` (mass coarser than the last edge is 1 − Σw and finer than the first 0).
    pub fn cumulative(&self, w: &[f64], d_m: f64) -> f64 {
        w.iter()
            .enumerate()
            .map(|(j, wj)| wj * self.fraction_finer(j, d_m))
            .sum()
    }
}

/// How the grains settle in the forward model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Settling {
    /// Stokes terminal speed v = (ρ_p − ρ_f) g d²/(18 μ) from t = 0, no hindrance (seed 000
    /// eq. 16): what the standard reductions assume, and the scenes' `physics = "ideal-stokes"`.
    IdealStokes,
    /// The scenes' `physics = "full"` without contacts: Dallavalle drag with the Di Felice
    /// voidage factor at the local solid fraction, [`crate::fluid::DragLaw::Dallavalle`], and a
    /// bed of packing [`hindered::BED_PACKING`]; solved exactly in the continuum
    /// ([`hindered`]).
    Hindered {
        /// Height of the cells over which the scenes average the solid fraction, m (0.002 in
        /// the scenes). Not used by the continuum model, whose voidage is the local one: the
        /// cell average changes the speeds only within a cell of each front.
        voidage_cell_m: f64,
    },
}

/// Excess density ρ − ρ_f, kg/m³, that a unit mass fraction of each bin leaves in each layer of
/// `col` at each of `times_s`: `out[t][j][k]` (time, bin, layer, top layer first). For
/// [`Settling::Hindered`] the speeds are those in the suspension of the distribution `w_ref`
/// (ignored by [`Settling::IdealStokes`]).
///
/// Ideal Stokes: the fraction of bin j present at depth y (layer centre) and time t is its mass
/// finer than the limiting diameter φ(y, t) = √(18 μ y/((ρ_p − ρ_f) g t)) (seed eq. 16), and its
/// excess density c₀ (1 − ρ_f/ρ_p) times that fraction (eq. 18 inverted). A bottomless
/// cylinder, as [`super::ideal_field`].
///
/// Hindered: the exact self-similar solution of [`hindered::Hindered`] for `w_ref` (layer means;
/// zero below the bed). Mass coarser than the last edge (1 − Σ w_ref) is not in the suspension.
pub fn unit_fields(
    col: &Column,
    settling: Settling,
    bins: &Bins,
    w_ref: &[f64],
    times_s: &[f64],
) -> Vec<Vec<Vec<f64>>> {
    match settling {
        Settling::IdealStokes => ideal_unit_fields(col, bins, times_s),
        Settling::Hindered { .. } => {
            let model = hindered::Hindered::new(col, bins, w_ref, hindered::BED_PACKING);
            times_s
                .par_iter()
                .map(|&t| model.unit_fields_at(t))
                .collect()
        }
    }
}

fn ideal_unit_fields(col: &Column, bins: &Bins, times_s: &[f64]) -> Vec<Vec<Vec<f64>>> {
    let an = &col.analysis;
    let excess = an.c0_kg_m3 * (1.0 - an.fluid_density_kg_m3 / an.grain_density_kg_m3);
    let h = col.height_m / col.layers as f64;
    times_s
        .iter()
        .map(|&t| {
            let phi: Vec<f64> = (0..col.layers)
                .map(|k| {
                    if t > 0.0 {
                        an.limiting_diameter_m((k as f64 + 0.5) * h, t)
                    } else {
                        f64::INFINITY
                    }
                })
                .collect();
            (0..bins.len())
                .map(|j| {
                    phi.iter()
                        .map(|&p| excess * bins.fraction_finer(j, p))
                        .collect()
                })
                .collect()
        })
        .collect()
}

/// The exact forward fields of the distribution `w` at each of `times_s`: the unit fields with
/// `w` as the reference ([`unit_fields`]), summed with the weights `w` ([`field_of`]). Under
/// [`Settling::Hindered`] this is the nonlinear forward model; an inversion iterates it (unit
/// fields at the current estimate, a linear solve, repeat).
pub fn fields_for(
    col: &Column,
    settling: Settling,
    bins: &Bins,
    w: &[f64],
    times_s: &[f64],
) -> Vec<LayeredField> {
    unit_fields(col, settling, bins, w, times_s)
        .iter()
        .map(|u| field_of(col, u, w))
        .collect()
}

/// The field ρ_f + Σ_j w_j · unit_j of one time's unit fields (`unit[j][k]`).
pub fn field_of(col: &Column, unit: &[Vec<f64>], w: &[f64]) -> LayeredField {
    let rho_f = col.analysis.fluid_density_kg_m3;
    let mut rho = vec![rho_f; col.layers];
    for (u, &wj) in unit.iter().zip(w) {
        for (r, x) in rho.iter_mut().zip(u) {
            *r += wj * x;
        }
    }
    LayeredField {
        layer_m: col.height_m / col.layers as f64,
        density_kg_m3: rho,
        fluid_density_kg_m3: rho_f,
        grains: None,
    }
}
