//! The list of spheres of a scenario: inline `[[spheres]]` plus rows of a `[spheres_csv]` file.

use crate::scenario::{Scenario, ScenarioError, SphereSpec};
use serde::Deserialize;
use std::path::Path;

/// One sphere to simulate, with its identifier resolved.
#[derive(Clone, Debug, PartialEq)]
pub struct SphereCase {
    /// Identifier (`sphere_id` column).
    pub id: String,
    /// The sphere's properties.
    pub spec: SphereSpec,
    /// Fall height of the lowest point above the free surface, m (kind `drop`).
    pub fall_height_m: Option<f64>,
}

#[derive(Deserialize)]
struct CsvRow {
    sphere_id: String,
    suspension: Option<u32>,
    diameter_m: f64,
    density_kg_m3: f64,
    v_terminal_measured_m_s: Option<f64>,
}

/// Resolves the spheres of `scenario`, read from `scenario_path`'s folder for relative CSV paths.
pub fn spheres(
    scenario: &Scenario,
    scenario_path: &Path,
) -> Result<Vec<SphereCase>, ScenarioError> {
    let mut out: Vec<SphereCase> = scenario
        .spheres
        .iter()
        .enumerate()
        .map(|(i, s)| SphereCase {
            id: s.id.clone().unwrap_or_else(|| format!("sphere-{i}")),
            spec: s.clone(),
            fall_height_m: None,
        })
        .collect();
    if let Some(src) = &scenario.spheres_csv {
        let base = scenario_path.parent().unwrap_or(Path::new("."));
        let csv_path = base.join(&src.path);
        let err = |m: String| ScenarioError::new(scenario_path, Some("spheres_csv.path"), m);
        let mut rdr = csv::ReaderBuilder::new()
            .comment(Some(b'#'))
            .from_path(&csv_path)
            .map_err(|e| {
                err(format!(
                    "cannot read `{}` (the path is relative to the scenario file's folder): {e}",
                    csv_path.display()
                ))
            })?;
        for (i, row) in rdr.deserialize::<CsvRow>().enumerate() {
            let row =
                row.map_err(|e| err(format!("`{}` row {}: {e}", csv_path.display(), i + 2)))?;
            if src.suspension.is_some() && row.suspension != src.suspension {
                continue;
            }
            let spec = SphereSpec {
                id: Some(row.sphere_id.clone()),
                diameter_m: row.diameter_m,
                density_kg_m3: row.density_kg_m3,
                youngs_modulus_pa: None,
                poisson_ratio: None,
                v_measured_m_s: row.v_terminal_measured_m_s,
                suspension: row.suspension,
            };
            crate::scenario::check_sphere(
                scenario_path,
                &format!("spheres_csv `{}` row {}", csv_path.display(), i + 2),
                &spec,
                scenario,
            )?;
            out.push(SphereCase {
                id: row.sphere_id,
                spec,
                fall_height_m: None,
            });
        }
        if out.is_empty() {
            return Err(err(format!(
                "`{}` has no sphere{}",
                csv_path.display(),
                src.suspension
                    .map(|s| format!(" of suspension {s}"))
                    .unwrap_or_default()
            )));
        }
    }
    if !scenario.release.fall_heights_m.is_empty() {
        out = out
            .iter()
            .flat_map(|c| {
                scenario
                    .release
                    .fall_heights_m
                    .iter()
                    .map(move |h| SphereCase {
                        id: format!("{}-H{}mm", c.id, (h * 1e3 * 10.0).round() / 10.0),
                        spec: c.spec.clone(),
                        fall_height_m: Some(*h),
                    })
            })
            .collect();
    }
    Ok(out)
}
