//! What a lane type must do: `LANES` landers side by side (eight in f64, sixteen in f32),
//! with the arithmetic, masks and comparisons the kernels use. Every kernel is written once
//! over `L: Lane`; `isa` has the lane types (AVX-512, AVX2 with FMA, and a portable one, in
//! f64 and f32) and picks one at run time.
//!
//! A mask (`Lane::Mask`) holds a truth value per lane, as comparisons return it; `&`, `|`
//! and `!` combine masks and `select` picks by one. Each lane type has the masks its
//! instruction set has: AVX-512's mask registers (a bit a lane), or, for AVX2 and the
//! portable types, lane values with every bit of a lane set (true) or clear (false).
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

/// A truth value per lane of a lane type (`Lane::Mask`).
pub trait Mask:
    Copy
    + Debug
    + BitAnd<Output = Self>
    + BitOr<Output = Self>
    + Not<Output = Self>
    + BitAndAssign
    + BitOrAssign
    + Send
    + Sync
    + 'static
{
    /// Every lane false.
    const NONE: Self;
    /// The mask as bits, lane `i` in bit `i`.
    fn to_bitmask(self) -> u32;
    /// Lane `i`, outside the kernels.
    fn lane(&self, i: usize) -> bool;
    /// Sets lane `i`, outside the kernels.
    fn set_lane(&mut self, i: usize, on: bool);
    /// Per lane: `a` where true, `b` where false.
    #[inline(always)]
    #[must_use]
    fn select<L: Lane<Mask = Self>>(self, a: L, b: L) -> L {
        L::blend(self, a, b)
    }
}

/// `LANES` landers side by side. Implementations are `#[inline(always)]` throughout: the
/// kernels are compiled inside functions per instruction set (see `isa`), and anything not
/// inlined there would lose that instruction set.
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
    + Send
    + Sync
    + 'static
{
    /// Number of landers a value holds (at most `MAX_LANES`).
    const LANES: usize;
    /// A truth value per lane.
    type Mask: Mask;
    /// Every lane 0.
    const ZERO: Self;
    /// The least positive normal number of the lanes' precision.
    const MIN_POSITIVE: f64;
    /// Distance from the origin beyond which a lane's state is moved back near it
    /// along the surface (`Block::recentre`): 2 m in f32, whose positions of tens of metres
    /// could not resolve a footpad's contact deflection of micrometres; never in f64.
    const RECENTRE_M: f64;
    /// Every lane `x` (rounded to the lanes' precision).
    fn splat(x: f64) -> Self;
    /// Lane `i`, outside the kernels (through memory).
    fn lane(&self, i: usize) -> f64;
    /// Sets lane `i` to `x` (rounded to the lanes' precision), outside the kernels.
    fn set_lane(&mut self, i: usize, x: f64);

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
    fn simd_eq(self, o: Self) -> Self::Mask;
    /// Mask: `self < o`.
    fn simd_lt(self, o: Self) -> Self::Mask;
    /// Mask: `self <= o`.
    fn simd_le(self, o: Self) -> Self::Mask;
    /// Mask: `self > o`.
    fn simd_gt(self, o: Self) -> Self::Mask;
    /// Mask: `self >= o`.
    fn simd_ge(self, o: Self) -> Self::Mask;
    /// Mask: NaN lanes.
    fn is_nan(self) -> Self::Mask;
    /// Per lane of `mask`: `a` where true, `b` where false (`Mask::select`).
    #[must_use]
    fn blend(mask: Self::Mask, a: Self, b: Self) -> Self;
}

/// All lanes true.
#[inline(always)]
#[must_use]
pub fn all_true<L: Lane>() -> L::Mask {
    !L::Mask::NONE
}

/// All lanes false.
#[inline(always)]
#[must_use]
pub fn all_false<L: Lane>() -> L::Mask {
    L::Mask::NONE
}

/// `*to = mask.select(x, *to)`, written as one plain store of the whole lane value.
///
/// Written as it reads, LLVM turns that load-select-store of one place into a masked store
/// (`vmaskmovpd`/`vmaskmovps` under AVX2), which the 2-core AMD EPYC machine runs slowly (a
/// tenth of the kernel's profile fell on the strut peaks' eight): with those written so,
/// the default sweep there ran at 0.93x (f64) and 0.79x (f32) of this (alternated, 2e5
/// samples, 1 thread). A volatile store is kept as written: the blend in registers, then a
/// store.
#[inline(always)]
pub fn select_into<L: Lane>(to: &mut L, mask: L::Mask, x: L) {
    let value = mask.select(x, *to);
    // SAFETY: `to` is a live, aligned, exclusive reference to an initialised `L` (a
    // `Copy` type with no drop), so writing a whole `L` through it is sound.
    unsafe { std::ptr::write_volatile(to, value) }
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

/// Broadcasts a scalar, outside the kernels: through memory, with no SIMD instruction
/// (code outside the kernels is compiled for the baseline CPU, and an instruction of the
/// kernel's set there would be an out-of-line call that leaves the vector unit dirty).
#[inline]
#[must_use]
pub fn lane<L: Lane>(x: f64) -> L {
    let mut l = L::ZERO;
    for i in 0..L::LANES {
        l.set_lane(i, x);
    }
    l
}
