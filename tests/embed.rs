//! The library example (examples/embed.rs, compiled here as a module so the test runs its very
//! code) renders a PNG that shows the mesh and exports the refined mesh, with the validation
//! layer on (it fails on any message or leak), and the export is what the pattern driver makes
//! at level 8.

mod common;

#[allow(dead_code)] // its `main` is the command line's; the test calls `run`
#[path = "../examples/embed.rs"]
mod embed;

use meshrefine::mesh::Mesh;

#[test]
fn the_library_example_renders_and_exports() {
    let _guard = common::gpu_lock();
    let out = common::output_dir().join("embed");
    std::fs::create_dir_all(&out).unwrap();
    let mesh = common::model_path("spot_control_tri.obj");
    embed::run(&mesh, &out).unwrap_or_else(|e| panic!("the example failed: {e:#}"));
    assert_eq!(meshrefine::gpu::live_objects(), 0);

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

/// README.md promises a short example: examples/embed.rs stays under 75 lines.
#[test]
fn the_library_example_is_under_75_lines() {
    let source = include_str!("../examples/embed.rs");
    let readme = include_str!("../README.md");
    assert!(readme.contains("[examples/embed.rs](examples/embed.rs) (under 75 lines)"));
    let lines = source.lines().count();
    assert!(lines < 75, "examples/embed.rs has {lines} lines");
}
