//! The driver seam (docs/architecture.md, "Drivers"): how barycentric samples are produced on the
//! GPU. [`Driver`] is the value users choose (`--driver static|pattern|tess`); [`DriverKind`] is
//! everything one driver answers about itself, each implemented in its own file
//! (`static_vbo.rs`, `pattern.rs`, `tess.rs`): its pipeline (stages, vertex input, topology), what
//! it prepares before drawing (the static buffer, level checks against the device), its counts
//! (refined triangles, stored vertices and indices, capture room, geometry bytes) and recording
//! its draws. [`Driver::kind`] is the one place that matches on the driver.
//!
//! A driver never knows which surface it draws: the surface is a specialization constant of its
//! evaluation stage, and the element records are opaque to it.

use super::frame::FrameWork;
use super::{Capture, DrawConfig, RenderError, Renderer, Scene};
use crate::gpu::{CommandPool, Context, DeviceInfo, GraphicsPipelineDesc};
use std::sync::Arc;

/// How barycentric samples are produced on the GPU. The submission mode belongs to the pattern
/// driver alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Driver {
    /// The CPU refines the whole mesh into one vertex buffer (the 2005 paper's baseline).
    Static,
    /// The refinement pattern is drawn for every coarse triangle; the vertex shader evaluates.
    Pattern(Submit),
    /// Vulkan tessellation shaders; the evaluation shader evaluates.
    Tess,
}

impl Default for Driver {
    fn default() -> Self {
        Driver::Pattern(Submit::default())
    }
}

impl Driver {
    /// The three drivers (the pattern driver with its default submission).
    pub const ALL: [Driver; 3] = [
        Driver::Static,
        Driver::Pattern(Submit::Instanced),
        Driver::Tess,
    ];

    /// Every driver and submission mode, `static` first (the benchmarks' reference).
    pub const VARIANTS: [Driver; 5] = [
        Driver::Static,
        Driver::Pattern(Submit::Push),
        Driver::Pattern(Submit::Ubo),
        Driver::Pattern(Submit::Instanced),
        Driver::Tess,
    ];

    /// Everything this driver answers about itself (the one `match` on drivers).
    pub fn kind(self) -> &'static dyn DriverKind {
        match self {
            Driver::Static => &super::static_vbo::StaticDriver,
            Driver::Pattern(_) => &super::pattern::PatternDriver,
            Driver::Tess => &super::tess::TessDriver,
        }
    }

    /// `static`, `pattern` or `tess`.
    pub fn name(self) -> &'static str {
        self.kind().name()
    }

    /// One line for `--help`.
    pub fn help(self) -> &'static str {
        self.kind().help()
    }

    /// The pattern driver's submission mode.
    pub fn submit(self) -> Option<Submit> {
        match self {
            Driver::Pattern(s) => Some(s),
            _ => None,
        }
    }

    /// The same kind of driver as `other` (submission modes aside).
    pub fn same_kind(self, other: Driver) -> bool {
        std::mem::discriminant(&self) == std::mem::discriminant(&other)
    }

    /// Triangles the GPU makes per element at `level` ([`DriverKind::refined_per_element`]).
    pub fn refined_per_element(self, level: u32) -> u32 {
        self.kind().refined_per_element(level)
    }

    /// GPU bytes of geometry this driver holds for `elements` elements at `level`
    /// ([`DriverKind::geometry_bytes`], without per-fragment sample attributes).
    pub fn geometry_bytes(self, level: u32, elements: u64) -> u64 {
        self.kind().geometry_bytes(level, elements, false)
    }

    /// Room a vertex capture needs per element at `level` ([`DriverKind::capture_per_element`]).
    pub fn capture_per_element(self, level: u32) -> Option<u32> {
        self.kind().capture_per_element(level)
    }
}

/// How the `pattern` driver hands each coarse triangle's record to the vertex shader.
/// The discriminant is the `SUBMIT` specialization constant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[repr(u32)]
pub enum Submit {
    /// Per coarse triangle: push constants, then draw (the paper's loop).
    Push = 0,
    /// Per coarse triangle: the record read from a uniform-buffer window, then draw.
    Ubo = 1,
    /// One instanced draw; each record read as instance-rate vertex attributes.
    #[default]
    Instanced = 2,
}

impl Submit {
    pub const ALL: [Submit; 3] = [Submit::Push, Submit::Ubo, Submit::Instanced];
    pub fn name(self) -> &'static str {
        match self {
            Submit::Push => "push",
            Submit::Ubo => "ubo",
            Submit::Instanced => "instanced",
        }
    }
}

/// What one driver answers about itself. Implemented by a unit struct in the driver's own file;
/// reached through [`Driver::kind`].
pub trait DriverKind: Sync {
    /// The name on the command line.
    fn name(&self) -> &'static str;

    /// One line for `--help`.
    fn help(&self) -> &'static str;

    /// Whether the CPU refines the mesh (the surface's Rust mirror) and the GPU only draws the
    /// result: nothing to capture, no GPU pre-pass (Loop's M0 -> M1), an animated frame uploads
    /// the refined mesh.
    fn refines_on_cpu(&self) -> bool {
        false
    }

    /// Triangles made per element at `level`.
    fn refined_per_element(&self, level: u32) -> u32;

    /// Refined vertices and indices stored on the GPU for `elements` elements at `level`.
    fn stored(&self, level: u32, elements: u64) -> (u64, u64);

    /// GPU bytes of geometry held for `elements` elements at `level` (the pattern and the
    /// records, or the refined buffers); `fragment_field`: the fragment stage evaluates the
    /// normal field, so every refined vertex the CPU stored also carries its sample.
    fn geometry_bytes(&self, level: u32, elements: u64, fragment_field: bool) -> u64;

    /// Refined vertices and indices stored on the GPU to draw `elements` elements adaptively
    /// up to `level`, at powers of two where `dyadic`: by default what `level` stores.
    fn stored_adaptive(&self, level: u32, elements: u64, _dyadic: bool) -> (u64, u64) {
        self.stored(level, elements)
    }

    /// [`DriverKind::geometry_bytes`] of an adaptive frame up to `level` (`dyadic`: at powers
    /// of two): by default a uniform frame's at `level`.
    fn adaptive_geometry_bytes(
        &self,
        level: u32,
        elements: u64,
        _dyadic: bool,
        fragment_field: bool,
    ) -> u64 {
        self.geometry_bytes(level, elements, fragment_field)
    }

    /// Room a vertex capture needs per element at `level`; `None` where nothing runs on the
    /// GPU to capture.
    fn capture_per_element(&self, level: u32) -> Option<u32>;

    /// Whether a vertex capture appends (an atomic counter says how many were written, since
    /// evaluation invocations may repeat) rather than writing fixed slots per element.
    fn capture_appends(&self) -> bool {
        false
    }

    /// How `export` reads back what this driver drew: the evaluated vertices (welded by their
    /// pattern index) or the rasterized triangles (transform feedback); `None`: nothing to read.
    fn export_capture(&self) -> Option<Capture>;

    /// The finest level this device lets the driver draw and the limit's name, where the
    /// device limits it (a hardware level limit; [`check_level`] is the policy).
    fn level_limit(&self, _device: &DeviceInfo) -> Option<(u32, &'static str)> {
        None
    }

    /// Whether it is the tessellator, whose levels are any integers under any largest level,
    /// rounded to powers of two only while it glides ([`DrawConfig::glides`]), rather than a
    /// driver with patterns (pattern, and static, which refines with their construction),
    /// whose largest adaptive level is a power of two and whose boundary is snapped
    /// ([`DrawConfig::rounding`]).
    fn integer_levels(&self) -> bool {
        false
    }

    /// Whether it geomorphs in its evaluation stage within the one pipeline that draws its
    /// uniform and its adaptive frames (a push constant says which): then that pipeline is
    /// built gliding whenever the configuration glides, not only its adaptive variant.
    fn geomorphs_in_evaluation(&self) -> bool {
        false
    }

    /// Fill in the pipeline's geometry stages (the variant that `capture` needs), vertex input
    /// and topology; `fragment_field`: the fragment stage evaluates the normal field.
    fn describe_pipeline(
        &self,
        desc: &mut GraphicsPipelineDesc,
        fragment_field: bool,
        capture: Capture,
    );

    /// Whether an adaptive frame at largest level `level` is drawn with a pipeline of its own
    /// ([`DriverKind::describe_adaptive_pipeline`]: the pattern driver's hierarchical patterns,
    /// at a power of two) rather than the uniform one.
    fn adaptive_pipeline(&self, _level: u32) -> bool {
        false
    }

    /// The pipeline of an adaptive frame (`FrameWork::adaptive`: each element at its own
    /// levels); a driver that does not draw adaptively describes its uniform pipeline.
    fn describe_adaptive_pipeline(
        &self,
        desc: &mut GraphicsPipelineDesc,
        fragment_field: bool,
        capture: Capture,
    ) {
        self.describe_pipeline(desc, fragment_field, capture)
    }

    /// Whether `cfg`, prepared in `scene` ([`Scene::prepare`]), can be drawn adaptively on this
    /// device: one sentence where not. A driver that draws adaptively checks what that needs
    /// (the pattern driver: a power-of-two level, room for its indirect commands); the default
    /// accepts (the frame is then drawn uniformly).
    fn check_adaptive(
        &self,
        _ctx: &Context,
        _scene: &Scene,
        _cfg: &DrawConfig,
    ) -> Result<(), RenderError> {
        Ok(())
    }

    /// Record what the frame's draws need computed on the GPU first (outside the rendering
    /// instance, after the pre-pass): the pattern driver's indirect commands of an adaptive
    /// frame. Nothing by default.
    fn cmd_before_rendering(
        &self,
        _cmd: &crate::gpu::Cmd<'_>,
        _r: &Renderer,
        _work: &FrameWork<'_>,
    ) {
    }

    /// Whether what [`DriverKind::prepare`] builds for `cfg` fits this device: checked by
    /// [`Scene::prepare`] before it warns that frames will be slow (and before any slow work).
    /// Nothing by default.
    fn check_fits(
        &self,
        _scene: &Scene,
        _ctx: &Context,
        _cfg: &DrawConfig,
    ) -> Result<(), RenderError> {
        Ok(())
    }

    /// Build what drawing `cfg` needs besides the pipelines (after the scene's checks).
    fn prepare(
        &self,
        _scene: &mut Scene,
        _ctx: &Arc<Context>,
        _pool: &CommandPool,
        _cfg: &DrawConfig,
    ) -> Result<(), RenderError> {
        Ok(())
    }

    /// Record the draws of `work.elements` (pipeline and frame sets already bound).
    fn cmd_draw(&self, cmd: &crate::gpu::Cmd<'_>, r: &Renderer, work: &FrameWork<'_>);
}

/// The least level limit of any Vulkan device: the required minimum of
/// maxTessellationGenerationLevel. No driver's level at or under it is refused
/// ([`check_level`]), whatever the device.
pub const LEAST_LEVEL_LIMIT: u32 = 64;

/// Check `cfg.level` against the device's limit for its driver. The one level policy: the
/// command line refuses with this error; the window lowers the level and the benchmark skips the
/// row, each showing the same sentence.
pub fn check_level(ctx: &Context, cfg: &DrawConfig) -> Result<(), RenderError> {
    check_level_on(&ctx.info, cfg)
}

/// [`check_level`] on a device known by its limits alone, none opened (`info`, which draws
/// nothing, [`crate::gpu::picked_device`]).
pub fn check_level_on(device: &DeviceInfo, cfg: &DrawConfig) -> Result<(), RenderError> {
    let kind = cfg.driver.kind();
    match kind.level_limit(device) {
        Some((max, limit)) if cfg.level > max => Err(RenderError::DriverLevel {
            driver: kind.name(),
            level: cfg.level,
            limit,
            max,
        }),
        _ => Ok(()),
    }
}

/// The finest level every driver draws on this device, where the device limits one (the
/// window's largest adaptive level when none is given: the panel switches drivers).
pub fn shared_level_limit(ctx: &Context) -> Option<u32> {
    (Driver::ALL.iter())
        .filter_map(|d| d.kind().level_limit(&ctx.info))
        .map(|(max, _)| max)
        .min()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The capability table of docs/architecture.md ("Drivers"), asked of each driver's file.
    #[test]
    fn drivers_answer_their_capabilities() {
        for d in Driver::VARIANTS {
            let k = d.kind();
            let (cpu, integer, evaluation, own_pipeline) = match d {
                Driver::Static => (true, false, false, false),
                Driver::Pattern(_) => (false, false, false, true),
                Driver::Tess => (false, true, true, false),
            };
            assert_eq!(k.refines_on_cpu(), cpu, "{}", d.name());
            assert_eq!(k.integer_levels(), integer, "{}", d.name());
            assert_eq!(k.geomorphs_in_evaluation(), evaluation, "{}", d.name());
            assert_eq!(k.adaptive_pipeline(16), own_pipeline, "{}", d.name());
            // Not at a level its hierarchical patterns cannot make.
            assert!(!k.adaptive_pipeline(12), "{}", d.name());
        }
    }

    /// Gliding and dyadic levels as docs/adaptivity.md ("Geomorphing") says: the pattern
    /// driver glides at powers of two with `geomorph` and draws integer levels without; the
    /// static driver never glides and draws integer levels; the tess driver glides (and rounds
    /// to powers of two) only under a largest level that is one, and draws integer levels
    /// otherwise.
    #[test]
    fn gliding_follows_the_levels() {
        // (driver, level, geomorph) -> (glides, dyadic levels)
        let cases = [
            (Driver::Tess, 16, true, (true, true)),
            (Driver::Tess, 12, true, (false, false)),
            (Driver::Tess, 16, false, (false, false)),
            (Driver::Pattern(Submit::Push), 16, true, (true, true)),
            (
                Driver::Pattern(Submit::Instanced),
                16,
                false,
                (false, false),
            ),
            (Driver::Static, 16, true, (false, false)),
            (Driver::Static, 16, false, (false, false)),
        ];
        for (d, level, geomorph, want) in cases {
            let cfg = DrawConfig {
                geomorph,
                ..DrawConfig::new(d, level)
            };
            let got = (cfg.glides(), cfg.dyadic_levels());
            assert_eq!(got, want, "{} at {level}, geomorph {geomorph}", d.name());
        }
    }
}
