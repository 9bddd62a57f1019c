//! Pictures and particle files of a sedimentation run: `cylinder.png` (seed Fig. 11) and the
//! `snapshots/` (CSV and VTK PolyData).

use crate::io::num;
use crate::scenes::sedimentation::state::State;
use std::io::{self, Write};
use std::path::Path;

/// Draws the cylinder at each snapshot time side by side: grey level = mass fraction per band
/// (black = the largest band fraction in suspension; the bed saturates), like seed Fig. 11. PNG;
/// panels in the order of `snapshot_times_s`, each topped by one tick per minute (up to 15).
pub fn draw_cylinder(path: &Path, pictures: &[(f64, Vec<f64>)]) -> io::Result<()> {
    use plotters::prelude::*;
    let (pw, ph, gap) = (80u32, 640u32, 40u32);
    let width = pictures.len() as u32 * (pw + gap) + gap;
    let root = BitMapBackend::new(path, (width, ph + 60)).into_drawing_area();
    root.fill(&WHITE)
        .map_err(|e| io::Error::other(e.to_string()))?;
    // Grey scale set by the suspension (the bottom band, with the bed, saturates to black).
    let fmax = pictures
        .iter()
        .flat_map(|p| p.1[..p.1.len().saturating_sub(1)].iter().copied())
        .fold(1e-300, f64::max);
    for (i, (t, f)) in pictures.iter().enumerate() {
        let t = *t;
        let x0 = (gap + i as u32 * (pw + gap)) as i32;
        let bands = f.len() as f64;
        for (k, frac) in f.iter().enumerate() {
            let grey = (255.0 * (1.0 - (frac / fmax).min(1.0))).round() as u8;
            let y0 = 30 + (k as f64 / bands * ph as f64) as i32;
            let y1 = 30 + ((k + 1) as f64 / bands * ph as f64).ceil() as i32;
            root.draw(&Rectangle::new(
                [(x0, y0), (x0 + pw as i32, y1)],
                RGBColor(grey, grey, grey).filled(),
            ))
            .map_err(|e| io::Error::other(e.to_string()))?;
        }
        root.draw(&Rectangle::new(
            [(x0, 30), (x0 + pw as i32, 30 + ph as i32)],
            BLACK.stroke_width(1),
        ))
        .map_err(|e| io::Error::other(e.to_string()))?;
        // Time marks as ticks above the panel, one per 60 s up to 15 (no fonts in the bitmap
        // backend; the panel times are the snapshot times, in order).
        let ticks = ((t / 60.0).round() as i32).clamp(1, 15);
        for j in 0..ticks {
            let x = x0 + 4 + j * 5;
            root.draw(&Rectangle::new([(x, 10), (x + 2, 22)], BLACK.filled()))
                .map_err(|e| io::Error::other(e.to_string()))?;
        }
    }
    root.present().map_err(|e| io::Error::other(e.to_string()))
}

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
