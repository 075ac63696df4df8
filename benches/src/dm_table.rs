//! Chrysanthou & Slater's figures beside umbra's discontinuity meshes:
//! build and illumination of scenes of 92-184 polygons, and moving an
//! object of 5-30 % of the scene against rebuilding; then a hall of 10k
//! polygons built and a box moved, with and without the EV / VE
//! discontinuities; last, dense closed meshes (the `meshes` demo) and the
//! polygons clipped per vertex under them.

use crate::output_change::OutputChange;
use bsp_core::ConvexPolygon;
use std::path::Path;
use std::time::Instant;
use umbra::{DmOptions, DmRun, Scene, dm_scene, dm_scene_moving, dm_scene_with, write_demo};

/// A demo written into `dir` and loaded.
pub fn demo(dir: &Path, name: &str) -> Scene {
    let path = write_demo(name, &dir.join(name)).expect("demo written");
    Scene::load(&path).expect("demo loads")
}

/// Moves of a box on the hall, back and forth (the first pays for
/// touching memory the build left cold; an application moving an object
/// frame after frame sees the others).
const HALL_MOVES: usize = 21;

/// Seconds of `moves` moves of object `name` by 0.05 along x and back,
/// each with its re-illumination, in order; `run`'s polygons follow the
/// object.
fn back_and_forth(run: &mut DmRun, scene: &Scene, name: &str, moves: usize) -> Vec<f64> {
    let index = scene
        .objects
        .iter()
        .position(|o| o.name == name)
        .expect("object exists");
    let (id, ks) = run.objects[index].clone();
    let step = (0.05 * run.pieces.grid.scale()).round() as i64;
    let here: Vec<ConvexPolygon> = ks.iter().map(|&k| run.pieces.polygons[k].clone()).collect();
    let there: Vec<ConvexPolygon> = here
        .iter()
        .map(|p| p.translated([step, 0, 0]).expect("on the grid"))
        .collect();
    let seconds = (0..moves)
        .map(|m| {
            let to = if m % 2 == 0 { &there } else { &here };
            let start = Instant::now();
            run.dm.move_object(id, to.clone()).expect("moves");
            run.dm.illuminate();
            start.elapsed().as_secs_f64()
        })
        .collect();
    // The scene's polygons where the last move left the object, for a
    // rebuild of the same state.
    let last = if moves % 2 == 1 { there } else { here };
    for (&k, p) in ks.iter().zip(last) {
        run.pieces.polygons[k] = p;
    }
    seconds
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The fastest of `runs` builds (with illumination).
fn best_build(scene: &Scene, runs: usize, options: DmOptions) -> DmRun {
    let mut best: Option<DmRun> = None;
    for _ in 0..runs {
        let run = dm_scene_with(scene, options).expect("the scene builds");
        if best
            .as_ref()
            .is_none_or(|b| run.stats.stats.seconds.total < b.stats.stats.seconds.total)
        {
            best = Some(run);
        }
    }
    best.expect("ran")
}

/// Median seconds to remove object `name` from a copy of the built DM
/// (the deletion alone, as the paper times it).
fn delete_seconds(run: &DmRun, scene: &Scene, name: &str, runs: usize) -> f64 {
    let index = scene
        .objects
        .iter()
        .position(|o| o.name == name)
        .expect("object exists");
    let id = run.objects[index].0;
    let times = (0..runs)
        .map(|_| {
            let mut dm = run.dm.clone();
            let start = Instant::now();
            dm.remove_object(id).expect("removable");
            start.elapsed().as_secs_f64()
        })
        .collect();
    median(times)
}

/// A moved object's figures.
struct MoveRow<'a> {
    scene: &'a str,
    object: &'a str,
    /// The object's share of the scene's polygons.
    share: f64,
    delete: f64,
    update: f64,
    rebuild: f64,
    /// A move's median seconds over a rebuild's, both on one thread: the
    /// work a move does against a rebuild's, beside the share of the
    /// output it must write (`change`), whatever share of a rebuild's two
    /// threads a move's few receivers can use.
    one_thread: f64,
    /// What one step of the move changes in the output.
    change: OutputChange,
}

/// Prints the table.
pub fn print() {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "Chrysanthou & Slater, incremental discontinuity meshes (paper: Sparc 20; umbra: this machine, {cores} cores)"
    );
    println!(
        "  paper: 92-184 polygons built and illuminated in 0.77-2.24 s; deleting a moving object of 5-30 % of the scene never above 4 % of a rebuild, usually about 1 %"
    );
    println!(
        "{:<22} {:>6} {:>9} {:>7} {:>7} {:>8} {:>8}",
        "scene", "input", "build ms", "cells", "nodes", "cmp/v", "cmp/vis"
    );
    let dir = std::env::temp_dir().join(format!("umbra-dm-table-{}", std::process::id()));
    let moves = [
        ("office", "desk_1", [0.05, 0.0, 0.0]),
        ("office", "monitor_1", [0.05, 0.0, 0.0]),
        ("cubes", "cube_1", [0.05, 0.0, 0.05]),
    ];
    let mut rows = Vec::new();
    for name in ["office", "cubes"] {
        let scene = demo(&dir, name);
        let outer = best_build(
            &scene,
            10,
            DmOptions {
                internal_discontinuities: false,
                ..DmOptions::default()
            },
        );
        let run = best_build(&scene, 10, DmOptions::default());
        for (label, r) in [("outer only", &outer), ("with EV/VE", &run)] {
            let s = &r.stats;
            println!(
                "{:<22} {:>6} {:>9.2} {:>7} {:>7} {:>8.2} {:>8.2}",
                format!("{name}, {label}"),
                s.stats.input_polygons,
                1e3 * s.stats.seconds.total,
                s.dm.cells,
                s.dm.tree_nodes,
                s.dm.comparisons_per_vertex,
                s.dm.comparisons_per_visibility_vertex
            );
        }
        let s = &run.stats;
        for (scene_name, object, by) in moves.iter().filter(|m| m.0 == name) {
            let delete = delete_seconds(&run, &scene, object, 11);
            let mut moving = dm_scene(&scene).expect("builds");
            let index = scene
                .objects
                .iter()
                .position(|o| &o.name == object)
                .expect("object");
            let share = moving.objects[index].1.len() as f64 / s.stats.input_polygons as f64;
            let figures = moving
                .move_steps(&scene, object, *by, 11, |_, _, _| {})
                .expect("moves");
            let one_thread = rayon::ThreadPoolBuilder::new()
                .num_threads(1)
                .build()
                .expect("a one-thread pool")
                .install(|| {
                    let mut moving = dm_scene(&scene).expect("builds");
                    let figures = moving
                        .move_steps(&scene, object, *by, 11, |_, _, _| {})
                        .expect("moves");
                    median(figures.update_seconds) / median(figures.rebuild_seconds)
                });
            let mut one_step = dm_scene(&scene).expect("builds");
            one_step
                .move_steps(&scene, object, *by, 1, |_, _, _| {})
                .expect("moves");
            let rebuilt = one_step.rebuilt().expect("rebuilds");
            let change = OutputChange::between(
                &run.mesh().expect("meshes"),
                &rebuilt.mesh().expect("meshes"),
            );
            rows.push(MoveRow {
                scene: scene_name,
                object,
                share,
                delete,
                update: median(figures.update_seconds.clone()),
                rebuild: median(figures.rebuild_seconds.clone()),
                one_thread,
                change,
            });
        }
    }
    println!(
        "  new cells / values: the share of a rebuild's output that one step's move must write (cells it lacked before, vertices new or of another irradiance); 1 thread: move % with move and rebuild on one thread"
    );
    println!(
        "{:<10} {:<10} {:>7} {:>10} {:>10} {:>11} {:>9} {:>9} {:>9} {:>10} {:>7}",
        "scene",
        "object",
        "share",
        "delete ms",
        "move ms",
        "rebuild ms",
        "delete %",
        "move %",
        "1 thread",
        "new cells",
        "values"
    );
    for row in rows {
        println!(
            "{:<10} {:<10} {:>6.1}% {:>10.3} {:>10.3} {:>11.3} {:>8.1}% {:>8.1}% {:>8.1}% {:>9.1}% {:>6.1}%",
            row.scene,
            row.object,
            100.0 * row.share,
            1e3 * row.delete,
            1e3 * row.update,
            1e3 * row.rebuild,
            100.0 * row.delete / row.rebuild,
            100.0 * row.update / row.rebuild,
            100.0 * row.one_thread,
            100.0 * row.change.cell_share(),
            100.0 * row.change.value_share()
        );
    }
    let hall = crate::rooms::box_hall(&dir, 1665, 7);
    println!(
        "hall of boxes: {} objects, 2 lights; box0 moved by 0.05 and back {HALL_MOVES} times (re-illumination included)",
        hall.objects.len()
    );
    println!(
        "  {:<16} {:>7} {:>8} {:>8} {:>9} {:>10} {:>11} {:>10} {:>7}",
        "discontinuities",
        "input",
        "build s",
        "cells",
        "rebuild s",
        "first ms",
        "median ms",
        "new cells",
        "values"
    );
    // The last row declares box0 movable at the build (as `umbra update`
    // does with the object it moves): its first move then costs what the
    // later ones do.
    for (label, internal, movable) in [
        ("outer only", false, false),
        ("with EV/VE", true, false),
        ("EV/VE, movable", true, true),
    ] {
        let options = DmOptions {
            internal_discontinuities: internal,
            ..DmOptions::default()
        };
        let start = Instant::now();
        let mut run = if movable {
            dm_scene_moving(&hall, options, "box0", [0.05, 0.0, 0.0], 1)
        } else {
            dm_scene_with(&hall, options)
        }
        .expect("the hall builds");
        let build = start.elapsed().as_secs_f64();
        let before = run.mesh().expect("the hall meshes");
        let moves = back_and_forth(&mut run, &hall, "box0", HALL_MOVES);
        let start = Instant::now();
        let moved = run.rebuilt().expect("the hall rebuilds");
        let rebuild = start.elapsed().as_secs_f64();
        let change = OutputChange::between(&before, &moved.mesh().expect("the hall meshes"));
        println!(
            "  {label:<16} {:>7} {build:>8.2} {:>8} {rebuild:>9.2} {:>10.2} {:>11.2} {:>9.2}% {:>6.2}%",
            run.stats.stats.input_polygons,
            run.stats.dm.cells,
            1e3 * moves[0],
            1e3 * median(moves),
            100.0 * change.cell_share(),
            100.0 * change.value_share()
        );
    }
    dense_meshes(&dir);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The `meshes` demo: dense closed meshes, their faces turned away from
/// the light casting nothing, many of their triangles covering each
/// vertex under them (the paper's scenes had 1.3 to 2.1 per vertex).
fn dense_meshes(dir: &Path) {
    let scene = demo(dir, "meshes");
    let start = Instant::now();
    let run = dm_scene_with(&scene, DmOptions::default()).expect("the meshes build");
    let build = start.elapsed().as_secs_f64();
    let s = &run.stats;
    println!(
        "dense closed meshes (`umbra demo meshes`, a torus and a bumpy sphere, with EV/VE): {} input, built and illuminated in {build:.2} s, {} cells, {:.2} polygons clipped per vertex ({:.2} per vertex in penumbra)",
        s.stats.input_polygons,
        s.dm.cells,
        s.dm.comparisons_per_vertex,
        s.dm.comparisons_per_visibility_vertex
    );
}
