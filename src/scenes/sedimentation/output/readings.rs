//! `readings.csv` and `readings_d7928.csv`: the run's virtual 152H hydrometer readings in the
//! laboratory's format, the one `settle reduce` reads (docs/commands/reduce.md): `# key = value`
//! figures of the test, then `time_min, reading, temperature_c, counting_sigma` rows
//! (`counting_sigma`: the reading's counting noise, 1σ of the representative grains in the
//! reading's unit, [`crate::instruments::counting`]; `settle invert` adds it to the
//! instrument's resolution, `settle reduce` ignores it); `readings_pipette.csv`
//! and `readings_sphere.csv`: its pipette's and buoyancy sphere's readings in the same format
//! (`direct_text`). All four carry the model figures `fluid_density_kg_m3`, `gravity_m_s2`
//! and `column_height_cm` (the run's ρ_f, g and H) for `settle invert`'s forward model.
//!
//! What the run knows is written as a laboratory would write it:
//! - `hydrometer = 152H`, readings R in g/L as the run's hydrometer reads them (`reading_g_per_l`
//!   of `instruments.csv`, full precision: no rounding to the 0.5 g/L of the scale);
//! - `dry_mass_g` the sample's mass (`sample.mass_kg`), `suspension_volume_ml` the volume that
//!   holds it at the run's initial concentration c₀ (M/c₀: the real cylinder's volume);
//! - `specific_gravity` G_s = ρ_p/ρ_f;
//! - `temperature_c` the temperature at which water has the run's viscosity (the reduction
//!   takes μ of water at that temperature, [`water_viscosity_pa_s`]), so the Stokes diameters
//!   use the same μ;
//! - `meniscus_correction = 0` (the virtual hydrometer is read at the liquid level) and
//!   `blank_reading = 0` (it reads 0 in the clear fluid of the run);
//! - for D7928 the hydrometer's own dimensions: H_r at the marks −5 and 60 g/L measured from
//!   the bulb's centre of volume (mid-length, the bulb is symmetric) on the run's 1/ρ scale
//!   ([`Hydrometer::mark_m`]), the bulb volume and the 27.8 cm² cylinder section of its
//!   calibration.
//!
//! Reduced by `settle reduce`, the percent finer is the run's own exactly when ρ_f = 1000 kg/m³:
//! P = 0.6226 G_s/(G_s − 1)(V/M) R · 100 with R = 1000 (ρ_s/ρ_f − 1)/0.6226 is the run's
//! 100 ρ_p (ρ_s − ρ_f)/((ρ_p − ρ_f) c₀) (seed eqs. 17–19), times ρ_f/1000 kg/m³. The
//! diameters differ by the standards' effective depth: they subtract half the rise of the
//! suspension when the bulb enters it (V_B/(2A) = 1.2 cm) and take the mark from a linear law
//! (D422 Table 2, D7928's interpolation between two marks), while the run takes the bulb
//! centre's true depth in a suspension that does not rise; and by D422's g = 9.80 m/s²
//! (D7928: 9.807 m/s² and ρ_w(T) for ρ_f).
//!
//! D422's schedule is the run's hydrometer times. D7928's (1, 2, 4, 15, 30, 60, 240, 1440 min,
//! within `time.end_s`) is read, without stepping to any new time, on what the run already
//! kept at those times: its hydrometer readings, its record profiles and its snapshots. Times
//! at which it kept nothing are listed in a comment line of `readings_d7928.csv`, not read.

use crate::instruments::hydrometer::{Hydrometer, HydrometerReading};
use crate::instruments::reduction::{d7928, water_viscosity_pa_s};
use crate::io::fmt::{clean_reading, num};
use crate::io::{Outputs, Table};
use crate::numerics::{bisect, Bisection};
use crate::scenes::sedimentation::instruments::{
    hydrometer_counting_sd, layered_field, InstrumentKind, InstrumentReading, InstrumentSet,
};
use crate::scenes::sedimentation::setup::Setup;
use crate::scenes::sedimentation::state::{profile, Profile};

/// Temperature (°C) at which water has the viscosity `mu` (Pa s), by bisection over 0–40 °C
/// of [`water_viscosity_pa_s`] (None outside that range).
pub fn water_temperature_c(mu_pa_s: f64) -> Option<f64> {
    let (lo, hi) = (0.0f64, 40.0f64);
    if !(water_viscosity_pa_s(hi)..=water_viscosity_pa_s(lo)).contains(&mu_pa_s) {
        return None;
    }
    // μ falls with the temperature.
    let (lo, hi) = bisect(lo, hi, Bisection::halvings(100), |t| {
        water_viscosity_pa_s(t) > mu_pa_s
    });
    Some(0.5 * (lo + hi))
}

/// Adds `readings.csv` (D422, the hydrometer's times) and `readings_d7928.csv` (D7928's
/// schedule, read on the states the run kept) to `out` (as files: their `#` lines make them
/// no plain table), when the run had hydrometer
/// readings, a 152H scale (0–60 g/L for G = 2.65) and a viscosity of water at 16–30 °C (the
/// range both standards accept); and `readings_pipette.csv` / `readings_sphere.csv` (the
/// pipette's and the sphere's readings at their times, full precision) when the run had those
/// and a viscosity of water at 0–40 °C (`direct_text`). Otherwise adds nothing.
pub fn write_all(
    out: &mut Outputs,
    setup: &Setup,
    readings: &[InstrumentReading],
    profiles: &[Profile],
    snapshots: &[super::Snapshot],
) {
    let set = InstrumentSet::new(setup);
    let spec = set.hydrometer.spec;
    let is_152h = spec.full_scale == 60.0 && spec.calibration_specific_gravity == 2.65;
    let hyd: Vec<Read> = readings
        .iter()
        .filter(|r| r.kind == InstrumentKind::Hydrometer)
        .filter_map(|r| r.hydrometer.map(|h| (r.point.time_s, h, r.counting_sd)))
        .collect();
    let Some(t_c) = water_temperature_c(setup.viscosity_pa_s) else {
        return;
    };
    let head = Head {
        name: &setup.common.name,
        sample: setup.spec.sample.sample,
        dry_mass_g: setup.spec.sample.mass_kg * 1e3,
        volume_ml: setup.spec.sample.mass_kg / set.analysis.c0_kg_m3 * 1e6,
        gs: set.analysis.grain_density_kg_m3 / set.analysis.fluid_density_kg_m3,
        t_c,
        fluid_density_kg_m3: set.analysis.fluid_density_kg_m3,
        gravity_m_s2: set.analysis.gravity_m_s2,
        column_height_cm: setup.height_m * 1e2,
    };
    for (kind, file) in [
        (InstrumentKind::Pipette, "readings_pipette.csv"),
        (InstrumentKind::Buoyancy, "readings_sphere.csv"),
    ] {
        let rows: Vec<&InstrumentReading> = readings.iter().filter(|r| r.kind == kind).collect();
        if !rows.is_empty() {
            out.table(readings_table(file, &direct_text(&head, &set, kind, &rows)));
        }
    }
    if hyd.is_empty() || !is_152h || !(16.0..=30.0).contains(&t_c) {
        return;
    }
    out.table(readings_table(
        "readings.csv",
        &head.text("d422", None, &hyd, &[]),
    ));
    let end_s = setup.common.time.end_s;
    let (at, missing) = d7928_readings(&set, setup, end_s, &hyd, profiles, snapshots);
    out.table(readings_table(
        "readings_d7928.csv",
        &head.text("d7928", Some(&set.hydrometer), &at, &missing),
    ));
}

/// The table of a readings file whose text `text` this module wrote: its `#` lines the
/// preamble, then the header and rows of numbers (no cell holds a comma or a quote, so the
/// table writes the same bytes back).
fn readings_table(name: &str, text: &str) -> Table {
    let mut lines = text.lines();
    let mut preamble = Vec::new();
    let mut header = "";
    for l in lines.by_ref() {
        if l.starts_with('#') {
            preamble.push(l.to_string());
        } else {
            header = l;
            break;
        }
    }
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    Table::with_rows(name, header.split(','), rows).with_preamble(preamble)
}

/// `readings_pipette.csv` (`kind` Pipette) or `readings_sphere.csv` (Buoyancy): the run's
/// readings of that instrument at its times, every figure at full precision ([`num`]), in the
/// format of `settle reduce` (docs/commands/reduce.md):
/// - pipette: `pipette_volume_ml` (the real draw's V), `pipette_depth_cm` (the tip's depth),
///   `pipette_region = disc` with `pipette_radius_cm` the radius of the 2D model's sampling
///   disc ([`crate::instruments::pipette`]); `drawn_mass_g` the real draw's dry mass (the
///   simulated mass over the wedge fraction);
/// - sphere: `sphere_diameter_mm`, `sphere_mass_g` (in air), `sphere_depth_cm` (its centre);
///   `apparent_mass_g` the dynamometer's reading;
/// - both: the model figures `fluid_density_kg_m3` (ρ_f of the run: the sphere's clear-fluid
///   apparent mass and Δρ = ρ_f (G_s − 1) = ρ_p − ρ_f), `gravity_m_s2` and `column_height_cm`
///   (the run's H), so that the reduction's percent finer and Stokes diameter are the run's own.
fn direct_text(
    head: &Head,
    set: &InstrumentSet,
    kind: InstrumentKind,
    rows: &[&InstrumentReading],
) -> String {
    let (what, instrument) = match kind {
        InstrumentKind::Pipette => ("pipette", "pipette"),
        _ => ("buoyancy sphere", "buoyancy-sphere"),
    };
    let mut t = format!(
        "# settle: the virtual {what} of {} at the run's {what} times; reduce with settle \
         reduce\n# instrument = {instrument}\n\
         # sample = {} (sample {})\n# source = settle {} virtual test\n\
         # dry_mass_g = {}\n# suspension_volume_ml = {}\n# specific_gravity = {}\n",
        head.name,
        head.name,
        head.sample,
        env!("CARGO_PKG_VERSION"),
        num(head.dry_mass_g),
        num(head.volume_ml),
        num(head.gs),
    );
    let column = match kind {
        InstrumentKind::Pipette => {
            let p = &set.pipette;
            t.push_str(&format!(
                "# pipette_volume_ml = {}\n# pipette_depth_cm = {}\n# pipette_region = disc\n\
                 # pipette_radius_cm = {}\n",
                num(p.volume_m3 * 1e6),
                num(p.depth_m * 1e2),
                num(p.radius_m() * 1e2)
            ));
            "drawn_mass_g"
        }
        _ => {
            let b = &set.sphere;
            t.push_str(&format!(
                "# sphere_diameter_mm = {}\n# sphere_mass_g = {}\n# sphere_depth_cm = {}\n",
                num(b.diameter_m * 1e3),
                num(b.mass_kg * 1e3),
                num(b.depth_m * 1e2)
            ));
            "apparent_mass_g"
        }
    };
    t.push_str(&head.model_lines(num));
    t.push_str(&format!("time_min,{column},temperature_c,counting_sigma\n"));
    for r in rows {
        let reading_kg = match (r.pipette, r.buoyancy) {
            (Some(p), _) => p.mass_kg,
            (_, Some(b)) => b.apparent_mass_kg,
            _ => continue,
        };
        t.push_str(&format!(
            "{},{},{},{}\n",
            num(r.point.time_s / 60.0),
            num(reading_kg * 1e3),
            num(head.t_c),
            num(r.counting_sd)
        ));
    }
    t
}

/// A hydrometer reading of a readings file: time (s), the reading, its counting σ (g/L).
type Read = (f64, HydrometerReading, f64);

/// The hydrometer at D7928's times within `end_s`: its reading at that time if the run took
/// one, else read on the record profile or the snapshot of that time (with its counting σ);
/// and the times (min) at which the run kept nothing.
fn d7928_readings(
    set: &InstrumentSet,
    setup: &Setup,
    end_s: f64,
    hyd: &[Read],
    profiles: &[Profile],
    snapshots: &[super::Snapshot],
) -> (Vec<Read>, Vec<f64>) {
    let (rho_p, rho_f) = (
        set.analysis.grain_density_kg_m3,
        set.analysis.fluid_density_kg_m3,
    );
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.max(1.0);
    let read = |pr: &Profile| {
        let r = set
            .hydrometer
            .read(&layered_field(pr, setup, rho_p, rho_f))?;
        Some((
            r,
            hydrometer_counting_sd(&set.hydrometer, pr, setup, rho_p, rho_f),
        ))
    };
    let (mut at, mut missing) = (Vec::new(), Vec::new());
    for t_min in d7928::TIMES_MIN {
        let t = t_min * 60.0;
        if t > end_s * (1.0 + 1e-12) {
            continue;
        }
        let r = hyd
            .iter()
            .find(|(x, _, _)| same(*x, t))
            .map(|(_, h, sd)| (*h, *sd))
            .or_else(|| {
                let pr = profiles
                    .iter()
                    .find(|p| same(p.time_s, t) && p.solid_m3.len() == set.layers);
                pr.and_then(read)
            })
            .or_else(|| {
                let sn = snapshots.iter().find(|sn| same(sn.time_s, t))?;
                read(&profile(&sn.state(), setup, set.layers, rho_p))
            });
        match r {
            Some((r, sd)) => at.push((t, r, sd)),
            None => missing.push(t_min),
        }
    }
    (at, missing)
}

/// The figures of the test common to both files.
struct Head<'a> {
    name: &'a str,
    sample: u32,
    dry_mass_g: f64,
    volume_ml: f64,
    gs: f64,
    t_c: f64,
    fluid_density_kg_m3: f64,
    gravity_m_s2: f64,
    column_height_cm: f64,
}

impl Head<'_> {
    /// The model figures (`settle invert`'s forward model): ρ_f, g and the column's height H,
    /// each formatted by `f`.
    fn model_lines(&self, f: impl Fn(f64) -> String) -> String {
        format!(
            "# fluid_density_kg_m3 = {}\n# gravity_m_s2 = {}\n# column_height_cm = {}\n",
            f(self.fluid_density_kg_m3),
            f(self.gravity_m_s2),
            f(self.column_height_cm)
        )
    }

    /// The file's text for `standard`, with the hydrometer's dimensions for D7928 (`measured`)
    /// and a comment naming the schedule's `missing` times (min).
    fn text(
        &self,
        standard: &str,
        measured: Option<&Hydrometer>,
        rows: &[Read],
        missing: &[f64],
    ) -> String {
        let schedule = match standard {
            "d422" => "the run's hydrometer times".to_string(),
            _ => format!(
                "ASTM D7928's schedule ({} min) within the run",
                d7928::TIMES_MIN.map(num).join(", ")
            ),
        };
        let mut t = format!(
            "# settle: the virtual 152H hydrometer of {} at {schedule}; reduce with settle reduce\n\
             # standard = {standard}\n# hydrometer = 152H\n\
             # sample = {} (sample {})\n# source = settle {} virtual test\n\
             # dry_mass_g = {}\n# suspension_volume_ml = {}\n# specific_gravity = {}\n\
             # meniscus_correction = 0\n# blank_reading = 0\n",
            self.name,
            self.name,
            self.sample,
            env!("CARGO_PKG_VERSION"),
            clean_reading(self.dry_mass_g),
            clean_reading(self.volume_ml),
            clean_reading(self.gs),
        );
        if let Some(h) = measured {
            let centre = 0.5 * h.spec.bulb_length_m;
            t.push_str(&format!(
                "# h_r1_cm = {}\n# r1 = -5\n# h_r2_cm = {}\n# r2 = 60\n\
                 # bulb_volume_ml = {}\n# cylinder_area_cm2 = {}\n",
                clean_reading((centre + h.mark_m(-5.0)) * 1e2),
                clean_reading((centre + h.mark_m(60.0)) * 1e2),
                clean_reading(h.bulb_volume_m3() * 1e6),
                clean_reading(h.spec.astm_cylinder_area_m2 * 1e4),
            ));
        }
        t.push_str(&self.model_lines(num));
        if !missing.is_empty() {
            t.push_str(&format!(
                "# not read at {} min: the run kept no state at those times\n",
                missing
                    .iter()
                    .map(|x| clean_reading(*x))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        t.push_str("time_min,reading,temperature_c,counting_sigma\n");
        for (time_s, r, sd) in rows {
            t.push_str(&format!(
                "{},{},{},{}\n",
                clean_reading(time_s / 60.0),
                clean_reading(r.reading),
                clean_reading(self.t_c),
                clean_reading(*sd)
            ));
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::readings_table;

    /// A readings file's table writes back the bytes of its text: the `#` lines (one holding
    /// commas) as the preamble, the header and the rows.
    #[test]
    fn readings_table_writes_its_text_back() {
        let text = "# instrument = pipette\n# not read at 1, 2 min: no state\n\
                    time_min,drawn_mass_g,temperature_c\n0.5,1.25,20\n2,0.75,20\n";
        let t = readings_table("readings_pipette.csv", text);
        assert_eq!(t.preamble().len(), 2);
        assert_eq!(t.header(), ["time_min", "drawn_mass_g", "temperature_c"]);
        assert_eq!(t.f64s("drawn_mass_g"), Some(vec![1.25, 0.75]));
        assert_eq!(String::from_utf8(t.to_csv().unwrap()).unwrap(), text);
    }
}
