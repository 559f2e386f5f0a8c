//! Reading back the triangles the `tess` driver's tessellator made, by transform feedback, in
//! passes whose buffer stays bounded, each pass handed on as it is read.

use super::headless::pass_limit;
use super::tess::tess_triangle_count;
use super::{Camera, Capture, DrawConfig, Headless, RenderError, Scene, XfbVertex};
use crate::gpu::{vk, Buffer, BufferDesc};

/// Bytes of one transform-feedback vertex.
const XFB_VERTEX_BYTES: u64 = std::mem::size_of::<XfbVertex>() as u64;

/// Largest transform-feedback buffer of one capture pass on lavapipe, whose device memory is
/// the host's: a large export is read back and welded pass by pass rather than held whole
/// (docs/platform.md). Other devices use one pass where their limits allow.
pub const LAVAPIPE_MAX_CAPTURE_PASS_BYTES: u64 = 64 << 20;

/// How far a capture is, reported as each pass ends ([`Headless::capture_progress`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CapturePass {
    /// Passes done, of `passes`.
    pub done: u32,
    pub passes: u32,
    /// Elements drawn so far, of `elements`.
    pub elements_done: u32,
    pub elements: u32,
}

impl Headless {
    /// Tell [`Headless::capture_progress`] that the elements before `first` of `n` are captured,
    /// in passes of `per_pass`.
    pub(super) fn report_pass(&mut self, first: u32, n: u32, per_pass: u32) {
        let per_pass = per_pass.max(1);
        self.report(CapturePass {
            done: first.div_ceil(per_pass),
            passes: n.div_ceil(per_pass).max(1),
            elements_done: first,
            elements: n,
        });
    }

    /// Tell [`Headless::capture_progress`] that `pass` is done.
    pub(super) fn report(&mut self, pass: CapturePass) {
        if let Some(report) = self.capture_progress.as_mut() {
            report(pass);
        }
    }

    /// Draw `cfg` (tess) with its transform-feedback variant and read back the triangles the
    /// tessellator made, as evaluated: `(position, normal)` per corner, in primitive order.
    pub fn capture_triangles(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
    ) -> Result<Vec<[XfbVertex; 3]>, RenderError> {
        let mut out = Vec::new();
        self.capture_triangles_each(scene, cfg, camera, |t| out.extend_from_slice(t))?;
        Ok(out)
    }

    /// [`Headless::capture_triangles`] handed to `each` pass by pass, in order, so that no more
    /// than one pass is held at once. The passes draw as many elements as one transform-feedback
    /// buffer holds at `cfg.level` (the largest level when drawing adaptively), the buffer at
    /// most maxTransformFeedbackBufferSize, one allocation, [`Headless::max_capture_bytes`], and
    /// on lavapipe [`LAVAPIPE_MAX_CAPTURE_PASS_BYTES`]; each pass reads back what the device
    /// says it wrote, straight from the mapped buffer.
    pub fn capture_triangles_each(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
        mut each: impl FnMut(&[[XfbVertex; 3]]),
    ) -> Result<(), RenderError> {
        // A level the device cannot tessellate is said as such before its capture's size.
        super::driver::check_level(&self.ctx, cfg)?;
        let per_element = tess_triangle_count(cfg.level) as u64 * 3 * XFB_VERTEX_BYTES;
        let lavapipe = self.ctx.info.is_lavapipe().then_some((
            LAVAPIPE_MAX_CAPTURE_PASS_BYTES,
            "lavapipe's capture pass size",
        ));
        let own = self
            .max_capture_bytes
            .map(|c| (c, super::headless::CAPTURE_CAP_NAME));
        let cap = [own, lavapipe].into_iter().flatten().min_by_key(|c| c.0);
        let (limit, limit_name) = pass_limit(
            (
                self.ctx.info.max_transform_feedback_buffer_size,
                "this device's maxTransformFeedbackBufferSize",
            ),
            self.ctx.info.max_memory_allocation_size,
            cap,
        );
        if self.ctx.info.transform_feedback && per_element > limit {
            // The largest level whose element fits: --level drawing uniformly, --max-level
            // adaptively (the passes are sized at it; a power of two where the draw glides).
            let fits = |l: u32| tess_triangle_count(l) as u64 * 3 * XFB_VERTEX_BYTES <= limit;
            let fitting = (1..cfg.level)
                .rev()
                .filter(|&l| !cfg.glides() || !self.adaptive || l.is_power_of_two())
                .find(|&l| fits(l));
            let remedy = match (fitting, self.adaptive) {
                (Some(l), false) => format!("use --level {l} or lower"),
                (Some(l), true) => format!("use --max-level {l} or lower"),
                (None, _) => "no level fits it".into(),
            };
            return Err(RenderError::OverLimit {
                what: format!(
                    "reading back the {} tessellated triangles of one element",
                    tess_triangle_count(cfg.level)
                ),
                needed: per_element,
                unit: "bytes",
                limit: limit_name,
                max: limit,
                remedy,
            });
        }
        let n = self.prepared_elements(scene, cfg, Capture::Triangles)?;
        let per_pass = (limit / per_element).clamp(1, n.max(1) as u64) as u32;
        let buffer = Buffer::new(
            &self.ctx,
            BufferDesc::new_readback(
                per_pass as u64 * per_element,
                vk::BufferUsageFlags::TRANSFORM_FEEDBACK_BUFFER_EXT,
            ),
            "transform feedback output",
        )?;
        let mut counter = Buffer::new(
            &self.ctx,
            BufferDesc::new_upload(
                4,
                vk::BufferUsageFlags::TRANSFORM_FEEDBACK_COUNTER_BUFFER_EXT,
            ),
            "transform feedback counter",
        )?;
        let wire = std::mem::replace(&mut self.wireframe, false);
        let mut first = 0;
        let result = loop {
            if first >= n {
                break Ok(());
            }
            let count = per_pass.min(n - first);
            let elements = first..first + count;
            counter.write_pod(0, &[0u32]);
            self.passes_reuse = first > 0;
            if let Err(e) = self.draw_inner(
                scene,
                cfg,
                camera,
                Capture::Triangles,
                Some((&buffer, &counter)),
                elements,
            ) {
                break Err(e);
            }
            let written = counter.read_pod::<u32>()[0] as u64;
            if written > buffer.size() {
                break Err(RenderError::CaptureOverflow {
                    written: written / XFB_VERTEX_BYTES,
                    capacity: buffer.size() / XFB_VERTEX_BYTES,
                });
            }
            let bytes = &buffer.mapped()
                [..(written / (3 * XFB_VERTEX_BYTES) * 3 * XFB_VERTEX_BYTES) as usize];
            match bytemuck::try_cast_slice::<u8, [XfbVertex; 3]>(bytes) {
                Ok(triangles) => each(triangles),
                Err(_) => each(&bytemuck::pod_collect_to_vec::<u8, [XfbVertex; 3]>(bytes)),
            }
            first += count;
            self.report_pass(first, n, per_pass);
        };
        self.wireframe = wire;
        self.passes_reuse = false;
        result
    }
}
