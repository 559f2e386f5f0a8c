//! The half-edge topology Loop subdivides: built from faces (or a mesh's position indices), it
//! refuses what Loop cannot subdivide (a face repeating a vertex, a non-manifold edge or vertex,
//! inconsistent orientation) with one offending edge or vertex (a face repeating a vertex or an
//! edge of more than two faces before any orientation conflict), and walks one-rings
//! counter-clockwise with their boundary flag.
#![forbid(unsafe_code)]

use crate::mesh::Mesh;
use std::collections::HashMap;

/// Why a mesh cannot be Loop-subdivided (one sentence; the caller adds the file).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TopologyError {
    #[error("face {face} repeats vertex {vertex}: Loop subdivision needs triangles of three distinct vertices")]
    RepeatedVertex { face: usize, vertex: u32 },
    #[error(
        "edge ({a}, {b}) is shared by more than two faces: Loop subdivision needs a manifold mesh"
    )]
    NonManifoldEdge { a: u32, b: u32 },
    #[error("edge ({a}, {b}) is used twice in the same direction: the faces around it are not consistently oriented")]
    OrientationConflict { a: u32, b: u32 },
    #[error("vertex {vertex} is non-manifold: its faces form {fans} separate fans, not one disk or half-disk")]
    NonManifoldVertex { vertex: u32, fans: usize },
    /// Past [`crate::subdiv::bft::CONTROL_LIMIT`], estimated before anything is built.
    #[error("its faces after one Loop step would list about {listed} control points (vertex {vertex} has {valence} neighbours, and each face around it lists them all), past the limit of {limit} control points that the basis function tables take")]
    TooManyControlPoints {
        listed: u64,
        vertex: u32,
        valence: usize,
        limit: u64,
    },
}

/// A triangle mesh's half-edge topology. Half-edge `3f + k` runs from corner k of face f to
/// corner k + 1.
#[derive(Clone, Debug)]
pub struct Topology {
    pub faces: Vec<[u32; 3]>,
    pub vertex_count: usize,
    /// The opposite half-edge, or `None` on a boundary.
    pub twin: Vec<Option<u32>>,
    /// One outgoing half-edge per vertex; on a boundary vertex, the boundary edge leaving it (so
    /// walking around from it visits every face).
    pub outgoing: Vec<u32>,
}

impl Topology {
    /// Builds the topology of `faces` over `vertex_count` vertices, refusing what Loop cannot
    /// subdivide: a face repeating a vertex or a non-manifold edge (the first in face order)
    /// before an orientation conflict, which only two faces on an edge can have, and those
    /// before a non-manifold vertex.
    pub fn new(faces: &[[u32; 3]], vertex_count: usize) -> Result<Self, TopologyError> {
        // Every edge's faces are counted before any orientation is compared: three faces on an
        // edge, two of them the same way round, are a non-manifold edge, which no flip mends.
        let mut undirected: HashMap<(u32, u32), u8> = HashMap::with_capacity(3 * faces.len());
        for (f, t) in faces.iter().enumerate() {
            for k in 0..3 {
                if t[k] == t[(k + 1) % 3] {
                    return Err(TopologyError::RepeatedVertex {
                        face: f,
                        vertex: t[k],
                    });
                }
            }
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let n = undirected.entry((a.min(b), a.max(b))).or_default();
                *n += 1;
                if *n > 2 {
                    return Err(TopologyError::NonManifoldEdge {
                        a: a.min(b),
                        b: a.max(b),
                    });
                }
            }
        }
        let mut directed: HashMap<(u32, u32), u32> = HashMap::with_capacity(3 * faces.len());
        for (f, t) in faces.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if directed.insert((a, b), (3 * f + k) as u32).is_some() {
                    return Err(TopologyError::OrientationConflict { a, b });
                }
            }
        }
        let half = 3 * faces.len();
        let head = |h: usize| faces[h / 3][(h % 3 + 1) % 3];
        let tail = |h: usize| faces[h / 3][h % 3];
        let twin: Vec<Option<u32>> = (0..half)
            .map(|h| directed.get(&(head(h), tail(h))).copied())
            .collect();
        // Every vertex's fans: walk counter-clockwise (next outgoing = twin of the previous edge
        // of the face) from each outgoing half-edge not yet visited.
        let mut outgoing_of: Vec<Vec<u32>> = vec![Vec::new(); vertex_count];
        for h in 0..half {
            outgoing_of[tail(h) as usize].push(h as u32);
        }
        let prev = |h: u32| 3 * (h / 3) + (h % 3 + 2) % 3;
        let mut outgoing = vec![u32::MAX; vertex_count];
        for (v, hs) in outgoing_of.iter().enumerate() {
            if hs.is_empty() {
                continue;
            }
            // The walk goes h -> twin(prev(h)); on a boundary vertex it must start at the
            // outgoing half-edge nothing leads to: the boundary edge leaving v (no twin).
            let start = hs
                .iter()
                .copied()
                .find(|&h| twin[h as usize].is_none())
                .unwrap_or(hs[0]);
            // Count the half-edges reached from `start` going counter-clockwise.
            let mut seen = 1;
            let mut h = start;
            loop {
                match twin[prev(h) as usize] {
                    Some(t) if t != start => {
                        h = t;
                        seen += 1;
                        if seen > hs.len() {
                            break;
                        }
                    }
                    _ => break,
                }
            }
            if seen != hs.len() {
                // Two or more fans meet at this vertex.
                let fans = hs.len().div_ceil(seen.max(1)).max(2);
                return Err(TopologyError::NonManifoldVertex {
                    vertex: v as u32,
                    fans,
                });
            }
            outgoing[v] = start;
        }
        Ok(Self {
            faces: faces.to_vec(),
            vertex_count,
            twin,
            outgoing,
        })
    }

    /// The topology of `mesh`'s positions.
    pub fn of_mesh(mesh: &Mesh) -> Result<Self, TopologyError> {
        Self::new(&mesh.position_indices(), mesh.positions.len())
    }

    pub(super) fn tail(&self, h: u32) -> u32 {
        self.faces[h as usize / 3][h as usize % 3]
    }

    pub(super) fn head(&self, h: u32) -> u32 {
        self.faces[h as usize / 3][(h as usize % 3 + 1) % 3]
    }

    pub(super) fn prev(h: u32) -> u32 {
        3 * (h / 3) + (h % 3 + 2) % 3
    }

    /// The one-ring of `v`, counter-clockwise, and whether `v` is on the boundary (then the ring
    /// runs from one boundary neighbour to the other). Empty for an unused vertex.
    pub fn one_ring(&self, v: u32) -> (Vec<u32>, bool) {
        let start = self.outgoing[v as usize];
        if start == u32::MAX {
            return (Vec::new(), false);
        }
        let mut ring = vec![self.head(start)];
        let mut h = start;
        loop {
            let p = Self::prev(h);
            match self.twin[p as usize] {
                Some(t) if t == start => return (ring, false),
                Some(t) => {
                    ring.push(self.head(t));
                    h = t;
                }
                None => {
                    // The boundary: the last neighbour is the tail of the face's previous edge.
                    ring.push(self.tail(p));
                    return (ring, true);
                }
            }
        }
    }
}
