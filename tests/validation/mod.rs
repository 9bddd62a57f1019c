//! Validation cases (MercuryDPM style): each is a scenario in `scenarios/`, reference data
//! (a table in `data/` or an independent solution) and a test stating its tolerance.

mod invert;
mod paste_drop;
mod sphere_drag;
mod stokes_single;
mod valentik;
