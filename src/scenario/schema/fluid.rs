//! The fluid and the drag law: `[fluid]` and `[drag]`.

use super::base::Physics;
use crate::error::BadInput;
use crate::scenario::check::{cc, oc, Check};
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
    /// Herschel–Bulkley τ = τ_y + K γ̇ⁿ: needs `yield_stress_pa`, `consistency_pa_sn` and
    /// `flow_index` (drag law `wilson-2003` only).
    #[serde(rename = "herschel-bulkley")]
    HerschelBulkley,
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
    /// Yield stress τ_y, Pa (Bingham and Herschel–Bulkley; ≥ 0).
    #[serde(default)]
    pub yield_stress_pa: Option<f64>,
    /// Consistency K, Pa sⁿ (Herschel–Bulkley only; > 0).
    #[serde(default)]
    pub consistency_pa_sn: Option<f64>,
    /// Flow index n, dimensionless (Herschel–Bulkley only; 0.1 ≤ n ≤ 2).
    #[serde(default)]
    pub flow_index: Option<f64>,
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
    /// Static resistance plus Newtonian drag at ρ v d/η_B, Bingham fluids only
    /// ([`crate::fluid::bingham::additive`]).
    BinghamAdditive,
    /// Ansley & Smith (1967), Bingham fluids only ([`crate::fluid::bingham::ansley_smith`]).
    AnsleySmith,
    /// Wilson et al. (2003) secant viscosity at 0.3 of the mean surface stress, Bingham and
    /// Herschel–Bulkley fluids
    /// ([`crate::fluid::bingham::wilson`]).
    #[serde(rename = "wilson-2003")]
    Wilson2003,
}

impl DragLawName {
    /// The `drag.law` value of the name (`bingham-fedem`, …).
    pub fn key(self) -> &'static str {
        match self {
            Self::Stokes => "stokes",
            Self::Dallavalle => "dallavalle",
            Self::BinghamFedem => "bingham-fedem",
            Self::SchillerNaumann => "schiller-naumann",
            Self::CliftGauvin => "clift-gauvin",
            Self::Morrison => "morrison",
            Self::BinghamAdditive => "bingham-additive",
            Self::AnsleySmith => "ansley-smith",
            Self::Wilson2003 => "wilson-2003",
        }
    }

    /// The yield-stress law this name selects besides f-EDEM's, if any.
    pub fn plastic(self) -> Option<crate::fluid::bingham::PlasticLaw> {
        use crate::fluid::bingham::PlasticLaw;
        match self {
            Self::BinghamAdditive => Some(PlasticLaw::Additive),
            Self::AnsleySmith => Some(PlasticLaw::AnsleySmith),
            Self::Wilson2003 => Some(PlasticLaw::Wilson),
            _ => None,
        }
    }

    /// True for the laws of a yield-stress fluid (`bingham-fedem` and the three above).
    pub fn is_yield_stress(self) -> bool {
        self == Self::BinghamFedem || self.plastic().is_some()
    }
}

/// When a sphere in a yield-stress fluid stays at rest.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum StaticCriterion {
    /// The drag law's own static resistance F(0⁺).
    #[default]
    Law,
    /// Also Beris et al. (1985): at rest while τ_y/(Δρ g d) ≥ 0.143/3
    /// ([`crate::fluid::bingham::beris`]), when that holds more than the law's own.
    Beris,
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
    /// `law` (default) or `beris`: the static criterion of the yield-stress laws.
    #[serde(default)]
    pub static_criterion: StaticCriterion,
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
    /// Herschel–Bulkley, τ = τ_y + K γ̇ⁿ above the yield stress.
    HerschelBulkley {
        /// Yield stress τ_y, Pa.
        yield_stress_pa: f64,
        /// Consistency K, Pa sⁿ.
        consistency_pa_sn: f64,
        /// Flow index n.
        flow_index: f64,
    },
}

impl Fluid {
    #[cfg_attr(not(test), allow(dead_code))] // read by the unit tests
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
            Rheology::HerschelBulkley => RheologyModel::HerschelBulkley {
                yield_stress_pa: self.yield_stress_pa?,
                consistency_pa_sn: self.consistency_pa_sn?,
                flow_index: self.flow_index?,
            },
        })
    }

    /// Density, and the viscosities the rheology needs (and no other): the rheology with its
    /// parameters.
    pub(crate) fn check(&self, c: &Check) -> Result<RheologyModel, BadInput> {
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
                self.no_herschel_bulkley(c)?;
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
                self.no_herschel_bulkley(c)?;
                Ok(RheologyModel::Bingham {
                    plastic_viscosity_pa_s: eb,
                    yield_stress_pa: ty,
                })
            }
            Rheology::HerschelBulkley => self.check_herschel_bulkley(c),
        }
    }

    /// `consistency_pa_sn` and `flow_index` belong to a Herschel–Bulkley fluid only.
    fn no_herschel_bulkley(&self, c: &Check) -> Result<(), BadInput> {
        let msg = "only allowed with rheology = \"herschel-bulkley\"";
        for (key, x) in [
            ("fluid.consistency_pa_sn", self.consistency_pa_sn),
            ("fluid.flow_index", self.flow_index),
        ] {
            if x.is_some() {
                return Err(c.err(key, msg));
            }
        }
        Ok(())
    }

    /// τ_y, K and n of a Herschel–Bulkley fluid, and no Newtonian or Bingham viscosity.
    fn check_herschel_bulkley(&self, c: &Check) -> Result<RheologyModel, BadInput> {
        let need = |key: &str, x: Option<f64>, what: &str| {
            x.ok_or_else(|| {
                c.err(
                    key,
                    format!("missing: a herschel-bulkley fluid needs {what}"),
                )
            })
        };
        let ty = need(
            "fluid.yield_stress_pa",
            self.yield_stress_pa,
            "0 ≤ yield_stress_pa ≤ 1e6 Pa",
        )?;
        c.range("fluid.yield_stress_pa", ty, cc(0.0, 1e6, "Pa"))?;
        let k = need(
            "fluid.consistency_pa_sn",
            self.consistency_pa_sn,
            "0 < consistency_pa_sn ≤ 1e6 Pa sⁿ",
        )?;
        c.range("fluid.consistency_pa_sn", k, oc(0.0, 1e6, "Pa sⁿ"))?;
        let n = need("fluid.flow_index", self.flow_index, "0.1 ≤ flow_index ≤ 2")?;
        c.range("fluid.flow_index", n, cc(0.1, 2.0, ""))?;
        let msg = "only allowed with rheology = \"newtonian\" or \"bingham\"; a herschel-bulkley fluid uses consistency_pa_sn and flow_index";
        for (key, x) in [
            ("fluid.viscosity_pa_s", self.viscosity_pa_s),
            ("fluid.plastic_viscosity_pa_s", self.plastic_viscosity_pa_s),
        ] {
            if x.is_some() {
                return Err(c.err(key, msg));
            }
        }
        Ok(RheologyModel::HerschelBulkley {
            yield_stress_pa: ty,
            consistency_pa_sn: k,
            flow_index: n,
        })
    }
}

impl RheologyModel {
    /// The viscosity every drag law and every kind takes, Pa s: η of a Newtonian fluid, the
    /// plastic viscosity η_B of a Bingham fluid, the consistency K of a Herschel–Bulkley fluid
    /// (its stress above τ_y at γ̇ = 1/s; a viscosity only for n = 1).
    pub fn drag_viscosity_pa_s(&self) -> f64 {
        match *self {
            RheologyModel::Newtonian { viscosity_pa_s } => viscosity_pa_s,
            RheologyModel::Bingham {
                plastic_viscosity_pa_s,
                ..
            } => plastic_viscosity_pa_s,
            RheologyModel::HerschelBulkley {
                consistency_pa_sn, ..
            } => consistency_pa_sn,
        }
    }

    /// The rheogram τ = τ_y + K γ̇ⁿ of the fluid: Bingham n = 1, K = η_B; Herschel–Bulkley as
    /// given; a Newtonian fluid is its limit τ_y = 0, K = η, n = 1.
    pub fn rheogram(&self) -> crate::fluid::bingham::YieldFluid {
        use crate::fluid::bingham::YieldFluid;
        match *self {
            RheologyModel::Newtonian { viscosity_pa_s } => YieldFluid {
                yield_stress_pa: 0.0,
                consistency_pa_sn: viscosity_pa_s,
                flow_index: 1.0,
            },
            RheologyModel::Bingham {
                plastic_viscosity_pa_s,
                yield_stress_pa,
            } => YieldFluid::bingham(yield_stress_pa, plastic_viscosity_pa_s),
            RheologyModel::HerschelBulkley {
                yield_stress_pa,
                consistency_pa_sn,
                flow_index,
            } => YieldFluid {
                yield_stress_pa,
                consistency_pa_sn,
                flow_index,
            },
        }
    }

    /// The yield stress τ_y, Pa: 0 for a Newtonian fluid.
    pub fn yield_stress_pa(&self) -> f64 {
        match *self {
            RheologyModel::Newtonian { .. } => 0.0,
            RheologyModel::Bingham {
                yield_stress_pa, ..
            }
            | RheologyModel::HerschelBulkley {
                yield_stress_pa, ..
            } => yield_stress_pa,
        }
    }
}

impl Drag {
    /// The drag law of this table in a fluid of rheology `rheology`, after the `physics` switch
    /// (`ideal-stokes` turns every law into Stokes drag with the fluid's viscosity, or its
    /// plastic viscosity for a Bingham fluid). Total: a yield-stress law takes the fluid's
    /// rheogram ([`RheologyModel::rheogram`]; validation allows it only in a yield-stress fluid).
    pub fn law(&self, rheology: RheologyModel, physics: Physics) -> crate::fluid::DragLaw {
        use crate::fluid::bingham::PlasticLaw;
        use crate::fluid::newtonian::CdCorrelation;
        use crate::fluid::DragLaw;
        let mu = rheology.drag_viscosity_pa_s();
        if physics == Physics::IdealStokes {
            return DragLaw::Stokes { viscosity_pa_s: mu };
        }
        let correlation = |cd| DragLaw::Correlation {
            viscosity_pa_s: mu,
            cd,
        };
        let plastic = |law| DragLaw::Plastic {
            law,
            fluid: rheology.rheogram(),
            beris: self.static_criterion == StaticCriterion::Beris,
        };
        match self.law {
            DragLawName::Stokes => DragLaw::Stokes { viscosity_pa_s: mu },
            DragLawName::Dallavalle => DragLaw::Dallavalle {
                viscosity_pa_s: mu,
                voidage: self.voidage,
            },
            DragLawName::SchillerNaumann => correlation(CdCorrelation::SchillerNaumann),
            DragLawName::CliftGauvin => correlation(CdCorrelation::CliftGauvin),
            DragLawName::Morrison => correlation(CdCorrelation::Morrison),
            DragLawName::BinghamFedem => DragLaw::Bingham {
                yield_stress_pa: rheology.yield_stress_pa(),
                plastic_viscosity_pa_s: mu,
            },
            DragLawName::BinghamAdditive => plastic(PlasticLaw::Additive),
            DragLawName::AnsleySmith => plastic(PlasticLaw::AnsleySmith),
            DragLawName::Wilson2003 => plastic(PlasticLaw::Wilson),
        }
    }

    /// Voidage in (0, 1]; a yield-stress law exactly for a yield-stress fluid (unless
    /// `ideal-stokes`), and a law that takes the fluid's rheogram.
    pub(crate) fn check(&self, c: &Check, fluid: &Fluid, physics: Physics) -> Result<(), BadInput> {
        c.range("drag.voidage", self.voidage, oc(0.0, 1.0, ""))?;
        const YIELD_LAWS: &str =
            "`bingham-fedem`, `bingham-additive`, `ansley-smith`, `wilson-2003`";
        match fluid.rheology {
            Rheology::Newtonian if self.law.is_yield_stress() => Err(c.err(
                "drag.law",
                format!("{} needs a yield-stress fluid (fluid.rheology = \"bingham\" or \"herschel-bulkley\"); allowed for a newtonian fluid: `stokes`, `dallavalle`, `schiller-naumann`, `clift-gauvin`, `morrison`", law_key(self.law)),
            )),
            Rheology::Bingham if !self.law.is_yield_stress() && physics == Physics::Full => Err(c.err(
                "drag.law",
                format!("a bingham fluid needs a yield-stress law: {YIELD_LAWS} (or physics = \"ideal-stokes\")"),
            )),
            Rheology::HerschelBulkley if physics == Physics::IdealStokes => Err(c.err(
                "physics",
                "a herschel-bulkley fluid has no single viscosity for `ideal-stokes`; use physics = \"full\" with drag.law = \"wilson-2003\"",
            )),
            Rheology::HerschelBulkley
                if !self.law.plastic().is_some_and(|p| p.supports_herschel_bulkley()) =>
            {
                Err(c.err(
                    "drag.law",
                    format!("{} does not take a herschel-bulkley fluid; the law that does: `wilson-2003` (the others need a bingham fluid, flow index 1)", law_key(self.law)),
                ))
            }
            _ => Ok(()),
        }
    }
}

/// The `drag.law` spelling of a law name, in backquotes.
fn law_key(law: DragLawName) -> String {
    format!("`{}`", law.key())
}
