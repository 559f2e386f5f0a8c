//! The two HUDs: the overlay panel's statistics and the window title, with the same figures
//! (docs/window.md, "The overlay panel").
#![forbid(unsafe_code)]

use super::ui::{self, PanelInfo};
use super::{camera, State};
use crate::render::DrawConfig;
use std::time::Instant;

impl State {
    /// The triangles `cfg` draws from `coarse` elements: at its level, or adaptively each drawn
    /// element at its inner level.
    pub(super) fn refined(&self, cfg: &DrawConfig, coarse: u64) -> u64 {
        match &self.levels {
            Some(r) => r.triangles_on(|l| cfg.driver.refined_per_element(l)).0,
            None => coarse * cfg.refined_per_element() as u64,
        }
    }

    /// Where this frame created pipelines (`before`: how many there were) on a software
    /// device, which compiles their shaders at the first draw (seconds, for the tessellator's
    /// on lavapipe), say so in the title while it waits.
    pub(super) fn say_compiling(&self, before: usize) {
        let software = self.ctx.info.device_type == crate::gpu::vk::PhysicalDeviceType::CPU;
        if software && self.renderer.pipeline_count() > before {
            self.window.set_title(
                "meshrefine | compiling this frame's new pipelines (seconds on a software device)",
            );
        }
    }

    /// Lay out the overlay panel for this frame, with the last frame's statistics.
    pub(super) fn run_ui(&mut self) -> ui::UiFrame {
        // The levels the chosen driver draws on this device, as `+` steps through them.
        let limit = (self.controls.cfg.driver.kind().level_limit(&self.ctx.info)).map(|(m, _)| m);
        let all: Vec<u32> = self.scene.patterns.levels().collect();
        let levels = super::input::usable_levels(&all, limit);
        let device = self.ctx.info.describe();
        let d = self.drawn;
        let coarse = self.scene.elements(d.surface).element_count as u64;
        let camera = camera::camera_args(&self.camera, self.viewing);
        // A hidden panel reads no levels (they are tallied when first read).
        let shown = self.ui.visible;
        let info = PanelInfo {
            device: &device,
            levels: &levels,
            wireframe_supported: self.renderer.wireframe_supported(),
            first: self.frames == 0,
            fps: self.fps,
            gpu_ms: self.gpu_ms,
            drawn: d,
            coarse,
            refined: if shown { self.refined(&d, coarse) } else { 0 },
            geometry_bytes: self.scene.geometry_bytes(&d, self.levels.is_some()),
            upload_bytes: (self.scene).animated_upload_bytes(&d, self.levels.is_some())
                + if self.controls.cage {
                    self.scene.cage_upload_bytes()
                } else {
                    0
                },
            table_bytes: self
                .scene
                .loop_
                .as_ref()
                .filter(|_| d.surface.uses_loop_faces())
                .map(|l| l.data.table_bytes()),
            has_texcoords: self.scene.data.uvs.is_some(),
            animating: self.controls.animate,
            note: self.budget_note.as_deref(),
            mode_note: self.mode_note.as_deref(),
            adaptive_rows: (shown.then(|| self.adaptive_summary(&d)).flatten())
                .map(|a| a.rows())
                .unwrap_or_default(),
            camera: &camera,
            screenshot_note: self.screenshot_note.as_deref(),
        };
        self.ui.run(&self.window, &mut self.controls, &info)
    }

    pub(super) fn update_title(&mut self, cfg: &DrawConfig) {
        let (t0, n0) = self.fps_window;
        let dt = t0.elapsed().as_secs_f64();
        if dt < 0.5 {
            // Until the first half second is measured, the frames so far (a scripted run of a
            // few slow frames ends before it).
            if self.fps == 0.0 && self.frames > n0 && dt > 0.0 {
                self.fps = (self.frames - n0) as f64 / dt;
            }
            return;
        }
        self.fps = (self.frames - n0) as f64 / dt;
        self.fps_window = (Instant::now(), self.frames);
        let coarse = self.scene.elements(cfg.surface).element_count as u64;
        let bytes = self.scene.geometry_bytes(cfg, self.levels.is_some());
        self.say_unmet(cfg);
        let c = &self.controls;
        let flags = format!(
            "{}{}{}",
            if c.wireframe { " wire" } else { "" },
            if c.cage { " cage" } else { "" },
            if c.animate { " animated" } else { "" },
        );
        let surface = format!("{} + {}", cfg.surface.name(), cfg.displace.name());
        let camera = camera::camera_args(&self.camera, self.viewing);
        let rates = title_rates(self.fps, self.gpu_ms);
        if let Some(a) = self.adaptive_summary(cfg) {
            // Gliding is the default: only its absence is said (static never glides; tess
            // under a largest level that is not a power of two draws integer levels).
            let still = !cfg.glides() && !cfg.driver.kind().refines_on_cpu();
            self.window.set_title(&format!(
                "meshrefine | {} {}{}{flags} | {surface} | {rates} | {coarse} -> {} | {:.2} MB geometry | {camera}",
                cfg.label(),
                a.mode(),
                if still { " geomorph off" } else { "" },
                a.counts(),
                bytes as f64 / 1e6,
            ));
            return;
        }
        self.window.set_title(&format!(
            "meshrefine | {} level {}{}{}{flags} | {surface} | {rates} | {} -> {} triangles | {:.2} MB geometry | driver's largest level {} | {camera}",
            cfg.label(),
            cfg.level,
            if c.lod && !c.adaptive { " (LOD)" } else { "" },
            // Adaptive mode that could not draw adaptively (the panel says why).
            if c.adaptive { " (uniform: adaptive mode off here)" } else { "" },
            coarse,
            self.refined(cfg, coarse),
            bytes as f64 / 1e6,
            self.driver_max(cfg),
        ));
    }

    /// Where the last adaptive frame does not meet the pixel error, the `note:` lines render
    /// prints, on standard error when their kinds (or the pixel error, or the largest level)
    /// change: not every frame.
    fn say_unmet(&mut self, cfg: &DrawConfig) {
        let Some(r) = self.levels.as_ref() else {
            self.unmet_said = None;
            return;
        };
        let u = r.unmet;
        let kinds = UnmetKinds {
            near: u.near > 0,
            unbounded: u.unbounded > 0,
            capped: u.capped > 0,
            max: cfg.level,
            pixel_error: self.controls.pixel_error.to_bits(),
            drawing: (cfg.surface, cfg.displace, cfg.driver.name()),
        };
        let mut lines = u.notes(self.controls.pixel_error, cfg.level);
        // The largest level the notes name is not --max-level's where the driver's limit on
        // this device or the frame budget lowered it: a last note says which.
        let asked = self.adaptive_max(cfg.driver);
        if !lines.is_empty() && cfg.level < asked {
            let why = match cfg.level == self.driver_max(cfg) {
                true => "the largest the driver draws on this device",
                false => "to keep frames interactive",
            };
            lines.push(format!(
                "note: the largest level, {}, is lowered from --max-level {asked}: {why}",
                cfg.level
            ));
        }
        if lines.is_empty() {
            self.unmet_said = None;
        } else if self.unmet_said != Some(kinds) {
            self.unmet_said = Some(kinds);
            for line in lines {
                eprintln!("{line}");
            }
        }
    }

    /// The finished frame's GPU time and its level pass's (where it recorded one).
    pub(super) fn read_frame_times(&mut self) -> anyhow::Result<()> {
        self.gpu_ms = self.queries.gpu_ms(0)?;
        let timed = self.level_cost.timed;
        self.level_cost.gpu_ms = timed.then(|| self.queries.gpu_ms(1)).transpose()?;
        Ok(())
    }

    /// What the last adaptive frame (drawing `cfg`) chose; None when it
    /// drew uniformly.
    fn adaptive_summary(&self, cfg: &DrawConfig) -> Option<AdaptiveSummary> {
        let r = self.levels.as_ref()?;
        let (triangles, uniform_triangles) = r.triangles_on(|l| cfg.driver.refined_per_element(l));
        Some(AdaptiveSummary {
            pixel_error: self.controls.pixel_error,
            max_level: cfg.level,
            cull: self.controls.cull,
            frozen: self.frozen.is_some(),
            triangles,
            uniform_level: r.uniform_level,
            uniform_triangles,
            histogram: compact_histogram(&r.histogram),
            culled: r.culled,
            unmet: r.unmet,
            cost: self.level_cost,
        })
    }
}

/// What an adaptive frame chose, for the panel and the title.
struct AdaptiveSummary {
    pixel_error: f32,
    max_level: u32,
    cull: bool,
    frozen: bool,
    /// Triangles drawn, each element at its inner level.
    triangles: u64,
    /// The smallest uniform level that meets the same bound (`LevelReport::uniform_level`),
    /// and the triangles every element makes there.
    uniform_level: u32,
    uniform_triangles: u64,
    histogram: String,
    culled: u64,
    /// Where the pixel error is not met.
    unmet: crate::lod::frame::Unmet,
    /// What choosing the levels cost.
    cost: LevelCost,
}

/// What choosing an adaptive frame's levels cost.
#[derive(Clone, Copy, Debug, Default)]
pub struct LevelCost {
    /// CPU milliseconds choosing them (`Scene::set_levels`: the bounds where they changed, and
    /// the tally of the level pass's CPU mirror the panel shows).
    pub cpu_ms: f64,
    /// GPU milliseconds of the level pass the frame recorded (timestamps around it); `None`
    /// where it recorded none (`static` and levels uploaded from the CPU need none).
    pub gpu_ms: Option<f64>,
    /// Whether the frame in flight records the level pass (its timestamps are read when it is
    /// done).
    pub timed: bool,
}

impl LevelCost {
    /// `level pass 0.05 ms GPU, choosing 0.10 ms CPU` (`none` for the pass where it ran none,
    /// `measuring` while the first frame that runs it is in flight).
    fn describe(&self) -> String {
        let gpu = match (self.gpu_ms, self.timed) {
            (Some(ms), _) => format!("{ms:.2} ms GPU"),
            (None, true) => "measuring".to_string(),
            (None, false) => "none".to_string(),
        };
        format!("{gpu}, choosing {:.2} ms CPU", self.cpu_ms)
    }
}

impl AdaptiveSummary {
    /// `adaptive 1 px max level 64 cull on frozen`.
    fn mode(&self) -> String {
        format!(
            "adaptive {} px max level {} cull {}{}",
            self.pixel_error,
            self.max_level,
            if self.cull { "on" } else { "off" },
            if self.frozen { " frozen" } else { "" },
        )
    }

    /// Adaptive drawing's triangles against the uniform level's (`adaptive draws 4.2x fewer`,
    /// or `1.9x more` where dyadic levels and transitions cost more than one integer level;
    /// `-` when nothing is drawn).
    fn ratio(&self) -> String {
        if self.triangles == 0 {
            return "-".to_string();
        }
        let r = self.uniform_triangles as f64 / self.triangles as f64;
        let than = if (0.95..1.05).contains(&r) {
            "adaptive draws about as many".to_string()
        } else if r >= 1.0 {
            format!("adaptive draws {r:.1}x fewer")
        } else {
            format!("adaptive draws {:.1}x more", 1.0 / r)
        };
        // Where no level meets the bound everywhere, the uniform level is the cap.
        if self.unmet.uniform_unmet() {
            format!("{than}; the uniform level does not meet the bound either")
        } else {
            than
        }
    }

    /// The title's counts: triangles against the uniform level, levels, culling, cost.
    fn counts(&self) -> String {
        format!(
            "{} triangles, uniform level {} {} ({}) | levels {} | culled {} | level pass {}",
            self.triangles,
            self.uniform_level,
            self.uniform_triangles,
            self.ratio(),
            self.histogram,
            self.culled,
            self.cost.describe(),
        )
    }

    /// The panel's rows.
    fn rows(&self) -> Vec<(&'static str, String)> {
        let mut rows = vec![
            (
                "uniform level",
                format!(
                    "{}: {} triangles, {}",
                    self.uniform_level,
                    self.uniform_triangles,
                    self.ratio()
                ),
            ),
            ("levels (level:n)", self.histogram.clone()),
            ("culled", self.culled.to_string()),
        ];
        let u = self.unmet;
        let unmet: Vec<String> = [
            (u.capped, "need a level above the largest"),
            (u.near, "hold the eye in their bounds"),
            (u.unbounded, "have no finite bound"),
        ]
        .iter()
        .filter(|(n, _)| *n > 0)
        .map(|(n, why)| format!("{n} {why}"))
        .collect();
        if !unmet.is_empty() {
            rows.push(("pixel error not met", unmet.join(", ")));
        }
        rows.push(("level pass", self.cost.describe()));
        if self.frozen {
            rows.push((
                "levels",
                "frozen: chosen for the camera of that moment".to_string(),
            ));
        }
        rows
    }
}

/// Elements per level in power-of-two ranges, ascending (`1:20 2:31 3-4:120 8:40`): powers of
/// two one by one, integer levels compactly.
fn compact_histogram(histogram: &std::collections::BTreeMap<u32, u64>) -> String {
    // Per range's top: elements, and whether any level in it is not the top.
    let mut bins: std::collections::BTreeMap<u32, (u64, bool)> = Default::default();
    for (&n, &count) in histogram {
        let top = n.max(1).next_power_of_two();
        let bin = bins.entry(top).or_default();
        bin.0 += count;
        bin.1 |= n != top;
    }
    let pairs: Vec<String> = (bins.iter())
        .map(|(&top, &(count, range))| match range {
            false => format!("{top}:{count}"),
            true => format!("{}-{top}:{count}", top / 2 + 1),
        })
        .collect();
    if pairs.is_empty() {
        "none".to_string()
    } else {
        pairs.join(" ")
    }
}

/// The title's frame rate and GPU time: `-` until a frame's GPU time has been read back (a
/// first frame compiling for seconds would otherwise read as 0 ms); two decimals under one
/// frame a second.
fn title_rates(fps: f64, gpu_ms: f64) -> String {
    if gpu_ms > 0.0 {
        let digits = if fps < 1.0 { 2 } else { 0 };
        format!("{fps:.digits$} fps | GPU {gpu_ms:.2} ms")
    } else {
        "- fps | GPU - ms".to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The title's rates: nothing measured reads `-`, not 0; slow frames keep their digits.
    #[test]
    fn title_rates_say_when_nothing_is_measured() {
        assert_eq!(title_rates(0.0, 0.0), "- fps | GPU - ms");
        assert_eq!(title_rates(0.05, 19873.2), "0.05 fps | GPU 19873.20 ms");
        assert_eq!(title_rates(59.6, 16.4), "60 fps | GPU 16.40 ms");
    }

    /// The level pass's cost reads `measuring` while the frame that first runs it is in flight,
    /// its GPU time once that frame is done, and `none` where no pass runs (docs/window.md).
    #[test]
    fn the_level_pass_cost_says_when_it_is_measuring() {
        let cost = |gpu_ms, timed| {
            LevelCost {
                cpu_ms: 0.125,
                gpu_ms,
                timed,
            }
            .describe()
        };
        assert_eq!(cost(None, true), "measuring, choosing 0.12 ms CPU");
        assert_eq!(cost(Some(0.5), true), "0.50 ms GPU, choosing 0.12 ms CPU");
        assert_eq!(cost(Some(0.5), false), "0.50 ms GPU, choosing 0.12 ms CPU");
        assert_eq!(cost(None, false), "none, choosing 0.12 ms CPU");
    }

    /// Dyadic levels are shown one by one, integer levels in power-of-two ranges.
    #[test]
    fn histograms_are_compact() {
        let h = |pairs: &[(u32, u64)]| compact_histogram(&pairs.iter().copied().collect());
        assert_eq!(h(&[(1, 3), (2, 5), (4, 7), (8, 1)]), "1:3 2:5 4:7 8:1");
        assert_eq!(
            h(&[(3, 1), (4, 2), (5, 4), (11, 1), (64, 2)]),
            "3-4:3 5-8:4 9-16:1 64:2"
        );
        assert_eq!(h(&[]), "none");
    }

    /// The uniform comparison says when the uniform level (then the cap) does not meet the
    /// bound either.
    #[test]
    fn the_uniform_comparison_says_when_it_does_not_meet_the_bound() {
        let mut a = AdaptiveSummary {
            pixel_error: 1.0,
            max_level: 64,
            cull: true,
            frozen: false,
            triangles: 1000,
            uniform_level: 16,
            uniform_triangles: 4200,
            histogram: "8:10".into(),
            culled: 0,
            unmet: crate::lod::frame::Unmet::default(),
            cost: LevelCost::default(),
        };
        assert_eq!(a.ratio(), "adaptive draws 4.2x fewer");
        a.unmet.near = 1;
        assert_eq!(
            a.ratio(),
            "adaptive draws 4.2x fewer; the uniform level does not meet the bound either"
        );
        a.unmet.near = 0;
        // Capped for transitions alone: the uniform level (no transitions) meets the bound.
        a.unmet.capped = 3;
        assert_eq!(a.ratio(), "adaptive draws 4.2x fewer");
        a.unmet.beyond_uniform = 1;
        assert_eq!(
            a.ratio(),
            "adaptive draws 4.2x fewer; the uniform level does not meet the bound either"
        );
        a.unmet = crate::lod::frame::Unmet::default();
        a.uniform_triangles = 520;
        assert_eq!(a.ratio(), "adaptive draws 1.9x more");
        a.uniform_triangles = 990;
        assert_eq!(a.ratio(), "adaptive draws about as many");
        a.triangles = 0;
        assert_eq!(a.ratio(), "-");
    }
}

/// What kinds of unmet pixel error the window last said, and for which pixel error, largest
/// level and drawing (surface, displacement, driver by name, whatever its submission: the
/// counts change with them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct UnmetKinds {
    near: bool,
    unbounded: bool,
    capped: bool,
    max: u32,
    pixel_error: u32,
    drawing: (
        crate::surface::Surface,
        crate::surface::Displace,
        &'static str,
    ),
}
