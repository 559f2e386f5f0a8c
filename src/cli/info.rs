//! `meshrefine info`: a mesh's statistics; with `--level`, what each driver would hold on the
//! GPU; with `--surface loop`, what Loop subdivision builds for it.
#![forbid(unsafe_code)]

use super::adaptive::{check_distance, check_view, Frame};
use super::args::InfoArgs;
use super::choices::boundary_name;
use super::input::{attach_surface_inputs, load_warnings, read_surface_files, Input};
use super::loop_check::loop_refusal;
use crate::note;
use anyhow::{bail, Result};
use meshrefine::gpu::ContextDesc;
use meshrefine::mesh::{LoadReport, Mesh};
use meshrefine::render::driver::LEAST_LEVEL_LIMIT;
use meshrefine::render::Driver;
use meshrefine::surface::loop_::LoopData;
use std::io::Write as _;

/// A line of `info`'s report, held until the whole report is made.
macro_rules! put {
    ($o:expr, $($arg:tt)*) => {
        $o.push(format!($($arg)*))
    };
}

/// Runs `meshrefine info` with `a`. The report is printed whole once every value is checked
/// and its levels chosen, so that a refusal found late (a camera at its own target, a
/// `--max-level` past the pattern driver's integer patterns) prints its one sentence alone.
pub fn run(a: &InfoArgs, desc: &ContextDesc) -> Result<()> {
    let mut lines = Vec::new();
    report(&mut lines, a, desc)?;
    for line in lines {
        out!("{line}");
    }
    Ok(())
}

fn report(o: &mut Vec<String>, a: &InfoArgs, desc: &ContextDesc) -> Result<()> {
    // A --device that names no device is refused before anything is printed, as render
    // refuses it, whether or not these options read a device's limits.
    if desc.device_name.is_some() {
        meshrefine::gpu::picked_device(desc)?;
    }
    check_level_options(a, desc)?;
    a.drawn.params.build().map_err(anyhow::Error::msg)?;
    let (mesh, report, shown) = match &a.mesh {
        Some(path) => {
            let (mesh, report) = Mesh::load_obj(path)?;
            (mesh, report, path.display().to_string())
        }
        None => (
            meshrefine::mesh::default_mesh(),
            LoadReport::default(),
            "the default mesh (spot)".to_string(),
        ),
    };
    let path: &str = &shown;
    let for_loop = a.surface.is_some_and(|s| s.facts().needs_every_face);
    if let Some(why) = loop_refusal(path, &mesh, &report, for_loop) {
        if for_loop {
            bail!("{why}");
        }
    }
    if a.pixel_error.is_some() {
        // The camera is refused before anything is printed, as its other errors are (its
        // distance needs the mesh's bounding box, the frame its levels are chosen in).
        let (centre, scale) = mesh.viewing_transform();
        check_distance(&a.camera.viewpoint, &Frame { centre, scale })?;
    }
    for w in load_warnings(path, &report) {
        note(format_args!("{w}"));
    }
    let mut input = Input {
        mesh,
        shown: shown.clone(),
        heightmap: None,
        tags: None,
        loop_refusal: None,
        report,
    };
    if a.pixel_error.is_some() {
        // The files the levels read and the parameters are refused before anything is
        // printed, as render refuses them before drawing.
        let so = a.surface_opts();
        let texcoords = input.mesh.triangles.iter().all(|t| t.t.is_some());
        if let Some(why) =
            (so.surface).incompatibility_on(so.drawn.displace, &input.mesh, texcoords)
        {
            bail!("'{path}': {why}");
        }
        read_surface_files(&mut input, &so, false)?;
        (so.drawn.params)
            .params_for(&input.mesh, &[so.drawn.displace])
            .map_err(anyhow::Error::msg)?;
    }
    let (mesh, report) = (&input.mesh, &input.report);
    print_stats(o, path, mesh, report)?;
    // Loop's data, built once: --level counts its GPU bytes, and with --pixel-error the levels
    // use it on the mesh as drawn (the same topology, so the same tables) and print Loop's
    // lines after theirs.
    let loop_ = for_loop.then(|| loop_data(a, path, mesh)).transpose()?;
    if let Some(level) = a.level {
        // Loop's drivers draw the faces of one Loop step, four to a coarse triangle.
        let elements = mesh.triangles.len() as u64 * if for_loop { 4 } else { 1 };
        print_geometry(o, level, elements, loop_.as_ref(), desc)?;
    }
    if let (Some(data), None) = (&loop_, &a.pixel_error) {
        print_loop(o, a, data)?;
    }
    print_levels(o, a, input, loop_)?;
    Ok(())
}

/// The mesh's statistics and what loading did.
fn print_stats(o: &mut Vec<String>, path: &str, mesh: &Mesh, report: &LoadReport) -> Result<()> {
    let s = mesh.stats();
    put!(o, "mesh: {}", crate::printable(path));
    put!(o, "vertices: {}", s.vertices);
    put!(o, "triangles: {}", s.triangles);
    put!(o, "boundary edges: {}", s.boundary_edges);
    put!(o, "non-manifold edges: {}", s.nonmanifold_edges);
    put!(o, "non-manifold vertices: {}", s.nonmanifold_vertices);
    put!(
        o,
        "inconsistently oriented edges: {}",
        s.inconsistently_oriented_edges
    );
    put!(
        o,
        "degenerate faces dropped: {}",
        report.dropped_degenerate.len()
    );
    put!(
        o,
        "normals: {}",
        if report.normals_computed {
            "computed (area-weighted)"
        } else {
            "from file"
        }
    );
    let hist: Vec<String> = s
        .valence_histogram
        .iter()
        .map(|(v, n)| format!("{v}:{n}"))
        .collect();
    put!(
        o,
        "valence histogram (valence:vertices): {}",
        hist.join(" ")
    );
    Ok(())
}

/// `--level`: the refined triangles of `elements` (the coarse triangles, or M1's faces for
/// `loop`), and each driver's GPU geometry (for `loop` on the GPU drivers, with M1, its passes'
/// data and the tables, as `bench` counts them); past [`LEAST_LEVEL_LIMIT`], where the device render
/// would draw on (its limits read, nothing opened) refuses the level to a driver, a note under
/// its line says so in render's sentence.
fn print_geometry(
    o: &mut Vec<String>,
    level: u32,
    elements: u64,
    loop_: Option<&LoopData>,
    desc: &ContextDesc,
) -> Result<()> {
    let t = elements;
    let element = if loop_.is_some() {
        "M1 face: the elements are one Loop step's faces"
    } else {
        "coarse triangle"
    };
    put!(
        o,
        "level {level}: {} refined triangles ({} per {element})",
        t * meshrefine::pattern::triangle_count(level) as u64,
        meshrefine::pattern::triangle_count(level)
    );
    // No device to ask (no Vulkan driver): the figures stand alone. Asked where some device
    // may refuse: a level past the least tessellation limit, or a static vertex buffer past
    // the least maxMemoryAllocationSize (1 GiB, or less as `desc` has the device seen).
    let static_bytes = t * meshrefine::pattern::vertex_count(level) as u64 * 24;
    let least_allocation = desc
        .max_memory_allocation_size
        .unwrap_or(u64::MAX)
        .min(1 << 30);
    // A --device that names none is refused, as render refuses it.
    let device = match level > LEAST_LEVEL_LIMIT || static_bytes > least_allocation {
        false => None,
        true => match meshrefine::gpu::picked_device(desc) {
            Ok(d) => Some(d),
            Err(e @ meshrefine::gpu::GpuError::DeviceNotFound { .. }) => return Err(e.into()),
            Err(_) => None,
        },
    };
    for d in Driver::ALL {
        // The tessellator's rings make more triangles than the level's lattice (about 1.5 N²).
        let own = d.refined_per_element(level);
        let made = if own == meshrefine::pattern::triangle_count(level) {
            String::new()
        } else {
            format!(", {} refined triangles ({own} per element)", t * own as u64)
        };
        let pass = match loop_ {
            Some(data) if !d.kind().refines_on_cpu() => {
                meshrefine::render::loop_gpu::LoopPass::gpu_bytes_of(data)
            }
            _ => 0,
        };
        put!(
            o,
            "  {:8} {:>14} bytes of GPU geometry{made}",
            d.name(),
            d.geometry_bytes(level, t) + pass
        );
        if let Some(device) = &device {
            let cfg = meshrefine::render::DrawConfig::new(d, level);
            let refused = meshrefine::render::driver::check_level_on(device, &cfg).err();
            let refused = refused.or_else(|| match d {
                Driver::Static => {
                    meshrefine::render::static_vbo::check_uniform_size_on(device, t, level).err()
                }
                _ => None,
            });
            if let Some(e) = refused {
                put!(o, "    note: {e}");
            }
        }
    }
    Ok(())
}

/// Loop's data for `mesh` (M1, the valence configurations, the basis function tables), with
/// progress on long builds.
fn loop_data(a: &InfoArgs, path: &str, mesh: &Mesh) -> Result<LoopData> {
    let lattice = meshrefine::surface::loop_::Lattice::new(a.drawn.params.bft_level);
    LoopData::new(
        mesh,
        a.drawn.params.boundary,
        lattice,
        meshrefine::surface::loop_::progress_line(path),
    )
    .map_err(|e| anyhow::anyhow!("'{}': the loop surface cannot subdivide it: {e}", path))
}

/// `--surface loop`: M1, the valence configurations and the basis function tables built.
fn print_loop(o: &mut Vec<String>, a: &InfoArgs, data: &LoopData) -> Result<()> {
    let lattice = meshrefine::surface::loop_::Lattice::new(a.drawn.params.bft_level);
    put!(
        o,
        "loop: M1 has {} vertices and {} faces ({} boundaries)",
        data.m1.vertex_count,
        data.m1.faces.len(),
        boundary_name(a.drawn.params.boundary)
    );
    let configs: Vec<String> = data
        .valences()
        .iter()
        .map(|&(v, b, n)| format!("{v}{}:{n}", if b { "b" } else { "" }))
        .collect();
    put!(
        o,
        "configurations: {} in {} tables (valence:tables, b = on a boundary): {}",
        data.tables.keys.len(),
        data.tables.configs.len(),
        configs.join(" ")
    );
    let control = || data.faces.iter().map(|f| f[1] & 0xffff);
    put!(
        o,
        "control points per face: {} to {}",
        control().min().unwrap_or(0),
        control().max().unwrap_or(0)
    );
    put!(
        o,
        "table level: {} ({} segments per M1-face edge, {} lattice points)",
        lattice.lmax,
        lattice.segments(),
        lattice.rows()
    );
    put!(o, "basis function tables: {} bytes", data.table_bytes());
    Ok(())
}

/// `--pixel-error` and the camera: one sentence for the first bad value, before any work.
/// A `--max-level` above [`LEAST_LEVEL_LIMIT`] for the tess driver (the only one with a
/// device level limit) is checked against the device render would draw on (its limits read,
/// nothing opened), as render refuses it; otherwise no device is needed (a largest level the
/// driver cannot take was refused with the other values, `adaptive::check_values`).
fn check_level_options(a: &InfoArgs, desc: &ContextDesc) -> Result<()> {
    let Some(px) = &a.pixel_error else {
        return Ok(());
    };
    check_view(px, &a.camera.viewpoint, a.level.is_some())?;
    if a.max_level > LEAST_LEVEL_LIMIT && matches!(a.driver, meshrefine::render::Driver::Tess) {
        let device = meshrefine::gpu::picked_device(desc)?;
        return super::adaptive::check_max_level(&device, a.max_level, a.driver);
    }
    Ok(())
}

/// With `--pixel-error`: the level each element is drawn at for the camera by `--driver` (the
/// level pass's levels, transition triangles included, rounded as the driver rounds them), and
/// the triangles against the smallest uniform level that meets the same bound. Everything is
/// as render has it with the same options: the surface as drawn (centred, at unit size, its
/// displacement, inputs and parameters), its default camera fitted to that surface, culling.
fn print_levels(
    o: &mut Vec<String>,
    a: &InfoArgs,
    mut input: Input,
    loop_: Option<LoopData>,
) -> Result<()> {
    use meshrefine::lod::cull::eye_outside;
    use meshrefine::lod::frame::{
        culled_facing_away, frame_levels, lod_records, uniform_level, unmet, LevelStats, LodView,
    };
    use meshrefine::lod::{Frustum, Lod, View};
    use meshrefine::render::{framing_points, MeshData};
    use meshrefine::surface::{stpn, Heightmap, Mirror, RecordKind, Sources};
    let Some(px) = a.pixel_error.as_ref().map(|p| p.value) else {
        return Ok(());
    };
    let c = &a.camera;
    let so = a.surface_opts();
    let (surface, displace) = (so.surface, so.drawn.displace);
    // The height map and tags render reads (stpn's triangles with three crease corners split).
    attach_surface_inputs(&mut input, &so, false)?;
    let path = input.shown.as_str();
    let params = (so.drawn.params)
        .params_for(&input.mesh, &[displace])
        .map_err(anyhow::Error::msg)?;
    let build = so.drawn.params.build().map_err(anyhow::Error::msg)?;
    // In the drawn frame (centred, unit radius), as render chooses its levels: single-precision
    // view maths far from the origin loses the mesh.
    let (centre, scale) = input.mesh.viewing_transform();
    let frame = Frame { centre, scale };
    let params = params.in_drawn_frame(centre, scale);
    let data = MeshData::new(input.mesh.for_viewing(), RecordKind::Corners, build.seams);
    // (A surface and displacement that cannot go together were refused before printing.)
    let mesh = &data.mesh;
    let tags = input.tags.take().unwrap_or_else(|| stpn::derive(mesh).0);
    if surface.facts().tags {
        stpn::check(mesh, &tags).map_err(anyhow::Error::msg)?;
    }
    let heightmap = input.heightmap.take().unwrap_or_else(Heightmap::generated);
    // Rounded as the driver draws them: powers of two for pattern and tess while they glide,
    // integers otherwise and for static.
    let rounding = meshrefine::render::DrawConfig {
        geomorph: a.geomorph.unwrap_or(true),
        ..meshrefine::render::DrawConfig::new(a.driver, a.max_level)
    }
    .rounding();
    let dyadic = rounding.dyadic();
    let loop_data = if surface.uses_loop_faces() {
        let data = match loop_ {
            Some(data) => data,
            None => loop_data(a, path, mesh)?,
        };
        print_loop(o, a, &data)?;
        let frame = data.frame(&mesh.positions);
        Some((data, frame))
    } else {
        None
    };
    let sources = Sources {
        uvs: data.uvs.as_deref(),
        heightmap: Some(&heightmap),
        // The height map's level at the largest level, as the scene reads it.
        lod: heightmap.lod_for(data.uv_extent, a.max_level),
        tags: Some(&tags),
        loop_: loop_data.as_ref().map(|(d, f)| (d, f)),
    };
    let mirror = Mirror::new(surface, displace, &build, &sources).map_err(anyhow::Error::msg)?;
    let records = match &loop_data {
        Some((d, _)) => &d.records[..],
        None => &data.records[..],
    };
    // Render's default camera: fitted to the surface as drawn, moved where the options ask.
    let aspect = c.width as f32 / c.height as f32;
    let framing = framing_points(&mirror, &params, records, &mesh.positions);
    let v = &c.viewpoint;
    let camera = v.camera(&framing, aspect, &frame)?;
    let (eye, fov) = (camera.eye(), camera.fov_y);
    let view = View::new(eye, fov, c.height, px, a.max_level);
    let frustum = Frustum::from_view_proj(camera.view_proj(aspect));
    // As render culls (`Scene::front_only`): outside the view, and facing away only where the
    // surface shows no face turned away (`DrawConfig::may_show_back_faces`) on a mesh wound
    // outwards, seen from outside.
    let cull = a.cull.unwrap_or(true);
    let bounds = lod_records(&Lod::new(&mirror, &params).drawn_as(rounding), records);
    let drawn = meshrefine::render::DrawConfig {
        params,
        build,
        ..meshrefine::render::DrawConfig::new(a.driver, a.max_level).with_surface(surface, displace)
    };
    let shows_back = drawn.may_show_back_faces(|| mesh.self_intersects());
    let back_faces =
        cull && !shows_back && mesh.closed_outward() && eye_outside(eye, &bounds, mesh);
    let lod_view = LodView::new(
        &view,
        cull.then_some(&frustum),
        back_faces,
        rounding,
        bounds.len() as u32,
    )
    .with_lattice_bounds(surface.uses_loop_faces());
    let levels = frame_levels(&lod_view, &bounds);
    let stats = LevelStats::new(&levels, dyadic, a.max_level);
    // The elements whose bound --max-level keeps from being met.
    let unmet = unmet(&lod_view, &bounds, &levels);
    let report = meshrefine::lod::LevelReport {
        uniform_level: uniform_level(&lod_view, &bounds, &levels),
        histogram: stats.histogram,
        culled: stats.culled,
        facing_away: culled_facing_away(&lod_view, &bounds, &levels),
        unmet,
    };
    // Render draws up to the largest level chosen where that draws the same (not the height
    // map, whose mip level follows the largest level), and refuses the pattern driver's integer
    // levels past its integer patterns, naming --max-level: refused here in the same sentence.
    if let (meshrefine::render::Driver::Pattern(_), Some(&top)) =
        (a.driver, report.histogram.keys().max())
    {
        use meshrefine::render::pattern::check_integer_levels;
        let cfg = meshrefine::render::DrawConfig {
            geomorph: a.geomorph.unwrap_or(true),
            ..meshrefine::render::DrawConfig::new(a.driver, a.max_level)
        }
        .with_surface(surface, displace);
        let drawn = cfg.lowered_to(top).map_or(cfg.level, |c| c.level);
        if check_integer_levels(drawn, dyadic).is_err() {
            check_integer_levels(a.max_level, dyadic)
                .map_err(|e| anyhow::anyhow!("--max-level {}: {e}", a.max_level))?;
        }
    }
    // As given, or where the framing camera is, in the mesh's coordinates.
    // Written as export's camera line writes them.
    let [ex, ey, ez] = v
        .eye()
        .unwrap_or(frame.mesh(eye).to_array())
        .map(super::adaptive::px);
    let [tx, ty, tz] =
        (v.look_at().unwrap_or(frame.mesh(camera.target).to_array())).map(super::adaptive::px);
    put!(o,
        "adaptive {} at {} px: {}x{}, fov-y {}°, eye {ex} {ey} {ez}, look-at {tx} {ty} {tz}, max level {}, driver {}",
        match displace {
            meshrefine::surface::Displace::None => surface.name().to_string(),
            d => format!("{} + {}", surface.name(), d.name()),
        },
        super::adaptive::px(px),
        c.width,
        c.height,
        v.fov.value,
        a.max_level,
        a.driver.name()
    );
    put!(
        o,
        "  levels (level:{}): {}",
        surface.facts().elements.label(),
        if report.histogram.is_empty() {
            "none (every element culled)".to_string()
        } else {
            report.histogram_line()
        }
    );
    put!(
        o,
        "  culled (outside the view or facing away): {}",
        report.culled
    );
    let u = &report.unmet;
    if u.near > 0 {
        put!(o,
            "  near: {} element(s) hold the eye in their bounds: drawn at --max-level {} whatever the pixel error, no pixel error is promised on them",
            u.near,
            a.max_level
        );
    }
    if u.unbounded > 0 {
        put!(o,
            "  unbounded: {} element(s) have no finite error bound (see docs/adaptivity.md): drawn at --max-level {} whatever the pixel error, no pixel error is promised on them",
            u.unbounded,
            a.max_level
        );
    }
    if u.capped > 0 {
        // Some may need it only for their transitions to coarser neighbours, or for gliding
        // (a polynomial patch's bound at the level it blends from), which a uniform frame
        // does neither of.
        let uniform = match u.beyond_uniform {
            b if b == u.capped => ", nor by any uniform level up to it".to_string(),
            0 => format!(" as drawn (for their transitions to coarser neighbours or for gliding: uniform level {} meets it on them)", a.max_level),
            b => format!(" as drawn, nor on {b} of them by any uniform level up to it (the others need it for their transitions to coarser neighbours or for gliding)"),
        };
        put!(o,
            "  capped: {} element(s) need a level above --max-level {}: the bound is not met on them{uniform}",
            u.capped,
            a.max_level
        );
    }
    if report.histogram.is_empty() {
        put!(o, "  refined triangles: none drawn");
        return Ok(());
    }
    // As the driver draws them (the tessellator makes about 1.5 N² at level N).
    let (adaptive, uniform) = report.triangles_on(|l| a.driver.refined_per_element(l));
    // Where the bound is not met on some elements (above --max-level, or met by no level),
    // the uniform level is the cap, which does not meet it either.
    let capped = if u.uniform_unmet() {
        "; the largest level, which does not meet the bound either"
    } else {
        ""
    };
    put!(o,
        "  refined triangles: {adaptive} adaptive against {uniform} at uniform level {} ({:.2}x{capped})",
        report.uniform_level,
        adaptive as f64 / uniform.max(1) as f64
    );
    Ok(())
}
