//! The hindered settling forward model: the continuum version of the sedimentation scene with
//! `physics = "full"` and `sample.contacts = false`.
//!
//! # What is modelled
//! Every grain moves at its terminal speed v(d, ε) under Dallavalle's drag with the Di Felice
//! voidage factor at the local voidage ε = 1 − φ of the suspension around it (seed 000 eqs. 7–9;
//! Dallavalle 1948; Di Felice 1994; [`super::speed::terminal_speed_m_s`]); grains that reach the
//! bed on the bottom join it (seed 000 §4.2–4.3: the bed rises by the deposited volume over the
//! cylinder's area and a packing fraction). As in the scene: no contacts, no lubrication, no
//! return flow of the fluid displaced by the settling grains (the fluid is at rest), the grains'
//! acceleration is neglected (their Stokes response time, under a millisecond for silt, is the
//! scene's only transient), and the buoyancy is that of the clear fluid. Not modelled: the
//! scene's averaging of φ over cells of `voidage_cell_m` (it changes speeds only within a cell of
//! each front), its statistical noise, and the bias of its representative grains, each of which
//! counts its whole weight in its own cell (φ seen by a grain is larger by about φ₀ × cells /
//! grains; 7 % of φ₀ with 100 000 grains in 2 mm cells).
//!
//! # Why it can be solved exactly
//! The suspension is horizontally uniform, so the problem is 1D in depth y, one conservation law
//! per grain size, ∂c_i/∂t + ∂(c_i v_i(ε))/∂y = 0 (Kynch 1952, polydisperse). It starts as a
//! Riemann problem (clear fluid above y = 0, uniform suspension below) and no information
//! travels upwards: in a dilute suspension every characteristic speed is downwards (for one size
//! f′(φ) = v (1 − (n + 1) φ) > 0 while φ < 1/(n + 1) ≈ 0.2), and the bed only removes the grains
//! that reach it. The solution above the bed is therefore self-similar, c_i(y, t) = C_i(y/t):
//! a staircase of constant states separated by the fronts of the sizes, coarsest (deepest)
//! first. It is built once per reference distribution by a sweep from the bulk upwards:
//!
//! - the front of the coarsest size k still present moves at s = v_k(ε⁻), its speed in the state
//!   below it (the Rankine–Hugoniot condition with c_k = 0 above);
//! - across it every finer size i keeps its flux relative to the front:
//!   c_i⁺ (s − v_i(ε⁺)) = c_i⁻ (s − v_i(ε⁻)), so the finer sizes are denser above the front
//!   (they settle faster in the clearer fluid there and pile up behind it);
//! - ε⁺ = 1 − Σ c_i⁺(ε⁺)/ρ_p is one scalar equation, whose left-minus-right side falls strictly
//!   from φ_k > 0 at ε⁻ to −∞ where a finer size would reach the front's speed: one root,
//!   found by a safeguarded Newton iteration, and every finer size stays behind the front.
//!
//! A size of zero reference mass (a tracer, for the unit fields of bins absent from `w_ref`) does
//! not change ε; where it would catch up with a front it rides on it (a layer of zero thickness
//! holding the mass the front sweeps up, c⁻ (s − v⁻) per unit time).
//!
//! Within each bin the log-uniform spread of diameters is resolved by sub-diameters at most 1 %
//! apart ([`SUB_DIAMETER_STEP`]), i.e. fronts at most 2 % apart in speed (the scenes' 220
//! classes are 1.5 % apart). Cost: O(S²) for S sub-diameters (a few milliseconds for 40 bins),
//! then O(layers × bins) per time; exact mass conservation.

use super::speed::SpeedTable;
use super::{Bins, Column};
use crate::numerics::{bisect, safeguarded_newton, Bisection, Stop};

/// Largest width of a sub-diameter of a bin, in ln d (1 %).
pub const SUB_DIAMETER_STEP: f64 = 0.01;

/// Packing fraction of the bed (the scenes' default `sample.bed_packing`).
pub const BED_PACKING: f64 = 0.6;

/// One grain size of the sweep.
struct Species {
    bin: usize,
    /// Share of its bin's mass (1/m for m sub-diameters).
    share: f64,
    /// Reference concentration in the bulk, kg/m³ (0 for a tracer).
    conc_kg_m3: f64,
    speed: SpeedTable,
}

/// The self-similar solution C(ξ), ξ = y/t, of one reference distribution: fronts (speeds,
/// ascending) and the constant states between them.
#[derive(Clone, Debug)]
pub struct Hindered {
    col: Column,
    bins: usize,
    /// Bed packing fraction.
    packing: f64,
    /// Front speeds ξ_i, m/s, ascending (the finest size's front first).
    fronts_m_s: Vec<f64>,
    /// Excess density per unit mass fraction of each bin in each state, kg/m³: state r lies
    /// between fronts r − 1 and r (state 0: clear fluid above the first front; the last: the
    /// bulk below every front). `unit[r * bins + j]`.
    unit: Vec<f64>,
    /// ∫₀^ξᵢ of the unit excess density of each bin, including the riding tracers' layers at
    /// the fronts, kg/m³ × m/s: `cum[i * bins + j]` at front i.
    cum: Vec<f64>,
    /// Reference concentration of each state, kg/m³.
    conc: Vec<f64>,
    /// ∫₀^ξᵢ of the reference concentration at each front.
    conc_cum: Vec<f64>,
    /// Voidage of each state.
    voidage: Vec<f64>,
}

impl Hindered {
    /// The solution for the suspension of mass fractions `w_ref` (one per bin; negative values
    /// count as 0) in `col`, with a bed of packing fraction `packing`.
    pub fn new(col: &Column, bins: &Bins, w_ref: &[f64], packing: f64) -> Self {
        let an = &col.analysis;
        let rho_p = an.grain_density_kg_m3;
        let mut species = Vec::new();
        let w = |j: usize| w_ref.get(j).copied().unwrap_or(0.0).max(0.0);
        let phi_bulk: f64 = (0..bins.len()).map(|j| an.c0_kg_m3 * w(j) / rho_p).sum();
        let eps_bulk = (1.0 - phi_bulk).clamp(0.0, 1.0);
        for j in 0..bins.len() {
            let (a, b) = (bins.edges_m[j], bins.edges_m[j + 1]);
            let m = (((b / a).ln() / SUB_DIAMETER_STEP).ceil() as usize).max(1);
            for i in 0..m {
                let d = a * (b / a).powf((i as f64 + 0.5) / m as f64);
                species.push(Species {
                    bin: j,
                    share: 1.0 / m as f64,
                    conc_kg_m3: an.c0_kg_m3 * w(j) / m as f64,
                    speed: SpeedTable::new(an, d, eps_bulk),
                });
            }
        }
        // Coarsest first: the order of the fronts from the bottom up.
        species.reverse();
        let mut me = Self {
            col: *col,
            bins: bins.len(),
            packing,
            fronts_m_s: Vec::new(),
            unit: Vec::new(),
            cum: Vec::new(),
            conc: Vec::new(),
            conc_cum: Vec::new(),
            voidage: Vec::new(),
        };
        me.sweep(&species, eps_bulk);
        me
    }

    /// The sweep from the bulk upwards (see the module doc); fills the fronts and states, then
    /// reverses them into ascending ξ and integrates.
    fn sweep(&mut self, sp: &[Species], eps_bulk: f64) {
        let an = self.col.analysis;
        let excess = an.c0_kg_m3 * (1.0 - an.fluid_density_kg_m3 / an.grain_density_kg_m3);
        let rho_p = an.grain_density_kg_m3;
        let nb = self.bins;
        let n = sp.len();
        // Relative concentration of each size (c / c_bulk) in the current state.
        let mut rel = vec![1.0; n];
        let mut alive = vec![true; n];
        let mut eps = eps_bulk;
        // Bottom-up lists: states (bulk first) and fronts with the riding layers above them.
        let mut states: Vec<(Vec<f64>, f64, f64)> = Vec::new();
        let mut fronts: Vec<(f64, Vec<f64>)> = Vec::new();
        let state_of = |rel: &[f64], alive: &[bool], eps: f64| {
            let mut u = vec![0.0; nb];
            let mut c = 0.0;
            for (k, s) in sp.iter().enumerate().filter(|(k, _)| alive[*k]) {
                u[s.bin] += excess * s.share * rel[k];
                c += s.conc_kg_m3 * rel[k];
            }
            (u, c, eps)
        };
        states.push(state_of(&rel, &alive, eps));
        let mut k = 0;
        while k < n {
            if !alive[k] {
                k += 1;
                continue;
            }
            let s = sp[k].speed.speed(eps);
            alive[k] = false;
            let eps_up = if sp[k].conc_kg_m3 * rel[k] > 0.0 {
                solve_voidage_above(sp, &rel, &alive, k, s, eps, rho_p)
            } else {
                eps
            };
            let mut riding = vec![0.0; nb];
            for i in (k + 1)..n {
                if !alive[i] {
                    continue;
                }
                let (below, above) = (sp[i].speed.speed(eps), sp[i].speed.speed(eps_up));
                if above < s {
                    rel[i] *= (s - below) / (s - above);
                } else {
                    // A tracer catching up with the front rides on it.
                    riding[sp[i].bin] += excess * sp[i].share * rel[i] * (s - below);
                    alive[i] = false;
                }
            }
            eps = eps_up;
            fronts.push((s, riding));
            states.push(state_of(&rel, &alive, eps));
            k += 1;
        }
        // Ascending ξ: the clear state first.
        states.reverse();
        fronts.reverse();
        self.fronts_m_s = fronts.iter().map(|f| f.0).collect();
        self.unit = states.iter().flat_map(|s| s.0.iter().copied()).collect();
        self.conc = states.iter().map(|s| s.1).collect();
        self.voidage = states.iter().map(|s| s.2).collect();
        let (mut cum, mut c_cum) = (vec![0.0; nb], 0.0);
        let mut prev = 0.0;
        for (i, (x, riding)) in fronts.iter().enumerate() {
            for j in 0..nb {
                cum[j] += self.unit[i * nb + j] * (x - prev) + riding[j];
            }
            c_cum += self.conc[i] * (x - prev);
            prev = *x;
            self.cum.extend_from_slice(&cum);
            self.conc_cum.push(c_cum);
        }
    }

    /// Front speeds, m/s, ascending (one per size of the sweep that ends a state).
    pub fn front_speeds_m_s(&self) -> &[f64] {
        &self.fronts_m_s
    }

    /// Voidage of the bulk suspension below every front.
    pub fn bulk_voidage(&self) -> f64 {
        *self.voidage.last().unwrap_or(&1.0)
    }

    /// Number of states in ξ at or below `xi` (index of the state holding ξ).
    fn state_at(&self, xi: f64) -> usize {
        self.fronts_m_s.partition_point(|&x| x <= xi)
    }

    /// ∫₀^ξ of the reference concentration over ξ, kg/m³ × m/s.
    fn conc_integral(&self, xi: f64) -> f64 {
        let r = self.state_at(xi);
        let (base, x0) = if r == 0 {
            (0.0, 0.0)
        } else {
            (self.conc_cum[r - 1], self.fronts_m_s[r - 1])
        };
        base + self.conc[r] * (xi - x0)
    }

    /// Height of the bed at time `t_s`, m: b P ρ_p = c₀ Σw H − ∫₀^(H−b) c dy (the suspension above
    /// the bed is the self-similar one), solved by bisection (the left side minus the right
    /// grows with b).
    pub fn bed_height_m(&self, t_s: f64) -> f64 {
        if t_s <= 0.0 {
            return 0.0;
        }
        let h = self.col.height_m;
        let total = self.conc.last().copied().unwrap_or(0.0) * h;
        let cap = self.packing * self.col.analysis.grain_density_kg_m3;
        let f = |b: f64| b * cap - total + t_s * self.conc_integral((h - b) / t_s);
        if f(0.0) >= 0.0 {
            return 0.0;
        }
        let rule = Bisection::until(Stop::Width(1e-15 * h), 200);
        let (lo, hi) = bisect(0.0, h, rule, |b| f(b) < 0.0);
        0.5 * (lo + hi)
    }

    /// Writes ∫₀^ξ of every bin's unit excess density into `out`, starting the search of the
    /// state at `*r` (ξ must not decrease between calls).
    fn unit_integral(&self, xi: f64, r: &mut usize, out: &mut [f64]) {
        let nb = self.bins;
        while *r < self.fronts_m_s.len() && self.fronts_m_s[*r] <= xi {
            *r += 1;
        }
        let u = &self.unit[*r * nb..(*r + 1) * nb];
        if *r == 0 {
            out.iter_mut().zip(u).for_each(|(o, u)| *o = u * xi);
        } else {
            let (base, x0) = (&self.cum[(*r - 1) * nb..*r * nb], self.fronts_m_s[*r - 1]);
            for ((o, u), b) in out.iter_mut().zip(u).zip(base) {
                *o = b + u * (xi - x0);
            }
        }
    }

    /// Excess density ρ − ρ_f per unit mass fraction of each bin in each layer of the column at
    /// time `t_s`, kg/m³ (`[bin][layer]`, top layer first): the mean over each layer of the
    /// self-similar field, and 0 below the bed (the bed's grains are not suspended).
    pub fn unit_fields_at(&self, t_s: f64) -> Vec<Vec<f64>> {
        let (nb, nl) = (self.bins, self.col.layers);
        let h = self.col.height_m / nl as f64;
        let mut out = vec![vec![0.0; nl]; nb];
        if t_s <= 0.0 {
            let bulk = &self.unit[self.unit.len() - nb..];
            for (o, &u) in out.iter_mut().zip(bulk) {
                o.iter_mut().for_each(|x| *x = u);
            }
            return out;
        }
        let cut = self.col.height_m - self.bed_height_m(t_s);
        let (mut r, mut prev, mut next) = (0, vec![0.0; nb], vec![0.0; nb]);
        for k in 0..nl {
            let y = ((k + 1) as f64 * h).min(cut);
            self.unit_integral(y / t_s, &mut r, &mut next);
            for ((o, a), b) in out.iter_mut().zip(&next).zip(&prev) {
                o[k] = t_s * (a - b) / h;
            }
            std::mem::swap(&mut prev, &mut next);
        }
        out
    }
}

/// ε⁺ above the front of size `k` moving at `s` from the state of voidage `eps` (see the module
/// doc): the root of G(ε) = 1 − ε − Σᵢ c_i⁺(ε)/ρ_p over the finer sizes still present, between
/// `eps` (G > 0) and the voidage where the first of them would reach `s` (G → −∞).
fn solve_voidage_above(
    sp: &[Species],
    rel: &[f64],
    alive: &[bool],
    k: usize,
    s: f64,
    eps: f64,
    rho_p: f64,
) -> f64 {
    let finer: Vec<(usize, f64)> = ((k + 1)..sp.len())
        .filter(|&i| alive[i] && sp[i].conc_kg_m3 * rel[i] > 0.0)
        .map(|i| (i, s - sp[i].speed.speed(eps)))
        .collect();
    let mut hi = 1.0f64;
    for &(i, _) in &finer {
        if let Some(p) = sp[i].speed.voidage_at(s) {
            hi = hi.min(p);
        }
    }
    // G and G′ at ε; +∞ distance to a pole counts as G = −∞.
    let g = |e: f64| -> (f64, f64) {
        let (mut sum, mut dsum) = (0.0, 0.0);
        for &(i, gap_below) in &finer {
            let gap = s - sp[i].speed.speed(e);
            if gap <= 0.0 {
                return (f64::NEG_INFINITY, 0.0);
            }
            let c = sp[i].conc_kg_m3 * rel[i] * gap_below / gap;
            sum += c;
            dsum += c * sp[i].speed.slope(e) / gap;
        }
        (1.0 - e - sum / rho_p, -1.0 - dsum / rho_p)
    };
    // G is concave and decreasing: Newton from either side lands on the far side of the root
    // and then converges monotonically; the bracket catches the steps that would cross a pole.
    // Newton on −G (increasing); a NaN G ends the search where it is, as G = 0 does, and a
    // slope G′ ≥ 0 (or NaN) refuses Newton's step (given as NaN).
    let end = safeguarded_newton(
        eps,
        hi,
        eps,
        200,
        |x| {
            let (gx, dg) = g(x);
            let r = if gx.is_nan() { 0.0 } else { -gx };
            (r, if dg < 0.0 { -dg } else { f64::NAN }, ())
        },
        |it| (it.next - it.at).abs() <= 1e-15 || it.hi - it.lo <= 1e-15,
    );
    let Some(last) = end.last else {
        return eps;
    };
    if last.residual == 0.0 && !end.stopped {
        return last.at;
    }
    // Stopped: the last point evaluated; out of iterations: the step after it.
    let x = if end.stopped { last.at } else { end.x };
    if g(x).0.is_finite() {
        x
    } else {
        last.lo
    }
}
