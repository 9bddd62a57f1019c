//! The index of a body in a world, shared by the worlds and their fault reports.

use serde::{Deserialize, Serialize};
use std::fmt;

/// Index of a body in a world, in the order of `add_sphere` calls (0, 1, …).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct BodyId(pub usize);

impl fmt::Display for BodyId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "body {}", self.0)
    }
}
