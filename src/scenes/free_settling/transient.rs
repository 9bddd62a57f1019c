//! The transient forces of a free-settling sphere (`[transient]`, issue 16): added mass, the
//! Basset history force and Brenner's wall correction of the approach to the container bottom.
//!
//! - Added mass alone changes only the inertia: the step is [`crate::dynamics::advance`] with the
//!   mass m_p + C_m m_f (any drag law and integrator, drops included: C_m times the immersed
//!   fluid mass while a drop crosses the surface).
//! - The history force is carried as state by [`crate::dynamics::transient::TransientBody`] (20
//!   states per body for the scenarios here), kernel fitted over 10 × `time.end_s`: Basset's
//!   t^{−1/2}, or Mei & Adrian's (1992) finite-Re kernel at the terminal Reynolds number of the
//!   quasi-steady drag (unbounded fluid; the kernel was derived for small unsteadiness about a
//!   steady Re, and it differs from Basset's only after t_c, when the sphere is near that speed).
//! - The wall multiplies the drag by Brenner's λ(gap) ([`crate::fluid::transient::wall`]), frozen
//!   over a step.
//!
//! The analytic columns: with Stokes drag and no wall, the exponential approach with the larger
//! inertia (added mass alone) or the Basset closed form ([`BassetProblem`], history on, released
//! from rest); none with the wall.

use super::scene::Scene;
use crate::dynamics::transient::{
    basset_coefficient, basset_kernel, mei_adrian_kernel_sum, MeiAdrianTable, TransientBody,
    TransientModel,
};
use crate::fluid::transient::wall::haberman_sayre_factor;
use crate::fluid::transient::BassetProblem;
use crate::fluid::{DragLaw, SphereDrag};
use crate::scenario::{Confinement, History, HistoryReynolds, Wall};

/// The transient forces of one sphere, fixed at release.
#[derive(Clone, Debug)]
pub(super) struct TransientSetup {
    /// C_m m_f (fully immersed), kg; 0 without added mass.
    pub added_mass_kg: f64,
    /// The history model, when the history force is on.
    pub history: Option<TransientModel>,
    /// The wall correction.
    pub wall: Wall,
    /// The side walls' factor on the drag (Haberman & Sayre), 1 when off.
    pub confinement: f64,
    /// The closed form (Stokes drag, history on, from rest, no wall).
    pub basset: Option<BassetProblem>,
    /// Mei & Adrian's kernel at the current Re: the fits and d/ν, s/m (Re = |v| d/ν).
    pub current_re: Option<(MeiAdrianTable, f64)>,
}

impl TransientSetup {
    /// The setup of a sphere of diameter `d_m`, mass `m_kg`, displaced fluid mass `m_f_kg`
    /// and drag `drag` in the scene `sc`; None when `[transient]` is absent or all off.
    pub fn new(sc: Scene, d_m: f64, m_kg: f64, m_f_kg: f64, drag: &SphereDrag) -> Option<Self> {
        let (s, f) = (sc.common, sc.spec);
        let t = s.transient.as_ref().filter(|t| t.any())?;
        let cm = if t.added_mass {
            t.added_mass_coefficient
        } else {
            0.0
        };
        let added = cm * m_f_kg;
        let mu = drag.law.viscosity_pa_s();
        let c_h = basset_coefficient(d_m, s.fluid_density_kg_m3, mu);
        let k = 3.0 * std::f64::consts::PI * mu * d_m;
        let nu = mu / s.fluid_density_kg_m3;
        let (tau_d, inertia) = (d_m * d_m / nu, m_kg + added);
        // Re at the terminal speed of the quasi-steady drag in an unbounded fluid.
        let re_t = || {
            let net = ((m_kg - m_f_kg) * s.gravity_m_s2).abs();
            drag.balance_speed(net).speed_m_s * d_m / nu
        };
        let current =
            t.history == History::MeiAdrian && t.history_reynolds == HistoryReynolds::Current;
        let current_re = current.then(|| {
            let table = MeiAdrianTable::new(inertia, k, c_h, s.time.end_s, tau_d, 4.0 * re_t());
            (table, d_m / nu)
        });
        let kernel = match t.history {
            History::Off => None,
            History::Basset => Some(basset_kernel(inertia, k, c_h, s.time.end_s)),
            History::MeiAdrian => Some(match &current_re {
                Some((table, _)) => table.at(f.release.velocity_m_s.abs() * d_m / nu),
                None => mei_adrian_kernel_sum(inertia, k, c_h, s.time.end_s, tau_d, re_t()),
            }),
        };
        let history = kernel.map(|ker| TransientModel {
            mass_kg: m_kg,
            added_mass_kg: added,
            history: Some((c_h, ker)),
        });
        let stokes = matches!(drag.law, DragLaw::Stokes { .. });
        let basset = (stokes
            && t.history == History::Basset
            && t.wall == Wall::Off
            && t.confinement == Confinement::Off
            && f.release.velocity_m_s == 0.0)
            .then(|| {
                let rho_p = m_kg / (std::f64::consts::PI * d_m.powi(3) / 6.0);
                BassetProblem::sphere(d_m, rho_p, s.fluid_density_kg_m3, mu, cm, s.gravity_m_s2)
            });
        Some(Self {
            current_re,
            added_mass_kg: added,
            history,
            wall: t.wall,
            confinement: match t.confinement {
                Confinement::Off => 1.0,
                Confinement::HabermanSayre => f
                    .container
                    .as_ref()
                    .and_then(|c| c.diameter_m)
                    .map_or(1.0, |big_d| haberman_sayre_factor(d_m / big_d)),
            },
            basset,
        })
    }

    /// The state of the history force at release, if on.
    pub fn body(&self, v0_m_s: f64) -> Option<TransientBody> {
        self.history
            .as_ref()
            .map(|m| TransientBody::new(m.clone(), v0_m_s))
    }
}
