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
//! # Transition triangles (the proof)
//! A driver draws an element at inner level `n` (`β = 1/n`) with the vertices of its boundary
//! on the edges' own samples: a vertex on edge `e` at lattice parameter `k/n` moves to a sample
//! of the edge's level `n_e <= n` (`a_e = 1/n_e`) less than `a_e` away (floor in the edge's
//! canonical direction; dyadic or not). When `n_e = n` nothing moves. Otherwise the drawn
//! triangles touching the edge are of three kinds. Their sides are bounded, in the element's
//! lattice directions `d_k` (src/lod/mod.rs), from its second-derivative bounds `M_k >= sup
//! |D²P[d_k, d_k]|` ([`super::Bounds::second`]) and its mixed ones `B_k >= sup |D²P[d_k,
//! d_{k+1}]|` ([`super::Bounds::mixed`]), by expanding the quadratic form `Q = D²P(y)` at any
//! point: `|Q(x u + z v)| <= x² |Q(u)| + z² |Q(v)| + 2|xz| |Q(u, v)|`
//! ([`super::Bounds::second_along`]). `B_k` is each surface's own bound of the mixed term where
//! it has one (a Bézier net's mixed second differences, src/lod/net.rs `Net::mixed`), and never
//! more than polarization's `Σ/2`, `Σ = M_0 + M_1 + M_2` (as `d_k + d_{k+1} = −d_{k+2}`,
//! `2 Q(d_k, d_{k+1}) = Q(d_{k+2}) − Q(d_k) − Q(d_{k+1})`), which is all a surface without one
//! (`loop`) gets. Note `Q(d_e, d_{e+2}) = Q(d_{e+2}, d_e)`, bounded by `B_{e+2}`.
//! - bases on the edge: `0` or `a_e d_e`: `|Q| <= a_e² M_e`;
//! - sides from a moved vertex to the next row: `α d_e + β d_{e+1}` with `−a_e < α < a_e + β`
//!   (floor) or `−a_e < α <= β` (ceiling); expanded on `(d_e, d_{e+1})` when `|α| <= a_e`
//!   (cross term `2|α|β B_e`) and on `(d_e, d_{e+2})` otherwise (`(α − β) d_e − β d_{e+2}`,
//!   `|α − β| <= a_e`, cross term `2|α − β|β B_{e+2}`): with the twist `T_e = 2 max(B_e,
//!   B_{e+2})`, `|Q| <= S_e = a_e² M_e + a_e β T_e + β² max(M_{e+1}, M_{e+2})`, texel extent
//!   `<= a_e + β`;
//! - at a corner between edges `e` and `f`, sides `y d_e + z d_f` with `0 <= y <= a_e`,
//!   `0 <= z <= a_f` (and sides of the second kind): with `m = min(y, z)`, `r = |y − z|`,
//!   `y d_e + z d_f = −m d_g + r d_j` (`g` the third direction, `j` one of `e`, `f`), so
//!   `|Q| <= m² M_g + r² M_j + 2 m r B_x`, `B_x = max_k B_k`, and with `m + r <= A = max(a_e,
//!   a_f)`: `M_x (m + r)² + m r (2 B_x − 2 M_x)`, largest at `m r = 0` or `m = r = A/2`, so
//!   `|Q| <= A² M_c`, `M_c = max(M_x, M_x/2 + B_x/2)`, `M_x = max_k M_k`.
//!
//! With `B_k = Σ/2` these are the bounds written with `Σ` alone; a surface's own mixed bound
//! makes them smaller wherever its twist across the edge is smaller than polarization allows
//! (on a nearly spherical patch of an equilateral element, `|Q(d_e, d_{e+1})|` is about a third
//! of `Σ/2`).
//!
//! Every drawn triangle's error is then at most `9/40` of its sides' largest `|Q|` plus the kink
//! terms at its sides' extent (the lattice triangle's proof, src/lod/mod.rs, holds for any
//! triangle). Two steps make every one of them meet the element's tolerance `τ`:
//! 1. The edge's level includes, for each of its elements, the level at which the chord
//!    `((1 + λ) k_1, 9/40 · max(M_c, M_e + λ T_e + λ² max(M_{e+1}, M_{e+2})) + (1 + λ)² k_2)`
//!    (`k` the kink terms) meets that element's tolerance ([`strip_need`]). So `a_e² · 9/40 M_c`
//!    and the kink terms at `A` fit in `τ`: the corners are covered whatever `n`, and so is
//!    `S_e` whenever `β <= λ a_e`. A dyadic driver takes `λ = 1/2` (a coarser edge is at most
//!    half the inner level, so it rarely needs step 2), an integer one `λ = 1` (no raise is
//!    needed then; step 2 only serves where a level is capped or a bound changes between the
//!    two). On Spot these choices draw fewer triangles than the others tried (`λ = 1/4`, and
//!    the other driver's).
//! 2. The element checks, on the drawn levels ([`LodView::dyadic`] says how the driver
//!    rounds), that `9/40 S_e + k_1 (a_e + β) + k_2 (a_e + β)² <= τ` for every edge drawn
//!    coarser than its inside, and raises its inner level where not: a quadratic
//!    `p β² + q β + r <= τ` solved for `β` (`strip_level`); raising it can make another edge
//!    coarser than it, so this repeats (at most three times). After step 1 this is a safety
//!    net (rounding at the thresholds); by itself, with step 1's share dropped, it would still
//!    keep the guarantee wherever the corners fit (the tests run it so, GPU against CPU).
//!
//! Interior lattice triangles meet `τ` at the element's own level. Where a level is capped at
//! the maximum, or a bound is infinite, nothing is promised (as for the levels themselves).
#![forbid(unsafe_code)]

use super::bound::Lod;
use super::levels::{drawn_level, ElementLevels};
use super::{Bounds, Chord, Frustum, Sphere, View, ELEMENT_FACTOR};
use crate::subdiv::bft::{progress_line, Progress};
use crate::surface::ElementRecord;
use bytemuck::{Pod, Zeroable};
use glam::{Vec3, Vec4};
use std::collections::{BTreeMap, HashMap};

/// The mirror's "no finite bound" (GLSL keeps no infinities): `LOD_HUGE` in glsl/include/lod.glsl.
pub const HUGE: f32 = 3.0e38;

/// One edge slot of a [`LodRecord`] (std430, 96 bytes): the same bits in both elements'.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct LodEdge {
    /// `(c1, c2)` of the edge curve's bound (`zw` unused).
    pub curve: [f32; 4],
    /// The transition needs ([`strip_need`]) `(c1, c2)` of the first element, then of the
    /// second (the first's again on a boundary): `[0]` for a dyadic driver, `[1]` for an
    /// integer one.
    pub needs: [[f32; 4]; 2],
    /// The edge's sphere, the first element's, the second's (centre, radius).
    pub sphere: [f32; 4],
    pub sphere_a: [f32; 4],
    pub sphere_b: [f32; 4],
}

/// What the level pass reads of one element (std430, 368 bytes): its own bounds and its three
/// stored edges'.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct LodRecord {
    /// The element's sphere (centre, radius).
    pub sphere: [f32; 4],
    /// Its normal cone (axis, cosine of the half-angle); cosine 0: none (never back-facing).
    pub cone: [f32; 4],
    /// `(c1, c2)` of its chord bound, then its kink terms per unit segment (`k1`, `k2`).
    pub chord: [f32; 4],
    /// `M_k` per stored direction (`w` unused).
    pub second: [f32; 4],
    /// `B_k` per stored pair of directions `(k, k + 1)` ([`super::Bounds::mixed`]; `w` unused).
    pub mixed: [f32; 4],
    pub edges: [LodEdge; 3],
}

const _: () = assert!(std::mem::size_of::<LodEdge>() == 96);
const _: () = assert!(std::mem::size_of::<LodRecord>() == 368);

/// Cull flags of [`LodView::flags`].
pub const CULL_FRUSTUM: u32 = 1;
pub const CULL_BACK_FACES: u32 = 2;
/// The driver rounds levels to powers of two ([`drawn_level`]).
pub const DYADIC: u32 = 4;

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
    /// [`CULL_FRUSTUM`], [`CULL_BACK_FACES`], [`DYADIC`].
    pub flags: u32,
    /// Elements.
    pub count: u32,
}

const _: () = assert!(std::mem::size_of::<LodView>() == 128);

impl LodView {
    /// `view`'s metric for `count` elements, culling against `frustum` when given and back
    /// faces when `back_faces`, for a driver that draws dyadic levels when `dyadic`.
    pub fn new(
        view: &View,
        frustum: Option<&Frustum>,
        back_faces: bool,
        dyadic: bool,
        count: u32,
    ) -> Self {
        let planes = frustum.map_or([[0.0; 4]; 6], |f| f.planes.map(|p| p.to_array()));
        let flags = if frustum.is_some() { CULL_FRUSTUM } else { 0 }
            | if back_faces { CULL_BACK_FACES } else { 0 }
            | if dyadic { DYADIC } else { 0 };
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

/// The chord an edge's level must meet at element `b`'s tolerance for the transition
/// triangles along stored edge `e` (module notes, step 1), for a driver that rounds as
/// `dyadic` says; zero where the element has no finite bound (nothing is promised there).
pub fn strip_need(b: &Bounds, e: usize, dyadic: bool) -> Chord {
    let (m, mixed) = (b.second, b.mixed);
    let finite = m.iter().chain(&mixed).all(|x| x.is_finite())
        && b.kink.c1.is_finite()
        && b.kink.c2.is_finite()
        && b.chord.c2.is_finite();
    if !finite {
        return Chord::ZERO;
    }
    let twist = twist(&mixed, e);
    let mx = m[0].max(m[1]).max(m[2]);
    let bx = mixed[0].max(mixed[1]).max(mixed[2]);
    let mc = mx.max(0.5 * mx + 0.5 * bx);
    let mb = m[(e + 1) % 3].max(m[(e + 2) % 3]);
    // The transition sides' bound at β = λ a: λ = 1/2 (a dyadic driver's coarser edge is at
    // most half the inner level), λ = 1 (an integer driver's may be just below it).
    let lambda = if dyadic { 0.5 } else { 1.0 };
    let ms = m[e] + lambda * twist + lambda * lambda * mb;
    let h = 1.0 + lambda;
    Chord {
        c1: h * b.kink.c1,
        c2: ELEMENT_FACTOR * mc.max(ms) + h * h * b.kink.c2,
    }
}

/// `T_e = 2 max(B_e, B_{e+2})`: what bounds the cross term of a transition side along stored
/// edge `e` (module notes), per unit `a_e β`. Mirror: `twist` in glsl/lod/levels.comp.
fn twist(mixed: &[f32], e: usize) -> f32 {
    2.0 * mixed[e].max(mixed[(e + 2) % 3])
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
    // The slots of each unique edge, in element order.
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
                second: [b.second[0], b.second[1], b.second[2], 0.0].map(clamp_huge),
                mixed: [b.mixed[0], b.mixed[1], b.mixed[2], 0.0].map(clamp_huge),
                edges: [LodEdge::zeroed(); 3],
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
        // Each element's needs (dyadic, integer) and sphere.
        let need = |&(i, e): &(usize, usize)| {
            let b = &elements[i];
            ([true, false].map(|d| strip_need(b, e, d)), b.sphere)
        };
        let (needs_a, sphere_a) = need(&list[0]);
        let (mut needs_b, mut sphere_b) = list.get(1).map_or((needs_a, sphere_a), need);
        for extra in list.iter().skip(2) {
            let (c, s) = need(extra);
            needs_b = [0, 1].map(|k| needs_b[k].max(c[k]));
            sphere_b = enclosing(sphere_b, s);
        }
        let [ec1, ec2] = chord2(edge.chord);
        let slot = LodEdge {
            curve: [ec1, ec2, 0.0, 0.0],
            needs: [0, 1].map(|k| {
                let ([a1, a2], [b1, b2]) = (chord2(needs_a[k]), chord2(needs_b[k]));
                [a1, a2, b1, b2]
            }),
            sphere: sphere4(&edge.sphere),
            sphere_a: sphere4(&sphere_a),
            sphere_b: sphere4(&sphere_b),
        };
        for &(i, e) in list {
            out[i].edges[e] = slot;
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
    let tol = tolerance(v, s);
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
    let needs = e.needs[if v.dyadic() { 0 } else { 1 }];
    let own = level(v, [e.curve[0], e.curve[1]], e.sphere);
    let a = level(v, [needs[0], needs[1]], e.sphere_a);
    let b = level(v, [needs[2], needs[3]], e.sphere_b);
    own.max(a).max(b)
}

/// The smallest inner level at which the transition triangles along stored edge `e`, drawn at
/// `a = 1/n_e`, meet tolerance `tol` (module notes, step 2), or the maximum level where none
/// does. Mirror: `strip_level` in glsl/lod/levels.comp.
fn strip_level(v: &LodView, r: &LodRecord, e: usize, a: f32, tol: f32) -> f32 {
    let m = r.second;
    let (k1, k2) = (r.chord[2], r.chord[3]);
    let t = twist(&r.mixed, e);
    let mb = m[(e + 1) % 3].max(m[(e + 2) % 3]);
    let p = ELEMENT_FACTOR * mb + k2;
    let q = ELEMENT_FACTOR * a * t + k1 + 2.0 * k2 * a;
    let c = (ELEMENT_FACTOR * a * m[e] + k1 + k2 * a) * a;
    let max = v.max_level as f32;
    if c >= tol {
        return max;
    }
    let d = tol - c;
    // β = (−q + sqrt(q² + 4pd)) / 2p, in the form without cancellation.
    let den = q + (q * q + 4.0 * p * d).sqrt();
    if den <= 0.0 {
        return 1.0;
    }
    let beta = 2.0 * d / den;
    ((1.0 + 1.0 / 65536.0) / beta).clamp(1.0, max)
}

/// Whether sphere `s` lies wholly outside one of the view's planes. Mirror: `lod_outside`.
fn outside(v: &LodView, s: [f32; 4]) -> bool {
    let c = Vec4::from(s).truncate();
    v.planes
        .iter()
        .any(|p| Vec4::from(*p).truncate().dot(c) + p[3] < -s[3])
}

/// Whether the element's cone faces away from the eye everywhere in its sphere. Mirror:
/// `lod_back_facing` (and [`super::NormalCone::back_facing`]).
fn back_facing(v: &LodView, cone: [f32; 4], s: [f32; 4]) -> bool {
    let d3 = Vec4::from(s).truncate() - v.eye();
    let d = d3.length();
    if cone[3] <= 0.0 || d <= s[3] {
        return false;
    }
    let axis = Vec4::from(cone).truncate();
    let beta = (d3.dot(axis) / d).clamp(-1.0, 1.0).acos();
    let gamma = (s[3] / d).asin();
    let theta = cone[3].clamp(-1.0, 1.0).acos();
    beta + gamma + theta < std::f32::consts::FRAC_PI_2 - 1e-4
}

/// One element's levels. Mirror: glsl/lod/levels.comp's `main`.
pub fn element_levels(v: &LodView, r: &LodRecord) -> ElementLevels {
    let edges = [0, 1, 2].map(|e| edge_level(v, &r.edges[e]));
    let culled = (v.flags & CULL_FRUSTUM != 0 && outside(v, r.sphere))
        || (v.flags & CULL_BACK_FACES != 0 && back_facing(v, r.cone, r.sphere));
    if culled {
        return ElementLevels { edges, inner: 0.0 };
    }
    let own = level(v, [r.chord[0], r.chord[1]], r.sphere);
    let inner = own.max(edges[0]).max(edges[1]).max(edges[2]);
    ElementLevels {
        edges,
        inner: raise_for_transitions(v, r, &edges, inner),
    }
}

/// The inner level raised until every transition triangle meets the element's tolerance
/// (module notes, step 2): unchanged where no edge is drawn coarser than the inside or the
/// triangles already fit, else the drawn level that fits (an exact integer).
fn raise_for_transitions(v: &LodView, r: &LodRecord, edges: &[f32; 3], inner: f32) -> f32 {
    let (dyadic, max) = (v.dyadic(), v.max_level);
    if r.chord[1] >= HUGE || r.chord[0] >= HUGE {
        return inner;
    }
    let tol = tolerance(v, r.sphere);
    let drawn_edges = edges.map(|l| drawn_level(l, dyadic, max));
    let mut n = drawn_level(inner, dyadic, max);
    let mut raised = false;
    for _ in 0..4 {
        if n >= max {
            break;
        }
        let mut need = 0.0f32;
        for (e, &ne) in drawn_edges.iter().enumerate() {
            if ne < n {
                need = need.max(strip_level(v, r, e, 1.0 / ne as f32, tol));
            }
        }
        if need <= n as f32 {
            break;
        }
        n = drawn_level(need, dyadic, max);
        raised = true;
    }
    if raised {
        n as f32
    } else {
        inner
    }
}

/// Every element's levels for `view`: the mirror of the level pass.
pub fn frame_levels(view: &LodView, records: &[LodRecord]) -> Vec<ElementLevels> {
    records.iter().map(|r| element_levels(view, r)).collect()
}

/// A largest level no finite bound reaches in practice: levels chosen under it are uncapped
/// ([`unmet`]).
pub const UNCAPPED: u32 = 1 << 20;

/// The visible elements on which the pixel error is not met, because the largest level keeps
/// them from it ([`unmet`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Unmet {
    /// Elements with a finite bound whose bounding sphere (or an edge's) holds the eye: no
    /// distance bounds their error in pixels, no level meets it.
    pub near: u64,
    /// Other elements with no finite bound (a `loop` surface with displacement, a normal field
    /// that may vanish): at the largest level whatever the pixel error.
    pub unbounded: u64,
    /// Elements whose bound needs a level above the largest.
    pub capped: u64,
}

/// Where the levels `levels`, chosen by `view` for `records`, do not meet the pixel error: each
/// visible element drawn at `view.max_level` is chosen again without that cap.
pub fn unmet(view: &LodView, records: &[LodRecord], levels: &[ElementLevels]) -> Unmet {
    let (dyadic, max) = (view.dyadic(), view.max_level);
    let free = LodView {
        max_level: UNCAPPED,
        ..*view
    };
    let mut u = Unmet::default();
    for (r, l) in records.iter().zip(levels) {
        if l.culled() || drawn_level(l.inner, dyadic, max) < max {
            continue;
        }
        match drawn_level(element_levels(&free, r).inner, dyadic, UNCAPPED) {
            n if n >= UNCAPPED => {
                let huge = |c: &[f32; 4]| c[0] >= HUGE || c[1] >= HUGE;
                // The metric's tolerance is zero where a sphere holds the eye (`View::tolerance`).
                let holds_eye = |s: &[f32; 4]| {
                    let s = Vec4::from(*s);
                    (s.truncate() - view.eye()).length() <= s.w
                };
                if huge(&r.chord) || r.edges.iter().any(|e| huge(&e.curve)) {
                    u.unbounded += 1;
                } else if holds_eye(&r.sphere) || r.edges.iter().any(|e| holds_eye(&e.sphere)) {
                    u.near += 1;
                } else {
                    u.capped += 1;
                }
            }
            n if n > max => u.capped += 1,
            _ => {}
        }
    }
    u
}

/// What one frame's levels draw: for `info`, the benchmark and the window.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LevelStats {
    /// Visible elements per drawn inner level.
    pub histogram: BTreeMap<u32, u64>,
    /// Elements culled (frustum or back faces).
    pub culled: u64,
    /// Refined triangles the visible elements make at their drawn inner levels (`N²` each; the
    /// transition triangles along coarser edges make a few less).
    pub triangles: u64,
}

impl LevelStats {
    /// The tally of `levels` as a driver that rounds as `dyadic` says, up to `max`, draws them.
    pub fn new(levels: &[ElementLevels], dyadic: bool, max: u32) -> Self {
        let mut s = Self::default();
        for l in levels {
            if l.culled() {
                s.culled += 1;
                continue;
            }
            let n = drawn_level(l.inner, dyadic, max);
            *s.histogram.entry(n).or_default() += 1;
            s.triangles += n as u64 * n as u64;
        }
        s
    }
}

mod cores;
use cores::on_every_core;

#[cfg(test)]
mod tests;
