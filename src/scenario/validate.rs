//! Range checks on a parsed scenario. Each failure names the key and the allowed range.

use super::load::ScenarioError;
use super::schema::*;
use std::path::Path;

/// Largest number of steps a run may take before it is refused as unbounded.
pub const MAX_STEPS: f64 = 1e10;

struct Check<'a> {
    file: &'a Path,
}

impl Check<'_> {
    fn err(&self, key: &str, msg: impl Into<String>) -> ScenarioError {
        ScenarioError::new(self.file, Some(key), msg)
    }

    /// `lo < x ≤ hi` (open below) with the unit in the message.
    fn in_open_closed(
        &self,
        key: &str,
        x: f64,
        lo: f64,
        hi: f64,
        unit: &str,
    ) -> Result<(), ScenarioError> {
        if x.is_finite() && x > lo && x <= hi {
            Ok(())
        } else {
            Err(self.err(
                key,
                format!(
                    "{x} is out of range: allowed {lo} < {key_short} ≤ {hi} {unit}",
                    key_short = short(key)
                ),
            ))
        }
    }

    fn in_closed(
        &self,
        key: &str,
        x: f64,
        lo: f64,
        hi: f64,
        unit: &str,
    ) -> Result<(), ScenarioError> {
        if x.is_finite() && x >= lo && x <= hi {
            Ok(())
        } else {
            Err(self.err(
                key,
                format!(
                    "{x} is out of range: allowed {lo} ≤ {} ≤ {hi} {unit}",
                    short(key)
                ),
            ))
        }
    }
}

impl Check<'_> {
    /// A count with `lo ≤ n ≤ hi`.
    fn count_in(&self, key: &str, n: usize, lo: usize, hi: usize) -> Result<(), ScenarioError> {
        if (lo..=hi).contains(&n) {
            Ok(())
        } else {
            Err(self.err(
                key,
                format!("{n} is out of range: allowed {lo} ≤ {} ≤ {hi}", short(key)),
            ))
        }
    }
}

fn short(key: &str) -> &str {
    key.rsplit('.').next().unwrap_or(key)
}

/// Validates ranges and cross-field rules.
pub fn validate(s: &Scenario, file: &Path) -> Result<(), ScenarioError> {
    let c = Check { file };
    if s.name.is_empty()
        || s.name.starts_with('.')
        || !s
            .name
            .chars()
            .all(|ch| ch.is_ascii_alphanumeric() || "_-.".contains(ch))
    {
        return Err(c.err(
            "name",
            format!("`{}` is not allowed: use letters, digits, `_`, `-` and `.`, not starting with `.` (it names the output folder)", s.name),
        ));
    }
    if s.dimension != 2 && s.dimension != 3 {
        return Err(c.err(
            "dimension",
            format!("{} is not allowed: 2 or 3", s.dimension),
        ));
    }
    c.in_open_closed("gravity_m_s2", s.gravity_m_s2, 0.0, 1000.0, "m/s²")?;

    // Fluid.
    c.in_open_closed(
        "fluid.density_kg_m3",
        s.fluid.density_kg_m3,
        0.0,
        25_000.0,
        "kg/m³",
    )?;
    match s.fluid.rheology {
        Rheology::Newtonian => {
            let mu = s.fluid.viscosity_pa_s.ok_or_else(|| {
                c.err(
                    "fluid.viscosity_pa_s",
                    "missing: a newtonian fluid needs its viscosity, 0 < viscosity_pa_s ≤ 1e6 Pa s",
                )
            })?;
            c.in_open_closed("fluid.viscosity_pa_s", mu, 0.0, 1e6, "Pa s")?;
            for k in ["plastic_viscosity_pa_s", "yield_stress_pa"] {
                let given = if k == "yield_stress_pa" {
                    s.fluid.yield_stress_pa
                } else {
                    s.fluid.plastic_viscosity_pa_s
                };
                if given.is_some() {
                    return Err(c.err(
                        &format!("fluid.{k}"),
                        "only allowed with rheology = \"bingham\"",
                    ));
                }
            }
        }
        Rheology::Bingham => {
            let eb = s.fluid.plastic_viscosity_pa_s.ok_or_else(|| {
                c.err(
                    "fluid.plastic_viscosity_pa_s",
                    "missing: a bingham fluid needs 0 < plastic_viscosity_pa_s ≤ 1e6 Pa s",
                )
            })?;
            c.in_open_closed("fluid.plastic_viscosity_pa_s", eb, 0.0, 1e6, "Pa s")?;
            let ty = s.fluid.yield_stress_pa.ok_or_else(|| {
                c.err(
                    "fluid.yield_stress_pa",
                    "missing: a bingham fluid needs 0 ≤ yield_stress_pa ≤ 1e6 Pa",
                )
            })?;
            c.in_closed("fluid.yield_stress_pa", ty, 0.0, 1e6, "Pa")?;
            if s.fluid.viscosity_pa_s.is_some() {
                return Err(c.err("fluid.viscosity_pa_s", "only allowed with rheology = \"newtonian\"; a bingham fluid uses plastic_viscosity_pa_s"));
            }
        }
    }

    // Drag.
    c.in_open_closed("drag.voidage", s.drag.voidage, 0.0, 1.0, "")?;
    if s.drag.law == DragLawName::BinghamFedem && s.fluid.rheology != Rheology::Bingham {
        return Err(c.err("drag.law", "`bingham-fedem` needs fluid.rheology = \"bingham\"; allowed for a newtonian fluid: `stokes`, `dallavalle`"));
    }
    if s.drag.law != DragLawName::BinghamFedem
        && s.fluid.rheology == Rheology::Bingham
        && s.physics == Physics::Full
    {
        return Err(c.err(
            "drag.law",
            "a bingham fluid needs `bingham-fedem` (or physics = \"ideal-stokes\")",
        ));
    }

    // Time.
    c.in_open_closed("time.end_s", s.time.end_s, 0.0, 1e9, "s")?;
    c.in_open_closed(
        "time.dt_s",
        s.time.dt_s,
        0.0,
        s.time.end_s,
        "s (at most time.end_s)",
    )?;
    let steps = s.time.end_s / s.time.dt_s;
    if steps > MAX_STEPS {
        return Err(c.err(
            "time.dt_s",
            format!(
                "{:.3e} steps (end_s/dt_s) exceed the limit of {MAX_STEPS:.0e}: raise dt_s",
                steps
            ),
        ));
    }

    // Container.
    if let Some(ct) = &s.container {
        c.in_open_closed("container.height_m", ct.height_m, 0.0, 1e4, "m")?;
        if let Some(dia) = ct.diameter_m {
            if s.dimension == 2 {
                return Err(c.err("container.diameter_m", "a cylinder is 3D-only: with dimension = 2 give container.width_m (the 2D projection of the cylinder)"));
            }
            c.in_open_closed("container.diameter_m", dia, 0.0, 1e4, "m")?;
        }
        if let Some(w) = ct.width_m {
            c.in_open_closed("container.width_m", w, 0.0, 1e4, "m")?;
        }
    }

    // Release.
    c.in_closed("release.depth_m", s.release.depth_m, 0.0, 1e4, "m")?;
    c.in_closed(
        "release.velocity_m_s",
        s.release.velocity_m_s,
        0.0,
        1e3,
        "m/s",
    )?;

    for (i, h) in s.release.fall_heights_m.iter().enumerate() {
        c.in_closed(&format!("release.fall_heights_m[{i}]"), *h, 0.0, 1e4, "m")?;
    }
    match s.kind {
        Kind::Drop if s.release.fall_heights_m.is_empty() => {
            return Err(c.err(
                "release.fall_heights_m",
                "missing: kind = \"drop\" needs at least one fall height ≥ 0 m",
            ));
        }
        Kind::FreeSettling if !s.release.fall_heights_m.is_empty() => {
            return Err(c.err("release.fall_heights_m", "only allowed with kind = \"drop\" (free_settling releases submerged spheres at release.depth_m)"));
        }
        _ => {}
    }

    if s.kind == Kind::Drop && s.engine == EngineChoice::Rapier {
        return Err(c.err("engine", "`rapier` is not available for kind = \"drop\" yet (no contacts there): allowed `auto`, `free`"));
    }

    // Spheres.
    let need = |present: bool, key: &str, what: &str| -> Result<(), ScenarioError> {
        if present {
            Ok(())
        } else {
            Err(c.err(
                key,
                format!("missing: kind = \"{}\" needs {what}", kind_name(s.kind)),
            ))
        }
    };
    match s.kind {
        Kind::RestitutionDrop => {
            need(
                s.restitution_drop.is_some(),
                "restitution_drop",
                "a [restitution_drop] table with drop_heights_m",
            )?;
            contact_scene_3d(&c, s)?;
            if s.spheres.len() != 1 || s.spheres_csv.is_some() {
                return Err(c.err(
                    "spheres",
                    "kind = \"restitution_drop\" drops one ball: give exactly one [[spheres]] table (no [spheres_csv])",
                ));
            }
            let rd = s.restitution_drop.as_ref().expect("checked above");
            if rd.drop_heights_m.is_empty() {
                return Err(c.err(
                    "restitution_drop.drop_heights_m",
                    "missing: give at least one drop height, 0 < h ≤ 100 m",
                ));
            }
            for (i, h) in rd.drop_heights_m.iter().enumerate() {
                c.in_open_closed(
                    &format!("restitution_drop.drop_heights_m[{i}]"),
                    *h,
                    0.0,
                    100.0,
                    "m",
                )?;
            }
            let n = rd.measured_rebound_heights_m.len();
            if n != 0 && n != rd.drop_heights_m.len() {
                return Err(c.err(
                    "restitution_drop.measured_rebound_heights_m",
                    format!(
                        "{n} values for {} drop heights: give one per drop height or none",
                        rd.drop_heights_m.len()
                    ),
                ));
            }
            for (i, h) in rd.measured_rebound_heights_m.iter().enumerate() {
                c.in_closed(
                    &format!("restitution_drop.measured_rebound_heights_m[{i}]"),
                    *h,
                    0.0,
                    100.0,
                    "m",
                )?;
            }
            c.in_open_closed("restitution_drop.tolerance", rd.tolerance, 0.0, 1.0, "")?;
        }
        Kind::TiltFriction => {
            need(
                s.tilt.is_some(),
                "tilt",
                "a [tilt] table (block_size_m, block_density_kg_m3, angles_deg, duration_s)",
            )?;
            contact_scene_3d(&c, s)?;
            let t = s.tilt.as_ref().expect("checked above");
            if t.block_size_m.len() != 3 {
                return Err(c.err(
                    "tilt.block_size_m",
                    format!(
                        "{} values: give the three edge lengths [x, y, z], each 0 < l ≤ 10 m",
                        t.block_size_m.len()
                    ),
                ));
            }
            for (i, l) in t.block_size_m.iter().enumerate() {
                c.in_open_closed(&format!("tilt.block_size_m[{i}]"), *l, 0.0, 10.0, "m")?;
            }
            c.in_open_closed(
                "tilt.block_density_kg_m3",
                t.block_density_kg_m3,
                0.0,
                25_000.0,
                "kg/m³",
            )?;
            if t.angles_deg.is_empty() {
                return Err(c.err(
                    "tilt.angles_deg",
                    "missing: give at least one angle, 0 ≤ angle < 90°",
                ));
            }
            for (i, a) in t.angles_deg.iter().enumerate() {
                if !(a.is_finite() && (0.0..90.0).contains(a)) {
                    return Err(c.err(
                        &format!("tilt.angles_deg[{i}]"),
                        format!("{a} is out of range: allowed 0 ≤ angle < 90°"),
                    ));
                }
            }
            c.in_closed(
                "tilt.duration_s",
                t.duration_s,
                s.time.dt_s,
                1e4,
                "s (at least time.dt_s)",
            )?;
            if t.duration_s / s.time.dt_s > MAX_STEPS {
                return Err(c.err("time.dt_s", format!(
                    "{:.3e} steps per angle (tilt.duration_s/dt_s) exceed the limit of {MAX_STEPS:.0e}: raise dt_s",
                    t.duration_s / s.time.dt_s)));
            }
            c.in_open_closed("tilt.slide_distance_m", t.slide_distance_m, 0.0, 1e3, "m")?;
            c.in_open_closed(
                "tilt.bisection_tolerance_deg",
                t.bisection_tolerance_deg,
                0.0,
                90.0,
                "°",
            )?;
        }
        Kind::FunnelPour => {
            need(
                s.funnel.is_some(),
                "funnel",
                "a [funnel] table (count, geometry)",
            )?;
            need(
                s.container.as_ref().is_some_and(|c| c.diameter_m.is_some()),
                "container.diameter_m",
                "a cylindrical [container] with diameter_m",
            )?;
            contact_scene_3d(&c, s)?;
            let f = s.funnel.as_ref().expect("checked above");
            let ct = s.container.as_ref().expect("checked above");
            c.count_in("funnel.count", f.count, 1, 100_000)?;
            c.in_open_closed("funnel.top_diameter_m", f.top_diameter_m, 0.0, 10.0, "m")?;
            let d_max = s.spheres.iter().map(|sp| sp.diameter_m).fold(0.0, f64::max);
            c.in_open_closed(
                "funnel.outlet_diameter_m",
                f.outlet_diameter_m,
                d_max,
                f.top_diameter_m,
                "m (wider than the largest ball, at most top_diameter_m)",
            )?;
            c.in_open_closed("funnel.cone_height_m", f.cone_height_m, 0.0, 10.0, "m")?;
            c.in_closed(
                "funnel.outlet_above_surface_m",
                f.outlet_above_surface_m,
                0.0,
                100.0,
                "m",
            )?;
            c.in_closed("funnel.column_height_m", f.column_height_m, 0.0, 10.0, "m")?;
            c.in_closed("funnel.fill_time_s", f.fill_time_s, 0.0, 1e3, "s")?;
            c.in_closed(
                "funnel.wall_above_surface_m",
                f.wall_above_surface_m,
                0.0,
                10.0,
                "m",
            )?;
            c.in_open_closed("funnel.wall_thickness_m", f.wall_thickness_m, 0.0, 1.0, "m")?;
            c.count_in("funnel.facets", f.facets, 8, 1024)?;
            c.in_open_closed("funnel.rest_speed_m_s", f.rest_speed_m_s, 0.0, 1e3, "m/s")?;
            c.in_open_closed(
                "funnel.z_bin_m",
                f.z_bin_m,
                0.0,
                ct.height_m,
                "m (at most container.height_m)",
            )?;
            c.in_open_closed(
                "funnel.grid_cell_m",
                f.grid_cell_m,
                0.0,
                ct.diameter_m.unwrap_or(f64::INFINITY),
                "m (at most container.diameter_m)",
            )?;
            if let Some(tc) = f.count_time_s {
                c.in_open_closed(
                    "funnel.count_time_s",
                    tc,
                    0.0,
                    s.time.end_s,
                    "s (within time.end_s)",
                )?;
            }
            for (i, z) in f.planes_z_m.iter().enumerate() {
                c.in_closed(
                    &format!("funnel.planes_z_m[{i}]"),
                    *z,
                    0.0,
                    ct.height_m,
                    "m (within the paste, above the cylinder bottom)",
                )?;
            }
        }
        Kind::Sedimentation => {
            need(
                s.sample.is_some(),
                "sample",
                "a [sample] table (csv, sample, mass_kg, density_kg_m3)",
            )?;
            need(
                s.container.as_ref().is_some_and(|c| c.width_m.is_some()),
                "container.width_m",
                "a [container] with width_m (B) and height_m (H)",
            )?;
            if s.dimension != 2 {
                return Err(c.err("dimension", "kind = \"sedimentation\" is the 2D projection of the cylinder (seed 000 §4.4): allowed 2"));
            }
            let sm = s.sample.as_ref().expect("checked above");
            c.in_open_closed("sample.mass_kg", sm.mass_kg, 0.0, 1e3, "kg")?;
            c.in_open_closed(
                "sample.density_kg_m3",
                sm.density_kg_m3,
                s.fluid.density_kg_m3,
                25_000.0,
                "kg/m³ (denser than the fluid)",
            )?;
            c.count_in("sample.n_diameters", sm.n_diameters, 2, 100_000)?;
            if sm.particles == 0 {
                return Err(c.err(
                    "sample.particles",
                    "0 is out of range: allowed particles ≥ 1 (the memory and time limits are \
                     checked by the run against its cost estimate)",
                ));
            }
            c.count_in("sample.layers", sm.layers, 1, 1_000_000)?;
            c.in_open_closed("sample.wedge_fraction", sm.wedge_fraction, 0.0, 1.0, "")?;
            c.in_open_closed("sample.voidage_cell_m", sm.voidage_cell_m, 0.0, 1.0, "m")?;
            c.in_open_closed("sample.bed_packing", sm.bed_packing, 0.0, 0.75, "")?;
            c.in_open_closed("sample.max_step_s", sm.max_step_s, 0.0, 1e6, "s")?;
            c.in_open_closed(
                "sample.lubrication_outer_cutoff",
                sm.lubrication_outer_cutoff,
                0.0,
                1.0,
                "(fraction of the effective radius a_eff)",
            )?;
            if sm.lubrication && !sm.contacts {
                return Err(c.err(
                    "sample.lubrication",
                    "the squeeze film is solved inside the contact solve: allowed lubrication = true only with sample.contacts = true (set lubrication = false too)",
                ));
            }
            if !(sm.lubrication_inner_cutoff > 0.0
                && sm.lubrication_inner_cutoff < sm.lubrication_outer_cutoff)
            {
                return Err(c.err(
                    "sample.lubrication_inner_cutoff",
                    format!(
                        "{} is out of range: allowed 0 < lubrication_inner_cutoff < lubrication_outer_cutoff = {} (fractions of the effective radius a_eff)",
                        sm.lubrication_inner_cutoff, sm.lubrication_outer_cutoff
                    ),
                ));
            }
            for (i, t) in sm
                .record_times_s
                .iter()
                .chain(&sm.snapshot_times_s)
                .enumerate()
            {
                c.in_open_closed(
                    &format!("sample.record_times_s/snapshot_times_s[{i}]"),
                    *t,
                    0.0,
                    s.time.end_s,
                    "s (within time.end_s)",
                )?;
            }
            if let Some(ins) = &s.instruments {
                // The instruments (seed 000 §4.5): times, hydrometer figures that give a floating
                // body inside the cylinder, sphere and pipette disc inside the suspension.
                let ct = s.container.as_ref().expect("checked above");
                let (h, b) = (ct.height_m, ct.width_m.unwrap_or(0.0));
                for (key, times) in [
                    ("instruments.hydrometer_times_s", &ins.hydrometer_times_s),
                    ("instruments.buoyancy_times_s", &ins.buoyancy_times_s),
                    ("instruments.pipette_times_s", &ins.pipette_times_s),
                ] {
                    for (i, t) in times.iter().enumerate() {
                        c.in_open_closed(
                            &format!("{key}[{i}]"),
                            *t,
                            0.0,
                            s.time.end_s,
                            "s (within time.end_s)",
                        )?;
                    }
                }
                let positive = [
                    (
                        "hydrometer_bulb_volume_m3",
                        ins.hydrometer_bulb_volume_m3,
                        1e-2,
                        "m³",
                    ),
                    (
                        "hydrometer_bulb_length_m",
                        ins.hydrometer_bulb_length_m,
                        h,
                        "m (within container.height_m)",
                    ),
                    (
                        "hydrometer_taper_m",
                        ins.hydrometer_taper_m,
                        0.5 * ins.hydrometer_bulb_length_m,
                        "m (at most half the bulb length)",
                    ),
                    (
                        "hydrometer_stem_length_m",
                        ins.hydrometer_stem_length_m,
                        10.0,
                        "m",
                    ),
                    (
                        "hydrometer_effective_depth_zero_m",
                        ins.hydrometer_effective_depth_zero_m,
                        h,
                        "m (within container.height_m)",
                    ),
                    (
                        "hydrometer_effective_depth_slope_m",
                        ins.hydrometer_effective_depth_slope_m,
                        1.0,
                        "m per g/L",
                    ),
                    (
                        "hydrometer_full_scale",
                        ins.hydrometer_full_scale,
                        1e3,
                        "g/L",
                    ),
                    (
                        "hydrometer_astm_cylinder_area_m2",
                        ins.hydrometer_astm_cylinder_area_m2,
                        10.0,
                        "m²",
                    ),
                    (
                        "sphere_diameter_m",
                        ins.sphere_diameter_m,
                        b,
                        "m (within container.width_m)",
                    ),
                    ("sphere_mass_kg", ins.sphere_mass_kg, 1e3, "kg"),
                    ("pipette_volume_m3", ins.pipette_volume_m3, 1.0, "m³"),
                ];
                for (key, x, hi, unit) in positive {
                    c.in_open_closed(&format!("instruments.{key}"), x, 0.0, hi, unit)?;
                }
                c.in_open_closed(
                    "instruments.hydrometer_calibration_specific_gravity",
                    ins.hydrometer_calibration_specific_gravity,
                    1.0,
                    30.0,
                    "",
                )?;
                let hy = crate::instruments::hydrometer::Hydrometer::new(
                    ins.hydrometer(),
                    s.fluid.density_kg_m3,
                );
                if !(hy.stem_radius_m > 0.0
                    && hy.bulb_radius_m > hy.stem_radius_m
                    && hy.zero_mark_m > 0.0
                    && hy.zero_mark_m <= ins.hydrometer_stem_length_m
                    && hy.mark_m(ins.hydrometer_full_scale) >= 0.0
                    && hy.clear_tip_depth_m() < h)
                {
                    return Err(c.err("instruments", format!(
                        "the hydrometer figures give no floating body that fits: stem radius {:.3e} m, bulb radius {:.3e} m (allowed 0 < stem < bulb), marks 0 and full scale at {:.3e} and {:.3e} m up the stem (allowed 0 ≤ marks ≤ stem length), clear-fluid tip depth {:.3e} m (allowed < container.height_m = {h} m)",
                        hy.stem_radius_m, hy.bulb_radius_m, hy.zero_mark_m, hy.mark_m(ins.hydrometer_full_scale), hy.clear_tip_depth_m())));
                }
                let rs = 0.5 * ins.sphere_diameter_m / h;
                c.in_open_closed(
                    "instruments.sphere_depth_fraction",
                    ins.sphere_depth_fraction,
                    rs,
                    1.0 - rs,
                    "of H (the whole sphere in the suspension)",
                )?;
                let hz = sm.projection_thickness_m(b);
                let rp = (sm.wedge_fraction * ins.pipette_volume_m3 / (hz * std::f64::consts::PI))
                    .sqrt();
                if rp > 0.5 * b {
                    return Err(c.err("instruments.pipette_volume_m3", format!(
                        "{} m³ is a disc of radius {rp:.3e} m in the 2D projection, wider than the cylinder (allowed radius ≤ B/2 = {} m)",
                        ins.pipette_volume_m3, 0.5 * b)));
                }
                c.in_open_closed(
                    "instruments.pipette_depth_fraction",
                    ins.pipette_depth_fraction,
                    rp / h,
                    1.0 - rp / h,
                    "of H (the whole sampled disc in the suspension)",
                )?;
            }
        }
        Kind::FreeSettling | Kind::Drop => {}
    }
    if let Some(ct) = &s.contacts {
        c.in_closed("contacts.restitution", ct.restitution, 0.0, 1.0, "")?;
        c.in_closed(
            "contacts.restitution_exponent",
            ct.restitution_exponent,
            0.0,
            1.0,
            "",
        )?;
        c.in_closed(
            "contacts.restitution_reference_speed_m_s",
            ct.restitution_reference_speed_m_s,
            1e-3,
            100.0,
            "m/s",
        )?;
        c.in_closed("contacts.friction", ct.friction, 0.0, 10.0, "")?;
        c.in_closed(
            "contacts.rolling_resistance",
            ct.rolling_resistance,
            0.0,
            1.0,
            "",
        )?;
    }
    if let Some(r) = &s.repeats {
        c.count_in("repeats.count", r.count, 1, 10_000)?;
    }
    if !matches!(s.kind, Kind::TiltFriction | Kind::Sedimentation)
        && s.spheres.is_empty()
        && s.spheres_csv.is_none()
    {
        return Err(c.err(
            "spheres",
            "missing: give at least one [[spheres]] table or a [spheres_csv] file",
        ));
    }
    for (i, sp) in s.spheres.iter().enumerate() {
        check_sphere_inner(&c, &format!("spheres[{i}]"), sp, s)?;
    }

    // Measurement.
    if let Some(m) = &s.measure {
        let h = s
            .container
            .as_ref()
            .map(|c| c.height_m)
            .unwrap_or(f64::INFINITY);
        match (m.section_top_depth_m, m.section_bottom_depth_m) {
            (None, None) => {}
            (Some(top), Some(bot)) => {
                c.in_closed(
                    "measure.section_top_depth_m",
                    top,
                    0.0,
                    h,
                    "m (within the container)",
                )?;
                if !(bot > top && bot <= h) {
                    return Err(c.err("measure.section_bottom_depth_m", format!(
                        "{bot} is out of range: allowed section_top_depth_m ({top}) < section_bottom_depth_m ≤ container.height_m ({h}) m")));
                }
            }
            (Some(_), None) => {
                return Err(c.err(
                    "measure.section_bottom_depth_m",
                    "missing: give both detectors of the measuring section or neither",
                ))
            }
            (None, Some(_)) => {
                return Err(c.err(
                    "measure.section_top_depth_m",
                    "missing: give both detectors of the measuring section or neither",
                ))
            }
        }
        c.in_open_closed("measure.steady_tolerance", m.steady_tolerance, 0.0, 1.0, "")?;
        c.in_open_closed(
            "measure.terminal_tolerance",
            m.terminal_tolerance,
            0.0,
            1.0,
            "",
        )?;
        if let Some(w) = m.terminal_window_m {
            c.in_open_closed("measure.terminal_window_m", w, 0.0, 1e4, "m")?;
        }
        for (i, t) in m.velocity_at_s.iter().enumerate() {
            c.in_open_closed(
                &format!("measure.velocity_at_s[{i}]"),
                *t,
                0.0,
                s.time.end_s,
                "s (within time.end_s)",
            )?;
        }
    }
    if let Some(e) = s.record.every_s {
        c.in_open_closed("record.every_s", e, 0.0, s.time.end_s, "s")?;
    }
    if let Some(sw) = &s.sweep {
        for (i, dt) in sw.dt_s.iter().enumerate() {
            c.in_open_closed(&format!("sweep.dt_s[{i}]"), *dt, 0.0, s.time.end_s, "s")?;
        }
        if let Some(t) = sw.tol {
            c.in_open_closed("sweep.tol", t, 0.0, 1.0, "")?;
        }
    }
    Ok(())
}

/// Checks one sphere (also used for spheres read from CSV, with `key` naming the row).
pub(crate) fn check_sphere(
    c_file: &Path,
    key: &str,
    sp: &SphereSpec,
    s: &Scenario,
) -> Result<(), ScenarioError> {
    check_sphere_inner(&Check { file: c_file }, key, sp, s)
}

fn check_sphere_inner(
    c: &Check,
    key: &str,
    sp: &SphereSpec,
    s: &Scenario,
) -> Result<(), ScenarioError> {
    c.in_open_closed(&format!("{key}.diameter_m"), sp.diameter_m, 0.0, 10.0, "m")?;
    c.in_open_closed(
        &format!("{key}.density_kg_m3"),
        sp.density_kg_m3,
        0.0,
        25_000.0,
        "kg/m³",
    )?;
    if let Some(e) = sp.youngs_modulus_pa {
        c.in_open_closed(&format!("{key}.youngs_modulus_pa"), e, 0.0, 1e13, "Pa")?;
    }
    if let Some(nu) = sp.poisson_ratio {
        if !(nu > -1.0 && nu < 0.5) {
            return Err(c.err(
                &format!("{key}.poisson_ratio"),
                format!("{nu} is out of range: allowed -1 < poisson_ratio < 0.5"),
            ));
        }
    }
    if let Some(v) = sp.v_measured_m_s {
        c.in_closed(&format!("{key}.v_measured_m_s"), v, 0.0, 1e3, "m/s")?;
    }
    if let Some(ct) = &s.container {
        if s.release.depth_m + 0.5 * sp.diameter_m > ct.height_m {
            return Err(c.err(
                "release.depth_m",
                format!(
                    "{} m puts {key} (d = {} m) below the container bottom at {} m",
                    s.release.depth_m, sp.diameter_m, ct.height_m
                ),
            ));
        }
    }
    Ok(())
}

/// Kinds with contacts run in a Rapier 3D world: a [contacts] table, dimension 3, engine `auto`
/// or `rapier`.
fn contact_scene_3d(c: &Check, s: &Scenario) -> Result<(), ScenarioError> {
    let kind = kind_name(s.kind);
    if s.contacts.is_none() {
        return Err(c.err(
            "contacts",
            format!("missing: kind = \"{kind}\" needs a [contacts] table (restitution, friction, rolling_resistance)"),
        ));
    }
    if s.dimension != 3 {
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
    Ok(())
}

/// The name of a kind as written in scenario files.
pub fn kind_name(k: Kind) -> &'static str {
    match k {
        Kind::FreeSettling => "free_settling",
        Kind::Drop => "drop",
        Kind::RestitutionDrop => "restitution_drop",
        Kind::TiltFriction => "tilt_friction",
        Kind::FunnelPour => "funnel_pour",
        Kind::Sedimentation => "sedimentation",
    }
}
