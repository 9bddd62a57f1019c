//! The checks of a table that read the whole scenario (its kind, engine, container, time):
//! `[release]`, `[[spheres]]` and `[transient]` against the other tables, and the common
//! requirements of the kinds with contacts. [`super::super::validate`] and the kinds' specs run
//! them.

use super::base::{Dim, EngineChoice, Kind, Physics};
use super::bodies::{Release, SphereSpec};
use super::contacts::Contacts;
use super::fluid::Rheology;
use super::scenario::Scenario;
use super::transient::{Confinement, History, HistoryReynolds, Transient, Wall};
use crate::dynamics::Integrator;
use crate::error::BadInput;
use crate::scenario::check::{cc, oc, Check};
use std::path::Path;

impl Release {
    /// Depth and speed in range; fall heights for kind `drop` only, each reached by free fall
    /// within `time.end_s`.
    pub(crate) fn check(&self, c: &Check, s: &Scenario) -> Result<(), BadInput> {
        c.table(
            "release",
            &[
                ("depth_m", self.depth_m, cc(0.0, 1e4, "m")),
                ("velocity_m_s", self.velocity_m_s, cc(0.0, 1e3, "m/s")),
            ],
        )?;
        c.each(
            "release.fall_heights_m",
            &self.fall_heights_m,
            cc(0.0, 1e4, "m"),
        )?;
        match s.kind {
            Kind::Drop if self.fall_heights_m.is_empty() => {
                return Err(c.err(
                    "release.fall_heights_m",
                    "missing: kind = \"drop\" needs at least one fall height ≥ 0 m",
                ));
            }
            Kind::FreeSettling if !self.fall_heights_m.is_empty() => {
                return Err(c.err("release.fall_heights_m", "only allowed with kind = \"drop\" (free_settling releases submerged spheres at release.depth_m)"));
            }
            _ => {}
        }
        // A ball still in the air at time.end_s has no settling distance (it would be written
        // as minus the height left to fall). In air it falls freely (no fluid forces above the
        // surface): h = v₀ T + ½ g T².
        let (g, v0, end) = (s.gravity_m_s2, self.velocity_m_s, s.time.end_s);
        let h_max = v0 * end + 0.5 * g * end * end;
        for (i, &h) in self.fall_heights_m.iter().enumerate() {
            if h >= h_max {
                let t_fall = ((v0 * v0 + 2.0 * g * h).sqrt() - v0) / g;
                return Err(c.err(
                    &format!("release.fall_heights_m[{i}]"),
                    format!(
                        "{h} m takes {t_fall:.4} s of free fall to reach the surface, not within time.end_s = {end} s: allowed 0 ≤ fall height < {h_max:.6} m (v₀ T + ½ g T², T = time.end_s), or raise time.end_s"
                    ),
                ));
            }
        }
        Ok(())
    }
}

impl SphereSpec {
    /// Checks one sphere; `key` names it (`spheres[0]`, or a CSV row). Besides its own ranges:
    /// narrower than the container and released above its bottom.
    pub(crate) fn check(&self, c: &Check, key: &str, s: &Scenario) -> Result<(), BadInput> {
        c.table(
            key,
            &[
                ("diameter_m", self.diameter_m, oc(0.0, 10.0, "m")),
                (
                    "density_kg_m3",
                    self.density_kg_m3,
                    oc(0.0, 25_000.0, "kg/m³"),
                ),
            ],
        )?;
        if let Some(e) = self.youngs_modulus_pa {
            c.range(&format!("{key}.youngs_modulus_pa"), e, oc(0.0, 1e13, "Pa"))?;
        }
        if let Some(nu) = self.poisson_ratio {
            if !(nu > -1.0 && nu < 0.5) {
                return Err(c.err(
                    &format!("{key}.poisson_ratio"),
                    format!("{nu} is out of range: allowed -1 < poisson_ratio < 0.5"),
                ));
            }
        }
        if let Some(v) = self.v_measured_m_s {
            c.range(&format!("{key}.v_measured_m_s"), v, cc(0.0, 1e3, "m/s"))?;
        }
        if let Some(ct) = &s.container {
            let (d, b) = (self.diameter_m, ct.narrowest_m());
            if d >= b {
                let which = if ct.diameter_m.is_some_and(|x| x <= b) {
                    "container.diameter_m"
                } else {
                    "container.width_m"
                };
                return Err(c.err(
                    &format!("{key}.diameter_m"),
                    format!(
                        "{d} m does not fit in the container: allowed 0 < diameter_m < {which} = {b} m"
                    ),
                ));
            }
            if let Some(t) = &s.transient {
                t.check_confined_sphere(c, key, d, s)?;
            }
            if s.release.depth_m + 0.5 * d > ct.height_m {
                return Err(c.err(
                    "release.depth_m",
                    format!(
                        "{} m puts {key} (d = {} m) below the container bottom at {} m",
                        s.release.depth_m, d, ct.height_m
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Kinds with contacts run in a Rapier 3D world: a `[contacts]` table (returned), dimension 3,
/// engine `auto` or `rapier`.
pub(crate) fn contact_scene_3d(c: &Check, s: &Scenario) -> Result<Contacts, BadInput> {
    let kind = s.kind.name();
    let Some(contacts) = &s.contacts else {
        return Err(c.err(
            "contacts",
            format!("missing: kind = \"{kind}\" needs a [contacts] table (restitution, friction, rolling_resistance)"),
        ));
    };
    if s.dimension != Dim::Three {
        return Err(c.err(
            "dimension",
            format!("kind = \"{kind}\" is 3D-only (Rapier 3D contacts): allowed 3"),
        ));
    }
    if s.engine == EngineChoice::Free {
        return Err(c.err(
            "engine",
            format!("kind = \"{kind}\" needs contacts: allowed `auto`, `rapier`"),
        ));
    }
    Ok(contacts.clone())
}

impl Transient {
    /// `added_mass_coefficient` in [0, 2]; in the Rapier scenes (`restitution_drop`,
    /// `funnel_pour`) the added mass only; the history force only in a Newtonian fluid, for kind
    /// `free_settling`, on the free engine, with the exponential integrator; the wall only with a
    /// `[container]`, for kind `free_settling`.
    pub(crate) fn check(&self, c: &Check, s: &Scenario) -> Result<(), BadInput> {
        c.range(
            "transient.added_mass_coefficient",
            self.added_mass_coefficient,
            cc(0.0, 2.0, ""),
        )?;
        let rapier_scene = matches!(s.kind, Kind::RestitutionDrop | Kind::FunnelPour);
        if rapier_scene && self.history != History::Off {
            return Err(c.err("transient.history", format!("the history force is not implemented in the Rapier scenes (kind = \"{}\"): use history = \"off\" (allowed there: added_mass, added_mass_coefficient)", s.kind.name())));
        }
        if self.any() && !rapier_scene && s.engine == EngineChoice::Rapier {
            return Err(c.err(
                "transient",
                "the transient forces run on the free engine only: use engine = \"auto\" or \"free\"",
            ));
        }
        if self.history != History::Off {
            if s.fluid.rheology == Rheology::Bingham && s.physics == Physics::Full {
                return Err(c.err("transient.history", "no history force is established for a yield-stress (Bingham) fluid: use history = \"off\" there (added mass applies)"));
            }
            if s.kind != Kind::FreeSettling {
                return Err(c.err("transient.history", format!("the history force is implemented for kind = \"free_settling\" only, not \"{}\": use history = \"off\"", s.kind.name())));
            }
            if s.time.integrator != Integrator::Exponential {
                return Err(c.err("transient.history", "the history force is integrated by the exponential scheme only: set time.integrator = \"exponential\""));
            }
        }
        if self.history_reynolds != HistoryReynolds::Terminal && self.history != History::MeiAdrian
        {
            return Err(c.err(
                "transient.history_reynolds",
                "only Mei & Adrian's kernel depends on the Reynolds number: set history = \"mei-adrian\" or remove history_reynolds",
            ));
        }
        if self.wall != Wall::Off {
            if s.kind != Kind::FreeSettling {
                return Err(c.err("transient.wall", format!("the wall correction is implemented for kind = \"free_settling\" only, not \"{}\"", s.kind.name())));
            }
            if s.container.is_none() {
                return Err(c.err(
                    "transient.wall",
                    "the wall correction needs a [container] (its bottom is the wall)",
                ));
            }
        }
        if self.confinement != Confinement::Off {
            self.check_confinement(c, s)?;
        }
        Ok(())
    }

    /// Haberman & Sayre's factor: kind `free_settling`, a cylindrical container
    /// (`container.diameter_m`). Each sphere's d/D is checked with the sphere
    /// ([`Transient::check_confined_sphere`]), so that spheres read from CSV are too.
    fn check_confinement(&self, c: &Check, s: &Scenario) -> Result<(), BadInput> {
        const KEY: &str = "transient.confinement";
        if s.kind != Kind::FreeSettling {
            return Err(c.err(KEY, format!("the confinement factor is implemented for kind = \"free_settling\" only, not \"{}\"", s.kind.name())));
        }
        if s.container.as_ref().and_then(|k| k.diameter_m).is_none() {
            return Err(c.err(KEY, "Haberman & Sayre's factor is for a sphere on the axis of a circular cylinder: give container.diameter_m (no factor is implemented for a square section)"));
        }
        Ok(())
    }

    /// With the confinement factor on, the sphere `key` of diameter `d_m` has d/D in Haberman &
    /// Sayre's range (0, [`crate::fluid::transient::wall::HABERMAN_SAYRE_MAX_RATIO`]].
    pub(crate) fn check_confined_sphere(
        &self,
        c: &Check,
        key: &str,
        d_m: f64,
        s: &Scenario,
    ) -> Result<(), BadInput> {
        use crate::fluid::transient::wall::HABERMAN_SAYRE_MAX_RATIO as MAX;
        let big_d = s.container.as_ref().and_then(|k| k.diameter_m);
        let (Confinement::HabermanSayre, Some(big_d)) = (self.confinement, big_d) else {
            return Ok(());
        };
        let ratio = d_m / big_d;
        if ratio > 0.0 && ratio <= MAX {
            return Ok(());
        }
        Err(c.err(
            &format!("{key}.diameter_m"),
            format!("d/D = {ratio:.4} with container.diameter_m = {big_d} m is outside Haberman & Sayre's range (0, {MAX}] (transient.confinement)"),
        ))
    }
}

/// Checks one sphere (also used for spheres read from CSV, with `key` naming the row).
pub(crate) fn check_sphere(
    file: &Path,
    key: &str,
    sp: &SphereSpec,
    s: &Scenario,
) -> Result<(), BadInput> {
    sp.check(&Check { file }, key, s)
}
