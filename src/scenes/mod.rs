//! Scene builders and runners, one module per scenario kind.

pub mod calibration;
pub mod free_settling;
pub mod funnel;
pub mod sedimentation;
pub mod spheres;

use crate::fluid::{DragLaw, SphereDrag};
use crate::scenario::{DragLawName, Physics, Rheology, Scenario};

/// The drag law a scenario asks for, after the `physics` switch (`ideal-stokes` turns every law
/// into Stokes drag with the fluid's viscosity, or its plastic viscosity for a Bingham fluid).
pub fn drag_law(s: &Scenario) -> DragLaw {
    let f = &s.fluid;
    let mu = match f.rheology {
        Rheology::Newtonian => f.viscosity_pa_s.unwrap_or(f64::NAN),
        Rheology::Bingham => f.plastic_viscosity_pa_s.unwrap_or(f64::NAN),
    };
    if s.physics == Physics::IdealStokes {
        return DragLaw::Stokes { viscosity_pa_s: mu };
    }
    match s.drag.law {
        DragLawName::Stokes => DragLaw::Stokes { viscosity_pa_s: mu },
        DragLawName::Dallavalle => DragLaw::Dallavalle {
            viscosity_pa_s: mu,
            voidage: s.drag.voidage,
        },
        DragLawName::BinghamFedem => DragLaw::Bingham {
            yield_stress_pa: f.yield_stress_pa.unwrap_or(0.0),
            plastic_viscosity_pa_s: mu,
        },
    }
}

/// The drag of one sphere of diameter `d_m` in the scenario's fluid.
pub fn sphere_drag(s: &Scenario, d_m: f64) -> SphereDrag {
    SphereDrag::new(drag_law(s), d_m, s.fluid.density_kg_m3)
}
