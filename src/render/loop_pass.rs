//! The Loop step M0 -> M1 on the GPU (Holländer & Boubekeur 2010): the computational entries
//! ([`crate::subdiv::stencils`]) are uploaded once per topology; every frame only M0's positions
//! are uploaded (bytes independent of the refinement level) and a compute pass applies the
//! entries, followed by a barrier that makes M1 visible to the draws.

use super::bindings::*;
use super::RenderError;
use crate::gpu::{
    vk, Buffer, BufferDesc, Cmd, CommandPool, Context, DescriptorPool, DescriptorSetLayout,
    Pipeline, PipelineLayout,
};
use crate::subdiv::Stencil;
use glam::Vec3;
use std::sync::Arc;

/// Invocations per workgroup (`local_size_x` of loop_step.comp).
const GROUP: u32 = 64;

pub struct LoopPass {
    /// M1 positions (`vec4`, w = 1), written by the pass.
    pub m1: Buffer,
    m0: Buffer,
    _offsets: Buffer,
    _entries: Buffer,
    pipeline: Pipeline,
    pipeline_layout: PipelineLayout,
    _pool: DescriptorPool,
    set: vk::DescriptorSet,
    _set_layout: DescriptorSetLayout,
    m0_count: u32,
    m1_count: u32,
}

impl LoopPass {
    /// The pass for `stencils` (one per M1 vertex) over `m0_count` M0 vertices.
    pub fn new(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        stencils: &[Stencil],
        m0_count: usize,
    ) -> Result<Self, RenderError> {
        use vk::DescriptorType as T;
        let c = vk::ShaderStageFlags::COMPUTE;
        let set_layout = DescriptorSetLayout::new(
            ctx,
            &[
                (LOOP_BINDING_OFFSETS, T::STORAGE_BUFFER, c),
                (LOOP_BINDING_ENTRIES, T::STORAGE_BUFFER, c),
                (LOOP_BINDING_M0, T::STORAGE_BUFFER, c),
                (LOOP_BINDING_M1, T::STORAGE_BUFFER, c),
            ],
            "loop step set",
        )?;
        let pipeline_layout = PipelineLayout::new(ctx, &[&set_layout], 4, c, "loop step")?;
        let pipeline = Pipeline::new_compute(
            ctx,
            &pipeline_layout,
            "subdiv/loop_step.comp",
            "loop step (M0 -> M1)",
        )?;
        let mut offsets = Vec::with_capacity(stencils.len() + 1);
        let mut entries: Vec<[u32; 2]> = Vec::new();
        offsets.push(0u32);
        for s in stencils {
            for (&p, &w) in s.parents.iter().zip(&s.weights) {
                entries.push([p, (w as f32).to_bits()]);
            }
            offsets.push(entries.len() as u32);
        }
        if entries.is_empty() {
            entries.push([0, 0]);
        }
        let storage = vk::BufferUsageFlags::STORAGE_BUFFER;
        let offsets_buf =
            Buffer::new_with_data(ctx, pool, storage, &offsets, "loop entry offsets")?;
        let entries_buf = Buffer::new_with_data(ctx, pool, storage, &entries, "loop entries")?;
        let m0 = Buffer::new(
            ctx,
            BufferDesc::new_upload(m0_count.max(1) as u64 * 16, storage),
            "M0 positions",
        )?;
        let m1 = Buffer::new(
            ctx,
            BufferDesc::new_readback(
                stencils.len().max(1) as u64 * 16,
                storage | vk::BufferUsageFlags::VERTEX_BUFFER,
            ),
            "M1 positions",
        )?;
        let dpool =
            DescriptorPool::new(ctx, 1, &[(T::STORAGE_BUFFER, 4)], "loop step descriptors")?;
        let set = dpool.allocate(&set_layout, "loop step set")?;
        for (binding, buffer) in [
            (LOOP_BINDING_OFFSETS, &offsets_buf),
            (LOOP_BINDING_ENTRIES, &entries_buf),
            (LOOP_BINDING_M0, &m0),
            (LOOP_BINDING_M1, &m1),
        ] {
            dpool.write_buffer(set, binding, T::STORAGE_BUFFER, buffer.raw, vk::WHOLE_SIZE);
        }
        Ok(Self {
            m1,
            m0,
            _offsets: offsets_buf,
            _entries: entries_buf,
            pipeline,
            pipeline_layout,
            _pool: dpool,
            set,
            _set_layout: set_layout,
            m0_count: m0_count as u32,
            m1_count: stencils.len() as u32,
        })
    }

    /// Upload M0's positions (animation: every frame). The caller makes sure no pending work
    /// reads them.
    pub fn upload_m0(&mut self, positions: &[Vec3]) {
        assert_eq!(positions.len() as u32, self.m0_count);
        let v: Vec<[f32; 4]> = positions.iter().map(|p| p.extend(1.0).to_array()).collect();
        self.m0.write_pod(0, &v);
    }

    /// Bytes [`LoopPass::upload_m0`] sends: M0's positions only, whatever the level.
    pub fn upload_bytes(&self) -> u64 {
        self.m0_count as u64 * 16
    }

    pub fn m1_count(&self) -> u32 {
        self.m1_count
    }

    /// Record the pass and the barrier to the draws that read M1.
    pub fn cmd_apply(&self, cmd: &Cmd<'_>) {
        cmd.bind_compute_pipeline(self.pipeline.raw);
        cmd.bind_compute_descriptor_set(self.pipeline_layout.raw, 0, self.set);
        cmd.push_constants(
            self.pipeline_layout.raw,
            vk::ShaderStageFlags::COMPUTE,
            0,
            bytemuck::bytes_of(&self.m1_count),
        );
        cmd.dispatch(self.m1_count.div_ceil(GROUP).max(1), 1, 1);
        cmd.barrier_compute_to_draw();
    }
}
