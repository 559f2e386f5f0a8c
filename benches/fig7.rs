//! Reproduces Boubekeur & Schlick 2005, Fig. 7 on this machine: coarse meshes of 10, 100 and
//! 1,000 triangles refined at levels 16, 32, 64 and 128 by every driver (`static`, `pattern` in
//! its three submission modes, `tess`), frame time from GPU timestamps and wall clock (median and
//! spread after warm-up), GPU geometry footprint, and ratios against `static` from the same run.
//!
//! Writes docs/bench/fig7.{md,csv,json} (see `meshrefine::bench::Harness`).
//! `MESHREFINE_BENCH_QUICK=1` runs a smaller set.

use meshrefine::bench::{grid_mesh, BenchOptions, Harness};
use meshrefine::surface::{Displace, Surface};

fn main() {
    let h = Harness::from_env();
    let (sizes, levels, frames): (&[u32], Vec<u32>, u32) = if h.quick {
        (&[10, 100], vec![8, 16], 2)
    } else {
        (&[10, 100, 1000], vec![16, 32, 64, 128], 11)
    };
    let meshes: Vec<_> = sizes.iter().map(|&n| grid_mesh(n)).collect();
    let opts = BenchOptions {
        levels,
        surfaces: vec![(Surface::Flat, Displace::None)],
        params: None,
        frames,
        width: 1280,
        height: 720,
        drivers: vec![],
    };
    h.run("fig7", &meshes, &opts);
}
