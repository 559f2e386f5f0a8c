//! Conversions from our enums to Vulkan values, in one place (wgpu-hal's `conv.rs`).

use crate::render::Driver;
use ash::vk;

/// Shader stages that read the push-constant block (every stage of every driver may).
pub const PUSH_STAGES: vk::ShaderStageFlags = vk::ShaderStageFlags::from_raw(
    vk::ShaderStageFlags::VERTEX.as_raw()
        | vk::ShaderStageFlags::TESSELLATION_CONTROL.as_raw()
        | vk::ShaderStageFlags::TESSELLATION_EVALUATION.as_raw()
        | vk::ShaderStageFlags::FRAGMENT.as_raw(),
);

/// Stages that evaluate surfaces or read per-mesh data.
pub const GEOMETRY_STAGES: vk::ShaderStageFlags = vk::ShaderStageFlags::from_raw(
    vk::ShaderStageFlags::VERTEX.as_raw()
        | vk::ShaderStageFlags::TESSELLATION_CONTROL.as_raw()
        | vk::ShaderStageFlags::TESSELLATION_EVALUATION.as_raw(),
);

/// Primitive topology each driver draws with.
pub fn topology(driver: Driver) -> vk::PrimitiveTopology {
    match driver {
        Driver::Static | Driver::Pattern => vk::PrimitiveTopology::TRIANGLE_STRIP,
        Driver::Tess => vk::PrimitiveTopology::PATCH_LIST,
    }
}
