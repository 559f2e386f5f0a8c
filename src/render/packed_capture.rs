//! The adaptive pattern driver's capture, packed: each element's vertices at the inner level it
//! is drawn at only, so that a capture holds what the chosen levels draw rather than every
//! element's finest pattern (docs/architecture.md, "Levels"). The levels are read back once
//! (an export is not a per-frame path), each element's slots counted from its inner level
//! ([`packed_offsets`]), and the vertex stage writes vertex `(i, j)` of its inner level's lattice
//! at the element's first slot plus that lattice's index (glsl/pattern/adaptive.vert), counting
//! what falls outside its element's room instead of writing it.

use super::headless::{CapturePlan, VERTEX_BYTES};
use super::{Camera, CaptureResult, DrawConfig, Headless, RenderError, Scene};
use crate::gpu::{vk, Buffer, BufferDesc};
use crate::lod::levels::ElementLevels;
use crate::pattern::adaptive::drawn_levels;
use crate::pattern::vertex_count;

/// Each element's first slot in the packed capture, and one past the last element's last:
/// `vertex_count(inner)` slots an element drawn at inner level `inner`, none where culled (0).
pub fn packed_offsets(inner_levels: &[u32]) -> Vec<u64> {
    let mut offsets = Vec::with_capacity(inner_levels.len() + 1);
    let mut slot = 0u64;
    offsets.push(slot);
    for &l in inner_levels {
        slot += if l == 0 { 0 } else { vertex_count(l) as u64 };
        offsets.push(slot);
    }
    offsets
}

/// The passes of a packed capture whose buffers hold at most `per_pass` slots (at least the
/// largest element's): consecutive elements, as many as fit.
pub fn packed_passes(offsets: &[u64], per_pass: u64) -> Vec<std::ops::Range<u32>> {
    let n = offsets.len().saturating_sub(1) as u32;
    let mut passes = Vec::new();
    let mut first = 0;
    while first < n {
        let mut end = first + 1;
        while end < n && offsets[end as usize + 1] - offsets[first as usize] <= per_pass {
            end += 1;
        }
        passes.push(first..end);
        first = end;
    }
    passes
}

impl Headless {
    /// [`Headless::capture`] of the pattern driver drawing adaptively: the levels the frames
    /// draw read back, each element captured at its inner level, in passes of at most `limit`
    /// bytes (named by the limit that sets it).
    pub(super) fn capture_packed(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
        (limit, limit_name): (u64, &'static str),
    ) -> Result<CaptureResult, RenderError> {
        let n = self.prepared_elements(scene, cfg, super::Capture::Vertices)?;
        cfg.driver.kind().check_adaptive(&self.ctx, scene, cfg)?;
        let inner: Vec<u32> = self
            .levels_drawn(scene, cfg)?
            .iter()
            .take(n as usize)
            .map(|l| drawn_levels(l, cfg.level, cfg.dyadic_levels()).map_or(0, |d| d.inner))
            .collect();
        let offsets = packed_offsets(&inner);
        let total = offsets.last().copied().unwrap_or(0);
        let remedy = |largest: u32| {
            let fits = (0..largest.max(1).ilog2())
                .rev()
                .map(|k| 1u32 << k)
                .find(|&l| vertex_count(l) as u64 * VERTEX_BYTES <= limit);
            match fits {
                Some(l) => format!(
                    "use a larger --pixel-error, or --max-level {l} or a smaller power of two"
                ),
                None => "use a larger --pixel-error".to_string(),
            }
        };
        let largest = inner.iter().copied().max().unwrap_or(0);
        let per_element = vertex_count(largest) as u64;
        if per_element * VERTEX_BYTES > limit {
            return Err(RenderError::OverLimit {
                what: format!(
                    "capturing the {per_element} evaluated vertices of one element drawn at level {largest}"
                ),
                needed: per_element * VERTEX_BYTES,
                unit: "bytes",
                limit: limit_name,
                max: limit,
                remedy: remedy(largest),
            });
        }
        if total > u32::MAX as u64 {
            return Err(RenderError::OverLimit {
                what: format!("capturing the {total} vertices the levels chosen draw"),
                needed: total,
                unit: "vertices",
                limit: "the 32-bit capture slots' range",
                max: u32::MAX as u64,
                remedy: remedy(largest),
            });
        }
        let ranges = packed_passes(&offsets, limit / VERTEX_BYTES);
        let passes: Vec<CapturePlan> = ranges
            .into_iter()
            .map(|e| {
                let (first, end) = (offsets[e.start as usize], offsets[e.end as usize]);
                CapturePlan {
                    elements: e,
                    base: first as u32,
                    slots: Some(end - first),
                }
            })
            .collect();
        let capacity = passes.iter().filter_map(|p| p.slots).max().unwrap_or(0);
        let words: Vec<u32> = offsets.iter().map(|&o| o as u32).collect();
        let mut slots = Buffer::new(
            &self.ctx,
            BufferDesc::new_upload(words.len() as u64 * 4, vk::BufferUsageFlags::STORAGE_BUFFER),
            "capture offsets",
        )?;
        slots.write_pod(0, &words);
        let (vertices, stats) =
            self.capture_passes(scene, cfg, camera, &passes, capacity, Some(&slots))?;
        Ok(CaptureResult {
            vertices,
            pattern_vertex_count: vertex_count(cfg.level),
            inner_levels: Some(inner),
            stats,
        })
    }

    /// The levels the adaptive frames of `cfg` draw: the level pass run alone where they carry
    /// it (each frame runs it again, to the same levels), then the mesh's levels buffer read.
    fn levels_drawn(
        &mut self,
        scene: &Scene,
        cfg: &DrawConfig,
    ) -> Result<Vec<ElementLevels>, RenderError> {
        let mesh = scene.elements(cfg.surface);
        if let Some((pass, view)) = scene.level_pass(cfg) {
            self.pool.submit_and_wait(|cmd| {
                pass.cmd_record(cmd, mesh, &view);
                cmd.barrier_to_host();
            })?;
        }
        Ok(mesh.levels.read_pod())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each element's slots follow the previous one's, `vertex_count(inner)` of them and none
    /// for a culled element; passes take consecutive elements while their slots fit.
    #[test]
    fn packed_slots_and_passes() {
        let offsets = packed_offsets(&[1, 0, 4, 2, 0]);
        assert_eq!(offsets, [0, 3, 3, 18, 24, 24]);
        assert_eq!(packed_passes(&offsets, 100), vec![0..5]);
        assert_eq!(packed_passes(&offsets, 15), [0..2, 2..3, 3..5]);
        assert_eq!(packed_passes(&offsets, 21), [0..3, 3..5]);
        assert!(packed_passes(&packed_offsets(&[]), 10).is_empty());
    }
}
