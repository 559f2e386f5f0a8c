//! Physical device choice and what we know of the chosen device: a discrete GPU first, then
//! integrated, virtual, CPU (lavapipe); `--device NAME` picks by name. Only Vulkan 1.3 devices
//! with a graphics + compute queue family are candidates.

use super::context::{GpuError, VkResultExt};
use ash::vk;
use std::ffi::{c_char, CStr};

/// Identity and limits of the chosen device, for logs and benchmark tables.
#[derive(Clone, Debug)]
pub struct DeviceInfo {
    pub name: String,
    pub driver_name: String,
    pub driver_info: String,
    pub driver_id: vk::DriverId,
    pub device_type: vk::PhysicalDeviceType,
    pub api_version: u32,
    pub limits: vk::PhysicalDeviceLimits,
    /// Optional features we enabled.
    pub pipeline_statistics: bool,
    pub vertex_stores: bool,
    pub fill_mode_non_solid: bool,
    /// `depthBiasClamp`: the wireframe's depth offset is clamped (else lines of steep and
    /// zero-area triangles, whose depth slope is unbounded, show through the surface).
    pub depth_bias_clamp: bool,
    /// Largest single allocation (Vulkan 1.1 maxMemoryAllocationSize).
    pub max_memory_allocation_size: u64,
    /// VK_EXT_transform_feedback (reads back the tessellator's triangles for export).
    pub transform_feedback: bool,
    pub max_transform_feedback_buffer_size: u64,
}

impl DeviceInfo {
    /// lavapipe (Mesa's llvmpipe Vulkan driver): some workarounds apply only there.
    pub fn is_lavapipe(&self) -> bool {
        self.driver_id == vk::DriverId::MESA_LLVMPIPE
    }
    pub fn describe(&self) -> String {
        format!(
            "{} ({}, {} {}, Vulkan {}.{}.{})",
            self.name,
            format!("{:?}", self.device_type)
                .to_lowercase()
                .replace('_', " "),
            self.driver_name,
            self.driver_info,
            vk::api_version_major(self.api_version),
            vk::api_version_minor(self.api_version),
            vk::api_version_patch(self.api_version)
        )
    }
}

fn cstr_field(chars: &[c_char]) -> String {
    // SAFETY: Vulkan fixed-size string fields are NUL-terminated.
    unsafe { CStr::from_ptr(chars.as_ptr()) }
        .to_string_lossy()
        .into_owned()
}

/// Every Vulkan 1.3 device with a graphics + compute queue family, with the family and what is
/// known of it before its features are queried.
pub(crate) fn candidates(
    instance: &ash::Instance,
) -> Result<Vec<(vk::PhysicalDevice, u32, DeviceInfo)>, GpuError> {
    // SAFETY: valid instance.
    let devices =
        unsafe { instance.enumerate_physical_devices() }.call("vkEnumeratePhysicalDevices")?;
    let mut candidates = Vec::new();
    for pd in devices {
        let mut driver = vk::PhysicalDeviceDriverProperties::default();
        let mut p11 = vk::PhysicalDeviceVulkan11Properties::default();
        let mut props2 = vk::PhysicalDeviceProperties2::default()
            .push_next(&mut driver)
            .push_next(&mut p11);
        // SAFETY: valid physical device; chain on the stack.
        unsafe { instance.get_physical_device_properties2(pd, &mut props2) };
        let props = props2.properties;
        if props.api_version < vk::API_VERSION_1_3 {
            continue;
        }
        // SAFETY: valid physical device.
        let families = unsafe { instance.get_physical_device_queue_family_properties(pd) };
        let Some(family) = families.iter().position(|f| {
            f.queue_flags
                .contains(vk::QueueFlags::GRAPHICS | vk::QueueFlags::COMPUTE)
        }) else {
            continue;
        };
        let info = DeviceInfo {
            name: cstr_field(&props.device_name),
            driver_name: cstr_field(&driver.driver_name),
            driver_info: cstr_field(&driver.driver_info),
            driver_id: driver.driver_id,
            device_type: props.device_type,
            api_version: props.api_version,
            limits: props.limits,
            pipeline_statistics: false,
            vertex_stores: false,
            fill_mode_non_solid: false,
            depth_bias_clamp: false,
            max_memory_allocation_size: p11.max_memory_allocation_size,
            transform_feedback: false,
            max_transform_feedback_buffer_size: 0,
        };
        candidates.push((pd, family as u32, info));
    }
    Ok(candidates)
}

pub(crate) fn pick_device(
    instance: &ash::Instance,
    desc: &ContextDesc,
) -> Result<(vk::PhysicalDevice, u32, DeviceInfo), GpuError> {
    let mut candidates = candidates(instance)?;
    if let Some(wanted) = &desc.device_name {
        let w = wanted.to_lowercase();
        let available = candidates
            .iter()
            .map(|c| c.2.name.clone())
            .collect::<Vec<_>>()
            .join(", ");
        return candidates
            .into_iter()
            .find(|c| c.2.name.to_lowercase().contains(&w))
            .ok_or(GpuError::DeviceNotFound {
                wanted: wanted.clone(),
                available,
            });
    }
    sort_by_default_rank(&mut candidates, |c| c.2.device_type);
    candidates.into_iter().next().ok_or(GpuError::NoDevice)
}

/// Sorts devices into the default order ([`default_rank`]), keeping the loader's order among
/// equals.
fn sort_by_default_rank<T>(devices: &mut [T], kind: impl Fn(&T) -> vk::PhysicalDeviceType) {
    devices.sort_by_key(|d| default_rank(kind(d)));
}

/// The default device's order (docs/cli.md, `--device`): a discrete GPU, then an integrated,
/// virtual or CPU device, then any other; among equals the loader's order (a stable sort).
fn default_rank(t: vk::PhysicalDeviceType) -> u32 {
    match t {
        vk::PhysicalDeviceType::DISCRETE_GPU => 0,
        vk::PhysicalDeviceType::INTEGRATED_GPU => 1,
        vk::PhysicalDeviceType::VIRTUAL_GPU => 2,
        vk::PhysicalDeviceType::CPU => 3,
        _ => 4,
    }
}

/// What to create.
#[derive(Clone, Debug, Default)]
pub struct ContextDesc {
    /// Enable VK_LAYER_KHRONOS_validation and the debug messenger.
    pub validate: bool,
    /// Pick the first device whose name contains this (case-insensitive).
    pub device_name: Option<String>,
    /// Instance extensions a window surface needs (from `ash_window::enumerate_required_extensions`).
    pub surface_extensions: Vec<&'static CStr>,
    /// Treat the device's `maxStorageBufferRange` as at most this many bytes: the device then
    /// looks as a device with less room would, so that a small mesh meets the limits a very
    /// large one meets (records bound in chunks, adaptive draws refused). For tests; the CLI
    /// reads it from `MESHREFINE_MAX_STORAGE_BUFFER_RANGE`.
    pub max_storage_buffer_range: Option<u32>,
    /// The same for `maxMemoryAllocationSize` (`MESHREFINE_MAX_MEMORY_ALLOCATION_SIZE`): what
    /// does not fit one allocation is refused or done another way, as on a smaller device.
    pub max_memory_allocation_size: Option<u64>,
    /// Features to treat as absent, by their Vulkan names (one of [`CHECKED_FEATURES`]): the
    /// device then looks as one without them would, refused for a required one, without what
    /// an optional one gives. For tests; the CLI reads it from `MESHREFINE_HIDE_FEATURES`.
    pub hidden_features: Vec<String>,
}

/// The device features meshrefine checks: the required ones (a device without them is refused,
/// naming it), then the optional ones (each missing one turns off what needs it, with a log
/// line).
pub const CHECKED_FEATURES: [&str; 7] = [
    "tessellationShader",
    "dynamicRendering",
    "transformFeedback",
    "vertexPipelineStoresAndAtomics",
    "fillModeNonSolid",
    "depthBiasClamp",
    "pipelineStatisticsQuery",
];

impl ContextDesc {
    /// `info` as this description has the device seen ([`Self::max_storage_buffer_range`],
    /// [`Self::max_memory_allocation_size`]).
    pub(crate) fn limited(&self, mut info: DeviceInfo) -> DeviceInfo {
        if let Some(cap) = self.max_storage_buffer_range {
            let range = &mut info.limits.max_storage_buffer_range;
            *range = (*range).min(cap);
        }
        if let Some(cap) = self.max_memory_allocation_size {
            info.max_memory_allocation_size = info.max_memory_allocation_size.min(cap);
        }
        info
    }
}

/// The most storage buffers one of meshrefine's pipelines binds to one shader stage: the Loop
/// step's and normals' compute set (per-vertex entry offsets, entries, M0, M1, one-ring offsets,
/// one-rings, M1's normals). Vulkan lets a device offer as few as 4; the drawing stages read
/// none outside the capture set's three (src/render/bindings.rs, `SET_MESH`), the pattern
/// driver's bins pass binds five.
pub const STORAGE_BUFFERS_PER_STAGE: u32 = 7;

/// The per-stage descriptor limits meshrefine's pipelines need beyond Vulkan's least, or a
/// sentence naming the limit (before any pipeline is made, so never a validation message).
pub(crate) fn check_stage_limits(info: &DeviceInfo) -> Result<(), GpuError> {
    let offered = info.limits.max_per_stage_descriptor_storage_buffers;
    if offered < STORAGE_BUFFERS_PER_STAGE {
        return Err(GpuError::StageLimit {
            device: info.name.clone(),
            what: "storage buffers",
            limit: "maxPerStageDescriptorStorageBuffers",
            offered,
            needed: STORAGE_BUFFERS_PER_STAGE,
            user: "Loop passes",
        });
    }
    Ok(())
}

/// What the chosen device offers beyond the required features: gathered once, before the device
/// is opened (as wgpu-hal's `expose_adapter` does), each missing optional feature said once.
pub(super) fn query_capabilities(
    instance: &ash::Instance,
    physical: vk::PhysicalDevice,
    mut info: DeviceInfo,
    desc: &ContextDesc,
) -> Result<DeviceInfo, GpuError> {
    // Features: required ones fail with a named error; optional ones degrade with a log line.
    // SAFETY: valid physical device.
    let mut available = unsafe { instance.get_physical_device_features(physical) };
    // SAFETY: valid physical device.
    let device_extensions =
        unsafe { instance.enumerate_device_extension_properties(physical) }.unwrap_or_default();
    let has_xfb = device_extensions
        .iter()
        .any(|e| e.extension_name_as_c_str() == Ok(ash::ext::transform_feedback::NAME));
    let mut f13 = vk::PhysicalDeviceVulkan13Features::default();
    let mut fxfb = vk::PhysicalDeviceTransformFeedbackFeaturesEXT::default();
    let mut f2 = vk::PhysicalDeviceFeatures2::default().push_next(&mut f13);
    if has_xfb {
        f2 = f2.push_next(&mut fxfb);
    }
    // SAFETY: valid physical device; the chain lives on the stack and names only structs of
    // supported extensions.
    unsafe { instance.get_physical_device_features2(physical, &mut f2) };
    // A feature a test hides is absent from here on, as on a device without it.
    let checked = CHECKED_FEATURES;
    if let Some(bad) = (desc.hidden_features.iter()).find(|h| !checked.contains(&h.as_str())) {
        return Err(GpuError::Other(format!(
            "cannot hide '{bad}': not a feature meshrefine checks (one of {})",
            checked.join(", ")
        )));
    }
    let hidden = |name: &str| desc.hidden_features.iter().any(|h| h == name);
    let off = |on: &mut vk::Bool32, name: &str| {
        if hidden(name) {
            *on = vk::FALSE;
        }
    };
    off(&mut available.tessellation_shader, "tessellationShader");
    off(&mut f13.dynamic_rendering, "dynamicRendering");
    off(&mut fxfb.transform_feedback, "transformFeedback");
    let stores = &mut available.vertex_pipeline_stores_and_atomics;
    off(stores, "vertexPipelineStoresAndAtomics");
    off(&mut available.fill_mode_non_solid, "fillModeNonSolid");
    off(&mut available.depth_bias_clamp, "depthBiasClamp");
    off(
        &mut available.pipeline_statistics_query,
        "pipelineStatisticsQuery",
    );
    let transform_feedback = has_xfb && fxfb.transform_feedback == vk::TRUE;
    let mut xfb_props = vk::PhysicalDeviceTransformFeedbackPropertiesEXT::default();
    if transform_feedback {
        let mut p2 = vk::PhysicalDeviceProperties2::default().push_next(&mut xfb_props);
        // SAFETY: as above.
        unsafe { instance.get_physical_device_properties2(physical, &mut p2) };
    }
    let dynamic_rendering = f13.dynamic_rendering == vk::TRUE;
    let missing = if available.tessellation_shader == vk::FALSE {
        Some("tessellationShader")
    } else if !dynamic_rendering {
        Some("dynamicRendering")
    } else {
        None
    };
    if let Some(feature) = missing {
        return Err(GpuError::MissingFeature {
            device: info.name.clone(),
            feature,
        });
    }
    super::device::check_stage_limits(&info)?;
    info.pipeline_statistics = available.pipeline_statistics_query == vk::TRUE;
    info.vertex_stores = available.vertex_pipeline_stores_and_atomics == vk::TRUE;
    info.fill_mode_non_solid = available.fill_mode_non_solid == vk::TRUE;
    info.depth_bias_clamp = available.depth_bias_clamp == vk::TRUE;
    info.transform_feedback = transform_feedback;
    info.max_transform_feedback_buffer_size = xfb_props.max_transform_feedback_buffer_size;
    if !info.transform_feedback {
        log::info!(
            "{}: no transformFeedback, the tess driver cannot be exported",
            info.name
        );
    }
    if !info.fill_mode_non_solid {
        log::warn!(
            "{}: no fillModeNonSolid, the wireframe view is off",
            info.name
        );
    }
    if info.fill_mode_non_solid && !info.depth_bias_clamp {
        log::info!(
            "{}: no depthBiasClamp, wireframe lines of steep triangles may show through the surface",
            info.name
        );
    }
    if !info.pipeline_statistics {
        log::warn!(
            "{}: no pipelineStatisticsQuery, statistics are off",
            info.name
        );
    }
    if !info.vertex_stores {
        let tess = if info.transform_feedback {
            "; export --driver tess still works (transform feedback)"
        } else {
            ""
        };
        log::warn!(
            "{}: no vertexPipelineStoresAndAtomics, evaluated vertices cannot be captured (export --driver pattern){tess}",
            info.name
        );
    }
    Ok(info)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn info(storage_buffers: u32) -> DeviceInfo {
        DeviceInfo {
            name: "Tiny GPU".into(),
            driver_name: String::new(),
            driver_info: String::new(),
            driver_id: vk::DriverId::default(),
            device_type: vk::PhysicalDeviceType::INTEGRATED_GPU,
            api_version: vk::API_VERSION_1_3,
            limits: vk::PhysicalDeviceLimits {
                max_per_stage_descriptor_storage_buffers: storage_buffers,
                ..Default::default()
            },
            pipeline_statistics: false,
            vertex_stores: false,
            fill_mode_non_solid: false,
            depth_bias_clamp: false,
            max_memory_allocation_size: 0,
            transform_feedback: false,
            max_transform_feedback_buffer_size: 0,
        }
    }

    /// A device offering Vulkan's least, 4 storage buffers a stage, is refused with one sentence
    /// naming the device, the limit and what needs more; 7 is enough.
    #[test]
    fn too_few_storage_buffers_per_stage_are_refused_naming_the_limit() {
        let err = check_stage_limits(&info(4)).unwrap_err().to_string();
        assert_eq!(
            err,
            "device 'Tiny GPU' offers 4 storage buffers per shader stage \
             (maxPerStageDescriptorStorageBuffers), and meshrefine's Loop passes bind 7"
        );
        assert!(check_stage_limits(&info(STORAGE_BUFFERS_PER_STAGE)).is_ok());
    }
}

#[cfg(test)]
mod rank_tests {
    use super::sort_by_default_rank;
    use ash::vk::PhysicalDeviceType as T;

    /// A discrete GPU first, then integrated, virtual, CPU and other devices, the loader's order
    /// kept among equals.
    #[test]
    fn the_default_device_is_a_discrete_gpu_first() {
        let mut listed = [
            ("cpu", T::CPU),
            ("other", T::OTHER),
            ("virtual", T::VIRTUAL_GPU),
            ("integrated", T::INTEGRATED_GPU),
            ("discrete b", T::DISCRETE_GPU),
            ("integrated b", T::INTEGRATED_GPU),
            ("discrete", T::DISCRETE_GPU),
        ];
        sort_by_default_rank(&mut listed, |d| d.1);
        let order: Vec<&str> = listed.iter().map(|d| d.0).collect();
        assert_eq!(
            order,
            [
                "discrete b",
                "discrete",
                "integrated",
                "integrated b",
                "virtual",
                "cpu",
                "other"
            ]
        );
    }
}
