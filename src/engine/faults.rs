//! Faults of a Rapier step: the checks a body's state must pass after each step (the fault
//! scan), the refusal of a step whose free-flight force Rapier's speed cap would clip, and the
//! [`Unstable`] report with the step that should cure it. Pure functions, SI units.
//!
//! Rapier silently caps every substep's speed at the settings' `max_linear_velocity_m_s` and
//! quarantines non-finite bodies (a blow-up can look like a frozen body), so the engine looks for
//! itself: non-finite state, speeds above half the cap, bodies leaving the domain, overlaps beyond
//! a fraction of the diameter.

use super::body_id::BodyId;
use crate::dynamics::{self, DtBasis, Integrator, Unstable};
use crate::fluid::SphereDrag;
use nalgebra::SVector;

/// What went wrong with a body: the quantity (`"position"`, `"speed"`, …) and its value (SI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fault {
    /// The quantity at fault, as printed in the [`Unstable`] report.
    pub quantity: &'static str,
    /// Its value (m, m/s; NaN when it has none, e.g. a quarantined body).
    pub value: f64,
}

/// The bounds the fault scan checks a body against (from the world's
/// [`super::EngineSettings`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaultLimits {
    /// Rapier's speed cap, m/s: a body above half of it is at fault.
    pub speed_cap_m_s: f64,
    /// Largest distance of a body's centre from the origin, m (None: no bound).
    pub max_distance_m: Option<f64>,
    /// Overlap beyond which a contact is at fault, as a fraction of the body's diameter (0: no
    /// check).
    pub max_penetration_fraction: f64,
}

/// The fault scan of one body after a step, in this order: quarantined by Rapier
/// (`quarantined`), non-finite position, non-finite speed, speed above half the cap, centre
/// beyond `max_distance_m` from the origin, deepest contact overlap (`deepest_overlap_m`, called
/// only when the penetration check is on) beyond `max_penetration_fraction` × `diameter_m`.
/// None when the body passes.
pub fn scan<const D: usize>(
    position_m: &SVector<f64, D>,
    velocity_m_s: &SVector<f64, D>,
    diameter_m: f64,
    quarantined: bool,
    limits: &FaultLimits,
    deepest_overlap_m: impl FnOnce() -> f64,
) -> Option<Fault> {
    let x = position_m;
    let speed = velocity_m_s.norm();
    let (quantity, value) = if quarantined {
        ("quarantined", f64::NAN)
    } else if !x.iter().all(|c| c.is_finite()) {
        ("position", x.norm())
    } else if !speed.is_finite() {
        ("velocity", speed)
    } else if speed > 0.5 * limits.speed_cap_m_s {
        ("speed", speed)
    } else if limits.max_distance_m.is_some_and(|r| x.norm() > r) {
        ("distance from the origin (outside the domain), m", x.norm())
    } else {
        let frac = limits.max_penetration_fraction;
        let depth = if frac > 0.0 { deepest_overlap_m() } else { 0.0 };
        if frac > 0.0 && depth > frac * diameter_m {
            ("penetration depth, m", depth)
        } else {
            return None;
        }
    };
    Some(Fault { quantity, value })
}

/// The refusal of a free-flight step: the speed `v₀ + a dt` its substeps would reach
/// (`substep_velocity_m_s`) is NaN or not below Rapier's cap `speed_cap_m_s`, which would clip
/// it. None when the step may be taken.
pub fn intermediate_speed<const D: usize>(
    substep_velocity_m_s: &SVector<f64, D>,
    speed_cap_m_s: f64,
) -> Option<Fault> {
    let speed = substep_velocity_m_s.norm();
    (speed.is_nan() || speed >= speed_cap_m_s).then_some(Fault {
        quantity: "intermediate speed",
        value: speed,
    })
}

/// The step suggested to a body at fault, s: half the step `dt_s`, and for the explicit
/// integrator at most half its stability limit 2m/(dF/dv) at the body's speed `speed_m_s` (taken
/// as 0 when not finite).
pub fn suggested_dt_s(
    integrator: Integrator,
    mass_kg: f64,
    drag: &SphereDrag,
    speed_m_s: f64,
    dt_s: f64,
) -> f64 {
    let half = 0.5 * dt_s;
    match integrator {
        Integrator::Explicit => {
            let s = if speed_m_s.is_finite() {
                speed_m_s
            } else {
                0.0
            };
            half.min(0.5 * dynamics::explicit_stable_dt_s(mass_kg, drag.slope_n_s_m(s)))
        }
        _ => half,
    }
}

/// Builds the run-wide [`Unstable`] report for body `index` of a world: `quantity` is what went
/// wrong (`"position"` or `"velocity"` non-finite, `"quarantined"` when Rapier disabled the body,
/// `"speed"` above half the speed cap, `"intermediate speed"` when the free-flight force would
/// exceed the cap and the step was refused, `"penetration"` for an overlap beyond
/// [`super::EngineSettings::max_penetration_fraction`], `"distance from the origin"` beyond
/// [`super::EngineSettings::max_distance_m`]), `value` its value, `suggested_dt_s` a step that
/// should cure it (half the current dt, and for the explicit integrator at most half its stability
/// limit). The advice is the explicit integrator's ([`DtBasis::ExplicitDrag`]) when the suggested
/// step is below half the current one, else [`DtBasis::Halved`].
pub(crate) fn unstable(
    index: usize,
    time_s: f64,
    dt_s: f64,
    quantity: &str,
    value: f64,
    suggested_dt_s: f64,
) -> Unstable {
    // The explicit integrator's drag limit, when below half the step, is the binding one.
    let dt_basis = if suggested_dt_s < 0.5 * dt_s * (1.0 - 1e-12) {
        DtBasis::ExplicitDrag
    } else {
        DtBasis::Halved
    };
    Unstable {
        body: BodyId(index).to_string(),
        time_s,
        step: (time_s / dt_s).round() as u64,
        what: format!("{quantity} = {value:.3e}"),
        dt_s,
        stable_dt_s: suggested_dt_s,
        dt_basis,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::DragLaw;
    use nalgebra::{Vector2, Vector3};

    const LIMITS: FaultLimits = FaultLimits {
        speed_cap_m_s: 10.0,
        max_distance_m: Some(1.0),
        max_penetration_fraction: 0.25,
    };

    fn quantity(x: Vector3<f64>, v: Vector3<f64>, q: bool, depth: f64) -> Option<&'static str> {
        scan(&x, &v, 0.01, q, &LIMITS, || depth).map(|f| f.quantity)
    }

    #[test]
    fn scan_order_and_bounds() {
        let (x, v) = (Vector3::new(0.1, 0.0, 0.2), Vector3::new(0.0, 0.0, -1.0));
        assert_eq!(quantity(x, v, false, 0.0), None);
        assert_eq!(quantity(x, v, true, 0.0), Some("quarantined"));
        let nan = Vector3::new(f64::NAN, 0.0, 0.0);
        assert_eq!(quantity(nan, nan, false, 0.0), Some("position"));
        assert_eq!(quantity(x, nan, false, 0.0), Some("velocity"));
        // Half the cap (5 m/s) is allowed, above it is not.
        assert_eq!(quantity(x, Vector3::new(0.0, 5.0, 0.0), false, 0.0), None);
        assert_eq!(
            quantity(x, Vector3::new(0.0, 5.01, 0.0), false, 0.0),
            Some("speed")
        );
        assert_eq!(
            quantity(Vector3::new(0.0, 0.8, 0.61), v, false, 0.0),
            Some("distance from the origin (outside the domain), m")
        );
        // Overlap bound 0.25 × 0.01 m.
        assert_eq!(quantity(x, v, false, 0.0025), None);
        let f = scan(&x, &v, 0.01, false, &LIMITS, || 0.003).unwrap();
        assert_eq!((f.quantity, f.value), ("penetration depth, m", 0.003));
        // With the check off, the overlap is not even computed.
        let off = FaultLimits {
            max_penetration_fraction: 0.0,
            max_distance_m: None,
            ..LIMITS
        };
        let far = Vector2::new(1e3, 0.0);
        assert_eq!(
            scan(&far, &Vector2::zeros(), 0.01, false, &off, || panic!(
                "computed"
            )),
            None
        );
    }

    #[test]
    fn intermediate_speed_at_the_cap() {
        assert_eq!(intermediate_speed(&Vector2::new(3.0, 4.0), 5.1), None);
        let f = intermediate_speed(&Vector2::new(3.0, 4.0), 5.0).unwrap();
        assert_eq!((f.quantity, f.value), ("intermediate speed", 5.0));
        assert!(intermediate_speed(&Vector2::new(f64::NAN, 0.0), 5.0).is_some());
    }

    #[test]
    fn suggested_step_and_advice() {
        // Stokes, k = 3π η d = 3π × 1e-3 × 1e-4; m = 1e-9 kg: 2m/k = 2.122e-3 s.
        let drag = SphereDrag::new(
            DragLaw::Stokes {
                viscosity_pa_s: 1e-3,
            },
            1e-4,
            1000.0,
        );
        let k = 3.0 * std::f64::consts::PI * 1e-7;
        let m = 1e-9;
        let limit = 2.0 * m / k;
        let s = suggested_dt_s(Integrator::Explicit, m, &drag, 1.0, 1e-2);
        assert!((s - 0.5 * limit).abs() < 1e-15, "{s}");
        assert_eq!(
            suggested_dt_s(Integrator::Explicit, m, &drag, f64::NAN, 1e-4),
            5e-5
        );
        assert_eq!(
            suggested_dt_s(Integrator::Exponential, m, &drag, 1.0, 1e-2),
            5e-3
        );
        let u = unstable(3, 0.25, 1e-2, "speed", 7.0, s);
        assert_eq!(
            (u.body.as_str(), u.step, u.dt_basis),
            ("body 3", 25, DtBasis::ExplicitDrag)
        );
        assert_eq!(u.what, "speed = 7.000e0");
        assert_eq!(
            unstable(0, 0.0, 1e-2, "speed", 7.0, 5e-3).dt_basis,
            DtBasis::Halved
        );
    }
}
