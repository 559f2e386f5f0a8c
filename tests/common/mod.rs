//! Shared test support: a validated Vulkan context per test, serialized (one device at a time in a
//! test process, and the live-object counter is process-wide), with the validation layer on; any
//! validation warning or error, leaked Vulkan object or leaked allocation fails the test.
#![allow(dead_code)]

pub mod cli;
pub mod random_levels;
pub mod watertight;

use meshrefine::gpu::{check_shutdown, live_objects, ContextDesc, ShutdownError};
use meshrefine::mesh::Mesh;
use meshrefine::render::{DrawConfig, Headless};
use meshrefine::surface::{CornerRecord, Displace, ElementRecord, Surface, SMOOTH_CORNER};
use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard};

static GPU_LOCK: Mutex<()> = Mutex::new(());

pub fn model_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/models")
        .join(name)
}

pub fn model(name: &str) -> Mesh {
    Mesh::load_obj(&model_path(name))
        .unwrap_or_else(|e| panic!("{e}"))
        .0
}

/// Directory for images written by failing tests (actual and diff).
pub fn output_dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/test-output");
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Serialize GPU use within a test process.
pub fn gpu_lock() -> MutexGuard<'static, ()> {
    GPU_LOCK.lock().unwrap_or_else(|p| p.into_inner())
}

/// Run `f` with a fresh validated headless renderer of `width`x`height`; afterwards assert that
/// the validation layer said nothing and that nothing leaked.
pub fn with_gpu<R>(width: u32, height: u32, f: impl FnOnce(&mut Headless) -> R) -> R {
    let _guard = gpu_lock();
    assert_eq!(live_objects(), 0, "a previous test leaked Vulkan objects");
    let desc = ContextDesc {
        validate: true,
        ..Default::default()
    };
    let mut h = Headless::new(&desc, width, height)
        .unwrap_or_else(|e| panic!("cannot create a validated Vulkan context: {e}"));
    let messages = h.ctx.messages_handle();
    let out = f(&mut h);
    drop(h);
    match check_shutdown(&messages) {
        Ok(()) => out,
        Err(ShutdownError::Validation(list)) => {
            panic!("validation layer / leak reports:\n{}", list.join("\n"))
        }
        Err(e) => panic!("{e}"),
    }
}

/// The pattern driver's position tolerance against the mirror (tests/gpu_mirror.rs
/// `position_tolerance`, per element record).
pub fn pattern_tolerance(cfg: &DrawConfig, r: f32, records: &[ElementRecord]) -> f32 {
    let eps = f32::EPSILON * r;
    let seamed = records
        .iter()
        .any(|x| (0..3).any(|i| CornerRecord::decode(x).p[i][3] != SMOOTH_CORNER));
    let base = if cfg.surface == Surface::Loop {
        64.0 * eps
    } else {
        0.0
    };
    let uses_normals =
        !matches!(cfg.surface, Surface::Flat | Surface::Loop) || cfg.displace != Displace::None;
    let seams = if seamed && uses_normals && cfg.surface != Surface::Loop {
        4.0 * eps
    } else {
        0.0
    };
    let a = cfg.params.amplitude.abs();
    base + seams
        + match cfg.displace {
            Displace::None => 0.0,
            Displace::Sine => 2e-3 * a + 8.0 * eps,
            Displace::Noise => 1e-5 * a + 8.0 * eps,
            Displace::Heightmap => 1e-4 * a + 8.0 * eps,
        }
}

/// The fields of one line of bench's CSV (not every test reads one).
#[allow(unused_imports)]
pub use meshrefine::bench::csv_fields;

/// Runs the binary with `args` as a user would, with the validation layer on and no display,
/// one at a time with this test process's other GPU work.
pub fn validated_cli(args: &[&str]) -> std::process::Output {
    let _guard = gpu_lock();
    std::process::Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .env("MESHREFINE_VALIDATE", "1")
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .args(args)
        .output()
        .expect("run meshrefine")
}

/// A path for `name` in the folder `dir` of the tests' temporary directory (made if missing).
pub fn tmp_file(dir: &str, name: &str) -> String {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(dir);
    std::fs::create_dir_all(&d).unwrap();
    d.join(name).to_str().unwrap().to_string()
}

/// A bicone: two poles of valence `n` joined by a ring of `n` vertices (`2n` triangles wound
/// outwards), as OBJ text; what Loop's faces around a vertex of high valence cost.
pub fn bicone_obj(n: usize) -> String {
    let mut obj = String::from("v 0 1 0\nv 0 -1 0\n");
    for k in 0..n {
        let a = std::f64::consts::TAU * k as f64 / n as f64;
        obj += &format!("v {} 0 {}\n", a.cos(), a.sin());
    }
    for k in 0..n {
        let (a, b) = (3 + k, 3 + (k + 1) % n);
        obj += &format!("f 1 {b} {a}\nf 2 {a} {b}\n");
    }
    obj
}

/// Tags for every vertex of `mesh`, centred on the origin: tension, sharpness and bias varying
/// from vertex to vertex in [-0.45, 0.45], [0, 9/11] and [-0.4, 0.4]; the first vertex and the
/// one farthest from it creases (no triangle holds both, as appendix B asks), their direction
/// across the radial normal.
pub fn own_tags(mesh: &meshrefine::mesh::Mesh) -> Vec<meshrefine::surface::stpn::VertexTag> {
    let p = &mesh.positions;
    let far = (0..p.len())
        .max_by(|&a, &b| p[a].distance(p[0]).total_cmp(&p[b].distance(p[0])))
        .unwrap();
    (0..p.len())
        .map(|i| {
            let k = i as f32;
            let normal = p[i].normalize();
            let crease = i == 0 || i == far;
            meshrefine::surface::stpn::VertexTag {
                tension: ((k * 7.0) % 10.0) / 10.0 - 0.45,
                sharpness: ((k * 3.0) % 10.0) / 11.0,
                bias: ((k * 5.0) % 9.0) / 10.0 - 0.4,
                direction: if crease {
                    normal.any_orthonormal_vector()
                } else {
                    glam::Vec3::ZERO
                },
                normal: if crease { normal } else { glam::Vec3::ZERO },
            }
        })
        .collect()
}
