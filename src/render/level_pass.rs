//! The level pass: every frame, each element's levels ([`ElementLevels`]) from its bounds and
//! the camera, written on the GPU into the mesh's levels buffer ([`GpuMesh::levels`]) before
//! the frame's draws read them (docs/adaptivity.md, "Levels per frame").
//!
//! Bounds are computed on the CPU once per mesh and parameters ([`LevelPass::update_bounds`],
//! `lod::frame::lod_records`) and uploaded as one `LodRecord` per element; a frame costs one
//! dispatch of cheap math (`glsl/lod/levels.comp`, mirrored by `lod::frame::frame_levels`), the
//! camera in push constants, and no readback.

use super::bindings::{LEVEL_BINDING_LEVELS, LEVEL_BINDING_RECORDS};
use super::gpu_mesh::GpuMesh;
use super::loop_gpu::dispatch_grid;
use super::RenderError;
use crate::gpu::{
    vk, Buffer, BufferDesc, Cmd, Context, DescriptorPool, DescriptorSetLayout, Pipeline,
    PipelineLayout,
};
use crate::lod::frame::{lod_records, LodRecord, LodView};
use crate::lod::levels::ElementLevels;
use crate::lod::Lod;
use crate::surface::ElementRecord;
use std::sync::Arc;

/// Invocations per workgroup (`local_size_x` of levels.comp).
const GROUP: u32 = 64;

/// The level pass's pipeline, its bounds on the GPU and the levels buffer it writes.
pub struct LevelPass {
    ctx: Arc<Context>,
    /// One `LodRecord` per element (at least one: a buffer may not be empty).
    records: Buffer,
    count: u32,
    /// The levels buffer the set points at (the mesh of the last [`LevelPass::update_bounds`]).
    levels: vk::Buffer,
    grid: [u32; 2],
    pipeline: Pipeline,
    layout: PipelineLayout,
    pool: DescriptorPool,
    set: vk::DescriptorSet,
    _set_layout: DescriptorSetLayout,
}

impl LevelPass {
    /// The pipeline and its descriptor set, with no bounds yet ([`LevelPass::update_bounds`]
    /// before the first [`LevelPass::cmd_record`]).
    pub fn new(ctx: &Arc<Context>) -> Result<Self, RenderError> {
        let c = vk::ShaderStageFlags::COMPUTE;
        let storage = vk::DescriptorType::STORAGE_BUFFER;
        let set_layout = DescriptorSetLayout::new(
            ctx,
            &[
                (LEVEL_BINDING_RECORDS, storage, c),
                (LEVEL_BINDING_LEVELS, storage, c),
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
        let pipeline = Pipeline::new_compute(ctx, &layout, "lod/levels.comp", "level pass")?;
        let pool = DescriptorPool::new(ctx, 1, &[(storage, 2)], "level pass descriptors")?;
        let set = pool.allocate(&set_layout, "level pass set")?;
        let records = Buffer::new(
            ctx,
            BufferDesc::new_upload(
                std::mem::size_of::<LodRecord>() as u64,
                vk::BufferUsageFlags::STORAGE_BUFFER,
            ),
            "level pass bounds",
        )?;
        Ok(Self {
            ctx: ctx.clone(),
            records,
            count: 0,
            levels: vk::Buffer::null(),
            grid: [1, 1],
            pipeline,
            layout,
            pool,
            set,
            _set_layout: set_layout,
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

    /// Upload bounds computed elsewhere (`lod::frame::lod_records`), one per element of `mesh`.
    /// The caller makes sure no pending work uses the pass.
    pub fn upload(&mut self, mesh: &GpuMesh, bounds: &[LodRecord]) -> Result<(), RenderError> {
        assert_eq!(bounds.len() as u32, mesh.element_count);
        let limits = &self.ctx.info.limits;
        let range = limits.max_storage_buffer_range as u64;
        let bytes = std::mem::size_of_val(bounds) as u64;
        for (what, needed) in [
            ("the level pass's bounds buffer", bytes),
            ("the level pass's levels buffer", mesh.levels.size()),
        ] {
            if needed > range {
                return Err(RenderError::OverLimit {
                    what: what.into(),
                    needed,
                    unit: "bytes",
                    limit: "this device's maxStorageBufferRange",
                    max: range,
                    remedy: "a coarser mesh fits".into(),
                });
            }
        }
        let max = limits.max_compute_work_group_count;
        let groups = (bounds.len() as u32).div_ceil(GROUP);
        let grid =
            dispatch_grid(groups, [max[0], max[1]]).ok_or_else(|| RenderError::OverLimit {
                what: "the level pass's elements".into(),
                needed: bounds.len() as u64,
                unit: "elements",
                limit: "this device's maxComputeWorkGroupCount",
                max: max[0] as u64 * max[1] as u64 * GROUP as u64,
                remedy: "use a coarser mesh".into(),
            })?;
        if self.records.size() < bytes.max(1) {
            self.records = Buffer::new(
                &self.ctx,
                BufferDesc::new_upload(bytes, vk::BufferUsageFlags::STORAGE_BUFFER),
                "level pass bounds",
            )?;
        }
        self.records.write_pod(0, bounds);
        let storage = vk::DescriptorType::STORAGE_BUFFER;
        self.pool.write_buffer(
            self.set,
            LEVEL_BINDING_RECORDS,
            storage,
            self.records.raw,
            vk::WHOLE_SIZE,
        );
        self.pool.write_buffer(
            self.set,
            LEVEL_BINDING_LEVELS,
            storage,
            mesh.levels.raw,
            mesh.element_count.max(1) as u64 * std::mem::size_of::<ElementLevels>() as u64,
        );
        self.count = bounds.len() as u32;
        self.levels = mesh.levels.raw;
        self.grid = grid;
        Ok(())
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
        let view = LodView {
            count: self.count,
            ..*view
        };
        cmd.barrier_draws_to_levels();
        cmd.bind_compute_pipeline(self.pipeline.raw);
        cmd.bind_compute_descriptor_set(self.layout.raw, 0, self.set);
        cmd.push_constants(
            self.layout.raw,
            vk::ShaderStageFlags::COMPUTE,
            0,
            bytemuck::bytes_of(&view),
        );
        let [x, y] = self.grid;
        cmd.dispatch(x, y, 1);
        cmd.barrier_levels_to_draws();
    }
}
