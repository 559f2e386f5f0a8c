//! Classification: which configuration each M1 face has. Each face's neighbourhood is labelled
//! canonically (the face's corners, then each corner's one-ring counter-clockwise from the next
//! corner), and the labelled faces around the corners are its key; of the six orientations
//! ([`Orient`]) the one with the smallest (frame, key) is the face's. Faces are classified
//! independently, so [`super::build`] shares them among threads.
#![forbid(unsafe_code)]

use super::{Orient, RING_REACH};
use crate::subdiv::Topology;
use std::collections::HashMap;

/// Faces incident to each vertex.
fn vertex_faces(topo: &Topology) -> Vec<Vec<u32>> {
    let mut vf = vec![Vec::new(); topo.vertex_count];
    for (f, t) in topo.faces.iter().enumerate() {
        for &v in t {
            vf[v as usize].push(f as u32);
        }
    }
    vf
}

/// What classification reads of M1 again and again: the faces at each vertex and each vertex's
/// one-ring (counter-clockwise, with its boundary flag).
pub(super) struct Neighbourhoods {
    pub(super) faces: Vec<Vec<u32>>,
    pub(super) rings: Vec<(Vec<u32>, bool)>,
}

impl Neighbourhoods {
    pub(super) fn new(topo: &Topology) -> Self {
        Self {
            faces: vertex_faces(topo),
            rings: (0..topo.vertex_count as u32)
                .map(|v| topo.one_ring(v))
                .collect(),
        }
    }
}

/// A labelling in progress: the vertices in label order, and the label of every M1 vertex
/// (`u32::MAX` for none). Reused face after face: [`Labels::clear`] resets only what was set.
pub(super) struct Labels {
    pub(super) of: Vec<u32>,
    pub(super) order: Vec<u32>,
}

impl Labels {
    pub(super) fn new(vertex_count: usize) -> Self {
        Self {
            of: vec![u32::MAX; vertex_count],
            order: Vec::new(),
        }
    }

    /// Labels `v` next unless it has a label.
    pub(super) fn add(&mut self, v: u32) {
        if self.of[v as usize] == u32::MAX {
            self.of[v as usize] = self.order.len() as u32;
            self.order.push(v);
        }
    }

    pub(super) fn of(&self, v: u32) -> u32 {
        self.of[v as usize]
    }

    pub(super) fn clear(&mut self) {
        for &v in &self.order {
            self.of[v as usize] = u32::MAX;
        }
        self.order.clear();
    }
}

/// Canonical labelling of face `f` in orientation `o` into `labels` (cleared first): the corners,
/// then each corner's one-ring (counter-clockwise, or clockwise for the mirror image, from the
/// next canonical corner, or from the boundary). A boundary fan longer than twice
/// [`RING_REACH`] and two is labelled only that far each way from the face, then its two ends
/// ([`truncated`]).
pub(super) fn label(
    topo: &Topology,
    nb: &Neighbourhoods,
    f: usize,
    o: Orient,
    labels: &mut Labels,
) {
    labels.clear();
    let t = topo.faces[f];
    let corners = [0, 1, 2].map(|i| t[o.stored(i)]);
    for &c in &corners {
        labels.add(c);
    }
    for k in 0..3 {
        let (ring, on_boundary) = &nb.rings[corners[k] as usize];
        let n = ring.len();
        // The ring as walked: reversed for the mirror image, and (inside) started at the face's
        // next corner, a neighbour since the face is (c_k, c_k+1, ...).
        let at = |i: usize| if o.mirror { ring[n - 1 - i] } else { ring[i] };
        let next = corners[(k + 1) % 3];
        if let Some((lo, hi)) = truncated(&at, n, *on_boundary, &corners) {
            for i in (lo..=hi).chain([0, n - 1]) {
                labels.add(at(i));
            }
            continue;
        }
        let start = if *on_boundary {
            0
        } else {
            (0..n).find(|&i| at(i) == next).unwrap_or(0)
        };
        for i in 0..n {
            labels.add(at((start + i) % n));
        }
    }
}

/// Where a boundary fan is longer than 2 · [`RING_REACH`] + 2, the places of its ring (walked
/// by `at` from the boundary, `n` of them) within that reach of the face's other corners. A
/// boundary vertex's rule and limit mask weigh only its two ends, so the face's weights reach no
/// further round the fan than that, and the ends through the vertex's own rule: faces whose
/// fans agree that far have equal tables (all of a wide fan's middle faces, and the faces at
/// the same place from an end whatever the fan's length), known before building them, and
/// their labels and keys say so ([`label`], [`key_of`]).
fn truncated(
    at: &impl Fn(usize) -> u32,
    n: usize,
    on_boundary: bool,
    corners: &[u32; 3],
) -> Option<(usize, usize)> {
    if !on_boundary || n <= 2 * RING_REACH + 2 {
        return None;
    }
    let places: Vec<usize> = (0..n).filter(|&i| corners.contains(&at(i))).collect();
    let (first, last) = (*places.first()?, *places.last()?);
    Some((
        first.saturating_sub(RING_REACH),
        (last + RING_REACH).min(n - 1),
    ))
}

/// How well orientation `o` of face `f` frames it, smaller first: canonical corner 0 is its
/// extraordinary vertex where it has one (else a boundary vertex, else any), and where that
/// corner is on the boundary, canonical corner 1 is on the side of its fan's nearer end.
/// Topological, so alike configurations take alike frames: the rows of two tables for faces
/// whose neighbourhoods agree near the face (a boundary fan's middle faces, whatever the fan's
/// width) then agree far from corner 0, and [`pack`] stores them once.
fn frame(topo: &Topology, nb: &Neighbourhoods, f: usize, o: Orient) -> (u8, usize) {
    let t = topo.faces[f];
    let (c0, c1) = (t[o.stored(0)], t[o.stored(1)]);
    let (ring, on_boundary) = &nb.rings[c0 as usize];
    let class = match (*on_boundary, ring.len()) {
        (false, 6) => 2,
        (true, 4) => 1,
        _ => 0,
    };
    if !on_boundary {
        return (class, 0);
    }
    // The ring as `label` walks it: from the boundary, reversed for the mirror image.
    let n = ring.len();
    let at = |i: usize| if o.mirror { ring[n - 1 - i] } else { ring[i] };
    (class, (0..n).find(|&i| at(i) == c1).unwrap_or(n))
}

/// A face's key in labels (reversed for a mirror image): rotated to start at its smallest label.
fn labelled(t: &[u32; 3], labels: &Labels, mirror: bool) -> [u32; 3] {
    let mut l = t.map(|v| labels.of(v));
    if mirror {
        l.swap(1, 2);
    }
    let m = (0..3).min_by_key(|&k| l[k]).unwrap();
    [l[m], l[(m + 1) % 3], l[(m + 2) % 3]]
}

/// The key of face `f` in orientation `o`, its labels left in `labels`.
fn key_of(
    topo: &Topology,
    nb: &Neighbourhoods,
    f: usize,
    o: Orient,
    labels: &mut Labels,
) -> Vec<[u32; 3]> {
    label(topo, nb, f, o, labels);
    // An inside corner 0's fan is faces (0, 1, 2), (0, 2, 3), ..., (0, n, 1) in labels, whatever
    // the face: where that ring is long, one entry (its length) stands for it, so a face around
    // a vertex of valence n is keyed in the time of labelling it, not of sorting n faces.
    let (ring, on_boundary) = &nb.rings[labels.order[0] as usize];
    let long = !on_boundary && ring.len() > 2 * RING_REACH + 2;
    let corners = if long { 1..3 } else { 0..3 };
    let mut faces: Vec<u32> = labels.order[corners]
        .iter()
        .flat_map(|&c| nb.faces[c as usize].iter().copied())
        .collect();
    faces.sort_unstable();
    faces.dedup();
    // Faces beyond a truncated fan's labels are left out (their labels would say nothing but
    // how wide the fan is), and a marker says the fan was truncated.
    let mut key: Vec<[u32; 3]> = faces
        .iter()
        .map(|&g| labelled(&topo.faces[g as usize], labels, o.mirror))
        .collect();
    let whole = key.len();
    key.retain(|t| !t.contains(&u32::MAX));
    if key.len() < whole {
        key.push([u32::MAX; 3]);
    }
    if long {
        key.push([u32::MAX, u32::MAX, ring.len() as u32]);
    }
    key.sort_unstable();
    key
}

/// An orientation's [`frame`] rank and key: the smallest is the face's canonical orientation.
type Framed = ((u8, usize), Vec<[u32; 3]>);

/// One thread's share of the faces, classified: its distinct keys in order of first appearance
/// (with the face and orientation that showed each first), and every face's key (an index into
/// those), orientation and control points.
pub(super) struct Classified {
    pub(super) keys: Vec<(Vec<[u32; 3]>, usize, Orient)>,
    pub(super) faces: Vec<(u32, Orient, Vec<u32>)>,
}

/// Classifies `range`'s faces; every 1,024 faces adds them to `done` and calls `tick`.
pub(super) fn classify(
    topo: &Topology,
    nb: &Neighbourhoods,
    range: std::ops::Range<usize>,
    done: &std::sync::atomic::AtomicUsize,
    tick: &mut dyn FnMut(),
) -> Classified {
    let mut labels = Labels::new(topo.vertex_count);
    let mut ids: HashMap<Vec<[u32; 3]>, u32> = HashMap::new();
    let mut out = Classified {
        keys: Vec::new(),
        faces: Vec::with_capacity(range.len()),
    };
    for (i, f) in range.enumerate() {
        if i % 1024 == 1023 {
            done.fetch_add(1024, std::sync::atomic::Ordering::Relaxed);
            tick();
        }
        // The smallest (frame, key) over the three rotations and the mirror image: a
        // configuration and its mirror share one table, and faces alike near their
        // extraordinary vertex are in the same frame ([`frame`]).
        // Only the orientations that frame the face best can have the smallest (frame, key):
        // the others' keys (as long as the largest valence at the face) are not computed.
        let frames: Vec<(Orient, (u8, usize))> =
            Orient::all().map(|o| (o, frame(topo, nb, f, o))).collect();
        let first = frames.iter().map(|x| x.1).min().expect("six orientations");
        let mut best: Option<(Framed, Orient, Vec<u32>)> = None;
        for (o, _) in frames.into_iter().filter(|x| x.1 == first) {
            let framed = (first, key_of(topo, nb, f, o, &mut labels));
            if best.as_ref().is_none_or(|b| framed < b.0) {
                best = Some((framed, o, labels.order.clone()));
            }
        }
        let ((_, key), orient, order) = best.expect("six orientations");
        let next = out.keys.len() as u32;
        let id = *ids.entry(key).or_insert_with_key(|key| {
            out.keys.push((key.clone(), f, orient));
            next
        });
        out.faces.push((id, orient, order));
    }
    out
}
