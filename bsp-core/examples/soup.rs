//! A random polygon soup cut by random planes, with statistics.
//!
//! ```text
//! cargo run --release -p bsp-core --example soup -- [--n 2000] [--planes 200] [--seed 1] [--check]
//! ```
//!
//! It builds `n` small random triangles in the unit cube (seeded, so every
//! run with the same arguments does the same work), snaps them to the grid,
//! then cuts every fragment by each of `planes` random planes through grid
//! points of the cube, in turn. It prints the input and output counts, how
//! many side queries the floating-point filter could not decide (exact
//! fallbacks), how well the fragments' areas add up to their triangles'
//! areas, and the time taken. `--check` also runs `check_invariants()` on
//! every fragment.

use bsp_core::predicates::exact_fallbacks;
use bsp_core::{ConvexPolygon, Grid, Plane, Split};
use rand::{Rng, SeedableRng};
use std::time::Instant;

/// Command-line options.
struct Options {
    /// Number of triangles.
    n: usize,
    /// Number of cutting planes.
    planes: usize,
    /// Seed of the generator.
    seed: u64,
    /// Check every fragment's invariants.
    check: bool,
}

fn parse_options() -> Result<Options, String> {
    let mut options = Options {
        n: 2000,
        planes: 200,
        seed: 1,
        check: false,
    };
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = |name: &str| {
            args.next()
                .ok_or_else(|| format!("{name} needs a value"))?
                .parse::<u64>()
                .map_err(|e| format!("{name}: {e}"))
        };
        match arg.as_str() {
            "--n" => options.n = value("--n")? as usize,
            "--planes" => options.planes = value("--planes")? as usize,
            "--seed" => options.seed = value("--seed")?,
            "--check" => options.check = true,
            "-h" | "--help" => {
                println!("usage: soup [--n TRIANGLES] [--planes PLANES] [--seed SEED] [--check]");
                std::process::exit(0);
            }
            other => return Err(format!("unknown argument {other:?} (try --help)")),
        }
    }
    Ok(options)
}

fn main() {
    let options = match parse_options() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("soup: {e}");
            std::process::exit(2);
        }
    };
    let mut rng = rand_pcg::Pcg64::seed_from_u64(options.seed);

    // Triangles about 0.05 across, centred anywhere in the unit cube.
    let grid = Grid::new([-0.1; 3], [1.1; 3]).expect("a valid box");
    let started = Instant::now();
    let mut soup: Vec<ConvexPolygon> = Vec::with_capacity(options.n);
    let mut rejected = 0_usize;
    while soup.len() < options.n {
        let centre: [f64; 3] = std::array::from_fn(|_| rng.random_range(0.0..1.0));
        let corners: Vec<_> = (0..3)
            .map(|_| {
                let p: [f64; 3] =
                    std::array::from_fn(|k| centre[k] + rng.random_range(-0.025..0.025));
                grid.snap(p).expect("inside the box")
            })
            .collect();
        match ConvexPolygon::from_grid_points(&corners, soup.len() as u32) {
            Ok(t) => soup.push(t),
            Err(_) => rejected += 1,
        }
    }
    let input_areas: Vec<f64> = soup.iter().map(ConvexPolygon::area).collect();
    let planes: Vec<Plane> = std::iter::repeat_with(|| {
        let mut point = || {
            let p: [f64; 3] = std::array::from_fn(|_| rng.random_range(0.0..1.0));
            grid.snap(p).expect("inside the box")
        };
        Plane::through(point(), point(), point())
    })
    .flatten()
    .take(options.planes)
    .collect();
    let setup = started.elapsed();

    // Cut everything by every plane.
    let fallbacks_before = exact_fallbacks();
    let (mut splits, mut cuts, mut vertex_queries, mut implicit_queries) =
        (0_u64, 0_u64, 0_u64, 0_u64);
    let started = Instant::now();
    let mut fragments = soup;
    let mut next = Vec::with_capacity(fragments.len());
    for plane in &planes {
        for fragment in fragments.drain(..) {
            splits += 1;
            vertex_queries += fragment.len() as u64;
            implicit_queries += (0..fragment.len())
                .filter(|&i| fragment.vertex_grid_point(i).is_none())
                .count() as u64;
            match fragment.split(plane) {
                Split::Both(back, front) => {
                    cuts += 1;
                    next.push(back);
                    next.push(front);
                }
                Split::Back | Split::Front | Split::Coplanar(_) => next.push(fragment),
            }
        }
        std::mem::swap(&mut fragments, &mut next);
    }
    let cutting = started.elapsed();
    let fallbacks = exact_fallbacks() - fallbacks_before;

    // Area conservation per input triangle.
    let mut areas = vec![0.0_f64; input_areas.len()];
    for f in &fragments {
        areas[f.source() as usize] += f.area();
    }
    let worst = areas
        .iter()
        .zip(&input_areas)
        .map(|(sum, whole)| (sum - whole).abs() / whole)
        .fold(0.0_f64, f64::max);
    let total_in: f64 = input_areas.iter().sum();
    let total_out: f64 = areas.iter().sum();

    let mut checked = "not run (use --check)".to_string();
    if options.check {
        let bad = fragments
            .iter()
            .filter(|f| f.check_invariants().is_err())
            .count();
        checked = format!("{bad} of {} fragments fail", fragments.len());
    }

    let seconds = cutting.as_secs_f64();
    println!("umbra soup (seed {})", options.seed);
    println!(
        "input polygons           {} triangles ({rejected} degenerate redrawn)",
        options.n
    );
    println!("cutting planes           {}", planes.len());
    println!("output fragments         {}", fragments.len());
    println!("splits                   {splits} ({cuts} made two parts)");
    println!("vertex side queries      {vertex_queries} ({implicit_queries} of implicit vertices)");
    println!(
        "exact fallbacks          {fallbacks} ({:.2e} of vertex side queries)",
        fallbacks as f64 / vertex_queries.max(1) as f64
    );
    println!("area error, worst input  {worst:.2e} (relative)");
    println!(
        "area error, total        {:.2e} (relative)",
        (total_out - total_in).abs() / total_in
    );
    println!("invariants               {checked}");
    println!(
        "time                     {:.3} s setup, {seconds:.3} s cutting ({:.2} M splits/s)",
        setup.as_secs_f64(),
        splits as f64 / seconds / 1e6
    );
}
