//! The fluid and the drag law: `[fluid]` and `[drag]`.

use super::super::check::{cc, oc, Check};
use super::super::load::ScenarioError;
use super::Physics;
use serde::{Deserialize, Serialize};

pub use crate::fluid::Submergence;

/// Rheology of the fluid.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Rheology {
    /// Newtonian: needs `viscosity_pa_s`.
    Newtonian,
    /// Bingham plastic: needs `plastic_viscosity_pa_s` and `yield_stress_pa`.
    Bingham,
}

/// The fluid.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Fluid {
    /// Density ρ_f, kg/m³ (0 < ρ_f ≤ 25 000).
    pub density_kg_m3: f64,
    /// `newtonian` or `bingham`.
    pub rheology: Rheology,
    /// Dynamic viscosity η, Pa s (Newtonian only; > 0).
    #[serde(default)]
    pub viscosity_pa_s: Option<f64>,
    /// Plastic viscosity η_B, Pa s (Bingham only; > 0).
    #[serde(default)]
    pub plastic_viscosity_pa_s: Option<f64>,
    /// Yield stress τ_y, Pa (Bingham only; ≥ 0).
    #[serde(default)]
    pub yield_stress_pa: Option<f64>,
    /// `full` (default) or `partial`: fluid forces on a sphere crossing the free surface.
    #[serde(default)]
    pub submergence: Submergence,
}

/// Names of the drag laws.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum DragLawName {
    /// Stokes' law, f-EDEM eq. 7.
    Stokes,
    /// Dallavalle C_d with Di Felice voidage, seed 000 eqs. 7–9.
    Dallavalle,
    /// f-EDEM eqs. 9, 14, 19 (Bingham fluids only).
    BinghamFedem,
    /// Schiller–Naumann (1933) C_d, Re < 800 ([`crate::fluid::newtonian::cd_schiller_naumann`]).
    SchillerNaumann,
    /// Clift–Gauvin (1971) C_d, Re < 3·10⁵ ([`crate::fluid::newtonian::cd_clift_gauvin`]).
    CliftGauvin,
    /// Morrison (2013) C_d, Re ≤ 10⁶ ([`crate::fluid::newtonian::cd_morrison`]).
    Morrison,
}

/// The drag law.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Drag {
    /// `stokes`, `dallavalle`, `bingham-fedem`, `schiller-naumann`, `clift-gauvin` or `morrison`.
    pub law: DragLawName,
    /// Fluid volume fraction ε for `dallavalle`, in (0, 1]. Default 1 (isolated sphere).
    #[serde(default = "one")]
    pub voidage: f64,
}

fn one() -> f64 {
    1.0
}

/// A fluid's rheology with its parameters: what a validated `[fluid]` table holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RheologyModel {
    /// Newtonian, shear stress τ = η γ̇.
    Newtonian {
        /// Dynamic viscosity η, Pa s.
        viscosity_pa_s: f64,
    },
    /// Bingham plastic, τ = τ_y + η_B γ̇ above the yield stress.
    Bingham {
        /// Plastic viscosity η_B, Pa s.
        plastic_viscosity_pa_s: f64,
        /// Yield stress τ_y, Pa.
        yield_stress_pa: f64,
    },
}

impl Fluid {
    /// The rheology with its parameters, or `None` when one the rheology needs is missing
    /// (never for a validated scenario, whose rheology is [`crate::scenario::Parsed::rheology`]).
    pub fn model(&self) -> Option<RheologyModel> {
        Some(match self.rheology {
            Rheology::Newtonian => RheologyModel::Newtonian {
                viscosity_pa_s: self.viscosity_pa_s?,
            },
            Rheology::Bingham => RheologyModel::Bingham {
                plastic_viscosity_pa_s: self.plastic_viscosity_pa_s?,
                yield_stress_pa: self.yield_stress_pa?,
            },
        })
    }

    /// Density, and the viscosities the rheology needs (and no other): the rheology with its
    /// parameters.
    pub(crate) fn check(&self, c: &Check) -> Result<RheologyModel, ScenarioError> {
        c.range(
            "fluid.density_kg_m3",
            self.density_kg_m3,
            oc(0.0, 25_000.0, "kg/m³"),
        )?;
        let present = |key: &str, x: Option<f64>, what: &str| {
            x.ok_or_else(|| c.err(key, format!("missing: {what}")))
        };
        let only = |key: &str, x: Option<f64>, msg: &str| match x {
            Some(_) => Err(c.err(key, msg)),
            None => Ok(()),
        };
        match self.rheology {
            Rheology::Newtonian => {
                let mu = present(
                    "fluid.viscosity_pa_s",
                    self.viscosity_pa_s,
                    "a newtonian fluid needs its viscosity, 0 < viscosity_pa_s ≤ 1e6 Pa s",
                )?;
                c.range("fluid.viscosity_pa_s", mu, oc(0.0, 1e6, "Pa s"))?;
                let msg = "only allowed with rheology = \"bingham\"";
                only(
                    "fluid.plastic_viscosity_pa_s",
                    self.plastic_viscosity_pa_s,
                    msg,
                )?;
                only("fluid.yield_stress_pa", self.yield_stress_pa, msg)?;
                Ok(RheologyModel::Newtonian { viscosity_pa_s: mu })
            }
            Rheology::Bingham => {
                let eb = present(
                    "fluid.plastic_viscosity_pa_s",
                    self.plastic_viscosity_pa_s,
                    "a bingham fluid needs 0 < plastic_viscosity_pa_s ≤ 1e6 Pa s",
                )?;
                c.range("fluid.plastic_viscosity_pa_s", eb, oc(0.0, 1e6, "Pa s"))?;
                let ty = present(
                    "fluid.yield_stress_pa",
                    self.yield_stress_pa,
                    "a bingham fluid needs 0 ≤ yield_stress_pa ≤ 1e6 Pa",
                )?;
                c.range("fluid.yield_stress_pa", ty, cc(0.0, 1e6, "Pa"))?;
                only(
                    "fluid.viscosity_pa_s",
                    self.viscosity_pa_s,
                    "only allowed with rheology = \"newtonian\"; a bingham fluid uses plastic_viscosity_pa_s",
                )?;
                Ok(RheologyModel::Bingham {
                    plastic_viscosity_pa_s: eb,
                    yield_stress_pa: ty,
                })
            }
        }
    }
}

impl RheologyModel {
    /// The viscosity every drag law and every kind takes, Pa s: η of a Newtonian fluid, the
    /// plastic viscosity η_B of a Bingham fluid.
    pub fn drag_viscosity_pa_s(&self) -> f64 {
        match *self {
            RheologyModel::Newtonian { viscosity_pa_s } => viscosity_pa_s,
            RheologyModel::Bingham {
                plastic_viscosity_pa_s,
                ..
            } => plastic_viscosity_pa_s,
        }
    }

    /// The yield stress τ_y, Pa: 0 for a Newtonian fluid.
    pub fn yield_stress_pa(&self) -> f64 {
        match *self {
            RheologyModel::Newtonian { .. } => 0.0,
            RheologyModel::Bingham {
                yield_stress_pa, ..
            } => yield_stress_pa,
        }
    }
}

impl Drag {
    /// Voidage in (0, 1]; `bingham-fedem` exactly for a Bingham fluid (unless `ideal-stokes`).
    pub(crate) fn check(
        &self,
        c: &Check,
        fluid: &Fluid,
        physics: Physics,
    ) -> Result<(), ScenarioError> {
        c.range("drag.voidage", self.voidage, oc(0.0, 1.0, ""))?;
        let bingham = fluid.rheology == Rheology::Bingham;
        if self.law == DragLawName::BinghamFedem && !bingham {
            return Err(c.err("drag.law", "`bingham-fedem` needs fluid.rheology = \"bingham\"; allowed for a newtonian fluid: `stokes`, `dallavalle`"));
        }
        if self.law != DragLawName::BinghamFedem && bingham && physics == Physics::Full {
            return Err(c.err(
                "drag.law",
                "a bingham fluid needs `bingham-fedem` (or physics = \"ideal-stokes\")",
            ));
        }
        Ok(())
    }
}
