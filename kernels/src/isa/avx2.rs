//! Eight f64 landers in two AVX2 registers, multiply-adds fused (FMA3).

use super::Kernel;
use crate::block::Block;
use crate::lane::{LANES, Lane};
use crate::params::Params;
use std::arch::x86_64::*;
use std::ops::{
    Add, AddAssign, BitAnd, BitAndAssign, BitOr, BitOrAssign, Div, Mul, MulAssign, Neg, Not, Sub,
    SubAssign,
};

/// Eight f64 lanes in two `__m256d`. Only made on a CPU with the features of `FEATURES`.
#[derive(Clone, Copy)]
#[repr(C, align(64))]
pub struct F64x8Avx2([__m256d; 2]);

// What the kernel is compiled for: x86-64-v3 (the same list as `compiled_kernel!` below).
x86_features!(
    "avx2", "avx", "fma", "bmi1", "bmi2", "lzcnt", "movbe", "popcnt", "f16c"
);

compiled_kernel!(
    F64x8Avx2,
    "f64x8 AVX2",
    "avx2,avx,fma,bmi1,bmi2,lzcnt,movbe,popcnt,f16c"
);

/// Applies a two-operand intrinsic to both halves.
macro_rules! halves {
    ($f:path, $a:expr, $b:expr) => {
        F64x8Avx2(unsafe { [$f($a.0[0], $b.0[0]), $f($a.0[1], $b.0[1])] })
    };
    ($f:path, $a:expr, $b:expr, $c:expr) => {
        F64x8Avx2(unsafe { [$f($a.0[0], $b.0[0], $c.0[0]), $f($a.0[1], $b.0[1], $c.0[1])] })
    };
}

macro_rules! binary {
    ($trait:ident, $f:ident, $assign:ident, $fa:ident, $intrinsic:ident) => {
        impl $trait for F64x8Avx2 {
            type Output = Self;
            #[inline(always)]
            fn $f(self, o: Self) -> Self {
                halves!($intrinsic, self, o)
            }
        }
        impl $assign for F64x8Avx2 {
            #[inline(always)]
            fn $fa(&mut self, o: Self) {
                *self = $trait::$f(*self, o);
            }
        }
    };
}
binary!(Add, add, AddAssign, add_assign, _mm256_add_pd);
binary!(Sub, sub, SubAssign, sub_assign, _mm256_sub_pd);
binary!(Mul, mul, MulAssign, mul_assign, _mm256_mul_pd);
binary!(BitAnd, bitand, BitAndAssign, bitand_assign, _mm256_and_pd);
binary!(BitOr, bitor, BitOrAssign, bitor_assign, _mm256_or_pd);

impl Div for F64x8Avx2 {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        halves!(_mm256_div_pd, self, o)
    }
}

impl Neg for F64x8Avx2 {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        halves!(_mm256_xor_pd, self, Self::splat(-0.0))
    }
}

impl Not for F64x8Avx2 {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        halves!(_mm256_xor_pd, self, Self::splat(f64::from_bits(u64::MAX)))
    }
}

macro_rules! compare {
    ($f:ident, $op:ident) => {
        #[inline(always)]
        fn $f(self, o: Self) -> Self {
            halves!(_mm256_cmp_pd::<$op>, self, o)
        }
    };
}

impl Lane for F64x8Avx2 {
    const ZERO: Self =
        Self(unsafe { std::mem::transmute::<[f64; LANES], [__m256d; 2]>([0.0; LANES]) });

    #[inline(always)]
    fn splat(x: f64) -> Self {
        Self::from_array([x; LANES])
    }
    #[inline(always)]
    fn from_array(a: [f64; LANES]) -> Self {
        // The same 64 bytes: no instruction needed (this runs outside the kernels too).
        Self(unsafe { std::mem::transmute::<[f64; LANES], [__m256d; 2]>(a) })
    }
    #[inline(always)]
    fn to_array(self) -> [f64; LANES] {
        unsafe { std::mem::transmute::<[__m256d; 2], [f64; LANES]>(self.0) }
    }
    #[inline(always)]
    fn as_array(&self) -> &[f64; LANES] {
        unsafe { &*std::ptr::from_ref(self).cast::<[f64; LANES]>() }
    }
    #[inline(always)]
    fn as_mut_array(&mut self) -> &mut [f64; LANES] {
        unsafe { &mut *std::ptr::from_mut(self).cast::<[f64; LANES]>() }
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        halves!(_mm256_fmadd_pd, self, a, b)
    }
    #[inline(always)]
    fn mul_sub(self, a: Self, b: Self) -> Self {
        halves!(_mm256_fmsub_pd, self, a, b)
    }
    #[inline(always)]
    fn mul_neg_add(self, a: Self, b: Self) -> Self {
        halves!(_mm256_fnmadd_pd, self, a, b)
    }
    #[inline(always)]
    fn mul_neg_sub(self, a: Self, b: Self) -> Self {
        halves!(_mm256_fnmsub_pd, self, a, b)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Self(unsafe { [_mm256_sqrt_pd(self.0[0]), _mm256_sqrt_pd(self.0[1])] })
    }
    #[inline(always)]
    fn abs(self) -> Self {
        self & Self::splat(f64::from_bits(i64::MAX as u64))
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        o.is_nan().select(self, self.fast_min(o))
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        o.is_nan().select(self, self.fast_max(o))
    }
    #[inline(always)]
    fn fast_min(self, o: Self) -> Self {
        halves!(_mm256_min_pd, self, o)
    }
    #[inline(always)]
    fn fast_max(self, o: Self) -> Self {
        halves!(_mm256_max_pd, self, o)
    }
    compare!(simd_eq, _CMP_EQ_OQ);
    compare!(simd_lt, _CMP_LT_OQ);
    compare!(simd_le, _CMP_LE_OQ);
    compare!(simd_gt, _CMP_GT_OQ);
    compare!(simd_ge, _CMP_GE_OQ);
    #[inline(always)]
    fn is_nan(self) -> Self {
        halves!(_mm256_cmp_pd::<_CMP_UNORD_Q>, self, self)
    }
    #[inline(always)]
    fn select(self, a: Self, b: Self) -> Self {
        halves!(_mm256_blendv_pd, b, a, self)
    }
    #[inline(always)]
    fn to_bitmask(self) -> u32 {
        let [lo, hi] = self.0;
        unsafe { (_mm256_movemask_pd(lo) | (_mm256_movemask_pd(hi) << 4)) as u32 }
    }
}
