//! The check every GPU test ends with (`tests/common`'s `with_gpu`: the validation layer on,
//! `check_shutdown` after the context is gone) catches what it promises to: a call the
//! validation layer rejects, made on a context created as the tests create theirs, makes the
//! shutdown check fail and names the problem; the same context without it passes; and a
//! wrapper still alive at shutdown (a leak; it keeps its context alive too) fails it, counted.
// The invalid call goes to ash directly: the crate's own wrappers refuse to make it.
#![allow(unsafe_code)]

use ash::vk;
use meshrefine::gpu::{
    check_shutdown, live_objects, Buffer, BufferDesc, Context, ContextDesc, ShutdownError,
};

/// A validated context; with `invalid`, a buffer of size zero created and destroyed (valid
/// usage requires a size above zero: `VUID-VkBufferCreateInfo-size-00912`).
fn run(invalid: bool) -> Result<(), ShutdownError> {
    let desc = ContextDesc {
        validate: true,
        ..Default::default()
    };
    let ctx = Context::new(&desc).expect("a validated Vulkan context");
    let messages = ctx.messages_handle();
    if invalid {
        let info = vk::BufferCreateInfo::default()
            .size(0)
            .usage(vk::BufferUsageFlags::STORAGE_BUFFER);
        // SAFETY: a valid device; the buffer, if created, is destroyed before the device.
        unsafe {
            if let Ok(buffer) = ctx.device.create_buffer(&info, None) {
                ctx.device.destroy_buffer(buffer, None);
            }
        }
    }
    drop(ctx);
    check_shutdown(&messages)
}

/// A validated context whose buffer is never dropped (forgotten, as a leak leaves it): the
/// buffer keeps the context alive, and the shutdown check counts both. Returns the check and
/// the live objects once the context was made. Last in the process: the forgotten wrappers stay
/// counted.
fn leak_a_buffer() -> (Result<(), ShutdownError>, isize) {
    let desc = ContextDesc {
        validate: true,
        ..Default::default()
    };
    let ctx = Context::new(&desc).expect("a validated Vulkan context");
    let with_context = live_objects();
    let messages = ctx.messages_handle();
    let usage = vk::BufferUsageFlags::STORAGE_BUFFER;
    let buffer = Buffer::new(&ctx, BufferDesc::new_upload(256, usage), "leaked").unwrap();
    assert_eq!(
        live_objects(),
        with_context + 1,
        "the buffer is not counted"
    );
    std::mem::forget(buffer);
    drop(ctx);
    (check_shutdown(&messages), with_context)
}

#[test]
fn a_validation_error_fails_the_shutdown_check() {
    run(false).expect("a context that does nothing wrong shuts down cleanly");
    match run(true) {
        Err(ShutdownError::Validation(list)) => assert!(
            list.iter().any(|m| m.contains("size")),
            "the report does not name the problem: {list:?}"
        ),
        other => panic!("an invalid call was not caught: {other:?}"),
    }
    match leak_a_buffer() {
        (Err(ShutdownError::Leaked(n)), with_context) => assert_eq!(n, with_context + 1),
        other => panic!("a leaked buffer was not caught: {other:?}"),
    }
}
