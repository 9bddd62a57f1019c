//! Moved to [`crate::scenes::free_settling::output`]; re-exported here until the callers move.

pub use crate::scenes::free_settling::output::{
    write_drop_chart as write_chart, write_drop_summary as write_summary, DROP_HEADER as HEADER,
};
