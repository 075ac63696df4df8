//! The angle between two vectors from `|a x b|` and `a . b`: `atan2` for a
//! non-negative first argument, inlined so that the edges of a light can
//! be integrated without a library call each.
//!
//! The argument is reduced to `t = min / max` in `[0, 1]` and then, by
//! `atan t = atan c + atan((t - c) / (1 + t c))` with `c` one of `0`,
//! `tan(pi/8)` and `1`, to `|u| <= tan(pi/16) < 0.2` (computed from `min`
//! and `max` with a single division), where the Taylor
//! series `u - u^3/3 + u^5/5 - ...` reaches `f64` precision after twelve
//! terms (the next is below `0.2^25 / 25 < 2e-19`).

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, FRAC_PI_8, PI, SQRT_2};

/// `tan(pi/16)` and `tan(3 pi/16)`: where the reduction changes centre
/// (any nearby values would do; they only bound `|u|`).
const TAN_PI_16: f64 = 0.198_912_367_379_658;
const TAN_3PI_16: f64 = 0.668_178_637_919_299;

/// `atan2(y, x)` for `y >= 0`, in `[0, pi]`; `0` for `y = x = 0`.
#[inline(always)]
pub(crate) fn angle(y: f64, x: f64) -> f64 {
    let ax = x.abs();
    let (num, den, swapped) = if y <= ax {
        (y, ax, false)
    } else {
        (ax, y, true)
    };
    if den == 0.0 {
        return 0.0;
    }
    let a = atan_ratio(num, den);
    let a = if swapped { FRAC_PI_2 - a } else { a };
    if x < 0.0 { PI - a } else { a }
}

/// `atan2(y, x) / y` for `y > 0`: the angle per unit of `|a x b|`, which
/// is what an edge of the contour integral needs.
///
/// For a small angle (`y <= tan(pi/16) x`, the common case of a light seen
/// from afar) it takes one division: with `r = 1 / x` and `u = y r`,
/// `atan u / y = r (1 + (atan u - u) / u)` from the series; otherwise it is
/// [`angle`]`(y, x) / y`.
#[inline(always)]
pub(crate) fn angle_over(y: f64, x: f64) -> f64 {
    if y <= TAN_PI_16 * x {
        let r = 1.0 / x;
        r * (1.0 + series_tail(y * r))
    } else {
        angle(y, x) / y
    }
}

/// `atan(num / den)` for `0 <= num <= den`, `den > 0`: the reduced
/// argument `(t - c) / (1 + t c)` of `t = num / den` is computed as
/// `(num - c den) / (den + c num)`, one division (with `c = 0`, `num / den`
/// itself), and the range is chosen by comparing `num` with multiples of
/// `den`.
#[inline(always)]
fn atan_ratio(num: f64, den: f64) -> f64 {
    if num <= TAN_PI_16 * den {
        series(num / den)
    } else if num <= TAN_3PI_16 * den {
        let c = SQRT_2 - 1.0;
        FRAC_PI_8 + series((num - c * den) / (den + c * num))
    } else {
        FRAC_PI_4 + series((num - den) / (den + num))
    }
}

/// The Taylor coefficients `(-1)^k / (2k + 1)` for `k = 1..=11`.
const SERIES: [f64; 11] = {
    let mut c = [0.0; 11];
    let mut k = 1;
    while k <= 11 {
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        c[k - 1] = sign / (2 * k + 1) as f64;
        k += 1;
    }
    c
};

/// `atan u` for `|u| <= 0.2`: the Taylor series to `u^23 / 23`.
#[inline(always)]
fn series(u: f64) -> f64 {
    u + u * series_tail(u)
}

/// `atan u / u - 1` for `|u| <= 0.2`, from the same series.
#[inline(always)]
fn series_tail(u: f64) -> f64 {
    // Estrin's scheme: the powers of z and the pairs of coefficients are
    // independent, so the chain of dependent operations is four deep
    // instead of eleven (the edges' angles are latency-bound).
    let c = &SERIES;
    let z = u * u;
    let z2 = z * z;
    let z4 = z2 * z2;
    let z8 = z4 * z4;
    let q0 = c[0] + c[1] * z;
    let q1 = c[2] + c[3] * z;
    let q2 = c[4] + c[5] * z;
    let q3 = c[6] + c[7] * z;
    let q4 = c[8] + c[9] * z;
    let r0 = q0 + q1 * z2;
    let r1 = q2 + q3 * z2;
    let r2 = q4 + c[10] * z2;
    z * ((r0 + r1 * z4) + r2 * z8)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    #[test]
    fn agrees_with_the_library_within_a_few_ulps() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        let mut worst = 0.0_f64;
        for _ in 0..200_000 {
            let y: f64 = rng.random_range(0.0..1.0) * 10f64.powi(rng.random_range(-8..8));
            let x: f64 = rng.random_range(-1.0..1.0) * 10f64.powi(rng.random_range(-8..8));
            let (ours, libm) = (angle(y, x), y.atan2(x));
            let ulp = f64::EPSILON * libm.abs().max(f64::MIN_POSITIVE);
            worst = worst.max((ours - libm).abs() / ulp);
        }
        assert!(worst <= 4.0, "worst error {worst} ulp");
        for (y, x) in [
            (0.0, 1.0),
            (0.0, -1.0),
            (1.0, 0.0),
            (0.0, 0.0),
            (1.0, 1.0),
            (1.0, -1.0),
            (3.0, 1e-300),
        ] {
            assert!(
                (angle(y, x) - f64::atan2(y, x)).abs() <= 4.0 * f64::EPSILON,
                "{y} {x}"
            );
        }
    }

    #[test]
    fn angle_over_agrees_with_the_library_within_a_few_ulps() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(4);
        let mut worst = 0.0_f64;
        for _ in 0..200_000 {
            let y: f64 =
                rng.random_range(f64::MIN_POSITIVE..1.0) * 10f64.powi(rng.random_range(-8..8));
            let x: f64 = rng.random_range(-1.0..1.0) * 10f64.powi(rng.random_range(-8..8));
            let (ours, libm) = (angle_over(y, x), y.atan2(x) / y);
            worst = worst.max((ours - libm).abs() / (f64::EPSILON * libm.abs()));
        }
        assert!(worst <= 4.0, "worst error {worst} ulp");
    }
}
