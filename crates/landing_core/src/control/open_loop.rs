//! A constant commanded acceleration: free flight, ballistic baselines and closed-form checks.

use nalgebra::SVector;

use super::{ControlLaw, LawInput};
use crate::error::{ParamError, ReadError, Validate, check};
use crate::lanes::Real;
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

const ACCELERATION: Param = Param::axes("acceleration")
    .unit("q/s^2")
    .doc("the commanded generalized acceleration, constant");

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenLoop<const D: usize, R = f64> {
    pub acceleration: SVector<R, D>,
}

crate::gather_struct!(OpenLoop<const D: usize, R> { lanes: [acceleration], shared: [] });

impl<const D: usize, R: Real> ControlLaw<R, D> for OpenLoop<D, R> {
    type Memory = ();
    const DIAGNOSTICS: &'static [&'static str] = &[];

    #[inline(always)]
    fn start(&self, _input: &LawInput<D, R>) {}

    #[inline(always)]
    fn command(&self, _memory: &(), _input: &LawInput<D, R>) -> SVector<R, D> {
        self.acceleration
    }
}

impl<const D: usize> Validate for OpenLoop<D> {
    fn validate(&self) -> Result<(), ParamError> {
        for (i, a) in self.acceleration.iter().enumerate() {
            check(&ACCELERATION, *a, |_| true).map_err(|e| e.on_axis(i))?;
        }
        Ok(())
    }
}

impl<const D: usize> Declared for OpenLoop<D> {
    const SCHEMA: Schema = Schema::new(&[ACCELERATION]);
}

impl<const D: usize> FromParams for OpenLoop<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            acceleration: p.axes(&ACCELERATION)?,
        })
    }
}
