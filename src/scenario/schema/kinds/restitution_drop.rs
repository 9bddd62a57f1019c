//! Kind `restitution_drop`: the kind's spec. The table `[restitution_drop]` is in
//! `tables/restitution_drop.rs`.

use super::super::rules::contact_scene_3d;
use super::super::{Contacts, RestitutionDropSpec, Scenario, SphereSpec};
use crate::error::BadInput;
use crate::scenario::check::Check;

/// A ball dropped on a plate in air (kind `restitution_drop`).
#[derive(Clone, Debug, PartialEq)]
pub struct RestitutionSpec {
    /// The `[restitution_drop]` table: heights, measurements, tolerance.
    pub drop: RestitutionDropSpec,
    /// The ball: the scenario's one `[[spheres]]` entry.
    pub ball: SphereSpec,
    /// The contact properties (`[contacts]`).
    pub contacts: Contacts,
}

/// The spec of a `restitution_drop` scenario: `[restitution_drop]`, `[contacts]` in 3D, one
/// ball.
pub(crate) fn spec(c: &Check, s: &Scenario) -> Result<RestitutionSpec, BadInput> {
    let rd = s.restitution_drop.as_ref().ok_or_else(|| {
        c.err(
            "restitution_drop",
            "missing: kind = \"restitution_drop\" needs a [restitution_drop] table with drop_heights_m",
        )
    })?;
    let contacts = contact_scene_3d(c, s)?;
    let ball = match (s.spheres.as_slice(), &s.spheres_csv) {
        ([ball], None) => ball,
        _ => return Err(c.err(
            "spheres",
            "kind = \"restitution_drop\" drops one ball: give exactly one [[spheres]] table (no [spheres_csv])",
        )),
    };
    rd.check(c)?;
    Ok(RestitutionSpec {
        drop: rd.clone(),
        ball: ball.clone(),
        contacts,
    })
}
