//! The `loop` surface on the GPU: the one place Loop's CPU data ([`crate::subdiv`]: M0 -> M1
//! entries, M1's one-rings, per-face words, control points and the packed basis function tables)
//! becomes GPU buffers, as OpenSubdiv's `GLPatchTable::Create` is for its far tables, and where
//! the passes that make M1 each frame are recorded.
//!
//! The Loop step M0 -> M1 on the GPU (Holländer & Boubekeur 2010): the computational entries
//! ([`crate::subdiv::stencils`]) are uploaded once per topology; every frame only M0's positions
//! are uploaded (bytes independent of the refinement level) and a compute pass applies the
//! entries, a second pass computes M1's one-ring normals, and barriers make both visible to the
//! draws. The tables the draws read are uploaded here too ([`LoopPass`]); [`LoopScene`] is a
//! scene's loop surface: its data, passes and M1-face records on the GPU.

use super::bindings::*;
use super::gpu_mesh::{Extras, GpuMesh, Patterns};
use super::scene::Scene;
use super::MeshData;
use super::RenderError;
use crate::gpu::{
    vk, Buffer, BufferDesc, Cmd, CommandPool, Context, DescriptorPool, DescriptorSetLayout,
    Pipeline, PipelineLayout,
};
use crate::subdiv::bft::{progress_line, Lattice};
use crate::subdiv::{LoopData, LoopFrame, Stencil};
use crate::surface::{BuildOptions, PrePass, RecordKind};
use glam::Vec3;
use std::sync::Arc;

/// Invocations per workgroup (`local_size_x` of loop_step.comp).
const GROUP: u32 = 64;

pub struct LoopPass {
    /// M1 positions and normals (`vec4`), written by the passes, read by the draws.
    pub m1: Buffer,
    pub n1: Buffer,
    /// The draws' tables: per-face entries, control points, the tables' rows and their maps.
    pub faces: Buffer,
    pub control: Buffer,
    pub tables: Buffer,
    pub table_rows: Buffer,
    m0: Buffer,
    _offsets: Buffer,
    _entries: Buffer,
    _ring_offsets: Buffer,
    _rings: Buffer,
    step: Pipeline,
    normals: Pipeline,
    pipeline_layout: PipelineLayout,
    _pool: DescriptorPool,
    set: vk::DescriptorSet,
    _set_layout: DescriptorSetLayout,
    m0_count: u32,
    m1_count: u32,
    /// Workgroups per dispatch row, and rows.
    grid: [u32; 2],
}

/// `groups` workgroups as rows of at most `max[0]` (maxComputeWorkGroupCount's first two), or
/// `None` where even `max[1]` rows of them are too few.
pub fn dispatch_grid(groups: u32, max: [u32; 2]) -> Option<[u32; 2]> {
    let x = groups.clamp(1, max[0].max(1));
    let y = groups.div_ceil(x).max(1);
    (y <= max[1]).then_some([x, y])
}

impl LoopPass {
    /// The passes and tables of `data`, with M0 at `m0`: the two compute pipelines, the
    /// buffers (the step's inputs, the draws' tables, M0, M1), the descriptor set over them and
    /// the dispatch grid.
    pub fn new(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        data: &LoopData,
        m0: &[Vec3],
    ) -> Result<Self, RenderError> {
        let passes = Passes::new(ctx)?;
        let step_inputs = StepInputs::upload(ctx, pool, data)?;
        let draw = DrawTables::upload(ctx, pool, data)?;
        let [m0_buf, m1, n1] = vertex_buffers(ctx, data)?;
        let (dpool, set) = passes.descriptors(
            ctx,
            [
                (LOOP_BINDING_OFFSETS, &step_inputs.offsets),
                (LOOP_BINDING_ENTRIES, &step_inputs.entries),
                (LOOP_BINDING_M0, &m0_buf),
                (LOOP_BINDING_M1, &m1),
                (LOOP_BINDING_RING_OFFSETS, &step_inputs.ring_offsets),
                (LOOP_BINDING_RINGS, &step_inputs.rings),
                (LOOP_BINDING_N1, &n1),
            ],
        )?;
        let m1_count = data.stencils.len() as u32;
        let max = ctx.info.limits.max_compute_work_group_count;
        let grid = m1_grid(m1_count, [max[0], max[1]])?;
        let mut pass = Self {
            m1,
            n1,
            faces: draw.faces,
            control: draw.control,
            tables: draw.tables,
            table_rows: draw.table_rows,
            m0: m0_buf,
            _offsets: step_inputs.offsets,
            _entries: step_inputs.entries,
            _ring_offsets: step_inputs.ring_offsets,
            _rings: step_inputs.rings,
            step: passes.step,
            normals: passes.normals,
            pipeline_layout: passes.pipeline_layout,
            _pool: dpool,
            set,
            _set_layout: passes.set_layout,
            m0_count: data.m0_count as u32,
            m1_count,
            grid,
        };
        pass.upload_m0(m0);
        debug_assert_eq!(pass.gpu_bytes(), Self::gpu_bytes_of(data));
        Ok(pass)
    }

    /// Dispatch rows of at most `width` workgroups (less than the device allows: for tests of the
    /// second dimension, which only meshes of millions of M1 vertices need).
    #[doc(hidden)]
    pub fn narrow_grid(&mut self, width: u32) {
        self.grid = dispatch_grid(self.m1_count.div_ceil(GROUP), [width, u32::MAX]).unwrap();
    }

    /// Upload M0's positions (animation: every frame). The caller makes sure no pending work
    /// reads them.
    pub fn upload_m0(&mut self, positions: &[Vec3]) {
        assert_eq!(positions.len() as u32, self.m0_count);
        let v: Vec<[f32; 4]> = positions.iter().map(|p| p.extend(1.0).to_array()).collect();
        self.m0.write_pod(0, &v);
    }

    /// Bytes [`LoopPass::upload_m0`] sends: M0's positions only, whatever the level.
    pub fn upload_bytes(&self) -> u64 {
        self.m0_count as u64 * 16
    }

    /// GPU bytes the loop surface holds besides the element records: M0, M1's positions and
    /// normals, the computational entries, the one-rings, the faces' table entries and control
    /// points, and the tables. None of it grows with the level.
    pub fn gpu_bytes(&self) -> u64 {
        [
            &self.m0,
            &self.m1,
            &self.n1,
            &self._offsets,
            &self._entries,
            &self._ring_offsets,
            &self._rings,
            &self.faces,
            &self.control,
            &self.tables,
            &self.table_rows,
        ]
        .iter()
        .map(|b| b.size())
        .sum()
    }

    /// [`LoopPass::gpu_bytes`] of `data` before any buffer is made (`info --level` prints it
    /// without a device): the same sizes, each buffer's as [`LoopPass::new`] makes it.
    pub fn gpu_bytes_of(data: &LoopData) -> u64 {
        let words = |n: usize| n as u64 * 4;
        let m1 = data.stencils.len().max(1) as u64 * 16;
        let entries: usize = data.stencils.iter().map(|s| s.parents.len()).sum();
        let packed = &data.tables.packed;
        [
            data.m0_count.max(1) as u64 * 16,
            m1,
            m1,
            words(data.stencils.len() + 1),
            entries.max(1) as u64 * 8,
            words(data.ring_offsets.len()),
            words(data.rings.len().max(1)),
            words(data.faces.len() * 4),
            words(if data.control.is_empty() {
                4
            } else {
                data.control.len()
            }),
            words(if packed.pool.is_empty() {
                4
            } else {
                packed.pool.len()
            }),
            words(packed.rows.len().max(1)),
        ]
        .iter()
        .sum()
    }

    pub fn m1_count(&self) -> u32 {
        self.m1_count
    }

    /// Record both passes (M0 -> M1, then M1's normals) and the barriers around them: after the
    /// previous draws' reads of M1, and before this frame's.
    pub fn cmd_apply(&self, cmd: &Cmd<'_>) {
        cmd.barrier_draw_to_compute();
        cmd.bind_compute_descriptor_set(self.pipeline_layout.raw, 0, self.set);
        cmd.push_constants(
            self.pipeline_layout.raw,
            vk::ShaderStageFlags::COMPUTE,
            0,
            bytemuck::bytes_of(&self.m1_count),
        );
        let [x, y] = self.grid;
        cmd.bind_compute_pipeline(self.step.raw);
        cmd.dispatch(x, y, 1);
        cmd.barrier_compute_to_draw();
        cmd.bind_compute_pipeline(self.normals.raw);
        cmd.dispatch(x, y, 1);
        cmd.barrier_compute_to_draw();
    }
}

/// A storage buffer may not be empty.
fn nonempty(v: &[u32]) -> &[u32] {
    if v.is_empty() {
        &[0]
    } else {
        v
    }
}

/// Buffers the passes read and write: storage buffers, also read as texel buffers.
const STORAGE: vk::BufferUsageFlags = vk::BufferUsageFlags::from_raw(
    vk::BufferUsageFlags::STORAGE_BUFFER.as_raw()
        | vk::BufferUsageFlags::UNIFORM_TEXEL_BUFFER.as_raw(),
);

/// The bindings of the passes' one descriptor set.
const PASS_BINDINGS: [u32; 7] = [
    LOOP_BINDING_OFFSETS,
    LOOP_BINDING_ENTRIES,
    LOOP_BINDING_M0,
    LOOP_BINDING_M1,
    LOOP_BINDING_RING_OFFSETS,
    LOOP_BINDING_RINGS,
    LOOP_BINDING_N1,
];

// The device check at start-up asks for as many storage buffers a stage as this set binds.
const _: () = assert!(PASS_BINDINGS.len() as u32 <= crate::gpu::STORAGE_BUFFERS_PER_STAGE);

/// The two compute passes (M0 -> M1, M1's normals) and the layout they share.
struct Passes {
    set_layout: DescriptorSetLayout,
    pipeline_layout: PipelineLayout,
    step: Pipeline,
    normals: Pipeline,
}

impl Passes {
    fn new(ctx: &Arc<Context>) -> Result<Self, RenderError> {
        let c = vk::ShaderStageFlags::COMPUTE;
        let set_layout = DescriptorSetLayout::new(
            ctx,
            &PASS_BINDINGS.map(|b| (b, vk::DescriptorType::STORAGE_BUFFER, c)),
            "loop passes set",
        )?;
        let pipeline_layout = PipelineLayout::new(ctx, &[&set_layout], 4, c, "loop passes")?;
        let step = Pipeline::new_compute(
            ctx,
            &pipeline_layout,
            "loop/loop_step.comp",
            "loop step (M0 -> M1)",
        )?;
        let normals = Pipeline::new_compute(
            ctx,
            &pipeline_layout,
            "loop/loop_normals.comp",
            "loop normals (M1 one-rings)",
        )?;
        Ok(Self {
            set_layout,
            pipeline_layout,
            step,
            normals,
        })
    }

    /// A pool with the one set, each binding written with its whole buffer.
    fn descriptors(
        &self,
        ctx: &Arc<Context>,
        buffers: [(u32, &Buffer); PASS_BINDINGS.len()],
    ) -> Result<(DescriptorPool, vk::DescriptorSet), RenderError> {
        use vk::DescriptorType as T;
        let dpool = DescriptorPool::new(
            ctx,
            1,
            &[(T::STORAGE_BUFFER, PASS_BINDINGS.len() as u32)],
            "loop passes descriptors",
        )?;
        let set = dpool.allocate(&self.set_layout, "loop passes set")?;
        for (binding, buffer) in buffers {
            dpool.write_buffer(set, binding, T::STORAGE_BUFFER, buffer.raw, vk::WHOLE_SIZE);
        }
        Ok((dpool, set))
    }
}

/// The step's inputs: the computational entries (each M1 vertex's parents and weights, as
/// offsets into `(parent, weight bits)` pairs) and M1's one-rings.
struct StepInputs {
    offsets: Buffer,
    entries: Buffer,
    ring_offsets: Buffer,
    rings: Buffer,
}

impl StepInputs {
    fn upload(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        data: &LoopData,
    ) -> Result<Self, RenderError> {
        let (offsets, entries) = entries_of(&data.stencils);
        let upload =
            |data: &[u32], name: &str| Buffer::new_with_data(ctx, pool, STORAGE, data, name);
        Ok(Self {
            offsets: upload(&offsets, "loop entry offsets")?,
            entries: Buffer::new_with_data(ctx, pool, STORAGE, &entries, "loop entries")?,
            ring_offsets: upload(&data.ring_offsets, "M1 ring offsets")?,
            rings: upload(nonempty(&data.rings), "M1 rings")?,
        })
    }
}

/// The stencils as entries: offsets (one more than stencils) into `(parent, weight as f32
/// bits)` pairs (at least one pair, as a storage buffer needs).
fn entries_of(stencils: &[Stencil]) -> (Vec<u32>, Vec<[u32; 2]>) {
    let mut offsets = Vec::with_capacity(stencils.len() + 1);
    let mut entries: Vec<[u32; 2]> = Vec::new();
    offsets.push(0u32);
    for s in stencils {
        for (&p, &w) in s.parents.iter().zip(&s.weights) {
            entries.push([p, (w as f32).to_bits()]);
        }
        offsets.push(entries.len() as u32);
    }
    if entries.is_empty() {
        entries.push([0, 0]);
    }
    (offsets, entries)
}

/// The draws' tables: per-face entries, control points, the packed tables' rows and their maps.
struct DrawTables {
    faces: Buffer,
    control: Buffer,
    tables: Buffer,
    table_rows: Buffer,
}

impl DrawTables {
    fn upload(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        data: &LoopData,
    ) -> Result<Self, RenderError> {
        let upload =
            |data: &[u32], name: &str| Buffer::new_with_data(ctx, pool, STORAGE, data, name);
        let faces = Buffer::new_with_data(ctx, pool, STORAGE, &data.faces, "loop face tables")?;
        // Read as texels of four (at least one texel, as every buffer view needs).
        let control = upload(
            if data.control.is_empty() {
                &[0; 4]
            } else {
                &data.control
            },
            "loop control points",
        )?;
        let packed = &data.tables.packed;
        let tables = Buffer::new_with_data(
            ctx,
            pool,
            STORAGE,
            if packed.pool.is_empty() {
                &[0.0f32; 4][..]
            } else {
                &packed.pool
            },
            "basis function tables",
        )?;
        let table_rows = upload(nonempty(&packed.rows), "basis function table rows")?;
        Ok(Self {
            faces,
            control,
            tables,
            table_rows,
        })
    }
}

/// M0's positions (written by the host), M1's positions and normals (written by the passes,
/// readable by the host): `vec4` each, at least one.
fn vertex_buffers(ctx: &Arc<Context>, data: &LoopData) -> Result<[Buffer; 3], RenderError> {
    let m0 = Buffer::new(
        ctx,
        BufferDesc::new_upload(data.m0_count.max(1) as u64 * 16, STORAGE),
        "M0 positions",
    )?;
    let m1_bytes = data.stencils.len().max(1) as u64 * 16;
    let m1 = Buffer::new(
        ctx,
        BufferDesc::new_readback(m1_bytes, STORAGE),
        "M1 positions",
    )?;
    let n1 = Buffer::new(
        ctx,
        BufferDesc::new_readback(m1_bytes, STORAGE),
        "M1 normals",
    )?;
    Ok([m0, m1, n1])
}

/// The dispatch grid over `m1_count` vertices in workgroups of [`GROUP`], within `max`
/// (maxComputeWorkGroupCount's first two).
fn m1_grid(m1_count: u32, max: [u32; 2]) -> Result<[u32; 2], RenderError> {
    dispatch_grid(m1_count.div_ceil(GROUP), max).ok_or_else(|| RenderError::OverLimit {
        what: "the loop surface's M1 vertices".into(),
        needed: m1_count as u64,
        unit: "vertices",
        limit: "this device's maxComputeWorkGroupCount",
        max: max[0] as u64 * max[1] as u64 * GROUP as u64,
        remedy: "use a coarser mesh".into(),
    })
}

/// The `loop` surface of a scene: tables and records (CPU), its passes and M1 faces (GPU), and
/// M1 as the CPU mirror computes it (the static driver and the tests read it), computed when
/// first read after M0 moved: an animated frame drawn on the GPU does no M1 work on the CPU.
pub struct LoopScene {
    pub data: LoopData,
    /// The options its data was built with (`PrePass::same_data`).
    pub(super) build: BuildOptions,
    pub(super) frame: std::cell::OnceCell<LoopFrame>,
    pub gpu: GpuMesh,
    pub pass: LoopPass,
    /// M0 moved since its positions were uploaded (`Scene::update_mesh`): they go up when the
    /// GPU next makes M1.
    pub(super) m0_stale: bool,
}

/// Whether the loop surface's buffers fit the device: the compute passes write M1 as storage
/// buffers; the drawing stages read M1, the face entries, the control points and the tables as
/// texel buffers (lavapipe fetches texels as vector gathers but reads storage buffers lane by
/// lane), four-component texels each, and the tables' row maps, one entry a texel.
fn loop_limits(data: &LoopData, limits: &vk::PhysicalDeviceLimits) -> Result<(), RenderError> {
    let m1 = data.stencils.len() as u64 * 16;
    let storage = limits.max_storage_buffer_range as u64;
    if m1 > storage {
        return Err(RenderError::OverLimit {
            what: "the loop surface's buffer of M1 positions".into(),
            needed: m1,
            unit: "bytes",
            limit: "this device's maxStorageBufferRange",
            max: storage,
            remedy: "use a coarser mesh".into(),
        });
    }
    let max = limits.max_texel_buffer_elements as u64;
    let packed = &data.tables.packed;
    for (what, texels) in [
        ("M1 positions", m1.div_ceil(16)),
        ("M1 face tables", data.faces.len() as u64),
        ("control points", (data.control.len() as u64).div_ceil(4)),
        (
            "basis function tables",
            (packed.pool.len() as u64).div_ceil(4),
        ),
        // One entry a texel.
        ("basis function table rows", packed.rows.len() as u64),
    ] {
        if texels > max {
            return Err(RenderError::OverLimit {
                what: format!("the loop surface's buffer of {what}"),
                needed: texels,
                unit: "texels",
                limit: "this device's maxTexelBufferElements",
                max,
                remedy: "use a coarser mesh or a lower --bft-level".into(),
            });
        }
    }
    Ok(())
}

impl Scene {
    /// Build the data of `pass` (the pre-pass a surface declares, `Surface::pre_pass`) with
    /// `build`'s options, unless it was built with them: what `Scene::prepare` runs before the
    /// surface is drawn. `on_gpu`: the GPU runs the pass this frame (moved M0 positions are
    /// uploaded for it).
    pub(super) fn prepare_pre_pass(
        &mut self,
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
        pass: PrePass,
        build: &BuildOptions,
        on_gpu: bool,
    ) -> Result<(), RenderError> {
        match pass {
            PrePass::LoopStep => {
                if let Some(l) = self.loop_.as_mut() {
                    if pass.same_data(&l.build, build) {
                        if on_gpu && std::mem::take(&mut l.m0_stale) {
                            l.pass.upload_m0(&self.data.mesh.positions);
                        }
                        return Ok(());
                    }
                }
                self.loop_ = None;
                self.static_vbo = None;
                self.loop_ = Some(LoopScene::new(ctx, pool, renderer, self, build)?);
            }
        }
        Ok(())
    }
}

impl LoopScene {
    pub(super) fn new(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
        scene: &Scene,
        build: &BuildOptions,
    ) -> Result<Self, RenderError> {
        let mesh = &scene.data.mesh;
        let lattice = Lattice::new(build.bft_level);
        let progress = progress_line("loop surface");
        let data = LoopData::new(mesh, build.boundary, lattice, progress)?;
        loop_limits(&data, &ctx.info.limits)?;
        let pass = LoopPass::new(ctx, pool, &data, &mesh.positions)?;
        let elements = MeshData {
            mesh: mesh.clone(),
            kind: RecordKind::LoopFaces,
            seams: scene.data.seams,
            records: data.records.clone(),
            uvs: None,
            uv_extent: 0.0,
        };
        let gpu = GpuMesh::new(
            ctx,
            pool,
            &renderer.mesh_layout,
            &elements,
            Patterns::Share(&scene.gpu.patterns),
            scene.max_chunk,
            Extras {
                heightmap: &scene.heightmap,
                tags: &scene.tags,
                loop_: Some(&pass),
            },
        )?;
        Ok(Self {
            data,
            build: *build,
            frame: std::cell::OnceCell::new(),
            gpu,
            pass,
            m0_stale: false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_support::load_model;
    use crate::subdiv::Boundary;

    #[test]
    fn dispatch_grids_cover_every_group_within_the_limits() {
        assert_eq!(dispatch_grid(12, [65535, 65535]), Some([12, 1]));
        assert_eq!(dispatch_grid(0, [65535, 65535]), Some([1, 1]));
        // 8.4 M vertices (lavapipe's maxStorageBufferRange of M1) in rows of 65,535 groups.
        assert_eq!(dispatch_grid(131_072, [65535, 65535]), Some([65535, 3]));
        assert_eq!(dispatch_grid(10, [3, 4]), Some([3, 4]));
        assert_eq!(dispatch_grid(13, [3, 4]), None);
    }

    /// A loop surface over a device's limits is one sentence naming the buffer, the limit and
    /// what to do; texels count four components.
    #[test]
    fn loop_buffers_are_checked_against_the_limits() {
        let (mesh, _) = load_model("spot_control_tri.obj");
        let data = LoopData::new(&mesh, Boundary::EdgeOnly, Lattice::default(), |_| {}).unwrap();
        let tables = data.tables.packed.pool.len() as u64 / 4;
        let mut limits = vk::PhysicalDeviceLimits {
            max_storage_buffer_range: u32::MAX,
            max_texel_buffer_elements: tables as u32,
            ..Default::default()
        };
        loop_limits(&data, &limits).unwrap();
        limits.max_texel_buffer_elements = tables as u32 - 1;
        let e = loop_limits(&data, &limits).unwrap_err().to_string();
        assert_eq!(
            e,
            format!(
                "the loop surface's buffer of basis function tables needs {tables} texels, over this \
                 device's maxTexelBufferElements ({}): use a coarser mesh or a lower --bft-level",
                tables - 1
            )
        );
        // Every other buffer the drawing stages read, each over a limit the ones before it fit
        // (the row maps, always fewer than the tables' texels, with the tables emptied).
        let mut no_tables = data.clone();
        no_tables.tables.packed.pool.clear();
        for (what, texels, data) in [
            ("M1 positions", data.stencils.len(), &data),
            ("M1 face tables", data.faces.len(), &data),
            ("control points", data.control.len().div_ceil(4), &data),
            (
                "basis function table rows",
                data.tables.packed.rows.len(),
                &no_tables,
            ),
        ] {
            limits.max_texel_buffer_elements = texels as u32 - 1;
            let e = loop_limits(data, &limits).unwrap_err().to_string();
            let over = format!("over this device's maxTexelBufferElements ({})", texels - 1);
            let what = format!("the loop surface's buffer of {what} needs {texels} texels, {over}");
            assert_eq!(
                e,
                format!("{what}: use a coarser mesh or a lower --bft-level")
            );
        }
        limits.max_storage_buffer_range = 1024;
        let e = loop_limits(&data, &limits).unwrap_err().to_string();
        assert!(
            e.starts_with("the loop surface's buffer of M1 positions needs")
                && e.contains("bytes, over this device's maxStorageBufferRange (1024)"),
            "{e}"
        );
    }
}
