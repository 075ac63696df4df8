//! `umbra render` end to end: PNG files of the right size, shadows where the
//! geometry puts them, the same bytes on every run, clear errors.

use std::path::Path;

use crate::{folder, umbra};
use umbra::{FragmentClass, Projection, Scene};

/// A floor, a square 5 above it and a point light 10 above the floor: the
/// square's umbra on the floor is `[-4, 4] x [-4, 4]`. The camera looks at
/// the floor from below the square, so the square hides none of it.
const SCENE: &str = r#"
ambient = 0.1

[[object]]
name = "floor"
polygons = [[[-10, 0, 10], [10, 0, 10], [10, 0, -10], [-10, 0, -10]]]

[[object]]
name = "square"
polygons = [[[-2, 5, 2], [2, 5, 2], [2, 5, -2], [-2, 5, -2]]]

[[light]]
type = "point"
position = [0, 10, 0]
intensity = 100.0
color = [1.0, 0.9, 0.8]

[camera]
eye = [0.0, 3.0, 12.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
fov_deg = 60.0
width = 160
height = 120
"#;

/// Reads a PNG back: (width, height, RGB bytes).
fn decode(path: &Path) -> (u32, u32, Vec<u8>) {
    let file = std::fs::File::open(path).unwrap();
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Renders `scene.toml` in `dir` with `view` into `name`, expecting success.
fn render(dir: &Path, view: &str, name: &str) -> (u32, u32, Vec<u8>) {
    let run = umbra(dir, &["render", "scene.toml", "-o", name, "--view", view]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    decode(&dir.join(name))
}

/// The pixel (column, row) where the floor point `p` shows.
fn pixel_of(p: [f64; 3]) -> (usize, usize) {
    let scene = Scene::from_toml_str(SCENE, "scene.toml").unwrap();
    let [x, y, _] = Projection::new(&scene.camera.unwrap()).project(p).unwrap();
    (x as usize, y as usize)
}

fn at(image: &(u32, u32, Vec<u8>), (x, y): (usize, usize)) -> [u8; 3] {
    let k = 3 * (y * image.0 as usize + x);
    [image.2[k], image.2[k + 1], image.2[k + 2]]
}

#[test]
fn the_shadow_is_dark_and_umbra_coloured() {
    let dir = folder(&[("scene.toml", SCENE)]);
    let in_shadow = pixel_of([0.0, 0.0, 1.0]);
    let lit = pixel_of([6.5, 0.0, 1.0]);

    let shaded = render(dir.path(), "shaded", "shaded.png");
    assert_eq!((shaded.0, shaded.1), (160, 120));
    assert_eq!(shaded.2.len(), 160 * 120 * 3);
    let (dark, bright) = (at(&shaded, in_shadow), at(&shaded, lit));
    for ch in 0..3 {
        assert!(dark[ch] + 40 < bright[ch], "{dark:?} vs {bright:?}");
    }
    // The ambient term alone still shows the floor in the shadow.
    assert!(dark[0] > 0, "{dark:?}");
    // The light is warm: red above blue where it shines.
    assert!(bright[0] > bright[2], "{bright:?}");

    let classes = render(dir.path(), "classes", "classes.png");
    assert_eq!((classes.0, classes.1), (160, 120));
    assert_eq!(at(&classes, in_shadow), FragmentClass::Umbra.srgb());
    assert_eq!(at(&classes, lit), FragmentClass::Lit.srgb());
    // No area light: nothing is penumbra.
    assert!(
        classes
            .2
            .chunks(3)
            .all(|p| p != FragmentClass::Penumbra.srgb())
    );
}

#[test]
fn the_same_scene_gives_the_same_bytes() {
    let dir = folder(&[("scene.toml", SCENE)]);
    for view in ["shaded", "classes", "fragments"] {
        render(dir.path(), view, "a.png");
        render(dir.path(), view, "b.png");
        let a = std::fs::read(dir.path().join("a.png")).unwrap();
        let b = std::fs::read(dir.path().join("b.png")).unwrap();
        assert_eq!(a, b, "{view}");
    }
}

/// The camera's up vector counts by its direction only, however long (a
/// length of 1e300 overflowed: refused as parallel to the view, then
/// rendered black), and a camera 1e200 away renders (the scene too small
/// to show).
#[test]
fn a_huge_up_vector_or_a_far_eye_renders() {
    let dir = folder(&[("scene.toml", SCENE)]);
    let unit = render(dir.path(), "shaded", "unit.png");
    let huge = SCENE.replace("up = [0.0, 1.0, 0.0]", "up = [0.0, 1e300, 0.0]");
    let dir = folder(&[("scene.toml", &huge)]);
    assert_eq!(render(dir.path(), "shaded", "huge.png"), unit);
    let far = SCENE.replace("eye = [0.0, 3.0, 12.0]", "eye = [0.0, 3e200, 12e200]");
    let dir = folder(&[("scene.toml", &far)]);
    let (width, height, _) = render(dir.path(), "shaded", "far.png");
    assert_eq!((width, height), (160, 120));
}

#[test]
fn fragments_are_outlined() {
    let dir = folder(&[("scene.toml", SCENE)]);
    let classes = render(dir.path(), "classes", "classes.png");
    let fragments = render(dir.path(), "fragments", "fragments.png");
    assert_eq!((fragments.0, fragments.1), (160, 120));
    assert_ne!(classes.2, fragments.2);
    // The outlines are drawn over the same classes: the middle of the
    // shadow is the same in both.
    let middle = pixel_of([0.0, 0.0, 1.0]);
    assert_eq!(at(&classes, middle), at(&fragments, middle));
    // ... and pixels darker than any class colour appear.
    let darkest = |image: &(u32, u32, Vec<u8>)| image.2.iter().copied().min().unwrap();
    assert!(darkest(&fragments) < darkest(&classes));
}

#[test]
fn a_scene_without_camera_is_refused() {
    let without = SCENE.split("[camera]").next().unwrap();
    let dir = folder(&[("scene.toml", without)]);
    let run = umbra(dir.path(), &["render", "scene.toml", "-o", "out.png"]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(run.stderr.contains("camera"), "{}", run.stderr);
    assert!(run.stderr.contains("scene.toml"), "{}", run.stderr);
    assert!(!run.stderr.contains("panicked"), "{}", run.stderr);
    assert!(!dir.path().join("out.png").exists());
}

#[test]
fn an_unwritable_output_leaves_nothing() {
    let dir = folder(&[("scene.toml", SCENE)]);
    let run = umbra(
        dir.path(),
        &["render", "scene.toml", "-o", "missing/out.png"],
    );
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(run.stderr.contains("missing/out.png"), "{}", run.stderr);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn per_light_irradiance_adds_up_to_the_vertex_irradiance() {
    let two_lights = SCENE.replace(
        "[camera]",
        "[[light]]\ntype = \"directional\"\ndirection = [1, -2, 0.5]\nintensity = 0.5\n\n[camera]",
    );
    let scene = Scene::from_toml_str(&two_lights, "scene.toml").unwrap();
    let shadows = umbra::shadow_scene(&scene).unwrap();
    assert_eq!(shadows.lights, 2);
    assert_eq!(
        shadows.light_irradiance.len(),
        2 * shadows.mesh.vertices.len()
    );
    for face in &shadows.mesh.faces {
        for &v in &face.vertices {
            let per_light = shadows.vertex_light_irradiance(v as usize);
            for (i, e) in per_light.iter().enumerate() {
                if face.lit_mask & (1 << i) == 0 {
                    assert_eq!(*e, 0.0);
                }
            }
            let total: f64 = per_light.iter().sum();
            let ply = f64::from(shadows.mesh.vertices[v as usize].1);
            assert!(
                (total - ply).abs() <= 1e-6 * total.max(1.0),
                "{total} {ply}"
            );
        }
    }
}

#[test]
fn back_faces_are_drawn_dark() {
    // The one-sided floor seen from below: its back shows, lit by the
    // ambient term only, in front of the black background.
    let below = SCENE.replace("eye = [0.0, 3.0, 12.0]", "eye = [0.0, -3.0, 12.0]");
    let scene = Scene::from_toml_str(&below, "scene.toml").unwrap();
    let p = Projection::new(&scene.camera.unwrap())
        .project([6.5, 0.0, 1.0])
        .unwrap();
    let (x, y) = (p[0] as u32, p[1] as u32);
    let shaded = umbra::render_scene(&scene, umbra::View::Shaded).unwrap();
    let back = shaded.pixel(x, y);
    assert!(back[0] > 0 && back[0] < 100, "{back:?}");
    let classes = umbra::render_scene(&scene, umbra::View::Classes).unwrap();
    assert_eq!(classes.pixel(x, y), FragmentClass::Umbra.srgb());
}
