//! Particle files of a sedimentation run: the `snapshots/` (CSV and VTK PolyData); the picture
//! of the cylinder (seed Fig. 11) is [`super::cylinder`].

use crate::io::fmt::num;
use crate::scenes::sedimentation::state::State;
use std::io::Write;
use std::path::Path;

/// Writes the grains of `st` to `dir/t<time>s.csv` (x, y, diameter, weight, settled) and
/// `dir/t<time>s.vtp` (VTK PolyData for ParaView: points with diameter and weight).
pub fn write_snapshot(dir: &Path, st: &State) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let stem = format!("t{:08.1}s", st.time_s);
    let mut w =
        csv::Writer::from_path(dir.join(format!("{stem}.csv"))).map_err(std::io::Error::other)?;
    w.write_record(["x_m", "y_m", "diameter_m", "weight", "settled"])
        .map_err(std::io::Error::other)?;
    for (g, s) in st.grains.iter().zip(&st.settled) {
        w.write_record([
            num(g.x_m),
            num(g.y_m),
            num(g.diameter_m),
            num(g.weight),
            s.to_string(),
        ])
        .map_err(std::io::Error::other)?;
    }
    w.flush()?;
    // VTK PolyData (ASCII .vtp) for ParaView: points with diameter and weight.
    let mut f = std::io::BufWriter::new(std::fs::File::create(dir.join(format!("{stem}.vtp")))?);
    let n = st.grains.len();
    writeln!(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>")?;
    writeln!(f, "<Piece NumberOfPoints=\"{n}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">")?;
    writeln!(f, "<PointData Scalars=\"diameter_m\">\n<DataArray type=\"Float64\" Name=\"diameter_m\" format=\"ascii\">")?;
    for g in &st.grains {
        write!(f, "{:e} ", g.diameter_m)?;
    }
    writeln!(
        f,
        "\n</DataArray>\n<DataArray type=\"Float64\" Name=\"weight\" format=\"ascii\">"
    )?;
    for g in &st.grains {
        write!(f, "{:e} ", g.weight)?;
    }
    writeln!(f, "\n</DataArray>\n</PointData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">")?;
    for g in &st.grains {
        write!(f, "{:e} {:e} 0 ", g.x_m, g.y_m)?;
    }
    writeln!(
        f,
        "\n</DataArray>\n</Points>\n</Piece>\n</PolyData>\n</VTKFile>"
    )?;
    f.flush()
}
