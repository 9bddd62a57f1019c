//! Transient forces: `[transient]` (kinds `free_settling` and `drop`; added mass alone in the
//! Rapier scenes `restitution_drop` and `funnel_pour`). Every key defaults to off, so a scenario
//! without the table keeps the quasi-steady forces of f-EDEM and seed 000.

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
}
