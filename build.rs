//! Compiles every GLSL file under `glsl/` to SPIR-V with shaderc and embeds it.
//!
//! - stage from the extension (`.vert .tesc .tese .geom .frag .comp`); `glsl/include/` holds
//!   shared code (`#include "x.glsl"` resolves next to the including file, then in `glsl/include`);
//! - warnings are errors; optimisation for performance in every profile (lavapipe compiles unoptimized SPIR-V slowly);
//! - binding numbers come from `src/render/bindings.rs` as macro definitions;
//! - a source that mentions `ELEMENT_ATTRIBUTES` is also compiled with it defined (`+elements`:
//!   the static driver's vertices carry their element and sample);
//! - a source that mentions `CAPTURE` is also compiled with `CAPTURE` defined (the capture
//!   variant writes its evaluated vertices to a storage buffer), one that mentions `XFB` with
//!   `XFB` defined (transform-feedback decorations on its outputs);
//! - errors are printed as `file:line: message` and fail the build.
//!
//! Output: `$OUT_DIR/shaders.rs`, a table `SHADERS: &[(&str, &[u8])]` keyed by the path below
//! `glsl/` (plus `+capture` / `+xfb` for the variants).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

#[allow(dead_code)]
mod bindings {
    include!("src/render/bindings.rs");
}

fn stage(path: &Path) -> Option<shaderc::ShaderKind> {
    use shaderc::ShaderKind::*;
    Some(match path.extension()?.to_str()? {
        "vert" => Vertex,
        "tesc" => TessControl,
        "tese" => TessEvaluation,
        "geom" => Geometry,
        "frag" => Fragment,
        "comp" => Compute,
        _ => return None,
    })
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            walk(&p, out);
        } else {
            out.push(p);
        }
    }
}

fn main() {
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    let glsl = root.join("glsl");
    let include_dir = glsl.join("include");
    let out_dir = PathBuf::from(std::env::var("OUT_DIR").unwrap());
    println!("cargo:rerun-if-changed=src/render/bindings.rs");
    println!("cargo:rerun-if-changed=glsl");

    let mut files = Vec::new();
    walk(&glsl, &mut files);
    for f in &files {
        println!("cargo:rerun-if-changed={}", f.display());
    }

    let compiler = shaderc::Compiler::new().expect("shaderc compiler");
    let mut table = String::from("pub static SHADERS: &[(&str, &[u8])] = &[\n");
    let mut failed = Vec::new();
    for path in files.iter().filter(|p| stage(p).is_some()) {
        let kind = stage(path).unwrap();
        let rel = path
            .strip_prefix(&glsl)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let source = std::fs::read_to_string(path).unwrap();
        // (suffix, macro) of each variant: plain, and those the source mentions.
        let variants: Vec<(&str, Option<&str>)> = std::iter::once(("", None))
            .chain(
                source
                    .contains("CAPTURE")
                    .then_some(("+capture", Some("CAPTURE"))),
            )
            .chain(source.contains("XFB").then_some(("+xfb", Some("XFB"))))
            .chain(
                source
                    .contains("ELEMENT_ATTRIBUTES")
                    .then_some(("+elements", Some("ELEMENT_ATTRIBUTES"))),
            )
            .collect();
        for &(suffix, define) in &variants {
            let mut opts = shaderc::CompileOptions::new().unwrap();
            opts.set_target_env(
                shaderc::TargetEnv::Vulkan,
                shaderc::EnvVersion::Vulkan1_3 as u32,
            );
            opts.set_source_language(shaderc::SourceLanguage::GLSL);
            opts.set_warnings_as_errors();
            opts.set_generate_debug_info();
            // Optimized in every profile: unoptimized SPIR-V (every local array copied, nothing
            // inlined) made lavapipe take seconds per pipeline at its first draw.
            opts.set_optimization_level(shaderc::OptimizationLevel::Performance);
            for (name, value) in bindings::GLSL_DEFINES {
                opts.add_macro_definition(name, Some(&value.to_string()));
            }
            if let Some(d) = define {
                opts.add_macro_definition(d, Some("1"));
            }
            let inc = include_dir.clone();
            opts.set_include_callback(move |name, _ty, from, _depth| {
                let from_dir = Path::new(from)
                    .parent()
                    .map(Path::to_path_buf)
                    .unwrap_or_default();
                for dir in [from_dir, inc.clone()] {
                    let p = dir.join(name);
                    if let Ok(content) = std::fs::read_to_string(&p) {
                        return Ok(shaderc::ResolvedInclude {
                            resolved_name: p.to_string_lossy().into_owned(),
                            content,
                        });
                    }
                }
                Err(format!("cannot find include \"{name}\""))
            });
            let file_name = path.to_string_lossy();
            match compiler.compile_into_spirv(&source, kind, &file_name, "main", Some(&opts)) {
                Ok(art) => {
                    if art.get_num_warnings() > 0 {
                        failed.push(art.get_warning_messages());
                        continue;
                    }
                    let key = format!("{rel}{suffix}");
                    let spv = out_dir.join(format!("{}.spv", key.replace(['/', '+'], "_")));
                    std::fs::write(&spv, art.as_binary_u8()).unwrap();
                    writeln!(
                        table,
                        "    ({key:?}, include_bytes!({:?})),",
                        spv.to_string_lossy()
                    )
                    .unwrap();
                }
                Err(e) => failed.push(e.to_string()),
            }
        }
    }
    table.push_str("];\n");
    if !failed.is_empty() {
        for msg in &failed {
            // shaderc prints "file:line: error: message"; keep it as is, one per line.
            for line in msg.lines() {
                println!("cargo:warning={line}");
            }
        }
        eprintln!("{}", failed.join("\n"));
        panic!(
            "GLSL compilation failed ({} shader(s)); see the messages above",
            failed.len()
        );
    }
    std::fs::write(out_dir.join("shaders.rs"), table).unwrap();
}
