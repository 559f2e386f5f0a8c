//! A mesh ready to draw with any surface and driver: its CPU data, its GPU data (`gpu_mesh.rs`),
//! the pattern set, Loop's data when drawn as `loop`, and the static driver's buffer when built.
//! [`Scene::prepare`] checks a configuration and builds what it needs, between frames.

use super::gpu_mesh::{Extras, GpuMesh, Patterns};
use super::loop_gpu::{LoopPass, LoopScene};
use super::MeshData;
use super::RenderError;
use crate::gpu::{vk, CommandPool, Context, GpuError};
use crate::lod::levels::drawn_level;
use crate::mesh::Mesh;
use crate::pattern::PatternSet;
use crate::surface::stpn::VertexTag;
use crate::surface::Surface;
use crate::surface::{
    build_records, ElementRecord, Heightmap, Mirror, RecordKind, Seams, Sources, RECORD_BYTES,
};
use std::sync::Arc;

/// Everything needed to draw one mesh with any driver: CPU data, GPU data, the pattern set and
/// (built on demand) the static driver's refined vertex buffer.
pub struct Scene {
    pub data: MeshData,
    pub gpu: GpuMesh,
    /// The `heightmap` displacement's map (a generated one until [`Scene::set_heightmap`]).
    pub heightmap: Heightmap,
    /// Every vertex's scalar tags (`stpn`): derived from the mesh's hard edges until
    /// [`Scene::set_tags`].
    pub tags: Vec<VertexTag>,
    pub(super) max_chunk: Option<u32>,
    pub patterns: PatternSet,
    pub static_vbo: Option<super::static_vbo::StaticVbo>,
    /// The next [`Scene::prepare`]s are for adaptive frames (`Headless::adaptive`): the static
    /// driver then refines at the levels of the last [`Scene::set_levels`]
    /// (src/render/static_adaptive.rs).
    pub adaptive_frames: bool,
    /// Those levels, for the static driver.
    pub(super) static_levels: Option<super::static_adaptive::StaticLevels>,
    /// The mesh is closed, consistently oriented and wound outwards (a positive
    /// [`Mesh::signed_volume`](crate::mesh::Mesh::signed_volume)), as its topology and
    /// orientation are at load (animation keeps them): only then are elements facing away from
    /// the eye culled ([`Scene::set_levels`]). An open surface shows its back side, and an
    /// inside-out one shows only faces that face away.
    pub closed: bool,
    /// [`Scene::closed`], and every normal pointing out as the winding says
    /// ([`Mesh::normals_point_out`](crate::mesh::Mesh::normals_point_out)), so lighting may
    /// tell the inside by the triangle's side.
    pub normals_outward: bool,
    /// Whether the coarse mesh intersects itself ([`Mesh::self_intersects`](crate::mesh::Mesh::self_intersects)),
    /// found when first asked (`flat` drawn adaptively with culling), again after
    /// [`Scene::update_mesh`].
    pub(super) self_intersecting: std::cell::OnceCell<bool>,
    /// The elements' spheres [`Scene::front_only`] computed alone where no bounds were at hand.
    pub(super) front_spheres: Option<super::scene_levels::FrontSpheres>,
    /// The warning that the level pass cannot hold this mesh's bounds was given (once a scene:
    /// the window chooses levels every frame).
    pub(super) cpu_levels_said: bool,
    /// The `loop` surface's M1 faces, built by the first `prepare` that draws it.
    pub loop_: Option<LoopScene>,
    /// The coarse mesh's edges for the cage overlay, made when first drawn ([`Scene::cage`]).
    pub cage: Option<super::cage::Cage>,
    /// The coarse records on the GPU are older than `data` (the mesh moved): the next
    /// `prepare` whose drawing reads them uploads them (`DrawConfig::reads_records`: not `loop`,
    /// nor `static` unless its fragments evaluate the normal field).
    records_stale: bool,
    warned_slow: bool,
    /// What the slow-frame warning of a uniform frame advises (the command's own option).
    pub uniform_advice: &'static str,
    /// Counts changes of the coarse data the level pass's bounds are made from
    /// ([`Scene::update_mesh`], the height map, the tags).
    pub(super) generation: u64,
    /// The level pass and the bounds it holds (src/render/scene_levels.rs).
    pub(super) levels: Option<super::scene_levels::SceneLevels>,
    pub(super) ctx: Arc<Context>,
}

/// What a refined triangle costs a software device (lavapipe) at high levels, in nanoseconds:
/// about the range docs/bench/table1.md measures at levels 16 and 32 over its surfaces and
/// drivers (level 4 costs more a triangle), rounded to 100 and 400 with a margin above, as
/// runs vary by a quarter. The range of
/// [`software_frame_seconds`].
pub const SOFTWARE_NS_PER_TRIANGLE: (f64, f64) = (100.0, 400.0);

/// The control points a vertex of a regular Loop face sums (its 12-point neighbourhood).
const REGULAR_CONTROL_POINTS: u32 = 12;

/// [`Scene::evaluation_weight`]: how many times its triangles' cost a frame takes (`factor`),
/// and the most control points a face of the mesh sums (`most`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EvaluationWeight {
    pub factor: f64,
    pub most: u32,
}

/// How long a frame of `refined` triangles takes on a software device, as a range in seconds;
/// `None` when even the slower estimate is under a second.
pub fn software_frame_seconds(refined: u64) -> Option<(f64, f64)> {
    let (a, b) = SOFTWARE_NS_PER_TRIANGLE;
    let (lo, hi) = (refined as f64 * a * 1e-9, refined as f64 * b * 1e-9);
    (hi >= 1.0).then_some((lo, hi))
}

/// A range of seconds as the slow-frame warning says it: one decimal under 10 s, whole seconds
/// from there (`0.3 to 1.2`, `2.5 to 10`, `39 to 156`), so that no end reads as 0.
fn seconds_range(lo: f64, hi: f64) -> String {
    let one = |s: f64| {
        if s >= 9.95 {
            format!("{s:.0}")
        } else {
            format!("{s:.1}")
        }
    };
    format!("{} to {}", one(lo), one(hi))
}

impl Scene {
    /// Upload `mesh` with patterns for LOD up to `max_level`.
    pub fn new(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
        mesh: Mesh,
        max_level: u32,
    ) -> Result<Self, RenderError> {
        Self::with_patterns(ctx, pool, renderer, mesh, PatternSet::up_to(max_level))
    }

    /// Upload `mesh` with exactly the given pattern set.
    pub fn with_patterns(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
        mesh: Mesh,
        patterns: PatternSet,
    ) -> Result<Self, RenderError> {
        Self::with_chunks(ctx, pool, renderer, mesh, patterns, None)
    }

    /// Upload `mesh` with exactly the given pattern set, its records in chunks of at most
    /// `max_chunk` elements (None: as many as the device's maxStorageBufferRange and
    /// maxTexelBufferElements allow; tests
    /// pass small chunks to exercise drawing chunk by chunk).
    pub fn with_chunks(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
        mesh: Mesh,
        patterns: PatternSet,
        max_chunk: Option<u32>,
    ) -> Result<Self, RenderError> {
        let data = MeshData::new(mesh, RecordKind::Corners, Seams::default());
        let closed = data.mesh.closed_outward();
        let normals_outward = closed && data.mesh.normals_point_out();
        let heightmap = Heightmap::generated();
        let (tags, _) = crate::surface::stpn::derive(&data.mesh);
        let gpu = GpuMesh::new(
            ctx,
            pool,
            &renderer.mesh_layout,
            &data,
            Patterns::Upload(&patterns),
            max_chunk,
            Extras {
                heightmap: &heightmap,
                tags: &tags,
                loop_: None,
            },
        )?;
        Ok(Self {
            data,
            gpu,
            heightmap,
            tags,
            max_chunk,
            patterns,
            static_vbo: None,
            adaptive_frames: false,
            closed,
            normals_outward,
            self_intersecting: std::cell::OnceCell::new(),
            front_spheres: None,
            cpu_levels_said: false,
            static_levels: None,
            loop_: None,
            cage: None,
            records_stale: false,
            warned_slow: false,
            uniform_advice: "a lower --level draws faster",
            generation: 0,
            levels: None,
            ctx: ctx.clone(),
        })
    }

    /// Check that `cfg` can be drawn here and build what it needs (pipelines, including the
    /// wireframe pass when `wire`, static buffers).
    /// Only between frames: may rewrite the mesh descriptor set.
    pub fn prepare(
        &mut self,
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &mut super::Renderer,
        cfg: &super::DrawConfig,
        capture: super::Capture,
        wire: bool,
    ) -> Result<(), RenderError> {
        if self.patterns.find(cfg.level).is_none() {
            let levels: Vec<String> = self.patterns.levels().map(|l| l.to_string()).collect();
            return Err(RenderError::LevelNotUploaded {
                level: cfg.level,
                levels: levels.join(", "),
            });
        }
        // The surface's own pre-pass makes its elements (the coarse triangles' records
        // otherwise).
        let pre_pass = cfg.surface.pre_pass();
        if let Some(pass) = pre_pass {
            let on_gpu = !cfg.driver.kind().refines_on_cpu();
            self.prepare_pre_pass(ctx, pool, renderer, pass, &cfg.build, on_gpu)?;
        }
        let coarse = pre_pass.is_none();
        if coarse && self.records_stale && cfg.reads_records() {
            self.gpu.update_records(&self.data.records);
            self.records_stale = false;
        }
        if let Some(why) =
            (cfg.surface).incompatibility_on(cfg.displace, &self.data.mesh, self.data.uvs.is_some())
        {
            return Err(RenderError::Incompatible(why));
        }
        if cfg.surface.facts().tags {
            super::gpu_mesh::check_tags(self.tags.len(), &ctx.info.limits)?;
            crate::surface::stpn::check(&self.data.mesh, &self.tags).map_err(RenderError::Tags)?;
        }
        if cfg.build.seams != self.data.seams && coarse {
            self.data.records = build_records(self.data.kind, &self.data.mesh, cfg.build.seams);
            self.data.seams = cfg.build.seams;
            self.gpu.update_records(&self.data.records);
            self.records_stale = false;
            self.static_vbo = None;
        }
        super::driver::check_level(ctx, cfg)?;
        use super::Capture;
        if capture == Capture::Vertices && !ctx.info.vertex_stores {
            let tess = if ctx.info.transform_feedback {
                "; --driver tess exports through transform feedback"
            } else {
                ""
            };
            return Err(GpuError::Other(format!(
                "device '{}' has no vertexPipelineStoresAndAtomics, which capturing evaluated vertices needs{tess}",
                ctx.info.name
            ))
            .into());
        }
        if capture == Capture::Triangles && !ctx.info.transform_feedback {
            return Err(GpuError::Other(format!(
                "device '{}' has no transformFeedback (VK_EXT_transform_feedback), which reading back the tessellator's triangles needs",
                ctx.info.name
            ))
            .into());
        }
        let kind = cfg.driver.kind();
        if capture == Capture::Triangles && kind.export_capture() != Some(Capture::Triangles) {
            return Err(RenderError::Unsupported(
                "triangle capture is for the tess driver",
            ));
        }
        if capture != Capture::None && kind.capture_per_element(cfg.level).is_none() {
            return Err(RenderError::Unsupported(
                "the static driver evaluates on the CPU: there is nothing to capture (use pattern or tess)",
            ));
        }
        kind.check_fits(self, ctx, cfg)?;
        renderer.prepare(cfg, capture, wire)?;
        // An adaptive frame's elements are not all at the configuration's (largest) level: it
        // warns from the levels chosen instead ([`Scene::warn_once_if_slow`]).
        if !self.adaptive_frames {
            let refined =
                self.elements(cfg.surface).element_count as u64 * cfg.refined_per_element() as u64;
            if !self.warned_slow {
                let weight = self.evaluation_weight(cfg, None);
                self.warn_once_if_slow(refined, weight, self.uniform_advice);
            }
        }
        kind.prepare(self, ctx, pool, cfg)?;
        Ok(())
    }

    /// Replace the coarse positions/normals (animation): loop's M0 positions are uploaded now,
    /// the records by the next `prepare` whose drawing reads them (what
    /// [`Scene::upload_bytes`] counts); the static buffer, if any, becomes stale and is rebuilt
    /// by the next `prepare`. Only between frames.
    pub fn update_mesh(&mut self, mesh: Mesh) {
        self.data = MeshData::new(mesh, self.data.kind, self.data.seams);
        // Moved corners may leave a file's normals pointing in (the topology, and so
        // `closed`, stays).
        self.normals_outward = self.closed && self.data.mesh.normals_point_out();
        self.self_intersecting = std::cell::OnceCell::new();
        self.generation += 1;
        if let Some(l) = &mut self.loop_ {
            // Loop: only M0's positions go up, when the GPU next makes M1 from them (the
            // mirror's M1 follows when it is read).
            l.m0_stale = true;
            l.frame = std::cell::OnceCell::new();
        }
        // The coarse records go up when the next frame that reads them is prepared: not for the
        // static driver unless its fragments evaluate the normal field, nor for `loop`.
        self.records_stale = true;
        self.static_vbo = None;
        if let Some(c) = &mut self.cage {
            c.stale = true;
        }
    }

    /// The cage overlay's lines (the coarse mesh's edges; Loop's control mesh), uploaded the
    /// first time they are asked for, and its pipeline prepared. Only between frames.
    pub fn prepare_cage(
        &mut self,
        ctx: &Arc<Context>,
        renderer: &mut super::Renderer,
    ) -> Result<(), RenderError> {
        renderer.prepare_cage()?;
        match &mut self.cage {
            None => self.cage = Some(super::cage::Cage::new(ctx, &self.data.mesh)?),
            Some(c) if c.stale => {
                c.update(&self.data.mesh.positions);
                c.stale = false;
            }
            Some(_) => {}
        }
        Ok(())
    }

    /// Bytes an animated frame uploads when drawing `cfg`: the coarse records (the local
    /// surfaces) or M0's positions (loop), independent of the level; on the static driver the
    /// refined vertices, and the records where its fragments read them.
    pub fn upload_bytes(&self, cfg: &super::DrawConfig) -> u64 {
        let count = self.elements(cfg.surface).element_count as u64;
        let records = if cfg.reads_records() && cfg.surface.pre_pass().is_none() {
            count * RECORD_BYTES as u64
        } else {
            0
        };
        if let Some(bytes) = self.static_adaptive_bytes(cfg) {
            return bytes + records;
        }
        if cfg.driver.kind().refines_on_cpu() {
            return cfg.geometry_bytes(count, false) + records;
        }
        match self.pre_pass(cfg) {
            Some(pass) => pass.upload_bytes(),
            None => self.gpu.element_count as u64 * RECORD_BYTES as u64,
        }
    }

    /// The elements `surface` draws: M1 faces for `loop` (once prepared), coarse triangles
    /// otherwise.
    pub fn elements(&self, surface: Surface) -> &GpuMesh {
        match &self.loop_ {
            Some(l) if surface.uses_loop_faces() => &l.gpu,
            _ => &self.gpu,
        }
    }

    /// [`Scene::elements`], to upload their levels ([`GpuMesh::upload_levels`]).
    pub fn elements_mut(&mut self, surface: Surface) -> &mut GpuMesh {
        match &mut self.loop_ {
            Some(l) if surface.uses_loop_faces() => &mut l.gpu,
            _ => &mut self.gpu,
        }
    }

    /// Skip the slow-frame warning of the next [`Scene::prepare`]s: drawn adaptively, the
    /// elements are not all at the configuration's (largest) level it would count them at
    /// (an adaptive frame warns from the levels chosen, [`Scene::warn_if_slow`]).
    pub fn skip_slow_warning(&mut self) {
        self.warned_slow = true;
    }

    /// [`Scene::warn_if_slow`] unless a slow frame was warned about already (or the warning
    /// skipped, [`Scene::skip_slow_warning`]).
    pub fn warn_once_if_slow(
        &mut self,
        refined: u64,
        weight: Option<EvaluationWeight>,
        advice: &str,
    ) {
        if !self.warned_slow {
            self.warn_if_slow(refined, weight, advice);
        }
    }

    /// Warn when frames of `refined` triangles take a second or more on a software device
    /// ([`software_frame_seconds`]), ending with `advice` (what draws faster); whether or not
    /// [`Scene::prepare`]'s own warning was skipped, which it skips from then on. `weight`:
    /// [`Scene::evaluation_weight`], how many times its triangles' cost such a frame takes.
    pub fn warn_if_slow(&mut self, refined: u64, weight: Option<EvaluationWeight>, advice: &str) {
        let factor = weight.map_or(1.0, |w| w.factor);
        let slow = software_frame_seconds((refined as f64 * factor) as u64)
            .filter(|_| self.ctx.info.device_type == vk::PhysicalDeviceType::CPU);
        if let Some((lo, hi)) = slow {
            let (a, b) = SOFTWARE_NS_PER_TRIANGLE;
            let heavier = match weight.filter(|w| w.factor >= 1.5) {
                Some(w) => format!(
                    ", {:.1} times that on average here: a vertex sums its Loop face's control points, up to {} on this mesh against {REGULAR_CONTROL_POINTS} on a regular face",
                    w.factor, w.most
                ),
                None => String::new(),
            };
            log::warn!(
                "{refined} refined triangles per frame on a software device ({}): about {} s a frame ({a:.0} to {b:.0} ns a triangle there{heavier}); {advice}",
                self.ctx.info.name,
                seconds_range(lo, hi)
            );
            self.warned_slow = true;
        }
    }

    /// How many times its triangles' cost a frame of `cfg` takes on a software device, for
    /// the slow-frame warning; `None` but for `loop` drawn on the GPU of a software device
    /// (the only one warned about). Each vertex of a Loop
    /// face sums the face's `K` control points (12 on a regular face; an extraordinary vertex's
    /// valence plus 6 around it), so a face counts `max(1, K / 12)` times its triangles: the
    /// mean over the triangles drawn at the levels `chosen` (an adaptive frame's, where the
    /// level pass's mirror chose them), or at the configuration's level on every face (also
    /// where the levels were uploaded instead of the pass, and not kept).
    pub fn evaluation_weight(
        &self,
        cfg: &super::DrawConfig,
        chosen: Option<&super::ChosenLevels>,
    ) -> Option<EvaluationWeight> {
        // Only a software device is warned about (what an estimate of it is for).
        if self.ctx.info.device_type != vk::PhysicalDeviceType::CPU {
            return None;
        }
        let data = &self
            .loop_
            .as_ref()
            .filter(|_| cfg.surface.uses_loop_faces())?
            .data;
        // `static` evaluates on the CPU before the frame: its frames draw triangles alone.
        if cfg.driver.kind().refines_on_cpu() {
            return None;
        }
        let levels = chosen.and_then(|c| c.levels());
        let dyadic = cfg.dyadic_levels();
        let (mut triangles, mut weighted, mut most) = (0.0f64, 0.0f64, 0u32);
        for (i, face) in data.faces.iter().enumerate() {
            let level = match &levels {
                Some(l) => l
                    .get(i)
                    .map_or(0, |l| drawn_level(l.inner, dyadic, cfg.level)),
                None => cfg.level,
            };
            let k = face[1] & 0xffff;
            let t = match level {
                0 => 0.0,
                l => cfg.driver.refined_per_element(l) as f64,
            };
            triangles += t;
            weighted += t * (k as f64 / REGULAR_CONTROL_POINTS as f64).max(1.0);
            most = most.max(k);
        }
        (triangles > 0.0).then(|| EvaluationWeight {
            factor: weighted / triangles,
            most,
        })
    }

    /// The records of [`Scene::elements`].
    pub fn records(&self, surface: Surface) -> &[ElementRecord] {
        match &self.loop_ {
            Some(l) if surface.uses_loop_faces() => &l.data.records,
            _ => &self.data.records,
        }
    }

    /// GPU bytes of geometry `cfg` draws from, uniformly or (`adaptive`) adaptively: the
    /// driver's own ([`super::DrawConfig::geometry_bytes`] of the elements) and, for loop, M1,
    /// its passes' data and the tables.
    pub fn geometry_bytes(&self, cfg: &super::DrawConfig, adaptive: bool) -> u64 {
        if let Some(bytes) = self.static_adaptive_bytes(cfg) {
            return bytes;
        }
        let elements = self.elements(cfg.surface).element_count as u64;
        cfg.geometry_bytes(elements, adaptive) + self.pre_pass(cfg).map_or(0, |p| p.gpu_bytes())
    }

    /// The bytes of the static buffer refined adaptively for `cfg` (each element at its own
    /// level, not `cfg.level`), when that is what the scene holds.
    fn static_adaptive_bytes(&self, cfg: &super::DrawConfig) -> Option<u64> {
        let vbo = self.static_vbo.as_ref()?;
        let same = cfg.driver.kind().refines_on_cpu()
            && (vbo.cfg.surface, vbo.cfg.displace, vbo.cfg.level)
                == (cfg.surface, cfg.displace, cfg.level);
        same.then_some(vbo.adaptive.as_ref()?.upload_bytes)
    }

    /// The passes `cfg` runs before drawing (Loop's M0 -> M1 on the GPU drivers; `static`
    /// draws what the CPU evaluated).
    pub fn pre_pass(&self, cfg: &super::DrawConfig) -> Option<&LoopPass> {
        match &self.loop_ {
            _ if cfg.driver.kind().refines_on_cpu() => None,
            Some(l) if cfg.surface.uses_loop_faces() => Some(&l.pass),
            _ => None,
        }
    }

    /// Replace the height map (between frames): uploaded, and the static buffer rebuilt.
    pub fn set_heightmap(
        &mut self,
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
        map: Heightmap,
    ) -> Result<(), RenderError> {
        self.heightmap = map;
        self.reupload(ctx, pool, renderer)
    }

    /// Replace the scalar tags (between frames), checked against appendix B's restrictions.
    pub fn set_tags(
        &mut self,
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
        tags: Vec<VertexTag>,
    ) -> Result<(), RenderError> {
        assert_eq!(tags.len(), self.data.mesh.positions.len());
        self.tags = tags;
        self.reupload(ctx, pool, renderer)
    }

    fn reupload(
        &mut self,
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &super::Renderer,
    ) -> Result<(), RenderError> {
        self.gpu = GpuMesh::new(
            ctx,
            pool,
            &renderer.mesh_layout,
            &self.data,
            Patterns::Upload(&self.patterns),
            self.max_chunk,
            Extras {
                heightmap: &self.heightmap,
                tags: &self.tags,
                loop_: None,
            },
        )?;
        self.generation += 1;
        self.static_vbo = None;
        self.records_stale = false;
        Ok(())
    }

    /// The height map's pyramid level for refinement level `level` ([`Heightmap::lod_for`]).
    pub fn heightmap_lod(&self, level: u32) -> f32 {
        self.heightmap.lod_for(self.data.uv_extent, level)
    }

    /// What the scene holds for the CPU mirrors to read besides the records (texture
    /// coordinates, the height map read at refinement level `level`, tags, Loop's M1 and tables
    /// once prepared for loop).
    pub fn sources(&self, level: u32) -> Sources<'_> {
        Sources {
            uvs: self.data.uvs.as_deref(),
            heightmap: Some(&self.heightmap),
            lod: self.heightmap_lod(level),
            tags: Some(&self.tags),
            loop_: self.loop_.as_ref().map(|l| {
                let frame = l
                    .frame
                    .get_or_init(|| l.data.frame(&self.data.mesh.positions));
                (&l.data, frame)
            }),
        }
    }

    /// The CPU mirror of what `cfg` draws (its surface and displacement with the inputs they
    /// declare, from [`Scene::sources`] at `level`), or the sentence saying what it lacks
    /// (loop before the scene was prepared for it; a height map without texture coordinates).
    pub fn mirror(&self, cfg: &super::DrawConfig, level: u32) -> Result<Mirror<'_>, RenderError> {
        Mirror::new(cfg.surface, cfg.displace, &cfg.build, &self.sources(level))
            .map_err(RenderError::Incompatible)
    }

    /// Centre and radius of the mesh's bounding sphere.
    pub fn bounding_sphere(&self) -> (glam::Vec3, f32) {
        let (lo, hi) = self.data.mesh.bounds();
        let c = (lo + hi) * 0.5;
        (c, ((hi - lo) * 0.5).length().max(1e-6))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn software_frames_over_a_second_are_estimated() {
        assert_eq!(software_frame_seconds(1_000_000), None);
        // Spot's 372 triangles at level 1024: 390 M triangles, tens of seconds or more.
        let (lo, hi) = software_frame_seconds(372 * 1024 * 1024).unwrap();
        assert!(lo > 30.0 && hi < 200.0 && lo < hi, "{lo} {hi}");
        assert_eq!(seconds_range(lo, hi), "39 to 156");
        // The smallest frame warned about: its lower end is not rounded to 0.
        let (lo, hi) = software_frame_seconds(2_500_000).unwrap();
        assert_eq!(seconds_range(lo, hi), "0.2 to 1.0");
        assert_eq!(seconds_range(2.5, 9.99), "2.5 to 10");
    }
}
