//! Bad lab inputs (issue 26, items 1–2), table-driven: each [`Case`] runs one command on files
//! it writes into a fresh folder and asserts its exit code, the words of its message and, for a
//! refusal, that nothing was written and no input changed. Wrong units (minutes under `time_s`,
//! seconds under `time_min`, 151H readings in a 152H file, °F, kg/m³ for G_s, t/m³ or metres in
//! `fit slump`) are refused with exit 2 naming the value, the likely unit and the fix; format
//! mistakes (mixed decimal marks, thousands separators, a decimal comma in a comma-separated
//! file, text, clock times and units in number cells) name the file, the line or the sheet's
//! cell and the column; doubtful values are warnings (console and `reduce.toml`), exit 0.
//! Fixtures: `tests/data/lab/` (written by `scripts/make_lab_fixtures.py`).

use crate::common::{settle, tmp, tree};
use std::path::Path;

/// One bad-input case: the command's arguments (a word equal to the name of one of `files` is
/// replaced by that file's path; `reduce` and `invert` get `--out`), the files, the expected
/// exit code and the words its message must contain (stderr for a refusal, stdout for exit 0).
struct Case {
    args: Vec<String>,
    files: Vec<(String, Vec<u8>)>,
    exit: i32,
    message_contains: Vec<&'static str>,
}

/// The readings sheet of the lab fixtures (D7928, 8 readings).
const D7928: &str = include_str!("../data/lab/utf8/soil_b3.csv");

const D422: &str = "# standard = d422\n# hydrometer = 152H\n# dry_mass_g = 50\n\
# specific_gravity = 2.65\n# meniscus_correction = 1\n# blank_reading = 6\n\
time_min,reading,temperature_c\n2,40,20\n5,35,20\n15,28,20\n60,20,20\n1440,10,20\n";

const PIPETTE: &str = "# instrument = pipette\n# dry_mass_g = 50\n# specific_gravity = 2.65\n\
# pipette_volume_ml = 10\n# pipette_depth_cm = 10\n# blank_reading = 0.005\n\
time_min,drawn_mass_g,temperature_c\n1,0.4,25\n10,0.2,25\n";

const SPHERE: &str = "# instrument = buoyancy-sphere\n# dry_mass_g = 50\n\
# specific_gravity = 2.65\n# sphere_diameter_mm = 25\n# sphere_mass_g = 20\n\
# sphere_depth_cm = 10\ntime_min,apparent_mass_g,temperature_c\n1,11.6,20\n10,11.7,20\n\
1440,11.9,20\n";

/// `text` as a spreadsheet on a Western-European Windows exports it: semicolons, decimal
/// commas, Windows-1252 (Latin-1), CRLF.
fn latin1(text: &str) -> Vec<u8> {
    let comma = |v: &str| {
        if v.parse::<f64>().is_ok() {
            v.replace('.', ",")
        } else {
            v.to_string()
        }
    };
    let lines: Vec<String> = text
        .lines()
        .map(|l| {
            if let Some((k, v)) = l.split_once('=').filter(|_| l.starts_with('#')) {
                format!("{k}= {}", comma(v.trim()))
            } else {
                l.split(',').map(comma).collect::<Vec<_>>().join(";")
            }
        })
        .collect();
    (lines.join("\r\n") + "\r\n")
        .chars()
        .map(|c| u8::try_from(u32::from(c)).expect("Latin-1"))
        .collect()
}

/// `text` with every `from` replaced by `to` (asserting there is one).
fn sub(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "`{from}` not in the base text");
    text.replace(from, to)
}

/// `text` with the table's column `col` (0-based) mapped by `f`.
fn map_col(text: &str, col: usize, f: impl Fn(&str) -> String) -> String {
    let mut header = true;
    text.lines()
        .map(|l| {
            if l.starts_with('#') {
                return l.to_string();
            }
            if header {
                header = false;
                return l.to_string();
            }
            let mut c: Vec<String> = l.split(',').map(str::to_string).collect();
            c[col] = f(&c[col]);
            c.join(",")
        })
        .collect::<Vec<_>>()
        .join("\n")
        + "\n"
}

fn file(name: &str, bytes: impl Into<Vec<u8>>) -> (String, Vec<u8>) {
    (name.to_string(), bytes.into())
}

fn fixture(name: &str) -> (String, Vec<u8>) {
    let path = Path::new("tests/data/lab").join(name);
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let base = path.file_name().unwrap().to_string_lossy().into_owned();
    (base, bytes)
}

fn case(
    args: &[&str],
    files: Vec<(String, Vec<u8>)>,
    exit: i32,
    message_contains: &[&'static str],
) -> Case {
    Case {
        args: args.iter().map(|a| a.to_string()).collect(),
        files,
        exit,
        message_contains: message_contains.to_vec(),
    }
}

/// A `settle reduce r.csv` case.
fn reduce(text: impl Into<Vec<u8>>, exit: i32, words: &[&'static str]) -> Case {
    case(&["reduce", "r.csv"], vec![file("r.csv", text)], exit, words)
}

/// A `settle invert r.csv` case.
fn invert(text: impl Into<Vec<u8>>, words: &[&'static str]) -> Case {
    case(
        &["invert", "r.csv", "--repeats", "0"],
        vec![file("r.csv", text)],
        2,
        words,
    )
}

/// A `settle reduce` case on a workbook fixture of `tests/data/lab/bad/`.
fn workbook(name: &str, words: &[&'static str]) -> Case {
    let f = fixture(&format!("bad/{name}"));
    let n = f.0.clone();
    Case {
        args: vec!["reduce".into(), n],
        files: vec![f],
        exit: 2,
        message_contains: words.to_vec(),
    }
}

fn slump(args: &[&str], exit: i32, words: &[&'static str]) -> Case {
    let mut a = vec!["fit", "slump"];
    a.extend_from_slice(args);
    case(&a, vec![], exit, words)
}

/// Minutes under `time_s`: the D7928 schedule 1 … 1440 read as seconds.
fn minutes_as_seconds(text: &str) -> String {
    sub(text, "time_min,", "time_s,")
}

/// Seconds under `time_min`.
fn seconds_as_minutes(text: &str) -> String {
    map_col(text, 0, |t| (t.parse::<f64>().unwrap() * 60.0).to_string())
}

/// Hours under `time_min`.
fn hours_as_minutes(text: &str) -> String {
    map_col(text, 0, |t| (t.parse::<f64>().unwrap() / 60.0).to_string())
}

/// Every refusal: exit 2, the words, nothing written.
fn refusals() -> Vec<Case> {
    let h151 = sub(
        &sub(D422, "152H", "151H"),
        "# meniscus_correction = 1\n# blank_reading = 6",
        "# meniscus_correction = 0.001\n# blank_reading = 1.001",
    );
    let h151_rows = "2,1.025,20\n5,1.020,20\n15,1.015,20\n60,1.010,20\n1440,1.005,20\n";
    let d422_table = |rows: &str| {
        format!(
            "{}time_min,reading,temperature_c\n{rows}",
            D422.split("time_min").next().unwrap()
        )
    };
    vec![
        // Wrong time units: refused with the likely unit and the fix.
        reduce(
            minutes_as_seconds(D7928),
            2,
            &[
                "row 1 (line 13), column 1 `time_s`",
                "1 s",
                "look like minutes",
                "time_min",
            ],
        ),
        reduce(
            seconds_as_minutes(D7928),
            2,
            &[
                "row 8 (line 20)",
                "86400 min",
                "look like seconds",
                "rename the column `time_s`",
            ],
        ),
        reduce(
            hours_as_minutes(D7928),
            2,
            &["`time_min`", "look like hours", "in minutes"],
        ),
        reduce(
            map_col(&minutes_as_seconds(D7928), 0, |t| {
                (t.parse::<f64>().unwrap() * 60_000.0).to_string()
            }),
            2,
            &["`time_s`", "14400000 is out of range", "milliseconds"],
        ),
        reduce(
            minutes_as_seconds(D422),
            2,
            &["`time_s`", "2 s", "time_min"],
        ),
        reduce(
            seconds_as_minutes(D422),
            2,
            &["`time_min`", "look like seconds"],
        ),
        reduce(
            minutes_as_seconds(PIPETTE),
            2,
            &["`time_s`", "look like minutes"],
        ),
        reduce(
            seconds_as_minutes(SPHERE),
            2,
            &["`time_min`", "86400 min", "look like seconds"],
        ),
        reduce(
            latin1(&minutes_as_seconds(D7928)),
            2,
            &["`time_s`", "look like minutes"],
        ),
        reduce(
            latin1(&seconds_as_minutes(D7928)),
            2,
            &["line 20", "look like seconds"],
        ),
        // A hydrometer's unit: 151H readings in a 152H file, and the reverse.
        reduce(
            d422_table(h151_rows),
            2,
            &[
                "key `hydrometer`",
                "151H readings",
                "set `# hydrometer = 151H`",
            ],
        ),
        reduce(
            format!(
                "{}time_min,reading,temperature_c\n2,40,20\n",
                h151.split("time_min").next().unwrap()
            ),
            2,
            &[
                "`reading`",
                "40 is out of range",
                "a 152H reading in g/L",
                "`# hydrometer = 152H`",
            ],
        ),
        reduce(
            d422_table("2,1025,20\n"),
            2,
            &[
                "`reading`",
                "1025 is out of range",
                "151H reading times 1000",
            ],
        ),
        // Temperatures in °F.
        reduce(
            map_col(D7928, 2, |_| "70.7".into()),
            2,
            &["column 3 `temperature_c`", "70.7", "°F", "21.5 °C"],
        ),
        reduce(
            sub(PIPETTE, "1,0.4,25", "1,0.4,77"),
            2,
            &["`temperature_c`", "77", "°F", "25 °C"],
        ),
        reduce(
            sub(
                &sub(D422, "time_min,reading,temperature_c", "time_min,reading"),
                "# blank_reading = 6",
                "# blank_reading = 6\n# temperature_c = 68",
            )
            .replace(",20\n", "\n"),
            2,
            &["key `temperature_c`", "68", "°F", "20 °C"],
        ),
        // Figures in the wrong unit.
        reduce(
            sub(D7928, "specific_gravity = 2.7", "specific_gravity = 2700"),
            2,
            &[
                "key `specific_gravity`",
                "line 6",
                "2700",
                "kg/m³",
                "give 2.7",
            ],
        ),
        reduce(
            sub(D422, "specific_gravity = 2.65", "specific_gravity = 2650"),
            2,
            &["`specific_gravity`", "give 2.65"],
        ),
        reduce(
            sub(
                D422,
                "# blank_reading = 6",
                "# blank_reading = 6\n# suspension_volume_ml = 1",
            ),
            2,
            &["key `suspension_volume_ml`", "litres", "1000"],
        ),
        reduce(
            sub(
                D422,
                "# blank_reading = 6",
                "# blank_reading = 6\n# column_height_cm = 0.457",
            ),
            2,
            &["key `column_height_cm`", "metres", "45.7"],
        ),
        reduce(
            sub(D7928, "h_r1_cm = 20.3", "h_r1_cm = 0.05"),
            2,
            &["key `h_r1_cm`", "metres", "give centimetres: 5"],
        ),
        reduce(
            sub(
                D422,
                "# blank_reading = 6",
                "# blank_reading = 6\n# fluid_density_kg_m3 = 1.0",
            ),
            2,
            &["key `fluid_density_kg_m3`", "g/cm³", "1000"],
        ),
        reduce(
            sub(
                SPHERE,
                "sphere_diameter_mm = 25",
                "sphere_diameter_mm = 0.25",
            ),
            2,
            &["key `sphere_diameter_mm`", "0.25", "millimetres"],
        ),
        reduce(
            sub(PIPETTE, "1,0.4,25", "1,400,25"),
            2,
            &["`drawn_mass_g`", "400", "milligrams", "0.4 g"],
        ),
        reduce(
            sub(SPHERE, "1,11.6,20", "1,11600,20"),
            2,
            &["`apparent_mass_g`", "milligrams", "11.6 g"],
        ),
        // The format layer: decimal marks, thousands, delimiters.
        reduce(
            "time_min;reading;temperature_c\n1;44,5;21.5\n",
            2,
            &[
                "both decimal marks",
                "`44,5` (line 2, column 2)",
                "`21.5` (line 2, column 3)",
            ],
        ),
        reduce(
            format!(
                "{}time_min;reading;temperature_c\n2;1.040,5;20\n",
                D422.split("time_min").next().unwrap()
            ),
            2,
            &["line 8, column 2", "`1.040,5`", "thousands separator"],
        ),
        reduce(
            "time_min\treading\ttemperature_c\n1\t44,5\t21.5\n",
            2,
            &["both decimal marks"],
        ),
        reduce(
            d422_table("2,40,5,20\n"),
            2,
            &[
                "row 1 (line 8)",
                "4 fields, the header has 3",
                "decimal comma",
            ],
        ),
        reduce(
            sub(D7928, "1,44.5,21.5,6.25", "1,44.5 g/L,21.5,6.25"),
            2,
            &[
                "row 1 (line 13), column 2 `reading`",
                "`44.5 g/L`",
                "the unit is the column's",
            ],
        ),
        reduce(
            sub(D7928, "2,40.0,21.5", "0:02,40.0,21.5"),
            2,
            &["row 2 (line 14), column 1 `time_min`", "clock time"],
        ),
        reduce(
            sub(D7928, "4,35.5,21.5", "4,,21.5"),
            2,
            &["row 3 (line 15), column 2 `reading`", "empty"],
        ),
        reduce(
            sub(D7928, "dry_mass_g = 48.797", "dry_mass_g = 48,797"),
            2,
            &[
                "key `dry_mass_g`",
                "line 5",
                "`48,797` is not a number",
                "decimal comma",
            ],
        ),
        // The same mistakes in a Latin-1, semicolon, decimal-comma CSV.
        reduce(
            latin1(&sub(D7928, "4,35.5,21.5", "4,61.5,21.5")),
            2,
            &[
                "row 3 (line 15), column 2 `reading`",
                "61.5 is out of range",
                "-5 to 60",
            ],
        ),
        reduce(
            latin1(&sub(D7928, "4,35.5", "1,35.5")),
            2,
            &["row 3 (line 15), column 1 `time_min`", "not after"],
        ),
        reduce(
            latin1(&sub(D7928, "4,35.5", "4,vierzig")),
            2,
            &[
                "row 3 (line 15), column 2 `reading`",
                "`vierzig` is not a number",
            ],
        ),
        reduce(
            latin1(&sub(D7928, "# dry_mass_g = 48.797\n", "")),
            2,
            &["key `dry_mass_g`", "missing"],
        ),
        reduce(
            latin1(&sub(D7928, "temperature_c", "temperature_°c")),
            2,
            &["column 3", "unknown column `temperature_°c`"],
        ),
        // Workbooks: errors name the sheet and the cell.
        workbook(
            "text_reading.xlsx",
            &["row 3 (cell Sheet1!B15), column 2 `reading`", "`forty`"],
        ),
        workbook(
            "comma_text.xlsx",
            &["cell Sheet1!B13", "`44,5`", "format the cell as a number"],
        ),
        workbook(
            "time_cell.xlsx",
            &["cell Sheet1!A14", "`time_min`", "clock time"],
        ),
        workbook(
            "unknown_key.xlsx",
            &["key `dry_mas_g`", "cell Sheet1!A5", "unknown key"],
        ),
        workbook(
            "minutes_as_seconds.xlsx",
            &["cell Sheet1!A13", "`time_s`", "look like minutes"],
        ),
        workbook("fahrenheit.xlsx", &["cell Sheet1!C13", "°F"]),
        workbook(
            "density_for_gs.xlsx",
            &["key `specific_gravity`", "cell Sheet1!A6", "give 2.7"],
        ),
        workbook(
            "off_scale.xlsx",
            &["row 4 (cell Sheet1!B16)", "99 is out of range"],
        ),
        case(
            &["reduce", "r.xlsx"],
            vec![file("r.xlsx", D7928)],
            2,
            &["r.xlsx", "not a workbook", "save it as .xlsx, .ods or CSV"],
        ),
        // invert reads through the same checks.
        invert(
            minutes_as_seconds(D7928),
            &["`time_s`", "look like minutes"],
        ),
        invert(
            seconds_as_minutes(D7928),
            &["`time_min`", "look like seconds"],
        ),
        invert(d422_table(h151_rows), &["151H readings"]),
        invert(
            latin1(&sub(D7928, "4,35.5", "4,vierzig")),
            &["line 15", "`vierzig`"],
        ),
        // The template.
        case(
            &["reduce", "--template", "d9999"],
            vec![],
            2,
            &["--template", "d9999", "allowed: d7928, d422"],
        ),
        // A template reduced before it is filled in.
        case(
            &["reduce", "r.csv"],
            vec![file("r.csv", settle::reduce::template("d7928").unwrap())],
            2,
            &["row 1", "column 2 `reading`", "empty"],
        ),
        // fit slump: t/m³, metres.
        slump(
            &[
                "--height-mm",
                "152",
                "--slump-mm",
                "102,103",
                "--density",
                "1.843",
            ],
            2,
            &["--density", "1.843", "t/m³", "--density 1843"],
        ),
        slump(
            &[
                "--height-mm",
                "0.152",
                "--slump-mm",
                "0.102",
                "--density",
                "1843",
            ],
            2,
            &["--height-mm", "0.152", "metres", "--height-mm 152"],
        ),
        slump(
            &[
                "--height-mm",
                "152",
                "--slump-mm",
                "0.102,0.103",
                "--density",
                "1843",
            ],
            2,
            &["--slump-mm", "metres", "--slump-mm 102,103"],
        ),
        slump(
            &[
                "--height-mm",
                "152",
                "--slump-mm",
                "102",
                "--density",
                "2.1",
            ],
            2,
            &["t/m³", "--density 2100"],
        ),
    ]
}

/// Doubtful values: exit 0 with a warning in the console (and in reduce.toml's warnings).
fn warnings() -> Vec<Case> {
    vec![
        reduce(
            sub(D7928, "specific_gravity = 2.7", "specific_gravity = 1.8"),
            0,
            &["warning:", "specific_gravity 1.8", "outside 2.0–3.5"],
        ),
        reduce(
            sub(D422, "specific_gravity = 2.65", "specific_gravity = 4.2"),
            0,
            &["warning:", "specific_gravity 4.2"],
        ),
        reduce(
            sub(PIPETTE, "1,0.4,25", "1,0.4,5"),
            0,
            &["warning:", "temperature 5 °C", "10–40 °C"],
        ),
        reduce(
            sub(D422, "2,40,20", "0.4,0,20"),
            0,
            &["warning:", "above the 75 µm sieve"],
        ),
        reduce(
            sub(
                &minutes_as_seconds(D422),
                "# dry_mass_g",
                "# source = settle 0.1.0 virtual test\n# dry_mass_g",
            ),
            0,
            &["warning:", "look like minutes", "virtual test: warned only"],
        ),
        slump(
            &["--height-mm", "30", "--slump-mm", "10", "--density", "1843"],
            0,
            &[
                "warning:",
                "mini-slump cone (57 mm)",
                "in centimetres? 300 mm",
            ],
        ),
        slump(
            &[
                "--height-mm",
                "400",
                "--slump-mm",
                "200",
                "--density",
                "1843",
            ],
            0,
            &["warning:", "ASTM C143 cone (300 mm)"],
        ),
        slump(
            &[
                "--height-mm",
                "152",
                "--slump-mm",
                "100",
                "--density",
                "3500",
            ],
            0,
            &["warning:", "--density 3500", "1000–3150"],
        ),
        slump(
            &[
                "--height-mm",
                "152",
                "--slump-mm",
                "100",
                "--density",
                "900",
            ],
            0,
            &["warning:", "--density 900"],
        ),
    ]
}

/// Words no message may hold: a programmer's, not a lab engineer's.
const JARGON: [&str; 7] = [
    "invalid digit",
    "expected f64",
    "ParseFloat",
    "Utf8Error",
    "stream did not contain valid UTF-8",
    "os error",
    "panicked",
];

/// Runs one case in a fresh folder; returns a description of what went wrong, if anything.
fn run(k: usize, c: &Case) -> Option<String> {
    let dir = tmp();
    let inputs = dir.path().join("in");
    std::fs::create_dir(&inputs).unwrap();
    for (name, bytes) in &c.files {
        std::fs::write(inputs.join(name), bytes).unwrap();
    }
    let out = dir.path().join("out");
    let mut cmd = settle();
    for a in &c.args {
        if c.files.iter().any(|(n, _)| n == a) {
            cmd.arg(inputs.join(a));
        } else {
            cmd.arg(a);
        }
    }
    let writes = matches!(c.args[0].as_str(), "reduce" | "invert")
        && !c.args.iter().any(|a| a == "--template");
    if writes {
        cmd.arg("--out").arg(&out);
    }
    let o = cmd.output().expect("spawn settle");
    let stdout = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    let said = if c.exit == 0 { &stdout } else { &stderr };
    let mut wrong = Vec::new();
    if o.status.code() != Some(c.exit) {
        wrong.push(format!("exit {:?}, expected {}", o.status.code(), c.exit));
    }
    for w in &c.message_contains {
        if !said.contains(w) {
            wrong.push(format!("no `{w}`"));
        }
    }
    for j in JARGON {
        if stderr.contains(j) || stdout.contains(j) {
            wrong.push(format!("jargon `{j}`"));
        }
    }
    if c.exit != 0 {
        if out.exists() && !tree(&out).is_empty() {
            wrong.push(format!("wrote {:?}", tree(&out)));
        }
        if stderr.trim().lines().count() != 1 {
            wrong.push("not one error line".into());
        }
        if let Some((name, _)) = c.files.first() {
            if !stderr.contains(name.as_str()) && c.args[0] != "fit" {
                wrong.push(format!("the message does not name {name}"));
            }
        }
    } else if writes && c.args[0] == "reduce" {
        let toml = out.join("r_reduced/reduce.toml");
        match std::fs::read_to_string(&toml) {
            Ok(t) => {
                let w = t.split("warnings = ").nth(1).unwrap_or("");
                if !c.message_contains[1..].iter().all(|m| w.contains(m)) {
                    wrong.push(format!("reduce.toml's warnings lack the message: {w}"));
                }
            }
            Err(e) => wrong.push(format!("no reduce.toml: {e}")),
        }
    }
    for (name, bytes) in &c.files {
        if std::fs::read(inputs.join(name)).ok().as_ref() != Some(bytes) {
            wrong.push(format!("{name} changed"));
        }
    }
    (!wrong.is_empty()).then(|| {
        format!(
            "case {k} ({}): {}\n  stdout: {stdout}\n  stderr: {stderr}",
            c.args.join(" "),
            wrong.join("; ")
        )
    })
}

fn run_all(cases: &[Case]) {
    let failures: Vec<String> = std::thread::scope(|s| {
        let chunks: Vec<_> = cases
            .chunks(cases.len().div_ceil(4).max(1))
            .enumerate()
            .map(|(i, ch)| {
                let base = i * cases.len().div_ceil(4).max(1);
                s.spawn(move || {
                    ch.iter()
                        .enumerate()
                        .filter_map(|(j, c)| run(base + j, c))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        chunks.into_iter().flat_map(|h| h.join().unwrap()).collect()
    });
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// Every clear mistake of a lab file is refused: exit 2, one line naming the file, where
/// (line or sheet cell, column) and the fix; nothing written, no input changed.
#[test]
fn bad_lab_inputs_are_refused_with_the_fix() {
    let cases = refusals();
    assert!(cases.len() >= 50, "{} cases", cases.len());
    run_all(&cases);
}

/// Every doubtful value is reduced with a warning in the console and reduce.toml.
#[test]
fn doubtful_lab_values_are_warned() {
    run_all(&warnings());
}
