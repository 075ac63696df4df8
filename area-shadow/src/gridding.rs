//! Gridding and adaptive subdivision of lit and penumbra fragments (the
//! 1992 paper's "grid" phase), so that interpolated vertex irradiance
//! follows the smooth falloff of light across a fragment.
//!
//! Cells are cut by axis-aligned planes at multiples of a cell size in grid
//! units: the same lattice for every polygon, so coplanar neighbours are
//! cut along the same lines. Each fragment is cut along the two axes of its
//! plane (the axes other than its normal's dominant one). Penumbra
//! fragments, where irradiance changes fastest, get half the cell size;
//! umbra fragments are not cut. Adaptive subdivision then halves a cell
//! across its longer side (so no cell becomes a sliver of the lattice)
//! while the irradiance at its corners varies by more than a tolerance.
//!
//! The cutting planes are planes through grid points: cells are exact
//! polygons like every other fragment.

use bsp_core::{ConvexPolygon, GridPoint, Plane, Split};
use svbsp::Fragment;

/// How a fragment is treated when gridding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GridClass {
    /// Sees no light at all: left whole.
    Dark,
    /// Sees part of some area light: the fine cell size.
    Penumbra,
    /// Otherwise: the regular cell size.
    Lit,
}

impl GridClass {
    /// The class of `fragment` in a scene of `lights` lights whose area
    /// lights have their bits in `area_mask`.
    pub fn of(fragment: &Fragment, lights: usize, area_mask: u32) -> Self {
        let all = if lights >= 32 {
            u32::MAX
        } else {
            (1_u32 << lights) - 1
        };
        let penumbra = all & !fragment.lit_mask & !fragment.umbra_mask & area_mask;
        if penumbra != 0 {
            GridClass::Penumbra
        } else if fragment.umbra_mask & all == all {
            GridClass::Dark
        } else {
            GridClass::Lit
        }
    }
}

/// The two in-plane axes of a polygon: the axes other than its normal's
/// dominant one.
fn plane_axes(polygon: &ConvexPolygon) -> [usize; 2] {
    match polygon.support().dominant_axis() {
        0 => [1, 2],
        1 => [0, 2],
        _ => [0, 1],
    }
}

/// The plane `x_axis = value` facing `+axis`.
fn axis_plane(axis: usize, value: i64) -> Option<Plane> {
    let mut normal = [0_i64; 3];
    normal[axis] = 1;
    let mut p = [0_i64; 3];
    p[axis] = value;
    let point = GridPoint::new(p[0], p[1], p[2]).ok()?;
    Plane::with_normal_through(normal, point)
}

/// `polygon`'s extent along `axis`, in grid units.
fn extent(polygon: &ConvexPolygon, axis: usize) -> (f64, f64) {
    polygon
        .vertices_f64()
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), v| {
            (lo.min(v[axis]), hi.max(v[axis]))
        })
}

/// Cuts `polygon` by the planes `x_axis = k * cell` that cross it.
fn cut_along(polygon: ConvexPolygon, axis: usize, cell: i64, out: &mut Vec<ConvexPolygon>) {
    let (lo, hi) = extent(&polygon, axis);
    let first = (lo / cell as f64).floor() as i64 + 1;
    let last = (hi / cell as f64).ceil() as i64 - 1;
    let mut rest = polygon;
    for k in first..=last {
        let Some(plane) = axis_plane(axis, k * cell) else {
            continue;
        };
        match rest.split(&plane) {
            Split::Both(back, front) => {
                out.push(back);
                rest = front;
            }
            Split::Back => {
                // The remaining planes lie further along: done.
                break;
            }
            Split::Front | Split::Coplanar(_) => {}
        }
    }
    out.push(rest);
}

/// Cuts `polygon` into the cells of the lattice of size `cell`.
pub fn grid_polygon(polygon: ConvexPolygon, cell: i64) -> Vec<ConvexPolygon> {
    if cell <= 0 {
        return vec![polygon];
    }
    let [u, v] = plane_axes(&polygon);
    let mut strips = Vec::new();
    cut_along(polygon, u, cell, &mut strips);
    let mut cells = Vec::new();
    for strip in strips {
        cut_along(strip, v, cell, &mut cells);
    }
    cells
}

/// Grids every fragment by its class: `cell` for lit ones, `cell / 2` for
/// penumbra, none for those that see no light. `area_mask` holds the bits
/// of the area lights among `lights` lights.
pub fn grid_fragments(
    fragments: Vec<Fragment>,
    lights: usize,
    area_mask: u32,
    cell: i64,
) -> Vec<Fragment> {
    let mut out = Vec::with_capacity(fragments.len());
    for fragment in fragments {
        let size = match GridClass::of(&fragment, lights, area_mask) {
            GridClass::Dark => 0,
            GridClass::Penumbra => (cell / 2).max(1),
            GridClass::Lit => cell,
        };
        let (lit_mask, umbra_mask) = (fragment.lit_mask, fragment.umbra_mask);
        for polygon in grid_polygon(fragment.polygon, size) {
            out.push(Fragment {
                polygon,
                lit_mask,
                umbra_mask,
            });
        }
    }
    out
}

/// Halves `polygon` across its longer in-plane side, at a lattice point;
/// `None` when that side is shorter than `min_size` grid units.
pub fn halve(polygon: &ConvexPolygon, min_size: f64) -> Option<(ConvexPolygon, ConvexPolygon)> {
    let [u, v] = plane_axes(polygon);
    let (ul, uh) = extent(polygon, u);
    let (vl, vh) = extent(polygon, v);
    let (axis, lo, hi) = if uh - ul >= vh - vl {
        (u, ul, uh)
    } else {
        (v, vl, vh)
    };
    if hi - lo < min_size.max(2.0) {
        return None;
    }
    let middle = ((lo + hi) / 2.0).round() as i64;
    match polygon.split(&axis_plane(axis, middle)?) {
        Split::Both(back, front) => Some((back, front)),
        _ => None,
    }
}

/// Adaptive subdivision: each lit or penumbra fragment is halved while the
/// irradiance at its corners (`irradiance(fragment)`, one value per
/// vertex) varies by more than `tolerance` times the largest of them, and
/// its longer side is at least `min_size` grid units.
pub fn subdivide_adaptive<F>(
    fragments: Vec<Fragment>,
    lights: usize,
    area_mask: u32,
    tolerance: f64,
    min_size: f64,
    mut irradiance: F,
) -> Vec<Fragment>
where
    F: FnMut(&Fragment) -> Vec<f64>,
{
    let mut out = Vec::with_capacity(fragments.len());
    let mut stack: Vec<Fragment> = fragments.into_iter().rev().collect();
    while let Some(fragment) = stack.pop() {
        if GridClass::of(&fragment, lights, area_mask) == GridClass::Dark {
            out.push(fragment);
            continue;
        }
        let values = irradiance(&fragment);
        let (lo, hi) = values
            .iter()
            .fold((f64::MAX, f64::MIN), |(lo, hi), &e| (lo.min(e), hi.max(e)));
        let varies = hi > 0.0 && hi - lo > tolerance * hi;
        match varies.then(|| halve(&fragment.polygon, min_size)).flatten() {
            Some((a, b)) => {
                stack.push(Fragment {
                    polygon: b,
                    ..fragment
                });
                stack.push(Fragment {
                    polygon: a,
                    ..fragment
                });
            }
            None => out.push(fragment),
        }
    }
    out
}
