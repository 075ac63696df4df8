//! Target `area`: small random scenes under one area light, classified by
//! the penumbra and umbra trees of `area-shadow` and made conforming.
//!
//! [`AreaCase::arbitrary`] decodes a floor, a few triangles with small
//! coordinates (so they touch, share planes with each other and with the
//! light, and cross the light's plane) and a parallelogram light, possibly
//! tilted. [`check_area`] checks that the fragments partition every piece
//! exactly, that sample points of a lit fragment (its centroid and points
//! near its vertices) see points inside the light near
//! each vertex and its centroid and an umbra fragment's see none of them (segments
//! tested against the triangles with Shewchuk's exact orientation), that
//! a penumbra fragment proven dark ([`area_shadow::dark::sees_none`], the
//! joint umbra of several triangles) sees none of them either, and that
//! the conforming mesh has no T-vertex.

use crate::scene::{check_partition, crosses, floor_and, gp, samples, touches};
use arbitrary::{Arbitrary, Unstructured};
use area_shadow::dark::sees_none;
use area_shadow::{AreaSource, Class, SceneLight, compute_shadows, conform_fragments};
use bsp_core::{BuildOptions, ConvexPolygon};
use svbsp::PieceFlags;

/// One decoded input of the `area` target; its `Debug` output is Rust code.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AreaCase {
    /// Triangles over the floor.
    pub triangles: Vec<[[i64; 3]; 3]>,
    /// The light: corner `(x, y, z)`, extents `(w, d)` along x and z, rise
    /// along x.
    pub light: ([i64; 3], [i64; 2], i64),
}

impl<'a> Arbitrary<'a> for AreaCase {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        let n = u.int_in_range(1_usize..=4)?;
        let mut triangles = Vec::with_capacity(n);
        for _ in 0..n {
            let mut t = [[0_i64; 3]; 3];
            for p in &mut t {
                *p = [
                    i64::from(u.int_in_range(-8_i8..=8)?),
                    i64::from(u.int_in_range(1_i8..=14)?),
                    i64::from(u.int_in_range(-8_i8..=8)?),
                ];
            }
            triangles.push(t);
        }
        let corner = [
            i64::from(u.int_in_range(-6_i8..=4)?),
            i64::from(u.int_in_range(9_i8..=12)?),
            i64::from(u.int_in_range(-6_i8..=4)?),
        ];
        let size = [
            i64::from(u.int_in_range(1_i8..=5)?),
            i64::from(u.int_in_range(1_i8..=5)?),
        ];
        let rise = i64::from(u.int_in_range(-3_i8..=3)?);
        Ok(Self {
            triangles,
            light: (corner, size, rise),
        })
    }
}

/// Decodes fuzzer bytes.
pub fn decode(data: &[u8]) -> Option<AreaCase> {
    AreaCase::arbitrary_take_rest(Unstructured::new(data)).ok()
}

/// The body of the `area` fuzz target.
pub fn run(data: &[u8]) {
    let Some(case) = decode(data) else { return };
    if let Err(problem) = check_area(&case) {
        panic!("area invariant violated: {problem}\n{case:?}");
    }
}

/// Classifies, conforms and checks; `Err` describes the first violated
/// invariant.
pub fn check_area(case: &AreaCase) -> Result<(), String> {
    let pieces = floor_and(&case.triangles);
    let ([x, y, z], [w, d], rise) = case.light;
    let quad = [
        gp([x, y, z]),
        gp([x + w, y + rise, z]),
        gp([x + w, y + rise, z + d]),
        gp([x, y, z + d]),
    ];
    let polygon = ConvexPolygon::from_grid_points(&quad, 0).map_err(|e| e.to_string())?;
    let polygon = if polygon.support().normal()[1] < 0 {
        polygon
    } else {
        polygon.flipped()
    };
    let light = AreaSource::new(polygon).map_err(|e| e.to_string())?;
    let flags: Vec<PieceFlags> = (0..pieces.len())
        .map(|k| PieceFlags {
            two_sided: k > 0,
            ..PieceFlags::default()
        })
        .collect();
    let out = compute_shadows(
        &pieces,
        &flags,
        &[SceneLight::Area(light.clone())],
        &BuildOptions::default(),
    )
    .map_err(|e| e.to_string())?;

    check_partition(&pieces, out.fragments.iter().map(|f| &f.polygon))?;

    let triangles: Vec<(usize, [[f64; 3]; 3])> = pieces
        .iter()
        .enumerate()
        .skip(1)
        .map(|(k, p)| (k, [0, 1, 2].map(|i| p.vertex_f64(i))))
        .collect();
    // Points strictly inside the light (a light vertex may lie in an
    // occluder's plane and be seen along a set of measure zero): the mean
    // of its vertices and each vertex moved a quarter of the way to it
    // (exact in f64: the mean of four integers is a quarter-integer; the
    // area centroid is rounded, and a hair off an occluder's vertex at the
    // true centre it made a touching segment cross).
    let corners: Vec<[f64; 3]> = light.vertices().map(|v| v.to_f64()).collect();
    let count = corners.len() as f64;
    let centre = [0, 1, 2].map(|i| corners.iter().map(|c| c[i]).sum::<f64>() / count);
    let mut targets: Vec<[f64; 3]> = light
        .vertices()
        .map(|v| {
            let v = v.to_f64();
            [0, 1, 2].map(|i| 0.75 * v[i] + 0.25 * centre[i])
        })
        .collect();
    targets.push(centre);
    let occluders: Vec<&ConvexPolygon> = pieces.iter().skip(1).collect();
    for f in &out.fragments {
        let mut class = Class::of(f, 0);
        if f.polygon.area() < 1e-3 {
            continue;
        }
        if class == Class::Penumbra {
            let two_sided = flags[f.polygon.source() as usize].two_sided;
            if !sees_none(&f.polygon, two_sided, &light, &occluders, &[]) {
                continue;
            }
            class = Class::Umbra;
        }
        let own = pieces[f.polygon.source() as usize].support();
        if own.is_coincident(light.support()) {
            // In the light's plane: nothing arrives (and a rounded centroid
            // would sit a hair off the plane).
            if class != Class::Umbra {
                return Err(format!("a fragment in the light's plane is {class:?}"));
            }
            continue;
        }
        // A sample on another triangle (they may touch or pierce each
        // other) has its sight lines start on that triangle: its rounding
        // decides the crossing, not the scene (as in target `shadows`).
        // Such a sample is skipped.
        let on_another = |c: [f64; 3]| {
            triangles
                .iter()
                .any(|(k, t)| !pieces[*k].support().is_coincident(own) && touches(c, t))
        };
        for (c, &x) in samples(&f.polygon)
            .iter()
            .filter(|&&c| !on_another(c))
            .flat_map(|&c| targets.iter().map(move |x| (c, x)))
        {
            let blocked = triangles
                .iter()
                .any(|(k, t)| !pieces[*k].support().is_coincident(own) && crosses(c, x, t));
            if class == Class::Lit && blocked {
                return Err(format!(
                    "lit fragment of piece {} has {x:?} hidden from {c:?}",
                    f.polygon.source()
                ));
            }
            if class == Class::Umbra && !blocked && facing(own, f, &flags, x, &light, c) {
                return Err(format!(
                    "umbra fragment of piece {} sees {x:?} from {c:?}",
                    f.polygon.source()
                ));
            }
        }
    }

    let (fragments, mesh) = conform_fragments(out.fragments, usize::MAX);
    for (f, face) in mesh.faces.iter().enumerate() {
        for k in 0..face.len() {
            let (a, b) = (
                mesh.coords[face[k] as usize],
                mesh.coords[face[(k + 1) % face.len()] as usize],
            );
            let d = [0, 1, 2].map(|i| b[i] - a[i]);
            let len2: f64 = d.iter().map(|v| v * v).sum();
            for (p, c) in mesh.coords.iter().enumerate() {
                if face.contains(&(p as u32)) {
                    continue;
                }
                let w = [0, 1, 2].map(|i| c[i] - a[i]);
                let t = (0..3).map(|i| w[i] * d[i]).sum::<f64>() / len2;
                let off: f64 = (0..3).map(|i| (w[i] - t * d[i]).powi(2)).sum();
                if t > 1e-9 && t < 1.0 - 1e-9 && off < 1e-18 * len2 {
                    return Err(format!(
                        "point {p} lies inside edge {k} of face {f} of {}",
                        fragments.len()
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Whether light from `x` could reach the receiving side of the fragment
/// at `c` at all: in front of the light, and on a receiving side.
fn facing(
    own: &bsp_core::Plane,
    f: &svbsp::Fragment,
    flags: &[PieceFlags],
    x: [f64; 3],
    light: &AreaSource,
    c: [f64; 3],
) -> bool {
    let value = |plane: &bsp_core::Plane, p: [f64; 3]| {
        let [a, b, cc, d] = plane.approx();
        a * p[0] + b * p[1] + cc * p[2] + d
    };
    let side = value(own, x);
    let receives = side > 0.0 || (flags[f.polygon.source() as usize].two_sided && side < 0.0);
    receives && value(light.support(), c) > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pseudo_random_bytes as bytes;

    #[test]
    fn seed_corpus_replays() {
        let files = crate::corpus_files("area").expect("corpus/area is readable");
        assert!(files.len() >= 8, "only {} seed files", files.len());
        for (name, data) in files {
            let case = decode(&data).expect("decodes");
            if let Err(problem) = check_area(&case) {
                panic!("corpus/area/{name}: {problem}\n{case:?}");
            }
        }
    }

    #[test]
    fn pseudo_random_inputs_pass() {
        for seed in 0..1_000 {
            let data = bytes(seed, 20 + (seed % 40) as usize);
            let Some(case) = decode(&data) else { continue };
            if let Err(problem) = check_area(&case) {
                panic!("seed {seed}: {problem}\n{case:?}");
            }
        }
    }

    #[test]
    fn light_edge_in_an_occluder_plane_casts_no_umbra() {
        // Found by the pseudo-random inputs: the light's edge x = 0 lies in
        // the second triangle's plane; the floor behind it saw part of the
        // light yet was classified umbra.
        let case = AreaCase {
            triangles: vec![
                [[2, 1, 0], [4, 14, -3], [4, 9, 7]],
                [[0, 3, 3], [0, 11, -4], [0, 2, 6]],
            ],
            light: ([0, 12, -1], [4, 1], 1),
        };
        check_area(&case).unwrap();
    }

    #[test]
    fn receiver_in_the_light_plane() {
        // Found by libFuzzer: the second triangle lies in the light's plane
        // x + y = 6; the oracle's rounded centroid sat a hair in front.
        let case = AreaCase {
            triangles: vec![
                [[7, 12, 6], [7, 12, 6], [-2, 6, -6]],
                [[5, 1, -8], [-2, 8, 0], [1, 5, 7]],
                [[-5, 13, 5], [1, 12, 0], [1, 12, -1]],
            ],
            light: ([-6, 12, -4], [2, 1], -2),
        };
        check_area(&case).unwrap();
    }

    #[test]
    fn coplanar_caps_repeated_below_each_other() {
        // Found by libFuzzer: two occluders in the plane z = -8 put that
        // plane twice on one path of the penumbra tree; a receiver in the
        // plane went to the empty side of the lower copy and a sliver in
        // another occluder's penumbra came out lit.
        let case = AreaCase {
            triangles: vec![
                [[-8, 4, -8], [-8, 3, -8], [4, 4, -8]],
                [[-8, 4, -8], [-4, 2, 2], [1, 3, 3]],
                [[-5, 4, -8], [-1, 11, -8], [-8, 1, -8]],
                [[-8, 1, -8], [-8, 1, -8], [-8, 1, -8]],
            ],
            light: ([-6, 9, -6], [1, 1], -3),
        };
        check_area(&case).unwrap();
    }

    /// Writes the seed corpus (run by hand when the decoder changes).
    #[test]
    fn a_bent_quads_halves_hide_the_light_together() {
        // Two triangles sharing the diagonal of a quad bent along it: from
        // the floor under the diagonal each hides part of the light, the
        // parts meeting along the diagonal's image. Proven dark as a hinge
        // (area_shadow::dark), and every fragment so proven sees none of
        // the light's sample points past the triangles (exact segments).
        let case = AreaCase {
            triangles: vec![
                [[-4, 6, -4], [4, 7, -4], [4, 6, 4]],
                [[-4, 6, -4], [4, 6, 4], [-4, 7, 4]],
            ],
            light: ([-1, 12, -1], [2, 2], 0),
        };
        check_area(&case).unwrap();
        let pieces = floor_and(&case.triangles);
        let light = AreaSource::new(
            ConvexPolygon::from_grid_points(
                &[
                    gp([-1, 12, -1]),
                    gp([1, 12, -1]),
                    gp([1, 12, 1]),
                    gp([-1, 12, 1]),
                ],
                0,
            )
            .unwrap(),
        )
        .unwrap();
        assert!(light.support().normal()[1] < 0);
        let under = ConvexPolygon::from_grid_points(
            &[gp([0, 0, 0]), gp([0, 0, 1]), gp([1, 0, 1]), gp([1, 0, 0])],
            0,
        )
        .unwrap();
        let occluders: Vec<&ConvexPolygon> = pieces.iter().skip(1).collect();
        assert!(sees_none(&under, false, &light, &occluders, &[]));
        for one in &occluders {
            assert!(!sees_none(&under, false, &light, &[*one], &[]));
        }
    }

    #[test]
    #[ignore = "rewrites corpus/area; run by hand"]
    fn regenerate_seed_corpus() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/area");
        std::fs::create_dir_all(&dir).unwrap();
        for seed in 0..12_u64 {
            let data = bytes(1000 + seed, 48);
            std::fs::write(dir.join(format!("seed-{seed:02}")), data).unwrap();
        }
    }
}
