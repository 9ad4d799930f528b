//! Instruction-set levels: the block rollout compiled for each, chosen at run time.
//!
//! The same generic rollout ([`crate::rollout`]) is instantiated once per level inside a
//! function compiled with that level's target features, so the lane operations become the
//! widest vector instructions the CPU has: SSE2 at the x86-64 baseline, AVX2 (x86-64-v3), or
//! AVX-512 (x86-64-v4). Every level runs the same IEEE operations in the same order, so a case
//! gives the same bits at every level of one machine architecture; only the speed differs. A
//! fused multiply-add happens only where the code writes `Real::mul_add` (one instruction at
//! AVX2 and AVX-512, libm's correctly rounded `fma` per lane at the baseline, which has none),
//! and libm is called nowhere else but on `sin_cos`'s cold path for arguments beyond 2^20 pi/2
//! (`lanes/math.rs`). Other architectures build the portable instance only (no x86 intrinsics
//! anywhere).
//!
//! The best level the CPU supports is used unless the environment variable `LANDING_KERNEL`
//! (`baseline`, `avx2`, `avx512`) or the caller forces one, for testing and benchmarking.

use std::fmt;

use nalgebra::SVector;

use crate::control::{AnyLaw, AnyMemory, ControlLaw, LawInput, LawVisitor, LawVisitorMut};
use crate::lanes::Real;
use crate::metrics::CommandStats;
use crate::params::Named;

crate::named! {
    /// An instruction-set level the block rollout is compiled for.
    #[derive(PartialOrd, Ord)]
    pub enum Level {
        /// The architecture's baseline (SSE2 on x86-64; the portable build elsewhere).
        Baseline => "baseline",
        /// x86-64-v3: AVX2, FMA, BMI1/2.
        Avx2 => "avx2",
        /// x86-64-v4: AVX-512 F, CD, BW, DQ, VL.
        Avx512 => "avx512",
    }
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
    /// The level named `name` (an error naming the levels if none is).
    pub fn from_name(name: &str) -> Result<Self, LevelError> {
        <Self as Named>::from_name(name).ok_or_else(|| LevelError::Unknown(name.to_string()))
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
        Self::ALL
            .iter()
            .copied()
            .filter(|l| l.is_supported())
            .collect()
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

    /// Cases per block at this level for blocks of width `B`.
    pub fn lanes<B: Blocks>(self) -> usize {
        match self {
            Level::Baseline => <B::Baseline as Real>::LANES,
            #[cfg(target_arch = "x86_64")]
            Level::Avx2 => <B::Avx2 as Real>::LANES,
            #[cfg(target_arch = "x86_64")]
            Level::Avx512 => <B::Avx512 as Real>::LANES,
            #[cfg(not(target_arch = "x86_64"))]
            _ => 1,
        }
    }
}

/// The lane types of a plant's blocks at each level. A block's lanes must fill several vector
/// registers, so that each instruction's latency hides behind the others' (measured: W1 took
/// 53, 41 and 37 ns per case-step at 8, 16 and 32 AVX-512 lanes), but a block must also stay
/// in the registers and the first-level cache: a plant with a large state (the flexible
/// tether's 38 components) or a law dominated by divisions gains nothing from width and loses
/// to the copies (W6: 262 ms at 8 lanes, 551 ms at 32). Once the exponential was shortened
/// and the statistics moved out of line, 16 AVX-512 lanes ran W1 as fast as 32 and W3 11 %
/// faster (17.2 against 19.4 ms at 24 lanes), with less padding in a last, partial block and
/// finer shares between threads (BENCHMARKS.md). The narrower levels have 16 registers, not
/// 32, and twice the instructions per case: at 16 lanes their period spilled and its code
/// outgrew the instruction cache, and 4 SSE2 and 8 AVX2 lanes ran W1 10 % and 22 to 30 %
/// faster on Intel (Emerald Rapids; W3 14 and 19 %; AVX2 unchanged on AMD Zen 4). Each plant
/// picks [`Wide`] or [`Narrow`] blocks ([`crate::plant::PlantModel::Blocks`]); a case's bits
/// do not depend on it.
/// Every law is compiled once per axis count and lane type, so the plants of one axis count
/// share a choice: the three-axis plants are wide, the two-axis (tether) plants narrow.
pub trait Blocks: Send + Sync + 'static {
    type Baseline: Real;
    #[cfg(target_arch = "x86_64")]
    type Avx2: Real;
    #[cfg(target_arch = "x86_64")]
    type Avx512: Real;
}

/// Blocks of 4 cases in SSE2 registers, 8 in AVX2, 16 in AVX-512.
pub struct Wide;

/// Blocks of 8 cases at every level.
pub struct Narrow;

#[cfg(target_arch = "x86_64")]
impl Blocks for Wide {
    type Baseline = crate::lanes::x86::Sse2<2>;
    type Avx2 = crate::lanes::x86::Avx2<2>;
    type Avx512 = crate::lanes::x86::Avx512<2>;
}

#[cfg(target_arch = "x86_64")]
impl Blocks for Narrow {
    type Baseline = crate::lanes::x86::Sse2<4>;
    type Avx2 = crate::lanes::x86::Avx2<2>;
    type Avx512 = crate::lanes::x86::Avx512<1>;
}

#[cfg(not(target_arch = "x86_64"))]
impl Blocks for Wide {
    type Baseline = crate::lanes::Lanes<8>;
}

#[cfg(not(target_arch = "x86_64"))]
impl Blocks for Narrow {
    type Baseline = crate::lanes::Lanes<8>;
}

/// How a block calls its law. The laws are the bulk of the code: inlined into every plant's
/// rollout at every instruction-set level they would be compiled thirty times over; called
/// out of line (once per control period) they are compiled once per level and axis count
/// (`level_laws!` below), at the price of one call per period.
pub(crate) trait LawCalls<const D: usize, R: Real> {
    fn start(law: &AnyLaw<D, R>, input: &LawInput<D, R>) -> AnyMemory<D, R>;
    fn command(
        law: &AnyLaw<D, R>,
        memory: &AnyMemory<D, R>,
        input: &LawInput<D, R>,
    ) -> SVector<R, D>;
    fn advance(law: &AnyLaw<D, R>, memory: &mut AnyMemory<D, R>, input: &LawInput<D, R>);
    /// [`ControlLaw::command_and_advance`]: the command, and the memory advanced over the
    /// period.
    fn command_and_advance(
        law: &AnyLaw<D, R>,
        memory: &mut AnyMemory<D, R>,
        input: &LawInput<D, R>,
    ) -> SVector<R, D>;
    fn diagnostics(
        law: &AnyLaw<D, R>,
        memory: &AnyMemory<D, R>,
        input: &LawInput<D, R>,
        out: &mut [R],
    );
    /// [`CommandStats::add`], out of line like the law.
    fn add_stats(stats: &mut CommandStats<D, R>, u: &SVector<R, D>, e: &SVector<R, D>, dt: f64);
    /// Runs `job` out of line, compiled once per level for its type. A block's control period
    /// goes through here ([`crate::rollout::Block::period`]): the built-in and the external
    /// drivers then share one compiled period per plant and level instead of inlining a copy
    /// each (which doubled the release build).
    fn out_of_line<J: OutOfLine<D, R>>(job: J) -> J::Output;
}

/// A piece of the rollout run out of line through [`LawCalls::out_of_line`], with the law
/// calls of the level it runs at.
pub(crate) trait OutOfLine<const D: usize, R: Real> {
    type Output;
    fn run<K: LawCalls<D, R>>(self) -> Self::Output;
}

/// The laws compiled for one level: out-of-line trampolines, generic over the axis count and
/// the lane type, that the level's block rollouts call once per control period (see
/// [`LawCalls`]). Only the level's own lane types are given them.
///
/// Each level's trampolines live in a module of their own (`$module`) because rustc places
/// every instance of a generic function in the codegen unit of the module that defines it:
/// in one module, every level's laws and periods for every plant were one codegen unit of
/// 40 % of the extension, optimised on one thread while the other core idled (the build's
/// critical path; BENCHMARKS.md). A module per level, and one for its periods, give the
/// optimiser six units to share out.
macro_rules! level_laws {
    ($module:ident, $name:ident $(, $features:literal)?) => {
        pub(crate) use $module::$name;

        mod $module {
            use super::*;

            pub(crate) struct $name;

            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn start<const D: usize, L: Real>(law: &AnyLaw<D, L>, input: &LawInput<D, L>) -> AnyMemory<D, L> {
                law.start(input)
            }

            // each law's command and advance a function of its own, with its own stack frame
            // (`LawVisitor`); the period matches on the law and calls it
            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn command<const D: usize, L: Real, C: ControlLaw<L, D>>(
                law: &C,
                memory: &C::Memory,
                input: &LawInput<D, L>,
            ) -> SVector<L, D> {
                law.command(memory, input)
            }

            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn advance<const D: usize, L: Real, C: ControlLaw<L, D>>(
                law: &C,
                memory: &mut C::Memory,
                input: &LawInput<D, L>,
            ) {
                law.advance(memory, input)
            }

            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn command_and_advance<const D: usize, L: Real, C: ControlLaw<L, D>>(
                law: &C,
                memory: &mut C::Memory,
                input: &LawInput<D, L>,
            ) -> SVector<L, D> {
                law.command_and_advance(memory, input)
            }

            struct Command<'a, const D: usize, L: Real>(&'a LawInput<D, L>);

            impl<const D: usize, L: Real> LawVisitor<D, L> for Command<'_, D, L> {
                type Output = SVector<L, D>;
                #[inline(always)]
                fn visit<C: ControlLaw<L, D>>(self, law: &C, memory: &C::Memory) -> SVector<L, D> {
                    // SAFETY: as for `LawCalls` below
                    unsafe { command(law, memory, self.0) }
                }
            }

            struct Advance<'a, const D: usize, L: Real>(&'a LawInput<D, L>);

            impl<const D: usize, L: Real> LawVisitorMut<D, L> for Advance<'_, D, L> {
                type Output = ();
                #[inline(always)]
                fn visit<C: ControlLaw<L, D>>(self, law: &C, memory: &mut C::Memory) {
                    // SAFETY: as for `LawCalls` below
                    unsafe { advance(law, memory, self.0) }
                }
            }

            struct CommandAndAdvance<'a, const D: usize, L: Real>(&'a LawInput<D, L>);

            impl<const D: usize, L: Real> LawVisitorMut<D, L> for CommandAndAdvance<'_, D, L> {
                type Output = SVector<L, D>;
                #[inline(always)]
                fn visit<C: ControlLaw<L, D>>(self, law: &C, memory: &mut C::Memory) -> SVector<L, D> {
                    // SAFETY: as for `LawCalls` below
                    unsafe {
                        // one call where the law makes it one; two otherwise, as before: at AVX2
                        // and AVX-512 LLVM inlines the memory updates' trampolines into the block
                        // loops, `#[inline(never)]` notwithstanding (their symbols are not in the
                        // binary), and every law made one function with its update would be
                        // compiled into every plant's loop. The branch is on a constant: the other
                        // function is not compiled.
                        if C::COMMANDS_AND_ADVANCES {
                            command_and_advance(law, memory, self.0)
                        } else {
                            let a = command(law, memory, self.0);
                            advance(law, memory, self.0);
                            a
                        }
                    }
                }
            }

            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn diagnostics<const D: usize, L: Real>(
                law: &AnyLaw<D, L>,
                memory: &AnyMemory<D, L>,
                input: &LawInput<D, L>,
                out: &mut [L],
            ) {
                law.diagnostics(memory, input, out)
            }

            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn add_stats<const D: usize, L: Real>(
                stats: &mut CommandStats<D, L>,
                u: &SVector<L, D>,
                e: &SVector<L, D>,
                dt: f64,
            ) {
                stats.add(u, e, dt)
            }

            // the periods (every plant's) in a unit apart from the laws
            mod period {
                use super::*;

                $(#[target_feature(enable = $features)])?
                #[inline(never)]
                pub(super) unsafe fn out_of_line<const D: usize, L: Real, J: OutOfLine<D, L>>(
                    job: J,
                ) -> J::Output {
                    job.run::<$name>()
                }
            }

            // SAFETY (every call below): this type is used only by the block rollouts of its
            // own level, which run only once `Level::resolve` has checked the CPU has it.
            impl<const D: usize, L: Real> LawCalls<D, L> for $name {
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
                    law.visit(memory, Command(input))
                }
                #[inline(always)]
                fn advance(law: &AnyLaw<D, L>, memory: &mut AnyMemory<D, L>, input: &LawInput<D, L>) {
                    law.visit_mut(memory, Advance(input))
                }
                #[inline(always)]
                fn command_and_advance(
                    law: &AnyLaw<D, L>,
                    memory: &mut AnyMemory<D, L>,
                    input: &LawInput<D, L>,
                ) -> SVector<L, D> {
                    law.visit_mut(memory, CommandAndAdvance(input))
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
                #[inline(always)]
                fn add_stats(
                    stats: &mut CommandStats<D, L>,
                    u: &SVector<L, D>,
                    e: &SVector<L, D>,
                    dt: f64,
                ) {
                    unsafe { add_stats(stats, u, e, dt) }
                }
                #[inline(always)]
                fn out_of_line<J: OutOfLine<D, L>>(job: J) -> J::Output {
                    unsafe { period::out_of_line(job) }
                }
            }
        }
    };
}

level_laws!(baseline, BaselineLaws);
#[cfg(target_arch = "x86_64")]
level_laws!(avx2, Avx2Laws, "avx2,fma,bmi1,bmi2,lzcnt,popcnt");
#[cfg(target_arch = "x86_64")]
level_laws!(
    avx512,
    Avx512Laws,
    "avx2,fma,bmi1,bmi2,lzcnt,popcnt,avx512f,avx512cd,avx512bw,avx512dq,avx512vl"
);

/// A block of cases to run at some level: [`dispatch`] (or [`run_scalar`]) picks the level's
/// lane type and law calls and hands them to [`LevelJob::run`], which is `#[inline(always)]`
/// so that the whole rollout is compiled inside the level's function, with its target
/// features.
pub(crate) trait LevelJob<const D: usize> {
    /// The plant's block widths ([`Wide`] or [`Narrow`]).
    type Blocks: Blocks;
    type Output;
    fn run<R: Real, K: LawCalls<D, R>>(self) -> Self::Output;
}

#[inline(never)]
fn run_baseline<const D: usize, J: LevelJob<D>>(job: J) -> J::Output {
    job.run::<<J::Blocks as Blocks>::Baseline, BaselineLaws>()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma,bmi1,bmi2,lzcnt,popcnt")]
fn run_avx2<const D: usize, J: LevelJob<D>>(job: J) -> J::Output {
    job.run::<<J::Blocks as Blocks>::Avx2, Avx2Laws>()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(
    enable = "avx2,fma,bmi1,bmi2,lzcnt,popcnt,avx512f,avx512cd,avx512bw,avx512dq,avx512vl"
)]
fn run_avx512<const D: usize, J: LevelJob<D>>(job: J) -> J::Output {
    job.run::<<J::Blocks as Blocks>::Avx512, Avx512Laws>()
}

/// Runs a block at `level` (which [`Level::resolve`] has checked this CPU supports).
pub(crate) fn dispatch<const D: usize, J: LevelJob<D>>(level: Level, job: J) -> J::Output {
    match level {
        Level::Baseline => run_baseline(job),
        // SAFETY: `Level::resolve` checked the CPU has the level's features.
        #[cfg(target_arch = "x86_64")]
        Level::Avx2 => unsafe { run_avx2(job) },
        #[cfg(target_arch = "x86_64")]
        Level::Avx512 => unsafe { run_avx512(job) },
        #[cfg(not(target_arch = "x86_64"))]
        _ => unreachable!("only the baseline is supported off x86-64"),
    }
}

/// Runs a block of one case with `f64` numbers: the width-1 instance of the same generic
/// rollout, which tests compare the lane kernels with bit for bit.
#[inline(never)]
pub(crate) fn run_scalar<const D: usize, J: LevelJob<D>>(job: J) -> J::Output {
    job.run::<f64, BaselineLaws>()
}
