//! `meshrefine view`: the window demo, or, where no display exists, one frame rendered
//! headlessly to a PNG (which says why).
#![forbid(unsafe_code)]

use super::adaptive::Frame;
use super::args::ViewArgs;
use super::input::{attach_surface_inputs, draw_config, for_viewing, load_mesh};
use super::loop_check::loop_refusal;
use super::options::Given;
use super::render::render_png;
use super::{check_messages, require_extension, with_context};
use anyhow::{Context as _, Result};
use meshrefine::gpu::ContextDesc;
use std::io::Write as _;

/// Runs `meshrefine view` with `a` (`given`: the options given on the command line).
pub fn run(a: &ViewArgs, desc: &ContextDesc, given: &Given) -> Result<()> {
    if let Some(shot) = &a.screenshot {
        require_extension(shot, "png", "screenshots are PNG images")?;
    }
    require_extension(
        &a.headless_output,
        "png",
        "the headless view writes a PNG image",
    )?;
    let for_loop = a.technique.surface.surface.facts().needs_every_face;
    let mut input = load_mesh(a.mesh.as_deref(), for_loop)?;
    if input.loop_refusal.is_none() && a.mesh.is_some() {
        // The panel can switch to loop later: say then, in the file's terms, why not.
        input.loop_refusal = loop_refusal(&input.shown, &input.mesh, &input.report, true);
    }
    let mut cfg = draw_config(&a.technique, &input.mesh)?;
    // The window is adaptive by default: it glides vertices unless --geomorph off.
    cfg.geomorph = a.adaptive.geomorph.unwrap_or(true);
    attach_surface_inputs(&mut input, &a.technique.surface, true)?;
    // An empty variable names no display, as an unset one.
    let vars = ["DISPLAY", "WAYLAND_DISPLAY"].map(std::env::var_os);
    let has_display = vars.iter().flatten().any(|v| !v.is_empty());
    let unset = if vars.iter().any(Option::is_some) {
        "unset or empty"
    } else {
        "unset"
    };
    let connected = has_display.then(meshrefine::app::connect);
    let why_headless = if let Some(Ok(event_loop)) = connected {
        // Only the window reads it: without a display, or one that cannot be reached, it is
        // ignored with the others below.
        if let Some(dir) = &a.screenshot_dir {
            if !dir.is_dir() {
                anyhow::bail!(
                    "--screenshot-dir '{}' is not a directory (the screenshot key writes meshrefine-<n>.png there)",
                    dir.display()
                );
            }
        }
        let (mesh, viewed) = for_viewing(&input.mesh, &cfg);
        let (centre, scale) = input.mesh.viewing_transform();
        // The window's pattern and static drivers draw adaptively up to a power of two (render
        // refuses another), tess the level as given but without gliding: said whichever the
        // window starts with, as the keys switch drivers.
        if let Some(m) = a.adaptive.max_level.filter(|m| !m.is_power_of_two()) {
            crate::note(format_args!(
                "warning: --max-level {m} is not a power of two: the pattern and static drivers draw adaptively up to {}, tess up to {m} (or its device's limit) without geomorphing",
                1u32 << m.ilog2()
            ));
        }
        let opts = meshrefine::app::ViewOptions {
            cfg: viewed,
            frames: a.frames,
            screenshot: a.screenshot.clone(),
            wireframe: a.wireframe.is_some_and(|w| w.refined()),
            cage: a.wireframe.is_some_and(|w| w.cage()),
            animate: a.animate,
            lod: a.lod,
            submit: a.technique.submit(),
            heightmap: input.heightmap.clone(),
            tags: input.tags.clone(),
            loop_refusal: input.loop_refusal.clone(),
            source: input.shown.clone(),
            frame_budget: !a.no_frame_budget,
            msaa: a.msaa,
            size: (a.width, a.height),
            fullscreen: a.fullscreen,
            panel: !a.hide_panel,
            background: a.background,
            view: a.view,
            screenshot_dir: a.screenshot_dir.clone(),
            viewing: (centre, scale),
            adaptive: {
                // Adaptive mode by default; `--level` or `--lod` start uniform.
                let ad = super::adaptive::Adaptive {
                    opts: &a.adaptive,
                    pixel_error: (a.adaptive.pixel_error.as_ref())
                        .map_or(meshrefine::app::DEFAULT_PIXEL_ERROR, |p| p.value),
                    cull: a.adaptive.cull.unwrap_or(true),
                    geomorph: a.adaptive.geomorph.unwrap_or(true),
                    by_default: a.adaptive.pixel_error.is_none(),
                };
                meshrefine::app::AdaptiveView {
                    on: !(given.has("level") || a.lod),
                    pixel_error: ad.pixel_error,
                    cull: ad.cull,
                    viewpoint: {
                        let frame = Frame { centre, scale };
                        super::adaptive::check_distance(&a.adaptive.viewpoint, &frame)?;
                        a.adaptive.viewpoint.drawn(&frame)
                    },
                    max_level: ad.opts.max_level,
                }
            },
        };
        return match meshrefine::app::run(event_loop, desc.clone(), mesh, opts) {
            Ok(messages) => check_messages(&messages),
            Err(e) => Err(e.context(format!("cannot show '{}'", input.shown))),
        };
    } else if let Some(Err(no_window)) = connected {
        no_window.to_string()
    } else {
        format!("no display found (DISPLAY and WAYLAND_DISPLAY are {unset})")
    };
    // What only a window reads: one warning naming them.
    let window_only: Vec<&str> = [
        "frames",
        "animate",
        "fullscreen",
        "hide_panel",
        "no_frame_budget",
        "screenshot_dir",
    ]
    .into_iter()
    .filter(|id| given.has(id))
    .collect();
    if !window_only.is_empty() {
        let names: Vec<String> = (window_only.iter())
            .map(|id| format!("--{}", id.replace('_', "-")))
            .collect();
        crate::note(format_args!(
            "warning: {} {} only to the window and {} ignored: {why_headless}",
            names.join(", "),
            if names.len() == 1 { "applies" } else { "apply" },
            if names.len() == 1 { "is" } else { "are" }
        ));
    }
    // `--lod` starts the window choosing one level by distance as its camera moves (not
    // adaptive): the one image is drawn uniformly at --level, and says so.
    let uniform = given.has("level") || a.lod;
    if a.lod {
        crate::note(format_args!(
            "warning: --lod chooses levels by distance only in the window: {why_headless}, so the image is drawn uniformly at --level {}",
            a.technique.level
        ));
    }
    // No panel switches to what an option applies to: warned about as render warns.
    let asked = (uniform, "--level or --lod");
    for w in super::options::drawn_image(given, &a.technique, &a.adaptive, asked) {
        crate::note(format_args!("warning: {w}"));
    }
    let image = super::render::ImageOptions {
        size: (a.width, a.height),
        wireframe: a.wireframe,
        view: a.view,
        background: a.background,
        msaa: a.msaa,
        // Adaptive by default as the window is; `--level` or `--lod` draw uniformly.
        adaptive: (a.adaptive).or_default(uniform),
        viewpoint: &a.adaptive.viewpoint,
    };
    // No window: the image will be written, so it must be writable before anything is drawn.
    let output = meshrefine::paths::Output::File;
    meshrefine::paths::check_output(&a.headless_output, "--headless-output", output)
        .map_err(anyhow::Error::msg)?;
    let line = with_context(desc, |ctx| {
        render_png(ctx, input, &cfg, &image, &a.headless_output)
    })?;
    if let Some(line) = line {
        out!("{line}");
    }
    let shown = std::fs::canonicalize(&a.headless_output).unwrap_or(a.headless_output.clone());
    out!(
        "{why_headless}: rendered the scene headlessly to {}",
        crate::printable(&shown.display().to_string())
    );
    // The last frame asked for: the one frame drawn.
    if let Some(shot) = &a.screenshot {
        // Not onto itself: copying a file to its own path empties it.
        let same = std::fs::canonicalize(shot).is_ok_and(|s| s == shown);
        if !same {
            let image = std::fs::read(&a.headless_output)?;
            meshrefine::paths::write_output(shot, |w| w.write_all(&image))
                .with_context(|| format!("cannot write the screenshot '{}'", shot.display()))?;
        }
        out!(
            "wrote the screenshot {}",
            crate::printable(&shot.display().to_string())
        );
    }
    Ok(())
}
