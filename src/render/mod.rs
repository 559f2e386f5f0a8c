//! Rendering: per-mesh GPU data ([`GpuMesh`]), pipelines ([`Renderer`]) and the three drivers
//! that produce barycentric samples on the GPU (`static`, `pattern`, `tess`, one file each).
//! A driver never knows which surface it draws: the surface is a specialization constant of its
//! evaluation stage.
#![forbid(unsafe_code)]

pub mod bindings;
mod camera;
mod error;
pub mod frame;
mod headless;
pub mod loop_pass;
pub mod pattern;
mod pipelines;
mod scene;
pub mod static_vbo;
pub mod tess;

pub use camera::Camera;
pub use error::RenderError;
pub use headless::{clear_color_srgb8, covered_pixels, CaptureResult, FrameTiming, Headless};
pub use pipelines::{Renderer, GEOMETRY_STAGES, PUSH_STAGES};
pub use scene::{GpuMesh, MeshData, Scene};

use crate::surface::{Displace, ElementRecord, Surface, SurfaceParams, RECORD_BYTES};
use bytemuck::{Pod, Zeroable};

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

/// `--driver static|pattern|tess` (the pattern driver with its default submission; `--submit`
/// picks another).
impl clap::ValueEnum for Driver {
    fn value_variants<'a>() -> &'a [Self] {
        &Driver::ALL
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        let help = match self {
            Driver::Static => "The CPU refines the whole mesh into one vertex buffer (the 2005 paper's baseline)",
            Driver::Pattern(_) => "The refinement pattern is drawn for every coarse triangle; the vertex shader evaluates",
            Driver::Tess => "Vulkan tessellation shaders; the evaluation shader evaluates",
        };
        Some(clap::builder::PossibleValue::new(self.name()).help(help))
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

    pub fn name(self) -> &'static str {
        match self {
            Driver::Static => "static",
            Driver::Pattern(_) => "pattern",
            Driver::Tess => "tess",
        }
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

    /// Triangles the GPU makes per element at `level`: the pattern's level² (also what `static`
    /// stores), or what the tessellator makes.
    pub fn refined_per_element(self, level: u32) -> u32 {
        match self {
            Driver::Tess => tess::tess_triangle_count(level),
            Driver::Static | Driver::Pattern(_) => crate::pattern::triangle_count(level),
        }
    }

    /// GPU bytes of geometry this driver holds for `elements` elements at `level`
    /// (pattern: that level's pattern + the records; static: the refined buffers; tess: records).
    pub fn geometry_bytes(self, level: u32, elements: u64) -> u64 {
        use crate::pattern::{index_count, vertex_count};
        let records = elements * RECORD_BYTES as u64;
        let pv = vertex_count(level) as u64;
        let pi = index_count(level) as u64;
        match self {
            Driver::Static => {
                let vertex = std::mem::size_of::<static_vbo::StaticVertex>() as u64;
                elements * pv * vertex + elements * pi * 4
            }
            Driver::Pattern(_) => pv * 12 + pi * 4 + records,
            Driver::Tess => records,
        }
    }

    /// Room a vertex capture needs per element at `level` (tess: every tessellator vertex twice,
    /// since implementations may repeat evaluation invocations); `None` where nothing runs on the
    /// GPU to capture.
    pub fn capture_per_element(self, level: u32) -> Option<u32> {
        match self {
            Driver::Static => None,
            Driver::Pattern(_) => Some(crate::pattern::vertex_count(level)),
            Driver::Tess => Some(2 * tess::tess_vertex_count(level)),
        }
    }
}

/// How the `pattern` driver hands each coarse triangle's record to the vertex shader.
/// The discriminant is the `SUBMIT` specialization constant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
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
    /// Suffix of the shader variant in the embedded table.
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
    pub params: SurfaceParams,
    pub driver: Driver,
    pub level: u32,
}

/// The level from which `loop` evaluates its normals per fragment ([`DrawConfig::fragment_normal_field`]):
/// 153 pattern vertices per M1 face, about as many refined vertices as pixels for Spot at 1280×720.
pub const LOOP_FRAGMENT_NORMALS: u32 = 16;

impl DrawConfig {
    /// The flat surface, no displacement, default parameters.
    pub fn new(driver: Driver, level: u32) -> Self {
        Self {
            surface: Surface::Flat,
            displace: Displace::None,
            params: SurfaceParams::default(),
            driver,
            level,
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

    /// Triangles the GPU makes per coarse triangle.
    pub fn refined_per_coarse(&self) -> u32 {
        self.driver.refined_per_element(self.level)
    }

    /// Whether the fragment stage evaluates the normal per fragment: the surface has a normal
    /// field of its own (with displacement, the fragment evaluates the displaced normal). Every
    /// driver hands the sample over; `static` then stores each refined vertex's element and sample
    /// beside it. Also `loop` from [`LOOP_FRAGMENT_NORMALS`] up through the pattern and the
    /// tessellator without displacement: its subdivision-shading normal is a second table sum,
    /// which the fragment stage then does instead of every vertex (cheaper where the refined
    /// vertices outnumber the pixels: about 15 % of loop's frame at level 32 on lavapipe).
    pub fn fragment_normal_field(&self) -> bool {
        self.surface.fragment_normal_field()
            || (self.surface == Surface::Loop
                && self.displace == Displace::None
                && self.driver != Driver::Static
                && self.level >= LOOP_FRAGMENT_NORMALS)
    }

    /// GPU bytes of geometry for `elements` elements ([`Driver::geometry_bytes`], plus the
    /// static buffer's element attributes when the normal field is evaluated per fragment).
    pub fn geometry_bytes(&self, elements: u64) -> u64 {
        let extra = if self.driver == Driver::Static && self.fragment_normal_field() {
            elements
                * crate::pattern::vertex_count(self.level) as u64
                * std::mem::size_of::<static_vbo::ElementVertex>() as u64
        } else {
            0
        };
        self.driver.geometry_bytes(self.level, elements) + extra
    }
}

/// `Frame` uniform block (glsl/include/records.glsl), std140.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct FrameUniforms {
    pub view_proj: [[f32; 4]; 4],
    pub eye: [f32; 4],
    pub light_dir: [f32; 4],
    pub base_color: [f32; 4],
    /// x: view (0 shaded, 1 normals).
    pub options: [f32; 4],
    /// The surfaces' and displacements' parameters ([`SurfaceParams::to_gpu`]).
    pub params: [f32; 4],
    /// xyz: [`SurfaceParams::origin`].
    pub origin: [f32; 4],
    /// x: height map bias; y: height map pyramid level ([`Scene::heightmap_lod`]).
    pub extra: [f32; 4],
}

const _: () = {
    assert!(std::mem::size_of::<FrameUniforms>() == 176);
    assert!(std::mem::offset_of!(FrameUniforms, eye) == 64);
    assert!(std::mem::offset_of!(FrameUniforms, light_dir) == 80);
    assert!(std::mem::offset_of!(FrameUniforms, base_color) == 96);
    assert!(std::mem::offset_of!(FrameUniforms, options) == 112);
    assert!(std::mem::offset_of!(FrameUniforms, params) == 128);
};

impl FrameUniforms {
    /// The view of `camera` on a target of `aspect` (width / height), lit from above and behind
    /// the camera's shoulder, the default surface colour, every view option off, `params` for
    /// the surfaces.
    pub fn new(camera: &Camera, aspect: f32, params: &SurfaceParams) -> Self {
        let eye = camera.eye();
        let light = eye - camera.target + glam::Vec3::new(0.3, 0.8, 0.2) * camera.distance;
        Self {
            view_proj: camera.view_proj(aspect).to_cols_array_2d(),
            eye: eye.extend(1.0).to_array(),
            light_dir: light.normalize().extend(0.0).to_array(),
            base_color: [0.80, 0.55, 0.35, 1.0],
            options: [0.0; 4],
            params: params.to_gpu(),
            origin: params.origin.extend(0.0).to_array(),
            extra: [params.bias, 0.0, 0.0, 0.0],
        }
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
    pub _pad0: f32,
    pub normal: [f32; 3],
    pub _pad1: f32,
}

const _: () = assert!(std::mem::size_of::<XfbVertex>() == 32);

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
