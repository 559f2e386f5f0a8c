//! Compiles every GLSL file under `glsl/` to SPIR-V with shaderc and embeds it.
//!
//! - stage from the extension (`.vert .tesc .tese .geom .frag .comp`); `glsl/include/` holds
//!   shared code (`#include "x.glsl"` resolves next to the including file, then in `glsl/include`);
//! - warnings are errors; optimisation for performance in every profile (lavapipe compiles unoptimized SPIR-V slowly);
//! - binding numbers come from `src/render/bindings.rs` as macro definitions;
//! - variants are declared in [`VARIANTS`]: a stage compiled again with a macro defined, e.g.
//!   `CAPTURE` (the capture variant writes its evaluated vertices to a storage buffer), `XFB`
//!   (transform-feedback decorations on its outputs), `ELEMENT_ATTRIBUTES` (the static driver's
//!   vertices carry their element and sample). A source that tests a variant macro it does not
//!   declare, or declares one it never tests, fails the build;
//! - every embedded name is also a constant in `names` (`tess/tess.tese+xfb` is
//!   `names::TESS_TESS_TESE_XFB`), so code that asks for a variant that is not built does not
//!   compile;
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

/// The variants: (source below `glsl/`, name suffix, macro defined).
const VARIANTS: &[(&str, &str, &str)] = &[
    ("pattern/pattern.vert", "capture", "CAPTURE"),
    ("pattern/adaptive.vert", "capture", "CAPTURE"),
    ("static/static.vert", "elements", "ELEMENT_ATTRIBUTES"),
    ("tess/tess.tese", "capture", "CAPTURE"),
    ("tess/tess.tese", "xfb", "XFB"),
];

/// The constant naming an embedded shader: `tess/tess.tese+xfb` -> `TESS_TESS_TESE_XFB`.
fn const_name(key: &str) -> String {
    key.to_uppercase().replace(['/', '.', '+'], "_")
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

/// `path`'s text followed by its includes' (recursively; for checking which macros it tests).
fn with_includes(path: &Path, include_dir: &Path) -> String {
    let mut text = std::fs::read_to_string(path).unwrap_or_default();
    let mut seen = vec![path.to_path_buf()];
    let mut k = 0;
    while k < seen.len() {
        let src = std::fs::read_to_string(&seen[k]).unwrap_or_default();
        let dir = seen[k].parent().map(Path::to_path_buf).unwrap_or_default();
        for line in src.lines() {
            let Some(name) = line.trim().strip_prefix("#include \"") else {
                continue;
            };
            let name = name.trim_end_matches('"');
            let found = [dir.join(name), include_dir.join(name)]
                .into_iter()
                .find(|p| p.exists());
            if let Some(p) = found.filter(|p| !seen.contains(p)) {
                text.push_str(&std::fs::read_to_string(&p).unwrap_or_default());
                seen.push(p);
            }
        }
        k += 1;
    }
    text
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
    let mut names =
        String::from("/// Every embedded shader's name.\n#[allow(dead_code)]\npub mod names {\n");
    let mut failed = Vec::new();
    for path in files.iter().filter(|p| stage(p).is_some()) {
        let kind = stage(path).unwrap();
        let rel = path
            .strip_prefix(&glsl)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let source = std::fs::read_to_string(path).unwrap();
        // (suffix, macro) of each variant: plain, and those declared for this source.
        let declared: Vec<(String, Option<&str>)> = VARIANTS
            .iter()
            .filter(|v| v.0 == rel)
            .map(|v| (format!("+{}", v.1), Some(v.2)))
            .collect();
        let expanded = with_includes(path, &include_dir);
        for (_, m) in &declared {
            let m = m.unwrap();
            if !(expanded.contains(&format!("ifdef {m}"))
                || expanded.contains(&format!("defined({m})")))
            {
                failed.push(format!(
                    "{}: the variant macro {m} is declared (build.rs VARIANTS) but neither the file nor its includes test it",
                    path.display()
                ));
            }
        }
        let variants: Vec<(String, Option<&str>)> = std::iter::once((String::new(), None))
            .chain(declared)
            .collect();
        for (suffix, define) in &variants {
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
                    writeln!(names, "    pub const {}: &str = {key:?};", const_name(&key)).unwrap();
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
    names.push_str("}\n");
    table.push_str(&names);
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
