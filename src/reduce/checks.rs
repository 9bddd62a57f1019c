//! Plausibility of a readings file, by physics and by the standards: what a test can be. A
//! clear mistake (a wrong unit) is refused as bad input naming the value, the likely cause and
//! the fix; a doubtful value is a warning (console and `reduce.toml`). Only ranges with a
//! source are checked; each constant says where it comes from.

use super::figures::{bad, Parsed};
use super::instrument::RowRules;
use crate::error::Error;
use crate::instruments::reduction::{HydrometerType, Instrument, LabReading, TestSetup};
use crate::io::fmt::sig_trim;
use crate::io::lab_file::Loc;
use std::path::Path;

/// The earliest first reading of a test, s. ASTM D7928-17 takes its first reading at 1 min and
/// ASTM D422-63 at 2 min (their schedules, `instruments::reduction::{d7928, d422}::TIMES_MIN`);
/// the pipette schedules of BS 1377-2 start later still. A first reading under 20 s (a third of
/// D7928's first) is a test no standard runs: the times were written in another unit.
pub const FIRST_READING_MIN_S: f64 = 20.0;

/// The latest last reading of a test, s: both D7928 and D422 end at 1440 min (24 h); three
/// times that (3 days) is no standard's test: the times were written in another unit.
pub const LAST_READING_MAX_S: f64 = 3.0 * 86_400.0;

/// The sieve that bounds a sedimentation analysis, m: ASTM D7928-17 and D422-63 reduce the
/// fraction passing the No. 200 sieve (75 µm); a diameter above it lies outside the method
/// (Stokes' law no longer holds and the fraction was sieved out). Warned.
pub const SIEVE_LIMIT_M: f64 = 75e-6;

/// The specific gravity of soil solids that is not doubtful. Mineral soils lie at 2.6–2.8
/// (quartz 2.65, feldspars 2.55–2.76, clay minerals 2.6–2.9); organic soils go below 2, soils
/// rich in iron oxides above 3 (hematite 5.3). Outside 2.0–3.5 (the range, wider than
/// every common mineral soil) a warning; outside 1.5–5 refused by the figure's own range.
pub const SPECIFIC_GRAVITY_OK: (f64, f64) = (2.0, 3.5);

/// The temperatures at which the water's viscosity and density are known to settle's
/// correlations within 0.1 %, °C (Kestin, Sokolov & Wakeham 1978 against IAPWS 2008; see
/// `docs/commands/reduce.md`): outside 10–40 °C a pipette or sphere reading is warned (the
/// hydrometer standards refuse outside their own, narrower ranges).
pub const TEMPERATURE_OK_C: (f64, f64) = (10.0, 40.0);

/// The plausibility checks of a read file (after the figures and rows passed their ranges):
/// the reading schedule (refused: a wrong time unit), 151H readings in a 152H file (refused),
/// and the doubtful values (returned as warnings).
pub(super) fn check(
    file: &Path,
    p: &Parsed,
    s: &TestSetup,
    readings: &[LabReading],
    locs: &[Loc],
    (time_col, j): (&str, usize),
) -> Result<Vec<String>, Error> {
    let mut warnings = Vec::new();
    // A settle run's own readings (`# source = settle …`) are a virtual test: its times are
    // the run's, not a standard's schedule, so they are warned, not refused.
    let virtual_test = p
        .figures
        .get("source")
        .is_some_and(|(v, _)| v.starts_with("settle "));
    let n = readings.len();
    let first = &readings[0];
    let schedule = schedule_problems(readings, locs, (time_col, j));
    for m in schedule {
        if virtual_test {
            warnings.push(format!("{m} (a settle run's virtual test: warned only)"));
        } else {
            return Err(bad(file, m));
        }
    }
    if let Instrument::Hydrometer(HydrometerType::H152) = s.instrument {
        let like_151 = readings.iter().all(|r| (0.99..=1.06).contains(&r.reading));
        if like_151 && n >= 2 {
            return Err(Error::bad_input(
                file,
                Some("hydrometer"),
                format!(
                    "every reading lies between 0.99 and 1.06 (row 1: {}): these are 151H \
                     readings (specific gravity of the suspension), not the 152H's g/L; fix: \
                     set `# hydrometer = 151H` (or --hydrometer 151H)",
                    sig_trim(first.reading, 6)
                ),
            ));
        }
    }
    let (g0, g1) = SPECIFIC_GRAVITY_OK;
    if !(g0..=g1).contains(&s.specific_gravity) {
        let at = p
            .figures
            .get("specific_gravity")
            .map(|(_, l)| format!("{l}: "))
            .unwrap_or_default();
        warnings.push(format!(
            "{at}specific_gravity {} is outside 2.0–3.5 (mineral soils 2.6–2.8): check it \
             (organic soils lie lower, iron-rich ones higher)",
            sig_trim(s.specific_gravity, 4)
        ));
    }
    if !matches!(s.instrument, Instrument::Hydrometer(_)) {
        let (t0, t1) = TEMPERATURE_OK_C;
        if let Some((k, r)) = readings
            .iter()
            .enumerate()
            .find(|(_, r)| !(t0..=t1).contains(&r.temperature_c))
        {
            warnings.push(format!(
                "row {} ({}): temperature {} °C is outside 10–40 °C, where the water's \
                 viscosity is known to 0.1 %: the diameters are less certain",
                k + 1,
                locs[k],
                sig_trim(r.temperature_c, 4)
            ));
        }
    }
    Ok(warnings)
}

/// What is wrong with the reading schedule (a first reading under 20 s, a last one after
/// 3 days): the messages, each naming the row, the column, the likely unit and the fix.
fn schedule_problems(
    readings: &[LabReading],
    locs: &[Loc],
    (time_col, j): (&str, usize),
) -> Vec<String> {
    let n = readings.len();
    let first = &readings[0];
    let last = &readings[n - 1];
    let in_min = time_col == "time_min";
    let shown = |t: f64| {
        if in_min {
            sig_trim(t / 60.0, 6)
        } else {
            sig_trim(t, 6)
        }
    };
    let unit = if in_min { "min" } else { "s" };
    let mut schedule = Vec::new();
    if first.time_s < FIRST_READING_MIN_S {
        let (likely, fix) = if in_min {
            (
                "the times look like hours",
                "give the times in minutes under `time_min` (or in seconds under `time_s`)",
            )
        } else {
            (
                "the times look like minutes",
                "rename the column `time_min`, or convert the times to seconds",
            )
        };
        schedule.push(format!(
            "row 1 ({}), column {} `{time_col}`: the first reading at {} {unit}{} is \
             earlier than any standard takes one (D7928's first at 1 min, D422's at 2 min; \
             refused under 20 s): {likely}; fix: {fix}",
            locs[0].at(j),
            j + 1,
            shown(first.time_s),
            if in_min {
                format!(" ({} s)", sig_trim(first.time_s, 4))
            } else {
                String::new()
            }
        ));
    }
    if last.time_s > LAST_READING_MAX_S {
        let (likely, fix) = if in_min {
            (
                "the times look like seconds",
                "rename the column `time_s`, or convert the times to minutes",
            )
        } else {
            (
                "the times look like another unit (milliseconds?)",
                "give the times in seconds under `time_s` (or in minutes under `time_min`)",
            )
        };
        schedule.push(format!(
            "row {n} ({}), column {} `{time_col}`: the last reading at {} {unit} ({} days) is \
             later than any standard's schedule (D7928 and D422 end at 1440 min, 24 h; refused \
             after 3 days): {likely}; fix: {fix}",
            locs[n - 1].at(j),
            j + 1,
            shown(last.time_s),
            sig_trim(last.time_s / 86_400.0, 3)
        ));
    }
    schedule
}

/// The likely cause of a value out of its column's range, for the message (empty when none
/// is likely): a temperature in °F, a 152H reading in a 151H file, a mass in mg.
pub(super) fn out_of_range_hint(column: &str, x: f64, rules: &RowRules) -> String {
    match column {
        "time_s" if x > rules_time_max("time_s") => {
            " (the times look like milliseconds: give seconds)".into()
        }
        "time_min" if x > rules_time_max("time_min") => {
            " (the times look like seconds or milliseconds: give minutes, or rename the column \
             `time_s`)"
                .into()
        }
        "temperature_c" if (50.0..=110.0).contains(&x) => format!(
            " ({} looks like °F, {} °C: give degrees Celsius)",
            sig_trim(x, 4),
            sig_trim((x - 32.0) / 1.8, 3)
        ),
        "reading" | "blank_reading" if rules.range.1 < 2.0 && (-5.0..=60.0).contains(&x) => {
            " (a 152H reading in g/L? this file's hydrometer is the 151H, read as specific \
             gravity: set `# hydrometer = 152H`, or write 1.0xx)"
                .into()
        }
        "reading" | "blank_reading" if rules.range.1 > 2.0 && (990.0..=1060.0).contains(&x) => {
            " (a 151H reading times 1000, or the suspension's density in g/L? the 152H reads \
             grams of soil per litre, -5 to 60)"
                .into()
        }
        "drawn_mass_g" | "apparent_mass_g" if x > rules.range.1 && x / 1000.0 <= rules.range.1 => {
            format!(
                " (in milligrams? {} mg is {} g: give grams)",
                sig_trim(x, 6),
                sig_trim(x / 1000.0, 6)
            )
        }
        _ => String::new(),
    }
}

/// The largest time a column allows (`super::input`'s ranges: 10⁷ s, 10⁶ min).
fn rules_time_max(column: &str) -> f64 {
    if column == "time_s" {
        1e7
    } else {
        1e6
    }
}

/// The warnings of a reduction's results: diameters above the 75 µm sieve.
pub(super) fn result_warnings(diameters_m: &[f64]) -> Vec<String> {
    let above: Vec<f64> = diameters_m
        .iter()
        .copied()
        .filter(|d| *d > SIEVE_LIMIT_M)
        .collect();
    if above.is_empty() {
        return Vec::new();
    }
    let max = above.iter().copied().fold(0.0, f64::max);
    vec![format!(
        "{} reading(s) give diameters above the 75 µm sieve (up to {} µm): the hydrometer and \
         pipette methods apply to the fraction passing it (ASTM D7928, D422); check the \
         readings' times and their unit",
        above.len(),
        sig_trim(max * 1e6, 3)
    )]
}
