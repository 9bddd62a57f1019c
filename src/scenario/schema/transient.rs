//! Transient forces: `[transient]` (kinds `free_settling` and `drop`; added mass alone in the
//! Rapier scenes `restitution_drop` and `funnel_pour`). Every key defaults to off, so a scenario
//! without the table keeps the quasi-steady forces of f-EDEM and seed 000.

use super::{EngineChoice, Kind, Physics, Rheology, Scenario};
use crate::dynamics::Integrator;
use crate::error::BadInput;
use crate::scenario::check::{cc, Check};
use serde::{Deserialize, Serialize};

/// The transient forces on a sphere.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Transient {
    /// Added mass C_m m_f on the sphere's acceleration. Default false.
    #[serde(default)]
    pub added_mass: bool,
    /// C_m, the added-mass coefficient (½ for a sphere in an unbounded fluid), in [0, 2].
    /// Default 0.5.
    #[serde(default = "half")]
    pub added_mass_coefficient: f64,
    /// The history force. Default `off`.
    #[serde(default)]
    pub history: History,
    /// The wall correction of the drag. Default `off`.
    #[serde(default)]
    pub wall: Wall,
    /// The Reynolds number of Mei & Adrian's kernel (`history = "mei-adrian"` only). Default
    /// `terminal`.
    #[serde(default)]
    pub history_reynolds: HistoryReynolds,
    /// The side walls' confinement factor on the drag (a cylindrical `[container]` with
    /// `diameter_m`, kind `free_settling`). Default `off`.
    #[serde(default)]
    pub confinement: Confinement,
}

/// Which confinement (side-wall) factor multiplies the drag.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Confinement {
    /// None: the side walls are not modelled.
    #[default]
    Off,
    /// Haberman & Sayre (1958): a sphere on the axis of a circular cylinder in creeping flow,
    /// d/D ≤ 0.8 ([`crate::fluid::transient::wall::haberman_sayre_factor`]).
    HabermanSayre,
}

/// Which Reynolds number Mei & Adrian's kernel takes.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum HistoryReynolds {
    /// Fixed at the terminal Re of the quasi-steady drag (unbounded fluid): one fit at release.
    #[default]
    Terminal,
    /// The body's current Re = |v| d/ν: the weights follow it (fits on a grid of Re, 8 per
    /// decade from 0.01, interpolated), the rates and the history states are kept.
    Current,
}

fn half() -> f64 {
    0.5
}

impl Default for Transient {
    fn default() -> Self {
        Self {
            added_mass: false,
            added_mass_coefficient: 0.5,
            history: History::Off,
            wall: Wall::Off,
            history_reynolds: HistoryReynolds::Terminal,
            confinement: Confinement::Off,
        }
    }
}

/// Which history force.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum History {
    /// None (quasi-steady).
    #[default]
    Off,
    /// Basset–Boussinesq, kernel t^{−1/2} (Maxey & Riley 1983), as a sum of exponentials.
    Basset,
    /// The finite-Reynolds kernel of Mei & Adrian (1992): Basset's at short times, decaying as
    /// t^{−2} beyond t_c ∝ (f_H/Re)² d²/ν; fitted by a sum of exponentials at the sphere's
    /// terminal Reynolds number (quasi-steady drag, unbounded fluid).
    MeiAdrian,
}

/// Which wall correction.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Wall {
    /// None.
    #[default]
    Off,
    /// Brenner (1961): the drag of a sphere approaching the container bottom.
    Brenner,
}

impl Transient {
    /// Whether any transient force is on.
    pub fn any(&self) -> bool {
        self.added_mass
            || self.history != History::Off
            || self.wall != Wall::Off
            || self.confinement != Confinement::Off
    }

    /// C_m when the added mass is on, else 0.
    pub fn added_mass_coefficient_on(&self) -> f64 {
        if self.added_mass {
            self.added_mass_coefficient
        } else {
            0.0
        }
    }

    /// `added_mass_coefficient` in [0, 2]; in the Rapier scenes (`restitution_drop`,
    /// `funnel_pour`) the added mass only; the history force only in a Newtonian fluid, for kind
    /// `free_settling`, on the free engine, with the exponential integrator; the wall only with a
    /// `[container]`, for kind `free_settling`.
    pub(crate) fn check(&self, c: &Check, s: &Scenario) -> Result<(), BadInput> {
        c.range(
            "transient.added_mass_coefficient",
            self.added_mass_coefficient,
            cc(0.0, 2.0, ""),
        )?;
        let rapier_scene = matches!(s.kind, Kind::RestitutionDrop | Kind::FunnelPour);
        if rapier_scene && self.history != History::Off {
            return Err(c.err("transient.history", format!("the history force is not implemented in the Rapier scenes (kind = \"{}\"): use history = \"off\" (allowed there: added_mass, added_mass_coefficient)", s.kind.name())));
        }
        if self.any() && !rapier_scene && s.engine == EngineChoice::Rapier {
            return Err(c.err(
                "transient",
                "the transient forces run on the free engine only: use engine = \"auto\" or \"free\"",
            ));
        }
        if self.history != History::Off {
            if s.fluid.rheology == Rheology::Bingham && s.physics == Physics::Full {
                return Err(c.err("transient.history", "no history force is established for a yield-stress (Bingham) fluid: use history = \"off\" there (added mass applies)"));
            }
            if s.kind != Kind::FreeSettling {
                return Err(c.err("transient.history", format!("the history force is implemented for kind = \"free_settling\" only, not \"{}\": use history = \"off\"", s.kind.name())));
            }
            if s.time.integrator != Integrator::Exponential {
                return Err(c.err("transient.history", "the history force is integrated by the exponential scheme only: set time.integrator = \"exponential\""));
            }
        }
        if self.history_reynolds != HistoryReynolds::Terminal && self.history != History::MeiAdrian
        {
            return Err(c.err(
                "transient.history_reynolds",
                "only Mei & Adrian's kernel depends on the Reynolds number: set history = \"mei-adrian\" or remove history_reynolds",
            ));
        }
        if self.wall != Wall::Off {
            if s.kind != Kind::FreeSettling {
                return Err(c.err("transient.wall", format!("the wall correction is implemented for kind = \"free_settling\" only, not \"{}\"", s.kind.name())));
            }
            if s.container.is_none() {
                return Err(c.err(
                    "transient.wall",
                    "the wall correction needs a [container] (its bottom is the wall)",
                ));
            }
        }
        if self.confinement != Confinement::Off {
            self.check_confinement(c, s)?;
        }
        Ok(())
    }

    /// Haberman & Sayre's factor: kind `free_settling`, a cylindrical container
    /// (`container.diameter_m`). Each sphere's d/D is checked with the sphere
    /// ([`Transient::check_confined_sphere`]), so that spheres read from CSV are too.
    fn check_confinement(&self, c: &Check, s: &Scenario) -> Result<(), BadInput> {
        const KEY: &str = "transient.confinement";
        if s.kind != Kind::FreeSettling {
            return Err(c.err(KEY, format!("the confinement factor is implemented for kind = \"free_settling\" only, not \"{}\"", s.kind.name())));
        }
        if s.container.as_ref().and_then(|k| k.diameter_m).is_none() {
            return Err(c.err(KEY, "Haberman & Sayre's factor is for a sphere on the axis of a circular cylinder: give container.diameter_m (no factor is implemented for a square section)"));
        }
        Ok(())
    }

    /// With the confinement factor on, the sphere `key` of diameter `d_m` has d/D in Haberman &
    /// Sayre's range (0, [`crate::fluid::transient::wall::HABERMAN_SAYRE_MAX_RATIO`]].
    pub(crate) fn check_confined_sphere(
        &self,
        c: &Check,
        key: &str,
        d_m: f64,
        s: &Scenario,
    ) -> Result<(), BadInput> {
        use crate::fluid::transient::wall::HABERMAN_SAYRE_MAX_RATIO as MAX;
        let big_d = s.container.as_ref().and_then(|k| k.diameter_m);
        let (Confinement::HabermanSayre, Some(big_d)) = (self.confinement, big_d) else {
            return Ok(());
        };
        let ratio = d_m / big_d;
        if ratio > 0.0 && ratio <= MAX {
            return Ok(());
        }
        Err(c.err(
            &format!("{key}.diameter_m"),
            format!("d/D = {ratio:.4} with container.diameter_m = {big_d} m is outside Haberman & Sayre's range (0, {MAX}] (transient.confinement)"),
        ))
    }
}
