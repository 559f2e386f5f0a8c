//! Timestamp and pipeline-statistics queries, available to every driver: a driver's draws are
//! bracketed by [`QueryPools::cmd_begin`] / [`QueryPools::cmd_end`].

use super::context::VkResultExt;
use super::{track_drop, track_new, Cmd, Context, GpuError};
use ash::vk;
use std::sync::Arc;

/// Pipeline statistics we collect, in the order Vulkan writes them (bit order).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PipelineStats {
    pub input_assembly_vertices: u64,
    pub input_assembly_primitives: u64,
    pub vertex_shader_invocations: u64,
    pub clipping_primitives: u64,
    pub tess_control_patches: u64,
    pub tess_evaluation_invocations: u64,
}

const STAT_FLAGS: vk::QueryPipelineStatisticFlags = vk::QueryPipelineStatisticFlags::from_raw(
    vk::QueryPipelineStatisticFlags::INPUT_ASSEMBLY_VERTICES.as_raw()
        | vk::QueryPipelineStatisticFlags::INPUT_ASSEMBLY_PRIMITIVES.as_raw()
        | vk::QueryPipelineStatisticFlags::VERTEX_SHADER_INVOCATIONS.as_raw()
        | vk::QueryPipelineStatisticFlags::CLIPPING_PRIMITIVES.as_raw()
        | vk::QueryPipelineStatisticFlags::TESSELLATION_CONTROL_SHADER_PATCHES.as_raw()
        | vk::QueryPipelineStatisticFlags::TESSELLATION_EVALUATION_SHADER_INVOCATIONS.as_raw(),
);

/// Two timestamps and (when supported) one statistics query per slot; one slot per frame in flight.
pub struct QueryPools {
    ctx: Arc<Context>,
    timestamps: vk::QueryPool,
    stats: Option<vk::QueryPool>,
    slots: u32,
    /// Nanoseconds per timestamp tick.
    period: f64,
}

impl QueryPools {
    pub fn new(ctx: &Arc<Context>, slots: u32) -> Result<Self, GpuError> {
        let info = vk::QueryPoolCreateInfo::default()
            .query_type(vk::QueryType::TIMESTAMP)
            .query_count(2 * slots);
        // SAFETY: valid device.
        let timestamps =
            unsafe { ctx.device.create_query_pool(&info, None) }.call("vkCreateQueryPool")?;
        ctx.set_name(timestamps, "timestamps");
        let stats = if ctx.info.pipeline_statistics {
            let info = vk::QueryPoolCreateInfo::default()
                .query_type(vk::QueryType::PIPELINE_STATISTICS)
                .query_count(slots)
                .pipeline_statistics(STAT_FLAGS);
            // SAFETY: feature enabled at device creation.
            match unsafe { ctx.device.create_query_pool(&info, None) } {
                Ok(p) => {
                    ctx.set_name(p, "pipeline statistics");
                    Some(p)
                }
                Err(e) => {
                    // SAFETY: created above, unused.
                    unsafe { ctx.device.destroy_query_pool(timestamps, None) };
                    return Err(GpuError::Vk {
                        call: "vkCreateQueryPool",
                        result: e,
                    });
                }
            }
        } else {
            None
        };
        track_new();
        Ok(Self {
            ctx: ctx.clone(),
            timestamps,
            stats,
            slots,
            period: ctx.info.limits.timestamp_period as f64,
        })
    }

    pub fn has_statistics(&self) -> bool {
        self.stats.is_some()
    }

    /// Reset the slot's queries and write the start timestamp; begin statistics.
    pub fn cmd_begin(&self, cmd: &Cmd<'_>, slot: u32) {
        let cmd = cmd.raw;
        assert!(slot < self.slots);
        let d = &self.ctx.device;
        // SAFETY: recording command buffer, queries in range, outside a render pass instance.
        unsafe {
            d.cmd_reset_query_pool(cmd, self.timestamps, 2 * slot, 2);
            if let Some(s) = self.stats {
                d.cmd_reset_query_pool(cmd, s, slot, 1);
            }
            d.cmd_write_timestamp(
                cmd,
                vk::PipelineStageFlags::TOP_OF_PIPE,
                self.timestamps,
                2 * slot,
            );
            if let Some(s) = self.stats {
                d.cmd_begin_query(cmd, s, slot, vk::QueryControlFlags::empty());
            }
        }
    }

    /// End statistics and write the end timestamp.
    pub fn cmd_end(&self, cmd: &Cmd<'_>, slot: u32) {
        if let Some(s) = self.stats {
            // SAFETY: matching cmd_begin recorded earlier in this command buffer.
            unsafe { self.ctx.device.cmd_end_query(cmd.raw, s, slot) };
        }
        self.cmd_end_time(cmd, slot);
    }

    /// Reset the slot's timestamps and write its start, without statistics: a span inside
    /// another slot's [`QueryPools::cmd_begin`]..[`QueryPools::cmd_end`] (statistics queries
    /// cannot nest). The start is written once the earlier commands completed (bottom of the
    /// pipe), so the span times only what is recorded after it. Outside a render pass instance.
    pub fn cmd_begin_time(&self, cmd: &Cmd<'_>, slot: u32) {
        assert!(slot < self.slots);
        let d = &self.ctx.device;
        // SAFETY: recording command buffer, queries in range, outside a render pass instance.
        unsafe {
            d.cmd_reset_query_pool(cmd.raw, self.timestamps, 2 * slot, 2);
            d.cmd_write_timestamp(
                cmd.raw,
                vk::PipelineStageFlags::BOTTOM_OF_PIPE,
                self.timestamps,
                2 * slot,
            );
        }
    }

    /// Write the end timestamp of a span begun by [`QueryPools::cmd_begin_time`] (or
    /// [`QueryPools::cmd_begin`]).
    pub fn cmd_end_time(&self, cmd: &Cmd<'_>, slot: u32) {
        // SAFETY: matching cmd_begin_time recorded earlier in this command buffer.
        unsafe {
            self.ctx.device.cmd_write_timestamp(
                cmd.raw,
                vk::PipelineStageFlags::BOTTOM_OF_PIPE,
                self.timestamps,
                2 * slot + 1,
            );
        }
    }

    /// GPU time of the slot in milliseconds; waits for the results. Call after the work completed.
    pub fn gpu_ms(&self, slot: u32) -> Result<f64, GpuError> {
        let mut t = [0u64; 2];
        // SAFETY: queries written by a submission the caller waited for.
        unsafe {
            self.ctx.device.get_query_pool_results(
                self.timestamps,
                2 * slot,
                &mut t,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .call("vkGetQueryPoolResults")?;
        Ok(t[1].wrapping_sub(t[0]) as f64 * self.period * 1e-6)
    }

    /// Statistics of the slot, if supported; waits for the results.
    pub fn statistics(&self, slot: u32) -> Result<Option<PipelineStats>, GpuError> {
        let Some(pool) = self.stats else {
            return Ok(None);
        };
        let mut r = [0u64; 6];
        // SAFETY: query written by a submission the caller waited for; 6 counters per query.
        unsafe {
            self.ctx.device.get_query_pool_results(
                pool,
                slot,
                std::slice::from_mut(&mut r),
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .call("vkGetQueryPoolResults")?;
        Ok(Some(PipelineStats {
            input_assembly_vertices: r[0],
            input_assembly_primitives: r[1],
            vertex_shader_invocations: r[2],
            clipping_primitives: r[3],
            tess_control_patches: r[4],
            tess_evaluation_invocations: r[5],
        }))
    }
}

impl Drop for QueryPools {
    fn drop(&mut self) {
        // SAFETY: no pending work uses the pools.
        unsafe {
            self.ctx.device.destroy_query_pool(self.timestamps, None);
            if let Some(s) = self.stats {
                self.ctx.device.destroy_query_pool(s, None);
            }
        }
        track_drop();
    }
}
