"""The Theorem 4 numbers of the Mars fixed-time guidance paper checked against one another (its
eq. 18, 26, 31, 32, 39, 40, 45).

The paper prints, for the same guidance and the same gains: T1 <= 74.5780 s (eq. 18) and
T2 <= 30.8217 s (eq. 26) without disturbance; theta1 = 0.2, theta2 = 0.1; and, under
a_p = 20 sin t, the s2 neighbourhood 26.5257 reached by 131.5173 s (eq. 39, 40) and the s1
neighbourhood 23.8472 m reached by 85.8610 s (eq. 31, 45), Fig. 9 and 10 showing them entered
at 7.89 s and 9.76 s. Eq. 40 is eq. 26 with every term divided by theta1, and eq. 45 is eq. 18
divided by theta2 (Theorem 1 with k = 1), whatever the gains, so the printed times fix theta1
and theta2; they are not the printed ones. The radii depend on the gains, which the paper does
not print: they are checked with the reconstruction that reproduces T1 and T2 to four
decimals (examples/mars_reproduction.py, "Fixed-time bounds").

    python examples/studies/mars_theorem4.py      (instant)
"""

from __future__ import annotations

from scipy.optimize import brentq

from landing import theory

T1, T2 = 74.5780, 30.8217  # eq. 18, 26 as printed
THETA1, THETA2 = 0.2, 0.1  # as printed
R2, T2P = 26.5257, 131.5173  # eq. 39, 40 as printed
R1, T1P = 23.8472, 85.8610  # eq. 31, 45 as printed
FIG9, FIG10 = 7.89, 9.76
AP = 20.0  # a_p = 20 sin t on each axis
# the reconstruction reproducing T1 and T2 (beta1, q1, beta2, q2) and (alpha1, gamma1, alpha2, gamma2)
S1_GAINS = (0.8, 0.95, 0.4, 1.05)
S2_GAINS = (0.9, 0.9, 0.5, 1.1)


def main() -> None:
    print("Theorem 4 as printed, checked against itself")
    print("1. times (gain-free: eq. 40 = eq. 26 / theta1, eq. 45 = eq. 18 / theta2)")
    print(f"  eq. 40 with T2 = {T2} s, theta1 = {THETA1}:   {T2 / THETA1:9.4f} s   printed {T2P} s")
    print(f"  eq. 45 with T1 = {T1} s, theta2 = {THETA2}:   {T1 / THETA2:9.4f} s   printed {T1P} s")
    print(f"  theta1 the printed times imply: {T2:.4f} / {T2P:.4f} = {T2 / T2P:.4f}   printed {THETA1}")
    print(f"  theta2 the printed times imply: {T1:.4f} / {T1P:.4f} = {T1 / T1P:.4f}   printed {THETA2}")
    print(f"  with theta1, theta2 swapped: {T2 / THETA2:.4f} s and {T1 / THETA1:.4f} s; neither order gives the printed times")
    print()
    print("2. the cascade (eq. 41-45 bound s1 with |s2| <= M, which holds only once s2 is inside)")
    print(f"  s1 inside its band by at most {T2P} + {T1P} = {T2P + T1P:.4f} s; eq. 32 prints max = {max(T2P, T1P):.4f} s")
    print(f"  with the printed theta and T1, T2: {T2 / THETA1:.4f} + {T1 / THETA2:.4f} = {T2 / THETA1 + T1 / THETA2:.4f} s")
    print(f"  Fig. 9, 10: s2 inside by {FIG9} s, s1 by {FIG10} s, {T2P / FIG9:.1f} and "
          f"{(T2P + T1P) / FIG10:.1f} times inside the printed bounds (upper bounds: no contradiction, no check)")
    print()
    print(f"3. radii (gain-dependent; the reconstruction {S1_GAINS}, {S2_GAINS}; a_pMAX = {AP} per axis)")
    r2 = theory.practical_radius(*S2_GAINS, AP, THETA1)
    print(f"  eq. 39, theta1 = {THETA1}: {r2:.4f}   printed {R2}")
    ap = brentq(lambda a: theory.practical_radius(*S2_GAINS, a, THETA1) - R2, 1e-6, 1e3)
    print(f"  a_pMAX for which eq. 39 gives {R2}: {ap:.4f} (the disturbance's per-axis bound is {AP}, its norm {AP * 3 ** 0.5:.4f})")
    r1 = theory.practical_radius(*S1_GAINS, R2, THETA2)
    print(f"  eq. 31 with M = {R2}, theta2 = {THETA2}: {r1:.4f} m   printed {R1} m")
    th2 = T1 / T1P
    print(f"  eq. 31 with M = {R2}, theta2 = {th2:.4f} (the one eq. 45 implies): "
          f"{theory.practical_radius(*S1_GAINS, R2, th2):.4f} m   printed {R1} m")
    low = theory.practical_radius(*S1_GAINS, R2, 1e-12)
    print(f"  eq. 31 with M = {R2} grows with theta2; its least value (theta2 -> 0) is {low:.4f} m > {R1} m: "
          "no theta2 gives the printed radius")

if __name__ == "__main__":
    main()
