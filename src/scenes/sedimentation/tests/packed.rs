//! The passes of the packed suspension (full physics without contacts) against the same passes
//! over the state.

use super::prepare;
use crate::scenes::sedimentation::simulate::voidage_grid;
use crate::scenes::sedimentation::step::Stepper;
use crate::scenes::sedimentation::suspension::{fill_part_grains, Suspension};
use crate::scenes::sedimentation::{setup, State};
use std::path::Path;

/// The voidage fill of the packed suspension sums each part of [`fill_part_grains`] entries (in
/// kind order, one part per thread) in parallel, then adds the parts; the fill of the state sums the grains in grain
/// order. Both sum exactly, in the quanta of `SolidQuanta`, so they must give the same bits,
/// whatever the number of threads (1, 2 and 3).
#[test]
fn packed_voidage_fill_equals_grain_order_whatever_the_threads() {
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
    let parts = st
        .len()
        .div_ceil(fill_part_grains(grid.cell_count(), st.len(), 3));
    assert!(parts >= 3, "{parts} parts on 3 threads");
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
        // A fresh grid each time (a fill converts only the cells whose sum changed).
        let mut fresh = voidage_grid(&su, &stepper);
        pool.install(|| sus.fill(&mut fresh));
        grid = fresh;
        let bits = |xs: &[f64]| xs.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        by_threads.push((bits(grid.solid_m3()), bits(grid.voidages())));
    }
    assert!(by_threads.windows(2).all(|w| w[0] == w[1]));
    let filled = grid.solid_m3().iter().filter(|&&x| x > 0.0).count();
    assert!(filled > 50, "{filled} cells hold grains");
    for (c, (a, b)) in grid.solid_m3().iter().zip(serial.solid_m3()).enumerate() {
        assert_eq!(a.to_bits(), b.to_bits(), "cell {c}: solid {a} against {b}");
        let (e, f) = (grid.voidage(c), serial.voidage(c));
        assert_eq!(
            e.to_bits(),
            f.to_bits(),
            "cell {c}: voidage {e} against {f}"
        );
    }
}

/// A cell's solid volume is the exact sum of its grains' volumes, rounded once: one grain of
/// 10⁻¹² m³ and 10⁶ of 10⁻³⁰ m³ hold 1.000000000001·10⁻¹² m³ (what exact arithmetic gives: a
/// sum in f64, grain by grain, would stay at 10⁻¹² m³, each small volume below half an ulp),
/// the same in any order of the grains.
#[test]
fn a_cell_holds_the_exact_sum_of_its_grains_in_any_order() {
    use crate::sample::GrainKind;
    use crate::scenes::sedimentation::voidage::SolidQuanta;
    let kind = |volume_m3: f64| GrainKind {
        class: 0,
        // weight × π d³/6 = volume with d = 1 m.
        diameter_m: 1.0,
        weight: volume_m3 * 6.0 / std::f64::consts::PI,
    };
    let kinds = vec![kind(1e-12), kind(1e-30)];
    let (big, small) = (kinds[0].volume_m3(), kinds[1].volume_m3());
    let n_small = 1_000_000usize;
    // The large grain first: a sum in f64 then loses every small one.
    let mut order = vec![0u32];
    order.extend(std::iter::repeat_n(1u32, n_small));
    let q = SolidQuanta::for_kinds(&kinds, &order);
    let sum = |ks: &[u32]| {
        let total: i128 = ks.iter().map(|&k| q.of([big, small][k as usize])).sum();
        q.volume_m3(total)
    };
    let naive = order.iter().fold(0.0, |s, &k| s + [big, small][k as usize]);
    let first = sum(&order);
    order.rotate_left(1);
    let last = sum(&order);
    assert_eq!(first.to_bits(), last.to_bits());
    let exact = big + n_small as f64 * small;
    assert!((naive - big).abs() <= f64::EPSILON * big, "naive {naive:e}");
    assert!(
        (first - exact).abs() <= 2.0 * f64::EPSILON * exact,
        "{first:e} against {exact:e}"
    );
    assert!((first - 1.000000000001e-12).abs() < 1e-27, "{first:e}");
}

/// Sample 2 with full physics and 2 000 grains: its setup and step constants.
fn sample2_small() -> (crate::scenes::sedimentation::Setup, Stepper) {
    let ov: Vec<String> = ["physics=full", "sample.particles=2000"]
        .map(String::from)
        .to_vec();
    let p = prepare(Path::new("scenarios/sedimentation_sample2.toml"), None, &ov).unwrap();
    let su = setup(&p).unwrap();
    let stepper = Stepper::new(&su);
    (su, stepper)
}

/// A fill converts only the cells whose sum changed since the last one: a grid refilled
/// again and again must hold what a fresh grid filled once holds, cell by cell, bit for bit,
/// including cells emptied, refilled, and the voidage on the Di Felice factor's clamp.
#[test]
fn a_refilled_grid_holds_what_a_fresh_one_holds() {
    let (su, stepper) = sample2_small();
    let mut grid = voidage_grid(&su, &stepper);
    let cells = grid.cell_count();
    let cell_volume = su.width_m * su.height_m * su.thickness_m / cells as f64;
    let mut changed = 0;
    for round in 0..6usize {
        // Round r puts grains in every (r + 1)-th cell, some with more solid than the cell.
        let fill: Vec<(usize, f64)> = (0..cells)
            .filter(|c| c % (round + 1) == 0)
            .map(|c| (c, cell_volume * [0.1, 0.5, 0.9][(c + round) % 3]))
            .chain((round % 2 == 0).then_some((0, cell_volume)))
            .collect();
        let before: Vec<u64> = grid.voidages().iter().map(|x| x.to_bits()).collect();
        grid.fill_cells(fill.iter().copied());
        let mut fresh = voidage_grid(&su, &stepper);
        fresh.fill_cells(fill.iter().copied());
        for (c, &was) in before.iter().enumerate() {
            assert_eq!(
                grid.solid_m3()[c].to_bits(),
                fresh.solid_m3()[c].to_bits(),
                "round {round} cell {c}"
            );
            assert_eq!(
                grid.voidage(c).to_bits(),
                fresh.voidage(c).to_bits(),
                "round {round} cell {c}"
            );
            changed += usize::from(was != grid.voidage(c).to_bits());
        }
    }
    assert!(
        grid.is_di_felice() && changed > cells,
        "{changed} voidages changed"
    );
}

/// The packed suspension refills the grid from the list of cells whose sums changed since its
/// last fill (while they are few): over rounds of changes, that grid must hold what a grid
/// filled from every sum holds, bit for bit, and a grid filled by anything else in between
/// (a stale stamp) must refuse the list, so that the caller reads every sum instead.
#[test]
fn a_grid_refilled_from_the_cells_that_changed_holds_the_full_fill() {
    let (su, stepper) = sample2_small();
    let mut listed = voidage_grid(&su, &stepper);
    let cells = listed.cell_count();
    let grain = listed
        .quanta()
        .of(su.width_m * su.height_m * su.thickness_m / cells as f64);
    let mut sums = vec![0i128; cells];
    listed.fill_sums(&sums);
    let mut changed_voidages = 0;
    for round in 1..7usize {
        let before = sums.clone();
        // Round r moves grains into every (r + 2)-th cell and out of every (r + 3)-th.
        for c in (0..cells).step_by(round + 2) {
            sums[c] += grain * (c % 3 + 1) as i128 / 4;
        }
        for c in (0..cells).step_by(round + 3) {
            sums[c] -= sums[c] / 2;
        }
        // The cells that changed, each twice, and one that did not.
        let list: Vec<u32> = (0..cells)
            .filter(|&c| sums[c] != before[c])
            .flat_map(|c| [c as u32, c as u32])
            .chain([1])
            .collect();
        let old: Vec<u64> = listed.voidages().iter().map(|x| x.to_bits()).collect();
        assert!(listed.fill_sums_at(&sums, &list, listed.stamp()));
        let mut full = voidage_grid(&su, &stepper);
        full.fill_sums(&sums);
        let bits = |xs: &[f64]| xs.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(
            bits(listed.solid_m3()),
            bits(full.solid_m3()),
            "round {round}"
        );
        assert_eq!(
            bits(listed.voidages()),
            bits(full.voidages()),
            "round {round}"
        );
        changed_voidages += old
            .iter()
            .zip(bits(listed.voidages()))
            .filter(|(a, b)| *a != b)
            .count();
    }
    assert!(
        changed_voidages > cells / 2,
        "{changed_voidages} voidages changed"
    );
    let stale = listed.stamp();
    listed.fill_sums(&vec![0; cells]);
    assert!(
        !listed.fill_sums_at(&sums, &[0], stale),
        "a stale stamp is refused"
    );
    assert_ne!(voidage_grid(&su, &stepper).stamp(), listed.stamp());
}

/// The packed suspension holds its grains in kind order, cut in chunks updated in parallel,
/// drops the settled ones as it goes, and writes heights back (records) and speeds (the end)
/// by grain index: against the per-grain loop over the state in grain order, every record's
/// heights and settled flags and the final heights, speeds and bed must be the same bits
/// (sample 5, 40 000 grains: three chunks of the free update, several hundred steps with
/// grains settling).
#[test]
fn the_packed_loop_in_kind_order_is_the_per_grain_loop_bit_for_bit() {
    use crate::scenes::sedimentation::simulate::StepLoop;
    packed_loop_is_the_per_grain_loop_bit_for_bit(StepLoop::Chosen);
}

/// The same with every path taken however few the grains (`Suspension::every_path`): every
/// kind's tabulated step read from its table per voidage cell, deposition's lists and sums in
/// parallel (by default only kinds with many grains per cell, and many grains near the bed,
/// as at the real count, take them).
#[test]
fn the_packed_loop_on_every_path_is_the_per_grain_loop_bit_for_bit() {
    use crate::scenes::sedimentation::simulate::StepLoop;
    packed_loop_is_the_per_grain_loop_bit_for_bit(StepLoop::PackedEveryPath);
}

fn packed_loop_is_the_per_grain_loop_bit_for_bit(
    packed_loop: crate::scenes::sedimentation::simulate::StepLoop,
) {
    use crate::scenes::sedimentation::observer::OnRecord;
    use crate::scenes::sedimentation::simulate::{simulate_on, StepLoop};
    let ov: Vec<String> = [
        "sample.particles=40000",
        "time.end_s=1800.0",
        "physics=full",
        "sample.snapshot_times_s=[]",
    ]
    .map(String::from)
    .to_vec();
    let p = prepare(Path::new("scenarios/sedimentation_sample5.toml"), None, &ov).unwrap();
    let su = setup(&p).unwrap();
    type Seen = (Vec<u64>, Vec<bool>);
    let on = |step_loop| {
        let mut seen: Vec<Seen> = Vec::new();
        let mut obs = OnRecord(|st: &State| {
            seen.push((
                st.y_m.iter().map(|y| y.to_bits()).collect(),
                st.settled.clone(),
            ))
        });
        let st = simulate_on(step_loop, &su, State::initial(&su), &[], &mut obs);
        (st, seen)
    };
    let (packed, packed_seen) = on(packed_loop);
    let (per_grain, per_grain_seen) = on(StepLoop::PerGrain);
    let settled = packed.settled.iter().filter(|&&s| s).count();
    assert!(
        settled > 1000 && settled < su.grains.len(),
        "{settled} grains settled"
    );
    assert!(packed_seen.len() >= 3, "{} records", packed_seen.len());
    assert!(packed_seen == per_grain_seen, "the records' heights differ");
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&packed.y_m), bits(&per_grain.y_m));
    assert_eq!(bits(&packed.velocity_m_s), bits(&per_grain.velocity_m_s));
    assert_eq!(packed.settled, per_grain.settled);
    assert_eq!(
        packed.bed_height_m.to_bits(),
        per_grain.bed_height_m.to_bits()
    );
    assert_eq!(packed.steps, per_grain.steps);
}
