//! The command line: arguments ([`args`], with [`choices`] adapting the library's enums), the
//! rule for options that do not apply ([`options`]), what every command loads ([`input`], with
//! Loop's refusals in [`loop_check`]), and one file per command: [`render`], [`view`],
//! [`export`], [`info`], [`bench`].
//!
//! Each command checks its output paths and the options it can check without reading anything
//! first, then loads its inputs, then creates a GPU context (validated when asked) and runs;
//! every failure is one sentence for `main` to print.
#![forbid(unsafe_code)]

mod adaptive;
mod args;
mod bench;
mod choices;
mod export;
mod info;
mod input;
mod loop_check;
mod numbers;
mod options;
mod params;
mod progress;
mod render;
mod view;

pub use args::Cli;
pub use options::{check_values, parse, warnings};

use crate::note;
use anyhow::{bail, Result};
use args::Command;
use meshrefine::gpu::{Context, ContextDesc, Messages, ShutdownError};
use std::io::Write as _;
use std::path::Path;
use std::sync::Arc;

/// The command line as it was run, for records (an export's header, bench's tables):
/// `meshrefine` and the arguments, each read lossily (a path need not be UTF-8) with its control
/// characters escaped, so that it stays one line, and single-quoted for a POSIX shell where it
/// holds anything but letters, digits and `-_./,=:+@%` (a path with a space runs again as given).
pub fn command_line() -> String {
    let plain = |c: char| c.is_alphanumeric() || "-_./,=:+@%".contains(c);
    let args: Vec<String> = std::env::args_os()
        .skip(1)
        .map(|a| {
            let a = crate::printable(&a.to_string_lossy()).into_owned();
            if !a.is_empty() && a.chars().all(plain) {
                a
            } else {
                format!("'{}'", a.replace('\'', "'\\''"))
            }
        })
        .collect();
    format!("meshrefine {}", args.join(" "))
}

/// Runs `cli`'s command (`given`: the options given on the command line).
pub fn run(cli: Cli, given: &options::Given) -> Result<()> {
    let desc = context_desc(&cli)?;
    options::check_outputs(&cli).map_err(anyhow::Error::msg)?;
    adaptive::check(&cli, given)?;
    match &cli.command {
        Command::Render(a) => render::run(a, &desc, given.has("level")),
        Command::View(a) => view::run(a, &desc, given),
        Command::Export(a) => export::run(a, &desc),
        Command::Info(a) => info::run(a, &desc),
        Command::Bench(a) => bench::run(a, &desc, given.has("levels")),
        Command::Devices => devices(&desc),
    }
}

fn context_desc(cli: &Cli) -> Result<ContextDesc> {
    let env = std::env::var("MESHREFINE_VALIDATE").is_ok_and(|v| !v.is_empty() && v != "0");
    Ok(ContextDesc {
        validate: cli.validate || env,
        device_name: cli.device.clone(),
        surface_extensions: vec![],
        max_storage_buffer_range: storage_range_env()?,
        max_memory_allocation_size: bytes_env(MAX_ALLOCATION_ENV, u64::MAX)?,
        hidden_features: hidden_features_env()?,
    })
}

/// The environment variable that has the device seen without some features (a test's knob:
/// the paths a device without them takes, on one that has them).
const HIDE_FEATURES_ENV: &str = "MESHREFINE_HIDE_FEATURES";

/// The features `MESHREFINE_HIDE_FEATURES` names, comma-separated, each one meshrefine checks.
fn hidden_features_env() -> Result<Vec<String>> {
    use meshrefine::gpu::CHECKED_FEATURES;
    let Ok(s) = std::env::var(HIDE_FEATURES_ENV) else {
        return Ok(Vec::new());
    };
    let names: Vec<String> = (s.split(','))
        .map(str::trim)
        .filter(|n| !n.is_empty())
        .map(str::to_string)
        .collect();
    if let Some(bad) = names
        .iter()
        .find(|n| !CHECKED_FEATURES.contains(&n.as_str()))
    {
        bail!(
            "{HIDE_FEATURES_ENV}: '{}' is not a feature meshrefine checks (one of {})",
            crate::printable(bad),
            CHECKED_FEATURES.join(", ")
        );
    }
    Ok(names)
}

/// The environment variable that has the device seen with a smaller `maxStorageBufferRange`
/// (a test's knob: a small mesh then meets the limits a very large one meets).
const MAX_STORAGE_RANGE_ENV: &str = "MESHREFINE_MAX_STORAGE_BUFFER_RANGE";

/// The same for `maxMemoryAllocationSize`.
const MAX_ALLOCATION_ENV: &str = "MESHREFINE_MAX_MEMORY_ALLOCATION_SIZE";

fn storage_range_env() -> Result<Option<u32>> {
    Ok(bytes_env(MAX_STORAGE_RANGE_ENV, u32::MAX as u64)?.map(|n| n as u32))
}

/// A test's knob read from environment variable `name`: a positive number of bytes, at most
/// `max`; `None` where it is not set.
pub fn bytes_env(name: &str, max: u64) -> Result<Option<u64>> {
    let Ok(s) = std::env::var(name) else {
        return Ok(None);
    };
    match s.trim().parse::<u64>() {
        Ok(n) if n > 0 && n <= max => Ok(Some(n)),
        _ if max < u64::MAX => {
            bail!("{name} must be a positive number of bytes, at most {max}, not '{s}'")
        }
        _ => bail!("{name} must be a positive number of bytes, not '{s}'"),
    }
}

/// Refuses an output path whose extension says another format than the one written.
pub fn require_extension(path: &Path, ext: &str, what: &str) -> Result<()> {
    let matches = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(ext));
    if !matches {
        // `.png` alone is a hidden file's name without an extension (Rust's reading).
        let bare = path
            .file_name()
            .and_then(|n| n.to_str())
            .is_some_and(|n| n.eq_ignore_ascii_case(&format!(".{ext}")));
        if bare {
            bail!(
                "output file '{}' has no name before its .{ext} (name it, e.g. out.{ext})",
                path.display()
            );
        }
        bail!(
            "output file '{}' does not end in .{ext}: {what} (name it .{ext})",
            path.display()
        );
    }
    Ok(())
}

/// After every GPU object is gone: fail if the validation layer complained or anything leaked.
pub fn check_messages(messages: &Arc<Messages>) -> Result<()> {
    meshrefine::gpu::check_shutdown(messages).map_err(noted)
}

/// The validation layer's messages as notes, before the error that counts them.
fn noted(e: ShutdownError) -> anyhow::Error {
    if let ShutdownError::Validation(list) = &e {
        for m in list {
            note(format_args!("validation: {m}"));
        }
    }
    e.into()
}

/// [`meshrefine::gpu::with_context`] with the validation layer's messages printed as notes.
pub fn with_context<R>(desc: &ContextDesc, f: impl FnOnce(Arc<Context>) -> Result<R>) -> Result<R> {
    meshrefine::gpu::with_context(desc, f).map_err(|e| match e.downcast::<ShutdownError>() {
        Ok(s) => noted(s),
        Err(e) => e,
    })
}

/// `meshrefine devices`: every Vulkan 1.3 device, the default first, with the features
/// meshrefine uses there (or why it cannot draw there).
fn devices(desc: &meshrefine::gpu::ContextDesc) -> Result<()> {
    let yes = |b: bool| if b { "yes" } else { "no" };
    let list = meshrefine::gpu::list_devices(desc)?;
    if list.is_empty() {
        anyhow::bail!("no Vulkan 1.3 device with a graphics and compute queue was found");
    }
    for (k, device) in list.iter().enumerate() {
        let default = if k == 0 { " (default)" } else { "" };
        match device {
            Ok(info) => {
                out!("{}{default}", info.describe());
                let l = &info.limits;
                out!(
                    "  tess driver levels (maxTessellationGenerationLevel): up to {}",
                    l.max_tessellation_generation_level
                );
                out!(
                    "  pattern export and capture (vertexPipelineStoresAndAtomics): {}",
                    yes(info.vertex_stores)
                );
                out!(
                    "  export through tess (transformFeedback): {}",
                    yes(info.transform_feedback)
                );
                out!(
                    "  wireframe (fillModeNonSolid): {}",
                    yes(info.fill_mode_non_solid)
                );
                out!(
                    "  wireframe kept off the far side (depthBiasClamp): {}",
                    yes(info.depth_bias_clamp)
                );
                out!(
                    "  vertex statistics (pipelineStatisticsQuery): {}",
                    yes(info.pipeline_statistics)
                );
                out!(
                    "  records per chunk bound (maxStorageBufferRange): {} bytes; largest allocation: {} bytes",
                    l.max_storage_buffer_range,
                    info.max_memory_allocation_size
                );
            }
            Err(e) => out!("unusable: {e}"),
        }
    }
    Ok(())
}
