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
    /// Elements culled: outside the view frustum (their bounding spheres are) or facing away.
    pub culled: u64,
    /// Of those, the ones culled for facing away (their spheres inside the view), where the
    /// report was made with the records (`Scene::set_levels`, `info`); 0 in a tally of levels
    /// alone (`Scene::drawn_levels`).
    pub facing_away: u64,
    /// The smallest level that, given to every element, meets the same pixel error on every
    /// visible one (`lod::frame::uniform_level`: any integer, a power of two where the bounds
    /// hold only there, without the transitions an adaptive frame draws, so possibly below its
    /// largest level; 1 when none is visible).
    pub uniform_level: u32,
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

    /// The triangles the visible elements make at their inner levels, and every element at
    /// [`LevelReport::uniform_level`], on a driver that draws `per_element(l)` triangles for an
    /// element at level `l` (`Driver::refined_per_element`: `N²` on the pattern and static
    /// drivers, the tessellator's count for `tess`, each element counted with its edges at its
    /// inner level).
    pub fn triangles_on(&self, per_element: impl Fn(u32) -> u32) -> (u64, u64) {
        let adaptive = (self.histogram.iter())
            .map(|(&l, &n)| n * per_element(l) as u64)
            .sum();
        let elements = self.histogram.values().sum::<u64>() + self.culled;
        (adaptive, elements * per_element(self.uniform_level) as u64)
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
    /// bound, those needing a level above `max`. What `render`, `view` and `export` print on
    /// standard error, and the window when they change.
    pub fn notes(&self, pixel_error: f32, max: u32) -> Vec<String> {
        let why_unbounded = "docs/adaptivity.md says where none exists";
        let elements = |n: u64, one: &str, many: &str| {
            let verb = if n == 1 { one } else { many };
            format!("{n} element{} {verb}", if n == 1 { "" } else { "s" })
        };
        // The pronouns of one element or several: (they, them, their, are).
        let words = |n: u64| match n {
            1 => ("it", "it", "its", "is"),
            _ => ("they", "them", "their", "are"),
        };
        let whatever = |n: u64| {
            let (they, them, their, are) = words(n);
            format!(
                "{they} {are} drawn at the largest level, {max}, whatever --pixel-error, and no pixel error is promised on {them}; --max-level sets {their} level"
            )
        };
        let mut out = Vec::new();
        if self.near > 0 {
            let their = words(self.near).2;
            out.push(format!(
                "note: {} the eye in {their} bounds (no distance bounds {their} error in pixels): {}",
                elements(self.near, "holds", "hold"),
                whatever(self.near)
            ));
        }
        if self.unbounded > 0 {
            out.push(format!(
                "note: {} no finite error bound ({why_unbounded}): {}",
                elements(self.unbounded, "has", "have"),
                whatever(self.unbounded)
            ));
        }
        if self.capped > 0 {
            out.push(format!(
                "note: the {} px bound is not met on {} element{}: {} a level above the largest, {max} (--max-level)",
                px(pixel_error),
                self.capped,
                if self.capped == 1 { "" } else { "s" },
                if self.capped == 1 { "it needs" } else { "they need" }
            ));
        }
        out
    }
}

/// A pixel error, or a camera coordinate, as printed: the shortest decimal that reads back as
/// the same `f32`, in exponent form far from 1 (`1e-30`, not thirty zeros; `2.5e7`).
pub fn px(value: f32) -> String {
    if value != 0.0 && !(1e-3..1e6).contains(&value.abs()) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

/// What one frame's levels draw: for `info`, the benchmark and the window.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LevelStats {
    /// Visible elements per drawn inner level.
    pub histogram: BTreeMap<u32, u64>,
    /// Elements culled (frustum or back faces).
    pub culled: u64,
}

impl LevelStats {
    /// The tally of `levels` as a driver that rounds as `dyadic` says, up to `max`, draws them.
    pub fn new(levels: &[super::levels::ElementLevels], dyadic: bool, max: u32) -> Self {
        let mut s = Self::default();
        for l in levels {
            if l.culled() {
                s.culled += 1;
                continue;
            }
            let n = super::levels::drawn_level(l.inner, dyadic, max);
            *s.histogram.entry(n).or_default() += 1;
        }
        s
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

#[cfg(test)]
mod notes_tests {
    use crate::lod::frame::Unmet;

    #[test]
    fn notes_agree_in_number() {
        let cases = [
            (
                (1, 1, 1),
                vec![
                    "1 element holds the eye in its bounds (no distance bounds its error in pixels): it is drawn at the largest level, 8",
                    "1 element has no finite error bound (docs/adaptivity.md says where none exists): it is drawn",
                    "no pixel error is promised on it; --max-level sets its level",
                    "not met on 1 element: it needs a level above the largest, 8",
                ],
            ),
            (
                (2, 0, 3),
                vec![
                    "2 elements hold the eye in their bounds (no distance bounds their error in pixels): they are drawn",
                    "not met on 3 elements: they need",
                ],
            ),
        ];
        for ((near, unbounded, capped), wanted) in cases {
            let unmet = Unmet {
                near,
                unbounded,
                capped,
                beyond_uniform: capped,
            };
            let notes = unmet.notes(1.0, 8).join("\n");
            for w in wanted {
                assert!(notes.contains(w), "{w:?} not in {notes}");
            }
        }
    }
}
