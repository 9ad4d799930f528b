//! Out-of-line wrappers of the lane transcendentals on `Lanes<16>`, to read the code the
//! compiler makes of them at the AVX-512 level and at the x86-64 baseline:
//!
//! ```text
//! cargo build --release -p landing_core --example lane_math_asm
//! objdump -d --no-show-raw-insn target/release/examples/lane_math_asm \
//!     | awk '/<lane_exp_avx512>:/,/^$/'
//! ```
//!
//! Each wrapper should be straight-line vector code (zmm registers at AVX-512) with no call,
//! except `sin_cos`'s single call to its cold per-lane path for |x| > 2^20 pi/2. Running the
//! example prints one value per function, as a smoke test.

use std::hint::black_box;

use landing_core::lanes::{Lanes, Real, math};

type L = Lanes<16>;

macro_rules! wrappers {
    ($($name:ident, $name_base:ident: |$x:ident, $y:ident| $body:expr;)*) => {
        $(
            /// # Safety
            /// The CPU must support AVX-512 F, DQ and VL, AVX2 and FMA.
            #[cfg(target_arch = "x86_64")]
            #[unsafe(no_mangle)]
            #[inline(never)]
            #[target_feature(enable = "avx512f,avx512dq,avx512vl,avx2,fma")]
            pub unsafe fn $name($x: &L, $y: &L, out: &mut [L; 2]) {
                *out = $body;
            }

            #[unsafe(no_mangle)]
            #[inline(never)]
            pub fn $name_base($x: &L, $y: &L, out: &mut [L; 2]) {
                *out = $body;
            }
        )*

        fn run_all(x: &L, y: &L) -> Vec<(&'static str, [L; 2])> {
            let mut results = Vec::new();
            $(
                let mut out = [L::splat(0.0); 2];
                $name_base(black_box(x), black_box(y), &mut out);
                results.push((stringify!($name_base), out));
                #[cfg(target_arch = "x86_64")]
                if is_x86_feature_detected!("avx512f")
                    && is_x86_feature_detected!("avx512dq")
                    && is_x86_feature_detected!("avx512vl")
                {
                    let mut fast = [L::splat(0.0); 2];
                    // SAFETY: the features were just detected
                    unsafe { $name(black_box(x), black_box(y), &mut fast) };
                    assert_eq!(fast, out, "{}: AVX-512 and baseline differ", stringify!($name));
                }
            )*
            results
        }
    };
}

wrappers! {
    lane_exp_avx512, lane_exp_base: |x, _y| [math::exp(*x), L::splat(0.0)];
    lane_ln_avx512, lane_ln_base: |x, _y| [math::ln(*x), L::splat(0.0)];
    lane_pow_avx512, lane_pow_base: |x, y| [math::pow(*x, *y), L::splat(0.0)];
    lane_tanh_avx512, lane_tanh_base: |x, _y| [math::tanh(*x), L::splat(0.0)];
    lane_sin_cos_avx512, lane_sin_cos_base: |x, _y| {
        let (s, c) = math::sin_cos(*x);
        [s, c]
    };
    lane_atan2_avx512, lane_atan2_base: |x, y| [math::atan2(*y, *x), L::splat(0.0)];
}

fn main() {
    let x = L::from_fn(|i| 0.1 + 0.37 * i as f64);
    let y = L::from_fn(|i| 1.5 - 0.2 * i as f64);
    for (name, out) in run_all(&x, &y) {
        println!(
            "{name:20} lane 3: {:.17} {:.17}",
            out[0].lane(3),
            out[1].lane(3)
        );
    }
}
