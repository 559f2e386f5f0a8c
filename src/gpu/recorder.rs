//! [`Cmd`]: safe recording of the commands the drivers use, so that no module outside `gpu`
//! calls ash. A `Cmd` exists only between `vkBeginCommandBuffer` and `vkEndCommandBuffer` of a
//! buffer that the `CommandPool` (or the frame loop through it) owns; resources passed in are
//! kept alive by their owners until the submission has been waited for (see the module docs).

use super::image::subresource;
use super::{Buffer, Context};
use ash::vk;

#[derive(Clone, Copy)]
pub struct Cmd<'a> {
    pub(crate) ctx: &'a Context,
    pub raw: vk::CommandBuffer,
}

impl<'a> Cmd<'a> {
    pub(crate) fn new(ctx: &'a Context, raw: vk::CommandBuffer) -> Self {
        Self { ctx, raw }
    }

    pub fn context(&self) -> &Context {
        self.ctx
    }

    pub fn bind_graphics_pipeline(&self, pipeline: vk::Pipeline) {
        // SAFETY (every method): `raw` is in the recording state (see the type's docs) and the
        // handles come from this device and outlive the submission.
        unsafe {
            self.ctx
                .device
                .cmd_bind_pipeline(self.raw, vk::PipelineBindPoint::GRAPHICS, pipeline)
        };
    }

    /// Set the cull mode of a pipeline created with `dynamic_cull`.
    pub fn set_cull_mode(&self, mode: vk::CullModeFlags) {
        // SAFETY: see `bind_graphics_pipeline`.
        unsafe { self.ctx.device.cmd_set_cull_mode(self.raw, mode) };
    }

    pub fn bind_descriptor_set(
        &self,
        layout: vk::PipelineLayout,
        set_index: u32,
        set: vk::DescriptorSet,
        dynamic_offsets: &[u32],
    ) {
        self.bind_descriptor_set_at(
            vk::PipelineBindPoint::GRAPHICS,
            layout,
            set_index,
            set,
            dynamic_offsets,
        )
    }

    fn bind_descriptor_set_at(
        &self,
        point: vk::PipelineBindPoint,
        layout: vk::PipelineLayout,
        set_index: u32,
        set: vk::DescriptorSet,
        dynamic_offsets: &[u32],
    ) {
        // SAFETY: see `bind_graphics_pipeline`.
        unsafe {
            self.ctx.device.cmd_bind_descriptor_sets(
                self.raw,
                point,
                layout,
                set_index,
                &[set],
                dynamic_offsets,
            )
        };
    }

    pub fn bind_compute_pipeline(&self, pipeline: vk::Pipeline) {
        // SAFETY: see `bind_graphics_pipeline`.
        unsafe {
            self.ctx
                .device
                .cmd_bind_pipeline(self.raw, vk::PipelineBindPoint::COMPUTE, pipeline)
        };
    }

    pub fn bind_compute_descriptor_set(
        &self,
        layout: vk::PipelineLayout,
        set_index: u32,
        set: vk::DescriptorSet,
    ) {
        self.bind_descriptor_set_at(vk::PipelineBindPoint::COMPUTE, layout, set_index, set, &[])
    }

    pub fn dispatch(&self, x: u32, y: u32, z: u32) {
        // SAFETY: see `bind_graphics_pipeline`; outside a rendering instance.
        unsafe { self.ctx.device.cmd_dispatch(self.raw, x, y, z) };
    }

    /// Make a compute pass's storage writes visible to later vertex, tessellation and compute
    /// stages and to vertex input (the next draw reads what the pass wrote).
    pub fn barrier_compute_to_draw(&self) {
        let barrier = vk::MemoryBarrier::default()
            .src_access_mask(vk::AccessFlags::SHADER_WRITE)
            .dst_access_mask(vk::AccessFlags::SHADER_READ | vk::AccessFlags::VERTEX_ATTRIBUTE_READ);
        // SAFETY: see `bind_graphics_pipeline`; outside a rendering instance.
        unsafe {
            self.ctx.device.cmd_pipeline_barrier(
                self.raw,
                vk::PipelineStageFlags::COMPUTE_SHADER,
                vk::PipelineStageFlags::VERTEX_INPUT
                    | vk::PipelineStageFlags::VERTEX_SHADER
                    | vk::PipelineStageFlags::TESSELLATION_EVALUATION_SHADER
                    | vk::PipelineStageFlags::FRAGMENT_SHADER
                    | vk::PipelineStageFlags::COMPUTE_SHADER,
                vk::DependencyFlags::empty(),
                &[barrier],
                &[],
                &[],
            )
        };
    }

    /// Before a compute pass rewrites what every drawing stage and indirect draws may read (the
    /// level pass's per-element levels): wait for the earlier draws' reads (write after read).
    pub fn barrier_draws_to_levels(&self) {
        // SAFETY: see `bind_graphics_pipeline`; outside a rendering instance.
        unsafe {
            self.ctx.device.cmd_pipeline_barrier(
                self.raw,
                LEVEL_READERS,
                vk::PipelineStageFlags::COMPUTE_SHADER,
                vk::DependencyFlags::empty(),
                &[],
                &[],
                &[],
            )
        };
    }

    /// After the level pass: its storage writes visible to every drawing stage (the control
    /// stage sets outer levels from them), to indirect-command reads and to later compute.
    pub fn barrier_levels_to_draws(&self) {
        let barrier = vk::MemoryBarrier::default()
            .src_access_mask(vk::AccessFlags::SHADER_WRITE)
            .dst_access_mask(
                vk::AccessFlags::SHADER_READ
                    | vk::AccessFlags::INDIRECT_COMMAND_READ
                    | vk::AccessFlags::VERTEX_ATTRIBUTE_READ,
            );
        // SAFETY: see `bind_graphics_pipeline`; outside a rendering instance.
        unsafe {
            self.ctx.device.cmd_pipeline_barrier(
                self.raw,
                vk::PipelineStageFlags::COMPUTE_SHADER,
                LEVEL_READERS,
                vk::DependencyFlags::empty(),
                &[barrier],
                &[],
                &[],
            )
        };
    }

    /// Wait for earlier draws' reads before a compute pass overwrites what they read (a
    /// write-after-read hazard: an execution dependency suffices).
    pub fn barrier_draw_to_compute(&self) {
        // SAFETY: see `bind_graphics_pipeline`; outside a rendering instance.
        unsafe {
            self.ctx.device.cmd_pipeline_barrier(
                self.raw,
                vk::PipelineStageFlags::VERTEX_INPUT
                    | vk::PipelineStageFlags::VERTEX_SHADER
                    | vk::PipelineStageFlags::TESSELLATION_EVALUATION_SHADER
                    | vk::PipelineStageFlags::FRAGMENT_SHADER
                    | vk::PipelineStageFlags::COMPUTE_SHADER,
                vk::PipelineStageFlags::COMPUTE_SHADER,
                vk::DependencyFlags::empty(),
                &[],
                &[],
                &[],
            )
        };
    }

    pub fn push_constants(
        &self,
        layout: vk::PipelineLayout,
        stages: vk::ShaderStageFlags,
        offset: u32,
        bytes: &[u8],
    ) {
        // SAFETY: see `bind_graphics_pipeline`; the range lies in the layout's push range.
        unsafe {
            self.ctx
                .device
                .cmd_push_constants(self.raw, layout, stages, offset, bytes)
        };
        self.ctx.count_host_bytes(bytes.len());
    }

    pub fn bind_vertex_buffer(&self, binding: u32, buffer: &Buffer) {
        // SAFETY: see `bind_graphics_pipeline`.
        unsafe {
            self.ctx
                .device
                .cmd_bind_vertex_buffers(self.raw, binding, &[buffer.raw], &[0])
        };
    }

    /// Bind `buffer` from byte `offset` as vertex buffer `binding`.
    pub fn bind_vertex_buffer_at(&self, binding: u32, buffer: &Buffer, offset: u64) {
        // SAFETY: see `bind_graphics_pipeline`; the caller keeps `offset` within the buffer.
        unsafe {
            self.ctx
                .device
                .cmd_bind_vertex_buffers(self.raw, binding, &[buffer.raw], &[offset])
        };
    }

    /// One indexed draw whose `VkDrawIndexedIndirectCommand` is at byte `offset` of `buffer`
    /// (written on the GPU).
    pub fn draw_indexed_indirect(&self, buffer: &Buffer, offset: u64) {
        // SAFETY: see `bind_graphics_pipeline`; `buffer` has INDIRECT_BUFFER usage and holds a
        // command at `offset` (a multiple of 4).
        unsafe {
            self.ctx
                .device
                .cmd_draw_indexed_indirect(self.raw, buffer.raw, offset, 1, 20)
        };
    }

    /// Make compute writes visible to indirect draws (commands, vertex input, stage) and copies.
    pub fn barrier_compute_to_indirect(&self) {
        use vk::{AccessFlags as A, PipelineStageFlags as S};
        let read = A::INDIRECT_COMMAND_READ | A::VERTEX_ATTRIBUTE_READ | A::SHADER_READ;
        let barrier = vk::MemoryBarrier::default()
            .src_access_mask(A::SHADER_WRITE)
            .dst_access_mask(read | A::TRANSFER_READ);
        let stages = S::DRAW_INDIRECT | S::VERTEX_INPUT | S::VERTEX_SHADER | S::TRANSFER;
        // SAFETY: see `bind_graphics_pipeline`; outside a rendering instance.
        unsafe {
            self.ctx.device.cmd_pipeline_barrier(
                self.raw,
                S::COMPUTE_SHADER,
                stages,
                vk::DependencyFlags::empty(),
                &[barrier],
                &[],
                &[],
            )
        };
    }

    /// Before a compute pass rewrites what earlier indirect draws read (their commands, vertex
    /// input, vertex stage) and what an earlier dispatch wrote: wait for both, and make the
    /// earlier compute writes visible to it.
    pub fn barrier_to_compute(&self) {
        let barrier = vk::MemoryBarrier::default()
            .src_access_mask(vk::AccessFlags::SHADER_WRITE)
            .dst_access_mask(vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE);
        // SAFETY: see `bind_graphics_pipeline`; outside a rendering instance.
        unsafe {
            self.ctx.device.cmd_pipeline_barrier(
                self.raw,
                vk::PipelineStageFlags::DRAW_INDIRECT
                    | vk::PipelineStageFlags::VERTEX_INPUT
                    | vk::PipelineStageFlags::VERTEX_SHADER
                    | vk::PipelineStageFlags::COMPUTE_SHADER,
                vk::PipelineStageFlags::COMPUTE_SHADER,
                vk::DependencyFlags::empty(),
                &[barrier],
                &[],
                &[],
            )
        };
    }

    pub fn bind_index_buffer_u32(&self, buffer: &Buffer) {
        // SAFETY: see `bind_graphics_pipeline`.
        unsafe {
            self.ctx
                .device
                .cmd_bind_index_buffer(self.raw, buffer.raw, 0, vk::IndexType::UINT32)
        };
    }

    pub fn draw(&self, vertices: u32, instances: u32, first_vertex: u32, first_instance: u32) {
        // SAFETY: see `bind_graphics_pipeline`.
        unsafe {
            self.ctx
                .device
                .cmd_draw(self.raw, vertices, instances, first_vertex, first_instance)
        };
    }

    pub fn draw_indexed(
        &self,
        indices: u32,
        instances: u32,
        first_index: u32,
        vertex_offset: i32,
        first_instance: u32,
    ) {
        // SAFETY: see `bind_graphics_pipeline`.
        unsafe {
            self.ctx.device.cmd_draw_indexed(
                self.raw,
                indices,
                instances,
                first_index,
                vertex_offset,
                first_instance,
            )
        };
    }

    /// Begin dynamic rendering into one colour and one depth attachment (both cleared), and set
    /// the viewport and scissor to the whole extent.
    pub fn begin_rendering(
        &self,
        color_view: vk::ImageView,
        depth_view: vk::ImageView,
        extent: vk::Extent2D,
        clear: [f32; 4],
    ) {
        self.begin_rendering_resolved(color_view, None, depth_view, extent, clear);
    }

    /// [`Cmd::begin_rendering`] into a multisampled colour attachment averaged into `resolve`
    /// (single-sampled, in COLOR_ATTACHMENT_OPTIMAL) when the instance ends; the multisampled
    /// samples themselves are not kept.
    pub fn begin_rendering_resolved(
        &self,
        color_view: vk::ImageView,
        resolve: Option<vk::ImageView>,
        depth_view: vk::ImageView,
        extent: vk::Extent2D,
        clear: [f32; 4],
    ) {
        let mut attachment = vk::RenderingAttachmentInfo::default()
            .image_view(color_view)
            .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
            .load_op(vk::AttachmentLoadOp::CLEAR)
            .store_op(vk::AttachmentStoreOp::STORE)
            .clear_value(vk::ClearValue {
                color: vk::ClearColorValue { float32: clear },
            });
        if let Some(resolve) = resolve {
            attachment = attachment
                .store_op(vk::AttachmentStoreOp::DONT_CARE)
                .resolve_mode(vk::ResolveModeFlags::AVERAGE)
                .resolve_image_view(resolve)
                .resolve_image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL);
        }
        let color = [attachment];
        let depth = vk::RenderingAttachmentInfo::default()
            .image_view(depth_view)
            .image_layout(vk::ImageLayout::DEPTH_ATTACHMENT_OPTIMAL)
            .load_op(vk::AttachmentLoadOp::CLEAR)
            .store_op(vk::AttachmentStoreOp::DONT_CARE)
            .clear_value(vk::ClearValue {
                depth_stencil: vk::ClearDepthStencilValue {
                    depth: 1.0,
                    stencil: 0,
                },
            });
        let area = vk::Rect2D {
            offset: vk::Offset2D::default(),
            extent,
        };
        let info = vk::RenderingInfo::default()
            .render_area(area)
            .layer_count(1)
            .color_attachments(&color)
            .depth_attachment(&depth);
        let viewport = vk::Viewport {
            x: 0.0,
            y: 0.0,
            width: extent.width as f32,
            height: extent.height as f32,
            min_depth: 0.0,
            max_depth: 1.0,
        };
        // SAFETY: see `bind_graphics_pipeline`; attachments are in the layouts named above.
        unsafe {
            self.ctx.device.cmd_begin_rendering(self.raw, &info);
            self.ctx.device.cmd_set_viewport(self.raw, 0, &[viewport]);
            self.ctx.device.cmd_set_scissor(self.raw, 0, &[area]);
        }
    }

    /// Begin dynamic rendering into one colour attachment, kept as it is (loaded), without
    /// depth: what is drawn over a resolved image (the window's overlay panel).
    pub fn begin_rendering_over(&self, color_view: vk::ImageView, extent: vk::Extent2D) {
        let color = [vk::RenderingAttachmentInfo::default()
            .image_view(color_view)
            .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
            .load_op(vk::AttachmentLoadOp::LOAD)
            .store_op(vk::AttachmentStoreOp::STORE)];
        let area = vk::Rect2D {
            offset: vk::Offset2D::default(),
            extent,
        };
        let info = vk::RenderingInfo::default()
            .render_area(area)
            .layer_count(1)
            .color_attachments(&color);
        // SAFETY: see `bind_graphics_pipeline`; the attachment is in the layout named above.
        unsafe { self.ctx.device.cmd_begin_rendering(self.raw, &info) };
    }

    pub fn end_rendering(&self) {
        // SAFETY: matches a `begin_rendering` on this command buffer.
        unsafe { self.ctx.device.cmd_end_rendering(self.raw) };
    }

    /// Image layout transition of the whole image (conservative stage and access masks).
    pub fn transition(
        &self,
        image: vk::Image,
        aspect: vk::ImageAspectFlags,
        old: vk::ImageLayout,
        new: vk::ImageLayout,
    ) {
        let barrier = vk::ImageMemoryBarrier::default()
            .image(image)
            .old_layout(old)
            .new_layout(new)
            .src_access_mask(vk::AccessFlags::MEMORY_WRITE)
            .dst_access_mask(vk::AccessFlags::MEMORY_READ | vk::AccessFlags::MEMORY_WRITE)
            .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
            .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
            .subresource_range(subresource(aspect));
        // SAFETY: see `bind_graphics_pipeline`; outside a rendering instance.
        unsafe {
            self.ctx.device.cmd_pipeline_barrier(
                self.raw,
                vk::PipelineStageFlags::ALL_COMMANDS,
                vk::PipelineStageFlags::ALL_COMMANDS,
                vk::DependencyFlags::empty(),
                &[],
                &[],
                &[barrier],
            )
        };
    }

    /// Make shader and transfer writes visible to the host once the submission's fence signals.
    pub fn barrier_to_host(&self) {
        let barrier = vk::MemoryBarrier::default()
            .src_access_mask(
                vk::AccessFlags::SHADER_WRITE
                    | vk::AccessFlags::TRANSFER_WRITE
                    | vk::AccessFlags::TRANSFORM_FEEDBACK_WRITE_EXT
                    | vk::AccessFlags::TRANSFORM_FEEDBACK_COUNTER_WRITE_EXT,
            )
            .dst_access_mask(vk::AccessFlags::HOST_READ);
        // SAFETY: see `bind_graphics_pipeline`; outside a rendering instance.
        unsafe {
            self.ctx.device.cmd_pipeline_barrier(
                self.raw,
                vk::PipelineStageFlags::ALL_COMMANDS,
                vk::PipelineStageFlags::HOST,
                vk::DependencyFlags::empty(),
                &[barrier],
                &[],
                &[],
            )
        };
    }

    /// Copy a colour image in TRANSFER_SRC_OPTIMAL to a buffer, tightly packed.
    pub fn copy_image_to_buffer(&self, image: vk::Image, extent: vk::Extent2D, buffer: &Buffer) {
        let region = vk::BufferImageCopy::default()
            .image_subresource(
                vk::ImageSubresourceLayers::default()
                    .aspect_mask(vk::ImageAspectFlags::COLOR)
                    .layer_count(1),
            )
            .image_extent(vk::Extent3D {
                width: extent.width,
                height: extent.height,
                depth: 1,
            });
        // SAFETY: see `bind_graphics_pipeline`; the buffer holds width*height*4 bytes.
        unsafe {
            self.ctx.device.cmd_copy_image_to_buffer(
                self.raw,
                image,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                buffer.raw,
                &[region],
            )
        };
    }

    pub fn copy_buffer(&self, src: &Buffer, dst: &Buffer, bytes: u64) {
        let region = vk::BufferCopy::default().size(bytes);
        // SAFETY: see `bind_graphics_pipeline`; both buffers hold `bytes`.
        unsafe {
            self.ctx
                .device
                .cmd_copy_buffer(self.raw, src.raw, dst.raw, &[region])
        };
    }

    /// VK_EXT_transform_feedback entry points. Panics if the extension is not enabled (callers
    /// check `DeviceInfo::transform_feedback` first).
    fn xfb(&self) -> &ash::ext::transform_feedback::DeviceFn {
        self.ctx
            .xfb
            .as_ref()
            .expect("transform feedback is enabled")
            .fp()
    }

    /// Bind `buffer` as transform-feedback buffer 0 and begin transform feedback (inside a
    /// rendering instance). Panics if the device has no VK_EXT_transform_feedback (callers check
    /// `DeviceInfo::transform_feedback` first).
    pub fn begin_transform_feedback(&self, buffer: &Buffer) {
        let fp = self.xfb();
        let buffers = [buffer.raw];
        let offsets = [0u64];
        let sizes = [buffer.size()];
        // SAFETY: see `bind_graphics_pipeline`; the extension is enabled, the buffer was created
        // with TRANSFORM_FEEDBACK_BUFFER usage, no counter buffers (capture starts at offset 0).
        unsafe {
            (fp.cmd_bind_transform_feedback_buffers_ext)(
                self.raw,
                0,
                1,
                buffers.as_ptr(),
                offsets.as_ptr(),
                sizes.as_ptr(),
            );
            (fp.cmd_begin_transform_feedback_ext)(
                self.raw,
                0,
                0,
                std::ptr::null(),
                std::ptr::null(),
            );
        }
    }

    /// End transform feedback begun by `begin_transform_feedback`; with `counter`, the device
    /// writes the bytes it wrote to buffer 0 (a `u32`) at the counter's offset 0 (the buffer was
    /// created with TRANSFORM_FEEDBACK_COUNTER_BUFFER usage; `barrier_to_host` makes it visible).
    pub fn end_transform_feedback(&self, counter: Option<&Buffer>) {
        let fp = self.xfb();
        let buffers = counter.map(|c| [c.raw]);
        let offsets = [0u64];
        // SAFETY: matches `begin_transform_feedback` in this rendering instance; with a counter,
        // one buffer handle and one offset, both arrays alive for the call.
        unsafe {
            match &buffers {
                Some(b) => (fp.cmd_end_transform_feedback_ext)(
                    self.raw,
                    0,
                    1,
                    b.as_ptr(),
                    offsets.as_ptr(),
                ),
                None => (fp.cmd_end_transform_feedback_ext)(
                    self.raw,
                    0,
                    0,
                    std::ptr::null(),
                    std::ptr::null(),
                ),
            }
        };
    }

    pub fn fill_buffer(&self, buffer: &Buffer, value: u32) {
        // SAFETY: see `bind_graphics_pipeline`.
        unsafe {
            self.ctx
                .device
                .cmd_fill_buffer(self.raw, buffer.raw, 0, vk::WHOLE_SIZE, value)
        };
    }
}

/// The stages that may read per-element levels: indirect draws, every geometry stage, the
/// fragment stage and compute.
const LEVEL_READERS: vk::PipelineStageFlags = vk::PipelineStageFlags::from_raw(
    vk::PipelineStageFlags::DRAW_INDIRECT.as_raw()
        | vk::PipelineStageFlags::VERTEX_INPUT.as_raw()
        | vk::PipelineStageFlags::VERTEX_SHADER.as_raw()
        | vk::PipelineStageFlags::TESSELLATION_CONTROL_SHADER.as_raw()
        | vk::PipelineStageFlags::TESSELLATION_EVALUATION_SHADER.as_raw()
        | vk::PipelineStageFlags::FRAGMENT_SHADER.as_raw()
        | vk::PipelineStageFlags::COMPUTE_SHADER.as_raw(),
);
