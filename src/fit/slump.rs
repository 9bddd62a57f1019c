//! `settle fit slump`: the yield stress of a paste from cylinder slump tests (Pashias & Boger
//! 1996; f-EDEM Appendix I, eqs. A1–A3), solved by [`crate::fluid::slump::yield_stress_pa`].

use crate::error::Error;
use crate::io::fmt::{g as fmt, short};
use std::path::Path;

/// One slump test: its slump and the yield stress it gives.
#[derive(Clone, Debug, PartialEq)]
pub struct SlumpTest {
    /// The slump S, mm.
    pub slump_mm: f64,
    /// The dimensionless slump S′ = S/H (eq. A2).
    pub relative_slump: f64,
    /// The yield stress τ_y, Pa (eqs. A1, A3).
    pub yield_stress_pa: f64,
}

/// The yield stresses of slump tests of one paste, as `settle fit slump` prints them.
#[derive(Clone, Debug, PartialEq)]
pub struct Slump {
    /// The mould's height H, mm.
    pub height_mm: f64,
    /// The paste's density ρ, kg/m³.
    pub density_kg_m3: f64,
    /// The gravitational acceleration, m/s².
    pub g_m_s2: f64,
    /// Each test, in the order given.
    pub tests: Vec<SlumpTest>,
    /// The mean yield stress of the tests, Pa.
    pub mean_yield_stress_pa: f64,
    /// Doubtful values (a mould or a density outside the usual ranges), also in `lines` as
    /// `warning: …`.
    pub warnings: Vec<String>,
    /// The lines `settle fit slump` prints.
    pub lines: Vec<String>,
}

/// The tallest standard slump mould, mm: the Abrams cone of ASTM C143 (300 mm high, 100 mm top
/// and 200 mm base diameters). A taller mould is warned.
pub const CONE_HEIGHT_MM: f64 = 300.0;

/// The smallest slump mould in use, mm: the mini-slump cone of Kantro (1980) for cement pastes
/// (57 mm high). A smaller mould is warned; under 1 mm it is a height in metres, refused.
pub const MINI_CONE_HEIGHT_MM: f64 = 57.0;

/// A paste's density that is not doubtful, kg/m³: more than water's (1000, the liquid of the
/// paste) and less than its solids' (mineral solids 2650 for quartz, cement 3150). Outside,
/// warned; under 100 kg/m³ it is a density in t/m³ (g/cm³), refused.
pub const PASTE_DENSITY_KG_M3: (f64, f64) = (1000.0, 3150.0);

/// The clear unit mistakes of `settle fit slump`, refused naming the value, the likely unit
/// and the fix; and the doubtful values, returned as warnings.
fn plausible(height_mm: f64, slumps_mm: &[f64], density: f64) -> Result<Vec<String>, Error> {
    let refuse =
        |option: &str, v: f64, m: String| Err(Error::bad_argument(option, Path::new(&short(v)), m));
    if density > 0.0 && density < 100.0 {
        return refuse(
            "--density",
            density,
            format!(
                "a paste of {} kg/m³ is far lighter than water (1000 kg/m³): the density looks like \
                 t/m³ (g/cm³); fix: give kg/m³, --density {}",
                short(density),
                short(density * 1000.0)
            ),
        );
    }
    if height_mm > 0.0 && height_mm < 1.0 {
        return refuse(
            "--height-mm",
            height_mm,
            format!(
                "a mould {} mm high: the height looks like metres; fix: give millimetres, \
                 --height-mm {}",
                short(height_mm),
                short(height_mm * 1000.0)
            ),
        );
    }
    if height_mm >= MINI_CONE_HEIGHT_MM && slumps_mm.iter().all(|s| *s > 0.0 && *s < 1.0) {
        return refuse(
            "--slump-mm",
            slumps_mm[0],
            format!(
                "slumps under 1 mm from a {} mm mould: the slumps look like metres; fix: give \
                 millimetres, --slump-mm {}",
                short(height_mm),
                slumps_mm
                    .iter()
                    .map(|s| short(s * 1000.0))
                    .collect::<Vec<_>>()
                    .join(",")
            ),
        );
    }
    let mut w = Vec::new();
    if height_mm > CONE_HEIGHT_MM {
        w.push(format!(
            "--height-mm {}: taller than the ASTM C143 cone (300 mm), the tallest standard \
             mould: check the unit",
            short(height_mm)
        ));
    } else if height_mm > 0.0 && height_mm < MINI_CONE_HEIGHT_MM {
        w.push(format!(
            "--height-mm {}: smaller than the mini-slump cone (57 mm), the smallest mould in \
             use: in centimetres? {} mm",
            short(height_mm),
            short(height_mm * 10.0)
        ));
    }
    let (d0, d1) = PASTE_DENSITY_KG_M3;
    if density >= 100.0 && !(d0..=d1).contains(&density) {
        w.push(format!(
            "--density {}: outside 1000–3150 kg/m³ (water to cement, the densest common \
             solid of a paste): check it",
            short(density)
        ));
    }
    Ok(w)
}

/// `settle fit slump` in memory: τ_y of each slump (mm) of a mould `height_mm` high, for a
/// paste of `density` kg/m³ under `g` m/s² (the command line's default:
/// [`crate::fluid::slump::G_M_S2`]), and their mean. A slump outside 0 < S < H (or a height,
/// density or g ≤ 0, or no slump) is bad input naming `--slump-mm` and the value, the command
/// line's message.
///
/// ```
/// let s = settle::fit::slump(152.0, &[102.0, 103.0, 100.0], 1843.0, 9.81)?;
/// assert!((s.mean_yield_stress_pa - 138.0).abs() < 0.05); // f-EDEM Table A1, recomputed
/// # Ok::<(), settle::Error>(())
/// ```
pub fn slump(height_mm: f64, slumps_mm: &[f64], density: f64, g: f64) -> Result<Slump, Error> {
    if slumps_mm.is_empty() {
        return Err(Error::bad_argument(
            "--slump-mm",
            Path::new(""),
            "no slump given: allowed one or more slumps 0 < S < height, mm",
        ));
    }
    for (option, v, unit) in [
        ("--height-mm", height_mm, "mm"),
        ("--density", density, "kg/m³"),
        ("--g", g, "m/s²"),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(Error::bad_argument(
                option,
                Path::new(&short(v)),
                format!("out of range: allowed > 0 {unit}"),
            ));
        }
    }
    let warnings = plausible(height_mm, slumps_mm, density)?;
    let mut tests = Vec::new();
    let mut lines = Vec::new();
    for s in slumps_mm {
        let t = crate::fluid::slump::yield_stress_pa(height_mm * 1e-3, s * 1e-3, density, g)
            .ok_or_else(|| {
                Error::bad_argument(
                    "--slump-mm",
                    Path::new(&short(*s)),
                    format!(
                        "out of range: allowed 0 < slump < height ({} mm), with height, \
                         density and g > 0",
                        short(height_mm)
                    ),
                )
            })?;
        lines.push(format!(
            "H = {} mm, S = {} mm, rho = {} kg/m3: S' = {}, tau_y = {} Pa",
            short(height_mm),
            short(*s),
            short(density),
            fmt(s / height_mm),
            fmt(t)
        ));
        tests.push(SlumpTest {
            slump_mm: *s,
            relative_slump: s / height_mm,
            yield_stress_pa: t,
        });
    }
    let mean = tests.iter().map(|t| t.yield_stress_pa).sum::<f64>() / tests.len() as f64;
    lines.push(format!(
        "mean tau_y = {} Pa over {} slumps (eqs. A1-A3, Pashias & Boger 1996)",
        fmt(mean),
        tests.len()
    ));
    lines.extend(warnings.iter().map(|w| format!("warning: {w}")));
    Ok(Slump {
        warnings,
        height_mm,
        density_kg_m3: density,
        g_m_s2: g,
        tests,
        mean_yield_stress_pa: mean,
        lines,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f-EDEM Table A1 recomputed (136.6, 132.7, 144.6 Pa; mean 138.0), as the command line
    /// prints it; a slump of the mould's height is bad input naming it.
    #[test]
    fn table_a1() {
        let s = slump(152.0, &[102.0, 103.0, 100.0], 1843.0, 9.81).unwrap();
        let t: Vec<f64> = s.tests.iter().map(|t| t.yield_stress_pa).collect();
        for (got, want) in t.iter().zip([136.6, 132.7, 144.6]) {
            assert!((got - want).abs() < 0.05, "{got} vs {want}");
        }
        assert!((s.tests[0].relative_slump - 102.0 / 152.0).abs() < 1e-15);
        assert_eq!(s.mean_yield_stress_pa, (t[0] + t[1] + t[2]) / 3.0);
        assert!(
            s.lines[0].ends_with("S' = 0.6711, tau_y = 136.6 Pa"),
            "{:?}",
            s.lines
        );
        assert!(s.lines[3].starts_with("mean tau_y = 138.0 Pa over 3 slumps"));
        let e = slump(152.0, &[100.0, 152.0], 1843.0, 9.81).unwrap_err();
        let m = e.to_string();
        assert!(m.starts_with("152: key `--slump-mm`: out of range"), "{m}");
        assert!(slump(152.0, &[], 1843.0, 9.81).is_err());
    }
}
