//! PD sliding mode, the seed-000 baseline: `s = e' + lambda e`,
//! `u = u_eq - k switch(s)` with the equivalent control from s' = 0 and the plant model.

use nalgebra::SVector;

use super::{ControlLaw, LawInput};
use crate::error::{ParamError, ReadError, Validate, check_axes};
use crate::lanes::{Real, add, mul, sub};
use crate::math::{BOUNDARY_LAYER, SWITCH, Switch};
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

// Named `lambda_` in tables and in Python alike: `lambda` is a Python keyword, and one name
// everywhere keeps error messages, `parameters` and TOML files in agreement.
const LAMBDA: Param = Param::axes("lambda_")
    .unit("1/s")
    .rule("lambda_ > 0")
    .doc("slope of the surface s = e' + lambda e");
const K: Param = Param::axes("k")
    .unit("q/s^2")
    .rule("k > 0")
    .doc("switching gain, in command units (m/s^2 on a small body)");

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PdSlidingMode<const D: usize, R = f64> {
    pub lambda: SVector<R, D>,
    pub k: SVector<R, D>,
    pub switch: Switch<R>,
}

crate::gather_struct!(PdSlidingMode<const D: usize, R> { lanes: [lambda, k, switch], shared: [] });

impl<const D: usize, R: Real> PdSlidingMode<D, R> {
    #[inline(always)]
    pub fn surface(&self, input: &LawInput<D, R>) -> SVector<R, D> {
        add(&input.de, &mul(&self.lambda, &input.e))
    }
}

impl<const D: usize, R: Real> ControlLaw<R, D> for PdSlidingMode<D, R> {
    type Memory = ();
    const DIAGNOSTICS: &'static [&'static str] = &["s"];

    #[inline(always)]
    fn start(&self, _input: &LawInput<D, R>) {}

    #[inline(always)]
    fn command(&self, _memory: &(), input: &LawInput<D, R>) -> SVector<R, D> {
        let s = self.surface(input);
        // s' = e'' + lambda e' = 0 with e'' = drift + a - q_ref''
        let equivalent = sub(
            &sub(&input.reference.acceleration, &input.drift),
            &mul(&self.lambda, &input.de),
        );
        let mut a = equivalent;
        for i in 0..D {
            a[i] = equivalent[i] - self.k[i] * self.switch.apply(s[i]);
        }
        a
    }

    #[inline(always)]
    fn diagnostics(&self, _memory: &(), input: &LawInput<D, R>, out: &mut [R]) {
        out[..D].copy_from_slice(self.surface(input).as_slice());
    }
}

impl<const D: usize> Validate for PdSlidingMode<D> {
    fn validate(&self) -> Result<(), ParamError> {
        check_axes(&LAMBDA, self.lambda.as_slice(), |v| v > 0.0)?;
        check_axes(&K, self.k.as_slice(), |v| v > 0.0)?;
        super::validate_switch(&self.switch)
    }
}

impl<const D: usize> Declared for PdSlidingMode<D> {
    const SCHEMA: Schema = Schema::new(&[LAMBDA, K, SWITCH, BOUNDARY_LAYER]);
}

impl<const D: usize> FromParams for PdSlidingMode<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            lambda: p.axes(&LAMBDA)?,
            k: p.axes(&K)?,
            switch: Switch::from_params(p)?,
        })
    }
}
