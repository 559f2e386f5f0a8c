//! Adaptive rows ([`BenchOptions::adaptive`]): each variant drawn with every element at the
//! levels its view asks for, against the same variant drawn uniformly, in the same run. For each
//! camera the frames go round the adaptive and uniform configurations in turn (one warm-up frame
//! each first); before each adaptive frame the level pass runs once alone, timed with
//! timestamps (`level_pass_ms`; every frame runs it again before its draws, inside its GPU
//! time), the uniform ones draw every element at their level (no culling). With
//! several cameras (a path) a row's figures are the means over the cameras of each camera's
//! medians. Timings are measured, never asserted.
#![forbid(unsafe_code)]

use super::{new_row, variants, AdaptiveCells, BenchAdaptive, BenchOptions, MeshSetup, Row, Stat};
use crate::lod::LevelReport;
use crate::mesh::Mesh;
use crate::pattern::PatternSet;
use crate::render::{Camera, DrawConfig, Headless, LevelView, RenderError};
use std::collections::BTreeMap;
use std::time::Instant;

/// One configuration timed on every camera.
struct Timed {
    row: Row,
    cfg: DrawConfig,
    adaptive: bool,
    drawn: bool,
    /// Per camera: the timed frames' GPU and wall milliseconds, and (adaptive) the
    /// milliseconds choosing the levels before each.
    gpu: Vec<Vec<f64>>,
    wall: Vec<Vec<f64>>,
    choose: Vec<Vec<f64>>,
    /// Where the levels were made: "gpu" (the level pass) or "cpu" (uploaded, or the static
    /// driver's, which needs no level pass).
    pass_on: &'static str,
    /// The static driver drawn adaptively: per camera, each timed frame's milliseconds
    /// refining and uploading, and bytes uploaded.
    refine: Vec<Vec<f64>>,
    upload: Vec<Vec<f64>>,
    /// Adaptive: what each camera's levels were.
    reports: Vec<LevelReport>,
}

/// Every variant of `opts` on `mesh`, adaptive at `a`'s views and uniform at the levels it is
/// compared with.
pub(super) fn run(
    ctx: &crate::gpu::Context,
    h: &mut Headless,
    mesh: &Mesh,
    opts: &BenchOptions,
    a: &BenchAdaptive,
) -> Result<(Vec<Row>, Vec<super::ViewUsed>), RenderError> {
    // Every level a uniform row may draw has its pattern uploaded (the scene checks it whatever
    // the driver): the levels asked for, the powers of two up to the largest level's, and every
    // level up to 128 (the tessellator's bounds are integers).
    let mut levels = opts.levels.clone();
    levels.extend(PatternSet::up_to(a.max_level.next_power_of_two()).levels());
    levels.extend(1..=a.max_level.min(128));
    let setup = BenchOptions {
        levels,
        ..opts.clone()
    };
    let mut m = MeshSetup::new(h, mesh, &setup)?;
    let mut rows = Vec::new();
    for cfg in variants(
        &m.surfaces,
        a.max_level,
        m.params,
        opts.build,
        &opts.drivers,
    ) {
        rows.extend(variant(ctx, h, &mut m, cfg, opts, a)?);
        m.scene.static_vbo = None;
    }
    h.adaptive = false;
    Ok((rows, m.views_used(&a.cameras)))
}

/// One variant: its adaptive row, then its uniform rows, drawn from `a`'s cameras, or where it
/// names none from [`BenchOptions::camera`] (by default fitted to the variant's surface x
/// displacement as drawn, at its largest level: render's default camera).
fn variant(
    ctx: &crate::gpu::Context,
    h: &mut Headless,
    m: &mut MeshSetup,
    cfg: DrawConfig,
    opts: &BenchOptions,
    a: &BenchAdaptive,
) -> Result<Vec<Row>, RenderError> {
    let view = |camera: Camera| LevelView {
        camera,
        width: opts.width,
        height: opts.height,
        pixel_error: a.pixel_error,
        cull: a.cull,
    };
    // The adaptive frame glides its vertices as asked; uniform frames have nothing to glide.
    let adaptive_cfg = DrawConfig {
        geomorph: a.geomorph,
        ..cfg
    };
    let mut first = timed(ctx, h, m, adaptive_cfg, true, "view".into(), a)?;
    // Fitted to the surface as prepared (loop's limit surface from its M1 faces).
    let cameras = if a.cameras.is_empty() {
        vec![m.camera(&cfg, opts)?]
    } else {
        a.cameras.clone()
    };
    let cameras = &cameras[..];
    let check = |m: &MeshSetup, c: &DrawConfig| c.driver.kind().check_adaptive(ctx, &m.scene, c);
    if first.drawn {
        if let Err(e) = check(m, &adaptive_cfg) {
            // As render draws it: up to the largest level the cameras' levels reach (the same
            // levels), where that fits.
            let mut reached = None;
            for &c in cameras {
                let chosen = m.scene.set_levels(&adaptive_cfg, &view(c))?;
                reached = reached.max(chosen.report().histogram.keys().max().copied());
            }
            let lowered = reached.and_then(|l| adaptive_cfg.lowered_to(l));
            match lowered.filter(|l| check(m, l).is_ok()) {
                Some(l) => {
                    first = timed(ctx, h, m, l, true, "view".into(), a)?;
                    let note = format!(
                        "drawn up to level {}, the largest its levels reach (up to --max-level {} the device cannot draw it adaptively)",
                        l.level, adaptive_cfg.level
                    );
                    if first.drawn {
                        first.row.note = note;
                    }
                }
                None => {
                    first.row.note = format!("not drawn: {e}");
                    first.drawn = false;
                }
            }
        }
    }
    // The smallest uniform level meeting the bound on every camera (any integer: a uniform
    // frame has no transitions to round for); none where the adaptive frame cannot be drawn
    // (its levels are not chosen): then only the levels asked for are timed.
    let mut bound = first.drawn.then_some(1);
    // Whether the largest level keeps some element's own bounds from being met: the bound's
    // uniform level is then the largest, which does not meet it either.
    let mut unmet = crate::lod::frame::Unmet::default();
    if let Some(b) = &mut bound {
        for &c in cameras {
            let chosen = m.scene.set_levels(&cfg, &view(c))?;
            *b = (*b).max(chosen.uniform_level);
            let u = &chosen.report().unmet;
            unmet.near += u.near;
            unmet.unbounded += u.unbounded;
            unmet.beyond_uniform += u.beyond_uniform;
        }
    }
    if unmet.uniform_unmet() {
        // The bound's row is in the table unless --no-bound-levels.
        let (level, row) = (
            bound.unwrap_or(cfg.level),
            if a.bound_levels { " (bound)" } else { "" },
        );
        let note = format!(
            "the bound is not met on every element{}: uniform {level}{row} does not meet it either",
            why_unmet(&unmet, cfg.level)
        );
        add_note(&mut first.row, note);
    }
    if let Some(b) = bound.filter(|b| a.bound_levels && b.next_power_of_two() > a.max_level) {
        let note = format!(
            "uniform {} (pow2, the power of two at or above the bound's {b}) is above --max-level {}: not timed",
            b.next_power_of_two(),
            a.max_level
        );
        add_note(&mut first.row, note);
    }
    let mut list = vec![first];
    for (level, from) in uniform_levels(opts, a, bound) {
        let cfg = DrawConfig { level, ..cfg };
        list.push(timed(ctx, h, m, cfg, false, from.join("+"), a)?);
    }
    let frames = opts.frames.max(1) as usize;
    let enough = |t: &Timed| {
        let gpu = t.gpu.last().map_or(&[][..], |g| &g[..]);
        !t.drawn
            || (gpu.len() >= frames
                && (gpu.iter().sum::<f64>() >= opts.min_total_ms || gpu.len() >= 20 * frames))
    };
    for &camera in cameras {
        for t in &mut list {
            t.gpu.push(Vec::new());
            t.wall.push(Vec::new());
            t.choose.push(Vec::new());
            t.refine.push(Vec::new());
            t.upload.push(Vec::new());
        }
        // Round 0 is every configuration's warm-up frame at this camera.
        let mut round = 0;
        while round == 0 || !list.iter().all(enough) {
            for t in list.iter_mut().filter(|t| t.drawn) {
                match frame(h, m, t, &camera, &view(camera), round) {
                    Ok(()) => {}
                    // What the device cannot hold of the levels chosen (the static driver's
                    // mesh refined for them, known only once they are): not drawn, as a level
                    // it refuses, and the other rows are still timed.
                    Err(e @ RenderError::OverLimit { .. }) => {
                        m.scene.static_vbo = None;
                        let said = std::mem::take(&mut t.row.note);
                        t.row.note = format!("not drawn: {e}");
                        add_note(&mut t.row, said);
                        t.drawn = false;
                    }
                    Err(e) => return Err(e),
                }
            }
            round += 1;
        }
    }
    h.adaptive = false;
    Ok(into_rows(list, cameras.len(), frames))
}

/// A ratio with two decimals, or two significant digits below 0.01 (0.00016, not 0.00).
fn ratio(x: f64) -> String {
    if x > 0.0 && x < 0.01 {
        let digits = (1 - x.log10().floor() as i32) as usize;
        format!("{x:.digits$}")
    } else {
        format!("{x:.2}")
    }
}

/// Why no level up to `max` meets the bound on every element: what the note of an adaptive row
/// says after "the bound is not met on every element" (" up to --max-level 64", then which
/// elements no level helps, in parentheses).
fn why_unmet(u: &crate::lod::frame::Unmet, max: u32) -> String {
    let mut fixed = Vec::new();
    if u.near > 0 {
        fixed.push("elements holding the eye in their bounds");
    }
    if u.unbounded > 0 {
        fixed.push("elements with no finite bound");
    }
    let capped = if u.beyond_uniform > 0 {
        format!(" up to --max-level {max}")
    } else {
        String::new()
    };
    match fixed.is_empty() {
        true => capped,
        false => format!("{capped} ({}, at any level)", fixed.join(" and ")),
    }
}

/// The uniform levels timed beside the adaptive frame, each with what asked for it: the
/// `--levels` given, and the bound's level and its power of two (unless above the largest
/// level: the adaptive row's note says so).
fn uniform_levels(
    opts: &BenchOptions,
    a: &BenchAdaptive,
    bound: Option<u32>,
) -> Vec<(u32, Vec<&'static str>)> {
    let mut uniform: Vec<(u32, Vec<&str>)> = Vec::new();
    let mut add = |level: u32, from: &'static str| match uniform.iter_mut().find(|u| u.0 == level) {
        Some(u) => u.1.push(from),
        None => uniform.push((level, vec![from])),
    };
    for &l in &opts.levels {
        add(l, "levels");
    }
    if let Some(bound) = bound.filter(|_| a.bound_levels) {
        add(bound, "bound");
        if bound.next_power_of_two() <= a.max_level {
            add(bound.next_power_of_two(), "pow2");
        }
    }
    uniform
}

/// One frame of configuration `t` at `camera` (round 0: its warm-up, not recorded): the levels
/// chosen for an adaptive one (the level pass timed alone), then the frame drawn and timed.
fn frame(
    h: &mut Headless,
    m: &mut MeshSetup,
    t: &mut Timed,
    camera: &Camera,
    view: &LevelView,
    round: u32,
) -> Result<(), RenderError> {
    let chose = if t.adaptive {
        let start = Instant::now();
        let report = m.scene.set_levels(&t.cfg, view)?;
        let cpu_ms = start.elapsed().as_secs_f64() * 1e3;
        if round == 0 {
            let first = t.reports.is_empty();
            let weight = first.then(|| m.scene.evaluation_weight(&t.cfg, Some(&report)));
            let report = report.into_report();
            // Counted from the levels chosen (its prepare, at the largest level, did not warn).
            if t.reports.is_empty() {
                let refined = drawn_triangles(&t.cfg, &report);
                m.scene
                    .warn_once_if_slow(refined, weight.flatten(), report.faster());
            }
            t.reports.push(report);
        }
        // The level pass on the GPU, timed alone (each frame runs it again before
        // its draws); the CPU's time where the levels were uploaded instead.
        match h.time_level_pass(&m.scene, &t.cfg)? {
            Some(gpu_ms) => {
                t.pass_on = "gpu";
                Some(gpu_ms)
            }
            None => {
                t.pass_on = "cpu";
                Some(cpu_ms)
            }
        }
    } else {
        None
    };
    h.adaptive = t.adaptive;
    let refines = t.adaptive && t.cfg.driver.kind().refines_on_cpu();
    if refines {
        // As for a moving camera, whose levels change every frame: refined and
        // uploaded again (src/render/static_adaptive.rs).
        m.scene.static_vbo = None;
    }
    let f = h.draw(&mut m.scene, &t.cfg, camera)?;
    let vbo = m.scene.static_vbo.as_ref().filter(|_| refines && round > 0);
    if let Some((v, a)) = vbo.and_then(|v| Some((v, v.adaptive.as_ref()?))) {
        t.refine.last_mut().unwrap().push(a.cpu_ms);
        t.upload.last_mut().unwrap().push(a.upload_bytes as f64);
        // What it stores is what it refined (the last camera's).
        t.row.stored_vertices = v.vertex_count as u64;
        t.row.stored_indices = v.index_count as u64;
        t.row.geometry_bytes = a.upload_bytes;
    }
    if round > 0 {
        t.row.vertex_invocations = f.stats.map(|s| s.vertex_shader_invocations);
        t.gpu.last_mut().unwrap().push(f.gpu_ms);
        t.wall.last_mut().unwrap().push(f.wall_ms);
        t.choose.last_mut().unwrap().extend(chose);
    }
    Ok(())
}

/// A configuration's row before timing; the device's refusal of its level in its note.
fn timed(
    ctx: &crate::gpu::Context,
    h: &mut Headless,
    m: &mut MeshSetup,
    cfg: DrawConfig,
    adaptive: bool,
    level_from: String,
    a: &BenchAdaptive,
) -> Result<Timed, RenderError> {
    // Prepared for the frames it times (the static driver refines nothing before levels).
    h.adaptive = adaptive;
    let (mut row, refused) = new_row(ctx, h, m, &cfg)?;
    h.adaptive = false;
    if let Some(e) = &refused {
        row.note = format!("not drawn: {e}");
    }
    row.adaptive = Some(AdaptiveCells {
        scene: a.scene.clone(),
        pixel_error: a.pixel_error,
        adaptive,
        level_from,
        ..AdaptiveCells::default()
    });
    Ok(Timed {
        row,
        cfg,
        adaptive,
        drawn: refused.is_none(),
        gpu: Vec::new(),
        wall: Vec::new(),
        choose: Vec::new(),
        pass_on: "gpu",
        refine: Vec::new(),
        upload: Vec::new(),
        reports: Vec::new(),
    })
}

/// The triangles `cfg`'s driver makes for the levels of `report`, each drawn element at its
/// inner level.
fn drawn_triangles(cfg: &DrawConfig, report: &LevelReport) -> u64 {
    report.triangles_on(|l| cfg.driver.refined_per_element(l)).0
}

/// The mean over cameras of each camera's median, the least minimum and the greatest maximum.
fn over_cameras(samples: &[Vec<f64>]) -> Option<Stat> {
    let stats: Vec<Stat> = (samples.iter())
        .filter(|s| !s.is_empty())
        .map(|s| Stat::of(s))
        .collect();
    (!stats.is_empty()).then(|| Stat {
        median: stats.iter().map(|s| s.median).sum::<f64>() / stats.len() as f64,
        min: stats.iter().map(|s| s.min).fold(f64::INFINITY, f64::min),
        max: stats
            .iter()
            .map(|s| s.max)
            .fold(f64::NEG_INFINITY, f64::max),
    })
}

/// The timed configurations' rows; the adaptive row's note compares it with the uniform rows
/// at the bound and its power of two. A row timed past `frames` (`--min-total-ms`) notes how
/// many frames it took, as the uniform benchmark's rows do.
fn into_rows(list: Vec<Timed>, cameras: usize, frames: usize) -> Vec<Row> {
    let mut rows: Vec<Row> = Vec::with_capacity(list.len());
    for t in list {
        let mut row = t.row;
        if !t.drawn {
            rows.push(row);
            continue;
        }
        row.gpu_ms = over_cameras(&t.gpu);
        row.wall_ms = over_cameras(&t.wall);
        let most = t.gpu.iter().map(Vec::len).max().unwrap_or(0);
        if most > frames {
            let timed = match cameras {
                1 => format!("{most} timed frames"),
                _ => format!("up to {most} timed frames per camera"),
            };
            // After what the row already says (the adaptive row's capped bound).
            row.note = [std::mem::take(&mut row.note), timed]
                .into_iter()
                .filter(|n| !n.is_empty())
                .collect::<Vec<_>>()
                .join("; ");
        }
        let cells = row
            .adaptive
            .as_mut()
            .expect("adaptive rows carry their cells");
        if t.adaptive {
            let n = t.reports.len().max(1) as u64;
            let per = |r: &LevelReport| drawn_triangles(&t.cfg, r);
            row.refined_triangles = (t.reports.iter().map(per).sum::<u64>() + n / 2) / n;
            let mut histogram: BTreeMap<u32, u64> = BTreeMap::new();
            for r in &t.reports {
                for (&l, &count) in &r.histogram {
                    *histogram.entry(l).or_default() += count;
                }
            }
            cells.histogram = LevelReport {
                histogram,
                ..LevelReport::default()
            }
            .histogram_line();
            let culled: u64 = t.reports.iter().map(|r| r.culled).sum();
            cells.culled_elements = Some((culled + n / 2) / n);
            cells.level_pass_ms = over_cameras(&t.choose).map(|s| s.median);
            cells.level_pass_on = Some(t.pass_on);
            cells.cpu_ms = over_cameras(&t.refine).map(|s| s.median);
            cells.upload_bytes = over_cameras(&t.upload).map(|s| s.median.round() as u64);
        }
        log::info!(
            "{} {} {} L{} ({}): {} triangles, gpu {:.2} ms",
            row.mesh,
            cells.scene,
            row.variant,
            row.level,
            cells.level_from,
            row.refined_triangles,
            row.gpu_ms.map_or(0.0, |s| s.median),
        );
        rows.push(row);
    }
    // The adaptive row (first) against the uniform rows it is measured against.
    let (first, rest) = rows
        .split_first_mut()
        .expect("a variant has its adaptive row");
    if let Some(gpu) = first.gpu_ms {
        let mut notes: Vec<String> = Some(std::mem::take(&mut first.note))
            .filter(|n| !n.is_empty())
            .into_iter()
            .collect();
        if first.refined_triangles == 0 {
            notes.push(
                "every element culled (outside the view or facing away from the eye; --cull off draws them)"
                    .to_string(),
            );
        }
        if cameras > 1 {
            notes.push(format!("means over {cameras} cameras"));
        }
        for u in rest.iter() {
            let Some(uniform) = u.gpu_ms else { continue };
            let from = u.adaptive.as_ref().map_or("", |c| c.level_from.as_str());
            let time = gpu.median / uniform.median;
            let tris = first.refined_triangles as f64 / u.refined_triangles.max(1) as f64;
            notes.push(format!(
                "{}x the triangles, {}x the GPU time of uniform {} ({from})",
                ratio(tris),
                ratio(time),
                u.level
            ));
        }
        first.note = notes.join("; ");
    }
    rows
}

/// `note` after what `row`'s note says already ("; " between).
fn add_note(row: &mut Row, note: String) {
    row.note = [std::mem::take(&mut row.note), note]
        .into_iter()
        .filter(|n| !n.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
}

#[cfg(test)]
mod tests {
    /// Ratios keep two decimals, and two significant digits where those would show 0.00.
    #[test]
    fn small_ratios_keep_two_significant_digits() {
        assert_eq!(super::ratio(0.35), "0.35");
        assert_eq!(super::ratio(12.345), "12.35");
        assert_eq!(super::ratio(0.0095), "0.0095");
        assert_eq!(super::ratio(372.0 / 2_285_568.0), "0.00016");
        assert_eq!(super::ratio(0.0), "0.00");
    }
}
