//! Counter-based random numbers.
//!
//! Every random draw is a pure function of `(seed, stream, case, counter)`: Philox4x64-10
//! (Salmon et al., "Parallel random numbers: as easy as 1, 2, 3", SC 2011) with the key
//! `[seed, stream]` and the counter `[counter, case, 0, 0]`. A case's numbers therefore do not
//! depend on which thread runs it, on the batch size or on the chunking, and a case can be
//! re-run alone with the same bits. It is the generator numpy ships as `numpy.random.Philox`,
//! which the Python tests use as the independent reference.

use crate::lanes::Real;

const M0: u64 = 0xD2E7_470E_E14C_6C93;
const M1: u64 = 0xCA5A_8263_9512_1157;
const W0: u64 = 0x9E37_79B9_7F4A_7C15;
const W1: u64 = 0xBB67_AE85_84CA_A73B;

#[inline(always)]
fn mulhilo(a: u64, b: u64) -> (u64, u64) {
    let p = (a as u128) * (b as u128);
    ((p >> 64) as u64, p as u64)
}

/// One Philox4x64 block with 10 rounds.
#[inline]
pub fn philox4x64_10(counter: [u64; 4], key: [u64; 2]) -> [u64; 4] {
    let mut c = counter;
    let mut k = key;
    for round in 0..10 {
        if round > 0 {
            k[0] = k[0].wrapping_add(W0);
            k[1] = k[1].wrapping_add(W1);
        }
        let (hi0, lo0) = mulhilo(M0, c[0]);
        let (hi1, lo1) = mulhilo(M1, c[2]);
        c = [hi1 ^ c[1] ^ k[0], lo1, hi0 ^ c[3] ^ k[1], lo0];
    }
    c
}

/// Stream identifiers: one independent stream per use, so adding a new random input never
/// shifts the numbers an existing one sees.
pub mod streams {
    /// Initial-state and parameter dispersions.
    pub const DISPERSION: u64 = 0;
    /// Random disturbance components (drawn once per control period).
    pub const DISTURBANCE: u64 = 1;
    /// Random disturbances proportional to the command (seed 002: up to 1 % of it).
    pub const COMMAND_NOISE: u64 = 2;
    /// A sensor's white noise and random walk ([`crate::navigation`]).
    pub const SENSOR: u64 = 3;
}

/// The random numbers of one case in one stream.
#[derive(Clone, Copy, Debug)]
pub struct CaseStream {
    key: [u64; 2],
    case: u64,
}

impl CaseStream {
    pub fn new(seed: u64, stream: u64, case: u64) -> Self {
        Self {
            key: [seed, stream],
            case,
        }
    }

    /// Four independent 64-bit words for `counter`.
    #[inline]
    pub fn block(&self, counter: u64) -> [u64; 4] {
        philox4x64_10([counter, self.case, 0, 0], self.key)
    }

    /// Four uniforms on `[0, 1)` (53-bit resolution).
    #[inline]
    pub fn uniforms(&self, counter: u64) -> [f64; 4] {
        self.block(counter).map(unit_open_above)
    }

    /// Four standard normals (Box-Muller on the block's two pairs).
    #[inline]
    pub fn normals(&self, counter: u64) -> [f64; 4] {
        let b = self.block(counter);
        let (z0, z1) = box_muller(b[0], b[1]);
        let (z2, z3) = box_muller(b[2], b[3]);
        [z0, z1, z2, z3]
    }

    /// Fill `out` with uniforms, four per counter starting at `first_counter`.
    pub fn fill_uniforms(&self, first_counter: u64, out: &mut [f64]) {
        for (j, chunk) in out.chunks_mut(4).enumerate() {
            let u = self.uniforms(first_counter + j as u64);
            chunk.copy_from_slice(&u[..chunk.len()]);
        }
    }

    /// Fill `out` with standard normals, four per counter starting at `first_counter`.
    pub fn fill_normals(&self, first_counter: u64, out: &mut [f64]) {
        for (j, chunk) in out.chunks_mut(4).enumerate() {
            let z = self.normals(first_counter + j as u64);
            chunk.copy_from_slice(&z[..chunk.len()]);
        }
    }
}

const TWO_POW_M53: f64 = 1.0 / (1u64 << 53) as f64;

/// `[0, 1)` from the top 53 bits.
#[inline(always)]
pub fn unit_open_above(x: u64) -> f64 {
    (x >> 11) as f64 * TWO_POW_M53
}

/// `(0, 1]` from the top 53 bits, safe for a logarithm.
#[inline(always)]
fn unit_open_below(x: u64) -> f64 {
    ((x >> 11) + 1) as f64 * TWO_POW_M53
}

#[inline]
fn box_muller(a: u64, b: u64) -> (f64, f64) {
    let r = (-2.0 * unit_open_below(a).ln()).sqrt();
    let (s, c) = (std::f64::consts::TAU * unit_open_above(b)).sin_cos();
    (r * c, r * s)
}

/// Box-Muller over a block's lanes: lane i holds one case's pair of words, as
/// [`CaseStream::normals`] takes them (a lane not set gives the normals 0 and 0, as the
/// padding lanes of a block had before). The logarithm and the sine and cosine are the lane
/// types' own ([`crate::lanes`]): the same bits at every instruction-set level, and within a
/// few ulp of libm's (the test below). libm, one lane at a time, cost a realistic campaign
/// more than half its time (the sensor's twelve normals per case and period; BENCHMARKS.md).
#[derive(Clone, Copy, Debug)]
pub(crate) struct LanePairs<R> {
    below: R,
    above: R,
}

impl<R: Real> LanePairs<R> {
    /// Every lane unset: a uniform of 1 below (its logarithm 0, so a radius of 0).
    #[inline(always)]
    pub(crate) fn new() -> Self {
        Self {
            below: R::one(),
            above: R::zero(),
        }
    }

    /// Lane `lane` at the words `(a, b)`.
    #[inline(always)]
    pub(crate) fn set(&mut self, lane: usize, a: u64, b: u64) {
        self.below.set_lane(lane, unit_open_below(a));
        self.above.set_lane(lane, unit_open_above(b));
    }

    /// The two normals of every lane.
    #[inline(always)]
    pub(crate) fn normals(self) -> (R, R) {
        let r = (R::splat(-2.0) * self.below.ln()).sqrt();
        let (s, c) = (R::splat(std::f64::consts::TAU) * self.above).sin_cos();
        (r * c, r * s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Known answers read off numpy.random.Philox (an independent implementation of the same
    // generator) for the Random123 test counters and keys.
    #[test]
    fn philox_known_answers() {
        assert_eq!(
            philox4x64_10([0; 4], [0; 2]),
            [
                0x16554d9eca36314c,
                0xdb20fe9d672d0fdc,
                0xd7e772cee186176b,
                0x7e68b68aec7ba23b
            ]
        );
        assert_eq!(
            philox4x64_10([u64::MAX; 4], [u64::MAX; 2]),
            [
                0x87b092c3013fe90b,
                0x438c3c67be8d0224,
                0x9cc7d7c69cd777b6,
                0xa09caebf594f0ba0
            ]
        );
        assert_eq!(
            philox4x64_10(
                [
                    0x243f6a8885a308d3,
                    0x13198a2e03707344,
                    0xa4093822299f31d0,
                    0x082efa98ec4e6c89
                ],
                [0x452821e638d01377, 0xbe5466cf34e90c6c]
            ),
            [
                0xa528f45403e61d95,
                0x38c72dbd566e9788,
                0xa5a1610e72fd18b5,
                0x57bd43b5e52b7fe6
            ]
        );
    }

    #[test]
    fn uniforms_in_range_and_moments() {
        let s = CaseStream::new(7, streams::DISTURBANCE, 3);
        let mut v = vec![0.0; 40_000];
        s.fill_uniforms(0, &mut v);
        assert!(v.iter().all(|&u| (0.0..1.0).contains(&u)));
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        let var = v.iter().map(|u| (u - mean).powi(2)).sum::<f64>() / v.len() as f64;
        // standard errors: 0.0014 for the mean, 0.0004 for the variance
        assert!((mean - 0.5).abs() < 0.007, "{mean}");
        assert!((var - 1.0 / 12.0).abs() < 0.002, "{var}");
    }

    #[test]
    fn normals_moments() {
        let s = CaseStream::new(1, streams::DISPERSION, 0);
        let mut v = vec![0.0; 40_000];
        s.fill_normals(0, &mut v);
        let n = v.len() as f64;
        let mean = v.iter().sum::<f64>() / n;
        let var = v.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / n;
        let kurt = v.iter().map(|z| (z - mean).powi(4)).sum::<f64>() / n / var.powi(2);
        assert!(mean.abs() < 0.025, "{mean}");
        assert!((var - 1.0).abs() < 0.035, "{var}");
        assert!((kurt - 3.0).abs() < 0.15, "{kurt}");
    }

    /// The lanes' Box-Muller against libm's, one lane at a time (`normals`): within 4 ulp of
    /// the pair's radius, for 4000 pairs, at lanes of every width the portable type has; and
    /// the lanes left unset give 0.
    #[test]
    fn lane_normals_agree_with_libm() {
        use crate::lanes::Lanes;
        fn check<const N: usize>() {
            let s = CaseStream::new(5, streams::SENSOR, 9);
            let mut worst = 0.0f64;
            for counter in 0..(4000 / N as u64) {
                let mut pairs = [LanePairs::<Lanes<N>>::new(); 2];
                let mut want = [[0.0; 4]; N];
                for (lane, want) in want.iter_mut().enumerate() {
                    let c = counter * N as u64 + lane as u64;
                    let w = s.block(c);
                    pairs[0].set(lane, w[0], w[1]);
                    pairs[1].set(lane, w[2], w[3]);
                    *want = s.normals(c);
                }
                let ((z0, z1), (z2, z3)) = (pairs[0].normals(), pairs[1].normals());
                for (lane, want) in want.iter().enumerate() {
                    let got = [z0.0[lane], z1.0[lane], z2.0[lane], z3.0[lane]];
                    for p in 0..2 {
                        let radius = want[2 * p].hypot(want[2 * p + 1]);
                        for z in 2 * p..2 * p + 2 {
                            let ulps = (got[z] - want[z]).abs() / (radius * f64::EPSILON);
                            worst = worst.max(ulps);
                        }
                    }
                }
            }
            assert!(worst <= 4.0, "{N} lanes: {worst} ulp of the radius");
            let (a, b) = LanePairs::<Lanes<N>>::new().normals();
            assert!(a.0.iter().chain(&b.0).all(|&z| z == 0.0));
        }
        check::<1>();
        check::<4>();
        check::<8>();
    }

    #[test]
    fn cases_and_streams_are_distinct() {
        let a = CaseStream::new(0, 0, 0).block(0);
        let b = CaseStream::new(0, 0, 1).block(0);
        let c = CaseStream::new(0, 1, 0).block(0);
        let d = CaseStream::new(1, 0, 0).block(0);
        assert_ne!(a, b);
        assert_ne!(a, c);
        assert_ne!(a, d);
        assert_ne!(b, c);
    }
}
