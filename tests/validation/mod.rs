//! Validation cases (MercuryDPM style): each is a scenario in `scenarios/`, reference data
//! (a table in `data/` or an independent solution) and a test stating its tolerance.

mod bingham_laws;
mod hindered;
mod invert;
mod invert_counting;
mod sedimentation_real_count;
mod sedimentation_reference;
mod slump;
mod sphere_drag;
mod stokes_single;
mod ten_cate;
