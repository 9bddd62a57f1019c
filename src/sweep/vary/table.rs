//! The table of a parameter sweep (`vary.csv`, `vary_part_I_of_N.csv`): one row per case and
//! body. Columns: the varied keys (named as `--vary` gave them; a categorical key's cells hold
//! the value's text), `body`, the result quantities
//! (units in their names; `reference_<quantity>` beside a quantity that has an analytic or
//! force-balance reference), then `status`, `steps`, `wall_time_s`, `reason`.

use super::super::table::{Row, Status};
use super::super::targets::has_reference;
use super::grid::Level;
use crate::io::fmt::num;
use crate::io::Table;
use std::io;
use std::path::Path;

/// The columns after the results.
const TAIL: [&str; 4] = ["status", "steps", "wall_time_s", "reason"];

/// One body in one case of a parameter sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct VaryRow {
    /// The values of the varied keys, in the order of [`VaryTable::keys`].
    pub point: Vec<Level>,
    /// Body identifier (`all` for a quantity of the whole scene).
    pub body: String,
    /// The results, in the order of [`VaryTable::results`] (NaN: none, or unstable).
    pub results: Vec<f64>,
    /// Stable or unstable.
    pub status: Status,
    /// Steps of this body.
    pub steps: u64,
    /// Wall time of the whole case, s.
    pub wall_time_s: f64,
    /// Why unstable (empty if stable).
    pub reason: String,
}

/// A parameter sweep's table.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct VaryTable {
    /// The varied keys.
    pub keys: Vec<String>,
    /// The result columns: quantity names with their units (and `reference_…`).
    pub results: Vec<String>,
    /// Rows in canonical order ([`VaryTable::sort`]).
    pub rows: Vec<VaryRow>,
}

impl VaryTable {
    /// The table of `cases` (the point of each case and the rows its run gave, as a dt sweep's
    /// [`Row`]s), in canonical order.
    pub fn from_cases(keys: &[String], cases: Vec<(Vec<Level>, Vec<Row>)>) -> Self {
        let mut t = Self {
            keys: keys.to_vec(),
            ..Self::default()
        };
        for (_, rows) in &cases {
            for r in rows {
                if !t.results.contains(&r.quantity) {
                    t.results.push(r.quantity.clone());
                    if has_reference(&r.quantity) {
                        t.results.push(format!("reference_{}", r.quantity));
                    }
                }
            }
        }
        for (point, rows) in cases {
            let mut bodies: Vec<VaryRow> = Vec::new();
            for r in rows {
                let i = match bodies.iter().position(|b| b.body == r.body) {
                    Some(i) => i,
                    None => {
                        bodies.push(VaryRow {
                            point: point.clone(),
                            body: r.body.clone(),
                            results: vec![f64::NAN; t.results.len()],
                            status: r.status,
                            steps: r.steps,
                            wall_time_s: r.wall_time_s,
                            reason: r.reason.clone(),
                        });
                        bodies.len() - 1
                    }
                };
                let b = &mut bodies[i];
                let col = |name: &str| t.results.iter().position(|c| c == name);
                if let Some(c) = col(&r.quantity) {
                    b.results[c] = r.value;
                }
                if let Some(c) = col(&format!("reference_{}", r.quantity)) {
                    b.results[c] = r.reference;
                }
            }
            t.rows.extend(bodies);
        }
        t.sort();
        t
    }

    /// Canonical order: cases by their key values (first key first, ascending by
    /// [`Level::order`]); within a case
    /// the bodies keep the scenario's order. A case's rows are never split between shards, so
    /// merged parts equal the unsharded table row for row.
    pub fn sort(&mut self) {
        self.rows.sort_by(|a, b| {
            a.point
                .iter()
                .zip(&b.point)
                .map(|(x, y)| x.order(y))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        });
    }

    /// Adds the rows of `other` (a part of the same sweep): its keys must be the same; result
    /// columns it lacks are NaN, and columns only it has are added.
    pub fn merge(&mut self, other: VaryTable) -> Result<(), String> {
        if self.keys.is_empty() && self.rows.is_empty() {
            *self = other;
            return Ok(());
        }
        if other.keys != self.keys {
            return Err(format!(
                "varies {} where the other parts vary {}",
                other.keys.join(", "),
                self.keys.join(", ")
            ));
        }
        for c in &other.results {
            if !self.results.contains(c) {
                self.results.push(c.clone());
                for r in &mut self.rows {
                    r.results.push(f64::NAN);
                }
            }
        }
        for mut r in other.rows {
            let values = std::mem::take(&mut r.results);
            r.results = self
                .results
                .iter()
                .map(|c| {
                    other
                        .results
                        .iter()
                        .position(|o| o == c)
                        .map_or(f64::NAN, |i| values[i])
                })
                .collect();
            self.rows.push(r);
        }
        Ok(())
    }

    /// The CSV header.
    pub fn header(&self) -> Vec<String> {
        let mut h = self.keys.clone();
        h.push("body".into());
        h.extend(self.results.iter().cloned());
        h.extend(TAIL.iter().map(|s| s.to_string()));
        h
    }

    /// The table as the CSV file `name` holds it (`vary.csv`, a part file).
    pub fn to_table(&self, name: &str) -> Table {
        let rows: Vec<Vec<String>> = self
            .rows
            .iter()
            .map(|r| {
                let mut v: Vec<String> = r.point.iter().map(Level::to_string).collect();
                v.push(r.body.clone());
                v.extend(r.results.iter().map(|x| num(*x)));
                v.push(
                    match r.status {
                        Status::Stable => "stable",
                        Status::Unstable => "unstable",
                    }
                    .into(),
                );
                v.push(r.steps.to_string());
                v.push(num(r.wall_time_s));
                v.push(r.reason.clone());
                v
            })
            .collect();
        Table::with_rows(name, self.header(), rows)
    }

    /// Writes the table to `path` atomically.
    pub fn write(&self, path: &Path) -> io::Result<()> {
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("vary.csv");
        crate::io::write_atomic(path, &self.to_table(name).to_csv()?)
    }

    /// Reads a table written by [`VaryTable::write`]; the error says what is wrong.
    pub fn read(path: &Path) -> Result<Self, String> {
        Self::from_csv(std::fs::File::open(path).map_err(|e| e.to_string())?)
    }

    /// Reads the CSV text of a table ([`VaryTable::write`]'s bytes); the error says what is
    /// wrong.
    pub fn from_csv(text: impl io::Read) -> Result<Self, String> {
        let mut rdr = csv::Reader::from_reader(text);
        let header: Vec<String> = rdr
            .headers()
            .map_err(|e| e.to_string())?
            .iter()
            .map(str::to_string)
            .collect();
        let body = header.iter().position(|h| h == "body");
        let tail = header.len().checked_sub(TAIL.len());
        let (Some(body), Some(tail)) = (body, tail) else {
            return Err("no `body` column: not a parameter sweep table".into());
        };
        if body > tail || header[tail..] != TAIL {
            return Err(format!(
                "the last columns are not {}: not a parameter sweep table",
                TAIL.join(", ")
            ));
        }
        let mut t = Self {
            keys: header[..body].to_vec(),
            results: header[body + 1..tail].to_vec(),
            rows: Vec::new(),
        };
        let f = |s: &str| s.trim().parse::<f64>().unwrap_or(f64::NAN);
        for rec in rdr.records() {
            let rec = rec.map_err(|e| e.to_string())?;
            let cell = |i: usize| rec.get(i).unwrap_or("");
            let status = match cell(tail) {
                "stable" => Status::Stable,
                "unstable" => Status::Unstable,
                s => return Err(format!("status `{s}`: allowed stable, unstable")),
            };
            t.rows.push(VaryRow {
                point: (0..body).map(|i| Level::parse(cell(i))).collect(),
                body: cell(body).to_string(),
                results: (body + 1..tail).map(|i| f(cell(i))).collect(),
                status,
                steps: cell(tail + 1).trim().parse().unwrap_or(0),
                wall_time_s: f(cell(tail + 2)),
                reason: cell(tail + 3).to_string(),
            });
        }
        Ok(t)
    }
}
