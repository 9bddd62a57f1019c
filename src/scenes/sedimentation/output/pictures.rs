//! Particle files of a sedimentation run: the `snapshots/` (CSV and VTK PolyData); the picture
//! of the cylinder (seed Fig. 11) is [`super::cylinder`].

use crate::io::fmt::num;
use crate::io::{Outputs, Table};
use crate::sample::Grains;
use crate::scenes::sedimentation::state::State;
use std::fmt::Write;

/// Adds the grains of `st` (the setup's `grains`) to `out` as `snapshots/t<time>s.csv` (x, y,
/// diameter, weight, settled) and `snapshots/t<time>s.vtp` (VTK PolyData for ParaView: points
/// with diameter and weight).
pub fn write_snapshot(out: &mut Outputs, st: &State, grains: &Grains) {
    let stem = format!("snapshots/t{:08.1}s", st.time_s);
    let mut t = Table::new(
        format!("{stem}.csv"),
        ["x_m", "y_m", "diameter_m", "weight", "settled"],
    );
    for (i, s) in st.settled.iter().enumerate() {
        let g = st.grain(grains, i);
        t.push(vec![
            num(g.x_m),
            num(g.y_m),
            num(g.diameter_m),
            num(g.weight),
            s.to_string(),
        ]);
    }
    out.table(t);
    out.file(format!("{stem}.vtp"), vtp(st, grains));
}

/// The grains of `st` (the setup's `grains`) as a VTK PolyData file (ASCII `.vtp`): points with
/// diameter and weight.
fn vtp(st: &State, grains: &Grains) -> String {
    let mut f = String::new();
    let n = st.len();
    let all = || (0..n).map(|i| st.grain(grains, i));
    // Writing to a String cannot fail.
    let _ = writeln!(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>");
    let _ = writeln!(f, "<Piece NumberOfPoints=\"{n}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">");
    let _ = writeln!(f, "<PointData Scalars=\"diameter_m\">\n<DataArray type=\"Float64\" Name=\"diameter_m\" format=\"ascii\">");
    for g in all() {
        let _ = write!(f, "{:e} ", g.diameter_m);
    }
    let _ = writeln!(
        f,
        "\n</DataArray>\n<DataArray type=\"Float64\" Name=\"weight\" format=\"ascii\">"
    );
    for g in all() {
        let _ = write!(f, "{:e} ", g.weight);
    }
    let _ = writeln!(f, "\n</DataArray>\n</PointData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">");
    for g in all() {
        let _ = write!(f, "{:e} {:e} 0 ", g.x_m, g.y_m);
    }
    let _ = writeln!(
        f,
        "\n</DataArray>\n</Points>\n</Piece>\n</PolyData>\n</VTKFile>"
    );
    f
}
