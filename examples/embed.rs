//! meshrefine as a library: load a mesh, choose a surface and a driver, render it to a PNG and
//! export the refined mesh the GPU evaluated, with the Vulkan validation layer on (any message
//! or leaked object fails the run).
//!
//!     cargo run --example embed -- [MESH.obj] [OUTPUT_FOLDER]
//!
//! Writes `embed.png` and `embed.obj` into the folder (default: the current one).

use anyhow::Context as _;
use meshrefine::export::to_obj;
use meshrefine::gpu::{with_context, ContextDesc};
use meshrefine::mesh::Mesh;
use meshrefine::render::{Camera, DrawConfig, Driver, Headless};
use meshrefine::surface::{Displace, Surface};
use std::path::{Path, PathBuf};

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let mesh_path = args.next().map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/models/spot_control_tri.obj"),
        PathBuf::from,
    );
    let out_dir = args
        .next()
        .map_or_else(|| PathBuf::from("."), PathBuf::from);
    run(&mesh_path, &out_dir)
}

/// Refine `mesh_path`, writing `embed.png` and `embed.obj` into `out_dir`.
pub fn run(mesh_path: &Path, out_dir: &Path) -> anyhow::Result<()> {
    // Loading checks the file and says what is wrong with it in one sentence.
    let (mesh, report) = Mesh::load_obj(mesh_path)?;
    if !report.dropped_degenerate.is_empty() {
        eprintln!(
            "warning: {} degenerate or duplicate faces left out",
            report.dropped_degenerate.len()
        );
    }

    // Curved PN triangles, 8 segments per coarse edge, drawn by the pattern driver.
    let cfg = DrawConfig::new(Driver::default(), 8).with_surface(Surface::Pn, Displace::None);

    let desc = ContextDesc {
        validate: true,
        ..Default::default()
    };
    let refined = with_context(&desc, |ctx| -> anyhow::Result<_> {
        let mut h = Headless::with_context(ctx, 640, 480)?;
        let mut scene = h.scene(mesh, cfg.level)?;
        let (centre, radius) = scene.bounding_sphere();
        let camera = Camera::framing(centre, radius);
        let image = h.render(&mut scene, &cfg, &camera)?;
        image.save_png(&out_dir.join("embed.png"))?;
        // The vertices the drawing pipeline evaluated, welded on exact bits.
        Ok(h.refined_mesh(&mut scene, &cfg, &camera)?)
    })
    .with_context(|| format!("cannot refine '{}'", mesh_path.display()))?;

    let header = [format!(
        "{} refined with {} by the {} driver at level {}",
        mesh_path.display(),
        cfg.surface.name(),
        cfg.label(),
        cfg.level
    )];
    std::fs::write(out_dir.join("embed.obj"), to_obj(&refined, &header))?;
    println!(
        "wrote embed.png and embed.obj ({} vertices, {} triangles) to {}",
        refined.positions.len(),
        refined.triangles.len(),
        out_dir.display()
    );
    Ok(())
}
