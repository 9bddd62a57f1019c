//! The voidage grid of full physics: square-ish cells of `voidage_cell_m` over the B × H
//! rectangle holding the solid volume of the suspended grains, from which each grain's drag takes
//! the local voidage ε = 1 − φ (clamped to [0.3, 1]) of Dallavalle's law with the Di Felice
//! factor ([`crate::fluid::DragLaw::Dallavalle`]).

use super::setup::Setup;
use super::state::State;
use crate::dynamics::terminal::TerminalTable;
use crate::dynamics::DallavalleGrain;
use crate::fluid::hindered::richardson_zaki_drag_factor;
use crate::fluid::{sphere_mass_kg, DragLaw, HinderedLaw, SphereDrag};
use crate::sample::{GrainKind, Grains};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// A number no grid or fill has taken yet ([`VoidageGrid::stamp`]).
fn new_stamp() -> u64 {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    NEXT.fetch_add(1, Ordering::Relaxed)
}

/// The grid of solid volume per cell (real units, m³) and the drag it gives.
#[derive(Clone, Debug)]
pub struct VoidageGrid {
    /// Cells across the width and up the height.
    ncx: usize,
    ncy: usize,
    width_m: f64,
    height_m: f64,
    /// Volume of one cell (with the projection thickness), m³.
    cell_volume_m3: f64,
    /// Solid volume of the suspended grains per cell, m³ (row-major, bottom row first).
    solid_m3: Vec<f64>,
    /// The sums `solid_m3` and `voidage` were last set from, in quanta: a fill converts only
    /// the cells whose sum changed (the same values, fewer conversions).
    sums_q: Vec<i128>,
    /// Which fill set `sums_q` ([`VoidageGrid::stamp`]).
    stamp: u64,
    /// The sums of [`VoidageGrid::fill_cells`] (kept from fill to fill: no allocation per
    /// step).
    next_q: Vec<i128>,
    /// The fixed point of the fills' sums ([`SolidQuanta`]).
    quanta: SolidQuanta,
    /// Voidage ε of every cell as [`VoidageGrid::drag`] takes it, set by [`VoidageGrid::fill`]
    /// only where the fast path of the free update reads it (full physics with the Di Felice
    /// factor, [`VoidageGrid::is_di_felice`]).
    voidage: Vec<f64>,
    /// The heights bounding each cell, m: a point of its column is in it exactly when
    /// `lo ≤ y < hi` ([`VoidageGrid::cell_after`]; −∞ below the bottom row, +∞ above the top
    /// one).
    bounds_m: Vec<(f64, f64)>,
    /// Stokes drag only (`ideal-stokes`): the grid is not used.
    ideal: bool,
    viscosity_pa_s: f64,
    fluid_density_kg_m3: f64,
    /// The hindered-settling factor (`sample.hindered`).
    hindered: HinderedLaw,
    /// The terminal state of each size class against the voidage (full physics with the Di
    /// Felice factor; [`VoidageGrid::with_terminal_tables`]), None for a class whose grains do
    /// not all have one diameter.
    tables: Vec<Option<TerminalTable>>,
}

impl VoidageGrid {
    /// An empty grid of cells of about `cell_m` over the cylinder of `setup`; `ideal` gives Stokes
    /// drag everywhere.
    pub fn new(setup: &Setup, cell_m: f64, ideal: bool, fluid_density_kg_m3: f64) -> Self {
        let (ncx, ncy) = (
            ((setup.width_m / cell_m).ceil() as usize).max(1),
            ((setup.height_m / cell_m).ceil() as usize).max(1),
        );
        let mut me = Self {
            ncx,
            ncy,
            width_m: setup.width_m,
            height_m: setup.height_m,
            cell_volume_m3: (setup.width_m / ncx as f64)
                * (setup.height_m / ncy as f64)
                * setup.thickness_m,
            solid_m3: vec![0.0; ncx * ncy],
            sums_q: vec![0; ncx * ncy],
            stamp: new_stamp(),
            next_q: Vec::new(),
            quanta: SolidQuanta::for_kinds(&setup.grains.kinds, &setup.grains.kind),
            voidage: vec![1.0; ncx * ncy],
            bounds_m: Vec::new(),
            ideal,
            viscosity_pa_s: setup.viscosity_pa_s,
            fluid_density_kg_m3,
            hindered: HinderedLaw::DiFelice,
            tables: Vec::new(),
        };
        let floors: Vec<f64> = (0..=ncy).map(|r| me.cells().row_floor_m(r)).collect();
        me.bounds_m = (0..ncx * ncy)
            .map(|c| (floors[c / ncx], floors[c / ncx + 1]))
            .collect();
        me
    }

    /// The same grid with the terminal-state table ([`TerminalTable`]) of every size class of
    /// `grains` (full physics with the Di Felice factor; otherwise none), for grains
    /// of density `grain_density_kg_m3` under gravity `gravity_m_s2`: built once per run, in
    /// parallel (each class is independent).
    pub fn with_terminal_tables(
        self,
        grains: &Grains,
        grain_density_kg_m3: f64,
        gravity_m_s2: f64,
    ) -> Self {
        if !self.is_di_felice() {
            return self;
        }
        // The kinds holding grains: the same classes and diameters as the grains themselves.
        let kinds = grains.kinds_present();
        let classes = kinds.iter().map(|g| g.class + 1).max().unwrap_or(0);
        let mut diameter: Vec<Option<f64>> = vec![None; classes];
        let mut single = vec![true; classes];
        for g in &kinds {
            match diameter[g.class] {
                None => diameter[g.class] = Some(g.diameter_m),
                Some(d) => single[g.class] &= d.to_bits() == g.diameter_m.to_bits(),
            }
        }
        let (rho_f, mu) = (self.fluid_density_kg_m3, self.viscosity_pa_s);
        let tables = diameter
            .par_iter()
            .zip(&single)
            .map(|(d, &one)| {
                let d = (*d).filter(|_| one)?;
                let m = sphere_mass_kg(d, grain_density_kg_m3);
                Some(TerminalTable::new(&DallavalleGrain {
                    diameter_m: d,
                    fluid_density_kg_m3: rho_f,
                    viscosity_pa_s: mu,
                    voidage: 1.0,
                    ln_voidage: 0.0,
                    mass_kg: m,
                    body_force_n: -(m - sphere_mass_kg(d, rho_f)) * gravity_m_s2,
                }))
            })
            .collect();
        Self { tables, ..self }
    }

    /// The terminal-state table of size class `class` if its grains have diameter `d_m`.
    pub fn terminal_table(&self, class: usize, d_m: f64) -> Option<&TerminalTable> {
        self.tables
            .get(class)?
            .as_ref()
            .filter(|t| t.diameter_m.to_bits() == d_m.to_bits())
    }

    /// The same grid with hindered-settling law `law` (default Di Felice).
    pub fn with_hindered(self, law: HinderedLaw) -> Self {
        Self {
            hindered: law,
            ..self
        }
    }

    /// The cell holding the point (x, y), m (points outside go to the nearest edge cell).
    pub fn cell_of(&self, x_m: f64, y_m: f64) -> usize {
        self.cells().cell_of(x_m, y_m)
    }

    /// The cell holding a point of the column of cell `cell` at height `y_m` (m): `cell` itself
    /// if the point is still in it (two comparisons), else [`Cells::cell_in_column`]. The same
    /// cell as [`VoidageGrid::cell_of`] in every case: the row is a non-decreasing function of
    /// the height, and the bounds are its exact steps.
    #[inline(always)]
    pub fn cell_after(&self, cell: usize, y_m: f64) -> usize {
        let (lo, hi) = self.bounds_m[cell];
        if lo <= y_m && y_m < hi {
            return cell;
        }
        let cells = self.cells();
        cells.cell_in_column(cells.column_of_cell(cell), y_m)
    }

    /// The layout of the cells (what [`VoidageGrid::cell_of`] reads), a copy.
    pub fn cells(&self) -> Cells {
        Cells {
            ncx: self.ncx,
            ncy: self.ncy,
            width_m: self.width_m,
            height_m: self.height_m,
        }
    }

    /// The real solid volume of every grain of `grains` (its weight times its volume), m³:
    /// computed once per run for [`VoidageGrid::fill`].
    pub fn grain_volumes_m3(&self, grains: &Grains) -> Vec<f64> {
        let volumes: Vec<f64> = grains.kinds.iter().map(|k| k.volume_m3()).collect();
        grains.kind.iter().map(|&k| volumes[k as usize]).collect()
    }

    /// Refills the grid with the solid volume of the suspended grains of `st` (grains `grains`)
    /// among `active` (ascending grain indices, every suspended grain among them), given the
    /// real solid volume of each grain ([`VoidageGrid::grain_volumes_m3`]), summed in grain
    /// order.
    pub fn fill(&mut self, st: &State, grains: &Grains, volumes_m3: &[f64], active: &[usize]) {
        let cells = self.cells();
        self.fill_cells(
            active
                .iter()
                .filter(|&&i| !st.settled[i])
                .map(|&i| (cells.cell_of(st.x_m(grains, i), st.y_m[i]), volumes_m3[i])),
        );
    }

    /// Refills the grid with the solid volumes (m³) of `cells_volumes` (cell, real solid volume
    /// of a grain), summed exactly ([`SolidQuanta`]): the same sums in any order.
    pub fn fill_cells(&mut self, cells_volumes: impl IntoIterator<Item = (usize, f64)>) {
        let mut sums = std::mem::take(&mut self.next_q);
        sums.clear();
        sums.resize(self.cell_count(), 0);
        for (c, v) in cells_volumes {
            sums[c] += self.quanta.of(v);
        }
        self.set_sums(&sums);
        self.next_q = sums;
    }

    /// The fixed point of this grid's sums of solid volume ([`SolidQuanta`]).
    pub fn quanta(&self) -> SolidQuanta {
        self.quanta
    }

    /// The solid volume of the suspended grains per cell, m³, as the last fill left it.
    #[cfg(test)]
    pub fn solid_m3(&self) -> &[f64] {
        &self.solid_m3
    }

    /// Number of cells of the grid.
    pub fn cell_count(&self) -> usize {
        self.solid_m3.len()
    }

    /// Refills the grid with the solid volume per cell `sums`, in quanta ([`SolidQuanta`];
    /// [`VoidageGrid::cell_count`] values).
    pub fn fill_sums(&mut self, sums: &[i128]) {
        self.set_sums(sums);
    }

    /// [`VoidageGrid::fill_sums`] where only the sums of the cells `changed` may differ from
    /// those of the fill that left the grid at `stamp` ([`VoidageGrid::stamp`]; any order,
    /// repeats allowed): those cells alone are read, the same values stored. Returns false,
    /// and does nothing, if the grid's last fill is not that one.
    #[must_use]
    pub fn fill_sums_at(&mut self, sums: &[i128], changed: &[u32], stamp: u64) -> bool {
        if stamp != self.stamp {
            return false;
        }
        self.set_sums_of(changed.iter().map(|&c| (c as usize, sums[c as usize])));
        true
    }

    /// Which fill left the grid as it is: a number that no other fill of any grid takes (a
    /// copy of the grid keeps it, with the same sums).
    pub fn stamp(&self) -> u64 {
        self.stamp
    }

    /// Stores the solid volume of each cell from its sum in quanta `sums`
    /// ([`Self::set_sums_of`]).
    fn set_sums(&mut self, sums: &[i128]) {
        self.set_sums_of(sums.iter().copied().enumerate());
    }

    /// Stores the solid volume of each cell `c` of `sums` from its sum in quanta `q` (m³, the
    /// exact sum rounded once) and the voidage it gives, where the sum changed since the last
    /// fill (elsewhere the same values are already there), keeps the sums for the next fill,
    /// and stamps the grid with a new number.
    #[inline(always)]
    fn set_sums_of(&mut self, sums: impl IntoIterator<Item = (usize, i128)>) {
        let (quanta, cell_volume_m3, di_felice) =
            (self.quanta, self.cell_volume_m3, self.is_di_felice());
        for (c, q) in sums {
            let last = &mut self.sums_q[c];
            if q != *last {
                *last = q;
                self.solid_m3[c] = quanta.volume_m3(q);
                if di_felice {
                    self.voidage[c] = voidage_of(self.solid_m3[c], cell_volume_m3);
                }
            }
        }
        self.stamp = new_stamp();
    }

    /// The voidage ε of every cell, as [`VoidageGrid::voidage`] reads it.
    #[inline(always)]
    pub fn voidages(&self) -> &[f64] {
        &self.voidage
    }

    /// Every cell's height bounds [lo, hi), m (what [`VoidageGrid::cell_after`] tests).
    pub fn cell_bounds(&self) -> &[(f64, f64)] {
        &self.bounds_m
    }

    /// The voidage ε of cell `cell` as [`VoidageGrid::drag`] takes it (valid after
    /// [`VoidageGrid::fill`] when [`VoidageGrid::is_di_felice`]).
    #[inline(always)]
    pub fn voidage(&self, cell: usize) -> f64 {
        self.voidage[cell]
    }

    /// Whether every cell's drag is Dallavalle's with the Di Felice factor (full physics,
    /// `hindered = "di-felice"`).
    pub fn is_di_felice(&self) -> bool {
        !self.ideal && self.hindered == HinderedLaw::DiFelice
    }

    /// The drag of a grain of diameter `d_m` in cell `cell`: Stokes (ideal) or Dallavalle with
    /// the cell's voidage ε = 1 − solid/cell volume, clamped to [0.3, 1] (Di Felice factor), or
    /// the lone grain's Dallavalle drag × ε^(−4.65) (`richardson-zaki`).
    pub fn drag(&self, d_m: f64, cell: usize) -> SphereDrag {
        let mu = self.viscosity_pa_s;
        let law = if self.ideal {
            DragLaw::Stokes { viscosity_pa_s: mu }
        } else {
            let eps = voidage_of(self.solid_m3[cell], self.cell_volume_m3);
            if self.hindered == HinderedLaw::RichardsonZaki {
                let lone = DragLaw::Dallavalle {
                    viscosity_pa_s: mu,
                    voidage: 1.0,
                };
                return SphereDrag::new(lone, d_m, self.fluid_density_kg_m3)
                    .scaled(richardson_zaki_drag_factor(eps));
            }
            DragLaw::Dallavalle {
                viscosity_pa_s: mu,
                voidage: eps,
            }
        };
        SphereDrag::new(law, d_m, self.fluid_density_kg_m3)
    }

    /// The drag of a grain of diameter `d_m` centred at (x, y), m.
    pub fn drag_at(&self, d_m: f64, x_m: f64, y_m: f64) -> SphereDrag {
        self.drag(d_m, self.cell_of(x_m, y_m))
    }
}

/// The fixed point in which a [`VoidageGrid`] sums the solid volume of its cells: a volume v
/// (m³) counts as the integer v·2^q (`i128`), so sums are exact and the same in any order
/// (the grains of a cell summed in grain order, kind by kind, in parts on any number of
/// threads), and a cell's volume is its sum converted back, rounded once (to nearest): the
/// exact sum, correctly rounded. q is the largest power for which every kind's volume v·2^q is
/// an integer (v has 53 significant bits: q = 52 − ⌊log₂ v⌋ for the smallest v), lowered if
/// needed so that the volume of every grain at once stays below 2^120; then the smallest
/// volumes are rounded down to whole quanta (the same quanta in every sum).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidQuanta {
    /// 2^q.
    scale: f64,
    /// 2^−q.
    unscale: f64,
}

impl SolidQuanta {
    /// The quanta of grains of kinds `kinds` (their volumes, weight × volume), grain i of
    /// kind `kind[i]`.
    pub fn for_kinds(kinds: &[GrainKind], kind: &[u32]) -> Self {
        let mut counts = vec![0f64; kinds.len()];
        for &k in kind {
            counts[k as usize] += 1.0;
        }
        let (mut q, mut total_m3) = (0i32, 0.0f64);
        for (k, &n) in kinds.iter().zip(&counts) {
            let v = k.volume_m3();
            if n > 0.0 && v > 0.0 && v.is_finite() {
                // ⌊log₂ v⌋, exactly: the exponent of v (a volume is a normal number).
                let exponent = ((v.to_bits() >> 52) & 0x7ff) as i32 - 1023;
                q = q.max(52 - exponent);
                total_m3 += n * v;
            }
        }
        if total_m3 > 0.0 && total_m3.is_finite() {
            q = q.min(119 - total_m3.log2().ceil() as i32);
        }
        let q = q.clamp(-1000, 1000);
        Self {
            scale: 2f64.powi(q),
            unscale: 2f64.powi(-q),
        }
    }

    /// Volume `v_m3` (m³) in quanta (rounded towards zero when not a whole number of them).
    #[inline(always)]
    pub fn of(&self, v_m3: f64) -> i128 {
        (v_m3 * self.scale) as i128
    }

    /// The volume (m³) of `q` quanta, rounded to nearest.
    #[inline(always)]
    pub fn volume_m3(&self, q: i128) -> f64 {
        // Through i64 where it fits (a conversion in hardware; the same rounding to nearest of
        // the same integer as the i128 one, a library call).
        let real = i64::try_from(q).map_or(q as f64, |q| q as f64);
        real * self.unscale
    }
}

/// The layout of the cells of a [`VoidageGrid`]: `ncx` × `ncy` cells over the `width_m` ×
/// `height_m` rectangle (m), row-major, bottom row first.
#[derive(Clone, Copy, Debug)]
pub struct Cells {
    ncx: usize,
    ncy: usize,
    width_m: f64,
    height_m: f64,
}

impl Cells {
    /// The cell holding the point (x, y), m (points outside go to the nearest edge cell).
    #[inline(always)]
    pub fn cell_of(&self, x_m: f64, y_m: f64) -> usize {
        self.cell_in_column(self.column_of(x_m), y_m)
    }

    /// The column of cells holding abscissa `x_m`, m (outside: the nearest edge column).
    #[inline(always)]
    pub fn column_of(&self, x_m: f64) -> usize {
        ((x_m / self.width_m * self.ncx as f64) as usize).min(self.ncx - 1)
    }

    /// The cell of column `column` ([`Cells::column_of`]) holding height `y_m`, m:
    /// [`Cells::cell_of`] with the column found once.
    #[inline(always)]
    pub fn cell_in_column(&self, column: usize, y_m: f64) -> usize {
        self.row_of(y_m) * self.ncx + column
    }

    /// The column of cell `cell`.
    #[inline(always)]
    pub fn column_of_cell(&self, cell: usize) -> usize {
        cell % self.ncx
    }

    /// The row of cells holding height `y_m`, m (below the bottom: 0; above the top: the top
    /// row).
    #[inline(always)]
    fn row_of(&self, y_m: f64) -> usize {
        ((y_m / self.height_m * self.ncy as f64) as usize).min(self.ncy - 1)
    }

    /// The lowest height whose row ([`Cells::cell_in_column`]) is `row` or above, m: −∞ for
    /// row 0, +∞ above the top row. Found from the nominal boundary by stepping one unit in the
    /// last place at a time (the rounding moves it by a few at most).
    fn row_floor_m(&self, row: usize) -> f64 {
        if row == 0 {
            return f64::NEG_INFINITY;
        }
        if row >= self.ncy {
            return f64::INFINITY;
        }
        let mut y = row as f64 * self.height_m / self.ncy as f64;
        while self.row_of(y) >= row {
            y = f64::from_bits(y.to_bits() - 1);
        }
        while self.row_of(y) < row {
            y = f64::from_bits(y.to_bits() + 1);
        }
        y
    }
}

/// The voidage ε = 1 − solid/cell volume of a cell of `cell_volume_m3` holding `solid_m3` of
/// grains, clamped to [0.3, 1].
fn voidage_of(solid_m3: f64, cell_volume_m3: f64) -> f64 {
    (1.0 - solid_m3 / cell_volume_m3).clamp(0.3, 1.0)
}
