//! Window surface and swapchain. Everything that depends on the swapchain's size (images, views,
//! depth image) lives here and is rebuilt together by [`Swapchain::recreate`].

use super::context::VkResultExt;
use super::image::create_view;
use super::{track_drop, track_new, Context, GpuError, Image, ImageDesc};
use ash::vk;
use raw_window_handle::{RawDisplayHandle, RawWindowHandle};
use std::sync::Arc;

/// Instance extensions needed to present to windows of `display`.
pub fn surface_extensions(
    display: RawDisplayHandle,
) -> Result<Vec<&'static std::ffi::CStr>, GpuError> {
    let names =
        ash_window::enumerate_required_extensions(display).call("enumerate_required_extensions")?;
    Ok(names
        .iter()
        // SAFETY: ash_window returns pointers to ash's 'static, NUL-terminated extension names.
        .map(|&p| unsafe { std::ffi::CStr::from_ptr(p) })
        .collect())
}

pub struct Swapchain {
    ctx: Arc<Context>,
    surface_fn: ash::khr::surface::Instance,
    swapchain_fn: ash::khr::swapchain::Device,
    surface: vk::SurfaceKHR,
    pub raw: vk::SwapchainKHR,
    pub images: Vec<vk::Image>,
    pub views: Vec<vk::ImageView>,
    pub depth: Option<Image>,
    /// The multisampled colour attachment resolved into the acquired image (`samples` > 1).
    pub msaa: Option<Image>,
    /// Samples per pixel of `msaa` and `depth`.
    pub samples: vk::SampleCountFlags,
    pub format: vk::Format,
    pub extent: vk::Extent2D,
}

/// An acquired swapchain image.
pub struct SwapchainFrame {
    pub index: u32,
    pub image: vk::Image,
    pub view: vk::ImageView,
    /// The swapchain no longer matches the surface exactly: recreate after presenting.
    pub suboptimal: bool,
}

impl Swapchain {
    pub fn new(
        ctx: &Arc<Context>,
        display: RawDisplayHandle,
        window: RawWindowHandle,
        size: (u32, u32),
        samples: vk::SampleCountFlags,
    ) -> Result<Self, GpuError> {
        // SAFETY: handles come from a live winit window that outlives the swapchain (the app
        // drops the swapchain before the window).
        let surface =
            unsafe { ash_window::create_surface(&ctx.entry, &ctx.instance, display, window, None) }
                .call("vkCreateSurfaceKHR")?;
        let surface_fn = ash::khr::surface::Instance::new(&ctx.entry, &ctx.instance);
        // SAFETY: valid physical device and surface.
        let supported = unsafe {
            surface_fn.get_physical_device_surface_support(ctx.physical, ctx.queue_family, surface)
        }
        .unwrap_or(false);
        if !supported {
            // SAFETY: unused surface.
            unsafe { surface_fn.destroy_surface(surface, None) };
            return Err(GpuError::Other(format!(
                "device '{}' cannot present to this window",
                ctx.info.name
            )));
        }
        let swapchain_fn = ash::khr::swapchain::Device::new(&ctx.instance, &ctx.device);
        track_new();
        let mut s = Self {
            ctx: ctx.clone(),
            surface_fn,
            swapchain_fn,
            surface,
            raw: vk::SwapchainKHR::null(),
            images: Vec::new(),
            views: Vec::new(),
            depth: None,
            msaa: None,
            samples,
            format: vk::Format::UNDEFINED,
            extent: vk::Extent2D::default(),
        };
        s.recreate(size)?;
        Ok(s)
    }

    /// (Re)build the swapchain and its dependents for a window of `size` pixels. The caller waits
    /// for the device to be idle first.
    pub fn recreate(&mut self, size: (u32, u32)) -> Result<(), GpuError> {
        let ctx = self.ctx.clone();
        // SAFETY: valid physical device and surface.
        let caps = unsafe {
            self.surface_fn
                .get_physical_device_surface_capabilities(ctx.physical, self.surface)
        }
        .call("vkGetPhysicalDeviceSurfaceCapabilitiesKHR")?;
        // SAFETY: as above.
        let formats = unsafe {
            self.surface_fn
                .get_physical_device_surface_formats(ctx.physical, self.surface)
        }
        .call("vkGetPhysicalDeviceSurfaceFormatsKHR")?;
        let format = formats
            .iter()
            .find(|f| {
                matches!(
                    f.format,
                    vk::Format::B8G8R8A8_SRGB | vk::Format::R8G8B8A8_SRGB
                ) && f.color_space == vk::ColorSpaceKHR::SRGB_NONLINEAR
            })
            .or(formats.first())
            .copied()
            .ok_or_else(|| GpuError::Other("the window surface offers no format".into()))?;
        let extent = if caps.current_extent.width != u32::MAX {
            caps.current_extent
        } else {
            vk::Extent2D {
                width: size
                    .0
                    .clamp(caps.min_image_extent.width, caps.max_image_extent.width),
                height: size
                    .1
                    .clamp(caps.min_image_extent.height, caps.max_image_extent.height),
            }
        };
        let mut count = caps.min_image_count + 1;
        if caps.max_image_count > 0 {
            count = count.min(caps.max_image_count);
        }
        let old = self.raw;
        let info = vk::SwapchainCreateInfoKHR::default()
            .surface(self.surface)
            .min_image_count(count)
            .image_format(format.format)
            .image_color_space(format.color_space)
            .image_extent(extent)
            .image_array_layers(1)
            .image_usage(vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSFER_SRC)
            .image_sharing_mode(vk::SharingMode::EXCLUSIVE)
            .pre_transform(caps.current_transform)
            .composite_alpha(vk::CompositeAlphaFlagsKHR::OPAQUE)
            .present_mode(vk::PresentModeKHR::FIFO)
            .clipped(true)
            .old_swapchain(old);
        // Attachments the device cannot allocate are one sentence, before anything is made.
        super::image::check_attachments(&ctx, extent.width, extent.height, self.samples)?;
        // SAFETY: valid surface; the old swapchain is retired by this call and idle.
        let raw = unsafe { self.swapchain_fn.create_swapchain(&info, None) }
            .call("vkCreateSwapchainKHR")?;
        self.destroy_dependents();
        if old != vk::SwapchainKHR::null() {
            // SAFETY: retired, idle (the caller waited).
            unsafe { self.swapchain_fn.destroy_swapchain(old, None) };
        }
        self.raw = raw;
        // SAFETY: swapchain just created.
        self.images = unsafe { self.swapchain_fn.get_swapchain_images(raw) }
            .call("vkGetSwapchainImagesKHR")?;
        for (i, &img) in self.images.iter().enumerate() {
            ctx.set_name(img, &format!("swapchain image {i}"));
            let view = create_view(&ctx, img, format.format, vk::ImageAspectFlags::COLOR)?;
            self.views.push(view);
        }
        self.depth = Some(Image::new(
            &ctx,
            ImageDesc::new_depth(extent).with_samples(self.samples),
            "swapchain depth",
        )?);
        if self.samples != vk::SampleCountFlags::TYPE_1 {
            self.msaa = Some(Image::new(
                &ctx,
                ImageDesc::new_msaa_color(extent, format.format, self.samples),
                "swapchain multisampled colour",
            )?);
        }
        self.format = format.format;
        self.extent = extent;
        log::debug!(
            "swapchain {}x{} {:?}, {} images",
            extent.width,
            extent.height,
            format.format,
            self.images.len()
        );
        Ok(())
    }

    fn destroy_dependents(&mut self) {
        for v in self.views.drain(..) {
            // SAFETY: views are idle (recreate and drop run after a device wait).
            unsafe { self.ctx.device.destroy_image_view(v, None) };
        }
        self.images.clear();
        self.depth = None;
        self.msaa = None;
    }

    /// Acquire the next image. `Ok(None)` means the swapchain is out of date: recreate it.
    pub fn acquire(&self, signal: vk::Semaphore) -> Result<Option<SwapchainFrame>, GpuError> {
        // SAFETY: valid swapchain; the semaphore is unsignalled with no pending wait.
        match unsafe {
            self.swapchain_fn
                .acquire_next_image(self.raw, u64::MAX, signal, vk::Fence::null())
        } {
            Ok((index, suboptimal)) => Ok(Some(SwapchainFrame {
                index,
                image: self.images[index as usize],
                view: self.views[index as usize],
                suboptimal,
            })),
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(None),
            Err(e) => Err(GpuError::Vk {
                call: "vkAcquireNextImageKHR",
                result: e,
            }),
        }
    }

    /// Present; returns whether the swapchain must be recreated.
    pub fn present(&self, index: u32, wait: vk::Semaphore) -> Result<bool, GpuError> {
        let swapchains = [self.raw];
        let indices = [index];
        let waits = [wait];
        let info = vk::PresentInfoKHR::default()
            .wait_semaphores(&waits)
            .swapchains(&swapchains)
            .image_indices(&indices);
        // SAFETY: image acquired from this swapchain; queue used from one thread.
        match unsafe { self.swapchain_fn.queue_present(self.ctx.queue, &info) } {
            Ok(suboptimal) => Ok(suboptimal),
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(true),
            Err(e) => Err(GpuError::Vk {
                call: "vkQueuePresentKHR",
                result: e,
            }),
        }
    }
}

impl Drop for Swapchain {
    fn drop(&mut self) {
        let _ = self.ctx.wait_idle();
        self.destroy_dependents();
        // SAFETY: idle device; swapchain before its surface.
        unsafe {
            self.swapchain_fn.destroy_swapchain(self.raw, None);
            self.surface_fn.destroy_surface(self.surface, None);
        }
        track_drop();
    }
}
