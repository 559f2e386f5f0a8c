//! Where a pattern frame's time goes on a software device (lavapipe): CPU milliseconds per
//! frame by thread, for uniform and adaptive frames of Spot (PN, largest level 32, 1920x1080)
//! at the close-up camera of docs/bench/adaptive.md, the variants taken round by round after a
//! warm-up round. lavapipe's queue thread runs the vertex side (fetch, vertex shader, clipping,
//! binning); the `llvmpipe-` threads rasterize and shade fragments.
//! CPU time, unlike the GPU timestamps, does not count time spent waiting for a core, so it
//! stays steady on a loaded machine. Linux only (/proc/self/task). docs/bench/geomorph-cost.md.
//!
//!     cargo run --example frame_threads -- [ROUNDS]

use meshrefine::gpu::ContextDesc;
use meshrefine::mesh::Mesh;
use meshrefine::render::{Camera, DrawConfig, Driver, Headless, LevelView, Submit};
use meshrefine::surface::{Displace, Surface, SurfaceParams};
use std::collections::BTreeMap;

/// CPU seconds by thread (utime + stime, in clock ticks of 10 ms).
fn cpu_by_thread() -> BTreeMap<String, f64> {
    let mut out = BTreeMap::new();
    let own = std::fs::read_to_string("/proc/self/comm").unwrap_or_default();
    for e in std::fs::read_dir("/proc/self/task").unwrap() {
        let p = e.unwrap().path();
        let Ok(stat) = std::fs::read_to_string(p.join("stat")) else {
            continue;
        };
        let comm = std::fs::read_to_string(p.join("comm")).unwrap_or_default();
        let rest = &stat[stat.rfind(')').unwrap() + 2..];
        let f: Vec<&str> = rest.split(' ').collect();
        let t = (f[11].parse::<f64>().unwrap() + f[12].parse::<f64>().unwrap()) / 100.0;
        // The main thread records and submits; lavapipe's queue thread, unnamed (the program's
        // name), runs the vertex side; the numbered raster threads count together.
        let name: String = if p.file_name() == Some(std::process::id().to_string().as_ref()) {
            "main".into()
        } else if comm == own {
            "queue (vertex side)".into()
        } else if comm.starts_with("llvmpipe-") {
            "raster (llvmpipe-N)".into()
        } else {
            comm.trim().into()
        };
        *out.entry(name).or_insert(0.0) += t;
    }
    out
}

fn main() -> anyhow::Result<()> {
    let rounds: usize = match std::env::args().nth(1) {
        Some(s) => s
            .parse()
            .map_err(|_| anyhow::anyhow!("ROUNDS must be a whole number, not '{s}'"))?,
        None => 6,
    };
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/models/spot_control_tri.obj");
    let (mesh, _) = Mesh::load_obj(&path)?;
    let (w, hgt) = (1920, 1080);
    let mut h = Headless::new(&ContextDesc::default(), w, hgt)?;
    let mut scene = h.scene(mesh, 32)?;
    let (_, r) = scene.bounding_sphere();
    let camera = Camera::looking(
        glam::Vec3::new(0.35, 0.65, -1.3),
        glam::Vec3::new(0.0, 0.5, -0.5),
        45f32.to_radians(),
        r,
    )
    .unwrap();
    // Name, submission, adaptive (pixel error, cull) or uniform, geomorphing.
    type Variant = (String, Submit, Option<(f32, bool)>, bool);
    let mut variants: Vec<Variant> = Vec::new();
    for submit in [Submit::Instanced, Submit::Push] {
        let name = |what: &str| format!("{} {what}", submit.name());
        variants.extend([
            (name("uniform 32"), submit, None, false),
            (name("adaptive 0.5 px"), submit, Some((0.5, true)), true),
            (
                name("adaptive 0.5 px, no geomorph"),
                submit,
                Some((0.5, true)),
                false,
            ),
            // The uniform triangles through the adaptive path.
            (
                name("adaptive all at 32, no geomorph, no cull"),
                submit,
                Some((1e-4, false)),
                false,
            ),
        ]);
    }
    let mut acc: Vec<(BTreeMap<String, f64>, f64, u64)> = vec![Default::default(); variants.len()];
    for round in 0..=rounds {
        for (k, &(_, submit, adaptive, geomorph)) in variants.iter().enumerate() {
            let mut cfg = DrawConfig::new(Driver::Pattern(submit), 32)
                .with_surface(Surface::Pn, Displace::None);
            cfg.params = SurfaceParams::for_radius(r);
            cfg.geomorph = geomorph;
            h.adaptive = adaptive.is_some();
            h.prepared_elements(&mut scene, &cfg, meshrefine::render::Capture::None)?;
            if let Some((pixel_error, cull)) = adaptive {
                scene.set_levels(
                    &cfg,
                    &LevelView {
                        camera,
                        width: w,
                        height: hgt,
                        pixel_error,
                        cull,
                    },
                )?;
            }
            let before = cpu_by_thread();
            let t = h.draw(&mut scene, &cfg, &camera)?;
            let after = cpu_by_thread();
            if round == 0 {
                continue; // warm-up
            }
            for (name, v) in &after {
                *acc[k].0.entry(name.clone()).or_insert(0.0) +=
                    v - before.get(name).copied().unwrap_or(0.0);
            }
            acc[k].1 += t.gpu_ms;
            acc[k].2 = t.stats.map_or(0, |s| s.vertex_shader_invocations);
        }
    }
    for ((name, ..), (cpu, gpu, vs)) in variants.iter().zip(&acc) {
        let n = rounds as f64;
        let total: f64 = cpu.values().sum();
        let parts: Vec<String> = (cpu.iter())
            .filter(|(_, v)| **v > 0.0)
            .map(|(k, v)| format!("{k} {:.0}", v / n * 1e3))
            .collect();
        println!(
            "{name:50} CPU {:4.0} ms/frame [{}], GPU {:5.1} ms, VS invocations {vs}",
            total / n * 1e3,
            parts.join(", "),
            gpu / n
        );
    }
    Ok(())
}
