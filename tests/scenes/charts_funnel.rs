//! The charts of a funnel pour read as issue 13 asks (f-EDEM Figs. 21–22): titles, axis labels
//! with units on both axes, tick labels of at most 6 significant digits, a labelled colour scale
//! of the presence maps, on a small pour (4 balls, 2 repeats, 0.5 s).

use crate::common::chart::assert_readable_chart;
use crate::common::tmp;

#[test]
fn the_z_distribution_and_presence_maps_have_units_on_both_axes() {
    let mut scenario = settle::load("scenarios/paste_68_balls.toml").expect("scenario");
    for kv in [
        "funnel.count=4",
        "funnel.fill_time_s=0.15",
        "funnel.count_time_s=0.4",
        "time.end_s=0.5",
        "time.dt_s=2e-5",
        "repeats.count=2",
        "repeats.seed=7",
    ] {
        let (key, value) = kv.split_once('=').unwrap();
        scenario = scenario.set(key, value).expect("override");
    }
    let dir = tmp();
    let out = scenario
        .run()
        .expect("runs")
        .write(dir.path())
        .expect("writes");
    let z = assert_readable_chart(
        &out.join("z_distribution.svg"),
        "ball centres in the paste",
        &[
            "ball centres in the bin, mean per repeat (balls)",
            "Z above the cylinder bottom (cm)",
        ],
    );
    assert!(z.iter().any(|t| t == "f-EDEM range 8.5–13.5 cm"));
    let texts = assert_readable_chart(
        &out.join("presence.svg"),
        "presence probability on horizontal planes",
        &[
            "x from the axis (mm)",
            "y from the axis (mm)",
            "presence probability (-)",
        ],
    );
    // One panel per plane of the scenario (13.5 … 8.5 cm), each named with its height.
    let panels = texts.iter().filter(|t| t.starts_with("plane Z = ")).count();
    assert_eq!(panels, 6, "{texts:?}");
    assert!(texts
        .iter()
        .any(|t| t == "plane Z = 13.5 cm above the bottom"));
    // Both axes of every panel are labelled.
    assert_eq!(
        texts
            .iter()
            .filter(|t| *t == "x from the axis (mm)")
            .count(),
        6
    );
    assert_eq!(
        texts
            .iter()
            .filter(|t| *t == "y from the axis (mm)")
            .count(),
        6
    );
}
