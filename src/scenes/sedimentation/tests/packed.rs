//! The passes of the packed suspension (full physics without contacts) against the same passes
//! over the state.

use super::prepare;
use crate::scenes::sedimentation::simulate::voidage_grid;
use crate::scenes::sedimentation::step::Stepper;
use crate::scenes::sedimentation::suspension::{fill_part_grains, Suspension};
use crate::scenes::sedimentation::{setup, State};
use std::path::Path;

/// The voidage fill of the packed suspension sums each part of [`fill_part_grains`] entries in
/// grain order, in parallel, then adds the parts in order. With more than one part that
/// reorders each cell's sum against the fill of the state in grain order, so the two agree to
/// rounding (within 1e-13 relative per cell, solid volume and voidage), not bit for bit; and
/// the sums must be the same bits whatever the number of threads (1, 2 and 3).
#[test]
fn packed_voidage_fill_agrees_with_grain_order_whatever_the_threads() {
    let ov: Vec<String> = [
        "physics=full",
        "sample.particles=200000",
        "sample.voidage_cell_m=0.02",
        "sample.snapshot_times_s=[]",
    ]
    .map(String::from)
    .to_vec();
    let p = prepare(Path::new("scenarios/sedimentation_sample2.toml"), None, &ov).unwrap();
    let su = setup(&p).unwrap();
    let mut st = State::initial(&su);
    let stepper = Stepper::new(&su);
    let mut grid = voidage_grid(&su, &stepper);
    assert!(grid.is_di_felice());
    let parts = st.len().div_ceil(fill_part_grains(grid.cell_count()));
    assert!(parts >= 3, "{parts} parts");
    let (mut sus, _) = Suspension::new(&mut st, &grid, &stepper, &su).unwrap();
    let mut serial = grid.clone();
    let volumes = serial.grain_volumes_m3(&su.grains);
    let all: Vec<usize> = (0..st.len()).collect();
    serial.fill(&st, &su.grains, &volumes, &all);
    let mut by_threads = Vec::new();
    for threads in [1, 2, 3] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| sus.fill(&mut grid));
        let bits = |xs: &[f64]| xs.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        by_threads.push((bits(grid.solid_m3()), bits(grid.voidages())));
    }
    assert!(by_threads.windows(2).all(|w| w[0] == w[1]));
    let filled = grid.solid_m3().iter().filter(|&&x| x > 0.0).count();
    assert!(filled > 50, "{filled} cells hold grains");
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs().max(1e-300);
    for (c, (a, b)) in grid.solid_m3().iter().zip(serial.solid_m3()).enumerate() {
        assert!(rel(*a, *b) < 1e-13, "cell {c}: solid {a} against {b}");
        let (e, f) = (grid.voidage(c), serial.voidage(c));
        assert!(rel(e, f) < 1e-13, "cell {c}: voidage {e} against {f}");
    }
}
