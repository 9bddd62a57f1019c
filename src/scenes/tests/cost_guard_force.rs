//! The cost guard's `--force` (moved from `tests/app/checkpoint.rs`, whose
//! `cost_guard_refuses_runs_beyond_the_limits` checks the refusals through `settle run`).

use crate::scenes::cost::check;
use crate::scenes::tests::prepare;
use std::path::Path;

/// --force lifts the time limit (checked without running it): a 68-ball pour of 15 repeats at
/// dt = 1e-8 s (1e8 steps × 1020 bodies ≈ 28 h) is refused for its time without it, and
/// estimated at more than a day with it.
#[test]
fn force_lifts_the_time_limit_of_the_cost_guard() {
    let p = prepare(
        Path::new("scenarios/paste_68_balls.toml"),
        Some(1e-8),
        &["repeats.count=15".into()],
    )
    .unwrap();
    assert!(check(&p, false).is_err());
    let c = check(&p, true).unwrap();
    assert!(c.wall_s > 24.0 * 3600.0, "{c:?}");
}
