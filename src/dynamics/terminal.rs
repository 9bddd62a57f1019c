//! The terminal state of a settling sphere under Dallavalle drag with the Di Felice factor as a
//! function of the voidage, tabulated once per run and diameter, and the exponential step near
//! terminal settling that uses it without a single transcendental function.
//!
//! The terminal speed u_t(ε) solves F(u; ε) = W (drag = submerged weight; seed 000 eqs. 7–9,
//! F as [`crate::fluid::newtonian::dallavalle_di_felice_derivatives`]). It is analytic in ε on
//! (0, 1] (its only singularity is at ε = 0), so a Chebyshev series on [ε_min, 1] converges
//! geometrically, as ρ⁻ⁿ with ρ = |τ| + √(τ² − 1), τ = (1 + ε_min)/(1 − ε_min) the image of
//! ε = 0 (Trefethen 2013, *Approximation Theory and Approximation Practice*, ch. 8): ρ ≈ 17.9
//! for ε_min = 0.8, so 15 terms reach 1e-18. The slope k_t = F'(u_t) and curvature
//! c_t = F''(u_t) are tabulated the same way (they need far less accuracy, see
//! [`exponential_near_terminal`]).

use super::{phi12, DallavalleGrain, PHI_SATURATED};
use crate::fluid::newtonian::dallavalle_di_felice_derivatives;
use crate::numerics::safeguarded_newton;

/// Lowest voidage tabulated: below it the step falls back to the Newton solve.
pub const TABLE_VOIDAGE_MIN: f64 = 0.8;

/// Chebyshev terms of u_t, k_t and c_t (u_t: 17.9⁻¹⁴ ≈ 3e-18; k_t: 17.9⁻¹⁰ ≈ 3e-13; c_t:
/// 17.9⁻⁶ ≈ 3e-8, relative to their first terms).
const NU: usize = 14;
const NK: usize = 10;
const NC: usize = 6;

/// u_t, k_t = F'(u_t) and c_t = F''(u_t) of one sphere (diameter, densities, viscosity,
/// gravity) as Chebyshev series in the voidage on [[`TABLE_VOIDAGE_MIN`], 1], kept as
/// polynomials in the Chebyshev variable t (power basis: Horner's rule is a chain of one
/// multiply-add per term, where Clenshaw's recurrence needs three). SI units.
#[derive(Clone, Debug, PartialEq)]
pub struct TerminalTable {
    /// Diameter it is for, m.
    pub diameter_m: f64,
    /// The sphere's mass m, kg (as given to [`TerminalTable::new`]).
    pub mass_kg: f64,
    /// The body force W on the sphere, N (as given to [`TerminalTable::new`]).
    pub body_force_n: f64,
    u: [f64; NU],
    k: [f64; NK],
    c: [f64; NC],
}

/// The terminal speed of `g` (its voidage and body force) to full precision, m/s, with F' and
/// F'' there: safeguarded Newton on F(u) = |W| from a bracket found by doubling.
pub fn terminal_state(g: &DallavalleGrain) -> (f64, f64, f64) {
    let w = g.body_force_n.abs();
    let law = |u: f64| {
        dallavalle_di_felice_derivatives(
            u,
            g.voidage,
            g.ln_voidage,
            g.diameter_m,
            g.fluid_density_kg_m3,
            g.viscosity_pa_s,
        )
    };
    let mut hi = 1e-9;
    while law(hi).0 < w {
        hi *= 2.0;
    }
    let end = safeguarded_newton(
        0.0,
        hi,
        hi,
        200,
        |u| {
            let (f, k, _) = law(u);
            (f - w, k, ())
        },
        |it| {
            (it.next - it.at).abs() <= f64::EPSILON * it.at
                || it.hi - it.lo <= 2.0 * f64::EPSILON * it.hi
        },
    );
    let u = end.x;
    let (_, k, c) = law(u);
    (u, k, c)
}

/// The Chebyshev variable of voidage `eps`: t ∈ [−1, 1] on [[`TABLE_VOIDAGE_MIN`], 1].
fn cheb_t(eps: f64) -> f64 {
    (2.0 * eps - (1.0 + TABLE_VOIDAGE_MIN)) * (1.0 / (1.0 - TABLE_VOIDAGE_MIN))
}

/// The point t of Chebyshev node m of n, tₘ = cos(π(m + ½)/n), and its voidage.
fn node(m: usize, n: usize) -> (f64, f64) {
    let t = (std::f64::consts::PI * (m as f64 + 0.5) / n as f64).cos();
    (
        t,
        0.5 * ((1.0 - TABLE_VOIDAGE_MIN) * t + 1.0 + TABLE_VOIDAGE_MIN),
    )
}

/// Σ aⱼ tʲ by Horner's rule for `L` polynomials `a` at their points `t` at once: lane by lane
/// the same operations as one polynomial alone (so the same bits), interleaved so that the
/// processor overlaps the lanes' chains of multiply-adds.
#[inline(always)]
fn horner_lanes<const N: usize, const L: usize>(a: [&[f64; N]; L], t: [f64; L]) -> [f64; L] {
    let mut acc = [0.0; L];
    for j in (0..N).rev() {
        for l in 0..L {
            acc[l] = acc[l] * t[l] + a[l][j];
        }
    }
    acc
}

/// The power-basis coefficients of Σ′ cⱼ Tⱼ(t) (first term halved), from
/// T₀ = 1, T₁ = t, Tⱼ₊₁ = 2t Tⱼ − Tⱼ₋₁.
fn power_basis<const N: usize>(c: &[f64; N]) -> [f64; N] {
    let mut a = [0.0; N];
    let (mut prev, mut cur) = ([0.0; N], [0.0; N]);
    cur[0] = 1.0;
    for (j, &cj) in c.iter().enumerate() {
        let w = if j == 0 { 0.5 * cj } else { cj };
        for (ai, ti) in a.iter_mut().zip(&cur) {
            *ai += w * ti;
        }
        let mut next = [0.0; N];
        for i in 0..N {
            next[i] = -prev[i];
            if j == 0 {
                // T₁ = t.
                next[i] = 0.0;
            }
        }
        for i in 0..N - 1 {
            next[i + 1] += if j == 0 { cur[i] } else { 2.0 * cur[i] };
        }
        prev = cur;
        cur = next;
    }
    a
}

/// Chebyshev coefficients (first halved in [`clenshaw`]) of `n` terms from the values `f` at the
/// n Chebyshev points tₘ = cos(π(m + ½)/n).
fn coefficients<const N: usize>(f: &[f64]) -> [f64; N] {
    let n = f.len();
    let mut c = [0.0; N];
    for (j, cj) in c.iter_mut().enumerate() {
        let mut s = 0.0;
        for (m, fm) in f.iter().enumerate() {
            s += fm * (std::f64::consts::PI * j as f64 * (m as f64 + 0.5) / n as f64).cos();
        }
        *cj = 2.0 * s / n as f64;
    }
    c
}

impl TerminalTable {
    /// The table of a sphere `g` (its voidage is ignored: the table spans
    /// [[`TABLE_VOIDAGE_MIN`], 1]).
    pub fn new(g: &DallavalleGrain) -> Self {
        let at = |n: usize| -> Vec<(f64, f64, f64)> {
            (0..n)
                .map(|m| {
                    let eps = node(m, n).1;
                    terminal_state(&DallavalleGrain {
                        voidage: eps,
                        ln_voidage: eps.ln(),
                        ..*g
                    })
                })
                .collect()
        };
        let su = at(NU);
        let sk = at(NK);
        let sc = at(NC);
        Self {
            diameter_m: g.diameter_m,
            mass_kg: g.mass_kg,
            body_force_n: g.body_force_n,
            u: power_basis(&coefficients::<NU>(
                &su.iter().map(|x| x.0).collect::<Vec<_>>(),
            )),
            k: power_basis(&coefficients::<NK>(
                &sk.iter().map(|x| x.1).collect::<Vec<_>>(),
            )),
            c: power_basis(&coefficients::<NC>(
                &sc.iter().map(|x| x.2).collect::<Vec<_>>(),
            )),
        }
    }

    /// (u_t, k_t, c_t) at voidage `eps` ∈ [[`TABLE_VOIDAGE_MIN`], 1], else None.
    pub fn at(&self, eps: f64) -> Option<(f64, f64, f64)> {
        if !(TABLE_VOIDAGE_MIN..=1.0).contains(&eps) {
            return None;
        }
        let t = [cheb_t(eps)];
        Some((
            horner_lanes([&self.u], t)[0],
            horner_lanes([&self.k], t)[0],
            horner_lanes([&self.c], t)[0],
        ))
    }
}

/// Largest |s₁ − u_t|/u_t of [`exponential_near_terminal`]: the neglected F''' (s₁ − u_t)³/6 is
/// then below 1e-15 F relatively (F''' u_t³/F is of order (p − 1), p ≈ 1 + 0.13 √Re the drag's
/// exponent).
pub const NEAR_TERMINAL: f64 = 3e-5;

/// The exponential step of [`super::exponential_dallavalle_1d`] (the scheme of
/// [`super::advance`]) for a sphere near its terminal state, from `table` instead of a Newton
/// solve: (velocity, m/s; displacement, m), or None (the caller then solves) when the voidage is
/// outside the table, the body force and p = v₀ + W dt/m point opposite ways, or the
/// backward-Euler speed s₁ is farther than [`NEAR_TERMINAL`] from u_t.
///
/// With δ = s₁ − u_t and F(u_t + δ) = W + k_t δ + c_t δ²/2 + O(δ³), the backward-Euler equation
/// s₁ + (dt/m) F(s₁) = |p| becomes (1 + λdt) δ + (dt/m) c_t δ²/2 = |p| − u_t − |W| dt/m
/// (λ = k_t/m), solved by one fixed-point correction of its linear root; then F(s₁) and
/// k = F'(s₁) = k_t + c_t δ by the same expansion, and the exponential update as in
/// [`super::advance`]. The step's result depends on s₁ only to second order (v₁ → s₁ + (W −
/// F(s₁))/k is a Newton step towards u_t), and on k only through (v₀ − s₁)/(λdt), so its error
/// is that of u_t (the table's, 1e-16 relative) plus O(δ³).
pub fn exponential_near_terminal(
    table: &TerminalTable,
    g: &DallavalleGrain,
    v0_m_s: f64,
    dt_s: f64,
) -> Option<(f64, f64)> {
    exponential_near_terminal_lanes(
        [table],
        [g.voidage],
        [dt_s / g.mass_kg],
        [g.body_force_n],
        [v0_m_s],
        dt_s,
    )[0]
}

/// [`exponential_near_terminal`] for `L` spheres at once, each with its table (`tables`), its
/// voidage, step over mass dt/m (s/kg: the caller may compute it once for many spheres of one
/// mass), body force (N) and velocity (m/s) over the same step `dt_s` (s). Each
/// lane's result is the one-sphere result bit for bit (the same operations in the same order);
/// the lanes go through each stage together (Horner's rule is a chain of 30 multiply-adds per
/// sphere, and the step three divisions), so that the processor overlaps and pairs them.
#[inline(always)]
pub fn exponential_near_terminal_lanes<const L: usize>(
    tables: [&TerminalTable; L],
    voidage: [f64; L],
    dt_over_mass_s_kg: [f64; L],
    body_force_n: [f64; L],
    v0_m_s: [f64; L],
    dt_s: f64,
) -> [Option<(f64, f64)>; L] {
    let t = voidage.map(cheb_t);
    let ut = horner_lanes(tables.map(|x| &x.u), t);
    let kt = horner_lanes(tables.map(|x| &x.k), t);
    let ct = horner_lanes(tables.map(|x| &x.c), t);
    near_terminal_step(
        [ut, kt, ct],
        voidage,
        dt_over_mass_s_kg,
        body_force_n,
        v0_m_s,
        dt_s,
    )
}

/// Σ aⱼ tₗʲ by Horner's rule for one polynomial `a` at `L` points `t`: lane by lane the same
/// operations as [`horner_lanes`] (so the same bits).
#[inline(always)]
fn horner_one<const N: usize, const L: usize>(a: &[f64; N], t: [f64; L]) -> [f64; L] {
    let mut acc = [0.0; L];
    for j in (0..N).rev() {
        for l in 0..L {
            acc[l] = acc[l] * t[l] + a[j];
        }
    }
    acc
}

/// What the tabulated step of `L` spheres computes before its φ factors: per lane whether the
/// step applies (`applies`: voidage in the table, body force and p the same way, s₁ within
/// [`NEAR_TERMINAL`] of u_t), z = −k dt/m, 1/z and a₀ dt (`num`).
struct NearTerminal<const L: usize> {
    applies: [bool; L],
    z: [f64; L],
    inv: [f64; L],
    num: [f64; L],
}

/// The stages of [`exponential_near_terminal_lanes`] before its φ factors, from the tabulated
/// terminal state `[u_t, k_t, c_t]` of each lane.
#[inline(always)]
fn near_terminal_core<const L: usize>(
    [ut, kt, ct]: [[f64; L]; 3],
    voidage: [f64; L],
    dt_over_mass_s_kg: [f64; L],
    body_force_n: [f64; L],
    v0_m_s: [f64; L],
) -> NearTerminal<L> {
    let mut inv_h1 = [0.0; L];
    for l in 0..L {
        inv_h1[l] = inv_h1_of(dt_over_mass_s_kg[l], kt[l]);
    }
    let mut near = near_terminal_after(
        [ut, kt, ct],
        inv_h1,
        dt_over_mass_s_kg,
        body_force_n,
        v0_m_s,
    );
    for (applies, &e) in near.applies.iter_mut().zip(&voidage) {
        *applies &= in_table(e);
    }
    near
}

/// 1/(1 + k_t dt/m), the factor of the first Newton correction (the tabulated step's one
/// division that depends on the voidage and the kind alone).
#[inline(always)]
fn inv_h1_of(dt_over_mass_s_kg: f64, kt: f64) -> f64 {
    1.0 / (1.0 + dt_over_mass_s_kg * kt)
}

/// Whether `voidage` is in the table's range [[`TABLE_VOIDAGE_MIN`], 1] (false for NaN).
#[inline(always)]
fn in_table(voidage: f64) -> bool {
    (TABLE_VOIDAGE_MIN..=1.0).contains(&voidage)
}

/// [`near_terminal_core`] from the terminal state and 1/(1 + k_t dt/m) of each lane
/// (`applies` without the test of the table's range, which the caller adds).
#[inline(always)]
fn near_terminal_after<const L: usize>(
    [ut, kt, ct]: [[f64; L]; 3],
    inv_h1: [f64; L],
    dt_over_mass_s_kg: [f64; L],
    body_force_n: [f64; L],
    v0_m_s: [f64; L],
) -> NearTerminal<L> {
    let (w, v0) = (body_force_n, v0_m_s);
    let (mut kk, mut p, mut d0, mut delta) = ([0.0; L], [0.0; L], [0.0; L], [0.0; L]);
    let (mut k, mut f0, mut num, mut z, mut inv) =
        ([0.0; L], [0.0; L], [0.0; L], [0.0; L], [0.0; L]);
    for l in 0..L {
        kk[l] = dt_over_mass_s_kg[l];
        p[l] = v0[l] + w[l] * kk[l];
    }
    for l in 0..L {
        d0[l] = (p[l].abs() - ut[l] - w[l].abs() * kk[l]) * inv_h1[l];
        delta[l] = d0[l] - 0.5 * kk[l] * ct[l] * d0[l] * d0[l] * inv_h1[l];
        // s₁ = u_t + δ along p; F(s₁) − k s₁ with k = F'(s₁).
        k[l] = kt[l] + ct[l] * delta[l];
        f0[l] =
            w[l].abs() + (kt[l] + 0.5 * ct[l] * delta[l]) * delta[l] - k[l] * (ut[l] + delta[l]);
        // a₀ dt φ₁ = (W − F₀ p̂ − k v₀)(dt/m) φ₁, a₀ dt² φ₂ likewise, with λdt = k dt/m.
        num[l] = (w[l] - p[l].signum() * f0[l] - v0[l] * k[l]) * kk[l];
        z[l] = -k[l] * kk[l];
    }
    // φ₁ = −1/z, φ₂ = (−1 − z)/z² with one division where z < PHI_SATURATED.
    for l in 0..L {
        inv[l] = 1.0 / z[l];
    }
    // Plain loops here and below (not `array::from_fn` or `map`, which may be left out of line
    // and so not built for the caller's vector width).
    let mut applies = [false; L];
    for l in 0..L {
        let same_way = p[l] * w[l] > 0.0;
        let near = delta[l].abs() <= NEAR_TERMINAL * ut[l];
        applies[l] = same_way && near;
    }
    NearTerminal {
        applies,
        z,
        inv,
        num,
    }
}

/// The step of [`exponential_near_terminal_lanes`] from the tabulated terminal state
/// `[u_t, k_t, c_t]` of each lane.
#[inline(always)]
fn near_terminal_step<const L: usize>(
    terminal: [[f64; L]; 3],
    voidage: [f64; L],
    dt_over_mass_s_kg: [f64; L],
    body_force_n: [f64; L],
    v0_m_s: [f64; L],
    dt_s: f64,
) -> [Option<(f64, f64)>; L] {
    let (v0, dt) = (v0_m_s, dt_s);
    let NearTerminal {
        applies,
        z,
        inv,
        num,
    } = near_terminal_core(terminal, voidage, dt_over_mass_s_kg, body_force_n, v0_m_s);
    let mut out = [None; L];
    for l in 0..L {
        if !applies[l] {
            continue;
        }
        let (phi1, phi2) = if z[l] < PHI_SATURATED {
            (-inv[l], (-1.0 - z[l]) * (inv[l] * inv[l]))
        } else {
            phi12(z[l])
        };
        out[l] = Some((v0[l] + num[l] * phi1, v0[l] * dt + num[l] * (dt * phi2)));
    }
    out
}

/// The steps of `L` spheres of one kind that [`exponential_near_terminal`] gives and whose φ
/// factors are saturated (z = −k dt/m below [`PHI_SATURATED`], every step of a grain
/// much longer than its relaxation time): lane by lane (velocity, m/s; displacement, m), and
/// whether that lane is such a step (`ok`); the other lanes' values are meaningless (the caller
/// takes [`exponential_near_terminal`] there, which gives None or the unsaturated step). No
/// branch: every stage is one vector operation on the lanes.
pub struct SaturatedSteps<const L: usize> {
    /// Velocity after the step, m/s.
    pub velocity_m_s: [f64; L],
    /// Displacement over the step, m.
    pub displacement_m: [f64; L],
    /// Whether the lane's step is given here.
    pub ok: [bool; L],
}

/// [`exponential_near_terminal`] for `L` spheres of one table (one diameter, mass and body
/// force: a grain kind), each with its voidage and velocity (m/s), over the same step `dt_s`
/// (s), where the step's φ factors are saturated ([`SaturatedSteps`]); `dt_over_mass_s_kg` is
/// dt/m (s/kg). On those lanes the same bits as one sphere alone (the same operations in the
/// same order as [`exponential_near_terminal_lanes`]); with one table the coefficients are
/// read once for all the lanes and every stage is the same operation on every lane, so the
/// compiler computes the lanes as vectors.
#[inline(always)]
pub fn exponential_near_terminal_kind_saturated<const L: usize>(
    table: &TerminalTable,
    voidage: [f64; L],
    dt_over_mass_s_kg: f64,
    v0_m_s: [f64; L],
    dt_s: f64,
) -> SaturatedSteps<L> {
    let mut t = [0.0; L];
    for l in 0..L {
        t[l] = cheb_t(voidage[l]);
    }
    let terminal = [
        horner_one(&table.u, t),
        horner_one(&table.k, t),
        horner_one(&table.c, t),
    ];
    let near = near_terminal_core(
        terminal,
        voidage,
        [dt_over_mass_s_kg; L],
        [table.body_force_n; L],
        v0_m_s,
    );
    saturated(near, v0_m_s, dt_s)
}

/// The saturated step of each lane ([`SaturatedSteps`]) from its [`NearTerminal`] stages.
#[inline(always)]
fn saturated<const L: usize>(near: NearTerminal<L>, v0: [f64; L], dt: f64) -> SaturatedSteps<L> {
    let NearTerminal {
        applies,
        z,
        inv,
        num,
    } = near;
    let (mut velocity_m_s, mut displacement_m, mut ok) = ([0.0; L], [0.0; L], [false; L]);
    for l in 0..L {
        let (phi1, phi2) = (-inv[l], (-1.0 - z[l]) * (inv[l] * inv[l]));
        velocity_m_s[l] = v0[l] + num[l] * phi1;
        displacement_m[l] = v0[l] * dt + num[l] * (dt * phi2);
        ok[l] = applies[l] && z[l] < PHI_SATURATED;
    }
    SaturatedSteps {
        velocity_m_s,
        displacement_m,
        ok,
    }
}

/// What the tabulated step of a sphere of `table` at each of `L` voidages over a step with
/// dt/m = `dt_over_mass_s_kg` (s/kg) reads of its voidage: `[u_t, k_t, c_t, 1/(1 + k_t dt/m)]`
/// per lane (m/s, N·s/m, N·s²/m², 1), u_t NaN where the voidage is outside the table (so that
/// the step does not apply there). The same operations as
/// [`exponential_near_terminal_kind_saturated`] does per lane, so the same bits: computed once
/// per voidage cell and kind (`L` cells at a time, the Horner chains interleaved), it serves
/// every grain of that kind in that cell ([`exponential_near_terminal_kind_at`]).
#[inline(always)]
pub fn kind_at_voidage<const L: usize>(
    table: &TerminalTable,
    voidage: [f64; L],
    dt_over_mass_s_kg: f64,
) -> [[f64; L]; 4] {
    let mut t = [0.0; L];
    for l in 0..L {
        t[l] = cheb_t(voidage[l]);
    }
    let mut ut = horner_one(&table.u, t);
    let kt = horner_one(&table.k, t);
    let ct = horner_one(&table.c, t);
    let mut inv_h1 = [0.0; L];
    for l in 0..L {
        if !in_table(voidage[l]) {
            ut[l] = f64::NAN;
        }
        inv_h1[l] = inv_h1_of(dt_over_mass_s_kg, kt[l]);
    }
    [ut, kt, ct, inv_h1]
}

/// [`exponential_near_terminal_kind_saturated`] from what each lane reads of its voidage,
/// `at[i][l]` = [`kind_at_voidage`]`[i][l]` (of the same table and dt/m): the same bits,
/// without the Horner chains and the division they feed.
#[inline(always)]
pub fn exponential_near_terminal_kind_at<const L: usize>(
    table: &TerminalTable,
    at: [[f64; L]; 4],
    dt_over_mass_s_kg: f64,
    v0_m_s: [f64; L],
    dt_s: f64,
) -> SaturatedSteps<L> {
    let [ut, kt, ct, inv_h1] = at;
    let near = near_terminal_after(
        [ut, kt, ct],
        inv_h1,
        [dt_over_mass_s_kg; L],
        [table.body_force_n; L],
        v0_m_s,
    );
    saturated(near, v0_m_s, dt_s)
}
