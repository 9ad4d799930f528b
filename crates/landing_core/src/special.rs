//! The standard normal distribution function and its inverse, for the dispersions that draw by
//! inversion ([`crate::dispersion`]'s truncated normal).

/// Phi(x) = P(Z <= x) for a standard normal Z, from the complementary error function (libm's,
/// accurate to an ulp or two): relative accuracy is kept in the lower tail, where Phi is small.
pub fn normal_cdf(x: f64) -> f64 {
    0.5 * libm::erfc(-x * std::f64::consts::FRAC_1_SQRT_2)
}

/// Evaluates the polynomial with coefficients `c` (lowest degree first) at `x` (Horner).
fn poly(c: &[f64; 8], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &k| acc * x + k)
}

/// Phi^-1(p) for p in (0, 1): Wichura's algorithm AS 241 (PPND16, Applied Statistics 37(3),
/// 1988, 477-484), relative accuracy about 1e-16; -inf at 0 and inf at 1.
// the coefficients as the paper prints them, to 20 digits
#[allow(clippy::excessive_precision, clippy::unreadable_literal)]
pub fn normal_quantile(p: f64) -> f64 {
    const A: [f64; 8] = [
        3.387132872796366608,
        133.14166789178437745,
        1971.5909503065514427,
        13731.693765509461125,
        45921.953931549871457,
        67265.770927008700853,
        33430.575583588128105,
        2509.0809287301226727,
    ];
    const B: [f64; 8] = [
        1.0,
        42.313330701600911252,
        687.1870074920579083,
        5394.1960214247511077,
        21213.794301586595867,
        39307.89580009271061,
        28729.085735721942674,
        5226.495278852545925,
    ];
    const C: [f64; 8] = [
        1.42343711074968357734,
        4.6303378461565452959,
        5.7694972214606914055,
        3.64784832476320460504,
        1.27045825245236838258,
        0.24178072517745061177,
        0.0227238449892691845833,
        7.7454501427834140764e-4,
    ];
    const D: [f64; 8] = [
        1.0,
        2.05319162663775882187,
        1.6763848301838038494,
        0.68976733498510000455,
        0.14810397642748007459,
        0.0151986665636164571966,
        5.475938084995344946e-4,
        1.05075007164441684324e-9,
    ];
    const E: [f64; 8] = [
        6.6579046435011037772,
        5.4637849111641143699,
        1.7848265399172913358,
        0.29656057182850489123,
        0.026532189526576123093,
        0.0012426609473880784386,
        2.71155556874348757815e-5,
        2.01033439929228813265e-7,
    ];
    const F: [f64; 8] = [
        1.0,
        0.59983220655588793769,
        0.13692988092273580531,
        0.0148753612908506148525,
        7.868691311456132591e-4,
        1.8463183175100546818e-5,
        1.4215117583164458887e-7,
        2.04426310338993978564e-15,
    ];
    if p <= 0.0 {
        return f64::NEG_INFINITY;
    }
    if p >= 1.0 {
        return f64::INFINITY;
    }
    let q = p - 0.5;
    if q.abs() <= 0.425 {
        let r = 0.180_625 - q * q;
        return q * poly(&A, r) / poly(&B, r);
    }
    let r = (-(if q < 0.0 { p } else { 1.0 - p }).ln()).sqrt();
    let x = if r <= 5.0 {
        poly(&C, r - 1.6) / poly(&D, r - 1.6)
    } else {
        poly(&E, r - 5.0) / poly(&F, r - 5.0)
    };
    if q < 0.0 { -x } else { x }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_quantile_inverts_the_distribution_function() {
        // Phi(Phi^-1(p)) = p through libm's erfc, an independent implementation; a relative
        // error e in x moves Phi by x phi(x) / Phi(x) e relatively, about x^2 e in the tails
        let round_trip = |p: f64| {
            let x = normal_quantile(p);
            let back = normal_cdf(x);
            assert!(
                (back / p - 1.0).abs() <= 1e-15 * (1.0 + x * x),
                "{p}: {back}"
            );
        };
        (1..2000).for_each(|k| round_trip(k as f64 / 2000.0));
        (3..300).for_each(|e| round_trip(10f64.powi(-e)));
        assert_eq!(normal_quantile(0.5), 0.0);
        // printed values: Phi^-1(0.975) = 1.959963984540054, Phi^-1(1e-10) = -6.361340902404056
        assert!((normal_quantile(0.975) - 1.959_963_984_540_054).abs() < 1e-15);
        assert!((normal_quantile(1e-10) + 6.361_340_902_404_056).abs() < 1e-14);
    }
}
