//! One AVX2 register of landers, multiply-adds fused (FMA3): four in f64 (`F64x4Avx2`),
//! eight in f32 (`F32x8Avx2`). Both lane types come from one macro, so they are the same
//! code over the two precisions.
//!
//! Two registers a lane value (eight f64 or sixteen f32 landers, as AVX-512 holds in one)
//! ran slower: the step keeps more values live than AVX2's sixteen registers hold, and at
//! two registers a value it spilled more (a third of the hot loop's time fell on stack
//! loads and stores in the MuJoCo-matched scenario). Measured on the 2-core AMD EPYC
//! machine, 1 thread, alternated, the same bytes: README, "One register a lane value".

// What the kernels are compiled for: x86-64-v3 (the same list as `compiled_kernel!` below).
x86_features!(
    "avx2", "avx", "fma", "bmi1", "bmi2", "lzcnt", "movbe", "popcnt", "f16c"
);

/// The lane type `$lane` of `$n` lanes of `$e` in one register `$v`, with the intrinsics
/// of its precision.
macro_rules! avx2_lane {
    (
        $(#[$doc:meta])* $lane:ident, $name:literal, $v:ty, $e:ty, $n:literal,
        movemask $movemask:ident,
        add $add:ident, sub $sub:ident, mul $mul:ident, div $div:ident, and $and:ident,
        or $or:ident, xor $xor:ident, andnot $andnot:ident, fmadd $fmadd:ident,
        fmsub $fmsub:ident, fnmadd $fnmadd:ident, fnmsub $fnmsub:ident, sqrt $sqrt:ident,
        min $min:ident, max $max:ident, cmp $cmp:ident, blendv $blendv:ident
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

        compiled_kernel!($lane, $name, "avx2,avx,fma,bmi1,bmi2,lzcnt,movbe,popcnt,f16c");

        vector_mask!(
            $lane,
            $e,
            |m| {
                #[allow(clippy::cast_sign_loss)]
                unsafe {
                    $movemask(m.0) as u32
                }
            }
        );

        /// Applies an intrinsic to the register.
        macro_rules! register {
            ($f:path, $a:expr) => {
                $lane(unsafe { $f($a.0) })
            };
            ($f:path, $a:expr, $b:expr) => {
                $lane(unsafe { $f($a.0, $b.0) })
            };
            ($f:path, $a:expr, $b:expr, $c:expr) => {
                $lane(unsafe { $f($a.0, $b.0, $c.0) })
            };
        }

        macro_rules! binary {
            ($trait:ident, $f:ident, $assign:ident, $fa:ident, $intrinsic:ident) => {
                impl $trait for $lane {
                    type Output = Self;
                    #[inline(always)]
                    fn $f(self, o: Self) -> Self {
                        register!($intrinsic, self, o)
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
        binary!(BitAnd, bitand, BitAndAssign, bitand_assign, $and);
        binary!(BitOr, bitor, BitOrAssign, bitor_assign, $or);

        impl Div for $lane {
            type Output = Self;
            #[inline(always)]
            fn div(self, o: Self) -> Self {
                register!($div, self, o)
            }
        }

        impl Neg for $lane {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                register!($xor, self, Self::splat(-0.0))
            }
        }

        impl Not for $lane {
            type Output = Self;
            #[inline(always)]
            fn not(self) -> Self {
                register!($xor, self, Self::from_array([<$e>::from_bits(!0); $n]))
            }
        }

        impl $lane {
            /// From the lanes: the same bytes, no instruction needed (this runs outside
            /// the kernels too).
            #[inline(always)]
            fn from_array(a: [$e; $n]) -> Self {
                Self(unsafe { std::mem::transmute::<[$e; $n], $v>(a) })
            }
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
                fn $f(self, o: Self) -> Self {
                    register!($cmp::<$op>, self, o)
                }
            };
        }

        impl Lane for $lane {
            const LANES: usize = $n;
            type Mask = Self;
            const ZERO: Self = Self(unsafe { std::mem::transmute::<[$e; $n], $v>([0.0; $n]) });
            const MIN_POSITIVE: f64 = <$e>::MIN_POSITIVE as f64;

            #[inline(always)]
            fn splat(x: f64) -> Self {
                #[allow(clippy::cast_possible_truncation)]
                Self::from_array([x as $e; $n])
            }
            lane_access!($e);
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                register!($fmadd, self, a, b)
            }
            #[inline(always)]
            fn mul_sub(self, a: Self, b: Self) -> Self {
                register!($fmsub, self, a, b)
            }
            #[inline(always)]
            fn mul_neg_add(self, a: Self, b: Self) -> Self {
                register!($fnmadd, self, a, b)
            }
            #[inline(always)]
            fn mul_neg_sub(self, a: Self, b: Self) -> Self {
                register!($fnmsub, self, a, b)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                register!($sqrt, self)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                // Clears the sign bits.
                register!($andnot, Self::splat(-0.0), self)
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
                register!($min, self, o)
            }
            #[inline(always)]
            fn fast_max(self, o: Self) -> Self {
                register!($max, self, o)
            }
            compare!(simd_eq, _CMP_EQ_OQ);
            compare!(simd_lt, _CMP_LT_OQ);
            compare!(simd_le, _CMP_LE_OQ);
            compare!(simd_gt, _CMP_GT_OQ);
            compare!(simd_ge, _CMP_GE_OQ);
            #[inline(always)]
            fn is_nan(self) -> Self {
                register!($cmp::<_CMP_UNORD_Q>, self, self)
            }
            #[inline(always)]
            fn blend(mask: Self, a: Self, b: Self) -> Self {
                register!($blendv, b, a, mask)
            }
        }
    };
}

/// Four f64 landers.
pub mod f64x4 {
    avx2_lane!(
        /// Four f64 lanes in one `__m256d`. Only made on a CPU with the features of
        /// `FEATURES`.
        F64x4Avx2, "f64x4 AVX2", __m256d, f64, 4,
        movemask _mm256_movemask_pd,
        add _mm256_add_pd, sub _mm256_sub_pd, mul _mm256_mul_pd, div _mm256_div_pd,
        and _mm256_and_pd, or _mm256_or_pd, xor _mm256_xor_pd, andnot _mm256_andnot_pd,
        fmadd _mm256_fmadd_pd, fmsub _mm256_fmsub_pd, fnmadd _mm256_fnmadd_pd,
        fnmsub _mm256_fnmsub_pd, sqrt _mm256_sqrt_pd, min _mm256_min_pd, max _mm256_max_pd,
        cmp _mm256_cmp_pd, blendv _mm256_blendv_pd
    );
}

/// Eight f32 landers.
pub mod f32x8 {
    avx2_lane!(
        /// Eight f32 lanes in one `__m256`. Only made on a CPU with the features of
        /// `FEATURES`.
        F32x8Avx2, "f32x8 AVX2", __m256, f32, 8,
        movemask _mm256_movemask_ps,
        add _mm256_add_ps, sub _mm256_sub_ps, mul _mm256_mul_ps, div _mm256_div_ps,
        and _mm256_and_ps, or _mm256_or_ps, xor _mm256_xor_ps, andnot _mm256_andnot_ps,
        fmadd _mm256_fmadd_ps, fmsub _mm256_fmsub_ps, fnmadd _mm256_fnmadd_ps,
        fnmsub _mm256_fnmsub_ps, sqrt _mm256_sqrt_ps, min _mm256_min_ps, max _mm256_max_ps,
        cmp _mm256_cmp_ps, blendv _mm256_blendv_ps
    );
}

pub use f32x8::F32x8Avx2;
pub use f64x4::F64x4Avx2;
