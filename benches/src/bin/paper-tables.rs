//! Prints umbra's figures beside the tables of the papers it implements.
//!
//! Chin & Feiner 1989, Table 1: Haines' SPD tetra scenes under one point
//! light, timed on an HP 9000/350.

use bsp_core::BuildOptions;
use std::time::Instant;
use svbsp::{Light, PieceFlags, compute_shadows};
use umbra_benches::{scene, tetra};

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
            triangles.extend(tetra::ground(offset, 8.0));
            let (grid, pieces) = scene::pieces(&triangles, &[tetra::LIGHT]);
            let light = Light::point(grid.snap(tetra::LIGHT).expect("light inside the grid"));
            let flags = vec![PieceFlags::default(); pieces.len()];
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
