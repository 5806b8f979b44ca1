//! The lane types, one per instruction set, and the choice among them at run time.
//!
//! The binary is compiled for plain x86-64 (or whatever target it is built for); the
//! kernels are compiled once more inside a function per instruction set that enables its
//! features (`#[target_feature]`), and `Isa::detect` picks the widest this CPU has. Nothing
//! outside those functions uses an instruction the CPU may lack, so the same binary runs on
//! any x86-64 machine.
//!
//! The AVX-512 and AVX2 kernels fuse their multiply-adds and give the same bits; the SSE2
//! kernel (x86-64 without AVX2, hence without FMA) rounds products and sums apart, so its
//! results differ from theirs in the last bits.

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
/// CPU features `$features` (a string literal, as `#[target_feature]` takes it):
/// `step_size`, `step` and `observe` as functions of their own (so that a profile names
/// them), `advance`, which runs them, and the lane type's `Kernel`, `Debug` and `PartialEq`.
#[cfg(target_arch = "x86_64")]
macro_rules! compiled_kernel {
    ($lane:ty, $name:literal, $features:literal) => {
        impl Kernel for $lane {
            const NAME: &'static str = $name;
            const FUSED: bool = true;
            #[inline]
            fn advance(p: &Params<Self>, block: &mut Block<Self>) -> u32 {
                // A value of this type exists only where `available()` held (see `Isa`).
                unsafe { advance(p, block) }
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

        /// One step of every lane holding a sample; the lanes it decided as bits.
        ///
        /// # Safety
        /// The CPU must have the features of `FEATURES` (`available()`).
        #[target_feature(enable = $features)]
        unsafe fn advance(p: &Params<$lane>, block: &mut Block<$lane>) -> u32 {
            unsafe {
                let dt = step_size(p, block);
                step(p, block, dt);
                observe(p, block).to_bitmask()
            }
        }

        #[target_feature(enable = $features)]
        #[inline(never)]
        unsafe fn step_size(p: &Params<$lane>, block: &Block<$lane>) -> $lane {
            crate::step::step_size(p, block)
        }

        #[target_feature(enable = $features)]
        #[inline(never)]
        unsafe fn step(p: &Params<$lane>, block: &mut Block<$lane>, dt: $lane) {
            crate::step::step(p, block, dt);
        }

        #[target_feature(enable = $features)]
        #[inline(never)]
        unsafe fn observe(p: &Params<$lane>, block: &mut Block<$lane>) -> $lane {
            crate::outcome::observe(p, block)
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
    /// One step of every lane holding a sample (`step_size`, `step`, `observe`); returns
    /// the lanes it decided as bits (lane `i` in bit `i`).
    fn advance(p: &Params<Self>, block: &mut Block<Self>) -> u32;
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
    /// AVX2 with FMA (x86-64-v3): two registers.
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

    /// Runs `w` with the kernel of `self`.
    ///
    /// # Panics
    /// If this CPU does not run that kernel (check `available` first).
    pub fn dispatch<W: WithKernel>(self, w: W) -> W::Output {
        assert!(self.available(), "this CPU has no {} kernel", self.key());
        match self {
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512 => w.run::<avx512::F64x8Avx512>(),
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => w.run::<avx2::F64x8Avx2>(),
            _ => w.run::<wide::f64x8>(),
        }
    }

    /// Lane type and instruction set of the kernel of `self`, as the binary reports them.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Isa::Avx512 => "f64x8 AVX-512",
            Isa::Avx2 => "f64x8 AVX2",
            Isa::Portable => <wide::f64x8 as Kernel>::NAME,
        }
    }

    /// Whether the kernel of `self` fuses its multiply-adds.
    #[must_use]
    pub fn fused(self) -> bool {
        match self {
            Isa::Avx512 | Isa::Avx2 => true,
            Isa::Portable => <wide::f64x8 as Kernel>::FUSED,
        }
    }

    /// The arithmetic of the kernel of `self`, as files record it: kernels with the same
    /// arithmetic write the same bits.
    #[must_use]
    pub fn arithmetic(self) -> &'static str {
        if self.fused() {
            "f64x8-fma"
        } else {
            "f64x8-nofma"
        }
    }
}
