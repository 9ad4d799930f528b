#!/usr/bin/env python3
"""Reference values for the lane transcendentals (src/lanes/math.rs), from mpmath.

    python3 crates/landing_core/tests/data/make_math_reference.py

writes math_reference.txt beside this script; tests/lane_math.rs reads it. Deterministic
(fixed seed). Each section `[name]` lists one point per line:

    x_bits [x2_bits] result_bits delta

with the bits of the binary64 arguments and of the correctly rounded result in hex, and
`delta = (exact - result) / ulp` (4 decimals), `ulp` being the spacing of binary64 in the
binade of the exact value (2^-1074 below 2^-1022). The test measures its error against
`result + delta ulp`, so fractional ulp errors are reported, not only whole steps. Results
that are not finite carry delta 0. `pow` and `atan2` lines have two arguments, (x, y) and
(y, x) in the order of the Rust signatures.

Every value is computed with 256 bits (more for huge trigonometric arguments, so that the
reduction by pi/2 keeps 256 bits) and rounded here to binary64 with subnormals, ties to even.
"""

import heapq
import math
import os
import random
import struct

from mpmath import mp, mpf

WORK_PREC = 256
INF = float("inf")
NAN = float("nan")


def bits(x):
    return struct.unpack("<Q", struct.pack("<d", x))[0]


def from_bits(b):
    return struct.unpack("<d", struct.pack("<Q", b))[0]


def ulp_exponent(v):
    """The exponent of the ulp of the binade of the (nonzero, finite) exact value v."""
    e = int(mp.floor(mp.log(abs(v), 2)))
    # log2 may round across a power of two: fix e so that 2^e <= |v| < 2^(e+1)
    while mpf(2) ** e > abs(v):
        e -= 1
    while mpf(2) ** (e + 1) <= abs(v):
        e += 1
    return max(e, -1022) - 52


def round_double(v):
    """(binary64 nearest to v, ties to even, with subnormals and overflow; delta in ulps)."""
    if mp.isnan(v):
        return NAN, 0.0
    if mp.isinf(v):
        return (INF if v > 0 else -INF), 0.0
    if v == 0:
        return 0.0, 0.0
    # far outside the range, log2 |v| would not even be an accurate integer
    if abs(v) >= mpf(2) ** 1024:
        return (INF if v > 0 else -INF), 0.0
    if abs(v) < mpf(2) ** -1080:
        return 0.0, float(v * mpf(2) ** 1074)
    q = ulp_exponent(v)
    scaled = v / mpf(2) ** q
    m = int(mp.nint(scaled))  # mpmath's nint rounds ties to even
    if abs(mpf(m) * mpf(2) ** q) >= mpf(2) ** 1024:
        return (INF if v > 0 else -INF), 0.0
    # |m| <= 2^53: float(m) and the scaling are exact
    return math.ldexp(float(m), q), float(scaled - m)


def fmt(x):
    return f"{bits(x):016x}"


def with_prec(extra, f, *args):
    with mp.workprec(WORK_PREC + extra):
        return f(*args)


# -- the functions, as mpmath sees them ---------------------------------------------------


def ref_exp(x):
    if math.isnan(x):
        return mpf("nan")
    if x == INF:
        return mpf("inf")
    if x == -INF:
        return mpf(0)
    return mp.exp(mpf(x))


def ref_ln(x):
    if math.isnan(x) or x < 0:
        return mpf("nan")
    if x == 0:
        return mpf("-inf")
    if x == INF:
        return mpf("inf")
    return mp.log(mpf(x))


def trig_extra(x):
    if not math.isfinite(x) or x == 0:
        return 0
    return max(0, math.frexp(x)[1]) + 64


def ref_sin(x):
    if not math.isfinite(x):
        return mpf("nan")
    return with_prec(trig_extra(x), lambda: +mp.sin(mpf(x)))


def ref_cos(x):
    if not math.isfinite(x):
        return mpf("nan")
    return with_prec(trig_extra(x), lambda: +mp.cos(mpf(x)))


def ref_tanh(x):
    if math.isnan(x):
        return mpf("nan")
    if math.isinf(x):
        return mpf(1 if x > 0 else -1)
    return mp.tanh(mpf(x))


def ref_atan2(y, x):
    """libm's conventions for zeros and infinities; mpmath's atan2 for the finite rest."""
    if math.isnan(x) or math.isnan(y):
        return mpf("nan")
    sy = math.copysign(1.0, y)
    xneg = math.copysign(1.0, x) < 0
    if y == 0:
        return sy * (mp.pi if xneg else mpf(0))
    if math.isinf(y):
        if math.isinf(x):
            return sy * (3 * mp.pi / 4 if xneg else mp.pi / 4)
        return sy * mp.pi / 2
    if math.isinf(x):
        return sy * (mp.pi if xneg else mpf(0))
    if x == 0:
        return sy * mp.pi / 2
    return mp.atan2(mpf(y), mpf(x))


def ref_pow(x, y):
    """The documented conventions of lanes::math::pow (x >= 0; x^0 = 1^y = 1)."""
    if y == 0 or x == 1:
        return mpf(1)
    if math.isnan(x) or math.isnan(y) or x < 0:
        return mpf("nan")
    if x == 0:
        return mpf(0) if y > 0 else mpf("inf")
    if math.isinf(x):
        return mpf("inf") if y > 0 else mpf(0)
    if math.isinf(y):
        if (x > 1) == (y > 0):
            return mpf("inf")
        return mpf(0)
    return mp.power(mpf(x), mpf(y))


# -- sampling helpers ---------------------------------------------------------------------

rng = random.Random(20260515)


def uniform(a, b):
    return rng.uniform(a, b)


def log_uniform(lo, hi):
    """|x| log-uniform in [lo, hi], random sign."""
    v = math.exp(rng.uniform(math.log(lo), math.log(hi)))
    return v if rng.random() < 0.5 else -v


def neighbours(x, n=2):
    """x and the n doubles on each side of it."""
    out = [x]
    b = bits(x)
    for d in range(1, n + 1):
        out.append(from_bits(b + d))
        if b - d >= 0:
            out.append(from_bits(b - d))
    return [v for v in out if math.isfinite(v)]


def random_bits_positive():
    """A positive finite double with uniformly random bits (so every binade equally)."""
    while True:
        v = from_bits(rng.getrandbits(63))
        if math.isfinite(v) and v > 0:
            return v


def subnormal():
    return from_bits(rng.randrange(1, 1 << 52))


def pio2_worst_cases(limit, count):
    """The doubles closest to a multiple of pi/2 below `limit`, hardest reductions first.

    For every k, the double nearest to k pi/2 is found with integer arithmetic on a 320-bit
    pi/2; the `count` smallest |x - k pi/2| are returned.
    """
    s = 320
    with mp.workprec(400):
        p = int(mp.nint(mp.pi / 2 * mpf(2) ** s))
    kmax = int(limit / (math.pi / 2))
    best = []
    for k in range(1, kmax + 1):
        v = k * p
        e = v.bit_length() - 1 - s
        shift = s + e - 52
        m = (v + (1 << (shift - 1))) >> shift
        r = abs((m << shift) - v)
        # keep |r| relative to 2^s as a float-like key (r itself is the exact distance)
        if len(best) < count:
            heapq.heappush(best, (-r, k, m, e - 52))
        elif r < -best[0][0]:
            heapq.heapreplace(best, (-r, k, m, e - 52))
    out = []
    for _, _, m, q in sorted(best, reverse=True):
        x = math.ldexp(float(m), q)
        if x < limit:
            out.append(x)
    return out


# -- the points ---------------------------------------------------------------------------


def points_exp():
    xs = [0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 10.0, -10.0, 100.0, 700.0, -700.0]
    xs += [INF, -INF, NAN, 1e-300, -1e-300, 5e-324, 1e-17, -1e-17]
    # overflow threshold (the largest x with a finite result is 709.782712893384)
    xs += neighbours(709.782712893384, 3) + [709.79, 710.0, 711.0, 1e300, 800.0]
    # subnormal results start below -708.396...; zero below -745.133...
    xs += neighbours(-708.3964185322641, 3) + neighbours(-745.1332191019411, 3)
    xs += neighbours(-744.44007192138122, 2) + [-745.2, -746.0, -750.0, -1e300]
    xs += [uniform(-745.2, -708.3) for _ in range(200)]
    # reduction boundaries: x near (k + 1/2) ln 2, where round(x / ln 2) changes
    for _ in range(300):
        k = rng.randrange(-1075, 1024)
        xs += neighbours(float((k + mpf(0.5)) * mp.log(2)), 1)
    xs += [uniform(-745.0, 709.7) for _ in range(1200)]
    xs += [uniform(-2.0, 2.0) for _ in range(400)]
    xs.append(10.74691893341766)  # the worst a dense search against mpmath found
    xs += [log_uniform(1e-300, 1.0) for _ in range(300)]
    return [(x,) for x in xs]


def points_ln():
    xs = [1.0, 0.0, -0.0, -1.0, INF, -INF, NAN, 2.0, 0.5, 10.0, math.e, 5e-324, 1e-310]
    xs += [2.2250738585072014e-308, 2.225073858507201e-308, 1.7976931348623157e308]
    xs += neighbours(1.0, 4) + [1.0 + 2.0**-30, 1.0 - 2.0**-30, 1.0 + 1e-10, 1.0 - 1e-10]
    # the sqrt(2) split of the mantissa, in several binades
    for e in (-1070, -1030, -1000, -3, -1, 0, 1, 5, 500, 1023):
        for v in neighbours(math.ldexp(math.sqrt(2.0), e), 2):
            if v > 0:
                xs.append(v)
    xs += [random_bits_positive() for _ in range(1300)]
    xs += [1.0 + log_uniform(1e-16, 0.5) for _ in range(400)]
    xs += [uniform(0.0, 100.0) for _ in range(300)]
    xs += [subnormal() for _ in range(200)]
    xs += [-random_bits_positive() for _ in range(20)]
    return [(x,) for x in xs]


def points_trig(worst):
    xs = [0.0, -0.0, INF, -INF, NAN, 5e-324, -5e-324, 1e-310, 1e-20, -1e-8, 1e-5]
    xs += [math.pi / 4, math.pi / 2, math.pi, 2 * math.pi, 1e5, 1e6, -1e6]
    # the reduction limit and the cold path beyond it
    xs += neighbours(1647099.0, 2) + neighbours(1647099.3291652855, 2)
    xs += [1e7, -3e9, 1e15, 2.0**52, 1e22, 1e100, 1.7976931348623157e308, -1e300]
    xs += [log_uniform(1.7e6, 1e308) for _ in range(60)]
    # the hardest reductions below the limit, and their neighbours
    for x in worst:
        xs += neighbours(x, 1)
        xs.append(-x)
    # quadrant boundaries: x near (k + 1/2) pi/2, where round(x 2/pi) changes
    for _ in range(250):
        k = rng.randrange(-(2**20) + 1, 2**20 - 1)
        xs += neighbours(float((k + mpf(0.5)) * mp.pi / 2), 1)
    xs += [uniform(-math.pi, math.pi) for _ in range(500)]
    xs += [uniform(-100.0, 100.0) for _ in range(300)]
    xs += [uniform(-1.6e6, 1.6e6) for _ in range(300)]
    xs += [log_uniform(1e-300, 1.0) for _ in range(200)]
    return [(x,) for x in xs]


def points_tanh():
    xs = [0.0, -0.0, INF, -INF, NAN, 5e-324, -5e-324, 1e-310, 1e-20, 1e-8, -1e-8]
    xs += [19.0, 20.0, 20.5, 22.0, 30.0, 1e300, -1e300, 1.0, -1.0]
    xs += neighbours(0.5493061443340549, 4)
    xs += neighbours(-0.5493061443340549, 2)
    xs += [uniform(0.5, 0.6) for _ in range(200)]
    xs += [uniform(0.55, 1.0) for _ in range(300)]
    xs += [uniform(-3.0, 3.0) for _ in range(900)]
    xs += [uniform(-25.0, 25.0) for _ in range(500)]
    xs += [log_uniform(1e-300, 1.0) for _ in range(400)]
    return [(x,) for x in xs]


def points_atan2():
    specials = [0.0, -0.0, 1.0, -1.0, INF, -INF, NAN, 5e-324, -1e-310, 1.7976931348623157e308]
    ps = [(y, x) for y in specials for x in specials]

    def pair_with_ratio(t):
        a = log_uniform(1e-300, 1e300)
        b = abs(a) * t
        if rng.random() < 0.5:
            a, b = b, a
        x = a if rng.random() < 0.5 else -a
        y = b if rng.random() < 0.5 else -b
        return (y, x)

    # the range boundaries of the reduction, b/a = 7/16, 11/16, 1
    for t in (7 / 16, 11 / 16, 1.0):
        for _ in range(60):
            ps.append(pair_with_ratio(t * (1 + rng.uniform(-1e-6, 1e-6))))
        for _ in range(20):
            ps.append(pair_with_ratio(t))
    # b/a a little above a power of two, where atan(b/a) is just below it: the rounding of
    # the quotient counts double there
    for k in range(2, 8):
        t = 2.0**-k
        for _ in range(50):
            ps.append(pair_with_ratio(t * (1 + rng.uniform(0, t * t / 3))))
    # the worst case a dense search (2e5 random points against mpmath) found
    ps.append((0.05148190843964584, 0.4099218230933299))
    ps += [pair_with_ratio(rng.random()) for _ in range(900)]
    ps += [pair_with_ratio(math.exp(rng.uniform(-40.0, 0.0))) for _ in range(400)]
    ps += [(uniform(-10.0, 10.0), uniform(-10.0, 10.0)) for _ in range(400)]
    # huge and subnormal pairs (the scaling), and their mixtures
    ps += [(log_uniform(1e300, 1.7e308), log_uniform(1e300, 1.7e308)) for _ in range(100)]
    ps += [(subnormal() * rng.choice([1, -1]), subnormal() * rng.choice([1, -1])) for _ in range(100)]
    ps += [(log_uniform(1e-310, 1e-300), log_uniform(1e300, 1e308)) for _ in range(30)]
    ps += [(log_uniform(1e300, 1e308), log_uniform(1e-310, 1e-300)) for _ in range(30)]
    return ps


def points_pow():
    specials = [0.0, -0.0, 1.0, 0.5, 2.0, -2.0, INF, -INF, NAN, 5e-324]
    ps = [(x, y) for x in specials for y in [0.0, -0.0, 1.0, -1.0, 0.5, 2.5, INF, -INF, NAN]]
    # the controllers' use: |s|^q with moderate q
    ps += [(abs(log_uniform(1e-8, 1e4)), uniform(0.1, 2.0)) for _ in range(900)]
    ps += [(abs(log_uniform(1e-3, 1e3)), uniform(-3.0, 3.0)) for _ in range(500)]
    ps += [(1.0 + log_uniform(1e-12, 0.1), uniform(-100.0, 100.0)) for _ in range(200)]
    ps += [(abs(log_uniform(1e-300, 1e300)), log_uniform(1e-3, 1.0)) for _ in range(200)]
    # overflow and underflow of the result
    ps += [(10.0, 308.0), (10.0, 309.0), (10.0, -323.0), (10.0, -324.0), (2.0, 1023.5)]
    ps += [(2.0, -1074.0), (2.0, -1075.0), (0.5, 1074.0), (1e-300, 2.0), (1e300, -2.0)]
    return ps


def main():
    worst = pio2_worst_cases(1647099.0, 200)
    sections = [
        ("exp", points_exp(), ref_exp),
        ("ln", points_ln(), ref_ln),
        ("sin", points_trig(worst), ref_sin),
        ("cos", points_trig(worst), ref_cos),
        ("tanh", points_tanh(), ref_tanh),
        ("atan2", points_atan2(), ref_atan2),
        ("pow", points_pow(), ref_pow),
    ]
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "math_reference.txt")
    mp.prec = WORK_PREC
    with open(path, "w") as out:
        out.write("# generated by make_math_reference.py (mpmath); do not edit\n")
        for name, pts, f in sections:
            out.write(f"[{name}]\n")
            seen = set()
            for args in pts:
                key = tuple(bits(a) for a in args)
                if key in seen:
                    continue
                seen.add(key)
                r, d = round_double(f(*args))
                if not math.isfinite(r):
                    d = 0.0
                cols = [fmt(a) for a in args] + [fmt(r), f"{d:.4f}"]
                out.write(" ".join(cols) + "\n")
            print(f"{name}: {len(seen)} points")


if __name__ == "__main__":
    main()
