//! One AVX-512 register of landers, multiply-adds fused: eight in f64 (`F64x8Avx512`),
//! sixteen in f32 (`F32x16Avx512`). Both lane types come from one macro, so they are the
//! same code over the two precisions.

// What the kernels are compiled for: x86-64-v4 (the same list as `compiled_kernel!` below).
x86_features!(
    "avx512f", "avx512dq", "avx512bw", "avx512vl", "avx512cd", "avx2", "avx", "fma", "bmi1",
    "bmi2", "lzcnt", "movbe", "popcnt", "f16c"
);

/// The lane type `$lane` of `$n` lanes of `$e` in one register `$v`, its masks `$mask` in
/// a mask register `$k` (a bit a lane), with the intrinsics of its precision.
macro_rules! avx512_lane {
    (
        $(#[$doc:meta])* $lane:ident, $name:literal, $v:ty, $e:ty, $n:literal, $mask:ident, $k:ty,
        set1 $set1:ident,
        add $add:ident, sub $sub:ident, mul $mul:ident, div $div:ident,
        xor $xor:ident, andnot $andnot:ident, fmadd $fmadd:ident, fmsub $fmsub:ident,
        fnmadd $fnmadd:ident, fnmsub $fnmsub:ident, sqrt $sqrt:ident, min $min:ident,
        max $max:ident, cmp $cmp:ident, blend $blend:ident
    ) => {
        use crate::isa::Kernel;
        use crate::block::Block;
        use crate::lane::{Lane, Mask};
        use crate::params::Params;
        use std::arch::x86_64::*;
        use std::ops::{
            Add, AddAssign, BitAnd, BitAndAssign, BitOr, BitOrAssign, Div, Mul, MulAssign, Neg,
            Not, Sub, SubAssign,
        };

        $(#[$doc])*
        #[derive(Clone, Copy)]
        #[repr(transparent)]
        pub struct $lane($v);

        compiled_kernel!(
            $lane,
            $name,
            "avx512f,avx512dq,avx512bw,avx512vl,avx512cd,avx2,avx,fma,bmi1,bmi2,lzcnt,movbe,popcnt,f16c"
        );

        /// A truth value per lane of `$lane`: a bit a lane, as compares leave them in a
        /// mask register and masked instructions take them.
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        #[repr(transparent)]
        pub struct $mask($k);

        macro_rules! mask_binary {
            ($trait:ident, $f:ident, $assign:ident, $fa:ident, $op:tt) => {
                impl $trait for $mask {
                    type Output = Self;
                    #[inline(always)]
                    fn $f(self, o: Self) -> Self {
                        Self(self.0 $op o.0)
                    }
                }
                impl $assign for $mask {
                    #[inline(always)]
                    fn $fa(&mut self, o: Self) {
                        *self = $trait::$f(*self, o);
                    }
                }
            };
        }
        mask_binary!(BitAnd, bitand, BitAndAssign, bitand_assign, &);
        mask_binary!(BitOr, bitor, BitOrAssign, bitor_assign, |);

        impl Not for $mask {
            type Output = Self;
            #[inline(always)]
            fn not(self) -> Self {
                Self(!self.0)
            }
        }

        impl Mask for $mask {
            const NONE: Self = Self(0);
            #[inline(always)]
            fn to_bitmask(self) -> u32 {
                u32::from(self.0)
            }
            #[inline(always)]
            fn lane(&self, i: usize) -> bool {
                self.0 >> i & 1 != 0
            }
            #[inline(always)]
            fn set_lane(&mut self, i: usize, on: bool) {
                if on {
                    self.0 |= 1 << i;
                } else {
                    self.0 &= !(1 << i);
                }
            }
        }

        macro_rules! binary {
            ($trait:ident, $f:ident, $assign:ident, $fa:ident, $intrinsic:ident) => {
                impl $trait for $lane {
                    type Output = Self;
                    #[inline(always)]
                    fn $f(self, o: Self) -> Self {
                        Self(unsafe { $intrinsic(self.0, o.0) })
                    }
                }
                impl $assign for $lane {
                    #[inline(always)]
                    fn $fa(&mut self, o: Self) {
                        *self = $trait::$f(*self, o);
                    }
                }
            };
        }
        binary!(Add, add, AddAssign, add_assign, $add);
        binary!(Sub, sub, SubAssign, sub_assign, $sub);
        binary!(Mul, mul, MulAssign, mul_assign, $mul);

        impl Div for $lane {
            type Output = Self;
            #[inline(always)]
            fn div(self, o: Self) -> Self {
                Self(unsafe { $div(self.0, o.0) })
            }
        }

        impl Neg for $lane {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                Self(unsafe { $xor(self.0, $set1(-0.0)) })
            }
        }

        impl $lane {
            /// The lanes, in place.
            #[inline(always)]
            fn as_array(&self) -> &[$e; $n] {
                unsafe { &*std::ptr::from_ref(self).cast::<[$e; $n]>() }
            }
            /// The lanes, in place, to change.
            #[inline(always)]
            fn as_mut_array(&mut self) -> &mut [$e; $n] {
                unsafe { &mut *std::ptr::from_mut(self).cast::<[$e; $n]>() }
            }
        }

        macro_rules! compare {
            ($f:ident, $op:ident) => {
                #[inline(always)]
                fn $f(self, o: Self) -> $mask {
                    $mask(unsafe { $cmp::<$op>(self.0, o.0) })
                }
            };
        }

        impl Lane for $lane {
            const LANES: usize = $n;
            type Mask = $mask;
            const ZERO: Self = Self(unsafe { std::mem::transmute::<[$e; $n], $v>([0.0; $n]) });
            const MIN_POSITIVE: f64 = <$e>::MIN_POSITIVE as f64;

            #[inline(always)]
            fn splat(x: f64) -> Self {
                #[allow(clippy::cast_possible_truncation)]
                Self(unsafe { $set1(x as $e) })
            }
            lane_access!($e);
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                Self(unsafe { $fmadd(self.0, a.0, b.0) })
            }
            #[inline(always)]
            fn mul_sub(self, a: Self, b: Self) -> Self {
                Self(unsafe { $fmsub(self.0, a.0, b.0) })
            }
            #[inline(always)]
            fn mul_neg_add(self, a: Self, b: Self) -> Self {
                Self(unsafe { $fnmadd(self.0, a.0, b.0) })
            }
            #[inline(always)]
            fn mul_neg_sub(self, a: Self, b: Self) -> Self {
                Self(unsafe { $fnmsub(self.0, a.0, b.0) })
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                Self(unsafe { $sqrt(self.0) })
            }
            #[inline(always)]
            fn abs(self) -> Self {
                // Clears the sign bits.
                Self(unsafe { $andnot($set1(-0.0), self.0) })
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
                Self(unsafe { $min(self.0, o.0) })
            }
            #[inline(always)]
            fn fast_max(self, o: Self) -> Self {
                Self(unsafe { $max(self.0, o.0) })
            }
            compare!(simd_eq, _CMP_EQ_OQ);
            compare!(simd_lt, _CMP_LT_OQ);
            compare!(simd_le, _CMP_LE_OQ);
            compare!(simd_gt, _CMP_GT_OQ);
            compare!(simd_ge, _CMP_GE_OQ);
            #[inline(always)]
            fn is_nan(self) -> $mask {
                $mask(unsafe { $cmp::<_CMP_UNORD_Q>(self.0, self.0) })
            }
            #[inline(always)]
            fn blend(mask: $mask, a: Self, b: Self) -> Self {
                Self(unsafe { $blend(mask.0, b.0, a.0) })
            }
        }
    };
}

/// Eight f64 landers.
pub mod f64x8 {
    avx512_lane!(
        /// Eight f64 lanes in a `__m512d`. Only made on a CPU with the features of
        /// `FEATURES`.
        F64x8Avx512, "f64x8 AVX-512", __m512d, f64, 8, K8, __mmask8,
        set1 _mm512_set1_pd,
        add _mm512_add_pd, sub _mm512_sub_pd, mul _mm512_mul_pd, div _mm512_div_pd,
        xor _mm512_xor_pd, andnot _mm512_andnot_pd, fmadd _mm512_fmadd_pd,
        fmsub _mm512_fmsub_pd, fnmadd _mm512_fnmadd_pd, fnmsub _mm512_fnmsub_pd,
        sqrt _mm512_sqrt_pd, min _mm512_min_pd, max _mm512_max_pd, cmp _mm512_cmp_pd_mask,
        blend _mm512_mask_blend_pd
    );
}

/// Sixteen f32 landers.
pub mod f32x16 {
    avx512_lane!(
        /// Sixteen f32 lanes in a `__m512`. Only made on a CPU with the features of
        /// `FEATURES`.
        F32x16Avx512, "f32x16 AVX-512", __m512, f32, 16, K16, __mmask16,
        set1 _mm512_set1_ps,
        add _mm512_add_ps, sub _mm512_sub_ps, mul _mm512_mul_ps, div _mm512_div_ps,
        xor _mm512_xor_ps, andnot _mm512_andnot_ps, fmadd _mm512_fmadd_ps,
        fmsub _mm512_fmsub_ps, fnmadd _mm512_fnmadd_ps, fnmsub _mm512_fnmsub_ps,
        sqrt _mm512_sqrt_ps, min _mm512_min_ps, max _mm512_max_ps, cmp _mm512_cmp_ps_mask,
        blend _mm512_mask_blend_ps
    );
}

pub use f32x16::F32x16Avx512;
pub use f64x8::F64x8Avx512;
