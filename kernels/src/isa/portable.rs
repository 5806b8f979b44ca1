//! Landers in `wide`'s types for the target the binary was compiled for: eight in
//! `wide::f64x8`, sixteen in `wide::f32x16`. SSE2 on a plain x86-64 build (multiply and add
//! rounded apart: x86-64 without AVX2 has no FMA), NEON on aarch64 (fused). The kernels of
//! machines that have neither AVX-512 nor AVX2.

use super::Kernel;
use crate::block::Block;
use crate::lane::Lane;
use crate::params::Params;
use wide::{f32x16, f64x8};

/// `Kernel` and `Lane` for the `wide` type `$t` of `$n` lanes of `$e`, named `$name`.
macro_rules! portable_lane {
    ($t:ident, $e:ty, $n:literal, $name:literal) => {
        impl Kernel for $t {
            const NAME: &'static str = if cfg!(target_arch = "x86_64") {
                if cfg!(target_feature = "fma") {
                    concat!($name, " portable (FMA)")
                } else {
                    concat!($name, " SSE2")
                }
            } else {
                concat!($name, " portable")
            };
            const FUSED: bool = !cfg!(target_arch = "x86_64") || cfg!(target_feature = "fma");
            #[inline(never)]
            fn advance(
                p: &Params<Self>,
                block: &mut Block<Self>,
                steps: u32,
            ) -> crate::step::Advanced {
                crate::step::advance::<Self, crate::step::PlainLoop>(p, block, steps)
            }
        }

        vector_mask!($t, $e, |m| $t::to_bitmask(m));

        impl Lane for $t {
            const LANES: usize = $n;
            type Mask = Self;
            const ZERO: Self = $t::ZERO;
            const MIN_POSITIVE: f64 = <$e>::MIN_POSITIVE as f64;

            #[inline(always)]
            fn splat(x: f64) -> Self {
                #[allow(clippy::cast_possible_truncation)]
                $t::splat(x as $e)
            }
            lane_access!($e);
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                $t::mul_add(self, a, b)
            }
            #[inline(always)]
            fn mul_sub(self, a: Self, b: Self) -> Self {
                $t::mul_sub(self, a, b)
            }
            #[inline(always)]
            fn mul_neg_add(self, a: Self, b: Self) -> Self {
                $t::mul_neg_add(self, a, b)
            }
            #[inline(always)]
            fn mul_neg_sub(self, a: Self, b: Self) -> Self {
                $t::mul_neg_sub(self, a, b)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                $t::sqrt(self)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                $t::abs(self)
            }
            #[inline(always)]
            fn min(self, o: Self) -> Self {
                $t::min(self, o)
            }
            #[inline(always)]
            fn max(self, o: Self) -> Self {
                $t::max(self, o)
            }
            #[inline(always)]
            fn fast_min(self, o: Self) -> Self {
                $t::fast_min(self, o)
            }
            #[inline(always)]
            fn fast_max(self, o: Self) -> Self {
                $t::fast_max(self, o)
            }
            #[inline(always)]
            fn simd_eq(self, o: Self) -> Self {
                $t::simd_eq(self, o)
            }
            #[inline(always)]
            fn simd_lt(self, o: Self) -> Self {
                $t::simd_lt(self, o)
            }
            #[inline(always)]
            fn simd_le(self, o: Self) -> Self {
                $t::simd_le(self, o)
            }
            #[inline(always)]
            fn simd_gt(self, o: Self) -> Self {
                $t::simd_gt(self, o)
            }
            #[inline(always)]
            fn simd_ge(self, o: Self) -> Self {
                $t::simd_ge(self, o)
            }
            #[inline(always)]
            fn is_nan(self) -> Self {
                $t::is_nan(self)
            }
            #[inline(always)]
            fn blend(mask: Self, a: Self, b: Self) -> Self {
                $t::select(mask, a, b)
            }
        }
    };
}

portable_lane!(f64x8, f64, 8, "f64x8");
portable_lane!(f32x16, f32, 16, "f32x16");
