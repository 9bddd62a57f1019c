//! Contacts and squeeze-film lubrication between representative grains of the sedimentation
//! cylinder (`physics = "full"`): the cluster solve of `scenes::sedimentation::contacts` on two-grain
//! cases with known answers, and the full run with contacts on. Each test states its tolerance.

use crate::dynamics::Integrator;
use crate::fluid::lubrication::{damping_n_s_m, effective_radius_m, Cutoffs};
use crate::fluid::{DragLaw, SphereDrag};
use crate::scenes::sedimentation::contacts::{
    resolve, ClusterGrain, ContactScene, PairFinder, Probe, Resolved,
};
use crate::scenes::sedimentation::{CONTACT_FILM_CHANGE_PER_STEP, CONTACT_TRAVEL_PER_SUBSTEP};
use std::f64::consts::PI;

const MU: f64 = 1e-3;
const RHO_P: f64 = 2500.0;
const RHO_F: f64 = 1000.0;
const G: f64 = 9.81;

fn scene(lubrication: bool, travel: f64, film: f64) -> ContactScene {
    ContactScene {
        width_m: 0.0635,
        floor_m: 0.0,
        density_kg_m3: RHO_P,
        fluid_density_kg_m3: RHO_F,
        gravity_m_s2: G,
        viscosity_pa_s: MU,
        lubrication: lubrication.then_some(Cutoffs::default()),
        outer_fraction: Cutoffs::default().outer,
        integrator: Integrator::Exponential,
        travel_per_substep: travel,
        film_change_per_step: film,
        friction: 0.0,
        restitution: crate::contact::RestitutionLaw::constant(0.0),
    }
}

fn stokes(d: f64) -> SphereDrag {
    SphereDrag::new(DragLaw::Stokes { viscosity_pa_s: MU }, d, RHO_F)
}

fn terminal(d: f64) -> f64 {
    -d * d * (RHO_P - RHO_F) * G / (18.0 * MU)
}

fn grain(x: f64, y: f64, d: f64) -> ClusterGrain {
    ClusterGrain {
        x_m: x,
        y_m: y,
        vy_m_s: terminal(d),
        diameter_m: d,
        drag: stokes(d),
    }
}

/// Steps a two-grain cluster (big = 0, small = 1) with `resolve` over `steps` steps of `dt`,
/// returning the states after each step.
fn run_pair(
    mut g: [ClusterGrain; 2],
    sc: &ContactScene,
    dt: f64,
    steps: usize,
) -> Vec<[Resolved; 2]> {
    let mut out = Vec::new();
    for _ in 0..steps {
        let (r, solve) = resolve(&g, &[(0, 1)], sc, dt);
        assert!(
            !solve.fallback,
            "the contact solve fell back to the free update"
        );
        for k in 0..2 {
            g[k].x_m = r[k].x_m;
            g[k].y_m = r[k].y_m;
            g[k].vy_m_s = r[k].vy_m_s;
        }
        out.push([r[0], r[1]]);
    }
    out
}

#[test]
fn a_big_grain_catches_a_small_one_and_does_not_pass_through_it() {
    // 70 µm above 10 µm, 5 µm off axis, 100 µm apart: the big one (4.0 mm/s) catches the small
    // one (0.08 mm/s) after ~25 ms. Frictionless discs: the small one is pushed aside and down
    // until the big one has gone past. Sampled every 0.2 ms. Tolerances: overlap at most 1 % of
    // the small diameter at every sample; at the end the big grain is below the small one, and
    // it got there around it (largest |Δx| ≥ 99 % of r₁ + r₂; the film's attraction while the
    // pair separates pulls Δx back by < 1 %).
    let (db, ds) = (70e-6, 10e-6);
    let touch = 0.5 * (db + ds);
    for lubrication in [false, true] {
        let sc = scene(
            lubrication,
            CONTACT_TRAVEL_PER_SUBSTEP,
            CONTACT_FILM_CHANGE_PER_STEP,
        );
        let g = [
            grain(0.03, 0.01 + 100e-6 + touch, db),
            grain(0.03 + 5e-6, 0.01, ds),
        ];
        let states = run_pair(g, &sc, 2e-4, 400);
        let mut widest: f64 = 0.0;
        for s in &states {
            let (dx, dy) = (s[1].x_m - s[0].x_m, s[1].y_m - s[0].y_m);
            let gap = (dx * dx + dy * dy).sqrt() - touch;
            assert!(
                gap > -0.01 * ds,
                "lubrication {lubrication}: overlap {:.3e} d_small",
                -gap / ds
            );
            widest = widest.max(dx.abs());
        }
        let last = states.last().unwrap();
        assert!(
            last[0].y_m < last[1].y_m - touch,
            "lubrication {lubrication}: the big grain did not get past the small one"
        );
        assert!(
            widest >= 0.99 * touch,
            "lubrication {lubrication}: the small grain was not pushed aside (|dx| ≤ {widest:e} m)"
        );
    }
}

/// Gap of two spheres settling along their line of centres (Stokes drag each, overdamped),
/// the faster one above, with the squeeze film c = 6πμ a_eff²/h between them: the approach is
/// u = Δu/(1 + c(1/k₁ + 1/k₂)) = Δu h/(h + a_eff), so (h − h₀) + a_eff ln(h/h₀) = −Δu t.
fn lubricated_gap_m(a_eff: f64, h0: f64, du: f64, t: f64) -> f64 {
    let f = |h: f64| (h - h0) + a_eff * (h / h0).ln() + du * t;
    let (mut lo, mut hi) = (1e-6 * h0, h0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn a_lubricated_pair_approaches_at_the_squeeze_film_rate() {
    // 70 µm right above 30 µm, gap 0.09 a_eff (inside the cut-off, a_eff = 10.5 µm): the free
    // relative speed Δu = 3.3 mm/s would close the gap in 0.29 ms; the film slows it to
    // h(t) above. Tolerance: 10 % of h at t = 2.4 ms (h = h₀/2) and 4.7 ms (h = h₀/4) (measured: 4.6 % and 7.6 % too
    // close, a systematic excess of the Rapier solve not yet explained), where
    // inertia (relative response time < 0.1 ms) and the frozen gap per Rapier step (2 %
    // change) are the known errors. Without lubrication the pair touches.
    let (db, ds) = (70e-6, 30e-6);
    let a = effective_radius_m(0.5 * db, 0.5 * ds);
    let h0 = 0.09 * a;
    let du = terminal(ds) - terminal(db);
    let mut g = [
        grain(0.03, 0.01 + 0.5 * (db + ds) + h0, db),
        grain(0.03, 0.01, ds),
    ];
    // Start on the overdamped state of the lubricated pair (else the pair's own inertial
    // transient, ~0.5 ms, first squeezes the film ~30 % harder than the steady force).
    let (kb, ks) = (3.0 * PI * MU * db, 3.0 * PI * MU * ds);
    let c0 = damping_n_s_m(0.5 * db, 0.5 * ds, h0, MU, Cutoffs::default());
    let u0 = du / (1.0 + c0 * (1.0 / kb + 1.0 / ks));
    g[0].vy_m_s += c0 * u0 / kb;
    g[1].vy_m_s -= c0 * u0 / ks;
    let gap = |r: &[Resolved]| (r[0].y_m - r[1].y_m) - 0.5 * (db + ds);
    for (t, fraction) in [(2.4e-3, 0.5), (4.7e-3, 0.25)] {
        let exact = lubricated_gap_m(a, h0, du, t);
        assert!(
            (exact / h0 - fraction).abs() < 0.02,
            "analytic h/h0 = {}",
            exact / h0
        );
        // Fine film steps (1 %), then the run's setting.
        for (film, tolerance) in [(0.01, 0.10), (CONTACT_FILM_CHANGE_PER_STEP, 0.30)] {
            let sc = scene(true, CONTACT_TRAVEL_PER_SUBSTEP, film);
            let (r, solve) = resolve(&g, &[(0, 1)], &sc, t);
            assert!(!solve.fallback);
            let steps = solve.rapier_steps;
            let h = gap(&r);
            println!("film {film}: t = {t:e} s: gap / squeeze-film solution = {:.4} ({steps} Rapier steps)", h / exact);
            assert!(
                (h / exact - 1.0).abs() < tolerance,
                "film {film}: t = {t:e} s: gap {h:e} m, squeeze-film solution {exact:e} m ({steps} Rapier steps)"
            );
        }
        assert!(
            du * t > 5.0 * h0,
            "the free approach would have closed the gap"
        );
        let (r, _) = resolve(&g, &[(0, 1)], &scene(false, 0.01, 0.01), t);
        assert!(
            gap(&r) < 0.05 * h0,
            "without lubrication the pair touches: gap {:e} m",
            gap(&r)
        );
    }
}

#[test]
fn a_grain_pushed_against_a_wall_stays_in_the_domain() {
    // 10 µm grain touching the wall x = 0, a 70 µm grain touching the wall 2 µm above contact
    // (30 µm to its right): the contact pushes the small one into the wall; the big one (no
    // friction) slides off it to the right and goes past. Sampled every 2 ms for 60 ms.
    // Tolerances: grain–grain overlap ≤ 1 % of the small diameter (measured 0.31 %), each disc
    // inside the walls, and the big grain ends below the small one having gone around it
    // (largest |Δx| ≥ 99 % of r₁ + r₂).
    let (db, ds): (f64, f64) = (70e-6, 10e-6);
    let touch = 0.5 * (db + ds);
    let dx = 0.5 * db - 0.5 * ds;
    let dy = (touch * touch - dx * dx).sqrt() + 2e-6;
    for lubrication in [false, true] {
        let sc = scene(
            lubrication,
            CONTACT_TRAVEL_PER_SUBSTEP,
            CONTACT_FILM_CHANGE_PER_STEP,
        );
        let g = [grain(0.5 * db, 0.005 + dy, db), grain(0.5 * ds, 0.005, ds)];
        // Each sample is its own solve from t = 0 (one Rapier world over the whole contact, as
        // in the run, where a step spans the whole contact).
        let states: Vec<[Resolved; 2]> = (1..=30)
            .map(|k| run_pair(g, &sc, 2e-3 * k as f64, 1)[0])
            .collect();
        let mut widest: f64 = 0.0;
        for s in &states {
            let (ddx, ddy) = (s[1].x_m - s[0].x_m, s[1].y_m - s[0].y_m);
            let gap = (ddx * ddx + ddy * ddy).sqrt() - touch;
            assert!(
                gap > -0.01 * ds,
                "lubrication {lubrication}: overlap {:.3e} d_small",
                -gap / ds
            );
            for (k, d) in [(0, db), (1, ds)] {
                assert!(s[k].x_m >= 0.5 * d && s[k].x_m <= sc.width_m - 0.5 * d);
            }
            widest = widest.max(ddx.abs());
        }
        let last = states.last().unwrap();
        assert!(
            last[0].y_m < last[1].y_m - touch,
            "lubrication {lubrication}: the big grain is stuck"
        );
        assert!(
            widest >= 0.99 * touch,
            "lubrication {lubrication}: |dx| ≤ {widest:e} m"
        );
    }
}

/// Largest overlap of suspended grains, in diameters of the smaller of each pair, and the number
/// of pairs overlapping by more than 5 % (pairs found by the cell list on frozen positions).
fn overlaps(
    st: &crate::scenes::sedimentation::State,
    grains: &crate::sample::Grains,
    width_m: f64,
) -> (f64, usize) {
    let all: Vec<_> = (0..st.len()).map(|i| st.grain(grains, i)).collect();
    let probes: Vec<Option<Probe>> = all
        .iter()
        .zip(&st.settled)
        .map(|(g, s)| {
            (!s).then_some(Probe {
                x_m: g.x_m,
                y_start_m: g.y_m,
                y_end_m: g.y_m,
                radius_m: 0.5 * g.diameter_m,
            })
        })
        .collect();
    let (mut worst, mut deep): (f64, usize) = (0.0, 0);
    for (i, j) in PairFinder::default().pairs(&probes, width_m, 0.1) {
        let (a, b) = (&all[i], &all[j]);
        let dist = ((a.x_m - b.x_m).powi(2) + (a.y_m - b.y_m).powi(2)).sqrt();
        let overlap = 0.5 * (a.diameter_m + b.diameter_m) - dist;
        let d = a.diameter_m.min(b.diameter_m);
        worst = worst.max(overlap / d);
        if overlap > 0.05 * d {
            deep += 1;
        }
    }
    (worst, deep)
}

#[test]
fn full_physics_with_contacts_accounts_for_every_grain() {
    use super::prepare;
    use crate::fluid::sphere_volume_m3;
    use crate::scenes::sedimentation::{setup, simulate, OnRecord, State};
    use std::path::Path;
    // Sample 1, 15 000 grains, full physics with contacts and lubrication, 120 s. Tolerances:
    // at every record time the suspended plus deposited solid volume equals the sample's to
    // 1e-12 (relative), every grain lies inside the cylinder (x within [r, B − r], y within
    // [bed − 1 % d, H]), the run found close pairs and resolved them in Rapier, and fewer than
    // 1 % of the cluster solves fell back to the free update. No two suspended grains overlap
    // by more than 1 % of the smaller diameter at a record time (measured 0.14 %), where the
    // same run without contacts has dozens of pairs inside each other by more than 5 %.
    let ov: Vec<String> = vec![
        "sample.particles=15000".into(),
        "time.end_s=120".into(),
        "time.dt_s=10".into(),
        "sample.record_times_s=[10.0, 30.0, 60.0, 120.0]".into(),
        "sample.snapshot_times_s=[]".into(),
        "sample.contacts=true".into(),
    ];
    let p = prepare(Path::new("scenarios/sedimentation_sample1.toml"), None, &ov).unwrap();
    let crate::scenario::SceneSpec::Sedimentation(spec) = &p.scene else {
        panic!("a sedimentation scenario")
    };
    let sm = &spec.sample;
    assert!(
        sm.contacts && sm.lubrication_on(),
        "contacts on, lubrication follows them"
    );
    let su = setup(&p).unwrap();
    let total: f64 = su
        .grains
        .to_vec()
        .iter()
        .map(|g| g.weight * sphere_volume_m3(g.diameter_m))
        .sum();
    let mut records = 0;
    let (mut worst, mut deep): (f64, usize) = (f64::NEG_INFINITY, 0);
    let st = simulate(
        &su,
        State::initial(&su),
        &[],
        &mut OnRecord(|st: &State| {
            records += 1;
            let mut volume = 0.0;
            for g in (0..st.len()).map(|i| st.grain(&su.grains, i)) {
                volume += g.weight * sphere_volume_m3(g.diameter_m);
                let r = 0.5 * g.diameter_m;
                assert!(g.x_m >= r * (1.0 - 1e-9) && g.x_m <= su.width_m - r * (1.0 - 1e-9));
                assert!(g.y_m - r >= -0.01 * g.diameter_m && g.y_m <= su.height_m);
            }
            assert!(((volume - total) / total).abs() < 1e-12);
            let (w, d) = overlaps(st, &su.grains, su.width_m);
            worst = worst.max(w);
            deep += d;
        }),
    );
    assert_eq!(records, 4);
    let c = st.contacts;
    assert!(c.pairs > 100 && c.rapier_steps > c.pairs, "contacts: {c:?}");
    assert!(
        (c.fallbacks as f64) < 0.01 * c.pairs as f64,
        "contacts: {c:?}"
    );
    println!("contacts: {c:?}; worst overlap {worst:.3e} d, {deep} pairs beyond 5 %");
    assert!(
        worst < 0.01 && deep == 0,
        "overlaps with contacts: worst {worst:e} d, {deep} beyond 5 %"
    );
    // The same run without contacts has grains inside each other (the check can fail).
    let mut ov_off = ov.clone();
    ov_off.push("sample.contacts=false".into());
    ov_off.push("sample.lubrication=false".into());
    let p = prepare(
        Path::new("scenarios/sedimentation_sample1.toml"),
        None,
        &ov_off,
    )
    .unwrap();
    // The same grains (the switches do not change the sample), without contacts.
    let su_off = setup(&p).unwrap();
    assert_eq!(su_off.grains.len(), su.grains.len());
    let mut deep_off = 0;
    let st = simulate(
        &su_off,
        State::initial(&su_off),
        &[],
        &mut OnRecord(|st: &State| deep_off += overlaps(st, &su_off.grains, su_off.width_m).1),
    );
    assert_eq!(st.contacts.pairs, 0);
    assert!(deep_off > 10, "without contacts: {deep_off} deep overlaps");
    println!("without contacts: {deep_off} pairs overlapping by more than 5 %");
}

/// Regression: after the engine learnt to stop runs whose contacts overlap by more than 0.25 d,
/// sample 2 fell back to the free update in 474 226 cluster-steps (against 20 before), because a
/// cluster that starts overlapping (left so by an earlier fallback, or by the sampling) tripped
/// the check instead of being pushed apart. The contact solve must undo such overlaps: two 20 µm
/// grains placed side by side overlapping by half a diameter end the step apart (overlap < 1 %
/// of d), without a fallback.
#[test]
fn a_cluster_that_starts_overlapping_is_pushed_apart_not_dropped() {
    let d = 20e-6;
    let sc = scene(
        true,
        CONTACT_TRAVEL_PER_SUBSTEP,
        CONTACT_FILM_CHANGE_PER_STEP,
    );
    let g = [grain(0.03, 0.2, d), grain(0.03 + 0.5 * d, 0.2, d)];
    let (r, solve) = resolve(&g, &[(0, 1)], &sc, 0.25);
    assert!(
        !solve.fallback,
        "the overlapping cluster fell back to the free update"
    );
    let dist = ((r[0].x_m - r[1].x_m).powi(2) + (r[0].y_m - r[1].y_m).powi(2)).sqrt();
    assert!(
        dist > 0.99 * d,
        "still overlapping: centres {dist:.3e} m apart, d = {d:e}"
    );
}

/// Two 1 mm grains in air-like fluid (Stokes number ≫ 1, so that the contact, not the drag,
/// decides the outcome), head-on: the upper one falls at 1 m/s onto the lower one at rest,
/// 1 mm below, within one step of 3 ms. The step's contact world takes `friction` and
/// `restitution` from the scene (`[contacts]`).
fn head_on(restitution: f64, friction: f64, offset_m: f64) -> [Resolved; 2] {
    let (mu, rho_f, d) = (1.8e-5, 1.2, 1e-3);
    let drag = SphereDrag::new(DragLaw::Stokes { viscosity_pa_s: mu }, d, rho_f);
    let sc = ContactScene {
        fluid_density_kg_m3: rho_f,
        viscosity_pa_s: mu,
        friction,
        restitution: crate::contact::RestitutionLaw::constant(restitution),
        ..scene(
            false,
            CONTACT_TRAVEL_PER_SUBSTEP,
            CONTACT_FILM_CHANGE_PER_STEP,
        )
    };
    let g = [
        ClusterGrain {
            x_m: 0.03 + offset_m,
            y_m: 0.01 + 2.0 * d,
            vy_m_s: -1.0,
            diameter_m: d,
            drag,
        },
        ClusterGrain {
            x_m: 0.03,
            y_m: 0.01,
            vy_m_s: 0.0,
            diameter_m: d,
            drag,
        },
    ];
    let (r, solve) = resolve(&g, &[(0, 1)], &sc, 3e-3);
    assert!(!solve.fallback && solve.rapier_steps > 0, "{solve:?}");
    [r[0], r[1]]
}

#[test]
fn restitution_of_the_scene_makes_a_head_on_pair_separate_after_impact() {
    // Equal masses, head-on, 1 m/s: with e = 0 (no [contacts], as before) the pair moves on
    // together (gap ≈ 0: below 2 % of d); with e = 1 the velocities swap at impact (after 1 ms),
    // so the lower grain leaves at ~1 m/s and the gap opens by ~2 mm over the 2 ms left (at
    // least 1.5 mm: gravity and drag change both grains alike to within 1 %), and with e = 0.5
    // by about half that (0.6–1.4 mm).
    let gap = |r: [Resolved; 2]| r[0].y_m - r[1].y_m - 1e-3;
    let inelastic = gap(head_on(0.0, 0.0, 0.0));
    let elastic = gap(head_on(1.0, 0.0, 0.0));
    let half = gap(head_on(0.5, 0.0, 0.0));
    println!(
        "gap after the step: e = 0 {inelastic:.3e} m, e = 0.5 {half:.3e} m, e = 1 {elastic:.3e} m"
    );
    assert!(inelastic.abs() < 2e-5, "e = 0: gap {inelastic:e} m");
    assert!(elastic > 1.5e-3, "e = 1: gap {elastic:e} m");
    assert!(half > 0.6e-3 && half < 1.4e-3, "e = 0.5: gap {half:e} m");
}

#[test]
fn friction_of_the_scene_changes_an_oblique_impact() {
    // The same impact 0.3 d off axis with e = 1: without friction the contact impulse lies along
    // the line of centres; with μ = 1 a tangential impulse is added, which changes where the
    // lower grain goes (its x differs by more than 1 µm).
    let base = head_on(1.0, 0.0, 0.3e-3);
    let rough = head_on(1.0, 1.0, 0.3e-3);
    let dx = (rough[1].x_m - base[1].x_m).abs() + (rough[0].x_m - base[0].x_m).abs();
    println!(
        "lower grain x: μ = 0 {:.6e} m, μ = 1 {:.6e} m",
        base[1].x_m, rough[1].x_m
    );
    assert!(dx > 1e-6, "friction changed nothing: Δx = {dx:e} m");
}
