//! The options `meshrefine view` starts the window demo with.

use super::AdaptiveView;
use crate::render::{Background, DrawConfig, View};
use std::path::PathBuf;

/// Options of `meshrefine view`.
#[derive(Clone, Debug)]
pub struct ViewOptions {
    pub cfg: DrawConfig,
    /// Exit after this many frames.
    pub frames: Option<u32>,
    /// Save the last frame here.
    pub screenshot: Option<PathBuf>,
    pub wireframe: bool,
    /// Start with the cage overlay (the coarse mesh's edges) on.
    pub cage: bool,
    pub animate: bool,
    /// Start with LOD by distance on.
    pub lod: bool,
    /// The pattern driver's submission (`--submit`): drawn where `cfg`'s driver is `pattern`,
    /// and what the keys switch to from another driver.
    pub submit: crate::render::Submit,
    /// The height map (None: the generated one).
    pub heightmap: Option<crate::surface::Heightmap>,
    /// The scalar tags (None: derived from the mesh's hard edges).
    pub tags: Option<Vec<crate::surface::stpn::VertexTag>>,
    /// Why the loop surface must not subdivide this mesh though it loaded (the file had faces
    /// the loader dropped): switching to loop then warns with it and shows pn.
    pub loop_refusal: Option<String>,
    /// The mesh as the user named it, for messages.
    pub source: String,
    /// On a software device, lower what a frame draws to keep it under a second
    /// (`--no-frame-budget` turns it off: frames then draw what is asked, however slow).
    pub frame_budget: bool,
    /// Samples per pixel (`--msaa`; `None`: 4 where supported, else the most the device has).
    pub msaa: Option<u32>,
    /// Adaptive mode's starting settings, and whether the demo starts in it.
    pub adaptive: AdaptiveView,
    /// The window's inner size at the start, in logical pixels (`--width`, `--height`), and
    /// the size leaving fullscreen returns to when the demo started fullscreen.
    pub size: (u32, u32),
    /// Start borderless fullscreen (`--fullscreen`; `F11` toggles).
    pub fullscreen: bool,
    /// Start with the overlay panel shown (`--hide-panel` starts without; `H` toggles).
    pub panel: bool,
    /// What the mesh is drawn on at the start (`--background`; `B` toggles).
    pub background: Background,
    /// What the fragment stage shows at the start (`--view`; `N` switches).
    pub view: View,
    /// Where the screenshot key writes `meshrefine-<n>.png` (None: the current directory).
    pub screenshot_dir: Option<PathBuf>,
    /// The transform of the drawn mesh from the file's coordinates (drawn = (mesh − centre) ·
    /// scale, `Mesh::viewing_transform`): the camera is reported in the file's coordinates.
    pub viewing: (glam::DVec3, f64),
}
