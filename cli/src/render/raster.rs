//! A z-buffered triangle rasteriser on a grid of samples, with
//! perspective-correct interpolation of one colour per vertex.

/// No triangle covers the sample.
pub(crate) const EMPTY: u32 = u32::MAX;

/// One triangle corner, already projected.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Corner {
    /// Position in sample units (pixel coordinates times the samples per
    /// pixel side).
    pub xy: [f64; 2],
    /// View depth (positive).
    pub depth: f64,
    /// The value to interpolate (a linear colour).
    pub value: [f64; 3],
}

/// The sample grid: per sample the nearest surface's inverse depth, the id
/// of the fragment it belongs to and, if asked for, its interpolated value.
#[derive(Debug)]
pub(crate) struct Samples {
    /// Samples per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// 1 / depth of the nearest surface so far (0: nothing).
    inverse_depth: Vec<f32>,
    /// Fragment id of the nearest surface, or [`EMPTY`].
    pub id: Vec<u32>,
    /// Interpolated value of the nearest surface (empty unless asked for).
    pub value: Vec<[f32; 3]>,
    /// Whether a triangle covers only samples it is nearer at (z-buffer),
    /// or every sample it covers (painter's order).
    depth_test: bool,
}

impl Samples {
    /// An empty grid; `values` says whether to keep interpolated values.
    /// `None` when the memory for it cannot be had (a big image: 20 bytes
    /// a sample).
    pub fn new(width: usize, height: usize, values: bool) -> Option<Self> {
        let n = width.checked_mul(height)?;
        Some(Self {
            width,
            height,
            inverse_depth: filled(n, 0.0)?,
            id: filled(n, EMPTY)?,
            value: if values {
                filled(n, [0.0; 3])?
            } else {
                Vec::new()
            },
            depth_test: true,
        })
    }

    /// An empty grid for the painter's algorithm: every triangle drawn
    /// covers what was there, whatever its depth.
    pub fn painter(width: usize, height: usize, values: bool) -> Option<Self> {
        Some(Self {
            depth_test: false,
            ..Self::new(width, height, values)?
        })
    }

    /// Replaces the interpolated values, sample after sample (a grid made
    /// without values takes none).
    pub fn set_values(&mut self, values: impl Iterator<Item = [f32; 3]>) {
        for (slot, v) in self.value.iter_mut().zip(values) {
            *slot = v;
        }
    }

    /// Draws one triangle of fragment `id` (either orientation): every
    /// sample whose centre lies inside or on its edges and which is nearer
    /// than what is there takes it. The first triangle drawn wins ties, so
    /// the result depends only on the drawing order.
    pub fn triangle(&mut self, c: [Corner; 3], id: u32) {
        let area = edge(c[0].xy, c[1].xy, c[2].xy);
        if area == 0.0 || !area.is_finite() {
            return;
        }
        let min_x = c.iter().map(|v| v.xy[0]).fold(f64::INFINITY, f64::min);
        let max_x = c.iter().map(|v| v.xy[0]).fold(f64::NEG_INFINITY, f64::max);
        let min_y = c.iter().map(|v| v.xy[1]).fold(f64::INFINITY, f64::min);
        let max_y = c.iter().map(|v| v.xy[1]).fold(f64::NEG_INFINITY, f64::max);
        // Samples whose centre (i + 0.5) lies in [min, max].
        let first = |lo: f64| (lo - 0.5).ceil().max(0.0);
        let last = |hi: f64, n: usize| (hi - 0.5).floor().min(n as f64 - 1.0);
        let (x0, x1) = (first(min_x), last(max_x, self.width));
        let (y0, y1) = (first(min_y), last(max_y, self.height));
        if x0 > x1 || y0 > y1 {
            return;
        }
        let inverse: [f64; 3] = [1.0 / c[0].depth, 1.0 / c[1].depth, 1.0 / c[2].depth];
        let keep_values = !self.value.is_empty();
        for y in y0 as usize..=y1 as usize {
            let py = y as f64 + 0.5;
            for x in x0 as usize..=x1 as usize {
                let p = [x as f64 + 0.5, py];
                // Barycentric coordinates, positive inside whatever the
                // orientation.
                let l0 = edge(c[1].xy, c[2].xy, p) / area;
                let l1 = edge(c[2].xy, c[0].xy, p) / area;
                let l2 = edge(c[0].xy, c[1].xy, p) / area;
                if l0 < 0.0 || l1 < 0.0 || l2 < 0.0 {
                    continue;
                }
                // 1 / depth is affine in screen space.
                let w = [l0 * inverse[0], l1 * inverse[1], l2 * inverse[2]];
                let inv = w[0] + w[1] + w[2];
                let k = y * self.width + x;
                if self.depth_test && inv as f32 <= self.inverse_depth[k] {
                    continue;
                }
                self.inverse_depth[k] = inv as f32;
                self.id[k] = id;
                if keep_values {
                    let mut v = [0.0f32; 3];
                    for (ch, out) in v.iter_mut().enumerate() {
                        let s =
                            w[0] * c[0].value[ch] + w[1] * c[1].value[ch] + w[2] * c[2].value[ch];
                        *out = (s / inv) as f32;
                    }
                    self.value[k] = v;
                }
            }
        }
    }
}

/// Twice the signed area of triangle `a b p`.
fn edge(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

/// `n` copies of `value`, or `None` if the memory cannot be had (rather
/// than aborting the process).
fn filled<T: Clone>(n: usize, value: T) -> Option<Vec<T>> {
    let mut out = Vec::new();
    out.try_reserve_exact(n).ok()?;
    out.resize(n, value);
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn corner(x: f64, y: f64, depth: f64, value: f64) -> Corner {
        Corner {
            xy: [x, y],
            depth,
            value: [value; 3],
        }
    }

    #[test]
    fn nearer_wins_and_values_are_perspective_correct() {
        let mut s = Samples::new(4, 4, true).unwrap();
        // A far square (two triangles, either orientation) over all samples.
        let far = [
            corner(0.0, 0.0, 10.0, 1.0),
            corner(4.0, 0.0, 10.0, 1.0),
            corner(4.0, 4.0, 10.0, 1.0),
        ];
        s.triangle(far, 7);
        s.triangle(
            [
                corner(0.0, 0.0, 10.0, 1.0),
                corner(0.0, 4.0, 10.0, 1.0),
                corner(4.0, 4.0, 10.0, 1.0),
            ],
            7,
        );
        assert!(s.id.iter().all(|&i| i == 7));
        // A nearer triangle over the left column wins there only.
        s.triangle(
            [
                corner(0.0, -10.0, 1.0, 0.0),
                corner(1.0, -10.0, 1.0, 0.0),
                corner(0.5, 20.0, 1.0, 0.0),
            ],
            3,
        );
        for y in 0..4 {
            assert_eq!(s.id[y * 4], 3);
            assert_eq!(s.id[y * 4 + 1], 7);
        }
        // A farther one changes nothing.
        s.triangle(far.map(|c| Corner { depth: 20.0, ..c }), 9);
        assert!(!s.id.contains(&9));
        // Unless painted.
        let mut p = Samples::painter(4, 4, false).unwrap();
        p.triangle(far, 7);
        p.triangle(far.map(|c| Corner { depth: 20.0, ..c }), 9);
        assert!(p.id.iter().all(|&i| i == 9 || i == EMPTY) && p.id.contains(&9));

        // Perspective: a value going from 0 at depth 1 to 1 at depth 3
        // across the screen. At the screen midpoint of such a segment
        // 1 / depth is the mean (2/3, depth 1.5), where the value is 0.25.
        let mut s = Samples::new(2, 1, true).unwrap();
        s.triangle(
            [
                corner(0.0, -5.0, 1.0, 0.0),
                corner(0.0, 5.0, 1.0, 0.0),
                corner(2.0, 0.0, 3.0, 1.0),
            ],
            0,
        );
        // Sample 0 centre at x = 0.5: a quarter of the way in screen space.
        // 1/depth = 0.75 * 1 + 0.25 / 3 = 5/6; value = (0.25 / 3) / (5/6).
        let expected = (0.25 / 3.0) / (5.0 / 6.0);
        assert!((f64::from(s.value[0][0]) - expected).abs() < 1e-6);
    }

    /// A grid whose samples no memory holds is refused, not aborted on
    /// (a 16384-pixel square image at 9 samples a pixel needs 48 GB).
    #[test]
    fn a_grid_beyond_memory_is_none() {
        assert!(Samples::new(1 << 40, 1 << 30, true).is_none());
        assert!(Samples::painter(usize::MAX, 2, false).is_none());
        // (2^50 samples, 4 PB: the allocator refuses.)
        assert!(Samples::new(1 << 30, 1 << 20, false).is_none());
        assert!(Samples::new(3, 2, true).is_some());
    }
}
