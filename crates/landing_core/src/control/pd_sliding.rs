//! PD sliding mode, the seed-000 baseline (SPEC 5 law 1): `s = e' + lambda e`,
//! `u = u_eq - k switch(s)` with the equivalent control from s' = 0 and the plant model.

use nalgebra::SVector;

use super::{ControlLaw, LawInput};
use crate::error::{ParamError, require_axes};
use crate::math::Switch;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PdSlidingMode<const D: usize> {
    pub lambda: SVector<f64, D>,
    pub k: SVector<f64, D>,
    pub switch: Switch,
}

impl<const D: usize> PdSlidingMode<D> {
    #[inline(always)]
    pub fn surface(&self, input: &LawInput<D>) -> SVector<f64, D> {
        input.de + self.lambda.component_mul(&input.e)
    }
}

impl<const D: usize> ControlLaw<D> for PdSlidingMode<D> {
    type Memory = ();
    const DIAGNOSTICS: &'static [&'static str] = &["s"];

    fn start(&self, _input: &LawInput<D>) {}

    #[inline(always)]
    fn command(&self, _memory: &(), input: &LawInput<D>) -> SVector<f64, D> {
        let s = self.surface(input);
        // s' = e'' + lambda e' = 0 with e'' = drift + a - q_ref''
        let equivalent =
            input.reference.acceleration - input.drift - self.lambda.component_mul(&input.de);
        SVector::from_fn(|i, _| equivalent[i] - self.k[i] * self.switch.apply(s[i]))
    }

    fn diagnostics(&self, _memory: &(), input: &LawInput<D>, out: &mut [f64]) {
        out[..D].copy_from_slice(self.surface(input).as_slice());
    }

    fn validate(&self) -> Result<(), ParamError> {
        require_axes(self.lambda.as_slice(), "lambda", "lambda > 0", |v| v > 0.0)?;
        require_axes(self.k.as_slice(), "k", "k > 0", |v| v > 0.0)?;
        super::validate_switch(&self.switch)
    }
}
