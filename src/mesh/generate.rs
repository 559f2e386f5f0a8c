//! Generated meshes: planar and wavy grids, a torus, a UV sphere and a half-disc fan, made to
//! order for the benchmarks (`cargo bench`, `meshrefine bench`) and the tests that need a mesh
//! of a given size or vertex valence. Each is a valid [`Mesh`] (positions only, counter-clockwise
//! faces) named after its shape and triangle count.
#![forbid(unsafe_code)]

use super::Mesh;
use glam::Vec3;

/// A planar grid of exactly `triangles` triangles (an even count) facing +z, 1 unit tall:
/// the coarse meshes of the 2005 paper's Fig. 7 are "10, 100, 1000 triangles".
pub fn grid_mesh(triangles: u32) -> Mesh {
    let quads = (triangles / 2).max(1);
    let mut cols = (quads as f64).sqrt().ceil() as u32;
    while quads % cols != 0 {
        cols += 1;
    }
    let rows = quads / cols;
    let mut positions = Vec::new();
    for j in 0..=rows {
        for i in 0..=cols {
            positions.push(Vec3::new(
                i as f32 / rows as f32,
                j as f32 / rows as f32,
                0.0,
            ));
        }
    }
    let tris = quad_triangles(cols, rows, |i, j| j * (cols + 1) + i);
    let (mut mesh, _) =
        Mesh::from_parts("grid", positions, None, tris).expect("a grid is a valid mesh");
    mesh.name = format!("grid{}", 2 * quads);
    mesh
}

/// Two triangles per quad of a `cols` x `rows` lattice whose vertex (i, j) is `at(i, j)`.
fn quad_triangles(cols: u32, rows: u32, at: impl Fn(u32, u32) -> u32) -> Vec<[u32; 3]> {
    let mut tris = Vec::with_capacity(2 * (cols * rows) as usize);
    for j in 0..rows {
        for i in 0..cols {
            tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    tris
}

/// A torus of `u` x `v` quads (2uv triangles, every vertex of valence 6), radii 1 and 0.4.
pub fn torus_mesh(u: u32, v: u32) -> Mesh {
    let tau = std::f32::consts::TAU;
    let mut positions = Vec::new();
    for j in 0..v {
        for i in 0..u {
            let (a, b) = (tau * i as f32 / u as f32, tau * j as f32 / v as f32);
            let r = 1.0 + 0.4 * b.cos();
            positions.push(Vec3::new(r * a.cos(), r * a.sin(), 0.4 * b.sin()));
        }
    }
    let tris = quad_triangles(u, v, |i, j| (j % v) * u + (i % u));
    let (mut mesh, _) =
        Mesh::from_parts("torus", positions, None, tris).expect("a torus is a valid mesh");
    mesh.name = format!("torus{}", 2 * u * v);
    mesh
}

/// A UV sphere of `segments` x `rings` (poles of valence `segments`: extraordinary vertices
/// beyond the 2010 paper's tables when over 18).
pub fn sphere_mesh(segments: u32, rings: u32) -> Mesh {
    let (pi, tau) = (std::f32::consts::PI, std::f32::consts::TAU);
    let mut positions = vec![Vec3::Z, -Vec3::Z];
    for j in 1..rings {
        let t = pi * j as f32 / rings as f32;
        for i in 0..segments {
            let a = tau * i as f32 / segments as f32;
            positions.push(Vec3::new(t.sin() * a.cos(), t.sin() * a.sin(), t.cos()));
        }
    }
    let at = |i: u32, j: u32| 2 + (j - 1) * segments + i % segments;
    let mut tris = Vec::new();
    for i in 0..segments {
        tris.push([0, at(i, 1), at(i + 1, 1)]);
        tris.push([1, at(i + 1, rings - 1), at(i, rings - 1)]);
    }
    for j in 1..rings - 1 {
        for i in 0..segments {
            tris.push([at(i, j), at(i, j + 1), at(i + 1, j + 1)]);
            tris.push([at(i, j), at(i + 1, j + 1), at(i + 1, j)]);
        }
    }
    let (mut mesh, _) =
        Mesh::from_parts("sphere", positions, None, tris).expect("a sphere is a valid mesh");
    mesh.name = format!("sphere{}", mesh.triangles.len());
    mesh
}

/// A boundary vertex with `k` triangles over a half disc (a boundary vertex of k + 1 edges),
/// and a second ring so the fan's own boundary vertices have neighbours beyond it.
pub fn half_disc_fan_mesh(k: u32) -> Mesh {
    let mut positions = vec![Vec3::ZERO];
    for ring in 1..=2 {
        for i in 0..=k * ring {
            let a = std::f32::consts::PI * i as f32 / (k * ring) as f32;
            positions.push(Vec3::new(a.cos(), a.sin(), 0.0) * ring as f32);
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
    Mesh::from_parts("fan", positions, None, tris)
        .expect("a fan is a valid mesh")
        .0
}

/// An open, wavy grid of `cols` x `rows` quads (boundary configurations everywhere round it).
pub fn wavy_grid_mesh(cols: u32, rows: u32) -> Mesh {
    let mut positions = Vec::new();
    for j in 0..=rows {
        for i in 0..=cols {
            let (x, y) = (i as f32 / rows as f32, j as f32 / rows as f32);
            positions.push(Vec3::new(x, y, 0.08 * (6.0 * x).sin() * (5.0 * y).cos()));
        }
    }
    let tris = quad_triangles(cols, rows, |i, j| j * (cols + 1) + i);
    let (mut mesh, _) =
        Mesh::from_parts("wavy", positions, None, tris).expect("a grid is a valid mesh");
    mesh.name = format!("wavygrid{}", 2 * cols * rows);
    mesh
}
