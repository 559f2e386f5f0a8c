//! One Loop step M0 -> M1 and its rules (the module notes give them): the refined positions
//! and faces ([`loop_step`], [`refined_faces`]), and each M1 vertex as a computational entry of
//! M0 parents and weights ([`stencils`]), the form the GPU pass and the tables apply; one-ring
//! normals.
#![forbid(unsafe_code)]

use super::{Boundary, Topology};
use glam::DVec3;

/// Loop's β for valence `n`.
pub fn beta(n: usize) -> f64 {
    let n = n as f64;
    let c = 3.0 / 8.0 + (2.0 * std::f64::consts::PI / n).cos() / 4.0;
    (5.0 / 8.0 - c * c) / n
}

/// The result of one Loop step: positions (the old vertices' new positions first, then one edge
/// point per edge) and four faces per face.
#[derive(Clone, Debug)]
pub struct Refined {
    pub positions: Vec<DVec3>,
    pub faces: Vec<[u32; 3]>,
}

/// Whether `v` is a corner under `boundary`: a boundary vertex with two edges (one face).
pub(super) fn corner(ring: &[u32], on_boundary: bool, boundary: Boundary) -> bool {
    boundary == Boundary::EdgeAndCorner && on_boundary && ring.len() == 2
}

/// One Loop step of `positions` over `topo`.
pub fn loop_step(topo: &Topology, positions: &[DVec3], boundary: Boundary) -> Refined {
    let nv = topo.vertex_count;
    let mut out: Vec<DVec3> = Vec::with_capacity(nv + 3 * topo.faces.len() / 2 + 8);
    for v in 0..nv as u32 {
        let p = positions[v as usize];
        let (ring, on_boundary) = topo.one_ring(v);
        let q = if ring.is_empty() || corner(&ring, on_boundary, boundary) {
            p
        } else if on_boundary {
            let (a, b) = (
                positions[ring[0] as usize],
                positions[*ring.last().unwrap() as usize],
            );
            p * 0.75 + (a + b) * 0.125
        } else {
            let n = ring.len();
            let b = beta(n);
            let sum: DVec3 = ring.iter().map(|&i| positions[i as usize]).sum();
            p * (1.0 - n as f64 * b) + sum * b
        };
        out.push(q);
    }
    // Edge points, one per undirected edge, numbered in half-edge order.
    let mut edge_point: Vec<u32> = vec![u32::MAX; topo.twin.len()];
    for h in 0..topo.twin.len() as u32 {
        if edge_point[h as usize] != u32::MAX {
            continue;
        }
        let (a, b) = (topo.tail(h), topo.head(h));
        let (pa, pb) = (positions[a as usize], positions[b as usize]);
        let opposite = |h: u32| topo.faces[h as usize / 3][(h as usize % 3 + 2) % 3];
        let q = match topo.twin[h as usize] {
            Some(t) => {
                let (c, d) = (
                    positions[opposite(h) as usize],
                    positions[opposite(t) as usize],
                );
                (pa + pb) * 0.375 + (c + d) * 0.125
            }
            None => (pa + pb) * 0.5,
        };
        let i = out.len() as u32;
        out.push(q);
        edge_point[h as usize] = i;
        if let Some(t) = topo.twin[h as usize] {
            edge_point[t as usize] = i;
        }
    }
    Refined {
        positions: out,
        faces: children(topo, &edge_point),
    }
}

/// The four faces of every face after one step, given each half-edge's edge point: face f's
/// children are `4f .. 4f + 4`, the corner faces `[t_k, e_k, e_(k+2)]` (k = 0, 1, 2, the vertex
/// point first) then the middle face `[e0, e1, e2]`, with `e_k` the point of edge (t_k, t_(k+1)).
fn children(topo: &Topology, edge_point: &[u32]) -> Vec<[u32; 3]> {
    let mut faces = Vec::with_capacity(4 * topo.faces.len());
    for (f, t) in topo.faces.iter().enumerate() {
        let e = [0, 1, 2].map(|k| edge_point[3 * f + k]);
        faces.push([t[0], e[0], e[2]]);
        faces.push([t[1], e[1], e[0]]);
        faces.push([t[2], e[2], e[1]]);
        faces.push([e[0], e[1], e[2]]);
    }
    faces
}

/// The faces of one Loop step over `topo` (as [`loop_step`] numbers them), without positions.
pub fn refined_faces(topo: &Topology) -> Vec<[u32; 3]> {
    let mut edge_point: Vec<u32> = vec![u32::MAX; topo.twin.len()];
    let mut next = topo.vertex_count as u32;
    for h in 0..topo.twin.len() {
        if edge_point[h] != u32::MAX {
            continue;
        }
        edge_point[h] = next;
        if let Some(t) = topo.twin[h] {
            edge_point[t as usize] = next;
        }
        next += 1;
    }
    children(topo, &edge_point)
}

/// One refined vertex as a weighted sum of parent vertices: the 2010 paper's "computational
/// entry" (parent indices and weights), built once per topology and applied to new positions
/// every frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Stencil {
    pub parents: Vec<u32>,
    pub weights: Vec<f64>,
}

impl Stencil {
    pub fn apply(&self, positions: &[DVec3]) -> DVec3 {
        self.parents
            .iter()
            .zip(&self.weights)
            .map(|(&i, &w)| positions[i as usize] * w)
            .sum()
    }
}

/// The computational entries of one Loop step over `topo`, in [`loop_step`]'s vertex order
/// (the vertices' new positions, then one edge point per edge).
pub fn stencils(topo: &Topology, boundary: Boundary) -> Vec<Stencil> {
    let mut out = Vec::with_capacity(topo.vertex_count + topo.twin.len() / 2 + 8);
    for v in 0..topo.vertex_count as u32 {
        out.push(vertex_stencil(topo, v, boundary, |n| {
            (0.75, 0.125, beta(n))
        }));
    }
    let mut done = vec![false; topo.twin.len()];
    for h in 0..topo.twin.len() as u32 {
        if done[h as usize] {
            continue;
        }
        let (a, b) = (topo.tail(h), topo.head(h));
        let opposite = |h: u32| topo.faces[h as usize / 3][(h as usize % 3 + 2) % 3];
        out.push(match topo.twin[h as usize] {
            Some(t) => {
                done[t as usize] = true;
                Stencil {
                    parents: vec![a, b, opposite(h), opposite(t)],
                    weights: vec![0.375, 0.375, 0.125, 0.125],
                }
            }
            None => Stencil {
                parents: vec![a, b],
                weights: vec![0.5, 0.5],
            },
        });
        done[h as usize] = true;
    }
    out
}

/// Each vertex's normal from its one-ring (counter-clockwise, with the boundary flag): the
/// normalized sum of the cross products of consecutive ring edges, i.e. the area-weighted normal
/// of the faces around it (on a boundary, only between the two boundary neighbours). The normals
/// subdivision shading starts from at the M1 vertices.
pub fn ring_normals(topo: &Topology, positions: &[DVec3]) -> Vec<DVec3> {
    (0..topo.vertex_count as u32)
        .map(|v| {
            let (ring, on_boundary) = topo.one_ring(v);
            let p = positions[v as usize];
            let pairs = if on_boundary {
                ring.len().saturating_sub(1)
            } else {
                ring.len()
            };
            let n: DVec3 = (0..pairs)
                .map(|i| {
                    let a = positions[ring[i] as usize] - p;
                    let b = positions[ring[(i + 1) % ring.len()] as usize] - p;
                    a.cross(b)
                })
                .sum();
            n.normalize_or_zero()
        })
        .collect()
}

/// A vertex rule on `v`'s one-ring: fixed at corners; `(centre, neighbour)` weights on a
/// boundary (the two boundary neighbours); inside, weight `w` on each of the n neighbours and
/// `1 - n w` on the centre. `weights(n)` gives (boundary centre, boundary neighbour, w).
pub(super) fn vertex_stencil(
    topo: &Topology,
    v: u32,
    boundary: Boundary,
    weights: impl Fn(usize) -> (f64, f64, f64),
) -> Stencil {
    let (ring, on_boundary) = topo.one_ring(v);
    if ring.is_empty() || corner(&ring, on_boundary, boundary) {
        return Stencil {
            parents: vec![v],
            weights: vec![1.0],
        };
    }
    let n = ring.len();
    let (bc, bn, w) = weights(n);
    if on_boundary {
        Stencil {
            parents: vec![v, ring[0], ring[n - 1]],
            weights: vec![bc, bn, bn],
        }
    } else {
        let mut parents = vec![v];
        parents.extend(&ring);
        let mut weights = vec![1.0 - n as f64 * w];
        weights.extend(std::iter::repeat_n(w, n));
        Stencil { parents, weights }
    }
}
