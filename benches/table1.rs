//! The 2010 paper's Table I and Fig. 8 on this machine (Holländer & Boubekeur, "Subdivision
//! meshes via real-time tessellation"): flat, Phong, PN and Loop (basis function tables) through
//! the pattern (instanced) and tess drivers, in one run.
//! - `table1`: the default mesh (Spot) and three more of 500-3,000 triangles (a UV sphere with
//!   two valence-32 poles, a torus, an open wavy grid), levels 4, 16 and 32 (the paper's depths 2,
//!   4 and 5): GPU time, throughput against flat, the M0 -> M1 passes' cost and the tables' bytes.
//! - `fig8`: per-triangle cost against level on the default mesh (levels 1 to 32);
//!   `python3 scripts/plot.py cost` draws docs/bench/fig8.svg from it.
//!
//! Writes docs/bench/{table1,fig8}.{md,csv,json} (see `meshrefine::bench::Harness`);
//! `MESHREFINE_BENCH_QUICK=1` (and `cargo test --benches`) runs a smaller, validated set.

use meshrefine::bench::{BenchOptions, Harness};
use meshrefine::mesh::generate::{sphere_mesh, torus_mesh, wavy_grid_mesh};
use meshrefine::render::{Driver, Submit, View};
use meshrefine::surface::{Displace, Surface};

fn main() {
    let h = Harness::from_env();
    let surfaces: Vec<(Surface, Displace)> =
        [Surface::Flat, Surface::Phong, Surface::Pn, Surface::Loop]
            .into_iter()
            .map(|s| (s, Displace::None))
            .collect();
    let drivers = vec![Driver::Pattern(Submit::Instanced), Driver::Tess];
    // Drawn centred and at unit size, as `meshrefine render` draws them.
    let mut meshes = vec![meshrefine::mesh::default_mesh()];
    if !h.quick {
        meshes.extend([
            sphere_mesh(32, 16),
            torus_mesh(32, 24),
            wavy_grid_mesh(40, 30),
        ]);
    }
    let meshes: Vec<_> = meshes
        .into_iter()
        .map(|m| {
            let name = m.name.clone();
            let mut v = m.for_viewing();
            v.name = name;
            v
        })
        .collect();
    let (levels, frames) = if h.quick {
        (vec![2], 1)
    } else {
        (vec![4, 16, 32], 3)
    };
    let opts = BenchOptions {
        build: Default::default(),
        levels,
        surfaces: surfaces.clone(),
        params: None,
        frames,
        width: 1280,
        height: 720,
        drivers: drivers.clone(),
        // At least 1.5 s of GPU time per variant, taken round the variants in turn.
        min_total_ms: if h.quick { 0.0 } else { 1500.0 },
        // One view of each mesh for every surface, as the recorded figures were made.
        camera: meshrefine::bench::BenchCamera::Framing,
        adaptive: None,
        view: View::Shaded,
        heightmap: None,
    };
    h.run("table1", &meshes, &opts);
    let fig8 = BenchOptions {
        build: Default::default(),
        levels: if h.quick {
            vec![1, 2]
        } else {
            vec![1, 2, 4, 8, 16, 32]
        },
        ..opts
    };
    h.run("fig8", &meshes[..1], &fig8);
}
