//! Particle files of a sedimentation run: the `snapshots/` (CSV and VTK PolyData); the picture
//! of the cylinder (seed Fig. 11) is [`super::cylinder`].
//!
//! A snapshot has a row per grain, so its files are as large as the run's state: its table
//! holds typed columns ([`Cells`]), the horizontal positions, diameters and weights shared by
//! every snapshot ([`GrainColumns`]), and its `.vtp` file is written from those same columns
//! when the outputs are written ([`Outputs::made_file`]). At N = 10⁶ this keeps the outputs of
//! three snapshots in about 50 B per grain, not 1.4 kB (the cells as strings and the VTK text,
//! held until the end of the run).

use crate::io::{Cells, Outputs, Table};
use crate::sample::Grains;
use std::io::{self, Write};
use std::sync::Arc;

/// The columns of the grains that do not change during a run (without contacts, the horizontal
/// position too), shared by the files of every snapshot.
#[derive(Clone, Debug)]
pub struct GrainColumns {
    /// Horizontal position of each grain at the start, m.
    pub x_m: Arc<[f64]>,
    /// Diameter of each grain, m.
    pub diameter_m: Arc<[f64]>,
    /// Real grains each representative grain stands for.
    pub weight: Arc<[f64]>,
}

impl GrainColumns {
    /// The columns of `grains`.
    pub fn of(grains: &Grains) -> Self {
        let kinds = || (0..grains.len()).map(|i| grains.kind_of(i));
        Self {
            x_m: grains.x_m.as_slice().into(),
            diameter_m: kinds().map(|k| k.diameter_m).collect(),
            weight: kinds().map(|k| k.weight).collect(),
        }
    }
}

/// Adds the grains at time `time_s` (s) to `out` as `snapshots/t<time>s.csv` (x, y, diameter,
/// weight, settled) and `snapshots/t<time>s.vtp` (VTK PolyData for ParaView: points with
/// diameter and weight): heights `y_m` (m), flags `settled`, horizontal positions `x_m` (m;
/// None: those of `grains`).
pub fn write_snapshot(
    out: &mut Outputs,
    time_s: f64,
    grains: &GrainColumns,
    y_m: Arc<[f64]>,
    x_m: Option<Arc<[f64]>>,
    settled: Arc<[bool]>,
) {
    let stem = format!("snapshots/t{time_s:08.1}s");
    let x_m = x_m.unwrap_or_else(|| grains.x_m.clone());
    let points = VtkPoints {
        x_m: x_m.clone(),
        y_m: y_m.clone(),
        diameter_m: grains.diameter_m.clone(),
        weight: grains.weight.clone(),
    };
    out.table(Table::with_columns(
        format!("{stem}.csv"),
        ["x_m", "y_m", "diameter_m", "weight", "settled"],
        vec![
            Cells::Numbers(x_m),
            Cells::Numbers(y_m),
            Cells::Numbers(grains.diameter_m.clone()),
            Cells::Numbers(grains.weight.clone()),
            Cells::Flags(settled),
        ],
    ));
    out.made_file(format!("{stem}.vtp"), Arc::new(move |w| points.write(w)));
}

/// The grains of a snapshot as a VTK PolyData file (ASCII `.vtp`): points with diameter and
/// weight.
struct VtkPoints {
    x_m: Arc<[f64]>,
    y_m: Arc<[f64]>,
    diameter_m: Arc<[f64]>,
    weight: Arc<[f64]>,
}

impl VtkPoints {
    /// Writes the file to `f`.
    fn write(&self, f: &mut dyn Write) -> io::Result<()> {
        let n = self.y_m.len();
        writeln!(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>")?;
        writeln!(f, "<Piece NumberOfPoints=\"{n}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">")?;
        writeln!(f, "<PointData Scalars=\"diameter_m\">\n<DataArray type=\"Float64\" Name=\"diameter_m\" format=\"ascii\">")?;
        for d in self.diameter_m.iter() {
            write!(f, "{d:e} ")?;
        }
        writeln!(
            f,
            "\n</DataArray>\n<DataArray type=\"Float64\" Name=\"weight\" format=\"ascii\">"
        )?;
        for w in self.weight.iter() {
            write!(f, "{w:e} ")?;
        }
        writeln!(f, "\n</DataArray>\n</PointData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">")?;
        for (x, y) in self.x_m.iter().zip(self.y_m.iter()) {
            write!(f, "{x:e} {y:e} 0 ")?;
        }
        writeln!(
            f,
            "\n</DataArray>\n</Points>\n</Piece>\n</PolyData>\n</VTKFile>"
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_snapshot_prints_its_grains_in_both_files() {
        let cols = GrainColumns {
            x_m: vec![0.01, 0.05].into(),
            diameter_m: vec![2.5e-5, 1e-6].into(),
            weight: vec![3.0, 1.5e8].into(),
        };
        let mut out = Outputs::new();
        write_snapshot(
            &mut out,
            60.0,
            &cols,
            vec![0.25, 0.0125].into(),
            None,
            vec![false, true].into(),
        );
        let csv = String::from_utf8(out.bytes("snapshots/t000060.0s.csv").unwrap()).unwrap();
        assert_eq!(
            csv,
            "x_m,y_m,diameter_m,weight,settled\n0.01,0.25,2.5e-5,3,false\n0.05,0.0125,1e-6,1.5e8,true\n"
        );
        let vtp = String::from_utf8(out.bytes("snapshots/t000060.0s.vtp").unwrap()).unwrap();
        assert!(vtp.contains("NumberOfPoints=\"2\""), "{vtp}");
        assert!(vtp.contains("\n2.5e-5 1e-6 \n</DataArray>"), "{vtp}");
        assert!(vtp.contains("\n3e0 1.5e8 \n</DataArray>"), "{vtp}");
        assert!(
            vtp.contains("\n1e-2 2.5e-1 0 5e-2 1.25e-2 0 \n</DataArray>\n</Points>"),
            "{vtp}"
        );
        // a contact moved the grains: their own horizontal positions
        write_snapshot(
            &mut out,
            60.0,
            &cols,
            vec![0.25, 0.0125].into(),
            Some(vec![0.02, 0.04].into()),
            vec![false, true].into(),
        );
        let t = out.get("snapshots/t000060.0s").unwrap();
        assert_eq!(t.f64s("x_m").unwrap(), [0.02, 0.04]);
    }
}
