//! Loop subdivision on the CPU (no Vulkan): a half-edge topology that refuses what Loop cannot
//! subdivide, one Loop step with OpenSubdiv's boundary rules, its computational entries, and
//! limit positions: the reference the GPU paths are checked against (itself checked against
//! OpenSubdiv by scripts/check-loop-osd.sh). One idea a file: `topology.rs`, `step.rs` (the rules,
//! one step and its computational entries), `limit.rs` (limit masks); [`bft`] builds the basis
//! function tables; `data.rs` holds one mesh's data for the `loop` surface ([`LoopData`]).
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

pub mod bft;
mod data;
mod limit;
mod step;
mod topology;

pub use data::{face_records, m1_topology, padded, FaceRecord, LoopData, LoopFrame, RING_BOUNDARY};
pub use limit::{limit_positions, limit_stencil, subdivide_to_limit};
pub use step::{beta, loop_step, refined_faces, ring_normals, stencils, Refined, Stencil};
pub use topology::{Topology, TopologyError};

/// How boundaries are subdivided.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Boundary {
    /// Boundary edges infinitely sharp (OpenSubdiv's VTX_BOUNDARY_EDGE_ONLY).
    #[default]
    EdgeOnly,
    /// As edge-only, and boundary vertices of valence 2 stay fixed (VTX_BOUNDARY_EDGE_AND_CORNER).
    EdgeAndCorner,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_support::load_model;
    use glam::DVec3;

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
