//! `atan2(y, x)` for `y >= 0`, inlined: the fdlibm algorithm (argument
//! reduction to |t| < 7/16 around atan(1/2), atan(1), atan(3/2), then an
//! odd polynomial of degree 23), about 1 ulp like the libm call it replaces,
//! but cheap enough to interleave across the edges of a polygon.

// The constants are fdlibm's, digit for digit as published (its
// atan(1) = pi/4 entry included), so that they can be checked against it.
#![allow(clippy::excessive_precision, clippy::approx_constant)]

const ATAN_HI: [f64; 4] = [
    4.636_476_090_008_060_935_15e-01,
    7.853_981_633_974_482_789_99e-01,
    9.827_937_232_473_290_540_82e-01,
    1.570_796_326_794_896_558_00e+00,
];
const ATAN_LO: [f64; 4] = [
    2.269_877_745_296_168_709_24e-17,
    3.061_616_997_868_383_017_93e-17,
    1.390_331_103_123_099_845_16e-17,
    6.123_233_995_736_766_035_87e-17,
];
const AT: [f64; 11] = [
    3.333_333_333_333_293_180_27e-01,
    -1.999_999_999_987_648_324_76e-01,
    1.428_571_427_250_346_637_11e-01,
    -1.111_111_040_546_235_578_80e-01,
    9.090_887_133_436_506_561_96e-02,
    -7.691_876_205_044_829_994_95e-02,
    6.661_073_137_387_531_206_69e-02,
    -5.833_570_133_790_573_486_45e-02,
    4.976_877_994_615_932_360_17e-02,
    -3.653_157_274_421_691_552_70e-02,
    1.628_582_011_536_578_236_23e-02,
];
const PI_HI: f64 = std::f64::consts::PI;
const PI_LO: f64 = 1.224_646_799_147_353_207_2e-16;

/// `atan(t)` for `t >= 0` (including `+inf`).
#[inline(always)]
fn atan_pos(t: f64) -> f64 {
    let (id, x) = if t < 0.4375 {
        (usize::MAX, t)
    } else if t < 0.6875 {
        (0, (2.0 * t - 1.0) / (2.0 + t))
    } else if t < 1.1875 {
        (1, (t - 1.0) / (t + 1.0))
    } else if t < 2.4375 {
        (2, (t - 1.5) / (1.0 + 1.5 * t))
    } else {
        (3, -1.0 / t)
    };
    let z = x * x;
    let w = z * z;
    let s1 = z * (AT[0] + w * (AT[2] + w * (AT[4] + w * (AT[6] + w * (AT[8] + w * AT[10])))));
    let s2 = w * (AT[1] + w * (AT[3] + w * (AT[5] + w * (AT[7] + w * AT[9]))));
    if id == usize::MAX {
        x - x * (s1 + s2)
    } else {
        ATAN_HI[id] - ((x * (s1 + s2) - ATAN_LO[id]) - x)
    }
}

/// `atan2(y, x)` for `y >= 0` and finite `x` (the angle between two
/// vectors from `|a x b|` and `a . b`), in `[0, pi]`.
#[inline(always)]
pub(crate) fn atan2_pos(y: f64, x: f64) -> f64 {
    if x > 0.0 {
        atan_pos(y / x)
    } else if x < 0.0 {
        PI_HI - (atan_pos(y / -x) - PI_LO)
    } else if y > 0.0 {
        0.5 * PI_HI
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ulps(a: f64, b: f64) -> u64 {
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
    }

    #[test]
    fn matches_libm() {
        // A simple LCG: no dev-dependency needed in unit tests.
        let mut s = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut worst = 0;
        for _ in 0..200_000 {
            let y = next() * 10f64.powf(next() * 20.0 - 10.0);
            let x = (next() - 0.5) * 10f64.powf(next() * 20.0 - 10.0);
            let (ours, libm) = (atan2_pos(y, x), y.atan2(x));
            worst = worst.max(ulps(ours, libm));
            assert!(ulps(ours, libm) <= 2, "atan2({y}, {x}): {ours} vs {libm}");
        }
        for (y, x) in [
            (0.0, 1.0),
            (0.0, -1.0),
            (1.0, 0.0),
            (0.0, 0.0),
            (1e-300, 1.0),
            (1.0, 1e-300),
        ] {
            assert!(ulps(atan2_pos(y, x), f64::atan2(y, x)) <= 1, "{y} {x}");
        }
        assert!(worst <= 2);
    }
}
