//! Immersion of a sphere crossing a free surface: which fractions of its volume and of its
//! projected area lie in the fluid, and so how much of its buoyancy and drag acts.
//!
//! With the sphere's centre at depth `z` below the surface (negative above) and radius `r`, the
//! immersed height of the sphere is `h = clamp(z + r, 0, d)`. Two models:
//! - [`Submergence::Full`] (f-EDEM): buoyancy and drag act in full as soon as the sphere's lowest
//!   point touches the surface (`z + r ≥ 0`), not at all before;
//! - [`Submergence::Partial`]: the buoyancy of the immersed spherical cap,
//!   `V_cap/V = h² (3r − h)/(4 r³)` (from `V_cap = π h² (3r − h)/3`, `V = 4π r³/3`), and the drag
//!   scaled by the immersed fraction of the projected area, `π (2 r h − h²)/(π r²)` while `h < r`
//!   and 1 once the equator is under.
//!
//! Pure functions, SI units.

use serde::{Deserialize, Serialize};

/// How fluid forces act on a sphere crossing the free surface.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "lowercase")]
pub enum Submergence {
    /// f-EDEM: the whole buoyancy and drag act from the moment the sphere's lowest point
    /// touches the surface.
    #[default]
    Full,
    /// Buoyancy on the immersed spherical cap's volume, drag scaled by the immersed fraction of
    /// the projected area, while the sphere crosses the surface.
    Partial,
}

/// Immersed fractions (volume, projected area), both in [0, 1], of a sphere of diameter `d_m`
/// whose centre is `depth_m` below the free surface (negative above). `full`: both 1 as soon as
/// the lowest point touches the surface (f-EDEM); `partial`: the spherical cap below the surface,
/// V_cap = π h² (3r − h)/3, and its projected area π (2 r h − h²) while h < r.
pub fn immersion(depth_m: f64, d_m: f64, submergence: Submergence) -> (f64, f64) {
    let r = 0.5 * d_m;
    let h = (depth_m + r).clamp(0.0, d_m);
    match submergence {
        Submergence::Full => {
            if depth_m + r >= 0.0 {
                (1.0, 1.0)
            } else {
                (0.0, 0.0)
            }
        }
        Submergence::Partial => {
            let vol = h * h * (3.0 * r - h) / (4.0 * r * r * r);
            let area = if h >= r {
                1.0
            } else {
                h * (2.0 * r - h) / (r * r)
            };
            (vol, area)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const D: f64 = 0.01;

    #[test]
    fn full_switches_when_the_lowest_point_touches() {
        assert_eq!(immersion(-0.5 * D - 1e-9, D, Submergence::Full), (0.0, 0.0));
        assert_eq!(immersion(-0.5 * D, D, Submergence::Full), (1.0, 1.0));
        assert_eq!(immersion(3.0 * D, D, Submergence::Full), (1.0, 1.0));
    }

    #[test]
    fn partial_is_the_spherical_cap() {
        let r = 0.5 * D;
        // Above the surface, and fully under.
        assert_eq!(immersion(-r - 1e-6, D, Submergence::Partial), (0.0, 0.0));
        let (v, a) = immersion(r + 1e-6, D, Submergence::Partial);
        assert!((v - 1.0).abs() < 1e-15 && a == 1.0, "{v} {a}");
        // Centre on the surface: half the volume, the whole projected area (the equator).
        let (v, a) = immersion(0.0, D, Submergence::Partial);
        assert!((v - 0.5).abs() < 1e-15 && a == 1.0, "{v} {a}");
        // A quarter of the diameter under (h = r/2): cap volume π h² (3r − h)/3 over 4π r³/3,
        // projected area π (2rh − h²) over π r², computed from the formulas directly.
        let h = 0.5 * r;
        let pi = std::f64::consts::PI;
        let vol = (pi * h * h * (3.0 * r - h) / 3.0) / (4.0 * pi * r.powi(3) / 3.0);
        let area = pi * (2.0 * r * h - h * h) / (pi * r * r);
        let (v, a) = immersion(h - r, D, Submergence::Partial);
        assert!(
            (v - vol).abs() < 1e-14 && (vol - 5.0 / 32.0).abs() < 1e-14,
            "{v}"
        );
        assert!(
            (a - area).abs() < 1e-14 && (area - 0.75).abs() < 1e-14,
            "{a}"
        );
    }

    #[test]
    fn submergence_names_are_lowercase() {
        #[derive(Deserialize)]
        struct T {
            s: Submergence,
        }
        let t: T = toml::from_str("s = \"partial\"").unwrap();
        assert_eq!(t.s, Submergence::Partial);
    }
}
