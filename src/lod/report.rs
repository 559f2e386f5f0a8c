//! What adaptive refinement draws for one camera: the elements at each drawn level and the
//! culled ones, tallied against the smallest uniform level that meets the same pixel error
//! everywhere (`Scene::set_levels`, `info --pixel-error`; the levels are the level pass's,
//! `lod::frame`).

use std::collections::BTreeMap;

/// The levels one camera asks for.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LevelReport {
    /// Elements per inner level (segments per edge), visible elements only.
    pub histogram: BTreeMap<u32, u64>,
    /// Elements outside the view frustum (their bounding spheres are).
    pub culled: u64,
    /// Triangles the visible elements make at their inner levels (`N²` each).
    pub adaptive_triangles: u64,
    /// The smallest level that, given to every element, meets the same pixel error everywhere:
    /// the largest inner level any visible element needs (1 when none is visible).
    pub uniform_level: u32,
    /// Triangles every element makes at [`LevelReport::uniform_level`].
    pub uniform_triangles: u64,
    /// Visible elements on which the pixel error is not met ([`Unmet`](super::frame::Unmet)).
    pub unmet: super::frame::Unmet,
}

impl LevelReport {
    /// `L:n` pairs, level ascending (`4:120 8:30`).
    pub fn histogram_line(&self) -> String {
        let pairs: Vec<String> = self
            .histogram
            .iter()
            .map(|(l, n)| format!("{l}:{n}"))
            .collect();
        pairs.join(" ")
    }

    /// What draws a frame of these levels faster, for the slow-frame warning: elements with no
    /// finite bound, or holding the eye in theirs, are at the largest level whatever the pixel
    /// error, so where they are most of the frame only a smaller largest level does.
    pub fn faster(&self) -> &'static str {
        let fixed = self.unmet.unbounded + self.unmet.near;
        if fixed * 2 >= self.histogram.values().sum::<u64>().max(1) {
            "a smaller --max-level draws faster"
        } else {
            "a larger --pixel-error or a smaller --max-level draws faster"
        }
    }
}

impl super::frame::Unmet {
    /// One `note:` sentence for each kind of element on which `pixel_error` is not met, drawn
    /// at largest level `max`: those holding the eye in their bounds, those with no finite
    /// bound (`loop_displaced`: the loop surface with displacement, which has none), those
    /// needing a level above `max`. What `render`, `view` and `export` print on standard
    /// error, and the window when they change.
    pub fn notes(&self, pixel_error: f32, max: u32, loop_displaced: bool) -> Vec<String> {
        let why_unbounded = if loop_displaced {
            "the loop surface with displacement has none"
        } else {
            "docs/adaptivity.md says where none exists"
        };
        let elements = |n: u64, one: &str, many: &str| {
            let verb = if n == 1 { one } else { many };
            format!("{n} element{} {verb}", if n == 1 { "" } else { "s" })
        };
        let whatever = format!(
            "they are drawn at the largest level, {max}, whatever --pixel-error, and no pixel error is promised on them; --max-level sets their level"
        );
        let mut out = Vec::new();
        if self.near > 0 {
            out.push(format!(
                "note: {} the eye in their bounds (no distance bounds their error in pixels): {whatever}",
                elements(self.near, "holds", "hold")
            ));
        }
        if self.unbounded > 0 {
            out.push(format!(
                "note: {} no finite error bound ({why_unbounded}): {whatever}",
                elements(self.unbounded, "has", "have")
            ));
        }
        if self.capped > 0 {
            out.push(format!(
                "note: the {} px bound is not met on {} element{}: they need a level above the largest, {max} (--max-level)",
                px(pixel_error),
                self.capped,
                if self.capped == 1 { "" } else { "s" }
            ));
        }
        out
    }
}

/// A pixel error as printed: as given where that is short, in exponent form far from 1
/// (`1e-30`, not thirty zeros).
pub fn px(value: f32) -> String {
    if value != 0.0 && !(1e-3..1e6).contains(&value.abs()) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

#[cfg(test)]
mod px_tests {
    #[test]
    fn pixel_errors_print_short() {
        assert_eq!(super::px(1.0), "1");
        assert_eq!(super::px(0.5), "0.5");
        assert_eq!(super::px(1e-30), "1e-30");
        assert_eq!(super::px(2.5e7), "2.5e7");
    }
}
