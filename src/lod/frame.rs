//! Levels per frame from bounds computed once: the level pass's CPU side and its mirror.
//!
//! Bounds depend on the coarse mesh and the surface parameters, never on the camera, so they
//! are computed once ([`lod_records`], with [`super::Lod`]) into one [`LodRecord`] per element;
//! every frame the level pass (`glsl/lod/levels.comp`, `src/render/level_pass.rs`) turns them
//! and the camera ([`LodView`]) into each element's [`ElementLevels`], and [`frame_levels`] is
//! its mirror, operation for operation.
//!
//! Each unique edge (keyed by its corners' global vertex indices, as the canonical order uses
//! them) is bounded once and the very same bits are written into the slots of every element
//! that has it, so both compute the edge's level from identical inputs with identical code.
//! An edge's level is the largest of three: its curve's own (its bound at its sphere), and for
//! each of its (one or two) elements the level the transition triangles along it need (below),
//! at that element's sphere.
//!
//! An element drawn finer than an edge draws transition triangles along it; what both levels
//! need for those to meet the pixel error too, and the proof, are in [`transitions`]: it
//! depends on how the driver rounds levels and snaps its boundary ([`Rounding`]).
#![forbid(unsafe_code)]

use super::bound::Lod;
use super::levels::{drawn_level, ElementLevels};
use super::{Bounds, Chord, Frustum, Sphere, View};
use crate::subdiv::bft::{progress_line, Progress};
use crate::surface::ElementRecord;
use bytemuck::{Pod, Zeroable};
use glam::{Vec3, Vec4};
use std::collections::HashMap;

/// The mirror's "no finite bound" (GLSL keeps no infinities): `LOD_HUGE` in glsl/include/lod.glsl.
pub const HUGE: f32 = 3.0e38;

/// One edge slot of a [`LodRecord`] (std430, 128 bytes): the same bits in both elements'.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct LodEdge {
    /// `(c1, c2)` of the edge curve's bound, then the first and the second element's cubic
    /// terms ([`Bounds::cubic`], [`HUGE`] where there is none: [`edge_need_level`]).
    pub curve: [f32; 4],
    /// The transition needs ([`strip_need`]) `(c1, c2)` of the first element, then of the
    /// second (the first's again on a boundary), for each [`Rounding`] (`[Rounding::index]`).
    pub needs: [[f32; 4]; 4],
    /// The edge's sphere, the first element's, the second's (centre, radius).
    pub sphere: [f32; 4],
    pub sphere_a: [f32; 4],
    pub sphere_b: [f32; 4],
}

/// What the level pass reads of one element (std430, 480 bytes): its own bounds, its three
/// stored edges' and its neighbours across them.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct LodRecord {
    /// The element's sphere (centre, radius).
    pub sphere: [f32; 4],
    /// Its normal cone (axis, cosine of the half-angle); cosine 0: none (never back-facing).
    pub cone: [f32; 4],
    /// `(c1, c2)` of its chord bound, then its kink terms per unit segment (`k1`, `k2`).
    pub chord: [f32; 4],
    /// `M_k` per stored direction, then the polynomial patch's cubic term
    /// ([`Bounds::cubic`], [`HUGE`] where there is none).
    pub second: [f32; 4],
    /// `B_k` per stored pair of directions `(k, k + 1)` ([`super::Bounds::mixed`]; `w` unused).
    pub mixed: [f32; 4],
    pub edges: [LodEdge; 3],
    /// Across each stored edge `e`, the other element that has it and its slot there,
    /// `j * 4 + e'`; [`lift::BOUNDARY`] where no other has it, [`lift::SHARED`] where more than
    /// one other has it (`w` unused): what the lift reads ([`lift`]).
    pub neighbours: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<LodEdge>() == 128);
const _: () = assert!(std::mem::size_of::<LodRecord>() == 480);

/// Cull flags of [`LodView::flags`].
pub const CULL_FRUSTUM: u32 = 1;
pub const CULL_BACK_FACES: u32 = 2;
/// The driver rounds levels to powers of two ([`drawn_level`]).
pub const DYADIC: u32 = 4;
/// The driver draws the lattice inside its boundary (the pattern and static drivers:
/// [`Rounding::Snapped`] with [`DYADIC`], [`Rounding::SnappedInteger`] without); without it, the
/// tessellator's rings ([`Rounding::TessSnapped`] with [`DYADIC`], [`Rounding::Integer`]
/// without).
pub const LATTICE: u32 = 8;
/// A second dispatch lifts edges from what the first left of every element ([`lift`]): at
/// integer levels ([`Rounding::SnappedInteger`], whose inner levels step 2 raises often) to a
/// neighbour's inner level where that saves its transition; at gliding levels (the dyadic
/// roundings) to the continuous level each of its elements' insides needs, so that an edge
/// glides at least as far as the insides beside it (there the first dispatch leaves only each
/// element's inside need, and the second chooses every level: [`lift::glided`]).
pub const LIFT: u32 = 16;
/// The records' bounds hold only where the drawn samples are lattice points, the powers of two
/// this dyadic rounding draws (`loop`'s, built for it: src/surface/loop_bound.rs, "Levels whose
/// samples are not lattice points"): a uniform frame meeting them is drawn at a power of two
/// ([`uniform_level`]). Read on the CPU alone ([`LodView::with_lattice_bounds`]).
pub const LATTICE_BOUNDS: u32 = 32;

/// How a driver rounds an element's levels and draws its boundary along a coarser edge: what
/// the level pass bounds the transition triangles for ([`transitions`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rounding {
    /// Any integer level, the tessellator's transitions (the tess driver without geomorphing):
    /// its outer edges at their own levels, the tessellator joining them to its first ring.
    Integer,
    /// Powers of two, the tessellator drawing every side at the inner level and its outer ring's
    /// vertices snapped as [`Rounding::Snapped`]'s (the tess driver while it glides): the
    /// pattern driver's boundary beside the tessellator's first ring.
    TessSnapped,
    /// Powers of two, every boundary vertex snapped to the nearest sample of its edge, a tie
    /// toward the nearer corner (the pattern driver, and the static baseline built as it draws).
    Snapped,
    /// Any integer level, snapped as [`Rounding::Snapped`] (the pattern driver and the static
    /// baseline without geomorphing: non-nested levels cannot glide).
    SnappedInteger,
}

impl Rounding {
    pub const ALL: [Rounding; 4] = [
        Rounding::TessSnapped,
        Rounding::Integer,
        Rounding::Snapped,
        Rounding::SnappedInteger,
    ];

    /// Whether levels are rounded to powers of two.
    pub fn dyadic(self) -> bool {
        matches!(self, Rounding::TessSnapped | Rounding::Snapped)
    }

    /// Whether boundary vertices move onto the nearest sample of their edge (at most half a
    /// sample), rather than anywhere within a sample (the tessellator's own transitions).
    pub fn snapped(self) -> bool {
        !matches!(self, Rounding::Integer)
    }

    /// Whether the inside is the tessellator's rings rather than the lattice (the tess driver).
    pub fn tessellator(self) -> bool {
        matches!(self, Rounding::Integer | Rounding::TessSnapped)
    }

    /// Where its transition needs are in [`LodEdge::needs`] (the order of [`Rounding::ALL`]).
    pub fn index(self) -> usize {
        match self {
            Rounding::TessSnapped => 0,
            Rounding::Integer => 1,
            Rounding::Snapped => 2,
            Rounding::SnappedInteger => 3,
        }
    }
}

/// The camera as the level pass reads it (push constants, 128 bytes; std140 and std430 alike).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct LodView {
    /// The view-projection's six planes ([`Frustum`]), `n·p + d >= 0` inside.
    pub planes: [[f32; 4]; 6],
    /// The eye, and `K` ([`View::k`]).
    pub eye_k: [f32; 4],
    pub pixel_error: f32,
    pub max_level: u32,
    /// [`CULL_FRUSTUM`], [`CULL_BACK_FACES`], [`DYADIC`], [`LATTICE`], [`LIFT`].
    pub flags: u32,
    /// Elements.
    pub count: u32,
}

const _: () = assert!(std::mem::size_of::<LodView>() == 128);

impl LodView {
    /// `view`'s metric for `count` elements, culling against `frustum` when given and back
    /// faces when `back_faces`, for a driver that rounds levels as `rounding` says.
    pub fn new(
        view: &View,
        frustum: Option<&Frustum>,
        back_faces: bool,
        rounding: Rounding,
        count: u32,
    ) -> Self {
        let planes = frustum.map_or([[0.0; 4]; 6], |f| f.planes.map(|p| p.to_array()));
        let flags = if frustum.is_some() { CULL_FRUSTUM } else { 0 }
            | if back_faces { CULL_BACK_FACES } else { 0 }
            | match rounding {
                Rounding::Integer => 0,
                Rounding::TessSnapped => DYADIC | LIFT,
                Rounding::Snapped => DYADIC | LATTICE | LIFT,
                Rounding::SnappedInteger => LATTICE | LIFT,
            };
        Self {
            planes,
            eye_k: view.eye.extend(view.k).to_array(),
            pixel_error: view.pixel_error,
            max_level: view.max_level.max(1),
            flags,
            count,
        }
    }

    pub fn dyadic(&self) -> bool {
        self.flags & DYADIC != 0
    }

    /// The same view over records whose bounds hold at its powers of two alone where
    /// `lattice` ([`LATTICE_BOUNDS`]; only a dyadic rounding's records can be built so).
    pub fn with_lattice_bounds(self, lattice: bool) -> Self {
        let flag = if lattice && self.dyadic() {
            LATTICE_BOUNDS
        } else {
            0
        };
        Self {
            flags: self.flags & !LATTICE_BOUNDS | flag,
            ..self
        }
    }

    /// The level a uniform frame draws to meet `need` (a continuous level a frame without
    /// gliding needs), up to the largest: any integer, or the power of two at or above it where
    /// the records' bounds hold only there ([`LATTICE_BOUNDS`]).
    pub fn uniform_drawn(&self, need: f32, max: u32) -> u32 {
        drawn_level(need, self.flags & LATTICE_BOUNDS != 0, max)
    }

    pub fn rounding(&self) -> Rounding {
        match (self.flags & DYADIC != 0, self.flags & LATTICE != 0) {
            (false, false) => Rounding::Integer,
            (false, true) => Rounding::SnappedInteger,
            (true, false) => Rounding::TessSnapped,
            (true, true) => Rounding::Snapped,
        }
    }

    fn eye(&self) -> Vec3 {
        Vec4::from(self.eye_k).truncate()
    }
}

fn clamp_huge(x: f32) -> f32 {
    if x.is_finite() {
        x
    } else {
        HUGE
    }
}

fn sphere4(s: &Sphere) -> [f32; 4] {
    s.centre.extend(clamp_huge(s.radius)).to_array()
}

fn chord2(c: Chord) -> [f32; 2] {
    [clamp_huge(c.c1), clamp_huge(c.c2)]
}

/// A sphere containing both (for an edge shared by more than two elements: a conservative
/// stand-in for the extra ones, whose tolerance is no larger than either's).
fn enclosing(a: Sphere, b: Sphere) -> Sphere {
    let d = (b.centre - a.centre).length();
    if d + b.radius <= a.radius {
        return a;
    }
    if d + a.radius <= b.radius {
        return b;
    }
    let r = 0.5 * (d + a.radius + b.radius);
    let centre = a.centre + (b.centre - a.centre) * ((r - a.radius) / d.max(f32::MIN_POSITIVE));
    Sphere {
        centre,
        radius: r * (1.0 + 4.0 * f32::EPSILON),
    }
}

/// An element's corners' global vertex indices (M1's for `loop`): what orders an edge
/// canonically (from the lower index to the higher).
pub fn corner_indices(lod: &Lod, rec: &ElementRecord) -> [u32; 3] {
    lod.mirror.corner_indices(rec)
}

/// The key of an element's stored edge `e`: its corners' global vertex indices, ascending.
fn edge_key(lod: &Lod, rec: &ElementRecord, e: usize) -> (u32, u32) {
    let idx = corner_indices(lod, rec);
    let (a, b) = (idx[e], idx[(e + 1) % 3]);
    (a.min(b), a.max(b))
}

/// Every element's [`LodRecord`]: its bounds, and its edges' (each unique edge bounded once,
/// the same bits in every slot that holds it), each element with its own texture coordinates
/// (the `heightmap` displacement's, [`Lod::for_element`]).
///
/// The bounds are computed on every core (a large `loop` mesh's take seconds to minutes on
/// one: each face's come from its lattice of exact limit points); the result does not depend
/// on how the work is shared.
pub fn lod_records(lod: &Lod, records: &[ElementRecord]) -> Vec<LodRecord> {
    lod_records_reporting(lod, records, progress_line("adaptive levels"))
}

/// [`lod_records`], telling `progress` how far it is (elements and edges bounded), on the
/// calling thread.
pub fn lod_records_reporting(
    lod: &Lod,
    records: &[ElementRecord],
    mut progress: impl FnMut(Progress),
) -> Vec<LodRecord> {
    // The slots of each unique edge, in element order (an element and a slot in one u32:
    // `LodRecord::neighbours`).
    assert!(records.len() < 1 << 30, "{} elements", records.len());
    let mut slots: HashMap<(u32, u32), Vec<(usize, usize)>> = HashMap::new();
    let mut order = Vec::new();
    for (i, rec) in records.iter().enumerate() {
        for e in 0..3 {
            let key = edge_key(lod, rec, e);
            let list = slots.entry(key).or_default();
            if list.is_empty() {
                order.push(key);
            }
            list.push((i, e));
        }
    }
    let total = records.len() + order.len();
    let elements: Vec<Bounds> = on_every_core(
        records.len(),
        |i| lod.for_element(i).element(&records[i]),
        &mut |d| progress(Progress::Bounds(d, total)),
    );
    let mut out: Vec<LodRecord> = elements
        .iter()
        .map(|b| {
            let cone = b.cone.map_or([0.0; 4], |c| c.axis.extend(c.cos).to_array());
            let [c1, c2] = chord2(b.chord);
            let [k1, k2] = chord2(b.kink);
            LodRecord {
                sphere: sphere4(&b.sphere),
                cone,
                chord: [c1, c2, k1, k2],
                second: [b.second[0], b.second[1], b.second[2], b.cubic].map(clamp_huge),
                mixed: [b.mixed[0], b.mixed[1], b.mixed[2], 0.0].map(clamp_huge),
                edges: [LodEdge::zeroed(); 3],
                neighbours: [0; 4],
            }
        })
        .collect();
    let edges: Vec<Bounds> = on_every_core(
        order.len(),
        |k| {
            let (i0, e0) = slots[&order[k]][0];
            lod.for_element(i0).edge(&records[i0], e0)
        },
        &mut |d| progress(Progress::Bounds(records.len() + d, total)),
    );
    for (key, edge) in order.into_iter().zip(edges) {
        let list = &slots[&key];
        // Each element's needs (one per rounding, Rounding::ALL's order) and sphere.
        let need = |&(i, e): &(usize, usize)| {
            let b = &elements[i];
            (Rounding::ALL.map(|d| strip_need(b, e, d)), b.sphere)
        };
        let (needs_a, sphere_a) = need(&list[0]);
        let (mut needs_b, mut sphere_b) = list.get(1).map_or((needs_a, sphere_a), need);
        let cubic_a = elements[list[0].0].cubic;
        let mut cubic_b = list.get(1).map_or(cubic_a, |&(i, _)| elements[i].cubic);
        for extra in list.iter().skip(2) {
            let (c, s) = need(extra);
            needs_b = [0, 1, 2, 3].map(|k| needs_b[k].max(c[k]));
            sphere_b = enclosing(sphere_b, s);
            cubic_b = cubic_b.max(elements[extra.0].cubic);
        }
        let [ec1, ec2] = chord2(edge.chord);
        let slot = LodEdge {
            curve: [ec1, ec2, cubic_a, cubic_b].map(clamp_huge),
            needs: [0, 1, 2, 3].map(|k| {
                let ([a1, a2], [b1, b2]) = (chord2(needs_a[k]), chord2(needs_b[k]));
                [a1, a2, b1, b2]
            }),
            sphere: sphere4(&edge.sphere),
            sphere_a: sphere4(&sphere_a),
            sphere_b: sphere4(&sphere_b),
        };
        for (k, &(i, e)) in list.iter().enumerate() {
            out[i].edges[e] = slot;
            out[i].neighbours[e] = match list.len() {
                1 => lift::BOUNDARY,
                2 => {
                    let (j, f) = list[1 - k];
                    (j * 4 + f) as u32
                }
                _ => lift::SHARED,
            };
        }
    }
    out
}

/// The world distance allowed inside sphere `s`. Mirror: `lod_tolerance`.
fn tolerance(v: &LodView, s: [f32; 4]) -> f32 {
    let dist = (Vec4::from(s).truncate() - v.eye()).length() - s[3];
    v.pixel_error * dist.max(0.0) / v.eye_k[3]
}

/// The continuous level of chord `c` inside sphere `s`, in `[1, max]`. Mirror: `lod_level`
/// (glsl/include/lod.glsl), as [`View::level`] with [`HUGE`] for infinity.
fn level(v: &LodView, c: [f32; 2], s: [f32; 4]) -> f32 {
    level_at(v, c, tolerance(v, s))
}

/// [`level`] at tolerance `tol` (a sphere's, computed once for the levels it gives). Mirror:
/// `level_at` in glsl/lod/levels.comp.
fn level_at(v: &LodView, c: [f32; 2], tol: f32) -> f32 {
    let max = v.max_level as f32;
    if tol > 0.0 && c[0].max(c[1]) < HUGE {
        Chord { c1: c[0], c2: c[1] }.level_for(tol).min(max)
    } else if c[0] == 0.0 && c[1] == 0.0 {
        1.0
    } else {
        max
    }
}

/// The continuous level of an edge slot: the largest of its curve's and both elements'
/// transition needs.
fn edge_level(v: &LodView, e: &LodEdge) -> f32 {
    let needs = e.needs[v.rounding().index()];
    let own = curve_level(v, e);
    let (ta, tb) = (tolerance(v, e.sphere_a), tolerance(v, e.sphere_b));
    let a = edge_need_level(v, [needs[0], needs[1]], e.curve[2], ta, own);
    edge_need_level(v, [needs[2], needs[3]], e.curve[3], tb, a)
}

/// The larger of `floor` and the level an edge needs for one element's transition triangles
/// ([`strip_need`]'s chord `need` at the element's tolerance `tol`): that of the chord or, where
/// the element is a polynomial patch (its cubic term `t` finite), the smaller level of its
/// tighter bound (src/lod/frame/transitions.rs, "Polynomial patches"), which is not computed
/// where the chord's is at most `floor` (it cannot matter there). Mirror: `edge_need_level` in
/// glsl/lod/levels.comp.
pub fn edge_need_level(v: &LodView, need: [f32; 2], t: f32, tol: f32, floor: f32) -> f32 {
    let general = level_at(v, need, tol);
    if general <= floor {
        return floor;
    }
    if t >= HUGE || need[0] != 0.0 || need[1] >= HUGE {
        return general;
    }
    let q = need[1] * transitions::POLYNOMIAL_SHARE;
    let t = t * transitions::need_extent_cubed(v.rounding());
    let n0 = level_at(v, [0.0, q], tol);
    floor.max(general.min(level_at(
        v,
        [0.0, q + inside::glide_factor(v) * t / n0],
        tol,
    )))
}

/// The continuous level an edge's own curve needs (no transitions).
fn curve_level(v: &LodView, e: &LodEdge) -> f32 {
    level(v, [e.curve[0], e.curve[1]], e.sphere)
}

/// Whether sphere `s` lies wholly outside one of the view's planes. Mirror: `lod_outside`.
fn outside(v: &LodView, s: [f32; 4]) -> bool {
    let c = Vec4::from(s).truncate();
    v.planes
        .iter()
        .any(|p| Vec4::from(*p).truncate().dot(c) + p[3] < -s[3])
}

/// Of the elements `levels` culls, those culled for facing away: their spheres are inside the
/// view (what `--cull off` would draw; the others lie outside it).
pub fn culled_facing_away(view: &LodView, records: &[LodRecord], levels: &[ElementLevels]) -> u64 {
    (records.iter().zip(levels))
        .filter(|(r, l)| l.culled() && !(view.flags & CULL_FRUSTUM != 0 && outside(view, r.sphere)))
        .count() as u64
}

/// Whether the element's cone faces away from the eye everywhere in its sphere
/// ([`super::NormalCone::back_facing`]; a cosine of 0 is no cone). Mirror: `lod_back_facing`.
fn back_facing(v: &LodView, cone: [f32; 4], s: [f32; 4]) -> bool {
    let sphere = super::Sphere {
        centre: Vec4::from(s).truncate(),
        radius: s[3],
    };
    let cone = super::NormalCone {
        axis: Vec4::from(cone).truncate(),
        cos: cone[3],
    };
    cone.cos > 0.0 && cone.back_facing(&sphere, v.eye())
}

/// Whether the view culls the element. Mirror: the start of glsl/lod/levels.comp's `main`.
fn element_levels_culled(v: &LodView, r: &LodRecord) -> bool {
    (v.flags & CULL_FRUSTUM != 0 && outside(v, r.sphere))
        || (v.flags & CULL_BACK_FACES != 0 && back_facing(v, r.cone, r.sphere))
}

/// One element's levels ([`ElementLevels::CULLED`] where it is culled) before the lift (all
/// that [`frame_levels`] gives it where the view does not lift). Mirror:
/// glsl/lod/levels.comp's `main`.
pub fn element_levels(v: &LodView, r: &LodRecord) -> ElementLevels {
    // A culled element draws nothing, and an edge's level is computed by each element that
    // draws it: no level is needed here.
    if element_levels_culled(v, r) {
        return ElementLevels::CULLED;
    }
    first_levels(v, r).0
}

/// [`element_levels`] before the lift, with what the integer lift reads of it
/// ([`lift::Before`]).
fn first_levels(v: &LodView, r: &LodRecord) -> (ElementLevels, lift::Before) {
    let edges = [0, 1, 2].map(|e| edge_level(v, &r.edges[e]));
    let own = own_level_above(v, r, edges[0].max(edges[1]).max(edges[2]));
    let (inner, failing) = raise_for_transitions(v, r, &edges, own);
    let levels = ElementLevels { edges, inner };
    (levels, lift::Before::new(own, inner, failing, 0.0))
}

/// The smallest level that, given to every element, meets `view`'s pixel error on every
/// element `levels` draws (up to the largest level): each element's own need and its edges'
/// curves', without the transition needs (a uniform frame has no coarser edges), as an integer
/// (every driver draws any uniform level; a power of two where the records' bounds hold only
/// there, [`LATTICE_BOUNDS`]), so possibly below the largest level the adaptive frame draws; 1
/// when none is drawn.
pub fn uniform_level(view: &LodView, records: &[LodRecord], levels: &[ElementLevels]) -> u32 {
    let max = view.max_level;
    let drawn = *view;
    // A uniform frame does not glide: its levels are those of the integer rounding.
    let view = &LodView {
        flags: view.flags & !DYADIC,
        ..*view
    };
    (records.iter().zip(levels))
        .filter(|(_, l)| !l.culled())
        .map(|(r, _)| drawn.uniform_drawn(own_need(view, r), max))
        .max()
        .unwrap_or(1)
}

/// The level element `r`'s own bounds need, its chord's and its edges' curves', without the
/// transitions to coarser edges (what a uniform frame draws).
fn own_need(view: &LodView, r: &LodRecord) -> f32 {
    let own = own_level(view, r);
    (r.edges.iter())
        .map(|e| curve_level(view, e))
        .fold(own, f32::max)
}

/// Every element's levels for `view`: the mirror of the level pass.
pub fn frame_levels(view: &LodView, records: &[LodRecord]) -> Vec<ElementLevels> {
    let culled = |r: &LodRecord| element_levels_culled(view, r);
    if lift::gliding(view) {
        // The first pass leaves each element's inside need alone; the second chooses every level.
        let before: Vec<_> = (records.iter())
            .map(|r| lift::Before::inside(view, r, culled(r)))
            .collect();
        return (records.iter().zip(&before))
            .map(|(r, me)| lift::glided(view, r, me, &before))
            .collect();
    }
    let (levels, before): (Vec<_>, Vec<_>) = records
        .iter()
        .map(|r| {
            if culled(r) {
                (ElementLevels::CULLED, lift::Before::CULLED)
            } else {
                first_levels(view, r)
            }
        })
        .unzip();
    if view.flags & LIFT == 0 {
        return levels;
    }
    (records.iter().zip(&levels).enumerate())
        .map(|(i, (r, l))| lift::lifted(view, r, l, &before[i], &before))
        .collect()
}

pub use super::report::LevelStats;

mod cores;
use cores::on_every_core;
mod inside;
pub use inside::{own_chord, own_error, own_level, own_level_above};
pub mod lift;
mod unmet;
pub use unmet::{element_unmet, unmet, Unmet, UNCAPPED};
pub mod transitions;
use transitions::raise_for_transitions;
pub use transitions::strip_need;

#[cfg(test)]
mod extent_tests;
#[cfg(test)]
mod lift_tests;
#[cfg(test)]
mod shared_tests;
#[cfg(test)]
mod tests;
