//! Unit tests of the tilt (moved from `tests/scenes/restitution_drop_and_tilt.rs`, f-EDEM
//! Appendix III): the threshold search follows the friction.

use crate::scenes::tests::prepare;
use crate::scenes::tilt_friction::{tilt_threshold, TiltSetup};
use std::path::Path;

/// The threshold follows `contacts.friction`: with μ = 0.5 it is atan(0.5) = 26.57° within 0.5°.
#[test]
fn tilt_threshold_follows_the_friction() {
    let p = prepare(
        Path::new("scenarios/tilt_friction.toml"),
        None,
        &["contacts.friction=0.5".into()],
    )
    .unwrap();
    let setup = TiltSetup::new(&p.common, p.scene.tilt_friction().unwrap());
    let search = tilt_threshold(&setup, &[20.0, 26.0, 27.0, 35.0], 0.1).unwrap();
    let (lo, hi) = search.bracket.expect("bracketed");
    let expected = 0.5f64.atan().to_degrees();
    assert!(hi - lo <= 0.1);
    assert!(
        (0.5 * (lo + hi) - expected).abs() < 0.5,
        "threshold {lo}–{hi}° vs {expected}°"
    );
}
