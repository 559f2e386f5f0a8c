//! Layouts and pipelines shared by all drivers, the per-frame uniform buffer (set 0) and the
//! capture output binding (set 2). Pipelines are created on first use, keyed by
//! (driver, submission, surface, displacement, normal field, capture, wireframe, adaptive,
//! geomorph, view); all but the capture (a stage variant) are specialization constants of the
//! same SPIR-V modules.

use super::bindings::*;
use super::{Capture, DrawConfig, Driver, FrameUniforms, View};
use crate::gpu::{
    vk, Buffer, BufferDesc, Context, DescriptorPool, DescriptorSetLayout, GpuError,
    GraphicsPipelineDesc, Pipeline, PipelineLayout,
};
use crate::surface::{Displace, NormalField, Surface};
use std::collections::HashMap;
use std::sync::Arc;

const fn stages(list: &[vk::ShaderStageFlags]) -> vk::ShaderStageFlags {
    let mut raw = 0;
    let mut i = 0;
    while i < list.len() {
        raw |= list[i].as_raw();
        i += 1;
    }
    vk::ShaderStageFlags::from_raw(raw)
}

/// Stages that evaluate surfaces or read per-mesh data.
pub const GEOMETRY_STAGES: vk::ShaderStageFlags = stages(&[
    vk::ShaderStageFlags::VERTEX,
    vk::ShaderStageFlags::TESSELLATION_CONTROL,
    vk::ShaderStageFlags::TESSELLATION_EVALUATION,
]);

/// Stages that read the push-constant block: the geometry stages only (a range visible to the
/// fragment stage costs lavapipe about 36 K instructions per push, docs/platform.md).
pub const PUSH_STAGES: vk::ShaderStageFlags = GEOMETRY_STAGES;

/// Every stage of every driver.
const ALL_STAGES: vk::ShaderStageFlags = stages(&[GEOMETRY_STAGES, vk::ShaderStageFlags::FRAGMENT]);

/// The largest depth offset of a wireframe line in front of its fill (depth units, `[0, 1]`; the
/// depth range hugs the bounding sphere, `Camera::depth_range`). A compromise: the slope-scaled
/// offset of a steep triangle needs room (a tenth of this thins the lines of Spot's ears seen
/// edge on), while steep, folded and zero-area triangles (snapping makes the last) pull their
/// lines through the surface in front of them by as much as the offset allows.
/// `tests/images.rs` checks that no line of the far side shows; docs/window.md says what
/// remains.
const WIRE_BIAS_CLAMP: f32 = -1e-3;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct PipelineKey {
    driver: Driver,
    surface: Surface,
    displace: Displace,
    /// `pn`'s and `stpn`'s normal field (`Paper` for the surfaces that have none of their own).
    normal_field: NormalField,
    fragment_field: bool,
    capture: Capture,
    /// Wireframe pass: polygon mode LINE, the fragment stage's WIRE variant.
    wire: bool,
    /// Each element at its own levels (`FrameWork::adaptive`).
    adaptive: bool,
    /// Adaptive and geomorphing (`DrawConfig::geomorph`).
    geomorph: bool,
    /// What the fragment stage shows ([`Renderer::set_view`]).
    view: View,
}

pub struct Renderer {
    ctx: Arc<Context>,
    pub frame_layout: DescriptorSetLayout,
    pub mesh_layout: DescriptorSetLayout,
    pub capture_layout: DescriptorSetLayout,
    pub layout: PipelineLayout,
    pipelines: HashMap<PipelineKey, Pipeline>,
    /// The cage overlay's lines (src/render/cage.rs), made when first asked for.
    cage: Option<Pipeline>,
    pub color_format: vk::Format,
    pub depth_format: vk::Format,
    /// Samples per pixel of the targets drawn into (`--msaa`).
    pub samples: vk::SampleCountFlags,
    /// What the fragment stage of the pipelines prepared and drawn next shows
    /// ([`Renderer::set_view`]).
    view: View,
    frame_ubo: Buffer,
    /// Kept alive for the frame set's binding.
    _noise_ubo: Buffer,
    pool: DescriptorPool,
    pub frame_set: vk::DescriptorSet,
    pub capture_set: vk::DescriptorSet,
}

impl Renderer {
    pub fn new(
        ctx: &Arc<Context>,
        color_format: vk::Format,
        depth_format: vk::Format,
    ) -> Result<Self, GpuError> {
        Self::multisampled(
            ctx,
            color_format,
            depth_format,
            vk::SampleCountFlags::TYPE_1,
        )
    }

    /// Pipelines for targets with `samples` per pixel (checked by `gpu::sample_count`).
    pub fn multisampled(
        ctx: &Arc<Context>,
        color_format: vk::Format,
        depth_format: vk::Format,
        samples: vk::SampleCountFlags,
    ) -> Result<Self, GpuError> {
        use vk::DescriptorType as T;
        let frame_layout = DescriptorSetLayout::new(
            ctx,
            &[
                (BINDING_FRAME, T::UNIFORM_BUFFER, ALL_STAGES), // camera, light, options, params
                (BINDING_NOISE, T::UNIFORM_BUFFER, ALL_STAGES), // Perlin's permutation
            ],
            "set 0: frame",
        )?;
        let mesh_layout = DescriptorSetLayout::new(
            ctx,
            &[
                // the records as texels (instanced adaptive pattern, tess; per-fragment normal
                // fields): no stage reads a storage buffer of this set
                (BINDING_ELEMENT_TEXELS, T::UNIFORM_TEXEL_BUFFER, ALL_STAGES),
                // one ElementRecord (ubo)
                (
                    BINDING_ELEMENT_UBO,
                    T::UNIFORM_BUFFER_DYNAMIC,
                    GEOMETRY_STAGES,
                ),
                // texture coordinates and the height map (heightmap displacement)
                (BINDING_UVS, T::UNIFORM_TEXEL_BUFFER, ALL_STAGES),
                (BINDING_HEIGHTMAP, T::UNIFORM_BUFFER, ALL_STAGES),
                (
                    BINDING_HEIGHTMAP_TEXELS,
                    T::UNIFORM_TEXEL_BUFFER,
                    ALL_STAGES,
                ),
                // every vertex's scalar tags (stpn)
                (BINDING_TAGS, T::UNIFORM_TEXEL_BUFFER, ALL_STAGES),
                // each element's levels (adaptive drawing)
                (BINDING_LEVELS, T::UNIFORM_TEXEL_BUFFER, ALL_STAGES),
                // the loop surface: M1, per-face table entries, control points, tables, row maps
                (BINDING_LOOP_P1, T::UNIFORM_TEXEL_BUFFER, ALL_STAGES),
                (BINDING_LOOP_N1, T::UNIFORM_TEXEL_BUFFER, ALL_STAGES),
                (BINDING_LOOP_FACES, T::UNIFORM_TEXEL_BUFFER, ALL_STAGES),
                (BINDING_LOOP_CONTROL, T::UNIFORM_TEXEL_BUFFER, ALL_STAGES),
                (BINDING_LOOP_TABLES, T::UNIFORM_TEXEL_BUFFER, ALL_STAGES),
                (BINDING_LOOP_ROWS, T::UNIFORM_TEXEL_BUFFER, ALL_STAGES),
            ],
            "set 1: mesh",
        )?;
        let capture_layout = DescriptorSetLayout::new(
            ctx,
            &[
                (BINDING_CAPTURE, T::STORAGE_BUFFER, GEOMETRY_STAGES), // CapturedVertex[] output
                (BINDING_CAPTURE_COUNT, T::STORAGE_BUFFER, GEOMETRY_STAGES), // append counter
                (BINDING_CAPTURE_OFFSETS, T::STORAGE_BUFFER, GEOMETRY_STAGES), // packed slots
            ],
            "set 2: capture",
        )?;
        let layout = PipelineLayout::new(
            ctx,
            &[&frame_layout, &mesh_layout, &capture_layout],
            std::mem::size_of::<super::PushBlock>() as u32,
            PUSH_STAGES,
            "drivers",
        )?;
        let frame_ubo = Buffer::new(
            ctx,
            BufferDesc::new_upload(
                std::mem::size_of::<FrameUniforms>() as u64,
                vk::BufferUsageFlags::UNIFORM_BUFFER,
            ),
            "frame uniforms",
        )?;
        let mut noise_ubo = Buffer::new(
            ctx,
            BufferDesc::new_upload(256 * 4, vk::BufferUsageFlags::UNIFORM_BUFFER),
            "noise permutation",
        )?;
        let table: Vec<u32> = crate::surface::noise::PERM
            .iter()
            .map(|&p| p as u32)
            .collect();
        noise_ubo.write_pod(0, &table);
        let pool = DescriptorPool::new(
            ctx,
            2,
            &[(T::UNIFORM_BUFFER, 2), (T::STORAGE_BUFFER, 3)],
            "renderer descriptors",
        )?;
        let frame_set = pool.allocate(&frame_layout, "frame set")?;
        pool.write_buffer(
            frame_set,
            BINDING_FRAME,
            T::UNIFORM_BUFFER,
            frame_ubo.raw,
            vk::WHOLE_SIZE,
        );
        pool.write_buffer(
            frame_set,
            BINDING_NOISE,
            T::UNIFORM_BUFFER,
            noise_ubo.raw,
            vk::WHOLE_SIZE,
        );
        let capture_set = pool.allocate(&capture_layout, "capture set")?;
        Ok(Self {
            ctx: ctx.clone(),
            frame_layout,
            mesh_layout,
            capture_layout,
            layout,
            pipelines: HashMap::new(),
            cage: None,
            color_format,
            depth_format,
            samples,
            view: View::default(),
            frame_ubo,
            _noise_ubo: noise_ubo,
            pool,
            frame_set,
            capture_set,
        })
    }

    /// Show `view` in the frames drawn from now on: the fragment stage's view is a
    /// specialization constant, so each view's pipelines do its own work alone (on a software
    /// rasteriser the views not shown cost time per fragment even behind a uniform branch).
    /// Set it before [`Renderer::prepare`], which creates the pipelines for the view set (each
    /// once: switching back and forth compiles nothing again).
    pub fn set_view(&mut self, view: View) {
        self.view = view;
    }

    /// Write this frame's uniforms. The caller makes sure no pending work reads them.
    pub fn set_frame(&mut self, f: &FrameUniforms) {
        self.frame_ubo.write_pod(0, std::slice::from_ref(f));
    }

    /// Point the capture bindings at `vertices`, `counter` and the packed capture's `offsets`
    /// (not while pending work uses the set).
    pub fn set_capture_target(
        &self,
        vertices: vk::Buffer,
        counter: vk::Buffer,
        offsets: vk::Buffer,
    ) {
        let t = vk::DescriptorType::STORAGE_BUFFER;
        self.pool.write_buffer(
            self.capture_set,
            BINDING_CAPTURE,
            t,
            vertices,
            vk::WHOLE_SIZE,
        );
        self.pool.write_buffer(
            self.capture_set,
            BINDING_CAPTURE_COUNT,
            t,
            counter,
            vk::WHOLE_SIZE,
        );
        self.pool.write_buffer(
            self.capture_set,
            BINDING_CAPTURE_OFFSETS,
            t,
            offsets,
            vk::WHOLE_SIZE,
        );
    }

    /// Whether the device can draw the wireframe pass (fillModeNonSolid).
    pub fn wireframe_supported(&self) -> bool {
        self.ctx.info.fill_mode_non_solid
    }

    /// Create (once) the pipelines `cfg` needs: the fill pipeline (or its capture variant), and
    /// the wireframe pass when `wire` is set and supported.
    pub fn prepare(
        &mut self,
        cfg: &DrawConfig,
        capture: Capture,
        wire: bool,
    ) -> Result<(), GpuError> {
        let mut keys = vec![key(cfg, capture, false, false, self.view)];
        if wire && self.wireframe_supported() {
            keys.push(key(cfg, Capture::None, true, false, self.view));
        }
        // The adaptive variants where the driver draws adaptively at this level (created
        // together: pipelines are compiled at their first draw).
        if adaptive_drawn(cfg) {
            keys.extend(keys.clone().into_iter().map(|k| PipelineKey {
                adaptive: true,
                geomorph: cfg.glides(),
                ..k
            }));
        }
        for k in keys {
            if !self.pipelines.contains_key(&k) {
                let p = self.create(k)?;
                self.pipelines.insert(k, p);
            }
        }
        Ok(())
    }

    /// How many drawing pipelines have been created (each once).
    pub fn pipeline_count(&self) -> usize {
        self.pipelines.len()
    }

    /// Create (once) the cage overlay's pipeline.
    pub fn prepare_cage(&mut self) -> Result<(), GpuError> {
        if self.cage.is_none() {
            self.cage = Some(super::cage::pipeline(
                &self.ctx,
                &self.layout,
                self.color_format,
                self.depth_format,
                self.samples,
            )?);
        }
        Ok(())
    }

    /// The cage overlay's pipeline; [`Renderer::prepare_cage`] must have been called.
    pub fn cage_pipeline(&self) -> vk::Pipeline {
        self.cage.as_ref().expect("cage pipeline prepared").raw
    }

    /// The pipeline for `cfg` (`adaptive`: its adaptive variant, where the driver draws
    /// adaptively at this level); [`Renderer::prepare`] must have been called.
    pub fn pipeline(
        &self,
        cfg: &DrawConfig,
        capture: Capture,
        wire: bool,
        adaptive: bool,
    ) -> vk::Pipeline {
        let adaptive = adaptive && adaptive_drawn(cfg);
        let key = key(cfg, capture, wire, adaptive, self.view);
        let pipeline = self.pipelines.get(&key);
        pipeline
            .unwrap_or_else(|| panic!("no pipeline prepared for {key:?}"))
            .raw
    }

    fn create(&self, key: PipelineKey) -> Result<Pipeline, GpuError> {
        let mut desc = GraphicsPipelineDesc {
            stages: vec![],
            spec: vec![
                (SPEC_SURFACE, key.surface as u32),
                (SPEC_SUBMIT, key.driver.submit().unwrap_or_default() as u32),
                (SPEC_WIRE, key.wire as u32),
                (SPEC_DISPLACE, key.displace as u32),
                (SPEC_FRAGMENT_FIELD, key.fragment_field as u32),
                (SPEC_NORMAL_FIELD, key.normal_field as u32),
                (SPEC_GEOMORPH, key.geomorph as u32),
                (SPEC_VIEW, key.view as u32),
            ],
            vertex_bindings: vec![],
            vertex_attributes: vec![],
            topology: vk::PrimitiveTopology::TRIANGLE_LIST,
            primitive_restart: false,
            patch_control_points: 0,
            color_format: self.color_format,
            depth_format: self.depth_format,
            polygon_mode: if key.wire {
                vk::PolygonMode::LINE
            } else {
                vk::PolygonMode::FILL
            },
            // Pull the lines towards the camera so they win the depth test against their fill,
            // by at most WIRE_BIAS_CLAMP of the depth range where the device clamps: steep
            // triangles, and the zero-area ones that snapping makes (an unbounded depth slope),
            // would otherwise pull lines of hidden sheets through the surface.
            depth_bias: key.wire.then_some((
                -1.0,
                -1.0,
                if self.ctx.info.depth_bias_clamp {
                    WIRE_BIAS_CLAMP
                } else {
                    0.0
                },
            )),
            // The wireframe lines test depth against their surface but do not write it, so the
            // cage overlay drawn after them is tested against the surface alone.
            depth_write: !key.wire,
            // The lines of faces turned away are culled where only front faces can be seen
            // (`FrameWork::wire_front_only`): a sheet just behind the surface (a snapped sliver
            // folded under its neighbours) would otherwise show through within the offset.
            dynamic_cull: key.wire,
            samples: self.samples,
        };
        let kind = key.driver.kind();
        if key.adaptive {
            kind.describe_adaptive_pipeline(&mut desc, key.fragment_field, key.capture);
        } else {
            kind.describe_pipeline(&mut desc, key.fragment_field, key.capture);
        }
        desc.stages.push((
            vk::ShaderStageFlags::FRAGMENT,
            crate::gpu::shaders::names::SHADE_SHADE_FRAG.to_string(),
        ));
        let name = format!(
            "{}{}{}{} ({} + {}, {})",
            DrawConfig::new(key.driver, 0).label(),
            if key.geomorph {
                " adaptive geomorph"
            } else if key.adaptive {
                " adaptive"
            } else {
                ""
            },
            key.capture.shader_suffix(),
            if key.wire { " wireframe" } else { "" },
            key.surface.name(),
            key.displace.name(),
            key.view.name()
        );
        Pipeline::new_graphics(&self.ctx, &self.layout, &desc, &name)
    }
}

/// Whether `cfg`'s adaptive frames have a pipeline of their own
/// ([`DriverKind::adaptive_pipeline`](super::DriverKind::adaptive_pipeline)).
fn adaptive_drawn(cfg: &DrawConfig) -> bool {
    cfg.driver.kind().adaptive_pipeline(cfg.level)
}

fn key(cfg: &DrawConfig, capture: Capture, wire: bool, adaptive: bool, view: View) -> PipelineKey {
    PipelineKey {
        view,
        // The driver carries the pattern driver's submission mode.
        driver: cfg.driver,
        surface: cfg.surface,
        displace: cfg.displace,
        normal_field: if cfg.surface.facts().options.contains(&"normal_field") {
            cfg.build.normal_field
        } else {
            NormalField::Paper
        },
        fragment_field: cfg.fragment_normal_field(),
        capture,
        wire,
        adaptive,
        // A driver that geomorphs in its evaluation stage (tess) draws adaptively with the
        // pipeline of its uniform frames (a push constant says adaptive).
        geomorph: (adaptive || cfg.driver.kind().geomorphs_in_evaluation()) && cfg.glides(),
    }
}
