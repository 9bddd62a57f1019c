//! Scene builders and runners, one module per scenario kind.

pub mod cost;
pub mod free_settling;
pub mod funnel_pour;
pub mod restitution_drop;
pub mod sedimentation;
pub mod tilt_friction;
pub mod validity;

use crate::fluid::newtonian::CdCorrelation;
use crate::fluid::{DragLaw, SphereDrag};
use crate::scenario::{DragLawName, Kind, Physics, RheologyModel, Scenario, SceneSpec};
use std::path::PathBuf;

/// A loaded scenario ready to run: the effective scenario and its input files, read and checked.
#[derive(Clone, Debug)]
pub struct Prepared {
    /// The scenario file.
    pub path: PathBuf,
    /// The effective scenario (overrides applied).
    pub scenario: Scenario,
    /// Its spheres (free settling and drops; read from `spheres_csv` when given).
    pub spheres: Vec<crate::scenario::inputs::SphereCase>,
    /// What the scenario's kind needs, typed ([`crate::scenario::Parsed::scene`]).
    pub scene: SceneSpec,
    /// The fluid's rheology with its parameters ([`crate::scenario::Parsed::rheology`]).
    pub rheology: RheologyModel,
    /// The measured curves of `[reference]`, read while the scenario is prepared (None
    /// without one).
    pub reference: Option<crate::scenario::inputs::MeasuredCurves>,
    /// The overrides as given on the command line (`--set`, `--dt`), recorded in `run.toml`;
    /// already applied to `scenario`.
    pub overrides: crate::scenario::Overrides,
}

/// How a run is carried out beyond its scenario: checkpoints, resumption, progress display.
#[derive(Clone, Debug, Default)]
pub struct RunContext {
    /// Where and how often to write checkpoints (None: never, not even on interruption).
    pub checkpoints: Option<crate::checkpoint::Checkpoints>,
    /// Continue from the checkpoints found there (`--resume`).
    pub resume: bool,
    /// No progress bar.
    pub quiet: bool,
}

/// What a scene reports to the runner after writing its own files into the staging folder.
#[derive(Clone, Debug, Default)]
pub struct SceneReport {
    /// Total steps over all worlds.
    pub steps: u64,
    /// Number of bodies (over all worlds).
    pub bodies: usize,
    /// Rapier settings used (recorded in run.toml).
    pub engine_settings: Option<crate::engine::EngineSettings>,
    /// Lines printed after the run (a short human-readable summary).
    pub lines: Vec<String>,
    /// The run stopped early on Ctrl-C/SIGTERM (outputs hold what was done).
    pub interrupted: bool,
    /// Validity warnings (a law used outside its range, a Reynolds number too high for Stokes
    /// drag, …): printed after the run and written to run.toml's `[run] warnings` (issue 13).
    pub warnings: Vec<String>,
}

/// The drag law a scenario asks for in a fluid of rheology `rheology`, after the `physics`
/// switch (`ideal-stokes` turns every law into Stokes drag with the fluid's viscosity, or its
/// plastic viscosity for a Bingham fluid).
pub fn drag_law(s: &Scenario, rheology: RheologyModel) -> DragLaw {
    let mu = rheology.drag_viscosity_pa_s();
    if s.physics == Physics::IdealStokes {
        return DragLaw::Stokes { viscosity_pa_s: mu };
    }
    match s.drag.law {
        DragLawName::Stokes => DragLaw::Stokes { viscosity_pa_s: mu },
        DragLawName::Dallavalle => DragLaw::Dallavalle {
            viscosity_pa_s: mu,
            voidage: s.drag.voidage,
        },
        DragLawName::SchillerNaumann => correlation(mu, CdCorrelation::SchillerNaumann),
        DragLawName::CliftGauvin => correlation(mu, CdCorrelation::CliftGauvin),
        DragLawName::Morrison => correlation(mu, CdCorrelation::Morrison),
        DragLawName::BinghamFedem => DragLaw::Bingham {
            yield_stress_pa: rheology.yield_stress_pa(),
            plastic_viscosity_pa_s: mu,
        },
        DragLawName::BinghamAdditive | DragLawName::AnsleySmith | DragLawName::Wilson2003 => s
            .drag
            .plastic_law(rheology)
            .expect("validated: a yield-stress law in a yield-stress fluid"),
    }
}

fn correlation(viscosity_pa_s: f64, cd: CdCorrelation) -> DragLaw {
    DragLaw::Correlation { viscosity_pa_s, cd }
}

/// The drag of one sphere of diameter `d_m` in the scenario's fluid of rheology `rheology`.
pub fn sphere_drag(s: &Scenario, rheology: RheologyModel, d_m: f64) -> SphereDrag {
    SphereDrag::new(drag_law(s, rheology), d_m, s.fluid.density_kg_m3)
}

/// The added-mass coefficient C_m of the scenario's Rapier scenes (`transient.added_mass`,
/// `transient.added_mass_coefficient`; 0 when off or without `[transient]`), for
/// [`crate::engine::dim3::World::set_added_mass_coefficient`].
pub fn added_mass_coefficient(s: &Scenario) -> f64 {
    s.transient
        .as_ref()
        .map_or(0.0, |t| t.added_mass_coefficient_on())
}

/// Runs the scene of `p` into the staging folder `stage`: the one match on the kind's spec,
/// each scene receiving its own. Free settling and drops also return their per-sphere results
/// (for the console table and the combined outputs of a several-file run).
pub fn run_scene(
    p: &Prepared,
    stage: &crate::io::StagedDir,
    ctx: &RunContext,
) -> Result<(Vec<free_settling::SphereResult>, SceneReport), crate::error::Error> {
    Ok(match &p.scene {
        SceneSpec::FreeSettling(_) => free_settling::run_scene(p, stage)?,
        SceneSpec::RestitutionDrop(r) => (Vec::new(), restitution_drop::run(p, r, stage)?),
        SceneSpec::TiltFriction(t) => (Vec::new(), tilt_friction::run(p, t, stage)?),
        SceneSpec::FunnelPour(f) => (Vec::new(), funnel_pour::run(p, f, stage, ctx)?),
        SceneSpec::Sedimentation(sd) => (Vec::new(), sedimentation::run(p, sd, stage, ctx)?),
    })
}

/// The load of scenario `s` as its kind's scene estimates it (`scenes/<kind>/cost.rs`), for
/// [`cost::estimate`] and [`cost::check`].
pub fn load(s: &Scenario) -> cost::Load {
    match s.kind {
        Kind::FreeSettling | Kind::Drop => free_settling::cost::load(s),
        Kind::RestitutionDrop => restitution_drop::cost::load(s),
        Kind::TiltFriction => tilt_friction::cost::load(s),
        Kind::FunnelPour => funnel_pour::cost::load(s),
        Kind::Sedimentation => sedimentation::cost::load(s),
    }
}
