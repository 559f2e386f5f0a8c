//! `meshrefine bench`: every driver and submission mode timed on one mesh, the table printed
//! and optionally written as markdown, CSV and JSON.
#![forbid(unsafe_code)]

use super::adaptive::Frame;
use super::args::BenchArgs;
use super::args::ViewpointOpts;
use super::input::{for_viewing, load_mesh, split_three_creases};
use super::with_context;
use anyhow::{bail, Context as _, Result};
use meshrefine::bench::BenchCamera;
use meshrefine::gpu::ContextDesc;
use meshrefine::render::{DrawConfig, Driver, RenderError};
use meshrefine::surface::{Displace, Heightmap};
use std::io::Write as _;

/// Runs `meshrefine bench` with `a` (`levels_given`: `--levels` was on the command line; with
/// `--pixel-error` only those uniform levels are timed beside the adaptive rows).
pub fn run(a: &BenchArgs, desc: &ContextDesc, levels_given: bool) -> Result<()> {
    // A value given twice in a list is timed once (as drivers are).
    let (levels, surfaces, displacements) = (
        dedup(&a.levels),
        dedup(&a.surfaces),
        dedup(&a.displacements),
    );
    (a.min_total_ms)
        .check(
            "min-total-ms",
            Some((0.0, f32::MAX, "a finite number >= 0")),
        )
        .map_err(anyhow::Error::msg)?;
    let every_face = surfaces.iter().any(|s| s.facts().needs_every_face);
    let mut input = load_mesh(a.mesh.as_deref(), every_face)?;
    if surfaces.iter().any(|s| s.facts().tags) {
        // As render does: every surface is then timed on the same, split, mesh.
        split_three_creases(&mut input, None)?;
    }
    // A surface and displacement that cannot go together (the height map without texture
    // coordinates) are refused before anything is timed, as render refuses them.
    let texcoords = input.mesh.triangles.iter().all(|t| t.t.is_some());
    for (&s, &d) in surfaces
        .iter()
        .flat_map(|s| displacements.iter().map(move |d| (s, d)))
    {
        if let Some(why) = s.incompatibility_on(d, &input.mesh, texcoords) {
            // Where the mesh could take the displacement with another surface, the remedy is
            // the lists' (render's, which the sentence ends with, is another displacement).
            let why = match why.strip_suffix(" (use sine or noise)") {
                Some(stem) if texcoords => format!(
                    "{stem} (leave {} out of --surfaces, or {} out of --displacements)",
                    s.name(),
                    d.name()
                ),
                _ => why,
            };
            bail!("cannot benchmark '{}': {why}", input.shown);
        }
    }
    let (mesh, _) = for_viewing(&input.mesh, &DrawConfig::new(Driver::default(), 1));
    let (centre, scale) = input.mesh.viewing_transform();
    let params = a
        .params
        .params_for(&input.mesh, &displacements)
        .map_err(anyhow::Error::msg)?
        .in_drawn_frame(centre, scale);
    let surfaces = surfaces
        .iter()
        .flat_map(|&s| displacements.iter().map(move |&d| (s, d)))
        .collect();
    let opts = meshrefine::bench::BenchOptions {
        levels,
        surfaces,
        params: Some(params),
        build: a.params.build().map_err(anyhow::Error::msg)?,
        frames: a.frames,
        width: a.width,
        height: a.height,
        // `pattern` stands for its three submission modes; adaptively every driver (static
        // refines on the CPU when the levels change).
        drivers: Driver::VARIANTS
            .into_iter()
            .filter(|v| {
                let all = a.drivers.is_empty() && a.adaptive.pixel_error.is_some();
                all || a.drivers.iter().any(|d| d.same_kind(*v))
            })
            .collect(),
        min_total_ms: a.min_total_ms.value as f64,
        camera: BenchCamera::default(),
        adaptive: None,
        view: a.view,
        heightmap: match &a.heightmap {
            Some(path) if displacements.contains(&Displace::Heightmap) => {
                Some(Heightmap::load_png(path).map_err(anyhow::Error::msg)?)
            }
            _ => None,
        },
    };
    let adaptive = a.adaptive.enabled(true);
    // Drawn centred and at unit size, like `render`: the timings do not change.
    let mut mesh = mesh;
    mesh.name = input.mesh.name.clone();
    let scene_frame = Frame { centre, scale };
    // Render's default camera: fitted to each surface x displacement as drawn, at --fov, moved
    // to --eye and --look-at where given.
    super::adaptive::check_distance(&a.adaptive.viewpoint, &scene_frame)?;
    let viewpoint = a.adaptive.viewpoint.drawn(&scene_frame);
    // Each surface x displacement has its own fitted camera: a refusal says whose.
    let several = opts.surfaces.len() > 1;
    let report = with_context(desc, |ctx| {
        let mut opts = opts;
        opts.camera = BenchCamera::Fitted(viewpoint);
        if let Some(ad) = &adaptive {
            // Each variant adaptive up to the largest level (a power of two when the pattern or
            // static driver is measured: its largest level), seen by the camera asked for, and uniform
            // at the levels it is compared with.
            if !levels_given {
                opts.levels.clear();
            }
            // The first driver measured whose levels are powers of two, else the first (never
            // none: adaptively every driver is measured unless some are named).
            let driver = (opts.drivers.iter().copied())
                .min_by_key(|d| d.kind().integer_levels())
                .unwrap_or_default();
            opts.adaptive = Some(meshrefine::bench::BenchAdaptive {
                scene: String::new(),
                cameras: Vec::new(),
                pixel_error: ad.pixel_error,
                cull: ad.cull,
                max_level: ad.max_level(&ctx, driver).map_err(|e| {
                    if a.drivers.is_empty() && e.to_string().contains("not a power of two") {
                        anyhow::anyhow!("{e} (bench measures every driver unless --drivers names some: --drivers tess takes any level)")
                    } else {
                        e
                    }
                })?,
                bound_levels: !a.no_bound_levels,
                geomorph: ad.geomorph,
            });
        }
        meshrefine::bench::run(ctx, &[mesh], &opts)
            .map_err(|e| no_direction(e, &a.adaptive.viewpoint, &scene_frame, several))
            .with_context(|| format!("cannot benchmark '{}'", input.shown))
    })?;
    // The cameras as `--eye`, `--look-at` and `--fov` take them: the values given, exactly, and
    // the fitted camera's mapped back to mesh coordinates.
    let mut report = report;
    let v = &a.adaptive.viewpoint;
    for shot in report.cameras.iter_mut().flat_map(|c| c.shots.iter_mut()) {
        let eye = v.eye().unwrap_or(scene_frame.mesh(shot.eye).to_array());
        let target = v
            .look_at()
            .unwrap_or(scene_frame.mesh(shot.target).to_array());
        shot.eye = eye.into();
        shot.target = target.into();
        shot.fov_y_degrees = v.fov.value;
    }
    report.camera_space = "in the mesh's own coordinates, as the options take them".into();
    if let Some(prefix) = &a.out {
        let command = super::command_line();
        if let Err(e) = report.write_files(prefix, &command) {
            // The measurements are not lost: the summary first (no word of where the full
            // table is), then why the files are not written.
            out!("{}", report.summary_table());
            return Err(e).with_context(|| {
                format!(
                    "cannot write the results to {}.{{md,csv,json}}",
                    prefix.display()
                )
            });
        }
    }
    out!("{}", report.summary(a.out.as_deref()));
    if let Some(prefix) = &a.out {
        out!(
            "wrote {}.{{md,csv,json}}",
            crate::printable(&prefix.display().to_string())
        );
    }
    // A run that timed nothing measured nothing: its rows say why, and it fails.
    let timed = report
        .rows
        .iter()
        .any(|r| r.gpu_ms.is_some() || r.wall_ms.is_some());
    if !timed {
        let why = (report.rows.iter())
            .find_map(|r| r.note.strip_prefix("not drawn: "))
            .unwrap_or("no variant was drawn");
        bail!(
            "nothing was measured on '{}': no variant could be drawn ({why})",
            input.shown
        );
    }
    Ok(())
}

/// `list` without its repeated values, in the order first given.
fn dedup<T: PartialEq + Copy>(list: &[T]) -> Vec<T> {
    let mut out: Vec<T> = Vec::with_capacity(list.len());
    for &x in list {
        if !out.contains(&x) {
            out.push(x);
        }
    }
    out
}

/// A camera without a view direction named as `render` names it: `--eye` and `--look-at` as
/// typed, the fitted camera's eye or target where one was not given (mesh coordinates), and
/// then, where several surfaces or displacements are timed, which one's fitted camera it was.
fn no_direction(e: RenderError, v: &ViewpointOpts, frame: &Frame, several: bool) -> anyhow::Error {
    let RenderError::NoViewDirection {
        surface,
        eye,
        target,
    } = e
    else {
        return e.into();
    };
    let sentence = v.no_direction(frame.mesh(eye), frame.mesh(target));
    // Both given: no fitted camera is in the sentence.
    if several && (v.eye.is_none() || v.look_at.is_none()) {
        anyhow::anyhow!("{sentence} (the camera fitted to {surface})")
    } else {
        anyhow::anyhow!("{sentence}")
    }
}
