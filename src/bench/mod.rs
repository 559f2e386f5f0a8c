//! Benchmarks shared by `cargo bench` (benches/fig7.rs) and `meshrefine bench`: every surface x
//! displacement x driver and submission mode on the same meshes and levels, in the same run, so the
//! ratios against `static` (same surface, displacement, mesh and level) compare like with like. Frame time from GPU timestamps and wall clock (submit to fence), median
//! and spread over timed frames after one warm-up frame (Mesa compiles shaders at the first draw);
//! the timed frames go round the variants in turn (static, push, ubo, instanced, tess, static, ...),
//! with several surfaces round every surface's variants together (each surface's `static` timed
//! alone before them: its buffer of refined vertices is one surface's), so a drift of the machine
//! touches every variant alike. Timings are measured, never asserted.
//!
//! Files: `options.rs` holds what a benchmark is asked for; this one the measured rows and [`run`], a short composition of
//! named phases (set up a mesh, list the variants, warm each up, time round them, turn the
//! samples into rows with their ratios); `report.rs` declares the table's columns once and
//! derives the markdown, CSV and JSON tables and the terminal summary from that list;
//! `harness.rs` is what the `cargo bench` targets call.
#![forbid(unsafe_code)]

mod adaptive;
mod columns;
mod harness;
mod options;
mod report;

pub use harness::Harness;
pub use options::{BenchAdaptive, BenchCamera, BenchOptions, Shot, ViewUsed, DRAWN_SPACE};
pub use report::{csv_fields, Align, Cell, Column, Report, COLUMNS, SUMMARY_WIDTH};

use crate::mesh::Mesh;
use crate::pattern::PatternSet;
use crate::render::{Camera, DrawConfig, Driver, Headless, RenderError, Scene};
use crate::surface::{BuildOptions, Displace, Surface, SurfaceParams};
use std::sync::Arc;

/// The surface every other's throughput is compared with (`throughput vs flat`): the cheapest,
/// linear interpolation.
pub const THROUGHPUT_REFERENCE: Surface = Surface::Flat;

/// What a row of an adaptive benchmark adds (its columns are empty on other rows).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AdaptiveCells {
    pub scene: String,
    pub pixel_error: f32,
    /// Each element drawn at its own levels (the row's level the largest allowed), or every
    /// element at the row's level.
    pub adaptive: bool,
    /// Where the row's levels come from: `view` (adaptive), and for a uniform row one or more
    /// of `levels` (asked for), `bound` (the smallest uniform level meeting the pixel error on
    /// every camera), `pow2` (the smallest power of two at or above it), joined by `+`.
    pub level_from: String,
    /// Milliseconds choosing the levels of one frame (median per camera, mean over cameras),
    /// and where they were chosen (`cpu`: `Scene::set_levels`' wall time, the levels' upload
    /// included when they change).
    pub level_pass_ms: Option<f64>,
    pub level_pass_on: Option<&'static str>,
    /// Elements culled (mean over cameras, rounded).
    pub culled_elements: Option<u64>,
    /// The static driver's adaptive rows: milliseconds refining on the CPU and uploading, and
    /// the bytes uploaded, per frame whose levels changed (every timed frame, as for a moving
    /// camera; median per camera, mean over cameras).
    pub cpu_ms: Option<f64>,
    pub upload_bytes: Option<u64>,
    /// Visible elements per drawn inner level, `L:n` ascending (summed over the cameras).
    pub histogram: String,
}

/// Median, min and max of a sample.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
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
    /// Adaptive benchmarks only ([`BenchOptions::adaptive`]).
    pub adaptive: Option<AdaptiveCells>,
    pub note: String,
}

impl Row {
    /// The refined triangles the row reports: none for an adaptive row that was not drawn
    /// (no levels were chosen); a uniform row's are its level's, drawn or not.
    pub fn shown_triangles(&self) -> Option<u64> {
        let adaptive = self.adaptive.as_ref().is_some_and(|a| a.adaptive);
        (!adaptive || self.gpu_ms.is_some()).then_some(self.refined_triangles)
    }

    /// Median GPU time per refined triangle, in nanoseconds: the per-triangle cost (none when
    /// no triangle was drawn: every element culled).
    pub fn ns_per_triangle(&self) -> Option<f64> {
        let triangles = self.refined_triangles;
        (self.gpu_ms)
            .filter(|_| triangles > 0)
            .map(|s| s.median * 1e6 / triangles as f64)
    }
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
    h.view = opts.view;
    let mut rows = Vec::new();
    let mut cameras = Vec::new();
    for mesh in meshes {
        if let Some(a) = &opts.adaptive {
            let (r, c) = adaptive::run(&ctx, &mut h, mesh, opts, a)?;
            rows.extend(r);
            cameras.extend(c);
            continue;
        }
        let mut m = MeshSetup::new(&mut h, mesh, opts)?;
        for &level in &opts.levels {
            // Every variant of every surface is warmed up, then the timed frames go round the
            // variants of every surface in turn, so a slow drift of the machine (this one moves
            // ±25 % from run to run) touches every variant alike and the ratios against `flat`
            // compare like with like (`static`, with several surfaces, aside: `time_round`).
            let mut runs = Vec::new();
            for cfg in variants(&m.surfaces, level, m.params, opts.build, &opts.drivers) {
                runs.push(warm_up(&ctx, &mut h, &mut m, cfg, opts)?);
            }
            time_round(&mut h, &mut m, &mut runs, opts)?;
            rows.extend(into_rows(runs));
            // Free the static buffers of this level before the next one.
            m.scene.static_vbo = None;
        }
        cameras.extend(m.views_used(&[]));
    }
    Ok(Report {
        device,
        // What was timed: at least one frame, whatever was asked.
        frames: opts.frames.max(1),
        width: opts.width,
        height: opts.height,
        view: opts.view,
        rows,
        cameras,
        camera_space: DRAWN_SPACE.into(),
    })
}

/// One mesh's scene, cameras, parameters, surfaces in the order measured, and Loop's pre-pass
/// cost.
struct MeshSetup {
    name: String,
    scene: Scene,
    /// The camera of each surface x displacement drawn so far ([`MeshSetup::camera`]).
    cameras: Vec<((Surface, Displace), Camera)>,
    coarse: u32,
    params: SurfaceParams,
    surfaces: Vec<(Surface, Displace)>,
    pre_pass_ms: Option<f64>,
}

impl MeshSetup {
    fn new(h: &mut Headless, mesh: &Mesh, opts: &BenchOptions) -> Result<Self, RenderError> {
        let mut scene: Scene = Scene::with_patterns(
            &h.ctx,
            &h.pool,
            &h.renderer,
            mesh.clone(),
            PatternSet::from_levels(&opts.levels),
        )?;
        // bench has no --level: its uniform rows are --levels' and, with --pixel-error, the
        // bound's own uniform levels.
        scene.uniform_advice =
            "lower --levels (and, with --pixel-error, --no-bound-levels or a larger --pixel-error) draw faster";
        if let Some(map) = &opts.heightmap {
            scene.set_heightmap(&h.ctx, &h.pool, &h.renderer, map.clone())?;
        }
        let (_, r) = scene.bounding_sphere();
        let coarse = scene.gpu.element_count;
        let params = opts.params.unwrap_or_else(|| SurfaceParams::for_radius(r));
        // The reference surface first (the throughput ratios are against it), then as asked.
        let mut surfaces = opts.surfaces.clone();
        surfaces.sort_by_key(|&(s, _)| s != THROUGHPUT_REFERENCE);
        // The cost of the passes a surface runs before drawing (Loop's M0 -> M1), timed alone
        // (median of the timed frames).
        let with_pre_pass = surfaces.iter().find(|(s, _)| s.uses_loop_faces());
        let pre_pass_ms = if let Some(&(surface, _)) = with_pre_pass {
            let mut cfg =
                DrawConfig::new(Driver::default(), opts.levels.first().copied().unwrap_or(1));
            cfg.surface = surface;
            cfg.params = params;
            cfg.build = opts.build;
            let mut times = Vec::new();
            for _ in 0..=opts.frames.max(1) {
                times.extend(h.time_pre_pass(&mut scene, &cfg)?);
            }
            Some(Stat::of(&times[1..]).median)
        } else {
            None
        };
        Ok(Self {
            name: mesh.name.clone(),
            scene,
            cameras: Vec::new(),
            coarse,
            params,
            surfaces,
            pre_pass_ms,
        })
    }
}

impl MeshSetup {
    /// The cameras its rows were drawn from, per surface x displacement in the order measured:
    /// `path` where given (every surface's), else each one's own.
    fn views_used(&self, path: &[Camera]) -> Vec<ViewUsed> {
        (self.surfaces.iter())
            .filter_map(|&(surface, displace)| {
                let own = (self.cameras.iter()).find(|(k, _)| *k == (surface, displace));
                let shots = match own {
                    _ if !path.is_empty() => path.iter().map(Shot::from).collect(),
                    Some((_, c)) => vec![Shot::from(c)],
                    None => return None,
                };
                Some(ViewUsed {
                    mesh: self.name.clone(),
                    surface,
                    displace,
                    shots,
                })
            })
            .collect()
    }

    /// The camera `cfg`'s frames are drawn from ([`BenchOptions::camera`]): fitted to its
    /// surface x displacement as drawn (the scene prepared for it: Loop's M1 faces exist), once
    /// per surface x displacement.
    fn camera(&mut self, cfg: &DrawConfig, opts: &BenchOptions) -> Result<Camera, RenderError> {
        let key = (cfg.surface, cfg.displace);
        if let Some(&(_, camera)) = self.cameras.iter().find(|(k, _)| *k == key) {
            return Ok(camera);
        }
        let camera = match opts.camera {
            BenchCamera::Fixed(camera) => camera,
            BenchCamera::Framing => {
                let (c, r) = self.scene.bounding_sphere();
                Camera::framing(c, r)
            }
            BenchCamera::Fitted(v) => {
                let aspect = opts.width as f32 / opts.height.max(1) as f32;
                let fitted = Camera::fit_with_fov(&self.scene.framing_points(cfg), aspect, v.fov_y);
                v.complete(fitted)
                    .ok_or_else(|| RenderError::NoViewDirection {
                        surface: match cfg.displace {
                            Displace::None => format!("the {} surface", cfg.surface.name()),
                            d => format!("the {} surface with {}", cfg.surface.name(), d.name()),
                        },
                        eye: v.eye.unwrap_or(fitted.eye()),
                        target: v.look_at.unwrap_or(fitted.target),
                    })?
            }
        };
        self.cameras.push((key, camera));
        Ok(camera)
    }
}

/// The variants measured at one level, in the order they are timed: every driver variant
/// asked for (all when `drivers` is empty) of every surface.
fn variants(
    surfaces: &[(Surface, Displace)],
    level: u32,
    params: SurfaceParams,
    build: BuildOptions,
    drivers: &[Driver],
) -> Vec<DrawConfig> {
    let mut list = Vec::new();
    for &(surface, displace) in surfaces {
        for driver in Driver::VARIANTS {
            let mut cfg = DrawConfig::new(driver, level).with_surface(surface, displace);
            cfg.params = params;
            cfg.build = build;
            if !drivers.is_empty() && !drivers.contains(&driver) {
                continue;
            }
            list.push(cfg);
        }
    }
    list
}

/// Prepares one variant, fills in what its row knows before timing (counts, bytes) and draws
/// its warm-up frame (shaders, static VBO); a level the device refuses is not drawn and its
/// row says why.
fn warm_up(
    ctx: &crate::gpu::Context,
    h: &mut Headless,
    m: &mut MeshSetup,
    cfg: DrawConfig,
    opts: &BenchOptions,
) -> Result<Run, RenderError> {
    let (mut row, refused) = new_row(ctx, h, m, &cfg)?;
    let drawn = refused.is_none();
    h.adaptive = false;
    if drawn {
        let camera = m.camera(&cfg, opts)?;
        h.draw(&mut m.scene, &cfg, &camera)?; // warm-up: shaders, static VBO
    } else if let Some(e) = refused {
        row.note = format!("not drawn: {e}");
    }
    Ok(Run {
        row,
        cfg,
        drawn,
        gpu: Vec::new(),
        wall: Vec::new(),
    })
}

/// A variant's row with what is known before timing (counts, bytes; the scene prepared for
/// `cfg`), and why the device refuses its level or cannot hold what it draws, if it does (then
/// nothing was prepared).
fn new_row(
    ctx: &crate::gpu::Context,
    h: &mut Headless,
    m: &mut MeshSetup,
    cfg: &DrawConfig,
) -> Result<(Row, Option<RenderError>), RenderError> {
    let (surface, displace, level) = (cfg.surface, cfg.displace, cfg.level);
    let scene = &mut m.scene;
    let mut refused = crate::render::driver::check_level(ctx, cfg).err();
    let prepared = match refused {
        None => match h.prepared_elements(scene, cfg, crate::render::Capture::None) {
            Ok(t) => Some(t),
            // What the device cannot hold (the static driver's mesh refined at a level): not
            // drawn, as a level it refuses, and the other rows are still timed.
            Err(e @ RenderError::OverLimit { .. }) => {
                refused = Some(e);
                None
            }
            Err(e) => return Err(e),
        },
        Some(_) => None,
    };
    // Not drawn: loop's M1 is there once another driver drew it.
    let t = prepared.unwrap_or_else(|| scene.elements(surface).element_count);
    let (kind, elements) = (cfg.driver.kind(), t as u64);
    let (stored_vertices, stored_indices) = match h.adaptive {
        true => kind.stored_adaptive(cfg.level, elements, cfg.dyadic_levels()),
        false => kind.stored(cfg.level, elements),
    };
    let geometry_bytes = scene.geometry_bytes(cfg, h.adaptive);
    let loop_scene = scene.loop_.as_ref().filter(|_| surface.uses_loop_faces());
    let row = Row {
        mesh: m.name.clone(),
        coarse_triangles: m.coarse,
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
        pre_pass_ms: loop_scene.and(m.pre_pass_ms),
        table_bytes: loop_scene.map(|l| l.data.table_bytes()),
        adaptive: None,
        note: String::new(),
    };
    Ok((row, refused))
}

/// Takes the timed frames round the drawn variants in turn until each has `frames` of them
/// and `min_total_ms` of GPU time (at most 20 × `frames`).
fn time_round(
    h: &mut Headless,
    m: &mut MeshSetup,
    runs: &mut [Run],
    opts: &BenchOptions,
) -> Result<(), RenderError> {
    let frames = opts.frames.max(1) as usize;
    let several = m.surfaces.len() > 1;
    let enough = |r: &Run| {
        r.gpu.len() >= frames
            && (r.gpu.iter().sum::<f64>() >= opts.min_total_ms || r.gpu.len() >= 20 * frames)
    };
    // `static` draws one buffer of refined vertices, rebuilt for another surface: with
    // several surfaces, each surface's `static` is timed alone (after a frame that builds
    // its buffer), then the other variants of every surface go round together.
    let drawn: Vec<usize> = (0..runs.len()).filter(|&i| runs[i].drawn).collect();
    let is_static = |i: &usize| runs[*i].cfg.driver.kind().refines_on_cpu();
    let groups: Vec<Vec<usize>> = if several {
        let (alone, together): (Vec<usize>, Vec<usize>) = drawn.iter().partition(|i| is_static(i));
        alone
            .into_iter()
            .map(|i| vec![i])
            .chain([together])
            .collect()
    } else {
        vec![drawn]
    };
    for group in groups {
        if several && group.len() == 1 {
            let camera = m.camera(&runs[group[0]].cfg, opts)?;
            h.draw(&mut m.scene, &runs[group[0]].cfg, &camera)?;
        }
        while !group.iter().all(|&i| enough(&runs[i])) {
            for &i in &group {
                let camera = m.camera(&runs[i].cfg, opts)?;
                let f = h.draw(&mut m.scene, &runs[i].cfg, &camera)?;
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
    Ok(())
}

/// Turns one level's timed variants into rows: medians and spreads, the ratios against the
/// `static` of the same surface and displacement, and throughput against `flat` with the same
/// variant and displacement (`flat`'s rows come first).
fn into_rows(runs: Vec<Run>) -> Vec<Row> {
    // Each variant's `static` of the same surface and displacement.
    let references: Vec<Option<(f64, f64)>> = runs
        .iter()
        .map(|r| {
            runs.iter()
                .find(|s| {
                    s.drawn
                        && s.cfg.driver.kind().refines_on_cpu()
                        && (s.cfg.surface, s.cfg.displace) == (r.cfg.surface, r.cfg.displace)
                })
                .map(|s| (Stat::of(&s.gpu).median, Stat::of(&s.wall).median))
        })
        .collect();
    // Refined triangles per GPU ms of `flat` by variant and displacement.
    let mut flat_rate: Vec<(String, Displace, f64)> = Vec::new();
    let mut rows = Vec::with_capacity(runs.len());
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
        if surface == THROUGHPUT_REFERENCE {
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
            row.level,
            surface.name(),
            displace.name(),
            row.variant,
            g.median,
            w.median
        );
        rows.push(row);
    }
    rows
}
