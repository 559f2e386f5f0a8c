//! `meshrefine info`: a mesh's statistics; with `--level`, what each driver would hold on the
//! GPU; with `--surface loop`, what Loop subdivision builds for it.
#![forbid(unsafe_code)]

use super::args::InfoArgs;
use super::choices::boundary_name;
use super::input::degenerate_warning;
use super::loop_check::loop_refusal;
use crate::note;
use anyhow::{bail, Result};
use meshrefine::mesh::{LoadReport, Mesh};
use meshrefine::render::Driver;
use meshrefine::surface::loop_::LoopData;
use std::io::Write as _;
use std::path::Path;

/// Runs `meshrefine info` with `a`.
pub fn run(a: &InfoArgs) -> Result<()> {
    let path = a.mesh.as_path();
    let (mesh, report) = Mesh::load_obj(path)?;
    let for_loop = a.surface.is_some_and(|s| s.facts().needs_every_face);
    if let Some(why) = loop_refusal(&path.display().to_string(), &mesh, &report, for_loop) {
        if for_loop {
            bail!("{why}");
        }
    }
    if let Some(w) = degenerate_warning(&path.display().to_string(), &report) {
        note(format_args!("{w}"));
    }
    print_stats(path, &mesh, &report)?;
    if let Some(level) = a.level {
        print_geometry(level, mesh.triangles.len() as u64)?;
    }
    if for_loop {
        print_loop(a, path, &mesh)?;
    }
    Ok(())
}

/// The mesh's statistics and what loading did.
fn print_stats(path: &Path, mesh: &Mesh, report: &LoadReport) -> Result<()> {
    let s = mesh.stats();
    out!("mesh: {}", path.display());
    out!("vertices: {}", s.vertices);
    out!("triangles: {}", s.triangles);
    out!("boundary edges: {}", s.boundary_edges);
    out!("non-manifold edges: {}", s.nonmanifold_edges);
    out!("non-manifold vertices: {}", s.nonmanifold_vertices);
    out!(
        "inconsistently oriented edges: {}",
        s.inconsistently_oriented_edges
    );
    out!(
        "degenerate faces dropped: {}",
        report.dropped_degenerate.len()
    );
    out!(
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
    out!("valence histogram (valence:vertices): {}", hist.join(" "));
    Ok(())
}

/// `--level`: the refined triangles of `triangles` coarse ones, and each driver's GPU geometry.
fn print_geometry(level: u32, triangles: u64) -> Result<()> {
    let t = triangles;
    out!(
        "level {level}: {} refined triangles ({} per coarse triangle)",
        t * meshrefine::pattern::triangle_count(level) as u64,
        meshrefine::pattern::triangle_count(level)
    );
    for d in Driver::ALL {
        out!(
            "  {:8} {:>14} bytes of GPU geometry",
            d.name(),
            d.geometry_bytes(level, t)
        );
    }
    Ok(())
}

/// `--surface loop`: M1, the valence configurations and the basis function tables built.
fn print_loop(a: &InfoArgs, path: &Path, mesh: &Mesh) -> Result<()> {
    let lattice = meshrefine::surface::loop_::Lattice::new(a.bft_level);
    let report = |p| note(format_args!("{}: {p}", path.display()));
    let data = LoopData::new(
        mesh,
        a.boundary,
        lattice,
        meshrefine::surface::loop_::throttled(report),
    )
    .map_err(|e| {
        anyhow::anyhow!(
            "'{}': the loop surface cannot subdivide it: {e}",
            path.display()
        )
    })?;
    out!(
        "loop: M1 has {} vertices and {} faces ({} boundaries)",
        data.m1.vertex_count,
        data.m1.faces.len(),
        boundary_name(a.boundary)
    );
    let configs: Vec<String> = data
        .valences()
        .iter()
        .map(|&(v, b, n)| format!("{v}{}:{n}", if b { "b" } else { "" }))
        .collect();
    out!(
        "configurations: {} in {} tables (valence:tables, b = on a boundary): {}",
        data.tables.keys.len(),
        data.tables.configs.len(),
        configs.join(" ")
    );
    let control = || data.tables.faces.iter().map(|f| f.control.len());
    out!(
        "control points per face: {} to {}",
        control().min().unwrap_or(0),
        control().max().unwrap_or(0)
    );
    out!(
        "table level: {} ({} segments per M1-face edge, {} lattice points)",
        lattice.lmax,
        lattice.segments(),
        lattice.rows()
    );
    out!("basis function tables: {} bytes", data.table_bytes());
    Ok(())
}
