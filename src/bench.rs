//! Benchmarks shared by `cargo bench` (benches/fig7.rs) and `meshrefine bench`: every surface x
//! displacement x driver and submission mode on the same meshes and levels, in the same run, so the
//! ratios against `static` (same surface, displacement, mesh and level) compare like with like. Frame time from GPU timestamps and wall clock (submit to fence), median
//! and spread over timed frames after one warm-up frame (Mesa compiles shaders at the first draw);
//! the timed frames go round the variants in turn (static, push, ubo, instanced, tess, static, ...),
//! with several surfaces round every surface's variants together (each surface's `static` timed
//! alone before them: its buffer of refined vertices is one surface's), so a drift of the machine
//! touches every variant alike. Timings are measured, never asserted.
#![forbid(unsafe_code)]

use crate::mesh::Mesh;
use crate::pattern::PatternSet;
use crate::render::{Camera, DrawConfig, Driver, Headless, RenderError, Scene};
use crate::surface::{Displace, Surface, SurfaceParams};
use std::fmt::Write as _;
use std::sync::Arc;

#[derive(Clone, Debug)]
pub struct BenchOptions {
    pub levels: Vec<u32>,
    /// Surface x displacement combinations measured (each against its own `static`).
    pub surfaces: Vec<(Surface, Displace)>,
    /// Parameters; `None`: [`SurfaceParams::for_radius`] of each mesh.
    pub params: Option<SurfaceParams>,
    pub frames: u32,
    pub width: u32,
    pub height: u32,
    /// The driver variants measured (empty: every one; `static` is the reference of the ratios).
    pub drivers: Vec<Driver>,
    /// Keep taking rounds past `frames` until every variant has this much GPU time in total
    /// (milliseconds; 0: exactly `frames`), so frames of a few milliseconds, whose timestamps
    /// jitter most, get more samples. At most 20 × `frames` rounds.
    pub min_total_ms: f64,
}

/// Median, min and max of a sample.
#[derive(Clone, Copy, Debug, Default)]
pub struct Stat {
    pub median: f64,
    pub min: f64,
    pub max: f64,
}

impl Stat {
    pub fn of(v: &[f64]) -> Self {
        let mut s = v.to_vec();
        s.sort_by(f64::total_cmp);
        if s.is_empty() {
            return Self::default();
        }
        let n = s.len();
        let median = if n % 2 == 1 {
            s[n / 2]
        } else {
            0.5 * (s[n / 2 - 1] + s[n / 2])
        };
        Self {
            median,
            min: s[0],
            max: s[n - 1],
        }
    }
}

#[derive(Clone, Debug)]
pub struct Row {
    pub mesh: String,
    pub coarse_triangles: u32,
    /// What the surface refines: the coarse triangles, or M1's faces for `loop`.
    pub elements: u32,
    pub level: u32,
    pub surface: Surface,
    pub displace: Displace,
    pub variant: String,
    pub refined_triangles: u64,
    pub gpu_ms: Option<Stat>,
    pub wall_ms: Option<Stat>,
    /// Vertices and indices of refined geometry stored on the GPU.
    pub stored_vertices: u64,
    pub stored_indices: u64,
    pub geometry_bytes: u64,
    /// Vertex-shader invocations of the last timed frame (pipeline statistics), where queried.
    pub vertex_invocations: Option<u64>,
    /// GPU and wall time relative to `static` at the same mesh and level (same run).
    pub gpu_ratio: Option<f64>,
    pub wall_ratio: Option<f64>,
    /// Refined triangles per GPU millisecond relative to `flat` with the same variant, mesh,
    /// level and displacement (same run; when flat was measured).
    pub throughput_vs_flat: Option<f64>,
    /// `loop`: GPU time of the M0 -> M1 and normals passes (timed alone, per frame), and the
    /// basis function tables' bytes.
    pub pre_pass_ms: Option<f64>,
    pub table_bytes: Option<u64>,
    pub note: String,
}

impl Row {
    /// Median GPU time per refined triangle, in nanoseconds: the per-triangle cost.
    pub fn ns_per_triangle(&self) -> Option<f64> {
        self.gpu_ms
            .map(|s| s.median * 1e6 / self.refined_triangles.max(1) as f64)
    }
}

pub struct Report {
    pub device: String,
    pub frames: u32,
    pub width: u32,
    pub height: u32,
    pub rows: Vec<Row>,
}

/// One variant's row and timed frames while the frames go round the variants.
struct Run {
    row: Row,
    cfg: DrawConfig,
    drawn: bool,
    gpu: Vec<f64>,
    wall: Vec<f64>,
}

/// Measure every variant on every mesh at every level.
pub fn run(
    ctx: Arc<crate::gpu::Context>,
    meshes: &[Mesh],
    opts: &BenchOptions,
) -> Result<Report, RenderError> {
    let device = ctx.info.describe();
    let mut h = Headless::with_context(ctx.clone(), opts.width, opts.height)?;
    let mut rows = Vec::new();
    for mesh in meshes {
        let mut scene: Scene = Scene::with_patterns(
            &h.ctx,
            &h.pool,
            &h.renderer,
            mesh.clone(),
            PatternSet::from_levels(&opts.levels),
        )?;
        let (c, r) = scene.bounding_sphere();
        let camera = Camera::framing(c, r);
        let coarse = scene.gpu.element_count;
        let params = opts.params.unwrap_or_else(|| SurfaceParams::for_radius(r));
        // Flat first (the reference of the throughput ratios), then as asked.
        let mut surfaces = opts.surfaces.clone();
        surfaces.sort_by_key(|&(s, _)| s != Surface::Flat);
        // The loop passes' cost, timed alone (median of the timed frames).
        let pre_pass_ms = if surfaces.iter().any(|&(s, _)| s == Surface::Loop) {
            let mut cfg =
                DrawConfig::new(Driver::default(), opts.levels.first().copied().unwrap_or(1));
            cfg.surface = Surface::Loop;
            cfg.params = params;
            let mut times = Vec::new();
            for _ in 0..=opts.frames.max(1) {
                times.extend(h.time_pre_pass(&mut scene, &cfg)?);
            }
            Some(Stat::of(&times[1..]).median)
        } else {
            None
        };
        for &level in &opts.levels {
            // Refined triangles per GPU ms of `flat` by variant and displacement.
            let mut flat_rate: Vec<(String, Displace, f64)> = Vec::new();
            // Every variant of every surface is warmed up, then the timed frames go round the
            // variants of every surface in turn, so a slow drift of the machine (this one moves
            // ±25 % from run to run) touches every variant alike and the ratios against `flat`
            // compare like with like (`static`, with several surfaces, aside: below).
            let mut runs: Vec<Run> = Vec::new();
            for &(surface, displace) in &surfaces {
                for driver in Driver::VARIANTS {
                    let mut cfg = DrawConfig::new(driver, level).with_surface(surface, displace);
                    cfg.params = params;
                    if !opts.drivers.is_empty() && !opts.drivers.contains(&driver) {
                        continue;
                    }
                    let refused = crate::render::driver::check_level(&ctx, &cfg).err();
                    let drawn = refused.is_none();
                    let t = if drawn {
                        h.prepared_elements(&mut scene, &cfg, crate::render::Capture::None)?
                    } else {
                        // Not drawn; loop's M1 is there once another driver drew it.
                        scene.elements(surface).element_count
                    };
                    let (stored_vertices, stored_indices) =
                        cfg.driver.kind().stored(cfg.level, t as u64);
                    let geometry_bytes = scene.geometry_bytes(&cfg);
                    let loop_scene = scene.subdiv.as_ref().filter(|_| surface == Surface::Loop);
                    let mut row = Row {
                        mesh: mesh.name.clone(),
                        coarse_triangles: coarse,
                        elements: t,
                        level,
                        surface,
                        displace,
                        variant: cfg.label(),
                        refined_triangles: t as u64 * cfg.refined_per_element() as u64,
                        gpu_ms: None,
                        wall_ms: None,
                        stored_vertices,
                        stored_indices,
                        geometry_bytes,
                        vertex_invocations: None,
                        gpu_ratio: None,
                        wall_ratio: None,
                        throughput_vs_flat: None,
                        pre_pass_ms: loop_scene.and(pre_pass_ms),
                        table_bytes: loop_scene.map(|l| l.data.table_bytes()),
                        note: String::new(),
                    };
                    if drawn {
                        h.draw(&mut scene, &cfg, &camera)?; // warm-up: shaders, static VBO
                    } else if let Some(e) = refused {
                        row.note = format!("not drawn: {e}");
                    }
                    runs.push(Run {
                        row,
                        cfg,
                        drawn,
                        gpu: Vec::new(),
                        wall: Vec::new(),
                    });
                }
            }
            let frames = opts.frames.max(1) as usize;
            let enough = |r: &Run| {
                r.gpu.len() >= frames
                    && (r.gpu.iter().sum::<f64>() >= opts.min_total_ms
                        || r.gpu.len() >= 20 * frames)
            };
            // `static` draws one buffer of refined vertices, rebuilt for another surface: with
            // several surfaces, each surface's `static` is timed alone (after a frame that builds
            // its buffer), then the other variants of every surface go round together.
            let drawn: Vec<usize> = (0..runs.len()).filter(|&i| runs[i].drawn).collect();
            let is_static = |i: &usize| runs[*i].cfg.driver.kind().refines_on_cpu();
            let groups: Vec<Vec<usize>> = if surfaces.len() > 1 {
                let (alone, together): (Vec<usize>, Vec<usize>) =
                    drawn.iter().partition(|i| is_static(i));
                alone
                    .into_iter()
                    .map(|i| vec![i])
                    .chain([together])
                    .collect()
            } else {
                vec![drawn]
            };
            for group in groups {
                if surfaces.len() > 1 && group.len() == 1 {
                    h.draw(&mut scene, &runs[group[0]].cfg, &camera)?;
                }
                while !group.iter().all(|&i| enough(&runs[i])) {
                    for &i in &group {
                        let f = h.draw(&mut scene, &runs[i].cfg, &camera)?;
                        let r = &mut runs[i];
                        r.row.vertex_invocations = f.stats.map(|s| s.vertex_shader_invocations);
                        r.gpu.push(f.gpu_ms);
                        r.wall.push(f.wall_ms);
                    }
                }
            }
            for r in runs.iter_mut().filter(|r| r.gpu.len() > frames) {
                r.row.note = format!("{} timed frames", r.gpu.len());
            }
            // Each variant's `static` of the same surface and displacement.
            let references: Vec<Option<(f64, f64)>> = runs
                .iter()
                .map(|r| {
                    runs.iter()
                        .find(|s| {
                            s.drawn
                                && s.cfg.driver.kind().refines_on_cpu()
                                && (s.cfg.surface, s.cfg.displace)
                                    == (r.cfg.surface, r.cfg.displace)
                        })
                        .map(|s| (Stat::of(&s.gpu).median, Stat::of(&s.wall).median))
                })
                .collect();
            for (
                Run {
                    mut row,
                    cfg,
                    drawn,
                    gpu,
                    wall,
                },
                reference,
            ) in runs.into_iter().zip(references)
            {
                let (surface, displace) = (cfg.surface, cfg.displace);
                if !drawn {
                    rows.push(row);
                    continue;
                }
                let (g, w) = (Stat::of(&gpu), Stat::of(&wall));
                if let Some((rg, rw)) = reference {
                    row.gpu_ratio = Some(g.median / rg);
                    row.wall_ratio = Some(w.median / rw);
                }
                let rate = row.refined_triangles as f64 / g.median.max(1e-9);
                if surface == Surface::Flat {
                    flat_rate.push((row.variant.clone(), displace, rate));
                }
                row.throughput_vs_flat = flat_rate
                    .iter()
                    .find(|(v, d, _)| *v == row.variant && *d == displace)
                    .map(|&(_, _, f)| rate / f);
                row.gpu_ms = Some(g);
                row.wall_ms = Some(w);
                log::info!(
                    "{} L{} {} + {} {}: gpu {:.2} ms wall {:.2} ms",
                    row.mesh,
                    level,
                    surface.name(),
                    displace.name(),
                    row.variant,
                    g.median,
                    w.median
                );
                rows.push(row);
            }
            // Free the static buffers of this level before the next one.
            scene.static_vbo = None;
        }
    }
    Ok(Report {
        device,
        // What was timed: at least one frame, whatever was asked.
        frames: opts.frames.max(1),
        width: opts.width,
        height: opts.height,
        rows,
    })
}

fn fmt_stat(s: &Option<Stat>) -> String {
    s.map(|s| format!("{:.2} ({:.2}–{:.2})", s.median, s.min, s.max))
        .unwrap_or_else(|| "–".into())
}

fn fmt_ratio(r: Option<f64>) -> String {
    r.map(|r| format!("{r:.2}")).unwrap_or_else(|| "–".into())
}

impl Report {
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "Device: {}. {}x{} offscreen, median (min–max) of {} timed frames (more where a note says so) after one warm-up frame, taken round the variants (of every surface together; with several surfaces each `static` alone first) in turn; ratios are against `static` at the same mesh and level, and throughput (refined triangles per GPU ms) against `flat` with the same variant, measured in the same run. Elements: the coarse triangles, or M1's faces for `loop`.\n",
            self.device, self.width, self.height, self.frames
        );
        let _ = writeln!(
            s,
            "| mesh | coarse tris | elements | level | surface | displace | variant | refined tris | GPU ms | wall ms | GPU ns / refined tri | GPU / static | wall / static | throughput / flat | M0→M1 ms | table bytes | stored vertices | stored indices | geometry bytes | VS invocations | note |"
        );
        let _ = writeln!(
            s,
            "|---|---:|---:|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
        );
        for r in &self.rows {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                r.mesh,
                r.coarse_triangles,
                r.elements,
                r.level,
                r.surface.name(),
                r.displace.name(),
                r.variant,
                r.refined_triangles,
                fmt_stat(&r.gpu_ms),
                fmt_stat(&r.wall_ms),
                r.ns_per_triangle()
                    .map(|v| format!("{v:.2}"))
                    .unwrap_or_else(|| "–".into()),
                fmt_ratio(r.gpu_ratio),
                fmt_ratio(r.wall_ratio),
                fmt_ratio(r.throughput_vs_flat),
                r.pre_pass_ms.map(|v| format!("{v:.3}")).unwrap_or_else(|| "–".into()),
                r.table_bytes.map(|v| v.to_string()).unwrap_or_else(|| "–".into()),
                r.stored_vertices,
                r.stored_indices,
                r.geometry_bytes,
                r.vertex_invocations.map(|v| v.to_string()).unwrap_or_else(|| "–".into()),
                r.note
            );
        }
        s
    }

    /// Write `prefix.md` (headed by the command that made it), `prefix.csv` and `prefix.json`.
    /// The folder must exist: outputs never create folders (the command line checks the prefix up front, `meshrefine::paths`).
    pub fn write_files(&self, prefix: &std::path::Path, command: &str) -> std::io::Result<()> {
        let with = |ext: &str| {
            let mut p = prefix.as_os_str().to_owned();
            p.push(ext);
            std::path::PathBuf::from(p)
        };
        std::fs::write(
            with(".md"),
            format!("Command: `{command}`\n\n{}", self.markdown()),
        )?;
        std::fs::write(with(".csv"), self.csv())?;
        std::fs::write(with(".json"), self.json())
    }

    pub fn csv(&self) -> String {
        let mut s = String::from(
            "device,mesh,coarse_triangles,elements,level,surface,displace,variant,refined_triangles,gpu_ms_median,gpu_ms_min,gpu_ms_max,wall_ms_median,wall_ms_min,wall_ms_max,gpu_ns_per_refined_triangle,gpu_ratio_vs_static,wall_ratio_vs_static,throughput_vs_flat,pre_pass_ms,table_bytes,stored_vertices,stored_indices,geometry_bytes,vertex_invocations,note\n",
        );
        let f = |x: Option<f64>| x.map(|v| format!("{v:.4}")).unwrap_or_default();
        for r in &self.rows {
            let _ = writeln!(
                s,
                "\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},\"{}\"",
                self.device,
                r.mesh,
                r.coarse_triangles,
                r.elements,
                r.level,
                r.surface.name(),
                r.displace.name(),
                r.variant,
                r.refined_triangles,
                f(r.gpu_ms.map(|s| s.median)),
                f(r.gpu_ms.map(|s| s.min)),
                f(r.gpu_ms.map(|s| s.max)),
                f(r.wall_ms.map(|s| s.median)),
                f(r.wall_ms.map(|s| s.min)),
                f(r.wall_ms.map(|s| s.max)),
                f(r.ns_per_triangle()),
                f(r.gpu_ratio),
                f(r.wall_ratio),
                f(r.throughput_vs_flat),
                f(r.pre_pass_ms),
                r.table_bytes.map(|v| v.to_string()).unwrap_or_default(),
                r.stored_vertices,
                r.stored_indices,
                r.geometry_bytes,
                r.vertex_invocations
                    .map(|v| v.to_string())
                    .unwrap_or_default(),
                r.note
            );
        }
        s
    }

    pub fn json(&self) -> String {
        let f = |x: Option<f64>| {
            x.map(|v| format!("{v:.4}"))
                .unwrap_or_else(|| "null".into())
        };
        let rows: Vec<String> = self
            .rows
            .iter()
            .map(|r| {
                format!(
                    "{{\"mesh\":\"{}\",\"coarse_triangles\":{},\"elements\":{},\"level\":{},\"surface\":\"{}\",\"displace\":\"{}\",\"variant\":\"{}\",\"refined_triangles\":{},\"gpu_ms_median\":{},\"wall_ms_median\":{},\"gpu_ns_per_refined_triangle\":{},\"gpu_ratio_vs_static\":{},\"wall_ratio_vs_static\":{},\"throughput_vs_flat\":{},\"pre_pass_ms\":{},\"table_bytes\":{},\"stored_vertices\":{},\"stored_indices\":{},\"geometry_bytes\":{},\"vertex_invocations\":{},\"note\":\"{}\"}}",
                    r.mesh, r.coarse_triangles, r.elements, r.level, r.surface.name(), r.displace.name(), r.variant, r.refined_triangles,
                    f(r.gpu_ms.map(|s| s.median)), f(r.wall_ms.map(|s| s.median)), f(r.ns_per_triangle()), f(r.gpu_ratio), f(r.wall_ratio),
                    f(r.throughput_vs_flat), f(r.pre_pass_ms), r.table_bytes.map(|v| v.to_string()).unwrap_or_else(|| "null".into()),
                    r.stored_vertices, r.stored_indices, r.geometry_bytes,
                    r.vertex_invocations.map(|v| v.to_string()).unwrap_or_else(|| "null".into()), r.note
                )
            })
            .collect();
        format!(
            "{{\"device\":\"{}\",\"frames\":{},\"width\":{},\"height\":{},\"rows\":[\n{}\n]}}\n",
            self.device.replace('"', "'"),
            self.frames,
            self.width,
            self.height,
            rows.join(",\n")
        )
    }
}

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

    /// Runs `opts` on `meshes` and prints the table; a full timed run also writes
    /// `docs/bench/<name>.{md,csv,json}`. The smoke run is a GPU test like the others: validation
    /// on, and any message or leak fails it; timed runs leave validation off (it slows command
    /// recording 7-10x). Device: the first Vulkan device (MESHREFINE_DEVICE picks one by name).
    pub fn run(&self, name: &str, meshes: &[Mesh], opts: &BenchOptions) {
        let desc = crate::gpu::ContextDesc {
            device_name: std::env::var("MESHREFINE_DEVICE").ok(),
            validate: !self.benching,
            ..Default::default()
        };
        let fail = |e: &dyn std::fmt::Display| -> ! {
            eprintln!("error: {e}");
            std::process::exit(1)
        };
        let report = crate::gpu::with_context(&desc, |ctx| {
            run(ctx, meshes, opts).map_err(Box::<dyn std::error::Error>::from)
        })
        .unwrap_or_else(|e| {
            if let Some(crate::gpu::ShutdownError::Validation(list)) = e.downcast_ref() {
                list.iter().for_each(|m| eprintln!("validation: {m}"));
            }
            fail(&e)
        });
        println!("{}", report.markdown());
        if self.benching && !self.quick {
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
            println!("wrote {}.{{md,csv,json}}", prefix.display());
        }
    }
}
