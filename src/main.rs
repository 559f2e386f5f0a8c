//! `meshrefine` binary: parses the command line, runs the command, turns every failure into one
//! clear sentence and a non-zero exit status.

mod cli;

use anyhow::{bail, Context as _, Result};
use clap::Parser;
use cli::{Cli, Command, Technique};
use meshrefine::gpu::{Context, ContextDesc, Messages};
use meshrefine::mesh::Mesh;
use meshrefine::render::{Camera, DrawConfig, Driver, Headless};
use std::path::Path;
use std::process::ExitCode;
use std::sync::Arc;

fn main() -> ExitCode {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn"))
        .format_timestamp(None)
        .init();
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
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

fn load_mesh(path: Option<&Path>) -> Result<Mesh> {
    match path {
        None => Ok(meshrefine::mesh::default_mesh()),
        Some(p) => {
            let (mesh, report) = Mesh::load_obj(p)?;
            if !report.dropped_degenerate.is_empty() {
                eprintln!(
                    "warning: '{}': dropped {} degenerate face(s) (repeated vertex or zero area)",
                    p.display(),
                    report.dropped_degenerate.len()
                );
            }
            if let Err(e) = mesh.require_manifold() {
                // Only Loop subdivision (not yet here) needs a manifold; say so anyway.
                eprintln!("warning: {e} (the flat surface does not need one)");
            }
            Ok(mesh)
        }
    }
}

/// What to draw: the technique's choices, parameters scaled to `mesh` where not given.
fn draw_config(t: &Technique, mesh: &Mesh) -> Result<DrawConfig> {
    Ok(DrawConfig {
        surface: t.surface.surface,
        displace: t.surface.displace,
        params: t
            .surface
            .params
            .params(mesh.bounding_radius())
            .map_err(anyhow::Error::msg)?,
        driver: t.driver,
        submit: t.submit,
        level: t.level,
    })
}

/// After every GPU object is gone: fail if the validation layer complained or anything leaked.
fn check_messages(messages: &Arc<Messages>) -> Result<()> {
    let list = messages.take();
    let leaked = meshrefine::gpu::live_objects();
    if leaked != 0 {
        bail!("{leaked} Vulkan object(s) were still alive at shutdown");
    }
    if !list.is_empty() {
        for m in &list {
            eprintln!("validation: {m}");
        }
        bail!(
            "the Vulkan validation layer reported {} problem(s)",
            list.len()
        );
    }
    Ok(())
}

fn run(cli: Cli) -> Result<()> {
    let desc = context_desc(&cli);
    match &cli.command {
        Command::Render(a) => {
            let mesh = load_mesh(a.mesh.as_deref())?;
            let cfg = draw_config(&a.technique, &mesh)?;
            let messages = {
                let ctx = Context::new(&desc)?;
                let messages = ctx.messages_handle();
                render_png(ctx, mesh, &cfg, a.width, a.height, a.wireframe, &a.output)?;
                messages
            };
            check_messages(&messages)?;
            println!("wrote {}", a.output.display());
        }
        Command::View(a) => {
            let mesh = load_mesh(a.mesh.as_deref())?;
            let cfg = draw_config(&a.technique, &mesh)?;
            let has_display = std::env::var_os("DISPLAY").is_some()
                || std::env::var_os("WAYLAND_DISPLAY").is_some();
            let why_headless = if has_display {
                let opts = meshrefine::app::ViewOptions {
                    cfg,
                    frames: a.frames,
                    screenshot: a.screenshot.clone(),
                    wireframe: a.wireframe,
                    animate: a.animate,
                    lod: a.lod,
                };
                match meshrefine::app::run(desc.clone(), mesh.clone(), opts) {
                    Ok(messages) => return check_messages(&messages),
                    Err(e) => match e.downcast::<meshrefine::app::NoWindowSystem>() {
                        Ok(no_window) => no_window.to_string(),
                        Err(e) => return Err(e),
                    },
                }
            } else {
                "no display found (DISPLAY and WAYLAND_DISPLAY are unset)".to_string()
            };
            let messages = {
                let ctx = Context::new(&desc)?;
                let messages = ctx.messages_handle();
                render_png(ctx, mesh, &cfg, 1280, 720, a.wireframe, &a.headless_output)?;
                messages
            };
            check_messages(&messages)?;
            let shown =
                std::fs::canonicalize(&a.headless_output).unwrap_or(a.headless_output.clone());
            println!(
                "{why_headless}: rendered the scene headlessly to {}",
                shown.display()
            );
        }
        Command::Export(a) => {
            let mesh = load_mesh(a.mesh.as_deref())?;
            let cfg = draw_config(&a.technique(), &mesh)?;
            let messages = {
                let ctx = Context::new(&desc)?;
                let messages = ctx.messages_handle();
                let device = ctx.info.describe();
                let mut h = Headless::with_context(ctx, 64, 64)?;
                let name = mesh.name.clone();
                let mut scene = h.scene(mesh, cfg.level)?;
                let (c, r) = scene.bounding_sphere();
                let camera = Camera::framing(c, r);
                let refined = if cfg.driver == Driver::Tess {
                    let triangles = h.capture_triangles(&mut scene, &cfg, &camera)?;
                    meshrefine::export::weld_triangles(&triangles)
                } else {
                    let cap = h.capture(&mut scene, &cfg, &camera)?;
                    let pattern = &scene.patterns.patterns[scene.patterns.find(cfg.level).unwrap()];
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
                std::fs::write(&a.output, meshrefine::export::to_obj(&refined, &header))
                    .with_context(|| format!("cannot write '{}'", a.output.display()))?;
                println!("{}", header[2]);
                messages
            };
            check_messages(&messages)?;
            println!("wrote {}", a.output.display());
        }
        Command::Info(a) => info(&a.mesh, a.level)?,
        Command::Bench(a) => {
            let mesh = load_mesh(a.mesh.as_deref())?;
            let ctx = Context::new(&desc)?;
            let messages = ctx.messages_handle();
            let params = a
                .params
                .params(mesh.bounding_radius())
                .map_err(anyhow::Error::msg)?;
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
            };
            let report = meshrefine::bench::run(ctx, &[mesh], &opts)?;
            println!("{}", report.markdown());
            check_messages(&messages)?;
            if let Some(prefix) = &a.out {
                let args: Vec<String> = std::env::args().skip(1).collect();
                let command = format!("meshrefine {}", args.join(" "));
                report
                    .write_files(prefix, &command)
                    .with_context(|| format!("cannot write '{}.md'", prefix.display()))?;
                println!("wrote {}.{{md,csv,json}}", prefix.display());
            }
        }
    }
    Ok(())
}

fn render_png(
    ctx: Arc<Context>,
    mesh: Mesh,
    cfg: &DrawConfig,
    width: u32,
    height: u32,
    wireframe: bool,
    out: &Path,
) -> Result<()> {
    let mut h = Headless::with_context(ctx, width, height)?;
    h.wireframe = wireframe;
    let mut scene = h.scene(mesh, cfg.level)?;
    let (c, r) = scene.bounding_sphere();
    let image = h.render(&mut scene, cfg, &Camera::framing(c, r))?;
    image
        .save_png(out)
        .with_context(|| format!("cannot write '{}'", out.display()))
}

fn info(path: &Path, level: Option<u32>) -> Result<()> {
    let (mesh, report) = Mesh::load_obj(path)?;
    let s = mesh.stats();
    println!("mesh: {}", path.display());
    println!("vertices: {}", s.vertices);
    println!("triangles: {}", s.triangles);
    println!("boundary edges: {}", s.boundary_edges);
    println!("non-manifold edges: {}", s.nonmanifold_edges);
    println!("non-manifold vertices: {}", s.nonmanifold_vertices);
    println!(
        "inconsistently oriented edges: {}",
        s.inconsistently_oriented_edges
    );
    println!(
        "degenerate faces dropped: {}",
        report.dropped_degenerate.len()
    );
    println!(
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
    println!("valence histogram (valence:vertices): {}", hist.join(" "));
    if let Some(level) = level {
        let t = s.triangles as u64;
        println!(
            "level {level}: {} refined triangles ({} per coarse triangle)",
            t * meshrefine::pattern::triangle_count(level) as u64,
            meshrefine::pattern::triangle_count(level)
        );
        for d in Driver::ALL {
            println!(
                "  {:8} {:>14} bytes of GPU geometry",
                d.name(),
                d.geometry_bytes(level, t)
            );
        }
    }
    Ok(())
}
