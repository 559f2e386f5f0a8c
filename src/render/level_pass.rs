//! The level pass: every frame, each element's levels ([`ElementLevels`]) from its bounds and
//! the camera, written on the GPU into the mesh's levels buffer ([`GpuMesh::levels`]) before
//! the frame's draws read them (docs/adaptivity.md, "Levels per frame").
//!
//! Bounds are computed on the CPU once per mesh and parameters ([`LevelPass::update_bounds`],
//! `lod::frame::lod_records`) and uploaded as one `LodRecord` per element; a frame costs one
//! dispatch of cheap math (`glsl/lod/levels.comp`, mirrored by `lod::frame::frame_levels`), the
//! camera in push constants, and no readback. The shader reads the bounds as texels
//! (a uniform texel buffer of `RGBA32F`, 30 texels an element), which lavapipe fetches
//! with vector gathers where it loads a storage buffer one invocation at a time
//! (docs/bench/level-pass-loads.md). A descriptor spans at most maxTexelBufferElements texels
//! of the bounds (4,473,924 bounds on lavapipe) and maxStorageBufferRange bytes of the levels,
//! so a larger mesh's bounds and levels are bound and dispatched in chunks, one descriptor set
//! and buffer view each: the shader is the same.
//!
//! Where the view lifts edges (`lod::frame::LIFT`, src/lod/frame/lift.rs), a second dispatch
//! per chunk, after a barrier, reads what the first left of every element (its own and its
//! neighbours', from a buffer bound whole) and writes the lifted levels. That buffer (16 bytes
//! an element) must fit maxStorageBufferRange (at least 2^27 bytes, 8.4 million elements); the
//! pattern driver's adaptive draws need at least 20 bytes an element of it (their bins), so
//! where they fit the lift does. Elsewhere the pass leaves the lift out ([`LevelPass::lifts`];
//! `Scene::set_levels` then clears the view's flag, so that the mirror does without it too):
//! at integer levels the first dispatch's levels meet the pixel error as well, with more
//! triangles; gliding edges then glide at their own levels (docs/adaptivity.md, "Gliding
//! edges"), which only the tess driver can reach (the pattern driver's draws do not fit first).

use super::bindings::{
    LEVEL_BINDING_BEFORE, LEVEL_BINDING_BEFORE_ALL, LEVEL_BINDING_LEVELS, LEVEL_BINDING_NEIGHBOURS,
    LEVEL_BINDING_RECORDS, SPEC_LIFTING,
};
use super::gpu_mesh::GpuMesh;
use super::loop_gpu::dispatch_grid;
use super::RenderError;
use crate::gpu::{
    vk, Buffer, BufferDesc, BufferView, Cmd, Context, DescriptorPool, DescriptorSetLayout,
    Pipeline, PipelineLayout,
};
use crate::lod::frame::{lod_records, LodEdge, LodRecord, LodView, LIFT};
use crate::lod::levels::ElementLevels;
use crate::lod::Lod;
use crate::surface::ElementRecord;
use std::sync::Arc;

/// Invocations per workgroup (`local_size_x` of levels.comp).
const GROUP: u32 = 64;

/// The texel format the shader reads the bounds in.
const RECORD_FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;
/// The texel format it reads the records' neighbours in.
const NEIGHBOURS_FORMAT: vk::Format = vk::Format::R32G32B32A32_UINT;
/// Bytes of what the first dispatch leaves of an element for the lift (a `vec4`; the levels'
/// size, so that the chunks' offsets into both are aligned alike).
const BEFORE_BYTES: u64 = 16;
const _: () = assert!(BEFORE_BYTES == std::mem::size_of::<ElementLevels>() as u64);

/// Texels of [`RECORD_FORMAT`] an element's bounds span (`RECORD_TEXELS` in levels.comp).
const RECORD_TEXELS: u64 = (std::mem::size_of::<LodRecord>() / 16) as u64;

// The texels levels.comp reads each field at (`RECORD_*`, `EDGE_*`).
const _: () = {
    use std::mem::{offset_of, size_of};
    assert!(size_of::<LodRecord>() == 30 * 16);
    assert!(offset_of!(LodRecord, sphere) == 0);
    assert!(offset_of!(LodRecord, cone) == 16);
    assert!(offset_of!(LodRecord, chord) == 2 * 16);
    assert!(offset_of!(LodRecord, second) == 3 * 16);
    assert!(offset_of!(LodRecord, mixed) == 4 * 16);
    assert!(offset_of!(LodRecord, edges) == 5 * 16);
    assert!(offset_of!(LodRecord, neighbours) == 29 * 16);
    assert!(size_of::<LodEdge>() == 8 * 16);
    assert!(offset_of!(LodEdge, curve) == 0);
    assert!(offset_of!(LodEdge, needs) == 16);
    assert!(offset_of!(LodEdge, sphere) == 5 * 16);
    assert!(offset_of!(LodEdge, sphere_a) == 6 * 16);
    assert!(offset_of!(LodEdge, sphere_b) == 7 * 16);
};

/// The level pass's pipeline, its bounds on the GPU and the levels buffer it writes.
pub struct LevelPass {
    ctx: Arc<Context>,
    /// The dispatches, each over a range of elements bound by its own set (declared before
    /// `records`, so that their views of it are dropped first).
    chunks: Vec<Chunk>,
    /// One `LodRecord` per element (at least one: a buffer may not be empty).
    records: Buffer,
    /// What the first dispatch leaves of each element for the lift ([`BEFORE_BYTES`] each).
    before: Buffer,
    /// Whether the whole of `before` fits one descriptor (else no lift is dispatched).
    lift: bool,
    count: u32,
    /// The levels buffer the sets point at (the mesh of the last [`LevelPass::update_bounds`]).
    levels: vk::Buffer,
    /// At most this many elements a chunk (None: as many as the device's limits allow; tests
    /// pass small chunks to exercise dispatching chunk by chunk).
    max_chunk: Option<u32>,
    pipeline: Pipeline,
    /// The lift's dispatch (`SPEC_LIFTING`).
    lift_pipeline: Pipeline,
    layout: PipelineLayout,
    /// Sets for the chunks (made again when their number changes).
    pool: DescriptorPool,
    set_layout: DescriptorSetLayout,
}

/// One dispatch of the level pass: `count` elements, bound by `set`, whose bounds `view` shows
/// (and `neighbours` their neighbours).
struct Chunk {
    count: u32,
    grid: [u32; 2],
    set: vk::DescriptorSet,
    _view: BufferView,
    _neighbours: BufferView,
}

impl LevelPass {
    /// The pipeline, with no bounds yet ([`LevelPass::update_bounds`] before the first
    /// [`LevelPass::cmd_record`]; the descriptor sets come with the bounds, one per chunk).
    pub fn new(ctx: &Arc<Context>) -> Result<Self, RenderError> {
        Self::with_max_chunk(ctx, None)
    }

    /// [`LevelPass::new`] dispatching at most `max_chunk` elements at a time (rounded down to a
    /// multiple of what keeps each chunk's buffers aligned, and up to that where smaller):
    /// tests exercise the chunks on small meshes.
    pub fn with_max_chunk(ctx: &Arc<Context>, max_chunk: Option<u32>) -> Result<Self, RenderError> {
        let c = vk::ShaderStageFlags::COMPUTE;
        let (texels, storage) = (
            vk::DescriptorType::UNIFORM_TEXEL_BUFFER,
            vk::DescriptorType::STORAGE_BUFFER,
        );
        let set_layout = DescriptorSetLayout::new(
            ctx,
            &[
                (LEVEL_BINDING_RECORDS, texels, c),
                (LEVEL_BINDING_LEVELS, storage, c),
                (LEVEL_BINDING_NEIGHBOURS, texels, c),
                (LEVEL_BINDING_BEFORE, storage, c),
                (LEVEL_BINDING_BEFORE_ALL, storage, c),
            ],
            "level pass set",
        )?;
        let layout = PipelineLayout::new(
            ctx,
            &[&set_layout],
            std::mem::size_of::<LodView>() as u32,
            c,
            "level pass",
        )?;
        let shader = "lod/levels.comp";
        let pipeline = Pipeline::new_compute(ctx, &layout, shader, "level pass")?;
        let lifting = vec![(SPEC_LIFTING, 1)];
        let lift_pipeline =
            Pipeline::new_compute_specialized(ctx, &layout, shader, &lifting, "level pass lift")?;
        let pool = DescriptorPool::new(
            ctx,
            1,
            &[(texels, 2), (storage, 3)],
            "level pass descriptors",
        )?;
        let records = Buffer::new(
            ctx,
            BufferDesc::new_upload(
                std::mem::size_of::<LodRecord>() as u64,
                vk::BufferUsageFlags::UNIFORM_TEXEL_BUFFER,
            ),
            "level pass bounds",
        )?;
        let before = before_buffer(ctx, 1)?;
        Ok(Self {
            ctx: ctx.clone(),
            chunks: Vec::new(),
            records,
            before,
            lift: false,
            count: 0,
            levels: vk::Buffer::null(),
            max_chunk,
            pipeline,
            lift_pipeline,
            layout,
            pool,
            set_layout,
        })
    }

    /// Bound `records` (the elements `mesh` draws) with `lod` and upload the bounds, when the
    /// mesh or the surface's parameters change. The caller makes sure no pending work uses the
    /// pass.
    pub fn update_bounds(
        &mut self,
        mesh: &GpuMesh,
        lod: &Lod,
        records: &[ElementRecord],
    ) -> Result<(), RenderError> {
        self.upload(mesh, &lod_records(lod, records))
    }

    /// Elements a chunk holds: as many as one descriptor may span of the bounds
    /// (maxTexelBufferElements texels) and of the levels (maxStorageBufferRange bytes), a
    /// multiple of what keeps the next chunk's offsets aligned to minTexelBufferOffsetAlignment
    /// and minStorageBufferOffsetAlignment, and at most `max_chunk`; all of `n` when they fit.
    fn chunk_size(&self, n: u64) -> u64 {
        level_chunk(&self.ctx.info.limits, self.max_chunk, n)
    }

    /// Upload bounds computed elsewhere (`lod::frame::lod_records`), one per element of `mesh`.
    /// The caller makes sure no pending work uses the pass.
    pub fn upload(&mut self, mesh: &GpuMesh, bounds: &[LodRecord]) -> Result<(), RenderError> {
        assert_eq!(bounds.len() as u32, mesh.element_count);
        let info = &self.ctx.info;
        let bytes = std::mem::size_of_val(bounds) as u64;
        let allocation = info.max_memory_allocation_size;
        for (what, needed) in [
            ("the level pass's bounds buffer", bytes),
            ("the level pass's levels buffer", mesh.levels.size()),
        ] {
            if needed > allocation {
                return Err(RenderError::OverLimit {
                    what: what.into(),
                    needed,
                    unit: "bytes",
                    limit: "this device's maxMemoryAllocationSize",
                    max: allocation,
                    remedy: "a coarser mesh fits".into(),
                });
            }
        }
        let n = bounds.len() as u64;
        let chunk = self.chunk_size(n);
        let record = std::mem::size_of::<LodRecord>() as u64;
        let level = std::mem::size_of::<ElementLevels>() as u64;
        let max = info.limits.max_compute_work_group_count;
        let over_groups = || RenderError::OverLimit {
            what: "the level pass's elements".into(),
            needed: n,
            unit: "elements",
            limit: "this device's maxComputeWorkGroupCount",
            max: max[0] as u64 * max[1] as u64 * GROUP as u64,
            remedy: "use a coarser mesh".into(),
        };
        // (first, count, grid) of each dispatch; one, of no element, for an empty mesh.
        let mut plan = Vec::new();
        let mut first = 0;
        loop {
            let count = chunk.min(n - first) as u32;
            let grid =
                dispatch_grid(count.div_ceil(GROUP), [max[0], max[1]]).ok_or_else(over_groups)?;
            plan.push((first, count, grid));
            first += chunk.max(1);
            if first >= n {
                break;
            }
        }
        // The views of the old bounds go before the buffer they show.
        let old: Vec<vk::DescriptorSet> = self.chunks.drain(..).map(|c| c.set).collect();
        if self.records.size() < bytes.max(1) {
            self.records = Buffer::new(
                &self.ctx,
                BufferDesc::new_upload(bytes, vk::BufferUsageFlags::UNIFORM_TEXEL_BUFFER),
                "level pass bounds",
            )?;
        }
        self.records.write_pod(0, bounds);
        if self.before.size() < n.max(1) * BEFORE_BYTES {
            self.before = before_buffer(&self.ctx, n)?;
        }
        let range = info.limits.max_storage_buffer_range as u64;
        self.lift = n * BEFORE_BYTES <= range;
        // At least one element, as every chunk holds one whatever the range (a range under
        // one element's bytes is only ever a test's lowered limit: Vulkan's least is 2^27).
        let whole = self
            .before
            .size()
            .min((range / BEFORE_BYTES).max(1) * BEFORE_BYTES);
        let (texels, storage) = (
            vk::DescriptorType::UNIFORM_TEXEL_BUFFER,
            vk::DescriptorType::STORAGE_BUFFER,
        );
        let sets = plan.len() as u32;
        let old = if sets != old.len() as u32 || old.is_empty() {
            self.pool = DescriptorPool::new(
                &self.ctx,
                sets,
                &[(texels, 2 * sets), (storage, 3 * sets)],
                "level pass descriptors",
            )?;
            Vec::new()
        } else {
            old
        };
        for (k, (first, count, grid)) in plan.into_iter().enumerate() {
            let set = match old.get(k) {
                Some(&set) => set,
                None => self.pool.allocate(&self.set_layout, "level pass set")?,
            };
            let span = count.max(1) as u64;
            let view = BufferView::span(
                &self.ctx,
                &self.records,
                RECORD_FORMAT,
                (first * record, span * record),
                &format!("level pass bounds {k}"),
            )?;
            let neighbours = BufferView::span(
                &self.ctx,
                &self.records,
                NEIGHBOURS_FORMAT,
                (first * record, span * record),
                &format!("level pass neighbours {k}"),
            )?;
            (self.pool).write_texel_buffer(set, LEVEL_BINDING_RECORDS, texels, view.raw);
            (self.pool).write_texel_buffer(set, LEVEL_BINDING_NEIGHBOURS, texels, neighbours.raw);
            (self.pool).write_buffer_at(
                set,
                LEVEL_BINDING_BEFORE,
                storage,
                self.before.raw,
                first * BEFORE_BYTES,
                span * BEFORE_BYTES,
            );
            (self.pool).write_buffer_at(
                set,
                LEVEL_BINDING_BEFORE_ALL,
                storage,
                self.before.raw,
                0,
                whole,
            );
            (self.pool).write_buffer_at(
                set,
                LEVEL_BINDING_LEVELS,
                storage,
                mesh.levels.raw,
                first * level,
                span * level,
            );
            self.chunks.push(Chunk {
                count,
                grid,
                set,
                _view: view,
                _neighbours: neighbours,
            });
        }
        self.count = bounds.len() as u32;
        self.levels = mesh.levels.raw;
        Ok(())
    }

    /// Chunks a frame's pass dispatches (each once, and once more where the view lifts).
    pub fn dispatches(&self) -> usize {
        self.chunks.len()
    }

    /// Whether it lifts edges where the view asks for it (`LIFT`): unless the buffer the lift
    /// reads exceeds one descriptor (maxStorageBufferRange).
    pub fn lifts(&self) -> bool {
        self.lift
    }

    /// Elements the pass has bounds for.
    pub fn count(&self) -> u32 {
        self.count
    }

    /// Record the pass for `view` (its `count` is the pass's own) into `mesh`'s levels, with
    /// the barriers around it: after the previous draws' reads of the levels, before this
    /// frame's (every drawing stage and indirect draws). Outside a rendering instance.
    pub fn cmd_record(&self, cmd: &Cmd<'_>, mesh: &GpuMesh, view: &LodView) {
        assert_eq!(
            mesh.levels.raw, self.levels,
            "the level pass's bounds are for another mesh (update_bounds)"
        );
        mesh.written_on_gpu();
        let lift = view.flags & LIFT != 0 && self.lift;
        let view = LodView {
            count: self.count,
            flags: if lift { view.flags } else { view.flags & !LIFT },
            ..*view
        };
        cmd.barrier_draws_to_levels();
        // The chunks write disjoint ranges, but each dispatch binds the whole buffer the lift
        // reads (what every chunk's first dispatch wrote), which the synchronization checks
        // take as read (and the chunk's range as written) whatever the dispatch: a barrier
        // between any two dispatches (chunks are for meshes of millions of elements).
        let passes: &[&Pipeline] = if lift {
            &[&self.pipeline, &self.lift_pipeline]
        } else {
            &[&self.pipeline]
        };
        let dispatches = (passes.iter()).flat_map(|&p| self.chunks.iter().map(move |c| (c, p)));
        let mut bound = vk::Pipeline::null();
        for (k, (chunk, pipeline)) in dispatches.enumerate() {
            if k > 0 {
                cmd.barrier_to_compute();
            }
            if pipeline.raw != bound {
                cmd.bind_compute_pipeline(pipeline.raw);
                bound = pipeline.raw;
            }
            let view = LodView {
                count: chunk.count,
                ..view
            };
            cmd.bind_compute_descriptor_set(self.layout.raw, 0, chunk.set);
            cmd.push_constants(
                self.layout.raw,
                vk::ShaderStageFlags::COMPUTE,
                0,
                bytemuck::bytes_of(&view),
            );
            let [x, y] = chunk.grid;
            cmd.dispatch(x, y, 1);
        }
        cmd.barrier_levels_to_draws();
    }
}

/// The buffer of what the first dispatch leaves of `n` elements (at least one) for the lift.
fn before_buffer(ctx: &Arc<Context>, n: u64) -> Result<Buffer, RenderError> {
    let desc = BufferDesc::new_gpu_only(
        n.max(1) * BEFORE_BYTES,
        vk::BufferUsageFlags::STORAGE_BUFFER,
    );
    Ok(Buffer::new(ctx, desc, "level pass lift")?)
}

/// [`LevelPass::chunk_size`] for a device's `limits`: elements a chunk of `n` holds.
fn level_chunk(limits: &vk::PhysicalDeviceLimits, max_chunk: Option<u32>, n: u64) -> u64 {
    let range = limits.max_storage_buffer_range as u64;
    let texels = limits.max_texel_buffer_elements as u64;
    let (record_align, level_align) = (
        limits.min_texel_buffer_offset_alignment.max(1),
        limits.min_storage_buffer_offset_alignment.max(1),
    );
    let (record, level) = (
        std::mem::size_of::<LodRecord>() as u64,
        std::mem::size_of::<ElementLevels>() as u64,
    );
    let bound = record_align.max(level_align);
    let step = (1..=bound)
        .find(|k| (k * record) % record_align == 0 && (k * level) % level_align == 0)
        .unwrap_or(bound);
    let fit = (texels / RECORD_TEXELS).min(range / level);
    let fit = fit.min(max_chunk.map_or(u64::MAX, u64::from));
    if fit >= n {
        n
    } else {
        (fit / step * step).max(step)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a device at Vulkan's least texel range (65,536 texels) with 256-byte offset
    /// alignments, a chunk of bounds spans at most that many texels (30 an element), in steps
    /// of 16 elements that keep both arrays' offsets aligned: 2,176 elements; a mesh that fits
    /// is one chunk, and `max_chunk` cuts smaller ones.
    #[test]
    fn chunks_follow_the_texel_limit_and_both_alignments() {
        let limits = crate::render::gpu_mesh::tests::least_texel_range();
        let chunk = level_chunk(&limits, None, 1_000_000);
        assert_eq!(chunk, 2_176);
        assert!(chunk * RECORD_TEXELS <= 65_536);
        assert_eq!(chunk * std::mem::size_of::<LodRecord>() as u64 % 256, 0);
        assert_eq!(chunk * std::mem::size_of::<ElementLevels>() as u64 % 256, 0);
        assert_eq!(level_chunk(&limits, None, 2_180), 2_180);
        assert_eq!(level_chunk(&limits, Some(100), 1_000), 96);
    }
}
