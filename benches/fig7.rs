//! Reproduces Boubekeur & Schlick 2005, Fig. 7 on this machine: coarse meshes of 10, 100 and
//! 1,000 triangles (and the default Spot, a real mesh, in the same run) refined at levels 16, 32,
//! 64 and 128 by every driver (`static`, `pattern` in
//! its three submission modes, `tess`), frame time from GPU timestamps and wall clock (median and
//! spread after warm-up, timed round the variants in turn until each has at least 11 frames and
//! 2 s of GPU time), GPU geometry footprint, and ratios against `static` from the same run.
//!
//! Writes docs/bench/fig7.{md,csv,json} (see `meshrefine::bench::Harness`).
//! `MESHREFINE_BENCH_QUICK=1` runs a smaller set.

use meshrefine::bench::{BenchOptions, Harness};
use meshrefine::mesh::generate::grid_mesh;
use meshrefine::render::View;
use meshrefine::surface::{Displace, Surface};

fn main() {
    let h = Harness::from_env();
    let (sizes, levels, frames): (&[u32], Vec<u32>, u32) = if h.quick {
        (&[10, 100], vec![8, 16], 2)
    } else {
        (&[10, 100, 1000], vec![16, 32, 64, 128], 11)
    };
    let mut meshes: Vec<_> = sizes.iter().map(|&n| grid_mesh(n)).collect();
    if !h.quick {
        // And a real mesh in the same run (issue 5's target): the default Spot, drawn centred
        // and at unit size as `meshrefine render` draws it.
        let spot = meshrefine::mesh::default_mesh();
        let mut viewed = spot.for_viewing();
        viewed.name = spot.name.clone();
        meshes.push(viewed);
    }
    let opts = BenchOptions {
        build: Default::default(),
        levels,
        surfaces: vec![(Surface::Flat, Displace::None)],
        params: None,
        frames,
        width: 1280,
        height: 720,
        drivers: vec![],
        // Frames of a few milliseconds (the small grids) jitter most: at least 2 s of GPU
        // time per variant.
        min_total_ms: if h.quick { 0.0 } else { 2000.0 },
        // One view of each mesh for every surface, as the recorded figures were made.
        camera: meshrefine::bench::BenchCamera::Framing,
        adaptive: None,
        view: View::Shaded,
        heightmap: None,
    };
    h.run("fig7", &meshes, &opts);
}
