use super::*;
use crate::fluid::{sphere_mass_kg, DragLaw};
use nalgebra::{SVector, Vector3};

/// f-EDEM Table 1: d = 0.1 mm, ρ_p = 2700, water. τ = 1.5 ms, v_t = 9.265e-3 m/s.
fn stokes_sphere() -> (SphereDrag, f64, Vector3<f64>) {
    let d = 1e-4;
    let drag = SphereDrag::new(
        DragLaw::Stokes {
            viscosity_pa_s: 1e-3,
        },
        d,
        1000.0,
    );
    let m = sphere_mass_kg(d, 2700.0);
    let w = Vector3::new(0.0, 0.0, -(m - sphere_mass_kg(d, 1000.0)) * 9.81);
    (drag, m, w)
}

fn run(integ: Integrator, dt: f64, t_end: f64) -> (f64, f64) {
    let (drag, m, w) = stokes_sphere();
    let mut v = Vector3::zeros();
    let mut x = Vector3::zeros();
    let n = (t_end / dt).round() as usize;
    for _ in 0..n {
        let s = advance(integ, &drag, m, &w, &v, dt);
        v = s.velocity_m_s;
        x += s.displacement_m;
    }
    (-v.z, -x.z)
}

fn analytic(t: f64) -> (f64, f64) {
    let (vt, tau) = (1e-8 * 1700.0 * 9.81 / 0.018, 1.5e-3);
    (
        vt * (1.0 - (-t / tau).exp()),
        vt * (t - tau * (1.0 - (-t / tau).exp())),
    )
}

#[test]
fn exponential_is_exact_for_stokes_drag_at_any_dt() {
    for dt in [1e-6, 1e-5, 1e-4, 1e-3, 1e-2] {
        let t = 0.02;
        let (v, x) = run(Integrator::Exponential, dt, t);
        let (va, xa) = analytic(t);
        assert!((v - va).abs() / va < 1e-9, "dt {dt}: v {v} vs {va}");
        assert!((x - xa).abs() / xa < 1e-9, "dt {dt}: x {x} vs {xa}");
    }
}

#[test]
fn implicit_is_stable_and_reaches_the_terminal_velocity_at_large_dt() {
    let (v, _) = run(Integrator::Implicit, 1e-2, 0.5);
    let (va, _) = analytic(0.5);
    assert!((v - va).abs() / va < 1e-12);
}

#[test]
fn explicit_diverges_beyond_twice_the_response_time() {
    // τ = 1.5 ms: 2τ = 3 ms. Below: converges; above: the error grows without bound.
    let (va, _) = analytic(0.3);
    let (v_ok, _) = run(Integrator::Explicit, 2.9e-3, 0.3);
    assert!((v_ok - va).abs() / va < 1e-3);
    let (v_bad, _) = run(Integrator::Explicit, 3.1e-3, 0.3);
    assert!((v_bad - va).abs() / va > 1.0);
    let (drag, m, _) = stokes_sphere();
    assert!((explicit_stable_dt_s(m, drag.slope_n_s_m(0.0)) - 3e-3).abs() < 1e-15);
}

fn paste_ball(d: f64) -> (SphereDrag, f64, f64) {
    // f-EDEM Table 4 paste: τ_y = 136 Pa, η_B = 0.7 Pa s, ρ = 1843; steel 8135.
    let drag = SphereDrag::new(
        DragLaw::Bingham {
            yield_stress_pa: 136.0,
            plastic_viscosity_pa_s: 0.7,
        },
        d,
        1843.0,
    );
    let m = sphere_mass_kg(d, 8135.0);
    let wn = (m - sphere_mass_kg(d, 1843.0)) * 9.81;
    (drag, m, wn)
}

#[test]
fn a_ball_below_the_static_resistance_never_creeps() {
    // 2 mm steel ball: net weight 3.2e-4 N < static resistance 6.5e-3 N.
    let (drag, m, wn) = paste_ball(0.002);
    assert!(wn < drag.static_resistance_n());
    let w = Vector3::new(0.0, 0.0, -wn);
    for integ in [Integrator::Implicit, Integrator::Exponential] {
        for dt in [1e-7, 1e-4, 1e-1] {
            let s = advance(integ, &drag, m, &w, &Vector3::zeros(), dt);
            assert_eq!(s.velocity_m_s, Vector3::zeros());
            assert_eq!(s.displacement_m, Vector3::zeros());
            assert_eq!(s.motion, Motion::Stuck);
        }
    }
}

#[test]
fn a_moving_ball_stops_and_stays_stopped_without_chatter() {
    let (drag, m, wn) = paste_ball(0.0126);
    assert!(wn < drag.static_resistance_n());
    let w = Vector3::new(0.0, 0.0, -wn);
    for dt in [1e-5, 1e-3] {
        let mut v = Vector3::new(0.0, 0.0, -1.0);
        let mut stopped_at = None;
        for i in 0..(0.2 / dt) as usize {
            let s = advance(Integrator::Exponential, &drag, m, &w, &v, dt);
            v = s.velocity_m_s;
            if stopped_at.is_some() {
                assert_eq!(v, Vector3::zeros(), "restarted after stopping, dt {dt}");
                assert_eq!(s.displacement_m, Vector3::zeros());
            }
            assert!(v.z <= 0.0, "velocity reversed: chatter");
            if s.motion == Motion::Stuck && stopped_at.is_none() {
                stopped_at = Some(i);
            }
        }
        assert!(stopped_at.is_some());
    }
}

/// Independent reference: RK4 with a tiny step on the smooth (creeping-branch) Bingham law.
#[test]
fn exponential_matches_a_fine_rk4_reference_for_bingham_settling() {
    // Valentik & Whitmore suspension 1, d = 19 mm, ρ_p = 7290: stays below Re' = 1 for t < 0.01 s.
    let d = 0.019;
    let drag = SphereDrag::new(
        DragLaw::Bingham {
            yield_stress_pa: 30.5,
            plastic_viscosity_pa_s: 0.0131,
        },
        d,
        1280.0,
    );
    let m = sphere_mass_kg(d, 7290.0);
    let wn = (m - sphere_mass_kg(d, 1280.0)) * 9.81;
    let f = |s: f64| {
        (wn - if s > 0.0 {
            drag.force_n(s)
        } else {
            drag.static_resistance_n()
        }) / m
    };
    let (mut s, h) = (0.0f64, 1e-7);
    for _ in 0..100_000 {
        let k1 = f(s);
        let k2 = f(s + 0.5 * h * k1);
        let k3 = f(s + 0.5 * h * k2);
        let k4 = f(s + h * k3);
        s += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    let w = Vector3::new(0.0, 0.0, -wn);
    for dt in [1e-4f64, 1e-3, 1e-2] {
        let mut v = Vector3::zeros();
        for _ in 0..(0.01 / dt).round() as usize {
            v = advance(Integrator::Exponential, &drag, m, &w, &v, dt).velocity_m_s;
        }
        assert!((-v.z / s - 1.0).abs() < 1e-6, "dt {dt}: {} vs {s}", -v.z);
    }
}

#[test]
fn every_scheme_that_is_stable_ends_at_the_force_balance() {
    // Valentik & Whitmore suspension 3, d = 25.4 mm, ρ_p = 6123: ends above Re' = 150.
    let d = 0.0254;
    let drag = SphereDrag::new(
        DragLaw::Bingham {
            yield_stress_pa: 17.5,
            plastic_viscosity_pa_s: 0.0081,
        },
        d,
        1226.0,
    );
    let m = sphere_mass_kg(d, 6123.0);
    let wn = (m - sphere_mass_kg(d, 1226.0)) * 9.81;
    let vt = drag.balance_speed(wn).speed_m_s;
    assert!(vt > 1.0);
    let w = Vector3::new(0.0, 0.0, -wn);
    for integ in [Integrator::Implicit, Integrator::Exponential] {
        let mut v = Vector3::zeros();
        for _ in 0..20_000 {
            v = advance(integ, &drag, m, &w, &v, 1e-3).velocity_m_s;
        }
        assert!(
            (-v.z / vt - 1.0).abs() < 1e-9,
            "{integ:?}: {} vs {vt}",
            -v.z
        );
    }
}

/// The sedimentation cylinder's grains: diameters 1–100 µm (the samples span 2.5–70 µm),
/// quartz-like densities, water at 0.8–1.3 mPa s.
fn cylinder_grain(d: f64, rho_p: f64, mu: f64, eps: f64) -> (DallavalleGrain, SphereDrag) {
    let m = sphere_mass_kg(d, rho_p);
    let g = DallavalleGrain {
        diameter_m: d,
        fluid_density_kg_m3: 1000.0,
        viscosity_pa_s: mu,
        voidage: eps,
        ln_voidage: eps.ln(),
        mass_kg: m,
        body_force_n: -(m - sphere_mass_kg(d, 1000.0)) * 9.81,
    };
    let drag = SphereDrag::new(
        DragLaw::Dallavalle {
            viscosity_pa_s: mu,
            voidage: eps,
        },
        d,
        1000.0,
    );
    (g, drag)
}

const DIAMETERS: [f64; 6] = [1e-6, 2.5e-6, 8e-6, 20e-6, 70e-6, 1e-4];
const DENSITIES: [f64; 3] = [2500.0, 2650.0, 2700.0];
const VISCOSITIES: [f64; 3] = [0.8e-3, 1e-3, 1.3e-3];

/// The force of `dallavalle_di_felice_derivatives` is `SphereDrag::force_n`'s (ε^(1−χ) as an
/// exponential: 1e-14), its derivatives those of the force (central differences: 1e-7).
#[test]
fn dallavalle_derivatives_match_the_force() {
    use crate::fluid::newtonian::dallavalle_di_felice_derivatives as fd;
    for d in DIAMETERS {
        for eps in [0.3, 0.8, 0.95, 0.999, 1.0] {
            let (g, drag) = cylinder_grain(d, 2500.0, 1e-3, eps);
            for v in [1e-9, 1e-6, 1e-4, 1e-2, 0.3] {
                let (f, k, c) = fd(v, eps, eps.ln(), d, 1000.0, 1e-3);
                assert!(
                    (f / drag.force_n(v) - 1.0).abs() < 1e-14,
                    "F at d {d} ε {eps} v {v}"
                );
                let h = 1e-5 * v;
                let k_num = (drag.force_n(v + h) - drag.force_n(v - h)) / (2.0 * h);
                assert!((k / k_num - 1.0).abs() < 1e-7, "F' at d {d} ε {eps} v {v}");
                let c_num = (fd(v + h, eps, eps.ln(), d, 1000.0, 1e-3).1
                    - fd(v - h, eps, eps.ln(), d, 1000.0, 1e-3).1)
                    / (2.0 * h);
                assert!(
                    (c - c_num).abs() < 1e-6 * c.abs().max(k / v),
                    "F'' at d {d} ε {eps}"
                );
            }
            let _ = g;
        }
    }
}

/// The saturated branch of `phi12` is the general one bit for bit (e^z − 1 rounds to −1).
#[test]
fn phi12_saturated_branch_is_the_general_one() {
    let mut z = PHI_SATURATED;
    while z > -1e6 {
        let em1 = z.exp_m1();
        assert_eq!(em1, -1.0);
        assert_eq!(phi12(z), (em1 / z, (em1 - z) / (z * z)));
        z *= 1.013;
    }
}

/// Relative difference of two steps of `dt` from `v0` (velocity against the speeds involved,
/// displacement against the largest of them times dt: a step that turns the grain round has a
/// displacement near zero).
fn step_difference(a: (f64, f64), b: (f64, f64), v0: f64, dt: f64) -> f64 {
    let speed = a.0.abs().max(b.0.abs()).max(v0.abs());
    let dv = (a.0 - b.0).abs() / speed;
    let dx = (a.1 - b.1).abs() / a.1.abs().max(speed * dt);
    dv.max(dx)
}

/// The fast exponential step of the cylinder (`exponential_dallavalle_1d`, Newton with exact
/// derivatives) against `advance` over the cylinder's diameters, densities, viscosities,
/// voidages (0.3–1), starting speeds (rest, half, near and at terminal, twice terminal) and
/// steps (0.1 ms – 10 s): within 1e-11 relative where dt is over 40 relaxation times (λdt ≥ 40,
/// nearly every step of the cylinder: the measured worst is 4e-12), 1e-9 otherwise (there `advance`'s central-difference
/// slope, accurate to 1e-10, matters to first order). And the tabulated step near terminal
/// (`terminal::exponential_near_terminal`) against both, wherever it applies (voidage
/// 0.8–1): within 1e-12 relative; its terminal speed within 1e-14 of the full solve.
#[test]
fn exponential_dallavalle_matches_advance() {
    use super::terminal::{exponential_near_terminal, terminal_state, TerminalTable};
    let mut worst = (0.0f64, 0.0f64, 0.0f64);
    let mut near = 0;
    let mut upwards = 0.0f64;
    for d in DIAMETERS {
        for rho_p in DENSITIES {
            for mu in VISCOSITIES {
                let table = TerminalTable::new(&cylinder_grain(d, rho_p, mu, 1.0).0);
                for eps in [0.3, 0.5, 0.8, 0.81, 0.9, 0.95, 0.975, 0.99, 0.999, 1.0] {
                    let (g, drag) = cylinder_grain(d, rho_p, mu, eps);
                    let (ut, _, _) = terminal_state(&g);
                    if let Some((tu, _, _)) = table.at(eps) {
                        worst.2 = worst.2.max((tu / ut - 1.0).abs());
                    }
                    let w = SVector::<f64, 1>::new(g.body_force_n);
                    for v0 in [
                        0.0,
                        0.5 * ut,
                        -0.5 * ut,
                        -ut * (1.0 - 1e-3),
                        -ut * (1.0 + 1e-5),
                        -ut,
                        -2.0 * ut,
                    ] {
                        for dt in [1e-4, 1e-2, 0.2, 10.0] {
                            let exact = advance(
                                Integrator::Exponential,
                                &drag,
                                g.mass_kg,
                                &w,
                                &SVector::<f64, 1>::new(v0),
                                dt,
                            );
                            let e = (exact.velocity_m_s[0], exact.displacement_m[0]);
                            let fast = exponential_dallavalle_1d(&g, v0, dt).expect("moving");
                            let sd = step_difference(e, fast, v0, dt);
                            let stiff = exact.drag_slope_n_s_m * dt / g.mass_kg;
                            if v0 > 0.0 || stiff < -PHI_SATURATED {
                                upwards = upwards.max(sd);
                            } else {
                                worst.0 = worst.0.max(sd);
                            }
                            if let Some(t) = exponential_near_terminal(&table, &g, v0, dt) {
                                near += 1;
                                worst.1 = worst.1.max(step_difference(e, t, v0, dt));
                            }
                        }
                    }
                }
            }
        }
    }
    assert!(worst.0 < 1e-11, "Newton step: {:e}", worst.0);
    // Within a few relaxation times (λdt < 40), or for a grain thrown upwards (it turns round
    // within the step), the result depends on the slope k to first order, and `advance`'s
    // central difference is accurate to 1e-10 only.
    eprintln!(
        "Newton step: {:e} (λdt ≥ 40), {upwards:e} (else); tabulated step {:e} ({near} steps), \
         terminal speed {:e}",
        worst.0, worst.1, worst.2
    );
    assert!(upwards < 1e-9, "Newton step, transient: {upwards:e}");
    assert!(worst.1 < 1e-12, "tabulated step: {:e}", worst.1);
    assert!(worst.2 < 1e-14, "tabulated terminal speed: {:e}", worst.2);
    assert!(near > 500, "the tabulated step applied {near} times");
}

/// The tabulated step of several spheres at once (`terminal::exponential_near_terminal_lanes`,
/// what the cylinder's free update calls) gives each lane the one-sphere step bit for bit,
/// whatever its neighbours: lanes mixing diameters, voidages inside and outside the table,
/// spheres at, near and far from terminal settling and thrown upwards (those lanes must give
/// None, as one sphere alone does).
#[test]
fn tabulated_step_lanes_match_one_sphere_bit_for_bit() {
    use super::terminal::{
        exponential_near_terminal, exponential_near_terminal_lanes, TerminalTable,
    };
    let mut cases = Vec::new();
    for (k, (d, rho_p)) in DIAMETERS
        .iter()
        .flat_map(|d| DENSITIES.iter().map(move |r| (*d, *r)))
        .enumerate()
    {
        let table = TerminalTable::new(&cylinder_grain(d, rho_p, VISCOSITIES[0], 1.0).0);
        for (j, eps) in [0.5, 0.8, 0.83, 0.97, 1.0].into_iter().enumerate() {
            let (g, _) = cylinder_grain(d, rho_p, VISCOSITIES[0], eps);
            let ut = super::terminal::terminal_state(&g).0;
            let v0 = [-ut, -ut * (1.0 + 1e-6), -0.5 * ut, 0.3 * ut, 0.0][(j + k) % 5];
            cases.push((table.clone(), g, v0));
        }
    }
    const L: usize = 16;
    let (mut some, mut none) = (0, 0);
    for dt in [1e-3, 0.5, 10.0] {
        for group in cases.chunks(L).filter(|c| c.len() == L) {
            let lanes = exponential_near_terminal_lanes::<L>(
                std::array::from_fn(|l| &group[l].0),
                std::array::from_fn(|l| group[l].1.voidage),
                std::array::from_fn(|l| dt / group[l].1.mass_kg),
                std::array::from_fn(|l| group[l].1.body_force_n),
                std::array::from_fn(|l| group[l].2),
                dt,
            );
            for (l, (table, g, v0)) in group.iter().enumerate() {
                let one = exponential_near_terminal(table, g, *v0, dt);
                let bits = |x: Option<(f64, f64)>| x.map(|(a, b)| (a.to_bits(), b.to_bits()));
                assert_eq!(bits(lanes[l]), bits(one), "lane {l}, dt {dt}");
                if one.is_some() {
                    some += 1;
                } else {
                    none += 1;
                }
            }
        }
    }
    assert!(some > 50 && none > 50, "{some} steps, {none} refusals");
}

/// The tabulated step of several spheres of one kind at once, where its φ factors are
/// saturated (`terminal::exponential_near_terminal_kind_saturated`, what the cylinder's free
/// update calls on a run of grains of one kind): every lane it takes gives the one-sphere step
/// bit for bit, and every lane it leaves is one where the one-sphere step refuses (None) or is
/// not saturated (it takes those lanes then); lanes at voidages inside and outside the table,
/// at, near and far from terminal settling and thrown upwards; and so do its builds for AVX2
/// and AVX-512 where the processor has them (the free update picks one at run time: nothing
/// may depend on the vector width); and so does the step from what each lane reads of its
/// voidage (`terminal::kind_at_voidage`, the free update's table per cell and kind).
#[test]
fn tabulated_step_of_one_kind_matches_one_sphere_bit_for_bit_on_every_vector_width() {
    use super::terminal::{
        exponential_near_terminal, exponential_near_terminal_kind_at,
        exponential_near_terminal_kind_saturated, kind_at_voidage, SaturatedSteps, TerminalTable,
    };
    use super::PHI_SATURATED;
    const L: usize = 16;
    type Kind = fn(&TerminalTable, [f64; L], f64, [f64; L], f64) -> SaturatedSteps<L>;
    let at = |t: &TerminalTable, e: [f64; L], k: f64, v: [f64; L], dt: f64| {
        // Each lane's reading computed alone (the free update computes 8 cells at a time).
        let rows = e.map(|e| kind_at_voidage::<1>(t, [e], k));
        let read = std::array::from_fn(|i| std::array::from_fn(|l| rows[l][i][0]));
        exponential_near_terminal_kind_at::<L>(t, read, k, v, dt)
    };
    let mut builds: Vec<(&str, Kind)> = vec![
        ("baseline", exponential_near_terminal_kind_saturated::<L>),
        ("per-cell table", at),
    ];
    #[cfg(target_arch = "x86_64")]
    {
        #[target_feature(enable = "avx2")]
        fn avx2(t: &TerminalTable, e: [f64; L], k: f64, v: [f64; L], dt: f64) -> SaturatedSteps<L> {
            exponential_near_terminal_kind_saturated::<L>(t, e, k, v, dt)
        }
        #[target_feature(enable = "avx512f")]
        fn avx512(
            t: &TerminalTable,
            e: [f64; L],
            k: f64,
            v: [f64; L],
            dt: f64,
        ) -> SaturatedSteps<L> {
            exponential_near_terminal_kind_saturated::<L>(t, e, k, v, dt)
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2.
            builds.push(("avx2", |t, e, k, v, dt| unsafe { avx2(t, e, k, v, dt) }));
        }
        if std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the processor has AVX-512F.
            builds.push(("avx512", |t, e, k, v, dt| unsafe { avx512(t, e, k, v, dt) }));
        }
    }
    let (mut taken, mut left) = (0, 0);
    for (d, rho_p) in DIAMETERS
        .iter()
        .flat_map(|d| DENSITIES.iter().map(move |r| (*d, *r)))
    {
        let table = TerminalTable::new(&cylinder_grain(d, rho_p, VISCOSITIES[0], 1.0).0);
        let eps: [f64; L] = std::array::from_fn(|l| [0.5, 0.8, 0.83, 0.9, 0.97, 0.999, 1.0][l % 7]);
        let grains = eps.map(|e| cylinder_grain(d, rho_p, VISCOSITIES[0], e).0);
        let v0: [f64; L] = std::array::from_fn(|l| {
            let ut = super::terminal::terminal_state(&grains[l]).0;
            [-ut, -ut * (1.0 + 1e-6), -0.5 * ut, 0.3 * ut, 0.0][l % 5]
        });
        for dt in [1e-5, 1e-3, 0.5, 10.0] {
            for (name, build) in &builds {
                let lanes = build(&table, eps, dt / grains[0].mass_kg, v0, dt);
                for l in 0..L {
                    let one = exponential_near_terminal(&table, &grains[l], v0[l], dt);
                    let bits = |(a, b): (f64, f64)| (a.to_bits(), b.to_bits());
                    if lanes.ok[l] {
                        let got = (lanes.velocity_m_s[l], lanes.displacement_m[l]);
                        assert_eq!(Some(bits(got)), one.map(bits), "{name}, lane {l}, dt {dt}");
                        taken += 1;
                    } else {
                        // Refused, or the step of an unsaturated lane: λdt = k dt/m small.
                        let k = super::terminal::terminal_state(&grains[l]).1;
                        let saturated = -k * dt / grains[l].mass_kg < PHI_SATURATED;
                        assert!(one.is_none() || !saturated, "{name}, lane {l}, dt {dt}");
                        left += 1;
                    }
                }
            }
        }
    }
    assert!(taken > 50 && left > 50, "{taken} taken, {left} left");
}
