//! Limit positions (the module notes give the masks): each vertex's limit mask as a stencil
//! ([`limit_stencil`]), every vertex's limit position, and the reference used by the tests and
//! `tools/loop_limit.rs`: subdivide, then push to the limit.
#![forbid(unsafe_code)]

use super::step::{beta, loop_step, vertex_stencil};
use super::{Boundary, Refined, Stencil, Topology, TopologyError};
use crate::mesh::Mesh;
use glam::DVec3;

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
