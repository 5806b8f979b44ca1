//! The lane types, one per instruction set and precision, and the choice among them at run
//! time.
//!
//! The binary is compiled for plain x86-64 (or whatever target it is built for); the
//! kernels are compiled once more inside functions per instruction set that enable its
//! features (`#[target_feature]`; one per combination of dampers, terrain, thrust and
//! regolith, `step::Loop`), and `Isa::detect` picks the widest this CPU has. Nothing
//! outside those functions uses an instruction the CPU may lack, so the same binary runs on
//! any x86-64 machine.
//!
//! The AVX-512 and AVX2 kernels of a precision fuse their multiply-adds and give the same
//! bits; the SSE2 kernels (x86-64 without AVX2, hence without FMA) round products and sums
//! apart, so their results differ from theirs in the last bits. A lander steps the same
//! whatever lane or block holds it, so the width of a lane value (eight f64 or sixteen f32
//! landers with AVX-512 and the portable kernels, four or eight with AVX2) changes no
//! bits. f32 and f64 results differ (see `Precision`).

/// `FEATURES` (the CPU features a kernel is compiled for, the same list as its
/// `#[target_feature]`) and `missing()` (those this CPU lacks).
#[cfg(target_arch = "x86_64")]
macro_rules! x86_features {
    ($($feature:tt),*) => {
        /// The CPU features this kernel is compiled for.
        pub const FEATURES: &[&str] = &[$($feature),*];

        /// The features of `FEATURES` this CPU lacks.
        #[must_use]
        pub fn missing() -> Vec<&'static str> {
            let mut missing = Vec::new();
            $(
                if !is_x86_feature_detected!($feature) {
                    missing.push($feature);
                }
            )*
            missing
        }

        /// Whether this CPU runs the kernel.
        #[must_use]
        pub fn available() -> bool {
            missing().is_empty()
        }
    };
}

/// The kernel of lane type `$lane` (named `$name`, multiply-adds fused), compiled for the
/// CPU features `$features` (a string literal, as `#[target_feature]` takes it): `advance`
/// (`step::advance`, each combination's loop and everything in it compiled for those
/// features), and the lane type's `Kernel`, `Debug` and `PartialEq`.
#[cfg(target_arch = "x86_64")]
macro_rules! compiled_kernel {
    ($lane:ty, $name:literal, $features:literal) => {
        impl Kernel for $lane {
            const NAME: &'static str = $name;
            const FUSED: bool = true;
            #[inline]
            fn advance(
                p: &Params<Self>,
                block: &mut Block<Self>,
                steps: u32,
            ) -> crate::step::Advanced {
                crate::step::advance::<Self, Compiled>(p, block, steps)
            }
        }

        /// The loop of each combination (`step::Loop`) in `advance_with`, compiled for this
        /// lane type's instruction set.
        struct Compiled;

        impl crate::step::Loop<$lane> for Compiled {
            #[inline(always)]
            fn run<
                const DAMPERS: bool,
                const TERRAIN: bool,
                const THRUST: bool,
                const REGOLITH: bool,
            >(
                p: &Params<$lane>,
                block: &mut Block<$lane>,
                steps: u32,
            ) -> crate::step::Advanced {
                // A value of this type exists only where `available()` held (see `Isa`).
                unsafe { advance_with::<DAMPERS, TERRAIN, THRUST, REGOLITH>(p, block, steps) }
            }
        }

        impl std::fmt::Debug for $lane {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                self.as_array().fmt(f)
            }
        }

        impl PartialEq for $lane {
            fn eq(&self, o: &Self) -> bool {
                self.as_array() == o.as_array()
            }
        }

        /// `step::advance_with` compiled for this lane type's instruction set.
        ///
        /// # Safety
        /// The CPU must have the features of `FEATURES` (`available()`).
        #[target_feature(enable = $features)]
        unsafe fn advance_with<
            const DAMPERS: bool,
            const TERRAIN: bool,
            const THRUST: bool,
            const REGOLITH: bool,
        >(
            p: &Params<$lane>,
            block: &mut Block<$lane>,
            steps: u32,
        ) -> crate::step::Advanced {
            crate::step::advance_with::<$lane, DAMPERS, TERRAIN, THRUST, REGOLITH>(p, block, steps)
        }
    };
}

/// `RECENTRE_M`, and `lane` and `set_lane` of a `Lane` impl, through the
/// lane type's `as_array` and `as_mut_array` of lanes of `$e` (memory, no instruction of
/// the kernel's set: these run outside the kernels).
macro_rules! lane_access {
    ($e:ty) => {
        const RECENTRE_M: f64 = if size_of::<$e>() == 4 {
            2.0
        } else {
            f64::INFINITY
        };
        #[inline(always)]
        fn lane(&self, i: usize) -> f64 {
            f64::from(self.as_array()[i])
        }
        #[inline(always)]
        fn set_lane(&mut self, i: usize, x: f64) {
            #[allow(clippy::cast_possible_truncation)]
            {
                self.as_mut_array()[i] = x as $e;
            }
        }
    };
}

/// `Mask` for the lane type `$lane` of lanes of `$e` whose masks are lane values, every bit
/// of a lane set (true) or clear (false), as its comparisons return them (AVX2 and the
/// portable types), with `$to_bitmask` turning one into bits.
macro_rules! vector_mask {
    ($lane:ty, $e:ty, |$m:ident| $to_bitmask:expr) => {
        impl crate::lane::Mask for $lane {
            const NONE: Self = <Self as crate::lane::Lane>::ZERO;
            #[inline(always)]
            fn to_bitmask(self) -> u32 {
                let $m = self;
                $to_bitmask
            }
            #[inline(always)]
            fn lane(&self, i: usize) -> bool {
                self.as_array()[i].to_bits() != 0
            }
            #[inline(always)]
            fn set_lane(&mut self, i: usize, on: bool) {
                self.as_mut_array()[i] = if on { <$e>::from_bits(!0) } else { 0.0 };
            }
        }
    };
}

#[cfg(target_arch = "x86_64")]
pub mod avx2;
#[cfg(target_arch = "x86_64")]
pub mod avx512;
mod portable;

use crate::block::Block;
use crate::lane::Lane;
use crate::params::Params;

/// A lane type with its compiled kernel.
pub trait Kernel: Lane {
    /// Lane type and instruction set, as the binary reports them.
    const NAME: &'static str;
    /// Whether multiply-adds are fused (rounded once): kernels that agree here give the
    /// same bits.
    const FUSED: bool;
    /// Up to `steps` steps of every lane holding a sample (`step::advance`): stops after
    /// the first step that decides a lane (bit `i` of `bits` for lane `i`) or asks for one
    /// to be recentred (bits 16-31, `step::outcome_bits`).
    fn advance(p: &Params<Self>, block: &mut Block<Self>, steps: u32) -> crate::step::Advanced;
}

/// Something to run with whichever kernel was chosen (a generic closure).
pub trait WithKernel {
    /// What it returns.
    type Output;
    /// Runs with kernel `K`.
    fn run<K: Kernel>(self) -> Self::Output;
}

/// The instruction sets with a kernel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Isa {
    /// AVX-512 (x86-64-v4): one register holds the eight lanes.
    Avx512,
    /// AVX2 with FMA (x86-64-v3): one register holds four lanes (f64) or eight (f32).
    Avx2,
    /// `wide` for the compiled target: SSE2 on plain x86-64, NEON on aarch64.
    Portable,
}

impl Isa {
    /// Every instruction set, widest first.
    pub const ALL: [Isa; 3] = [Isa::Avx512, Isa::Avx2, Isa::Portable];

    /// The widest instruction set this CPU runs.
    #[must_use]
    pub fn detect() -> Isa {
        Isa::ALL
            .into_iter()
            .find(|i| i.available())
            .unwrap_or(Isa::Portable)
    }

    /// Whether this CPU runs the kernel of `self`.
    #[must_use]
    pub fn available(self) -> bool {
        match self {
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512 => avx512::available(),
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => avx2::available(),
            Isa::Portable => true,
            #[cfg(not(target_arch = "x86_64"))]
            _ => false,
        }
    }

    /// The name users give it (`--kernel`).
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Isa::Avx512 => "avx512",
            Isa::Avx2 => "avx2",
            Isa::Portable => "portable",
        }
    }

    /// The instruction set named `key`, if any.
    #[must_use]
    pub fn from_key(key: &str) -> Option<Isa> {
        Isa::ALL.into_iter().find(|i| i.key() == key)
    }

    /// The CPU features the kernel of `self` needs that this CPU lacks.
    #[must_use]
    pub fn missing_features(self) -> Vec<&'static str> {
        match self {
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512 => avx512::missing(),
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => avx2::missing(),
            Isa::Portable => Vec::new(),
            #[cfg(not(target_arch = "x86_64"))]
            _ => vec!["an x86-64 CPU"],
        }
    }

    /// Whether the kernels of `self` fuse their multiply-adds.
    #[must_use]
    pub fn fused(self) -> bool {
        match self {
            Isa::Avx512 | Isa::Avx2 => true,
            Isa::Portable => <wide::f64x8 as Kernel>::FUSED,
        }
    }

    /// The kernel of `self` in `precision`.
    #[must_use]
    pub fn kernel(self, precision: Precision) -> KernelKind {
        KernelKind {
            isa: self,
            precision,
        }
    }
}

/// The precision of the lanes: f64, or f32 (twice the landers per lane value). The
/// physics is the same code; f32 rounds every operation to 24 bits instead of 53, so single
/// samples near a decision threshold may end otherwise, while the shares a sweep reports
/// agree within their sampling error (measured in the README).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Precision {
    /// f64 landers: eight per lane value (AVX-512, portable), four (AVX2).
    F64,
    /// f32 landers: sixteen per lane value (AVX-512, portable), eight (AVX2).
    F32,
}

impl Precision {
    /// Both precisions, the default first.
    pub const ALL: [Precision; 2] = [Precision::F64, Precision::F32];

    /// The name users give it (the scenario's `simulation.precision`).
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Precision::F64 => "f64",
            Precision::F32 => "f32",
        }
    }

    /// The precision named `key`, if any.
    #[must_use]
    pub fn from_key(key: &str) -> Option<Precision> {
        Precision::ALL.into_iter().find(|p| p.key() == key)
    }
}

/// A kernel: instruction set and precision.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KernelKind {
    /// The instruction set.
    pub isa: Isa,
    /// The lanes' precision.
    pub precision: Precision,
}

impl KernelKind {
    /// Runs `w` with this kernel.
    ///
    /// # Panics
    /// If this CPU does not run its instruction set (check `isa.available()` first).
    pub fn dispatch<W: WithKernel>(self, w: W) -> W::Output {
        assert!(
            self.isa.available(),
            "this CPU has no {} kernel",
            self.isa.key()
        );
        match (self.isa, self.precision) {
            #[cfg(target_arch = "x86_64")]
            (Isa::Avx512, Precision::F64) => w.run::<avx512::F64x8Avx512>(),
            #[cfg(target_arch = "x86_64")]
            (Isa::Avx512, Precision::F32) => w.run::<avx512::F32x16Avx512>(),
            #[cfg(target_arch = "x86_64")]
            (Isa::Avx2, Precision::F64) => w.run::<avx2::F64x4Avx2>(),
            #[cfg(target_arch = "x86_64")]
            (Isa::Avx2, Precision::F32) => w.run::<avx2::F32x8Avx2>(),
            (_, Precision::F64) => w.run::<wide::f64x8>(),
            (_, Precision::F32) => w.run::<wide::f32x16>(),
        }
    }

    /// Lane type and instruction set, as the binary reports them.
    #[must_use]
    pub fn name(self) -> &'static str {
        match (self.isa, self.precision) {
            (Isa::Avx512, Precision::F64) => "f64x8 AVX-512",
            (Isa::Avx512, Precision::F32) => "f32x16 AVX-512",
            (Isa::Avx2, Precision::F64) => "f64x4 AVX2",
            (Isa::Avx2, Precision::F32) => "f32x8 AVX2",
            (Isa::Portable, Precision::F64) => <wide::f64x8 as Kernel>::NAME,
            (Isa::Portable, Precision::F32) => <wide::f32x16 as Kernel>::NAME,
        }
    }

    /// Landers per lane value (per block).
    #[must_use]
    pub fn lanes(self) -> usize {
        struct Lanes;
        impl WithKernel for Lanes {
            type Output = usize;
            fn run<K: Kernel>(self) -> usize {
                K::LANES
            }
        }
        self.dispatch(Lanes)
    }

    /// Whether this kernel fuses its multiply-adds.
    #[must_use]
    pub fn fused(self) -> bool {
        self.isa.fused()
    }

    /// The arithmetic of this kernel, as files record it: kernels with the same arithmetic
    /// write the same bits.
    #[must_use]
    pub fn arithmetic(self) -> &'static str {
        match (self.precision, self.fused()) {
            (Precision::F64, true) => "f64x8-fma",
            (Precision::F64, false) => "f64x8-nofma",
            (Precision::F32, true) => "f32x16-fma",
            (Precision::F32, false) => "f32x16-nofma",
        }
    }
}
