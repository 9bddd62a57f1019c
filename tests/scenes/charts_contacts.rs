//! The restitution drop's `rebound_height.svg` and the tilt test's `tilt_displacement.svg` in the
//! shared chart look: title, axis labels with units, readable ticks, legend outside the data.

use super::charts_free_settling::assert_legend_outside;
use crate::common::chart::assert_readable_chart;
use crate::common::{settle, tmp};

#[test]
fn rebound_and_tilt_charts_are_readable() {
    let out = tmp();
    let o = settle()
        .args(["run", "-q", "--out"])
        .arg(out.path())
        .args([
            "scenarios/restitution_drop.toml",
            "scenarios/tilt_friction.toml",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rebound = out.path().join("restitution_drop/rebound_height.svg");
    let texts = assert_readable_chart(
        &rebound,
        "rebound height against drop height",
        &["drop height H_f (mm)", "rebound height H_r (mm)"],
    );
    assert!(texts
        .iter()
        .any(|t| t.contains("measured (f-EDEM Table A2)")));
    assert_legend_outside(&rebound, &["ideal e(v)", "simulated", "measured"]);
    let tilt = out.path().join("tilt_friction/tilt_displacement.svg");
    let texts = assert_readable_chart(
        &tilt,
        "tilt_friction",
        &["tilt angle θ (°)", "displacement down the slope (mm)"],
    );
    // The threshold printed to 4 significant digits: atan(0.341) = 18.83°.
    assert!(
        texts.iter().any(|t| t.contains("atan(μ) = 18.83°")),
        "{texts:?}"
    );
    assert_legend_outside(&tilt, &["sticks", "slides", "atan(μ)"]);
}
