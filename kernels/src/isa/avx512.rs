//! Eight f64 landers in one AVX-512 register, multiply-adds fused.

use super::Kernel;
use crate::block::Block;
use crate::lane::{LANES, Lane};
use crate::params::Params;
use std::arch::x86_64::*;
use std::ops::{
    Add, AddAssign, BitAnd, BitAndAssign, BitOr, BitOrAssign, Div, Mul, MulAssign, Neg, Not, Sub,
    SubAssign,
};

/// Eight f64 lanes in a `__m512d`. Only made on a CPU with the features of `FEATURES`.
#[derive(Clone, Copy)]
#[repr(transparent)]
pub struct F64x8Avx512(__m512d);

// What the kernel is compiled for: x86-64-v4 (the same list as `compiled_kernel!` below).
x86_features!(
    "avx512f", "avx512dq", "avx512bw", "avx512vl", "avx512cd", "avx2", "avx", "fma", "bmi1",
    "bmi2", "lzcnt", "movbe", "popcnt", "f16c"
);

compiled_kernel!(
    F64x8Avx512,
    "f64x8 AVX-512",
    "avx512f,avx512dq,avx512bw,avx512vl,avx512cd,avx2,avx,fma,bmi1,bmi2,lzcnt,movbe,popcnt,f16c"
);

/// A mask vector (all bits of a lane set) from a compare mask.
#[inline(always)]
fn widen(k: __mmask8) -> __m512d {
    unsafe { _mm512_maskz_mov_pd(k, _mm512_castsi512_pd(_mm512_set1_epi64(-1))) }
}

/// The compare mask of a mask vector (its sign bits).
#[inline(always)]
fn narrow(m: __m512d) -> __mmask8 {
    unsafe { _mm512_movepi64_mask(_mm512_castpd_si512(m)) }
}

macro_rules! binary {
    ($trait:ident, $f:ident, $assign:ident, $fa:ident, $intrinsic:ident) => {
        impl $trait for F64x8Avx512 {
            type Output = Self;
            #[inline(always)]
            fn $f(self, o: Self) -> Self {
                Self(unsafe { $intrinsic(self.0, o.0) })
            }
        }
        impl $assign for F64x8Avx512 {
            #[inline(always)]
            fn $fa(&mut self, o: Self) {
                *self = $trait::$f(*self, o);
            }
        }
    };
}
binary!(Add, add, AddAssign, add_assign, _mm512_add_pd);
binary!(Sub, sub, SubAssign, sub_assign, _mm512_sub_pd);
binary!(Mul, mul, MulAssign, mul_assign, _mm512_mul_pd);
binary!(BitAnd, bitand, BitAndAssign, bitand_assign, _mm512_and_pd);
binary!(BitOr, bitor, BitOrAssign, bitor_assign, _mm512_or_pd);

impl Div for F64x8Avx512 {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        Self(unsafe { _mm512_div_pd(self.0, o.0) })
    }
}

impl Neg for F64x8Avx512 {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self(unsafe { _mm512_xor_pd(self.0, _mm512_set1_pd(-0.0)) })
    }
}

impl Not for F64x8Avx512 {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        Self(unsafe { _mm512_xor_pd(self.0, _mm512_castsi512_pd(_mm512_set1_epi64(-1))) })
    }
}

macro_rules! compare {
    ($f:ident, $op:ident) => {
        #[inline(always)]
        fn $f(self, o: Self) -> Self {
            Self(widen(unsafe { _mm512_cmp_pd_mask::<$op>(self.0, o.0) }))
        }
    };
}

impl Lane for F64x8Avx512 {
    const ZERO: Self = Self(unsafe { std::mem::transmute::<[f64; LANES], __m512d>([0.0; LANES]) });

    #[inline(always)]
    fn splat(x: f64) -> Self {
        Self(unsafe { _mm512_set1_pd(x) })
    }
    #[inline(always)]
    fn from_array(a: [f64; LANES]) -> Self {
        // The same 64 bytes: no instruction needed (this runs outside the kernels too).
        Self(unsafe { std::mem::transmute::<[f64; LANES], __m512d>(a) })
    }
    #[inline(always)]
    fn to_array(self) -> [f64; LANES] {
        unsafe { std::mem::transmute::<__m512d, [f64; LANES]>(self.0) }
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
        Self(unsafe { _mm512_fmadd_pd(self.0, a.0, b.0) })
    }
    #[inline(always)]
    fn mul_sub(self, a: Self, b: Self) -> Self {
        Self(unsafe { _mm512_fmsub_pd(self.0, a.0, b.0) })
    }
    #[inline(always)]
    fn mul_neg_add(self, a: Self, b: Self) -> Self {
        Self(unsafe { _mm512_fnmadd_pd(self.0, a.0, b.0) })
    }
    #[inline(always)]
    fn mul_neg_sub(self, a: Self, b: Self) -> Self {
        Self(unsafe { _mm512_fnmsub_pd(self.0, a.0, b.0) })
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Self(unsafe { _mm512_sqrt_pd(self.0) })
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
        Self(unsafe { _mm512_min_pd(self.0, o.0) })
    }
    #[inline(always)]
    fn fast_max(self, o: Self) -> Self {
        Self(unsafe { _mm512_max_pd(self.0, o.0) })
    }
    compare!(simd_eq, _CMP_EQ_OQ);
    compare!(simd_lt, _CMP_LT_OQ);
    compare!(simd_le, _CMP_LE_OQ);
    compare!(simd_gt, _CMP_GT_OQ);
    compare!(simd_ge, _CMP_GE_OQ);
    #[inline(always)]
    fn is_nan(self) -> Self {
        Self(widen(unsafe {
            _mm512_cmp_pd_mask::<_CMP_UNORD_Q>(self.0, self.0)
        }))
    }
    #[inline(always)]
    fn select(self, a: Self, b: Self) -> Self {
        Self(unsafe { _mm512_mask_blend_pd(narrow(self.0), b.0, a.0) })
    }
    #[inline(always)]
    fn to_bitmask(self) -> u32 {
        u32::from(narrow(self.0))
    }
}
