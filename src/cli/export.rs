//! `meshrefine export`: the refined mesh as the GPU's drawing pipeline evaluated it, read back
//! and welded into OBJ.
#![forbid(unsafe_code)]

use super::adaptive::{Adaptive, Frame};
use super::args::ExportArgs;
use super::input::{apply_surface_inputs, attach_surface_inputs, draw_config, load_mesh, Input};
use super::{require_extension, with_context};
use anyhow::{bail, Context as _, Result};
use meshrefine::export::{element_texcoord, TexcoordOf};
use meshrefine::gpu::{Context, ContextDesc};
use meshrefine::render::{Camera, Capture, CapturedVertex, DrawConfig, Headless};
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
    let adaptive = a.adaptive.enabled(false);
    let shown = input.shown.clone();
    let check_size = move |level| {
        meshrefine::export::check_size(elements, level)
            .map_err(|e| anyhow::anyhow!("cannot export '{shown}': {e}"))
    };
    if adaptive.is_none() {
        check_size(a.level)?;
    }
    let mut cfg = draw_config(&a.technique(), &input.mesh)?;
    attach_surface_inputs(&mut input, &a.surface, false)?;
    let size = (a.width, a.height);
    let counts = with_context(desc, |ctx| {
        if let Some(a) = &adaptive {
            cfg.level = a.max_level(&ctx, cfg.driver)?;
            cfg.geomorph = a.geomorph;
            check_size(cfg.level)?;
        }
        let shown = input.shown.clone();
        export(ctx, input, &cfg, &a.output, adaptive, size)
            .with_context(|| format!("cannot export '{shown}'"))
    })?;
    out!("{counts}");
    out!("wrote {}", a.output.display());
    Ok(())
}

/// Captures what the GPU evaluated (adaptively, for an image of `size`, when `adaptive` says
/// so) and writes it as OBJ; returns the counts line.
fn export(
    ctx: Arc<Context>,
    input: Input,
    cfg: &DrawConfig,
    output: &Path,
    adaptive: Option<Adaptive>,
    size: (u32, u32),
) -> Result<String> {
    let device = ctx.info.describe();
    let mut h = Headless::with_context(ctx, 64, 64)?;
    let name = input.mesh.name.clone();
    let mut scene = h.scene(input.mesh.clone(), cfg.level)?;
    apply_surface_inputs(&h, &mut scene, &input)?;
    let (c, r) = scene.bounding_sphere();
    let mut camera = Camera::framing(c, r);
    let mut drawn = None;
    if let Some(a) = &adaptive {
        // Drawn as it is: the mesh's own coordinates.
        let capture = cfg.driver.kind().export_capture().unwrap_or(Capture::None);
        let (cam, _) = a.set_up(&mut h, &mut scene, cfg, capture, size, &Frame::IDENTITY)?;
        camera = cam;
        drawn = Some((a, cam));
    }
    let refined = if cfg.driver.kind().export_capture() == Some(Capture::Triangles) {
        let triangles = h.capture_triangles(&mut scene, cfg, &camera)?;
        meshrefine::export::weld_triangles(&triangles)
    } else {
        let cap = h.capture(&mut scene, cfg, &camera)?;
        // Texture coordinates per captured vertex, from its element and sample (the local
        // surfaces' elements are the coarse triangles, whose corners carry them).
        let uvs = scene
            .data
            .uvs
            .as_deref()
            .filter(|_| !cfg.surface.uses_loop_faces());
        let records = scene.records(cfg.surface);
        let texcoord = |v: &CapturedVertex| {
            let e = v.id[0] as usize;
            let bary = [v.coord[0], v.coord[1], v.coord[2]];
            let corners = uvs.map_or(&[[0.0; 2]; 3], |u| &u[e]);
            element_texcoord(cfg.surface, &cfg.params, &records[e], bary, corners)
        };
        let uv = uvs.map(|_| &texcoord as TexcoordOf<'_>);
        if drawn.is_some() {
            meshrefine::export::weld_adaptive_with(&cap, cfg.level, uv)
                .map_err(anyhow::Error::msg)?
        } else {
            let Some(pattern) = scene.patterns.find(cfg.level) else {
                bail!("no pattern of level {} was made", cfg.level);
            };
            let pattern = &scene.patterns.patterns[pattern];
            meshrefine::export::weld_with(&cap, pattern, uv).map_err(anyhow::Error::msg)?
        }
    };
    if scene.data.uvs.is_some() && refined.texcoords.is_empty() {
        crate::note(format_args!(
            "warning: '{name}' has texture coordinates, but {} writes none (vt): {}",
            if cfg.surface.uses_loop_faces() {
                "--surface loop"
            } else {
                "--driver tess"
            },
            if cfg.surface.uses_loop_faces() {
                "its elements are Loop's M1 faces, which carry none"
            } else {
                "the tessellator's triangles are read back without their samples; --driver pattern writes them"
            }
        ));
    }
    // The levels the GPU's level pass wrote for the capture, as the driver drew them.
    let drawn = drawn.map(|(a, cam)| {
        let (_, report) = scene.drawn_levels(cfg);
        a.header(&cam, &Frame::IDENTITY, size, &report)
    });
    let mut header = vec![
        format!(
            "meshrefine export of '{name}': surface {}, displacement {}, driver {}, {} {}",
            cfg.surface.name(),
            cfg.displace.name(),
            cfg.label(),
            if drawn.is_some() {
                "max level"
            } else {
                "level"
            },
            cfg.level
        ),
        format!("evaluated on {device}"),
        format!(
            "{} vertices, {} normals, {} triangles{}",
            refined.positions.len(),
            refined.normals.len(),
            refined.triangles.len(),
            if refined.texcoords.is_empty() {
                String::new()
            } else {
                format!(", {} texture coordinates", refined.texcoords.len())
            }
        ),
    ];
    header.extend(drawn.into_iter().flatten());
    std::fs::write(output, meshrefine::export::to_obj(&refined, &header))
        .with_context(|| format!("cannot write '{}'", output.display()))?;
    Ok(header[2].clone())
}
