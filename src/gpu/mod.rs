//! The Vulkan layer: the only module that calls `ash` (and the only one with `unsafe`).
//!
//! Ownership follows docs/architecture.md ("Vulkan objects"): one [`Context`] (entry, instance,
//! debug messenger, device, queue, allocator) behind an `Arc`; every resource wrapper holds an
//! `Arc<Context>` and destroys its handle in `Drop`, so parents outlive children. Headless code
//! submits and waits, so nothing in flight is ever destroyed; the window loop waits for the frame's
//! fence before reusing or dropping anything that frame used.
//!
//! Leak checks: [`live_objects`] counts wrappers alive (every owning wrapper registers itself), and
//! dropping the context reports gpu-allocator allocations that were never freed as an error
//! message (collected like validation messages), which the tests turn into failures.

mod buffer;
mod checked;
mod commands;
mod context;
mod device;
mod image;
mod overlay;
mod pipeline;
mod query;
mod recorder;
mod swapchain;

pub use buffer::{Buffer, BufferDesc, BufferView};
pub use checked::{check_shutdown, with_context, ShutdownError};
pub use commands::{CommandPool, Fence, Semaphore};
pub use context::{list_devices, picked_device, Context, ContextDesc, GpuError, Messages};
pub use device::{DeviceInfo, CHECKED_FEATURES, STORAGE_BUFFERS_PER_STAGE};
pub use image::{
    sample_count, Image, ImageDesc, OffscreenTarget, Readback, DEPTH_FORMAT, MSAA_COUNTS,
    OFFSCREEN_FORMAT,
};
pub use overlay::Overlay;
pub use pipeline::{
    DescriptorPool, DescriptorSetLayout, GraphicsPipelineDesc, Pipeline, PipelineLayout,
    ShaderModule, SpecConstants,
};
pub use query::{PipelineStats, QueryPools};
pub use recorder::Cmd;
pub use swapchain::{surface_extensions, Swapchain, SwapchainFrame};

pub use ash::vk;

use std::sync::atomic::{AtomicIsize, Ordering};

static LIVE_OBJECTS: AtomicIsize = AtomicIsize::new(0);

/// Owning wrappers (and contexts) alive in this process. Zero after everything is dropped.
pub fn live_objects() -> isize {
    LIVE_OBJECTS.load(Ordering::SeqCst)
}

pub(crate) fn track_new() {
    LIVE_OBJECTS.fetch_add(1, Ordering::SeqCst);
}

pub(crate) fn track_drop() {
    LIVE_OBJECTS.fetch_sub(1, Ordering::SeqCst);
}

/// The embedded SPIR-V, keyed by path below `glsl/` (`+capture` for capture variants).
pub mod shaders {
    include!(concat!(env!("OUT_DIR"), "/shaders.rs"));

    /// SPIR-V words of an embedded shader. Panics on an unknown name (a programming error: the
    /// table is generated from the same tree).
    pub fn spirv(name: &str) -> Vec<u32> {
        let bytes = SHADERS
            .iter()
            .find(|(n, _)| *n == name)
            .unwrap_or_else(|| panic!("no embedded shader named {name}"))
            .1;
        ash::util::read_spv(&mut std::io::Cursor::new(bytes))
            .expect("embedded SPIR-V is well formed")
    }
}
