//! Contact properties: `[contacts]`.

use crate::error::BadInput;
use crate::scenario::check::{cc, Check};
use serde::{Deserialize, Serialize};

fn default_reference_speed() -> f64 {
    1.0
}

/// Contact properties of every collider of a scene with contacts.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Contacts {
    /// Coefficient of restitution, 0 ≤ e ≤ 1 (f-EDEM Table 4: 0.612, steel on steel); with a
    /// non-zero `restitution_exponent`, the value at `restitution_reference_speed_m_s`.
    pub restitution: f64,
    /// Exponent k of the speed-dependent restitution e(v) = e (v / v_ref)^(−k), clamped below 1
    /// ([`crate::contact::RestitutionLaw`]), v the impact (approach) speed; 0 ≤ k ≤ 1.
    /// Default 0: a constant coefficient.
    #[serde(default)]
    pub restitution_exponent: f64,
    /// Reference speed v_ref of the speed-dependent restitution, m/s, 1e-3 ≤ v_ref ≤ 100.
    /// Default 1 m/s.
    #[serde(default = "default_reference_speed")]
    pub restitution_reference_speed_m_s: f64,
    /// Coulomb (static) friction coefficient ≥ 0 (f-EDEM Table 4: 0.341).
    pub friction: f64,
    /// Rolling resistance coefficient μ_r ≥ 0: a torque μ_r · r · |F_n| opposing the rolling
    /// (f-EDEM Table 4: 0.002). Default 0.
    #[serde(default)]
    pub rolling_resistance: f64,
}

impl Contacts {
    /// The restitution law these settings give.
    pub fn restitution_law(&self) -> crate::contact::RestitutionLaw {
        crate::contact::RestitutionLaw {
            coefficient: self.restitution,
            exponent: self.restitution_exponent,
            reference_speed_m_s: self.restitution_reference_speed_m_s,
        }
    }
}

impl Contacts {
    /// Restitution and its speed law, friction and rolling resistance within their ranges.
    pub(crate) fn check(&self, c: &Check) -> Result<(), BadInput> {
        c.table(
            "contacts",
            &[
                ("restitution", self.restitution, cc(0.0, 1.0, "")),
                (
                    "restitution_exponent",
                    self.restitution_exponent,
                    cc(0.0, 1.0, ""),
                ),
                (
                    "restitution_reference_speed_m_s",
                    self.restitution_reference_speed_m_s,
                    cc(1e-3, 100.0, "m/s"),
                ),
                ("friction", self.friction, cc(0.0, 10.0, "")),
                (
                    "rolling_resistance",
                    self.rolling_resistance,
                    cc(0.0, 1.0, ""),
                ),
            ],
        )
    }
}
