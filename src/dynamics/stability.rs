//! Detection of numerical instability in a run: non-finite state, and velocity oscillating
//! about its equilibrium with growing amplitude (the signature of an explicit drag update with
//! dt > 2 m/(dF/dv)). Rapier's speed cap hides such a blow-up as a bounded flip-flop, so this
//! check looks at the growth of the deviation, not at a speed bound alone.

pub use crate::error::{DtBasis, Unstable};

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
