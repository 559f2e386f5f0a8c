//! Rendering: per-mesh GPU data ([`GpuMesh`]), pipelines ([`Renderer`]) and the three drivers
//! that produce barycentric samples on the GPU (`static`, `pattern`, `tess`, one file each).
//! A driver never knows which surface it draws: the surface is a specialization constant of its
//! evaluation stage.
#![forbid(unsafe_code)]

pub mod bindings;
pub mod cage;
mod camera;
pub mod driver;
mod error;
pub mod frame;
mod framing;
pub use framing::{framing_points, Framing, REACH};
mod capture;
mod gpu_mesh;
mod headless;
pub mod level_pass;
pub mod loop_gpu;
mod mesh_data;
mod packed_capture;
pub mod pattern;
mod pipelines;
mod scene;
mod scene_levels;
pub mod static_adaptive;
pub mod static_vbo;
pub mod tess;
mod xfb_capture;

pub use camera::{Camera, Viewpoint, FIT_MARGIN};
pub use driver::{Driver, DriverKind, Submit};
pub use error::RenderError;
pub use frame::Background;
pub use gpu_mesh::{GpuMesh, GpuPattern};
pub use headless::{
    background_srgb8, clear_color_srgb8, covered_pixels, covered_pixels_on, CaptureResult,
    FrameTiming, Headless,
};
pub use level_pass::LevelPass;
pub use mesh_data::MeshData;
pub use pipelines::{Renderer, GEOMETRY_STAGES, PUSH_STAGES};
pub use scene::{software_frame_seconds, EvaluationWeight, Scene};
pub use scene_levels::{ChosenLevels, LevelView};
pub use xfb_capture::{CapturePass, LAVAPIPE_MAX_CAPTURE_PASS_BYTES};

use crate::surface::{BuildOptions, Displace, ElementRecord, Surface, SurfaceParams};
use bytemuck::{Pod, Zeroable};

/// Whether a frame also reads back what its geometry stages evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Capture {
    #[default]
    None,
    /// Every evaluated vertex to a storage buffer (the `CAPTURE` shader variants).
    Vertices,
    /// The triangles as rasterized, by transform feedback (the `XFB` variant; `tess` only).
    Triangles,
}

impl Capture {
    /// Suffix of the capture variant in pipeline and shader names.
    pub fn shader_suffix(self) -> &'static str {
        match self {
            Capture::None => "",
            Capture::Vertices => "+capture",
            Capture::Triangles => "+xfb",
        }
    }
}

/// What to draw and how: surface x displacement x driver (and the pattern driver's submission
/// mode), at a level, with the surfaces' parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawConfig {
    pub surface: Surface,
    pub displace: Displace,
    /// Per-frame values (the `Frame` block): a frame may change them without rebuilding.
    pub params: SurfaceParams,
    /// Options that change what is built: the mesh's data (records, Loop's tables) and the
    /// pipelines (the normal field's specialization constant).
    pub build: BuildOptions,
    pub driver: Driver,
    pub level: u32,
    /// Adaptive drawing glides the vertices a level adds (docs/adaptivity.md, "Geomorphing";
    /// [`DrawConfig::glides`]); uniform drawing ignores it.
    pub geomorph: bool,
}

/// The level from which `loop` evaluates its normals per fragment
/// ([`DrawConfig::fragment_normal_field`]; declared by the surface).
pub const LOOP_FRAGMENT_NORMALS: u32 = crate::surface::loop_::FRAGMENT_NORMALS_FROM;

impl DrawConfig {
    /// The flat surface, no displacement, default parameters.
    pub fn new(driver: Driver, level: u32) -> Self {
        Self {
            surface: Surface::Flat,
            displace: Displace::None,
            params: SurfaceParams::default(),
            build: BuildOptions::default(),
            driver,
            level,
            geomorph: false,
        }
    }

    pub fn with_surface(mut self, surface: Surface, displace: Displace) -> Self {
        self.surface = surface;
        self.displace = displace;
        self
    }

    /// Short label such as `pattern/instanced` or `tess`.
    pub fn label(&self) -> String {
        match self.driver {
            Driver::Pattern(s) => format!("pattern/{}", s.name()),
            d => d.name().to_string(),
        }
    }

    /// Whether adaptive frames glide their vertices: [`DrawConfig::geomorph`], except for the
    /// static driver, which never does (it refines on the CPU when the levels change), and a
    /// driver with integer levels (the tess driver, [`DriverKind::integer_levels`]) under a
    /// largest level that is not a power of two (its morph needs dyadic levels), which then
    /// draws its integer levels without gliding.
    pub fn glides(&self) -> bool {
        let kind = self.driver.kind();
        self.geomorph
            && !kind.refines_on_cpu()
            && (!kind.integer_levels() || self.level.is_power_of_two())
    }

    /// Whether a closed mesh makes a closed surface: not where open seams
    /// (`--pn-seams open`) crack a surface that follows the normals (every one but `flat`).
    pub fn closed_surface(&self) -> bool {
        self.build.seams == crate::surface::Seams::Closed || self.surface == Surface::Flat
    }

    /// Whether the surface drawn from a closed mesh wound outwards may show faces turned away
    /// from an eye outside it and its elements' bounds: open seams (cracks), `loop` (its
    /// elements' bounds hold the limit patch, not the coarse triangle), a displacement that
    /// moves it (it may fold), `flat` on a mesh that intersects itself (`self_intersects`,
    /// asked only then). Where not, the level pass culls elements facing away and the wireframe
    /// the lines of faces turned away (`Scene::front_only`, and `info` alike).
    pub fn may_show_back_faces(&self, self_intersects: impl FnOnce() -> bool) -> bool {
        !self.closed_surface()
            || self.surface.uses_loop_faces()
            || self.params.moves(self.displace)
            || (self.surface == Surface::Flat && self_intersects())
    }

    /// Whether adaptive levels are rounded to powers of two: while the pattern or tess driver
    /// glides (the pattern driver's hierarchical patterns, the tessellator's morph between
    /// them).
    pub fn dyadic_levels(&self) -> bool {
        self.rounding().dyadic()
    }

    /// How the driver rounds adaptive levels and meets a coarser edge, as the level pass
    /// bounds it: for tess while it glides, dyadic levels with its outer ring drawn at the
    /// inner level and snapped onto the edges' samples, else the tessellator's own transitions
    /// at integer levels; the pattern's boundary snapped to the nearest edge sample for pattern
    /// and static (dyadic while the pattern driver glides: its hierarchical patterns; else
    /// integer).
    pub fn rounding(&self) -> crate::lod::frame::Rounding {
        use crate::lod::frame::Rounding;
        if !self.driver.kind().integer_levels() {
            if self.glides() {
                Rounding::Snapped
            } else {
                Rounding::SnappedInteger
            }
        } else if self.glides() {
            Rounding::TessSnapped
        } else {
            Rounding::Integer
        }
    }

    /// This configuration at `drawn`, the largest level an adaptive frame's elements were given
    /// (a power of two at or above it where [`DrawConfig::power_of_two_max`]), where that is
    /// below the largest level and draws the same: not for the height map, whose mip level
    /// follows the largest level, nor where the normal field would move between fragments and
    /// vertices (`loop` from level 16). What `render`, `export` and `bench` draw where the draws
    /// up to the largest level do not fit the device.
    pub fn lowered_to(&self, drawn: u32) -> Option<DrawConfig> {
        let level = if self.power_of_two_max() {
            drawn.next_power_of_two()
        } else {
            drawn
        };
        let lowered = DrawConfig { level, ..*self };
        let same = self.displace != crate::surface::Displace::Heightmap
            && lowered.fragment_normal_field() == self.fragment_normal_field();
        (level < self.level && same).then_some(lowered)
    }

    /// Whether the largest level of an adaptive frame is a power of two: the pattern and
    /// static drivers' (their adaptive patterns are built up to a power of two, whichever
    /// levels they draw), the tess driver's while it glides.
    pub fn power_of_two_max(&self) -> bool {
        !self.driver.kind().integer_levels() || self.dyadic_levels()
    }

    /// Triangles the GPU makes per element.
    pub fn refined_per_element(&self) -> u32 {
        self.driver.refined_per_element(self.level)
    }

    /// Whether the fragment stage evaluates the normal per fragment: the surface has a normal
    /// field of its own (with displacement, the fragment evaluates the displaced normal). Every
    /// driver hands the sample over; `static` then stores each refined vertex's element and sample
    /// beside it. Also `loop` from [`LOOP_FRAGMENT_NORMALS`] up through the pattern and the
    /// tessellator without displacement: its subdivision-shading normal is a second table sum,
    /// which the fragment stage then does instead of every vertex (cheaper where the refined
    /// vertices outnumber the pixels: docs/bench/resolution).
    pub fn fragment_normal_field(&self) -> bool {
        self.surface.fragment_normal_field(
            self.displace,
            self.level,
            !self.driver.kind().refines_on_cpu(),
        )
    }

    /// Whether drawing this reads the elements' records on the GPU: every driver but the
    /// static one, which does only where its fragments evaluate the normal field.
    pub fn reads_records(&self) -> bool {
        !self.driver.kind().refines_on_cpu() || self.fragment_normal_field()
    }

    /// GPU bytes of geometry for `elements` elements ([`Driver::geometry_bytes`], plus the
    /// static buffer's element attributes when the normal field is evaluated per fragment);
    /// with `adaptive`, of an adaptive frame up to `self.level`
    /// ([`DriverKind::adaptive_geometry_bytes`]).
    pub fn geometry_bytes(&self, elements: u64, adaptive: bool) -> u64 {
        let (kind, field) = (self.driver.kind(), self.fragment_normal_field());
        if adaptive {
            kind.adaptive_geometry_bytes(self.level, elements, self.dyadic_levels(), field)
        } else {
            kind.geometry_bytes(self.level, elements, field)
        }
    }
}

/// What the fragment stage shows: its specialization constant `SPEC_VIEW`
/// ([`Renderer::set_view`]), each view's pipelines doing its work alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[repr(u32)]
pub enum View {
    /// Lit surface.
    #[default]
    Shaded = 0,
    /// The normal field as colour.
    Normals = 1,
    /// The lit surface coloured by each element's level (blue at 1 to red at 256).
    Levels = 2,
    /// One colour, unlit: the fragment stage does no work beyond writing it, reads no
    /// varying (the geometry's silhouette; timing what drawing the refined triangles costs
    /// without shading them).
    Plain = 3,
}

impl View {
    pub const ALL: [View; 4] = [View::Shaded, View::Normals, View::Levels, View::Plain];

    pub fn name(self) -> &'static str {
        match self {
            View::Shaded => "shaded",
            View::Normals => "normals",
            View::Levels => "levels",
            View::Plain => "plain",
        }
    }
}

/// `Frame` uniform block (glsl/include/records.glsl), std140.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct FrameUniforms {
    pub view_proj: [[f32; 4]; 4],
    /// xyz: camera position.
    pub eye: [f32; 4],
    /// xyz: direction towards the light; w: 1 where the surface drawn is closed and wound
    /// outwards, its normals pointing out ([`Scene::normals_outward`],
    /// [`DrawConfig::closed_surface`], undisplaced, as a displacement may fold it): the
    /// fragment stage's two-sided lighting then turns a normal facing away on back faces only
    /// (the inside, seen from an eye within the surface), as the rasteriser says
    /// (glsl/shade/shade.frag).
    pub light_dir: [f32; 4],
    /// rgb: surface colour.
    pub base_color: [f32; 4],
    /// The surfaces' and displacements' parameters ([`SurfaceParams::to_gpu`]).
    pub params: [f32; 4],
    /// xyz: [`SurfaceParams::origin`].
    pub origin: [f32; 4],
    /// Unused: keeps the block's offsets and size (what the fragment stage shows is a
    /// specialization constant: [`Renderer::set_view`]).
    pub unused: u32,
    /// The height map displacement's bias ([`SurfaceParams::bias`]).
    pub heightmap_bias: f32,
    /// The height map pyramid level to read ([`Scene::heightmap_lod`]).
    pub heightmap_lod: f32,
    /// The level every element is drawn at; 0 when each is drawn at its own
    /// ([`FrameUniforms::adaptive`]).
    pub level: f32,
}

const _: () = {
    assert!(std::mem::size_of::<FrameUniforms>() == 160);
    assert!(std::mem::offset_of!(FrameUniforms, eye) == 64);
    assert!(std::mem::offset_of!(FrameUniforms, light_dir) == 80);
    assert!(std::mem::offset_of!(FrameUniforms, base_color) == 96);
    assert!(std::mem::offset_of!(FrameUniforms, params) == 112);
    assert!(std::mem::offset_of!(FrameUniforms, origin) == 128);
    assert!(std::mem::offset_of!(FrameUniforms, unused) == 144);
    assert!(std::mem::offset_of!(FrameUniforms, heightmap_bias) == 148);
    assert!(std::mem::offset_of!(FrameUniforms, heightmap_lod) == 152);
};

impl FrameUniforms {
    /// The frame that draws `cfg` of `scene` seen by `camera` on a target of `aspect` (width /
    /// height): lit from above and behind the camera's shoulder, the default
    /// surface colour. The one way every frame (headless, window, benchmark) gets its uniforms.
    pub fn new(camera: &Camera, aspect: f32, cfg: &DrawConfig, scene: &Scene) -> Self {
        let eye = camera.eye();
        let light = eye - camera.target + glam::Vec3::new(0.3, 0.8, 0.2) * camera.distance;
        let params = &cfg.params;
        let one_sided =
            scene.normals_outward && cfg.closed_surface() && cfg.displace == Displace::None;
        Self {
            view_proj: camera.view_proj(aspect).to_cols_array_2d(),
            eye: eye.extend(1.0).to_array(),
            light_dir: (light.normalize())
                .extend(f32::from(u8::from(one_sided)))
                .to_array(),
            base_color: [0.80, 0.55, 0.35, 1.0],
            params: params.to_gpu(),
            origin: params.origin.extend(0.0).to_array(),
            unused: 0,
            heightmap_bias: params.bias,
            heightmap_lod: scene.heightmap_lod(cfg.level),
            level: cfg.level as f32,
        }
    }

    /// The same frame with each element drawn at its own levels (the levels view reads them).
    pub fn adaptive(self) -> Self {
        Self { level: 0.0, ..self }
    }
}

/// `Push` push-constant block (glsl/include/records.glsl): 128 bytes, the guaranteed minimum.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct PushBlock {
    /// The draw's element (`push` submission).
    pub rec: ElementRecord,
    pub draw: DrawWords,
}

/// `Push::draw`: x level N; y first element of the draw; z pattern vertex count; w the draw's
/// element (`push`, `ubo`).
pub type DrawWords = [u32; 4];

const _: () = {
    assert!(std::mem::size_of::<PushBlock>() == 128);
    assert!(std::mem::offset_of!(PushBlock, draw) == 112);
};

/// Byte offset of `PushBlock::draw`.
pub const PUSH_DRAW_OFFSET: u32 = 112;

/// One vertex written by transform feedback (glsl/include/varyings.glsl, `XFB` variant).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct XfbVertex {
    pub position: [f32; 3],
    /// The element sampled, among all the scene's elements (as `CapturedVertex::id` x).
    pub element: u32,
    pub normal: [f32; 3],
    /// The sample's `(w, u, v)` the surface was evaluated at (outer-edge samples snapped).
    pub bary: [f32; 3],
}

const _: () = {
    assert!(std::mem::size_of::<XfbVertex>() == 40);
    assert!(std::mem::offset_of!(XfbVertex, element) == 12);
    assert!(std::mem::offset_of!(XfbVertex, normal) == 16);
    assert!(std::mem::offset_of!(XfbVertex, bary) == 28);
};

/// `CapturedVertex` (glsl/include/records.glsl), std430.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct CapturedVertex {
    /// xyz; w = 1 once written.
    pub position: [f32; 4],
    pub normal: [f32; 4],
    /// The sample as the driver produced it: pattern `(w, u, v)` or `gl_TessCoord`.
    pub coord: [f32; 4],
    /// x: element; y: pattern vertex index, or `u32::MAX` for tess samples.
    pub id: [u32; 4],
}

const _: () = {
    assert!(std::mem::size_of::<CapturedVertex>() == 64);
    assert!(std::mem::offset_of!(CapturedVertex, coord) == 32);
    assert!(std::mem::offset_of!(CapturedVertex, id) == 48);
};
