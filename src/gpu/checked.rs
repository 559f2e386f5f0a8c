//! One way to run GPU work with its checks: create a context, run, drop every Vulkan object, then
//! fail if the validation layer said anything or anything leaked. Used by the binary, the bench
//! harness and the tests alike.

use super::{live_objects, Context, ContextDesc, GpuError, Messages};
use std::sync::Arc;

/// What the checks found at shutdown.
#[derive(Debug, thiserror::Error)]
pub enum ShutdownError {
    #[error("{0} Vulkan object(s) were still alive at shutdown")]
    Leaked(isize),
    /// The layer's messages (and leaked allocations gpu-allocator reported).
    #[error("the Vulkan validation layer reported {} problem(s)", .0.len())]
    Validation(Vec<String>),
}

/// After every GPU object is gone: an error if any wrapper is still alive, or if the validation
/// layer (or the allocator's leak report) left messages in `messages`.
pub fn check_shutdown(messages: &Messages) -> Result<(), ShutdownError> {
    let list = messages.take();
    let leaked = live_objects();
    if leaked != 0 {
        return Err(ShutdownError::Leaked(leaked));
    }
    if !list.is_empty() {
        return Err(ShutdownError::Validation(list));
    }
    Ok(())
}

/// Create a context from `desc`, run `f` with it (`f` owns the context: everything it made is
/// dropped when it returns), then [`check_shutdown`]. An error of `f` is returned as it is.
pub fn with_context<R, E>(
    desc: &ContextDesc,
    f: impl FnOnce(Arc<Context>) -> Result<R, E>,
) -> Result<R, E>
where
    E: From<GpuError> + From<ShutdownError>,
{
    let ctx = Context::new(desc)?;
    let messages = ctx.messages_handle();
    let out = f(ctx)?;
    check_shutdown(&messages)?;
    Ok(out)
}
