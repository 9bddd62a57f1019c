//! The test's figures of a readings file, instrument by instrument (`# instrument = hydrometer |
//! pipette | buoyancy-sphere`, default hydrometer), and the rules its rows are checked by.
//! Figures of another instrument are refused, so that a file never silently means something
//! else than its author thought.

use super::figures::{
    bad, d7928_keys, figure, keys_of, kinds, required, Parsed, ReduceOptions, HYDROMETER, PIPETTE,
    SPHERE,
};
use crate::error::Error;
use crate::instruments::reduction::d7928::MeasuredHydrometer;
use crate::instruments::reduction::{
    water_density_kg_m3, HydrometerType, Instrument, ModelFigures, PipetteRegion, Standard,
    TestSetup,
};
use crate::io::fmt::{num, sig_trim};
use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::path::Path;

/// The instruments a readings file may name.
const INSTRUMENTS: &str = "hydrometer, pipette, buoyancy-sphere";
/// The section of ASTM D422's cylinder, cm² (the column height's default section).
const DEFAULT_CYLINDER_AREA_CM2: f64 = 27.8;

/// How the rows of a readings file are checked.
pub(super) struct RowRules {
    /// The reading column.
    pub reading: &'static str,
    /// Its allowed range, and the text saying so.
    pub range: (f64, f64),
    /// The allowed range as text (with its unit).
    pub allowed: String,
    /// Temperature range, °C, and its text.
    pub temperature_range: (f64, f64),
    /// The temperature range as text.
    pub temperature_text: String,
    /// The figure `temperature_c`, if given.
    pub temperature_figure: Option<f64>,
    /// The figure `blank_reading`, if given.
    pub blank_figure: Option<f64>,
    /// Whether a blank is required (hydrometer), optional with 0 as default (pipette) or
    /// refused (sphere: None).
    pub blank: Option<BlankRule>,
    /// Range of a blank reading in its column, and its text.
    pub blank_range: (f64, f64),
    /// The blank's range as text.
    pub blank_allowed: String,
}

/// Whether an instrument needs a blank reading.
#[derive(Clone, Copy, PartialEq)]
pub(super) enum BlankRule {
    /// The hydrometer: a `blank_reading` column or figure is required.
    Required,
    /// The pipette: 0 unless given.
    ZeroUnlessGiven,
}

impl RowRules {
    /// Columns the instrument may have besides the time and its reading.
    pub fn optional_columns(&self) -> Vec<&'static str> {
        let mut c = vec!["temperature_c"];
        if self.blank.is_some() {
            c.push("blank_reading");
        }
        c
    }

    /// Checks the temperature and blank columns against their figures; returns the constant
    /// temperature and blank (None: read from the column).
    pub fn check_columns(
        &self,
        file: &Path,
        at: &BTreeMap<&'static str, usize>,
    ) -> Result<(Option<f64>, Option<f64>), Error> {
        let temperature = match (self.temperature_figure, at.contains_key("temperature_c")) {
            (Some(_), true) => {
                return Err(Error::bad_input(
                    file,
                    Some("temperature_c"),
                    "given both as a column and as a `# temperature_c` line: keep one",
                ))
            }
            (None, false) => {
                return Err(bad(
                    file,
                    "header: missing column `temperature_c` (or give the line \
                     `# temperature_c = …` if the temperature was constant)"
                        .into(),
                ))
            }
            (t, _) => t,
        };
        let column = at.contains_key("blank_reading");
        let blank = match (self.blank, self.blank_figure, column) {
            (_, Some(_), true) => {
                return Err(Error::bad_input(
                    file,
                    Some("blank_reading"),
                    "given both as a column and as a `# blank_reading` line: keep one",
                ))
            }
            (Some(BlankRule::Required), None, false) => {
                return Err(Error::bad_input(
                    file,
                    Some("blank_reading"),
                    "missing: add a `blank_reading` column (the companion cylinder's reading \
                     at each reading, D7928) or a line `# blank_reading = …` (the control \
                     cylinder's reading, D422's composite correction plus the scale's zero)",
                ))
            }
            (_, Some(b), false) => Some(b),
            (Some(BlankRule::ZeroUnlessGiven), None, false) | (None, _, _) => Some(0.0),
            (Some(_), None, true) => None,
        };
        Ok((temperature, blank))
    }
}

/// The test's figures of a readings file and the rules of its rows.
pub(super) fn setup(
    file: &Path,
    p: &Parsed,
    req: &ReduceOptions,
) -> Result<(TestSetup, RowRules), Error> {
    let kind = match p.figures.get("instrument") {
        None => "hydrometer".to_string(),
        Some((v, line)) => {
            let k = v.to_ascii_lowercase();
            if !INSTRUMENTS.split(", ").any(|i| i == k) {
                return Err(Error::bad_input(
                    file,
                    Some("instrument"),
                    format!("{line}: unknown instrument `{v}`; allowed: {INSTRUMENTS}"),
                ));
            }
            k
        }
    };
    let mass_g = required(
        file,
        "dry_mass_g",
        figure(file, p, "dry_mass_g", (1e-3, 1e4), "0.001–10000 g")?,
        "the oven-dry mass of the specimen in suspension, g",
    )?;
    let gs = required(
        file,
        "specific_gravity",
        figure(file, p, "specific_gravity", (1.5, 5.0), "1.5–5")?,
        "G_s of the soil solids",
    )?;
    let volume_ml = figure(
        file,
        p,
        "suspension_volume_ml",
        (100.0, 1e4),
        "100–10000 mL",
    )?
    .unwrap_or(1000.0);
    let model = model_figures(file, p)?;
    let mut s = TestSetup {
        standard: Standard::D7928,
        instrument: Instrument::Hydrometer(HydrometerType::H152),
        dry_mass_kg: mass_g * 1e-3,
        specific_gravity: gs,
        meniscus_correction: 0.0,
        suspension_volume_m3: volume_ml * 1e-6,
        measured: None,
        model,
    };
    let rules = match kind.as_str() {
        "hydrometer" => hydrometer(file, p, req, &mut s)?,
        other => {
            refuse_foreign(file, p, other)?;
            for (option, key) in [(&req.standard, "standard"), (&req.hydrometer, "hydrometer")] {
                if option.is_some() {
                    return Err(Error::bad_input(
                        file,
                        Some(key),
                        format!(
                            "--{key}: for the hydrometer only; this file's instrument is \
                             {other}: remove --{key}"
                        ),
                    ));
                }
            }
            let h = column_height_m(file, p, &s)?;
            if other == "pipette" {
                pipette(file, p, h, &mut s)?
            } else {
                sphere(file, p, h, &mut s)?
            }
        }
    };
    Ok((s, rules))
}

/// Refuses the figures that belong to another instrument than `kind`.
fn refuse_foreign(file: &Path, p: &Parsed, kind: &str) -> Result<(), Error> {
    for owner in [HYDROMETER, PIPETTE, SPHERE]
        .into_iter()
        .filter(|o| *o != kind)
    {
        if let Some(k) = keys_of(owner).find(|k| p.figures.contains_key(*k)) {
            let line = &p.figures[k].1;
            let what = if d7928_keys().any(|d| d == k) {
                "a D7928 hydrometer dimension"
            } else {
                &format!("a {owner} figure")
            };
            return Err(Error::bad_input(
                file,
                Some(k),
                format!(
                    "{line}: {what}, not used by a {kind} (the file's `instrument`): \
                     remove it, or set `# instrument = {owner}`"
                ),
            ));
        }
    }
    Ok(())
}

/// The model figures (`settle invert`'s), for every instrument (`hydrometer_bulb_length_cm`
/// is a hydrometer figure: [`refuse_foreign`] refuses it for the others).
fn model_figures(file: &Path, p: &Parsed) -> Result<ModelFigures, Error> {
    let bulb = figure(file, p, "hydrometer_bulb_length_cm", (1.0, 50.0), "1–50 cm")?;
    Ok(ModelFigures {
        fluid_density_kg_m3: figure(
            file,
            p,
            "fluid_density_kg_m3",
            (500.0, 3000.0),
            "500–3000 kg/m³",
        )?,
        gravity_m_s2: figure(file, p, "gravity_m_s2", (0.1, 100.0), "0.1–100 m/s²")?,
        column_height_m: figure(file, p, "column_height_cm", (1.0, 1000.0), "1–1000 cm")?
            .map(|h| h * 1e-2),
        hydrometer_bulb_length_m: bulb.map(|l| l * 1e-2),
    })
}

/// Height of the suspension H, m: `column_height_cm`, else `suspension_volume_ml` over the
/// cylinder's section (`cylinder_area_cm2`, `cylinder_diameter_cm`, default 27.8 cm²).
fn column_height_m(file: &Path, p: &Parsed, s: &TestSetup) -> Result<f64, Error> {
    if let Some(h) = s.model.column_height_m {
        return Ok(h);
    }
    let area = cylinder_area_cm2(file, p)?.unwrap_or(DEFAULT_CYLINDER_AREA_CM2);
    Ok(s.suspension_volume_m3 * 1e6 / area * 1e-2)
}

/// The cylinder's inside section from `cylinder_area_cm2` or `cylinder_diameter_cm`, cm².
fn cylinder_area_cm2(file: &Path, p: &Parsed) -> Result<Option<f64>, Error> {
    let area = figure(file, p, "cylinder_area_cm2", (1.0, 1000.0), "1–1000 cm²")?;
    let diameter = figure(
        file,
        p,
        "cylinder_diameter_cm",
        (0.1, 100.0),
        "a length of 0.1–100 cm",
    )?;
    match (area, diameter) {
        (Some(_), Some(_)) => Err(Error::bad_input(
            file,
            Some("cylinder_diameter_cm"),
            "give cylinder_area_cm2 or cylinder_diameter_cm, not both",
        )),
        (a, None) => Ok(a),
        (None, Some(d)) => Ok(Some(PI * d * d / 4.0)),
    }
}

/// The `temperature_c` figure within `range`.
fn temperature_figure(
    file: &Path,
    p: &Parsed,
    range: (f64, f64),
    text: &str,
) -> Result<Option<f64>, Error> {
    figure(file, p, "temperature_c", range, text)
}

/// The water correlations' range, °C: the pipette's and the sphere's temperatures.
const WATER_RANGE_C: (f64, f64) = (0.0, 40.0);

/// The rules of a pipette's or a sphere's rows.
fn direct_rules(
    file: &Path,
    p: &Parsed,
    reading: &'static str,
    (hi, allowed): (f64, String),
    blank: Option<BlankRule>,
    blank_figure: Option<f64>,
) -> Result<RowRules, Error> {
    let text = "0–40 °C (the range of the water correlations)".to_string();
    Ok(RowRules {
        reading,
        range: (0.0, hi),
        allowed: allowed.clone(),
        temperature_range: WATER_RANGE_C,
        temperature_figure: temperature_figure(file, p, WATER_RANGE_C, &text)?,
        temperature_text: text,
        blank_figure,
        blank,
        blank_range: (0.0, hi),
        blank_allowed: allowed,
    })
}

/// A pipette's figures.
fn pipette(file: &Path, p: &Parsed, height_m: f64, s: &mut TestSetup) -> Result<RowRules, Error> {
    let volume_ml = required(
        file,
        "pipette_volume_ml",
        figure(file, p, "pipette_volume_ml", (0.1, 1000.0), "0.1–1000 mL")?,
        "the volume of one draw, mL",
    )?;
    let region_given = p.figures.get("pipette_region");
    let disc = match region_given.map(|(v, l)| (v.to_ascii_lowercase(), l)) {
        None => false,
        Some((v, _)) if v == "sphere" => false,
        Some((v, _)) if v == "disc" => true,
        Some((v, l)) => {
            return Err(Error::bad_input(
                file,
                Some("pipette_region"),
                format!("{l}: unknown region `{v}`; allowed: sphere, disc"),
            ))
        }
    };
    let radius_cm = figure(file, p, "pipette_radius_cm", (0.01, 100.0), "0.01–100 cm")?;
    let region_radius_cm = match (disc, radius_cm) {
        (true, Some(r)) => r,
        (true, None) => required(
            file,
            "pipette_radius_cm",
            None,
            "pipette_region = disc: the radius of the disc the draw comes from, cm",
        )?,
        (false, Some(_)) => {
            return Err(Error::bad_input(
                file,
                Some("pipette_radius_cm"),
                "used with `# pipette_region = disc` only: remove it, or set the region",
            ))
        }
        (false, None) => (3.0 * volume_ml / (4.0 * PI)).cbrt(),
    };
    let h_cm = height_m * 1e2;
    let depth_cm = required(
        file,
        "pipette_depth_cm",
        figure(
            file,
            p,
            "pipette_depth_cm",
            (region_radius_cm, h_cm - region_radius_cm),
            &inside_text("the draw", region_radius_cm, h_cm),
        )?,
        "the depth of the pipette's tip below the free surface, cm",
    )?;
    s.instrument = Instrument::Pipette {
        volume_m3: volume_ml * 1e-6,
        depth_m: depth_cm * 1e-2,
        region: if disc {
            PipetteRegion::Disc {
                radius_m: region_radius_cm * 1e-2,
            }
        } else {
            PipetteRegion::Sphere
        },
    };
    let m = s.dry_mass_kg * 1e3;
    let range = (
        m,
        format!(
            "0 to {} g (dry_mass_g: a draw holds at most the specimen)",
            num(m)
        ),
    );
    let blank = figure(file, p, "blank_reading", (0.0, m), &range.1)?;
    direct_rules(
        file,
        p,
        "drawn_mass_g",
        range,
        Some(BlankRule::ZeroUnlessGiven),
        blank,
    )
}

/// The allowed depths of a region of radius `r_cm` inside a column of `h_cm`, as text.
fn inside_text(what: &str, r_cm: f64, h_cm: f64) -> String {
    format!(
        "{}–{} cm ({what}, of radius {} cm, within the suspension of height {} cm: \
         column_height_cm, else suspension_volume_ml over the cylinder's section)",
        sig_trim(r_cm, 4),
        sig_trim(h_cm - r_cm, 4),
        sig_trim(r_cm, 4),
        sig_trim(h_cm, 4)
    )
}

/// A buoyancy sphere's figures.
fn sphere(file: &Path, p: &Parsed, height_m: f64, s: &mut TestSetup) -> Result<RowRules, Error> {
    if let Some((_, line)) = p.figures.get("blank_reading") {
        return Err(Error::bad_input(
            file,
            Some("blank_reading"),
            format!(
                "{line}: not used by a buoyancy-sphere (its clear-fluid apparent mass is \
                 m_air − ρ_f V_sp): give the dispersant solution's `fluid_density_kg_m3` instead"
            ),
        ));
    }
    let d_mm = required(
        file,
        "sphere_diameter_mm",
        figure(file, p, "sphere_diameter_mm", (1.0, 500.0), "1–500 mm")?,
        "the sphere's diameter, mm",
    )?;
    let mass_g = required(
        file,
        "sphere_mass_g",
        figure(file, p, "sphere_mass_g", (1e-3, 1e5), "0.001–100000 g")?,
        "the sphere's mass in air, g",
    )?;
    let rho = s
        .model
        .fluid_density_kg_m3
        .unwrap_or(water_density_kg_m3(4.0));
    let displaced_g = rho * PI * (d_mm * 1e-3).powi(3) / 6.0 * 1e3;
    if mass_g <= displaced_g {
        return Err(Error::bad_input(
            file,
            Some("sphere_mass_g"),
            format!(
                "{}: a sphere of {mass_g} g and Ø {d_mm} mm floats (it displaces {} g of \
                 the fluid); allowed: more than {} g",
                p.figures["sphere_mass_g"].1,
                sig_trim(displaced_g, 4),
                sig_trim(displaced_g, 4)
            ),
        ));
    }
    let (r_cm, h_cm) = (0.05 * d_mm, height_m * 1e2);
    let depth_cm = required(
        file,
        "sphere_depth_cm",
        figure(
            file,
            p,
            "sphere_depth_cm",
            (r_cm, h_cm - r_cm),
            &inside_text("the sphere", r_cm, h_cm),
        )?,
        "the depth of the sphere's centre below the free surface, cm",
    )?;
    s.instrument = Instrument::BuoyancySphere {
        diameter_m: d_mm * 1e-3,
        mass_kg: mass_g * 1e-3,
        depth_m: depth_cm * 1e-2,
    };
    let range = (
        mass_g,
        format!("0 to {} g (sphere_mass_g: its mass in air)", num(mass_g)),
    );
    direct_rules(file, p, "apparent_mass_g", range, None, None)
}

/// A hydrometer's figures (the standard and the hydrometer: the command line's, else the
/// file's).
fn hydrometer(
    file: &Path,
    p: &Parsed,
    req: &ReduceOptions,
    s: &mut TestSetup,
) -> Result<RowRules, Error> {
    refuse_foreign(file, p, "hydrometer")?;
    let (standard, h) = kinds(file, p, req)?;
    let (s0, s1) = h.scale();
    let cm_max = 0.1 * (s1 - s0);
    let cm = required(
        file,
        "meniscus_correction",
        figure(
            file,
            p,
            "meniscus_correction",
            (0.0, cm_max),
            &format!(
                "0–{} {} (0 if read at the liquid level)",
                num(cm_max),
                h.unit()
            ),
        )?,
        "reading at the liquid level minus reading at the top of the meniscus",
    )?;
    let scale = scale_text(h);
    let blank = figure(file, p, "blank_reading", (s0, s1), &scale)?;
    let measured = match standard {
        Standard::D7928 => Some(measured(file, p, h)?),
        Standard::D422 => {
            if let Some(k) = d7928_keys().find(|k| p.figures.contains_key(*k)) {
                return Err(Error::bad_input(
                    file,
                    Some(k),
                    "used by d7928 only (D422 takes the effective depth from its Table 2): \
                     remove it or reduce with --standard d7928",
                ));
            }
            None
        }
    };
    s.standard = standard;
    s.instrument = Instrument::Hydrometer(h);
    s.meniscus_correction = cm;
    s.measured = measured;
    let (t0, t1) = standard.temperature_range_c();
    let text = format!("{t0}–{t1} °C for {}", standard.name());
    Ok(RowRules {
        reading: "reading",
        range: (s0, s1),
        allowed: scale.clone(),
        temperature_range: (t0, t1),
        temperature_figure: temperature_figure(file, p, (t0, t1), &text)?,
        temperature_text: text,
        blank_figure: blank,
        blank: Some(BlankRule::Required),
        blank_range: (s0, s1),
        blank_allowed: scale,
    })
}

/// The hydrometer's scale as text.
fn scale_text(h: HydrometerType) -> String {
    let (a, b) = h.scale();
    format!(
        "{} to {} {} (the {}'s scale)",
        num(a),
        num(b),
        h.unit(),
        h.name()
    )
}

/// The hydrometer's measured dimensions (D7928), in SI.
fn measured(file: &Path, p: &Parsed, h: HydrometerType) -> Result<MeasuredHydrometer, Error> {
    let len = (0.1, 100.0);
    let (s0, s1) = h.scale();
    let r1 = figure(file, p, "r1", (s0, s1), "a reading on the scale")?.unwrap_or(s0);
    let r2 = figure(file, p, "r2", (s0, s1), "a reading on the scale")?.unwrap_or(s1);
    let cm = "a length of 0.1–100 cm";
    let h1 = required(
        file,
        "h_r1_cm",
        figure(file, p, "h_r1_cm", len, cm)?,
        "D7928: distance from the bulb's centre of volume to the mark r1, cm",
    )?;
    let h2 = required(
        file,
        "h_r2_cm",
        figure(file, p, "h_r2_cm", len, cm)?,
        "D7928: distance from the bulb's centre of volume to the mark r2, cm",
    )?;
    let vb = required(
        file,
        "bulb_volume_ml",
        figure(file, p, "bulb_volume_ml", (1.0, 1000.0), "1–1000 mL")?,
        "D7928: the bulb's volume, mL",
    )?;
    let Some(area_cm2) = cylinder_area_cm2(file, p)? else {
        return Err(Error::bad_input(
            file,
            Some("cylinder_area_cm2"),
            "missing: add `# cylinder_area_cm2 = …` or `# cylinder_diameter_cm = …` \
             (D7928: the sedimentation cylinder's inside section)",
        ));
    };
    if !(r1 < r2 && h1 > h2) {
        return Err(Error::bad_input(
            file,
            Some("h_r1_cm"),
            format!(
                "the mark r1 = {r1} must be above the mark r2 = {r2} on the stem: r1 < r2 and \
                 h_r1_cm ({h1}) > h_r2_cm ({h2})"
            ),
        ));
    }
    Ok(MeasuredHydrometer {
        h_r1_m: h1 * 1e-2,
        h_r2_m: h2 * 1e-2,
        r1,
        r2,
        bulb_volume_m3: vb * 1e-6,
        cylinder_area_m2: area_cm2 * 1e-4,
    })
}
