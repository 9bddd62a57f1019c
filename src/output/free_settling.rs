//! Moved to [`crate::scenes::free_settling::output`]; re-exported here until the callers move.

pub use crate::scenes::free_settling::output::{
    metrics, rel_error, rel_error_vs_force_balance, summary_row, write_chart, write_metrics,
    write_probes, write_summary, write_timeseries, SUMMARY_HEADER,
};
