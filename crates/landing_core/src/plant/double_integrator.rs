//! The double integrator `q'' = u + d` per axis: the plant on which a law's reaching law holds
//! exactly (no drift, unit inertia), used to check the theory's bounds against simulation and
//! as the simplest test bed for any law.

use nalgebra::SVector;

use super::{Plant, PlantModel};
use crate::error::{ParamError, ReadError, Validate};
use crate::lanes::{Real, add, filled, zeros};
use crate::navigation::{FILTER, Navigation, SENSOR};
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

pub type DoubleIntegratorState<R = f64> = SVector<R, 6>;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DoubleIntegrator<R = f64> {
    /// Per-axis limit on the commanded acceleration |u_i|; infinite for none.
    pub acceleration_limit: SVector<R, 3>,
    /// The sensor and filter the law reads through; None for the true state.
    pub navigation: Option<Navigation<3, R>>,
}

crate::gather_struct!(DoubleIntegrator<R> { lanes: [acceleration_limit, navigation], shared: [] });

impl Default for DoubleIntegrator {
    fn default() -> Self {
        Self {
            acceleration_limit: SVector::repeat(f64::INFINITY),
            navigation: None,
        }
    }
}

impl<R: Real> Plant<R, 3> for DoubleIntegrator<R> {
    type State = DoubleIntegratorState<R>;

    #[inline(always)]
    fn coordinates(&self, x: &Self::State) -> (SVector<R, 3>, SVector<R, 3>) {
        (
            SVector::from([x[0], x[1], x[2]]),
            SVector::from([x[3], x[4], x[5]]),
        )
    }

    #[inline(always)]
    fn modelled_acceleration(&self, _t: f64, _x: &Self::State) -> SVector<R, 3> {
        zeros()
    }

    #[inline(always)]
    fn inertia(&self, _x: &Self::State) -> SVector<R, 3> {
        filled(R::one())
    }

    #[inline(always)]
    fn actuate(&self, _x: &Self::State, a: &SVector<R, 3>) -> SVector<R, 3> {
        let l = &self.acceleration_limit;
        let mut u = *a;
        for i in 0..3 {
            u[i] = a[i].clamp(-l[i], l[i]);
        }
        u
    }

    #[inline(always)]
    fn navigation(&self) -> Option<&Navigation<3, R>> {
        self.navigation.as_ref()
    }

    #[inline(always)]
    fn derivative(
        &self,
        _t: f64,
        x: &Self::State,
        u: &SVector<R, 3>,
        d: &SVector<R, 3>,
    ) -> Self::State {
        let a = add(u, d);
        DoubleIntegratorState::from([x[3], x[4], x[5], a[0], a[1], a[2]])
    }
}

impl PlantModel<3> for DoubleIntegrator {
    type At<R: Real> = DoubleIntegrator<R>;
    type Blocks = crate::kernel::Wide;
    const STATE_NAMES: &'static [&'static str] = &["x", "y", "z", "vx", "vy", "vz"];
    const CONTROL_NAMES: &'static [&'static str] = &["ax", "ay", "az"];
}

impl Validate for DoubleIntegrator {
    fn validate(&self) -> Result<(), ParamError> {
        for (i, &l) in self.acceleration_limit.iter().enumerate() {
            if l.is_nan() || l <= 0.0 {
                return Err(
                    ParamError::new(ACCELERATION_LIMIT.name, l, ACCELERATION_LIMIT.rule).on_axis(i),
                );
            }
        }
        Ok(())
    }
}

const ACCELERATION_LIMIT: Param = Param::axes("acceleration_limit")
    .unit("m/s^2")
    .rule("acceleration_limit > 0")
    .optional()
    .doc("per-axis limit on |u_i|; None for none");

impl Declared for DoubleIntegrator {
    const SCHEMA: Schema = Schema::new(&[ACCELERATION_LIMIT, SENSOR, FILTER]);
}

impl FromParams for DoubleIntegrator {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            acceleration_limit: p
                .opt_axes::<3>(&ACCELERATION_LIMIT)?
                .unwrap_or(SVector::repeat(f64::INFINITY)),
            navigation: Navigation::read(p)?,
        })
    }
}
