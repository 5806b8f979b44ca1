//! What a lane type must do: `LANES` landers side by side (eight in f64, sixteen in f32),
//! with the arithmetic, masks and comparisons the kernels use. Every kernel is written once
//! over `L: Lane`; `isa` has the lane types (AVX-512, AVX2 with FMA, and a portable one, in
//! f64 and f32) and picks one at run time.
//!
//! A mask is a lane value with every bit of a lane set (true) or clear (false), as
//! comparisons return it; `select`, `&`, `|` and `!` work on masks.
//!
//! Every lane type computes each lane as IEEE 754 arithmetic of its precision does: `+ - * /`
//! and `sqrt` correctly rounded, the multiply-adds fused (rounded once) where the CPU has
//! FMA. So the AVX-512 and AVX2 lane types of one precision give the same bits, and a sweep
//! the same file. Values cross the lane type's boundary as f64 (`splat`, `lane`,
//! `set_lane`), rounded to nearest on the way in for f32.

use std::fmt::Debug;
use std::ops::{
    Add, AddAssign, BitAnd, BitAndAssign, BitOr, BitOrAssign, Div, Mul, MulAssign, Neg, Not, Sub,
    SubAssign,
};

/// The most landers a lane value holds (of any lane type): the size of the per-lane arrays
/// kept beside a block.
pub const MAX_LANES: usize = 16;

/// `LANES` landers side by side. Implementations are `#[inline(always)]` throughout: the
/// kernels are compiled inside one function per instruction set (see `isa`), and anything
/// not inlined there would lose that instruction set.
pub trait Lane:
    Copy
    + Debug
    + PartialEq
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + BitAnd<Output = Self>
    + BitOr<Output = Self>
    + Not<Output = Self>
    + BitAndAssign
    + BitOrAssign
    + Send
    + Sync
    + 'static
{
    /// Number of landers a value holds (at most `MAX_LANES`).
    const LANES: usize;
    /// Every lane 0.
    const ZERO: Self;
    /// The least positive normal number of the lanes' precision.
    const MIN_POSITIVE: f64;
    /// Distance from the origin beyond which a lane's state is moved back near it
    /// (`Block::recentre`): 2 m in f32, whose positions of tens of metres could not resolve
    /// a footpad's contact deflection of micrometres; never in f64.
    const RECENTRE_M: f64;
    /// Every lane `x` (rounded to the lanes' precision).
    fn splat(x: f64) -> Self;
    /// Lane `i`, outside the kernels (through memory).
    fn lane(&self, i: usize) -> f64;
    /// Sets lane `i` to `x` (rounded to the lanes' precision), outside the kernels.
    fn set_lane(&mut self, i: usize, x: f64);
    /// Sets lane `i` of the mask `self` to `on`, outside the kernels.
    fn set_mask_lane(&mut self, i: usize, on: bool);

    /// `self * a + b`, fused where the CPU has FMA.
    #[must_use]
    fn mul_add(self, a: Self, b: Self) -> Self;
    /// `self * a - b`.
    #[must_use]
    fn mul_sub(self, a: Self, b: Self) -> Self;
    /// `b - self * a`.
    #[must_use]
    fn mul_neg_add(self, a: Self, b: Self) -> Self;
    /// `-(self * a) - b`.
    #[must_use]
    fn mul_neg_sub(self, a: Self, b: Self) -> Self;
    /// Square root.
    #[must_use]
    fn sqrt(self) -> Self;
    /// Absolute value.
    #[must_use]
    fn abs(self) -> Self;
    /// The smaller of the two; `self` where `o` is NaN.
    #[must_use]
    fn min(self, o: Self) -> Self;
    /// The larger of the two; `self` where `o` is NaN.
    #[must_use]
    fn max(self, o: Self) -> Self;
    /// The smaller of the two; `o` where either is NaN (one instruction).
    #[must_use]
    fn fast_min(self, o: Self) -> Self;
    /// The larger of the two; `o` where either is NaN (one instruction).
    #[must_use]
    fn fast_max(self, o: Self) -> Self;

    /// Mask: `self == o` (false where either is NaN).
    fn simd_eq(self, o: Self) -> Self;
    /// Mask: `self < o`.
    fn simd_lt(self, o: Self) -> Self;
    /// Mask: `self <= o`.
    fn simd_le(self, o: Self) -> Self;
    /// Mask: `self > o`.
    fn simd_gt(self, o: Self) -> Self;
    /// Mask: `self >= o`.
    fn simd_ge(self, o: Self) -> Self;
    /// Mask: NaN lanes.
    fn is_nan(self) -> Self;
    /// Per lane of the mask `self`: `a` where true, `b` where false.
    #[must_use]
    fn select(self, a: Self, b: Self) -> Self;
    /// The mask `self` as bits, lane `i` in bit `i`.
    fn to_bitmask(self) -> u32;
}

/// All lanes true (all bits set), as masks from comparisons are.
#[inline(always)]
#[must_use]
pub fn all_true<L: Lane>() -> L {
    L::ZERO.simd_eq(L::ZERO)
}

/// All lanes false.
#[inline(always)]
#[must_use]
pub fn all_false<L: Lane>() -> L {
    L::ZERO
}

/// `acc.max(x)` for an accumulator `acc` that is never NaN: lanes where `x` is NaN keep
/// `acc`, as with `max`, but in one instruction (`max` also guards against a NaN `acc`).
#[inline(always)]
#[must_use]
pub fn max_into<L: Lane>(acc: L, x: L) -> L {
    x.fast_max(acc)
}

/// `acc.min(x)` for an accumulator `acc` that is never NaN (see `max_into`).
#[inline(always)]
#[must_use]
pub fn min_into<L: Lane>(acc: L, x: L) -> L {
    x.fast_min(acc)
}
