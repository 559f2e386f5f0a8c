//! `tess` driver: Vulkan tessellation shaders. Each coarse triangle is a 3-vertex patch; the
//! control stage sets every level to N (adaptively: each outer level from its edge's level, the
//! inner level from the element's, [`outer_levels`]; geomorphing, every level the inner one and
//! the outer ring snapped onto the edges' samples, [`morph`]), the evaluation stage evaluates the
//! surface.
//!
//! lavapipe workaround (docs/platform.md): a tessellated draw whose evaluation stage emits more than
//! 65,536 vertices renders garbage there, so on lavapipe the patches are split into draws of at
//! most 65,535 evaluated vertices. gl_PrimitiveID restarts in every draw, so each draw pushes its
//! first triangle. A second lavapipe bug, found by the loop surface's tests: past
//! 4,095 patch vertices (1,365 triangle patches) in one draw its gl_PrimitiveID in the evaluation
//! stage starts over (Mesa's draw module splits draws into chunks of 4,096 vertices), so patches
//! past that read another element's record; draws on lavapipe also hold at most 1,365 patches.
//! Other devices get one draw.

use super::bindings::SET_MESH;
use super::driver::DriverKind;
use super::frame::FrameWork;
use super::{Capture, GpuMesh, Renderer, PUSH_DRAW_OFFSET, PUSH_STAGES};
use crate::gpu::shaders::names;
use crate::gpu::{vk, Cmd, Context, GraphicsPipelineDesc};
use crate::lod::levels::{drawn_level, ElementLevels};
use crate::surface::RECORD_BYTES;

pub mod morph;

/// Largest evaluated-vertex count of one tessellated draw that lavapipe renders correctly.
pub const LAVAPIPE_MAX_TESS_VERTICES_PER_DRAW: u32 = 65_535;

/// Most triangle patches of one tessellated draw whose gl_PrimitiveID lavapipe numbers right.
pub const LAVAPIPE_MAX_PATCHES_PER_DRAW: u32 = 4_095 / 3;

/// Evaluated vertices of one tessellated draw on lavapipe while transform feedback captures it.
/// Mesa's draw module then sends the draw through its primitive pipeline, which, each time its
/// small vertex buffer fills (every few dozen vertices), resets a header in every vertex the
/// draw evaluated: a cost that grows with the square of the draw's size. Draws of this size keep
/// that reset cheap next to the evaluation itself, and few enough that the cost of each draw
/// stays small.
pub const LAVAPIPE_CAPTURE_VERTICES_PER_DRAW: u32 = 4_096;

/// Patches per draw on this device for `level`; `capture`: drawn for transform feedback.
pub fn patches_per_draw(ctx: &Context, level: u32, triangles: u32, capture: bool) -> u32 {
    if ctx.info.is_lavapipe() {
        let budget = if capture {
            LAVAPIPE_CAPTURE_VERTICES_PER_DRAW
        } else {
            LAVAPIPE_MAX_TESS_VERTICES_PER_DRAW
        };
        (budget / tess_vertex_count(level)).clamp(1, LAVAPIPE_MAX_PATCHES_PER_DRAW)
    } else {
        triangles.max(1)
    }
}

/// The `tess` driver's answers ([`DriverKind`]).
pub struct TessDriver;

impl DriverKind for TessDriver {
    fn name(&self) -> &'static str {
        "tess"
    }

    fn help(&self) -> &'static str {
        "Vulkan tessellation shaders; the evaluation shader evaluates"
    }

    fn refined_per_element(&self, level: u32) -> u32 {
        tess_triangle_count(level)
    }

    /// The tessellator stores nothing.
    fn stored(&self, _level: u32, _elements: u64) -> (u64, u64) {
        (0, 0)
    }

    /// The records alone.
    fn geometry_bytes(&self, _level: u32, elements: u64, _fragment_field: bool) -> u64 {
        elements * RECORD_BYTES as u64
    }

    /// Every tessellator vertex twice, since implementations may repeat evaluation invocations.
    fn capture_per_element(&self, level: u32) -> Option<u32> {
        Some(2 * tess_vertex_count(level))
    }

    fn capture_appends(&self) -> bool {
        true
    }

    fn export_capture(&self) -> Option<Capture> {
        Some(Capture::Triangles)
    }

    fn level_limit(&self, device: &crate::gpu::DeviceInfo) -> Option<(u32, &'static str)> {
        Some((
            device.limits.max_tessellation_generation_level,
            "maxTessellationGenerationLevel",
        ))
    }

    /// The tessellator takes any integer level per edge and inside.
    fn integer_levels(&self) -> bool {
        true
    }

    /// Its evaluation stage glides (`glsl/tess/tess_morph.glsl`, mirror [`morph`]) in the
    /// pipeline that draws uniform frames too.
    fn geomorphs_in_evaluation(&self) -> bool {
        true
    }

    fn describe_pipeline(
        &self,
        desc: &mut GraphicsPipelineDesc,
        _fragment_field: bool,
        capture: Capture,
    ) {
        let tese = match capture {
            Capture::None => names::TESS_TESS_TESE,
            Capture::Vertices => names::TESS_TESS_TESE_CAPTURE,
            Capture::Triangles => names::TESS_TESS_TESE_XFB,
        };
        desc.stages = vec![
            (vk::ShaderStageFlags::VERTEX, names::TESS_TESS_VERT.into()),
            (
                vk::ShaderStageFlags::TESSELLATION_CONTROL,
                names::TESS_TESS_TESC.into(),
            ),
            (vk::ShaderStageFlags::TESSELLATION_EVALUATION, tese.into()),
        ];
        desc.topology = vk::PrimitiveTopology::PATCH_LIST;
        desc.patch_control_points = 3;
    }

    fn cmd_draw(&self, cmd: &Cmd<'_>, r: &Renderer, work: &FrameWork<'_>) {
        cmd_draw(
            cmd,
            r,
            work.mesh,
            work.cfg.level,
            work.adaptive,
            work.elements.clone(),
            work.capture == Capture::Triangles,
        );
    }
}

/// Record the tessellated draws of the elements `range` of `mesh` at `level`, chunk by chunk
/// ([`GpuMesh::chunks`]); `adaptive`: each element at its own levels ([`GpuMesh::levels`]), at
/// most `level` (the draws are split for `level`, the most an element can make); `capture`:
/// drawn for transform feedback ([`patches_per_draw`]).
pub fn cmd_draw(
    cmd: &Cmd<'_>,
    r: &Renderer,
    mesh: &GpuMesh,
    level: u32,
    adaptive: bool,
    range: std::ops::Range<u32>,
    capture: bool,
) {
    let per_draw = patches_per_draw(cmd.context(), level, mesh.element_count, capture);
    for c in mesh.chunks(range) {
        cmd.bind_descriptor_set(r.layout.raw, SET_MESH, c.set, &[0]);
        let mut first = c.first;
        while first < c.first + c.count {
            let count = per_draw.min(c.first + c.count - first);
            // x level (adaptive: the largest), y the chunk's first element, z 1 when adaptive,
            // w this draw's first element within the chunk (gl_PrimitiveID counts from there).
            let draw = [level, c.base, adaptive as u32, first - c.base];
            cmd.push_constants(
                r.layout.raw,
                PUSH_STAGES,
                PUSH_DRAW_OFFSET,
                bytemuck::cast_slice(&draw),
            );
            cmd.draw(3 * count, 1, 0, 0);
            first += count;
        }
    }
}

/// Weights of a tessellator sample `tc = gl_TessCoord` at integer level `n` (tess driver, uniform
/// drawing): [`tess_weights_levels`] with every level `n`.
/// Mirror of `tess_weights()` in `glsl/tess/tess_weights.glsl`.
pub fn tess_weights(tc: [f32; 3], n: u32) -> [f32; 3] {
    tess_weights_levels(tc, [n; 3], n)
}

/// Weights of a tessellator sample `tc = gl_TessCoord` with integer level `outer[i]` on the patch
/// edge where `tc[i] == 0` (`gl_TessLevelOuter[i]`, see [`outer_levels`]) and inner level `inner`
/// (at least every outer level). Outer-edge samples are snapped to their own edge's lattice (`k/n`,
/// `(n-k)/n` with `n` the edge's level, exact zero), as the pattern's weights are, so the two
/// elements sharing an edge get the same weights; interior samples (every coordinate at least
/// `1/inner`) are used as given.
/// Mirror of `tess_weights_levels()` in `glsl/tess/tess_weights.glsl`.
pub fn tess_weights_levels(tc: [f32; 3], outer: [u32; 3], inner: u32) -> [f32; 3] {
    let half_step = 0.5 / inner as f32;
    // The edge the sample lies on (a corner: the first of its two).
    let Some(edge) = tc.iter().position(|&c| c < half_step) else {
        return tc;
    };
    let fnn = outer[edge] as f32;
    let mut k = tc.map(|c| {
        if c < half_step {
            0.0
        } else {
            (c * fnn).round()
        }
    });
    if k[0] == 0.0 {
        k[1] = fnn - k[2];
    } else if k[1] == 0.0 {
        k[2] = fnn - k[0];
    } else {
        k[0] = fnn - k[1];
    }
    k.map(|x| x / fnn)
}

/// The tessellation levels the control stage sets for an element drawn adaptively with levels
/// `levels` and largest level `max`: `(outer, inner)` with `outer[i]` the level of the patch edge
/// where `gl_TessCoord[i] == 0`, between patch vertices `i + 1` and `i + 2`, which is stored edge
/// `(i + 1) mod 3`; `None` for a culled element (its patch is discarded).
/// Mirror of `glsl/tess/tess.tesc`.
pub fn outer_levels(levels: &ElementLevels, max: u32) -> Option<([u32; 3], u32)> {
    let inner = drawn_level(levels.inner, false, max);
    if inner == 0 {
        return None;
    }
    let e = levels.edges.map(|l| drawn_level(l, false, max));
    Some(([e[1], e[2], e[0]], inner))
}

/// Distinct vertices the tessellator makes for one triangle patch with outer levels `outer` and
/// inner level `inner >= 2` or every level 1 (integer, equal spacing): the inner rings of a
/// uniform level-`inner` patch and an outer ring of `outer[0] + outer[1] + outer[2]` vertices.
pub const fn tess_vertex_count_levels(outer: [u32; 3], inner: u32) -> u32 {
    tess_vertex_count(inner) - 3 * inner + outer[0] + outer[1] + outer[2]
}

/// Triangles the tessellator makes for one patch with outer levels `outer` and inner level `inner`
/// (as [`tess_vertex_count_levels`]): a triangulated disk of `V` vertices with `B` on its boundary
/// has `2V - B - 2` triangles (Euler).
pub const fn tess_triangle_count_levels(outer: [u32; 3], inner: u32) -> u32 {
    2 * tess_vertex_count_levels(outer, inner) - (outer[0] + outer[1] + outer[2]) - 2
}

/// Distinct vertices the tessellator makes for one triangle patch with every level `n` (integer,
/// equal spacing): concentric rings of `n, n-2, n-4, ...` segments per side, closed by a centre
/// vertex (even `n`) or a last triangle (odd `n`). Vulkan spec, "Triangle Tessellation".
pub const fn tess_vertex_count(n: u32) -> u32 {
    if n % 2 == 0 {
        let h = n / 2;
        3 * h * (h + 1) + 1
    } else {
        let h = n.div_ceil(2);
        3 * h * h
    }
}

/// Triangles the tessellator makes for one patch at level `n`: a ring of `m` segments and the
/// ring inside it (`m - 2`) are joined by `6m - 6` triangles; an innermost ring of one segment is
/// one triangle. More than a level-`n` pattern's `n²` for `n >= 2` (1.5x as `n` grows).
pub const fn tess_triangle_count(n: u32) -> u32 {
    let mut m = n;
    let mut t = 0;
    while m >= 2 {
        t += 6 * m - 6;
        m -= 2;
    }
    if m == 1 {
        t += 1;
    }
    t
}

/// The tessellator's triangles with every level `n` (equal spacing), as integers `K` of their
/// corners' weights `K/(3n)`: its rings (`n, n − 2, ...` segments a side), each strip between two
/// rings cut into parallelograms and corner regions, each split along either diagonal
/// (`diagonal`: the one from the outer ring's earlier vertex; the specification leaves the
/// choice to the implementation), the centre's fan (even `n`) or the last triangle (odd `n`).
/// The model the tess driver's bounds assume (src/lod/mod.rs, "The tessellator's inside";
/// `tests/tess_rings.rs` checks its sides against what the device draws).
pub fn ring_triangles(n: u32, diagonal: bool) -> Vec<[[i32; 3]; 3]> {
    let n = n as i32;
    let s = 3 * n;
    // Ring `r`'s vertex `j` (of `3m`, from corner 0's), `m = n − 2r` segments a side.
    let ring = |r: i32, j: i32| {
        let m = n - 2 * r;
        let (c, j) = ((j / m) % 3, j % m);
        let (a, b) = (((c + 2) % 3) as usize, ((c + 1) % 3) as usize);
        let mut k = [0; 3];
        k[a] = 2 * r;
        k[b] = 2 * r + 3 * j;
        k[c as usize] = s - k[a] - k[b];
        k
    };
    let mut out = vec![];
    let split = |out: &mut Vec<[[i32; 3]; 3]>, p0, p1, q0, q1| {
        // The quadrilateral p0 p1 q1 q0 (outer p, inner q).
        if diagonal {
            out.push([p0, p1, q1]);
            out.push([p0, q1, q0]);
        } else {
            out.push([p0, p1, q0]);
            out.push([p1, q1, q0]);
        }
    };
    let mut r = 0;
    while n - 2 * r >= 2 {
        let m = n - 2 * r;
        if m == 2 {
            let centre = [n; 3];
            for j in 0..6 {
                out.push([ring(r, j), ring(r, (j + 1) % 6), centre]);
            }
            break;
        }
        let mi = m - 2;
        for c in 0..3 {
            // The corner region: the outer corner, its neighbours, the inner corner.
            let (prev, corner, next) = (
                ring(r, (c * m + 3 * m - 1) % (3 * m)),
                ring(r, c * m),
                ring(r, c * m + 1),
            );
            split(&mut out, prev, corner, ring(r + 1, c * mi), next);
            // The side's parallelograms.
            for j in 0..mi {
                let (p0, p1) = (ring(r, c * m + 1 + j), ring(r, c * m + 2 + j));
                let (q0, q1) = (
                    ring(r + 1, c * mi + j),
                    ring(r + 1, (c * mi + j + 1) % (3 * mi)),
                );
                split(&mut out, p0, p1, q0, q1);
            }
        }
        r += 1;
    }
    if n - 2 * r == 1 {
        out.push([ring(r, 0), ring(r, 1), ring(r, 2)]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tess_weights_snap_edges_only() {
        let n = 7;
        // On the edge v = 0, slightly off the lattice: snapped to (4/7, 3/7, 0).
        assert_eq!(
            tess_weights([0.571_428_5, 0.428_571_6, 0.0], n),
            [4.0 / 7.0, 3.0 / 7.0, 0.0]
        );
        // A corner.
        assert_eq!(tess_weights([0.0, 1.0, 0.0], n), [0.0, 1.0, 0.0]);
        // Interior samples are untouched.
        let inner = [0.2, 0.3, 0.5];
        assert_eq!(tess_weights(inner, n), inner);
    }

    /// The snapping as it was before per-edge levels, operation for operation.
    fn uniform_reference(tc: [f32; 3], n: u32) -> [f32; 3] {
        let fnn = n as f32;
        let half_step = 0.5 / fnn;
        if tc.iter().all(|&c| c >= half_step) {
            return tc;
        }
        let mut k = tc.map(|c| {
            if c < half_step {
                0.0
            } else {
                (c * fnn).round()
            }
        });
        if k[0] == 0.0 {
            k[1] = fnn - k[2];
        } else if k[1] == 0.0 {
            k[2] = fnn - k[0];
        } else {
            k[0] = fnn - k[1];
        }
        k.map(|x| x / fnn)
    }

    /// With every level equal, the per-edge snapping gives the uniform weights bit for bit, on
    /// the lattice, off it, on edges, at corners and inside.
    #[test]
    fn equal_levels_snap_as_uniform() {
        let mut seed = 0x2545_f491_u32;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            (seed >> 8) as f32 / (1 << 24) as f32
        };
        for n in [1u32, 2, 3, 7, 16, 64] {
            for _ in 0..2000 {
                let (a, b) = (next(), next());
                let mut tc = [a, (1.0 - a) * b, 0.0];
                tc[2] = 1.0 - tc[0] - tc[1];
                // Put some on an edge.
                let zero = (next() * 4.0) as usize;
                if zero < 3 {
                    tc[zero] = 0.0;
                }
                let got = tess_weights_levels(tc, [n; 3], n);
                assert_eq!(
                    got.map(f32::to_bits),
                    uniform_reference(tc, n).map(f32::to_bits)
                );
                assert_eq!(got, tess_weights(tc, n));
            }
        }
    }

    /// An edge sample snaps to its own edge's lattice: here edge `tc[2] == 0` at level 3 inside a
    /// level-8 patch, and the corners stay exact.
    #[test]
    fn edge_samples_snap_to_their_edge_level() {
        let (outer, inner) = ([5, 2, 3], 8);
        assert_eq!(
            tess_weights_levels([0.666_666_6, 0.333_333_4, 0.0], outer, inner),
            [2.0 / 3.0, 1.0 / 3.0, 0.0]
        );
        assert_eq!(
            tess_weights_levels([0.0, 0.400_000_2, 0.599_999_8], outer, inner),
            [0.0, 2.0 / 5.0, 3.0 / 5.0]
        );
        for c in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
            assert_eq!(tess_weights_levels(c, outer, inner), c);
        }
        // The first inner ring (coordinates from 1/8) is left alone.
        let ring = [0.75, 0.125, 0.125];
        assert_eq!(tess_weights_levels(ring, outer, inner), ring);
    }

    /// Outer level `i` is stored edge `i + 1`; culled elements have none; levels are rounded up
    /// and capped.
    #[test]
    fn outer_levels_follow_the_stored_edges() {
        let l = ElementLevels {
            edges: [1.5, 3.0, 4.2],
            inner: 6.5,
        };
        assert_eq!(outer_levels(&l, 64), Some(([3, 5, 2], 7)));
        assert_eq!(outer_levels(&l, 4), Some(([3, 4, 2], 4)));
        let culled = ElementLevels {
            edges: [3.0; 3],
            inner: 0.0,
        };
        assert_eq!(outer_levels(&culled, 64), None);
    }

    #[test]
    fn tessellator_counts_with_levels() {
        for n in 1..40u32 {
            assert_eq!(tess_vertex_count_levels([n; 3], n), tess_vertex_count(n));
            assert_eq!(
                tess_triangle_count_levels([n; 3], n),
                tess_triangle_count(n)
            );
        }
        // Inner level 4 (19 vertices, 7 inside the outer ring) with edges of 1, 2, 3 segments: an
        // outer ring of 6.
        assert_eq!(tess_vertex_count_levels([1, 2, 3], 4), 7 + 6);
        assert_eq!(tess_triangle_count_levels([1, 2, 3], 4), 2 * 13 - 6 - 2);
    }

    #[test]
    fn tessellator_counts() {
        assert_eq!((tess_vertex_count(1), tess_triangle_count(1)), (3, 1));
        assert_eq!((tess_vertex_count(2), tess_triangle_count(2)), (7, 6));
        assert_eq!((tess_vertex_count(3), tess_triangle_count(3)), (12, 13));
        assert_eq!((tess_vertex_count(4), tess_triangle_count(4)), (19, 24));
        assert_eq!(tess_triangle_count(64), 6144);
        // Euler: a triangulated disk has V - E + F = 1, E = (3F + boundary) / 2, boundary = 3n.
        for n in 1..40u32 {
            let (v, f) = (tess_vertex_count(n) as i64, tess_triangle_count(n) as i64);
            let e = (3 * f + 3 * n as i64) / 2;
            assert_eq!(v - e + f, 1, "level {n}");
        }
    }
}
