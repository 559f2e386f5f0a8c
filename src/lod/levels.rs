//! Each element's levels as the drivers read them when they draw adaptively: the continuous
//! levels of its three stored edges and its inner level (`N` segments per edge, real,
//! `>= 1`), one `vec4` per element in the mesh's levels buffer (set 1, `BINDING_LEVELS`,
//! src/render/bindings.rs). The level pass writes it every frame from the camera; tests and
//! CPU-chosen levels upload it ([`crate::render::GpuMesh::upload_levels`]).
//!
//! A driver rounds each continuous level to the level it draws with [`drawn_level`] (the GLSL
//! twin is `drawn_level` in glsl/include/levels.glsl): the two elements that share an edge read
//! the same value for it and round it the same way, so they sample the edge identically.
//! An inner level of zero means the element is culled: it draws nothing (the level pass then
//! writes [`ElementLevels::CULLED`], computing none of its levels).
#![forbid(unsafe_code)]

use bytemuck::{Pod, Zeroable};

/// One element's levels (std430 `vec4`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ElementLevels {
    /// Stored edges `k` = corner `k` → corner `k + 1`.
    pub edges: [f32; 3],
    /// At least the largest edge level; `0.0`: culled.
    pub inner: f32,
}

const _: () = assert!(std::mem::size_of::<ElementLevels>() == 16);

impl ElementLevels {
    /// Level 1 everywhere: the coarse triangle itself.
    pub const UNIFORM_1: ElementLevels = ElementLevels::uniform(1.0);

    /// Nothing drawn.
    pub const CULLED: ElementLevels = ElementLevels {
        edges: [0.0; 3],
        inner: 0.0,
    };

    /// The same level on every edge and inside.
    pub const fn uniform(level: f32) -> Self {
        Self {
            edges: [level; 3],
            inner: level,
        }
    }

    /// Whether the element draws nothing.
    pub fn culled(&self) -> bool {
        self.inner <= 0.0
    }
}

/// The level a driver draws for continuous level `level`: its ceiling, raised to a power of two
/// for a `dyadic` driver (hierarchical patterns), capped at `max` (itself a power of two for a
/// dyadic driver). Zero (culled) stays zero.
pub fn drawn_level(level: f32, dyadic: bool, max: u32) -> u32 {
    if level <= 0.0 {
        return 0;
    }
    // The float compare first: a level beyond u32 (or infinite) is the maximum.
    let n = if level >= max as f32 {
        max
    } else {
        (level.ceil() as u32).clamp(1, max)
    };
    if dyadic {
        n.next_power_of_two().min(max)
    } else {
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drawn_levels_round_up_and_cap() {
        assert_eq!(drawn_level(0.0, false, 64), 0);
        assert_eq!(drawn_level(1.0, false, 64), 1);
        assert_eq!(drawn_level(1.0001, false, 64), 2);
        assert_eq!(drawn_level(5.5, false, 64), 6);
        assert_eq!(drawn_level(5.5, true, 64), 8);
        assert_eq!(drawn_level(8.0, true, 64), 8);
        assert_eq!(drawn_level(63.2, false, 64), 64);
        assert_eq!(drawn_level(1e30, true, 64), 64);
        assert_eq!(drawn_level(f32::INFINITY, false, 64), 64);
        assert_eq!(drawn_level(100.0, true, 32), 32);
    }
}
