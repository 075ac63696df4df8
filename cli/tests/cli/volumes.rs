//! `umbra render --method volumes` (Bergeron's shadow volumes counted along
//! eye rays) against `--method fragments` (umbra's object-space fragments):
//! on point-light scenes the two agree away from shadow edges.
//!
//! The rule, fixed before any scene was tried: images are the classes view
//! at 96 x 72; a pixel is compared only if its 3 x 3 neighbourhood is one
//! colour in both images (a pixel next to any edge, whose samples blend two
//! classes or a surface and the sky, is left out); at least 99.5 % of the
//! compared pixels must be equal, at least half of all pixels must be
//! compared, and the compared pixels must hold both lit and umbra pixels.

use std::path::Path;

use umbra::{
    FragmentClass, Image, Method, Order, RenderOptions, Scene, View, render_scene_with, write_demo,
};

use crate::{folder, umbra};

const WIDTH: u32 = 96;
const HEIGHT: u32 = 72;

fn camera(eye: [f64; 3], target: [f64; 3]) -> String {
    format!(
        "[camera]\neye = {eye:?}\ntarget = {target:?}\nfov_deg = 60.0\nwidth = {WIDTH}\nheight = {HEIGHT}\n"
    )
}

/// A floor `[-s, s]^2` at y = 0 facing up.
fn floor(s: f64) -> String {
    format!(
        "[[object]]\nname = \"floor\"\npolygons = [[[{m}, 0, {s}], [{s}, 0, {s}], [{s}, 0, {m}], [{m}, 0, {m}]]]\n",
        m = -s
    )
}

/// An OBJ box `[lo, hi]` with outward counter-clockwise faces; `open`
/// leaves out its top.
fn box_obj(lo: [f64; 3], hi: [f64; 3], open: bool) -> String {
    let mut obj = String::new();
    for i in 0..8 {
        let c = |axis: usize, bit: usize| if i & bit == 0 { lo[axis] } else { hi[axis] };
        obj += &format!("v {} {} {}\n", c(0, 1), c(1, 2), c(2, 4));
    }
    let mut faces = vec![
        [1, 5, 7, 3],
        [2, 4, 8, 6],
        [1, 2, 6, 5],
        [1, 3, 4, 2],
        [5, 6, 8, 7],
    ];
    if !open {
        faces.push([3, 7, 8, 4]);
    }
    for f in faces {
        obj += &format!("f {} {} {} {}\n", f[0], f[1], f[2], f[3]);
    }
    obj
}

fn point_light(position: [f64; 3], extra: &str) -> String {
    format!("[[light]]\ntype = \"point\"\nposition = {position:?}\nintensity = 50.0\n{extra}\n")
}

fn classes(scene: &Scene, method: Method) -> Image {
    render_scene_with(
        scene,
        &RenderOptions {
            view: View::Classes,
            method,
            order: Order::ZBuffer,
        },
    )
    .unwrap()
}

/// Compares the two methods' images of `scene` under the rule above;
/// returns (compared, equal) pixel counts.
fn cross_check(scene: &Scene, name: &str) -> (usize, usize) {
    let a = classes(scene, Method::Fragments);
    let b = classes(scene, Method::Volumes);
    let (w, h) = (a.width as usize, a.height as usize);
    let uniform = |image: &Image, x: usize, y: usize| {
        let centre = image.pixel(x as u32, y as u32);
        (y - 1..=y + 1).all(|j| (x - 1..=x + 1).all(|i| image.pixel(i as u32, j as u32) == centre))
    };
    let (lit, umbra) = (FragmentClass::Lit.srgb(), FragmentClass::Umbra.srgb());
    let (mut compared, mut equal, mut seen_lit, mut seen_umbra) = (0, 0, 0, 0);
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            if !uniform(&a, x, y) || !uniform(&b, x, y) {
                continue;
            }
            compared += 1;
            let (pa, pb) = (a.pixel(x as u32, y as u32), b.pixel(x as u32, y as u32));
            if pa == pb {
                equal += 1;
                seen_lit += usize::from(pa == lit);
                seen_umbra += usize::from(pa == umbra);
            }
        }
    }
    eprintln!(
        "{name}: {equal} of {compared} compared pixels agree ({seen_lit} lit, {seen_umbra} umbra)"
    );
    assert!(
        compared * 2 >= w * h,
        "{name}: only {compared} of {} pixels compared",
        w * h
    );
    assert!(
        equal * 1000 >= compared * 995,
        "{name}: {equal} of {compared} compared pixels agree"
    );
    assert!(
        seen_lit > 20 && seen_umbra > 20,
        "{name}: {seen_lit} lit, {seen_umbra} umbra pixels"
    );
    (compared, equal)
}

fn load(dir: &Path) -> Scene {
    Scene::load(dir.join("scene.toml")).unwrap()
}

#[test]
fn open_box_lit_from_inside() {
    // The box has no top; the light inside shines out of it onto a wall
    // behind, whose lower part is in the box's shadow, as is the floor.
    let scene = format!(
        "{}[[object]]\nname = \"box\"\nmesh = \"box.obj\"\ntwo_sided = true\n\
         [[object]]\nname = \"wall\"\npolygons = [[[-8, 0, -6], [8, 0, -6], [8, 10, -6], [-8, 10, -6]]]\n\
         {}{}",
        floor(8.0),
        point_light([0.3, 1.7, 0.2], ""),
        camera([5.0, 7.0, 9.0], [0.0, 1.5, -2.0])
    );
    let obj = box_obj([-1.5, 0.5, -1.5], [1.5, 2.5, 1.5], true);
    let dir = folder(&[("scene.toml", &scene), ("box.obj", &obj)]);
    cross_check(&load(dir.path()), "open box, light inside");
}

#[test]
fn open_box_lit_from_outside() {
    let scene = format!(
        "{}[[object]]\nname = \"box\"\nmesh = \"box.obj\"\ntwo_sided = true\n{}{}",
        floor(8.0),
        point_light([-3.0, 6.0, 2.0], ""),
        camera([4.0, 7.0, 7.0], [0.0, 0.5, 0.0])
    );
    let obj = box_obj([-1.5, 0.5, -1.5], [1.5, 2.5, 1.5], true);
    let dir = folder(&[("scene.toml", &scene), ("box.obj", &obj)]);
    cross_check(&load(dir.path()), "open box, light outside");
}

#[test]
fn closed_boxes() {
    let scene = format!(
        "{}[[object]]\nname = \"a\"\nmesh = \"a.obj\"\n[[object]]\nname = \"b\"\nmesh = \"b.obj\"\n{}{}",
        floor(8.0),
        point_light([1.0, 8.0, 1.5], ""),
        camera([3.0, 9.0, 9.0], [0.0, 0.0, 0.0])
    );
    let a = box_obj([-3.0, 0.0, -2.0], [-1.0, 2.0, 0.0], false);
    let b = box_obj([0.5, 2.5, 0.5], [2.0, 3.5, 2.0], false);
    let dir = folder(&[("scene.toml", &scene), ("a.obj", &a), ("b.obj", &b)]);
    cross_check(&load(dir.path()), "closed boxes");
}

#[test]
fn a_twisted_quad() {
    // Its corners alternate in height; seen from the light, on its side,
    // edges 0-1 and 2-3 cross: it is L-twisted.
    let scene = format!(
        "{}[[object]]\nname = \"quad\"\ntwo_sided = true\npolygons = [[[-2, 2, -2], [2, 4, -2], [2, 2, 2], [-2, 4, 2]]]\n\
         [[object]]\nname = \"wall\"\npolygons = [[[8, 0, 7], [-8, 0, 7], [-8, 8, 7], [8, 8, 7]]]\n{}{}",
        floor(8.0),
        point_light([0.2, 3.1, -12.0], ""),
        camera([7.0, 6.0, -6.0], [0.0, 2.5, 5.0])
    );
    let dir = folder(&[("scene.toml", &scene)]);
    let scene = load(dir.path());
    // The volumes see it twisted.
    let pieces = umbra::Pieces::from_scene(&scene).unwrap();
    let quad: Vec<_> = pieces
        .grid
        .snap_all(&scene.objects[1].polygons[0].vertices)
        .unwrap()
        .0;
    let umbra::SnappedLight::Point(light) = pieces.lights[0] else {
        panic!("a point light");
    };
    assert!(svbsp::bergeron::is_l_twisted(
        &quad,
        &svbsp::LightSource::Point(light)
    ));
    cross_check(&scene, "twisted quad");
}

#[test]
fn the_eye_inside_a_shadow_volume() {
    // The eye is under a closed slab, in its shadow volume: its counts
    // start at 2 and the floor's shadow around it must still come out.
    let scene = format!(
        "{}[[object]]\nname = \"slab\"\nmesh = \"slab.obj\"\n{}{}",
        floor(10.0),
        point_light([0.0, 9.0, 0.0], ""),
        camera([0.4, 2.0, 0.3], [4.0, 0.0, 3.0])
    );
    let slab = box_obj([-3.0, 4.0, -3.0], [3.0, 4.5, 3.0], false);
    let dir = folder(&[("scene.toml", &scene), ("slab.obj", &slab)]);
    cross_check(&load(dir.path()), "eye in shadow");
}

#[test]
fn a_light_with_a_range() {
    // The floor straddles the sphere of influence; the wall is wholly
    // beyond it and takes no part (umbra in both methods).
    let scene = format!(
        "{}[[object]]\nname = \"box\"\nmesh = \"box.obj\"\n\
         [[object]]\nname = \"wall\"\npolygons = [[[20, 0, 8], [20, 0, -8], [20, 8, -8], [20, 8, 8]]]\n\
         [[object]]\nname = \"far\"\nmesh = \"far.obj\"\n{}{}",
        floor(8.0),
        point_light([0.5, 5.0, 0.3], "falloff_start = 1.0\nrange = 9.0"),
        camera([-6.0, 8.0, 9.0], [3.0, 0.0, 0.0])
    );
    let obj = box_obj([-1.0, 1.5, -1.0], [1.0, 2.5, 1.0], false);
    let far = box_obj([17.0, 0.0, -1.0], [18.0, 3.0, 1.0], false);
    let dir = folder(&[("scene.toml", &scene), ("box.obj", &obj), ("far.obj", &far)]);
    cross_check(&load(dir.path()), "range");
}

#[test]
fn the_point_light_demos() {
    // The demos' shadows are finer: 160 x 160 leaves enough umbra pixels
    // away from edges.
    for name in ["tetra", "window"] {
        let dir = folder(&[]);
        let mut scene = Scene::load(write_demo(name, dir.path()).unwrap()).unwrap();
        let camera = scene.camera.as_mut().unwrap();
        (camera.width, camera.height) = (160, 160);
        cross_check(&scene, name);
    }
}

#[test]
fn the_command_takes_the_method_and_refuses_area_lights() {
    let scene = format!(
        "{}[[object]]\nname = \"box\"\nmesh = \"box.obj\"\n{}{}",
        floor(8.0),
        point_light([1.0, 6.0, 1.0], ""),
        camera([4.0, 7.0, 7.0], [0.0, 0.5, 0.0])
    );
    let obj = box_obj([-1.0, 0.0, -1.0], [1.0, 2.0, 1.0], false);
    let area = scene.replace(
        "type = \"point\"\nposition = [1.0, 6.0, 1.0]",
        "type = \"area\"\nvertices = [[-1, 6, -1], [-1, 6, 1], [1, 6, 1], [1, 6, -1]]",
    );
    assert_ne!(area, scene);
    let dir = folder(&[
        ("scene.toml", &scene),
        ("area.toml", &area),
        ("box.obj", &obj),
    ]);
    let run = umbra(
        dir.path(),
        &["render", "scene.toml", "-o", "v.png", "--method", "volumes"],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(dir.path().join("v.png").exists());
    let run = umbra(
        dir.path(),
        &["render", "area.toml", "-o", "a.png", "--method", "volumes"],
    );
    assert_ne!(run.code, 0);
    assert!(run.stderr.contains("area light"), "{}", run.stderr);
    assert!(!dir.path().join("a.png").exists());
}
