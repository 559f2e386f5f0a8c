//! Loop subdivision on the CPU (no Vulkan): a half-edge topology that refuses what Loop cannot
//! subdivide, one Loop step with OpenSubdiv's boundary rules, its computational entries, and
//! limit positions: the reference the GPU paths are checked against (itself checked against
//! OpenSubdiv by scripts/check-loop-osd.sh). [`bft`] builds the basis function tables.
//!
//! Rules (Loop 1987; boundaries as OpenSubdiv's Loop scheme):
//! - interior vertex of valence n: `(1 − nβ) P + β Σ P_i`, `β = (1/n)(5/8 − (3/8 + cos(2π/n)/4)²)`;
//! - interior edge (a, b) with opposite vertices c, d: `3/8 (a + b) + 1/8 (c + d)`;
//! - boundary edges are infinitely sharp ([`Boundary::EdgeOnly`], OpenSubdiv's
//!   VTX_BOUNDARY_EDGE_ONLY): boundary vertex `1/8 P_prev + 3/4 P + 1/8 P_next`, boundary edge point
//!   `1/2 (a + b)`; with [`Boundary::EdgeAndCorner`] (VTX_BOUNDARY_EDGE_AND_CORNER) a boundary vertex
//!   of valence 2 (two edges, one face) is a corner and stays where it is;
//! - limit positions: interior `(1 − nχ) P + χ Σ P_i`, `χ = 1/(n + 3/(8β))`; boundary
//!   `(P_prev + 4 P + P_next)/6`; corners fixed.
#![forbid(unsafe_code)]

use crate::mesh::Mesh;
use glam::DVec3;
use std::collections::HashMap;

pub mod bft;
mod data;

pub use data::{face_records, m1_topology, padded, FaceRecord, LoopData, LoopFrame, RING_BOUNDARY};

/// How boundaries are subdivided.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum Boundary {
    /// Boundary edges infinitely sharp (OpenSubdiv's VTX_BOUNDARY_EDGE_ONLY).
    #[default]
    EdgeOnly,
    /// As edge-only, and boundary vertices of valence 2 stay fixed (VTX_BOUNDARY_EDGE_AND_CORNER).
    EdgeAndCorner,
}

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
    /// subdivide (the first problem found).
    pub fn new(faces: &[[u32; 3]], vertex_count: usize) -> Result<Self, TopologyError> {
        let mut directed: HashMap<(u32, u32), u32> = HashMap::with_capacity(3 * faces.len());
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

    fn tail(&self, h: u32) -> u32 {
        self.faces[h as usize / 3][h as usize % 3]
    }

    fn head(&self, h: u32) -> u32 {
        self.faces[h as usize / 3][(h as usize % 3 + 1) % 3]
    }

    fn prev(h: u32) -> u32 {
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
fn corner(ring: &[u32], on_boundary: bool, boundary: Boundary) -> bool {
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

/// The limit mask of vertex `v`: its limit position as a weighted sum of its one-ring.
pub fn limit_stencil(topo: &Topology, v: u32, boundary: Boundary) -> Stencil {
    vertex_stencil(topo, v, boundary, |n| {
        (
            4.0 / 6.0,
            1.0 / 6.0,
            1.0 / (n as f64 + 3.0 / (8.0 * beta(n))),
        )
    })
}

/// A vertex rule on `v`'s one-ring: fixed at corners; `(centre, neighbour)` weights on a
/// boundary (the two boundary neighbours); inside, weight `w` on each of the n neighbours and
/// `1 - n w` on the centre. `weights(n)` gives (boundary centre, boundary neighbour, w).
fn vertex_stencil(
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

/// The limit position of every vertex of `topo`.
pub fn limit_positions(topo: &Topology, positions: &[DVec3], boundary: Boundary) -> Vec<DVec3> {
    (0..topo.vertex_count as u32)
        .map(|v| limit_stencil(topo, v, boundary).apply(positions))
        .collect()
}

/// `steps` Loop steps of `mesh`, then the limit positions: the CPU reference surface.
pub fn subdivide_to_limit(
    mesh: &Mesh,
    steps: u32,
    boundary: Boundary,
) -> Result<Refined, TopologyError> {
    let mut faces = mesh.position_indices();
    let mut positions: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    let mut topo = Topology::new(&faces, positions.len())?;
    for _ in 0..steps {
        let r = loop_step(&topo, &positions, boundary);
        positions = r.positions;
        faces = r.faces;
        topo = Topology::new(&faces, positions.len())?;
    }
    Ok(Refined {
        positions: limit_positions(&topo, &positions, boundary),
        faces,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_support::load_model;

    #[test]
    fn one_rings_are_counter_clockwise_and_find_the_boundary() {
        let (mesh, _) = load_model("octahedron.obj");
        let topo = Topology::of_mesh(&mesh).unwrap();
        for v in 0..6 {
            let (ring, boundary) = topo.one_ring(v);
            assert_eq!((ring.len(), boundary), (4, false), "vertex {v}");
            // Counter-clockwise: (v, ring[i], ring[i+1]) is a face, in the faces' orientation.
            for i in 0..4 {
                let (a, b) = (ring[i], ring[(i + 1) % 4]);
                assert!(
                    topo.faces
                        .iter()
                        .any(|f| (0..3)
                            .any(|k| f[k] == v && f[(k + 1) % 3] == a && f[(k + 2) % 3] == b)),
                    "vertex {v}: ({v}, {a}, {b}) is not a face"
                );
            }
        }
        let (grid, _) = load_model("grid_open_8x8.obj");
        let topo = Topology::of_mesh(&grid).unwrap();
        let boundary = (0..grid.positions.len() as u32)
            .filter(|&v| topo.one_ring(v).1)
            .count();
        assert_eq!(boundary, 32);
    }

    #[test]
    fn non_manifold_meshes_are_refused() {
        let (mesh, _) = load_model("nonmanifold_edge.obj");
        let e = Topology::of_mesh(&mesh).unwrap_err();
        assert!(matches!(e, TopologyError::NonManifoldEdge { .. }), "{e}");
        // Two triangles meeting at one vertex only: a bow tie.
        let bow = [[0, 1, 2], [0, 3, 4]];
        assert!(matches!(
            Topology::new(&bow, 5).unwrap_err(),
            TopologyError::NonManifoldVertex { vertex: 0, .. }
        ));
        // One face flipped against its neighbour.
        let flipped = [[0, 1, 2], [0, 1, 3]];
        assert!(matches!(
            Topology::new(&flipped, 4).unwrap_err(),
            TopologyError::OrientationConflict { .. }
        ));
    }

    /// One step: V + E vertices, 4F faces, a closed mesh stays closed, and the limit of a mesh
    /// lies inside the convex hull and converges as steps are added.
    #[test]
    fn loop_step_counts_and_limit_convergence() {
        let (mesh, _) = load_model("icosahedron.obj");
        let topo = Topology::of_mesh(&mesh).unwrap();
        let pos: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        let r = loop_step(&topo, &pos, Boundary::EdgeOnly);
        assert_eq!(r.positions.len(), 12 + 30);
        assert_eq!(r.faces.len(), 80);
        Topology::new(&r.faces, r.positions.len()).unwrap();
        // Limit positions of the original vertices are the same after one more step.
        let l0 = limit_positions(&topo, &pos, Boundary::EdgeOnly);
        let t1 = Topology::new(&r.faces, r.positions.len()).unwrap();
        let l1 = limit_positions(&t1, &r.positions, Boundary::EdgeOnly);
        for v in 0..12 {
            assert!(
                (l0[v] - l1[v]).length() < 1e-12,
                "vertex {v}: {} vs {}",
                l0[v],
                l1[v]
            );
        }
    }

    /// A planar mesh stays planar, and boundary rules: with edge-and-corner, valence-2 boundary
    /// vertices (the grid's corners) stay fixed.
    #[test]
    fn boundary_rules() {
        let (grid, _) = load_model("grid_open_8x8.obj");
        let r = subdivide_to_limit(&grid, 2, Boundary::EdgeOnly).unwrap();
        assert!(r.positions.iter().all(|p| p.z.abs() < 1e-12));
        let corners = subdivide_to_limit(&grid, 1, Boundary::EdgeAndCorner).unwrap();
        let topo = Topology::of_mesh(&grid).unwrap();
        for v in 0..grid.positions.len() as u32 {
            let (ring, b) = topo.one_ring(v);
            if b && ring.len() == 2 {
                assert_eq!(
                    corners.positions[v as usize],
                    grid.positions[v as usize].as_dvec3()
                );
            }
        }
    }

    /// The computational entries reproduce the Loop step: applied to the coarse positions they
    /// give the same refined positions, and each one's weights sum to one.
    #[test]
    fn stencils_reproduce_the_loop_step() {
        for file in [
            "spot_control_tri.obj",
            "grid_open_8x8.obj",
            "fan24_open.obj",
        ] {
            let (mesh, _) = load_model(file);
            let topo = Topology::of_mesh(&mesh).unwrap();
            let pos: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
            for boundary in [Boundary::EdgeOnly, Boundary::EdgeAndCorner] {
                let r = loop_step(&topo, &pos, boundary);
                let s = stencils(&topo, boundary);
                assert_eq!(s.len(), r.positions.len(), "{file}");
                for (i, st) in s.iter().enumerate() {
                    assert!((st.weights.iter().sum::<f64>() - 1.0).abs() < 1e-12);
                    assert!(
                        (st.apply(&pos) - r.positions[i]).length() < 1e-12,
                        "{file} vertex {i}"
                    );
                }
            }
        }
    }

    /// Ring normals point outwards on a closed convex mesh (along the vertex direction from the
    /// centre, for the octahedron exactly) and along +z on the planar grid, boundary included.
    #[test]
    fn ring_normals_follow_the_orientation() {
        let (oct, _) = load_model("octahedron.obj");
        let topo = Topology::of_mesh(&oct).unwrap();
        let pos: Vec<DVec3> = oct.positions.iter().map(|p| p.as_dvec3()).collect();
        for (n, p) in ring_normals(&topo, &pos).iter().zip(&pos) {
            assert!((*n - p.normalize()).length() < 1e-12, "{n} vs {p}");
        }
        let (grid, _) = load_model("grid_open_8x8.obj");
        let topo = Topology::of_mesh(&grid).unwrap();
        let pos: Vec<DVec3> = grid.positions.iter().map(|p| p.as_dvec3()).collect();
        let up = grid.normals[0].as_dvec3();
        for n in ring_normals(&topo, &pos) {
            assert!((n - up).length() < 1e-12, "{n}");
        }
    }

    #[test]
    fn beta_matches_the_known_values() {
        // Regular valence 6: β = 1/16; valence 3: 3/16.
        assert!((beta(6) - 1.0 / 16.0).abs() < 1e-15);
        assert!((beta(3) - 3.0 / 16.0).abs() < 1e-15);
    }
}
