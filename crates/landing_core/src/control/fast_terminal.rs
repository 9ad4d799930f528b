//! Fast terminal sliding mode (seed 000 eq. 6, 14, 19).
//!
//! ```text
//! s = e' + alpha e + beta sig^(p/q)(e)                                   (eq. 6)
//! u_eq = q_ref'' - drift - (alpha + beta (p/q) |e|^(p/q - 1)) e'       (eq. 14, s' = 0)
//! u = u_eq - k switch(s)                                                (eq. 18, 19)
//! ```
//!
//! The seed takes p < q odd integers so that e^(p/q) keeps the sign of e; `sig` does that for
//! any 0 < p < q, which is what is required. `|e|^(p/q - 1)` is singular at e = 0: there |e| is
//! floored at the named guard `e_floor`.

use nalgebra::SVector;

use super::{ControlLaw, LawInput};
use crate::error::{ParamError, ReadError, Validate, check, check_axes};
use crate::lanes::axes::Axes;
use crate::lanes::{Mask, Real, sub};
use crate::math::{BOUNDARY_LAYER, SWITCH, Switch, sgn};
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

pub(super) const ALPHA: Param = Param::axes("alpha")
    .unit("1/s")
    .rule("alpha > 0")
    .doc("gain of e in the surface s = e' + alpha e + beta sig^(p/q)(e)");
pub(super) const BETA: Param = Param::axes("beta")
    .unit("q^(1 - p/q)/s")
    .rule("beta > 0")
    .doc("gain of sig^(p/q)(e) in the surface");
pub(super) const P: Param = Param::axes("p")
    .unit("1")
    .rule("p > 0")
    .doc("numerator of the exponent p/q");
pub(super) const Q: Param = Param::axes("q")
    .unit("1")
    .rule("q > p")
    .doc("denominator of the exponent p/q");
pub(super) const E_FLOOR: Param = Param::scalar("e_floor")
    .unit("q")
    .rule("e_floor > 0")
    .doc("singularity guard: floor on |e| in |e|^(p/q - 1) of the equivalent control");
pub(super) const K: Param = Param::axes("k")
    .unit("q/s^2")
    .rule("k > 0")
    .doc("switching gain, in command units");

/// The fast terminal surface and its equivalent control, shared with the fuzzy-blended law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TerminalSurface<const D: usize, R = f64> {
    pub alpha: SVector<R, D>,
    pub beta: SVector<R, D>,
    pub p: SVector<R, D>,
    pub q: SVector<R, D>,
    /// Floor on |e| in |e|^(p/q - 1), in units of q.
    pub e_floor: R,
}

crate::gather_struct!(TerminalSurface<const D: usize, R> {
    lanes: [alpha, beta, p, q, e_floor],
    shared: [],
});

/// What the fast terminal laws derive from their gains, once per block
/// ([`ControlLaw::Memory`]): divisions and powers of constants that an out-of-line law call
/// would otherwise repeat at every control period (the same operations, so the same bits).
#[derive(Clone, Copy, Debug)]
pub struct TerminalConstants<const D: usize, R> {
    /// The exponent r = p / q.
    r: SVector<R, D>,
    /// e_floor^(r - 1), the slope |e|^(r - 1) where |e| is below the floor.
    floor_slope: SVector<R, D>,
}

impl<const D: usize, R: Real> TerminalSurface<D, R> {
    /// The constants of [`TerminalSurface::evaluate`].
    #[inline(always)]
    pub fn constants(&self) -> TerminalConstants<D, R> {
        let r = Axes::of(&self.p) / Axes::of(&self.q);
        TerminalConstants {
            r: r.vector(),
            floor_slope: Axes([self.e_floor; D]).powf(r - 1.0).vector(),
        }
    }

    /// (s, u_eq) at this instant, the axes side by side ([`Axes`], as the MSS law: each
    /// step of the chain issues every axis's instructions together).
    #[inline(always)]
    pub fn evaluate(
        &self,
        k: &TerminalConstants<D, R>,
        input: &LawInput<D, R>,
    ) -> (SVector<R, D>, SVector<R, D>) {
        let e = Axes::of(&input.e);
        let de = Axes::of(&input.de);
        let (alpha, beta) = (Axes::of(&self.alpha), Axes::of(&self.beta));
        let r = Axes::of(&k.r);
        let abs = e.abs();
        // |e|^r once (0 at e = 0); |e|^(r-1) = |e|^r / |e| away from the floor
        let pow = abs.powf(r);
        let s = de + alpha * e + beta * sgn(e) * pow;
        let above = abs.simd_ge(Axes([self.e_floor; D]));
        let slope = if above.all() {
            pow / abs
        } else {
            Real::select(above, pow / abs, Axes::of(&k.floor_slope))
        };
        let eq = Axes::of(&sub(&input.reference.acceleration, &input.drift))
            - (alpha + beta * r * slope) * de;
        (s.vector(), eq.vector())
    }
}

impl<const D: usize> Validate for TerminalSurface<D> {
    fn validate(&self) -> Result<(), ParamError> {
        check_axes(&ALPHA, self.alpha.as_slice(), |v| v > 0.0)?;
        check_axes(&BETA, self.beta.as_slice(), |v| v > 0.0)?;
        check_axes(&P, self.p.as_slice(), |v| v > 0.0)?;
        for i in 0..D {
            check(&Q, self.q[i], |v| v > self.p[i]).map_err(|e| e.on_axis(i))?;
        }
        check(&E_FLOOR, self.e_floor, |v| v > 0.0)
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FastTerminalSmc<const D: usize, R = f64> {
    pub surface: TerminalSurface<D, R>,
    pub k: SVector<R, D>,
    pub switch: Switch<R>,
}

crate::gather_struct!(FastTerminalSmc<const D: usize, R> {
    lanes: [surface, k, switch],
    shared: [],
});

impl<const D: usize, R: Real> ControlLaw<R, D> for FastTerminalSmc<D, R> {
    type Memory = TerminalConstants<D, R>;
    const ADVANCES: bool = false;
    const DIAGNOSTICS: &'static [&'static str] = &["s"];

    #[inline(always)]
    fn start(&self, _input: &LawInput<D, R>) -> TerminalConstants<D, R> {
        self.surface.constants()
    }

    #[inline(always)]
    fn command(&self, k: &TerminalConstants<D, R>, input: &LawInput<D, R>) -> SVector<R, D> {
        let (s, eq) = self.surface.evaluate(k, input);
        let mut a = eq;
        for i in 0..D {
            a[i] = eq[i] - self.k[i] * self.switch.apply(s[i]);
        }
        a
    }

    #[inline(always)]
    fn diagnostics(&self, k: &TerminalConstants<D, R>, input: &LawInput<D, R>, out: &mut [R]) {
        out[..D].copy_from_slice(self.surface.evaluate(k, input).0.as_slice());
    }
}

impl<const D: usize> Validate for FastTerminalSmc<D> {
    fn validate(&self) -> Result<(), ParamError> {
        self.surface.validate()?;
        check_axes(&K, self.k.as_slice(), |v| v > 0.0)?;
        super::validate_switch(&self.switch)
    }
}

impl<const D: usize> FromParams for TerminalSurface<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            alpha: p.axes(&ALPHA)?,
            beta: p.axes(&BETA)?,
            p: p.axes(&P)?,
            q: p.axes(&Q)?,
            e_floor: p.scalar(&E_FLOOR)?,
        })
    }
}

impl<const D: usize> Declared for FastTerminalSmc<D> {
    const SCHEMA: Schema = Schema::new(&[ALPHA, BETA, P, Q, K, SWITCH, BOUNDARY_LAYER, E_FLOOR]);
}

impl<const D: usize> FromParams for FastTerminalSmc<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            surface: TerminalSurface::from_params(p)?,
            k: p.axes(&K)?,
            switch: Switch::from_params(p)?,
        })
    }
}
