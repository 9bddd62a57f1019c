//! Transient forces on a sphere accelerating in a fluid at rest: the exact Basset–Boussinesq
//! solution ([`closed_form`]), the complex error function it needs ([`faddeeva`]), the
//! sum-of-exponentials approximation of the history kernel ([`kernel`]) and the wall corrections
//! ([`wall`]). The state integrator that uses them is [`crate::dynamics::transient`].

pub mod closed_form;
pub mod faddeeva;

pub use closed_form::BassetProblem;
pub mod kernel;

pub use kernel::ExpSum;
pub mod wall;
