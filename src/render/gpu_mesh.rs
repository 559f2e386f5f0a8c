//! Per-mesh GPU data (descriptor set 1): the elements' records, as texels per chunk and in an
//! aligned uniform array, the inputs the surfaces read (texture coordinates, the height map,
//! scalar tags, Loop's texel buffers), and the refinement patterns. Bytes uploaded per frame
//! depend on the coarse mesh only ([`GpuMesh::update_records`]), never on the refinement level.

use super::bindings::*;
use super::loop_gpu::LoopPass;
use super::{MeshData, RenderError};
use crate::gpu::{
    vk, Buffer, BufferDesc, BufferView, CommandPool, Context, DescriptorPool, GpuError,
};
use crate::lod::levels::ElementLevels;
use crate::pattern::{Pattern, PatternSet};
use crate::surface::stpn::VertexTag;
use crate::surface::{ElementRecord, Heightmap, RECORD_BYTES};
use std::sync::Arc;

/// One pattern level on the GPU: barycentric vertices and its triangle list.
pub struct GpuPattern {
    pub level: u32,
    pub vertices: Buffer,
    pub indices: Buffer,
    pub vertex_count: u32,
    pub index_count: u32,
}

impl GpuPattern {
    pub fn new(ctx: &Arc<Context>, pool: &CommandPool, p: &Pattern) -> Result<Self, GpuError> {
        let vertices = Buffer::new_with_data(
            ctx,
            pool,
            vk::BufferUsageFlags::VERTEX_BUFFER,
            &p.bary,
            &format!("pattern {} vertices", p.level),
        )?;
        let indices = Buffer::new_with_data(
            ctx,
            pool,
            vk::BufferUsageFlags::INDEX_BUFFER,
            &p.indices,
            &format!("pattern {} triangles", p.level),
        )?;
        Ok(Self {
            level: p.level,
            vertices,
            indices,
            vertex_count: p.bary.len() as u32,
            index_count: p.indices.len() as u32,
        })
    }
}

/// GPU data of one mesh.
pub struct GpuMesh {
    pub element_count: u32,
    /// Each chunk's records, texture coordinates and levels as texels
    /// ([`BINDING_ELEMENT_TEXELS`], [`BINDING_UVS`], [`BINDING_LEVELS`]; declared, so dropped,
    /// before the buffers they show).
    _chunk_views: Vec<BufferView>,
    /// The loop buffers' texel views, then the height map's and the tags' (declared before the
    /// tags, the height map's texels and the placeholder; a [`LoopScene`] drops its `gpu`
    /// before its `pass`, which owns the loop buffers).
    _views: Vec<BufferView>,
    /// `ElementRecord[]`, bound as a uniform texel buffer per chunk (what the stages read per
    /// invocation: the instanced adaptive pattern, tess, fragment normal fields) and, in
    /// windows of [`UBO_WINDOW`] records, as a dynamic
    /// uniform buffer (`ubo` submission); padded to whole windows.
    pub records: Buffer,
    /// Each element's texture coordinates (`heightmap`, texels per chunk), and the height map's
    /// pyramid layout (a uniform buffer).
    pub uvs: Buffer,
    pub heightmap: Buffer,
    /// Every vertex's scalar tags (`stpn`), a uniform texel buffer (after its view).
    pub tags: Buffer,
    /// Each element's levels ([`ElementLevels`], 16 bytes), read by the drivers when they draw
    /// adaptively (`FrameWork::adaptive`); written by the level pass or [`GpuMesh::upload_levels`].
    pub levels: Buffer,
    /// The levels [`GpuMesh::upload_levels`] last wrote; `levels` holds them unless the level
    /// pass has been recorded to write it since ([`GpuMesh::written_on_gpu`]).
    uploaded_levels: Option<Vec<ElementLevels>>,
    gpu_wrote_levels: std::cell::Cell<bool>,
    /// Shared by the scene's meshes (the loop surface's M1 draws the same patterns).
    pub patterns: Arc<Vec<GpuPattern>>,
    /// The pattern driver's adaptive draws of these elements (built by its `prepare`).
    pub adaptive: Option<super::pattern::AdaptivePattern>,
    pub pool: DescriptorPool,
    /// One descriptor set per chunk of [`GpuMesh::chunk`] elements: a texel view may span at
    /// most maxTexelBufferElements texels (and a chunk keeps within maxStorageBufferRange bytes
    /// of records: `chunk_size`), so a larger mesh is drawn chunk by chunk.
    pub sets: Vec<vk::DescriptorSet>,
    /// Elements per chunk.
    pub chunk: u32,
    /// The height map's texels, every level (a uniform texel buffer; after its view).
    pub heightmap_texels: Buffer,
    /// Bound where a surface's buffers are absent (every binding must be valid).
    _placeholder: Buffer,
}

/// The patterns a [`GpuMesh`] draws: uploaded for it, or another mesh's, shared.
pub enum Patterns<'a> {
    Upload(&'a PatternSet),
    Share(&'a Arc<Vec<GpuPattern>>),
}

/// What the mesh set binds besides records and texture coordinates.
#[derive(Clone, Copy)]
pub struct Extras<'a> {
    pub heightmap: &'a Heightmap,
    pub tags: &'a [VertexTag],
    /// The `loop` surface's M1 and tables (a placeholder is bound without).
    pub loop_: Option<&'a LoopPass>,
}

/// The part of an element range that lies in one chunk of records.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Chunk {
    /// The chunk's descriptor set: its first record (`fetch_record(0)`) is element `base`.
    pub set: vk::DescriptorSet,
    pub base: u32,
    /// The first element to draw (global index) and how many.
    pub first: u32,
    pub count: u32,
}

/// Elements per chunk for per-element arrays of `sizes` bytes each: as many as `max_range` bytes
/// hold of the largest (what one descriptor of it may span), a multiple of what
/// keeps every array's chunk offsets aligned to `align` (one such step where the range holds
/// less: only a range below Vulkan's least, `MESHREFINE_MAX_STORAGE_BUFFER_RANGE`, does).
pub fn chunk_elements(max_range: u64, align: u64, sizes: &[u64]) -> u32 {
    let gcd = |mut a: u64, mut b: u64| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    let align = align.max(1);
    let step = sizes.iter().fold(1, |step, &s| {
        let k = align / gcd(align, s);
        step / gcd(step, k) * k
    });
    let largest = sizes.iter().copied().max().unwrap_or(1);
    // At least one step, whatever the range: a chunk offset must stay aligned.
    let n = (max_range / largest) / step * step;
    n.clamp(step.min(u32::MAX as u64), u32::MAX as u64) as u32
}

/// Bytes of one element's levels on the GPU.
const LEVELS_BYTES: u64 = std::mem::size_of::<ElementLevels>() as u64;

/// Bytes of one element's texture coordinates on the GPU (three `vec2`, padded).
const UV_BYTES: u64 = 32;

impl GpuMesh {
    /// Upload `data`'s records and every per-mesh input the surfaces read, and write one
    /// descriptor set per chunk of records.
    pub fn new(
        ctx: &Arc<Context>,
        cmd_pool: &CommandPool,
        set_layout: &crate::gpu::DescriptorSetLayout,
        data: &MeshData,
        patterns: Patterns<'_>,
        max_chunk: Option<u32>,
        extras: Extras<'_>,
    ) -> Result<Self, RenderError> {
        let n = data.records.len() as u64;
        let chunk = chunk_size(&ctx.info.limits, max_chunk);
        let chunks = n.div_ceil(chunk as u64).max(1) as u32;
        check_heightmap(extras.heightmap, &ctx.info.limits)?;
        let records = upload_records(ctx, &data.records)?;
        // Written by the level pass (storage), read by the drawing stages (texels).
        let levels = upload(
            ctx,
            &vec![ElementLevels::UNIFORM_1; n.max(1) as usize],
            vk::BufferUsageFlags::STORAGE_BUFFER | TEXELS,
            "element levels",
        )?;
        let inputs = SurfaceInputs::upload(ctx, data, &extras)?;
        let patterns = match patterns {
            Patterns::Upload(set) => Arc::new(
                set.patterns
                    .iter()
                    .map(|p| GpuPattern::new(ctx, cmd_pool, p))
                    .collect::<Result<Vec<_>, _>>()?,
            ),
            Patterns::Share(uploaded) => uploaded.clone(),
        };
        let pool = DescriptorPool::new(
            ctx,
            chunks,
            &[
                (vk::DescriptorType::UNIFORM_TEXEL_BUFFER, 11 * chunks),
                (vk::DescriptorType::UNIFORM_BUFFER, chunks),
                (vk::DescriptorType::UNIFORM_BUFFER_DYNAMIC, chunks),
            ],
            "mesh descriptors",
        )?;
        let placeholder = Buffer::new_with_data(ctx, cmd_pool, TEXELS, &[0u32; 4], "placeholder")?;
        let mut views = loop_views(ctx, extras.loop_, &placeholder)?;
        let mut chunk_views = Vec::with_capacity(3 * chunks as usize);
        for (buffer, format, name) in [
            (
                &inputs.heightmap_texels,
                vk::Format::R32_SFLOAT,
                "height map texels view",
            ),
            (
                &inputs.tags,
                vk::Format::R32G32B32A32_SFLOAT,
                "vertex scalar tags view",
            ),
        ] {
            views.push(BufferView::new(ctx, buffer, format, name)?);
        }
        let sets = (0..chunks as u64)
            .map(|c| {
                let set = pool.allocate(set_layout, &format!("mesh set {c}"))?;
                let first = c * chunk as u64;
                let count = (n - first.min(n)).min(chunk as u64).max(1);
                write_mesh_set(&pool, set, &records, &inputs, &views);
                let rec_size = RECORD_BYTES as u64;
                let uv_first = if inputs.own_uvs { first } else { 0 };
                let spans = [
                    (
                        BINDING_ELEMENT_TEXELS,
                        &records,
                        vk::Format::R32G32B32A32_UINT,
                        (first * rec_size, count * rec_size),
                        "element record texels",
                    ),
                    (
                        BINDING_UVS,
                        &inputs.uvs,
                        vk::Format::R32G32B32A32_SFLOAT,
                        (uv_first * UV_BYTES, count.min(inputs.uv_count) * UV_BYTES),
                        "element texture coordinate texels",
                    ),
                    (
                        BINDING_LEVELS,
                        &levels,
                        vk::Format::R32G32B32A32_SFLOAT,
                        (first * LEVELS_BYTES, count * LEVELS_BYTES),
                        "element level texels",
                    ),
                ];
                for (binding, buffer, format, span, name) in spans {
                    let view = BufferView::span(ctx, buffer, format, span, &format!("{name} {c}"))?;
                    pool.write_texel_buffer(
                        set,
                        binding,
                        vk::DescriptorType::UNIFORM_TEXEL_BUFFER,
                        view.raw,
                    );
                    chunk_views.push(view);
                }
                Ok(set)
            })
            .collect::<Result<Vec<_>, GpuError>>()?;
        Ok(Self {
            element_count: n as u32,
            records,
            uvs: inputs.uvs,
            heightmap: inputs.heightmap,
            heightmap_texels: inputs.heightmap_texels,
            tags: inputs.tags,
            levels,
            uploaded_levels: None,
            gpu_wrote_levels: Default::default(),
            patterns,
            adaptive: None,
            pool,
            sets,
            chunk,
            _views: views,
            _chunk_views: chunk_views,
            _placeholder: placeholder,
        })
    }

    /// The chunks `elements` spans, in order, each with its part of the range.
    pub fn chunks(&self, elements: std::ops::Range<u32>) -> Vec<Chunk> {
        let mut out = Vec::new();
        let mut first = elements.start;
        while first < elements.end.min(self.element_count) {
            let c = first / self.chunk;
            let base = c * self.chunk;
            let end = (base + self.chunk).min(elements.end);
            out.push(Chunk {
                set: self.sets[c as usize],
                base,
                first,
                count: end - first,
            });
            first = end;
        }
        out
    }

    /// The pattern of `level`, if the set holds it.
    pub fn pattern(&self, level: u32) -> Option<&GpuPattern> {
        self.patterns.iter().find(|p| p.level == level)
    }

    /// Upload every element's levels (tests and CPU-chosen levels; the level pass writes the
    /// same buffer on the GPU), unless the buffer holds them already (a still frame of the
    /// static driver uploads nothing). The caller makes sure no pending work reads them.
    pub fn upload_levels(&mut self, levels: &[ElementLevels]) {
        assert_eq!(levels.len() as u32, self.element_count);
        if self.gpu_wrote_levels.take() || self.uploaded_levels.as_deref() != Some(levels) {
            self.levels.write_pod(0, levels);
            self.uploaded_levels = Some(levels.to_vec());
        }
    }

    /// Said by the level pass when it records writes to `levels`: the next upload writes them
    /// all.
    pub fn written_on_gpu(&self) {
        self.gpu_wrote_levels.set(true);
    }

    /// Upload new coarse records (animation). The caller makes sure no pending work reads them.
    pub fn update_records(&mut self, records: &[ElementRecord]) {
        assert_eq!(records.len() as u32, self.element_count);
        self.records.write_pod(0, records);
    }
}

/// Elements per chunk on this device: as many records as one texel view spans
/// (maxTexelBufferElements texels, seven a record; the texture coordinates' and levels' views,
/// two and one texels an element, then fit too), and at most maxStorageBufferRange bytes of
/// records, the device's largest buffer range (no set 1 binding is a storage buffer, but this
/// is the limit `MESHREFINE_MAX_STORAGE_BUFFER_RANGE` lowers to cut small chunks in tests), or
/// `max_chunk` (tests use small chunks).
fn chunk_size(limits: &vk::PhysicalDeviceLimits, max_chunk: Option<u32>) -> u32 {
    let rec_size = RECORD_BYTES as u64;
    // Both alignments are powers of two: the larger is a multiple of the other.
    let align =
        (limits.min_storage_buffer_offset_alignment).max(limits.min_texel_buffer_offset_alignment);
    let texel_range = limits.max_texel_buffer_elements as u64 * 16;
    let range = (limits.max_storage_buffer_range as u64).min(texel_range);
    let range = max_chunk.map_or(range, |c| range.min(c as u64 * rec_size));
    chunk_elements(range, align, &[rec_size, UV_BYTES, LEVELS_BYTES])
}

/// The records, padded to whole `ubo` windows (texel, uniform and vertex buffer alike).
fn upload_records(ctx: &Arc<Context>, data: &[ElementRecord]) -> Result<Buffer, GpuError> {
    let n = data.len() as u64;
    let rec_size = RECORD_BYTES as u64;
    let mut records = Buffer::new(
        ctx,
        BufferDesc::new_upload(
            n.div_ceil(UBO_WINDOW as u64).max(1) * UBO_WINDOW as u64 * rec_size,
            vk::BufferUsageFlags::UNIFORM_BUFFER
                | vk::BufferUsageFlags::UNIFORM_TEXEL_BUFFER
                | vk::BufferUsageFlags::VERTEX_BUFFER,
        ),
        "element records",
    )?;
    records.write_pod(0, data);
    Ok(records)
}

/// The per-mesh inputs the surfaces and displacements read besides the records: texture
/// coordinates and the height map (`heightmap`), scalar tags (`stpn`). Each buffer holds at
/// least one entry: every binding must be valid whatever is drawn.
struct SurfaceInputs {
    uvs: Buffer,
    /// Entries in `uvs`, and whether they are the elements' own (else one zero entry).
    uv_count: u64,
    own_uvs: bool,
    heightmap: Buffer,
    heightmap_texels: Buffer,
    tags: Buffer,
}

impl SurfaceInputs {
    fn upload(ctx: &Arc<Context>, data: &MeshData, extras: &Extras<'_>) -> Result<Self, GpuError> {
        let n = data.records.len() as u64;
        // Texture coordinates (zeros without them: the binding is always valid).
        let uv_words: Vec<[f32; 8]> = match &data.uvs {
            Some(uvs) => uvs
                .iter()
                .map(|t| {
                    [
                        t[0][0], t[0][1], t[1][0], t[1][1], t[2][0], t[2][1], 0.0, 0.0,
                    ]
                })
                .collect(),
            None => vec![[0.0; 8]; n.max(1) as usize],
        };
        let tags = uploaded_tags(extras.tags, &ctx.info.limits);
        let tag_words: Vec<[f32; 12]> = if tags.is_empty() {
            vec![[0.0; 12]]
        } else {
            tags.iter().map(VertexTag::to_gpu).collect()
        };
        Ok(Self {
            uvs: upload(ctx, &uv_words, TEXELS, "element texture coordinates")?,
            uv_count: uv_words.len() as u64,
            own_uvs: data.uvs.is_some(),
            heightmap: upload(
                ctx,
                &extras.heightmap.gpu_header(),
                vk::BufferUsageFlags::UNIFORM_BUFFER,
                "height map pyramid layout",
            )?,
            heightmap_texels: upload(
                ctx,
                &extras.heightmap.gpu_texels(),
                TEXELS,
                "height map texels",
            )?,
            tags: upload(ctx, &tag_words, TEXELS, "vertex scalar tags")?,
        })
    }
}

/// The usage of the buffers the stages read as texels.
const TEXELS: vk::BufferUsageFlags = vk::BufferUsageFlags::UNIFORM_TEXEL_BUFFER;

/// A host-visible buffer of `usage` holding `words`.
fn upload<T: bytemuck::Pod>(
    ctx: &Arc<Context>,
    words: &[T],
    usage: vk::BufferUsageFlags,
    name: &str,
) -> Result<Buffer, GpuError> {
    let size = std::mem::size_of_val(words) as u64;
    let mut b = Buffer::new(ctx, BufferDesc::new_upload(size, usage), name)?;
    b.write_pod(0, words);
    Ok(b)
}

/// Refuses a height map whose pyramid has more texels than a texel buffer may hold on this
/// device (maxTexelBufferElements), before anything is uploaded.
fn check_heightmap(map: &Heightmap, limits: &vk::PhysicalDeviceLimits) -> Result<(), RenderError> {
    let needed = map.texel_count();
    let max = limits.max_texel_buffer_elements as u64;
    if needed > max {
        let l = &map.levels[0];
        return Err(RenderError::OverLimit {
            what: format!(
                "height map '{}' ({} x {} pixels, with its mip pyramid)",
                map.source, l.w, l.h
            ),
            needed,
            unit: "texels",
            limit: "this device's maxTexelBufferElements",
            max,
            remedy: "use a smaller height map".into(),
        });
    }
    Ok(())
}

/// The scalar tags to upload: all of them where they fit one texel-buffer descriptor
/// ([`check_tags`]), else none (one zero entry is bound): every mesh carries tags, derived if
/// not given, but only `stpn` reads them, and drawing it refuses a mesh whose tags do not fit.
fn uploaded_tags<'a>(tags: &'a [VertexTag], limits: &vk::PhysicalDeviceLimits) -> &'a [VertexTag] {
    if check_tags(tags.len(), limits).is_ok() {
        tags
    } else {
        &[]
    }
}

/// `count` vertices' scalar tags fit one texel-buffer descriptor (three texels a vertex), or a
/// sentence naming the limit (checked where a surface that reads tags is drawn).
pub fn check_tags(count: usize, limits: &vk::PhysicalDeviceLimits) -> Result<(), RenderError> {
    let needed = 3 * count as u64;
    let max = limits.max_texel_buffer_elements as u64;
    if needed > max {
        return Err(RenderError::OverLimit {
            what: format!("the scalar-tag buffer of {count} vertices"),
            needed,
            unit: "texels",
            limit: "this device's maxTexelBufferElements",
            max,
            remedy: "use a mesh with fewer vertices".into(),
        });
    }
    Ok(())
}

/// Texel views of the `loop` surface's buffers (M1, face entries, control points, tables, row
/// maps), or of `placeholder` where the mesh is not drawn as `loop`.
fn loop_views(
    ctx: &Arc<Context>,
    loop_: Option<&LoopPass>,
    placeholder: &Buffer,
) -> Result<Vec<BufferView>, GpuError> {
    let loop_buffers = match loop_ {
        Some(l) => [&l.m1, &l.n1, &l.faces, &l.control, &l.tables, &l.table_rows],
        None => [placeholder; 6],
    };
    let formats = [
        vk::Format::R32G32B32A32_SFLOAT,
        vk::Format::R32G32B32A32_SFLOAT,
        vk::Format::R32G32B32A32_UINT,
        vk::Format::R32G32B32A32_UINT,
        vk::Format::R32G32B32A32_SFLOAT,
        vk::Format::R32_UINT,
    ];
    loop_buffers
        .iter()
        .zip(formats)
        .zip([
            "M1 positions",
            "M1 normals",
            "face entries",
            "control",
            "tables",
            "table rows",
        ])
        .map(|((b, f), name)| BufferView::new(ctx, b, f, &format!("loop {name} view")))
        .collect()
}

/// Write what set 1 shares between chunks: the records' `ubo` window, the height map's layout,
/// and the loop, height map texel and tag views (each chunk's own texel views are written
/// beside it, in [`GpuMesh::new`]).
fn write_mesh_set(
    pool: &DescriptorPool,
    set: vk::DescriptorSet,
    records: &Buffer,
    inputs: &SurfaceInputs,
    views: &[BufferView],
) {
    let rec_size = RECORD_BYTES as u64;
    pool.write_buffer(
        set,
        BINDING_ELEMENT_UBO,
        vk::DescriptorType::UNIFORM_BUFFER_DYNAMIC,
        records.raw,
        UBO_WINDOW as u64 * rec_size,
    );
    pool.write_buffer(
        set,
        BINDING_HEIGHTMAP,
        vk::DescriptorType::UNIFORM_BUFFER,
        inputs.heightmap.raw,
        vk::WHOLE_SIZE,
    );
    for (binding, view) in [
        BINDING_LOOP_P1,
        BINDING_LOOP_N1,
        BINDING_LOOP_FACES,
        BINDING_LOOP_CONTROL,
        BINDING_LOOP_TABLES,
        BINDING_LOOP_ROWS,
        BINDING_HEIGHTMAP_TEXELS,
        BINDING_TAGS,
    ]
    .into_iter()
    .zip(views)
    {
        pool.write_texel_buffer(
            set,
            binding,
            vk::DescriptorType::UNIFORM_TEXEL_BUFFER,
            view.raw,
        );
    }
}

#[cfg(test)]
pub(super) mod tests;
