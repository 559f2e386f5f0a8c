//! `meshrefine` binary: parses the command line, runs the command, turns every failure into one
//! clear sentence and a non-zero exit status.
//!
//! Standard output is written only through [`out!`], which returns write errors: a closed pipe
//! (`meshrefine info x.obj | head -2`) ends the program quietly with status 0, as Unix filters
//! do; any other write error (`>/dev/full`) is an `error:` line and status 1. Warnings and
//! errors go to standard error, where a failed write is ignored (there is nowhere else to say
//! it).
#![forbid(unsafe_code)]

mod cli;
mod loop_check;
mod options;

use anyhow::{bail, Context as _, Result};
use cli::{Cli, Command, Technique};
use meshrefine::gpu::{Context, ContextDesc, Messages, ShutdownError};
use meshrefine::mesh::{LoadReport, Mesh, MeshError};
use meshrefine::render::{covered_pixels, Camera, Capture, DrawConfig, Driver, Headless};
use meshrefine::surface::loop_::LoopData;
use meshrefine::surface::Surface;
use std::io::Write as _;
use std::path::Path;
use std::process::ExitCode;
use std::sync::Arc;

/// A failed write to standard output.
#[derive(Debug)]
struct StdoutError(std::io::Error);

impl std::fmt::Display for StdoutError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "cannot write to standard output: {}", self.0)
    }
}

impl std::error::Error for StdoutError {}

/// `println!` that returns a [`StdoutError`] from the enclosing function instead of panicking.
macro_rules! out {
    ($($arg:tt)*) => {
        writeln!(std::io::stdout().lock(), $($arg)*).map_err(StdoutError)?
    };
}

/// A line on standard error (warnings, validation messages); a failed write is ignored.
fn note(line: std::fmt::Arguments) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

fn main() -> ExitCode {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn"))
        .format_timestamp(None)
        .init();
    let (cli, given) = match options::parse() {
        Ok(parsed) => parsed,
        // --help, --version (to stdout) or a usage error (to stderr, status 2).
        Err(e) => {
            return match e.print() {
                Err(w) if w.kind() != std::io::ErrorKind::BrokenPipe => {
                    note(format_args!("error: {}", StdoutError(w)));
                    ExitCode::FAILURE
                }
                _ => ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(1)),
            };
        }
    };
    for w in options::warnings(&cli, &given) {
        note(format_args!("warning: {w}"));
    }
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let closed_pipe = e.chain().any(|c| {
                c.downcast_ref::<StdoutError>()
                    .is_some_and(|s| s.0.kind() == std::io::ErrorKind::BrokenPipe)
            });
            if closed_pipe {
                // The reader has gone (`| head`): nobody wants the rest. Quietly done.
                return ExitCode::SUCCESS;
            }
            note(format_args!("error: {e:#}"));
            ExitCode::FAILURE
        }
    }
}

fn context_desc(cli: &Cli) -> ContextDesc {
    let env = std::env::var("MESHREFINE_VALIDATE").is_ok_and(|v| !v.is_empty() && v != "0");
    ContextDesc {
        validate: cli.validate || env,
        device_name: cli.device.clone(),
        surface_extensions: vec![],
    }
}

/// A loaded mesh and what messages call it.
struct Input {
    mesh: Mesh,
    /// The path as given, or "the default mesh (spot)".
    shown: String,
    /// `--heightmap`, loaded (None: the scene's generated map).
    heightmap: Option<meshrefine::surface::Heightmap>,
    /// `--tags`, parsed and checked (None: the scene's tags derived from hard edges).
    tags: Option<Vec<meshrefine::surface::stpn::VertexTag>>,
    /// Why `--surface loop` must refuse the mesh though it loaded ([`loop_refusal`]).
    loop_refusal: Option<String>,
    /// What loading did (the faces' lines and the file's vertex numbers, for messages).
    report: LoadReport,
}

/// Loads what `--heightmap` and `--tags` name for `input`'s mesh; with `--surface stpn` and no
/// tags file, says where derived tags cannot keep a crease.
/// `any` for the window, whose panel can switch to the surface or displacement they apply to.
fn attach_surface_inputs(input: &mut Input, s: &cli::SurfaceOpts, any: bool) -> Result<()> {
    input.heightmap = s.heightmap(any).map_err(anyhow::Error::msg)?;
    let lines = &input.report.triangle_lines;
    input.tags = (s.tags(&input.mesh, &input.shown, lines, any)).map_err(anyhow::Error::msg)?;
    if s.surface == meshrefine::surface::Surface::Stpn && s.tags.is_none() {
        split_three_creases(input, s.crease_angle)?;
        let (_, corners) =
            meshrefine::surface::stpn::derive_with_angle(&input.mesh, s.crease_angle);
        if corners > 0 {
            note(format_args!(
                "warning: '{}': {corners} vertices where three or more hard edges meet stay smooth under stpn (scalar-tagged PN triangles allow one crease per vertex; give tags with --tags)",
                input.shown
            ));
        }
    }
    Ok(())
}

/// Scalar-tagged PN allows two crease corners per triangle: a triangle whose three corners
/// carry derived creases (from split normals or `--crease-angle`) is split at its centroid
/// (`Mesh::split_at_centroids`: the new vertex is smooth, the old edges stay, so the surface
/// stays watertight), with one warning; `input` then carries the tags.
fn split_three_creases(input: &mut Input, crease_angle: Option<f32>) -> Result<()> {
    use meshrefine::surface::stpn;
    let mut tags = match input.tags.take() {
        Some(t) => t,
        None => stpn::derive(&input.mesh).0,
    };
    let which: Vec<usize> = (input.mesh.triangles.iter().enumerate())
        .filter(|(_, t)| t.p.iter().all(|&p| tags[p as usize].crease()))
        .map(|(i, _)| i)
        .collect();
    let source = match crease_angle {
        Some(a) => format!("--crease-angle {a}"),
        None => "the mesh's split normals".to_string(),
    };
    if let Some(&first) = which.first() {
        let face = input.report.face(first);
        let origin = input.mesh.split_at_centroids(&which).map_err(|e| {
            anyhow::anyhow!(
                "'{}': {face} {} (the creases come from {source}), and it cannot be split: {e}",
                input.shown,
                stpn::three_creases_message(&input.mesh, first)
            )
        })?;
        let lines = &input.report.triangle_lines;
        if !lines.is_empty() {
            input.report.triangle_lines = origin.iter().map(|&t| lines[t]).collect();
        }
        tags.resize(input.mesh.positions.len(), stpn::VertexTag::default());
        note(format_args!(
            "warning: '{}': split {} triangle(s) at their centroids, whose three corners are crease vertices (from {source}; scalar-tagged PN triangles allow two; the first: {face})",
            input.shown,
            which.len()
        ));
    }
    input.tags = Some(tags);
    Ok(())
}

/// Gives `scene` the height map and tags `input` carries.
fn apply_surface_inputs(
    h: &Headless,
    scene: &mut meshrefine::render::Scene,
    input: &Input,
) -> Result<()> {
    if let Some(map) = input.heightmap.clone() {
        h.set_heightmap(scene, map)?;
    }
    if let Some(tags) = input.tags.clone() {
        scene.set_tags(&h.ctx, &h.pool, &h.renderer, tags)?;
    }
    Ok(())
}

/// How many degenerate faces a warning lists before "and N more".
const LISTED_DEGENERATE: usize = 3;

/// One warning line for every dropped face: the count, then the first few runs of faces with
/// the same line and reason.
fn degenerate_warning(shown: &str, report: &LoadReport) -> Option<String> {
    let dropped = &report.dropped_degenerate;
    if dropped.is_empty() {
        return None;
    }
    let mut runs: Vec<(String, usize)> = Vec::new();
    for d in dropped {
        let what = d.describe();
        match runs.last_mut() {
            Some((last, n)) if *last == what => *n += 1,
            _ => runs.push((what, 1)),
        }
    }
    let mut listed: Vec<String> = runs
        .iter()
        .take(LISTED_DEGENERATE)
        .map(|(what, n)| match n {
            1 => what.clone(),
            n => format!("{what} ({n} triangles)"),
        })
        .collect();
    if runs.len() > LISTED_DEGENERATE {
        listed.push(format!("and {} more", runs.len() - LISTED_DEGENERATE));
    }
    Some(format!(
        "warning: '{shown}': dropped {} degenerate face(s) (repeated vertex, zero area, an area f32 cannot represent, or the same three vertices as an earlier face): {}",
        dropped.len(),
        listed.join("; ")
    ))
}

/// Loop subdivides the file's topology, which a dropped face would change (a hole where it
/// was): with `--surface loop` the first dropped face is an error, not a warning. With
/// `topology`, also what Loop cannot subdivide in the faces kept ([`loop_check`]).
fn loop_refusal(shown: &str, mesh: &Mesh, report: &LoadReport, topology: bool) -> Option<String> {
    let Some(d) = report.dropped_degenerate.first() else {
        return topology
            .then(|| loop_check::topology_refusal(mesh, report))
            .flatten()
            .map(|why| format!("'{shown}': the loop surface cannot subdivide it: {why}"));
    };
    let face = match d.line {
        Some(l) => format!("the face at line {l}"),
        None => format!("face {}", d.face),
    };
    if d.reason == meshrefine::mesh::DUPLICATE_FACE {
        return Some(format!(
            "'{shown}': the loop surface cannot subdivide it: {face} {}: Loop subdivision cannot take two faces on the same three vertices (after one step their edges would be shared by four faces), and dropping one, as the other surfaces do, would open a hole",
            d.reason
        ));
    }
    Some(format!(
        "'{shown}': the loop surface cannot subdivide it: {face} {} ({} degenerate face(s) in all): Loop subdivision needs every face of the file, and dropping it, as the other surfaces do, would open a hole",
        d.reason,
        report.dropped_degenerate.len()
    ))
}

/// Loads `path` (the default mesh when `None`); `for_loop` when the loop surface will subdivide
/// it, which refuses degenerate faces instead of dropping them.
fn load_mesh(path: Option<&Path>, for_loop: bool) -> Result<Input> {
    let Some(p) = path else {
        return Ok(Input {
            mesh: meshrefine::mesh::default_mesh(),
            shown: "the default mesh (spot)".into(),
            heightmap: None,
            tags: None,
            loop_refusal: None,
            report: LoadReport::default(),
        });
    };
    let shown = p.display().to_string();
    let (mesh, report) = Mesh::load_obj(p)?;
    let loop_refusal = loop_refusal(&shown, &mesh, &report, for_loop);
    if let Some(why) = loop_refusal.as_ref().filter(|_| for_loop) {
        bail!("{why}");
    }
    if let Some(w) = degenerate_warning(&shown, &report) {
        note(format_args!("{w}"));
    }
    if let Err(MeshError::NonManifold {
        edges, vertices, ..
    }) = mesh.require_manifold()
    {
        // Only Loop subdivision needs a manifold (and refuses the mesh when it is drawn).
        let e = MeshError::NonManifold {
            path: shown.clone(),
            edges,
            vertices,
        };
        note(format_args!("warning: {e} (only --surface loop needs one)"));
    }
    Ok(Input {
        mesh,
        shown,
        heightmap: None,
        tags: None,
        loop_refusal,
        report,
    })
}

/// Refuses an output path whose extension says another format than the one written.
fn require_extension(path: &Path, ext: &str, what: &str) -> Result<()> {
    let matches = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(ext));
    if !matches {
        bail!(
            "output file '{}' does not end in .{ext}: {what} (name it .{ext})",
            path.display()
        );
    }
    Ok(())
}

/// The draw configuration for `mesh` (displacement parameters not given are scaled to it, and
/// checked against its scale). An explicit `--submit` with another driver than `pattern` is
/// ignored with a warning (options.rs).
fn draw_config(t: &Technique, mesh: &Mesh) -> Result<DrawConfig> {
    Ok(DrawConfig {
        surface: t.surface.surface,
        displace: t.surface.displace,
        params: t
            .surface
            .params
            .params_for(mesh, &[t.surface.displace])
            .map_err(anyhow::Error::msg)?,
        // `--driver pattern` parses as the pattern driver; `--submit` gives its mode.
        driver: match t.driver {
            Driver::Pattern(_) => Driver::Pattern(t.submit()),
            d => d,
        },
        level: t.level,
    })
}

/// After every GPU object is gone: fail if the validation layer complained or anything leaked.
fn check_messages(messages: &Arc<Messages>) -> Result<()> {
    meshrefine::gpu::check_shutdown(messages).map_err(noted)
}

/// The validation layer's messages as notes, before the error that counts them.
fn noted(e: ShutdownError) -> anyhow::Error {
    if let ShutdownError::Validation(list) = &e {
        for m in list {
            note(format_args!("validation: {m}"));
        }
    }
    e.into()
}

/// [`meshrefine::gpu::with_context`] with the validation layer's messages printed as notes.
fn with_context<R>(desc: &ContextDesc, f: impl FnOnce(Arc<Context>) -> Result<R>) -> Result<R> {
    meshrefine::gpu::with_context(desc, f).map_err(|e| match e.downcast::<ShutdownError>() {
        Ok(s) => noted(s),
        Err(e) => e,
    })
}

fn run(cli: Cli) -> Result<()> {
    let desc = context_desc(&cli);
    options::check_outputs(&cli).map_err(anyhow::Error::msg)?;
    match &cli.command {
        Command::Render(a) => {
            require_extension(&a.output, "png", "render writes PNG images only")?;
            let for_loop = a.technique.surface.surface == Surface::Loop;
            let mut input = load_mesh(a.mesh.as_deref(), for_loop)?;
            let cfg = draw_config(&a.technique, &input.mesh)?;
            attach_surface_inputs(&mut input, &a.technique.surface, false)?;
            let size = (a.width, a.height);
            with_context(&desc, |ctx| {
                render_png(ctx, input, &cfg, size, a.wireframe, &a.output)
            })?;
            out!("wrote {}", a.output.display());
        }
        Command::View(a) => {
            if let Some(shot) = &a.screenshot {
                require_extension(shot, "png", "screenshots are PNG images")?;
            }
            require_extension(
                &a.headless_output,
                "png",
                "the headless view writes a PNG image",
            )?;
            let for_loop = a.technique.surface.surface == Surface::Loop;
            let mut input = load_mesh(a.mesh.as_deref(), for_loop)?;
            if input.loop_refusal.is_none() && a.mesh.is_some() {
                // The panel can switch to loop later: say then, in the file's terms, why not.
                input.loop_refusal = loop_refusal(&input.shown, &input.mesh, &input.report, true);
            }
            let cfg = draw_config(&a.technique, &input.mesh)?;
            attach_surface_inputs(&mut input, &a.technique.surface, true)?;
            let has_display = std::env::var_os("DISPLAY").is_some()
                || std::env::var_os("WAYLAND_DISPLAY").is_some();
            let why_headless = if has_display {
                let (mesh, viewed) = for_viewing(&input.mesh, &cfg);
                let opts = meshrefine::app::ViewOptions {
                    cfg: viewed,
                    frames: a.frames,
                    screenshot: a.screenshot.clone(),
                    wireframe: a.wireframe,
                    animate: a.animate,
                    lod: a.lod,
                    heightmap: input.heightmap.clone(),
                    tags: input.tags.clone(),
                    loop_refusal: input.loop_refusal.clone(),
                };
                match meshrefine::app::run(desc.clone(), mesh, opts) {
                    Ok(messages) => return check_messages(&messages),
                    Err(e) => match e.downcast::<meshrefine::app::NoWindowSystem>() {
                        Ok(no_window) => no_window.to_string(),
                        Err(e) => return Err(e.context(format!("cannot show '{}'", input.shown))),
                    },
                }
            } else {
                "no display found (DISPLAY and WAYLAND_DISPLAY are unset)".to_string()
            };
            with_context(&desc, |ctx| {
                let out = &a.headless_output;
                render_png(ctx, input, &cfg, (1280, 720), a.wireframe, out)
            })?;
            let shown =
                std::fs::canonicalize(&a.headless_output).unwrap_or(a.headless_output.clone());
            out!(
                "{why_headless}: rendered the scene headlessly to {}",
                shown.display()
            );
        }
        Command::Export(a) => {
            require_extension(&a.output, "obj", "export writes Wavefront OBJ text only")?;
            let for_loop = a.surface.surface == Surface::Loop;
            let mut input = load_mesh(a.mesh.as_deref(), for_loop)?;
            // Loop's elements are M1's faces, four per triangle.
            let elements = input.mesh.triangles.len() as u64 * if for_loop { 4 } else { 1 };
            meshrefine::export::check_size(elements, a.level)
                .map_err(|e| anyhow::anyhow!("cannot export '{}': {e}", input.shown))?;
            let cfg = draw_config(&a.technique(), &input.mesh)?;
            attach_surface_inputs(&mut input, &a.surface, false)?;
            let counts = with_context(&desc, |ctx| {
                let shown = input.shown.clone();
                export(ctx, input, &cfg, &a.output)
                    .with_context(|| format!("cannot export '{shown}'"))
            })?;
            out!("{counts}");
            out!("wrote {}", a.output.display());
        }
        Command::Info(a) => info(a)?,
        Command::Bench(a) => {
            if !(a.min_total_ms.is_finite() && a.min_total_ms >= 0.0) {
                bail!(
                    "--min-total-ms {} is not a finite number >= 0",
                    a.min_total_ms
                );
            }
            let mut input = load_mesh(a.mesh.as_deref(), a.surfaces.contains(&Surface::Loop))?;
            if a.surfaces.contains(&Surface::Stpn) {
                // As render does: every surface is then timed on the same, split, mesh.
                split_three_creases(&mut input, None)?;
            }
            let (mesh, _) = for_viewing(&input.mesh, &DrawConfig::new(Driver::default(), 1));
            let (centre, scale) = input.mesh.viewing_transform();
            let params = a
                .params
                .params_for(&input.mesh, &a.displacements)
                .map_err(anyhow::Error::msg)?
                .in_drawn_frame(centre, scale);
            let surfaces = a
                .surfaces
                .iter()
                .flat_map(|&s| a.displacements.iter().map(move |&d| (s, d)))
                .collect();
            let opts = meshrefine::bench::BenchOptions {
                levels: a.levels.clone(),
                surfaces,
                params: Some(params),
                frames: a.frames,
                width: a.width,
                height: a.height,
                // `pattern` stands for its three submission modes.
                drivers: Driver::VARIANTS
                    .into_iter()
                    .filter(|v| a.drivers.iter().any(|d| d.same_kind(*v)))
                    .collect(),
                min_total_ms: a.min_total_ms,
            };
            // Drawn centred and at unit size, like `render`: the timings do not change.
            let mut mesh = mesh;
            mesh.name = input.mesh.name.clone();
            let report = with_context(&desc, |ctx| {
                meshrefine::bench::run(ctx, &[mesh], &opts)
                    .with_context(|| format!("cannot benchmark '{}'", input.shown))
            })?;
            if let Some(prefix) = &a.out {
                let args: Vec<String> = std::env::args().skip(1).collect();
                let command = format!("meshrefine {}", args.join(" "));
                report
                    .write_files(prefix, &command)
                    .with_context(|| format!("cannot write '{}.md'", prefix.display()))?;
            }
            out!("{}", report.summary(a.out.as_deref()));
            if let Some(prefix) = &a.out {
                out!("wrote {}.{{md,csv,json}}", prefix.display());
            }
        }
    }
    Ok(())
}

/// Captures what the GPU evaluated and writes it as OBJ; returns the counts line.
fn export(ctx: Arc<Context>, input: Input, cfg: &DrawConfig, output: &Path) -> Result<String> {
    let device = ctx.info.describe();
    let mut h = Headless::with_context(ctx, 64, 64)?;
    let name = input.mesh.name.clone();
    let mut scene = h.scene(input.mesh.clone(), cfg.level)?;
    apply_surface_inputs(&h, &mut scene, &input)?;
    let (c, r) = scene.bounding_sphere();
    let camera = Camera::framing(c, r);
    let refined = if cfg.driver.kind().export_capture() == Some(Capture::Triangles) {
        let triangles = h.capture_triangles(&mut scene, cfg, &camera)?;
        meshrefine::export::weld_triangles(&triangles)
    } else {
        let cap = h.capture(&mut scene, cfg, &camera)?;
        let Some(pattern) = scene.patterns.find(cfg.level) else {
            bail!("no pattern of level {} was made", cfg.level);
        };
        let pattern = &scene.patterns.patterns[pattern];
        meshrefine::export::weld(&cap, pattern).map_err(anyhow::Error::msg)?
    };
    let header = vec![
        format!(
            "meshrefine export of '{name}': surface {}, displacement {}, driver {}, level {}",
            cfg.surface.name(),
            cfg.displace.name(),
            cfg.label(),
            cfg.level
        ),
        format!("evaluated on {device}"),
        format!(
            "{} vertices, {} normals, {} triangles",
            refined.positions.len(),
            refined.normals.len(),
            refined.triangles.len()
        ),
    ];
    std::fs::write(output, meshrefine::export::to_obj(&refined, &header))
        .with_context(|| format!("cannot write '{}'", output.display()))?;
    Ok(header[2].clone())
}

/// Renders `input` (centred and at unit size, see [`Mesh::for_viewing`]) to a PNG. A blank
/// The mesh as drawn (centred, unit size: [`Mesh::for_viewing`]) and `cfg` with its displacement
/// moved into the same frame, so the surface drawn is the mesh's own, only moved and scaled.
fn for_viewing(mesh: &Mesh, cfg: &DrawConfig) -> (Mesh, DrawConfig) {
    let (centre, scale) = mesh.viewing_transform();
    let mut viewed = *cfg;
    viewed.params = cfg.params.in_drawn_frame(centre, scale);
    (mesh.for_viewing(), viewed)
}

/// image is still written, then reported as an error: it shows nothing.
fn render_png(
    ctx: Arc<Context>,
    input: Input,
    cfg: &DrawConfig,
    (width, height): (u32, u32),
    wireframe: bool,
    out: &Path,
) -> Result<()> {
    let triangles = input.mesh.triangles.len();
    let image = {
        let mut h = Headless::with_context(ctx, width, height)?;
        h.wireframe = wireframe;
        let (mesh, viewed) = for_viewing(&input.mesh, cfg);
        let mut scene = h.scene(mesh, cfg.level)?;
        apply_surface_inputs(&h, &mut scene, &input)?;
        let (c, r) = scene.bounding_sphere();
        h.render(&mut scene, &viewed, &Camera::framing(c, r))
    }
    .with_context(|| format!("cannot render '{}'", input.shown))?;
    image
        .save_png(out)
        .with_context(|| format!("cannot write '{}'", out.display()))?;
    if covered_pixels(&image) == 0 {
        // The camera frames the undisplaced mesh: a displacement larger than the mesh moves
        // the surface out of the picture, whatever the triangles' size.
        let radius = input.mesh.bounding_radius() as f64;
        let reach = cfg.params.reach(cfg.displace);
        let why = if reach > radius {
            format!(
                "the displacement ({}) moves the surface up to {:.3e} times the mesh's bounding radius, out of the frame, which shows the undisplaced mesh",
                cfg.params.reach_options(cfg.displace),
                reach / radius
            )
        } else {
            "each is much smaller than a pixel when the whole mesh is framed, or seen edge-on"
                .to_string()
        };
        bail!(
            "'{}' is blank: no pixel of the {width}x{height} image shows any of the {triangles} triangle(s) of '{}' ({why})",
            out.display(),
            input.shown
        );
    }
    Ok(())
}

fn info(a: &cli::InfoArgs) -> Result<()> {
    let (path, level) = (a.mesh.as_path(), a.level);
    let (mesh, report) = Mesh::load_obj(path)?;
    let for_loop = a.surface == Some(Surface::Loop);
    if let Some(why) = loop_refusal(&path.display().to_string(), &mesh, &report, for_loop) {
        if for_loop {
            bail!("{why}");
        }
    }
    if let Some(w) = degenerate_warning(&path.display().to_string(), &report) {
        note(format_args!("{w}"));
    }
    let s = mesh.stats();
    out!("mesh: {}", path.display());
    out!("vertices: {}", s.vertices);
    out!("triangles: {}", s.triangles);
    out!("boundary edges: {}", s.boundary_edges);
    out!("non-manifold edges: {}", s.nonmanifold_edges);
    out!("non-manifold vertices: {}", s.nonmanifold_vertices);
    out!(
        "inconsistently oriented edges: {}",
        s.inconsistently_oriented_edges
    );
    out!(
        "degenerate faces dropped: {}",
        report.dropped_degenerate.len()
    );
    out!(
        "normals: {}",
        if report.normals_computed {
            "computed (area-weighted)"
        } else {
            "from file"
        }
    );
    let hist: Vec<String> = s
        .valence_histogram
        .iter()
        .map(|(v, n)| format!("{v}:{n}"))
        .collect();
    out!("valence histogram (valence:vertices): {}", hist.join(" "));
    if let Some(level) = level {
        let t = s.triangles as u64;
        out!(
            "level {level}: {} refined triangles ({} per coarse triangle)",
            t * meshrefine::pattern::triangle_count(level) as u64,
            meshrefine::pattern::triangle_count(level)
        );
        for d in Driver::ALL {
            out!(
                "  {:8} {:>14} bytes of GPU geometry",
                d.name(),
                d.geometry_bytes(level, t)
            );
        }
    }
    if a.surface == Some(Surface::Loop) {
        let lattice = meshrefine::surface::loop_::Lattice::new(a.bft_level);
        let report = |p| note(format_args!("{}: {p}", path.display()));
        let data = LoopData::new(
            &mesh,
            a.boundary,
            lattice,
            meshrefine::surface::loop_::throttled(report),
        )
        .map_err(|e| {
            anyhow::anyhow!(
                "'{}': the loop surface cannot subdivide it: {e}",
                path.display()
            )
        })?;
        out!(
            "loop: M1 has {} vertices and {} faces ({} boundaries)",
            data.m1.vertex_count,
            data.m1.faces.len(),
            clap::ValueEnum::to_possible_value(&a.boundary)
                .map_or(String::new(), |v| v.get_name().to_string())
        );
        let configs: Vec<String> = data
            .valences()
            .iter()
            .map(|&(v, b, n)| format!("{v}{}:{n}", if b { "b" } else { "" }))
            .collect();
        out!(
            "configurations: {} in {} tables (valence:tables, b = on a boundary): {}",
            data.tables.keys.len(),
            data.tables.configs.len(),
            configs.join(" ")
        );
        out!(
            "control points per face: {} to {}",
            data.tables
                .faces
                .iter()
                .map(|f| f.control.len())
                .min()
                .unwrap_or(0),
            data.tables
                .faces
                .iter()
                .map(|f| f.control.len())
                .max()
                .unwrap_or(0)
        );
        out!(
            "table level: {} ({} segments per M1-face edge, {} lattice points)",
            lattice.lmax,
            lattice.segments(),
            lattice.rows()
        );
        out!("basis function tables: {} bytes", data.table_bytes());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use meshrefine::mesh::DegenerateFace;

    #[test]
    fn degenerate_warning_is_one_line_with_the_first_runs() {
        let face = |line, reason| DegenerateFace {
            face: 0,
            line: Some(line),
            reason,
        };
        let mut report = LoadReport::default();
        assert_eq!(degenerate_warning("x.obj", &report), None);
        report.dropped_degenerate = vec![face(7, "has zero area"); 1000];
        report
            .dropped_degenerate
            .extend([8, 9, 10, 11].map(|l| face(l, "repeats a vertex index")));
        let w = degenerate_warning("x.obj", &report).unwrap();
        assert!(!w.contains('\n'));
        assert!(
            w.starts_with("warning: 'x.obj': dropped 1004 degenerate face(s) "),
            "{w}"
        );
        assert!(
            w.ends_with(": at line 7, has zero area (1000 triangles); at line 8, repeats a vertex index; at line 9, repeats a vertex index; and 2 more"),
            "{w}"
        );
    }
}
