//! What a free-settling run reads ([`Scene`]): the typed common part of its prepared scenario
//! and the spec of its kind.

use crate::scenario::{Common, FreeSettlingSpec, SceneSpec};
use crate::scenes::Prepared;

/// What a free-settling run reads: the typed common part and the kind's spec.
#[derive(Clone, Copy, Debug)]
pub struct Scene<'a> {
    /// What every kind reads.
    pub common: &'a Common,
    /// Container, release and measurements.
    pub spec: &'a FreeSettlingSpec,
}

impl<'a> Scene<'a> {
    /// The scene of a prepared free-settling or drop scenario (None for another kind).
    pub fn of(p: &'a Prepared) -> Option<Self> {
        match &p.scene {
            SceneSpec::FreeSettling(spec) => Some(Self {
                common: &p.common,
                spec,
            }),
            _ => None,
        }
    }
}
