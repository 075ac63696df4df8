//! An open box (a cup: five quads, turned so the grid bends them) under an
//! area light that shines into it: the light reaching its inside walls
//! through the opening is seen, whatever the rounding did to the box. The
//! umbra of an open surface holds only outside it (a body the rounding
//! moved in leaves part of the inside outside the body).

use crate::area::face_points;
use crate::vectors::{cross, dot, inner_points, sub};
use crate::{folder, umbra};
use umbra::{OutputMesh, load_ply};

/// The cup, its walls facing out (`inward = false`, two-sided) or in
/// (one-sided, receiving inside).
fn cup(inward: bool) -> String {
    let mut quads = [
        [[-1, -1, -1], [-1, -1, 1], [-1, 1, 1], [-1, 1, -1]],
        [[1, -1, -1], [1, 1, -1], [1, 1, 1], [1, -1, 1]],
        [[-1, -1, -1], [1, -1, -1], [1, -1, 1], [-1, -1, 1]],
        [[-1, -1, -1], [-1, 1, -1], [1, 1, -1], [1, -1, -1]],
        [[-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]],
    ];
    if inward {
        quads.iter_mut().for_each(|q| q.reverse());
    }
    let polygons: Vec<String> = quads.iter().map(|q| format!("{q:?}")).collect();
    format!(
        r#"
[[object]]
name = "cup"
polygons = [{}]
translate = [0, 1.5, 0]
scale = 0.5
rotate_deg = [45.593384712049414, -71.63056856681807, 2.6074741784614162]
two_sided = {}

[[light]]
type = "area"
vertices = [[-0.2, 4, -0.2], [0.2, 4, -0.2], [0.2, 4, 0.2], [-0.2, 4, 0.2]]
intensity = 1
"#,
        polygons.join(", "),
        !inward
    )
}

/// Whether the segment `p`-`l` crosses the convex polygon `q` (`None`:
/// too close to its border or plane to tell in floating point).
pub(crate) fn crosses(p: [f64; 3], l: [f64; 3], q: &[[f64; 3]]) -> Option<bool> {
    let mut n = [0.0; 3];
    for i in 0..q.len() {
        let c = cross(q[i], q[(i + 1) % q.len()]);
        n = std::array::from_fn(|k| n[k] + c[k]);
    }
    let length = dot(n, n).sqrt();
    let n = n.map(|c| c / length);
    let margin = 1e-7;
    let (dp, dl) = (dot(n, sub(p, q[0])), dot(n, sub(l, q[0])));
    if dp.abs() <= margin || dl.abs() <= margin {
        return None;
    }
    if (dp > 0.0) == (dl > 0.0) {
        return Some(false);
    }
    let t = dp / (dp - dl);
    let x: [f64; 3] = std::array::from_fn(|k| p[k] + t * (l[k] - p[k]));
    let mut inside = true;
    for i in 0..q.len() {
        let edge = sub(q[(i + 1) % q.len()], q[i]);
        let s = dot(cross(edge, sub(x, q[i])), n) / dot(edge, edge).sqrt();
        if s.abs() <= margin {
            return None;
        }
        inside &= s > 0.0;
    }
    Some(inside)
}

/// Every umbra face sees none of the light from points inside it (its
/// centre, and halfway to each corner): each segment to 11 x 11 points of
/// the light that reaches its receiving side crosses a face of another
/// polygon. Returns how many umbra faces were checked.
fn assert_umbra_sees_nothing(mesh: &OutputMesh, two_sided: bool, what: &str) -> usize {
    let faces: Vec<Vec<[f64; 3]>> = (0..mesh.faces.len())
        .map(|f| face_points(mesh, f))
        .collect();
    let mut checked = 0;
    for (f, face) in mesh.faces.iter().enumerate() {
        if face.umbra_mask & 1 == 0 {
            continue;
        }
        checked += 1;
        let corners = &faces[f];
        for p in inner_points(corners) {
            for i in 0..11 {
                for j in 0..11 {
                    let l = [-0.2 + 0.04 * f64::from(i), 4.0, -0.2 + 0.04 * f64::from(j)];
                    // A one-sided face receives on its counter-clockwise side.
                    let normal = cross(sub(corners[1], corners[0]), sub(corners[2], corners[0]));
                    let toward = dot(normal, sub(l, p));
                    if !two_sided && toward <= 0.0 {
                        continue;
                    }
                    let blocked = mesh
                        .faces
                        .iter()
                        .zip(&faces)
                        .filter(|(other, _)| other.source != face.source)
                        .any(|(_, q)| crosses(p, l, q) != Some(false));
                    assert!(
                        blocked,
                        "{what}: umbra face {f} sees the light from {p:?} at {l:?}"
                    );
                }
            }
        }
    }
    checked
}

#[test]
fn light_through_an_open_box_reaches_its_inside() {
    for inward in [false, true] {
        let dir = folder(&[("scene.toml", cup(inward).as_str())]);
        for command in ["shadow", "dm"] {
            let run = umbra(dir.path(), &[command, "scene.toml", "-o", "out.ply"]);
            assert_eq!(run.code, 0, "{}", run.stderr);
            let mesh = load_ply(&dir.path().join("out.ply")).unwrap();
            let what = format!(
                "{command}, walls facing {}",
                if inward { "in" } else { "out" }
            );
            let umbrae = assert_umbra_sees_nothing(&mesh, !inward, &what);
            let lit = mesh.faces.iter().filter(|f| f.lit_mask & 1 != 0).count();
            assert!(
                umbrae > 0 && lit > 0,
                "{what}: {umbrae} umbra, {lit} lit faces"
            );
        }
    }
}
