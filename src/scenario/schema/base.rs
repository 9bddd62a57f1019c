//! The small types every table reads: the kind, the dimension, the physics switch and the
//! engine choice, and the range of times within a run. A leaf: it reads no other table.

use crate::scenario::check::{oc, Range};
use serde::{Deserialize, Serialize};

/// Kinds of scene.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// Independent spheres settling from rest in a still fluid, no contacts between them
    /// (f-EDEM §3 single sphere, §4.1 Valentik–Whitmore tanks). Each sphere runs alone.
    FreeSettling,
    /// Spheres dropped from `release.fall_heights_m` above the free surface through air into the
    /// fluid, each alone, until they stop (f-EDEM §4.2 steel balls in paste backfill).
    Drop,
    /// A ball dropped on a plate in air; rebound heights against measurements (f-EDEM App. II).
    RestitutionDrop,
    /// A block on a plate tilted to a series of angles: sticks or slides (f-EDEM App. III).
    TiltFriction,
    /// Many balls released from a funnel into the fluid-filled cylinder, with contacts (f-EDEM
    /// §4.2, 68 steel balls into paste backfill), repeated with different seeds.
    FunnelPour,
    /// A 2D projection of the ASTM D422 sedimentation cylinder: a soil sample of representative
    /// grains settling from a homogeneous suspension (seed 000 §4–5).
    Sedimentation,
}

/// Physics switch.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Physics {
    /// Everything the scenario asks for.
    #[default]
    Full,
    /// Stokes drag only, no yield stress, no voidage, no contacts.
    IdealStokes,
}

/// Engine choice.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum EngineChoice {
    /// `free` where the scene has no contacts, `rapier` otherwise.
    #[default]
    Auto,
    /// Our own integrator only (no contact pipeline): exact free flight, fastest.
    Free,
    /// Every body in a Rapier world, fluid forces through the force hook.
    Rapier,
}

/// The engine a scenario runs on, after `engine = "auto"` is resolved ([`crate::scenario::Scenario::engine`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Engine {
    /// Our own integrator only: exact free flight, no contacts.
    Free,
    /// Every body in a Rapier world, fluid forces through the force hook.
    Rapier,
}

impl Engine {
    /// The name written in `run.toml` and shown to the user: `free` or `rapier`.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Free => "free",
            Engine::Rapier => "rapier",
        }
    }
}

impl std::fmt::Display for Engine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The dimension of a scene. In TOML it is the number `2` or `3` (`dimension = 2`); any other
/// number is refused when parsed as a `Dim`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(try_from = "i64", into = "u8")]
pub enum Dim {
    /// A 2D scene: gravity along −y.
    Two,
    /// A 3D scene: gravity along −z.
    Three,
}

/// A dimension other than 2 or 3 (the number read).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BadDim(pub i64);

impl std::fmt::Display for BadDim {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} is not allowed: 2 or 3", self.0)
    }
}

impl TryFrom<i64> for Dim {
    type Error = BadDim;
    fn try_from(n: i64) -> Result<Self, BadDim> {
        match n {
            2 => Ok(Dim::Two),
            3 => Ok(Dim::Three),
            _ => Err(BadDim(n)),
        }
    }
}

impl From<Dim> for u8 {
    fn from(d: Dim) -> u8 {
        match d {
            Dim::Two => 2,
            Dim::Three => 3,
        }
    }
}

/// `(0, end_s]` with the note used for times within a run.
pub(crate) fn within_run(end_s: f64) -> Range<'static> {
    oc(0.0, end_s, "s (within time.end_s)")
}
