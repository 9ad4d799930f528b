//! Fixed-time nonsingular terminal sliding mode with RBF compensation (seed 003 eq. 19-24;
//! ), the seed's "FNTSMC".
//!
//! ```text
//! s   = e2 + K1 zeta1(e1) + K2 zeta2(e1)                                        (eq. 20)
//! zeta_k(e1) = sig^pk(e1)                 for |e1| > sigma_phi                  (eq. 21)
//!            = l_k e1 + m_k sig^2(e1)     for |e1| <= sigma_phi
//!   l_k = (2 - p_k) sigma_phi^(p_k - 1),  m_k = (p_k - 1) sigma_phi^(p_k - 2)
//! u   = -M (K1 zeta1' + K2 zeta2' + K3 (sig^as(s) + sig^bs(s))) - W^T Phi(z) - eps_max sign(s)
//!                                                                               (eq. 22, 23)
//! W'  = Gamma N Phi(z),  N = M^-1 K3 (sig^(2as-1)(s) + sig^(2bs-1)(s))           (eq. 24)
//! ```
//! with e1 = q - q_d, e2 = q' - q_d', p1 > 1 > p2 > 0, 1/2 < as < 1 < bs. The law drives
//! `s' = -K3 (sig^as(s) + sig^bs(s)) + M^-1 (f - W^T Phi - eps_max sign(s))` on the plant
//! `M q'' = u + f` (eq. 17, 19), so the network's output W^T Phi estimates the unknown f in the
//! actuators' units (N, N m). The command returned is u / M plus the reference acceleration
//! minus the plant's modelled drift (both zero on the tethered satellite).
//!
//! The weights are the law's memory, advanced once per control period by forward Euler after
//! the command. Gamma is `gamma I` per axis; each axis has its own network
//! (`rbf.rs`), initially zero. The seed does not print Gamma, the centres, widths or node count:
//! they come from examples/studies/tether_rbf.py (docs/parameters.md).
//!
//! Singularity guard: sigma_phi. Outside it the slope `p2 |e1|^(p2 - 1)` is finite; inside,
//! zeta is the quadratic whose value and slope match sig^p at |e1| = sigma_phi (Remark 3).
//!
//! Table 2 of the seed prints alpha_s = (1.1, 1.8), beta_s = (0.89, 0.7), against its own
//! ranges as in (1/2, 1), bs in (1, 3/2). The law is symmetric in the two exponents (u and N
//! use sig^as + sig^bs), so the swap changes nothing but the names: the presets store them in
//! the text's roles, as = (0.89, 0.7), bs = (1.1, 1.8). The upper limit 3/2 on bs plays no
//! part in the proof (only 2 bs > max(1, bs), true for any bs > 1) and Table 2's own 1.8
//! breaks it, so the validation asks bs > 1 only.
//!
//! Meaningful on any fully actuated plant; on the 3-axis ones each axis has its own network.

use nalgebra::{SMatrix, SVector};

use super::rbf::{self, MAX_GRID, MAX_NODES};
use super::{ControlLaw, LawInput};
use crate::error::{ParamError, ReadError, Validate, check, check_axes};
use crate::lanes::axes::Axes;
use crate::lanes::math::PowLog;
use crate::lanes::slots::Slots;
use crate::lanes::{Mask, Real, sub, zeros};
use crate::math::sgn;
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

/// zeta of eq. 21 with exponent p and threshold sigma (one case).
#[inline(always)]
pub fn zeta(e: f64, p: f64, sigma: f64) -> f64 {
    ZetaPair::new(e, [p, p], sigma).zeta[0]
}

/// d zeta / d e1 (one case); eq. 23's zeta' is this times e2.
#[inline(always)]
pub fn zeta_slope(e: f64, p: f64, sigma: f64) -> f64 {
    ZetaPair::new(e, [p, p], sigma).slope[0]
}

/// zeta_1, zeta_2 of eq. 21 and their slopes at e1, for the exponents p1, p2 and the
/// threshold sigma of one axis. Outside the threshold the powers of |e1| share one logarithm;
/// inside, the quadratic's coefficients (powers of sigma) are computed only when some lane is
/// there.
#[derive(Clone, Copy, Debug)]
struct ZetaPair<R> {
    zeta: [R; 2],
    slope: [R; 2],
}

impl<R: Real> ZetaPair<R> {
    #[inline(always)]
    fn new(e: R, p: [R; 2], sigma: R) -> Self {
        let a = e.abs();
        let l = PowLog::of(a);
        let sign = e.signum0();
        let outside = a.simd_gt(sigma);
        let mut zeta = [R::zero(); 2];
        let mut slope = [R::zero(); 2];
        for k in 0..2 {
            // |e|^p and p |e|^(p-1) = p |e|^p / |e|
            let pw = l.pow(p[k]);
            zeta[k] = sign * pw;
            slope[k] = p[k] * pw / a;
        }
        if !outside.all() {
            let ls = PowLog::of(sigma);
            for k in 0..2 {
                // l_k = (2 - p) sigma^(p - 1), m_k = (p - 1) sigma^(p - 2)
                let s1 = ls.pow(p[k] - 1.0);
                let lk = (R::splat(2.0) - p[k]) * s1;
                let mk = (p[k] - 1.0) * (s1 / sigma);
                zeta[k] = R::select(outside, zeta[k], lk * e + mk * e * a);
                slope[k] = R::select(outside, slope[k], lk + R::splat(2.0) * mk * a);
            }
        }
        Self { zeta, slope }
    }
}

const K1: Param = Param::axes("k1")
    .unit("q^(1 - p1)/s")
    .rule("k1 > 0")
    .doc("gain of zeta1 in the surface s = e2 + k1 zeta1(e1) + k2 zeta2(e1)");
const K2: Param = Param::axes("k2")
    .unit("q^(1 - p2)/s")
    .rule("k2 > 0")
    .doc("gain of zeta2 in the surface");
const K3: Param = Param::axes("k3")
    .unit("1/s")
    .rule("k3 > 0")
    .doc("gain of the reaching law sig^alpha_s(s) + sig^beta_s(s)");
const EPS_MAX: Param = Param::axes("eps_max")
    .unit("N, N m")
    .rule("eps_max >= 0")
    .doc("bound of the network's approximation error, in actuator units");
const P1: Param = Param::axes("p1")
    .unit("1")
    .rule("p1 > 1")
    .doc("exponent of zeta1, above 1");
const P2: Param = Param::axes("p2")
    .unit("1")
    .rule("0 < p2 < 1")
    .doc("exponent of zeta2, below 1");
const ALPHA_S: Param = Param::axes("alpha_s")
    .unit("1")
    .rule("1/2 < alpha_s < 1")
    .doc("exponent of the reaching law, below 1");
const BETA_S: Param = Param::axes("beta_s")
    .unit("1")
    .rule("beta_s > 1")
    .doc("exponent of the reaching law, above 1");
const SIGMA_PHI: Param = Param::axes("sigma_phi")
    .unit("q")
    .rule("sigma_phi > 0")
    .doc("singularity guard: the threshold inside which zeta is the matching quadratic");
const GAMMA: Param = Param::axes("gamma")
    .unit("1")
    .rule("gamma >= 0")
    .doc("adaptation gain of the network (Gamma = gamma I); 0 switches it off");
const RBF_NODES: Param = Param::count("rbf_nodes", &[1, 2, 3, 4, 5, 6, 7])
    .unit("1")
    .rule("rbf_nodes in 1..=7")
    .doc("centres per input of each axis's network (rbf_nodes^2 nodes), shared by the cases");
const RBF_SCALE_E1: Param = Param::axes("rbf_scale_e1")
    .unit("q")
    .rule("rbf_scale_e1 > 0")
    .doc("e1 at the edge of the centre grid");
const RBF_SCALE_E2: Param = Param::axes("rbf_scale_e2")
    .unit("q/s")
    .rule("rbf_scale_e2 > 0")
    .doc("e2 at the edge of the centre grid");
const RBF_WIDTH: Param = Param::axes("rbf_width")
    .unit("1")
    .rule("rbf_width > 0")
    .doc("Gaussian width b on the normalised inputs");

/// Gains per axis with the seed's symbols; `gamma` is Gamma's diagonal value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedTimeNtsmc<const D: usize, R = f64> {
    pub k1: SVector<R, D>,
    pub k2: SVector<R, D>,
    pub k3: SVector<R, D>,
    /// Bound of the network's approximation error, in actuator units (N, N m).
    pub eps_max: SVector<R, D>,
    pub p1: SVector<R, D>,
    pub p2: SVector<R, D>,
    pub alpha_s: SVector<R, D>,
    pub beta_s: SVector<R, D>,
    pub sigma_phi: SVector<R, D>,
    /// Adaptation gain Gamma = gamma I; 0 switches the network off.
    pub gamma: SVector<R, D>,
    /// Centres per input of each axis's network (rbf_nodes^2 nodes), 1..=7. Shared by a block.
    pub rbf_nodes: usize,
    /// e1 and e2 at the edge of the centre grid: the inputs are e1 / rbf_scale_e1 and
    /// e2 / rbf_scale_e2.
    pub rbf_scale_e1: SVector<R, D>,
    pub rbf_scale_e2: SVector<R, D>,
    /// Gaussian width b on the normalised inputs.
    pub rbf_width: SVector<R, D>,
}

crate::gather_struct!(FixedTimeNtsmc<const D: usize, R> {
    lanes: [
        k1, k2, k3, eps_max, p1, p2, alpha_s, beta_s, sigma_phi, gamma, rbf_scale_e1,
        rbf_scale_e2, rbf_width,
    ],
    shared: [rbf_nodes],
});

/// What the law computes at one instant, every axis at once ([`Axes`]: the same operations lane
/// by lane as axis after axis, so the same bits, with D times the independent work for the
/// processor between the logarithms and exponentials of each step).
#[derive(Clone, Copy, Debug)]
struct Surfaces<'p, const D: usize, R> {
    s: Axes<R, D>,
    /// ln |s|, shared by the powers of s in the reaching law and the adaptation
    ln_abs_s: PowLog<Axes<R, D>>,
    /// K1 zeta1' + K2 zeta2'
    surface_rate: Axes<R, D>,
    /// the network's basis, rbf_nodes^2 entries
    phi: &'p [Axes<R, D>],
}

/// `sig^a(s)` from the logarithm of |s| (0 at s = 0 for a > 0).
#[inline(always)]
fn sig_from_ln<R: Real>(s: R, ln_abs: PowLog<R>, a: R) -> R {
    sgn(s) * ln_abs.pow(a)
}

impl<const D: usize, R: Real> FixedTimeNtsmc<D, R> {
    #[inline(always)]
    fn surfaces<'p>(
        &self,
        input: &LawInput<D, R>,
        phi: &'p mut Slots<Axes<R, D>, MAX_NODES>,
    ) -> Surfaces<'p, D, R> {
        let (e1, e2) = (Axes::of(&input.e), Axes::of(&input.de));
        let (k1, k2) = (Axes::of(&self.k1), Axes::of(&self.k2));
        let p = [Axes::of(&self.p1), Axes::of(&self.p2)];
        let z = ZetaPair::new(e1, p, Axes::of(&self.sigma_phi));
        let s = e2 + k1 * z.zeta[0] + k2 * z.zeta[1];
        let surface_rate = (k1 * z.slope[0] + k2 * z.slope[1]) * e2;
        let zn = [
            e1 / Axes::of(&self.rbf_scale_e1),
            e2 / Axes::of(&self.rbf_scale_e2),
        ];
        Surfaces {
            s,
            ln_abs_s: PowLog::of(s.abs()),
            surface_rate,
            phi: rbf::basis(self.rbf_nodes, zn, Axes::of(&self.rbf_width), phi),
        }
    }

    /// The sliding variable s per axis (eq. 20).
    #[inline(always)]
    pub fn s(&self, input: &LawInput<D, R>) -> SVector<R, D> {
        let mut phi = Slots::EMPTY;
        self.surfaces(input, &mut phi).s.vector()
    }

    /// The network's estimate W^T Phi of the unknown terms per axis, in actuator units.
    pub fn estimate(
        &self,
        weights: &SMatrix<R, MAX_NODES, D>,
        input: &LawInput<D, R>,
    ) -> SVector<R, D> {
        let mut phi = Slots::EMPTY;
        self.outputs(weights, self.surfaces(input, &mut phi).phi)
            .vector()
    }

    /// W^T Phi on every axis, each axis's sum in node order.
    #[inline(always)]
    fn outputs(&self, weights: &SMatrix<R, MAX_NODES, D>, phi: &[Axes<R, D>]) -> Axes<R, D> {
        let mut sum = [R::zero(); D];
        for (i, total) in sum.iter_mut().enumerate() {
            for (j, phi) in phi.iter().enumerate() {
                *total += weights[(j, i)] * phi.0[i];
            }
        }
        Axes(sum)
    }

    /// The command (eq. 22, 23) with the weights before this period's update.
    #[inline(always)]
    fn command_at(
        &self,
        weights: &SMatrix<R, MAX_NODES, D>,
        input: &LawInput<D, R>,
        sf: &Surfaces<'_, D, R>,
    ) -> SVector<R, D> {
        let reach = Axes::of(&self.k3)
            * (sig_from_ln(sf.s, sf.ln_abs_s, Axes::of(&self.alpha_s))
                + sig_from_ln(sf.s, sf.ln_abs_s, Axes::of(&self.beta_s)));
        let compensation = self.outputs(weights, sf.phi) + Axes::of(&self.eps_max) * sgn(sf.s);
        let a = Axes::of(&sub(&input.reference.acceleration, &input.drift));
        (a - (sf.surface_rate + reach + compensation / Axes::of(&input.inertia))).vector()
    }

    /// Whether some axis adapts its weights in some lane (Gamma != 0).
    #[inline(always)]
    fn adapts(&self) -> bool {
        !(0..D).all(|i| self.gamma[i].simd_eq(R::zero()).all())
    }

    /// The weights' update over one period (eq. 24, forward Euler).
    #[inline(always)]
    fn adapt(
        &self,
        weights: &mut SMatrix<R, MAX_NODES, D>,
        input: &LawInput<D, R>,
        sf: &Surfaces<'_, D, R>,
    ) {
        // 2 as - 1 > 0 and 2 bs - 1 > 1: both powers are finite at s = 0
        let two = <Axes<R, D> as Real>::splat(2.0);
        let big_n = Axes::of(&self.k3)
            * (sig_from_ln(sf.s, sf.ln_abs_s, two * Axes::of(&self.alpha_s) - 1.0)
                + sig_from_ln(sf.s, sf.ln_abs_s, two * Axes::of(&self.beta_s) - 1.0))
            / Axes::of(&input.inertia);
        for i in 0..D {
            if self.gamma[i].simd_eq(R::zero()).all() {
                continue;
            }
            let step = R::splat(input.dt) * self.gamma[i] * big_n.0[i];
            for (j, phi) in sf.phi.iter().enumerate() {
                weights[(j, i)] += step * phi.0[i];
            }
        }
    }
}

impl<const D: usize, R: Real> ControlLaw<R, D> for FixedTimeNtsmc<D, R> {
    /// The network weights, one column per axis (rows past rbf_nodes^2 stay zero).
    type Memory = SMatrix<R, MAX_NODES, D>;
    const DIAGNOSTICS: &'static [&'static str] = &["s", "rbf"];
    const COMMANDS_AND_ADVANCES: bool = true;

    #[inline(always)]
    fn start(&self, _input: &LawInput<D, R>) -> Self::Memory {
        zeros()
    }

    #[inline(always)]
    fn command(&self, weights: &Self::Memory, input: &LawInput<D, R>) -> SVector<R, D> {
        let mut phi = Slots::EMPTY;
        self.command_at(weights, input, &self.surfaces(input, &mut phi))
    }

    #[inline(always)]
    fn advance(&self, weights: &mut Self::Memory, input: &LawInput<D, R>) {
        // Gamma = 0 leaves the weights where they are (w + 0 phi = w): skip the work
        if self.adapts() {
            let mut phi = Slots::EMPTY;
            self.adapt(weights, input, &self.surfaces(input, &mut phi));
        }
    }

    /// The surfaces and the network's basis once for both (they were a third of the law's
    /// work, computed twice: BENCHMARKS.md).
    #[inline(always)]
    fn command_and_advance(
        &self,
        weights: &mut Self::Memory,
        input: &LawInput<D, R>,
    ) -> SVector<R, D> {
        let mut phi = Slots::EMPTY;
        let sf = self.surfaces(input, &mut phi);
        let u = self.command_at(weights, input, &sf);
        if self.adapts() {
            self.adapt(weights, input, &sf);
        }
        u
    }

    #[inline(always)]
    fn diagnostics(&self, weights: &Self::Memory, input: &LawInput<D, R>, out: &mut [R]) {
        let mut phi = Slots::EMPTY;
        let sf = self.surfaces(input, &mut phi);
        let estimate = self.outputs(weights, sf.phi);
        out[..D].copy_from_slice(&sf.s.0);
        out[D..2 * D].copy_from_slice(&estimate.0);
    }
}

impl<const D: usize> Validate for FixedTimeNtsmc<D> {
    fn validate(&self) -> Result<(), ParamError> {
        check_axes(&K1, self.k1.as_slice(), |v| v > 0.0)?;
        check_axes(&K2, self.k2.as_slice(), |v| v > 0.0)?;
        check_axes(&K3, self.k3.as_slice(), |v| v > 0.0)?;
        check_axes(&EPS_MAX, self.eps_max.as_slice(), |v| v >= 0.0)?;
        check_axes(&P1, self.p1.as_slice(), |v| v > 1.0)?;
        check_axes(&P2, self.p2.as_slice(), |v| v > 0.0 && v < 1.0)?;
        check_axes(&ALPHA_S, self.alpha_s.as_slice(), |v| v > 0.5 && v < 1.0)?;
        check_axes(&BETA_S, self.beta_s.as_slice(), |v| v > 1.0)?;
        check_axes(&SIGMA_PHI, self.sigma_phi.as_slice(), |v| v > 0.0)?;
        check_axes(&GAMMA, self.gamma.as_slice(), |v| v >= 0.0)?;
        check(&RBF_NODES, self.rbf_nodes as f64, |_| {
            (1..=MAX_GRID).contains(&self.rbf_nodes)
        })?;
        check_axes(&RBF_SCALE_E1, self.rbf_scale_e1.as_slice(), |v| v > 0.0)?;
        check_axes(&RBF_SCALE_E2, self.rbf_scale_e2.as_slice(), |v| v > 0.0)?;
        check_axes(&RBF_WIDTH, self.rbf_width.as_slice(), |v| v > 0.0)
    }
}

impl<const D: usize> Declared for FixedTimeNtsmc<D> {
    const SCHEMA: Schema = Schema::new(&[
        K1,
        K2,
        K3,
        EPS_MAX,
        P1,
        P2,
        ALPHA_S,
        BETA_S,
        SIGMA_PHI,
        GAMMA,
        RBF_NODES,
        RBF_SCALE_E1,
        RBF_SCALE_E2,
        RBF_WIDTH,
    ]);
}

impl<const D: usize> FromParams for FixedTimeNtsmc<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            k1: p.axes(&K1)?,
            k2: p.axes(&K2)?,
            k3: p.axes(&K3)?,
            eps_max: p.axes(&EPS_MAX)?,
            p1: p.axes(&P1)?,
            p2: p.axes(&P2)?,
            alpha_s: p.axes(&ALPHA_S)?,
            beta_s: p.axes(&BETA_S)?,
            sigma_phi: p.axes(&SIGMA_PHI)?,
            gamma: p.axes(&GAMMA)?,
            rbf_nodes: p.count(&RBF_NODES)?,
            rbf_scale_e1: p.axes(&RBF_SCALE_E1)?,
            rbf_scale_e2: p.axes(&RBF_SCALE_E2)?,
            rbf_width: p.axes(&RBF_WIDTH)?,
        })
    }
}
