//! Images with views, and the offscreen colour + depth target of headless rendering.

use super::context::VkResultExt;
use super::{track_drop, track_new, Buffer, BufferDesc, CommandPool, Context, GpuError};
use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ImageDesc {
    pub extent: vk::Extent2D,
    pub format: vk::Format,
    pub usage: vk::ImageUsageFlags,
    pub aspect: vk::ImageAspectFlags,
    /// Samples per pixel (multisampled attachments are resolved, never read back).
    pub samples: vk::SampleCountFlags,
}

impl ImageDesc {
    pub fn new_color(extent: vk::Extent2D, format: vk::Format) -> Self {
        Self {
            extent,
            format,
            usage: vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSFER_SRC,
            aspect: vk::ImageAspectFlags::COLOR,
            samples: vk::SampleCountFlags::TYPE_1,
        }
    }
    /// A multisampled colour attachment, resolved into a single-sampled image at the end of
    /// the rendering instance.
    pub fn new_msaa_color(
        extent: vk::Extent2D,
        format: vk::Format,
        samples: vk::SampleCountFlags,
    ) -> Self {
        Self {
            usage: vk::ImageUsageFlags::COLOR_ATTACHMENT,
            samples,
            ..Self::new_color(extent, format)
        }
    }
    pub fn new_depth(extent: vk::Extent2D) -> Self {
        Self {
            extent,
            format: DEPTH_FORMAT,
            usage: vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT,
            aspect: vk::ImageAspectFlags::DEPTH,
            samples: vk::SampleCountFlags::TYPE_1,
        }
    }
    /// The same with `samples` per pixel.
    pub fn with_samples(self, samples: vk::SampleCountFlags) -> Self {
        Self { samples, ..self }
    }
}

/// Depth format used by every target (mandatory for depth attachments in Vulkan).
pub const DEPTH_FORMAT: vk::Format = vk::Format::D32_SFLOAT;

pub struct Image {
    ctx: Arc<Context>,
    pub raw: vk::Image,
    pub view: vk::ImageView,
    allocation: Option<Allocation>,
    pub desc: ImageDesc,
}

impl Image {
    pub fn new(ctx: &Arc<Context>, desc: ImageDesc, name: &str) -> Result<Self, GpuError> {
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_2D)
            .format(desc.format)
            .extent(vk::Extent3D {
                width: desc.extent.width,
                height: desc.extent.height,
                depth: 1,
            })
            .mip_levels(1)
            .array_layers(1)
            .samples(desc.samples)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(desc.usage)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        // SAFETY: valid device and create info.
        let raw = unsafe { ctx.device.create_image(&info, None) }.call("vkCreateImage")?;
        // SAFETY: image from this device.
        let requirements = unsafe { ctx.device.get_image_memory_requirements(raw) };
        let max = ctx.info.max_memory_allocation_size;
        if requirements.size > max {
            // SAFETY: not bound, not in use.
            unsafe { ctx.device.destroy_image(raw, None) };
            return Err(GpuError::Other(format!(
                "image '{name}' needs {} bytes, over this device's maxMemoryAllocationSize ({max})",
                requirements.size
            )));
        }
        let allocation = match ctx.allocator().allocate(&AllocationCreateDesc {
            name,
            requirements,
            location: MemoryLocation::GpuOnly,
            linear: false,
            allocation_scheme: AllocationScheme::GpuAllocatorManaged,
        }) {
            Ok(a) => a,
            Err(e) => {
                // SAFETY: unused image.
                unsafe { ctx.device.destroy_image(raw, None) };
                return Err(GpuError::Alloc {
                    name: name.into(),
                    source: e,
                });
            }
        };
        // SAFETY: memory satisfies the requirements; bound once.
        if let Err(e) = unsafe {
            ctx.device
                .bind_image_memory(raw, allocation.memory(), allocation.offset())
        } {
            let _ = ctx.allocator().free(allocation);
            // SAFETY: unused image.
            unsafe { ctx.device.destroy_image(raw, None) };
            return Err(GpuError::Vk {
                call: "vkBindImageMemory",
                result: e,
            });
        }
        let view = match create_view(ctx, raw, desc.format, desc.aspect) {
            Ok(v) => v,
            Err(e) => {
                let _ = ctx.allocator().free(allocation);
                // SAFETY: unused image.
                unsafe { ctx.device.destroy_image(raw, None) };
                return Err(e);
            }
        };
        ctx.set_name(raw, name);
        ctx.set_name(view, &format!("{name} view"));
        track_new();
        Ok(Self {
            ctx: ctx.clone(),
            raw,
            view,
            allocation: Some(allocation),
            desc,
        })
    }
}

/// A 2D view of the whole image (also used for swapchain images).
pub(crate) fn create_view(
    ctx: &Context,
    image: vk::Image,
    format: vk::Format,
    aspect: vk::ImageAspectFlags,
) -> Result<vk::ImageView, GpuError> {
    let info = vk::ImageViewCreateInfo::default()
        .image(image)
        .view_type(vk::ImageViewType::TYPE_2D)
        .format(format)
        .subresource_range(subresource(aspect));
    // SAFETY: image from this device.
    unsafe { ctx.device.create_image_view(&info, None) }.call("vkCreateImageView")
}

pub(crate) fn subresource(aspect: vk::ImageAspectFlags) -> vk::ImageSubresourceRange {
    vk::ImageSubresourceRange::default()
        .aspect_mask(aspect)
        .level_count(1)
        .layer_count(1)
}

impl Drop for Image {
    fn drop(&mut self) {
        // SAFETY: not in use by pending work (see module docs of gpu).
        unsafe {
            self.ctx.device.destroy_image_view(self.view, None);
            self.ctx.device.destroy_image(self.raw, None);
        }
        if let Some(a) = self.allocation.take() {
            let _ = self.ctx.allocator().free(a);
        }
        track_drop();
    }
}

/// RGBA8 pixels read back from a target.
#[derive(Clone, Debug, PartialEq)]
pub struct Readback {
    pub width: u32,
    pub height: u32,
    /// Tightly packed RGBA8, row-major, top row first.
    pub rgba: Vec<u8>,
}

impl Readback {
    /// Write as a PNG file, replacing what was there only once the whole image is written
    /// ([`crate::paths::write_output`]).
    pub fn save_png(&self, path: &std::path::Path) -> std::io::Result<()> {
        crate::paths::write_output(path, |file| self.encode_png(file))
    }

    fn encode_png(&self, file: &mut dyn std::io::Write) -> std::io::Result<()> {
        let mut enc = png::Encoder::new(file, self.width, self.height);
        enc.set_color(png::ColorType::Rgba);
        enc.set_depth(png::BitDepth::Eight);
        // Rendered images are mostly flat background and smooth gradients: adaptive filtering
        // and the best compression keep them small (the gallery is made of them).
        enc.set_compression(png::Compression::Best);
        enc.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
        let mut w = enc.write_header().map_err(std::io::Error::other)?;
        w.write_image_data(&self.rgba)
            .map_err(std::io::Error::other)?;
        w.finish().map_err(std::io::Error::other)
    }
}

/// Offscreen colour + depth images for headless rendering, with a readback buffer. With
/// multisampling, `msaa` is the multisampled colour attachment (and `depth` is multisampled
/// too), resolved into `color` at the end of the frame; `color` is what is read back.
pub struct OffscreenTarget {
    pub color: Image,
    pub msaa: Option<Image>,
    pub depth: Image,
    readback: Buffer,
}

/// Colour format of offscreen targets (stored as sRGB so PNGs look like the window).
pub const OFFSCREEN_FORMAT: vk::Format = vk::Format::R8G8B8A8_SRGB;

impl OffscreenTarget {
    pub fn new(ctx: &Arc<Context>, width: u32, height: u32) -> Result<Self, GpuError> {
        Self::multisampled(ctx, width, height, vk::SampleCountFlags::TYPE_1)
    }

    /// The target with `samples` per pixel (checked by [`sample_count`]).
    pub fn multisampled(
        ctx: &Arc<Context>,
        width: u32,
        height: u32,
        samples: vk::SampleCountFlags,
    ) -> Result<Self, GpuError> {
        check_attachments(ctx, width, height, samples)?;
        let extent = vk::Extent2D { width, height };
        let color = Image::new(
            ctx,
            ImageDesc::new_color(extent, OFFSCREEN_FORMAT),
            "offscreen colour",
        )?;
        let msaa = if samples == vk::SampleCountFlags::TYPE_1 {
            None
        } else {
            Some(Image::new(
                ctx,
                ImageDesc::new_msaa_color(extent, OFFSCREEN_FORMAT, samples),
                "offscreen multisampled colour",
            )?)
        };
        let depth = Image::new(
            ctx,
            ImageDesc::new_depth(extent).with_samples(samples),
            "offscreen depth",
        )?;
        let readback = Buffer::new(
            ctx,
            BufferDesc::new_readback(
                width as u64 * height as u64 * 4,
                vk::BufferUsageFlags::empty(),
            ),
            "offscreen readback",
        )?;
        Ok(Self {
            color,
            msaa,
            depth,
            readback,
        })
    }

    pub fn extent(&self) -> vk::Extent2D {
        self.color.desc.extent
    }

    /// Copy the colour image (in TRANSFER_SRC_OPTIMAL layout) to host memory.
    pub fn read(&self, pool: &CommandPool) -> Result<Readback, GpuError> {
        let extent = self.extent();
        pool.submit_and_wait(|cmd| {
            cmd.copy_image_to_buffer(self.color.raw, extent, &self.readback);
            cmd.barrier_to_host();
        })?;
        Ok(Readback {
            width: extent.width,
            height: extent.height,
            rgba: self.readback.mapped().to_vec(),
        })
    }
}

/// The sample counts `--msaa` accepts.
pub const MSAA_COUNTS: [u32; 4] = [1, 2, 4, 8];

/// Whether attachments of `width` x `height` at `samples` per pixel fit the device: each side
/// within `maxImageDimension2D`, and each attachment (4 bytes a sample: RGBA8, BGRA8, D32) one
/// allocation within `maxMemoryAllocationSize`. Refused here in one sentence, before any
/// Vulkan object is made, rather than by the allocator (and the validation layer) later:
/// offscreen targets and the window's swapchain alike.
pub fn check_attachments(
    ctx: &Context,
    width: u32,
    height: u32,
    samples: vk::SampleCountFlags,
) -> Result<(), GpuError> {
    let max = ctx.info.limits.max_image_dimension2_d;
    if width == 0 || height == 0 || width > max || height > max {
        return Err(GpuError::Other(format!(
            "image size {width}x{height} is outside what the device supports (1..={max} per side)"
        )));
    }
    let n = samples.as_raw().max(1) as u64;
    let bytes = width as u64 * height as u64 * 4 * n;
    let max_bytes = ctx.info.max_memory_allocation_size;
    if bytes > max_bytes {
        // In MiB to a tenth, the need rounded up and the limit down (so that they never
        // read alike), or in bytes under 1 MiB.
        let (need, max) = if max_bytes >= 1 << 20 {
            let tenths = |b: u64, up: bool| {
                let t = if up {
                    (b * 10).div_ceil(1 << 20)
                } else {
                    (b * 10) >> 20
                };
                match t % 10 {
                    0 => format!("{} MiB", t / 10),
                    d => format!("{}.{d} MiB", t / 10),
                }
            };
            (tenths(bytes, true), tenths(max_bytes, false))
        } else {
            (format!("{bytes} bytes"), format!("{max_bytes} bytes"))
        };
        let remedy = if n > 1 {
            "fewer samples per pixel (--msaa) or a smaller image fits"
        } else {
            "a smaller image fits"
        };
        return Err(GpuError::Other(format!(
            "a {width}x{height} image at {n} sample(s) per pixel needs {need} per attachment, over the {max} this device allocates at once (maxMemoryAllocationSize): {remedy}",
        )));
    }
    Ok(())
}

/// The sample count for `requested` samples per pixel (`None`: 4 where the device supports it
/// for both colour and depth attachments, else the largest it supports), or one sentence
/// saying why the device cannot.
pub fn sample_count(
    ctx: &Context,
    requested: Option<u32>,
) -> Result<vk::SampleCountFlags, GpuError> {
    let limits = &ctx.info.limits;
    let supported = limits.framebuffer_color_sample_counts & limits.framebuffer_depth_sample_counts;
    let flag = |n: u32| vk::SampleCountFlags::from_raw(n);
    match requested {
        None => Ok([4, 8, 2, 1]
            .into_iter()
            .map(flag)
            .find(|&f| supported.contains(f))
            .unwrap_or(vk::SampleCountFlags::TYPE_1)),
        Some(n) if !MSAA_COUNTS.contains(&n) => Err(GpuError::Other(format!(
            "--msaa {n} is not one of 1, 2, 4, 8"
        ))),
        Some(n) if supported.contains(flag(n)) => Ok(flag(n)),
        Some(n) => {
            let offered: Vec<String> = MSAA_COUNTS
                .iter()
                .filter(|&&c| supported.contains(flag(c)))
                .map(|c| c.to_string())
                .collect();
            Err(GpuError::Other(format!(
                "--msaa {n} is not supported by {} for colour and depth attachments (it offers {})",
                ctx.info.name,
                offered.join(", ")
            )))
        }
    }
}
