//! The frame budget: on a software device the window never starts a frame its slower estimate
//! puts over a second; it draws the finest level (uniform mode) or the largest level (adaptive
//! mode) that fits, and the panel and the log say so (docs/window.md, "Frames stay interactive
//! on a software device").
#![forbid(unsafe_code)]

use super::State;
use crate::gpu::vk;
use crate::render::{software_frame_seconds, DrawConfig};

impl State {
    /// How many times its triangles' cost the estimate counts a frame of `cfg` at: Loop's faces
    /// by their control points ([`crate::render::Scene::evaluation_weight`], the mean over the
    /// faces, as if each drew as many triangles), 1 for the other surfaces. What is measured
    /// on slow frames needs no weight: it was measured on this mesh.
    fn loop_weight(&self, cfg: &DrawConfig) -> f64 {
        (self.scene.evaluation_weight(cfg, None)).map_or(1.0, |w| w.factor)
    }

    /// On a software device, lower `cfg.level` to the finest level whose frame the slower
    /// estimate ([`software_frame_seconds`], or the slower rate measured on this configuration's
    /// slow frames) puts under a second (the wireframe pass counted as a second draw), and say so in the panel: the window stays responsive
    /// whatever level is asked for. Other devices draw what is asked.
    pub(super) fn fit_frame_budget(&mut self, cfg: &mut DrawConfig, wire: bool) {
        self.budget_note = None;
        if self.ctx.info.device_type != crate::gpu::vk::PhysicalDeviceType::CPU
            || !self.frame_budget
        {
            return;
        }
        let elements = self.scene.elements(cfg.surface).element_count as u64;
        let passes = if wire { 2 } else { 1 };
        let measured = self.measured_rates.for_config(cfg, wire, false);
        let weight = self.loop_weight(cfg);
        let fits = |level: u32| {
            let mut c = *cfg;
            c.level = level;
            let refined = elements * c.refined_per_element() as u64 * passes;
            software_frame_seconds((refined as f64 * weight) as u64).is_none()
                && refined as f64 * measured * 1e-9 < 1.0
        };
        if fits(cfg.level) {
            return;
        }
        let asked = cfg.level;
        cfg.level = self
            .scene
            .patterns
            .levels()
            .filter(|&l| l < asked && fits(l))
            .last()
            .unwrap_or(1);
        let note = format!(
            "level {asked} would take over a second a frame on this software device: drawing level {}",
            cfg.level
        );
        if self.level_note != Some(asked) {
            log::warn!("{note}");
            self.level_note = Some(asked);
        }
        self.budget_note = Some(note);
    }

    /// On a software device, the largest level at most `cfg.level` whose adaptive frame (the
    /// elements of `report`, each at its inner level capped there; the wireframe pass counted
    /// as a second draw) the slower estimate (or the slower rate measured on this
    /// configuration's slow frames, adaptive frames being slower a triangle on lavapipe than
    /// the uniform ones the estimate comes from) puts under a second, said in the panel;
    /// `cfg.level` elsewhere.
    pub(super) fn fit_adaptive_budget(
        &mut self,
        cfg: &DrawConfig,
        chosen: &crate::render::ChosenLevels,
    ) -> u32 {
        if self.ctx.info.device_type != vk::PhysicalDeviceType::CPU || !self.frame_budget {
            return cfg.level;
        }
        // Only a software device's budget reads the tally (the mirror runs now).
        let report = chosen.report();
        let passes = if self.controls.wireframe { 2 } else { 1 };
        let measured = self
            .measured_rates
            .for_config(cfg, self.controls.wireframe, true);
        let weight = self.loop_weight(cfg);
        let fits = |cap: u32| {
            let refined: u64 = (report.histogram.iter())
                .map(|(&n, &count)| count * cfg.driver.refined_per_element(n.min(cap)) as u64)
                .sum();
            software_frame_seconds((refined as f64 * passes as f64 * weight) as u64).is_none()
                && (refined * passes) as f64 * measured * 1e-9 < 1.0
        };
        let asked = cfg.level;
        if fits(asked) {
            return asked;
        }
        let pow2 = cfg.power_of_two_max();
        let level = (self.scene.patterns.levels())
            .filter(|&l| l < asked && (!pow2 || l.is_power_of_two()) && fits(l))
            .last()
            .unwrap_or(1);
        let note = format!(
            "max level {asked} would take over a second a frame on this software device at {} px: drawing up to level {level}",
            self.controls.pixel_error
        );
        if self.level_note != Some(asked) {
            log::warn!("{note}");
            self.level_note = Some(asked);
        }
        self.budget_note = Some(note);
        level
    }
}
