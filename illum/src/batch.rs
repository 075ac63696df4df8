//! Many receivers in parallel with rayon.
//!
//! Every receiver is computed independently and written to its own slot of
//! the output; there is no parallel reduction, so the results are bit for
//! bit the same whatever the number of threads.

use crate::area_light::AreaLight;
use crate::error::IllumError;
use crate::point_light::Sidedness;
use crate::vec3::Vec3;
use crate::visibility::{VisiblePart, visible_irradiance};
use rayon::prelude::*;

/// A point to evaluate and its unit normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Receiver {
    /// Position.
    pub position: Vec3,
    /// Unit normal.
    pub normal: Vec3,
}

/// Receivers handed to one rayon task at least.
const MIN_CHUNK: usize = 64;

fn check_len(receivers: usize, output: usize) -> Result<(), IllumError> {
    if receivers == output {
        Ok(())
    } else {
        Err(IllumError::LengthMismatch { receivers, output })
    }
}

/// `out[i] = f(&receivers[i])`, in parallel.
pub fn evaluate_batch<F>(receivers: &[Receiver], out: &mut [f64], f: F) -> Result<(), IllumError>
where
    F: Fn(&Receiver) -> f64 + Sync,
{
    check_len(receivers.len(), out.len())?;
    out.par_iter_mut()
        .zip(receivers.par_iter())
        .with_min_len(MIN_CHUNK)
        .for_each(|(o, r)| *o = f(r));
    Ok(())
}

/// Irradiance from the visible part of `light` past `occluders` at every
/// receiver, in parallel; each rayon task reuses one [`VisiblePart`].
pub fn area_irradiance_batch<O>(
    light: &AreaLight,
    occluders: &[O],
    receivers: &[Receiver],
    sidedness: Sidedness,
    out: &mut [f64],
) -> Result<(), IllumError>
where
    O: AsRef<[Vec3]> + Sync,
{
    check_len(receivers.len(), out.len())?;
    out.par_iter_mut()
        .zip(receivers.par_iter())
        .with_min_len(MIN_CHUNK)
        .for_each_init(VisiblePart::new, |scratch, (o, r)| {
            *o = visible_irradiance(light, occluders, r.position, r.normal, sidedness, scratch);
        });
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn length_mismatch_is_an_error() {
        let mut out = [0.0; 2];
        let r = [Receiver {
            position: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
        }];
        assert_eq!(
            evaluate_batch(&r, &mut out, |_| 1.0),
            Err(IllumError::LengthMismatch {
                receivers: 1,
                output: 2
            })
        );
    }
}
