//! A frame loop, as an application drawing shadows would run one: a box
//! slides across a floor among others under a square light; each frame
//! moves it, then reads again only the receivers the move changed (their
//! cells, classes and vertex irradiance, as it would hand them to the
//! GPU), and keeps the rest.
//!
//! `cargo run --release -p dm-mesh --example frames [FRAMES]`

use std::collections::HashMap;
use std::time::Instant;

use area_shadow::AreaSource;
use bsp_core::{ConvexPolygon, GridPoint};
use dm_mesh::{CellClass, DmLight, DmScene, PieceId};
use svbsp::PieceFlags;

fn point(x: i64, y: i64, z: i64) -> GridPoint {
    GridPoint::new(x, y, z).expect("on the grid")
}

fn polygon(corners: [[i64; 3]; 4]) -> ConvexPolygon {
    let points: Vec<GridPoint> = corners.iter().map(|&[x, y, z]| point(x, y, z)).collect();
    ConvexPolygon::from_grid_points(&points, 0).expect("a convex quad")
}

/// An axis-aligned box from `lo` to `hi`, its faces turned outwards.
fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> Vec<ConvexPolygon> {
    let ([x0, y0, z0], [x1, y1, z1]) = (lo, hi);
    vec![
        polygon([[x0, y1, z0], [x0, y1, z1], [x1, y1, z1], [x1, y1, z0]]),
        polygon([[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]]),
        polygon([[x0, y0, z0], [x0, y0, z1], [x0, y1, z1], [x0, y1, z0]]),
        polygon([[x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]]),
        polygon([[x0, y0, z0], [x0, y1, z0], [x1, y1, z0], [x1, y0, z0]]),
        polygon([[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]]),
    ]
}

/// What the application keeps of one receiver: per class, its cells'
/// count, and the sum of its vertices' irradiance.
#[derive(Debug, Default, Clone, Copy)]
struct Uploaded {
    cells: [usize; 3],
    irradiance: f64,
}

/// Reads a receiver's cells and vertex values, as a renderer would.
fn upload(scene: &DmScene, piece: PieceId) -> Uploaded {
    let dm = scene.receiver(piece).expect("a live receiver");
    let mut out = Uploaded::default();
    for (face, cell) in dm.cells() {
        let class = match dm.class(cell, 0) {
            CellClass::Lit => 0,
            CellClass::Penumbra => 1,
            CellClass::Umbra => 2,
        };
        out.cells[class] += 1;
        for v in dm.mesh().face_vertices(face) {
            out.irradiance += scene.vertex_irradiance(piece, v).unwrap_or(0.0);
        }
    }
    out
}

fn main() -> Result<(), dm_mesh::Error> {
    let frames: i64 = std::env::args()
        .nth(1)
        .and_then(|n| n.parse().ok())
        .unwrap_or(40);
    let flags = PieceFlags::default();
    let floor = polygon([
        [-600, 0, 600],
        [600, 0, 600],
        [600, 0, -600],
        [-600, 0, -600],
    ]);
    let mut objects = vec![(vec![floor], flags)];
    // A grid of static boxes, and the one that moves (last).
    for i in -3..=3 {
        for j in -3..=3 {
            let (x, z) = (150 * i, 150 * j + 75);
            objects.push((cuboid([x - 20, 0, z - 20], [x + 20, 50, z + 20]), flags));
        }
    }
    objects.push((cuboid([-500, 0, -20], [-460, 60, 20]), flags));
    let light = AreaSource::from_grid_points(&[
        point(-40, 400, -40),
        point(40, 400, -40),
        point(40, 400, 40),
        point(-40, 400, 40),
    ])
    .expect("a light facing down");
    let started = Instant::now();
    let mover = objects.len() - 1;
    let (mut scene, ids) = DmScene::build_movable(
        vec![DmLight::new(light, 1.0)?],
        objects,
        &[mover],
        Default::default(),
    )?;
    scene.illuminate();
    let mut uploaded: HashMap<PieceId, Uploaded> = scene
        .receivers()
        .map(|(p, _)| (p, upload(&scene, p)))
        .collect();
    println!(
        "built, illuminated and read {} receivers in {:.1} ms",
        uploaded.len(),
        1e3 * started.elapsed().as_secs_f64()
    );
    for frame in 1..=frames {
        let since = scene.revision();
        let started = Instant::now();
        let old = scene.object_pieces(ids[mover]).unwrap_or_default().to_vec();
        scene.translate_object(ids[mover], [24, 0, 0])?;
        let moved = started.elapsed().as_secs_f64();
        // The moved box's old faces are gone; every other receiver not
        // listed keeps what was read of it.
        for piece in old {
            uploaded.remove(&piece);
        }
        let changed: Vec<PieceId> = scene.receivers_changed_since(since).collect();
        for &piece in &changed {
            uploaded.insert(piece, upload(&scene, piece));
        }
        if frame % 10 == 0 || frame == 1 {
            let (cells, umbra, sum) = uploaded.values().fold((0, 0, 0.0), |acc, u| {
                (
                    acc.0 + u.cells.iter().sum::<usize>(),
                    acc.1 + u.cells[2],
                    acc.2 + u.irradiance,
                )
            });
            println!(
                "frame {frame}: moved in {:.2} ms, read {} of {} receivers again in {:.2} ms; {cells} cells ({umbra} in umbra), vertex irradiance sum {sum:.4e}",
                1e3 * moved,
                changed.len(),
                uploaded.len(),
                1e3 * (started.elapsed().as_secs_f64() - moved)
            );
        }
    }
    Ok(())
}
