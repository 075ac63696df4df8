//! Closed parts of one object cast as the same parts would as objects of
//! their own: random boxes apart from each other (wound out or in, a face
//! short, or dented: no convex body) over a floor, under one or two area lights (the second
//! perhaps inside the first box), all in one object or each in its own,
//! give the same `umbra shadow` and `umbra dm` output.

use proptest::prelude::*;
use umbra::{Scene, dm_scene, shadow_scene};

use crate::folder;

/// What a box is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// Wound outward.
    Out,
    /// Wound inward.
    In,
    /// Its top left out.
    Open,
    /// Its top dented: four triangles to a point below its middle, a
    /// closed surface that is no convex body.
    Dented,
}

/// A box's faces as TOML polygons: `[lo, hi]`, counter-clockwise seen
/// from outside unless wound inward.
fn box_faces(lo: [f64; 3], hi: [f64; 3], kind: Kind) -> Vec<String> {
    let corner = |i: usize| {
        [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ]
    };
    // Counter-clockwise seen from outside: -z, +z, -y, +y, -x, +x.
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let mut polygons: Vec<Vec<[f64; 3]>> = faces
        .iter()
        .enumerate()
        .filter(|&(k, _)| k != 3 || kind == Kind::Out || kind == Kind::In)
        .map(|(_, face)| face.iter().map(|&i| corner(i)).collect())
        .collect();
    if kind == Kind::Dented {
        let dent = [
            (lo[0] + hi[0]) / 2.0,
            (lo[1] + 3.0 * hi[1]) / 4.0,
            (lo[2] + hi[2]) / 2.0,
        ];
        let top = faces[3];
        for k in 0..4 {
            polygons.push(vec![corner(top[k]), corner(top[(k + 1) % 4]), dent]);
        }
    }
    polygons
        .into_iter()
        .map(|mut corners| {
            if kind == Kind::In {
                corners.reverse();
            }
            format!("{corners:?}")
        })
        .collect()
}

/// A square light of side `side` about `centre`, facing down.
fn light(centre: [f64; 3], side: f64) -> String {
    let (h, [x, y, z]) = (side / 2.0, centre);
    format!(
        "[[light]]\ntype = \"area\"\nvertices = [[{}, {y}, {}], [{}, {y}, {}], [{}, {y}, {}], [{}, {y}, {}]]\n\n",
        x - h,
        z - h,
        x + h,
        z - h,
        x + h,
        z + h,
        x - h,
        z + h,
    )
}

const FLOOR: &str = "[[-8.0, 0.0, -8.0], [-8.0, 0.0, 8.0], [8.0, 0.0, 8.0], [8.0, 0.0, -8.0]]";

/// The scene with the floor and the boxes in one object, and with each in
/// its own.
fn scenes(boxes: &[Vec<String>], lights: &str) -> (String, String) {
    let all: Vec<String> = std::iter::once(FLOOR.to_string())
        .chain(boxes.iter().flatten().cloned())
        .collect();
    let one = format!(
        "[[object]]\nname = \"all\"\npolygons = [{}]\n\n{lights}",
        all.join(", ")
    );
    let mut apart = format!("[[object]]\nname = \"floor\"\npolygons = [{FLOOR}]\n\n");
    for (k, faces) in boxes.iter().enumerate() {
        apart += &format!(
            "[[object]]\nname = \"box{k}\"\npolygons = [{}]\n\n",
            faces.join(", ")
        );
    }
    apart += lights;
    (one, apart)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn closed_parts_of_one_object_cast_as_objects_of_their_own(
        boxes in prop::collection::vec(
            (0.0_f64..1.0, 1.0_f64..3.0, -3.0_f64..3.0, 0.5_f64..2.5, 0.5_f64..2.0, 0_u8..4),
            1..4,
        ),
        second_light in 0_u8..3,
    ) {
        // Box k over x in [-7 + 5k, ...], at most 3 wide: apart from the
        // others, and from the floor.
        let quarter = |x: f64| (4.0 * x).round() / 4.0;
        let mut corners = Vec::new();
        let faces: Vec<Vec<String>> = boxes
            .iter()
            .enumerate()
            .map(|(k, &(dx, y, z, width, height, kind))| {
                let lo = [quarter(-7.0 + 5.0 * k as f64 + dx), quarter(y), quarter(z)];
                let hi = [quarter(lo[0] + width), quarter(lo[1] + height), quarter(lo[2] + width)];
                corners.push((lo, hi));
                let kind = [Kind::Out, Kind::In, Kind::Open, Kind::Dented][usize::from(kind)];
                box_faces(lo, hi, kind)
            })
            .collect();
        let mut lights = light([0.0, 8.0, 0.0], 1.0);
        let (lo, hi) = corners[0];
        let middle: [f64; 3] = std::array::from_fn(|a| (lo[a] + hi[a]) / 2.0);
        match second_light {
            // Inside the first box: no light is clear of it.
            1 => lights += &light(middle, 0.25),
            // Over it, beside the others.
            2 => lights += &light([middle[0], 6.0, middle[2]], 0.5),
            _ => {}
        }
        let (one, apart) = scenes(&faces, &lights);
        let dir = folder(&[("one.toml", &one), ("apart.toml", &apart)]);
        let one = Scene::load(dir.path().join("one.toml")).unwrap();
        let apart = Scene::load(dir.path().join("apart.toml")).unwrap();
        let (a, b) = (shadow_scene(&one).unwrap(), shadow_scene(&apart).unwrap());
        prop_assert!(a.mesh == b.mesh, "umbra shadow: the outputs differ");
        let (a, b) = (dm_scene(&one).unwrap(), dm_scene(&apart).unwrap());
        prop_assert!(a.mesh().unwrap() == b.mesh().unwrap(), "umbra dm: the outputs differ");
    }
}
