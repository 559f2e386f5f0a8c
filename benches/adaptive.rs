//! Adaptive refinement against uniform refinement, in the same run (docs/benchmarks.md,
//! "Adaptive refinement"): three scenes drawn with PN triangles at 1920x1080, culling on:
//! - `close-up`: Spot's control cage seen from close to its head;
//! - `grazing`: the 16x16 terrain seen from low over its edge, looking across it;
//! - `flythrough`: three cameras on a path toward Spot's head, each row the mean over them.
//!
//! For pixel errors 0.5, 1, 2 and 4 and the drivers pattern/instanced, tess and static (refining
//! on the CPU and uploading every frame, as for a moving camera): each element at its own
//! levels (up to 64, the default largest level), and every element at the smallest uniform
//! level meeting the same bound and at the smallest power of two at or above it. Writes
//! docs/bench/adaptive.{md,csv,json} (see `meshrefine::bench::Harness`); then the pattern
//! driver without geomorphing (integer levels, the integer patterns) on the same scenes into
//! docs/bench/adaptive-integer.{md,csv,json}. `MESHREFINE_BENCH_QUICK=1` runs a smaller set
//! (4 px, largest level 8).

use glam::Vec3;
use meshrefine::bench::{BenchAdaptive, BenchOptions, Harness};
use meshrefine::mesh::Mesh;
use meshrefine::render::{Camera, Driver, Submit, View};
use meshrefine::surface::{Displace, Surface};

/// A mesh of assets/models, centred and at unit size as `meshrefine render` draws it, and the
/// map from its own coordinates to the drawn ones.
fn model(file: &str) -> (Mesh, impl Fn(Vec3) -> Vec3) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/models")
        .join(file);
    let (mesh, _) = Mesh::load_obj(&path).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1)
    });
    let (centre, scale) = mesh.viewing_transform();
    let drawn = move |p: Vec3| ((p.as_dvec3() - centre) * scale).as_vec3();
    (mesh.for_viewing(), drawn)
}

/// A camera at `eye` looking at `target`, both in the mesh's coordinates.
fn camera(drawn: &impl Fn(Vec3) -> Vec3, eye: Vec3, target: Vec3) -> Camera {
    Camera::looking(drawn(eye), drawn(target), 45f32.to_radians(), 1.0)
        .expect("the scenes' cameras have a view direction")
}

fn main() {
    let h = Harness::from_env();
    let (pixel_errors, frames, (width, height), max_level, path_steps) = if h.quick {
        (vec![4.0], 1, (192, 108), 8, 2)
    } else {
        // The default largest level (64, lavapipe's tessellator limit), so that the close-up's
        // finest elements get their level and the uniform rows the level meeting the bound;
        // two timed frames, as lavapipe draws a 1080p frame of uniform tess at level 64 on Spot
        // (2.3 M triangles) in seconds (docs/benchmarks.md).
        (vec![0.5, 1.0, 2.0, 4.0], 2, (1920, 1080), 64, 3)
    };
    // Spot's head is at -z (its snout at z = -0.70), its ears up to y = 0.98.
    let (spot, spot_drawn) = model("spot_control_tri.obj");
    let head = Vec3::new(0.0, 0.5, -0.5);
    let close = Vec3::new(0.35, 0.65, -1.3);
    let far = Vec3::new(2.0, 1.6, -5.0);
    let path: Vec<Camera> = (0..path_steps)
        .map(|i| {
            let t = i as f32 / (path_steps - 1).max(1) as f32;
            camera(&spot_drawn, far.lerp(close, t), head)
        })
        .collect();
    // The terrain spans x, z in [-2, 2] with heights up to 0.44: an eye just above its edge.
    let (terrain, terrain_drawn) = model("terrain_16x16.obj");
    let grazing = camera(
        &terrain_drawn,
        Vec3::new(-1.6, 0.35, 2.2),
        Vec3::new(1.2, 0.05, -2.0),
    );
    let scenes = [
        ("close-up", &spot, vec![camera(&spot_drawn, close, head)]),
        ("grazing", &terrain, vec![grazing]),
        ("flythrough", &spot, path),
    ];
    // (geomorphing, drivers): the default, every driver (static never glides: integer levels);
    // then the pattern driver at integer levels.
    let runs = [
        (
            "adaptive",
            true,
            vec![
                Driver::Pattern(Submit::Instanced),
                Driver::Tess,
                Driver::Static,
            ],
        ),
        (
            "adaptive-integer",
            false,
            vec![Driver::Pattern(Submit::Instanced)],
        ),
    ];
    for (name, geomorph, drivers) in runs {
        h.run_all(
            name,
            &jobs(
                &scenes,
                &pixel_errors,
                frames,
                (width, height),
                max_level,
                geomorph,
                &drivers,
            ),
        );
    }
}

/// Every scene at every pixel error for `drivers`, geomorphing as `geomorph` says.
fn jobs(
    scenes: &[(&str, &Mesh, Vec<Camera>)],
    pixel_errors: &[f32],
    frames: u32,
    (width, height): (u32, u32),
    max_level: u32,
    geomorph: bool,
    drivers: &[Driver],
) -> Vec<(Vec<Mesh>, BenchOptions)> {
    let mut jobs = Vec::new();
    for (scene, mesh, cameras) in scenes {
        for &pixel_error in pixel_errors {
            let opts = BenchOptions {
                build: Default::default(),
                levels: vec![],
                surfaces: vec![(Surface::Pn, Displace::None)],
                params: None,
                frames,
                width,
                height,
                drivers: drivers.to_vec(),
                min_total_ms: 0.0,
                camera: meshrefine::bench::BenchCamera::default(),
                adaptive: Some(BenchAdaptive {
                    scene: (*scene).into(),
                    cameras: cameras.clone(),
                    pixel_error,
                    cull: true,
                    max_level,
                    bound_levels: true,
                    geomorph,
                }),
                view: View::Shaded,
                heightmap: None,
            };
            jobs.push((vec![(*mesh).clone()], opts));
        }
    }
    jobs
}
