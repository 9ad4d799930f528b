//! The simplified tethered satellite (seed eq. 17): `M q'' = u + f(q, q')`.
//!
//! The seed leaves f unknown (its RBF network estimates it). To simulate, f has to be
//! something; here it is the rigid-dumbbell limit of the flexible model, with the main
//! satellite as the origin of the Hill frame, a rigid massless tether of length L0 from it to
//! the sub-satellite's attachment point, and the sub-satellite's centre a/2 further out:
//!
//! ```text
//! phi''   = u_phi / (m_s rho0) - 3 n^2 sin(phi) cos(phi) + d_phi          rho0 = L0 + a/2
//! theta'' = (u_theta - (a/2) T sin(theta - phi)) / J + d_theta            J = m_s a^2 / 6
//! T       = m_s rho0 ((phi' + n)^2 + n^2 (3 cos^2(phi) - 1)), floored at 0
//! ```
//!
//! phi obeys the tangential balance of a point mass on a rigid rod in the Hill frame (gravity
//! gradient; the Coriolis terms cancel at constant length); the tension T of the radial
//! balance pulls the attachment point, a/2 from the centre, towards the main satellite, which
//! turns the attitude towards the line. In the form of eq. 17, f collects these terms and the
//! factor m_s rho0 / (mu L0) between the model's inertia and the true one (1.5 % for the
//! seed's masses).

use nalgebra::{SVector, Vector2};

use super::flexible::{AXIAL_DAMPING, AXIAL_STIFFNESS, NODES, TETHER_DENSITY};
use super::{TetherBody, rigid_tension};
use crate::error::{ParamError, ReadError, Validate};
use crate::lanes::{Real, zeros};
use crate::params::{FromParams, ParamSource};
use crate::plant::{Plant, PlantModel};

pub type SimplifiedState<R = f64> = SVector<R, 4>;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TetheredSimplified<R = f64> {
    pub body: TetherBody<R>,
}

crate::gather_struct!(TetheredSimplified<R> { lanes: [body], shared: [] });

impl Default for TetheredSimplified {
    fn default() -> Self {
        Self {
            body: TetherBody::default(),
        }
    }
}

impl<R: Real> TetheredSimplified<R> {
    /// Distance from the main satellite to the sub-satellite's centre, `L0 + a/2`.
    #[inline(always)]
    pub fn arm(&self) -> R {
        self.body.length + R::splat(0.5) * self.body.side
    }

    /// The tether tension at state `x` (N).
    #[inline(always)]
    pub fn tension(&self, x: &SimplifiedState<R>) -> R {
        rigid_tension(
            self.body.sub_mass,
            self.arm(),
            self.body.orbital_rate,
            x[0],
            x[2],
        )
    }
}

impl<R: Real> Plant<R, 2> for TetheredSimplified<R> {
    type State = SimplifiedState<R>;

    #[inline(always)]
    fn coordinates(&self, x: &SimplifiedState<R>) -> (Vector2<R>, Vector2<R>) {
        (Vector2::new(x[0], x[1]), Vector2::new(x[2], x[3]))
    }

    /// Nothing: every term but the inertia is unknown to the controller (seed section 3.1.3).
    #[inline(always)]
    fn modelled_acceleration(&self, _t: f64, _x: &SimplifiedState<R>) -> Vector2<R> {
        zeros()
    }

    #[inline(always)]
    fn inertia(&self, _x: &SimplifiedState<R>) -> Vector2<R> {
        self.body.inertia()
    }

    #[inline(always)]
    fn actuate(&self, _x: &SimplifiedState<R>, acceleration: &Vector2<R>) -> Vector2<R> {
        self.body.actuate(acceleration)
    }

    #[inline(always)]
    fn derivative(
        &self,
        _t: f64,
        x: &SimplifiedState<R>,
        u: &Vector2<R>,
        d: &Vector2<R>,
    ) -> SimplifiedState<R> {
        let b = &self.body;
        let n = b.orbital_rate;
        let (phi, theta) = (x[0], x[1]);
        let rho = self.arm();
        let (s, c) = phi.sin_cos();
        let phi_dd = u[0] / (b.sub_mass * rho) - R::splat(3.0) * n * n * s * c + d[0];
        let t = self.tension(x);
        let theta_dd = (u[1] - R::splat(0.5) * b.side * t * (theta - phi).sin())
            / b.moment_of_inertia()
            + d[1];
        SimplifiedState::new(x[2], x[3], phi_dd, theta_dd)
    }
}

impl PlantModel<2> for TetheredSimplified {
    type At<R: Real> = TetheredSimplified<R>;
    // Narrow like the flexible tether: the laws of a two-axis plant are then compiled for
    // three lane types instead of five (every law is compiled once per axis count and lane
    // type), which shortens the build; this small plant gains nothing from wider blocks.
    type Blocks = crate::kernel::Narrow;
    const STATE_NAMES: &'static [&'static str] = &["phi", "theta", "phi_dot", "theta_dot"];
    const CONTROL_NAMES: &'static [&'static str] = &["thrust", "torque"];

    fn figures(&self) -> Vec<(&'static str, Vec<f64>)> {
        self.body.figures()
    }

    /// The state is the angles and rates themselves.
    fn state_at(
        &self,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Option<Result<Vec<f64>, ParamError>> {
        Some(Ok(vec![q[0], q[1], qd[0], qd[1]]))
    }
}

impl Validate for TetheredSimplified {
    fn validate(&self) -> Result<(), ParamError> {
        self.body.validate()
    }
}

impl FromParams for TetheredSimplified {
    /// The shared body; the flexible model's tether parameters are known but unused here.
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        for param in [&NODES, &TETHER_DENSITY, &AXIAL_STIFFNESS, &AXIAL_DAMPING] {
            p.skip(param);
        }
        Ok(Self {
            body: TetherBody::from_params(p)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_oscillations_have_the_closed_form_frequencies() {
        // linearised at rest: phi'' = -3 n^2 phi; theta'' = -(a/2) T0 (theta - phi) / J with
        // T0 = 3 n^2 m_s rho0
        let p = TetheredSimplified::default();
        let b = p.body;
        let n = b.orbital_rate;
        let eps = 1e-7;
        let zero = Vector2::zeros();
        let dx = p.derivative(0.0, &SimplifiedState::new(eps, eps, 0.0, 0.0), &zero, &zero);
        assert!((dx[2] / eps + 3.0 * n * n).abs() < 1e-12 * n * n);
        assert!(dx[3].abs() < 1e-18, "aligned: no torque");
        let dx = p.derivative(0.0, &SimplifiedState::new(0.0, eps, 0.0, 0.0), &zero, &zero);
        let t0 = 3.0 * n * n * b.sub_mass * p.arm();
        let k = 0.5 * b.side * t0 / b.moment_of_inertia();
        assert!((dx[3] / eps + k).abs() < 1e-9 * k);
    }

    #[test]
    fn commands_and_disturbances_enter_as_documented() {
        let p = TetheredSimplified::default();
        let b = p.body;
        let x = SimplifiedState::zeros();
        let dx = p.derivative(0.0, &x, &Vector2::new(0.1, 0.05), &Vector2::new(1e-6, 2e-6));
        assert!((dx[2] - (0.1 / (b.sub_mass * p.arm()) + 1e-6)).abs() < 1e-18);
        assert!((dx[3] - (0.05 / b.moment_of_inertia() + 2e-6)).abs() < 1e-15);
    }
}
