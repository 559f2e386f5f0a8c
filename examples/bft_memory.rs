//! The basis function tables' memory for every configuration up to a valence (default 18): the
//! union of the configurations of closed spheres whose poles have valence n = 3 .. max (interior
//! extraordinary vertices) and of open half-disc fans of k = 1 .. max - 1 triangles (boundary
//! vertices of k + 1 edges), configurations deduplicated by key and tables by content, as one
//! mesh's are.
//! For table levels 4 and 5 (and 6 when asked: `cargo run --release --example bft_memory
//! [MAX_VALENCE] [LEVEL...]`).

use meshrefine::bench::sphere_mesh;
use meshrefine::mesh::Mesh;
use meshrefine::subdiv::bft::{build, Lattice};
use meshrefine::subdiv::{loop_step, Boundary, Topology};
use std::collections::HashMap;

fn fan(k: u32) -> Mesh {
    // A boundary vertex with k triangles over a half disc, and a second ring so the fan's
    // own boundary vertices have neighbours beyond it.
    let mut positions = vec![glam::Vec3::ZERO];
    for ring in 1..=2 {
        for i in 0..=k * ring {
            let a = std::f32::consts::PI * i as f32 / (k * ring) as f32;
            positions.push(glam::Vec3::new(a.cos(), a.sin(), 0.0) * ring as f32);
        }
    }
    let r1 = |i: u32| 1 + i;
    let r2 = |i: u32| 2 + k + i;
    let mut tris = Vec::new();
    for i in 0..k {
        tris.push([0, r1(i), r1(i + 1)]);
        // Two outer triangles per inner one (ring 2 has 2k segments).
        tris.push([r1(i), r2(2 * i), r2(2 * i + 1)]);
        tris.push([r1(i), r2(2 * i + 1), r1(i + 1)]);
        tris.push([r1(i + 1), r2(2 * i + 1), r2(2 * i + 2)]);
    }
    Mesh::from_parts("fan", positions, None, tris).unwrap().0
}

fn main() {
    let args: Vec<u32> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let max = args.first().copied().unwrap_or(18);
    let levels = if args.len() > 1 {
        args[1..].to_vec()
    } else {
        vec![4, 5]
    };
    let mut meshes: Vec<(String, Mesh)> = (3..=max)
        .map(|n| (format!("sphere{n}"), sphere_mesh(n, 8)))
        .collect();
    meshes.extend((1..max).map(|k| (format!("fan{k}"), fan(k))));
    for lmax in levels {
        let lattice = Lattice::new(lmax);
        let boundary = Boundary::EdgeOnly;
        // Configurations by key, tables by content (as `build` shares them within a mesh).
        let mut keys: HashMap<Vec<[u32; 3]>, ()> = HashMap::new();
        let mut all: HashMap<Vec<i64>, usize> = HashMap::new();
        for (_, mesh) in &meshes {
            let topo = Topology::of_mesh(mesh).unwrap();
            let p: Vec<glam::DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
            let m1 = loop_step(&topo, &p, boundary);
            let t1 = Topology::new(&m1.faces, m1.positions.len()).unwrap();
            let tables = build(&t1, boundary, lattice, |_| {}).unwrap();
            keys.extend(tables.keys.into_iter().map(|k| (k, ())));
            for c in tables.configs {
                all.insert(
                    c.weights
                        .iter()
                        .map(|w| (w * (1u64 << 40) as f64).round() as i64)
                        .collect(),
                    c.control,
                );
            }
        }
        // As stored on the GPU: rows padded to a multiple of four weights.
        let bytes: usize = all
            .values()
            .map(|&k| lattice.rows() * meshrefine::surface::subdivision::padded(k) * 4)
            .sum();
        println!(
            "table level {lmax} ({} segments): {} configurations in {} tables up to valence {max}, {bytes} bytes ({:.2} MiB)",
            lattice.segments(),
            keys.len(),
            all.len(),
            bytes as f64 / (1 << 20) as f64
        );
    }
}
