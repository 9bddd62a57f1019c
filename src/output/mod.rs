//! Kind-specific writers (moving into their scenes' `output.rs`); the infrastructure that was here
//! (staged folders, `write_atomic`, `num`, charts, metrics) is now [`crate::io`], re-exported here
//! until every caller uses the new path.

pub mod drop;
pub mod free_settling;
pub use crate::scenes::sedimentation::output::granulometry;

pub use crate::io::*;
