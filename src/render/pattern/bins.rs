//! The adaptive pattern driver's draws without a readback: the patterns it draws from, the
//! indirect commands and bins glsl/pattern/bins.comp writes from the levels buffer each frame,
//! and whether a device can hold them.

use super::super::{GpuMesh, RenderError};
use crate::gpu::shaders::names;
use crate::gpu::{
    vk, Buffer, BufferDesc, Cmd, CommandPool, Context, DescriptorPool, DescriptorSetLayout,
    Pipeline, PipelineLayout,
};
use crate::pattern::adaptive::{Hierarchy, IntegerPatterns};
use bytemuck::{Pod, Zeroable};
use std::sync::Arc;

/// Whether this device can hold the adaptive draws of `elements` elements in chunks of `chunk`
/// at largest level `level` (a power of two): the bins pass binds its commands and lists whole,
/// so each must fit maxStorageBufferRange and one allocation. Nothing else is asked of the
/// device: the draws are core `vkCmdDrawIndexedIndirect` with a draw count of 1 and
/// `firstInstance` 0 (neither multiDrawIndirect nor drawIndirectFirstInstance).
pub fn check_adaptive_fits(
    ctx: &Context,
    elements: u32,
    chunk: u32,
    level: u32,
    dyadic: bool,
) -> Result<(), RenderError> {
    let limits = &ctx.info.limits;
    let range = limits.max_storage_buffer_range as u64;
    let (max, limit) = if ctx.info.max_memory_allocation_size < range {
        (
            ctx.info.max_memory_allocation_size,
            "maxMemoryAllocationSize",
        )
    } else {
        (range, "maxStorageBufferRange")
    };
    check_integer_levels(level, dyadic)?;
    let needed = adaptive_need(elements, chunk, level, dyadic);
    if needed > max {
        // Smaller record chunks (a smaller maxStorageBufferRange makes them) take more bins,
        // so the sentence names them where the mesh is split.
        let chunked = if chunk < elements {
            format!(" in chunks of {chunk}")
        } else {
            String::new()
        };
        let mut remedies = Vec::new();
        if let Some(l) = fitting_level(max, elements, chunk, level, dyadic) {
            remedies.push(format!("use --max-level {l}"));
        }
        // Integer levels bin by every level, powers of two by a few.
        if !dyadic && adaptive_need(elements, chunk, level, true) <= max {
            remedies.push("use --geomorph on".into());
        }
        match fitting_elements(max, chunk, level, dyadic) {
            0 => {}
            1 => remedies.push("draw one element adaptively".into()),
            fits => remedies.push(format!("draw at most about {fits} elements adaptively")),
        }
        remedies.push("draw uniformly".into());
        let last = remedies.pop().unwrap_or_default();
        let remedy = match remedies.len() {
            0 => last,
            _ => format!("{}, or {last}", remedies.join(", ")),
        };
        return Err(RenderError::OverLimit {
            what: format!(
                "drawing {elements} elements{chunked} adaptively up to level {level} (indirect commands and bins)"
            ),
            needed,
            unit: "bytes",
            limit,
            max,
            remedy,
        });
    }
    Ok(())
}

/// The larger of the commands' and the bin lists' bytes ([`adaptive_bytes`]): what one
/// buffer must hold.
fn adaptive_need(elements: u32, chunk: u32, level: u32, dyadic: bool) -> u64 {
    let (commands, lists) = adaptive_bytes(elements, chunk, level, dyadic);
    commands.max(lists)
}

/// The largest power of two below `level` (the pattern driver's largest level is one, drawn
/// dyadic or at integer levels) at which `elements` in chunks of `chunk` fit `max` bytes, if
/// one does.
fn fitting_level(max: u64, elements: u32, chunk: u32, level: u32, dyadic: bool) -> Option<u32> {
    (0..level.trailing_zeros())
        .rev()
        .map(|k| 1 << k)
        .find(|&l| adaptive_need(elements, chunk, l, dyadic) <= max)
}

/// The most elements, in chunks of `chunk`, whose draws up to `level` fit `max` bytes (0 if
/// not even one's do).
fn fitting_elements(max: u64, chunk: u32, level: u32, dyadic: bool) -> u64 {
    let fits = |n: u32| adaptive_need(n, chunk, level, dyadic) <= max;
    if !fits(1) {
        return 0;
    }
    // The bytes grow with the elements: bisect between one that fits and one past it.
    let (mut lo, mut hi) = (1u64, u32::MAX as u64 + 1);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if fits(mid as u32) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// Whether the pattern driver can draw integer levels (`dyadic` false) up to `level`, the
/// largest an element is drawn at: `INTEGER_MAX_LEVEL` (128) at most (`info` asks as render
/// does).
pub fn check_integer_levels(level: u32, dyadic: bool) -> Result<(), RenderError> {
    if !dyadic && level > INTEGER_MAX_LEVEL {
        return Err(RenderError::Incompatible(format!(
            "drawing integer levels without geomorphing takes one pattern per level, at most up to level {INTEGER_MAX_LEVEL}, not {level}: use --geomorph on, or --max-level {INTEGER_MAX_LEVEL} or a smaller power of two"
        )));
    }
    Ok(())
}

/// The largest level of the integer patterns: they hold every level's vertices and triangles,
/// growing with the cube of the largest (at 128, 4.4 MB of vertices and 8.4 MB of indices; at
/// 1024, over 2 GiB of vertices and 4 GiB of indices).
pub const INTEGER_MAX_LEVEL: u32 = 128;

/// The levels an adaptive draw bins by at largest level `level`: the hierarchy's `2^l`,
/// `l = 0..=L` where `dyadic`, else every level `1..=level`.
fn bins_per_chunk(level: u32, dyadic: bool) -> u32 {
    if dyadic {
        level.trailing_zeros() + 1
    } else {
        level
    }
}

/// Blocks of [`BLOCK`] elements in a chunk of `chunk` of a mesh of `elements`.
fn blocks_per_chunk(elements: u32, chunk: u32) -> u32 {
    chunk.min(elements.max(1)).div_ceil(BLOCK)
}

/// Bytes of the adaptive draws' commands and bin lists.
fn adaptive_bytes(elements: u32, chunk: u32, level: u32, dyadic: bool) -> (u64, u64) {
    let n = elements.max(1) as u64;
    let levels = bins_per_chunk(level, dyadic) as u64;
    let bins = n.div_ceil(chunk.max(1) as u64) * levels;
    ((n + bins) * COMMAND_BYTES, levels * n * 4)
}

/// Bytes of one `VkDrawIndexedIndirectCommand`.
const COMMAND_BYTES: u64 = 20;

/// Elements, blocks or bins one dispatch of the bins pass covers.
const BINS_PER_DISPATCH: u32 = 64 * 65_535;

/// Elements a block of the bins pass ranks in order (phase 2 of glsl/pattern/bins.comp).
const BLOCK: u32 = 64;

/// `Push` of glsl/pattern/bins.comp.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct BinsPush {
    phase: u32,
    first: u32,
    end: u32,
    f: u32,
    n: u32,
    chunk: u32,
    dyadic: u32,
    lo: u32,
    hi: u32,
    blocks_per_chunk: u32,
}

/// What drawing one mesh's elements adaptively at largest level `f` needs: the patterns (at
/// dyadic levels, the finest level's vertices in hierarchical order and each level's index
/// range into them, [`Hierarchy`]; at integer levels, every level's own vertices and
/// triangles), the indirect commands and bins
/// the pass glsl/pattern/bins.comp writes from the levels buffer each frame, and that pass.
/// Built by [`super::PatternDriver`]'s `prepare` for a level that is a power of two.
pub struct AdaptivePattern {
    pub level: u32,
    /// Levels are powers of two (geomorphing), else any integer.
    pub dyadic: bool,
    /// The hierarchy's vertices (dyadic) or the integer patterns'.
    pub vertices: Buffer,
    /// Every level's triangles: dyadic, indexing the hierarchy's vertices (a level its first
    /// ones); integer, each level's own (drawn with its vertex offset).
    pub indices: Buffer,
    /// Per element one command (`push`, `ubo`), then per chunk and level one bin's command.
    pub commands: Buffer,
    /// Each bin's elements, in element order: level `l`, chunk `c` from entry `l n + c chunk`.
    pub lists: Buffer,
    /// Each element's rank among its block's at its level, and each block's count (then
    /// offset) per level: what puts the lists in element order.
    _ranks: Buffer,
    _blocks: Buffer,
    elements: u32,
    chunk: u32,
    chunks: u32,
    set: vk::DescriptorSet,
    _pool: DescriptorPool,
    pipeline: Pipeline,
    layout: PipelineLayout,
    _set_layout: DescriptorSetLayout,
}

impl AdaptivePattern {
    /// For `mesh`'s elements at largest level `f` (a power of two), at powers of two where
    /// `dyadic`, else at integer levels.
    pub fn new(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        mesh: &GpuMesh,
        f: u32,
        dyadic: bool,
    ) -> Result<Self, RenderError> {
        use vk::BufferUsageFlags as U;
        let n = mesh.element_count.max(1);
        let chunks = n.div_ceil(mesh.chunk);
        let (vertices, indices) = if dyadic {
            let hierarchy = Hierarchy::new(f);
            let name = format!("hierarchical patterns up to {f}");
            let vertices =
                Buffer::new_with_data(ctx, pool, U::VERTEX_BUFFER, &hierarchy.bary, &name)?;
            let indices =
                Buffer::new_with_data(ctx, pool, U::INDEX_BUFFER, &hierarchy.indices, &name)?;
            (vertices, indices)
        } else {
            let p = IntegerPatterns::new(f);
            let name = format!("integer patterns up to {f}");
            let vertices = Buffer::new_with_data(ctx, pool, U::VERTEX_BUFFER, &p.bary, &name)?;
            let indices = Buffer::new_with_data(ctx, pool, U::INDEX_BUFFER, &p.indices, &name)?;
            (vertices, indices)
        };
        let (command_bytes, list_bytes) = adaptive_bytes(n, mesh.chunk, f, dyadic);
        let commands = Buffer::new(
            ctx,
            // (read back by tests)
            BufferDesc::new_gpu_only(
                command_bytes,
                U::STORAGE_BUFFER | U::INDIRECT_BUFFER | U::TRANSFER_SRC,
            ),
            "adaptive pattern commands",
        )?;
        let lists = Buffer::new(
            ctx,
            BufferDesc::new_gpu_only(
                list_bytes,
                U::STORAGE_BUFFER | U::VERTEX_BUFFER | U::TRANSFER_SRC,
            ),
            "adaptive pattern bins",
        )?;
        // Never larger than the lists (a block holds at least one element, a list entry each).
        let block_bytes = chunks as u64
            * blocks_per_chunk(n, mesh.chunk) as u64
            * bins_per_chunk(f, dyadic) as u64
            * 4;
        let ranks = Buffer::new(
            ctx,
            BufferDesc::new_gpu_only(n as u64 * 4, U::STORAGE_BUFFER),
            "adaptive pattern ranks",
        )?;
        let blocks = Buffer::new(
            ctx,
            BufferDesc::new_gpu_only(block_bytes, U::STORAGE_BUFFER),
            "adaptive pattern blocks",
        )?;
        let c = vk::ShaderStageFlags::COMPUTE;
        let t = vk::DescriptorType::STORAGE_BUFFER;
        // The device check at start-up asks for at least this many storage buffers a stage.
        const _: () = assert!(BINS_STORAGE_BUFFERS <= crate::gpu::STORAGE_BUFFERS_PER_STAGE);
        let bindings: Vec<_> = (0..BINS_STORAGE_BUFFERS).map(|b| (b, t, c)).collect();
        let set_layout = DescriptorSetLayout::new(ctx, &bindings, "pattern bins set")?;
        let layout = PipelineLayout::new(
            ctx,
            &[&set_layout],
            std::mem::size_of::<BinsPush>() as u32,
            c,
            "pattern bins",
        )?;
        let pipeline =
            Pipeline::new_compute(ctx, &layout, names::PATTERN_BINS_COMP, "pattern bins")?;
        let dpool = DescriptorPool::new(
            ctx,
            1,
            &[(t, BINS_STORAGE_BUFFERS)],
            "pattern bins descriptors",
        )?;
        let set = dpool.allocate(&set_layout, "pattern bins set")?;
        let buffers = [&mesh.levels, &commands, &lists, &ranks, &blocks];
        for (b, buffer) in buffers.into_iter().enumerate() {
            dpool.write_buffer(set, b as u32, t, buffer.raw, vk::WHOLE_SIZE);
        }
        Ok(Self {
            level: f,
            dyadic,
            vertices,
            indices,
            commands,
            lists,
            _ranks: ranks,
            _blocks: blocks,
            elements: n,
            chunk: mesh.chunk,
            chunks,
            set,
            _pool: dpool,
            pipeline,
            layout,
            _set_layout: set_layout,
        })
    }

    /// Bins per chunk: levels in the hierarchy (`L + 1`), or every integer level.
    pub fn levels(&self) -> u32 {
        bins_per_chunk(self.level, self.dyadic)
    }

    /// Record the bins pass for `elements`: the bins' commands, each element's command, then
    /// the bins' lists in element order (glsl/pattern/bins.comp, phases 0 to 4); barriers
    /// before (earlier draws read the same buffers), between the phases and after (the draws
    /// read them: indirect commands, vertex input, vertex stage).
    pub fn cmd_bins(&self, cmd: &Cmd<'_>, elements: std::ops::Range<u32>) {
        cmd.barrier_to_compute();
        cmd.bind_compute_pipeline(self.pipeline.raw);
        cmd.bind_compute_descriptor_set(self.layout.raw, 0, self.set);
        let bins = self.chunks * self.levels();
        let per_chunk = blocks_per_chunk(self.elements, self.chunk);
        let phases = [
            (0, 0..bins),
            (1, elements.clone()),
            (2, 0..self.chunks * per_chunk),
            (3, 0..bins),
            (4, elements.clone()),
        ];
        for (phase, range) in phases {
            let mut first = range.start;
            while first < range.end {
                let end = range.end.min(first + BINS_PER_DISPATCH);
                let push = BinsPush {
                    phase,
                    first,
                    end,
                    f: self.level,
                    n: self.elements,
                    chunk: self.chunk,
                    dyadic: self.dyadic as u32,
                    lo: elements.start,
                    hi: elements.end,
                    blocks_per_chunk: per_chunk,
                };
                cmd.push_constants(
                    self.layout.raw,
                    vk::ShaderStageFlags::COMPUTE,
                    0,
                    bytemuck::bytes_of(&push),
                );
                cmd.dispatch((end - first).div_ceil(64), 1, 1);
                first = end;
            }
            if phase < 4 {
                cmd.barrier_to_compute();
            }
        }
        cmd.barrier_compute_to_indirect();
    }

    /// Byte offset of element `e`'s command.
    pub(super) fn element_command(&self, e: u32) -> u64 {
        e as u64 * COMMAND_BYTES
    }

    /// Byte offset of the bin of the chunk starting at element `base` and bin `l` (level `2^l`,
    /// or `l + 1` at integer levels).
    pub fn bin_command(&self, base: u32, l: u32) -> u64 {
        let bin = (base / self.chunk) * self.levels() + l;
        (self.elements as u64 + bin as u64) * COMMAND_BYTES
    }

    /// Byte offset of that bin's element list.
    pub fn bin_list(&self, base: u32, l: u32) -> u64 {
        (l as u64 * self.elements as u64 + base as u64) * 4
    }
}

/// The bins pass's storage buffers (glsl/pattern/bins.comp): the levels, the commands, the bins'
/// lists, the ranks and the blocks.
const BINS_STORAGE_BUFFERS: u32 = 5;

#[cfg(test)]
mod tests {
    use super::*;

    /// The bytes docs/cli.md ("Size limits") quotes per element, counted from what the lists
    /// and commands hold: a 4-byte slot per element in each level's bin (powers of two up to 64:
    /// 1, 2, 4, ..., 64, seven bins; integer levels: 64 bins), and a 20-byte command per
    /// element plus one per bin of each chunk.
    #[test]
    fn adaptive_bytes_are_the_documented_slots_and_commands() {
        let n = 1_000_000u32;
        let chunk = 1_198_372; // lavapipe's records per chunk: one chunk here
        let (commands, lists) = adaptive_bytes(n, chunk, 64, true);
        assert_eq!(lists, 28 * n as u64);
        assert_eq!(commands, 20 * (n as u64 + 7));
        let (commands, lists) = adaptive_bytes(n, chunk, 64, false);
        assert_eq!(lists, 256 * n as u64);
        assert_eq!(commands, 20 * (n as u64 + 64));
        // All at level 1: the commands, 20 bytes an element, are what counts.
        let (commands, lists) = adaptive_bytes(n, chunk, 1, true);
        assert_eq!((commands, lists), (20 * (n as u64 + 1), 4 * n as u64));
        // Chunks of 1000: a bin per level in each.
        let (commands, _) = adaptive_bytes(n, 1000, 64, true);
        assert_eq!(commands, 20 * (n as u64 + 1000 * 7));
        // The elements lavapipe's 128 MiB holds, as the docs say: about 4.8 million while
        // geomorphing, 520,000 at integer levels, 6.7 million all at level 1.
        let range = 128u64 << 20;
        let fits = |n: u32, level: u32, dyadic: bool| {
            let (commands, lists) = adaptive_bytes(n, chunk, level, dyadic);
            commands.max(lists) <= range
        };
        assert!(fits(4_790_000, 64, true) && !fits(4_800_000, 64, true));
        assert!(fits(524_000, 64, false) && !fits(525_000, 64, false));
        assert!(fits(6_700_000, 1, true) && !fits(6_720_000, 1, true));
    }

    /// What a refusal offers fits, and one more element or the next level up does not, with
    /// the commands' share of small chunks counted.
    #[test]
    fn refusals_offer_what_fits() {
        for (max, chunk, level, dyadic) in [
            (7_000u64, 62u32, 64u32, true),
            (7_920, 70, 64, true),
            (128 << 20, 1_198_372, 64, true),
            (100_000, 40, 64, false),
        ] {
            let n = fitting_elements(max, chunk, level, dyadic);
            assert!(n > 0);
            assert!(adaptive_need(n as u32, chunk, level, dyadic) <= max);
            assert!(adaptive_need(n as u32 + 1, chunk, level, dyadic) > max);
            let elements = n as u32 + 1;
            let l = fitting_level(max, elements, chunk, level, dyadic).unwrap();
            assert!(adaptive_need(elements, chunk, l, dyadic) <= max);
            assert!(l.is_power_of_two());
            assert!(2 * l == level || adaptive_need(elements, chunk, 2 * l, dyadic) > max);
        }
        // Small chunks: their bins' commands, not the lists, are what does not fit.
        assert!(fitting_elements(7_000, 15, 64, true) < 7_000 / 28);
        assert_eq!(fitting_elements(10, 15, 64, true), 0);
        assert_eq!(fitting_level(10, 1, 1, 64, true), None);
    }
}
