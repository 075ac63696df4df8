//! Target `shadows`: small random scenes under a point or directional
//! light, shadowed by `svbsp` with cones of one to four pieces, so that
//! every cut of the cone partition, the cones' scene BSPs and trees, and the
//! joining of pieces found alike are exercised.
//!
//! [`ShadowsCase::arbitrary`] decodes a floor, a few triangles with small
//! coordinates (so they touch, share planes and straddle the planes through
//! the light), a light (a grid point possibly among the triangles, or a
//! direction) and the cone size. [`check_shadows`] checks that the
//! fragments partition every piece exactly, that each fragment is lit or in
//! umbra, never both, that sample points of every fragment (its centroid
//! and points near its vertices) see the light exactly when it is lit
//! (segments tested against the triangles with Shewchuk's exact
//! orientation), and that the lit area of every piece is the one a single
//! cone gives.

use crate::scene::{check_partition, crosses, floor_and, gp, samples, touches};
use arbitrary::{Arbitrary, Unstructured};
use bsp_core::predicates::Side;

use svbsp::{Light, LightSource, PieceFlags, ShadowOptions, ShadowOutput, compute_shadows_with};

/// One decoded input of the `shadows` target; its `Debug` output is Rust
/// code.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ShadowsCase {
    /// Triangles over the floor.
    pub triangles: Vec<[[i64; 3]; 3]>,
    /// A point light at this grid point, or, if `directional`, a light
    /// travelling along it.
    pub light: [i64; 3],
    /// Whether the light is directional.
    pub directional: bool,
    /// At most this many pieces per cone.
    pub cone_pieces: usize,
}

fn small(u: &mut Unstructured<'_>, lo: i8, hi: i8) -> arbitrary::Result<i64> {
    Ok(i64::from(u.int_in_range(lo..=hi)?))
}

impl<'a> Arbitrary<'a> for ShadowsCase {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        let n = u.int_in_range(1_usize..=8)?;
        let mut triangles = Vec::with_capacity(n);
        for _ in 0..n {
            let mut t = [[0_i64; 3]; 3];
            for p in &mut t {
                *p = [small(u, -8, 8)?, small(u, 1, 12)?, small(u, -8, 8)?];
            }
            triangles.push(t);
        }
        let directional = u.arbitrary()?;
        let light = if directional {
            [small(u, -4, 4)?, small(u, -6, -1)?, small(u, -4, 4)?]
        } else {
            [small(u, -10, 10)?, small(u, 2, 20)?, small(u, -10, 10)?]
        };
        Ok(Self {
            triangles,
            light,
            directional,
            cone_pieces: u.int_in_range(1_usize..=4)?,
        })
    }
}

/// Decodes fuzzer bytes.
pub fn decode(data: &[u8]) -> Option<ShadowsCase> {
    ShadowsCase::arbitrary_take_rest(Unstructured::new(data)).ok()
}

/// The body of the `shadows` fuzz target.
pub fn run(data: &[u8]) {
    let Some(case) = decode(data) else { return };
    if let Err(problem) = check_shadows(&case) {
        panic!("shadows invariant violated: {problem}\n{case:?}");
    }
}

/// The lit area of every piece.
fn lit_area(out: &ShadowOutput, pieces: usize) -> Vec<f64> {
    let mut area = vec![0.0; pieces];
    for f in out.fragments.iter().filter(|f| f.lit_mask & 1 != 0) {
        area[f.polygon.source() as usize] += f.polygon.area();
    }
    area
}

/// Shadows the case in small cones and in one, and checks; returns the
/// number of cones, or `Err` with the first violated invariant.
pub fn check_shadows(case: &ShadowsCase) -> Result<usize, String> {
    let pieces = floor_and(&case.triangles);
    let source = if case.directional {
        LightSource::Directional(case.light.map(|c| c as i32))
    } else {
        LightSource::Point(gp(case.light))
    };
    let light = Light {
        source,
        range: None,
    };
    // Every other triangle two-sided, the rest one-sided.
    let flags: Vec<PieceFlags> = (0..pieces.len())
        .map(|k| PieceFlags {
            two_sided: k % 2 == 1,
            ..PieceFlags::default()
        })
        .collect();
    let run = |cone_pieces| {
        let options = ShadowOptions {
            cone_pieces,
            ..ShadowOptions::default()
        };
        compute_shadows_with(&pieces, &flags, &[light], &options).map_err(|e| e.to_string())
    };
    let out = run(case.cone_pieces)?;

    check_partition(&pieces, out.fragments.iter().map(|f| &f.polygon))?;
    for f in &out.fragments {
        if (f.lit_mask & 1 != 0) == (f.umbra_mask & 1 != 0) {
            return Err(format!(
                "a fragment of piece {} is lit and umbra, or neither",
                f.polygon.source()
            ));
        }
    }

    let triangles: Vec<(usize, [[f64; 3]; 3])> = pieces
        .iter()
        .enumerate()
        .skip(1)
        .map(|(k, p)| (k, [0, 1, 2].map(|i| p.vertex_f64(i))))
        .collect();
    for f in &out.fragments {
        if f.polygon.area() < 1e-3 {
            continue;
        }
        let k = f.polygon.source() as usize;
        let own = pieces[k].support();
        let facing = light.source.side(own);
        let receives = facing == Side::Front || (flags[k].two_sided && facing == Side::Back);
        let lit = f.lit_mask & 1 != 0;
        if !receives {
            if lit {
                return Err(format!("piece {k} is lit from behind or edge-on"));
            }
            continue;
        }
        for c in samples(&f.polygon) {
            // A sample on another triangle (they may pierce each other) has
            // its sight line start on that triangle: its rounding decides
            // the crossing, not the scene. Such a sample is skipped.
            if triangles
                .iter()
                .any(|(j, t)| *j != k && !pieces[*j].support().is_coincident(own) && touches(c, t))
            {
                continue;
            }
            // The light, or a point far back along a directional light's
            // rays (beyond everything: the scene spans 40 units).
            let x = match light.source {
                LightSource::Point(p) => p.to_f64(),
                LightSource::Directional(d) => [0, 1, 2].map(|i| c[i] - 1000.0 * f64::from(d[i])),
            };
            let blocked = triangles
                .iter()
                .any(|(j, t)| !pieces[*j].support().is_coincident(own) && crosses(c, x, t));
            if lit == blocked {
                return Err(format!(
                    "fragment of piece {k} is {} but the light is {} from {c:?}",
                    if lit { "lit" } else { "in umbra" },
                    if blocked { "hidden" } else { "seen" }
                ));
            }
        }
    }

    let cones = out.lights[0].cones;
    let whole = run(usize::MAX)?;
    let (a, b) = (lit_area(&out, pieces.len()), lit_area(&whole, pieces.len()));
    for k in 0..pieces.len() {
        if (a[k] - b[k]).abs() > 1e-9 * pieces[k].area() {
            return Err(format!(
                "piece {k}: lit area {} in cones, {} in one",
                a[k], b[k]
            ));
        }
    }
    Ok(cones)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pseudo_random_bytes as bytes;

    #[test]
    fn seed_corpus_replays() {
        let files = crate::corpus_files("shadows").expect("corpus/shadows is readable");
        assert!(files.len() >= 8, "only {} seed files", files.len());
        for (name, data) in files {
            let case = decode(&data).expect("decodes");
            if let Err(problem) = check_shadows(&case) {
                panic!("corpus/shadows/{name}: {problem}\n{case:?}");
            }
        }
    }

    #[test]
    fn pseudo_random_inputs_pass() {
        let (mut cases, mut cut) = (0, 0);
        for seed in 0..1_000 {
            let data = bytes(seed, 30 + (seed % 60) as usize);
            let Some(case) = decode(&data) else { continue };
            match check_shadows(&case) {
                Ok(cones) => {
                    cases += 1;
                    cut += usize::from(cones > 1);
                }
                Err(problem) => panic!("seed {seed}: {problem}\n{case:?}"),
            }
        }
        // The inputs must exercise the partition, not only single cones.
        assert!(
            cases > 900 && cut > cases / 3,
            "{cut} of {cases} cut into cones"
        );
    }

    /// Found by libFuzzer: triangle 3's edge passes through the centroid of
    /// triangle 5 (they pierce each other), so the centroid's sight line
    /// started on triangle 3 and the oracle, not the shadows, was wrong.
    fn piercing_case(cone_pieces: usize) -> ShadowsCase {
        ShadowsCase {
            triangles: vec![
                [[7, 1, 6], [5, 3, 0], [-1, 7, 7]],
                [[-2, 7, 4], [-2, 3, -2], [-7, 4, -6]],
                [[-6, 9, 0], [-2, 10, 2], [2, 4, -7]],
                [[-2, 12, -8], [-8, 1, 7], [5, 1, 1]],
                [[-8, 10, 2], [0, 9, 0], [-2, 10, 2]],
                [[2, 4, -7], [-2, 12, -8], [-8, 1, 7]],
                [[5, 1, 1], [-8, 10, 2], [0, 9, -4]],
                [[0, 5, -3], [0, 9, 8], [1, 2, 3]],
            ],
            light: [-3, -4, 1],
            directional: true,
            cone_pieces,
        }
    }

    #[test]
    fn piercing_triangles_under_a_directional_light() {
        for cone_pieces in [usize::MAX, 1, 2, 3] {
            if let Err(problem) = check_shadows(&piercing_case(cone_pieces)) {
                panic!("cones of {cone_pieces}: {problem}");
            }
        }
    }

    /// Writes the seed corpus (run by hand when the decoder changes).
    #[test]
    #[ignore = "rewrites corpus/shadows; run by hand"]
    fn regenerate_seed_corpus() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/shadows");
        std::fs::create_dir_all(&dir).unwrap();
        for seed in 0..16_u64 {
            let data = bytes(10_000 + seed, 40 + 4 * seed as usize);
            if decode(&data).is_some() {
                std::fs::write(dir.join(format!("seed-{seed:02}")), data).unwrap();
            }
        }
    }
}
