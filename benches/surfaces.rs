//! Every surface x procedural displacement x driver on the default mesh (Spot, 372 triangles) at
//! levels 16 and 32: GPU time, per-refined-triangle cost and ratios against `static` of the same
//! surface and displacement, in one run. Writes docs/bench/surfaces.{md,csv,json} (see
//! `meshrefine::bench::Harness`); `MESHREFINE_BENCH_QUICK=1` runs a smaller set. (The height map
//! needs texture coordinates, which the default mesh lacks: `meshrefine bench MESH
//! --displacements heightmap` measures it on a mesh that has them.)

use meshrefine::bench::{BenchOptions, Harness};
use meshrefine::render::View;
use meshrefine::surface::{Displace, Surface};

fn main() {
    let h = Harness::from_env();
    let (levels, frames) = if h.quick {
        (vec![4], 1)
    } else {
        (vec![16, 32], 3)
    };
    let surfaces = Surface::LOCAL
        .iter()
        .flat_map(|&s| {
            [Displace::None, Displace::Sine, Displace::Noise]
                .into_iter()
                .map(move |d| (s, d))
        })
        .collect();
    // Drawn centred and at unit size, as `meshrefine render` draws it.
    let mesh = meshrefine::mesh::default_mesh().for_viewing();
    let opts = BenchOptions {
        build: Default::default(),
        levels,
        surfaces,
        params: None,
        frames,
        width: 1280,
        height: 720,
        drivers: vec![],
        min_total_ms: 0.0,
        // One view of each mesh for every surface, as the recorded figures were made.
        camera: meshrefine::bench::BenchCamera::Framing,
        adaptive: None,
        view: View::Shaded,
        heightmap: None,
    };
    h.run("surfaces", &[mesh], &opts);
}
