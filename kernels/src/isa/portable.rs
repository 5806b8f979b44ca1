//! Eight f64 landers in `wide::f64x8` for the target the binary was compiled for: SSE2 on
//! a plain x86-64 build (multiply and add rounded apart: x86-64 without AVX2 has no FMA),
//! NEON on aarch64 (fused). The kernel of machines that have neither AVX-512 nor AVX2.

use super::Kernel;
use crate::block::Block;
use crate::lane::{LANES, Lane};
use crate::params::Params;
use wide::f64x8;

impl Kernel for f64x8 {
    const NAME: &'static str = if cfg!(target_arch = "x86_64") {
        if cfg!(target_feature = "fma") {
            "f64x8 portable (FMA)"
        } else {
            "f64x8 SSE2"
        }
    } else {
        "f64x8 portable"
    };
    const FUSED: bool = !cfg!(target_arch = "x86_64") || cfg!(target_feature = "fma");
    #[inline(never)]
    fn advance(p: &Params<Self>, block: &mut Block<Self>) -> u32 {
        crate::step::advance(p, block)
    }
}

impl Lane for f64x8 {
    const ZERO: Self = f64x8::ZERO;

    #[inline(always)]
    fn splat(x: f64) -> Self {
        f64x8::splat(x)
    }
    #[inline(always)]
    fn from_array(a: [f64; LANES]) -> Self {
        f64x8::new(a)
    }
    #[inline(always)]
    fn to_array(self) -> [f64; LANES] {
        f64x8::to_array(self)
    }
    #[inline(always)]
    fn as_array(&self) -> &[f64; LANES] {
        f64x8::as_array(self)
    }
    #[inline(always)]
    fn as_mut_array(&mut self) -> &mut [f64; LANES] {
        f64x8::as_mut_array(self)
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        f64x8::mul_add(self, a, b)
    }
    #[inline(always)]
    fn mul_sub(self, a: Self, b: Self) -> Self {
        f64x8::mul_sub(self, a, b)
    }
    #[inline(always)]
    fn mul_neg_add(self, a: Self, b: Self) -> Self {
        f64x8::mul_neg_add(self, a, b)
    }
    #[inline(always)]
    fn mul_neg_sub(self, a: Self, b: Self) -> Self {
        f64x8::mul_neg_sub(self, a, b)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64x8::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64x8::abs(self)
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        f64x8::min(self, o)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        f64x8::max(self, o)
    }
    #[inline(always)]
    fn fast_min(self, o: Self) -> Self {
        f64x8::fast_min(self, o)
    }
    #[inline(always)]
    fn fast_max(self, o: Self) -> Self {
        f64x8::fast_max(self, o)
    }
    #[inline(always)]
    fn simd_eq(self, o: Self) -> Self {
        f64x8::simd_eq(self, o)
    }
    #[inline(always)]
    fn simd_lt(self, o: Self) -> Self {
        f64x8::simd_lt(self, o)
    }
    #[inline(always)]
    fn simd_le(self, o: Self) -> Self {
        f64x8::simd_le(self, o)
    }
    #[inline(always)]
    fn simd_gt(self, o: Self) -> Self {
        f64x8::simd_gt(self, o)
    }
    #[inline(always)]
    fn simd_ge(self, o: Self) -> Self {
        f64x8::simd_ge(self, o)
    }
    #[inline(always)]
    fn is_nan(self) -> Self {
        f64x8::is_nan(self)
    }
    #[inline(always)]
    fn select(self, a: Self, b: Self) -> Self {
        f64x8::select(self, a, b)
    }
    #[inline(always)]
    fn to_bitmask(self) -> u32 {
        f64x8::to_bitmask(self)
    }
}
