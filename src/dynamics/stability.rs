//! Detection of numerical instability in a run: non-finite state, and velocity oscillating
//! about its equilibrium with growing amplitude (the signature of an explicit drag update with
//! dt > 2 m/(dF/dv)). Rapier's speed cap hides such a blow-up as a bounded flip-flop, so this
//! check looks at the growth of the deviation, not at a speed bound alone.

use std::fmt;

/// A run that went unstable: which body, when, what quantity, and a step that would be stable.
#[derive(Clone, Debug, PartialEq)]
pub struct Unstable {
    /// Identifier of the body.
    pub body: String,
    /// Simulated time at which the instability was detected, s.
    pub time_s: f64,
    /// Step index at detection.
    pub step: u64,
    /// What went wrong (`velocity is NaN`, `velocity oscillates with growing amplitude`, …).
    pub what: String,
    /// The time step in use, s.
    pub dt_s: f64,
    /// Largest time step expected to be stable for this body, s (infinite if unknown; 0 when no
    /// step is stable for the scheme in use, e.g. explicit drag at a yield-stress stop).
    pub stable_dt_s: f64,
    /// How `stable_dt_s` was found, which sets the advice printed.
    pub dt_basis: DtBasis,
}

/// How the suggested step of an [`Unstable`] report was found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DtBasis {
    /// The explicit drag update's limit 2 m/(dF/dv) (0: no step holds a yield-stress stop).
    #[default]
    ExplicitDrag,
    /// Half the step in use: a fault of the contacts, the speed cap or the domain, which a
    /// body travelling a smaller fraction of its diameter per step avoids.
    Halved,
}

impl fmt::Display for Unstable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unstable: body `{}` at t = {:.6e} s (step {}): {} with dt = {:.3e} s",
            self.body, self.time_s, self.step, self.what, self.dt_s
        )?;
        if self.dt_basis == DtBasis::Halved {
            write!(
                f,
                "; try dt ≤ {:.3e} s (half the step: contacts and the speed cap hold when a body \
                 travels a small fraction of its diameter per step), or check the initial \
                 positions and the scene's settings",
                self.stable_dt_s
            )?;
        } else if self.stable_dt_s == 0.0 {
            write!(
                f,
                "; no time step makes the explicit scheme hold a body at rest against a yield stress: use integrator = \"implicit\" or \"exponential\""
            )?;
        } else if self.stable_dt_s.is_finite() {
            write!(
                f,
                "; largest stable dt for this body ≈ {:.3e} s (2m/(dF/dv)): use dt < {:.3e} s or integrator = \"exponential\"",
                self.stable_dt_s, self.stable_dt_s
            )?;
        }
        Ok(())
    }
}

impl std::error::Error for Unstable {}

/// Watches one body's velocity deviation from its equilibrium velocity step after step.
#[derive(Clone, Debug, Default)]
pub struct Monitor {
    growing: u32,
}

impl Monitor {
    /// Number of consecutive overshooting, growing steps that counts as divergence.
    pub const STRIKES: u32 = 3;

    /// Checks one step. `dev0`, `dev1`: velocity minus equilibrium velocity before and after the
    /// step (any dimension, as slices). Returns a description when the body is unstable.
    pub fn check(&mut self, dev0: &[f64], dev1: &[f64]) -> Option<String> {
        if dev1.iter().any(|x| !x.is_finite()) {
            return Some("velocity is not finite (NaN or infinite)".into());
        }
        let dot: f64 = dev0.iter().zip(dev1).map(|(a, b)| a * b).sum();
        let n0: f64 = dev0.iter().map(|a| a * a).sum();
        let n1: f64 = dev1.iter().map(|a| a * a).sum();
        if dot < 0.0 && n1 > n0 * (1.0 + 1e-9) {
            self.growing += 1;
        } else {
            self.growing = 0;
        }
        (self.growing >= Self::STRIKES).then(|| {
            format!(
                "velocity oscillates about its equilibrium with growing amplitude (|v − v_eq| = {:.3e} m/s)",
                n1.sqrt()
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_decaying_oscillation_is_stable_a_growing_one_is_not() {
        let mut m = Monitor::default();
        let mut d = 1.0;
        for _ in 0..50 {
            assert!(m.check(&[d], &[-0.9 * d]).is_none());
            d *= -0.9;
        }
        let mut m = Monitor::default();
        let mut hits = 0;
        let mut d = 1.0;
        for _ in 0..5 {
            if m.check(&[d], &[-1.1 * d]).is_some() {
                hits += 1;
            }
            d *= -1.1;
        }
        assert_eq!(hits, 3);
        assert!(Monitor::default().check(&[1.0], &[f64::NAN]).is_some());
    }
}
