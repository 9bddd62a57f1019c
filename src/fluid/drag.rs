//! A drag law bound to one sphere in one fluid: the magnitude of the drag as a function of the
//! sphere's speed relative to the fluid, its slope, its static resistance and its jumps.
//!
//! Every law here gives a drag magnitude F(v) that is non-decreasing in the speed v, possibly
//! with a finite limit F(0⁺) > 0 (yield stress) and upward jumps (f-EDEM eq. 19). The integrators
//! in [`crate::dynamics`] rely on that monotonicity: it makes the implicit update unique.

use super::bingham::{
    bingham_drag_n, bingham_static_resistance_n, reynolds_bingham, speed_at_reynolds_bingham,
    yield_drag_n, BinghamRegime, BINGHAM_RE_HIGH, BINGHAM_RE_LOW,
};
use super::bingham::{plastic, PlasticLaw, YieldFluid};
use super::buoyancy::sphere_area_m2;
use super::newtonian::{cd_dallavalle, di_felice_factor, drag_from_cd_n, reynolds, CdCorrelation};
use crate::numerics::safeguarded_newton;
use std::f64::consts::PI;

/// Which drag law acts on a sphere, with the fluid properties it needs.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum DragLaw {
    /// Stokes' law F = 3π η d v (f-EDEM eq. 7). Linear: exact under the exponential integrator.
    Stokes {
        /// Dynamic viscosity η, Pa s.
        viscosity_pa_s: f64,
    },
    /// Dallavalle C_d with the Di Felice voidage factor (seed 000 eqs. 7–9):
    /// F = ½ C_d(Re) ρ_f A v² ε^(1−χ(Re)), Re = ε ρ_f v d / η.
    Dallavalle {
        /// Dynamic viscosity η, Pa s.
        viscosity_pa_s: f64,
        /// Local fluid volume fraction ε ∈ (0, 1]; 1 for an isolated sphere.
        voidage: f64,
    },
    /// A single-sphere C_d(Re) correlation of a Newtonian fluid (Schiller–Naumann, Clift–Gauvin,
    /// Morrison; see [`CdCorrelation`]): F = ½ C_d(Re) ρ_f A v², Re = ρ_f v d / η (f-EDEM eq. 5).
    /// Tends to Stokes' law as Re → 0.
    Correlation {
        /// Dynamic viscosity η, Pa s.
        viscosity_pa_s: f64,
        /// Which correlation.
        cd: CdCorrelation,
    },
    /// Bingham drag of f-EDEM (eqs. 9, 14, 19).
    Bingham {
        /// Yield stress τ_y, Pa.
        yield_stress_pa: f64,
        /// Plastic viscosity η_B, Pa s.
        plastic_viscosity_pa_s: f64,
    },
    /// Another yield-stress law (additive, Ansley & Smith, Wilson et al.; see [`PlasticLaw`]) in a
    /// Bingham or Herschel–Bulkley fluid, optionally with Beris et al.'s static criterion.
    /// Smooth (no jumps), increasing, with a finite static resistance.
    Plastic {
        /// Which law.
        law: PlasticLaw,
        /// The fluid's rheogram.
        fluid: YieldFluid,
        /// Hold a sphere at rest up to Beris et al.'s critical yield number
        /// ([`super::bingham::beris`]) when the law's own static resistance is lower.
        beris: bool,
    },
}

/// Where a speed sits on a drag law, for reporting (`regime` column of the summaries).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DragRegime {
    /// Not moving.
    Static,
    /// Newtonian law: a single smooth branch.
    Smooth,
    /// A branch of f-EDEM eq. 19.
    Bingham(BinghamRegime),
    /// Sitting exactly on a jump of the law (set-valued drag there).
    Jump,
}

impl DragRegime {
    /// CSV label: `static`, `smooth`, `re<1`, `1<=re<=150`, `re>150` or `jump`.
    pub fn label(self) -> &'static str {
        match self {
            Self::Static => "static",
            Self::Smooth => "smooth",
            Self::Bingham(r) => r.label(),
            Self::Jump => "jump",
        }
    }
}

/// A drag law evaluated for one sphere (diameter) in one fluid (density).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SphereDrag {
    /// The law and its fluid properties.
    pub law: DragLaw,
    /// Sphere diameter d, m.
    pub diameter_m: f64,
    /// Fluid density ρ_f, kg/m³.
    pub fluid_density_kg_m3: f64,
    jumps: [f64; 2],
    n_jumps: usize,
    scale: f64,
}

impl DragLaw {
    /// The viscosity the law acts with, Pa s: the fluid's for a Newtonian law (Stokes,
    /// Dallavalle, a C_d correlation), the plastic viscosity η_B for the Bingham law.
    pub fn viscosity_pa_s(&self) -> f64 {
        match *self {
            DragLaw::Stokes { viscosity_pa_s }
            | DragLaw::Dallavalle { viscosity_pa_s, .. }
            | DragLaw::Correlation { viscosity_pa_s, .. } => viscosity_pa_s,
            DragLaw::Bingham {
                plastic_viscosity_pa_s,
                ..
            } => plastic_viscosity_pa_s,
            DragLaw::Plastic { fluid, .. } => fluid.consistency_pa_sn,
        }
    }

    /// The viscosity of a Newtonian law, Pa s; None for the yield-stress laws (f-EDEM's Reynolds
    /// number is Re′, eq. 18).
    pub fn newtonian_viscosity_pa_s(&self) -> Option<f64> {
        match self {
            DragLaw::Bingham { .. } | DragLaw::Plastic { .. } => None,
            _ => Some(self.viscosity_pa_s()),
        }
    }
}

impl SphereDrag {
    /// Binds `law` to a sphere of diameter `diameter_m` in a fluid of density `fluid_density_kg_m3`.
    pub fn new(law: DragLaw, diameter_m: f64, fluid_density_kg_m3: f64) -> Self {
        let (jumps, n_jumps) = match law {
            DragLaw::Bingham {
                yield_stress_pa,
                plastic_viscosity_pa_s,
            } => {
                let at = |re| {
                    speed_at_reynolds_bingham(
                        fluid_density_kg_m3,
                        diameter_m,
                        yield_stress_pa,
                        plastic_viscosity_pa_s,
                        re,
                    )
                };
                ([at(BINGHAM_RE_LOW), at(BINGHAM_RE_HIGH)], 2)
            }
            _ => ([f64::INFINITY; 2], 0),
        };
        Self {
            law,
            diameter_m,
            fluid_density_kg_m3,
            jumps,
            n_jumps,
            scale: 1.0,
        }
    }

    /// The same law with every force multiplied by `fraction` ∈ [0, 1]: the drag on a sphere
    /// crossing the free surface, scaled by the immersed fraction of its projected area
    /// (`submergence = "partial"`). The jump speeds do not change (Re' does not depend on area).
    pub fn scaled(&self, fraction: f64) -> Self {
        Self {
            scale: fraction,
            ..*self
        }
    }

    /// Speeds (m/s, ascending) at which the drag jumps upwards. Empty for Newtonian laws; for the
    /// Bingham law the speeds where Re' = 1 and Re' = 150.
    pub fn jump_speeds(&self) -> &[f64] {
        &self.jumps[..self.n_jumps]
    }

    /// Drag magnitude at speed `speed_m_s` > 0, N. At a jump speed, the value of the branch the
    /// law assigns that speed to (eq. 19: Re' = 1 and Re' = 150 belong to the middle branch).
    pub fn force_n(&self, speed_m_s: f64) -> f64 {
        self.scale * self.unscaled_force_n(speed_m_s)
    }

    fn unscaled_force_n(&self, speed_m_s: f64) -> f64 {
        let d = self.diameter_m;
        let rho = self.fluid_density_kg_m3;
        let v = speed_m_s;
        match self.law {
            DragLaw::Stokes { viscosity_pa_s } => 3.0 * PI * viscosity_pa_s * d * v,
            DragLaw::Dallavalle {
                viscosity_pa_s,
                voidage,
            } => {
                if v <= 0.0 {
                    return 0.0;
                }
                let re = reynolds(rho, voidage * v, d, viscosity_pa_s);
                drag_from_cd_n(cd_dallavalle(re), rho, d, v) * di_felice_factor(voidage, re)
            }
            DragLaw::Correlation { viscosity_pa_s, cd } => {
                if v <= 0.0 {
                    return 0.0;
                }
                drag_from_cd_n(cd.cd(reynolds(rho, v, d, viscosity_pa_s)), rho, d, v)
            }
            DragLaw::Bingham {
                yield_stress_pa,
                plastic_viscosity_pa_s,
            } => {
                if v <= 0.0 {
                    return bingham_static_resistance_n(d, yield_stress_pa);
                }
                bingham_drag_n(rho, d, yield_stress_pa, plastic_viscosity_pa_s, v)
            }
            DragLaw::Plastic { law, fluid, .. } => law.force_n(&fluid, rho, d, v),
        }
    }

    /// Static resistance F(0⁺), N: the drag a sphere at rest can oppose to a driving force before
    /// it moves. Zero for Newtonian laws; (π²/4 + 3π) d² τ_y for the Bingham law; for the other
    /// yield-stress laws their own F(0⁺), or Beris et al.'s threshold when the criterion is on and
    /// that is larger (then the drag drops from it to F(0⁺) once the sphere moves, like static
    /// and kinetic friction).
    pub fn static_resistance_n(&self) -> f64 {
        match self.law {
            DragLaw::Bingham {
                yield_stress_pa, ..
            } => self.scale * bingham_static_resistance_n(self.diameter_m, yield_stress_pa),
            DragLaw::Plastic { law, fluid, beris } => {
                self.scale * plastic::static_resistance_n(law, &fluid, self.diameter_m, beris)
            }
            _ => 0.0,
        }
    }

    /// Slope dF/dv at speed `speed_m_s` ≥ 0 within its branch, N s/m (right derivative at 0).
    pub fn slope_n_s_m(&self, speed_m_s: f64) -> f64 {
        self.scale * self.unscaled_slope_n_s_m(speed_m_s)
    }

    fn unscaled_slope_n_s_m(&self, speed_m_s: f64) -> f64 {
        let d = self.diameter_m;
        let rho = self.fluid_density_kg_m3;
        let a = sphere_area_m2(d);
        let v = speed_m_s.max(0.0);
        match self.law {
            DragLaw::Stokes { viscosity_pa_s } => 3.0 * PI * viscosity_pa_s * d,
            DragLaw::Plastic { .. } => {
                // The drag is finite at rest: a step of 1e-9 m/s at least keeps the difference
                // above the rounding of F(0⁺) (a smaller one returns 0 at v = 0).
                let h = (v * 1e-6).max(1e-9);
                if v > h {
                    (self.unscaled_force_n(v + h) - self.unscaled_force_n(v - h)) / (2.0 * h)
                } else {
                    (self.unscaled_force_n(v + h) - self.unscaled_force_n(v)) / h
                }
            }
            DragLaw::Dallavalle { .. } | DragLaw::Correlation { .. } => {
                // Central difference on the smooth law, one-sided near zero.
                let h = (v * 1e-6).max(1e-15);
                if v > h {
                    (self.unscaled_force_n(v + h) - self.unscaled_force_n(v - h)) / (2.0 * h)
                } else {
                    (self.unscaled_force_n(v + h) - self.unscaled_force_n(v)) / h
                }
            }
            DragLaw::Bingham {
                plastic_viscosity_pa_s,
                ..
            } => match self.bingham_regime(v) {
                BinghamRegime::Creeping => 12.0 * a * plastic_viscosity_pa_s / d,
                BinghamRegime::Intermediate => {
                    14.56 * a * plastic_viscosity_pa_s / d + 0.195 * rho * a * v
                }
                BinghamRegime::Newton => 0.4 * rho * a * v,
            },
        }
    }

    /// Regime of the Bingham law at a speed (speed 0 counts as creeping).
    fn bingham_regime(&self, speed_m_s: f64) -> BinghamRegime {
        match self.law {
            DragLaw::Bingham {
                yield_stress_pa,
                plastic_viscosity_pa_s,
            } => {
                if speed_m_s <= 0.0 {
                    return BinghamRegime::Creeping;
                }
                BinghamRegime::of(reynolds_bingham(
                    self.fluid_density_kg_m3,
                    speed_m_s,
                    self.diameter_m,
                    yield_stress_pa,
                    plastic_viscosity_pa_s,
                ))
            }
            _ => BinghamRegime::Creeping,
        }
    }

    /// Regime label of a speed for reports; `at_jump` marks a speed held on a jump.
    pub fn regime(&self, speed_m_s: f64, at_jump: bool) -> DragRegime {
        if at_jump {
            DragRegime::Jump
        } else if speed_m_s <= 0.0 {
            DragRegime::Static
        } else {
            match self.law {
                DragLaw::Bingham { .. } => DragRegime::Bingham(self.bingham_regime(speed_m_s)),
                _ => DragRegime::Smooth,
            }
        }
    }

    /// Solves `s + k·F(s) = target` for s ≥ 0 with k ≥ 0: the backward-Euler speed update
    /// (k = dt/m). [`Self::balance_speed`] solves the force balance F(s) = force the same way.
    ///
    /// The left side is strictly increasing with upward jumps, so the solution is unique: either
    /// s = 0 (the target does not overcome the static resistance), an interior root of one
    /// branch, or a jump speed (the target falls inside the jump). Safeguarded Newton iteration
    /// on each continuous branch; `guess` (m/s) warm-starts it.
    pub fn solve_implicit(&self, k: f64, target: f64, guess: f64) -> Solved {
        if target <= k * self.static_resistance_n() || target <= 0.0 {
            return Solved::zero();
        }
        // Walk the continuous branches [lo, hi) between jumps; hi of the last one is `target`,
        // because h(s) ≥ s.
        let mut lo = 0.0;
        let mut branch = 0;
        for &j in self.jump_speeds() {
            if j >= target {
                break;
            }
            let left = j + k * self.force_below(j);
            if target < left {
                return self.branch_root(branch, 1.0, k, target, lo, j, guess);
            }
            if target <= j + k * self.force_above(j) {
                return Solved {
                    speed_m_s: j,
                    at_jump: true,
                };
            }
            lo = j;
            branch += 1;
        }
        self.branch_root(branch, 1.0, k, target, lo, target, guess)
    }

    /// Polynomial form F(v) = a + b v + c v² of continuous branch `i` (counted from v = 0 across
    /// the jumps), where the law has one: Stokes (one branch) and the Bingham law of f-EDEM
    /// (three branches, see [`super::bingham`]). None for Dallavalle and the C_d correlations.
    pub fn branch_polynomial(&self, i: usize) -> Option<(f64, f64, f64)> {
        let f = self.scale;
        self.unscaled_branch_polynomial(i)
            .map(|(a, b, c)| (f * a, f * b, f * c))
    }

    fn unscaled_branch_polynomial(&self, i: usize) -> Option<(f64, f64, f64)> {
        let d = self.diameter_m;
        let a_p = sphere_area_m2(d);
        let rho = self.fluid_density_kg_m3;
        match self.law {
            DragLaw::Stokes { viscosity_pa_s } => Some((0.0, 3.0 * PI * viscosity_pa_s * d, 0.0)),
            DragLaw::Bingham {
                yield_stress_pa: ty,
                plastic_viscosity_pa_s: eb,
            } => {
                let fy = yield_drag_n(d, ty);
                Some(match i {
                    0 => (fy + 12.0 * a_p * ty, 12.0 * a_p * eb / d, 0.0),
                    1 => (
                        fy + 14.56 * a_p * ty,
                        14.56 * a_p * eb / d,
                        0.0975 * rho * a_p,
                    ),
                    _ => (fy, 0.0, 0.2 * rho * a_p),
                })
            }
            DragLaw::Dallavalle { .. } | DragLaw::Correlation { .. } | DragLaw::Plastic { .. } => {
                None
            }
        }
    }

    /// Root of `alpha·s + k·F(s) = target` on branch `i` within [lo, hi]: closed form where the
    /// branch is a polynomial of degree ≤ 2, safeguarded Newton otherwise.
    #[allow(clippy::too_many_arguments)]
    fn branch_root(
        &self,
        i: usize,
        alpha: f64,
        k: f64,
        target: f64,
        lo: f64,
        hi: f64,
        guess: f64,
    ) -> Solved {
        if let Some((a, b, c)) = self.branch_polynomial(i) {
            // k c s² + (alpha + k b) s + (k a − target) = 0, positive root in a stable form.
            let (qa, qb, qc) = (k * c, alpha + k * b, k * a - target);
            let s = if qa == 0.0 {
                -qc / qb
            } else {
                -2.0 * qc / (qb + (qb * qb - 4.0 * qa * qc).sqrt())
            };
            return Solved {
                speed_m_s: s.clamp(lo, hi),
                at_jump: false,
            };
        }
        self.newton(
            &|s| alpha * s + k * self.force_n(s),
            |s| alpha + k * self.slope_n_s_m(s),
            lo,
            hi,
            target,
            guess,
        )
    }

    /// Speed at which the drag balances a driving force `force_n` ≥ 0 (terminal velocity of the
    /// force balance, f-EDEM eq. 15), m/s. Zero when the force does not exceed the static
    /// resistance; a jump speed when the force falls inside a jump.
    pub fn balance_speed(&self, force_n: f64) -> Solved {
        if force_n <= self.static_resistance_n() {
            return Solved::zero();
        }
        let mut lo = 0.0;
        for (i, &j) in self.jump_speeds().iter().enumerate() {
            if force_n < self.force_below(j) {
                return self.branch_root(i, 0.0, 1.0, force_n, lo, j, j);
            }
            if force_n <= self.force_above(j) {
                return Solved {
                    speed_m_s: j,
                    at_jump: true,
                };
            }
            lo = j;
        }
        let mut hi = lo.max(1e-12) * 2.0;
        while self.force_n(hi) < force_n {
            if hi > 1e300 {
                // No drag can balance the force (e.g. a zero-scaled law in air).
                return Solved {
                    speed_m_s: f64::INFINITY,
                    at_jump: false,
                };
            }
            hi *= 2.0;
        }
        self.branch_root(self.jump_speeds().len(), 0.0, 1.0, force_n, lo, hi, hi)
    }

    /// Drag just below a jump speed (left limit), N: the lower branch's closed form.
    fn force_below(&self, jump_m_s: f64) -> f64 {
        self.bingham_branch_force(jump_m_s, jump_m_s != self.jumps[0])
    }

    /// Drag just above a jump speed (right limit), N: the upper branch's closed form.
    fn force_above(&self, jump_m_s: f64) -> f64 {
        self.bingham_branch_force(jump_m_s, jump_m_s == self.jumps[0])
    }

    /// Closed form of a Bingham branch (see the module doc of [`super::bingham`]) at a speed:
    /// `middle` picks 1 ≤ Re' ≤ 150; otherwise the branch below Re' = 1 for speeds up to the
    /// first jump and above Re' = 150 beyond it.
    fn bingham_branch_force(&self, speed_m_s: f64, middle: bool) -> f64 {
        self.scale * self.unscaled_branch_force(speed_m_s, middle)
    }

    fn unscaled_branch_force(&self, speed_m_s: f64, middle: bool) -> f64 {
        let d = self.diameter_m;
        let a = sphere_area_m2(d);
        let rho = self.fluid_density_kg_m3;
        let v = speed_m_s;
        match self.law {
            DragLaw::Bingham {
                yield_stress_pa: ty,
                plastic_viscosity_pa_s: eb,
            } => {
                let fy = yield_drag_n(d, ty);
                if middle {
                    fy + 14.56 * a * (ty + eb * v / d) + 0.0975 * rho * a * v * v
                } else if v <= self.jumps[0] {
                    fy + 12.0 * a * (ty + eb * v / d)
                } else {
                    fy + 0.2 * rho * a * v * v
                }
            }
            _ => self.unscaled_force_n(v),
        }
    }

    /// Safeguarded Newton for `f(s) = target` on [lo, hi] with f continuous and increasing.
    fn newton(
        &self,
        f: &dyn Fn(f64) -> f64,
        df: impl Fn(f64) -> f64,
        lo: f64,
        hi: f64,
        target: f64,
        guess: f64,
    ) -> Solved {
        let start = if guess > lo && guess < hi {
            guess
        } else {
            0.5 * (lo + hi)
        };
        let end = safeguarded_newton(
            lo,
            hi,
            start,
            200,
            |s| (f(s) - target, df(s), ()),
            |it| {
                (it.next - it.at).abs() <= 4.0 * f64::EPSILON * it.at.abs().max(f64::MIN_POSITIVE)
                    || it.hi - it.lo <= 4.0 * f64::EPSILON * it.hi
            },
        );
        Solved {
            speed_m_s: end.x,
            at_jump: false,
        }
    }
}

/// A speed found by [`SphereDrag::solve_implicit`] or [`SphereDrag::balance_speed`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solved {
    /// The speed, m/s (≥ 0).
    pub speed_m_s: f64,
    /// True when the speed is held on a jump of the drag law (set-valued drag there).
    pub at_jump: bool,
}

impl Solved {
    fn zero() -> Self {
        Self {
            speed_m_s: 0.0,
            at_jump: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::bingham::net_weight_n;

    fn susp1(d: f64) -> SphereDrag {
        SphereDrag::new(
            DragLaw::Bingham {
                yield_stress_pa: 30.5,
                plastic_viscosity_pa_s: 0.0131,
            },
            d,
            1280.0,
        )
    }

    #[test]
    fn bingham_drag_is_monotone_with_upward_jumps() {
        let law = susp1(0.019);
        let mut prev = law.static_resistance_n();
        for i in 1..20000 {
            let v = i as f64 * 1e-4;
            let f = law.force_n(v);
            assert!(f >= prev, "drag decreases at v = {v}");
            prev = f;
        }
        for &j in law.jump_speeds() {
            assert!(law.force_below(j) < law.force_above(j));
            assert!((law.force_above(j) / law.force_n(j * (1.0 + 1e-12)) - 1.0).abs() < 1e-9);
            assert!((law.force_below(j) / law.force_n(j * (1.0 - 1e-12)) - 1.0).abs() < 1e-9);
        }
    }

    #[test]
    fn balance_speed_solves_the_force_balance() {
        let law = susp1(0.0254);
        let w = net_weight_n(0.0254, 6142.0, 1280.0, 9.81);
        let s = law.balance_speed(w);
        assert!(!s.at_jump);
        assert!((law.force_n(s.speed_m_s) / w - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_force_inside_a_jump_holds_the_speed_on_the_jump() {
        let law = susp1(0.019);
        let j = law.jump_speeds()[0];
        let inside = 0.5 * (law.force_below(j) + law.force_above(j));
        let s = law.balance_speed(inside);
        assert!(s.at_jump);
        assert_eq!(s.speed_m_s, j);
        // Same for the implicit update: target whose solution falls inside the jump.
        let k = 0.01;
        let target = j + k * inside;
        let s = law.solve_implicit(k, target, 0.0);
        assert!(s.at_jump && s.speed_m_s == j);
    }

    #[test]
    fn below_the_static_resistance_nothing_moves() {
        let law = susp1(0.019);
        let fs = law.static_resistance_n();
        assert_eq!(law.balance_speed(0.999 * fs).speed_m_s, 0.0);
        assert_eq!(
            law.solve_implicit(0.1, 0.1 * 0.999 * fs, 0.0).speed_m_s,
            0.0
        );
    }

    #[test]
    fn implicit_solution_satisfies_its_equation_in_every_branch() {
        let law = susp1(0.0254);
        for target in [0.02, 0.3, 1.0, 5.0, 40.0] {
            let k = 0.05;
            let s = law.solve_implicit(k, target, 0.0);
            if !s.at_jump && s.speed_m_s > 0.0 {
                let r = s.speed_m_s + k * law.force_n(s.speed_m_s) - target;
                assert!(r.abs() < 1e-12 * target, "target {target}: residual {r}");
            }
        }
    }

    #[test]
    fn dallavalle_tends_to_96_percent_of_stokes_at_low_re() {
        let law = SphereDrag::new(
            DragLaw::Dallavalle {
                viscosity_pa_s: 1e-3,
                voidage: 1.0,
            },
            2.5e-6,
            1000.0,
        );
        let v = 5e-6;
        let stokes = 3.0 * PI * 1e-3 * 2.5e-6 * v;
        assert!((law.force_n(v) / stokes - 0.96).abs() < 0.01);
    }
}
