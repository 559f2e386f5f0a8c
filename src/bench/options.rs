//! What a benchmark is asked for: the meshes' levels, surfaces, drivers and frames
//! ([`BenchOptions`]), the camera ([`BenchCamera`]), the adaptive views ([`BenchAdaptive`]),
//! and the cameras its rows were drawn from, as the tables name them ([`ViewUsed`]).
#![forbid(unsafe_code)]

use crate::render::{Camera, Driver, View, Viewpoint};
use crate::surface::{BuildOptions, Displace, Surface, SurfaceParams};

#[derive(Clone, Debug)]
pub struct BenchOptions {
    pub levels: Vec<u32>,
    /// Surface x displacement combinations measured (each against its own `static`).
    pub surfaces: Vec<(Surface, Displace)>,
    /// Parameters; `None`: [`SurfaceParams::for_radius`] of each mesh.
    pub params: Option<SurfaceParams>,
    /// Options built into the mesh's data (seams, Loop's boundary rule and table level).
    pub build: BuildOptions,
    pub frames: u32,
    pub width: u32,
    pub height: u32,
    /// The driver variants measured (empty: every one; `static` is the reference of the ratios).
    pub drivers: Vec<Driver>,
    /// Keep taking rounds past `frames` until every variant has this much GPU time in total
    /// (milliseconds; 0: exactly `frames`), so frames of a few milliseconds, whose timestamps
    /// jitter most, get more samples. At most 20 × `frames` rounds.
    pub min_total_ms: f64,
    /// The camera the frames are drawn from, in the drawn coordinates: by default the one
    /// fitted to each surface x displacement as drawn (render's default camera). Adaptive rows
    /// draw from [`BenchAdaptive::cameras`] where it names any.
    pub camera: BenchCamera,
    /// Draw adaptively ([`crate::render::Scene::set_levels`]): each variant once with each element at the
    /// levels the view asks for, and, in the same run, uniformly at `levels` and (with
    /// [`BenchAdaptive::bound_levels`]) at the smallest uniform level meeting the same bound
    /// and the smallest power of two at or above it; `None`: every element at each of `levels`.
    pub adaptive: Option<BenchAdaptive>,
    /// What the frames show: [`View::Plain`] times the refined triangles without shading them.
    pub view: View,
    /// The `heightmap` displacement's map (`None`: the generated one).
    pub heightmap: Option<crate::surface::Heightmap>,
}

/// The camera of a benchmark's frames ([`BenchOptions::camera`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BenchCamera {
    /// Fitted to each surface x displacement as drawn ([`Viewpoint::camera`]: at its field of
    /// view, moved to its eye or point looked at where it gives one), as `render` frames it.
    Fitted(Viewpoint),
    /// The same camera for every row.
    Fixed(Camera),
    /// The camera framing each mesh's bounding sphere from the usual direction
    /// ([`Camera::framing`]), one for every surface, displacement and driver of the mesh: the
    /// paper-figure benchmarks (`cargo bench --bench fig7`, `table1`, `surfaces`) time every
    /// surface from one view of the mesh.
    Framing,
}

impl Default for BenchCamera {
    /// The fitted camera at 45 degrees.
    fn default() -> Self {
        Self::Fitted(Viewpoint::default())
    }
}

/// The views adaptive rows are drawn for, and what they are compared with.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchAdaptive {
    /// The scene's name in the table (`close-up`, `grazing`, ...; may be empty).
    pub scene: String,
    /// In the drawn coordinates; one: a still view; several: a path whose frames are averaged
    /// (each row's times and counts are the means over the cameras); none:
    /// [`BenchOptions::camera`].
    pub cameras: Vec<Camera>,
    pub pixel_error: f32,
    pub cull: bool,
    /// The largest level an element may get (a power of two for the pattern driver).
    pub max_level: u32,
    /// Also time the smallest uniform level meeting the bound on every camera
    /// ([`crate::lod::LevelReport::uniform_level`], any integer; a power of two for `loop` while
    /// levels glide) and the smallest power of two at or above it.
    pub bound_levels: bool,
    /// Glide the vertices a level adds (`DrawConfig::geomorph`).
    pub geomorph: bool,
}

/// The cameras one mesh's rows of one surface x displacement were drawn from (one, or a
/// path's: [`BenchAdaptive::cameras`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ViewUsed {
    pub mesh: String,
    pub surface: Surface,
    pub displace: Displace,
    pub shots: Vec<Shot>,
}

/// Where a camera stands, where it looks and its vertical field of view in degrees (up is
/// +Y, as on the command line).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shot {
    pub eye: glam::Vec3,
    pub target: glam::Vec3,
    pub fov_y_degrees: f32,
}

impl From<&Camera> for Shot {
    fn from(c: &Camera) -> Self {
        Self {
            eye: c.eye(),
            target: c.target,
            fov_y_degrees: c.fov_y.to_degrees(),
        }
    }
}

/// [`super::Report::camera_space`] where the caller does not map the cameras back.
pub const DRAWN_SPACE: &str =
    "in the coordinates the meshes were drawn in: centred and at unit size, `Mesh::for_viewing`, in the benchmarks";
