//! Reproduces Boubekeur & Schlick 2005, Fig. 7 on this machine: coarse meshes of 10, 100 and
//! 1,000 triangles refined at levels 16, 32, 64 and 128 by every driver (`static`, `pattern` in
//! its three submission modes, `tess`), frame time from GPU timestamps and wall clock (median and
//! spread after warm-up), GPU geometry footprint, and ratios against `static` from the same run.
//!
//! Writes docs/bench/fig7.{md,csv,json}. Device: the first Vulkan device (prefers a discrete GPU;
//! set MESHREFINE_DEVICE to pick one by name). `MESHREFINE_BENCH_QUICK=1` runs a smaller set.

use meshrefine::bench::{grid_mesh, run, BenchOptions};
use meshrefine::gpu::{Context, ContextDesc};
use std::path::PathBuf;

fn main() {
    // `cargo bench` passes --bench; `cargo test --benches` runs it with no argument: do a smoke run.
    let benching = std::env::args().any(|a| a == "--bench");
    let level = if benching { "info" } else { "warn" };
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or(level)).init();
    let quick = !benching || std::env::var_os("MESHREFINE_BENCH_QUICK").is_some();
    let (sizes, levels, frames): (&[u32], Vec<u32>, u32) = if quick {
        (&[10, 100], vec![8, 16], 2)
    } else {
        (&[10, 100, 1000], vec![16, 32, 64, 128], 5)
    };
    // The smoke run (`cargo test`) is a GPU test like the others: validation on, and any message
    // fails it. Timed runs leave validation off (it slows command recording 7-10x).
    let desc = ContextDesc {
        device_name: std::env::var("MESHREFINE_DEVICE").ok(),
        validate: !benching,
        ..Default::default()
    };
    let ctx = match Context::new(&desc) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    let meshes: Vec<_> = sizes.iter().map(|&n| grid_mesh(n)).collect();
    let opts = BenchOptions {
        levels,
        surfaces: vec![(
            meshrefine::surface::Surface::Flat,
            meshrefine::surface::Displace::None,
        )],
        params: None,
        frames,
        width: 1280,
        height: 720,
    };
    let messages = ctx.messages_handle();
    let report = match run(ctx, &meshes, &opts) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    let problems = messages.take();
    if !problems.is_empty() || meshrefine::gpu::live_objects() != 0 {
        eprintln!(
            "error: validation / leaks: {problems:?}, {} live objects",
            meshrefine::gpu::live_objects()
        );
        std::process::exit(1);
    }
    let md = report.markdown();
    println!("{md}");
    if benching && !quick {
        let prefix = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs/bench/fig7");
        report
            .write_files(&prefix, "cargo bench --bench fig7")
            .unwrap();
        println!("wrote {}.{{md,csv,json}}", prefix.display());
    }
}
