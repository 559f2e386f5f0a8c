//! Reading back every vertex a drawing pipeline evaluated (the capture variants), in passes
//! whose storage buffer stays within the device's limits.

use super::headless::{pass_limit, CapturePlan, CAPTURE_CAP_NAME, VERTEX_BYTES};
use super::xfb_capture::CapturePass;
use super::{
    Camera, Capture, CaptureResult, CapturedVertex, DrawConfig, Headless, RenderError, Scene,
};
use crate::gpu::{vk, Buffer, BufferDesc, PipelineStats};
use crate::pattern::vertex_count;

impl Headless {
    /// Draw with the capture variant of `cfg`'s pipeline and read back every evaluated vertex.
    /// A capture buffer may span at most maxStorageBufferRange bytes, so a large capture is made
    /// in passes, each drawing as many elements as fit. Drawing adaptively, the pattern driver
    /// captures each element at its drawn inner level only, packed ([`CaptureResult`]).
    pub fn capture(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
    ) -> Result<CaptureResult, RenderError> {
        let pv = vertex_count(cfg.level);
        let Some(per_element) = cfg.driver.capture_per_element(cfg.level) else {
            return Err(RenderError::Unsupported(
                "the static driver evaluates on the CPU: there is nothing to capture (use pattern or tess)",
            ));
        };
        let limit = pass_limit(
            (
                self.ctx.info.limits.max_storage_buffer_range as u64,
                "this device's maxStorageBufferRange",
            ),
            self.ctx.info.max_memory_allocation_size,
            self.max_capture_bytes.map(|c| (c, CAPTURE_CAP_NAME)),
        );
        if self.adaptive && !cfg.driver.kind().capture_appends() {
            return self.capture_packed(scene, cfg, camera, limit);
        }
        let (limit, limit_name) = limit;
        let fits = |per: u64| per * VERTEX_BYTES <= limit && per <= u32::MAX as u64;
        if !fits(per_element as u64) {
            let per_at = |l: u32| cfg.driver.capture_per_element(l).unwrap_or(0) as u64;
            let remedy = match (1..cfg.level).rev().find(|&l| fits(per_at(l))) {
                Some(l) => format!("use --level {l} or lower"),
                None => "no level fits it".to_string(),
            };
            return Err(RenderError::OverLimit {
                what: format!("capturing the {per_element} evaluated vertices of one element"),
                needed: per_element as u64 * VERTEX_BYTES,
                unit: "bytes",
                limit: limit_name,
                max: limit,
                remedy,
            });
        }
        let n = self.prepared_elements(scene, cfg, Capture::Vertices)?;
        let per_pass = (limit / (per_element as u64 * VERTEX_BYTES))
            .min(u32::MAX as u64 / per_element as u64)
            .min(n.max(1) as u64) as u32;
        let appends = cfg.driver.kind().capture_appends();
        let passes = (0..n)
            .step_by(per_pass as usize)
            .map(|first| {
                let elements = first..n.min(first + per_pass);
                let slots = (!appends).then(|| elements.len() as u64 * pv as u64);
                CapturePlan {
                    elements,
                    base: 0,
                    slots,
                }
            })
            .collect::<Vec<_>>();
        let capacity = per_pass as u64 * per_element as u64;
        let (vertices, stats) = self.capture_passes(scene, cfg, camera, &passes, capacity, None)?;
        Ok(CaptureResult {
            vertices,
            pattern_vertex_count: pv,
            inner_levels: None,
            stats,
        })
    }

    /// Draw the capture `passes` (each into a buffer of `capacity` slots, zeroed first so that
    /// a missed vertex keeps `w = 0`; `offsets`: the packed capture's per-element slots) and
    /// read back what each wrote, in order.
    pub(super) fn capture_passes(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
        passes: &[CapturePlan],
        capacity: u64,
        offsets: Option<&Buffer>,
    ) -> Result<(Vec<CapturedVertex>, Option<PipelineStats>), RenderError> {
        let n = passes.last().map_or(0, |p| p.elements.end);
        let vertices = Buffer::new(
            &self.ctx,
            BufferDesc::new_readback(
                capacity.max(1) * VERTEX_BYTES,
                vk::BufferUsageFlags::STORAGE_BUFFER,
            ),
            "capture output",
        )?;
        let mut counter = Buffer::new(
            &self.ctx,
            BufferDesc::new_upload(16, vk::BufferUsageFlags::STORAGE_BUFFER),
            "capture counter",
        )?;
        // Without a packed capture the counter stands in for the offsets, which nothing reads.
        let packed = offsets.is_some();
        let offsets = offsets.map_or(counter.raw, |o| o.raw);
        self.renderer
            .set_capture_target(vertices.raw, counter.raw, offsets);
        let wire = std::mem::replace(&mut self.wireframe, false);
        let mut out = Vec::new();
        let mut stats = None;
        let mut result = Ok(());
        for (k, pass) in passes.iter().enumerate() {
            let first = pass.elements.start;
            counter.write_pod(0, &[0u32, capacity as u32, first, pass.base]);
            // Unwritten entries keep w = 0, so a missed vertex is detectable.
            if let Err(e) = self
                .pool
                .submit_and_wait(|cmd| cmd.fill_buffer(&vertices, 0))
            {
                result = Err(e.into());
                break;
            }
            self.passes_reuse = k > 0;
            match self.draw_inner(
                scene,
                cfg,
                camera,
                Capture::Vertices,
                None,
                pass.elements.clone(),
            ) {
                Ok(t) => stats = t.stats,
                Err(e) => {
                    result = Err(e);
                    break;
                }
            }
            let mut read: Vec<CapturedVertex> = vertices.read_pod();
            let count = counter.read_pod::<u32>()[0] as u64;
            match pass.slots {
                // Appended: the counter says how many.
                None if count > capacity => {
                    result = Err(RenderError::CaptureOverflow {
                        written: count,
                        capacity,
                    });
                    break;
                }
                None => read.truncate(count as usize),
                // Packed: the counter holds the vertices there was no room for.
                Some(_) if packed && count > 0 => {
                    result = Err(RenderError::Capture(format!(
                        "the GPU drew {count} vertices at levels other than those the capture was sized for"
                    )));
                    break;
                }
                Some(slots) => read.truncate(slots as usize),
            }
            out.extend(read);
            self.report(CapturePass {
                done: k as u32 + 1,
                passes: passes.len() as u32,
                elements_done: pass.elements.end,
                elements: n,
            });
        }
        self.wireframe = wire;
        self.passes_reuse = false;
        result.map(|()| (out, stats))
    }
}
