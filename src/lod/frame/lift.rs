//! The lift: at integer levels ([`super::Rounding::SnappedInteger`], the pattern driver without
//! geomorphing and the static baseline), an edge drawn a little coarser than an element's inside
//! costs that element a raise of its inner level (step 2 of [`super::transitions`]: along an
//! edge finer than half the inside, the snapped boundary's moves are as long as a lattice side,
//! and its transition triangles need a finer inside). Drawing the edge at the element's own
//! inner level instead leaves no transition there at all; it costs nothing more where every
//! other element of the edge is drawn at least that fine already (or draws nothing).
//!
//! So, after the levels of every element are chosen (the first pass: edges, the inner level
//! its own bounds need, [`Before::own`], and the raised one, [`Before::inner`]), a second pass
//! gives each edge the largest of its level and the levels `n` proposed for it: an element
//! proposes its own (unraised) inner level `n` for an edge whose transition triangles do not
//! fit at `n` ([`Before::failing`], step 2's first test), where `n` is above the edge's drawn
//! level and the element across the edge draws at least `n` (or nothing, or there is none).
//! An element with a lifted edge then chooses its inner level again from its edges, as the
//! first pass does (its own need, at least its finest edge, raised where a coarser edge's
//! triangles still do not fit).
//!
//! Both elements of an edge compute its lifted level from the same inputs (the edge's level,
//! the same bits in both; both elements' [`Before`]) with the same operations, so they sample
//! the edge identically, as before the lift. The bound still holds: a lifted edge is finer than
//! its own and its transition needs ask (an edge's curve, its bases and its corners only get
//! shorter, [`super::transitions`] step 1), and the second pass's step 2 checks every edge
//! still coarser than the inside on the lifted levels. An edge shared by three elements or more
//! is never lifted.
//!
//! The lift reads each element's neighbours ([`super::LodRecord::neighbours`]), so on the GPU it
//! is a second dispatch of the level pass, after every element's first levels are written
//! (glsl/lod/levels.comp, `lift_levels`). On Spot close up as `pn` (0.5 to 4 px) it draws
//! 0.31-0.33x the triangles of the smallest uniform level meeting the bound, where the first
//! pass alone draws 0.34-0.36x (docs/benchmarks.md). Lifting also where the element across must
//! then be drawn finer draws more: always, 0.33-0.35x; where its added triangles are fewer than
//! half those the raise saves, 0.32-0.34x. A second round of lifts (a third dispatch) draws
//! 0.1-1.4 % fewer triangles than one. The dyadic roundings are not lifted:
//! their coarser edges are at most half the inside, where the transitions rarely need a raise,
//! and a gliding edge must change continuously with the camera; the tessellator's integer
//! levels take transitions that need no raise.
#![forbid(unsafe_code)]

use super::{own_level_above, raise_for_transitions, LodRecord, LodView};
use crate::lod::levels::{drawn_level, ElementLevels};

/// [`LodRecord::neighbours`] of an edge no other element has.
pub const BOUNDARY: u32 = u32::MAX;
/// [`LodRecord::neighbours`] of an edge more than two elements have (never lifted).
pub const SHARED: u32 = u32::MAX - 1;

/// What the lift reads of an element's first levels (on the GPU, one `vec4` per element:
/// `own`, `inner`, `failing` as a float, 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Before {
    /// The continuous inner level its own bounds and its edges need, before step 2's raise.
    pub own: f32,
    /// Its inner level after the raise; 0: culled.
    pub inner: f32,
    /// Bit `e`: edge `e`'s transition triangles do not fit at `own`'s drawn level.
    pub failing: u32,
}

impl Before {
    pub const CULLED: Before = Before {
        own: 0.0,
        inner: 0.0,
        failing: 0,
    };

    pub fn new(own: f32, inner: f32, failing: u32) -> Self {
        Self {
            own,
            inner,
            failing,
        }
    }

    fn culled(&self) -> bool {
        self.inner <= 0.0
    }

    /// The level `n` it proposes for its edge in slot `slot` (0: none), given the element on
    /// the other side (`None`: there is none).
    fn proposal(&self, slot: usize, edge: u32, other: Option<&Before>, max: u32) -> u32 {
        let n = drawn_level(self.own, false, max);
        let across = other
            .filter(|o| !o.culled())
            .map_or(u32::MAX, |o| drawn_level(o.inner, false, max));
        if self.failing >> slot & 1 != 0 && n > edge && n <= across {
            n
        } else {
            0
        }
    }
}

/// Element `r`'s levels after the lift, from its first levels `l` and what the first pass left
/// of every element (`before`, its own at `me`). Mirror: `lift_levels` in glsl/lod/levels.comp.
pub fn lifted(
    v: &LodView,
    r: &LodRecord,
    l: &ElementLevels,
    me: &Before,
    before: &[Before],
) -> ElementLevels {
    if me.culled() {
        return *l;
    }
    let max = v.max_level;
    let mut edges = l.edges;
    for (e, &across) in r.neighbours[..3].iter().enumerate() {
        if across == SHARED {
            continue;
        }
        let drawn = drawn_level(l.edges[e], false, max);
        let other = (across != BOUNDARY).then(|| &before[(across / 4) as usize]);
        let mut n = me.proposal(e, drawn, other, max);
        if let Some(o) = other.filter(|o| !o.culled()) {
            n = n.max(o.proposal((across % 4) as usize, drawn, Some(me), max));
        }
        if n > 0 {
            edges[e] = n as f32;
        }
    }
    if edges == l.edges {
        return *l;
    }
    let own = own_level_above(v, r, edges[0].max(edges[1]).max(edges[2]));
    let (inner, _) = raise_for_transitions(v, r, &edges, own);
    ElementLevels { edges, inner }
}
