//! Fuzzy-blended fast terminal sliding mode (seed 000 eq. 20-22).
//!
//! ```text
//! u = a(D) u_eq + b(D) u_s,   a = exp(-N D),   b = 1 - exp(-M D)          (eq. 20, 22)
//! D_i = s_i / sqrt(1 + alpha_i^2),   D = |(D_1, ..., D_n)|                 (eq. 21, 22)
//! ```
//!
//! with s, u_eq of the fast terminal law (eq. 6, 14) and u_s = -k switch(s) (eq. 18). Far from
//! the surface the switching part dominates, near it the equivalent control; as printed, u_eq
//! (which holds the gravity and frame cancellation) is scaled by a(D) too.

use nalgebra::SVector;

use super::fast_terminal::{ALPHA, BETA, E_FLOOR, K, P, Q, TerminalConstants, TerminalSurface};
use super::{ControlLaw, LawInput};
use crate::error::{ParamError, ReadError, Validate, check, check_axes};
use crate::lanes::{Real, norm};
use crate::math::{BOUNDARY_LAYER, SWITCH, Switch};
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

const N: Param = Param::scalar("n")
    .unit("s/q")
    .rule("n > 0")
    .doc("N of eq. 22: how fast the equivalent control's weight a(D) = exp(-N D) falls");
const M: Param = Param::scalar("m")
    .unit("s/q")
    .rule("m > 0")
    .doc("M of eq. 22: how fast the switching weight b(D) = 1 - exp(-M D) rises");

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FuzzyFastTerminalSmc<const D: usize, R = f64> {
    pub surface: TerminalSurface<D, R>,
    pub k: SVector<R, D>,
    pub switch: Switch<R>,
    /// N of eq. 22: how fast a(D) falls with the distance to the surface.
    pub n: R,
    /// M of eq. 22: how fast b(D) rises.
    pub m: R,
}

crate::gather_struct!(FuzzyFastTerminalSmc<const D: usize, R> {
    lanes: [surface, k, switch, n, m],
    shared: [],
});

/// What the law derives from its gains, once per block ([`ControlLaw::Memory`]): the
/// surface's constants and each axis's distance scale sqrt(1 + alpha_i^2) of eq. 21.
#[derive(Clone, Copy, Debug)]
pub struct FuzzyTerminalConstants<const D: usize, R> {
    surface: TerminalConstants<D, R>,
    scale: SVector<R, D>,
}

impl<const D: usize, R: Real> FuzzyFastTerminalSmc<D, R> {
    /// (a, b, D) at this distance vector.
    #[inline(always)]
    pub fn blend(&self, k: &FuzzyTerminalConstants<D, R>, s: &SVector<R, D>) -> (R, R, R) {
        let mut scaled = *s;
        for i in 0..D {
            scaled[i] = s[i] / k.scale[i];
        }
        let dist = norm(&scaled);
        (
            (-self.n * dist).exp(),
            R::one() - (-self.m * dist).exp(),
            dist,
        )
    }
}

impl<const D: usize, R: Real> ControlLaw<R, D> for FuzzyFastTerminalSmc<D, R> {
    type Memory = FuzzyTerminalConstants<D, R>;
    const ADVANCES: bool = false;
    const DIAGNOSTICS: &'static [&'static str] = &["s"];
    const SCALAR_DIAGNOSTICS: &'static [&'static str] = &["a", "b", "distance"];

    #[inline(always)]
    fn start(&self, _input: &LawInput<D, R>) -> FuzzyTerminalConstants<D, R> {
        let mut scale = self.surface.alpha;
        for i in 0..D {
            let alpha = self.surface.alpha[i];
            scale[i] = (R::one() + alpha * alpha).sqrt();
        }
        FuzzyTerminalConstants {
            surface: self.surface.constants(),
            scale,
        }
    }

    #[inline(always)]
    fn command(&self, k: &FuzzyTerminalConstants<D, R>, input: &LawInput<D, R>) -> SVector<R, D> {
        let (s, eq) = self.surface.evaluate(&k.surface, input);
        let (a, b, _) = self.blend(k, &s);
        let mut u = eq;
        for i in 0..D {
            u[i] = a * eq[i] - b * self.k[i] * self.switch.apply(s[i]);
        }
        u
    }

    #[inline(always)]
    fn diagnostics(&self, k: &FuzzyTerminalConstants<D, R>, input: &LawInput<D, R>, out: &mut [R]) {
        let (s, _) = self.surface.evaluate(&k.surface, input);
        let (a, b, dist) = self.blend(k, &s);
        out[..D].copy_from_slice(s.as_slice());
        out[D..D + 3].copy_from_slice(&[a, b, dist]);
    }
}

impl<const D: usize> Validate for FuzzyFastTerminalSmc<D> {
    fn validate(&self) -> Result<(), ParamError> {
        self.surface.validate()?;
        check_axes(&K, self.k.as_slice(), |v| v > 0.0)?;
        check(&N, self.n, |v| v > 0.0)?;
        check(&M, self.m, |v| v > 0.0)?;
        super::validate_switch(&self.switch)
    }
}

impl<const D: usize> Declared for FuzzyFastTerminalSmc<D> {
    const SCHEMA: Schema =
        Schema::new(&[ALPHA, BETA, P, Q, K, N, M, SWITCH, BOUNDARY_LAYER, E_FLOOR]);
}

impl<const D: usize> FromParams for FuzzyFastTerminalSmc<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            surface: TerminalSurface::from_params(p)?,
            k: p.axes(&K)?,
            switch: Switch::from_params(p)?,
            n: p.scalar(&N)?,
            m: p.scalar(&M)?,
        })
    }
}
