//! Shader modules, descriptor set layouts and pools, pipeline layouts, graphics pipelines.
//! Pipelines use dynamic rendering (Vulkan 1.3), dynamic viewport and scissor.

use super::context::VkResultExt;
use super::{shaders, track_drop, track_new, Context, GpuError};
use ash::vk;
use std::ffi::CStr;
use std::sync::Arc;

pub struct ShaderModule {
    ctx: Arc<Context>,
    pub raw: vk::ShaderModule,
}

impl ShaderModule {
    /// Module from the embedded shader `name` (path below `glsl/`, e.g. `pattern/pattern.vert`).
    pub fn new(ctx: &Arc<Context>, name: &str) -> Result<Self, GpuError> {
        let code = shaders::spirv(name);
        let info = vk::ShaderModuleCreateInfo::default().code(&code);
        // SAFETY: valid SPIR-V compiled by build.rs.
        let raw =
            unsafe { ctx.device.create_shader_module(&info, None) }.call("vkCreateShaderModule")?;
        ctx.set_name(raw, name);
        track_new();
        Ok(Self {
            ctx: ctx.clone(),
            raw,
        })
    }
}

impl Drop for ShaderModule {
    fn drop(&mut self) {
        // SAFETY: modules may be destroyed once pipelines are created.
        unsafe { self.ctx.device.destroy_shader_module(self.raw, None) };
        track_drop();
    }
}

pub struct DescriptorSetLayout {
    ctx: Arc<Context>,
    pub raw: vk::DescriptorSetLayout,
}

impl DescriptorSetLayout {
    /// `bindings`: (binding, type, stages).
    pub fn new(
        ctx: &Arc<Context>,
        bindings: &[(u32, vk::DescriptorType, vk::ShaderStageFlags)],
        name: &str,
    ) -> Result<Self, GpuError> {
        let b: Vec<_> = bindings
            .iter()
            .map(|&(binding, ty, stages)| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(binding)
                    .descriptor_type(ty)
                    .descriptor_count(1)
                    .stage_flags(stages)
            })
            .collect();
        let info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&b);
        // SAFETY: valid device and create info.
        let raw = unsafe { ctx.device.create_descriptor_set_layout(&info, None) }
            .call("vkCreateDescriptorSetLayout")?;
        ctx.set_name(raw, name);
        track_new();
        Ok(Self {
            ctx: ctx.clone(),
            raw,
        })
    }
}

impl Drop for DescriptorSetLayout {
    fn drop(&mut self) {
        // SAFETY: layouts are not used by pending work after their owner drops them.
        unsafe {
            self.ctx
                .device
                .destroy_descriptor_set_layout(self.raw, None)
        };
        track_drop();
    }
}

pub struct PipelineLayout {
    ctx: Arc<Context>,
    pub raw: vk::PipelineLayout,
}

impl PipelineLayout {
    pub fn new(
        ctx: &Arc<Context>,
        sets: &[&DescriptorSetLayout],
        push_constant_bytes: u32,
        push_stages: vk::ShaderStageFlags,
        name: &str,
    ) -> Result<Self, GpuError> {
        let layouts: Vec<_> = sets.iter().map(|s| s.raw).collect();
        let ranges = [vk::PushConstantRange::default()
            .stage_flags(push_stages)
            .size(push_constant_bytes)];
        let info = vk::PipelineLayoutCreateInfo::default()
            .set_layouts(&layouts)
            .push_constant_ranges(&ranges);
        // SAFETY: valid device and create info.
        let raw = unsafe { ctx.device.create_pipeline_layout(&info, None) }
            .call("vkCreatePipelineLayout")?;
        ctx.set_name(raw, name);
        track_new();
        Ok(Self {
            ctx: ctx.clone(),
            raw,
        })
    }
}

impl Drop for PipelineLayout {
    fn drop(&mut self) {
        // SAFETY: not used by pending work.
        unsafe { self.ctx.device.destroy_pipeline_layout(self.raw, None) };
        track_drop();
    }
}

/// Descriptor pool that frees all its sets when dropped.
pub struct DescriptorPool {
    ctx: Arc<Context>,
    pub raw: vk::DescriptorPool,
}

impl DescriptorPool {
    pub fn new(
        ctx: &Arc<Context>,
        max_sets: u32,
        sizes: &[(vk::DescriptorType, u32)],
        name: &str,
    ) -> Result<Self, GpuError> {
        let s: Vec<_> = sizes
            .iter()
            .map(|&(ty, n)| vk::DescriptorPoolSize::default().ty(ty).descriptor_count(n))
            .collect();
        let info = vk::DescriptorPoolCreateInfo::default()
            .max_sets(max_sets)
            .pool_sizes(&s);
        // SAFETY: valid device and create info.
        let raw = unsafe { ctx.device.create_descriptor_pool(&info, None) }
            .call("vkCreateDescriptorPool")?;
        ctx.set_name(raw, name);
        track_new();
        Ok(Self {
            ctx: ctx.clone(),
            raw,
        })
    }

    pub fn allocate(
        &self,
        layout: &DescriptorSetLayout,
        name: &str,
    ) -> Result<vk::DescriptorSet, GpuError> {
        let layouts = [layout.raw];
        let info = vk::DescriptorSetAllocateInfo::default()
            .descriptor_pool(self.raw)
            .set_layouts(&layouts);
        // SAFETY: pool and layout from this device.
        let set = unsafe { self.ctx.device.allocate_descriptor_sets(&info) }
            .call("vkAllocateDescriptorSets")?[0];
        self.ctx.set_name(set, name);
        Ok(set)
    }

    /// Point `binding` of `set` at `buffer` (whole buffer, or `range` bytes for dynamic uniform buffers).
    pub fn write_buffer(
        &self,
        set: vk::DescriptorSet,
        binding: u32,
        ty: vk::DescriptorType,
        buffer: vk::Buffer,
        range: u64,
    ) {
        self.write_buffer_at(set, binding, ty, buffer, 0, range)
    }

    /// Point `binding` of `set` at `range` bytes of `buffer` from `offset`.
    pub fn write_buffer_at(
        &self,
        set: vk::DescriptorSet,
        binding: u32,
        ty: vk::DescriptorType,
        buffer: vk::Buffer,
        offset: u64,
        range: u64,
    ) {
        let info = [vk::DescriptorBufferInfo::default()
            .buffer(buffer)
            .offset(offset)
            .range(range)];
        let write = vk::WriteDescriptorSet::default()
            .dst_set(set)
            .dst_binding(binding)
            .descriptor_type(ty)
            .buffer_info(&info);
        // SAFETY: set not in use by pending work while it is written (written before recording).
        unsafe { self.ctx.device.update_descriptor_sets(&[write], &[]) };
    }

    /// Point texel-buffer `binding` of `set` at `view`.
    pub fn write_texel_buffer(
        &self,
        set: vk::DescriptorSet,
        binding: u32,
        ty: vk::DescriptorType,
        view: vk::BufferView,
    ) {
        let views = [view];
        let write = vk::WriteDescriptorSet::default()
            .dst_set(set)
            .dst_binding(binding)
            .descriptor_type(ty)
            .texel_buffer_view(&views);
        // SAFETY: set not in use by pending work while it is written (written before recording).
        unsafe { self.ctx.device.update_descriptor_sets(&[write], &[]) };
    }
}

impl Drop for DescriptorPool {
    fn drop(&mut self) {
        // SAFETY: sets from this pool are not used by pending work.
        unsafe { self.ctx.device.destroy_descriptor_pool(self.raw, None) };
        track_drop();
    }
}

/// Specialization constants: (constant id, u32 value).
pub type SpecConstants = Vec<(u32, u32)>;

/// Everything that makes a graphics pipeline.
#[derive(Clone, Debug)]
pub struct GraphicsPipelineDesc {
    /// (stage, embedded shader name)
    pub stages: Vec<(vk::ShaderStageFlags, String)>,
    pub spec: SpecConstants,
    /// (binding, stride, per-instance)
    pub vertex_bindings: Vec<(u32, u32, bool)>,
    /// (location, binding, format, offset)
    pub vertex_attributes: Vec<(u32, u32, vk::Format, u32)>,
    pub topology: vk::PrimitiveTopology,
    pub primitive_restart: bool,
    pub patch_control_points: u32,
    pub color_format: vk::Format,
    pub depth_format: vk::Format,
    pub polygon_mode: vk::PolygonMode,
    /// (constant factor, slope factor, clamp): the clamp (0: none; needs the device's
    /// `depthBiasClamp`) bounds the offset where the slope is unbounded (a zero-area triangle).
    pub depth_bias: Option<(f32, f32, f32)>,
    /// Whether fragments write depth (overlays such as wireframes only test it).
    pub depth_write: bool,
    /// Whether the cull mode is set when drawing (`vkCmdSetCullMode`, core in Vulkan 1.3)
    /// rather than fixed at none.
    pub dynamic_cull: bool,
    /// Samples per pixel of the attachments drawn into.
    pub samples: vk::SampleCountFlags,
}

pub struct Pipeline {
    ctx: Arc<Context>,
    pub raw: vk::Pipeline,
}

impl Pipeline {
    /// A graphics pipeline of `desc`: shader stages (specialized), vertex input, the fixed
    /// states, then the create call.
    pub fn new_graphics(
        ctx: &Arc<Context>,
        layout: &PipelineLayout,
        desc: &GraphicsPipelineDesc,
        name: &str,
    ) -> Result<Self, GpuError> {
        let modules = desc
            .stages
            .iter()
            .map(|(_, n)| ShaderModule::new(ctx, n))
            .collect::<Result<Vec<_>, _>>()?;
        let spec = Specialization::new(&desc.spec);
        let spec_info = spec.info();
        let stages = shader_stages(desc, &modules, &spec_info);
        let vertex = VertexInput::new(desc);
        let vertex_input = vertex.state();
        let fixed = FixedStates::new(desc);
        let created = create_graphics(ctx, layout, desc, &stages, &vertex_input, &fixed);
        Self::adopt(ctx, created, "vkCreateGraphicsPipelines", name)
    }

    /// The wrapper of the one pipeline a create call made (named and counted).
    fn adopt(
        ctx: &Arc<Context>,
        created: Result<Vec<vk::Pipeline>, (Vec<vk::Pipeline>, vk::Result)>,
        call: &'static str,
        name: &str,
    ) -> Result<Self, GpuError> {
        let raw = created.map_err(|(_, result)| GpuError::Vk { call, result })?[0];
        ctx.set_name(raw, name);
        track_new();
        Ok(Self {
            ctx: ctx.clone(),
            raw,
        })
    }
}

/// Specialization constants as Vulkan reads them: one 4-byte entry each, packed in order.
struct Specialization {
    entries: Vec<vk::SpecializationMapEntry>,
    data: Vec<u8>,
}

impl Specialization {
    fn new(spec: &SpecConstants) -> Self {
        let entries = spec
            .iter()
            .enumerate()
            .map(|(i, &(id, _))| {
                vk::SpecializationMapEntry::default()
                    .constant_id(id)
                    .offset(4 * i as u32)
                    .size(4)
            })
            .collect();
        let data = spec.iter().flat_map(|&(_, v)| v.to_ne_bytes()).collect();
        Self { entries, data }
    }

    fn info(&self) -> vk::SpecializationInfo<'_> {
        vk::SpecializationInfo::default()
            .map_entries(&self.entries)
            .data(&self.data)
    }
}

/// One stage per module, each running `main` with the same specialization.
fn shader_stages<'a>(
    desc: &GraphicsPipelineDesc,
    modules: &[ShaderModule],
    spec: &'a vk::SpecializationInfo<'a>,
) -> Vec<vk::PipelineShaderStageCreateInfo<'a>> {
    let main: &CStr = c"main";
    desc.stages
        .iter()
        .zip(modules)
        .map(|((stage, _), m)| {
            vk::PipelineShaderStageCreateInfo::default()
                .stage(*stage)
                .module(m.raw)
                .name(main)
                .specialization_info(spec)
        })
        .collect()
}

/// The vertex bindings and attributes of a [`GraphicsPipelineDesc`].
struct VertexInput {
    bindings: Vec<vk::VertexInputBindingDescription>,
    attributes: Vec<vk::VertexInputAttributeDescription>,
}

impl VertexInput {
    fn new(desc: &GraphicsPipelineDesc) -> Self {
        let bindings = desc
            .vertex_bindings
            .iter()
            .map(|&(binding, stride, instance)| {
                vk::VertexInputBindingDescription::default()
                    .binding(binding)
                    .stride(stride)
                    .input_rate(if instance {
                        vk::VertexInputRate::INSTANCE
                    } else {
                        vk::VertexInputRate::VERTEX
                    })
            })
            .collect();
        let attributes = desc
            .vertex_attributes
            .iter()
            .map(|&(location, binding, format, offset)| {
                vk::VertexInputAttributeDescription::default()
                    .location(location)
                    .binding(binding)
                    .format(format)
                    .offset(offset)
            })
            .collect();
        Self {
            bindings,
            attributes,
        }
    }

    fn state(&self) -> vk::PipelineVertexInputStateCreateInfo<'_> {
        vk::PipelineVertexInputStateCreateInfo::default()
            .vertex_binding_descriptions(&self.bindings)
            .vertex_attribute_descriptions(&self.attributes)
    }
}

/// The states that hold no pointers: assembly, tessellation, one dynamic viewport and scissor,
/// rasterization (no culling), the attachments' samples, depth test and write.
struct FixedStates {
    input_assembly: vk::PipelineInputAssemblyStateCreateInfo<'static>,
    tessellation: vk::PipelineTessellationStateCreateInfo<'static>,
    viewport: vk::PipelineViewportStateCreateInfo<'static>,
    raster: vk::PipelineRasterizationStateCreateInfo<'static>,
    multisample: vk::PipelineMultisampleStateCreateInfo<'static>,
    depth: vk::PipelineDepthStencilStateCreateInfo<'static>,
}

impl FixedStates {
    fn new(desc: &GraphicsPipelineDesc) -> Self {
        Self {
            input_assembly: vk::PipelineInputAssemblyStateCreateInfo::default()
                .topology(desc.topology)
                .primitive_restart_enable(desc.primitive_restart),
            tessellation: vk::PipelineTessellationStateCreateInfo::default()
                .patch_control_points(desc.patch_control_points),
            viewport: vk::PipelineViewportStateCreateInfo::default()
                .viewport_count(1)
                .scissor_count(1),
            raster: vk::PipelineRasterizationStateCreateInfo::default()
                .polygon_mode(desc.polygon_mode)
                .depth_bias_enable(desc.depth_bias.is_some())
                .depth_bias_constant_factor(desc.depth_bias.map_or(0.0, |b| b.0))
                .depth_bias_slope_factor(desc.depth_bias.map_or(0.0, |b| b.1))
                .depth_bias_clamp(desc.depth_bias.map_or(0.0, |b| b.2))
                .cull_mode(vk::CullModeFlags::NONE)
                .front_face(vk::FrontFace::COUNTER_CLOCKWISE)
                .line_width(1.0),
            multisample: vk::PipelineMultisampleStateCreateInfo::default()
                .rasterization_samples(desc.samples),
            depth: vk::PipelineDepthStencilStateCreateInfo::default()
                .depth_test_enable(true)
                .depth_write_enable(desc.depth_write)
                .depth_compare_op(vk::CompareOp::LESS_OR_EQUAL),
        }
    }
}

/// The create call: the phases' states with colour blending (write RGBA), dynamic viewport and
/// scissor, and dynamic rendering's attachment formats.
fn create_graphics(
    ctx: &Context,
    layout: &PipelineLayout,
    desc: &GraphicsPipelineDesc,
    stages: &[vk::PipelineShaderStageCreateInfo<'_>],
    vertex_input: &vk::PipelineVertexInputStateCreateInfo<'_>,
    fixed: &FixedStates,
) -> Result<Vec<vk::Pipeline>, (Vec<vk::Pipeline>, vk::Result)> {
    let blend_attachments = [vk::PipelineColorBlendAttachmentState::default()
        .color_write_mask(vk::ColorComponentFlags::RGBA)];
    let blend = vk::PipelineColorBlendStateCreateInfo::default().attachments(&blend_attachments);
    let dynamic_states = [
        vk::DynamicState::VIEWPORT,
        vk::DynamicState::SCISSOR,
        vk::DynamicState::CULL_MODE,
    ];
    let dynamic_count = if desc.dynamic_cull { 3 } else { 2 };
    let dynamic = vk::PipelineDynamicStateCreateInfo::default()
        .dynamic_states(&dynamic_states[..dynamic_count]);
    let color_formats = [desc.color_format];
    let mut rendering = vk::PipelineRenderingCreateInfo::default()
        .color_attachment_formats(&color_formats)
        .depth_attachment_format(desc.depth_format);
    let mut info = vk::GraphicsPipelineCreateInfo::default()
        .stages(stages)
        .vertex_input_state(vertex_input)
        .input_assembly_state(&fixed.input_assembly)
        .viewport_state(&fixed.viewport)
        .rasterization_state(&fixed.raster)
        .multisample_state(&fixed.multisample)
        .depth_stencil_state(&fixed.depth)
        .color_blend_state(&blend)
        .dynamic_state(&dynamic)
        .layout(layout.raw)
        .push_next(&mut rendering);
    if desc.patch_control_points > 0 {
        info = info.tessellation_state(&fixed.tessellation);
    }
    // SAFETY: every pointer in the create info outlives the call.
    unsafe {
        ctx.device
            .create_graphics_pipelines(vk::PipelineCache::null(), &[info], None)
    }
}

impl Pipeline {
    /// A compute pipeline running the embedded shader `shader` (a `.comp` below `glsl/`).
    pub fn new_compute(
        ctx: &Arc<Context>,
        layout: &PipelineLayout,
        shader: &str,
        name: &str,
    ) -> Result<Self, GpuError> {
        Self::new_compute_specialized(ctx, layout, shader, &vec![], name)
    }

    /// A compute pipeline with specialization constants `spec` (id, value).
    pub fn new_compute_specialized(
        ctx: &Arc<Context>,
        layout: &PipelineLayout,
        shader: &str,
        spec: &SpecConstants,
        name: &str,
    ) -> Result<Self, GpuError> {
        let module = ShaderModule::new(ctx, shader)?;
        let spec = Specialization::new(spec);
        let spec_info = spec.info();
        let stage = vk::PipelineShaderStageCreateInfo::default()
            .stage(vk::ShaderStageFlags::COMPUTE)
            .module(module.raw)
            .name(c"main")
            .specialization_info(&spec_info);
        let info = vk::ComputePipelineCreateInfo::default()
            .stage(stage)
            .layout(layout.raw);
        // SAFETY: every pointer in the create info outlives the call.
        let created = unsafe {
            ctx.device
                .create_compute_pipelines(vk::PipelineCache::null(), &[info], None)
        };
        Self::adopt(ctx, created, "vkCreateComputePipelines", name)
    }
}

impl Drop for Pipeline {
    fn drop(&mut self) {
        // SAFETY: not used by pending work.
        unsafe { self.ctx.device.destroy_pipeline(self.raw, None) };
        track_drop();
    }
}
