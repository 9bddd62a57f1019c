//! Drag on a sphere in a Bingham plastic: the law of f-EDEM §2 after Dedegil 1987
//! ([`fedem`], re-exported here), and the other plastic laws ([`PlasticLaw`]).
//!
//! f-EDEM's law:
//!
//! F_d = (π d / 2)² τ_y + ½ C_d ρ_f v² A                        (f-EDEM eq. 9)
//! Re' = ρ_f v² / (τ_y + η_B v / d)                              (f-EDEM eq. 14)
//! C_d = 24/Re' (Re' < 1); 29.12/Re' + 0.195 (1 ≤ Re' ≤ 150); 0.4 (Re' > 150)   (f-EDEM eq. 19)
//!
//! Substituting eq. 14 into eq. 19 makes every branch a quadratic in the speed v:
//! - Re' < 1:        F = F_y + 12 A (τ_y + η_B v/d)
//! - 1 ≤ Re' ≤ 150:  F = F_y + 14.56 A (τ_y + η_B v/d) + 0.0975 ρ_f A v²
//! - Re' > 150:      F = F_y + 0.2 ρ_f A v²
//!
//! with F_y = (π d/2)² τ_y and A = π d²/4. As v → 0 the drag tends to the finite static
//! resistance F_y + 12 A τ_y = (π²/4 + 3π) d² τ_y: at rest the drag is set-valued, like Coulomb
//! friction. Eq. 19 jumps upwards at Re' = 1 (C_d 24 → 29.315) and Re' = 150 (0.389 → 0.4), so
//! the drag is a monotone increasing function of v with two upward jumps.

pub mod additive;
pub mod ansley_smith;
pub mod beris;
pub mod fedem;
pub mod plastic;
pub mod wilson;

pub use fedem::{
    bingham_drag_n, bingham_static_resistance_n, cd_fedem, cd_from_terminal_velocity, net_weight_n,
    reynolds_bingham, speed_at_reynolds_bingham, yield_drag_n, BinghamRegime, BINGHAM_RE_HIGH,
    BINGHAM_RE_LOW,
};
pub use plastic::{PlasticLaw, YieldFluid};
