//! The yield-stress drag laws besides f-EDEM's, behind one type: which law, the fluid's
//! rheogram, and whether Beris et al.'s static criterion holds slow spheres at rest.

use super::additive::additive_drag_n;
use super::ansley_smith::{ansley_smith_drag_n, ansley_smith_static_resistance_n};
use super::beris::beris_static_resistance_n;
use super::fedem::bingham_static_resistance_n;
use super::wilson::{wilson_drag_n, wilson_static_resistance_n};

/// A yield-stress drag law other than f-EDEM's (each in its own module of [`super`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum PlasticLaw {
    /// Static resistance (π²/4 + 3π) d² τ_y plus the Newtonian drag at ρ v d/η_B
    /// ([`super::additive`]). Bingham fluids only.
    Additive,
    /// Ansley & Smith (1967): the standard drag curve at Re* ([`super::ansley_smith`]). Bingham
    /// fluids only.
    AnsleySmith,
    /// Wilson et al. (2003): the standard drag curve with the rheogram's secant viscosity at 0.3
    /// of the mean surface stress ([`super::wilson`]). Bingham and Herschel–Bulkley fluids.
    Wilson,
}

impl PlasticLaw {
    /// Every law, in table order.
    pub const ALL: [PlasticLaw; 3] = [Self::Additive, Self::AnsleySmith, Self::Wilson];

    /// The `drag.law` value: `bingham-additive`, `ansley-smith`, `wilson-2003`.
    pub fn key(self) -> &'static str {
        match self {
            Self::Additive => "bingham-additive",
            Self::AnsleySmith => "ansley-smith",
            Self::Wilson => "wilson-2003",
        }
    }

    /// True when the law takes a Herschel–Bulkley rheogram (flow index n ≠ 1).
    pub fn supports_herschel_bulkley(self) -> bool {
        self == Self::Wilson
    }

    /// Drag magnitude at speed `speed_m_s` ≥ 0 in `fluid`, N (the law's own static resistance at
    /// v = 0). For the Bingham-only laws K is η_B and n is ignored.
    pub fn force_n(
        self,
        fluid: &YieldFluid,
        fluid_density_kg_m3: f64,
        d_m: f64,
        speed_m_s: f64,
    ) -> f64 {
        let (rho, ty, k) = (
            fluid_density_kg_m3,
            fluid.yield_stress_pa,
            fluid.consistency_pa_sn,
        );
        match self {
            Self::Additive => additive_drag_n(rho, d_m, ty, k, speed_m_s),
            Self::AnsleySmith => ansley_smith_drag_n(rho, d_m, ty, k, speed_m_s),
            Self::Wilson => wilson_drag_n(rho, d_m, ty, k, fluid.flow_index, speed_m_s),
        }
    }

    /// The law's own static resistance F(0⁺), N.
    pub fn own_static_resistance_n(self, fluid: &YieldFluid, d_m: f64) -> f64 {
        let ty = fluid.yield_stress_pa;
        match self {
            Self::Additive => bingham_static_resistance_n(d_m, ty),
            Self::AnsleySmith => ansley_smith_static_resistance_n(d_m, ty),
            Self::Wilson => wilson_static_resistance_n(d_m, ty),
        }
    }
}

/// A yield-stress fluid's rheogram, τ = τ_y + K γ̇ⁿ above the yield stress (Herschel & Bulkley
/// 1926); a Bingham plastic is n = 1 with K = η_B.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct YieldFluid {
    /// Yield stress τ_y, Pa.
    pub yield_stress_pa: f64,
    /// Consistency K, Pa sⁿ (the plastic viscosity η_B of a Bingham plastic).
    pub consistency_pa_sn: f64,
    /// Flow index n, dimensionless (1 for a Bingham plastic).
    pub flow_index: f64,
}

impl YieldFluid {
    /// A Bingham plastic: τ = τ_y + η_B γ̇.
    pub fn bingham(yield_stress_pa: f64, plastic_viscosity_pa_s: f64) -> Self {
        Self {
            yield_stress_pa,
            consistency_pa_sn: plastic_viscosity_pa_s,
            flow_index: 1.0,
        }
    }
}

/// Static resistance of `law` in `fluid` for a sphere of diameter `d_m`, N: the law's own, or,
/// with `beris`, the larger of it and Beris et al.'s ([`super::beris`]). The criterion can hold a
/// sphere the law would let move, never start one the law holds.
pub fn static_resistance_n(law: PlasticLaw, fluid: &YieldFluid, d_m: f64, beris: bool) -> f64 {
    let own = law.own_static_resistance_n(fluid, d_m);
    if beris {
        own.max(beris_static_resistance_n(d_m, fluid.yield_stress_pa))
    } else {
        own
    }
}
