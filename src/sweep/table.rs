//! The sweep table (`sweep.csv`, `sweep_part_I_of_N.csv`): one typed [`Row`] per integrator,
//! dt, body and quantity; CSV read and write (serde); [`finish`] fills the error against the
//! finest stable dt and puts rows in their canonical order.

use crate::dynamics::Integrator;
use crate::io::fmt::num;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::collections::BTreeMap;
use std::io;

/// Whether a case ran to the end.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Ran to the end; values are measured.
    Stable,
    /// Stopped by the stability monitor; values are NaN and `reason` says why.
    Unstable,
}

/// One row of a sweep: a quantity of a body in a case. The columns of `sweep.csv` are its
/// fields, in this order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// Integrator.
    pub integrator: Integrator,
    /// Time step, s.
    #[serde(serialize_with = "ser_num", deserialize_with = "de_num")]
    pub dt_s: f64,
    /// Stable or unstable.
    pub status: Status,
    /// Why unstable (empty if stable).
    pub reason: String,
    /// Wall time of the whole case, s.
    #[serde(serialize_with = "ser_num", deserialize_with = "de_num")]
    pub wall_time_s: f64,
    /// Steps of this body.
    #[serde(deserialize_with = "de_steps")]
    pub steps: u64,
    /// Body identifier (`all` for a quantity of the whole scene).
    pub body: String,
    /// Quantity name (`terminal_velocity_m_s`, `velocity_at_0.01s_m_s`, …).
    pub quantity: String,
    /// Value (NaN if unstable), in the unit its name gives.
    #[serde(serialize_with = "ser_num", deserialize_with = "de_num")]
    pub value: f64,
    /// Analytic or force-balance reference (NaN if none).
    #[serde(serialize_with = "ser_num", deserialize_with = "de_num")]
    pub reference: f64,
    /// Relative error against the reference, (value − reference)/reference.
    #[serde(serialize_with = "ser_num", deserialize_with = "de_num")]
    pub error_vs_reference: f64,
    /// Relative error against the finest stable dt of the same integrator (filled by `finish`).
    #[serde(serialize_with = "ser_num", deserialize_with = "de_num")]
    pub error_vs_finest: f64,
}

/// Column names of `sweep.csv`.
pub const HEADER: [&str; 12] = [
    "integrator",
    "dt_s",
    "status",
    "reason",
    "wall_time_s",
    "steps",
    "body",
    "quantity",
    "value",
    "reference",
    "error_vs_reference",
    "error_vs_finest",
];

fn ser_num<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&num(*x))
}

/// A number, NaN when the cell is empty or not a number (as written for unstable cases).
fn de_num<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    let s = String::deserialize(d)?;
    Ok(s.trim().parse().unwrap_or(f64::NAN))
}

fn de_steps<'de, D: Deserializer<'de>>(d: D) -> Result<u64, D::Error> {
    let s = String::deserialize(d)?;
    Ok(s.trim().parse().unwrap_or(0))
}

/// Relative difference (a − b)/b; 0 when both are 0, ∞ when only b is.
pub fn rel(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        if a == 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    } else {
        (a - b) / b
    }
}

/// Position of an integrator in [`Integrator::ALL`]: the row order.
pub fn integrator_rank(i: Integrator) -> usize {
    Integrator::ALL
        .iter()
        .position(|&x| x == i)
        .unwrap_or(Integrator::ALL.len())
}

/// Fills `error_vs_finest`: for each (integrator, body, quantity), relative to the value at the
/// finest dt whose case is stable. Rows are sorted by integrator order, dt descending, body,
/// quantity, so that merged shards equal an unsharded sweep row for row.
pub fn finish(rows: &mut [Row]) {
    rows.sort_by(|a, b| {
        integrator_rank(a.integrator)
            .cmp(&integrator_rank(b.integrator))
            .then(b.dt_s.total_cmp(&a.dt_s))
            .then(a.body.cmp(&b.body))
            .then(a.quantity.cmp(&b.quantity))
    });
    type Key = (usize, String, String);
    let key = |r: &Row| -> Key {
        (
            integrator_rank(r.integrator),
            r.body.clone(),
            r.quantity.clone(),
        )
    };
    let mut finest: BTreeMap<Key, (f64, f64)> = BTreeMap::new();
    for r in rows.iter().filter(|r| r.status == Status::Stable) {
        let e = finest.entry(key(r)).or_insert((f64::INFINITY, f64::NAN));
        if r.dt_s < e.0 {
            *e = (r.dt_s, r.value);
        }
    }
    for r in rows.iter_mut() {
        r.error_vs_finest = match finest.get(&key(r)) {
            Some((_, v)) if r.status == Status::Stable => rel(r.value, *v),
            _ => f64::NAN,
        };
    }
}

/// The rows as CSV text (header [`HEADER`], numbers as [`num`] prints them).
pub fn to_csv(rows: &[Row]) -> io::Result<Vec<u8>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    if rows.is_empty() {
        w.write_record(HEADER).map_err(io::Error::other)?;
    }
    for r in rows {
        w.serialize(r).map_err(io::Error::other)?;
    }
    w.into_inner().map_err(|e| io::Error::other(e.to_string()))
}

/// Reads rows written by [`to_csv`].
pub fn from_csv(rdr: impl io::Read) -> Result<Vec<Row>, csv::Error> {
    csv::Reader::from_reader(rdr).deserialize().collect()
}

/// Writes rows to `path` atomically (see [`crate::io::write_atomic`]).
pub fn write_rows(path: &std::path::Path, rows: &[Row]) -> io::Result<()> {
    crate::io::write_atomic(path, &to_csv(rows)?)
}

/// Reads a file written by [`write_rows`].
#[cfg(test)]
pub fn read_rows(path: &std::path::Path) -> Result<Vec<Row>, csv::Error> {
    from_csv(std::fs::File::open(path)?)
}
