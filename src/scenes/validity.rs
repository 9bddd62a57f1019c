//! The validity warnings of scenes with spheres: the drag law a scenario uses, checked against
//! its validated range ([`crate::fluid::validity`]) at the spheres' results.

use super::Prepared;
use crate::fluid::validity::{bingham_fedem_warning, correlation_warning, stokes_warning};
use crate::fluid::DragLaw;

/// One sphere as the checks see it: id, diameter (m), density (kg/m³), speed (m/s) at which its
/// drag law is judged (the simulated terminal velocity).
#[derive(Clone, Debug)]
pub struct SphereAt {
    /// Sphere id.
    pub id: String,
    /// Diameter, m.
    pub diameter_m: f64,
    /// Density, kg/m³.
    pub density_kg_m3: f64,
    /// Speed, m/s.
    pub speed_m_s: f64,
}

/// The warnings of the scenario's drag law over `spheres`: Stokes drag above its Reynolds
/// number range; a C_d correlation above its stated range; f-EDEM's Bingham drag outside its
/// validated density and diameter ranges.
pub fn drag_warnings(p: &Prepared, spheres: &[SphereAt]) -> Vec<String> {
    let law = p.common.drag;
    let mut out = Vec::new();
    let reynolds = |viscosity_pa_s: f64| -> Vec<(String, f64)> {
        spheres
            .iter()
            .map(|s| {
                let re = crate::fluid::newtonian::reynolds(
                    p.common.fluid_density_kg_m3,
                    s.speed_m_s.abs(),
                    s.diameter_m,
                    viscosity_pa_s,
                );
                (s.id.clone(), re)
            })
            .collect()
    };
    match law {
        DragLaw::Stokes { viscosity_pa_s } => out.extend(stokes_warning(&reynolds(viscosity_pa_s))),
        DragLaw::Correlation { viscosity_pa_s, cd } => {
            out.extend(correlation_warning(cd, &reynolds(viscosity_pa_s)))
        }
        DragLaw::Bingham { .. } => {
            let ranges: Vec<(String, f64, f64)> = spheres
                .iter()
                .map(|s| (s.id.clone(), s.density_kg_m3, s.diameter_m))
                .collect();
            out.extend(bingham_fedem_warning(&ranges));
        }
        DragLaw::Dallavalle { .. } | DragLaw::Plastic { .. } => {}
    }
    out
}
