//! A constant commanded acceleration: free flight, ballistic baselines and closed-form checks.

use nalgebra::SVector;

use super::{ControlLaw, LawInput};
use crate::error::{ParamError, require};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenLoop<const D: usize> {
    pub acceleration: SVector<f64, D>,
}

impl<const D: usize> ControlLaw<D> for OpenLoop<D> {
    type Memory = ();
    const DIAGNOSTICS: &'static [&'static str] = &[];

    fn start(&self, _input: &LawInput<D>) {}

    #[inline(always)]
    fn command(&self, _memory: &(), _input: &LawInput<D>) -> SVector<f64, D> {
        self.acceleration
    }

    fn validate(&self) -> Result<(), ParamError> {
        for (i, a) in self.acceleration.iter().enumerate() {
            require(true, "acceleration", *a, "finite values").map_err(|e| e.on_axis(i))?;
        }
        Ok(())
    }
}
