//! `meshrefine export`: the refined mesh as the GPU's drawing pipeline evaluated it, read back
//! and welded into OBJ.
#![forbid(unsafe_code)]

use super::args::ExportArgs;
use super::input::{apply_surface_inputs, attach_surface_inputs, draw_config, load_mesh, Input};
use super::{require_extension, with_context};
use anyhow::{bail, Context as _, Result};
use meshrefine::gpu::{Context, ContextDesc};
use meshrefine::render::{Camera, Capture, DrawConfig, Headless};
use std::io::Write as _;
use std::path::Path;
use std::sync::Arc;

/// Runs `meshrefine export` with `a`.
pub fn run(a: &ExportArgs, desc: &ContextDesc) -> Result<()> {
    require_extension(&a.output, "obj", "export writes Wavefront OBJ text only")?;
    let for_loop = a.surface.surface.facts().needs_every_face;
    let mut input = load_mesh(a.mesh.as_deref(), for_loop)?;
    // Loop's elements are M1's faces, four per triangle.
    let elements = input.mesh.triangles.len() as u64 * if for_loop { 4 } else { 1 };
    meshrefine::export::check_size(elements, a.level)
        .map_err(|e| anyhow::anyhow!("cannot export '{}': {e}", input.shown))?;
    let cfg = draw_config(&a.technique(), &input.mesh)?;
    attach_surface_inputs(&mut input, &a.surface, false)?;
    let counts = with_context(desc, |ctx| {
        let shown = input.shown.clone();
        export(ctx, input, &cfg, &a.output).with_context(|| format!("cannot export '{shown}'"))
    })?;
    out!("{counts}");
    out!("wrote {}", a.output.display());
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
