//! The free update of one suspended grain over one step, written once. Every loop of the step
//! calls it: the per-grain loop over the [`State`](super::super::state::State) (runs with
//! contacts), the packed suspension (full physics without contacts,
//! [`Suspension`](super::super::suspension::Suspension)) and the ideal-Stokes intervals
//! ([`Stepper::ideal_interval`]). The loops differ in which grains they visit and where those
//! live; what happens to a grain is this:
//!
//! 1. its step under the drag mode [`Drag`] (one type per mode, so that every loop is compiled
//!    for its mode): [`CellDrag`], the drag of its voidage cell with the run's integrator (full
//!    physics, or ideal Stokes step by step), or [`StokesDrag`], the exponential update for
//!    Stokes drag with its φ factors computed once per step size (the ideal-Stokes intervals);
//! 2. [`after_step`]: the move, a stop on the bed surface, and the fault test of
//!    [`Stepper::grain_fault`] on the new height and speed;
//! 3. deposition ([`on_bed`], [`bed_rise_m`]): a grain touching the bed surface joins it.

use super::super::voidage::VoidageGrid;
use super::stepper::Stepper;
use crate::dynamics::terminal::exponential_near_terminal;
use crate::dynamics::{advance, exponential_dallavalle_1d, DallavalleGrain};
use crate::fluid::{sphere_mass_kg, sphere_volume_m3};
use nalgebra::SVector;

/// How the step of one grain follows from its speed at the step's start: the drag mode of the
/// free update.
pub trait Drag {
    /// What the step reads of one grain besides its speed.
    type Grain;
    /// The step of grain `g` from vertical velocity `v0_m_s` (m/s): its new velocity (m/s) and
    /// its displacement (m), before any stop on the bed.
    fn step(&self, g: &Self::Grain, v0_m_s: f64) -> (f64, f64);
}

/// The drag of a grain's voidage cell with the run's integrator, over one step of `dt_s`:
/// Dallavalle's drag with the Di Felice factor by the exponential integrator (the tabulated
/// terminal state, [`exponential_near_terminal`], or else [`exponential_dallavalle_1d`]) on a
/// Di Felice grid, otherwise [`advance`] with the cell's drag ([`VoidageGrid::drag`]: Stokes in
/// ideal Stokes, Richardson–Zaki, other integrators).
#[derive(Clone, Copy)]
pub struct CellDrag<'a> {
    /// The run's step constants.
    pub stepper: &'a Stepper,
    /// The voidage grid of this step.
    pub grid: &'a VoidageGrid,
    /// [`Stepper::fast_path`] on `grid`.
    pub fast: bool,
    /// Step, s.
    pub dt_s: f64,
}

/// What [`CellDrag`] reads of a grain.
#[derive(Clone, Copy, Debug)]
pub struct CellGrain {
    /// Diameter, m.
    pub diameter_m: f64,
    /// Size class (whose terminal-state table the fast path reads).
    pub class: usize,
    /// Its voidage cell ([`VoidageGrid::cell_of`]).
    pub cell: usize,
}

impl<'a> CellDrag<'a> {
    /// The drag of the cells of `grid` over a step of `dt_s` with the constants of `stepper`.
    pub fn new(stepper: &'a Stepper, grid: &'a VoidageGrid, dt_s: f64) -> Self {
        Self {
            stepper,
            grid,
            fast: stepper.fast_path(grid),
            dt_s,
        }
    }
}

impl Drag for CellDrag<'_> {
    type Grain = CellGrain;

    #[inline(always)]
    fn step(&self, g: &CellGrain, v0_m_s: f64) -> (f64, f64) {
        let (k, grid, d, dt) = (self.stepper, self.grid, g.diameter_m, self.dt_s);
        let (gacc, rho_f) = (k.gravity_m_s2, k.fluid_density_kg_m3);
        let m = sphere_mass_kg(d, k.grain_density_kg_m3);
        let w = -(m - sphere_mass_kg(d, rho_f)) * gacc;
        let quick = self.fast.then(|| {
            let voidage = grid.voidage(g.cell);
            let mut grain = DallavalleGrain {
                diameter_m: d,
                fluid_density_kg_m3: rho_f,
                viscosity_pa_s: k.viscosity_pa_s,
                voidage,
                // Read only by the solve below, which computes it.
                ln_voidage: 0.0,
                mass_kg: m,
                body_force_n: w,
            };
            grid.terminal_table(g.class, d)
                .and_then(|t| exponential_near_terminal(t, &grain, v0_m_s, dt))
                .or_else(|| {
                    grain.ln_voidage = voidage.ln();
                    exponential_dallavalle_1d(&grain, v0_m_s, dt)
                })
        });
        match quick.flatten() {
            Some(step) => step,
            None => {
                let drag = grid.drag(d, g.cell);
                let w = SVector::<f64, 1>::new(w);
                let v0 = SVector::<f64, 1>::new(v0_m_s);
                let step = advance(k.integrator, &drag, m, &w, &v0, dt);
                (step.velocity_m_s[0], step.displacement_m[0])
            }
        }
    }
}

/// Stokes drag by the exponential integrator over one step of `dt_s`: m v̇ = W − k v, exact,
/// v₁ = v₀ + a₀ dt φ₁(−λdt), dx = v₀ dt + a₀ dt² φ₂(−λdt) with a₀ = (W − k v₀)/m and λ = k/m
/// (Hochbruck & Ostermann 2010, Acta Numerica 19, §2.1): the same operations as
/// [`advance`] for Stokes drag, with each grain's factors dt φ₁ and dt² φ₂ computed once per
/// step size ([`StokesGrain`]) rather than once per step.
#[derive(Clone, Copy, Debug)]
pub struct StokesDrag {
    /// Step, s.
    pub dt_s: f64,
}

/// What [`StokesDrag`] reads of a grain. SI units.
#[derive(Clone, Copy, Debug)]
pub struct StokesGrain {
    /// Mass m, kg.
    pub mass_kg: f64,
    /// Body force W (gravity and buoyancy, negative downwards), N.
    pub body_force_n: f64,
    /// Stokes drag slope k = 3π μ d, N s/m.
    pub slope_n_s_m: f64,
    /// dt φ₁(−k dt/m) of the step, s.
    pub dt_phi1_s: f64,
    /// dt² φ₂(−k dt/m) of the step, s².
    pub dt2_phi2_s2: f64,
}

impl Drag for StokesDrag {
    type Grain = StokesGrain;

    #[inline(always)]
    fn step(&self, g: &StokesGrain, v0_m_s: f64) -> (f64, f64) {
        let a0 = (g.body_force_n - v0_m_s * g.slope_n_s_m) / g.mass_kg;
        (
            v0_m_s + a0 * g.dt_phi1_s,
            v0_m_s * self.dt_s + a0 * g.dt2_phi2_s2,
        )
    }
}

/// Where a grain may be after its step: above the bed surface and within the cylinder, slower
/// than the speed bound. SI units.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Bed surface, m: a grain whose bottom reaches it stops on it.
    pub floor_m: f64,
    /// Speed above which a grain is a fault, m/s ([`Stepper::speed_bound_m_s`]).
    pub speed_bound_m_s: f64,
}

/// A grain at height `y0_m` (its centre; half its diameter `half_d_m`, m) after its step
/// `(v1, dx)` (m/s, m): it moves by dx, stopping on the bed surface `lim.floor_m` if it reaches
/// it, at speed v1. Returns its new height (m), its speed (m/s), and whether it now fails the
/// test of [`Stepper::grain_fault`] on them (not finite, faster than the speed bound, or its
/// centre above `top_m`, the cylinder's height plus its diameter).
#[inline(always)]
pub fn after_step(
    y0_m: f64,
    (v1, dx): (f64, f64),
    half_d_m: f64,
    top_m: f64,
    lim: Limits,
) -> (f64, f64, bool) {
    let mut y1 = y0_m + dx;
    if y1 - half_d_m <= lim.floor_m {
        y1 = lim.floor_m + half_d_m;
    }
    (y1, v1, vertical_fault(y1, v1, top_m, lim.speed_bound_m_s))
}

/// The free update of one grain `g` at height `y0_m` and speed `v0_m_s` under the drag mode
/// `drag` ([`Drag::step`], then [`after_step`]): (height, m; speed, m/s; fault).
#[inline(always)]
pub fn free_step<D: Drag>(
    drag: &D,
    g: &D::Grain,
    y0_m: f64,
    v0_m_s: f64,
    half_d_m: f64,
    top_m: f64,
    lim: Limits,
) -> (f64, f64, bool) {
    after_step(y0_m, drag.step(g, v0_m_s), half_d_m, top_m, lim)
}

/// The vertical part of the fault test of [`Stepper::grain_fault`]: a height `y_m` or speed
/// `v_m_s` not finite, a speed above `bound_m_s` (m/s), or a centre above `top_m` (m).
#[inline(always)]
pub fn vertical_fault(y_m: f64, v_m_s: f64, top_m: f64, bound_m_s: f64) -> bool {
    // `|`, not `||`: every test made, no branch (the same result).
    !(y_m.is_finite() & v_m_s.is_finite()) | (v_m_s.abs() > bound_m_s) | (y_m > top_m)
}

/// The horizontal part of the fault test of [`Stepper::grain_fault`]: a centre at `x_m` not
/// finite or beside the walls of a cylinder `width_m` wide (m; 1e-12 m of slack).
#[inline(always)]
pub fn horizontal_fault(x_m: f64, width_m: f64) -> bool {
    !x_m.is_finite() || x_m < -1e-12 || x_m > width_m + 1e-12
}

/// Whether a grain at height `y_m` with half its diameter `half_d_m` touches the bed surface
/// `bed_m` (m; 1e-15 m of slack) and joins the bed (deposition, serial in grain order).
#[inline(always)]
pub fn on_bed(y_m: f64, half_d_m: f64, bed_m: f64) -> bool {
    y_m - half_d_m <= bed_m + 1e-15
}

/// The rise of the bed surface, m, when a grain of diameter `d_m` (m) standing for `weight`
/// real grains joins it: its real solid volume over the bed's area times its packing fraction,
/// `bed_area_m2` (m²).
#[inline(always)]
pub fn bed_rise_m(weight: f64, d_m: f64, bed_area_m2: f64) -> f64 {
    weight * sphere_volume_m3(d_m) / bed_area_m2
}
