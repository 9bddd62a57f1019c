//! A sphere moving along one line (the vertical) in a fluid at rest, with added mass and the
//! Basset–Boussinesq history force carried as state, integrated exactly at any time step for
//! Stokes drag.
//!
//! # Equation (Maxey & Riley 1983; Gatignol 1983; fluid at rest)
//!
//! (m_p + C_m m_f) v′ = W − F_d(v) − F_H,   F_H = C_H ∫₀ᵗ v′(τ) K(t − τ) dτ,
//!
//! with W the net weight (m_p − m_f) g plus any other constant force, F_d the steady drag, C_m
//! the added-mass coefficient (½ for a sphere) and C_H = (3/2) d² √(π ρ_f μ), K(t) = t^{−1/2}
//! (Basset). The kernel is the sum of exponentials of [`ExpSum`]: K ≈ w₀ δ + Σ w_j e^{−λ_j t},
//! so F_H = C_H (w₀ v′ + Σ w_j q_j) with the states q_j′ = v′ − λ_j q_j (q_j(0) = 0: the fluid is
//! at rest at release, and a sphere released with a speed starts its history then).
//!
//! # Why a sum of exponentials carried as state
//!
//! The alternative of the issue, a window of van Hinsberg et al.'s (2011) second-order weights
//! plus an exponential tail, keeps a window of past accelerations and is second order in dt.
//! Carried as state, Stokes drag + added mass + the exponential sum is a *linear* system
//! y′ = J y + e g in y = (v, x, q₁ … q_m), which the exponential integrator solves exactly at any
//! dt, and needs O(m) memory and an (m+2)² product per step.
//!
//! # Scheme
//!
//! J holds the drag slope k (frozen: the propagator is rebuilt when dF/dv drifts by more than
//! [`SLOPE_TOLERANCE`]) and g = W − F_d(v) + k v is the rest of the force (constant for Stokes
//! drag). Exponential time differencing of second order (ETD2, Cox & Matthews 2002, J. Comput.
//! Phys. 176:430): y₁ = e^{J dt} y₀ + dt φ₁(J dt) e g₀ + dt φ₂(J dt) e (g₀ − g₋₁), with e^{J dt},
//! φ₁ and φ₂ from one exponential of the augmented matrix [[J dt, e dt, 0], [0, 0, 1], [0, 0, 0]]
//! (Al-Mohy & Higham's scaling and squaring, `nalgebra`). For Stokes drag (g constant) this is
//! exact up to the kernel fit; for a nonlinear drag the remainder is second order in dt.
//!
//! Memory per body: (m + 2) state values, and the propagator (m + 2)² + 2(m + 2) values, shared
//! by every step of the same dt and slope.

use crate::fluid::transient::ExpSum;
use nalgebra::{DMatrix, DVector};

/// Relative drift of the drag slope dF/dv past which the propagator is rebuilt.
pub const SLOPE_TOLERANCE: f64 = 0.01;

/// The transient forces on one body.
#[derive(Clone, Debug, PartialEq)]
pub struct TransientModel {
    /// Sphere mass m_p, kg.
    pub mass_kg: f64,
    /// Added mass C_m m_f, kg (0: off).
    pub added_mass_kg: f64,
    /// History force: C_H = (3/2) d² √(π ρ_f μ), N s^{1/2}/m, and the kernel's exponential sum.
    pub history: Option<(f64, ExpSum)>,
}

impl TransientModel {
    /// The effective inertia M′ = m_p + C_m m_f + C_H w₀, kg (w₀ the kernel's unresolved
    /// short-time weight, see [`ExpSum::instant_sqrt_s`]).
    pub fn inertia_kg(&self) -> f64 {
        self.mass_kg
            + self.added_mass_kg
            + self
                .history
                .as_ref()
                .map_or(0.0, |(c, k)| c * k.instant_sqrt_s)
    }

    /// State variables per body: v, x and one per exponential.
    pub fn states(&self) -> usize {
        2 + self.history.as_ref().map_or(0, |(_, k)| k.len())
    }
}

/// e^{J dt} and the φ-columns for one (dt, slope).
#[derive(Clone, Debug)]
struct Propagator {
    dt_s: f64,
    slope_n_s_m: f64,
    phi: DMatrix<f64>,
    u1: DVector<f64>,
    u2: DVector<f64>,
}

/// C_H = (3/2) d² √(π ρ_f μ), N s^{1/2}/m: the Basset history force is C_H ∫ v′ (t−τ)^{−1/2} dτ
/// (Maxey & Riley 1983), for a sphere of diameter `d_m` in a fluid of density `rho_f_kg_m3` and
/// viscosity `mu_pa_s`.
pub fn basset_coefficient(d_m: f64, rho_f_kg_m3: f64, mu_pa_s: f64) -> f64 {
    1.5 * d_m * d_m * (std::f64::consts::PI * rho_f_kg_m3 * mu_pa_s).sqrt()
}

/// The exponential sum of the Basset kernel for a body of inertia `inertia_kg` (m_p + C_m m_f),
/// Stokes drag slope `k_n_s_m` (3πμd) and history coefficient `c_h`, over a run of `run_s`
/// seconds: nodes from 1e-2 of the faster of the two time scales M/k and M²/(π C_H²) (the
/// shorter times go to the instantaneous weight w₀) to 10 × the run (shorter runs: 10⁴ × that
/// time scale), at step [`crate::fluid::transient::kernel::DEFAULT_STEP`].
pub fn basset_kernel(inertia_kg: f64, k_n_s_m: f64, c_h: f64, run_s: f64) -> ExpSum {
    let b = k_n_s_m / inertia_kg;
    let c = c_h / inertia_kg;
    let t_scale = (1.0 / b).min(1.0 / (std::f64::consts::PI * c * c));
    let t_lo = 1e-2 * t_scale;
    ExpSum::covering(
        t_lo,
        (10.0 * run_s).max(1e4 * t_scale),
        crate::fluid::transient::kernel::DEFAULT_STEP,
    )
}

/// The times t_lo … t_hi a history kernel is fitted on (s): from 1e-2 of the faster of M/k and
/// M²/(π C_H²) to 10 × the run (at least 10⁴ × that time scale), as in [`basset_kernel`].
fn history_times(inertia_kg: f64, k_n_s_m: f64, c_h: f64, run_s: f64) -> (f64, f64) {
    let b = k_n_s_m / inertia_kg;
    let c = c_h / inertia_kg;
    let t_scale = (1.0 / b).min(1.0 / (std::f64::consts::PI * c * c));
    (1e-2 * t_scale, (10.0 * run_s).max(1e4 * t_scale))
}

/// The exponential sum of Mei & Adrian's (1992) finite-Re kernel
/// ([`crate::fluid::transient::kernel::mei_adrian_kernel`]) at Reynolds number `reynolds` for a
/// sphere of viscous diffusion time `tau_d_s` = d²/ν, over the same times as [`basset_kernel`]
/// (same arguments), fitted with non-negative weights on the same log-spaced rates
/// ([`ExpSum::fit`]).
pub fn mei_adrian_kernel_sum(
    inertia_kg: f64,
    k_n_s_m: f64,
    c_h: f64,
    run_s: f64,
    tau_d_s: f64,
    reynolds: f64,
) -> ExpSum {
    let (t_lo, t_hi) = history_times(inertia_kg, k_n_s_m, c_h, run_s);
    ExpSum::fit(
        t_lo,
        t_hi,
        crate::fluid::transient::kernel::DEFAULT_STEP,
        |t| crate::fluid::transient::kernel::mei_adrian_kernel(t, tau_d_s, reynolds),
    )
}

/// Mei & Adrian's kernel fitted on one set of rates at a grid of Reynolds numbers, for a kernel
/// that follows the body's current Re (`transient.history_reynolds = "current"`): the weights at
/// Re are interpolated linearly in ln Re between the two nearest fits (non-negative, as both
/// are); below the grid (Re < [`MeiAdrianTable::RE_MIN`]) the kernel is Basset's over the run.
#[derive(Clone, Debug)]
pub struct MeiAdrianTable {
    ln_re: Vec<f64>,
    /// Per grid point: every term's weight (s^{−1/2}) and w₀ (s^{1/2}).
    fits: Vec<(Vec<f64>, f64)>,
    /// The rates shared by every fit, 1/s.
    pub rates_per_s: Vec<f64>,
}

impl MeiAdrianTable {
    /// Lowest Reynolds number of the grid (there t_c ≈ 6e3 d²/ν: Basset's kernel).
    pub const RE_MIN: f64 = 1e-2;
    /// Grid points per decade of Re.
    pub const PER_DECADE: f64 = 8.0;

    /// The fits from Re = [`Self::RE_MIN`] to `re_max` for the body of [`mei_adrian_kernel_sum`]
    /// (same arguments).
    pub fn new(
        inertia_kg: f64,
        k_n_s_m: f64,
        c_h: f64,
        run_s: f64,
        tau_d_s: f64,
        re_max: f64,
    ) -> Self {
        let (t_lo, t_hi) = history_times(inertia_kg, k_n_s_m, c_h, run_s);
        let (l0, l1) = (Self::RE_MIN.ln(), re_max.max(10.0 * Self::RE_MIN).ln());
        let n = ((l1 - l0) / std::f64::consts::LN_10 * Self::PER_DECADE).ceil() as usize;
        let ln_re: Vec<f64> = (0..=n)
            .map(|i| l0 + (l1 - l0) * i as f64 / n as f64)
            .collect();
        let mut rates = Vec::new();
        let fits = ln_re
            .iter()
            .map(|l| {
                let e = ExpSum::fit_all(
                    t_lo,
                    t_hi,
                    crate::fluid::transient::kernel::DEFAULT_STEP,
                    |t| crate::fluid::transient::kernel::mei_adrian_kernel(t, tau_d_s, l.exp()),
                );
                rates = e.rates_per_s;
                (e.weights_per_sqrt_s, e.instant_sqrt_s)
            })
            .collect();
        Self {
            ln_re,
            fits,
            rates_per_s: rates,
        }
    }

    /// The sum at Reynolds number `re` (clamped to the grid).
    pub fn at(&self, re: f64) -> ExpSum {
        let mut w = vec![0.0; self.rates_per_s.len()];
        let w0 = self.weights_into(re, &mut w);
        ExpSum {
            rates_per_s: self.rates_per_s.clone(),
            weights_per_sqrt_s: w,
            instant_sqrt_s: w0,
        }
    }

    /// Writes the weights at `re` into `w` and returns w₀.
    pub fn weights_into(&self, re: f64, w: &mut [f64]) -> f64 {
        let l = re.max(Self::RE_MIN).ln();
        let last = self.ln_re.len() - 1;
        let i = self.ln_re.partition_point(|x| *x <= l).clamp(1, last) - 1;
        let a = ((l - self.ln_re[i]) / (self.ln_re[i + 1] - self.ln_re[i])).clamp(0.0, 1.0);
        let (p, q) = (&self.fits[i], &self.fits[i + 1]);
        for (j, wj) in w.iter_mut().enumerate() {
            *wj = p.0[j] + a * (q.0[j] - p.0[j]);
        }
        p.1 + a * (q.1 - p.1)
    }
}

/// One body's state under [`TransientModel`].
#[derive(Clone, Debug)]
pub struct TransientBody {
    model: TransientModel,
    inertia_kg: f64,
    /// (v, x, q₁ … q_m); x is the displacement within the current step.
    y: DVector<f64>,
    /// Room for the next state (no allocation per step).
    scratch: DVector<f64>,
    prop: Option<Propagator>,
    /// Velocity, drag, constant force and step at the start of the previous step (for ETD2).
    prev: Option<(f64, f64, f64, f64)>,
}

impl TransientBody {
    /// A body of `model` released with velocity `v0_m_s` (along the line of motion).
    pub fn new(model: TransientModel, v0_m_s: f64) -> Self {
        let n = model.states();
        let mut y = DVector::zeros(n);
        y[0] = v0_m_s;
        Self {
            inertia_kg: model.inertia_kg(),
            model,
            scratch: y.clone(),
            y,
            prop: None,
            prev: None,
        }
    }

    /// Replaces the history kernel's weights by `w` (one per term, s^{−1/2}) and its
    /// instantaneous weight by `w0` (s^{1/2}), for a kernel that changes with the body's
    /// Reynolds number ([`MeiAdrianTable`]); the states q_j are kept (they do not depend on the
    /// weights). The propagator is rebuilt only when the weights (summed) or w₀ moved by more than
    /// [`SLOPE_TOLERANCE`] (relative), as for the drag slope.
    pub fn set_history_weights(&mut self, w: &[f64], w0: f64) {
        let Some((_, k)) = self.model.history.as_mut() else {
            return;
        };
        let total: f64 = k.weights_per_sqrt_s.iter().sum();
        let moved: f64 = k
            .weights_per_sqrt_s
            .iter()
            .zip(w)
            .map(|(a, b)| (a - b).abs())
            .sum();
        if moved > SLOPE_TOLERANCE * total
            || (k.instant_sqrt_s - w0).abs() > SLOPE_TOLERANCE * k.instant_sqrt_s
        {
            k.weights_per_sqrt_s.copy_from_slice(w);
            k.instant_sqrt_s = w0;
            self.inertia_kg = self.model.inertia_kg();
            self.prop = None;
        }
    }

    /// Current velocity, m/s.
    pub fn velocity_m_s(&self) -> f64 {
        self.y[0]
    }

    /// The model.
    pub fn model(&self) -> &TransientModel {
        &self.model
    }

    /// The history force C_H (w₀ v′ + Σ w_j q_j) without its w₀ v′ part, N (0 without history).
    pub fn history_memory_n(&self) -> f64 {
        self.model.history.as_ref().map_or(0.0, |(c, k)| {
            c * k
                .weights_per_sqrt_s
                .iter()
                .enumerate()
                .map(|(j, w)| w * self.y[2 + j])
                .sum::<f64>()
        })
    }

    /// Advances by `dt_s` under the constant force `w_n` (along the line, N) and the drag
    /// `drag(v) = (F_d, dF_d/dv)` (N, N s/m; F_d opposes v, so F_d(v) has the sign of v).
    /// Returns (velocity at the end, displacement), (m/s, m).
    pub fn step(&mut self, dt_s: f64, w_n: f64, drag: impl Fn(f64) -> (f64, f64)) -> (f64, f64) {
        let (g0, g_prev, v0, f0, _) = self.forcing(dt_s, w_n, &drag, true);
        let p = self.prop.as_ref().expect("propagator built by forcing");
        // In place: scratch = Φ y₀ + u₁ g₀ + u₂ (g₀ − g₋₁), no allocation per step.
        self.y[1] = 0.0;
        self.scratch.gemv(1.0, &p.phi, &self.y, 0.0);
        self.scratch.axpy(g0, &p.u1, 1.0);
        self.scratch.axpy(g0 - g_prev, &p.u2, 1.0);
        std::mem::swap(&mut self.y, &mut self.scratch);
        self.prev = Some((v0, f0, w_n, dt_s));
        (self.y[0], self.y[1])
    }

    /// The state `dt_s` ahead without advancing (dense output inside a step): (velocity,
    /// displacement).
    pub fn peek(&mut self, dt_s: f64, w_n: f64, drag: impl Fn(f64) -> (f64, f64)) -> (f64, f64) {
        let (g0, g_prev, _, _, k) = self.forcing(dt_s, w_n, &drag, false);
        let own;
        let p = match &self.prop {
            Some(p) if p.dt_s == dt_s && p.slope_n_s_m == k => p,
            _ => {
                own = self.propagator(dt_s, k);
                &own
            }
        };
        let mut y0 = self.y.clone();
        y0[1] = 0.0;
        let y1 = &p.phi * &y0 + &p.u1 * g0 + &p.u2 * (g0 - g_prev);
        (y1[0], y1[1])
    }

    /// (g₀, g₋₁, v₀, F₀, slope in J) of a step of `dt` from the current state, rebuilding the kept
    /// propagator (`keep`) when dt or the drag slope changed.
    fn forcing(
        &mut self,
        dt: f64,
        w: f64,
        drag: &impl Fn(f64) -> (f64, f64),
        keep: bool,
    ) -> (f64, f64, f64, f64, f64) {
        let v0 = self.y[0];
        let (f0, k0) = drag(v0);
        let fresh = match &self.prop {
            Some(p) => {
                p.dt_s != dt || (k0 - p.slope_n_s_m).abs() > SLOPE_TOLERANCE * p.slope_n_s_m.abs()
            }
            None => true,
        };
        let k = if fresh {
            if keep {
                self.prop = Some(self.propagator(dt, k0));
            }
            k0
        } else {
            self.prop.as_ref().expect("propagator present").slope_n_s_m
        };
        let g0 = w - f0 + k * v0;
        // ETD2 needs the previous step's forcing at the same dt; the first step (and a partial
        // step) takes it constant.
        let g_prev = match self.prev {
            Some((v, f, wp, dtp)) if keep && dtp == dt => wp - f + k * v,
            _ => g0,
        };
        (g0, g_prev, v0, f0, k)
    }

    /// The propagator of step `dt` with the drag slope `k` frozen in J.
    fn propagator(&self, dt: f64, k: f64) -> Propagator {
        let n = self.y.len();
        let mi = 1.0 / self.inertia_kg;
        let mut a = DMatrix::<f64>::zeros(n + 2, n + 2);
        // Row of v: v′ = (−k v − C_H Σ w_j q_j + g)/M′.
        a[(0, 0)] = -k * mi;
        if let Some((c, ker)) = &self.model.history {
            for (j, wj) in ker.weights_per_sqrt_s.iter().enumerate() {
                a[(0, 2 + j)] = -c * wj * mi;
            }
        }
        a[(1, 0)] = 1.0;
        for j in 2..n {
            for col in 0..n {
                a[(j, col)] = a[(0, col)];
            }
            a[(j, j)] -= self.model.history.as_ref().expect("history").1.rates_per_s[j - 2];
        }
        // e: the forcing enters v′ and every q_j′ through v′.
        a[(0, n)] = mi;
        for j in 2..n {
            a[(j, n)] = mi;
        }
        a[(n, n + 1)] = 1.0;
        for r in 0..n {
            for col in 0..n + 1 {
                a[(r, col)] *= dt;
            }
        }
        let e = a.exp();
        Propagator {
            dt_s: dt,
            slope_n_s_m: k,
            phi: e.view((0, 0), (n, n)).into_owned(),
            u1: e.view((0, n), (n, 1)).column(0).into_owned(),
            u2: e.view((0, n + 1), (n, 1)).column(0).into_owned(),
        }
    }
}

#[cfg(test)]
mod tests;
