//! Shared by the tree's tests: a floor under a tilted light, random
//! occluders between them, trees built from them, and a comparison of two
//! trees' regions.

use crate::cell::{CellClass, Sides};
use crate::critical::{UnitPlanes, internal_planes};
use crate::surface::Surroundings;
use crate::tree::ReceiverDm;
use area_shadow::{AreaSource, volume_planes};
use bsp_core::{ConvexPolygon, GridPoint, Split};
use rand::Rng;
use rand_pcg::Pcg64;

fn g(x: i32, y: i32, z: i32) -> GridPoint {
    GridPoint { x, y, z }
}

pub(crate) fn floor() -> ConvexPolygon {
    ConvexPolygon::from_grid_points(
        &[g(-60, 0, 60), g(60, 0, 60), g(60, 0, -60), g(-60, 0, -60)],
        0,
    )
    .unwrap()
}

pub(crate) fn light() -> AreaSource {
    AreaSource::from_grid_points(&[g(-3, 40, -2), g(4, 40, -3), g(5, 41, 3), g(-2, 41, 4)]).unwrap()
}

/// Units numbered in order, as a receiver numbers them.
pub(crate) fn numbered(planes: &[UnitPlanes]) -> Vec<(u32, &UnitPlanes)> {
    planes
        .iter()
        .enumerate()
        .map(|(k, p)| (k as u32, p))
        .collect()
}

/// Random triangles and axis-aligned squares between the floor and the
/// light (some in one common plane, squares on a lattice sharing edge
/// lines, so that their discontinuities coincide).
pub(crate) fn occluders(rng: &mut Pcg64, n: usize) -> Vec<UnitPlanes> {
    let light = light();
    let mut out = Vec::new();
    while out.len() < n {
        let lattice = rng.random_bool(0.4);
        let y = if lattice || rng.random_bool(0.2) {
            20
        } else {
            rng.random_range(5..35)
        };
        let (x, z) = if lattice {
            (4 * rng.random_range(-6..6), 4 * rng.random_range(-6..6))
        } else {
            (rng.random_range(-30..30), rng.random_range(-30..30))
        };
        let polygon = if lattice || rng.random_bool(0.5) {
            let s = if lattice {
                4 * rng.random_range(1..3)
            } else {
                rng.random_range(2..10)
            };
            ConvexPolygon::from_grid_points(
                &[
                    g(x, y, z),
                    g(x + s, y, z),
                    g(x + s, y, z - s),
                    g(x, y, z - s),
                ],
                0,
            )
        } else {
            let mut c = || {
                (
                    rng.random_range(-8..8),
                    rng.random_range(-2..3),
                    rng.random_range(-8..8),
                )
            };
            let (a, b, d) = (c(), c(), c());
            ConvexPolygon::from_grid_points(
                &[
                    g(x + a.0, y + a.1, z + a.2),
                    g(x + b.0, y + b.1, z + b.2),
                    g(x + d.0, y + d.1, z + d.2),
                ],
                0,
            )
        };
        let Ok(polygon) = polygon else { continue };
        let volumes = volume_planes(&polygon, &light);
        if volumes.penumbra.is_empty() {
            continue;
        }
        let internal = internal_planes(&polygon, &light, &volumes, &Surroundings::default());
        out.push(UnitPlanes::new(volumes, internal));
    }
    out
}

/// A floor tiled to depth `tiles` with `units` inserted one by one.
pub(crate) fn fresh(units: &[(u32, &UnitPlanes)], tiles: u32) -> ReceiverDm<u32> {
    let mut dm = ReceiverDm::new(floor(), false, &[light()]);
    dm.tile(tiles);
    for &(k, p) in units {
        dm.insert(k, 0, p);
    }
    dm
}

/// The same, the tiles grown apart ([`ReceiverDm::insert_tiled`]), three
/// at a time (so that batches end between tiles and at the last one).
pub(crate) fn fresh_tiled(units: &[(u32, &UnitPlanes)], tiles: u32) -> ReceiverDm<u32> {
    let mut dm = ReceiverDm::new(floor(), false, &[light()]);
    let order: Vec<(u32, u8)> = units.iter().map(|&(k, _)| (k, 0)).collect();
    let planes =
        |k: u32, _: u8| -> &UnitPlanes { units.iter().find(|u| u.0 == k).expect("a unit").1 };
    dm.insert_tiles_apart(tiles, &order, &planes, 0, 3);
    dm
}

/// A cell: its polygon, class and occluder keys (umbra marked).
type CellView = (ConvexPolygon, CellClass, Vec<(u32, Sides)>);

/// Checks that every pair of overlapping cells of `a` and `b` has the
/// same class (and, outside umbra, the same occluders), and that the class
/// areas agree.
pub(crate) fn same_regions(a: &ReceiverDm<u32>, b: &ReceiverDm<u32>) {
    let cells = |dm: &ReceiverDm<u32>| -> Vec<CellView> {
        dm.cells()
            .map(|(f, c)| {
                let mut keys: Vec<(u32, Sides)> = c
                    .entries()
                    .iter()
                    .map(|e| (dm.unit(e.unit).unwrap().0, e.umbra))
                    .collect();
                keys.sort_unstable();
                (dm.mesh().face_polygon(f, 0).unwrap(), dm.class(c, 0), keys)
            })
            .collect()
    };
    let (ca, cb) = (cells(a), cells(b));
    let area = |cs: &[CellView], k: CellClass| -> f64 {
        cs.iter().filter(|c| c.1 == k).map(|c| c.0.area()).sum()
    };
    let whole = floor().area();
    for k in [CellClass::Lit, CellClass::Penumbra, CellClass::Umbra] {
        assert!(
            (area(&ca, k) - area(&cb, k)).abs() <= 1e-9 * whole,
            "{k:?} areas differ"
        );
    }
    for (p, class, keys) in &ca {
        for (q, other_class, other_keys) in &cb {
            let mut piece = Some(p.clone());
            for e in q.edges() {
                piece = piece.and_then(|x| match x.split(e) {
                    Split::Back => Some(x),
                    Split::Both(back, _) => Some(back),
                    _ => None,
                });
            }
            if piece.is_some() {
                assert_eq!(class, other_class, "overlapping cells of different classes");
                // Outside umbra nothing is culled: the lists are the
                // occluders whose penumbra holds the cell, whatever the
                // order of insertion.
                if *class != CellClass::Umbra {
                    assert_eq!(keys, other_keys, "overlapping cells with different lists");
                }
            }
        }
    }
}
