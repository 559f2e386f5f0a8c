//! `meshrefine export`: the refined mesh as the GPU's drawing pipeline evaluated it, read back
//! and welded into OBJ.
#![forbid(unsafe_code)]

use super::adaptive::{Adaptive, Frame};
use super::args::ExportArgs;
use super::input::{
    apply_surface_inputs, attach_surface_inputs, draw_config, for_viewing, load_mesh, Input,
};
use super::progress::{count, count_of, plural, ProgressLine};
use super::{require_extension, with_context};
use anyhow::{bail, Context as _, Result};
use glam::Vec2;
use meshrefine::export::{element_texcoord, RefinedMesh, TexcoordOf, TriangleWelder};
use meshrefine::gpu::{Context, ContextDesc};
use meshrefine::render::driver::LEAST_LEVEL_LIMIT;
use meshrefine::render::{
    Camera, Capture, CapturedVertex, ChosenLevels, DrawConfig, Driver, Headless, Scene, XfbVertex,
};
use std::io::Write as _;
use std::path::Path;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex};

/// Runs `meshrefine export` with `a`.
pub fn run(a: &ExportArgs, desc: &ContextDesc) -> Result<()> {
    require_extension(&a.output, "obj", "export writes Wavefront OBJ text only")?;
    let mut progress = ProgressLine::new().map_err(anyhow::Error::msg)?;
    let max_capture_bytes = capture_bytes_env()?;
    let for_loop = a.surface.surface.facts().needs_every_face;
    let mut input = load_mesh(a.mesh.as_deref(), for_loop)?;
    // Loop's elements are M1's faces, four per triangle.
    let elements = input.mesh.triangles.len() as u64 * if for_loop { 4 } else { 1 };
    let adaptive = a.adaptive.enabled(false);
    let shown = input.shown.clone();
    let mut cfg = draw_config(&a.technique(), &input.mesh)?;
    // Refused up front, before any GPU work; but a level the device may refuse (above the
    // least limit of a driver a device limits) is checked against the device first, so that
    // the size's remedy is never a level the driver then refuses. Adaptive sizes are checked
    // on the levels chosen (`check_adaptive`).
    let mut too_large = None;
    if adaptive.is_none() {
        let per_element = |l| cfg.driver.refined_per_element(l);
        match meshrefine::export::check_size(elements, cfg.level, per_element) {
            Ok(triangles) => progress.set_size(triangles),
            Err(e) if cfg.level > LEAST_LEVEL_LIMIT && cfg.driver == Driver::Tess => {
                too_large = Some(e)
            }
            Err(e) => bail!("cannot export '{shown}': {e}"),
        }
    }
    attach_surface_inputs(&mut input, &a.surface, false)?;
    if adaptive.is_some() {
        // A camera too far from the mesh is refused before any GPU work, as render's is.
        let (centre, scale) = input.mesh.viewing_transform();
        super::adaptive::check_distance(&a.adaptive.viewpoint, &Frame { centre, scale })
            .with_context(|| format!("cannot export '{shown}'"))?;
    }
    let size = (a.width, a.height);
    let counts = with_context(desc, |ctx| {
        let shown = input.shown.clone();
        // Every refusal, the options' on this device included, names the mesh as render's do.
        (|| {
            if let Some(a) = &adaptive {
                cfg.level = a.max_level(&ctx, cfg.driver)?;
                cfg.geomorph = a.geomorph;
            } else if let Some(e) = too_large {
                meshrefine::render::driver::check_level(&ctx, &cfg)?;
                bail!(e);
            }
            let knobs = (progress, max_capture_bytes);
            export(ctx, input, &cfg, &a.output, adaptive, size, knobs)
        })()
        .with_context(|| format!("cannot export '{shown}'"))
    })?;
    out!("{counts}");
    out!(
        "wrote {}",
        crate::printable(&a.output.display().to_string())
    );
    Ok(())
}

/// Captures what the GPU evaluated (adaptively, for an image of `size`, when `adaptive` says
/// so) and writes it as OBJ, reporting on `progress` and capturing in passes of at most
/// `max_capture_bytes` where given; returns the counts line.
fn export(
    ctx: Arc<Context>,
    input: Input,
    cfg: &DrawConfig,
    output: &Path,
    adaptive: Option<Adaptive>,
    size: (u32, u32),
    (mut progress, max_capture_bytes): (ProgressLine, Option<u64>),
) -> Result<String> {
    let device = ctx.info.describe();
    let mut h = Headless::with_context(ctx, 64, 64)?;
    let name = input.mesh.name.clone();
    // Drawn as render draws it, centred and at unit size (the camera and levels are render's,
    // single-precision view maths keeps the mesh far from the origin), written back in the
    // mesh's coordinates.
    let (mesh, mut viewed) = for_viewing(&input.mesh, cfg);
    let (centre, scale) = input.mesh.viewing_transform();
    let frame = Frame { centre, scale };
    let mut scene = h.scene(mesh, viewed.level)?;
    // An export draws no frames to wait for: it captures in passes and reports its own
    // progress, so the slow-frame estimate would mislead.
    scene.skip_slow_warning();
    apply_surface_inputs(&h, &mut scene, &input)?;
    let mut adaptive_camera =
        adaptive_camera(&mut h, &mut scene, &viewed, adaptive.as_ref(), size, &frame)?;
    // The header names the largest level allowed, whichever the draws were set up to.
    let allowed = viewed;
    if let Some((a, (camera, chosen))) = adaptive.as_ref().zip(adaptive_camera.as_mut()) {
        // As render does: drawn up to the largest level chosen where the largest allowed does
        // not fit (the same levels, so the same vertices).
        let capture = viewed
            .driver
            .kind()
            .export_capture()
            .unwrap_or(Capture::None);
        let fits = a.lower_to_fit(&mut h, &mut scene, &viewed, capture, *camera, size, chosen)?;
        if let Some(fits) = fits {
            (viewed, *chosen) = fits;
        }
        // A driver that cannot draw these levels is said alone, before any note on them.
        if let Some(why) = super::adaptive::cannot_adapt(&mut h, &mut scene, &viewed, capture)? {
            bail!(why);
        }
        progress.set_size(check_adaptive(a, &viewed, chosen)?);
        // Drawn: where they miss the pixel error (none said of levels refused above).
        a.note_unmet(&viewed, chosen);
    }
    let cfg = &viewed;
    let adaptive_camera = adaptive_camera.map(|(camera, _)| camera);
    let camera = adaptive_camera.unwrap_or_else(|| {
        let (c, r) = scene.bounding_sphere();
        Camera::framing(c, r)
    });
    // Long exports say how far they are on standard error (passes captured, lines written).
    let progress = Arc::new(Mutex::new(progress));
    h.max_capture_bytes = max_capture_bytes;
    let passes = report_capture_passes(&mut h, &progress);
    let mut refined = capture(&mut h, &mut scene, cfg, &camera, adaptive_camera.is_some())?;
    refined.placement = meshrefine::export::Placement { centre, scale };
    if scene.data.uvs.is_some() && cfg.surface.uses_loop_faces() {
        crate::note(format_args!(
            "warning: '{}' has texture coordinates, but --surface loop writes none (vt): its elements are Loop's M1 faces, which carry none",
            input.shown
        ));
    }
    let faces = input.mesh.triangles.len();
    let with_vt = input
        .mesh
        .triangles
        .iter()
        .filter(|t| t.t.is_some())
        .count();
    if with_vt > 0 && with_vt < faces {
        // Written for every refined vertex or for none: coordinates on some faces only are not.
        crate::note(format_args!(
            "warning: '{}' gives texture coordinates (vt) on {with_vt} of its {faces} triangles, not on every one: the export writes none",
            input.shown
        ));
    }
    // The levels the GPU's level pass wrote for the capture, as the driver drew them.
    let levels = adaptive.as_ref().zip(adaptive_camera).map(|(a, cam)| {
        let (_, report) = scene.drawn_levels(cfg);
        a.header(&cam, &frame, size, &report)
    });
    let header = header(&name, &allowed, &device, &refined, levels);
    h.capture_progress = None;
    let passes = passes.load(Ordering::Relaxed);
    let written = write_obj(output, &refined, &header, |(done, total)| {
        let text = format!(
            "export: writing, {} lines",
            count_of(done as u64, total as u64)
        );
        lock(&progress).report(1, done as f64 / total.max(1) as f64, &text);
    });
    written.with_context(|| format!("cannot write '{}'", output.display()))?;
    lock(&progress).finish(&format!(
        "export: {}, {} triangles, written",
        plural(passes as u64, "pass"),
        count(refined.triangles.len() as u64)
    ));
    Ok(header[2].clone())
}

/// The adaptive camera of the export, its levels set up for the capture, and what they draw
/// (`None`: uniform).
fn adaptive_camera(
    h: &mut Headless,
    scene: &mut Scene,
    cfg: &DrawConfig,
    adaptive: Option<&Adaptive>,
    size: (u32, u32),
    frame: &Frame,
) -> Result<Option<(Camera, ChosenLevels)>> {
    let Some(a) = adaptive else {
        return Ok(None);
    };
    let capture = cfg.driver.kind().export_capture().unwrap_or(Capture::None);
    let set_up = a.set_up(h, scene, cfg, capture, size, frame)?;
    Ok(Some(set_up))
}

/// The refined triangles the levels `chosen` for an adaptive export make (the level pass's CPU
/// mirror: what is captured), refused before anything is captured when they are none (every
/// element culled) or more than an export writes.
fn check_adaptive(a: &Adaptive, cfg: &DrawConfig, chosen: &ChosenLevels) -> Result<u64> {
    if chosen.histogram.is_empty() {
        bail!(
            "every one of its {} elements is culled (outside the view or facing away from the eye), so there is nothing to export; --cull off exports them",
            chosen.culled
        );
    }
    // Powers of two where the levels are (the tessellator's too while it glides: another
    // largest level would draw integer levels, more triangles than the estimate counts).
    let power_of_two = !cfg.driver.kind().integer_levels() || cfg.dyadic_levels();
    // The pixel error as typed (render's default when none was).
    let named = (a.opts.pixel_error.as_ref())
        .map_or_else(|| super::adaptive::px(a.pixel_error), |t| t.text.clone());
    let per_element = |l| cfg.driver.refined_per_element(l);
    // Drawn at the largest level whatever the pixel error.
    let fixed = chosen.unmet.unbounded + chosen.unmet.near;
    meshrefine::export::check_adaptive_size(
        &chosen.histogram,
        &named,
        (cfg.level, fixed),
        power_of_two,
        per_element,
    )
    .map_err(anyhow::Error::msg)
}

/// Reports each captured pass on `progress`; the count of passes done so far.
fn report_capture_passes(h: &mut Headless, progress: &Arc<Mutex<ProgressLine>>) -> Arc<AtomicU32> {
    let passes = Arc::new(AtomicU32::new(0));
    h.capture_progress = Some(Box::new({
        let (progress, passes) = (progress.clone(), passes.clone());
        move |p| {
            passes.store(p.done, Ordering::Relaxed);
            let text = format!(
                "export: {}/{} ({} of {} elements)",
                p.done,
                plural(p.passes as u64, "pass"),
                p.elements_done,
                p.elements
            );
            let fraction = p.done as f64 / p.passes as f64;
            lock(&progress).report(0, fraction, &text);
        }
    }));
    passes
}

/// What the GPU drew, captured and welded (with texture coordinates where the mesh has them).
fn capture(
    h: &mut Headless,
    scene: &mut Scene,
    cfg: &DrawConfig,
    camera: &Camera,
    adaptive: bool,
) -> Result<RefinedMesh> {
    // Texture coordinates of a vertex from its element and sample (the local surfaces'
    // elements are the coarse triangles, whose corners carry them; Loop's M1 faces carry none),
    // from copies of the corners' coordinates and the records: the tess capture welds each pass
    // while it holds the scene.
    let with_uv = (scene.data.uvs.as_ref())
        .filter(|_| !cfg.surface.uses_loop_faces())
        .map(|uvs| (uvs.clone(), scene.records(cfg.surface).to_vec()));
    let texcoord_at = |e: u32, bary: [f32; 3]| match &with_uv {
        Some((uvs, records)) => {
            let (e, corners) = (e as usize, &uvs[e as usize]);
            element_texcoord(cfg.surface, &cfg.params, &records[e], bary, corners)
        }
        None => Vec2::ZERO, // never asked: no texture coordinates are written
    };
    if cfg.driver.kind().export_capture() == Some(Capture::Triangles) {
        // Welded pass by pass: the captured triangles are never held whole.
        let texcoord = |v: &XfbVertex| texcoord_at(v.element, v.bary);
        let mut welder = if with_uv.is_some() {
            TriangleWelder::with_texcoords(&texcoord)
        } else {
            TriangleWelder::default()
        };
        h.capture_triangles_each(scene, cfg, camera, |t| welder.add(t))?;
        return Ok(welder.finish());
    }
    let cap = h.capture(scene, cfg, camera)?;
    let texcoord = |v: &CapturedVertex| texcoord_at(v.id[0], [v.coord[0], v.coord[1], v.coord[2]]);
    let uv = with_uv.as_ref().map(|_| &texcoord as TexcoordOf<'_>);
    if adaptive {
        return meshrefine::export::weld_adaptive_with(&cap, cfg.level, uv)
            .map_err(anyhow::Error::msg);
    }
    let Some(pattern) = scene.patterns.find(cfg.level) else {
        bail!("no pattern of level {} was made", cfg.level);
    };
    let pattern = &scene.patterns.patterns[pattern];
    meshrefine::export::weld_with(&cap, pattern, uv).map_err(anyhow::Error::msg)
}

/// The OBJ's comment lines: what was refined, how, on which device, the counts (the third
/// line, which `export` also prints) and the adaptive camera and levels.
fn header(
    name: &str,
    cfg: &DrawConfig,
    device: &str,
    refined: &RefinedMesh,
    levels: Option<[String; 2]>,
) -> Vec<String> {
    let mut header = vec![
        format!(
            "meshrefine export of '{}': surface {}, displacement {}, driver {}, {} {}",
            // One comment line whatever the name holds.
            crate::printable(name),
            cfg.surface.name(),
            cfg.displace.name(),
            cfg.label(),
            if levels.is_some() {
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
    header.extend(levels.into_iter().flatten());
    // What made it, options and all (the lines above name only the technique).
    header.push(format!("command: {}", super::command_line()));
    header
}

/// Write `refined` with `header` to `output` as OBJ, streamed through a buffer, replacing what
/// was there only once the whole file is written (`meshrefine::paths::write_output`).
fn write_obj(
    output: &Path,
    refined: &meshrefine::export::RefinedMesh,
    header: &[String],
    progress: impl FnMut((usize, usize)),
) -> std::io::Result<()> {
    meshrefine::paths::write_output(output, |mut w| {
        meshrefine::export::write_obj(refined, header, &mut w, progress)
    })
}

/// The environment variable that caps a capture pass's buffer, in bytes (a test's knob: a
/// small cap makes an export in many passes, which writes the same file as one).
const MAX_CAPTURE_BYTES_ENV: &str = "MESHREFINE_MAX_CAPTURE_BYTES";

fn capture_bytes_env() -> Result<Option<u64>> {
    super::bytes_env(MAX_CAPTURE_BYTES_ENV, u64::MAX)
}

/// The progress line, even if a report panicked while holding it.
fn lock(p: &Mutex<ProgressLine>) -> std::sync::MutexGuard<'_, ProgressLine> {
    p.lock().unwrap_or_else(|e| e.into_inner())
}
