//! Reading a file into the [`Test`] the inversion fits: the column and conversions of the
//! test, and its instrument as the forward model reads it.

use super::problem::{DrawRegion, Probe, Test};
use crate::error::Error;
use crate::instruments::buoyancy::BuoyancySphere;
use crate::instruments::forward::Column;
use crate::instruments::hydrometer::{Hydrometer, HydrometerSpec};
use crate::instruments::reduction::{
    reduce, water_density_kg_m3, water_viscosity_pa_s, HydrometerType, Instrument, LabReading,
    PipetteRegion, Reduced, Standard, TestSetup,
};
use crate::instruments::Analysis;
use crate::reduce::{Readings, ReduceOptions};
use std::path::Path;

/// Reads one readings file: its [`Test`] (readings of resolution `resolution`, else the
/// instrument's default) and its standard reduction.
pub fn read_test(file: &Path, resolution: Option<f64>) -> Result<(Test, Vec<Reduced>), Error> {
    read_test_of(&Readings::File(file.to_path_buf()), resolution)
}

/// [`read_test`] of readings given as a file or in memory.
pub(crate) fn read_test_of(
    readings: &Readings,
    resolution: Option<f64>,
) -> Result<(Test, Vec<Reduced>), Error> {
    let file = &readings.path();
    if let Readings::File(f) = readings {
        if !f.is_file() {
            return Err(Error::bad_input(
                file,
                None,
                "no such readings file (give the path of a CSV in the format of `settle reduce`)",
            ));
        }
    }
    let read = crate::reduce::read_checked(readings, &ReduceOptions::default())?;
    let (setup, lab) = (read.setup, read.readings);
    let mut test = test_of(file, &setup, &lab, resolution)?;
    test.input = Some((read.detected, read.warnings));
    if let Some(c) = read.counting_sigma {
        test.counting_sigma = c;
    }
    Ok((test, reduce(&setup, &lab)))
}

/// The analysis of a file's test: μ_w at the mean temperature of its readings, ρ_f the file's
/// `fluid_density_kg_m3` or ρ_w at that temperature, ρ_p = G_s ρ_f, g the file's
/// `gravity_m_s2` or 9.807 m/s², c₀ = dry mass / suspension volume.
fn analysis(setup: &TestSetup, readings: &[LabReading]) -> Analysis {
    let t = readings.iter().map(|r| r.temperature_c).sum::<f64>() / readings.len() as f64;
    let rho_f = setup
        .model
        .fluid_density_kg_m3
        .unwrap_or_else(|| water_density_kg_m3(t));
    Analysis {
        viscosity_pa_s: water_viscosity_pa_s(t),
        grain_density_kg_m3: setup.specific_gravity * rho_f,
        fluid_density_kg_m3: rho_f,
        gravity_m_s2: setup.model.gravity_m_s2.unwrap_or(9.807),
        c0_kg_m3: setup.dry_mass_kg / setup.suspension_volume_m3,
    }
}

/// Section of the cylinder when the file does not give it, m² (ASTM D422's 27.8 cm²).
pub const DEFAULT_CYLINDER_AREA_M2: f64 = 27.8e-4;
/// Default resolution of the 152H, g/L (its scale's smallest division).
pub const HYDROMETER_RESOLUTION: f64 = 0.5;
/// Default resolution of a pipette's drawn mass, g (1 mg: an analytical balance reads 0.1 mg,
/// the drying and weighing of a 35 mL draw's solids are good to about 1 mg).
pub const PIPETTE_RESOLUTION_G: f64 = 1e-3;
/// Default resolution of the buoyancy sphere's apparent mass, g (a 0.01 g balance).
pub const SPHERE_RESOLUTION_G: f64 = 1e-2;

/// The instrument of a file as the forward model reads it, and its default resolution.
fn probe_of(file: &Path, setup: &TestSetup, rho_f: f64) -> Result<(Probe, f64), Error> {
    Ok(match setup.instrument {
        Instrument::Hydrometer(h) => {
            if h != HydrometerType::H152 {
                return Err(Error::bad_input(
                    file,
                    Some("hydrometer"),
                    "invert models the 152H only (its bulb geometry): the 151H is not supported",
                ));
            }
            let mut spec = HydrometerSpec::default();
            if let (Standard::D7928, Some(m)) = (setup.standard, setup.measured) {
                // D7928's measured dimensions: the effective depth is linear in the reading
                // between the marks r1 and r2, H_m(r) (from the bulb's centre, less V_B/(2A)).
                spec.bulb_volume_m3 = m.bulb_volume_m3;
                spec.astm_cylinder_area_m2 = m.cylinder_area_m2;
                spec.effective_depth_zero_m = m.effective_depth_m(0.0);
                spec.effective_depth_slope_m = (m.h_r1_m - m.h_r2_m) / (m.r2 - m.r1);
            }
            if let Some(l2) = setup.model.hydrometer_bulb_length_m {
                spec.bulb_length_m = l2;
            }
            (
                Probe::Hydrometer(Hydrometer::new(spec, rho_f)),
                HYDROMETER_RESOLUTION,
            )
        }
        Instrument::Pipette {
            volume_m3,
            depth_m,
            region,
        } => (
            Probe::Pipette {
                volume_m3,
                depth_m,
                region: match region {
                    PipetteRegion::Sphere => DrawRegion::Sphere,
                    PipetteRegion::Disc { radius_m } => DrawRegion::Disc { radius_m },
                },
            },
            PIPETTE_RESOLUTION_G,
        ),
        Instrument::BuoyancySphere {
            diameter_m,
            mass_kg,
            depth_m,
        } => (
            Probe::Sphere(BuoyancySphere {
                diameter_m,
                mass_kg,
                depth_m,
            }),
            SPHERE_RESOLUTION_G,
        ),
    })
}

/// The test of one readings file.
fn test_of(
    file: &Path,
    setup: &TestSetup,
    readings: &[LabReading],
    resolution: Option<f64>,
) -> Result<Test, Error> {
    let an = analysis(setup, readings);
    let area = setup
        .measured
        .map(|m| m.cylinder_area_m2)
        .unwrap_or(DEFAULT_CYLINDER_AREA_M2);
    let height = setup
        .model
        .column_height_m
        .unwrap_or(setup.suspension_volume_m3 / area);
    let layers = ((height / 1.25e-4).ceil() as usize).clamp(400, 8000);
    let (probe, default_resolution) = probe_of(file, setup, an.fluid_density_kg_m3)?;
    let (top, bottom) = probe.depth_span_m(0.0);
    if bottom > height || top < 0.0 {
        return Err(Error::bad_input(
            file,
            None,
            format!(
                "the {} reaches {} m below the surface, deeper than the column ({} m): check \
                 its depth and column_height_cm",
                probe.name(),
                crate::io::fmt::g(bottom),
                crate::io::fmt::g(height)
            ),
        ));
    }
    let offsets = readings
        .iter()
        .map(|r| match probe {
            Probe::Sphere(_) => 0.0,
            _ => r.blank_reading,
        })
        .collect();
    Ok(Test {
        file: file.to_path_buf(),
        col: Column {
            height_m: height,
            layers,
            analysis: an,
        },
        probe,
        times_s: readings.iter().map(|r| r.time_s).collect(),
        readings: readings.iter().map(|r| r.reading).collect(),
        offsets,
        resolution: resolution.unwrap_or(default_resolution),
        counting_sigma: vec![0.0; readings.len()],
        input: None,
    })
}
