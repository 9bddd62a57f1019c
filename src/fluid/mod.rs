//! Fluid forces on a sphere: gravity and buoyancy, Newtonian drag laws and the Bingham
//! yield-stress drag of f-EDEM. Every function here is pure and works in SI units.
//!
//! Sources:
//! - **f-EDEM**: Zhang, Y. & Li, L. (2024). Introduction and implementation of fluid forces in a
//!   DEM code for simulating particle settlement in fluids. *Powder Technology* 119238.
//! - **Seed 000**: one-way coupled DEM of the hydrometer test (Dallavalle drag, Di Felice voidage).
//! - **Dedegil (1987)**, the yield-stress drag term; **Di Felice (1994)**, the voidage function.

pub mod bingham;
pub mod buoyancy;
pub mod drag;
pub mod hindered;
pub mod immersion;
pub mod lubrication;
pub mod newtonian;
pub mod slump;
pub mod transient;
pub mod validity;

pub use bingham::BinghamRegime;
pub use buoyancy::{buoyancy_n, sphere_area_m2, sphere_mass_kg, sphere_volume_m3, weight_n};
pub use drag::{DragLaw, DragRegime, Solved, SphereDrag};
pub use hindered::HinderedLaw;
pub use immersion::{immersion, Submergence};
