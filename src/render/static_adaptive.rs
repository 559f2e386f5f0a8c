//! The `static` driver drawn adaptively: the CPU baseline of adaptive refinement, what a user
//! would do without refinement on the GPU. When the levels change (`Scene::set_levels`, from the
//! level pass's CPU mirror `lod::frame::frame_levels`), every element is refined on the CPU at
//! its drawn levels with the pattern driver's crack-free construction (`pattern::adaptive`: its
//! inner level's lattice, boundary vertices snapped onto their edge's level, the same
//! triangles), evaluated with the surfaces' mirrors and uploaded as one vertex and index buffer;
//! the draws then read each element's index range. Triangles that snapping made degenerate are
//! not stored. Vertices do not glide (gliding would re-upload every frame), so the levels are
//! those the pattern driver draws without geomorphing: any integer. docs/adaptivity.md, "The
//! static baseline".

use super::bindings::SET_MESH;
use super::static_vbo::{static_vertex, ElementVertex, StaticVbo, StaticVertex};
use super::{DrawConfig, GpuMesh, RenderError, Renderer, Scene, PUSH_DRAW_OFFSET, PUSH_STAGES};
use crate::gpu::{vk, Buffer, Cmd, CommandPool, Context};
use crate::lod::levels::ElementLevels;
use crate::pattern::adaptive::{drawn_levels, integer_bary, DrawnLevels};
use crate::pattern::Pattern;
use crate::surface::{ElementRecord, Mirror};
use std::sync::Arc;
use std::time::Instant;

/// A mesh refined adaptively on the CPU.
#[derive(Clone, Debug, Default)]
pub struct AdaptiveRefined {
    pub vertices: Vec<StaticVertex>,
    /// Each vertex's sample (`(w, u, v)` bits, element), when asked for.
    pub samples: Vec<ElementVertex>,
    /// Triangles, indices into `vertices`.
    pub indices: Vec<u32>,
    /// Element `t`'s triangles are `indices[first[t] .. first[t + 1]]` (`first` has one entry
    /// more than there are elements).
    pub first: Vec<u32>,
    /// Each element's drawn levels (`None`: culled, nothing drawn).
    pub drawn: Vec<Option<DrawnLevels>>,
}

/// The drawn levels of `levels` at largest level `max`, as the pattern driver draws them
/// without geomorphing (integers).
pub fn drawn(levels: &[ElementLevels], max: u32) -> Vec<Option<DrawnLevels>> {
    levels.iter().map(|l| drawn_levels(l, max, false)).collect()
}

/// Every element of `records` refined on the CPU at its drawn levels `drawn` (from [`drawn`]) at
/// largest level `cfg.level`, with `cfg`'s surface, displacement and parameters (`mirror`: the
/// surface and displacement with their inputs): element `t`'s vertices are the pattern
/// driver's adaptive vertices without geomorphing (`pattern::adaptive::integer_element`,
/// snapped weights included) in the inner level's pattern order, its triangles that pattern's,
/// less those snapping made degenerate.
/// `samples`: also each vertex's sample, for the per-fragment normal field.
pub fn refine_adaptive(
    cfg: &DrawConfig,
    records: &[ElementRecord],
    drawn: Vec<Option<DrawnLevels>>,
    mirror: &Mirror,
    samples: bool,
) -> AdaptiveRefined {
    let f = cfg.level;
    let mut out = AdaptiveRefined {
        first: Vec::with_capacity(records.len() + 1),
        ..AdaptiveRefined::default()
    };
    // The uniform patterns by level (up to f).
    let mut patterns: Vec<Option<Pattern>> = vec![None; f as usize + 1];
    // Each vertex's weights: equal weights, the same point.
    let mut points = Vec::new();
    for (t, rec) in records.iter().enumerate() {
        out.first.push(out.indices.len() as u32);
        let Some(d) = drawn[t] else { continue };
        let pattern = patterns[d.inner as usize].get_or_insert_with(|| Pattern::uniform(d.inner));
        let base = out.vertices.len() as u32;
        points.clear();
        for (i, j) in pattern.lattice() {
            let b = integer_bary(i, j, &d);
            out.vertices
                .push(static_vertex(&mirror.eval(&cfg.params, t, rec, b)));
            if samples {
                out.samples
                    .push([b[0].to_bits(), b[1].to_bits(), b[2].to_bits(), t as u32]);
            }
            points.push(b);
        }
        for tri in pattern.indices.chunks_exact(3) {
            let [a, b, c] = [tri[0], tri[1], tri[2]].map(|k| points[k as usize]);
            if a != b && b != c && c != a {
                out.indices.extend(tri.iter().map(|&k| base + k));
            }
        }
    }
    out.first.push(out.indices.len() as u32);
    out.drawn = drawn;
    out
}

/// What an adaptive static buffer draws and what making it cost.
#[derive(Clone, Debug)]
pub struct AdaptiveIndex {
    /// Element `t` draws indices `first[t] .. first[t + 1]`.
    pub first: Vec<u32>,
    pub drawn: Vec<Option<DrawnLevels>>,
    /// Milliseconds refining on the CPU and uploading (wall time).
    pub cpu_ms: f64,
    /// Bytes uploaded: vertices, samples and indices.
    pub upload_bytes: u64,
}

/// The levels `Scene::set_levels` chose for a static configuration, and for what.
#[derive(Clone, Debug)]
pub(super) struct StaticLevels {
    cfg: DrawConfig,
    generation: u64,
    levels: Vec<ElementLevels>,
}

impl StaticLevels {
    pub(super) fn new(cfg: &DrawConfig, generation: u64, levels: Vec<ElementLevels>) -> Self {
        Self {
            cfg: key(cfg),
            generation,
            levels,
        }
    }
}

/// What refined vertices depend on: the configuration less gliding, which the static driver
/// never does.
fn key(cfg: &DrawConfig) -> DrawConfig {
    DrawConfig {
        geomorph: false,
        ..*cfg
    }
}

/// The levels chosen for `cfg` in `scene`, if any.
fn levels_for<'a>(scene: &'a Scene, cfg: &DrawConfig) -> Option<&'a [ElementLevels]> {
    (scene.static_levels.as_ref())
        .filter(|l| l.cfg == key(cfg) && l.generation == scene.generation)
        .map(|l| &l.levels[..])
}

impl Scene {
    /// The levels the last [`Scene::set_levels`] chose for the static configuration `cfg`
    /// (the level pass's CPU mirror), which its adaptive frames draw; `None` before.
    pub fn static_levels(&self, cfg: &DrawConfig) -> Option<&[ElementLevels]> {
        levels_for(self, cfg)
    }
}

/// For an adaptive frame of `cfg`: refine and upload where the drawn levels changed (nothing
/// before levels are chosen).
pub(super) fn prepare(
    scene: &mut Scene,
    ctx: &Arc<Context>,
    pool: &CommandPool,
    cfg: &DrawConfig,
) -> Result<(), RenderError> {
    if !cfg.level.is_power_of_two() {
        scene.static_vbo = None;
        return Ok(());
    }
    let Some(levels) = levels_for(scene, cfg) else {
        scene.static_vbo = None;
        return Ok(());
    };
    let want = drawn(levels, cfg.level);
    let current = scene
        .static_vbo
        .as_ref()
        .is_some_and(|v| v.cfg == *cfg && v.adaptive.as_ref().is_some_and(|a| a.drawn == want));
    if current {
        return Ok(());
    }
    scene.static_vbo = None;
    // Refused before any work where even a lower bound of the buffers' size is too large (the
    // refinement itself would take minutes and more memory than the machine has).
    check_size(
        ctx,
        cfg,
        least_bytes(&want, cfg.fragment_normal_field()),
        true,
    )?;
    let start = Instant::now();
    let refined = refine_adaptive(
        cfg,
        scene.records(cfg.surface),
        want,
        &scene.mirror(cfg, cfg.level)?,
        cfg.fragment_normal_field(),
    );
    scene.static_vbo = Some(upload(ctx, pool, cfg, refined, start)?);
    Ok(())
}

/// One buffer per array (a one-entry placeholder where nothing is drawn: Vulkan has no empty
/// buffer).
fn upload(
    ctx: &Arc<Context>,
    pool: &CommandPool,
    cfg: &DrawConfig,
    mut r: AdaptiveRefined,
    start: Instant,
) -> Result<StaticVbo, RenderError> {
    let bytes = |v: usize, size: usize| (v * size) as u64;
    let upload_bytes = bytes(r.vertices.len(), std::mem::size_of::<StaticVertex>())
        + bytes(r.samples.len(), std::mem::size_of::<ElementVertex>())
        + bytes(r.indices.len(), 4);
    check_size(ctx, cfg, upload_bytes, false)?;
    let (vertex_count, index_count) = (r.vertices.len() as u32, r.indices.len() as u32);
    if r.vertices.is_empty() {
        r.vertices.push([0.0; 6]);
        r.indices.push(0);
        if cfg.fragment_normal_field() {
            r.samples.push([0; 4]);
        }
    }
    let usage = vk::BufferUsageFlags::VERTEX_BUFFER;
    let vertices = Buffer::new_with_data(ctx, pool, usage, &r.vertices, "static vertices")?;
    let elements = if cfg.fragment_normal_field() {
        let name = "static vertex samples";
        Some(Buffer::new_with_data(ctx, pool, usage, &r.samples, name)?)
    } else {
        None
    };
    let usage = vk::BufferUsageFlags::INDEX_BUFFER;
    let indices = Buffer::new_with_data(ctx, pool, usage, &r.indices, "static triangles")?;
    Ok(StaticVbo {
        cfg: *cfg,
        level: cfg.level,
        adaptive: Some(AdaptiveIndex {
            first: r.first,
            drawn: r.drawn,
            cpu_ms: start.elapsed().as_secs_f64() * 1e3,
            upload_bytes,
        }),
        vertices,
        elements,
        indices,
        index_count,
        vertex_count,
        pattern_vertex_count: 0,
        pattern_index_count: 0,
    })
}

/// Whether the refined mesh's buffers, `bytes` in all (`at_least`: a lower bound of them),
/// fit one allocation on this device (one sentence where not).
fn check_size(
    ctx: &Context,
    cfg: &DrawConfig,
    bytes: u64,
    at_least: bool,
) -> Result<(), RenderError> {
    let checked = super::static_vbo::check_allocation(
        ctx,
        bytes,
        || {
            format!(
                "the static driver's adaptively refined mesh (largest level {})",
                cfg.level
            )
        },
        "use a larger pixel error, a lower --max-level or the pattern driver",
    );
    match checked {
        Err(RenderError::OverLimit {
            what,
            needed,
            limit,
            max,
            remedy,
            ..
        }) if at_least => Err(RenderError::OverLimit {
            what,
            needed,
            unit: "bytes or more",
            limit,
            max,
            remedy,
        }),
        other => other,
    }
}

/// A lower bound of the bytes [`refine_adaptive`] makes for `drawn` (`samples`: with each
/// vertex's sample): every element's lattice vertices, exactly, and the triangles of its
/// lattice that touch no boundary vertex (`(n − 3)²` at inner level `n`), which snapping never
/// makes degenerate.
pub fn least_bytes(drawn: &[Option<DrawnLevels>], samples: bool) -> u64 {
    let vertex = (std::mem::size_of::<StaticVertex>()
        + if samples {
            std::mem::size_of::<ElementVertex>()
        } else {
            0
        }) as u64;
    (drawn.iter().flatten())
        .map(|d| {
            let n = d.inner as u64;
            (n + 1) * (n + 2) / 2 * vertex + 3 * 4 * n.saturating_sub(3).pow(2)
        })
        .sum()
}

/// Whether `cfg` can be drawn adaptively: a power-of-two largest level (its elements are drawn
/// once `Scene::set_levels` chose their levels; before, nothing).
pub(super) fn check(cfg: &DrawConfig) -> Result<(), RenderError> {
    super::pattern::check_dyadic(
        cfg.level,
        "the static driver takes the pattern driver's largest levels: a power of two",
        "",
    )
}

/// The draws of the elements `range`: one indexed draw per chunk of records over its elements'
/// index ranges, or with `per_element` one per element, its index within the chunk in the push
/// constants' `draw.w` (the vertex stage passes it to the fragment stage, which reads the
/// element's levels for the `levels` view).
pub(super) fn cmd_draw(
    cmd: &Cmd<'_>,
    r: &Renderer,
    mesh: &GpuMesh,
    level: u32,
    a: &AdaptiveIndex,
    range: std::ops::Range<u32>,
    per_element: bool,
) {
    for c in mesh.chunks(range) {
        let (start, end) = (
            a.first[c.first as usize],
            a.first[(c.first + c.count) as usize],
        );
        if start == end {
            continue;
        }
        cmd.bind_descriptor_set(r.layout.raw, SET_MESH, c.set, &[0]);
        let push = |element: u32| {
            let draw = [level, c.base, 0, element];
            cmd.push_constants(
                r.layout.raw,
                PUSH_STAGES,
                PUSH_DRAW_OFFSET,
                bytemuck::cast_slice(&draw),
            );
        };
        if !per_element {
            push(0);
            cmd.draw_indexed(end - start, 1, start, 0, 0);
            continue;
        }
        for e in c.first..c.first + c.count {
            let (start, end) = (a.first[e as usize], a.first[e as usize + 1]);
            if start < end {
                push(e - c.base);
                cmd.draw_indexed(end - start, 1, start, 0, 0);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pattern::adaptive::adaptive_element;
    use crate::render::Driver;
    use crate::surface::{Displace, Surface};

    /// One element at mixed levels: the vertices are the adaptive mirror's weights, evaluated,
    /// in its order, and the degenerate triangles are gone.
    #[test]
    fn vertices_are_the_adaptive_mirrors() {
        let mesh = crate::mesh::default_mesh();
        let records = crate::surface::build_records(
            crate::surface::RecordKind::Corners,
            &mesh,
            crate::surface::Seams::default(),
        );
        let cfg = DrawConfig::new(Driver::Static, 8).with_surface(Surface::Pn, Displace::None);
        let levels = ElementLevels {
            edges: [1.0, 3.0, 8.0],
            inner: 8.0,
        };
        let all = vec![levels; 2];
        let mut culled = all.clone();
        culled[1] = ElementLevels::CULLED;
        let mirror = crate::surface::Mirror::new(
            cfg.surface,
            cfg.displace,
            &cfg.build,
            &crate::surface::Sources::default(),
        )
        .unwrap();
        let r = refine_adaptive(&cfg, &records[..2], drawn(&culled, 8), &mirror, true);
        let e = adaptive_element(&levels, 8, false).unwrap();
        assert_eq!(r.vertices.len(), e.bary.len());
        assert_eq!(
            r.first,
            vec![0, r.indices.len() as u32, r.indices.len() as u32]
        );
        for (k, b) in e.bary.iter().enumerate() {
            let p = mirror.eval(&cfg.params, 0, &records[0], *b);
            assert_eq!(r.vertices[k][..3], p.position.to_array());
            assert_eq!(r.samples[k][..3], b.map(f32::to_bits));
        }
        // Edge 0 at level 1 merges 7 of its 9 boundary vertices into the corners, edge 1 at
        // level 3 five into its samples: the triangles between them and the first row
        // become degenerate.
        let all_tris = Pattern::uniform(8).indices.len();
        assert!(
            r.indices.len() < all_tris,
            "{} of {all_tris}",
            r.indices.len()
        );
        let both = refine_adaptive(&cfg, &records[..2], drawn(&all, 8), &mirror, false);
        assert_eq!(both.indices.len(), 2 * r.indices.len());
        assert!(both.samples.is_empty());
        // The size checked before refining is at most what is made (vertices exactly): 45
        // vertices of 24 bytes (and samples of 16), 25 of its 64 triangles never degenerate.
        let made = |r: &AdaptiveRefined| {
            (24 * r.vertices.len() + 16 * r.samples.len() + 4 * r.indices.len()) as u64
        };
        assert_eq!(least_bytes(&drawn(&culled, 8), true), 45 * 40 + 25 * 12);
        assert!(least_bytes(&drawn(&culled, 8), true) <= made(&r));
        assert!(least_bytes(&drawn(&all, 8), false) <= made(&both));
    }
}
