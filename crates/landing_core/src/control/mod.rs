//! Control laws.
//!
//! A law reads the tracking errors and the plant's model at a control instant and returns a
//! commanded generalized acceleration `a`, meaning `q'' = drift + a + d` with `drift` the
//! plant's modelled acceleration and `d` the unknown disturbance. The plant's actuator turns
//! `a` into thrust, torque or control acceleration. Laws with internal states (integrators,
//! adaptive weights) keep them in their `Memory`, advanced once per control period by forward
//! Euler after the command is computed.
//!
//! Every law is written once over [`Real`] lanes (see [`crate::lanes`]). The registry at the end
//! of this file lists each law once, with its name at the Python boundary; it generates
//! [`AnyLaw`], the law chosen at run time, whose `match` per control period is perfectly
//! predicted and keeps the number of compiled rollouts to one per plant and instruction set.

mod fast_terminal;
mod fixed_time_mss;
mod fixed_time_ntsmc;
mod fuzzy_fast_terminal;
mod fuzzy_variable_rate;
mod integral_reaching;
mod ntsmc;
mod open_loop;
mod pd_sliding;
pub mod rbf;
mod super_twisting;
mod tabulated;

pub use fast_terminal::{FastTerminalSmc, TerminalConstants, TerminalSurface};
pub use fixed_time_mss::{FixedTimeMss, MssVariant};
pub use fixed_time_ntsmc::{FixedTimeNtsmc, zeta, zeta_slope};
pub use fuzzy_fast_terminal::{FuzzyFastTerminalSmc, FuzzyTerminalConstants};
pub use fuzzy_variable_rate::{FuzzyVariableRate, VariableRateMemory};
pub use integral_reaching::{IntegralExponentialReaching, IntegralSurface};
pub use ntsmc::Ntsmc;
pub use open_loop::OpenLoop;
pub use pd_sliding::PdSlidingMode;
pub use super_twisting::{SuperTwisting, SuperTwistingVariant};
pub use tabulated::{AfterTable, Tabulated};

use nalgebra::SVector;

use crate::error::{ParamError, ReadError, Validate, check};
use crate::lanes::{Gather, Real};
use crate::math::{BOUNDARY_LAYER, Switch};
use crate::params::{Declared, FromParams, ParamSource};
use crate::reference::RefPoint;

/// What a law sees at a control instant.
#[derive(Clone, Copy, Debug)]
pub struct LawInput<const D: usize, R = f64> {
    pub t: f64,
    /// Control period.
    pub dt: f64,
    /// Tracking error `e = q - q_ref`.
    pub e: SVector<R, D>,
    /// Rate error `e' = q' - q_ref'`.
    pub de: SVector<R, D>,
    pub reference: RefPoint<D, R>,
    /// The plant's modelled acceleration (see `Plant::modelled_acceleration`).
    pub drift: SVector<R, D>,
    /// The plant's diagonal inertia (see `Plant::inertia`).
    pub inertia: SVector<R, D>,
}

/// What a kernel does with one law at its own type ([`AnyLaw::visit`]): the kernels compile
/// each law's command into a function of its own this way. Dispatched inside one function, the
/// match over every law had the stack frame of the largest (50 kB, probed page by page at every
/// call, whichever law ran: 1.4 % more instructions in W1 than before the realistic loop,
/// BENCHMARKS.md).
pub(crate) trait LawVisitor<const D: usize, R: Real> {
    type Output;
    fn visit<C: ControlLaw<R, D>>(self, law: &C, memory: &C::Memory) -> Self::Output;
}

/// [`LawVisitor`] with the law's memory to update ([`AnyLaw::visit_mut`]).
pub(crate) trait LawVisitorMut<const D: usize, R: Real> {
    type Output;
    fn visit<C: ControlLaw<R, D>>(self, law: &C, memory: &mut C::Memory) -> Self::Output;
}

pub trait ControlLaw<R: Real, const D: usize>: Send + Sync {
    /// Internal state carried from one control period to the next, made by `start`. A law may
    /// also keep there what it derives from its gains alone, computed once per block rather
    /// than at every period (the law is called out of line, so the compiler cannot hoist it).
    type Memory: Copy + Send + Sync + std::fmt::Debug;

    /// Whether `advance` changes the memory (the rollout calls it only then).
    const ADVANCES: bool = std::mem::size_of::<Self::Memory>() > 0;

    /// Names of the law's diagnostic signals (sliding variables, adaptive terms), each a
    /// D-vector, recorded alongside the states.
    const DIAGNOSTICS: &'static [&'static str];

    /// Names of scalar diagnostic signals (blending coefficients, distances), recorded after
    /// the D-vector ones.
    const SCALAR_DIAGNOSTICS: &'static [&'static str] = &[];

    fn start(&self, input: &LawInput<D, R>) -> Self::Memory;

    /// Commanded generalized acceleration at this instant.
    fn command(&self, memory: &Self::Memory, input: &LawInput<D, R>) -> SVector<R, D>;

    /// Advance the memory over one control period (forward Euler with `input.dt`).
    #[inline(always)]
    fn advance(&self, _memory: &mut Self::Memory, _input: &LawInput<D, R>) {}

    /// Whether the law overrides [`Self::command_and_advance`]: its rollout then makes that one
    /// call per period where the other laws make two, `command` and `advance`.
    const COMMANDS_AND_ADVANCES: bool = false;

    /// `command`, then `advance` over the period, in one call, for a law whose update needs
    /// what its command computed (the fixed-time NTSMC's surfaces and network basis), to
    /// compute that once; such a law sets [`Self::COMMANDS_AND_ADVANCES`]. It must give what
    /// the two calls give, bit for bit.
    #[inline(always)]
    fn command_and_advance(
        &self,
        memory: &mut Self::Memory,
        input: &LawInput<D, R>,
    ) -> SVector<R, D> {
        let u = self.command(memory, input);
        self.advance(memory, input);
        u
    }

    /// Write `DIAGNOSTICS.len() * D + SCALAR_DIAGNOSTICS.len()` values into `out`, signal by
    /// signal.
    #[inline(always)]
    fn diagnostics(&self, _memory: &Self::Memory, _input: &LawInput<D, R>, _out: &mut [R]) {}
}

/// Number of values a law's diagnostics take per recorded instant.
pub fn diagnostic_width<const D: usize, R: Real, L: ControlLaw<R, D>>() -> usize {
    L::DIAGNOSTICS.len() * D + L::SCALAR_DIAGNOSTICS.len()
}

/// Names and widths of a law's diagnostic signals, in recording order.
fn layout<const D: usize, L: ControlLaw<f64, D>>() -> Vec<(&'static str, usize)> {
    L::DIAGNOSTICS
        .iter()
        .map(|n| (*n, D))
        .chain(L::SCALAR_DIAGNOSTICS.iter().map(|n| (*n, 1)))
        .collect()
}

/// A switching function's boundary layer must be positive.
pub(crate) fn validate_switch(switch: &Switch) -> Result<(), ParamError> {
    match switch.width() {
        Some(phi) => check(&BOUNDARY_LAYER, phi, |v| v > 0.0),
        None => Ok(()),
    }
}

/// The law registry: each law once, with its name at the Python boundary. Generates
/// [`LawKind`] (the names), [`AnyLaw`] (one variant per law), [`AnyMemory`], their dispatch and
/// the parsing of a law's table.
macro_rules! laws {
    ($($variant:ident => $kind:literal,)*) => {
        crate::named! {
            /// The laws' names at the Python boundary, in registry order, and their schemas.
            pub enum LawKind in "law" {
                $($variant => $kind: <$variant<3> as Declared>::SCHEMA,)*
            }
        }

        /// A law chosen at run time (one case's, `AnyLaw<D>`, or a block's,
        /// `AnyLaw<D, Lanes<W>>`).
        #[derive(Clone, Debug, PartialEq)]
        pub enum AnyLaw<const D: usize, R = f64> {
            $($variant($variant<D, R>),)*
        }

        /// The memory of an [`AnyLaw`]: the same variant as its law.
        #[derive(Clone, Copy, Debug)]
        pub enum AnyMemory<const D: usize, R: Real> {
            $($variant(<$variant<D, R> as ControlLaw<R, D>>::Memory),)*
        }

        /// The laws' names at the Python boundary, in registry order.
        pub const LAW_KINDS: &[&str] = LawKind::NAMES;

        $(
            impl<const D: usize, R: Real> From<$variant<D, R>> for AnyLaw<D, R> {
                fn from(law: $variant<D, R>) -> Self {
                    Self::$variant(law)
                }
            }
        )*

        impl<const D: usize, R: Real> AnyLaw<D, R> {
            /// The law's kind (its name at the Python boundary).
            pub fn kind(&self) -> LawKind {
                match self {
                    $(Self::$variant(_) => LawKind::$variant,)*
                }
            }

            /// Names and widths of the diagnostic signals, in recording order.
            pub fn diagnostic_layout(&self) -> Vec<(&'static str, usize)> {
                match self {
                    $(Self::$variant(_) => layout::<D, $variant<D>>(),)*
                }
            }

            /// Number of diagnostic values per recorded instant.
            pub fn diagnostic_width(&self) -> usize {
                match self {
                    $(Self::$variant(_) => diagnostic_width::<D, R, $variant<D, R>>(),)*
                }
            }

            /// Whether the law has a memory to advance (otherwise `advance` does nothing, and
            /// the rollout need not call it).
            pub fn has_memory(&self) -> bool {
                match self {
                    $(Self::$variant(_) => <$variant<D, R> as ControlLaw<R, D>>::ADVANCES,)*
                }
            }

            #[inline(always)]
            pub fn start(&self, input: &LawInput<D, R>) -> AnyMemory<D, R> {
                match self {
                    $(Self::$variant(l) => AnyMemory::$variant(l.start(input)),)*
                }
            }

            #[inline(always)]
            pub fn command(&self, memory: &AnyMemory<D, R>, input: &LawInput<D, R>) -> SVector<R, D> {
                match (self, memory) {
                    $((Self::$variant(l), AnyMemory::$variant(m)) => l.command(m, input),)*
                    // start() makes the memory of the law's own variant
                    _ => unreachable!("a law's memory has the law's variant"),
                }
            }

            /// Calls `visitor` with the law and its memory at their own types.
            #[inline(always)]
            pub(crate) fn visit<V: LawVisitor<D, R>>(&self, memory: &AnyMemory<D, R>, visitor: V) -> V::Output {
                match (self, memory) {
                    $((Self::$variant(l), AnyMemory::$variant(m)) => visitor.visit(l, m),)*
                    _ => unreachable!("a law's memory has the law's variant"),
                }
            }

            /// [`AnyLaw::visit`] with the memory to update.
            #[inline(always)]
            pub(crate) fn visit_mut<V: LawVisitorMut<D, R>>(
                &self,
                memory: &mut AnyMemory<D, R>,
                visitor: V,
            ) -> V::Output {
                match (self, memory) {
                    $((Self::$variant(l), AnyMemory::$variant(m)) => visitor.visit(l, m),)*
                    _ => unreachable!("a law's memory has the law's variant"),
                }
            }

            #[inline(always)]
            pub fn advance(&self, memory: &mut AnyMemory<D, R>, input: &LawInput<D, R>) {
                match (self, memory) {
                    $((Self::$variant(l), AnyMemory::$variant(m)) => l.advance(m, input),)*
                    _ => unreachable!("a law's memory has the law's variant"),
                }
            }

            #[inline(always)]
            pub fn diagnostics(&self, memory: &AnyMemory<D, R>, input: &LawInput<D, R>, out: &mut [R]) {
                match (self, memory) {
                    $((Self::$variant(l), AnyMemory::$variant(m)) => l.diagnostics(m, input, out),)*
                    _ => unreachable!("a law's memory has the law's variant"),
                }
            }
        }

        impl<const D: usize, R: Real> Gather<R> for AnyLaw<D, R> {
            type Case = AnyLaw<D>;

            fn gather<'a>(case: &dyn Fn(usize) -> &'a AnyLaw<D>) -> Self {
                match case(0) {
                    $(AnyLaw::$variant(_) => Self::$variant(Gather::gather(&|i| match case(i) {
                        AnyLaw::$variant(l) => l,
                        _ => unreachable!("a block's laws have one kind"),
                    })),)*
                }
            }

            fn same_shape(a: &AnyLaw<D>, b: &AnyLaw<D>) -> bool {
                match (a, b) {
                    $((AnyLaw::$variant(x), AnyLaw::$variant(y)) =>
                        <$variant<D, R> as Gather<R>>::same_shape(x, y),)*
                    _ => false,
                }
            }
        }

        impl<const D: usize> AnyLaw<D> {
            /// The law a table describes (its `kind` names it), validated.
            pub fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
                let law = match p.kind::<LawKind>()? {
                    $(LawKind::$variant => Self::$variant(<$variant<D>>::from_params(p)?),)*
                };
                law.validate()?;
                Ok(law)
            }
        }

        impl<const D: usize> Validate for AnyLaw<D> {
            fn validate(&self) -> Result<(), ParamError> {
                match self {
                    $(Self::$variant(l) => l.validate(),)*
                }
            }
        }
    };
}

laws! {
    FixedTimeMss => "fixed_time_mss",
    SuperTwisting => "super_twisting",
    OpenLoop => "open_loop",
    PdSlidingMode => "pd_sliding_mode",
    FastTerminalSmc => "fast_terminal_smc",
    FuzzyFastTerminalSmc => "fuzzy_fast_terminal_smc",
    IntegralExponentialReaching => "integral_exponential_reaching",
    FuzzyVariableRate => "fuzzy_variable_rate",
    Ntsmc => "ntsmc",
    FixedTimeNtsmc => "fixed_time_ntsmc",
    Tabulated => "tabulated",
}

/// The laws, read for each axis count ([`crate::params::ByAxes`]).
pub struct Laws;

impl crate::params::ReadFor for Laws {
    type At<const D: usize> = AnyLaw<D>;
    fn read<const D: usize>(p: &mut crate::params::Reader<'_>) -> Result<AnyLaw<D>, ReadError> {
        AnyLaw::<D>::from_params(p)
    }
}
