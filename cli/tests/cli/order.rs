//! `umbra render --order bsp` (back-to-front traversal of the scene BSP
//! from the eye) draws the same image as the z-buffer on scenes whose
//! polygons do not interpenetrate.

use umbra::{Image, Method, Order, RenderOptions, Scene, View, render_scene_with, write_demo};

use crate::{folder, umbra};

/// Floating boxes over a floor, a two-sided card and a wall: nothing
/// touches, so the z-buffer's nearest surface is always the painter's last.
const SCENE: &str = r#"
ambient = 0.05

[[object]]
name = "floor"
polygons = [[[-8, 0, 8], [8, 0, 8], [8, 0, -8], [-8, 0, -8]]]

[[object]]
name = "wall"
polygons = [[[-8, 0.5, -7], [8, 0.5, -7], [8, 7, -7], [-8, 7, -7]]]

[[object]]
name = "box"
mesh = "box.obj"

[[object]]
name = "card"
two_sided = true
polygons = [[[1, 3, 1], [3, 3.5, 1], [3, 3, 3], [1, 2.5, 3]]]

[[light]]
type = "point"
position = [-1.0, 8.0, 2.0]
intensity = 60.0

[[light]]
type = "directional"
direction = [0.3, -1.0, -0.4]
intensity = 0.3
color = [0.6, 0.7, 1.0]

[camera]
eye = [5.0, 6.0, 10.0]
target = [0.0, 1.5, 0.0]
fov_deg = 55.0
width = 96
height = 72
"#;

const BOX: &str = "v -2 1 -2\nv -0.5 1 -2\nv -2 2.5 -2\nv -0.5 2.5 -2\nv -2 1 -0.5\nv -0.5 1 -0.5\nv -2 2.5 -0.5\nv -0.5 2.5 -0.5\n\
f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 1 3 4 2\nf 5 6 8 7\nf 3 7 8 4\n";

/// Pixels that differ, and the largest difference of a channel.
fn compare(a: &Image, b: &Image) -> (usize, u8) {
    let differ = a
        .rgb
        .chunks(3)
        .zip(b.rgb.chunks(3))
        .filter(|(p, q)| p != q)
        .count();
    let most = a
        .rgb
        .iter()
        .zip(&b.rgb)
        .map(|(p, q)| p.abs_diff(*q))
        .max()
        .unwrap_or(0);
    (differ, most)
}

fn image(scene: &Scene, view: View, method: Method, order: Order) -> Image {
    render_scene_with(
        scene,
        &RenderOptions {
            view,
            method,
            order,
        },
    )
    .unwrap()
}

#[test]
fn bsp_order_draws_the_z_buffer_image() {
    let dir = folder(&[("scene.toml", SCENE), ("box.obj", BOX)]);
    let scene = Scene::load(dir.path().join("scene.toml")).unwrap();
    for method in [Method::Fragments, Method::Volumes] {
        for view in [View::Shaded, View::Classes, View::Fragments] {
            let z = image(&scene, view, method, Order::ZBuffer);
            let bsp = image(&scene, view, method, Order::Bsp);
            let (differ, most) = compare(&z, &bsp);
            // Which surface every sample shows is the order's whole job:
            // the classes and fragments views show it byte for byte. The
            // painter draws fragments clipped to BSP parts, another
            // triangulation of the same affine values, so shaded values
            // may round to the neighbouring 8-bit level.
            match view {
                View::Shaded => assert!(most <= 1, "{method:?}: {differ} pixels, by {most}"),
                _ => assert_eq!(differ, 0, "{method:?} {view:?}: {differ} pixels differ"),
            }
        }
    }
}

#[test]
fn bsp_order_on_the_demos() {
    for name in ["tetra", "window"] {
        let dir = folder(&[]);
        let mut scene = Scene::load(write_demo(name, dir.path()).unwrap()).unwrap();
        let camera = scene.camera.as_mut().unwrap();
        (camera.width, camera.height) = (96, 72);
        let z = image(&scene, View::Classes, Method::Fragments, Order::ZBuffer);
        let bsp = image(&scene, View::Classes, Method::Fragments, Order::Bsp);
        let (differ, _) = compare(&z, &bsp);
        assert_eq!(differ, 0, "{name}: {differ} pixels differ");
    }
}

#[test]
fn the_command_takes_the_order() {
    let dir = folder(&[("scene.toml", SCENE), ("box.obj", BOX)]);
    for order in ["zbuffer", "bsp"] {
        let out = format!("{order}.png");
        let run = umbra(
            dir.path(),
            &[
                "render",
                "scene.toml",
                "-o",
                &out,
                "--order",
                order,
                "--view",
                "classes",
            ],
        );
        assert_eq!(run.code, 0, "{}", run.stderr);
    }
    let a = std::fs::read(dir.path().join("zbuffer.png")).unwrap();
    let b = std::fs::read(dir.path().join("bsp.png")).unwrap();
    assert!(a == b, "the two orders wrote different images");
}
