//! The one place that names the SIMD type: every kernel is written over `Lane`.
//!
//! `f64x8`: eight landers per vector. f64 keeps the kernels within rounding of the f64
//! reference model (penetrations are micrometres on positions of metres, which f32 cannot
//! resolve); see the README's performance section for the measured choice.

/// Eight f64 lanes.
pub type Lane = wide::f64x8;

/// Number of landers advanced together by one kernel call.
pub const LANES: usize = 8;

/// Name of the lane type, as the binary reports it.
pub const LANE_NAME: &str = "f64x8";

/// A lane vector with every lane set to `x`.
#[inline(always)]
#[must_use]
pub fn splat(x: f64) -> Lane {
    Lane::splat(x)
}

/// All lanes true (all bits set), as masks from comparisons are.
#[inline(always)]
#[must_use]
pub fn all_true() -> Lane {
    splat(0.0).simd_eq(splat(0.0))
}

/// All lanes false.
#[inline(always)]
#[must_use]
pub fn all_false() -> Lane {
    splat(0.0)
}

/// A mask from booleans.
#[inline]
#[must_use]
pub fn mask_from(b: [bool; LANES]) -> Lane {
    let t = f64::from_bits(u64::MAX);
    Lane::from(b.map(|x| if x { t } else { 0.0 }))
}

/// The lanes of a mask as booleans.
#[inline]
#[must_use]
pub fn mask_to(m: Lane) -> [bool; LANES] {
    let bits = m.to_bitmask();
    std::array::from_fn(|i| bits & (1 << i) != 0)
}
