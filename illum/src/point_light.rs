//! Point and directional lights, with Bergeron's sphere of influence.

use crate::error::IllumError;
use crate::vec3::{Vec3, dot, norm, scale, sub};

/// Which sides of a receiver take light.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Sidedness {
    /// Only the side the normal points to; light from behind gives 0.
    #[default]
    OneSided,
    /// Both sides, with `|cos|`.
    TwoSided,
}

impl Sidedness {
    /// The cosine factor a receiver of this kind takes: `max(cos, 0)` or
    /// `|cos|`.
    #[inline]
    pub fn cosine(self, cos: f64) -> f64 {
        match self {
            Sidedness::OneSided => cos.max(0.0),
            Sidedness::TwoSided => cos.abs(),
        }
    }
}

/// Bergeron's sphere of influence: factor 1 up to `start`,
/// `((range - r) / (range - start))^exponent` between, 0 from `range` on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Falloff {
    start: f64,
    range: f64,
    exponent: f64,
}

impl Falloff {
    /// Checks `0 <= start <= range`, `range > 0`, `exponent > 0`, all finite.
    pub fn new(start: f64, range: f64, exponent: f64) -> Result<Self, IllumError> {
        let ok = start.is_finite()
            && range.is_finite()
            && exponent.is_finite()
            && start >= 0.0
            && start <= range
            && range > 0.0
            && exponent > 0.0;
        if ok {
            Ok(Self {
                start,
                range,
                exponent,
            })
        } else {
            Err(IllumError::BadFalloff {
                start,
                range,
                exponent,
            })
        }
    }

    /// Distance where the decrease starts.
    pub fn start(&self) -> f64 {
        self.start
    }

    /// Distance where the factor reaches 0.
    pub fn range(&self) -> f64 {
        self.range
    }

    /// Shape of the decrease.
    pub fn exponent(&self) -> f64 {
        self.exponent
    }

    /// The factor at distance `r`.
    #[inline]
    pub fn factor(&self, r: f64) -> f64 {
        if r <= self.start {
            1.0
        } else if r >= self.range {
            0.0
        } else {
            ((self.range - r) / (self.range - self.start)).powf(self.exponent)
        }
    }
}

fn check_vec(v: Vec3) -> Result<Vec3, IllumError> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(v)
    } else {
        Err(IllumError::BadVector { value: v })
    }
}

fn check_strength(s: f64) -> Result<f64, IllumError> {
    if s.is_finite() && s >= 0.0 {
        Ok(s)
    } else {
        Err(IllumError::BadStrength { value: s })
    }
}

/// An isotropic point light of radiant intensity `intensity`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLight {
    position: Vec3,
    intensity: f64,
    falloff: Option<Falloff>,
}

impl PointLight {
    /// A point light without falloff; the position must be finite and the
    /// intensity finite and non-negative.
    pub fn new(position: Vec3, intensity: f64) -> Result<Self, IllumError> {
        Ok(Self {
            position: check_vec(position)?,
            intensity: check_strength(intensity)?,
            falloff: None,
        })
    }

    /// The same light with a sphere of influence.
    pub fn with_falloff(self, falloff: Falloff) -> Self {
        Self {
            falloff: Some(falloff),
            ..self
        }
    }

    /// Position.
    pub fn position(&self) -> Vec3 {
        self.position
    }

    /// Radiant intensity.
    pub fn intensity(&self) -> f64 {
        self.intensity
    }

    /// Sphere of influence, if any.
    pub fn falloff(&self) -> Option<Falloff> {
        self.falloff
    }

    /// `I * cos / r^2 * falloff(r)` at `p` on a receiver of unit normal `n`;
    /// 0 at the light's own position.
    #[inline]
    pub fn irradiance(&self, p: Vec3, n: Vec3, sidedness: Sidedness) -> f64 {
        let d = sub(self.position, p);
        // In units of the largest component, so that the square of a
        // distance of 1e-200 does not underflow to 0 (nor one of 1e200
        // overflow): the value itself then over- or underflows only when
        // it is out of range.
        let m = d.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
        if m == 0.0 {
            return 0.0;
        }
        let unit = d.map(|c| c / m);
        let scaled = dot(unit, unit).sqrt();
        let r = m * scaled;
        let f = self.falloff.map_or(1.0, |f| f.factor(r));
        if f == 0.0 {
            return 0.0;
        }
        let cos = sidedness.cosine(dot(n, unit) / scaled);
        self.intensity * cos * f / (scaled * scaled) / m / m
    }
}

/// A directional light: parallel rays travelling along `direction`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectionalLight {
    direction: Vec3,
    irradiance: f64,
}

impl DirectionalLight {
    /// `direction` is the way light travels (normalised here; must be finite
    /// and non-zero); `irradiance` is measured perpendicular to it.
    pub fn new(direction: Vec3, irradiance: f64) -> Result<Self, IllumError> {
        let direction = check_vec(direction)?;
        // Scaled to a largest component of 1 before its length is taken,
        // which would underflow for a tiny direction (1e-300) and
        // overflow for a huge one.
        let largest = direction.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
        if largest == 0.0 {
            return Err(IllumError::BadVector { value: direction });
        }
        let direction = direction.map(|c| c / largest);
        let len = norm(direction);
        Ok(Self {
            direction: scale(direction, 1.0 / len),
            irradiance: check_strength(irradiance)?,
        })
    }

    /// Unit direction of travel.
    pub fn direction(&self) -> Vec3 {
        self.direction
    }

    /// Irradiance on a surface facing the light.
    pub fn strength(&self) -> f64 {
        self.irradiance
    }

    /// `I * cos` on a receiver of unit normal `n` (`cos = -n . direction`).
    #[inline]
    pub fn irradiance(&self, n: Vec3, sidedness: Sidedness) -> f64 {
        self.irradiance * sidedness.cosine(-dot(n, self.direction))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn falloff_profile() {
        let f = Falloff::new(5.0, 20.0, 2.0).unwrap();
        assert_eq!(f.factor(0.0), 1.0);
        assert_eq!(f.factor(5.0), 1.0);
        assert!((f.factor(12.5) - 0.25).abs() < 1e-15);
        assert_eq!(f.factor(20.0), 0.0);
        assert_eq!(f.factor(100.0), 0.0);
        let step = Falloff::new(3.0, 3.0, 1.0).unwrap();
        assert_eq!(step.factor(2.999), 1.0);
        assert_eq!(step.factor(3.001), 0.0);
    }

    #[test]
    fn bad_falloff_is_an_error() {
        assert!(Falloff::new(5.0, 4.0, 1.0).is_err());
        assert!(Falloff::new(-1.0, 4.0, 1.0).is_err());
        assert!(Falloff::new(0.0, 0.0, 1.0).is_err());
        assert!(Falloff::new(0.0, 4.0, 0.0).is_err());
        assert!(Falloff::new(0.0, f64::NAN, 1.0).is_err());
    }

    #[test]
    fn inverse_square_holds_where_the_squared_distance_leaves_the_float_range() {
        // At a unit's scale: 3 / 5^2 * cos, with cos = 3 / 5.
        let unit = PointLight::new([4.0, 3.0, 0.0], 3.0).unwrap();
        let e = unit.irradiance([0.0; 3], [0.0, 1.0, 0.0], Sidedness::OneSided);
        assert!((e - 0.072).abs() < 1e-15);
        // Scaled by s, with the intensity times k: k / s^2 times that,
        // though the distance squared under- (1e-340) or overflows (1e340).
        for (s, k) in [(1e-170, 1e-300), (1e170, 1e300)] {
            let light = PointLight::new([4.0 * s, 3.0 * s, 0.0], 3.0 * k).unwrap();
            let e = light.irradiance([0.0; 3], [0.0, 1.0, 0.0], Sidedness::OneSided);
            let want = 0.072 * (k / s) / s;
            assert!(
                (e - want).abs() < 1e-14 * want,
                "scale {s:e}: {e} for {want}"
            );
        }
    }

    #[test]
    fn point_light_inverse_square_cosine() {
        let l = PointLight::new([0.0, 2.0, 0.0], 8.0).unwrap();
        let up = [0.0, 1.0, 0.0];
        assert!((l.irradiance([0.0; 3], up, Sidedness::OneSided) - 2.0).abs() < 1e-15);
        // 45 degrees at distance 2 sqrt 2.
        let e = l.irradiance([2.0, 0.0, 0.0], up, Sidedness::OneSided);
        assert!((e - 8.0 * (0.5_f64).sqrt() / 8.0).abs() < 1e-15);
        let down = [0.0, -1.0, 0.0];
        assert_eq!(l.irradiance([0.0; 3], down, Sidedness::OneSided), 0.0);
        assert!((l.irradiance([0.0; 3], down, Sidedness::TwoSided) - 2.0).abs() < 1e-15);
        assert_eq!(l.irradiance([0.0, 2.0, 0.0], up, Sidedness::OneSided), 0.0);
    }

    #[test]
    fn point_light_falloff_applies() {
        let l = PointLight::new([0.0, 10.0, 0.0], 100.0)
            .unwrap()
            .with_falloff(Falloff::new(5.0, 20.0, 1.0).unwrap());
        let up = [0.0, 1.0, 0.0];
        // r = 10: factor (20 - 10) / 15.
        let e = l.irradiance([0.0; 3], up, Sidedness::OneSided);
        assert!((e - 100.0 / 100.0 * (10.0 / 15.0)).abs() < 1e-15);
        assert_eq!(
            l.irradiance([0.0, -10.0, 0.0], up, Sidedness::OneSided),
            0.0
        );
    }

    #[test]
    fn directional_cosine() {
        let l = DirectionalLight::new([0.0, -2.0, 0.0], 3.0).unwrap();
        assert!((l.irradiance([0.0, 1.0, 0.0], Sidedness::OneSided) - 3.0).abs() < 1e-15);
        assert_eq!(l.irradiance([0.0, -1.0, 0.0], Sidedness::OneSided), 0.0);
        assert!((l.irradiance([0.0, -1.0, 0.0], Sidedness::TwoSided) - 3.0).abs() < 1e-15);
        assert!(DirectionalLight::new([0.0; 3], 1.0).is_err());
        assert!(PointLight::new([f64::NAN, 0.0, 0.0], 1.0).is_err());
        assert!(PointLight::new([0.0; 3], -1.0).is_err());
    }

    /// A direction whose length underflows or overflows `f64` (its
    /// components do not) is a direction like any other.
    #[test]
    fn tiny_and_huge_directions_normalise() {
        for (given, unit) in [
            ([0.0, -1e-300, 0.0], [0.0, -1.0, 0.0]),
            ([3e-320, 0.0, -4e-320], [0.6, 0.0, -0.8]),
            ([1e300, 1e300, 0.0], [0.5_f64.sqrt(), 0.5_f64.sqrt(), 0.0]),
        ] {
            let d = DirectionalLight::new(given, 1.0).unwrap().direction();
            for k in 0..3 {
                assert!((d[k] - unit[k]).abs() < 1e-3, "{given:?}: {d:?}");
            }
        }
    }
}
