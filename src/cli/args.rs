//! The command line's arguments: `meshrefine view | render | export | info | bench`, declared
//! with clap's derive. Options that take a library value (surface, displacement, driver, ...)
//! parse through [`choices`], which maps names to the library's enums.
#![forbid(unsafe_code)]

use super::choices::{self, Trimmed};
pub use super::numbers::TypedF32;
use super::numbers::{typed_f32, typed_vec3, whole_in, whole_number, TypedVec3};
use clap::{Args, Parser, Subcommand};
use meshrefine::render::{Driver, Submit};
use meshrefine::surface::loop_::Boundary;
use meshrefine::surface::{Displace, NormalField, Seams, Surface};
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "meshrefine",
    version,
    about = "Refine coarse triangle meshes on the GPU (Vulkan)"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
    /// Enable the Vulkan validation layer (also: MESHREFINE_VALIDATE=1).
    #[arg(long, global = true)]
    pub validate: bool,
    /// Use the first Vulkan device whose name contains NAME (case-insensitive).
    #[arg(long, global = true, value_name = "NAME", value_parser = Trimmed(clap::builder::StringValueParser::new()))]
    pub device: Option<String>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Open the window demo (headless render to a PNG when no display exists).
    #[command(after_help = meshrefine::app::KEY_HELP)]
    View(ViewArgs),
    /// Render a mesh headlessly to a PNG.
    Render(RenderArgs),
    /// Write the refined mesh, read back from the GPU's drawing pipeline, as OBJ.
    Export(ExportArgs),
    /// Mesh statistics; with --level, the GPU geometry bytes of each driver.
    Info(InfoArgs),
    /// Time every driver and submission mode on a mesh (ratios against `static`).
    Bench(BenchArgs),
    /// List the Vulkan devices and the features meshrefine uses on each (the first is the
    /// default; --device NAME picks another).
    Devices,
}

/// The surfaces' and displacements' parameters.
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Surface parameters")]
pub struct ParamOpts {
    /// Phong tessellation's shape factor, within [0, 1].
    #[arg(long, value_parser = Trimmed(typed_f32), allow_hyphen_values = true, default_value = "0.75")]
    pub alpha: TypedF32,
    /// Displacement amplitude in the mesh's units (default: 3% of its bounding radius).
    #[arg(long, value_parser = Trimmed(typed_f32), allow_hyphen_values = true)]
    pub amplitude: Option<TypedF32>,
    /// Displacement frequency per mesh unit (default: 24 / bounding radius).
    #[arg(long, value_parser = Trimmed(typed_f32), allow_hyphen_values = true)]
    pub frequency: Option<TypedF32>,
    /// Octaves of the noise displacement (1 to 8).
    #[arg(long, allow_hyphen_values = true, default_value = "1", value_parser = Trimmed(whole_number))]
    pub octaves: String,
    /// PN and Phong geometry at split normals (a position with several vn): `closed` is
    /// crack-free, `open` is the papers' behaviour (cracks).
    #[arg(long, value_parser = choices::seams(), default_value = "closed")]
    pub pn_seams: Seams,
    /// The normal field of pn and stpn (what shading and displacement use; docs/surfaces.md
    /// compares them).
    #[arg(long, value_parser = choices::normal_field(), default_value = NormalField::default().name())]
    pub normal_field: NormalField,
    /// Height map displacement: P' = P + a·(h − bias)·N, h in [0, 1].
    #[arg(long, value_parser = Trimmed(typed_f32), default_value = "0", allow_hyphen_values = true)]
    pub bias: TypedF32,
    /// Loop subdivision's boundaries (--surface loop): `edge-only` keeps boundary edges sharp
    /// (OpenSubdiv's VTX_BOUNDARY_EDGE_ONLY), `edge-and-corner` also pins boundary vertices of
    /// valence 2 (VTX_BOUNDARY_EDGE_AND_CORNER).
    #[arg(long, value_parser = choices::boundary(), default_value = "edge-only")]
    pub boundary: Boundary,
    /// The loop surface's basis function tables' level (--surface loop): 2^N segments per
    /// M1-face edge, the lattice whose points are exact limit points; each level up takes four
    /// times the memory.
    #[arg(long, allow_hyphen_values = true, default_value_t = meshrefine::surface::loop_::DEFAULT_LMAX,
          value_parser = Trimmed(whole_in(0..=u32::MAX)))]
    pub bft_level: u32,
}

/// Surface and displacement.
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Surface and displacement")]
pub struct SurfaceOpts {
    /// Surface defined by each coarse triangle (default: curved PN triangles, smooth out of the
    /// box).
    #[arg(long, value_parser = choices::surface(), default_value = "pn")]
    pub surface: Surface,
    #[command(flatten)]
    pub drawn: DrawnOpts,
}

/// What the surface is drawn with besides which surface it is: its displacement, inputs and
/// parameters (render's options, which `info --pixel-error` reads too).
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Surface and displacement")]
pub struct DrawnOpts {
    /// Displacement along the surface's normal.
    #[arg(long, value_parser = choices::displace(), default_value = "none")]
    pub displace: Displace,
    /// Grayscale PNG (8 or 16 bits) for --displace heightmap, sampled at the mesh's texture
    /// coordinates (default: a generated map of smooth bumps).
    #[arg(value_parser = choices::path(), long, value_name = "FILE.png")]
    pub heightmap: Option<PathBuf>,
    /// Scalar tags for --surface stpn (lines `t X Y Z TENSION [SHARPNESS BIAS DX DY DZ]`;
    /// default: tags derived from the mesh's hard edges).
    #[arg(value_parser = choices::path(), long, value_name = "FILE")]
    pub tags: Option<PathBuf>,
    /// For --surface stpn without --tags (or under it): edges whose faces meet at more than this
    /// many degrees are creases too (default: only positions with two vn are).
    #[arg(long, allow_hyphen_values = true, value_name = "DEGREES", value_parser = Trimmed(typed_f32))]
    pub crease_angle: Option<TypedF32>,
    #[command(flatten)]
    pub params: ParamOpts,
}

#[derive(Args, Debug, Clone)]
pub struct Technique {
    #[command(flatten)]
    pub surface: SurfaceOpts,
    /// How barycentric samples are produced on the GPU.
    #[arg(long, value_parser = choices::driver(), default_value = "pattern", help_heading = "Driver and level")]
    pub driver: Driver,
    /// How the pattern driver hands each coarse triangle to the vertex shader [default:
    /// instanced]. Only for --driver pattern (`view` may switch to it).
    #[arg(long, value_parser = choices::submit(), help_heading = "Driver and level")]
    pub submit: Option<Submit>,
    /// Refinement level N: N segments per coarse edge, N² triangles per coarse triangle (the tess
    /// driver's rings about 1.5 N²), every element at it (render and view draw adaptively, at
    /// 1 px, unless it is given; the window's uniform mode, `M`, starts at it).
    #[arg(long, allow_hyphen_values = true, default_value_t = 16, value_parser = level(), help_heading = "Driver and level")]
    pub level: u32,
}

impl Technique {
    /// The submission mode: the one given, else `instanced`.
    pub fn submit(&self) -> Submit {
        self.submit.unwrap_or(Submit::Instanced)
    }
}

#[derive(Args, Debug)]
pub struct ViewArgs {
    /// OBJ file (default: the embedded Spot control mesh).
    #[arg(value_parser = choices::path())]
    pub mesh: Option<PathBuf>,
    #[command(flatten)]
    pub technique: Technique,
    /// Exit after N frames (at least 1).
    #[arg(long, allow_hyphen_values = true, value_parser = Trimmed(whole_in(1..=u32::MAX)), help_heading = "Window")]
    pub frames: Option<u32>,
    /// Save the last frame to this PNG file.
    #[arg(value_parser = choices::path(), long, value_name = "FILE.png", help_heading = "Window")]
    pub screenshot: Option<PathBuf>,
    /// Start with a wireframe on: the refined edges (the default when no value is given, or
    /// when a mesh path follows), the cage (the coarse mesh's edges) or both.
    #[arg(long, value_name = "WHAT", num_args = 0..=1, default_missing_value = "refined",
          value_parser = super::choices::wireframe(), help_heading = "Window")]
    pub wireframe: Option<meshrefine::render::cage::Wireframe>,
    /// What the window shows at the start (N switches), and the headless fallback's image.
    #[arg(long, default_value = "shaded", value_parser = super::choices::view(), help_heading = "Window")]
    pub view: meshrefine::render::View,
    /// Start with the coarse-mesh animation on.
    #[arg(long, help_heading = "Window")]
    pub animate: bool,
    /// On a software device, draw what is asked even when a frame takes over a second (by
    /// default the window lowers the level to keep frames under a second, and says so).
    #[arg(long, help_heading = "Window")]
    pub no_frame_budget: bool,
    /// Start with level of detail on: the level is chosen by distance to the camera among the
    /// pattern set (powers of two up to --level).
    #[arg(long, help_heading = "Window")]
    pub lod: bool,
    /// Multisampled anti-aliasing: samples per pixel, 1 (none), 2, 4 or 8 (default: 4 where
    /// the device supports it for colour and depth attachments, else the most it supports).
    #[arg(long, allow_hyphen_values = true, value_parser = msaa_counts(), help_heading = "Window")]
    pub msaa: Option<u32>,
    /// Where the headless fallback writes its image when no display exists.
    #[arg(
        long,
        value_parser = choices::path(),
        value_name = "FILE.png",
        default_value = "meshrefine-view.png",
        help_heading = "Window"
    )]
    pub headless_output: PathBuf,
    /// The window's width (and the headless fallback image's), in pixels at scale factor 1.
    #[arg(long, allow_hyphen_values = true, default_value_t = 1280, value_parser = image_side(), help_heading = "Window")]
    pub width: u32,
    /// The window's height (and the headless fallback image's), in pixels at scale factor 1.
    #[arg(long, allow_hyphen_values = true, default_value_t = 720, value_parser = image_side(), help_heading = "Window")]
    pub height: u32,
    /// Start borderless fullscreen on the window's monitor (F11 toggles; leaving it returns
    /// to --width x --height).
    #[arg(long, help_heading = "Window")]
    pub fullscreen: bool,
    /// Start with the overlay panel hidden (H shows it), as screenshots then show the scene
    /// alone.
    #[arg(long, help_heading = "Window")]
    pub hide_panel: bool,
    /// What the mesh is drawn on (B toggles).
    #[arg(long, default_value = "dark", value_parser = super::choices::background(),
          help_heading = "Window")]
    pub background: meshrefine::render::Background,
    /// Where the screenshot key (F12) writes meshrefine-<n>.png, an existing directory
    /// (default: the current directory).
    #[arg(value_parser = choices::path(), long, value_name = "DIR", help_heading = "Window")]
    pub screenshot_dir: Option<PathBuf>,
    #[command(flatten)]
    pub adaptive: AdaptiveOpts,
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// OBJ file (default: the embedded Spot control mesh).
    #[arg(value_parser = choices::path())]
    pub mesh: Option<PathBuf>,
    /// Output PNG.
    #[arg(
        short,
        long,
        value_parser = choices::path(),
        value_name = "FILE.png",
        default_value = "meshrefine.png",
        help_heading = "Output"
    )]
    pub output: PathBuf,
    /// The image's width in pixels.
    #[arg(long, allow_hyphen_values = true, default_value_t = 1280, value_parser = image_side(), help_heading = "Output")]
    pub width: u32,
    /// The image's height in pixels.
    #[arg(long, allow_hyphen_values = true, default_value_t = 720, value_parser = image_side(), help_heading = "Output")]
    pub height: u32,
    /// Draw a wireframe: the refined edges (the default when no value is given, or when a mesh
    /// path follows), the cage (the coarse mesh's edges) or both.
    #[arg(long, value_name = "WHAT", num_args = 0..=1, default_missing_value = "refined",
          value_parser = super::choices::wireframe(), help_heading = "Output")]
    pub wireframe: Option<meshrefine::render::cage::Wireframe>,
    /// What the image shows.
    #[arg(long, default_value = "shaded", value_parser = super::choices::view(),
          help_heading = "Output")]
    pub view: meshrefine::render::View,
    /// What the image is drawn on.
    #[arg(long, default_value = "dark", value_parser = super::choices::background(),
          help_heading = "Output")]
    pub background: meshrefine::render::Background,
    /// Multisampled anti-aliasing: samples per pixel, 1 (none), 2, 4 or 8 (default: 4 where
    /// the device supports it for colour and depth attachments, else the most it supports).
    #[arg(long, allow_hyphen_values = true, value_parser = msaa_counts(), help_heading = "Output")]
    pub msaa: Option<u32>,
    #[command(flatten)]
    pub technique: Technique,
    #[command(flatten)]
    pub adaptive: AdaptiveOpts,
}

#[derive(Args, Debug)]
pub struct ExportArgs {
    /// OBJ file (default: the embedded Spot control mesh).
    #[arg(value_parser = choices::path())]
    pub mesh: Option<PathBuf>,
    /// Output OBJ.
    #[arg(value_parser = choices::path(), short, long, value_name = "FILE.obj", help_heading = "Output")]
    pub output: PathBuf,
    #[command(flatten)]
    pub surface: SurfaceOpts,
    /// Whose GPU evaluation to read back (static evaluates on the CPU: nothing to read back).
    #[arg(
        long,
        value_parser = Trimmed(clap::builder::EnumValueParser::<ExportDriver>::new()),
        default_value = "pattern",
        help_heading = "Driver and level"
    )]
    pub driver: ExportDriver,
    /// How the pattern driver hands each coarse triangle to the vertex shader [default:
    /// instanced]. Only for --driver pattern.
    #[arg(long, value_parser = choices::submit(), help_heading = "Driver and level")]
    pub submit: Option<Submit>,
    /// Refinement level N: N segments per coarse edge.
    #[arg(long, allow_hyphen_values = true, default_value_t = 16, value_parser = level(), help_heading = "Driver and level")]
    pub level: u32,
    #[command(flatten)]
    pub adaptive: AdaptiveOpts,
    /// The image's width in pixels the levels are chosen for (with --pixel-error).
    #[arg(long, allow_hyphen_values = true, default_value_t = 1280, value_parser = image_side(), help_heading = "Adaptive drawing")]
    pub width: u32,
    /// The image's height in pixels the levels are chosen for (with --pixel-error).
    #[arg(long, allow_hyphen_values = true, default_value_t = 720, value_parser = image_side(), help_heading = "Adaptive drawing")]
    pub height: u32,
}

/// The drivers whose evaluated geometry can be read back.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportDriver {
    /// The refinement pattern's vertices, as the vertex shader evaluated them.
    Pattern,
    /// The tessellator's triangles, by transform feedback.
    Tess,
}

impl ExportDriver {
    /// The driver it names (the command line's one mapping onto [`Driver`]).
    pub fn driver(self) -> Driver {
        match self {
            ExportDriver::Pattern => Driver::Pattern(Submit::Instanced),
            ExportDriver::Tess => Driver::Tess,
        }
    }
}

impl ExportArgs {
    pub fn technique(&self) -> Technique {
        Technique {
            surface: self.surface.clone(),
            driver: self.driver.driver(),
            submit: self.submit,
            level: self.level,
        }
    }
}

#[derive(Args, Debug)]
pub struct InfoArgs {
    /// OBJ file (default: the embedded Spot control mesh).
    #[arg(value_parser = choices::path())]
    pub mesh: Option<PathBuf>,
    /// Also print the GPU geometry bytes each driver would hold at this level.
    #[arg(long, allow_hyphen_values = true, value_parser = level(), help_heading = "Driver and level")]
    pub level: Option<u32>,
    /// Also report what this surface builds (`loop`: M1, valences, configurations and the basis
    /// function tables' memory).
    #[arg(long, value_parser = choices::surface(), help_heading = "Surface and displacement")]
    pub surface: Option<Surface>,
    /// The displacement, inputs and parameters of the surface whose levels are reported (with
    /// --pixel-error; Loop's --boundary and --bft-level also with --surface loop): the levels
    /// and the default camera are those of the surface as render draws it.
    #[command(flatten)]
    pub drawn: DrawnOpts,
    /// Report the level adaptive refinement gives each element for this pixel error, seen by
    /// the camera below: the level histogram and the triangles against the smallest uniform
    /// level that meets the same bound (--surface, default pn; not with --level). The levels
    /// are those render draws with the same options.
    #[arg(long, value_parser = Trimmed(typed_f32), allow_hyphen_values = true, help_heading = "Adaptive drawing")]
    pub pixel_error: Option<TypedF32>,
    #[command(flatten)]
    pub camera: CameraOpts,
    /// Leave out of the report the elements outside the view or, on a closed mesh wound
    /// outwards seen from outside, facing away from the eye, as render culls them (with
    /// --pixel-error; default: on, as render).
    #[arg(long, value_parser = choices::cull(), help_heading = "Adaptive drawing")]
    pub cull: Option<bool>,
    /// The largest level any element gets (with --pixel-error): a power of two for the pattern
    /// and static drivers, as render's.
    #[arg(long, allow_hyphen_values = true, default_value_t = 64, value_parser = level(), help_heading = "Adaptive drawing")]
    pub max_level: u32,
    /// The driver whose rounding of the levels is reported (with --pixel-error): pattern and
    /// tess draw powers of two while geomorphing, any integer without; static any integer.
    #[arg(long, value_parser = choices::driver(), default_value = "pattern", help_heading = "Adaptive drawing")]
    pub driver: Driver,
    /// Whether the reported drawing geomorphs (with --pixel-error; default: on, as render's):
    /// pattern then draws powers of two, tess too under a --max-level that is one.
    #[arg(long, value_parser = choices::geomorph(), help_heading = "Adaptive drawing")]
    pub geomorph: Option<bool>,
}

impl InfoArgs {
    /// The surface options as render reads them: the surface whose levels are reported (pn
    /// unless --surface), its displacement, inputs and parameters.
    pub fn surface_opts(&self) -> SurfaceOpts {
        SurfaceOpts {
            surface: self.surface.unwrap_or(Surface::Pn),
            drawn: self.drawn.clone(),
        }
    }
}

/// A camera in the mesh's own coordinates (up is +Y); the default is render's: the camera
/// fitted to the surface as drawn.
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Camera (with --pixel-error)")]
pub struct CameraOpts {
    #[command(flatten)]
    pub viewpoint: ViewpointOpts,
    /// The image's width in pixels.
    #[arg(long, allow_hyphen_values = true, default_value_t = 1280, value_parser = image_side())]
    pub width: u32,
    /// The image's height in pixels (the metric counts pixels of this height).
    #[arg(long, allow_hyphen_values = true, default_value_t = 720, value_parser = image_side())]
    pub height: u32,
}

/// Where the camera is and where it looks, in the mesh's own coordinates (up is +Y); the
/// default is the camera fitted to the surface as drawn (displacement included) at `--fov`,
/// the same for every command; an `--eye` or `--look-at` given alone keeps the other from it.
#[derive(Args, Debug, Clone)]
pub struct ViewpointOpts {
    /// Camera position X,Y,Z (default: the fitted camera's, which frames the surface as
    /// drawn).
    #[arg(long, value_parser = Trimmed(typed_vec3), allow_hyphen_values = true)]
    pub eye: Option<TypedVec3>,
    /// The point looked at X,Y,Z (default: the fitted camera's target).
    #[arg(long, value_parser = Trimmed(typed_vec3), allow_hyphen_values = true)]
    pub look_at: Option<TypedVec3>,
    /// Vertical field of view in degrees (without --eye the camera is fitted with it: the
    /// surface fills the image as at 45 degrees, until at wide angles the eye, kept outside the
    /// surface's reach, stays back and the surface takes less of the image).
    #[arg(long, value_parser = Trimmed(typed_f32), allow_hyphen_values = true, default_value = "45")]
    pub fov: TypedF32,
}

/// Adaptive drawing: each element at the level a pixel error asks for, seen by a camera.
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Adaptive drawing")]
pub struct AdaptiveOpts {
    /// Draw adaptively: each element at the level that keeps the surface within this many
    /// pixels of the drawn mesh, seen by the camera below (a distance d at point p counts
    /// d * K / |p - eye| pixels, K = height / (2 tan(fov / 2)): off the view axis the screen
    /// can show up to 1/cos² of the angle more).
    // Each command's default ends these options' help (`options::command`).
    #[arg(long, value_parser = Trimmed(typed_f32), allow_hyphen_values = true)]
    pub pixel_error: Option<TypedF32>,
    /// The largest level any element gets when drawing adaptively, at most what the device
    /// draws.
    #[arg(long, allow_hyphen_values = true, value_parser = level())]
    pub max_level: Option<u32>,
    /// Draw nothing of the elements outside the view or facing away (when drawing adaptively).
    #[arg(long, value_parser = choices::cull())]
    pub cull: Option<bool>,
    /// Glide the vertices a finer level adds from their coarser neighbours' midpoint to the
    /// surface as the level grows, so nothing pops when levels change (when drawing
    /// adaptively; default: on). While gliding, edges glide at least as far as the insides
    /// beside them need: the pixel error is proven where a triangle's vertices glide together,
    /// checked but not proven where they glide by different amounts (docs/adaptivity.md,
    /// "Gliding edges"); off, it is proven.
    #[arg(long, value_parser = choices::geomorph())]
    pub geomorph: Option<bool>,
    #[command(flatten, next_help_heading = "Camera")]
    pub viewpoint: ViewpointOpts,
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// OBJ file (default: the embedded Spot control mesh).
    #[arg(value_parser = choices::path())]
    pub mesh: Option<PathBuf>,
    /// Surfaces to measure (comma separated).
    #[arg(long, value_parser = choices::surface(), value_delimiter = ',', default_value = "flat", help_heading = "Measurement")]
    pub surfaces: Vec<Surface>,
    /// Displacements to measure with every surface (comma separated).
    #[arg(long, value_parser = choices::displace(), value_delimiter = ',', default_value = "none", help_heading = "Measurement")]
    pub displacements: Vec<Displace>,
    /// Drivers to measure (comma separated; default: every driver and submission mode; `pattern`
    /// means all three submissions; the ratios to static need `static` among them).
    #[arg(long, value_parser = choices::driver(), value_delimiter = ',', help_heading = "Measurement")]
    pub drivers: Vec<Driver>,
    #[command(flatten)]
    pub params: ParamOpts,
    /// Levels to measure (comma separated).
    #[arg(long, allow_hyphen_values = true, value_delimiter = ',', default_value = "8,16,32,64",
          value_parser = level(), help_heading = "Measurement")]
    pub levels: Vec<u32>,
    /// Also write the results to PREFIX.md (with this command line), PREFIX.csv and PREFIX.json
    /// (a PREFIX ending in .md, .csv or .json names the three without it).
    #[arg(long, value_name = "PREFIX", value_parser = out_prefix(), help_heading = "Measurement")]
    pub out: Option<PathBuf>,
    /// Timed frames per variant (after one warm-up frame; 1 to 100000).
    #[arg(long, allow_hyphen_values = true, default_value_t = 5, value_parser = Trimmed(whole_in(1..=100_000)), help_heading = "Measurement")]
    pub frames: u32,
    /// Keep timing past --frames until every variant has this many GPU milliseconds in total
    /// (at most 20 x --frames frames): more samples for short frames, whose timestamps jitter.
    #[arg(
        long,
        value_name = "MS",
        value_parser = Trimmed(typed_f32),
        default_value = "0",
        allow_hyphen_values = true,
        help_heading = "Measurement"
    )]
    pub min_total_ms: TypedF32,
    /// Grayscale PNG (8 or 16 bits) for --displacements heightmap, sampled at the mesh's
    /// texture coordinates (default: a generated map of smooth bumps).
    #[arg(value_parser = choices::path(), long, value_name = "FILE.png", help_heading = "Measurement")]
    pub heightmap: Option<PathBuf>,
    /// The offscreen image's width in pixels.
    #[arg(long, allow_hyphen_values = true, default_value_t = 1280, value_parser = image_side(), help_heading = "Measurement")]
    pub width: u32,
    /// The offscreen image's height in pixels.
    #[arg(long, allow_hyphen_values = true, default_value_t = 720, value_parser = image_side(), help_heading = "Measurement")]
    pub height: u32,
    /// What the frames show: `plain` draws the surface in one unlit colour, so that the times
    /// are the refined triangles' alone (no fragment work; the `shaded` default lights each
    /// pixel, evaluating pn's normal field per fragment).
    #[arg(long, default_value = "shaded", value_parser = super::choices::view(),
          help_heading = "Measurement")]
    pub view: meshrefine::render::View,
    #[command(flatten)]
    pub adaptive: AdaptiveOpts,
    /// With --pixel-error: leave out the uniform rows at the smallest level meeting the same
    /// bound and at the smallest power of two at or above it (the levels given by --levels are
    /// still timed).
    #[arg(long, help_heading = "Adaptive drawing")]
    pub no_bound_levels: bool,
}

/// The largest image side, in pixels, any command takes (`--width`, `--height`): the largest
/// `maxImageDimension2D` of common devices (lavapipe's too); a device that draws less refuses
/// the image in one sentence when it is made.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// `--width`, `--height`: 1 to [`MAX_IMAGE_SIDE`], in every command a usage error (status 2)
/// outside.
fn image_side() -> Trimmed<impl Fn(&str) -> Result<u32, String> + Clone + Send + Sync> {
    Trimmed(whole_in(1..=MAX_IMAGE_SIDE))
}

/// `--level`, `--max-level`, an item of bench's `--levels`: 1 to 1024.
fn level() -> Trimmed<impl Fn(&str) -> Result<u32, String> + Clone + Send + Sync> {
    Trimmed(whole_in(1..=1024))
}

/// `bench --out`'s prefix: one of the files it names (`run.csv`) stands for the three
/// (`run`), the extension left out in any case; any other path is the prefix as given (its
/// bytes kept: a path need not be UTF-8).
fn out_prefix() -> impl clap::builder::TypedValueParser<Value = PathBuf> {
    use clap::builder::TypedValueParser as _;
    choices::path().map(|path| {
        let written = (path.extension().and_then(|e| e.to_str())).is_some_and(|e| {
            ["md", "csv", "json"]
                .iter()
                .any(|x| e.eq_ignore_ascii_case(x))
        });
        if written {
            path.with_extension("")
        } else {
            path
        }
    })
}

/// `--msaa`: 1, 2, 4 or 8.
fn msaa_counts() -> impl clap::builder::TypedValueParser<Value = u32> {
    use clap::builder::TypedValueParser as _;
    Trimmed(clap::builder::PossibleValuesParser::new([
        "1", "2", "4", "8",
    ]))
    .map(|s| s.parse::<u32>().expect("a possible value"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory as _;
    use std::any::TypeId;

    /// Every option that takes a number takes a negative one as its value (`--frequency
    /// -1e-30`, which clap's own test of a negative number misses), so that the option's own
    /// check answers rather than clap's "unexpected argument".
    #[test]
    fn every_numeric_option_takes_hyphen_values() {
        let numbers = [
            TypeId::of::<f32>(),
            TypeId::of::<f64>(),
            TypeId::of::<u32>(),
            TypeId::of::<u64>(),
            TypeId::of::<TypedF32>(),
            TypeId::of::<[f32; 3]>(),
            TypeId::of::<TypedVec3>(),
        ];
        let cli = Cli::command();
        let mut seen = 0;
        for sub in cli.get_subcommands() {
            for arg in sub.get_arguments().filter(|a| a.get_long().is_some()) {
                let id = arg.get_value_parser().type_id();
                if numbers.iter().any(|t| id == *t) {
                    seen += 1;
                    assert!(
                        arg.is_allow_hyphen_values_set(),
                        "{} --{}",
                        sub.get_name(),
                        arg.get_long().unwrap()
                    );
                }
            }
        }
        assert!(seen > 40, "{seen}");
    }

    /// `bench --out` naming one of its files (any case) stands for the three; other paths are
    /// the prefix as given.
    #[test]
    fn bench_out_names_the_prefix() {
        let prefix = |v: &str| match Cli::try_parse_from(["meshrefine", "bench", "--out", v]) {
            Ok(Cli {
                command: Command::Bench(b),
                ..
            }) => b.out.unwrap(),
            other => panic!("{other:?}"),
        };
        for (given, meant) in [
            ("run.md", "run"),
            ("dir/run.CSV", "dir/run"),
            ("run.json", "run"),
            ("run.2026", "run.2026"),
            ("run", "run"),
            (".md", ".md"),
        ] {
            assert_eq!(prefix(given), PathBuf::from(meant), "{given}");
        }
    }

    /// `--width` and `--height` are checked by clap alike in every command: 0 and
    /// MAX_IMAGE_SIDE + 1 are usage errors, MAX_IMAGE_SIDE is taken.
    #[test]
    fn image_sides_are_checked_alike_in_every_command() {
        for command in ["render", "view", "export", "info", "bench"] {
            for option in ["--width", "--height"] {
                let parse = |v: &str| {
                    let mut args = vec!["meshrefine", command, option, v];
                    if command == "export" {
                        args.extend(["-o", "x.obj"]);
                    }
                    Cli::try_parse_from(args)
                };
                for bad in ["0", "16385", "-1"] {
                    let e = parse(bad).expect_err(bad);
                    assert_eq!(e.kind(), clap::error::ErrorKind::ValueValidation, "{e}");
                }
                parse("16384").unwrap();
            }
        }
    }

    /// What is no whole number, given to an option that takes one, is called so (not the
    /// integer parser's "invalid digit"); a whole number out of range names the range.
    #[test]
    fn integer_options_call_other_values_no_whole_number() {
        let cases: [&[&str]; 8] = [
            &["render", "--level", "2.5"],
            &["render", "--width", "1e3"],
            &["export", "-o", "x.obj", "--height", "7.0"],
            &["info", "--max-level", "64 "],
            &["bench", "--levels", "2 4"],
            &["bench", "--levels", "2,4.5"],
            &["bench", "--frames", "ten"],
            &["render", "--bft-level", "x"],
        ];
        for args in cases {
            let e = Cli::try_parse_from([&["meshrefine"][..], args].concat());
            match (args[2].trim(), e) {
                // Spaces around a number are left out.
                ("64", Ok(_)) => {}
                (_, Err(e)) => {
                    assert_eq!(e.kind(), clap::error::ErrorKind::ValueValidation, "{e}");
                    assert!(
                        e.to_string().contains(": not a whole number"),
                        "{args:?}: {e}"
                    );
                }
                (_, Ok(_)) => panic!("{args:?} parsed"),
            }
        }
        let e = Cli::try_parse_from(["meshrefine", "render", "--level", "2000"]).unwrap_err();
        assert!(e.to_string().contains("2000 is not in 1..=1024"), "{e}");
        let e = Cli::try_parse_from(["meshrefine", "bench", "--frames", "100001"]).unwrap_err();
        assert!(e.to_string().contains("100001 is not in 1..=100000"), "{e}");
        Cli::try_parse_from(["meshrefine", "bench", "--frames", "100000"]).unwrap();
        // A sign and leading zeros are read; a negative number or one past every integer type
        // names the range (a long one cut to 40 characters), a character that shows nothing is
        // named escaped.
        let level = |v: &str| match Cli::try_parse_from(["meshrefine", "render", "--level", v]) {
            Ok(Cli {
                command: Command::Render(r),
                ..
            }) => Ok(r.technique.level),
            Ok(_) => panic!("not render"),
            Err(e) => Err(e.to_string()),
        };
        assert_eq!(level("+3"), Ok(3));
        assert_eq!(level("007"), Ok(7));
        let refused = |v: &str, said: &str| {
            let e = level(v).unwrap_err();
            assert!(e.contains(said), "{v}: {e}");
        };
        refused("-3", ": -3 is not in 1..=1024");
        let huge = "9".repeat(60);
        refused(
            &huge,
            &format!(": {}… (60 characters) is not in 1..=1024", &huge[..40]),
        );
        refused("3\u{200b}", ": not a whole number ('3\\u{200b}')");
    }

    /// bench's lists read items with spaces around them, as `--eye` does; a bad item is still
    /// a usage error.
    #[test]
    fn list_items_are_read_without_the_spaces_around_them() {
        let cli = Cli::try_parse_from([
            "meshrefine",
            "bench",
            "--levels",
            " 2, 4",
            "--surfaces",
            "flat, pn",
            "--displacements",
            "none, sine",
            "--drivers",
            "static, tess",
        ])
        .unwrap();
        let Command::Bench(b) = cli.command else {
            panic!("not bench");
        };
        assert_eq!(b.levels, [2, 4]);
        assert_eq!(b.surfaces, [Surface::Flat, Surface::Pn]);
        assert_eq!(b.displacements, [Displace::None, Displace::Sine]);
        assert_eq!(b.drivers, [Driver::Static, Driver::Tess]);
        for bad in [["--levels", " 0, 4"], ["--surfaces", "flat, bogus"]] {
            let e = Cli::try_parse_from(["meshrefine", "bench", bad[0], bad[1]]).unwrap_err();
            let usage = [
                clap::error::ErrorKind::InvalidValue,
                clap::error::ErrorKind::ValueValidation,
            ];
            assert!(usage.contains(&e.kind()), "{e}");
        }
        // An empty item is named as such, not as a missing value or an unparsable number.
        let lists = [
            ("--levels", "2"),
            ("--surfaces", "pn"),
            ("--displacements", "sine"),
            ("--drivers", "tess"),
        ];
        for (list, item) in lists {
            for v in [format!("{item},,{item}"), format!("{item},"), " , ".into()] {
                let e = Cli::try_parse_from(["meshrefine", "bench", list, &v]).unwrap_err();
                assert_eq!(e.kind(), clap::error::ErrorKind::ValueValidation, "{e}");
                let text = e.to_string();
                assert!(
                    text.contains("an empty item in the list"),
                    "{list} {v:?}: {text}"
                );
            }
        }
    }

    /// Every option's value but a path reads without the spaces around it: whole numbers,
    /// names and on/off as the real numbers and points do; an empty value is named as such.
    #[test]
    fn values_are_read_without_the_spaces_around_them() {
        let cli = Cli::try_parse_from([
            "meshrefine",
            "render",
            "--max-level",
            " 128",
            "--width",
            "64 ",
            "--height",
            " 32 ",
            "--msaa",
            " 4",
            "--surface",
            " phong ",
            "--cull",
            "off ",
            "--bft-level",
            " 5",
        ])
        .unwrap();
        let Command::Render(r) = cli.command else {
            panic!("not render");
        };
        assert_eq!((r.width, r.height, r.msaa), (64, 32, Some(4)));
        assert_eq!(r.adaptive.max_level, Some(128));
        assert_eq!(r.adaptive.cull, Some(false));
        assert_eq!(r.technique.surface.surface, Surface::Phong);
        assert_eq!(r.technique.surface.drawn.params.bft_level, 5);
        let cli = Cli::try_parse_from(["meshrefine", "export", "-o", "x.obj", "--driver", " tess"]);
        let Command::Export(e) = cli.unwrap().command else {
            panic!("not export");
        };
        assert_eq!(e.driver, ExportDriver::Tess);
        let cli = Cli::try_parse_from(["meshrefine", "info", "--level", " 8 "]).unwrap();
        let Command::Info(i) = cli.command else {
            panic!("not info");
        };
        assert_eq!(i.level, Some(8));
        // In bench's lists, around each item.
        let cli = Cli::try_parse_from([
            "meshrefine",
            "bench",
            "--levels",
            "2, 4 ",
            "--surfaces",
            "flat, pn",
            "--drivers",
            " tess ,static",
        ])
        .unwrap();
        let Command::Bench(b) = cli.command else {
            panic!("not bench");
        };
        assert_eq!(b.levels, [2, 4]);
        assert_eq!(b.surfaces, [Surface::Flat, Surface::Pn]);
        assert_eq!(b.drivers, [Driver::Tess, Driver::Static]);
        let empty = [
            ("--level", " "),
            ("--surface", ""),
            ("--width", "  "),
            ("--fov", " "),
            ("--eye", ""),
            ("--octaves", ""),
            ("--device", " "),
        ];
        for (option, value) in empty {
            let e = Cli::try_parse_from(["meshrefine", "render", option, value]).unwrap_err();
            assert_eq!(e.kind(), clap::error::ErrorKind::ValueValidation, "{e}");
            assert!(e.to_string().contains("an empty value"), "{option}: {e}");
        }
        // Paths too (kept as given: an empty one is refused, one of spaces is a name), on
        // every command that takes one, the mesh included.
        let paths: [&[&str]; 12] = [
            &["render", "-o"],
            &["render", "--heightmap"],
            &["render", "--tags"],
            &["render"],
            &["export", "-o"],
            &["info"],
            &["bench", "--out"],
            &["bench", "--heightmap"],
            &["view", "--screenshot"],
            &["view", "--screenshot-dir"],
            &["view", "--headless-output"],
            &["view"],
        ];
        for args in paths {
            let e = Cli::try_parse_from([&["meshrefine"][..], args, &[""]].concat()).unwrap_err();
            assert_eq!(e.kind(), clap::error::ErrorKind::ValueValidation, "{e}");
            assert!(e.to_string().contains("an empty value"), "{args:?}: {e}");
        }
        let cli = Cli::try_parse_from(["meshrefine", "render", "-o", " "]).unwrap();
        let Command::Render(r) = cli.command else {
            panic!("not render");
        };
        assert_eq!(r.output, PathBuf::from(" "));
    }
}
