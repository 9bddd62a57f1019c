//! The instruments of seed 000 §4.5 (hydrometer, buoyancy sphere, pipette).
//!
//! Unit tests on synthetic fields (exact to rounding unless stated): the 152H geometry
//! reproduces its figures; in clear fluid it reads R = 0 at its clear-fluid depth; in a uniform
//! suspension it reads that density; in a step profile it floats at the hand-computed depth; the
//! eq. 21 pressure sum converges to the displaced weight; the sphere and pipette read known
//! fields and grains.
//!
//! End to end (`ideal-stokes`, 50 000 grains; `scenes::sedimentation::tests::instruments`, a unit
//! test, as it reads the scene's instruments): at every reading of every instrument,
//! |w_o − F(φ_o)| ≤ 4σ + (the instrument's own approximation) + 0.3 %, where σ is the 1σ of w_o
//! from the grain count (`sd_percent`) and the instrument's own approximation is what the same
//! instrument reads on the exact ideal suspension of the discretised sample
//! (c = c_0 F_n(φ(y, t))) minus the input curve at its diameter; and the simulation matches that
//! exact reading within 4σ + 0.3 %. The hydrometer's error is its finite bulb: its exact reading
//! is the bulb-weighted mean of F(φ(y)) over 14 cm of depth.

mod forward;
mod reduction;

use crate::common::{read_csv_records, settle, tmp};
use settle::instruments::buoyancy::BuoyancySphere;
use settle::instruments::hydrometer::{Hydrometer, HydrometerSpec};
use settle::instruments::pipette::{GrainSample, Pipette};
use settle::instruments::{ideal_field, Analysis, LayeredField};
use std::f64::consts::PI;

const H: f64 = 0.457;
const RHO_F: f64 = 1000.0;

fn analysis() -> Analysis {
    Analysis {
        viscosity_pa_s: 1e-3,
        grain_density_kg_m3: 2500.0,
        fluid_density_kg_m3: RHO_F,
        gravity_m_s2: 9.81,
        c0_kg_m3: 0.06 / (PI * 0.0635f64.powi(2) / 4.0 * H),
    }
}

#[test]
fn the_152h_geometry_reproduces_its_figures() {
    let h = Hydrometer::astm_152h(RHO_F);
    let s = h.spec;
    assert!((h.bulb_volume_m3() - 67e-6).abs() < 1e-15);
    assert!((s.bulb_length_m - 0.14).abs() < 1e-15);
    // Stem Ø 5.70 mm, bulb Ø 27.7 mm.
    assert!(
        (2.0 * h.stem_radius_m - 5.698e-3).abs() < 5e-6,
        "{}",
        h.stem_radius_m
    );
    assert!(
        (2.0 * h.bulb_radius_m - 27.75e-3).abs() < 5e-5,
        "{}",
        h.bulb_radius_m
    );
    // ASTM D422 Table 2: L = L1 + (L2 − V_B/A)/2 = 16.29 − 0.164 R cm, exact at 0 and 60, within
    // 0.1 cm (the table's rounding) between.
    let half = 0.5 * (0.14 - 67e-6 / 27.8e-4);
    let mut worst: f64 = 0.0;
    for r in 0..=60 {
        let l = h.mark_m(r as f64) + half;
        let table = 0.1629 - 0.00164 * r as f64;
        worst = worst.max((l - table).abs());
        if r == 0 || r == 60 {
            assert!((l - table).abs() < 1e-12, "R = {r}: {l} vs {table}");
        }
    }
    assert!(worst < 1e-3 && worst > 5e-4, "largest deviation {worst} m");
    // Volume of the body by quadrature of its section.
    let n = 200_000;
    let len = h.length_m();
    let v: f64 = (0..n)
        .map(|i| h.area_m2((i as f64 + 0.5) * len / n as f64) * len / n as f64)
        .sum();
    assert!((v / h.volume_below(len) - 1.0).abs() < 1e-6);
}

#[test]
fn clear_fluid_reads_zero_at_the_clear_depth() {
    let h = Hydrometer::astm_152h(RHO_F);
    let f = LayeredField::uniform(H, 4000, RHO_F, RHO_F);
    let r = h.read(&f).unwrap();
    assert!(r.reading.abs() < 1e-6, "R = {}", r.reading);
    assert!((r.tip_depth_m - h.clear_tip_depth_m()).abs() < 1e-9);
    assert!((r.stem_immersed_m - h.zero_mark_m).abs() < 1e-9);
    assert!((r.astm_effective_depth_m - 0.1629).abs() < 1e-9);
    assert!((r.density_kg_m3 - RHO_F).abs() < 1e-6);
    let p = h.point(&analysis(), &r, 600.0);
    assert!(p.percent_finer.abs() < 1e-6);
}

#[test]
fn a_uniform_suspension_reads_its_density() {
    let h = Hydrometer::astm_152h(RHO_F);
    let an = analysis();
    for rho in [1005.0, 1015.0, 1024.9, 1037.0] {
        let f = LayeredField::uniform(H, 4000, RHO_F, rho);
        let r = h.read(&f).unwrap();
        assert!(
            (r.density_kg_m3 - rho).abs() < 1e-6,
            "{rho}: {}",
            r.density_kg_m3
        );
        assert!((r.bulb_mean_density_kg_m3 - rho).abs() < 1e-6);
        // R in g/L of G_s = 2.65 soil, and the mark of R is where the surface is.
        let expect_r = (rho / RHO_F - 1.0) * 1000.0 / (1.0 - 1.0 / 2.65);
        assert!((r.reading - expect_r).abs() < 1e-5, "{}", r.reading);
        assert!((h.mark_m(r.reading) - r.stem_immersed_m).abs() < 1e-9);
        // w_o = 100 c/c0.
        let c = 2500.0 * (rho - RHO_F) / 1500.0;
        assert!((h.point(&an, &r, 60.0).percent_finer - 100.0 * c / an.c0_kg_m3).abs() < 1e-6);
    }
    // The initial suspension of seed 000 (60 g in the 1.447 L cylinder): ρ = 1024.9 kg/m³.
    let rho0 = an.density_of_concentration(an.c0_kg_m3);
    assert!((rho0 - 1024.88).abs() < 0.01, "{rho0}");
    let r = h
        .read(&LayeredField::uniform(H, 4000, RHO_F, rho0))
        .unwrap();
    assert!((h.point(&an, &r, 60.0).percent_finer - 100.0).abs() < 1e-6);
}

#[test]
fn a_step_profile_floats_at_the_hand_computed_depth() {
    // Clear fluid down to y_s, then ρ2: with y_s on the cylindrical part of the bulb the
    // displaced mass is ρ1 V_sub(tip) + (ρ2 − ρ1)(V_cone + π R_b² (tip − y_s − e)), linear in tip.
    let h = Hydrometer::astm_152h(RHO_F);
    let (rho1, rho2, ys) = (RHO_F, 1030.0, 0.15);
    let f = LayeredField::from_fn(H, 4570, RHO_F, |y| if y < ys { rho1 } else { rho2 });
    let (rb, rs, e, l2) = (
        h.bulb_radius_m,
        h.stem_radius_m,
        h.spec.taper_m,
        h.spec.bulb_length_m,
    );
    let a_s = PI * rs * rs;
    let v_cone = PI * e / 3.0 * (rb * rb + rb * rs + rs * rs);
    let a_b = PI * rb * rb;
    let tip = (h.mass_kg - rho1 * (67e-6 - a_s * l2) - (rho2 - rho1) * (v_cone - a_b * (ys + e)))
        / (rho1 * a_s + (rho2 - rho1) * a_b);
    assert!(ys > tip - l2 + e && ys < tip - e, "step on the cylinder");
    let got = h.float_tip_depth_m(&f).unwrap();
    assert!((got - tip).abs() < 1e-9, "tip {got} vs hand {tip}");
    // It floats higher than in clear fluid, and the reading is the mean over the whole
    // submerged volume.
    assert!(got < h.clear_tip_depth_m());
    let r = h.read(&f).unwrap();
    let v_sub = h.volume_below(got);
    assert!((r.density_kg_m3 - h.mass_kg / v_sub).abs() < 1e-9);
}

#[test]
fn eq21_pressure_sum_converges_to_the_displaced_weight() {
    let h = Hydrometer::astm_152h(RHO_F);
    let g = 9.81;
    let mut last = f64::INFINITY;
    for layers in [400, 4000, 40_000] {
        // A stratified suspension: 1000 at the top, up to 1030 at the bottom, with a kink.
        let f = LayeredField::from_fn(H, layers, RHO_F, |y| {
            1000.0 + 30.0 * (y / H).powf(0.7) + if y > 0.2 { 5.0 } else { 0.0 }
        });
        let tip = h.float_tip_depth_m(&f).unwrap();
        let exact = g * h.displaced_mass_kg(&f, tip);
        assert!((exact - g * h.mass_kg).abs() < 1e-9);
        let rel = (h.pressure_force_eq21_n(&f, tip, g) / exact - 1.0).abs();
        assert!(rel < 0.2 * last.max(1e-7) || rel < 1e-7, "{layers}: {rel}");
        last = rel;
    }
    assert!(last < 1e-4, "{last}");
}

#[test]
fn the_buoyancy_sphere_weighs_what_it_displaces() {
    let an = analysis();
    let sp = BuoyancySphere {
        diameter_m: 0.025,
        mass_kg: 0.020,
        depth_m: 0.3 * H,
    };
    let v = PI * 0.025f64.powi(3) / 6.0;
    // Clear water: 20 − 8.18 = 11.82 g (the seed quotes 1.62 g).
    let r = sp.read(&LayeredField::uniform(H, 4000, RHO_F, RHO_F));
    assert!((r.apparent_mass_kg - (0.020 - RHO_F * v)).abs() < 1e-12);
    assert!((r.apparent_mass_kg * 1e3 - 11.818).abs() < 1e-3);
    assert!(sp.point(&an, &r, 60.0).percent_finer.abs() < 1e-9);
    // Initial suspension: 11.61 g (seed: 1.52 g), reads 100 %.
    let rho0 = an.density_of_concentration(an.c0_kg_m3);
    let r = sp.read(&LayeredField::uniform(H, 4000, RHO_F, rho0));
    assert!((r.apparent_mass_kg * 1e3 - 11.615).abs() < 1e-3);
    assert!((sp.point(&an, &r, 60.0).percent_finer - 100.0).abs() < 1e-9);
    // A step at the centre: half the sphere in each density.
    let f = LayeredField::from_fn(
        H,
        45_700,
        RHO_F,
        |y| {
            if y < 0.3 * H {
                1000.0
            } else {
                1020.0
            }
        },
    );
    let r = sp.read(&f);
    assert!(
        (r.density_kg_m3 - 1010.0).abs() < 1e-3,
        "{}",
        r.density_kg_m3
    );
}

#[test]
fn the_pipette_weighs_the_grains_in_its_disc() {
    let an = analysis();
    let hz = PI * 0.0635 / 720.0;
    let p = Pipette {
        volume_m3: 35e-6,
        depth_m: 0.3 * H,
        wedge_fraction: 1.0 / 180.0,
        thickness_m: hz,
        axis_x_m: 0.0635 / 2.0,
    };
    // Disc of 7.02 cm², radius 14.95 mm.
    assert!((PI * p.radius_m().powi(2) * hz - 35e-6 / 180.0).abs() < 1e-15);
    assert!((p.radius_m() - 0.014946).abs() < 1e-5, "{}", p.radius_m());
    // Grains on a fine grid of known mass per area: the disc's mass is that per area × its area.
    let (nx, ny) = (400, 2000);
    let (dx, dy) = (0.0635 / nx as f64, H / ny as f64);
    let c = an.c0_kg_m3 * 0.37; // kg/m³
    let m_cell = c * dx * dy * hz;
    let grains = (0..nx * ny).map(|i| GrainSample {
        x_m: ((i % nx) as f64 + 0.5) * dx,
        depth_m: ((i / nx) as f64 + 0.5) * dy,
        mass_kg: m_cell,
    });
    let r = p.read(grains);
    assert!(
        (r.concentration_kg_m3 / c - 1.0).abs() < 0.01,
        "{}",
        r.concentration_kg_m3 / c
    );
    assert!((r.mass_kg - r.concentration_kg_m3 * 35e-6).abs() < 1e-12);
    assert!((p.point(&an, &r, 60.0).percent_finer - 37.0).abs() < 0.4);
    // The field version on a uniform suspension reads its concentration exactly.
    let f = LayeredField::uniform(H, 4000, RHO_F, an.density_of_concentration(c));
    let cf = p.field_concentration(&an, &f);
    assert!((cf / c - 1.0).abs() < 1e-9, "{cf} vs {c}");
}

#[test]
fn the_hydrometer_error_comes_from_its_finite_bulb() {
    // Sample 4 (92 % between 25 and 35 µm) on the exact ideal suspension at 300 s: the 152H's
    // reading is the bulb-weighted mean of F(φ(y)), far from F at the bulb centre where F is
    // steep; a short bulb (2 cm, same volume and scale) cuts the error.
    let an = analysis();
    let curve = settle::sample::Distribution {
        points: vec![(2.5e-6, 0.0), (25e-6, 5.0), (35e-6, 97.0), (70e-6, 100.0)],
    };
    let finer = |d: f64| curve.percent_finer(d) / 100.0;
    let f = ideal_field(&an, H, 4000, 300.0, finer);
    let err = |h: &Hydrometer| {
        let r = h.read(&f).unwrap();
        let p = h.point(&an, &r, 300.0);
        p.percent_finer - curve.percent_finer(p.diameter_m)
    };
    let long = err(&Hydrometer::astm_152h(RHO_F));
    let short = err(&Hydrometer::new(
        HydrometerSpec {
            bulb_length_m: 0.02,
            taper_m: 0.005,
            effective_depth_zero_m: 0.1629 - 0.06,
            ..HydrometerSpec::default()
        },
        RHO_F,
    ));
    assert!(long.abs() > 3.0, "152H error {long}");
    assert!(
        short.abs() < 0.35 * long.abs(),
        "short {short} vs 152H {long}"
    );
}

// End to end (`ideal-stokes`, 50 000 grains) against the input curve:
// `scenes::sedimentation::tests::instruments` (a unit test: it reads the scene's instruments).

#[test]
fn several_samples_write_one_error_summary() {
    let dir = tmp();
    let mut cmd = settle();
    cmd.args([
        "run",
        "-q",
        "scenarios/sedimentation_sample2.toml",
        "scenarios/sedimentation_sample3.toml",
        "--out",
    ])
    .arg(dir.path());
    for o in [
        "physics=ideal-stokes",
        "sample.particles=5000",
        "sample.max_step_s=1e5",
        "sample.record_times_s=[86400.0]",
        "sample.snapshot_times_s=[]",
        "instruments.hydrometer_times_s=[120.0, 900.0]",
    ] {
        cmd.args(["--set", o]);
    }
    let o = cmd.output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rows = read_csv_records(&dir.path().join("combined/instrument_errors.csv"));
    assert_eq!(rows.len(), 6);
    assert_eq!(rows[0]["sample"], "2");
    assert_eq!(rows[0]["instrument"], "hydrometer");
    assert_eq!(rows[0]["readings"], "2");
    assert_eq!(rows[5]["sample"], "3");
    assert_eq!(rows[5]["instrument"], "pipette");
}

#[test]
fn bad_instruments_are_refused() {
    for (ov, key) in [
        (
            "instruments.sphere_depth_fraction=0.01",
            "sphere_depth_fraction",
        ),
        ("instruments.pipette_volume_m3=1e-3", "pipette_volume_m3"),
        (
            "instruments.hydrometer_times_s=[-1.0]",
            "hydrometer_times_s",
        ),
        ("instruments.hydrometer_times_s=[1e6]", "hydrometer_times_s"),
        (
            "instruments.hydrometer_bulb_length_m=0.6",
            "hydrometer_bulb_length_m",
        ),
        (
            "instruments.hydrometer_effective_depth_slope_m=0.01",
            "instruments",
        ),
        ("instruments.nonsense=1", "nonsense"),
    ] {
        let (k, v) = ov.split_once('=').unwrap();
        let e = settle::load("scenarios/sedimentation_sample1.toml")
            .unwrap()
            .set(k, v)
            .err()
            .unwrap_or_else(|| panic!("{ov} accepted"));
        assert!(e.to_string().contains(key), "{ov}: {e}");
    }
}
