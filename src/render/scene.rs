//! Per-mesh GPU data (descriptor set 1): the elements' records, in a storage buffer and in an
//! aligned uniform array, and the refinement patterns. Bytes uploaded per frame depend on the
//! coarse mesh only ([`GpuMesh::update_records`]), never on the refinement level.

use super::bindings::*;
use super::loop_gpu::{LoopPass, LoopScene};
use super::RenderError;
use crate::gpu::{
    vk, Buffer, BufferDesc, BufferView, CommandPool, Context, DescriptorPool, GpuError,
};
use crate::mesh::Mesh;
use crate::pattern::{Pattern, PatternSet};
use crate::surface::stpn::VertexTag;
use crate::surface::Surface;
use crate::surface::{build_records, ElementRecord, Heightmap, RecordKind, Seams, RECORD_BYTES};
use std::sync::Arc;

/// CPU-side data of a mesh ready to draw: the mesh and its elements' records.
#[derive(Clone, Debug)]
pub struct MeshData {
    pub mesh: Mesh,
    pub kind: RecordKind,
    /// The seams the records were built for.
    pub seams: Seams,
    pub records: Vec<ElementRecord>,
    /// Each element's texture coordinates (stored corner order), when every triangle has them.
    pub uvs: Option<Vec<[[f32; 2]; 3]>>,
    /// Mean longest texture-space edge of the elements (0 without coordinates).
    pub uv_extent: f32,
}

impl MeshData {
    pub fn new(mesh: Mesh, kind: RecordKind, seams: Seams) -> Self {
        let records = build_records(kind, &mesh, seams);
        let uvs: Option<Vec<[[f32; 2]; 3]>> = mesh
            .triangles
            .iter()
            .map(|t| {
                t.t.map(|c| c.map(|i| mesh.texcoords[i as usize].to_array()))
            })
            .collect();
        let uv_extent = uvs.as_ref().map_or(0.0, |uvs| {
            let longest = |t: &[[f32; 2]; 3]| {
                (0..3)
                    .map(|k| {
                        let (a, b) = (glam::Vec2::from(t[k]), glam::Vec2::from(t[(k + 1) % 3]));
                        (a - b).length() as f64
                    })
                    .fold(0.0, f64::max)
            };
            (uvs.iter().map(longest).sum::<f64>() / uvs.len().max(1) as f64) as f32
        });
        Self {
            mesh,
            kind,
            seams,
            records,
            uvs,
            uv_extent,
        }
    }
}

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
    /// `ElementRecord[]`, bound as a storage buffer (instanced pattern, tess, fragment normal
    /// fields) and, in windows of [`UBO_WINDOW`] records, as a dynamic uniform buffer (`ubo`
    /// submission); padded to whole windows.
    pub records: Buffer,
    /// Each element's texture coordinates (`heightmap`), and the height map's pyramid.
    pub uvs: Buffer,
    pub heightmap: Buffer,
    /// Every vertex's scalar tags (`stpn`).
    pub tags: Buffer,
    /// Shared by the scene's meshes (the loop surface's M1 draws the same patterns).
    pub patterns: Arc<Vec<GpuPattern>>,
    pub pool: DescriptorPool,
    /// One descriptor set per chunk of [`GpuMesh::chunk`] elements: a storage-buffer descriptor
    /// may span at most maxStorageBufferRange bytes, so a larger mesh is drawn chunk by chunk.
    pub sets: Vec<vk::DescriptorSet>,
    /// Elements per chunk.
    pub chunk: u32,
    /// The loop buffers' texel views (a [`LoopScene`] drops its `gpu` before its `pass`, which
    /// owns the buffers; the placeholder's views before the placeholder, declared after).
    _views: Vec<BufferView>,
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
    pub subdiv: Option<&'a LoopPass>,
}

/// The part of an element range that lies in one chunk of records.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Chunk {
    /// The chunk's descriptor set: `records[0]` there is element `base`.
    pub set: vk::DescriptorSet,
    pub base: u32,
    /// The first element to draw (global index) and how many.
    pub first: u32,
    pub count: u32,
}

/// Elements per chunk for per-element arrays of `sizes` bytes each: as many as one
/// storage-buffer descriptor can span (`max_range` bytes) for the largest, a multiple of what
/// keeps every array's chunk offsets aligned to `align`.
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
    let n = (max_range / largest) / step * step;
    n.clamp(1, u32::MAX as u64) as u32
}

/// Bytes of one element's texture coordinates on the GPU (three `vec2`, padded).
const UV_BYTES: u64 = 32;

impl GpuMesh {
    pub fn new(
        ctx: &Arc<Context>,
        cmd_pool: &CommandPool,
        set_layout: &crate::gpu::DescriptorSetLayout,
        data: &MeshData,
        patterns: Patterns<'_>,
        max_chunk: Option<u32>,
        extras: Extras<'_>,
    ) -> Result<Self, RenderError> {
        let Extras {
            heightmap,
            tags,
            subdiv,
        } = extras;
        let n = data.records.len() as u64;
        let rec_size = RECORD_BYTES as u64;
        let limits = &ctx.info.limits;
        let align = limits.min_storage_buffer_offset_alignment;
        let range = limits.max_storage_buffer_range as u64;
        let range = max_chunk.map_or(range, |c| range.min(c as u64 * rec_size));
        let chunk = chunk_elements(range, align, &[rec_size, UV_BYTES]);
        let chunks = n.div_ceil(chunk as u64).max(1) as u32;
        let mut records = Buffer::new(
            ctx,
            BufferDesc::new_upload(
                n.div_ceil(UBO_WINDOW as u64).max(1) * UBO_WINDOW as u64 * rec_size,
                vk::BufferUsageFlags::STORAGE_BUFFER
                    | vk::BufferUsageFlags::UNIFORM_BUFFER
                    | vk::BufferUsageFlags::VERTEX_BUFFER,
            ),
            "element records",
        )?;
        records.write_pod(0, &data.records);
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
        let mut uvs = Buffer::new(
            ctx,
            BufferDesc::new_upload(
                uv_words.len() as u64 * UV_BYTES,
                vk::BufferUsageFlags::STORAGE_BUFFER,
            ),
            "element texture coordinates",
        )?;
        uvs.write_pod(0, &uv_words);
        let hm_words = heightmap.to_gpu();
        let mut hm = Buffer::new(
            ctx,
            BufferDesc::new_upload(
                hm_words.len() as u64 * 4,
                vk::BufferUsageFlags::STORAGE_BUFFER,
            ),
            "height map pyramid",
        )?;
        hm.write_pod(0, &hm_words);
        let tag_words: Vec<[f32; 12]> = if tags.is_empty() {
            vec![[0.0; 12]]
        } else {
            tags.iter().map(VertexTag::to_gpu).collect()
        };
        let mut tags_buffer = Buffer::new(
            ctx,
            BufferDesc::new_upload(
                tag_words.len() as u64 * 48,
                vk::BufferUsageFlags::STORAGE_BUFFER,
            ),
            "vertex scalar tags",
        )?;
        tags_buffer.write_pod(0, &tag_words);
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
                (vk::DescriptorType::STORAGE_BUFFER, 4 * chunks),
                (vk::DescriptorType::UNIFORM_TEXEL_BUFFER, 6 * chunks),
                (vk::DescriptorType::UNIFORM_BUFFER_DYNAMIC, chunks),
            ],
            "mesh descriptors",
        )?;
        let placeholder = Buffer::new_with_data(
            ctx,
            cmd_pool,
            vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::UNIFORM_TEXEL_BUFFER,
            &[0u32; 4],
            "placeholder",
        )?;
        let loop_buffers = match subdiv {
            Some(l) => [&l.m1, &l.n1, &l.faces, &l.control, &l.tables, &l.table_rows],
            None => [&placeholder; 6],
        };
        let formats = [
            vk::Format::R32G32B32A32_SFLOAT,
            vk::Format::R32G32B32A32_SFLOAT,
            vk::Format::R32G32B32A32_UINT,
            vk::Format::R32G32B32A32_UINT,
            vk::Format::R32G32B32A32_SFLOAT,
            vk::Format::R32_UINT,
        ];
        let views = loop_buffers
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
            .collect::<Result<Vec<_>, _>>()?;
        let mut sets = Vec::with_capacity(chunks as usize);
        for c in 0..chunks as u64 {
            let set = pool.allocate(set_layout, &format!("mesh set {c}"))?;
            let first = c * chunk as u64;
            let count = (n - first.min(n)).min(chunk as u64).max(1);
            pool.write_buffer_at(
                set,
                BINDING_ELEMENTS,
                vk::DescriptorType::STORAGE_BUFFER,
                records.raw,
                first * rec_size,
                count * rec_size,
            );
            pool.write_buffer(
                set,
                BINDING_ELEMENT_UBO,
                vk::DescriptorType::UNIFORM_BUFFER_DYNAMIC,
                records.raw,
                UBO_WINDOW as u64 * rec_size,
            );
            let uv_first = if data.uvs.is_some() { first } else { 0 };
            pool.write_buffer_at(
                set,
                BINDING_UVS,
                vk::DescriptorType::STORAGE_BUFFER,
                uvs.raw,
                uv_first * UV_BYTES,
                count.min(uv_words.len() as u64) * UV_BYTES,
            );
            pool.write_buffer(
                set,
                BINDING_HEIGHTMAP,
                vk::DescriptorType::STORAGE_BUFFER,
                hm.raw,
                vk::WHOLE_SIZE,
            );
            pool.write_buffer(
                set,
                BINDING_TAGS,
                vk::DescriptorType::STORAGE_BUFFER,
                tags_buffer.raw,
                vk::WHOLE_SIZE,
            );
            for (binding, view) in [
                BINDING_LOOP_P1,
                BINDING_LOOP_N1,
                BINDING_LOOP_FACES,
                BINDING_LOOP_CONTROL,
                BINDING_LOOP_TABLES,
                BINDING_LOOP_ROWS,
            ]
            .into_iter()
            .zip(&views)
            {
                pool.write_texel_buffer(
                    set,
                    binding,
                    vk::DescriptorType::UNIFORM_TEXEL_BUFFER,
                    view.raw,
                );
            }
            sets.push(set);
        }
        Ok(Self {
            element_count: n as u32,
            records,
            uvs,
            heightmap: hm,
            tags: tags_buffer,
            patterns,
            pool,
            sets,
            chunk,
            _views: views,
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

    /// Upload new coarse records (animation). The caller makes sure no pending work reads them.
    pub fn update_records(&mut self, records: &[ElementRecord]) {
        assert_eq!(records.len() as u32, self.element_count);
        self.records.write_pod(0, records);
    }
}

/// Everything needed to draw one mesh with any driver: CPU data, GPU data, the pattern set and
/// (built on demand) the static driver's refined vertex buffer.
pub struct Scene {
    pub data: MeshData,
    pub gpu: GpuMesh,
    /// The `heightmap` displacement's map (a generated one until [`Scene::set_heightmap`]).
    pub heightmap: Heightmap,
    /// Every vertex's scalar tags (`stpn`): derived from the mesh's hard edges until
    /// [`Scene::set_tags`].
    pub tags: Vec<VertexTag>,
    pub(super) max_chunk: Option<u32>,
    pub patterns: PatternSet,
    pub static_vbo: Option<super::static_vbo::StaticVbo>,
    /// The `loop` surface's M1 faces, built by the first `prepare` that draws it.
    pub subdiv: Option<LoopScene>,
    /// The coarse records on the GPU are older than `data` (an animated frame drawn with loop,
    /// which does not read them, uploads M0 only); the next other surface uploads them.
    records_stale: bool,
    warned_slow: bool,
}

impl Scene {
    /// Upload `mesh` with patterns for LOD up to `max_level`.
    pub fn new(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
        mesh: Mesh,
        max_level: u32,
    ) -> Result<Self, RenderError> {
        Self::with_patterns(ctx, pool, renderer, mesh, PatternSet::up_to(max_level))
    }

    /// Upload `mesh` with exactly the given pattern set.
    pub fn with_patterns(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
        mesh: Mesh,
        patterns: PatternSet,
    ) -> Result<Self, RenderError> {
        Self::with_chunks(ctx, pool, renderer, mesh, patterns, None)
    }

    /// Upload `mesh` with exactly the given pattern set, its records in chunks of at most
    /// `max_chunk` elements (None: as many as the device's maxStorageBufferRange allows; tests
    /// pass small chunks to exercise drawing chunk by chunk).
    pub fn with_chunks(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
        mesh: Mesh,
        patterns: PatternSet,
        max_chunk: Option<u32>,
    ) -> Result<Self, RenderError> {
        let data = MeshData::new(mesh, RecordKind::Corners, Seams::default());
        let heightmap = Heightmap::generated();
        let (tags, _) = crate::surface::stpn::derive(&data.mesh);
        let gpu = GpuMesh::new(
            ctx,
            pool,
            &renderer.mesh_layout,
            &data,
            Patterns::Upload(&patterns),
            max_chunk,
            Extras {
                heightmap: &heightmap,
                tags: &tags,
                subdiv: None,
            },
        )?;
        Ok(Self {
            data,
            gpu,
            heightmap,
            tags,
            max_chunk,
            patterns,
            static_vbo: None,
            subdiv: None,
            records_stale: false,
            warned_slow: false,
        })
    }

    /// Check that `cfg` can be drawn here and build what it needs (pipelines, including the
    /// wireframe pass when `wire`, static buffers).
    /// Only between frames: may rewrite the mesh descriptor set.
    pub fn prepare(
        &mut self,
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &mut super::Renderer,
        cfg: &super::DrawConfig,
        capture: super::Capture,
        wire: bool,
    ) -> Result<(), RenderError> {
        if self.patterns.find(cfg.level).is_none() {
            let levels: Vec<String> = self.patterns.levels().map(|l| l.to_string()).collect();
            return Err(RenderError::LevelNotUploaded {
                level: cfg.level,
                levels: levels.join(", "),
            });
        }
        if cfg.surface == Surface::Loop
            && self.subdiv.as_ref().is_none_or(|l| {
                l.data.boundary != cfg.params.boundary
                    || l.data.tables.lattice.lmax != cfg.params.bft_level
            })
        {
            self.subdiv = None;
            self.static_vbo = None;
            let lattice = crate::surface::loop_::Lattice::new(cfg.params.bft_level);
            self.subdiv = Some(LoopScene::new(
                ctx,
                pool,
                renderer,
                self,
                cfg.params.boundary,
                lattice,
            )?);
        }
        if cfg.surface != Surface::Loop && self.records_stale {
            self.gpu.update_records(&self.data.records);
            self.records_stale = false;
        }
        if cfg.surface == Surface::Loop && cfg.displace == crate::surface::Displace::Heightmap {
            return Err(RenderError::Unsupported(
                "the loop surface has no texture coordinates: the heightmap displacement needs them (use sine or noise)",
            ));
        }
        if cfg.surface == crate::surface::Surface::Stpn {
            crate::surface::stpn::check(&self.data.mesh, &self.tags).map_err(RenderError::Tags)?;
        }
        if cfg.displace == crate::surface::Displace::Heightmap && self.data.uvs.is_none() {
            return Err(RenderError::Unsupported(
                "the mesh has no texture coordinates (vt on every face): the heightmap displacement reads the map there",
            ));
        }
        if cfg.params.seams != self.data.seams && cfg.surface != Surface::Loop {
            self.data.records = build_records(self.data.kind, &self.data.mesh, cfg.params.seams);
            self.data.seams = cfg.params.seams;
            self.gpu.update_records(&self.data.records);
            self.static_vbo = None;
        }
        super::driver::check_level(ctx, cfg)?;
        use super::Capture;
        if capture == Capture::Vertices && !ctx.info.vertex_stores {
            return Err(GpuError::MissingFeature {
                device: ctx.info.name.clone(),
                feature: "vertexPipelineStoresAndAtomics (needed to capture evaluated vertices)",
            }
            .into());
        }
        if capture == Capture::Triangles && !ctx.info.transform_feedback {
            return Err(GpuError::MissingFeature {
                device: ctx.info.name.clone(),
                feature: "transformFeedback (VK_EXT_transform_feedback, needed to read back the tessellator's triangles)",
            }
            .into());
        }
        let kind = cfg.driver.kind();
        if capture == Capture::Triangles && kind.export_capture() != Some(Capture::Triangles) {
            return Err(RenderError::Unsupported(
                "triangle capture is for the tess driver",
            ));
        }
        if capture != Capture::None && kind.capture_per_element(cfg.level).is_none() {
            return Err(RenderError::Unsupported(
                "the static driver evaluates on the CPU: there is nothing to capture (use pattern or tess)",
            ));
        }
        renderer.prepare(cfg, capture, wire)?;
        let refined =
            self.elements(cfg.surface).element_count as u64 * cfg.refined_per_element() as u64;
        if ctx.info.device_type == vk::PhysicalDeviceType::CPU
            && refined > 50_000_000
            && !self.warned_slow
        {
            log::warn!(
                "{refined} refined triangles per frame on a software device ({}): expect seconds per frame",
                ctx.info.name
            );
            self.warned_slow = true;
        }
        kind.prepare(self, ctx, pool, cfg)?;
        Ok(())
    }

    /// Replace the coarse positions/normals (animation), for drawing `surface` next: its new
    /// data is uploaded (the records, or for loop M0's positions alone, what
    /// [`Scene::upload_bytes`] counts); the static buffer, if any, becomes stale and is rebuilt
    /// by the next `prepare`. Only between frames.
    pub fn update_mesh(&mut self, mesh: Mesh, surface: Surface) {
        self.data = MeshData::new(mesh, self.data.kind, self.data.seams);
        if let Some(l) = &mut self.subdiv {
            // Loop: only M0's positions go up; the passes make M1 on the GPU (the mirror's M1
            // follows when it is read).
            l.pass.upload_m0(&self.data.mesh.positions);
            l.frame = std::cell::OnceCell::new();
        }
        if surface == Surface::Loop && self.subdiv.is_some() {
            self.records_stale = true;
        } else {
            self.gpu.update_records(&self.data.records);
            self.records_stale = false;
        }
        self.static_vbo = None;
    }

    /// Bytes an animated frame uploads when drawing `cfg`: the refined vertices (static), the
    /// coarse records (the local surfaces), or M0's positions (loop): the last two independent
    /// of the level.
    pub fn upload_bytes(&self, cfg: &super::DrawConfig) -> u64 {
        if cfg.driver.kind().refines_on_cpu() {
            return cfg.geometry_bytes(self.elements(cfg.surface).element_count as u64);
        }
        match self.pre_pass(cfg) {
            Some(pass) => pass.upload_bytes(),
            None => self.gpu.element_count as u64 * RECORD_BYTES as u64,
        }
    }

    /// The elements `surface` draws: M1 faces for `loop` (once prepared), coarse triangles
    /// otherwise.
    pub fn elements(&self, surface: Surface) -> &GpuMesh {
        match (&self.subdiv, surface) {
            (Some(l), Surface::Loop) => &l.gpu,
            _ => &self.gpu,
        }
    }

    /// The records of [`Scene::elements`].
    pub fn records(&self, surface: Surface) -> &[ElementRecord] {
        match (&self.subdiv, surface) {
            (Some(l), Surface::Loop) => &l.data.records,
            _ => &self.data.records,
        }
    }

    /// GPU bytes of geometry `cfg` draws from: the driver's own ([`super::DrawConfig::geometry_bytes`]
    /// of the elements) and, for loop, M1, its passes' data and the tables.
    pub fn geometry_bytes(&self, cfg: &super::DrawConfig) -> u64 {
        let elements = self.elements(cfg.surface).element_count as u64;
        cfg.geometry_bytes(elements) + self.pre_pass(cfg).map_or(0, |p| p.gpu_bytes())
    }

    /// The passes `cfg` runs before drawing (Loop's M0 -> M1 on the GPU drivers; `static`
    /// draws what the CPU evaluated).
    pub fn pre_pass(&self, cfg: &super::DrawConfig) -> Option<&LoopPass> {
        match (&self.subdiv, cfg.surface) {
            _ if cfg.driver.kind().refines_on_cpu() => None,
            (Some(l), Surface::Loop) => Some(&l.pass),
            _ => None,
        }
    }

    /// Replace the height map (between frames): uploaded, and the static buffer rebuilt.
    pub fn set_heightmap(
        &mut self,
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
        map: Heightmap,
    ) -> Result<(), RenderError> {
        self.heightmap = map;
        self.reupload(ctx, pool, renderer)
    }

    /// Replace the scalar tags (between frames), checked against appendix B's restrictions.
    pub fn set_tags(
        &mut self,
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
        tags: Vec<VertexTag>,
    ) -> Result<(), RenderError> {
        assert_eq!(tags.len(), self.data.mesh.positions.len());
        self.tags = tags;
        self.reupload(ctx, pool, renderer)
    }

    fn reupload(
        &mut self,
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
    ) -> Result<(), RenderError> {
        self.gpu = GpuMesh::new(
            ctx,
            pool,
            &renderer.mesh_layout,
            &self.data,
            Patterns::Upload(&self.patterns),
            self.max_chunk,
            Extras {
                heightmap: &self.heightmap,
                tags: &self.tags,
                subdiv: None,
            },
        )?;
        self.static_vbo = None;
        Ok(())
    }

    /// The height map's pyramid level for refinement level `level` ([`Heightmap::lod_for`]).
    pub fn heightmap_lod(&self, level: u32) -> f32 {
        self.heightmap.lod_for(self.data.uv_extent, level)
    }

    /// What the CPU mirror reads besides the records (texture coordinates, height map, tags).
    pub fn inputs(&self, level: u32) -> super::static_vbo::MeshInputs<'_> {
        super::static_vbo::MeshInputs {
            uvs: self.data.uvs.as_deref(),
            map: &self.heightmap,
            lod: self.heightmap_lod(level),
            tags: &self.tags,
            subdiv: self.subdiv.as_ref().map(|l| {
                let frame = l
                    .frame
                    .get_or_init(|| l.data.frame(&self.data.mesh.positions));
                (&l.data, frame)
            }),
        }
    }

    /// Centre and radius of the mesh's bounding sphere.
    pub fn bounding_sphere(&self) -> (glam::Vec3, f32) {
        let (lo, hi) = self.data.mesh.bounds();
        let c = (lo + hi) * 0.5;
        (c, ((hi - lo) * 0.5).length().max(1e-6))
    }
}
