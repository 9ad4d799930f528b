//! The flexible tethered satellite: the plant the seed-003 controllers are validated on.
//!
//! The seed's finite-element model (its eq. 1-8) is not reproducible from its text; this is a
//! planar model of the same physics, written in the orbital (Hill) frame of the
//! main satellite's circular orbit, with the main satellite as its origin:
//!
//! - the tether is N lumped masses (the nodal-position discretisation: each node carries one
//!   segment's mass, rho_t h, and the sub-satellite the half segment at its end), joined by
//!   N + 1 axial spring-dampers of rest length h = L0 / (N + 1) from the main satellite to the
//!   sub-satellite's attachment point. A
//!   segment pulls with `T = EA (l - h)/h + c_A l'/h` when stretched (Kelvin-Voigt material
//!   damping) and never pushes: `T = 0` when slack, and `T >= 0` always;
//! - every node and the sub-satellite's centre feel the linearised gravity gradient and the
//!   frame's Coriolis terms (Clohessy-Wiltshire): `x'' = 2 n y' + 3 n^2 x + F_x/m`,
//!   `y'' = -2 n x' + F_y/m` (x radial up, y along track);
//! - the sub-satellite is a rigid cube of side a and mass m_s; the tether is attached a/2 from
//!   its centre along its body axis (the one that looks at the main satellite at theta = 0), so
//!   the tension turns it; a cube's gravity-gradient torque is zero (isotropic inertia);
//! - the main satellite (100 times heavier) keeps its circular orbit: it is the frame's fixed
//!   origin, and its attitude is not modelled.
//!
//! State layout (see `names.rs`): `[xs, ys, theta, vxs, vys, omega]` for the sub-satellite
//! (omega = theta'), then `[x_k, y_k, vx_k, vy_k]` for the nodes k = 1..N from the main
//! satellite outwards; `4 N + 6` components in all. Const generics cannot compute `4 N + 6`
//! from N, so the state size S is a second parameter, checked at compile time.
//!
//! phi and theta are read off the state: phi is the angle of the sub-satellite's centre seen
//! from the main satellite, from nadir; theta is the cube's attitude. The thrust acts on the
//! centre, perpendicular to the main-to-centre line; a generalized disturbance d enters as an
//! extra force `m rho d_phi` along the thrust (m the sub-satellite's translational mass) and an
//! extra torque `J d_theta`, which add exactly d to phi'' and theta'' of the rigid limit.

use nalgebra::{SVector, Vector2};

use super::names::{MAX_NODES, NAMES};
use super::{TetherBody, rigid_tension};
use crate::error::{ParamError, ReadError, Validate, check, require};
use crate::lanes::{Gather, Real, add, neg, scale_by, sub, zeros};
use crate::params::{FromParams, Param, ParamSource};
use crate::plant::{Plant, PlantModel};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TetheredFlexible<const N: usize, const S: usize, R = f64> {
    pub body: TetherBody<R>,
    /// Tether linear density rho_t, kg/m.
    pub density: R,
    /// Axial stiffness EA, N.
    pub axial_stiffness: R,
    /// Kelvin-Voigt axial damping c_A (tension per unit strain rate), N s.
    pub axial_damping: R,
}

crate::named! {
    /// The node counts the bindings offer (each is its own fixed-size state type): enough for
    /// the refinement study to show convergence, few enough to keep the compiled rollouts few.
    pub enum NodeCount {
        N2 = 2,
        N4 = 4,
        N8 = 8,
        N16 = 16,
    }
}

/// The node counts' values.
pub const NODE_COUNTS: &[usize] = NodeCount::VALUES;

/// The node count (it picks the type, in the registry).
pub const NODES: Param = Param::count("nodes", NodeCount::VALUES)
    .unit("1")
    .rule("nodes in {2, 4, 8, 16}")
    .doc("tether nodes of the flexible model, shared by the cases (each is its own state size)");
pub(super) const TETHER_DENSITY: Param = Param::scalar("tether_density")
    .unit("kg/m")
    .rule("tether_density > 0")
    .doc("the tether's linear density");
pub(super) const AXIAL_STIFFNESS: Param = Param::scalar("axial_stiffness")
    .unit("N")
    .rule("axial_stiffness > 0")
    .doc("the tether's axial stiffness EA");
pub(super) const AXIAL_DAMPING: Param = Param::scalar("axial_damping")
    .unit("N s")
    .rule("axial_damping >= 0")
    .doc("Kelvin-Voigt axial damping c_A (tension per unit strain rate)");

pub type TetheredFlexible2<R = f64> = TetheredFlexible<2, 14, R>;
pub type TetheredFlexible4<R = f64> = TetheredFlexible<4, 22, R>;
pub type TetheredFlexible8<R = f64> = TetheredFlexible<8, 38, R>;
pub type TetheredFlexible16<R = f64> = TetheredFlexible<16, 70, R>;

impl<const N: usize, const S: usize, R: Real> Gather<R> for TetheredFlexible<N, S, R> {
    type Case = TetheredFlexible<N, S>;

    fn gather<'a>(case: &dyn Fn(usize) -> &'a Self::Case) -> Self {
        Self {
            body: Gather::gather(&|i| &case(i).body),
            density: Gather::gather(&|i| &case(i).density),
            axial_stiffness: Gather::gather(&|i| &case(i).axial_stiffness),
            axial_damping: Gather::gather(&|i| &case(i).axial_damping),
        }
    }
}

/// The Clohessy-Wiltshire field on a point mass at radial offset `px` with velocity
/// `(vx, vy)`: gravity gradient and Coriolis terms of the Hill frame (a function, not a
/// closure, so that it is always inlined into the kernel).
#[inline(always)]
fn hill_field<R: Real>(n: R, n2: R, px: R, vx: R, vy: R) -> (R, R) {
    (
        R::splat(2.0) * n * vy + R::splat(3.0) * n2 * px,
        -(R::splat(2.0) * n * vx),
    )
}

/// Adds the pull `f` of segment j to the accelerations: it pulls node j (if j >= 1) outwards
/// and node j + 1 inwards, or, for the last segment, the sub-satellite (`on_attachment`).
#[inline(always)]
fn apply_pull<const N: usize, const S: usize, R: Real>(
    dx: &mut SVector<R, S>,
    on_attachment: &mut Vector2<R>,
    inv_node: R,
    j: usize,
    f: &Vector2<R>,
) {
    if j >= 1 {
        let i = 6 + 4 * (j - 1);
        dx[i + 2] += f[0] * inv_node;
        dx[i + 3] += f[1] * inv_node;
    }
    if j < N {
        let i = 6 + 4 * j;
        dx[i + 2] -= f[0] * inv_node;
        dx[i + 3] -= f[1] * inv_node;
    } else {
        *on_attachment = neg(f);
    }
}

/// 2D cross product (z component).
#[inline(always)]
fn cross<R: Real>(a: &Vector2<R>, b: &Vector2<R>) -> R {
    a[0] * b[1] - a[1] * b[0]
}

impl<const N: usize, const S: usize> Default for TetheredFlexible<N, S> {
    /// The defaults of docs/parameters.md: a YES2-class 0.5 mm Dyneema tether.
    fn default() -> Self {
        Self {
            body: TetherBody::default(),
            density: 1.9e-4,
            axial_stiffness: 1.0e4,
            axial_damping: 5.0,
        }
    }
}

impl<const N: usize, const S: usize, R: Real> TetheredFlexible<N, S, R> {
    const LAYOUT: () = assert!(
        S == 4 * N + 6 && N >= 1 && N <= MAX_NODES,
        "the state size must be 4 N + 6, with 1 <= N <= MAX_NODES"
    );

    pub const NODES: usize = N;

    /// Rest length of one segment, h = L0 / (N + 1).
    #[inline(always)]
    pub fn segment_length(&self) -> R {
        self.body.length / ((N + 1) as f64)
    }

    /// Mass of one node, rho_t h.
    #[inline(always)]
    pub fn node_mass(&self) -> R {
        self.density * self.segment_length()
    }

    /// The sub-satellite's translational mass: m_s plus the half segment lumped at its end
    /// (so that the discretised tether keeps its whole mass, and refining N converges at
    /// second order). Its rotation keeps J = m_s a^2 / 6.
    #[inline(always)]
    pub fn end_mass(&self) -> R {
        self.body.sub_mass + R::splat(0.5) * self.node_mass()
    }

    /// Position and velocity of the tether's attachment point on the sub-satellite.
    #[inline(always)]
    pub fn attachment(&self, x: &SVector<R, S>) -> (Vector2<R>, Vector2<R>) {
        let (s, c) = x[2].sin_cos();
        self.attachment_at(x, s, c)
    }

    /// [`Self::attachment`] given the sine and cosine of the cube's attitude (computed once
    /// per derivative: the sine's rare slow path is a call, which the compiler would not
    /// merge with a second evaluation).
    #[inline(always)]
    fn attachment_at(&self, x: &SVector<R, S>, s: R, c: R) -> (Vector2<R>, Vector2<R>) {
        let half = R::splat(0.5) * self.body.side;
        (
            Vector2::new(x[0] + half * c, x[1] + half * s),
            Vector2::new(x[3] - half * x[5] * s, x[4] + half * x[5] * c),
        )
    }

    /// Point j of the chain: 0 is the main satellite, 1..=N the nodes, N + 1 the attachment
    /// (given).
    #[inline(always)]
    fn point(
        x: &SVector<R, S>,
        j: usize,
        attachment: &(Vector2<R>, Vector2<R>),
    ) -> (Vector2<R>, Vector2<R>) {
        if j == 0 {
            (zeros(), zeros())
        } else if j <= N {
            let k = 6 + 4 * (j - 1);
            (
                Vector2::new(x[k], x[k + 1]),
                Vector2::new(x[k + 2], x[k + 3]),
            )
        } else {
            *attachment
        }
    }

    /// Segment j (from point j to point j + 1): the vector `d` along it, the rate `dv` at which
    /// its ends separate, and its length.
    #[inline(always)]
    fn segment(
        x: &SVector<R, S>,
        j: usize,
        attachment: &(Vector2<R>, Vector2<R>),
    ) -> (Vector2<R>, Vector2<R>, R) {
        let (p0, v0) = Self::point(x, j, attachment);
        let (p1, v1) = Self::point(x, j + 1, attachment);
        let d = sub(&p1, &p0);
        (d, sub(&v1, &v0), (d[0] * d[0] + d[1] * d[1]).sqrt())
    }

    /// Tension of a segment `d` of length `l` (`inv_l = 1/l` where it is taut) whose ends
    /// separate at `dv`, `T = EA (l - h)/h + c_A l'/h`, and the unit vector `d / l`; zero
    /// (and a zero vector) where the segment is slack, and `T >= 0` always. `h` and `inv_h =
    /// 1/h` come from the caller ([`Prepared`] keeps them).
    #[inline(always)]
    fn pull(
        &self,
        (h, inv_h): (R, R),
        d: &Vector2<R>,
        dv: &Vector2<R>,
        l: R,
        inv_l: R,
    ) -> (R, Vector2<R>) {
        let taut = l.simd_gt(h);
        let u = scale_by(d, inv_l);
        let strain = (l - h) * inv_h;
        let rate = (u[0] * dv[0] + u[1] * dv[1]) * inv_h;
        let t = self.axial_stiffness * strain + self.axial_damping * rate;
        let zero = R::zero();
        (
            R::select(taut, t.max(zero), zero),
            Vector2::new(R::select(taut, u[0], zero), R::select(taut, u[1], zero)),
        )
    }
}

/// A flexible tether with the figures its derivative divides by, computed once when a block is
/// gathered: the segment's rest length `h` and `1/h`, `1/(rho_t h)`, the sub-satellite's
/// translational mass `m` and `1/m`, `1/J_s`, and the controller's inertia. Computed in the
/// derivative, as they were, they ran at every RK4 stage (LLVM did not hoist them out of the
/// step loop), 16 of a stage's 23 vector divisions, on the divider that the segments' square
/// roots and reciprocals keep busy (BENCHMARKS.md). They are the same operations on the same
/// values, computed once: the bits do not change.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prepared<const N: usize, const S: usize, R> {
    tether: TetheredFlexible<N, S, R>,
    h: R,
    inv_h: R,
    inv_node: R,
    end_mass: R,
    inv_end_mass: R,
    inv_moment: R,
    inertia: Vector2<R>,
}

impl<const N: usize, const S: usize, R: Real> Prepared<N, S, R> {
    #[inline(always)]
    pub fn new(tether: &TetheredFlexible<N, S, R>) -> Self {
        let () = TetheredFlexible::<N, S, R>::LAYOUT;
        let one = R::one();
        let h = tether.segment_length();
        let end_mass = tether.end_mass();
        Self {
            tether: *tether,
            h,
            inv_h: one / h,
            inv_node: one / tether.node_mass(),
            end_mass,
            inv_end_mass: one / end_mass,
            inv_moment: one / tether.body.moment_of_inertia(),
            inertia: tether.body.inertia(),
        }
    }

    /// `x'` of the chain and the sub-satellite (see the module documentation), written into
    /// `dx`: every component is set before the springs' pulls are added, so `dx` may hold
    /// anything on entry (the rollout's stage buffer; made and returned here, the 38-component
    /// state was zeroed and copied out at every stage: 15 % of W6, BENCHMARKS.md).
    #[inline(always)]
    fn chain_into(
        &self,
        x: &SVector<R, S>,
        u: &Vector2<R>,
        d: &Vector2<R>,
        dx: &mut SVector<R, S>,
    ) {
        let tether = &self.tether;
        let b = &tether.body;
        let n = b.orbital_rate;
        let n2 = n * n;
        let (h, inv_node) = (self.h, self.inv_node);
        let (s, c) = x[2].sin_cos();
        let attachment = tether.attachment_at(x, s, c);
        // Hill-frame field on every point mass; spring forces are added below
        for k in 0..N {
            let i = 6 + 4 * k;
            dx[i] = x[i + 2];
            dx[i + 1] = x[i + 3];
            let (ax, ay) = hill_field(n, n2, x[i], x[i + 2], x[i + 3]);
            dx[i + 2] = ax;
            dx[i + 3] = ay;
        }
        let mut pull_on_attachment = zeros();
        let rest = (h, self.inv_h);
        // Segments two at a time, their lengths' reciprocals from one division,
        // `1/a = b / (a b)`: the divider, shared with the square roots, bounds the step. A
        // slack segment needs no reciprocal; 1 in its place keeps the product in range (a
        // taut length is at least the rest length).
        let one = R::one();
        let mut j = 0;
        while j < N {
            let (d0, dv0, l0) = TetheredFlexible::<N, S, R>::segment(x, j, &attachment);
            let (d1, dv1, l1) = TetheredFlexible::<N, S, R>::segment(x, j + 1, &attachment);
            let a0 = R::select(l0.simd_gt(h), l0, one);
            let a1 = R::select(l1.simd_gt(h), l1, one);
            let inv = one / (a0 * a1);
            let (t0, u0) = tether.pull(rest, &d0, &dv0, l0, inv * a1);
            let (t1, u1) = tether.pull(rest, &d1, &dv1, l1, inv * a0);
            apply_pull::<N, S, R>(dx, &mut pull_on_attachment, inv_node, j, &scale_by(&u0, t0));
            apply_pull::<N, S, R>(
                dx,
                &mut pull_on_attachment,
                inv_node,
                j + 1,
                &scale_by(&u1, t1),
            );
            j += 2;
        }
        if j == N {
            let (d0, dv0, l0) = TetheredFlexible::<N, S, R>::segment(x, j, &attachment);
            let (t0, u0) = tether.pull(rest, &d0, &dv0, l0, one / l0);
            apply_pull::<N, S, R>(dx, &mut pull_on_attachment, inv_node, j, &scale_by(&u0, t0));
        }
        // the sub-satellite: thrust perpendicular to the main-to-centre line, through the centre
        let rho = (x[0] * x[0] + x[1] * x[1]).sqrt();
        let along = Vector2::new(-x[1], x[0]) / rho;
        let m = self.end_mass;
        let force = add(
            &pull_on_attachment,
            &scale_by(&along, u[0] + m * rho * d[0]),
        );
        let (ax, ay) = hill_field(n, n2, x[0], x[3], x[4]);
        let half = R::splat(0.5) * b.side;
        let arm = Vector2::new(half * c, half * s);
        dx[0] = x[3];
        dx[1] = x[4];
        dx[2] = x[5];
        dx[3] = ax + force[0] * self.inv_end_mass;
        dx[4] = ay + force[1] * self.inv_end_mass;
        dx[5] = (cross(&arm, &pull_on_attachment) + u[1]) * self.inv_moment + d[1];
    }
}

impl<const N: usize, const S: usize, R: Real> Gather<R> for Prepared<N, S, R> {
    type Case = TetheredFlexible<N, S>;

    #[inline]
    fn gather<'a>(case: &dyn Fn(usize) -> &'a TetheredFlexible<N, S>) -> Self {
        Self::new(&TetheredFlexible::<N, S, R>::gather(case))
    }

    fn same_shape(a: &TetheredFlexible<N, S>, b: &TetheredFlexible<N, S>) -> bool {
        <TetheredFlexible<N, S, R> as Gather<R>>::same_shape(a, b)
    }
}

impl<const N: usize, const S: usize, R: Real> Plant<R, 2> for Prepared<N, S, R> {
    type State = SVector<R, S>;

    #[inline(always)]
    fn coordinates(&self, x: &SVector<R, S>) -> (Vector2<R>, Vector2<R>) {
        let (px, py, vx, vy) = (x[0], x[1], x[3], x[4]);
        let phi = (-py).atan2(-px);
        let dphi = (px * vy - py * vx) / (px * px + py * py);
        (Vector2::new(phi, x[2]), Vector2::new(dphi, x[5]))
    }

    /// Nothing: the controller knows the inertia only (seed section 3.1.3).
    #[inline(always)]
    fn modelled_acceleration(&self, _t: f64, _x: &SVector<R, S>) -> Vector2<R> {
        zeros()
    }

    /// The simplified model's M: the controller does not know the flexible dynamics.
    #[inline(always)]
    fn inertia(&self, _x: &SVector<R, S>) -> Vector2<R> {
        self.inertia
    }

    #[inline(always)]
    fn actuate(&self, _x: &SVector<R, S>, acceleration: &Vector2<R>) -> Vector2<R> {
        self.tether.body.actuate_with(&self.inertia, acceleration)
    }

    #[inline(always)]
    fn derivative(
        &self,
        _t: f64,
        x: &SVector<R, S>,
        u: &Vector2<R>,
        d: &Vector2<R>,
    ) -> SVector<R, S> {
        let mut dx = zeros();
        self.chain_into(x, u, d, &mut dx);
        dx
    }

    /// `derivative`, written in place (the modelled acceleration is zero: no drift to reuse).
    #[inline(always)]
    fn derivative_into(
        &self,
        _t: f64,
        x: &SVector<R, S>,
        u: &Vector2<R>,
        d: &Vector2<R>,
        _drift: &Vector2<R>,
        dx: &mut SVector<R, S>,
    ) {
        self.chain_into(x, u, d, dx);
    }

    /// The first node must not sit on the main satellite: the tether's direction (the pitch
    /// angle the laws control) is undefined there.
    #[inline(always)]
    fn in_domain(&self, x: &SVector<R, S>) -> R::Mask {
        let zero = R::zero();
        !(x[0].simd_eq(zero) & x[1].simd_eq(zero))
    }
}

impl<const N: usize, const S: usize> TetheredFlexible<N, S> {
    /// Tension of segment j (0 at the main satellite, N at the sub-satellite), N.
    pub fn tension(&self, x: &SVector<f64, S>, j: usize) -> f64 {
        assert!(j <= N, "segment {j} of {}", N + 1);
        let (d, dv, l) = Self::segment(x, j, &self.attachment(x));
        let h = self.segment_length();
        self.pull((h, 1.0 / h), &d, &dv, l, 1.0 / l).0
    }

    /// The Jacobi integral of the Hill frame, the energy-like constant of the motion without
    /// control and damping: per mass `|v|^2 / 2 - 3 n^2 x^2 / 2`, the cube's `J omega^2 / 2`
    /// (its inertial rate is omega + n; the frame's share is a constant), and the elastic energy
    /// `EA (l - h)^2 / (2 h)` of each stretched segment.
    pub fn jacobi(&self, x: &SVector<f64, S>) -> f64 {
        let n2 = self.body.orbital_rate * self.body.orbital_rate;
        let point_mass = |m: f64, px: f64, vx: f64, vy: f64| {
            m * (0.5 * (vx * vx + vy * vy) - 1.5 * n2 * px * px)
        };
        let mut c = point_mass(self.end_mass(), x[0], x[3], x[4])
            + 0.5 * self.body.moment_of_inertia() * x[5] * x[5];
        for k in 0..N {
            let i = 6 + 4 * k;
            c += point_mass(self.node_mass(), x[i], x[i + 2], x[i + 3]);
        }
        let h = self.segment_length();
        for j in 0..=N {
            let l = Self::segment(x, j, &self.attachment(x)).2;
            if l > h {
                c += 0.5 * self.axial_stiffness * (l - h) * (l - h) / h;
            }
        }
        c
    }

    /// A state at the given angles and rates: the sub-satellite's centre at angle phi, the
    /// tether straight from the main satellite to the attachment point and stretched by the
    /// rigid dumbbell's tension, its nodes evenly spaced, every point of the line turning at
    /// phi' about the main satellite except the cube, which turns at theta'.
    pub fn state_at(
        &self,
        phi: f64,
        theta: f64,
        dphi: f64,
        dtheta: f64,
    ) -> Result<SVector<f64, S>, ParamError> {
        let () = Self::LAYOUT;
        self.validate()?;
        for (name, v) in [
            ("phi", phi),
            ("theta", theta),
            ("phi_dot", dphi),
            ("theta_dot", dtheta),
        ] {
            require(true, name, v, "finite values")?;
        }
        let b = &self.body;
        let a = b.side;
        let t0 = rigid_tension(b.sub_mass, b.length + 0.5 * a, b.orbital_rate, phi, dphi);
        let l = b.length * (1.0 + t0 / self.axial_stiffness);
        // |rho e(phi) - (a/2) e(theta)| = l, with e(x) = -(cos x, sin x)
        let cd = (theta - phi).cos();
        let rho = 0.5 * (a * cd + (a * a * cd * cd - a * a + 4.0 * l * l).sqrt());
        let (sp, cp) = phi.sin_cos();
        let r = Vector2::new(-rho * cp, -rho * sp);
        let v = Vector2::new(-r[1], r[0]) * dphi;
        let mut x = SVector::<f64, S>::zeros();
        x[0] = r[0];
        x[1] = r[1];
        x[2] = theta;
        x[3] = v[0];
        x[4] = v[1];
        x[5] = dtheta;
        let (pa, va) = self.attachment(&x);
        for k in 0..N {
            let f = (k + 1) as f64 / (N + 1) as f64;
            let i = 6 + 4 * k;
            x[i] = pa[0] * f;
            x[i + 1] = pa[1] * f;
            x[i + 2] = va[0] * f;
            x[i + 3] = va[1] * f;
        }
        Ok(x)
    }

    /// The largest RK4 step that keeps the tether's fastest axial mode stable. A node between
    /// two segments has stiffness and damping eigenvalues up to K = 4 k / m and C = 4 c / m
    /// (k = EA / h, c = c_A / h); the mode's roots of `l^2 + C l + K = 0` have modulus
    /// `sqrt(K)` when complex and `(C + sqrt(C^2 - 4 K)) / 2` at most when real. RK4's stability
    /// region reaches |lambda| dt = 2.5 in every left-half-plane direction.
    pub fn max_step(&self) -> f64 {
        let h = self.segment_length();
        let m = self.node_mass();
        let k = 4.0 * self.axial_stiffness / (h * m);
        let c = 4.0 * self.axial_damping / (h * m);
        let lambda = if c * c <= 4.0 * k {
            k.sqrt()
        } else {
            0.5 * (c + (c * c - 4.0 * k).sqrt())
        };
        2.5 / lambda
    }
}

/// The one-case plant is its prepared form, the reciprocals computed per call.
impl<const N: usize, const S: usize, R: Real> Plant<R, 2> for TetheredFlexible<N, S, R> {
    type State = SVector<R, S>;

    fn coordinates(&self, x: &SVector<R, S>) -> (Vector2<R>, Vector2<R>) {
        Prepared::new(self).coordinates(x)
    }

    fn modelled_acceleration(&self, t: f64, x: &SVector<R, S>) -> Vector2<R> {
        Prepared::new(self).modelled_acceleration(t, x)
    }

    fn inertia(&self, x: &SVector<R, S>) -> Vector2<R> {
        Prepared::new(self).inertia(x)
    }

    fn actuate(&self, x: &SVector<R, S>, acceleration: &Vector2<R>) -> Vector2<R> {
        Prepared::new(self).actuate(x, acceleration)
    }

    fn derivative(
        &self,
        t: f64,
        x: &SVector<R, S>,
        u: &Vector2<R>,
        d: &Vector2<R>,
    ) -> SVector<R, S> {
        Prepared::new(self).derivative(t, x, u, d)
    }

    fn in_domain(&self, x: &SVector<R, S>) -> R::Mask {
        Prepared::new(self).in_domain(x)
    }
}

impl<const N: usize, const S: usize> PlantModel<2> for TetheredFlexible<N, S> {
    type At<R: Real> = Prepared<N, S, R>;
    type Blocks = crate::kernel::Narrow;
    const STATE_NAMES: &'static [&'static str] = NAMES.split_at(S).0;
    const CONTROL_NAMES: &'static [&'static str] = &["thrust", "torque"];

    fn figures(&self) -> Vec<(&'static str, Vec<f64>)> {
        let mut f = self.body.figures();
        f.push(("nodes", vec![N as f64]));
        f.push(("segment_length", vec![self.segment_length()]));
        f
    }

    fn max_step(&self) -> f64 {
        TetheredFlexible::max_step(self)
    }

    /// The tether laid straight and stretched by the rigid dumbbell's tension
    /// ([`TetheredFlexible::state_at`]).
    fn state_at(
        &self,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Option<Result<Vec<f64>, ParamError>> {
        Some(
            TetheredFlexible::state_at(self, q[0], q[1], qd[0], qd[1])
                .map(|x| x.as_slice().to_vec()),
        )
    }

    fn check_initial(&self, x: &[f64]) -> Result<(), ParamError> {
        for (i, v) in x.iter().enumerate() {
            require(true, "x0", *v, "finite values").map_err(|e| e.on_axis(i))?;
        }
        let rho = x[0].hypot(x[1]);
        require(
            rho > 0.0,
            "x0",
            rho,
            "the sub-satellite away from the main satellite, hypot(x0[0], x0[1]) > 0",
        )
    }
}

impl<const N: usize, const S: usize> Validate for TetheredFlexible<N, S> {
    fn validate(&self) -> Result<(), ParamError> {
        let () = Self::LAYOUT;
        self.body.validate()?;
        check(&TETHER_DENSITY, self.density, |v| v > 0.0)?;
        check(&AXIAL_STIFFNESS, self.axial_stiffness, |v| v > 0.0)?;
        check(&AXIAL_DAMPING, self.axial_damping, |v| v >= 0.0)
    }
}

impl<const N: usize, const S: usize> FromParams for TetheredFlexible<N, S> {
    /// The shared body and the tether (`nodes` itself picks the type, in the registry).
    fn from_params<Src: ParamSource>(p: &mut Src) -> Result<Self, ReadError> {
        p.skip(&NODES);
        Ok(Self {
            body: TetherBody::from_params(p)?,
            density: p.scalar(&TETHER_DENSITY)?,
            axial_stiffness: p.scalar(&AXIAL_STIFFNESS)?,
            axial_damping: p.scalar(&AXIAL_DAMPING)?,
        })
    }
}
