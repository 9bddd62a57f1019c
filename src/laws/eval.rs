//! Every law on every sphere: the predicted terminal velocity (the force balance of f-EDEM
//! eq. 15 solved by the same [`SphereDrag::balance_speed`] the simulator's integrators rely on),
//! the velocity error, and the force error at the measured speed.

use super::data::{DataSet, Sphere};
use crate::fluid::bingham::{beris, net_weight_n, PlasticLaw};
use crate::fluid::{DragLaw, SphereDrag};
use crate::io::metrics::ErrorStats;

/// Standard gravity of the evaluation, m/s² (the scenarios' default, f-EDEM's value).
pub const G_M_S2: f64 = 9.81;

/// One law as `settle laws` evaluates it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Law {
    /// f-EDEM eqs. 9, 14, 19 (`bingham-fedem`); constants fitted to Valentik & Whitmore.
    Fedem,
    /// Another yield-stress law, with (`true`) or without Beris et al.'s static criterion.
    Plastic(PlasticLaw, bool),
}

impl Law {
    /// The laws of the table, in order: f-EDEM, additive, Ansley & Smith, Wilson et al., and the
    /// last two with Beris et al.'s static criterion (for f-EDEM's and the additive law the
    /// criterion changes nothing: their own static resistance, 11.9 d² τ_y, exceeds Beris's
    /// 11.0 d² τ_y).
    pub const ALL: [Law; 6] = [
        Law::Fedem,
        Law::Plastic(PlasticLaw::Additive, false),
        Law::Plastic(PlasticLaw::AnsleySmith, false),
        Law::Plastic(PlasticLaw::AnsleySmith, true),
        Law::Plastic(PlasticLaw::Wilson, false),
        Law::Plastic(PlasticLaw::Wilson, true),
    ];

    /// Name in tables and CSV files: the `drag.law` value, `+beris` with the criterion.
    pub fn key(self) -> String {
        match self {
            Law::Fedem => "bingham-fedem".into(),
            Law::Plastic(p, false) => p.key().into(),
            Law::Plastic(p, true) => format!("{}+beris", p.key()),
        }
    }

    /// True when the law has constants fitted to the Valentik–Whitmore spheres (f-EDEM's eq. 19:
    /// 29.12 and 0.195 from Table 3).
    pub fn fitted_to_valentik(self) -> bool {
        self == Law::Fedem
    }

    /// The drag law for `sphere` in its fluid; None when the law does not take that fluid
    /// (a Herschel–Bulkley fluid and a Bingham-only law).
    pub fn drag(self, data: &DataSet, sphere: &Sphere) -> Option<SphereDrag> {
        let f = &data.fluids[sphere.fluid];
        let law = match self {
            Law::Fedem if f.is_bingham() => DragLaw::Bingham {
                yield_stress_pa: f.rheogram.yield_stress_pa,
                plastic_viscosity_pa_s: f.rheogram.consistency_pa_sn,
            },
            Law::Plastic(p, beris) if f.is_bingham() || p.supports_herschel_bulkley() => {
                DragLaw::Plastic {
                    law: p,
                    fluid: f.rheogram,
                    beris,
                }
            }
            _ => return None,
        };
        Some(SphereDrag::new(law, sphere.diameter_m, f.density_kg_m3))
    }
}

/// What a law predicts for a sphere.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum State {
    /// Moving at a speed where the drag balances the net weight.
    Moving,
    /// Held at rest: the net weight does not exceed the static resistance.
    Static,
    /// Held on a jump of the law (f-EDEM's eq. 19 at Re′ = 1 or 150): no speed balances.
    Jump,
}

impl State {
    /// CSV label.
    pub fn label(self) -> &'static str {
        match self {
            State::Moving => "moving",
            State::Static => "static",
            State::Jump => "jump",
        }
    }
}

/// One law's prediction for one sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prediction {
    /// Index of the sphere in [`DataSet::spheres`].
    pub sphere: usize,
    /// Predicted terminal velocity, m/s (0 when static).
    pub v_predicted_m_s: f64,
    /// Moving, static or on a jump.
    pub state: State,
    /// (predicted − measured)/measured.
    pub rel_error: f64,
    /// drag(v_measured)/net weight − 1: the law's force error at the measured speed.
    pub force_rel_error: f64,
}

/// Net weight of a sphere in its fluid, N.
pub fn net_weight(data: &DataSet, s: &Sphere) -> f64 {
    net_weight_n(
        s.diameter_m,
        s.density_kg_m3,
        data.fluids[s.fluid].density_kg_m3,
        G_M_S2,
    )
}

/// Yield number Y = τ_y/(Δρ g d) of a sphere.
pub fn yield_number(data: &DataSet, s: &Sphere) -> f64 {
    let f = &data.fluids[s.fluid];
    beris::yield_number(
        f.rheogram.yield_stress_pa,
        s.density_kg_m3 - f.density_kg_m3,
        G_M_S2,
        s.diameter_m,
    )
}

/// The predictions of `law` for every sphere it takes.
pub fn predict(law: Law, data: &DataSet) -> Vec<Prediction> {
    data.spheres
        .iter()
        .enumerate()
        .filter_map(|(i, s)| {
            let drag = law.drag(data, s)?;
            let w = net_weight(data, s);
            let sol = drag.balance_speed(w);
            let state = if sol.at_jump {
                State::Jump
            } else if sol.speed_m_s <= 0.0 {
                State::Static
            } else {
                State::Moving
            };
            Some(Prediction {
                sphere: i,
                v_predicted_m_s: sol.speed_m_s,
                state,
                rel_error: sol.speed_m_s / s.v_measured_m_s - 1.0,
                force_rel_error: drag.force_n(s.v_measured_m_s) / w - 1.0,
            })
        })
        .collect()
}

/// One law's figures over the data set.
#[derive(Clone, Debug)]
pub struct LawResult {
    /// The law.
    pub law: Law,
    /// Per-sphere predictions.
    pub predictions: Vec<Prediction>,
    /// Velocity error statistics.
    pub velocity: ErrorStats,
    /// Force error statistics at the measured speed.
    pub force: ErrorStats,
    /// Spheres predicted static.
    pub n_static: usize,
    /// Spheres predicted on a jump.
    pub n_jump: usize,
    /// Leave-one-suspension-out velocity error statistics (laws with fitted constants only).
    pub loso: Option<ErrorStats>,
}

impl LawResult {
    /// Evaluates `law` on `data` (without the leave-one-out figures).
    pub fn of(law: Law, data: &DataSet) -> Self {
        let predictions = predict(law, data);
        let errs: Vec<f64> = predictions.iter().map(|p| p.rel_error).collect();
        let ferrs: Vec<f64> = predictions.iter().map(|p| p.force_rel_error).collect();
        let count = |st| predictions.iter().filter(|p| p.state == st).count();
        Self {
            law,
            velocity: ErrorStats::of(law.key(), &errs),
            force: ErrorStats::of(law.key(), &ferrs),
            n_static: count(State::Static),
            n_jump: count(State::Jump),
            predictions,
            loso: None,
        }
    }

    /// True when the law meets issue 15's aim: mean |velocity error| ≤ 15 % and at least 85 %
    /// of the spheres within 25 %.
    pub fn meets_aim(&self) -> bool {
        self.velocity.n > 0 && self.velocity.mean_abs <= 0.15 && self.velocity.within_25pct >= 0.85
    }

    /// The prediction for the sphere with id `id`, if the law took it.
    pub fn for_sphere(&self, data: &DataSet, id: &str) -> Option<&Prediction> {
        self.predictions
            .iter()
            .find(|p| data.spheres[p.sphere].id == id)
    }
}
