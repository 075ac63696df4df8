//! Runs a fixed amount of discontinuity-mesh work, so that an instruction
//! counter (`valgrind --tool=callgrind`) can weigh a move against a
//! rebuild on a machine whose clock is shared.
//!
//! `dm-cost SCENE OBJECT MOVES REBUILDS [DELETES]`: builds and illuminates SCENE
//! once, moves OBJECT back and forth by 0.05 along x MOVES times
//! (re-illuminating after each), removes OBJECT from DELETES copies of the
//! result, then rebuilds the scene REBUILDS times.
//! The cost of one move is the difference of two runs' counts divided by
//! the difference of their MOVES; likewise for rebuilds.
//!
//! `DM_COST_DELETION=collapse` removes by collapsing and re-merging
//! ([`Deletion::Collapse`]) instead of the paper's local deletion;
//! `DM_COST_OUTER=1` leaves the internal discontinuities out (as
//! `paper-tables dm` builds the hall); `DM_COST_OVERLAP=cube` pairs
//! occluders and receivers through the shadow overlap cube instead of the
//! grid; `DM_COST_FACES=1` has each polygon of a convex body cast its
//! own unit (the body only its umbra); `DM_COST_MOVABLE=1` declares OBJECT
//! movable at the build (`DmScene::build_movable`).
//!
//! To profile one move (move M, 0 by default: `DM_COST_PERF_MOVE=M`):
//! `mkfifo ctl ack; perf record -D -1 --control fifo:ctl,ack -- env
//! DM_COST_PERF_CTL=ctl,ack dm-cost ...` samples that move alone.

use std::process::ExitCode;

use bsp_core::ConvexPolygon;
use umbra::{Deletion, DmOptions, OverlapKind, Scene, dm_scene_moving, dm_scene_with};

/// The allocator of the `umbra` binary, so the figures are the command's.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [scene, object, moves, rebuilds, ..] = args.as_slice() else {
        eprintln!("usage: dm-cost SCENE OBJECT MOVES REBUILDS");
        return ExitCode::FAILURE;
    };
    let (Ok(moves), Ok(rebuilds)) = (moves.parse::<u32>(), rebuilds.parse::<u32>()) else {
        eprintln!("dm-cost: MOVES and REBUILDS are whole numbers");
        return ExitCode::FAILURE;
    };
    let scene = match Scene::load(std::path::Path::new(scene)) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("dm-cost: {e}");
            return ExitCode::FAILURE;
        }
    };
    let Some(index) = scene.objects.iter().position(|o| &o.name == object) else {
        eprintln!("dm-cost: no object `{object}`");
        return ExitCode::FAILURE;
    };
    let deletion = match std::env::var("DM_COST_DELETION").as_deref() {
        Ok("collapse") => Deletion::Collapse,
        _ => Deletion::Local,
    };
    let options = DmOptions {
        deletion,
        internal_discontinuities: std::env::var_os("DM_COST_OUTER").is_none(),
        overlap: match std::env::var("DM_COST_OVERLAP").as_deref() {
            Ok("cube") => OverlapKind::Cube,
            _ => OverlapKind::Grid,
        },
        convex_bodies: std::env::var_os("DM_COST_FACES").is_none(),
    };
    // DM_COST_MOVABLE=1: OBJECT declared movable at the build (as `umbra
    // update` does), so its first move costs what the later ones do.
    let build = || match std::env::var_os("DM_COST_MOVABLE") {
        Some(_) => dm_scene_moving(&scene, options, object, [0.05, 0.0, 0.0], 1),
        None => dm_scene_with(&scene, options),
    };
    let mut run = build().expect("the scene builds");
    if let Some(kb) = resident_kb() {
        eprintln!("resident after the build: {} MB", kb / 1024);
    }
    let (id, ks) = run.objects[index].clone();
    let step = (0.05 * run.pieces.grid.scale()).round() as i64;
    let here: Vec<ConvexPolygon> = ks.iter().map(|&k| run.pieces.polygons[k].clone()).collect();
    let there: Vec<ConvexPolygon> = here
        .iter()
        .map(|p| p.translated([step, 0, 0]).expect("on the grid"))
        .collect();
    let cells =
        |dm: &umbra::DmRun| -> usize { dm.dm.receivers().map(|(_, r)| r.cell_count()).sum() };
    let cells_before = cells(&run);
    // What bounds a move's share of a rebuild: the cells the object's
    // pieces hold, and the cells of other receivers that list it (inside
    // its penumbrae), all of which a move remakes.
    let (mut own, mut listing) = (0, 0);
    for (piece, dm) in run.dm.receivers() {
        if run.dm.piece_object(piece) == Some(id) {
            own += dm.cell_count();
            continue;
        }
        listing += dm
            .cells()
            .filter(|(_, c)| {
                c.entries().iter().any(|e| {
                    dm.unit_source(e.unit)
                        .is_some_and(|(o, _)| run.dm.piece_object(o) == Some(id))
                })
            })
            .count();
    }
    eprintln!(
        "footprint: {} pieces of {}; its pieces hold {own} of {cells_before} cells ({:.1} %), {listing} other cells list it ({:.1} %)",
        ks.len(),
        run.pieces.polygons.len(),
        100.0 * own as f64 / cells_before as f64,
        100.0 * listing as f64 / cells_before as f64
    );
    // The move a profiler sees (DM_COST_PERF_MOVE, the first by default).
    let profiled: u32 = std::env::var("DM_COST_PERF_MOVE")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(0);
    let mut evaluated = 0;
    for m in 0..moves {
        let to = if m % 2 == 0 { &there } else { &here };
        let since = run.dm.revision();
        let started = std::time::Instant::now();
        profile_move(m == profiled, "enable");
        run.dm.move_object(id, to.clone()).expect("moves");
        let moved = started.elapsed().as_secs_f64();
        let stats = run.dm.illuminate();
        profile_move(m == profiled, "disable");
        let elapsed = started.elapsed().as_secs_f64();
        // What an application reads again: the receivers listed changed.
        let listing = std::time::Instant::now();
        let changed = run.dm.receivers_changed_since(since).count();
        eprintln!(
            "move {m}: {:.2} ms ({:.2} ms before illumination), {} vertices looked at, {} re-evaluated; {changed} receivers changed (listed in {:.1} us)",
            1e3 * elapsed,
            1e3 * moved,
            stats.vertices,
            stats.evaluated,
            1e6 * listing.elapsed().as_secs_f64()
        );
        evaluated += stats.evaluated;
        if std::env::var_os("DM_COST_VERBOSE").is_some() {
            for &piece in run.dm.object_pieces(id).unwrap_or_default() {
                if let Some(dm) = run.dm.receiver(piece) {
                    eprintln!("  its piece: {} cells", dm.cell_count());
                }
            }
        }
    }
    eprintln!(
        "cells: {cells_before} after the build, {} after the moves; {} vertices after the build",
        cells(&run),
        run.stats.dm.vertices
    );
    // DELETES (optional): removals of OBJECT from copies of the state.
    let deletes: u32 = args.get(4).and_then(|d| d.parse().ok()).unwrap_or(0);
    // (With DM_COST_CLONE_ONLY set the copies are made but nothing is
    // removed: the difference is the removals alone.)
    let clone_only = std::env::var_os("DM_COST_CLONE_ONLY").is_some();
    for _ in 0..deletes {
        let mut copy = run.dm.clone();
        if !clone_only {
            copy.remove_object(id).expect("removable");
        }
        std::hint::black_box(copy);
    }
    for _ in 0..rebuilds {
        std::hint::black_box(build().expect("builds"));
    }
    println!("{moves} moves ({evaluated} vertices re-evaluated), {rebuilds} rebuilds");
    ExitCode::SUCCESS
}

/// With `DM_COST_PERF_CTL=CTL,ACK` set (two FIFOs), tells `perf record
/// --control fifo:CTL,ACK -D -1` to sample (`enable`) or stop
/// (`disable`) around one move alone (the first one's cost, for instance,
/// a count over many moves hides). It waits for perf's acknowledgement,
/// so the window holds that move and nothing else.
fn profile_move(chosen: bool, command: &str) {
    use std::io::{Read, Write};
    let Some(fifos) = std::env::var("DM_COST_PERF_CTL").ok().filter(|_| chosen) else {
        return;
    };
    let Some((ctl, ack)) = fifos.split_once(',') else {
        return;
    };
    if let Ok(mut f) = std::fs::OpenOptions::new().write(true).open(ctl) {
        let _ = writeln!(f, "{command}");
    }
    if let Ok(mut f) = std::fs::File::open(ack) {
        let mut reply = [0u8; 5];
        let _ = f.read(&mut reply);
    }
}

/// The process's resident memory in KB (Linux's `/proc/self/status`;
/// `None` elsewhere): what the built scene keeps, beside the peak a
/// `time -v` reports, which the build's passing tile meshes set.
fn resident_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}
