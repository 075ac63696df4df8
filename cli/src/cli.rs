//! Command-line parsing (clap) and the commands of FORMATS.md §4.
//!
//! The only place besides `main.rs` that prints.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{ArgGroup, Args, Parser, Subcommand, ValueEnum};
use svbsp::SetOp;
use umbra::{
    Deletion, DemoFiles, DmOptions, DmRun, DmStats, Motion, ObjMesh, Outputs, OverlapKind, Pieces,
    PlyEncoding, Result, Scene, ShadowOptions, csg, dm_scene_moving, dm_scene_with,
    render_scene_with, save_csg_obj, scene_grid, shadow_scene, shadow_scene_with, stage_obj,
    stage_ply,
};

/// Exact object-space shadows: splits every receiving polygon into lit,
/// penumbra and umbra fragments along the exact shadow boundaries.
#[derive(Debug, Parser)]
#[command(name = "umbra", version, propagate_version = true)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The commands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Classify and illuminate every receiving polygon for point,
    /// directional and area lights; write PLY (and OBJ, stats).
    Shadow(ShadowArgs),
    /// Render an image from the scene's camera, shadows included.
    Render(RenderArgs),
    /// Build discontinuity meshes (DM-trees) of every receiver for the area
    /// lights, illuminated; point and directional lights' shadows cut the
    /// cells.
    Dm(DmArgs),
    /// Move an object step by step, updating the discontinuity meshes
    /// incrementally; reports update and rebuild times.
    Update(UpdateArgs),
    /// BSP set operations on closed OBJ meshes.
    Csg(CsgArgs),
    /// Write a built-in scene (scene file and meshes) into a folder.
    Demo(DemoArgs),
    /// Load and validate a scene, cut it into convex pieces on the grid and
    /// print a summary (nothing is written).
    Check(CheckArgs),
    /// Draw one input polygon's fragments in its own plane as SVG.
    Svg(SvgArgs),
}

/// Options of `umbra shadow`.
#[derive(Debug, Args)]
pub struct ShadowArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// Output PLY file [default: the scene's name with `.ply`].
    #[arg(short, long, value_name = "OUT.ply")]
    pub output: Option<PathBuf>,
    /// Also write the fragments as OBJ.
    #[arg(long, value_name = "OUT.obj")]
    pub obj: Option<PathBuf>,
    /// Write run statistics as JSON.
    #[arg(long, value_name = "S.json")]
    pub stats: Option<PathBuf>,
    /// Gridding: lit fragments are cut into square cells of the scene's
    /// largest extent / N (one lattice for all polygons), penumbra
    /// fragments into cells half that size; umbra stays whole.
    #[arg(long, value_name = "N")]
    pub grid: Option<u32>,
    /// Adaptive subdivision: lit and penumbra cells are halved across their
    /// longer side while the irradiance at their corners varies by more
    /// than TOL times the largest (e.g. 0.1).
    #[arg(long, value_name = "TOL", value_parser = positive_tolerance)]
    pub adaptive: Option<f64>,
    /// Write ASCII PLY instead of binary little-endian.
    #[arg(long)]
    pub ascii: bool,
}

/// A finite tolerance above zero.
fn positive_tolerance(text: &str) -> std::result::Result<f64, String> {
    match text.parse::<f64>() {
        Ok(t) if t.is_finite() && t > 0.0 => Ok(t),
        _ => Err(format!("expected a positive number, not `{text}`")),
    }
}

/// What `umbra render` shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum View {
    /// Illuminated surfaces.
    Shaded,
    /// Lit, penumbra and umbra in flat colours.
    Classes,
    /// The classes, with every fragment outlined.
    Fragments,
}

/// How `umbra render` finds shadows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Method {
    /// Draw umbra's object-space fragments.
    Fragments,
    /// Count Bergeron's shadow polygons along every eye ray (point and
    /// directional lights only; no fragments).
    Volumes,
}

/// How `umbra render` finds visible surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Order {
    /// A z-buffer.
    Zbuffer,
    /// Back-to-front traversal of the scene BSP from the eye (painter's
    /// algorithm, as the papers render).
    Bsp,
}

/// How `umbra update` takes a moved object's discontinuities out.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum)]
pub enum DeletionArg {
    /// Chrysanthou & Slater's local deletion, node by node.
    #[default]
    Local,
    /// Collapse the subtrees the object grew and re-merge the others there.
    Collapse,
}

/// Which structure pairs occluders with the receivers they may shadow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum)]
pub enum OverlapArg {
    /// A uniform grid of receiver boxes and penumbra boxes.
    #[default]
    Grid,
    /// The paper's shadow overlap cube (direction tiles around each light).
    Cube,
}

/// Options of `umbra render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// The scene file (TOML); it needs a `[camera]`.
    pub scene: PathBuf,
    /// Output PNG file.
    #[arg(short, long, value_name = "IMG.png")]
    pub output: PathBuf,
    /// What to show.
    #[arg(long, value_enum, default_value_t = View::Shaded)]
    pub view: View,
    /// How shadows are found.
    #[arg(long, value_enum, default_value_t = Method::Fragments)]
    pub method: Method,
    /// How visible surfaces are found.
    #[arg(long, value_enum, default_value_t = Order::Zbuffer)]
    pub order: Order,
}

/// Options of `umbra dm`.
#[derive(Debug, Args)]
pub struct DmArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// Output PLY file (same layout as `umbra shadow`; one face per cell).
    #[arg(short, long, value_name = "OUT.ply")]
    pub output: PathBuf,
    /// Also write the cells as OBJ (the PLY's vertices and faces; groups
    /// name each face's source, lit_mask and umbra_mask).
    #[arg(long, value_name = "OUT.obj")]
    pub obj: Option<PathBuf>,
    /// Write run statistics as JSON (FORMATS.md §3 fields, plus `dm`: tree
    /// nodes, cells, comparisons per vertex, build phases).
    #[arg(long, value_name = "S.json")]
    pub stats: Option<PathBuf>,
    /// Leave out the internal EV / VE discontinuities inside penumbrae
    /// (cells bounded by penumbra and umbra edges only: fewer cells,
    /// faster; vertex irradiance stays exact).
    #[arg(long)]
    pub outer_only: bool,
    /// Which structure pairs occluders with the receivers they may shadow.
    #[arg(long, value_enum, default_value_t = OverlapArg::Grid)]
    pub overlap: OverlapArg,
    /// Write ASCII PLY instead of binary little-endian.
    #[arg(long)]
    pub ascii: bool,
}

/// Options of `umbra update`.
#[derive(Debug, Args)]
pub struct UpdateArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// Name of the object to move.
    #[arg(long = "move", value_name = "NAME")]
    pub object: String,
    /// Displacement of each step. After step s the object is s times this
    /// away, rounded to whole grid steps (exact for decimals such as 0.1
    /// when the scene is written in decimals: its grid step is then a power
    /// of ten, or twice or five times one). The grid holds the object's
    /// whole way: a way out of the scene's box makes its step coarser (a
    /// warning says by how much).
    #[arg(long, value_name = "DX,DY,DZ", value_parser = parse_vector, allow_hyphen_values = true)]
    pub by: [f64; 3],
    /// Number of steps.
    #[arg(long, value_name = "K", default_value_t = 1)]
    pub steps: u32,
    /// Output PLY file (the final state).
    #[arg(short, long, value_name = "OUT.ply")]
    pub output: PathBuf,
    /// Also write the cells as OBJ (the PLY's vertices and faces; groups
    /// name each face's source, lit_mask and umbra_mask).
    #[arg(long, value_name = "OUT.obj")]
    pub obj: Option<PathBuf>,
    /// Write run statistics as JSON, with `update.update_seconds`,
    /// `update.rebuild_seconds` and `update.changed_receivers` (the
    /// polygons whose cells or values the step changed), one entry per
    /// step.
    #[arg(long, value_name = "S.json")]
    pub stats: Option<PathBuf>,
    /// Leave out the internal EV / VE discontinuities inside penumbrae
    /// (cells bounded by penumbra and umbra edges only: fewer cells,
    /// faster; vertex irradiance stays exact).
    #[arg(long)]
    pub outer_only: bool,
    /// How each step takes the object's discontinuities out of the trees.
    #[arg(long, value_enum, default_value_t = DeletionArg::Local)]
    pub deletion: DeletionArg,
    /// Which structure pairs occluders with the receivers they may shadow.
    #[arg(long, value_enum, default_value_t = OverlapArg::Grid)]
    pub overlap: OverlapArg,
    /// Write ASCII PLY instead of binary little-endian.
    #[arg(long)]
    pub ascii: bool,
}

/// Options of `umbra csg`.
#[derive(Debug, Args)]
#[command(group(ArgGroup::new("operation").required(true).args(["union", "intersect", "subtract"])))]
pub struct CsgArgs {
    /// First closed mesh (OBJ; one without faces is the empty solid).
    pub a: PathBuf,
    /// A union B.
    #[arg(long)]
    pub union: bool,
    /// A intersect B.
    #[arg(long)]
    pub intersect: bool,
    /// A minus B.
    #[arg(long)]
    pub subtract: bool,
    /// Second closed mesh (OBJ; one without faces is the empty solid).
    pub b: PathBuf,
    /// Output OBJ file.
    #[arg(short, long, value_name = "OUT.obj")]
    pub output: PathBuf,
}

/// Options of `umbra demo`.
#[derive(Debug, Args)]
pub struct DemoArgs {
    /// The scene: `room`, `room1`, `tetra`, `window`, `office`, `cubes` or `meshes`.
    #[arg(default_value = "room")]
    pub name: String,
    /// Folder to write into [default: a folder named after the scene].
    #[arg(short, long, value_name = "DIR")]
    pub output: Option<PathBuf>,
}

/// Options of `umbra check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
}

/// Options of `umbra svg`.
#[derive(Debug, Args)]
pub struct SvgArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// The input polygon to draw (0-based, FORMATS.md numbering).
    #[arg(long, value_name = "N")]
    pub polygon: u32,
    /// Output SVG file.
    #[arg(short, long, value_name = "OUT.svg")]
    pub output: PathBuf,
}

fn parse_vector(text: &str) -> std::result::Result<[f64; 3], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!("expected DX,DY,DZ, got `{text}`"));
    }
    let mut v = [0.0; 3];
    for (slot, part) in v.iter_mut().zip(&parts) {
        let x: f64 = part
            .parse()
            .map_err(|_| format!("`{part}` is not a number"))?;
        if !x.is_finite() {
            return Err(format!("`{part}` is not finite"));
        }
        *slot = x;
    }
    Ok(v)
}

/// A spinner with the current phase on a terminal (stderr); nothing when
/// stderr is not a terminal, so scripts and logs stay quiet.
struct Progress(Option<indicatif::ProgressBar>);

impl Progress {
    fn start(phase: &str) -> Self {
        use std::io::IsTerminal;
        if !std::io::stderr().is_terminal() {
            return Self(None);
        }
        let bar = indicatif::ProgressBar::new_spinner();
        bar.enable_steady_tick(std::time::Duration::from_millis(120));
        bar.set_message(phase.to_string());
        Self(Some(bar))
    }

    fn say(&self, phase: &str) {
        if let Some(bar) = &self.0 {
            bar.set_message(phase.to_string());
        }
    }

    fn finish(&self) {
        if let Some(bar) = &self.0 {
            bar.finish_and_clear();
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        // An error leaves no spinner behind its message.
        self.finish();
    }
}

/// `umbra shadow`: every output is written to a temporary file and renamed,
/// and nothing is written unless the whole computation succeeded.
fn run_shadow(args: &ShadowArgs) -> Result<()> {
    let progress = Progress::start("loading the scene");
    let scene = Scene::load(&args.scene)?;
    progress.say("computing shadows");
    let options = ShadowOptions {
        grid: args.grid,
        adaptive: args.adaptive,
    };
    let result = shadow_scene_with(&scene, &options)?;
    progress.say("writing");
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| args.scene.with_extension("ply"));
    let encoding = if args.ascii {
        PlyEncoding::Ascii
    } else {
        PlyEncoding::BinaryLittleEndian
    };
    let mut outputs = Outputs::default();
    stage_ply(&mut outputs, &output, &result.mesh, encoding)?;
    if let Some(obj) = &args.obj {
        stage_obj(&mut outputs, obj, &result.mesh)?;
    }
    if let Some(stats) = &args.stats {
        result.stats.stage(&mut outputs, stats)?;
    }
    outputs.commit()?;
    progress.finish();
    warn_dropped(&scene, &result.stats.dropped_polygons);
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "{}: {} input polygons, {} fragments, {:.3} s",
        output.display(),
        result.stats.input_polygons,
        result.stats.output_fragments,
        result.stats.seconds.total
    );
    Ok(())
}

/// `umbra render`: the image is written atomically, and only once the whole
/// rendering succeeded.
fn run_render(args: &RenderArgs) -> Result<()> {
    let started = std::time::Instant::now();
    let progress = Progress::start("loading the scene");
    let scene = Scene::load(&args.scene)?;
    progress.say("rendering");
    let view = match args.view {
        View::Shaded => umbra::View::Shaded,
        View::Classes => umbra::View::Classes,
        View::Fragments => umbra::View::Fragments,
    };
    let method = match args.method {
        Method::Fragments => umbra::Method::Fragments,
        Method::Volumes => umbra::Method::Volumes,
    };
    let order = match args.order {
        Order::Zbuffer => umbra::Order::ZBuffer,
        Order::Bsp => umbra::Order::Bsp,
    };
    let image = render_scene_with(
        &scene,
        &umbra::RenderOptions {
            view,
            method,
            order,
        },
    )?;
    progress.say("writing");
    image.save_png(&args.output)?;
    progress.finish();
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "{}: {} x {} pixels, {:.3} s",
        args.output.display(),
        image.width,
        image.height,
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

fn encoding(ascii: bool) -> PlyEncoding {
    if ascii {
        PlyEncoding::Ascii
    } else {
        PlyEncoding::BinaryLittleEndian
    }
}

fn dm_options(outer_only: bool, deletion: DeletionArg, overlap: OverlapArg) -> DmOptions {
    DmOptions {
        internal_discontinuities: !outer_only,
        deletion: match deletion {
            DeletionArg::Local => Deletion::Local,
            DeletionArg::Collapse => Deletion::Collapse,
        },
        overlap: match overlap {
            OverlapArg::Grid => OverlapKind::Grid,
            OverlapArg::Cube => OverlapKind::Cube,
        },
        ..DmOptions::default()
    }
}

/// Where `umbra dm` and `umbra update` write.
struct DmFiles<'a> {
    ply: &'a Path,
    ascii: bool,
    obj: Option<&'a Path>,
    stats: Option<&'a Path>,
}

/// Writes a DM run's PLY and, if asked, its OBJ and its statistics,
/// together; returns the statistics written.
fn save_dm(run: &DmRun, files: &DmFiles<'_>) -> Result<DmStats> {
    let mut outputs = Outputs::default();
    let (mesh, figures) = run.output()?;
    stage_ply(&mut outputs, files.ply, &mesh, encoding(files.ascii))?;
    if let Some(obj) = files.obj {
        stage_obj(&mut outputs, obj, &mesh)?;
    }
    if let Some(stats) = files.stats {
        figures.stage(&mut outputs, stats)?;
    }
    outputs.commit()?;
    Ok(figures)
}

/// `umbra dm`: outputs are written only once everything succeeded.
fn run_dm(args: &DmArgs) -> Result<()> {
    let progress = Progress::start("loading the scene");
    let scene = Scene::load(&args.scene)?;
    progress.say("building discontinuity meshes");
    let options = dm_options(args.outer_only, DeletionArg::Local, args.overlap);
    let run = dm_scene_with(&scene, options)?;
    progress.say("writing");
    let s = save_dm(
        &run,
        &DmFiles {
            ply: &args.output,
            ascii: args.ascii,
            obj: args.obj.as_deref(),
            stats: args.stats.as_deref(),
        },
    )?;
    progress.finish();
    warn_dropped(&scene, &s.stats.dropped_polygons);
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "{}: {} input polygons, {} cells, {} tree nodes, {:.2} comparisons per vertex, {:.3} s",
        args.output.display(),
        s.stats.input_polygons,
        s.dm.cells,
        s.dm.tree_nodes,
        s.dm.comparisons_per_vertex,
        s.stats.seconds.total
    );
    Ok(())
}

/// `umbra update`: moves the object step by step; writes the final state.
fn run_update(args: &UpdateArgs) -> Result<()> {
    let progress = Progress::start("loading the scene");
    let scene = Scene::load(&args.scene)?;
    progress.say("building discontinuity meshes");
    let options = dm_options(args.outer_only, args.deletion, args.overlap);
    let mut run = dm_scene_moving(&scene, options, &args.object, args.by, args.steps)?;
    progress.say("moving");
    let mut lines = Vec::new();
    let figures = run.move_steps(
        &scene,
        &args.object,
        args.by,
        args.steps,
        |k, update, rebuild| {
            lines.push(format!(
                "step {k}: update {:.3} ms, rebuild {:.3} ms ({:.1} %)",
                update * 1e3,
                rebuild * 1e3,
                100.0 * update / rebuild.max(1e-12)
            ));
        },
    )?;
    run.refresh_figures();
    run.stats.update = Some(figures);
    progress.say("writing");
    let s = save_dm(
        &run,
        &DmFiles {
            ply: &args.output,
            ascii: args.ascii,
            obj: args.obj.as_deref(),
            stats: args.stats.as_deref(),
        },
    )?;
    progress.finish();
    warn_dropped(&scene, &s.stats.dropped_polygons);
    warn_coarser(&scene, args, run.pieces.grid.cell_size());
    let mut out = std::io::stdout().lock();
    for line in lines {
        let _ = writeln!(out, "{line}");
    }
    let _ = writeln!(
        out,
        "{}: `{}` moved {} times, {} cells",
        args.output.display(),
        args.object,
        args.steps,
        run.stats.dm.cells
    );
    Ok(())
}

/// Says on stderr when the moved object's way took the grid past the
/// scene's own box, so that its step (`cell`, world units) grew: every
/// vertex of the output then snapped to the coarser grid.
fn warn_coarser(scene: &Scene, args: &UpdateArgs, cell: f64) {
    let Some(object) = scene.objects.iter().position(|o| o.name == args.object) else {
        return;
    };
    let still = Motion {
        object,
        by: args.by,
        steps: 0,
    };
    let Ok(own) = scene_grid(scene, Some(still)) else {
        return;
    };
    if cell > own.cell_size() {
        eprintln!(
            "umbra: warning: `{}`'s way ({} steps of {:?}) leaves the scene's box: the grid grew \
             to hold it, its step from {} to {}",
            args.object,
            args.steps,
            args.by,
            own.cell_size(),
            cell
        );
    }
}

/// Where input polygon `input` was written: its mesh file and line, or its
/// object's name for inline polygons.
fn polygon_place(scene: &Scene, input: u32) -> String {
    match scene.input_polygons().nth(input as usize) {
        Some((object, polygon)) => {
            let object = &scene.objects[object];
            match (&object.mesh, polygon.line) {
                (Some(mesh), Some(line)) => format!("{}:{line}", mesh.display()),
                _ => format!("object `{}`", object.name),
            }
        }
        None => "not in the scene".into(),
    }
}

/// The most dropped polygons a warning names one by one.
const NAMED_DROPS: usize = 5;

/// Says on stderr that the output leaves out the `dropped` input polygons
/// (no area once snapped: the output partitions every other polygon, not
/// these), naming the first few; `umbra check` lists them all.
fn warn_dropped(scene: &Scene, dropped: &[u32]) {
    if dropped.is_empty() {
        return;
    }
    let named: Vec<String> = dropped
        .iter()
        .take(NAMED_DROPS)
        .map(|&input| format!("{input} ({})", polygon_place(scene, input)))
        .collect();
    let more = match dropped.len().saturating_sub(NAMED_DROPS) {
        0 => String::new(),
        n => format!(" and {n} more"),
    };
    eprintln!(
        "umbra: warning: {} input polygon{} left out, with no area once snapped to the scene's grid \
         (degenerate, or smaller than a grid step; `umbra check` shows the step): {}{more}",
        dropped.len(),
        if dropped.len() == 1 { "" } else { "s" },
        named.join(", ")
    );
}

/// Runs one command.
pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Shadow(args) => run_shadow(&args),
        Command::Render(args) => run_render(&args),
        Command::Dm(args) => run_dm(&args),
        Command::Update(args) => run_update(&args),
        Command::Csg(args) => {
            let a = ObjMesh::load(&args.a)?;
            let b = ObjMesh::load(&args.b)?;
            for (mesh, path) in [(&a, &args.a), (&b, &args.b)] {
                // (An empty result written before, or maybe the wrong file.)
                if mesh.faces.is_empty() {
                    eprintln!(
                        "umbra: warning: {} has no faces: read as the empty solid",
                        path.display()
                    );
                }
            }
            let op = if args.union {
                SetOp::Union
            } else if args.intersect {
                SetOp::Intersection
            } else {
                SetOp::Difference
            };
            let mesh = csg(&a, &args.a, &b, &args.b, op)?;
            save_csg_obj(&args.output, &mesh)?;
            let mut out = std::io::stdout().lock();
            let _ = writeln!(
                out,
                "{}: {} vertices, {} faces",
                args.output.display(),
                mesh.vertices.len(),
                mesh.faces.len()
            );
            Ok(())
        }
        Command::Demo(args) => {
            let dir = args.output.unwrap_or_else(|| PathBuf::from(&args.name));
            let files = DemoFiles::named(&args.name)?;
            let path = files.write(&dir)?;
            let mut out = std::io::stdout().lock();
            let _ = writeln!(out, "wrote the `{}` scene: {}", args.name, path.display());
            drop(out);
            if files.runs_dm() {
                return run_dm(&DmArgs {
                    scene: path.clone(),
                    output: path.with_extension("ply"),
                    obj: None,
                    stats: Some(path.with_extension("json")),
                    ascii: false,
                    outer_only: false,
                    overlap: OverlapArg::Grid,
                });
            }
            // ... and run it, as `umbra shadow` would.
            run_shadow(&ShadowArgs {
                scene: path.clone(),
                output: Some(path.with_extension("ply")),
                obj: None,
                stats: Some(path.with_extension("json")),
                grid: files.grid,
                adaptive: None,
                ascii: false,
            })
        }
        Command::Svg(args) => {
            let scene = Scene::load(&args.scene)?;
            let result = shadow_scene(&scene)?;
            let svg = umbra::fragments_svg(&scene, &result.mesh, args.polygon)?;
            umbra::save_svg(&args.output, &svg)?;
            let mut out = std::io::stdout().lock();
            let _ = writeln!(out, "{}", args.output.display());
            Ok(())
        }
        Command::Check(args) => {
            let scene = Scene::load(&args.scene)?;
            let pieces = Pieces::from_scene(&scene)?;
            let mut out = std::io::stdout().lock();
            let _ = writeln!(out, "scene          {}", scene.path.display());
            let _ = writeln!(out, "objects        {}", scene.objects.len());
            let _ = writeln!(out, "lights         {}", scene.lights.len());
            let _ = writeln!(out, "input polygons {}", pieces.input_polygons);
            let _ = writeln!(out, "convex pieces  {}", pieces.polygons.len());
            let _ = writeln!(
                out,
                "dropped        {} (zero area once snapped)",
                pieces.dropped.len()
            );
            for &input in &pieces.dropped {
                let at = polygon_place(&scene, input);
                let _ = writeln!(out, "  dropped input polygon {input} ({at})");
            }
            let _ = writeln!(out, "grid cell      {:e}", pieces.grid.cell_size());
            let _ = writeln!(out, "largest snap   {:e}", pieces.max_snap_distance);
            Ok(())
        }
    }
}
