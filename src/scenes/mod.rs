//! Scene builders and runners, one module per scenario kind.

pub mod cost;
pub mod free_settling;
pub mod funnel_pour;
pub mod restitution_drop;
pub mod sedimentation;
#[cfg(test)]
mod tests;
pub mod tilt_friction;
pub mod validity;

use crate::error::BadInput;
use crate::scenario::{Common, RheologyModel, SceneSpec};
use std::path::{Path, PathBuf};

/// A loaded scenario ready to run: its typed parts and its input files, read and checked.
/// Parse, don't validate: nothing raw is left here (the raw scenario stops at the loader,
/// [`crate::scenario::Parsed`]); scenes read [`Prepared::common`] and their spec
/// ([`Prepared::scene`]), and the effective scenario survives only as the record of the run
/// ([`Prepared::record_table`], [`Prepared::fingerprint`]).
#[derive(Clone, Debug)]
pub struct Prepared {
    /// The scenario file.
    pub path: PathBuf,
    /// What every kind reads, typed ([`crate::scenario::Parsed::common`]).
    pub common: Common,
    /// Its spheres (free settling and drops; read from `spheres_csv` when given, one case per
    /// fall height of a drop).
    pub spheres: Vec<crate::scenario::inputs::SphereCase>,
    /// What the scenario's kind needs, typed ([`crate::scenario::Parsed::scene`]).
    pub scene: SceneSpec,
    /// The fluid's rheology with its parameters ([`crate::scenario::Parsed::rheology`]).
    pub rheology: RheologyModel,
    /// The measured curves of `[reference]`, read while the scenario is prepared (None
    /// without one).
    pub reference: Option<crate::scenario::inputs::MeasuredCurves>,
    /// The overrides as given on the command line (`--set`, `--dt`), recorded in `run.toml`;
    /// already applied.
    pub overrides: crate::scenario::Overrides,
    /// The effective scenario (overrides applied), kept only as the run's record.
    record: crate::scenario::Record,
}

impl Prepared {
    /// Reads, overrides, validates and prepares the text `text` of the scenario file `path`
    /// (its folder is where relative input files are found), as `settle run --dt DT_S --set
    /// OVERRIDES` does: `--dt` is `time.dt_s`; `check` vets the typed common part before the
    /// input files (`spheres_csv`, `sample.csv`, `[reference]`) are read.
    pub fn parse(
        text: &str,
        path: &Path,
        dt_s: Option<f64>,
        overrides: &[String],
        check: impl FnOnce(&Common) -> Result<(), BadInput>,
    ) -> Result<Prepared, BadInput> {
        let mut ov = overrides.to_vec();
        if let Some(dt) = dt_s.filter(|d| !d.is_finite()) {
            return Err(BadInput::new(
                path,
                Some("time.dt_s"),
                format!("--dt {dt} is out of range: allowed 0 < dt_s ≤ time.end_s s"),
            ));
        }
        if let Some(dt) = dt_s {
            ov.push(format!("time.dt_s={dt:e}"));
        }
        let parsed: crate::scenario::Parsed = crate::scenario::parse_str(text, path, &ov)?;
        check(&parsed.common)?;
        let spheres = parsed.spheres(path)?;
        let reference = parsed.reference(path)?;
        let (common, scene, rheology, record) = parsed.into_parts();
        Ok(Prepared {
            path: path.to_path_buf(),
            common,
            spheres,
            scene,
            rheology,
            reference,
            overrides: crate::scenario::Overrides {
                set: overrides.to_vec(),
                dt_s,
            },
            record,
        })
    }

    /// The effective scenario as `run.toml` records it in `[scenario]`: the tables its kind
    /// uses, defaults filled in, input files as absolute paths, so that the record runs again
    /// anywhere.
    pub fn record_table(&self) -> Result<toml::Table, crate::error::Error> {
        self.record
            .table(&self.path)
            .map_err(|e| crate::error::Error::Io(self.path.clone(), std::io::Error::other(e)))
    }

    /// The whole effective scenario as TOML text: equal for two preparations exactly when they
    /// describe the same case (the checkpoints of `settle run` refuse to resume another).
    pub fn fingerprint(&self) -> String {
        self.record.fingerprint()
    }
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
    /// The simulated time an interrupted run reached, s (`run.toml`'s `reached_s`; None when
    /// complete, or for a kind without one clock).
    pub reached_s: Option<f64>,
    /// Validity warnings (a law used outside its range, a Reynolds number too high for Stokes
    /// drag, …): printed after the run and written to run.toml's `[run] warnings` (issue 13).
    pub warnings: Vec<String>,
}

/// Runs the scene of `p`, its tables and files into `out`: the one match on the kind's spec,
/// each scene receiving its own. Free settling and drops also return their per-sphere results
/// (for the console table and the combined outputs of a several-file run).
pub fn run_scene(
    p: &Prepared,
    out: &mut crate::io::Outputs,
    ctx: &RunContext,
) -> Result<(Vec<free_settling::SphereResult>, SceneReport), crate::error::Error> {
    Ok(match &p.scene {
        SceneSpec::FreeSettling(f) => free_settling::run_scene(p, f, out)?,
        SceneSpec::RestitutionDrop(r) => (Vec::new(), restitution_drop::run(p, r, out)?),
        SceneSpec::TiltFriction(t) => (Vec::new(), tilt_friction::run(p, t, out)?),
        SceneSpec::FunnelPour(f) => (Vec::new(), funnel_pour::run(p, f, out, ctx)?),
        SceneSpec::Sedimentation(sd) => (Vec::new(), sedimentation::run(p, sd, out, ctx)?),
    })
}

/// The load of the prepared scenario `p` as its kind's scene estimates it
/// (`scenes/<kind>/cost.rs`), for [`cost::estimate`] and [`cost::check`].
pub fn load(p: &Prepared) -> cost::Load {
    let c = &p.common;
    match &p.scene {
        SceneSpec::FreeSettling(_) => free_settling::cost::load(c, p.spheres.len()),
        SceneSpec::RestitutionDrop(_) => restitution_drop::cost::load(c),
        SceneSpec::TiltFriction(_) => tilt_friction::cost::load(c),
        SceneSpec::FunnelPour(f) => funnel_pour::cost::load(c, f),
        SceneSpec::Sedimentation(sd) => sedimentation::cost::load(c, sd),
    }
}
