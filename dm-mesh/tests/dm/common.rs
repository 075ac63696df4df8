//! Random scenes: a floor, objects of a few triangles or a box (faces whole
//! or cut into triangles) above it, and a parallelogram light above those.

use area_shadow::AreaSource;
use bsp_core::{ConvexPolygon, GridPoint};
use dm_mesh::{CellClass, DmLight, DmOptions, DmScene, PieceId};
use proptest::prelude::*;
use svbsp::PieceFlags;

pub fn gp(x: i64, y: i64, z: i64) -> GridPoint {
    GridPoint::new(x, y, z).unwrap()
}

pub fn floor(half: i64) -> ConvexPolygon {
    let pts = [
        gp(-half, 0, half),
        gp(half, 0, half),
        gp(half, 0, -half),
        gp(-half, 0, -half),
    ];
    ConvexPolygon::from_grid_points(&pts, 0).unwrap()
}

/// The rectangle `x[0]..x[1]` by `z[0]..z[1]` at height `y`, facing up.
pub fn level_rect(x: [i64; 2], y: i64, z: [i64; 2]) -> ConvexPolygon {
    let pts = [
        gp(x[0], y, z[0]),
        gp(x[0], y, z[1]),
        gp(x[1], y, z[1]),
        gp(x[1], y, z[0]),
    ];
    ConvexPolygon::from_grid_points(&pts, 0).unwrap()
}

/// A parallelogram light at height `h`, rising by `tilt` along x, facing
/// down.
pub fn light(x0: i64, z0: i64, w: i64, d: i64, h: i64, tilt: i64) -> AreaSource {
    let pts = [
        gp(x0, h, z0),
        gp(x0 + w, h + tilt, z0),
        gp(x0 + w, h + tilt, z0 + d),
        gp(x0, h, z0 + d),
    ];
    let polygon = ConvexPolygon::from_grid_points(&pts, 0).unwrap();
    if polygon.support().normal()[1] < 0 {
        AreaSource::new(polygon).unwrap()
    } else {
        AreaSource::new(polygon.flipped()).unwrap()
    }
}

/// One object: its polygons and flags.
pub type Object = (Vec<ConvexPolygon>, PieceFlags);

/// A scene: objects (the floor first) and one light.
#[derive(Debug, Clone)]
pub struct TestScene {
    pub objects: Vec<Object>,
    pub light: AreaSource,
}

impl TestScene {
    pub fn build(&self) -> (DmScene, Vec<dm_mesh::ObjectId>) {
        self.build_with(DmOptions::default())
    }

    pub fn build_with(&self, options: DmOptions) -> (DmScene, Vec<dm_mesh::ObjectId>) {
        let light = DmLight::new(self.light.clone(), 1.0).unwrap();
        DmScene::build_with(vec![light], self.objects.clone(), options).unwrap()
    }

    /// Built and checked, with the first object's first piece (the floor).
    pub fn build_over_floor(
        &self,
    ) -> Result<(DmScene, Vec<dm_mesh::ObjectId>, PieceId), TestCaseError> {
        let (scene, ids) = self.build();
        scene.check_invariants().map_err(TestCaseError::fail)?;
        let floor = scene.object_pieces(ids[0]).unwrap()[0];
        Ok((scene, ids, floor))
    }

    /// Every polygon of the scene.
    pub fn polygons(&self) -> Vec<ConvexPolygon> {
        self.objects.iter().flat_map(|o| o.0.clone()).collect()
    }
}

/// A triangle object: corners offset from a centre; one in three lies in
/// the common plane y = 100.
fn triangles(centre: [i64; 3], corners: &[[i64; 3]]) -> Vec<ConvexPolygon> {
    corners
        .chunks(3)
        .filter_map(|tri| {
            let pts: Vec<GridPoint> = tri
                .iter()
                .map(|o| {
                    let y = if centre[1] % 3 == 0 {
                        100
                    } else {
                        120 + centre[1] / 2 + o[1]
                    };
                    gp(centre[0] + o[0], y, centre[2] + o[2])
                })
                .collect();
            ConvexPolygon::from_grid_points(&pts, 0).ok()
        })
        .collect()
}

/// Flags of an object whose polygons receive on both sides.
pub fn two_sided_flags() -> PieceFlags {
    PieceFlags {
        two_sided: true,
        ..PieceFlags::default()
    }
}

/// Flags of an object whose polygons bound a closed surface.
pub fn closed_surface_flags() -> PieceFlags {
    PieceFlags {
        closed_surface: true,
        ..PieceFlags::default()
    }
}

/// An axis-aligned box `[lo, hi]`, faces outwards.
pub fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> Vec<ConvexPolygon> {
    let [x0, y0, z0] = lo;
    let [x1, y1, z1] = hi;
    let faces = [
        [
            gp(x0, y0, z0),
            gp(x1, y0, z0),
            gp(x1, y0, z1),
            gp(x0, y0, z1),
        ],
        [
            gp(x0, y1, z0),
            gp(x0, y1, z1),
            gp(x1, y1, z1),
            gp(x1, y1, z0),
        ],
        [
            gp(x0, y0, z0),
            gp(x0, y0, z1),
            gp(x0, y1, z1),
            gp(x0, y1, z0),
        ],
        [
            gp(x1, y0, z0),
            gp(x1, y1, z0),
            gp(x1, y1, z1),
            gp(x1, y0, z1),
        ],
        [
            gp(x0, y0, z0),
            gp(x0, y1, z0),
            gp(x1, y1, z0),
            gp(x1, y0, z0),
        ],
        [
            gp(x0, y0, z1),
            gp(x1, y0, z1),
            gp(x1, y1, z1),
            gp(x0, y1, z1),
        ],
    ];
    faces
        .iter()
        .map(|f| ConvexPolygon::from_grid_points(f, 0).unwrap())
        .collect()
}

/// [`cuboid`] with each face left whole or cut into two triangles along
/// either diagonal (two bits of `cuts` per face): the triangles hide the
/// light together where no one of them does.
pub fn triangulated_cuboid(lo: [i64; 3], hi: [i64; 3], cuts: u32) -> Vec<ConvexPolygon> {
    let mut out = Vec::new();
    for (f, face) in cuboid(lo, hi).into_iter().enumerate() {
        let g: Vec<GridPoint> = (0..4).map(|k| face.vertex_grid_point(k).unwrap()).collect();
        let parts = match (cuts >> (2 * f)) & 3 {
            1 => [[g[0], g[1], g[2]], [g[0], g[2], g[3]]],
            2 => [[g[1], g[2], g[3]], [g[1], g[3], g[0]]],
            _ => {
                out.push(face);
                continue;
            }
        };
        out.extend(
            parts
                .iter()
                .map(|t| ConvexPolygon::from_grid_points(t, 0).unwrap()),
        );
    }
    out
}

pub fn scene() -> impl Strategy<Value = TestScene> {
    scene_with(1..5)
}

/// Scenes of `objects` objects over the floor (many of them: the floor's
/// tree starts tiled, see `ReceiverDm::tile`).
pub fn scene_with(objects: std::ops::Range<usize>) -> impl Strategy<Value = TestScene> {
    (
        prop::collection::vec(
            (
                prop::array::uniform3(-200_i64..200),
                prop::collection::vec(prop::array::uniform3(-60_i64..60), 3..7),
                any::<bool>(),
                any::<u32>(),
            ),
            objects,
        ),
        (
            -120_i64..60,
            -120_i64..60,
            20_i64..100,
            20_i64..100,
            180_i64..260,
            -40_i64..40,
        ),
    )
        .prop_map(|(objects, (x0, z0, w, d, h, tilt))| {
            let mut out = vec![(vec![floor(500)], PieceFlags::default())];
            for (c, corners, as_box, cuts) in objects {
                if as_box {
                    let lo = [c[0], 30 + c[1].rem_euclid(60), c[2]];
                    let size = corners[0].map(|s| 10 + s.abs());
                    let hi = [lo[0] + size[0], lo[1] + size[1].min(60), lo[2] + size[2]];
                    out.push((triangulated_cuboid(lo, hi, cuts), closed_surface_flags()));
                } else {
                    let tris = triangles(c, &corners[..corners.len() / 3 * 3]);
                    if !tris.is_empty() {
                        out.push((tris, two_sided_flags()));
                    }
                }
            }
            TestScene {
                objects: out,
                light: light(x0, z0, w, d, h, tilt),
            }
        })
}

/// Area of each class (lit, penumbra, umbra) on a receiver for light 0.
pub fn class_areas(scene: &DmScene, piece: PieceId) -> [f64; 3] {
    light_class_areas(scene, piece, 0)
}

/// The lit, penumbra and umbra areas of a receiver under light `light`.
pub fn light_class_areas(scene: &DmScene, piece: PieceId, light: usize) -> [f64; 3] {
    let dm = scene.receiver(piece).unwrap();
    let mut out = [0.0; 3];
    for (f, cell) in dm.cells() {
        let area = dm.mesh().face_polygon(f, 0).unwrap().area();
        out[match dm.class(cell, light) {
            CellClass::Lit => 0,
            CellClass::Penumbra => 1,
            CellClass::Umbra => 2,
        }] += area;
    }
    out
}

/// Two boxes of two objects standing face to face (the second's face
/// against the first's in a plane `x = c` or `z = c`, overlapping it with
/// area), each one- or two-sided and its faces cut at random, under a
/// light whose plane crosses the contact plane (or, with its edge in it,
/// touches it): each box hides from the faces in contact the part of the
/// light on its own side.
pub fn facing_boxes() -> impl Strategy<Value = TestScene> {
    (
        (
            prop::array::uniform3(-80_i64..80),
            prop::array::uniform3(10_i64..60),
            any::<bool>(),
        ),
        (
            prop::array::uniform3(0_i64..1000),
            prop::array::uniform3(0_i64..30),
            prop::array::uniform3(1_i64..40),
        ),
        (any::<[bool; 2]>(), any::<[u32; 2]>()),
        (0_i64..60, 1_i64..60, -60_i64..60, 20_i64..100),
        (180_i64..260, -40_i64..40),
    )
        .prop_map(
            |((a, size, along_x), (at, below, above), (two_sided, cuts), light_span, (h, tilt))| {
                let axis = if along_x { 0 } else { 2 };
                let lo_a = [a[0], 40 + a[1].rem_euclid(50), a[2]];
                let hi_a: [i64; 3] = std::array::from_fn(|k| lo_a[k] + size[k]);
                // The second box: past the first along `axis`, and over a
                // stretch `[o, o + above)` of each other axis that starts
                // inside the first's.
                let mut lo_b = [0; 3];
                let mut hi_b = [0; 3];
                for k in 0..3 {
                    if k == axis {
                        lo_b[k] = hi_a[k];
                        hi_b[k] = hi_a[k] + 10 + at[k] % 40;
                    } else {
                        let o = lo_a[k] + at[k] % size[k];
                        lo_b[k] = o - below[k];
                        hi_b[k] = o + above[k];
                    }
                }
                let flags = |two_sided: bool| PieceFlags {
                    two_sided,
                    closed_surface: !two_sided,
                    ..PieceFlags::default()
                };
                let objects = vec![
                    (vec![floor(500)], PieceFlags::default()),
                    (
                        triangulated_cuboid(lo_a, hi_a, cuts[0]),
                        flags(two_sided[0]),
                    ),
                    (
                        triangulated_cuboid(lo_b, hi_b, cuts[1]),
                        flags(two_sided[1]),
                    ),
                ];
                // The light across the contact plane `c`: `before` of it
                // on the first box's side, `after` on the second's.
                let (before, after, across, depth) = light_span;
                let c = hi_a[axis];
                let other = lo_a[2 - axis] + across;
                let light = if axis == 0 {
                    light(c - before, other, before + after, depth, h, tilt)
                } else {
                    light(other, c - before, depth, before + after, h, tilt)
                };
                TestScene { objects, light }
            },
        )
}

/// A closed surface far from convex: an octahedron whose faces are split
/// in four, its 6 corners pushed out by 30-40 % of `radius` about
/// `centre` and its 12 edges' midpoints in by as much (`seed` picks how
/// far), triangles facing out. Each corner then stands over 100 grid
/// units (for a radius of 600) in front of the plane of the triangle
/// between its neighbours' midpoints.
pub fn bumpy_body(centre: [i64; 3], radius: f64, seed: u32) -> Vec<ConvexPolygon> {
    let axes: [[f64; 3]; 6] = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    // The octahedron's faces, counter-clockwise seen from outside.
    let faces = [
        [0, 2, 4],
        [4, 2, 1],
        [1, 2, 5],
        [5, 2, 0],
        [0, 4, 3],
        [4, 1, 3],
        [1, 5, 3],
        [5, 0, 3],
    ];
    let unit = |v: [f64; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|c| c / l)
    };
    // Each direction's corner, pushed by a hash of its rounded direction:
    // out along an axis, in between.
    let corner = |d: [f64; 3]| {
        let key = d.iter().fold(seed, |h, c| {
            (h ^ ((c * 1000.0).round() as i32 as u32)).wrapping_mul(0x9e37_79b9)
        });
        let push = 0.3 + 0.1 * f64::from(key >> 16) / 65_536.0;
        let axis = d.iter().any(|c| c.abs() == 1.0);
        let r = radius * if axis { 1.0 + push } else { 1.0 - push };
        gp(
            centre[0] + (r * d[0]).round() as i64,
            centre[1] + (r * d[1]).round() as i64,
            centre[2] + (r * d[2]).round() as i64,
        )
    };
    let mut out = Vec::new();
    for [a, b, c] in faces {
        let (a, b, c) = (axes[a], axes[b], axes[c]);
        let mid = |p: [f64; 3], q: [f64; 3]| unit(std::array::from_fn(|k| p[k] + q[k]));
        let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
        for t in [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]] {
            out.push(ConvexPolygon::from_grid_points(&t.map(corner), 0).unwrap());
        }
    }
    out
}

/// A ring about the vertical axis through `centre`: `rings` x
/// `segments` quads (a tube of radius `small` along a circle of radius
/// `big`) cut into triangles, facing out. It has no kernel (the hole's
/// centre is outside it): it stands for several convex cores inside it.
pub fn ring_body(
    centre: [i64; 3],
    (big, small): (f64, f64),
    (rings, segments): (u32, u32),
) -> Vec<ConvexPolygon> {
    let at = |i: u32, j: u32| {
        let (u, v) = (
            std::f64::consts::TAU * f64::from(i % rings) / f64::from(rings),
            std::f64::consts::TAU * f64::from(j % segments) / f64::from(segments),
        );
        let r = big + small * v.cos();
        gp(
            centre[0] + (r * u.cos()).round() as i64,
            centre[1] + (small * v.sin()).round() as i64,
            centre[2] + (r * u.sin()).round() as i64,
        )
    };
    let mut out = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            for t in [[a, b, c], [a, c, d]] {
                out.push(ConvexPolygon::from_grid_points(&t, 0).unwrap());
            }
        }
    }
    out
}

/// How far (grid units) a closed surface facing out is from convex: the
/// most any of its corners stands in front of one of its faces' planes.
pub fn concavity(faces: &[ConvexPolygon]) -> f64 {
    let corners: Vec<[f64; 3]> = faces.iter().flat_map(|f| f.vertices_f64()).collect();
    faces
        .iter()
        .map(|f| {
            let [a, b, c, d] = f.support().approx();
            let norm = (a * a + b * b + c * c).sqrt();
            corners
                .iter()
                .map(|v| (a * v[0] + b * v[1] + c * v[2] + d) / norm)
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

/// Two bumpy closed bodies (far from convex: each casts the umbra of a
/// convex core of its kernel, besides its triangles' shadows) over a
/// floor, under a light smaller than they are.
pub fn bumpy_bodies() -> impl Strategy<Value = TestScene> {
    (
        prop::array::uniform2((prop::array::uniform3(-1500_i64..1500), any::<u32>())),
        (-600_i64..200, -600_i64..200, 100_i64..500),
    )
        .prop_map(|(bodies, (x0, z0, w))| {
            let mut objects = vec![(vec![floor(5000)], svbsp::PieceFlags::default())];
            for (c, seed) in bodies {
                let centre = [c[0], 1500 + c[1] / 3, c[2]];
                objects.push((bumpy_body(centre, 600.0, seed), closed_surface_flags()));
            }
            TestScene {
                objects,
                light: light(x0, z0, w, w, 4000, 0),
            }
        })
}

/// A ring (no kernel: several cores) and a bumpy body over a floor, under
/// a light smaller than the ring's tube is thick.
pub fn ring_bodies() -> impl Strategy<Value = TestScene> {
    (
        prop::array::uniform3(-1500_i64..1500),
        (prop::array::uniform3(-1500_i64..1500), any::<u32>()),
        (6_u32..10, 4_u32..7),
        (-600_i64..200, -600_i64..200, 100_i64..400),
    )
        .prop_map(|(ring, (c, seed), counts, (x0, z0, w))| {
            let mut objects = vec![(vec![floor(5000)], svbsp::PieceFlags::default())];
            let centre = [ring[0], 1500 + ring[1] / 3, ring[2]];
            objects.push((
                ring_body(centre, (900.0, 450.0), counts),
                closed_surface_flags(),
            ));
            let centre = [c[0], 1500 + c[1] / 3, c[2]];
            objects.push((bumpy_body(centre, 600.0, seed), closed_surface_flags()));
            TestScene {
                objects,
                light: light(x0, z0, w, w, 4000, 0),
            }
        })
}

/// A wide plate (object 1) over a floor crowded with the shadows of 36
/// small boxes under a wide light: the plate's penumbra holds many of the
/// floor's cells.
pub fn plate_over_boxes() -> TestScene {
    let mut objects = vec![
        (vec![floor(500)], PieceFlags::default()),
        (
            vec![level_rect([-150, 150], 220, [-150, 150])],
            two_sided_flags(),
        ),
    ];
    for i in 0..6_i64 {
        for k in 0..6_i64 {
            let (x, z) = (-330 + 130 * i + 7 * k, -330 + 130 * k - 5 * i);
            let height = 30 + 17 * ((i * 5 + k * 3) % 4);
            objects.push((
                cuboid([x, 0, z], [x + 24, height, z + 18]),
                closed_surface_flags(),
            ));
        }
    }
    TestScene {
        objects,
        light: light(-60, -40, 160, 120, 420, 10),
    }
}

/// The cells of `piece`'s DM-tree with their classes under light 0.
pub fn floor_cells(scene: &DmScene, piece: PieceId) -> Vec<(ConvexPolygon, CellClass)> {
    let dm = scene.receiver(piece).unwrap();
    dm.cells()
        .map(|(f, c)| (dm.mesh().face_polygon(f, 0).unwrap(), dm.class(c, 0)))
        .collect()
}

/// One cell: vertex coordinate bits, entries, vertex irradiance bits.
pub type CellPrint = (Vec<[u64; 3]>, Vec<dm_mesh::Entry>, Vec<u64>);

/// Everything one receiver holds, in its mesh's order: per cell its
/// vertices (exact coordinates as f64 bits), entries and irradiance bits.
pub fn receiver_print(scene: &DmScene, piece: PieceId) -> Vec<CellPrint> {
    let dm = scene.receiver(piece).unwrap();
    dm.cells()
        .map(|(face, cell)| {
            let vertices = dm.mesh().face_vertices(face);
            (
                vertices
                    .iter()
                    .map(|&v| {
                        let p = dm.mesh().vertex(v).unwrap().position.to_f64();
                        p.map(f64::to_bits)
                    })
                    .collect(),
                cell.entries().to_vec(),
                vertices
                    .iter()
                    .map(|&v| scene.vertex_irradiance(piece, v).unwrap_or(-1.0).to_bits())
                    .collect(),
            )
        })
        .collect()
}
