//! The one place that names the SIMD type: every kernel is written over `Lane`.
//!
//! `f64x8`: eight landers per vector (one AVX-512 register, two AVX2 ones). f64 keeps the
//! kernels within rounding of the f64 reference model (penetrations are micrometres on
//! positions of metres, which f32 cannot resolve); see the README's performance section for
//! the measured choice.

/// Eight f64 lanes.
pub type Lane = wide::f64x8;

/// Number of landers advanced together by one kernel call.
pub const LANES: usize = 8;

/// Name of the lane type, as the binary reports it.
pub const LANE_NAME: &str = "f64x8";

/// The instruction set `Lane` was compiled for, as the binary reports it.
pub const INSTRUCTION_SET: &str = if cfg!(target_feature = "avx512f") {
    "AVX-512"
} else if cfg!(target_feature = "avx2") {
    "AVX2"
} else {
    "baseline"
};

/// The CPU features this build was compiled to use that the running CPU lacks (empty when
/// it has them all). Code compiled for a feature the CPU lacks dies of an illegal
/// instruction; the binary checks this first and explains instead.
#[must_use]
pub fn missing_cpu_features() -> Vec<&'static str> {
    #[allow(unused_mut)]
    let mut missing = Vec::new();
    #[cfg(target_arch = "x86_64")]
    {
        macro_rules! check {
            ($($feature:tt),*) => {$(
                if cfg!(target_feature = $feature) && !std::arch::is_x86_feature_detected!($feature) {
                    missing.push($feature);
                }
            )*};
        }
        check!(
            "avx", "avx2", "fma", "bmi1", "bmi2", "lzcnt", "movbe", "avx512f", "avx512bw",
            "avx512cd", "avx512dq", "avx512vl"
        );
    }
    missing
}

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

/// `acc.max(x)` for an accumulator `acc` that is never NaN: lanes where `x` is NaN keep
/// `acc`, as with `max`, but in one instruction (`max` also guards against a NaN `acc`).
#[inline(always)]
#[must_use]
pub fn max_into(acc: Lane, x: Lane) -> Lane {
    x.fast_max(acc)
}

/// `acc.min(x)` for an accumulator `acc` that is never NaN (see `max_into`).
#[inline(always)]
#[must_use]
pub fn min_into(acc: Lane, x: Lane) -> Lane {
    x.fast_min(acc)
}
