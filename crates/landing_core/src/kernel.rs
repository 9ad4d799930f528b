//! Instruction-set levels: the block rollout compiled for each, chosen at run time.
//!
//! The same generic rollout ([`crate::rollout`]) is instantiated once per level inside a
//! function compiled with that level's target features, so the lane operations become the
//! widest vector instructions the CPU has: SSE2 at the x86-64 baseline, AVX2 (x86-64-v3), or
//! AVX-512 (x86-64-v4). Every level runs the same IEEE operations in the same order (no fused
//! multiply-add anywhere, no libm in the step), so a case gives the same bits at every level of
//! one machine architecture; only the speed differs. Other architectures build the portable
//! instance only (no x86 intrinsics anywhere).
//!
//! The best level the CPU supports is used unless the environment variable `LANDING_KERNEL`
//! (`baseline`, `avx2`, `avx512`) or the caller forces one, for testing and benchmarking.

use std::fmt;

use crate::lanes::Real;

/// An instruction-set level the block rollout is compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Level {
    /// The architecture's baseline (SSE2 on x86-64; the portable build elsewhere).
    Baseline,
    /// x86-64-v3: AVX2, FMA (unused), BMI1/2.
    Avx2,
    /// x86-64-v4: AVX-512 F, CD, BW, DQ, VL.
    Avx512,
}

/// The environment variable that forces a level.
pub const LEVEL_VARIABLE: &str = "LANDING_KERNEL";

/// A level that cannot be used.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LevelError {
    Unknown(String),
    Unsupported(Level),
}

impl fmt::Display for LevelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Unknown(name) => {
                write!(f, "kernel level {name:?} is not one of {:?}", Level::NAMES)
            }
            Self::Unsupported(level) => write!(
                f,
                "kernel level {:?} is not supported by this CPU (supported: {:?})",
                level.name(),
                Level::supported()
                    .iter()
                    .map(|l| l.name())
                    .collect::<Vec<_>>()
            ),
        }
    }
}

impl std::error::Error for LevelError {}

impl Level {
    pub const ALL: [Level; 3] = [Level::Baseline, Level::Avx2, Level::Avx512];
    pub const NAMES: [&'static str; 3] = ["baseline", "avx2", "avx512"];

    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    pub fn from_name(name: &str) -> Result<Self, LevelError> {
        Self::ALL
            .into_iter()
            .find(|l| l.name() == name)
            .ok_or_else(|| LevelError::Unknown(name.to_string()))
    }

    /// Whether this CPU can run the level.
    pub fn is_supported(self) -> bool {
        match self {
            Level::Baseline => true,
            #[cfg(target_arch = "x86_64")]
            Level::Avx2 => {
                std::arch::is_x86_feature_detected!("avx2")
                    && std::arch::is_x86_feature_detected!("fma")
                    && std::arch::is_x86_feature_detected!("bmi1")
                    && std::arch::is_x86_feature_detected!("bmi2")
            }
            #[cfg(target_arch = "x86_64")]
            Level::Avx512 => {
                Level::Avx2.is_supported()
                    && std::arch::is_x86_feature_detected!("avx512f")
                    && std::arch::is_x86_feature_detected!("avx512cd")
                    && std::arch::is_x86_feature_detected!("avx512bw")
                    && std::arch::is_x86_feature_detected!("avx512dq")
                    && std::arch::is_x86_feature_detected!("avx512vl")
            }
            #[cfg(not(target_arch = "x86_64"))]
            _ => false,
        }
    }

    /// The levels this CPU supports, lowest first.
    pub fn supported() -> Vec<Level> {
        Self::ALL.into_iter().filter(|l| l.is_supported()).collect()
    }

    /// The best level this CPU supports.
    pub fn best() -> Level {
        *Self::supported()
            .last()
            .expect("the baseline is always supported")
    }

    /// `requested` if given, else the level `LANDING_KERNEL` names, else the best; an error if
    /// the name is unknown or the CPU lacks the level.
    pub fn resolve(requested: Option<Level>) -> Result<Level, LevelError> {
        let level = match requested {
            Some(l) => l,
            None => match std::env::var(LEVEL_VARIABLE) {
                Ok(name) if !name.is_empty() => Self::from_name(&name)?,
                _ => Self::best(),
            },
        };
        if level.is_supported() {
            Ok(level)
        } else {
            Err(LevelError::Unsupported(level))
        }
    }

    /// Cases per block at this level: wide enough that the lanes of one operation fill several
    /// vector registers, which hides the latency of each instruction behind the others'.
    pub fn lanes(self) -> usize {
        match self {
            Level::Baseline => <BaselineLanes as Real>::LANES,
            #[cfg(target_arch = "x86_64")]
            Level::Avx2 => <Avx2Lanes as Real>::LANES,
            #[cfg(target_arch = "x86_64")]
            Level::Avx512 => <Avx512Lanes as Real>::LANES,
            #[cfg(not(target_arch = "x86_64"))]
            _ => 1,
        }
    }
}

/// The lane type of each level: 8 cases in 4 SSE2 registers, 16 in 4 AVX2 registers, 32 in 4
/// AVX-512 registers (elsewhere, the portable `Lanes<8>`).
#[cfg(target_arch = "x86_64")]
pub(crate) type BaselineLanes = crate::lanes::x86::Sse2<4>;
#[cfg(not(target_arch = "x86_64"))]
pub(crate) type BaselineLanes = crate::lanes::Lanes<8>;
#[cfg(target_arch = "x86_64")]
pub(crate) type Avx2Lanes = crate::lanes::x86::Avx2<4>;
#[cfg(target_arch = "x86_64")]
pub(crate) type Avx512Lanes = crate::lanes::x86::Avx512<4>;

/// The laws compiled for one level: out-of-line trampolines, generic over the axis count only,
/// that the level's block rollouts call once per control period (see
/// [`LawCalls`](crate::rollout::LawCalls)).
macro_rules! level_laws {
    ($name:ident, $lanes:ty $(, $features:literal)?) => {
        pub(crate) struct $name;

        const _: () = {
            use nalgebra::SVector;

            use crate::control::{AnyLaw, AnyMemory, LawInput};
            use crate::rollout::LawCalls;

            type L = $lanes;

            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn start<const D: usize>(law: &AnyLaw<D, L>, input: &LawInput<D, L>) -> AnyMemory<D, L> {
                law.start(input)
            }

            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn command<const D: usize>(
                law: &AnyLaw<D, L>,
                memory: &AnyMemory<D, L>,
                input: &LawInput<D, L>,
            ) -> SVector<L, D> {
                law.command(memory, input)
            }

            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn advance<const D: usize>(
                law: &AnyLaw<D, L>,
                memory: &mut AnyMemory<D, L>,
                input: &LawInput<D, L>,
            ) {
                law.advance(memory, input)
            }

            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn diagnostics<const D: usize>(
                law: &AnyLaw<D, L>,
                memory: &AnyMemory<D, L>,
                input: &LawInput<D, L>,
                out: &mut [L],
            ) {
                law.diagnostics(memory, input, out)
            }

            // SAFETY (every call below): this type is used only by the block rollouts of its
            // own level, which run only once `Level::resolve` has checked the CPU has it.
            impl<const D: usize> LawCalls<D, L> for $name {
                #[inline(always)]
                fn start(law: &AnyLaw<D, L>, input: &LawInput<D, L>) -> AnyMemory<D, L> {
                    unsafe { start(law, input) }
                }
                #[inline(always)]
                fn command(
                    law: &AnyLaw<D, L>,
                    memory: &AnyMemory<D, L>,
                    input: &LawInput<D, L>,
                ) -> SVector<L, D> {
                    unsafe { command(law, memory, input) }
                }
                #[inline(always)]
                fn advance(law: &AnyLaw<D, L>, memory: &mut AnyMemory<D, L>, input: &LawInput<D, L>) {
                    unsafe { advance(law, memory, input) }
                }
                #[inline(always)]
                fn diagnostics(
                    law: &AnyLaw<D, L>,
                    memory: &AnyMemory<D, L>,
                    input: &LawInput<D, L>,
                    out: &mut [L],
                ) {
                    unsafe { diagnostics(law, memory, input, out) }
                }
            }
        };
    };
}

level_laws!(BaselineLaws, BaselineLanes);
#[cfg(target_arch = "x86_64")]
level_laws!(Avx2Laws, Avx2Lanes, "avx2,fma,bmi1,bmi2,lzcnt,popcnt");
#[cfg(target_arch = "x86_64")]
level_laws!(
    Avx512Laws,
    Avx512Lanes,
    "avx2,fma,bmi1,bmi2,lzcnt,popcnt,avx512f,avx512cd,avx512bw,avx512dq,avx512vl"
);
