//! Instance, device, queue, allocator, validation messages (device choice: `device.rs`).

pub use super::device::ContextDesc;
use super::device::{pick_device, query_capabilities, DeviceInfo};
use super::{track_drop, track_new};
use ash::vk;
use gpu_allocator::vulkan::{Allocator, AllocatorCreateDesc};
use std::ffi::{c_char, c_void, CString};
use std::mem::ManuallyDrop;
use std::sync::{Arc, Mutex};

/// Errors of the Vulkan layer. A Vulkan failure names the call.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error("cannot load the Vulkan library: {0} (install libvulkan1 and a driver, e.g. mesa-vulkan-drivers)")]
    Loading(String),
    #[error("{call} failed: {result}")]
    Vk {
        call: &'static str,
        result: vk::Result,
    },
    #[error("no Vulkan 1.3 device found (install mesa-vulkan-drivers for lavapipe, the software rasterizer)")]
    NoDevice,
    #[error("no Vulkan device matches --device '{wanted}'; available: {available}")]
    DeviceNotFound { wanted: String, available: String },
    #[error("device '{device}' lacks the required feature {feature}")]
    MissingFeature {
        device: String,
        feature: &'static str,
    },
    #[error("device '{device}' offers {offered} {what} per shader stage ({limit}), and meshrefine's {user} bind {needed}")]
    StageLimit {
        device: String,
        what: &'static str,
        limit: &'static str,
        offered: u32,
        needed: u32,
        user: &'static str,
    },
    #[error("the Vulkan validation layer VK_LAYER_KHRONOS_validation is not installed (apt-get install vulkan-validationlayers)")]
    NoValidationLayer,
    #[error("the overlay renderer (egui-ash-renderer) failed: {0}")]
    Overlay(#[from] egui_ash_renderer::RendererError),
    #[error("GPU memory allocation '{name}' failed: {source}")]
    Alloc {
        name: String,
        source: gpu_allocator::AllocationError,
    },
    #[error("{0}")]
    Other(String),
}

pub(crate) trait VkResultExt<T> {
    fn call(self, name: &'static str) -> Result<T, GpuError>;
}

impl<T> VkResultExt<T> for Result<T, vk::Result> {
    fn call(self, name: &'static str) -> Result<T, GpuError> {
        self.map_err(|result| GpuError::Vk { call: name, result })
    }
}

/// Validation-layer warnings and errors (and leak reports) collected during the context's life.
#[derive(Default, Debug)]
pub struct Messages {
    list: Mutex<Vec<String>>,
    /// While set (during `vkCreateInstance`), warnings and errors are collected without being
    /// logged: [`Messages::release`] logs them once the call's outcome is known.
    held: std::sync::atomic::AtomicBool,
}

impl Messages {
    pub fn push(&self, m: String) {
        self.list.lock().unwrap().push(m);
    }
    pub fn take(&self) -> Vec<String> {
        std::mem::take(&mut *self.list.lock().unwrap())
    }

    fn holding(&self) -> bool {
        self.held.load(std::sync::atomic::Ordering::Relaxed)
    }

    /// Hold the messages from now on (not logged until [`Messages::release`]).
    fn hold(&self) {
        self.held.store(true, std::sync::atomic::Ordering::Relaxed);
    }

    /// Stop holding: the messages collected are logged as errors where the call they came
    /// from succeeded (`created`); where it failed, its own error is the one sentence said and
    /// they are logged at debug level (the loader's "Found no drivers!" beside "Unable to find
    /// a Vulkan driver"), and dropped from the list.
    fn release(&self, created: bool) {
        self.held.store(false, std::sync::atomic::Ordering::Relaxed);
        if created {
            for m in self.list.lock().unwrap().iter() {
                log::error!("vulkan validation: {m}");
            }
        } else {
            for m in self.take() {
                log::debug!("vulkan validation (instance not created): {m}");
            }
        }
    }
}

pub struct Context {
    pub entry: ash::Entry,
    pub instance: ash::Instance,
    debug_instance: Option<ash::ext::debug_utils::Instance>,
    messenger: vk::DebugUtilsMessengerEXT,
    debug_device: Option<ash::ext::debug_utils::Device>,
    /// VK_EXT_transform_feedback entry points, when enabled.
    pub(crate) xfb: Option<ash::ext::transform_feedback::Device>,
    pub physical: vk::PhysicalDevice,
    pub info: DeviceInfo,
    pub device: ash::Device,
    pub queue: vk::Queue,
    pub queue_family: u32,
    /// Shared (an `Arc`) only with the overlay renderer, which the context outlives.
    allocator: ManuallyDrop<Arc<Mutex<Allocator>>>,
    /// Its heap address is the messenger's user data: it outlives the messenger and instance.
    messages: Arc<Messages>,
    /// Bytes the CPU has handed the device through this context ([`Context::host_bytes`]).
    host_bytes: std::sync::atomic::AtomicU64,
}

unsafe extern "system" fn debug_callback(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    types: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user: *mut c_void,
) -> vk::Bool32 {
    // SAFETY: the loader passes a valid callback-data pointer for the duration of the call.
    let msg = unsafe { (*data).message_as_c_str() }
        .map(|m| m.to_string_lossy().into_owned())
        .unwrap_or_default();
    let text = format!("[{types:?}] {msg}");
    if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::ERROR)
        || severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::WARNING)
    {
        // SAFETY: `user` points at the Context's Arc<Messages> contents, alive until after the
        // messenger and the instance are destroyed.
        let messages = unsafe { &*(user as *const Messages) };
        if !messages.holding() {
            log::error!("vulkan validation: {text}");
        }
        messages.push(text);
    } else if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::INFO) {
        log::debug!("vulkan: {text}");
    } else {
        log::trace!("vulkan: {text}");
    }
    vk::FALSE
}

/// The instance and its debug messenger: the first phase of [`Context::new`].
struct InstanceParts {
    entry: ash::Entry,
    instance: ash::Instance,
    debug_instance: Option<ash::ext::debug_utils::Instance>,
    messenger: vk::DebugUtilsMessengerEXT,
}

impl InstanceParts {
    /// Load the loader, check for the validation layer, create the instance (with the
    /// messenger collecting into `messages` when validating).
    fn new(desc: &ContextDesc, messages: &Arc<Messages>) -> Result<Self, GpuError> {
        // SAFETY: loads the system Vulkan loader; no other Vulkan call happens before.
        let entry = unsafe { ash::Entry::load() }.map_err(|e| GpuError::Loading(e.to_string()))?;

        // SAFETY: plain enumeration on a valid entry.
        let layers = unsafe { entry.enumerate_instance_layer_properties() }
            .call("vkEnumerateInstanceLayerProperties")?;
        let validation = c"VK_LAYER_KHRONOS_validation";
        let has_validation = layers
            .iter()
            .any(|l| l.layer_name_as_c_str() == Ok(validation));
        if desc.validate && !has_validation {
            return Err(GpuError::NoValidationLayer);
        }
        // SAFETY: as above.
        let exts = unsafe { entry.enumerate_instance_extension_properties(None) }
            .call("vkEnumerateInstanceExtensionProperties")?;
        let has_debug_utils = exts
            .iter()
            .any(|e| e.extension_name_as_c_str() == Ok(ash::ext::debug_utils::NAME))
            || desc.validate;

        let app_name = CString::new("meshrefine").unwrap();
        let app = vk::ApplicationInfo::default()
            .application_name(&app_name)
            .engine_name(&app_name)
            .api_version(vk::API_VERSION_1_3);
        let mut ext_names: Vec<*const c_char> =
            desc.surface_extensions.iter().map(|e| e.as_ptr()).collect();
        if has_debug_utils {
            ext_names.push(ash::ext::debug_utils::NAME.as_ptr());
        }
        let layer_names: Vec<*const c_char> = if desc.validate {
            vec![validation.as_ptr()]
        } else {
            vec![]
        };

        let mut messenger_info = vk::DebugUtilsMessengerCreateInfoEXT::default()
            .message_severity(
                vk::DebugUtilsMessageSeverityFlagsEXT::ERROR
                    | vk::DebugUtilsMessageSeverityFlagsEXT::WARNING
                    | vk::DebugUtilsMessageSeverityFlagsEXT::INFO,
            )
            .message_type(
                vk::DebugUtilsMessageTypeFlagsEXT::GENERAL
                    | vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                    | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE,
            )
            .pfn_user_callback(Some(debug_callback))
            .user_data(Arc::as_ptr(messages) as *mut c_void);
        let mut instance_info = vk::InstanceCreateInfo::default()
            .application_info(&app)
            .enabled_extension_names(&ext_names)
            .enabled_layer_names(&layer_names);
        // Synchronization validation too: hazards between commands (missing barriers) are
        // reported like any other validation error.
        let enabled_checks = [vk::ValidationFeatureEnableEXT::SYNCHRONIZATION_VALIDATION];
        let mut validation_features =
            vk::ValidationFeaturesEXT::default().enabled_validation_features(&enabled_checks);
        if desc.validate {
            // Also catch messages from vkCreateInstance / vkDestroyInstance themselves.
            instance_info = instance_info
                .push_next(&mut messenger_info)
                .push_next(&mut validation_features);
        }
        // SAFETY: all pointers in the create info outlive the call.
        messages.hold();
        let instance = unsafe { entry.create_instance(&instance_info, None) };
        messages.release(instance.is_ok());
        let instance = instance.call("vkCreateInstance")?;

        let (debug_instance, messenger) = if desc.validate {
            let di = ash::ext::debug_utils::Instance::new(&entry, &instance);
            // SAFETY: valid instance; the user-data box outlives the messenger (destroyed in Drop).
            let m = unsafe { di.create_debug_utils_messenger(&messenger_info, None) };
            match m {
                Ok(m) => (Some(di), m),
                Err(e) => {
                    // SAFETY: nothing else was created from this instance.
                    unsafe { instance.destroy_instance(None) };
                    return Err(GpuError::Vk {
                        call: "vkCreateDebugUtilsMessengerEXT",
                        result: e,
                    });
                }
            }
        } else if has_debug_utils {
            (
                Some(ash::ext::debug_utils::Instance::new(&entry, &instance)),
                vk::DebugUtilsMessengerEXT::null(),
            )
        } else {
            (None, vk::DebugUtilsMessengerEXT::null())
        };
        Ok(Self {
            entry,
            instance,
            debug_instance,
            messenger,
        })
    }

    /// Destroy the messenger and the instance (a later phase failed; nothing else was made).
    fn destroy(&self) {
        if let Some(di) = &self.debug_instance {
            if self.messenger != vk::DebugUtilsMessengerEXT::null() {
                // SAFETY: messenger created from this instance; nothing uses it any more.
                unsafe { di.destroy_debug_utils_messenger(self.messenger, None) };
            }
        }
        // SAFETY: no child object remains.
        unsafe { self.instance.destroy_instance(None) };
    }
}

/// Open the device with the features `info` says are there, and one queue of `queue_family`.
fn open_device(
    instance: &ash::Instance,
    physical: vk::PhysicalDevice,
    queue_family: u32,
    info: &DeviceInfo,
    desc: &ContextDesc,
) -> Result<ash::Device, GpuError> {
    let features = vk::PhysicalDeviceFeatures::default()
        .tessellation_shader(true)
        .pipeline_statistics_query(info.pipeline_statistics)
        .vertex_pipeline_stores_and_atomics(info.vertex_stores)
        .fill_mode_non_solid(info.fill_mode_non_solid)
        .depth_bias_clamp(info.depth_bias_clamp);
    // maintenance4: every Vulkan 1.3 device has it, and SPIR-V for 1.3 may state compute
    // workgroup sizes with LocalSizeId, which needs it enabled.
    let mut enable13 = vk::PhysicalDeviceVulkan13Features::default()
        .dynamic_rendering(true)
        .maintenance4(true);
    let priorities = [1.0f32];
    let queue_info = [vk::DeviceQueueCreateInfo::default()
        .queue_family_index(queue_family)
        .queue_priorities(&priorities)];
    let mut device_exts: Vec<*const c_char> = Vec::new();
    if !desc.surface_extensions.is_empty() {
        device_exts.push(ash::khr::swapchain::NAME.as_ptr());
    }
    let mut enable_xfb =
        vk::PhysicalDeviceTransformFeedbackFeaturesEXT::default().transform_feedback(true);
    let mut device_info = vk::DeviceCreateInfo::default()
        .queue_create_infos(&queue_info)
        .enabled_features(&features)
        .push_next(&mut enable13);
    if info.transform_feedback {
        device_exts.push(ash::ext::transform_feedback::NAME.as_ptr());
        device_info = device_info.push_next(&mut enable_xfb);
    }
    let device_info = device_info.enabled_extension_names(&device_exts);
    // SAFETY: valid physical device, create info pointers outlive the call.
    unsafe { instance.create_device(physical, &device_info, None) }.call("vkCreateDevice")
}

/// Every Vulkan 1.3 device with a graphics + compute queue, each with what meshrefine would use
/// of it or why it cannot draw there, without opening any; the first one is what a context picks
/// by default (or by `desc.device_name`).
pub fn list_devices(desc: &ContextDesc) -> Result<Vec<Result<DeviceInfo, GpuError>>, GpuError> {
    let messages = Arc::new(Messages::default());
    let parts = InstanceParts::new(desc, &messages)?;
    let listed = super::device::candidates(&parts.instance).map(|found| {
        let picked = pick_device(&parts.instance, desc).ok().map(|p| p.0);
        let mut list: Vec<_> = found
            .into_iter()
            .map(|(pd, _, info)| (Some(pd) != picked, pd, info))
            .collect();
        list.sort_by_key(|c| c.0);
        list.into_iter()
            .map(|(_, pd, info)| {
                query_capabilities(&parts.instance, pd, info, desc).map(|i| desc.limited(i))
            })
            .collect()
    });
    parts.destroy();
    listed
}

/// What a context would open for `desc` (the device [`Context::new`] picks, its capabilities
/// queried, or why it cannot draw there), without opening it.
pub fn picked_device(desc: &ContextDesc) -> Result<DeviceInfo, GpuError> {
    let messages = Arc::new(Messages::default());
    let parts = InstanceParts::new(desc, &messages)?;
    let picked = pick_device(&parts.instance, desc)
        .and_then(|(physical, _, info)| query_capabilities(&parts.instance, physical, info, desc))
        .map(|info| desc.limited(info));
    parts.destroy();
    picked
}

impl Context {
    /// Instance, then the device's capabilities, then the device opened with them.
    pub fn new(desc: &ContextDesc) -> Result<Arc<Self>, GpuError> {
        let messages = Arc::new(Messages::default());
        let parts = InstanceParts::new(desc, &messages)?;
        let opened = pick_device(&parts.instance, desc).and_then(|(physical, family, info)| {
            let info = desc.limited(query_capabilities(&parts.instance, physical, info, desc)?);
            let device = open_device(&parts.instance, physical, family, &info, desc)?;
            Ok((physical, family, info, device))
        });
        let (physical, queue_family, info, device) = match opened {
            Ok(o) => o,
            Err(e) => {
                parts.destroy();
                return Err(e);
            }
        };
        let InstanceParts {
            entry,
            instance,
            debug_instance,
            messenger,
        } = parts;
        // SAFETY: the family and index 0 were requested above.
        let queue = unsafe { device.get_device_queue(queue_family, 0) };
        let xfb = info
            .transform_feedback
            .then(|| ash::ext::transform_feedback::Device::new(&instance, &device));
        let debug_device = debug_instance
            .as_ref()
            .map(|_| ash::ext::debug_utils::Device::new(&instance, &device));

        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: instance.clone(),
            device: device.clone(),
            physical_device: physical,
            debug_settings: gpu_allocator::AllocatorDebugSettings {
                log_leaks_on_shutdown: false,
                ..Default::default()
            },
            buffer_device_address: false,
            allocation_sizes: gpu_allocator::AllocationSizes::default(),
        })
        .map_err(|e| GpuError::Alloc {
            name: "allocator".into(),
            source: e,
        })?;

        log::info!("using {}", info.describe());
        track_new();
        Ok(Arc::new(Self {
            entry,
            instance,
            debug_instance,
            messenger,
            debug_device,
            xfb,
            physical,
            info,
            device,
            queue,
            queue_family,
            allocator: ManuallyDrop::new(Arc::new(Mutex::new(allocator))),
            messages,
            host_bytes: std::sync::atomic::AtomicU64::new(0),
        }))
    }

    /// Validation warnings/errors and leak reports so far.
    pub fn messages(&self) -> &Messages {
        &self.messages
    }

    /// Bytes the CPU has handed the device through this context so far: every write into a
    /// host-visible buffer (records, levels' bounds, uniforms, staging copies of what lives in
    /// device memory) and every push constant recorded. The difference across a frame is what
    /// that frame uploaded, counted where the bytes go, not from a scene's own accounting.
    pub fn host_bytes(&self) -> u64 {
        self.host_bytes.load(std::sync::atomic::Ordering::Relaxed)
    }

    pub(crate) fn count_host_bytes(&self, n: usize) {
        (self.host_bytes).fetch_add(n as u64, std::sync::atomic::Ordering::Relaxed);
    }

    /// A handle to the message list that survives the context (to read leak reports after drop).
    pub fn messages_handle(&self) -> Arc<Messages> {
        self.messages.clone()
    }

    pub(crate) fn allocator(&self) -> std::sync::MutexGuard<'_, Allocator> {
        self.allocator.lock().unwrap()
    }

    /// The allocator itself, for a renderer that allocates through it (the overlay). Its holder
    /// also holds an `Arc<Context>`, so the allocator is never used after the context drops.
    pub(crate) fn shared_allocator(&self) -> Arc<Mutex<Allocator>> {
        Arc::clone(&self.allocator)
    }

    /// Give a Vulkan object a debug name (VK_EXT_debug_utils), when available.
    pub fn set_name<H: vk::Handle>(&self, handle: H, name: &str) {
        if let Some(dd) = &self.debug_device {
            let name = CString::new(name).unwrap_or_default();
            let info = vk::DebugUtilsObjectNameInfoEXT::default()
                .object_handle(handle)
                .object_name(&name);
            // SAFETY: the handle belongs to this device.
            let _ = unsafe { dd.set_debug_utils_object_name(&info) };
        }
    }

    /// Wait until the device is idle.
    pub fn wait_idle(&self) -> Result<(), GpuError> {
        // SAFETY: valid device.
        unsafe { self.device.device_wait_idle() }.call("vkDeviceWaitIdle")
    }
}

impl Drop for Context {
    fn drop(&mut self) {
        // SAFETY: we own the device; waiting has no preconditions.
        let _ = unsafe { self.device.device_wait_idle() };
        {
            let allocator = self.allocator.lock().unwrap();
            let report = allocator.generate_report();
            for a in &report.allocations {
                self.messages.push(format!(
                    "leak: GPU allocation '{}' ({} bytes) was never freed",
                    a.name, a.size
                ));
            }
        }
        // SAFETY: taken exactly once, here, before the device it uses is destroyed.
        let allocator = unsafe { ManuallyDrop::take(&mut self.allocator) };
        // Every other holder (the overlay) holds an Arc<Context> too, so none is left; should one
        // be, leaking the allocator is the safe choice (freeing needs the device).
        match Arc::try_unwrap(allocator) {
            Ok(allocator) => drop(allocator),
            Err(shared) => {
                self.messages
                    .push("leak: the GPU allocator is still shared when the context drops".into());
                std::mem::forget(shared);
            }
        }
        // SAFETY: every child object holds an Arc<Context>, so none is alive; idle device.
        unsafe { self.device.destroy_device(None) };
        if let Some(di) = &self.debug_instance {
            if self.messenger != vk::DebugUtilsMessengerEXT::null() {
                // SAFETY: created from this instance, destroyed once.
                unsafe { di.destroy_debug_utils_messenger(self.messenger, None) };
            }
        }
        // SAFETY: all children destroyed above.
        unsafe { self.instance.destroy_instance(None) };
        track_drop();
    }
}
