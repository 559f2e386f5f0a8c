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
//! 0.1-1.4 % fewer triangles than one. The tessellator's integer levels take transitions that
//! need no raise, and are not lifted.
//!
//! **Gliding.** The dyadic roundings (both drivers while they glide) are lifted otherwise. A
//! vertex on an edge glides with the edge's continuous level, a vertex inside with the
//! element's; an element whose edges come from their curves and transitions alone can have an
//! edge gliding behind what its inside needs, and the triangles between that edge and the rest
//! can miss the pixel error while they morph (an element drawn at level 2 has no vertex of its own:
//! its inside is its three edges' midpoints). So each edge takes the largest of its level and
//! the continuous levels its elements' insides need by their own bounds ([`Before::inside`]:
//! the element's chord bound, which holds over the whole element, its edges included): every
//! vertex of an element drawn at that level then glides at least as far as a uniform glide of
//! the element would, which meets the pixel error (docs/adaptivity.md, "The factor"; the mixed
//! factors between that glide and the finer level are checked, not proven: "What is proven,
//! what is checked"). The lift is a maximum of levels that change continuously with the camera, so edges still glide without popping, and doubles
//! an edge's drawn level exactly where the lifted level passes a power of two, where its new
//! vertices start on the coarser mesh. An element culled this frame still tells its edges its
//! need ([`Before::inside`]): its neighbour's edge must not jump when it turns away. An edge
//! shared by three elements or more is not lifted.
//!
//! Gliding levels need nothing of the first pass but the insides' needs, so there the first
//! pass computes those alone (and culling), and the second every level, once ([`glided`]):
//! each element's edges, lifted, and its inner level, raised for its transitions.
#![forbid(unsafe_code)]

use super::{edge_level, own_level, own_level_above, raise_for_transitions, LodRecord, LodView};
use crate::lod::levels::{drawn_level, ElementLevels};

/// [`LodRecord::neighbours`] of an edge no other element has.
pub const BOUNDARY: u32 = u32::MAX;
/// [`LodRecord::neighbours`] of an edge more than two elements have (never lifted).
pub const SHARED: u32 = u32::MAX - 1;

/// What the lift reads of an element's first levels (on the GPU, one `vec4` per element:
/// `own`, `inner`, `failing` as a float, `inside`). Where levels glide the first pass leaves
/// only `inside` and whether the element is culled ([`Before::inside`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Before {
    /// The continuous inner level its own bounds and its edges need, before step 2's raise.
    pub own: f32,
    /// Its inner level after the raise (where levels glide, 1); 0: culled.
    pub inner: f32,
    /// Bit `e`: edge `e`'s transition triangles do not fit at `own`'s drawn level.
    pub failing: u32,
    /// Where levels glide ([`gliding`]), the continuous level its inside's own bounds need
    /// ([`super::own_level`]), culled or not; else 0.
    pub inside: f32,
}

/// Whether `v`'s levels glide and are lifted for it (the dyadic roundings with [`super::LIFT`]).
pub fn gliding(v: &LodView) -> bool {
    v.dyadic() && v.flags & super::LIFT != 0
}

impl Before {
    pub const CULLED: Before = Before {
        own: 0.0,
        inner: 0.0,
        failing: 0,
        inside: 0.0,
    };

    /// What element `r` leaves where levels glide: its inside's own need, which its edges take
    /// whether it is `culled` or not (so that culling changes no edge of an element that
    /// draws), and whether it draws. Mirror: the gliding branch of `first_levels` in
    /// glsl/lod/levels.comp.
    pub fn inside(v: &LodView, r: &LodRecord, culled: bool) -> Before {
        Before {
            inner: if culled { 0.0 } else { 1.0 },
            inside: own_level(v, r),
            ..Before::CULLED
        }
    }

    pub fn new(own: f32, inner: f32, failing: u32, inside: f32) -> Self {
        Self {
            own,
            inner,
            failing,
            inside,
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

/// Element `r`'s levels after the lift at integer levels, from its first levels `l` and what
/// the first pass left of every element (`before`, its own at `me`). Mirror: `lift_levels` in
/// glsl/lod/levels.comp.
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

/// Element `r`'s levels where they glide, from what the first pass left of every element
/// (`before`, its own at `me`: [`Before::inside`]): each edge the largest of its own level
/// and both its elements' inside needs (an edge of one element: its own; of three or more: not
/// lifted), the inner level the largest of those and its own need, raised where a coarser
/// edge's transition triangles do not fit, as the first pass does at integer levels. Mirror:
/// the gliding branch of `lift_levels` in glsl/lod/levels.comp.
pub fn glided(v: &LodView, r: &LodRecord, me: &Before, before: &[Before]) -> ElementLevels {
    if me.culled() {
        return ElementLevels::CULLED;
    }
    let mut edges = [0, 1, 2].map(|e| edge_level(v, &r.edges[e]));
    for (e, &across) in r.neighbours[..3].iter().enumerate() {
        if across == SHARED {
            continue;
        }
        let other = if across == BOUNDARY {
            me.inside
        } else {
            before[(across / 4) as usize].inside
        };
        // The same maximum from both sides (max is exact and commutative).
        edges[e] = edges[e].max(me.inside.max(other));
    }
    // `own_level_above(v, r, largest)`, the same bits: the larger of the floor and the own need.
    let own = edges[0].max(edges[1]).max(edges[2]).max(me.inside);
    let (inner, _) = raise_for_transitions(v, r, &edges, own);
    ElementLevels { edges, inner }
}
