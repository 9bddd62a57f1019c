//! The typed setup of a sedimentation run: what the scene reads of its scenario (the common part
//! and the sedimentation spec), geometry, the sample's representative grains, the fluid
//! viscosity, and the default record times.

use crate::error::BadInput;
use crate::sample::{
    discretize, real_grains, representative_grains, Distribution, Grains, SizeClass,
};
use crate::scenario::{Common, Contacts, SceneSpec, SedimentationSpec};

/// Largest travel of the fastest grain of a contact cluster per Rapier step, in diameters of
/// the cluster's smallest grain.
pub const CONTACT_TRAVEL_PER_SUBSTEP: f64 = 1.0;

/// Largest relative change of a squeeze film's gap per Rapier step of the contact solve in the
/// run. The approach from h_out to h_in takes ln(h_out/h_in)/f Rapier steps; the frozen gap
/// makes the film approach too fast by a first-order error in f (see
/// `src/scenes/sedimentation/tests/contacts.rs` for the measured figures).
pub const CONTACT_FILM_CHANGE_PER_STEP: f64 = 0.25;

/// Limiting diameter of seed eq. 16 (Stokes), m: the largest grain still above depth y at time
/// t, φ_o = √(18 μ y / ((ρ_p − ρ_f) g t)).
pub fn limiting_diameter_m(
    depth_m: f64,
    time_s: f64,
    mu: f64,
    rho_p: f64,
    rho_f: f64,
    g: f64,
) -> f64 {
    (18.0 * mu * depth_m / ((rho_p - rho_f) * g * time_s)).sqrt()
}

/// The prepared sample of a sedimentation scenario.
pub struct Setup {
    /// Distribution.
    pub distribution: Distribution,
    /// Discrete classes.
    pub classes: Vec<SizeClass>,
    /// The grains' constants, held once: kind (class, diameter, weight) and horizontal position
    /// at t = 0 (the state holds what changes: heights, speeds, settled flags).
    pub grains: Grains,
    /// Modelled sample mass (wedge fraction of the sample), kg.
    pub model_mass_kg: f64,
    /// Width B, height H and projection thickness h_z, m.
    pub width_m: f64,
    /// Height H of the suspension, m.
    pub height_m: f64,
    /// Projection thickness h_z, m.
    pub thickness_m: f64,
    /// Viscosity of the fluid for the drag, the squeeze film and the analysis, Pa s (η of a
    /// Newtonian fluid, η_B of a Bingham one:
    /// [`crate::scenario::RheologyModel::drag_viscosity_pa_s`]).
    pub viscosity_pa_s: f64,
    /// Contact properties of the grains' contact solve (`[contacts]`; without it frictionless
    /// grains with restitution 0).
    pub contacts: GrainContacts,
    /// The scenario's sedimentation spec: sample, cylinder, instruments, contacts.
    pub spec: SedimentationSpec,
    /// What every kind reads of the scenario: name, physics, gravity, fluid density, time (the
    /// scene reads nothing else of it).
    pub common: Common,
}

/// Friction and restitution of the grains' contacts in the cylinder's contact solve, from the
/// scenario's `[contacts]` (Coulomb friction μ and restitution law e(v),
/// [`crate::contact::RestitutionLaw`]). Without `[contacts]`: μ = 0, e = 0 (frictionless,
/// perfectly inelastic discs, walls and floor).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GrainContacts {
    /// Coulomb friction coefficient of every collider (grains, walls, bed).
    pub friction: f64,
    /// Restitution of every contact.
    pub restitution: crate::contact::RestitutionLaw,
}

impl Default for GrainContacts {
    fn default() -> Self {
        Self {
            friction: 0.0,
            restitution: crate::contact::RestitutionLaw::constant(0.0),
        }
    }
}

impl GrainContacts {
    /// The contact properties of a `[contacts]` table (None: the defaults).
    pub fn of(contacts: Option<&Contacts>) -> Self {
        contacts.map_or_else(Self::default, |c| Self {
            friction: c.friction,
            restitution: c.restitution_law(),
        })
    }
}

/// Builds the sample of a prepared scenario `p`, for a caller that does not dispatch on its
/// spec (benchmarks, tests): nothing is parsed or validated again (its spec was built, its
/// `sample.csv` read, as it was prepared); one of another kind is a bad input.
pub fn setup(p: &crate::scenes::Prepared) -> Result<Setup, BadInput> {
    let SceneSpec::Sedimentation(spec) = &p.scene else {
        return Err(BadInput::new(
            &p.path,
            Some("kind"),
            format!(
                "`{}` has no sample: allowed kind = \"sedimentation\"",
                p.common.kind.name()
            ),
        ));
    };
    Ok(setup_of(p, spec))
}

/// Builds the sample of a prepared sedimentation scenario of spec `spec` (its distribution
/// read as the scenario was parsed).
pub fn setup_of(p: &crate::scenes::Prepared, spec: &SedimentationSpec) -> Setup {
    setup_with(&p.common, spec, spec.distribution.clone())
}

/// Builds the sample of a sedimentation scenario of common part `common` (its fluid's rheology
/// among it) and spec `spec` from its particle-size `distribution` (normally
/// [`SedimentationSpec::distribution`], read as the scenario was parsed).
pub fn setup_with(common: &Common, spec: &SedimentationSpec, distribution: Distribution) -> Setup {
    let sm = &spec.sample;
    let (width, height) = (spec.width_m, spec.height_m);
    let classes = discretize(&distribution, sm.n_diameters);
    let model_mass = sm.mass_kg * sm.wedge_fraction;
    let grains = if sm.real_grains {
        real_grains(
            &classes,
            model_mass,
            sm.density_kg_m3,
            width,
            height,
            sm.seed,
        )
    } else {
        representative_grains(
            &classes,
            sm.particles,
            model_mass,
            sm.density_kg_m3,
            width,
            height,
            sm.seed,
        )
    };
    Setup {
        distribution,
        classes,
        grains,
        model_mass_kg: model_mass,
        width_m: width,
        height_m: height,
        thickness_m: sm.projection_thickness_m(width),
        viscosity_pa_s: common.rheology.drag_viscosity_pa_s(),
        contacts: GrainContacts::of(spec.contacts.as_ref()),
        spec: spec.clone(),
        common: common.clone(),
    }
}

/// Default record times: every 10 s to 60 s, then ×1.25 up to `end_s` (and `end_s`).
pub fn default_record_times(end_s: f64) -> Vec<f64> {
    let mut t = vec![10.0, 20.0, 30.0, 40.0, 50.0, 60.0];
    let mut x = 60.0;
    while x * 1.25 < end_s {
        x = (x * 1.25).round();
        t.push(x);
    }
    t.push(end_s);
    t.retain(|&x| x <= end_s);
    t
}
