//! Shared test support: a validated Vulkan context per test, serialized (one device at a time in a
//! test process, and the live-object counter is process-wide), with the validation layer on; any
//! validation warning or error, leaked Vulkan object or leaked allocation fails the test.
#![allow(dead_code)]

pub mod random_levels;

use meshrefine::gpu::{check_shutdown, live_objects, ContextDesc, ShutdownError};
use meshrefine::mesh::Mesh;
use meshrefine::render::Headless;
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
