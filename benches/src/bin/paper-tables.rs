//! Prints umbra's figures beside the tables of the papers it implements.
//!
//! Chin & Feiner 1989, Table 1: Haines' SPD tetra scenes under one point
//! light, timed on an HP 9000/350. Chin & Feiner 1992, Figure 8: a
//! furnished room under two quad lights (plate 6), timed on an HP 9000/375.
//! Chrysanthou & Slater: discontinuity meshes built and updated as objects
//! move, on a Sparc 20 ([`umbra_benches::dm_table`]).

use bsp_core::BuildOptions;
use std::time::Instant;
use svbsp::{Light, compute_shadows};
use umbra::{ShadowOptions, shadow_scene_with};
use umbra_benches::{rooms, scene, tetra};

/// The allocator of the `umbra` binary, so the figures are the command's.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// One row of the 1989 paper's Table 1.
struct PaperRow {
    name: &'static str,
    depth: u32,
    input: usize,
    front_facing: usize,
    edges: usize,
    nodes: usize,
    fragments: usize,
    seconds: f64,
}

const TABLE_1: [PaperRow; 2] = [
    PaperRow {
        name: "Tetra256",
        depth: 4,
        input: 258,
        front_facing: 130,
        edges: 390,
        nodes: 577,
        fragments: 723,
        seconds: 4.15,
    },
    PaperRow {
        name: "Tetra1024",
        depth: 5,
        input: 1026,
        front_facing: 514,
        edges: 1542,
        nodes: 2894,
        fragments: 3345,
        seconds: 25.44,
    },
];

fn main() {
    // `paper-tables dm`: the discontinuity-mesh table alone.
    if std::env::args().nth(1).as_deref() == Some("dm") {
        umbra_benches::dm_table::print();
        return;
    }
    // Table 1 on one thread: the 1989 paper's figures are one processor's,
    // and so is the speed goal.
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a one-thread pool")
        .install(table_1);
    println!();
    figure_8();
    println!();
    umbra_benches::dm_table::print();
}

/// The 1992 paper's Figure 8 row for plate 6 beside the `room` demo.
fn figure_8() {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "Chin & Feiner 1992, Figure 8, plate 6 (paper: HP 9000/375; umbra: this machine, {cores} cores)"
    );
    println!(
        "{:<30} {:>6} {:>6} {:>8} {:>8} {:>10} {:>9} {:>8}",
        "scene", "input", "lights", "shadow", "grid", "illum", "total", "output"
    );
    println!(
        "{:<30} {:>6} {:>6} {:>8.1} {:>8.1} {:>10} {:>9.1} {:>8}",
        "plate 6 (paper)", 151, 2, 35.8, 23.2, "178.1+247.2", 484.3, 9344
    );
    let dir = std::env::temp_dir().join(format!("umbra-figure-8-{}", std::process::id()));
    let room = rooms::demo_room(&dir);
    for (label, grid) in [
        ("umbra room, no grid", None),
        ("umbra room, --grid 40", Some(40)),
    ] {
        let options = ShadowOptions {
            grid,
            adaptive: None,
        };
        // The fastest of 20 runs.
        let mut best: Option<umbra::ShadowResult> = None;
        for _ in 0..20 {
            let result = shadow_scene_with(&room, &options).expect("the demo runs");
            if best
                .as_ref()
                .is_none_or(|b| result.stats.seconds.total < b.stats.seconds.total)
            {
                best = Some(result);
            }
        }
        let best = best.expect("ran");
        let s = &best.stats;
        println!(
            "{:<30} {:>6} {:>6} {:>8.4} {:>8.4} {:>10.4} {:>9.4} {:>8}",
            label,
            s.input_polygons,
            s.lights.len(),
            s.seconds.shadow,
            s.seconds.grid,
            s.seconds.illum,
            s.seconds.total,
            s.output_fragments
        );
        for (i, l) in s.lights.iter().enumerate() {
            println!(
                "    light {i}: penumbra nodes {}, umbra nodes {}, fragments lit/penumbra/umbra {}/{}/{}, vertices lit/penumbra/umbra {}/{}/{}",
                l.penumbra_nodes.unwrap_or(0),
                l.umbra_nodes.unwrap_or(0),
                l.lit,
                l.penumbra,
                l.umbra,
                l.lit_vertices.unwrap_or(0),
                l.penumbra_vertices.unwrap_or(0),
                l.umbra_vertices.unwrap_or(0)
            );
        }
    }
    let hall = rooms::box_hall(&dir, 1665, 7);
    let result = shadow_scene_with(&hall, &ShadowOptions::default()).expect("the hall runs");
    let s = &result.stats;
    println!(
        "{:<30} {:>6} {:>6} {:>8.4} {:>8.4} {:>10.4} {:>9.4} {:>8}",
        "umbra hall of boxes, no grid",
        s.input_polygons,
        s.lights.len(),
        s.seconds.shadow,
        s.seconds.grid,
        s.seconds.illum,
        s.seconds.total,
        s.output_fragments
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The 1989 paper's Table 1 beside umbra's SVBSP pass.
fn table_1() {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "Chin & Feiner 1989, Table 1 (paper: HP 9000/350; umbra: this machine, {cores} cores, one used)"
    );
    println!(
        "{:<24} {:>7} {:>7} {:>7} {:>7} {:>9} {:>11}",
        "scene", "input", "facing", "edges", "nodes", "fragments", "seconds"
    );
    for row in &TABLE_1 {
        println!(
            "{:<24} {:>7} {:>7} {:>7} {:>7} {:>9} {:>11.2}",
            format!("{} (paper)", row.name),
            row.input,
            row.front_facing,
            row.edges,
            row.nodes,
            row.fragments,
            row.seconds
        );
        for (label, offset) in [("ground in contact", 1.0), ("ground below", 1.0625)] {
            let mut triangles = tetra::tetra_triangles(row.depth);
            let closed = triangles.len();
            triangles.extend(tetra::ground(offset, 8.0));
            let (grid, pieces) = scene::pieces(&triangles, &[tetra::LIGHT]);
            let light = Light::point(grid.snap(tetra::LIGHT).expect("light inside the grid"));
            let flags = tetra::flags(closed, pieces.len());
            // The fastest of 20 runs, with its two phases.
            let mut best = (f64::INFINITY, 0.0, 0.0);
            let mut out = None;
            for _ in 0..20 {
                let start = Instant::now();
                let result = compute_shadows(&pieces, &flags, &[light], &BuildOptions::default())
                    .expect("valid scene");
                let seconds = start.elapsed().as_secs_f64();
                if seconds < best.0 {
                    best = (seconds, result.bsp_seconds, result.shadow_seconds);
                }
                out = Some(result);
            }
            let out = out.expect("ran at least once");
            let s = &out.lights[0];
            println!(
                "{:<24} {:>7} {:>7} {:>7} {:>7} {:>9} {:>11.6}  (scene BSP {:.6}, SVBSP {:.6}; {} shadow planes spared)",
                format!("  umbra, {label}"),
                pieces.len(),
                s.front_facing_polygons,
                s.front_facing_edges,
                s.tree_nodes,
                out.fragments.len(),
                best.0,
                best.1,
                best.2,
                s.planes_skipped
            );
        }
    }
}
