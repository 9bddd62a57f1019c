//! `settle reduce --template d7928|d422`: a commented readings file to fill in, printed to
//! stdout (the README's lab quick start). Each figure line is a `# key = value` line with a
//! typical value and, on the line above it, what it is; the table has the standard's reading
//! schedule with the readings left to fill.

use crate::error::Error;
use crate::instruments::reduction::{d422, d7928};
use std::path::Path;

/// The readings template of `standard` (`d7928` or `d422`): a CSV `settle reduce` reads once
/// the readings are filled in. Bad input naming `--template` for another standard.
pub fn template(standard: &str) -> Result<String, Error> {
    let (name, times): (&str, &[f64]) = match standard.to_ascii_lowercase().as_str() {
        "d7928" => ("d7928", &d7928::TIMES_MIN),
        "d422" => ("d422", &d422::TIMES_MIN),
        _ => {
            return Err(Error::bad_argument(
                "--template",
                Path::new(standard),
                "unknown standard; allowed: d7928, d422",
            ))
        }
    };
    let mut t = format!(
        "# settle readings template, ASTM {}: fill in the figures and the readings, then run\n\
         # settle reduce THIS_FILE   (format: docs/commands/reduce.md)\n\
         # Comment lines without an equals sign are notes: keep or delete them.\n\
         # standard = {name}\n\
         # 152H (g/L) or 151H (specific gravity)\n\
         # hydrometer = 152H\n\
         # oven-dry mass of the specimen in suspension, g\n\
         # dry_mass_g = 50\n\
         # specific gravity of the soil solids\n\
         # specific_gravity = 2.65\n\
         # meniscus correction, in reading units (the top of the meniscus read minus the liquid level)\n\
         # meniscus_correction = 1.0\n\
         # volume of the suspension, mL\n\
         # suspension_volume_ml = 1000\n",
        name.to_uppercase()
    );
    if name == "d7928" {
        t.push_str(
            "# hydrometer's measured dimensions: bulb centre of volume to the marks r1 and r2 (cm), bulb volume (mL)\n\
             # h_r1_cm = 20.3\n\
             # h_r2_cm = 8.6\n\
             # bulb_volume_ml = 55\n\
             # inside section of the sedimentation cylinder, cm2\n\
             # cylinder_area_cm2 = 27.8\n\
             # free text (not used)\n\
             # sample = \n\
             # date = \n\
             # the readings at D7928's schedule; blank_reading: the companion cylinder's reading\n\
             time_min,reading,temperature_c,blank_reading\n",
        );
    } else {
        t.push_str(
            "# the control cylinder's reading (composite correction plus the scale's zero)\n\
             # blank_reading = 6.0\n\
             # free text (not used)\n\
             # sample = \n\
             # date = \n\
             # the readings at D422's schedule\n\
             time_min,reading,temperature_c\n",
        );
    }
    let blank = if name == "d7928" { "," } else { "" };
    for m in times {
        t.push_str(&format!("{m},,{blank}\n"));
    }
    Ok(t)
}
