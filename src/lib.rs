//! meshrefine: GPU mesh refinement on raw Vulkan.
//!
//! The math modules (`mesh`, `pattern`, `surface`) hold no Vulkan and no unsafe code; `gpu` is
//! the only module that calls ash; `render` composes them into the drivers (`static`, `pattern`,
//! `tess`); `app` is the window demo; `export` writes what the GPU evaluated.
//!
//! Design: docs/architecture.md. Lints: the `[lints]` table of Cargo.toml (`unsafe_code` is
//! denied everywhere but `gpu` and `interrupt`, the
//! signal handler that removes an interrupted output's temporary file).

pub mod app;
pub mod bench;
pub mod export;
#[allow(unsafe_code)]
pub mod gpu;
// Signal handlers, through libc (the module's notes say why each call is safe).
#[allow(unsafe_code)]
pub mod interrupt;
pub mod lod;
pub mod mesh;
pub mod paths;
pub mod pattern;
pub mod render;
pub mod subdiv;
pub mod surface;
