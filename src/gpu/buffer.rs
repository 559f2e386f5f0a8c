//! Buffers with gpu-allocator memory. Host-visible buffers are written and read through byte
//! slices and `bytemuck`; device-local buffers are filled through a staging copy.

use super::context::VkResultExt;
use super::{track_drop, track_new, CommandPool, Context, GpuError};
use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// What a buffer is for and where it lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BufferDesc {
    pub size: u64,
    pub usage: vk::BufferUsageFlags,
    pub location: MemoryLocation,
}

impl BufferDesc {
    /// Device-local, filled once through a staging copy (patterns, static vertex buffers).
    pub fn new_gpu_only(size: u64, usage: vk::BufferUsageFlags) -> Self {
        Self {
            size,
            usage: usage | vk::BufferUsageFlags::TRANSFER_DST,
            location: MemoryLocation::GpuOnly,
        }
    }
    /// Host-visible, written by the CPU every frame (records, uniforms).
    pub fn new_upload(size: u64, usage: vk::BufferUsageFlags) -> Self {
        Self {
            size,
            usage,
            location: MemoryLocation::CpuToGpu,
        }
    }
    /// Host-visible, read back by the CPU (capture, image readback).
    pub fn new_readback(size: u64, usage: vk::BufferUsageFlags) -> Self {
        Self {
            size,
            usage: usage | vk::BufferUsageFlags::TRANSFER_DST,
            location: MemoryLocation::GpuToCpu,
        }
    }
}

pub struct Buffer {
    ctx: Arc<Context>,
    pub raw: vk::Buffer,
    allocation: Option<Allocation>,
    pub desc: BufferDesc,
}

impl Buffer {
    pub fn new(ctx: &Arc<Context>, desc: BufferDesc, name: &str) -> Result<Self, GpuError> {
        let max = ctx.info.max_memory_allocation_size;
        if desc.size > max {
            return Err(GpuError::Other(format!(
                "buffer '{name}' needs {} bytes, over this device's maxMemoryAllocationSize ({max})",
                desc.size
            )));
        }
        let info = vk::BufferCreateInfo::default()
            .size(desc.size.max(4))
            .usage(desc.usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE);
        // SAFETY: valid device and create info.
        let raw = unsafe { ctx.device.create_buffer(&info, None) }.call("vkCreateBuffer")?;
        // SAFETY: buffer just created from this device.
        let requirements = unsafe { ctx.device.get_buffer_memory_requirements(raw) };
        let allocation = ctx.allocator().allocate(&AllocationCreateDesc {
            name,
            requirements,
            location: desc.location,
            linear: true,
            allocation_scheme: AllocationScheme::GpuAllocatorManaged,
        });
        let allocation = match allocation {
            Ok(a) => a,
            Err(e) => {
                // SAFETY: not bound, not in use.
                unsafe { ctx.device.destroy_buffer(raw, None) };
                return Err(GpuError::Alloc {
                    name: name.into(),
                    source: e,
                });
            }
        };
        // SAFETY: memory from the allocator satisfies the requirements; bound once.
        let bound = unsafe {
            ctx.device
                .bind_buffer_memory(raw, allocation.memory(), allocation.offset())
        };
        if let Err(e) = bound {
            let _ = ctx.allocator().free(allocation);
            // SAFETY: not in use.
            unsafe { ctx.device.destroy_buffer(raw, None) };
            return Err(GpuError::Vk {
                call: "vkBindBufferMemory",
                result: e,
            });
        }
        ctx.set_name(raw, name);
        track_new();
        Ok(Self {
            ctx: ctx.clone(),
            raw,
            allocation: Some(allocation),
            desc,
        })
    }

    /// A device-local buffer holding `data`, uploaded through a staging buffer and waited for.
    pub fn new_with_data<T: bytemuck::Pod>(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        usage: vk::BufferUsageFlags,
        data: &[T],
        name: &str,
    ) -> Result<Self, GpuError> {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        let buffer = Self::new(
            ctx,
            BufferDesc::new_gpu_only(bytes.len() as u64, usage),
            name,
        )?;
        let mut staging = Self::new(
            ctx,
            BufferDesc::new_upload(bytes.len() as u64, vk::BufferUsageFlags::TRANSFER_SRC),
            &format!("{name} (staging)"),
        )?;
        staging.write(0, bytes);
        pool.submit_and_wait(|cmd| cmd.copy_buffer(&staging, &buffer, bytes.len() as u64))?;
        Ok(buffer)
    }

    pub fn size(&self) -> u64 {
        self.desc.size
    }

    /// Mapped bytes of a host-visible buffer.
    pub fn mapped(&self) -> &[u8] {
        let slice = self
            .allocation
            .as_ref()
            .and_then(|a| a.mapped_slice())
            .expect("buffer is not host-visible");
        &slice[..self.desc.size as usize]
    }

    /// Write `bytes` at `offset` into a host-visible buffer.
    pub fn write(&mut self, offset: usize, bytes: &[u8]) {
        let size = self.desc.size as usize;
        let slice = self
            .allocation
            .as_mut()
            .and_then(|a| a.mapped_slice_mut())
            .expect("buffer is not host-visible");
        slice[..size][offset..offset + bytes.len()].copy_from_slice(bytes);
        self.ctx.count_host_bytes(bytes.len());
    }

    /// Write a slice of `Pod` values at byte `offset`.
    pub fn write_pod<T: bytemuck::Pod>(&mut self, offset: usize, data: &[T]) {
        self.write(offset, bytemuck::cast_slice(data));
    }

    /// Copy of the contents as `T`s (host-visible buffers).
    pub fn read_pod<T: bytemuck::Pod>(&self) -> Vec<T> {
        let bytes = self.mapped();
        let n = bytes.len() / std::mem::size_of::<T>();
        bytemuck::pod_collect_to_vec(&bytes[..n * std::mem::size_of::<T>()])
    }
}

impl Drop for Buffer {
    fn drop(&mut self) {
        // SAFETY: owners only drop buffers that no pending GPU work uses (see module docs).
        unsafe { self.ctx.device.destroy_buffer(self.raw, None) };
        if let Some(a) = self.allocation.take() {
            let _ = self.ctx.allocator().free(a);
        }
        track_drop();
    }
}

/// A typed view of a buffer, for a texel-buffer descriptor (`samplerBuffer` in GLSL).
pub struct BufferView {
    ctx: Arc<Context>,
    pub raw: vk::BufferView,
}

impl BufferView {
    /// The whole of `buffer` as texels of `format`.
    pub fn new(
        ctx: &Arc<Context>,
        buffer: &Buffer,
        format: vk::Format,
        name: &str,
    ) -> Result<Self, GpuError> {
        Self::span(ctx, buffer, format, (0, vk::WHOLE_SIZE), name)
    }

    /// `range` bytes of `buffer` from `offset` as texels of `format` (the offset a multiple of
    /// minTexelBufferOffsetAlignment, the range of the texel size and at most
    /// maxTexelBufferElements of them).
    pub fn span(
        ctx: &Arc<Context>,
        buffer: &Buffer,
        format: vk::Format,
        (offset, range): (u64, u64),
        name: &str,
    ) -> Result<Self, GpuError> {
        let info = vk::BufferViewCreateInfo::default()
            .buffer(buffer.raw)
            .format(format)
            .offset(offset)
            .range(range);
        // SAFETY: the buffer outlives the view (its owner keeps both and drops the view first).
        let raw =
            unsafe { ctx.device.create_buffer_view(&info, None) }.call("vkCreateBufferView")?;
        ctx.set_name(raw, name);
        track_new();
        Ok(Self {
            ctx: ctx.clone(),
            raw,
        })
    }
}

impl Drop for BufferView {
    fn drop(&mut self) {
        // SAFETY: no pending GPU work uses the view.
        unsafe { self.ctx.device.destroy_buffer_view(self.raw, None) };
        track_drop();
    }
}
