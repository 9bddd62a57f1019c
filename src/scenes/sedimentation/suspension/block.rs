//! What the two builds of a full block's end share ([`super::update`], [`super::wide`]): the
//! number of lanes, the block's constants and what its end finds.

/// Grains of one kind whose terminal-state table the free update evaluates together
/// ([`exponential_near_terminal_kind_saturated`]): a multiple of 16, at most 32. 32 rather than
/// 16: twice the independent Horner chains in flight (measured 1.13–1.32× the free update).
///
/// [`exponential_near_terminal_kind_saturated`]:
///     crate::dynamics::terminal::exponential_near_terminal_kind_saturated
pub(super) const LANES: usize = 32;

/// What `Block::end` (or `wide::finish`) found of a block: bit `l` of `left` set if lane `l`
/// left its cell (or its height is not a number), of `near` if it is within reach of the bed;
/// whether any lane fails
/// the fault test; the largest speed of the lanes not near the bed (each the larger of its
/// speed and the Stokes terminal speed), m/s, 0 if none.
#[derive(Debug, PartialEq)]
pub(super) struct BlockEnd {
    pub(super) left: u32,
    pub(super) near: u32,
    pub(super) bad: bool,
    pub(super) vmax: f64,
}

/// The constants of a block's end, SI units: half the grains' diameter, the height above which
/// a centre is a fault, the bed surface, the speed bound, the height below which a bottom is
/// within reach of the bed, the grains' Stokes terminal speed.
#[derive(Clone, Copy, Debug)]
pub(super) struct EndConstants {
    pub(super) half_d_m: f64,
    pub(super) top_m: f64,
    pub(super) floor_m: f64,
    pub(super) speed_bound_m_s: f64,
    pub(super) reach_m: f64,
    pub(super) stokes_m_s: f64,
}
