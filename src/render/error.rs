//! What can go wrong while preparing or drawing, beyond the Vulkan layer's own errors.

use crate::gpu::GpuError;

#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// A request needs more than one of the device's limits allows.
    #[error("{what} needs {needed} {unit}, over {limit} ({max}): {remedy}")]
    OverLimit {
        what: String,
        needed: u64,
        /// What `needed` and `max` count: "bytes", "texels" or "vertices".
        unit: &'static str,
        /// The limit, as the sentence names it: "this device's maxStorageBufferRange".
        limit: &'static str,
        max: u64,
        remedy: String,
    },
    /// A level beyond what the device lets a driver draw (the one message for refusing,
    /// lowering or skipping it).
    #[error("level {level} is beyond this device's {limit} ({max}): the {driver} driver cannot draw it (use a level up to {max}, or the pattern driver, which this limit does not bind)")]
    DriverLevel {
        driver: &'static str,
        level: u32,
        limit: &'static str,
        max: u32,
    },
    #[error("level {level} is not among the uploaded pattern levels ({levels})")]
    LevelNotUploaded { level: u32, levels: String },
    /// A surface and displacement that cannot be drawn together on this mesh
    /// ([`crate::surface::Surface::incompatibility`]).
    #[error("{0}")]
    Incompatible(String),
    /// What a capture read back cannot be welded into a mesh.
    #[error("the capture cannot be welded: {0}")]
    Capture(String),
    /// A combination that cannot be drawn or read back (one sentence saying why).
    #[error("{0}")]
    Unsupported(&'static str),
    /// The scalar tags break a restriction of scalar-tagged PN triangles.
    #[error("{0}")]
    Tags(String),
    /// The mesh cannot be Loop-subdivided (the `loop` surface).
    #[error("the loop surface cannot subdivide it: {0}")]
    Loop(crate::surface::loop_::TopologyError),
    #[error("the tessellator evaluated {written} vertices, more than the {capacity} the capture buffer holds")]
    CaptureOverflow { written: u64, capacity: u64 },
    /// An eye and a point looked at that give no view direction (`Viewpoint::complete`): the
    /// camera fitted to `surface` completed with what was given, its eye and target in the
    /// drawn frame, for the caller to name as they were typed.
    #[error("--eye and --look-at give no view direction with the camera fitted to {surface}: the eye is within 1e-4 radii of the surface of the point looked at")]
    NoViewDirection {
        surface: String,
        eye: glam::Vec3,
        target: glam::Vec3,
    },
}

impl From<crate::surface::loop_::TopologyError> for RenderError {
    fn from(e: crate::surface::loop_::TopologyError) -> Self {
        RenderError::Loop(e)
    }
}
