//! Adaptive mode in the window: each element at the levels its bound needs for the current
//! camera and window size (`Scene::set_levels`), up to the largest level, or the frozen levels;
//! where the driver cannot draw adaptively, the frame is drawn uniformly and the panel says why
//! (docs/window.md, "Adaptive mode").
#![forbid(unsafe_code)]

use super::{State, ViewOptions};
use crate::render::{DrawConfig, Viewpoint};
use anyhow::Result;
use std::time::Instant;

/// Adaptive mode in the window: each element at the levels its bound needs for the current
/// camera and window size (`Scene::set_levels`), the largest level as `cfg.level`
/// (docs/window.md, "Adaptive mode").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveView {
    /// Start in adaptive mode (else uniform: every element at `cfg.level`).
    pub on: bool,
    pub pixel_error: f32,
    pub cull: bool,
    /// Where the first camera is and looks, and its field of view (drawn coordinates): what
    /// it does not give comes from the camera fitted to the surface drawn, at its field of view
    /// ([`Viewpoint::camera`]).
    pub viewpoint: Viewpoint,
    /// The largest level; None: [`DEFAULT_MAX_LEVEL`], or less where a driver cannot draw it
    /// on this device.
    pub max_level: Option<u32>,
}

/// The pixel error adaptive mode starts with when none is given.
pub const DEFAULT_PIXEL_ERROR: f32 = 1.0;

/// The largest level adaptive mode starts with when none is given.
pub const DEFAULT_MAX_LEVEL: u32 = 64;

impl State {
    /// The configuration this frame draws, prepared, and whether it draws adaptively (then
    /// with its levels chosen and uploaded, or for the static driver refined on the CPU at
    /// them): adaptive mode draws adaptively where the driver can
    /// (`DriverKind::check_adaptive`), and otherwise uniformly, saying why in the panel.
    pub(super) fn prepare_frame(&mut self, opts: &ViewOptions) -> Result<(DrawConfig, bool)> {
        self.mode_note = None;
        self.levels = None;
        // The pipelines prepared below are this view's.
        self.renderer.set_view(self.controls.view);
        if !self.controls.freeze {
            self.frozen = None;
        } else if self.frozen.is_none() {
            self.frozen = Some((self.camera, self.swapchain.extent));
        }
        if self.controls.adaptive {
            let driver = self.controls.cfg.driver;
            // The static driver refines on the CPU at the levels chosen (the CPU baseline).
            let on_cpu = driver.kind().refines_on_cpu();
            self.scene.adaptive_frames = on_cpu;
            // Start from the largest level the last frame drew (the budget may have lowered
            // it): the pattern driver's adaptive draws are rebuilt only when it changes.
            let max = self.adaptive_max(driver);
            let guess = self.adaptive_level.map_or(max, |l| l.min(max));
            let cfg = self.prepare_config(opts, Some(guess))?;
            let cfg = self.choose_levels(opts, cfg, max)?;
            if on_cpu {
                // Refined and uploaded again where the levels changed.
                let (none, wire) = (crate::render::Capture::None, self.controls.wireframe);
                (self.scene).prepare(
                    &self.ctx,
                    &self.pool,
                    &mut self.renderer,
                    &cfg,
                    none,
                    wire,
                )?;
            }
            let kind = cfg.driver.kind();
            match kind.check_adaptive(&self.ctx, &self.scene, &cfg) {
                Ok(()) => return Ok((cfg, true)),
                Err(e) => {
                    self.levels = None;
                    self.mode_note = Some(format!("{e}: drawing uniformly"));
                }
            }
        }
        self.scene.adaptive_frames = false;
        self.adaptive_level = None;
        Ok((self.prepare_config(opts, None)?, false))
    }

    /// The largest level adaptive mode asks of `driver`: the panel's, a power of two unless
    /// its levels are the tessellator's ([`DriverKind::integer_levels`](crate::render::DriverKind):
    /// the pattern driver's geomorphing patterns split 1 to 4, the static one takes its
    /// levels).
    pub(super) fn adaptive_max(&self, driver: crate::render::Driver) -> u32 {
        let max = self.controls.max_level.max(1);
        if driver.kind().integer_levels() {
            max
        } else {
            1 << max.ilog2()
        }
    }

    /// This frame's levels for `cfg` (prepared; the previous frame is done with the levels) up to
    /// `max`, seen by the camera and window (or the frozen ones), uploaded; on a software device
    /// the largest level lowered until the slower estimate of the adaptive triangles is under a
    /// second, said in the panel. Returns `cfg` at the largest level drawn, prepared.
    pub(super) fn choose_levels(
        &mut self,
        opts: &ViewOptions,
        mut cfg: DrawConfig,
        max: u32,
    ) -> Result<DrawConfig> {
        let (camera, extent) = self.frozen.unwrap_or((self.camera, self.swapchain.extent));
        let view = crate::render::LevelView {
            camera,
            width: extent.width,
            height: extent.height,
            pixel_error: self.controls.pixel_error,
            cull: self.controls.cull,
        };
        let prepared = cfg.level;
        // What the bound asks for up to `max` (or the driver's limit), then the budget's cap.
        cfg.level = max.min(self.driver_max(&cfg));
        let t0 = Instant::now();
        let mut report = self.scene.set_levels(&cfg, &view)?;
        let level = self.fit_adaptive_budget(&cfg, &report);
        let mut seconds = t0.elapsed().as_secs_f64();
        if level != cfg.level {
            cfg.level = level;
            let t0 = Instant::now();
            report = self.scene.set_levels(&cfg, &view)?;
            seconds += t0.elapsed().as_secs_f64();
        }
        if cfg.level != prepared {
            cfg = self.prepare_config(opts, Some(cfg.level))?;
            if cfg.level != level {
                // Lowered again to what the driver draws: the levels must not exceed it.
                report = self.scene.set_levels(&cfg, &view)?;
            }
        }
        self.level_cost.cpu_ms = seconds * 1e3;
        self.levels = Some(report);
        self.adaptive_level = Some(cfg.level);
        Ok(cfg)
    }

    /// The largest level the driver of `cfg` draws on this device among the window's levels.
    pub(super) fn driver_max(&self, cfg: &DrawConfig) -> u32 {
        let limit = cfg
            .driver
            .kind()
            .level_limit(&self.ctx.info)
            .map(|(max, _)| max);
        (self.scene.patterns.levels())
            .filter(|&l| limit.is_none_or(|max| l <= max))
            .filter(|&l| cfg.driver.kind().integer_levels() || l.is_power_of_two())
            .last()
            .unwrap_or(1)
    }

    /// After a slow frame (over a quarter second, so that the triangles dominate its time)
    /// drawn as the one before it (no pipeline compiled in it), in either mode: its GPU time
    /// per refined triangle and pass, kept if slower than the last one measured for the same
    /// driver, surface, displacement, wireframe and mode (on lavapipe the tessellator's
    /// wireframe pass costs a hundred times a shaded one's triangles, adaptive frames more than
    /// uniform ones), for the frame budget ([`MeasuredRates`]). Called before the next frame
    /// is prepared: what is measured is the frame as drawn, whatever keys were pressed since.
    pub(super) fn measure_rate(&mut self) {
        let Some((d, wire, adaptive)) = self.last_drawn else {
            return;
        };
        if !self.warm || self.gpu_ms < 250.0 {
            return;
        }
        let coarse = self.scene.elements(d.surface).element_count as u64;
        let triangles = self.refined(&d, coarse) * if wire { 2 } else { 1 };
        if triangles == 0 {
            return;
        }
        let ns = self.gpu_ms * 1e6 / triangles as f64;
        self.measured_rates.record(&d, wire, adaptive, ns);
    }
}

/// What a measured rate is for: driver, surface, displacement, wireframe, adaptive.
type RateKey = (
    crate::render::Driver,
    crate::surface::Surface,
    crate::surface::Displace,
    bool,
    bool,
);

/// The slowest GPU time per refined triangle and pass measured on each configuration's slow
/// frames (`State::measure_rate`), which the frame budget also counts.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct MeasuredRates(Vec<(RateKey, f64)>);

impl MeasuredRates {
    fn key(cfg: &DrawConfig, wire: bool, adaptive: bool) -> RateKey {
        (cfg.driver, cfg.surface, cfg.displace, wire, adaptive)
    }

    /// Keep `ns` for `cfg` drawn so where it is slower than the one kept.
    pub fn record(&mut self, cfg: &DrawConfig, wire: bool, adaptive: bool, ns: f64) {
        let key = Self::key(cfg, wire, adaptive);
        match self.0.iter_mut().find(|(k, _)| *k == key) {
            Some((_, kept)) => *kept = kept.max(ns),
            None => self.0.push((key, ns)),
        }
    }

    /// The rate measured for `cfg` drawn with or without the wireframe, adaptively or not; 0
    /// where none is.
    pub fn for_config(&self, cfg: &DrawConfig, wire: bool, adaptive: bool) -> f64 {
        let key = Self::key(cfg, wire, adaptive);
        (self.0.iter().find(|(k, _)| *k == key)).map_or(0.0, |&(_, ns)| ns)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each configuration keeps its own slowest rate: another's does not replace it.
    #[test]
    fn rates_are_kept_per_configuration() {
        use crate::render::Driver;
        let pn = DrawConfig::new(Driver::Pattern(Default::default()), 8);
        let tess = DrawConfig::new(Driver::Tess, 8);
        let mut r = MeasuredRates::default();
        r.record(&tess, true, false, 30_000.0);
        r.record(&pn, false, true, 500.0);
        r.record(&tess, true, false, 20_000.0);
        assert_eq!(r.for_config(&tess, true, false), 30_000.0);
        assert_eq!(r.for_config(&tess, false, false), 0.0);
        assert_eq!(r.for_config(&tess, true, true), 0.0);
        assert_eq!(r.for_config(&pn, false, true), 500.0);
    }
}
