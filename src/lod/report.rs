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
