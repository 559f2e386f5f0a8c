//! The library example (examples/embed.rs) runs as documented: it renders a PNG that shows the
//! mesh and exports the refined mesh, with the validation layer on (the example fails on any
//! message or leak), and the export is what the pattern driver makes at level 8.

mod common;

use meshrefine::mesh::Mesh;
use std::path::PathBuf;
use std::process::Command;

#[test]
fn the_library_example_renders_and_exports() {
    let _guard = common::gpu_lock();
    // target/<profile>/deps/embed-<hash> -> target/<profile>/examples/embed
    let exe = std::env::current_exe().unwrap();
    let example: PathBuf = exe
        .parent()
        .and_then(|deps| deps.parent())
        .unwrap()
        .join("examples/embed");
    assert!(
        example.exists(),
        "{} is not built (cargo test builds examples)",
        example.display()
    );
    let out = common::output_dir().join("embed");
    std::fs::create_dir_all(&out).unwrap();
    let mesh = common::model_path("spot_control_tri.obj");
    let run = Command::new(&example)
        .arg(&mesh)
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "the example failed: {stderr}");
    assert!(!stderr.contains("validation"), "{stderr}");

    let image = png::Decoder::new(std::fs::File::open(out.join("embed.png")).unwrap());
    let mut reader = image.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut pixels).unwrap();
    assert_eq!((info.width, info.height), (640, 480));
    // The background is uniform: the mesh shows where pixels differ from the corner's.
    let corner = &pixels[..4];
    let shown = pixels.chunks_exact(4).filter(|p| p != &corner).count();
    assert!(shown > 640 * 480 / 20, "only {shown} pixels show the mesh");

    let (refined, _) = Mesh::load_obj(&out.join("embed.obj")).unwrap();
    let coarse = common::model("spot_control_tri.obj").triangles.len();
    // Level 8: 64 triangles per coarse triangle, none dropped by the welding.
    assert_eq!(refined.triangles.len(), 64 * coarse);
}
