//! Command pool, one-shot submissions, fences and semaphores.

use super::context::VkResultExt;
use super::{track_drop, track_new, Cmd, Context, GpuError};
use ash::vk;
use std::sync::Arc;

pub struct CommandPool {
    ctx: Arc<Context>,
    pub raw: vk::CommandPool,
    name: String,
}

impl CommandPool {
    pub fn new(ctx: &Arc<Context>, name: &str) -> Result<Self, GpuError> {
        let info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(ctx.queue_family)
            .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
        // SAFETY: valid device.
        let raw =
            unsafe { ctx.device.create_command_pool(&info, None) }.call("vkCreateCommandPool")?;
        ctx.set_name(raw, name);
        track_new();
        Ok(Self {
            ctx: ctx.clone(),
            raw,
            name: name.to_string(),
        })
    }

    pub fn allocate(&self, count: u32) -> Result<Vec<vk::CommandBuffer>, GpuError> {
        let info = vk::CommandBufferAllocateInfo::default()
            .command_pool(self.raw)
            .level(vk::CommandBufferLevel::PRIMARY)
            .command_buffer_count(count);
        // SAFETY: pool from this device; externally synchronized by &self being single-threaded use.
        let cmds = unsafe { self.ctx.device.allocate_command_buffers(&info) }
            .call("vkAllocateCommandBuffers")?;
        for (i, &c) in cmds.iter().enumerate() {
            self.ctx.set_name(c, &format!("{} #{i}", self.name));
        }
        Ok(cmds)
    }

    /// Record with `f`, submit, wait. Headless work and uploads go through here.
    pub fn submit_and_wait(&self, f: impl FnOnce(&Cmd<'_>)) -> Result<(), GpuError> {
        let cmd = self.allocate(1)?[0];
        let result = (|| {
            let begin = vk::CommandBufferBeginInfo::default()
                .flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
            // SAFETY: freshly allocated command buffer.
            unsafe { self.ctx.device.begin_command_buffer(cmd, &begin) }
                .call("vkBeginCommandBuffer")?;
            f(&Cmd::new(&self.ctx, cmd));
            // SAFETY: recording.
            unsafe { self.ctx.device.end_command_buffer(cmd) }.call("vkEndCommandBuffer")?;
            let fence = Fence::new(&self.ctx, false, "one-shot")?;
            let cmds = [cmd];
            let submit = vk::SubmitInfo::default().command_buffers(&cmds);
            // SAFETY: single queue used from one thread at a time; fence unsignalled.
            unsafe {
                self.ctx
                    .device
                    .queue_submit(self.ctx.queue, &[submit], fence.raw)
            }
            .call("vkQueueSubmit")?;
            fence.wait()
        })();
        // SAFETY: the submission was waited for (or never made).
        unsafe { self.ctx.device.free_command_buffers(self.raw, &[cmd]) };
        result
    }

    /// Reset and begin `cmd` (allocated from this pool, not pending), record with `f`, end it.
    pub fn record(&self, cmd: vk::CommandBuffer, f: impl FnOnce(&Cmd<'_>)) -> Result<(), GpuError> {
        // SAFETY: the caller waited for the fence of the last submission of `cmd`.
        unsafe {
            self.ctx
                .device
                .reset_command_buffer(cmd, vk::CommandBufferResetFlags::empty())
        }
        .call("vkResetCommandBuffer")?;
        // SAFETY: reset above.
        unsafe {
            self.ctx
                .device
                .begin_command_buffer(cmd, &vk::CommandBufferBeginInfo::default())
        }
        .call("vkBeginCommandBuffer")?;
        f(&Cmd::new(&self.ctx, cmd));
        // SAFETY: recording.
        unsafe { self.ctx.device.end_command_buffer(cmd) }.call("vkEndCommandBuffer")
    }

    /// Submit `cmd`: wait for `wait` at colour output, signal `signal` and `fence`.
    pub fn submit(
        &self,
        cmd: vk::CommandBuffer,
        wait: &Semaphore,
        signal: &Semaphore,
        fence: &Fence,
    ) -> Result<(), GpuError> {
        let waits = [wait.raw];
        let stages = [vk::PipelineStageFlags::ALL_COMMANDS];
        let signals = [signal.raw];
        let cmds = [cmd];
        let submit = vk::SubmitInfo::default()
            .wait_semaphores(&waits)
            .wait_dst_stage_mask(&stages)
            .command_buffers(&cmds)
            .signal_semaphores(&signals);
        // SAFETY: one queue, used from one thread; fence unsignalled (reset by the caller).
        unsafe {
            self.ctx
                .device
                .queue_submit(self.ctx.queue, &[submit], fence.raw)
        }
        .call("vkQueueSubmit")
    }
}

impl Drop for CommandPool {
    fn drop(&mut self) {
        // SAFETY: no command buffer from this pool is pending (headless waits; the window loop
        // waits for idle before dropping).
        unsafe { self.ctx.device.destroy_command_pool(self.raw, None) };
        track_drop();
    }
}

pub struct Fence {
    ctx: Arc<Context>,
    pub raw: vk::Fence,
}

impl Fence {
    pub fn new(ctx: &Arc<Context>, signaled: bool, name: &str) -> Result<Self, GpuError> {
        let flags = if signaled {
            vk::FenceCreateFlags::SIGNALED
        } else {
            vk::FenceCreateFlags::empty()
        };
        // SAFETY: valid device.
        let raw = unsafe {
            ctx.device
                .create_fence(&vk::FenceCreateInfo::default().flags(flags), None)
        }
        .call("vkCreateFence")?;
        ctx.set_name(raw, name);
        track_new();
        Ok(Self {
            ctx: ctx.clone(),
            raw,
        })
    }

    pub fn wait(&self) -> Result<(), GpuError> {
        // SAFETY: fence from this device.
        unsafe { self.ctx.device.wait_for_fences(&[self.raw], true, u64::MAX) }
            .call("vkWaitForFences")
    }

    pub fn reset(&self) -> Result<(), GpuError> {
        // SAFETY: fence not pending (waited for by the caller).
        unsafe { self.ctx.device.reset_fences(&[self.raw]) }.call("vkResetFences")
    }
}

impl Drop for Fence {
    fn drop(&mut self) {
        // SAFETY: owners wait for the fence (or idle) before dropping it.
        unsafe { self.ctx.device.destroy_fence(self.raw, None) };
        track_drop();
    }
}

pub struct Semaphore {
    ctx: Arc<Context>,
    pub raw: vk::Semaphore,
}

impl Semaphore {
    pub fn new(ctx: &Arc<Context>, name: &str) -> Result<Self, GpuError> {
        // SAFETY: valid device.
        let raw = unsafe {
            ctx.device
                .create_semaphore(&vk::SemaphoreCreateInfo::default(), None)
        }
        .call("vkCreateSemaphore")?;
        ctx.set_name(raw, name);
        track_new();
        Ok(Self {
            ctx: ctx.clone(),
            raw,
        })
    }
}

impl Drop for Semaphore {
    fn drop(&mut self) {
        // SAFETY: the window loop waits for idle before dropping semaphores.
        unsafe { self.ctx.device.destroy_semaphore(self.raw, None) };
        track_drop();
    }
}
