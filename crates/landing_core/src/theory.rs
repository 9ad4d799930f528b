//! Convergence bounds of the sliding-mode laws: the fixed-time laws of seed 001 (sections II and
//! III; docs/reproduction-mars.md) and seed 003, and seed 000's terminal reaching times.
//!
//! Every bound here is checked against simulation by `landing.theory` in Python.

use crate::error::{ParamError, require};

/// Lemma 2 with k = 1 on V = s^2 / 2 for the scalar reaching law
/// `s' = -c1 sig^e1(s) - c2 sig^e2(s)`, 0 < e1 < 1 < e2 (seed eq. 3, 18, 26):
///
/// `T <= 1 / (c1 (1 - e1) 2^((e1 - 1)/2)) + 1 / (c2 (e2 - 1) 2^((e2 - 1)/2))`,
///
/// whatever s(0). (V' = -c1 2^((e1+1)/2) V^((e1+1)/2) - ..., and Lemma 2's
/// `1/(alpha (1 - p)) + 1/(beta (g - 1))` with p = (e1+1)/2, g = (e2+1)/2.)
pub fn fixed_time_bound(c1: f64, e1: f64, c2: f64, e2: f64) -> Result<f64, ParamError> {
    check_reaching(c1, e1, c2, e2)?;
    Ok(1.0 / (c1 * (1.0 - e1) * 2f64.powf((e1 - 1.0) / 2.0))
        + 1.0 / (c2 * (e2 - 1.0) * 2f64.powf((e2 - 1.0) / 2.0)))
}

fn check_reaching(c1: f64, e1: f64, c2: f64, e2: f64) -> Result<(), ParamError> {
    require(c1 > 0.0, "c1", c1, "c1 > 0")?;
    require(c2 > 0.0, "c2", c2, "c2 > 0")?;
    require(e1 > 0.0 && e1 < 1.0, "e1", e1, "0 < e1 < 1")?;
    require(e2 > 1.0, "e2", e2, "e2 > 1")
}

fn check_theta(theta: f64) -> Result<(), ParamError> {
    require(theta > 0.0 && theta < 1.0, "theta", theta, "0 < theta < 1")
}

/// Theorem 1 (k = 1) for `s' = -c1 sig^e1(s) - c2 sig^e2(s) + d`, |d| <= d_max: the time to
/// reach the neighbourhood of [`practical_radius`], `fixed_time_bound / theta` (seed eq. 6, 40).
pub fn practical_time_bound(
    c1: f64,
    e1: f64,
    c2: f64,
    e2: f64,
    theta: f64,
) -> Result<f64, ParamError> {
    check_theta(theta)?;
    Ok(fixed_time_bound(c1, e1, c2, e2)? / theta)
}

/// The neighbourhood that `s' = -c1 sig^e1(s) - c2 sig^e2(s) + d`, |d| <= d_max, reaches and
/// keeps (seed eq. 38, 39): outside it `(1 - theta)(c1 |s|^e1 + c2 |s|^e2) >= d_max`, so V
/// decreases at least at the rate of the law with gains theta c1, theta c2. Hence
/// `|s| <= min{(d_max / ((1 - theta) c1))^(1/e1), (d_max / ((1 - theta) c2))^(1/e2)}`.
pub fn practical_radius(
    c1: f64,
    e1: f64,
    c2: f64,
    e2: f64,
    d_max: f64,
    theta: f64,
) -> Result<f64, ParamError> {
    check_reaching(c1, e1, c2, e2)?;
    check_theta(theta)?;
    require(d_max >= 0.0, "d_max", d_max, "d_max >= 0")?;
    let k = d_max / (1.0 - theta);
    Ok((k / c1).powf(1.0 / e1).min((k / c2).powf(1.0 / e2)))
}

/// Bounds of the fixed-time MSS guidance on one axis (seed Theorems 2 to 4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MssBounds {
    /// Eq. 18: time for s1 to reach 0 once on s2 = 0.
    pub t1: f64,
    /// Eq. 26: time for s2 to reach 0 from anywhere (no disturbance).
    pub t2: f64,
    /// Eq. 39: neighbourhood of s2 under |a_p| <= ap_max.
    pub s2_radius: f64,
    /// Eq. 40: time to reach it.
    pub s2_time: f64,
    /// Eq. 31: neighbourhood of s1 = r - r_d once s2 is in its neighbourhood.
    pub s1_radius: f64,
    /// Eq. 45: time for s1 to reach its neighbourhood once s2 is in its own.
    pub s1_time: f64,
    /// Eq. 32 as printed: `max(s2_time, s1_time)`. s1 only follows its perturbed reaching law
    /// once s2 is in its neighbourhood, so the times add up: see [`MssBounds::settle_time`].
    pub printed_time: f64,
}

impl MssBounds {
    /// A sound bound on the time after which s1 stays in its neighbourhood: s2 first reaches
    /// its own (s2_time), then s1 reaches its (s1_time).
    pub fn settle_time(&self) -> f64 {
        self.s2_time + self.s1_time
    }

    /// Each bound by its field's name, with the settle time (as the bindings hand them out).
    pub fn named(&self) -> [(&'static str, f64); 8] {
        [
            ("t1", self.t1),
            ("t2", self.t2),
            ("s2_radius", self.s2_radius),
            ("s2_time", self.s2_time),
            ("s1_radius", self.s1_radius),
            ("s1_time", self.s1_time),
            ("printed_time", self.printed_time),
            ("settle_time", self.settle_time()),
        ]
    }
}

/// Seed 001's bounds for one axis of `FixedTimeMss` with gains
/// (beta1, q1, beta2, q2, alpha1, gamma1, alpha2, gamma2), disturbance bound `ap_max` on that
/// axis and the splitting constants theta1 (for s2) and theta2 (for s1).
#[allow(clippy::too_many_arguments)]
pub fn mss_bounds(
    beta1: f64,
    q1: f64,
    beta2: f64,
    q2: f64,
    alpha1: f64,
    gamma1: f64,
    alpha2: f64,
    gamma2: f64,
    ap_max: f64,
    theta1: f64,
    theta2: f64,
) -> Result<MssBounds, ParamError> {
    let rename = |e: ParamError, names: [&'static str; 4]| {
        let param = match e.param {
            "c1" => names[0],
            "e1" => names[1],
            "c2" => names[2],
            "e2" => names[3],
            "theta" => names[0],
            other => other,
        };
        ParamError { param, ..e }
    };
    let s1_names = ["beta1", "q1", "beta2", "q2"];
    let s2_names = ["alpha1", "gamma1", "alpha2", "gamma2"];
    let t1 = fixed_time_bound(beta1, q1, beta2, q2).map_err(|e| rename(e, s1_names))?;
    let t2 = fixed_time_bound(alpha1, gamma1, alpha2, gamma2).map_err(|e| rename(e, s2_names))?;
    check_theta(theta1).map_err(|e| ParamError {
        param: "theta1",
        ..e
    })?;
    check_theta(theta2).map_err(|e| ParamError {
        param: "theta2",
        ..e
    })?;
    require(ap_max >= 0.0, "ap_max", ap_max, "ap_max >= 0")?;
    let s2_radius = practical_radius(alpha1, gamma1, alpha2, gamma2, ap_max, theta1)?;
    let s2_time = t2 / theta1;
    let s1_radius = practical_radius(beta1, q1, beta2, q2, s2_radius, theta2)?;
    let s1_time = t1 / theta2;
    Ok(MssBounds {
        t1,
        t2,
        s2_radius,
        s2_time,
        s1_radius,
        s1_time,
        printed_time: s2_time.max(s1_time),
    })
}

/// Seed 001 Remark 1, written sign-consistently for any initial state: lower bounds on the
/// final time under an acceleration limit `a_max` on one axis with gravity `g` on that axis
/// (negative for z up).
///
/// - `tf1`: the first time the position can reach 0, pushing at full thrust towards the target
///   with gravity: the smallest positive root of `r0 + v0 t + (a t^2)/2 = 0`,
///   `a = -sgn(r0) a_max + g`. (The seed prints `(-v0 + sqrt(v0^2 - 2 a_max r0)) / a_max`,
///   its root for r0 < 0 without gravity.)
/// - `tf2`: the time to null the velocity at full thrust against it,
///   `|v0| / (a_max - sgn(v0) g)` (the seed's `-v0 / (a_max - g)` for a falling lander with g
///   taken positive).
///
/// Either is infinite when the thrust cannot overcome gravity in the needed direction.
pub fn min_final_time(r0: f64, v0: f64, a_max: f64, g: f64) -> Result<(f64, f64), ParamError> {
    require(a_max > 0.0, "a_max", a_max, "a_max > 0")?;
    require(true, "r0", r0, "finite values")?;
    require(true, "v0", v0, "finite values")?;
    require(true, "g", g, "finite values")?;
    let tf1 = if r0 == 0.0 {
        0.0
    } else {
        let a = -r0.signum() * a_max + g;
        smallest_positive_root(0.5 * a, v0, r0)
    };
    let tf2 = if v0 == 0.0 {
        0.0
    } else {
        let decel = a_max - v0.signum() * g;
        if decel > 0.0 {
            v0.abs() / decel
        } else {
            f64::INFINITY
        }
    };
    Ok((tf1, tf2))
}

/// The shortest time to bring one axis from (r0, v0) to rest at 0 with the acceleration
/// limited to `[g - a_max, g + a_max]` (thrust up to `a_max` either way plus gravity `g`):
/// the bang-bang solution of the time-optimal double integrator, one switch. Infinite when the
/// thrust cannot overcome gravity. A true lower bound on any landing time on that axis when
/// `a_max` is the largest acceleration the engine can give (thrust limit over the smallest
/// mass).
pub fn min_time_to_rest(r0: f64, v0: f64, a_max: f64, g: f64) -> Result<f64, ParamError> {
    require(a_max > 0.0, "a_max", a_max, "a_max > 0")?;
    require(true, "r0", r0, "finite values")?;
    require(true, "v0", v0, "finite values")?;
    require(true, "g", g, "finite values")?;
    let (up, down) = (g + a_max, g - a_max);
    if up <= 0.0 || down >= 0.0 {
        return Ok(f64::INFINITY);
    }
    if r0 == 0.0 && v0 == 0.0 {
        return Ok(0.0);
    }
    let mut best = f64::INFINITY;
    // accelerate with `a` for t1, then with `b` (opposite sign) for t2 down to rest at 0:
    // the second arc ends at the origin, so x1 = v1^2 / (2 b) with v1 = v0 + a t1
    for (a, b) in [(up, down), (down, up)] {
        // r0 + v0 t + a t^2 / 2 = (v0 + a t)^2 / (2 b)
        let qa = 0.5 * a - a * a / (2.0 * b);
        let qb = v0 - v0 * a / b;
        let qc = r0 - v0 * v0 / (2.0 * b);
        for t1 in nonnegative_roots(qa, qb, qc) {
            let t2 = -(v0 + a * t1) / b;
            if t2 >= -1e-12 {
                best = best.min(t1 + t2.max(0.0));
            }
        }
    }
    Ok(best)
}

/// Non-negative roots of `a t^2 + b t + c = 0`.
fn nonnegative_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(2);
    if a == 0.0 {
        if b != 0.0 && -c / b >= 0.0 {
            out.push(-c / b);
        }
        return out;
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return out;
    }
    let q = -0.5 * (b + if b >= 0.0 { 1.0 } else { -1.0 } * disc.sqrt());
    for t in [q / a, if q != 0.0 { c / q } else { 0.0 }] {
        if t >= 0.0 {
            out.push(t);
        }
    }
    out
}

/// Smallest positive root of `a t^2 + b t + c = 0` (infinite if none).
fn smallest_positive_root(a: f64, b: f64, c: f64) -> f64 {
    let mut best = f64::INFINITY;
    let mut consider = |t: f64| {
        if t > 0.0 && t < best {
            best = t;
        }
    };
    if a == 0.0 {
        if b != 0.0 {
            consider(-c / b);
        }
        return best;
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return best;
    }
    // numerically stable pair of roots
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q != 0.0 {
        consider(q / a);
        consider(c / q);
    } else {
        consider(0.0);
    }
    best
}

// Seed 003: the fixed-time NTSMC with RBF compensation (law 9), Theorem 1.

fn check_reaching_exponents(alpha_s: f64, beta_s: f64) -> Result<(), ParamError> {
    require(
        alpha_s > 0.5 && alpha_s < 1.0,
        "alpha_s",
        alpha_s,
        "1/2 < alpha_s < 1",
    )?;
    require(beta_s > 1.0, "beta_s", beta_s, "beta_s > 1")
}

fn check_fntsmc_exponents(p1: f64, p2: f64, alpha_s: f64, beta_s: f64) -> Result<(), ParamError> {
    require(p1 > 1.0, "p1", p1, "p1 > 1")?;
    require(p2 > 0.0 && p2 < 1.0, "p2", p2, "0 < p2 < 1")?;
    check_reaching_exponents(alpha_s, beta_s)
}

/// Seed 000 eq. 7: on the fast terminal surface `s = e' + alpha e + beta sig^(p/q)(e) = 0`
/// (eq. 6, 0 < p < q), `e' = -alpha e - beta sig^(p/q)(e)` reaches 0 from `e0` at
///
/// `t_s = q / (alpha (q - p)) ln((alpha |e0|^((q - p)/q) + beta) / beta)`
///
/// (with y = |e|^(1 - p/q), `y' = -(1 - p/q)(alpha y + beta)`, linear). At alpha = 0 it is
/// eq. 5, the terminal surface `s = e' + beta sig^(p/q)(e)`, where y falls at a constant rate:
/// `t_s = q / (beta (q - p)) |e0|^((q - p)/q)`, the limit of eq. 7 as alpha tends to 0.
/// The seed prints both with p and q swapped ([`terminal_reaching_time_printed`]).
pub fn terminal_reaching_time(
    e0: f64,
    alpha: f64,
    beta: f64,
    p: f64,
    q: f64,
) -> Result<f64, ParamError> {
    check_terminal(e0, alpha, beta, p, q)?;
    let r = 1.0 - p / q;
    let y0 = e0.abs().powf(r);
    Ok(if alpha == 0.0 {
        y0 / (beta * r)
    } else {
        (alpha * y0 / beta).ln_1p() / (alpha * r)
    })
}

/// Seed 000's eq. 7 as printed, `p / (alpha (p - q)) (ln(alpha |e0|^((p - q)/p) + beta) - ln
/// beta)` (the seed writes e0 without the bars), and at alpha = 0 its eq. 5,
/// `p / (beta (p - q)) |e0|^((p - q)/p)`: p and q swapped against
/// [`terminal_reaching_time`], so negative for the seed's own p < q. Returned as printed,
/// whatever its sign, so that the reproduction can show it.
pub fn terminal_reaching_time_printed(
    e0: f64,
    alpha: f64,
    beta: f64,
    p: f64,
    q: f64,
) -> Result<f64, ParamError> {
    check_terminal(e0, alpha, beta, p, q)?;
    let y0 = e0.abs().powf((p - q) / p);
    Ok(if alpha == 0.0 {
        p / (beta * (p - q)) * y0
    } else {
        p / (alpha * (p - q)) * ((alpha * y0 + beta).ln() - beta.ln())
    })
}

fn check_terminal(e0: f64, alpha: f64, beta: f64, p: f64, q: f64) -> Result<(), ParamError> {
    require(e0.is_finite(), "e0", e0, "finite")?;
    require(
        alpha >= 0.0 && alpha.is_finite(),
        "alpha",
        alpha,
        "alpha >= 0",
    )?;
    require(beta > 0.0 && beta.is_finite(), "beta", beta, "beta > 0")?;
    require(p > 0.0, "p", p, "p > 0")?;
    require(q > p && q.is_finite(), "q", q, "q > p")
}

/// Seed 003 eq. 42 as printed: `T_s <= 2 / (c_v (z4 - 1)) + 2 / (c_v (1 - z3))` with
/// `z3 = (d_V0 + d_0) / d_V0`, `z4 = (d_Vinf + d_inf) / d_Vinf`. The seed gives
/// `d_V0 = 2 alpha_s`, `d_Vinf = 2 beta_s`; the degrees of the limit fields `-K3 sig^alpha_s`,
/// `-K3 sig^beta_s` (weight 1) are `alpha_s - 1` and `beta_s - 1`, so
/// `z3 = (3 alpha_s - 1) / (2 alpha_s)` and `z4 = (3 beta_s - 1) / (2 beta_s)`. The constant
/// `c_v` of Lemma 2 is never given ("selecting the suitable c_v"), so the printed bound cannot
/// be evaluated from the seed alone; it is a function of `c_v` here. K3 does not appear in it.
pub fn fntsmc_ts_printed(c_v: f64, alpha_s: f64, beta_s: f64) -> Result<f64, ParamError> {
    require(c_v > 0.0, "c_v", c_v, "c_v > 0")?;
    check_reaching_exponents(alpha_s, beta_s)?;
    let z3 = (3.0 * alpha_s - 1.0) / (2.0 * alpha_s);
    let z4 = (3.0 * beta_s - 1.0) / (2.0 * beta_s);
    Ok(2.0 / (c_v * (z4 - 1.0)) + 2.0 / (c_v * (1.0 - z3)))
}

/// Seed 003 eq. 47 as printed: `T_d <= 2 / (d g1 (1 - p1)) + 2 / (d g2 (p2 - 1))` with
/// `g1 = 2^((p1+1)/2) K1`, `g2 = 2^((p2+1)/2) (K2 - 1/(p2+1))` (eq. 45), `0 < d < 1`.
///
/// It is not a bound for the law of eq. 21. Lemma 4 needs `0 < (p1+1)/2 < 1 < (p2+1)/2`, i.e.
/// p1 < 1 < p2, while eq. 21 asks p1 > 1 > p2 (and Table 2 follows eq. 21): both terms change
/// sign. It also needs g2 > 0, i.e. K2 > 1/(p2+1), which Table 2 breaks on both axes
/// (0.08 < 0.50, 0.5 < 0.63). The value is returned as printed, whatever its sign, so that the
/// reproduction can show it; [`fntsmc_bounds`] is the sound bound.
pub fn fntsmc_td_printed(k1: f64, p1: f64, k2: f64, p2: f64, d: f64) -> Result<f64, ParamError> {
    require(k1 > 0.0, "k1", k1, "k1 > 0")?;
    require(k2 > 0.0, "k2", k2, "k2 > 0")?;
    require(p1 > 0.0 && p1 != 1.0, "p1", p1, "p1 > 0, p1 != 1")?;
    require(p2 > 0.0 && p2 != 1.0, "p2", p2, "p2 > 0, p2 != 1")?;
    require(d > 0.0 && d < 1.0, "d", d, "0 < d < 1")?;
    let g1 = 2f64.powf((p1 + 1.0) / 2.0) * k1;
    let g2 = 2f64.powf((p2 + 1.0) / 2.0) * (k2 - 1.0 / (p2 + 1.0));
    Ok(2.0 / (d * g1 * (1.0 - p1)) + 2.0 / (d * g2 * (p2 - 1.0)))
}

/// Sound fixed-time bounds of the FNTSMC on one axis (see [`fntsmc_bounds`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FntsmcBounds {
    /// Time for s to reach its neighbourhood (0 without disturbance): the reaching law
    /// `s' = -K3 (sig^alpha_s(s) + sig^beta_s(s)) + Delta`, Lemma 2 (k = 1) on V = s^2/2.
    pub ts: f64,
    /// Neighbourhood of s under |Delta| <= d_max.
    pub s_radius: f64,
    /// Time for |e1| to come within max(sigma_phi, e1_radius) once s is in its neighbourhood:
    /// outside sigma_phi, `e1' = -K2 sig^p2(e1) - K1 sig^p1(e1) + s` is the same reaching law.
    pub td: f64,
    /// Neighbourhood of e1 (outside sigma_phi) under |s| <= s_radius.
    pub e1_radius: f64,
    /// Inside sigma_phi, `|e1|' <= -rate |e1| + |s|`: the smallest of (K1 zeta1 + K2 zeta2)/e1.
    pub inside_rate: f64,
    /// Time from sigma_phi to the tolerance at that rate (infinite if the tolerance is below
    /// what |s| <= s_radius lets e1 reach).
    pub t_inside: f64,
    /// ts + td + t_inside: |e1| stays within the tolerance from then on.
    pub total: f64,
}

impl FntsmcBounds {
    /// Each bound by its field's name (as the bindings hand them out).
    pub fn named(&self) -> [(&'static str, f64); 7] {
        [
            ("ts", self.ts),
            ("s_radius", self.s_radius),
            ("td", self.td),
            ("e1_radius", self.e1_radius),
            ("inside_rate", self.inside_rate),
            ("t_inside", self.t_inside),
            ("total", self.total),
        ]
    }
}

/// Seed 003 Theorem 1 made sound, for one axis of the FNTSMC on a plant where the law holds
/// as derived (`M q'' = u + f`, no saturation) and the lumped disturbance of the s dynamics,
/// `Delta = M^-1 (f - W^T Phi - eps_max sign(s))`, is bounded by `d_max`.
///
/// With `d_max = 0` these are the fixed-time bounds the theorem claims, from Lemma 2 as in
/// seed 001 (`fixed_time_bound`): `ts` for s to reach 0, then `td` for |e1| to reach
/// sigma_phi, then `t_inside` to reach `tol` (e1 decays at least exponentially inside
/// sigma_phi: the fixed-time part of the law ends there, by design of eq. 21). With
/// `d_max > 0`, Theorem 1 of seed 001 with the splitting constant theta gives the practical
/// neighbourhoods and `/ theta` times.
#[allow(clippy::too_many_arguments)]
pub fn fntsmc_bounds(
    k1: f64,
    p1: f64,
    k2: f64,
    p2: f64,
    k3: f64,
    alpha_s: f64,
    beta_s: f64,
    sigma_phi: f64,
    tol: f64,
    d_max: f64,
    theta: f64,
) -> Result<FntsmcBounds, ParamError> {
    require(k1 > 0.0, "k1", k1, "k1 > 0")?;
    require(k2 > 0.0, "k2", k2, "k2 > 0")?;
    require(k3 > 0.0, "k3", k3, "k3 > 0")?;
    check_fntsmc_exponents(p1, p2, alpha_s, beta_s)?;
    require(sigma_phi > 0.0, "sigma_phi", sigma_phi, "sigma_phi > 0")?;
    require(tol > 0.0, "tol", tol, "tol > 0")?;
    require(d_max >= 0.0, "d_max", d_max, "d_max >= 0")?;
    check_theta(theta)?;
    let reach_s = fixed_time_bound(k3, alpha_s, k3, beta_s)?;
    let reach_e = fixed_time_bound(k2, p2, k1, p1)?;
    // (K1 zeta1 + K2 zeta2) / e1 over 0 < |e1| <= sigma: l + m |e1| lies between l and
    // l + m sigma = sigma^(p-1)
    let floor =
        |k: f64, p: f64| k * ((2.0 - p) * sigma_phi.powf(p - 1.0)).min(sigma_phi.powf(p - 1.0));
    let rate = floor(k1, p1) + floor(k2, p2);
    let (ts, s_radius, td, e1_radius, shrink) = if d_max == 0.0 {
        (reach_s, 0.0, reach_e, 0.0, 1.0)
    } else {
        let s_radius = practical_radius(k3, alpha_s, k3, beta_s, d_max, theta)?;
        let e1_radius = practical_radius(k2, p2, k1, p1, s_radius, theta)?;
        (reach_s / theta, s_radius, reach_e / theta, e1_radius, theta)
    };
    // after ts + td, |e1| <= max(sigma_phi, e1_radius); inside sigma_phi,
    // |e1|' <= -rate |e1| + s_radius <= -shrink rate |e1| while (1 - shrink) rate |e1| >= s_radius
    let t_inside = if tol >= sigma_phi.max(e1_radius) {
        0.0
    } else if e1_radius > sigma_phi || rate <= 0.0 || (1.0 - shrink) * rate * tol < s_radius {
        f64::INFINITY
    } else {
        (sigma_phi / tol).ln() / (shrink * rate)
    };
    Ok(FntsmcBounds {
        ts,
        s_radius,
        td,
        e1_radius,
        inside_rate: rate,
        t_inside,
        total: ts + td + t_inside,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_bounds_from_the_spec_reconstruction() {
        let t1 = fixed_time_bound(0.8, 0.95, 0.4, 1.05).unwrap();
        let t2 = fixed_time_bound(0.9, 0.9, 0.5, 1.1).unwrap();
        assert!((t1 - 74.5780).abs() < 5e-5, "{t1}");
        assert!((t2 - 30.8217).abs() < 5e-5, "{t2}");
    }

    #[test]
    fn radius_is_where_the_reaching_law_beats_the_disturbance() {
        // at the radius, (1 - theta) times the larger-radius term equals d_max for the binding
        // term
        let (c1, e1, c2, e2, d, th) = (0.9, 0.9, 0.5, 1.1, 20.0, 0.2);
        let r = practical_radius(c1, e1, c2, e2, d, th).unwrap();
        let a = (1.0 - th) * c1 * r.powf(e1);
        let b = (1.0 - th) * c2 * r.powf(e2);
        assert!((a.max(b) - d).abs() < 1e-9 * d);
        assert!(a.min(b) <= d);
    }

    #[test]
    fn remark1_closed_forms() {
        // seed nominal x axis without gravity: -2000 + 100 t + a t^2 / 2 = 0
        let a = 50_000.0 / 1905.0;
        let (tf1, tf2) = min_final_time(-2000.0, 100.0, a, 0.0).unwrap();
        let expect = (-100.0 + (100.0f64 * 100.0 + 2.0 * a * 2000.0).sqrt()) / a;
        assert!((tf1 - expect).abs() < 1e-12);
        assert!((tf2 - 100.0 / a).abs() < 1e-12);
        // falling lander: thrust up against gravity nulls the velocity in 75 / (a - g)
        let (_, tf2) = min_final_time(1500.0, -75.0, a, -3.7114).unwrap();
        assert!((tf2 - 75.0 / (a - 3.7114)).abs() < 1e-12);
        // an engine weaker than gravity cannot stop a fall
        assert_eq!(
            min_final_time(1500.0, -75.0, 2.0, -3.7114).unwrap().1,
            f64::INFINITY
        );
    }

    #[test]
    fn time_to_rest_matches_the_symmetric_closed_form() {
        // no gravity, from rest at distance d: accelerate half way, brake half way, 2 sqrt(d/a)
        let t = min_time_to_rest(-2000.0, 0.0, 20.0, 0.0).unwrap();
        assert!((t - 2.0 * (2000.0f64 / 20.0).sqrt()).abs() < 1e-9, "{t}");
        // moving towards the target already: v_peak^2 = (v0^2 + 2 a d) / 2
        let (a, d, v0) = (21.0, 2000.0, 100.0);
        let vp = ((v0 * v0 + 2.0 * a * d) / 2.0f64).sqrt();
        let t = min_time_to_rest(-d, v0, a, 0.0).unwrap();
        assert!((t - ((vp - v0) / a + vp / a)).abs() < 1e-9, "{t}");
        // just braking: from v0 towards the target exactly on the braking curve
        let t = min_time_to_rest(-v0 * v0 / (2.0 * a), v0, a, 0.0).unwrap();
        assert!((t - v0 / a).abs() < 1e-6, "{t}");
        // gravity makes braking a fall harder than starting it
        let falling = min_time_to_rest(1500.0, -75.0, 26.0, -3.7114).unwrap();
        let no_g = min_time_to_rest(1500.0, -75.0, 26.0, 0.0).unwrap();
        assert!(falling > 0.0 && no_g > 0.0 && falling.is_finite());
        assert_eq!(
            min_time_to_rest(10.0, 0.0, 3.0, -3.7114).unwrap(),
            f64::INFINITY
        );
    }

    #[test]
    fn invalid_gains_name_the_seed_symbol() {
        let e = mss_bounds(0.8, 1.2, 0.4, 1.05, 0.9, 0.9, 0.5, 1.1, 20.0, 0.2, 0.1).unwrap_err();
        assert_eq!(e.param, "q1");
        let e = mss_bounds(0.8, 0.9, 0.4, 1.05, 0.9, 0.9, 0.5, 1.1, 20.0, 1.2, 0.1).unwrap_err();
        assert_eq!(e.param, "theta1");
    }

    #[test]
    fn fntsmc_bounds_compose_the_reaching_laws() {
        // Table 2, attitude axis (alpha_s, beta_s in the text's roles)
        let b = fntsmc_bounds(0.6, 1.1, 0.5, 0.6, 0.8, 0.7, 1.8, 0.001, 1e-5, 0.0, 0.5).unwrap();
        assert_eq!(b.ts, fixed_time_bound(0.8, 0.7, 0.8, 1.8).unwrap());
        assert_eq!(b.td, fixed_time_bound(0.5, 0.6, 0.6, 1.1).unwrap());
        // inside sigma: K1 (2 - p1) sigma^(p1-1) + K2 sigma^(p2-1)
        let rate = 0.6 * 0.9 * 0.001f64.powf(0.1) + 0.5 * 0.001f64.powf(-0.4);
        assert!((b.inside_rate - rate).abs() < 1e-12 * rate);
        assert!((b.t_inside - (100.0f64).ln() / rate).abs() < 1e-12);
        assert_eq!(b.total, b.ts + b.td + b.t_inside);
        // a disturbance stretches the times by 1/theta and opens neighbourhoods
        let p = fntsmc_bounds(0.6, 1.1, 0.5, 0.6, 0.8, 0.7, 1.8, 0.001, 1e-3, 1e-3, 0.5).unwrap();
        assert_eq!(p.ts, 2.0 * b.ts);
        assert!(p.s_radius > 0.0 && p.e1_radius > 0.0 && p.t_inside == 0.0);
        // a tolerance below what the disturbed s allows is never guaranteed
        let q = fntsmc_bounds(0.6, 1.1, 0.5, 0.6, 0.8, 0.7, 1.8, 0.001, 1e-9, 1e-3, 0.5).unwrap();
        assert_eq!(q.total, f64::INFINITY);
        let e =
            fntsmc_bounds(0.6, 0.9, 0.5, 0.6, 0.8, 0.7, 1.8, 0.001, 1e-5, 0.0, 0.5).unwrap_err();
        assert_eq!((e.param, e.rule), ("p1", "p1 > 1"));
    }

    #[test]
    fn fntsmc_printed_bounds_as_printed() {
        // eq. 47 with Table 2 (in-plane axis): g2 = 2^0.995 (0.08 - 1/1.99) < 0, and both
        // terms flip sign with p1 > 1 > p2; their sum happens to be positive
        let d = 0.5;
        let g1 = 2f64.powf(1.05) * 0.08;
        let g2 = 2f64.powf(0.995) * (0.08 - 1.0 / 1.99);
        assert!(g2 < 0.0);
        let printed = fntsmc_td_printed(0.08, 1.1, 0.08, 0.99, d).unwrap();
        let first = 2.0 / (d * g1 * (1.0 - 1.1));
        assert!(first < 0.0);
        assert!((printed - first - 2.0 / (d * g2 * (0.99 - 1.0))).abs() < 1e-9);
        // eq. 42: z3 = (3 as - 1)/(2 as), z4 = (3 bs - 1)/(2 bs)
        let ts = fntsmc_ts_printed(2.0, 0.89, 1.1).unwrap();
        let z3 = (3.0 * 0.89 - 1.0) / 1.78;
        let z4 = (3.3 - 1.0) / 2.2;
        assert!((ts - (1.0 / (z4 - 1.0) + 1.0 / (1.0 - z3))).abs() < 1e-12);
    }
}
