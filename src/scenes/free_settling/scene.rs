//! What a free-settling run reads ([`Scene`]): the typed common part of its scenario and the
//! spec of its kind, from a prepared scenario or (for the functions that take a scenario as
//! read) from the raw one.

use crate::scenario::{Common, FreeSettlingSpec, RheologyModel, Scenario};

/// What a free-settling run reads: the typed common part and the kind's spec.
#[derive(Clone, Copy, Debug)]
pub struct Scene<'a> {
    /// What every kind reads.
    pub common: &'a Common,
    /// Container, release and measurements.
    pub spec: &'a FreeSettlingSpec,
}

/// The typed parts of a free-settling or drop scenario `s` whose fluid has rheology
/// `rheology`, for the functions that take a scenario as read ([`super::run`] and the others):
/// the same values as [`crate::scenario::Parsed`] holds.
pub(super) fn typed(s: &Scenario, rheology: RheologyModel) -> (Common, FreeSettlingSpec) {
    (Common::of(s, rheology), FreeSettlingSpec::of(s))
}
