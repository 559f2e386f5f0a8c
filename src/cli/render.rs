//! `meshrefine render`: one frame of a mesh, drawn headlessly, to a PNG.
#![forbid(unsafe_code)]

use super::adaptive::{cannot_adapt, Adaptive, Frame};
use super::args::{RenderArgs, ViewpointOpts};
use super::input::{
    apply_surface_inputs, attach_surface_inputs, draw_config, for_viewing, load_mesh, Input,
};
use super::{require_extension, with_context};
use crate::note;
use anyhow::{bail, Context as _, Result};
use meshrefine::gpu::{sample_count, Context, ContextDesc};
use meshrefine::render::cage::Wireframe;
use meshrefine::render::{covered_pixels_on, Background, Capture, DrawConfig, Headless, View};
use std::io::Write as _;
use std::path::Path;
use std::sync::Arc;

/// Runs `meshrefine render` with `a` (`level_given`: `--level` was given, so it draws
/// uniformly; otherwise adaptively, at `--pixel-error` or 1 px).
pub fn run(a: &RenderArgs, desc: &ContextDesc, level_given: bool) -> Result<()> {
    require_extension(&a.output, "png", "render writes PNG images only")?;
    let for_loop = a.technique.surface.surface.facts().needs_every_face;
    let mut input = load_mesh(a.mesh.as_deref(), for_loop)?;
    let cfg = draw_config(&a.technique, &input.mesh)?;
    attach_surface_inputs(&mut input, &a.technique.surface, false)?;
    // A camera too far from the mesh is refused before any GPU work (its distance needs only
    // the mesh's bounding box; one without a view direction needs the surface as drawn).
    let (centre, scale) = input.mesh.viewing_transform();
    super::adaptive::check_distance(&a.adaptive.viewpoint, &Frame { centre, scale })
        .with_context(|| format!("cannot render '{}'", input.shown))?;
    let image = ImageOptions {
        size: (a.width, a.height),
        wireframe: a.wireframe,
        view: a.view,
        background: a.background,
        msaa: a.msaa,
        adaptive: (a.adaptive).or_default(level_given),
        viewpoint: &a.adaptive.viewpoint,
    };
    let report = with_context(desc, |ctx| render_png(ctx, input, &cfg, &image, &a.output))?;
    if let Some(line) = report {
        out!("{line}");
    }
    out!(
        "wrote {}",
        crate::printable(&a.output.display().to_string())
    );
    Ok(())
}

/// The line that says what adaptive drawing chose.
fn levels_line(a: &Adaptive, max: u32, report: &meshrefine::lod::LevelReport) -> String {
    let histogram = match report.histogram_line() {
        h if h.is_empty() => "none".to_string(),
        h => h,
    };
    format!(
        "adaptive at {} px, max level {max}: levels (level:elements) {histogram}; culled {}",
        super::adaptive::px(a.pixel_error),
        report.culled
    )
}

/// The note that an image drawn adaptively by default is drawn at `level` instead, and why.
fn uniform_instead(level: u32, why: &str) {
    note(format_args!(
        "note: drawing uniformly at level {level} (the default --level): {why}"
    ));
}

/// How `render` and the headless `view` draw their image.
pub struct ImageOptions<'a> {
    /// Width and height in pixels.
    pub size: (u32, u32),
    /// The wireframe drawn over the surface, if any.
    pub wireframe: Option<Wireframe>,
    /// What the image shows, on what.
    pub view: View,
    pub background: Background,
    /// Samples per pixel (`None`: the default, `gpu::sample_count`).
    pub msaa: Option<u32>,
    /// Draw adaptively for the camera (`--pixel-error`, or by default).
    pub adaptive: Option<Adaptive<'a>>,
    /// The camera (`--eye`, `--look-at`, `--fov`), adaptive or uniform.
    pub viewpoint: &'a ViewpointOpts,
}

/// Renders `input` (centred and at unit size, see [`Mesh::for_viewing`]) to a PNG as `image`
/// says, adaptively when it says so (then returns the line saying what it chose). A blank image is still
/// written, then reported as an error: it shows nothing.
///
/// [`Mesh::for_viewing`]: meshrefine::mesh::Mesh::for_viewing
pub fn render_png(
    ctx: Arc<Context>,
    input: Input,
    cfg: &DrawConfig,
    opts: &ImageOptions<'_>,
    out: &Path,
) -> Result<Option<String>> {
    let (width, height) = opts.size;
    let (wireframe, msaa, adaptive) = (opts.wireframe, opts.msaa, opts.adaptive);
    let triangles = input.mesh.triangles.len();
    let samples = sample_count(&ctx, msaa)?;
    let mut line = None;
    // The elements culled when the level pass culled every one (nothing was drawn).
    let mut culled_all = None;
    // Whether the level pass culled any element.
    let image = (|| -> Result<_> {
        let mut cfg = *cfg;
        let uniform_level = cfg.level;
        if let Some(a) = &adaptive {
            cfg.level = a.max_level(&ctx, cfg.driver)?;
            cfg.geomorph = a.geomorph;
        }
        let mut h = Headless::multisampled(ctx, width, height, samples)?;
        h.wireframe = wireframe.is_some_and(Wireframe::refined);
        h.cage = wireframe.is_some_and(Wireframe::cage);
        h.view = opts.view;
        h.background = opts.background;
        let (mesh, mut viewed) = for_viewing(&input.mesh, &cfg);
        let mut scene = h.scene(mesh, cfg.level)?;
        apply_surface_inputs(&h, &mut scene, &input)?;
        // Prepared (for adaptive frames when drawing adaptively: `static` refines nothing yet)
        // so that the framing sees the surface drawn: Loop's limit surface from its M1 faces.
        h.adaptive = adaptive.is_some();
        if adaptive.is_some() {
            // Adaptive frames are not all at the largest level: they warn from the levels
            // chosen (below).
            scene.skip_slow_warning();
        }
        h.prepared_elements(&mut scene, &viewed, Capture::None)?;
        let (centre, scale) = input.mesh.viewing_transform();
        let frame = Frame { centre, scale };
        // The camera fitted to the surface as drawn, moved where the options ask.
        let uniform_camera = |scene: &meshrefine::render::Scene, viewed: &DrawConfig| {
            let framing = scene.framing_points(viewed);
            (opts.viewpoint).camera(&framing, width as f32 / height as f32, &frame)
        };
        let mut camera = uniform_camera(&scene, &viewed)?;
        // The triangles of a frame drawn as chosen below, for the slow-frame warning, and what
        // draws faster.
        let mut slow = None;
        // The levels chosen, for the notes on an unmet pixel error once they are drawn.
        let mut chosen = None;
        if let Some(a) = &adaptive {
            let size = (width, height);
            let (cam, mut report) =
                a.set_up(&mut h, &mut scene, &viewed, Capture::None, size, &frame)?;
            camera = cam;
            if let Some(fits) = a.lower_to_fit(
                &mut h,
                &mut scene,
                &viewed,
                Capture::None,
                camera,
                size,
                &report,
            )? {
                (viewed, report) = fits;
            }
            line = Some(levels_line(a, cfg.level, &report));
            let drawn = report
                .triangles_on(|l| viewed.driver.refined_per_element(l))
                .0;
            let weight = scene.evaluation_weight(&viewed, Some(&report));
            slow = Some((drawn, weight, report.faster()));
            culled_all =
                (report.histogram.is_empty()).then_some((report.culled, report.facing_away));
            chosen = Some(report);
        }
        let refusal = (adaptive)
            .map(|_| cannot_adapt(&mut h, &mut scene, &viewed, Capture::None))
            .transpose()?
            .flatten();
        if let Some(why) = refusal
            .as_ref()
            .filter(|_| adaptive.is_some_and(|a| !a.by_default))
        {
            // Asked for: refused in one sentence, before any warning that frames are slow.
            bail!("{why}");
        }
        if let (Some(a), Some(report), None) = (&adaptive, &chosen, &refusal) {
            a.note_unmet(&viewed, report);
        }
        if let Some(why) = refusal {
            uniform_instead(uniform_level, &why);
            h.adaptive = false;
            line = None;
            viewed.level = uniform_level;
            culled_all = None;
            let elements = scene.elements(viewed.surface).element_count as u64;
            let refined = elements * viewed.refined_per_element() as u64;
            let weight = scene.evaluation_weight(&viewed, None);
            slow = Some((refined, weight, "a lower --level draws faster"));
            camera = uniform_camera(&scene, &viewed)?;
        }
        if let Some((refined, weight, advice)) = slow {
            scene.warn_if_slow(refined, weight, advice);
        }
        Ok(h.render(&mut scene, &viewed, &camera)?)
    })()
    .with_context(|| format!("cannot render '{}'", input.shown))?;
    image
        .save_png(out)
        .with_context(|| format!("cannot write '{}'", out.display()))?;
    if covered_pixels_on(&image, opts.background) == 0 {
        // The default camera frames the surface as drawn, displacement included: only a camera
        // given on the command line can look past it.
        // A field of view other than the default names itself: at 179° the mesh is a speck.
        let fov = &opts.viewpoint.fov;
        let at_fov = if fov.value != 45.0 {
            format!(" at --fov {}", fov.text)
        } else {
            String::new()
        };
        // The options that placed the camera, as given.
        let v = opts.viewpoint;
        let given = match (v.eye.is_some(), v.look_at.is_some()) {
            (true, true) => "--eye and --look-at",
            (true, false) => "--eye",
            _ => "--look-at",
        };
        // The default eye stays clear of the surface: only an --eye given can come nearer it
        // than the near plane.
        let near = if v.eye.is_some() {
            ", or nearer the eye than the near plane"
        } else {
            ""
        };
        let camera = if v.placed() {
            format!("the camera given by {given} sees none of them, or each is much smaller than a pixel there{at_fov}, or seen edge-on{near}")
        } else {
            format!("each is much smaller than a pixel when the whole mesh is framed{at_fov}, or seen edge-on")
        };
        // Culling draws nothing visible away (docs/adaptivity.md, "Culling"): --cull off would
        // give the same blank image, so it is not suggested.
        let why = match culled_all {
            Some((n, away)) => {
                let facing = match away {
                    0 => String::new(),
                    a => format!(", or they face away from the eye ({a} of them)"),
                };
                // Loop's elements are M1's faces, four to a triangle: named, beside the
                // triangle count the sentence gives.
                let elements = match cfg.surface.facts().elements {
                    meshrefine::surface::Elements::CoarseTriangles => "elements",
                    meshrefine::surface::Elements::LoopFaces => {
                        "elements (M1's faces, four to a triangle)"
                    }
                };
                if v.placed() {
                    format!("culling removed all {n} {elements}: the camera given by {given} sees none of them{facing}")
                } else {
                    format!("culling removed all {n} {elements}, outside the view{facing}")
                }
            }
            None => camera,
        };
        // A few pixels' samples can all miss a mesh that covers most of them (not one culled
        // away whole: nothing was drawn).
        let why = if width.min(height) <= 4 && samples.as_raw() > 1 && culled_all.is_none() {
            format!("{why}; or its {} samples per pixel all miss the mesh: --msaa 1 samples each pixel's centre", samples.as_raw())
        } else {
            why
        };
        // What adaptive drawing chose is said first, as for an image that shows the mesh.
        if let Some(line) = &line {
            out!("{line}");
        }
        bail!(
            "'{}' is blank: no pixel of the {width}x{height} image shows any of the {triangles} triangle(s) of '{}' ({why})",
            out.display(),
            input.shown
        );
    }
    Ok(line)
}
