//! The `cargo bench` harness: the benches' `main` builds its meshes and options and hands them
//! to [`Harness::run`], which times them (or, under `cargo test --benches`, runs a small
//! validated smoke run) and prints or writes the table.
#![forbid(unsafe_code)]

use super::{run, BenchOptions, Report};
use crate::mesh::Mesh;

/// What a `cargo bench` target measures: its meshes and options, timed or as a smoke run.
pub struct Harness {
    /// `cargo bench` passed `--bench` (a timed run); otherwise `cargo test --benches` runs a
    /// validated smoke run.
    pub benching: bool,
    /// A smaller set (a smoke run, or `MESHREFINE_BENCH_QUICK=1`).
    pub quick: bool,
}

impl Harness {
    /// Reads the command line and environment, and sets up logging.
    pub fn from_env() -> Self {
        let benching = std::env::args().any(|a| a == "--bench");
        let level = if benching { "info" } else { "warn" };
        env_logger::Builder::from_env(env_logger::Env::default().default_filter_or(level)).init();
        let quick = !benching || std::env::var_os("MESHREFINE_BENCH_QUICK").is_some();
        Self { benching, quick }
    }

    /// Runs `opts` on `meshes` and prints the summary ([`Report::summary`]); a full timed run
    /// also writes the full table to `docs/bench/<name>.{md,csv,json}`. The smoke run is a GPU test like the others: validation
    /// on, and any message or leak fails it; timed runs leave validation off (it slows command
    /// recording 7-10x). Device: the first Vulkan device (MESHREFINE_DEVICE picks one by name).
    pub fn run(&self, name: &str, meshes: &[Mesh], opts: &BenchOptions) {
        self.run_all(name, &[(meshes.to_vec(), opts.clone())]);
    }

    /// [`Harness::run`] for several sets of meshes and options in one table (one context, the
    /// rows in order; the first options' frame size and count head it).
    pub fn run_all(&self, name: &str, jobs: &[(Vec<Mesh>, BenchOptions)]) {
        let desc = crate::gpu::ContextDesc {
            device_name: std::env::var("MESHREFINE_DEVICE").ok(),
            validate: !self.benching,
            ..Default::default()
        };
        let report = crate::gpu::with_context(&desc, |ctx| {
            let mut all: Option<Report> = None;
            for (meshes, opts) in jobs {
                let report = run(ctx.clone(), meshes, opts)?;
                match &mut all {
                    Some(all) => all.rows.extend(report.rows),
                    None => all = Some(report),
                }
            }
            all.ok_or_else(|| Box::<dyn std::error::Error>::from("nothing to measure"))
        })
        .unwrap_or_else(|e| {
            if let Some(crate::gpu::ShutdownError::Validation(list)) = e.downcast_ref() {
                list.iter().for_each(|m| eprintln!("validation: {m}"));
            }
            fail(&e)
        });
        if self.benching && !self.quick {
            let prefix = write_docs(name, &report);
            print!("{}", report.summary(Some(&prefix)));
        } else {
            print!("{}", report.summary_table());
            println!("A full `cargo bench` run writes the full table to docs/bench/{name}.{{md,csv,json}}.");
        }
    }
}

fn fail(e: &dyn std::fmt::Display) -> ! {
    eprintln!("error: {e}");
    std::process::exit(1)
}

/// Writes `docs/bench/<name>.{md,csv,json}`, headed by the `cargo bench` command that made
/// them, keeping a hand-written "## Runs compared" section of the old `.md`; returns the prefix.
fn write_docs(name: &str, report: &Report) -> std::path::PathBuf {
    let prefix = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("docs/bench")
        .join(name);
    // The bench target (argv[0] is `target/<profile>/deps/<target>-<hash>`), which may
    // write several tables.
    let target = std::env::args()
        .next()
        .and_then(|a| {
            let stem = std::path::Path::new(&a).file_stem()?.to_str()?.to_owned();
            Some(stem.split('-').next().unwrap_or(&stem).to_owned())
        })
        .unwrap_or_else(|| name.to_owned());
    let command = if target == name {
        format!("cargo bench --bench {name}")
    } else {
        format!("cargo bench --bench {target}` (its part written as `{name}")
    };
    // A hand-written "## Runs compared" section (earlier runs beside this one) is kept.
    let md = prefix.with_extension("md");
    let kept = std::fs::read_to_string(&md).ok().and_then(|old| {
        old.find("\n## Runs compared")
            .map(|at| old[at..].to_owned())
    });
    report
        .write_files(&prefix, &command)
        .unwrap_or_else(|e| fail(&e));
    if let Some(section) = kept {
        let mut s = std::fs::read_to_string(&md).unwrap_or_else(|e| fail(&e));
        s.push_str(&section);
        std::fs::write(&md, s).unwrap_or_else(|e| fail(&e));
    }
    prefix
}
