//! meshrefine: GPU mesh refinement on raw Vulkan.
//!
//! The math modules (`mesh`, `pattern`, `surface`) hold no Vulkan and no unsafe code; `gpu` is
//! the only module that calls ash; `render` composes them into the drivers (`static`, `pattern`,
//! `tess`); `app` is the window demo; `export` writes what the GPU evaluated.
//!
//! Design: docs/architecture.md. Lints: the `[lints]` table of Cargo.toml (`unsafe_code` is
//! denied everywhere but `gpu`).

pub mod app;
pub mod bench;
pub mod export;
#[allow(unsafe_code)]
pub mod gpu;
pub mod lod;
pub mod mesh;
pub mod paths;
pub mod pattern;
pub mod render;
pub mod subdiv;
pub mod surface;
