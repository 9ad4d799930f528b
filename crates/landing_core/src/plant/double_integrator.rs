//! The double integrator `q'' = u + d` per axis: the plant on which a law's reaching law holds
//! exactly (no drift, unit inertia), used to check the theory's bounds against simulation and
//! as the simplest test bed for any law.

use nalgebra::SVector;

use super::Plant;
use crate::error::ParamError;

pub type DoubleIntegratorState = SVector<f64, 6>;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DoubleIntegrator {
    /// Per-axis limit on the commanded acceleration |u_i|; infinite for none.
    pub acceleration_limit: SVector<f64, 3>,
}

impl Default for DoubleIntegrator {
    fn default() -> Self {
        Self {
            acceleration_limit: SVector::repeat(f64::INFINITY),
        }
    }
}

impl Plant<3> for DoubleIntegrator {
    type State = DoubleIntegratorState;
    const STATE_NAMES: &'static [&'static str] = &["x", "y", "z", "vx", "vy", "vz"];
    const CONTROL_NAMES: &'static [&'static str] = &["ax", "ay", "az"];

    #[inline(always)]
    fn coordinates(&self, x: &Self::State) -> (SVector<f64, 3>, SVector<f64, 3>) {
        (x.fixed_rows::<3>(0).into(), x.fixed_rows::<3>(3).into())
    }

    #[inline(always)]
    fn modelled_acceleration(&self, _t: f64, _x: &Self::State) -> SVector<f64, 3> {
        SVector::zeros()
    }

    #[inline(always)]
    fn inertia(&self, _x: &Self::State) -> SVector<f64, 3> {
        SVector::repeat(1.0)
    }

    #[inline(always)]
    fn actuate(&self, _x: &Self::State, a: &SVector<f64, 3>) -> SVector<f64, 3> {
        let l = &self.acceleration_limit;
        SVector::from_fn(|i, _| a[i].clamp(-l[i], l[i]))
    }

    #[inline(always)]
    fn derivative(
        &self,
        _t: f64,
        x: &Self::State,
        u: &SVector<f64, 3>,
        d: &SVector<f64, 3>,
    ) -> Self::State {
        let a = u + d;
        DoubleIntegratorState::from([x[3], x[4], x[5], a[0], a[1], a[2]])
    }

    fn validate(&self) -> Result<(), ParamError> {
        for (i, &l) in self.acceleration_limit.iter().enumerate() {
            if l.is_nan() || l <= 0.0 {
                return Err(
                    ParamError::new("acceleration_limit", l, "acceleration_limit > 0").on_axis(i),
                );
            }
        }
        Ok(())
    }
}
