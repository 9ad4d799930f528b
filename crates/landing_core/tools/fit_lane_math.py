#!/usr/bin/env python3
"""Minimax polynomial coefficients for the lane transcendentals (src/lanes/math.rs).

Each kernel is fitted by the Remez exchange algorithm in 60-digit mpmath arithmetic, with a
weight that measures the error the polynomial contributes to the *final* result relative to
that result (so coefficients are not spent where the polynomial term is small). The
coefficients are then rounded to binary64, the three low-order ones one at a time with the
rest refitted around each, and the weighted error of the rounded polynomial is re-measured on
a dense grid and printed in bits.

    python3 crates/landing_core/tools/fit_lane_math.py

prints the Rust constant arrays of src/lanes/exp_log.rs and src/lanes/trig.rs (about a minute).
Deterministic; needs only mpmath. Optional arguments: the number of coefficients of the atan
and tanh polynomials (11 and 11).
"""

import sys

from mpmath import mp, mpf, matrix, lu_solve

mp.dps = 60


def remez(f, w, powers, a, b, iters=40, grid=3000):
    """Minimise max |w(x) (sum_j c_j x^p_j - f(x))| over [a, b]."""
    n = len(powers)
    m = n + 1  # reference size
    # Chebyshev-like initial reference, kept off the endpoints' zero weights
    xs = [
        (a + b) / 2 - (b - a) / 2 * mp.cos(mp.pi * (i + mpf("0.5")) / m)
        for i in range(m)
    ]
    # a reference point on a zero of the weight makes the system singular: nudge it
    xs = [x + (b - a) / (4 * m) if abs(w(x)) < mpf("1e-30") else x for x in xs]
    gx = [a + (b - a) * mpf(i) / grid for i in range(grid + 1)]
    gx = [x for x in gx if w(x) != 0]
    fx = [f(x) for x in gx]
    wx = [w(x) for x in gx]
    last = None
    for _ in range(iters):
        A = matrix(m, m)
        rhs = matrix(m, 1)
        for i, x in enumerate(xs):
            for j, p in enumerate(powers):
                A[i, j] = x**p
            A[i, n] = (-1) ** i / w(x)
            rhs[i] = f(x)
        sol = lu_solve(A, rhs)
        c = [sol[j] for j in range(n)]
        level = abs(sol[n])

        def err(x, fxv=None, wxv=None):
            fv = f(x) if fxv is None else fxv
            wv = w(x) if wxv is None else wxv
            return wv * (sum(cj * x**p for cj, p in zip(c, powers)) - fv)

        es = [err(x, fv, wv) for x, fv, wv in zip(gx, fx, wx)]
        # one extremum per run of equal sign, refined by golden-section search
        runs = []
        start = 0
        for i in range(1, len(es) + 1):
            if i == len(es) or (es[i] > 0) != (es[start] > 0):
                k = max(range(start, i), key=lambda t: abs(es[t]))
                runs.append(k)
                start = i
        cand = []
        for k in runs:
            lo = gx[max(k - 1, 0)]
            hi = gx[min(k + 1, len(gx) - 1)]
            sgn = 1 if es[k] > 0 else -1
            g = (mp.sqrt(5) - 1) / 2
            x1 = hi - g * (hi - lo)
            x2 = lo + g * (hi - lo)
            f1 = sgn * err(x1)
            f2 = sgn * err(x2)
            for _ in range(60):
                if f1 > f2:
                    hi, x2, f2 = x2, x1, f1
                    x1 = hi - g * (hi - lo)
                    f1 = sgn * err(x1)
                else:
                    lo, x1, f1 = x1, x2, f2
                    x2 = lo + g * (hi - lo)
                    f2 = sgn * err(x2)
            xb = (lo + hi) / 2
            eb = err(xb)
            if abs(eb) < abs(es[k]):
                xb, eb = gx[k], es[k]
            cand.append((xb, eb))
        while len(cand) > m:
            if abs(cand[0][1]) < abs(cand[-1][1]):
                cand.pop(0)
            else:
                cand.pop()
        if len(cand) < m:
            raise RuntimeError(f"only {len(cand)} alternation points for {m}")
        xs = [x for x, _ in cand]
        peak = max(abs(e) for _, e in cand)
        if last is not None and abs(peak - level) / peak < mpf("1e-6"):
            break
        last = peak
    return c, peak


def check(f, w, powers, coeffs, a, b, n=20000):
    """Max weighted error of the binary64-rounded coefficients, on a dense grid."""
    worst = mpf(0)
    for i in range(n + 1):
        x = a + (b - a) * mpf(i) / n
        wv = w(x)
        if wv == 0:
            continue
        e = abs(wv * (sum(mpf(cj) * x**p for cj, p in zip(coeffs, powers)) - f(x)))
        worst = max(worst, e)
    return worst


def report(name, f, w, powers, a, b, fix=3):
    """Fit, then round to binary64. The low-order coefficients carry the most weight, so
    they are rounded one at a time and the rest refitted around each rounded value."""
    fixed = []
    level = None
    for _ in range(fix + 1):
        rest = powers[len(fixed) :]

        def g(x, fixed=tuple(fixed)):
            return f(x) - sum(mpf(cj) * x**p for cj, p in zip(fixed, powers))

        c, level = remez(g, w, rest, a, b)
        if len(fixed) == fix:
            fixed += [float(cj) for cj in c]
            break
        fixed.append(float(c[0]))
    worst = check(f, w, powers, fixed, a, b)
    print(
        f"// {name}: degree {powers[-1]}, minimax weighted error 2^{float(mp.log(level, 2)):.2f},"
        f" with binary64 coefficients 2^{float(mp.log(worst, 2)):.2f}"
    )
    print(f"const {name}: [f64; {len(fixed)}] = [")
    for r in fixed:
        print(f"    {r!r},")
    print("];")
    sys.stdout.flush()


def small(x):
    return abs(x) < mpf("1e-25")


def main():
    # exp(r) = 1 + r + r^2 Q(r) on |r| <= ln2/2 (+ a margin for the rounding of k)
    h = mp.log(2) / 2 * (1 + mpf("1e-6"))

    def q_exp(r):
        if small(r):
            return mpf(1) / 2 + r / 6
        return (mp.exp(r) - 1 - r) / r**2

    report(
        "EXP_Q",
        q_exp,
        lambda r: r**2 / mp.exp(r),
        list(range(10)),
        -h,
        h,
    )

    # log(1+f) = 2 atanh(s) = 2s + s z L(z), s = f/(2+f), z = s^2, |s| <= 3 - 2 sqrt(2)
    smax = (3 - 2 * mp.sqrt(2)) * (1 + mpf("1e-6"))

    def l_log(z):
        if small(z):
            return mpf(2) / 3 + 2 * z / 5
        s = mp.sqrt(z)
        return (2 * mp.atanh(s) - 2 * s) / (s * z)

    report(
        "LOG_L",
        l_log,
        lambda z: mp.sqrt(z) * z / (2 * mp.atanh(mp.sqrt(z))) if z else mpf(0),
        list(range(7)),
        mpf(0),
        smax**2,
    )

    # sin(x) = x + x^3 S(z), cos(x) = 1 - z/2 + z^2 C(z), z = x^2, |x| <= pi/4 (+ margin)
    zmax = (mp.pi / 4 * (1 + mpf("1e-6"))) ** 2

    def s_sin(z):
        if small(z):
            return -mpf(1) / 6 + z / 120
        x = mp.sqrt(z)
        return (mp.sin(x) - x) / (x * z)

    def c_cos(z):
        if small(z):
            return mpf(1) / 24 - z / 720
        x = mp.sqrt(z)
        return (mp.cos(x) - 1 + z / 2) / z**2

    report(
        "SIN_S",
        s_sin,
        lambda z: mp.sqrt(z) * z / mp.sin(mp.sqrt(z)) if z else mpf(0),
        list(range(6)),
        mpf(0),
        zmax,
    )
    report(
        "COS_C",
        c_cos,
        lambda z: z**2 / mp.cos(mp.sqrt(z)),
        list(range(6)),
        mpf(0),
        zmax,
    )

    # atan(u) = u + u z P(z), z = u^2, |u| <= 7/16
    umax = mpf(7) / 16 * (1 + mpf("1e-6"))

    def p_atan(z):
        if small(z):
            return -mpf(1) / 3 + z / 5
        u = mp.sqrt(z)
        return (mp.atan(u) - u) / (u * z)

    report(
        "ATAN_P",
        p_atan,
        lambda z: mp.sqrt(z) * z / mp.atan(mp.sqrt(z)) if z else mpf(0),
        list(range(int(sys.argv[1]) if len(sys.argv) > 1 else 11)),
        mpf(0),
        umax**2,
    )

    # tanh(x) = x + x z T(z), z = x^2, |x| <= ln(3)/2 (where tanh = 1/2)
    tmax = mp.log(3) / 2 * (1 + mpf("1e-4"))

    def t_tanh(z):
        if small(z):
            return -mpf(1) / 3 + 2 * z / 15
        x = mp.sqrt(z)
        return (mp.tanh(x) - x) / (x * z)

    report(
        "TANH_T",
        t_tanh,
        lambda z: mp.sqrt(z) * z / mp.tanh(mp.sqrt(z)) if z else mpf(0),
        list(range(int(sys.argv[2]) if len(sys.argv) > 2 else 11)),
        mpf(0),
        tmax**2,
    )


if __name__ == "__main__":
    main()
