//! `export` keeps texture coordinates: where the input has them, every refined vertex gets the
//! coordinates its surface interpolates there (the corners' coordinates, linearly by the
//! sample's barycentric weights; computed on the CPU from the captured element and sample), and
//! faces index them (`f v/vt/vn`). Positions still weld on their bits alone: a seam of the
//! input's texture coordinates gives its vertices two `vt` each, one `v`, no crack; without a
//! seam, one `vt` per vertex. Input without texture coordinates exports as before: no `vt`,
//! faces `f v//vn`.

mod common;

use common::model_path;
use meshrefine::mesh::Mesh;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Tolerance on an exported texture coordinate against the expected interpolation: the
/// interpolation in f32 and the shortest decimal printing.
const UV_TOLERANCE: f32 = 1e-6;

fn tmp(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("export-texcoords");
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// Runs `meshrefine export` (validation layer on) and returns the OBJ text.
fn export(mesh: &Path, name: &str, extra: &[&str]) -> (String, String) {
    let obj = tmp(name);
    let _guard = common::gpu_lock();
    let out = Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .env("MESHREFINE_VALIDATE", "1")
        .args([
            "export",
            mesh.to_str().unwrap(),
            "-o",
            obj.to_str().unwrap(),
        ])
        .args(extra)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{extra:?}: {stderr}");
    (std::fs::read_to_string(&obj).unwrap(), stderr)
}

fn load(text: &str, name: &str) -> Mesh {
    let path = tmp(name);
    std::fs::write(&path, text).unwrap();
    Mesh::load_obj(&path).unwrap().0
}

/// Every face corner's texture coordinates, against `expected` of its position.
fn check_corners(mesh: &Mesh, what: &str, expected: impl Fn(glam::Vec3) -> glam::Vec2) {
    for tri in &mesh.triangles {
        let t = tri.t.unwrap_or_else(|| panic!("{what}: a face without vt"));
        for (&pi, &ti) in tri.p.iter().zip(&t) {
            let p = mesh.positions[pi as usize];
            let uv = mesh.texcoords[ti as usize];
            let want = expected(p);
            assert!(
                (uv - want).abs().max_element() <= UV_TOLERANCE,
                "{what}: vertex {p} has vt {uv}, expected {want}"
            );
        }
    }
}

#[test]
fn exports_carry_the_interpolated_texture_coordinates() {
    // grid_uv_8x8: vt = ((x + 1) / 2, (y + 1) / 2) at every vertex of the file, so on the flat
    // surface (positions linear in the sample, as the coordinates) at every refined vertex.
    let grid = model_path("grid_uv_8x8.obj");
    let on_grid = |p: glam::Vec3| glam::Vec2::new((p.x + 1.0) * 0.5, (p.y + 1.0) * 0.5);
    for (name, extra) in [
        ("grid-flat-4.obj", vec!["--surface", "flat", "--level", "4"]),
        (
            "grid-flat-adaptive.obj",
            vec![
                "--surface",
                "flat",
                "--pixel-error",
                "1",
                "--max-level",
                "8",
            ],
        ),
    ] {
        let (text, _) = export(&grid, name, &extra);
        let vt = text.lines().filter(|l| l.starts_with("vt ")).count();
        let v = text.lines().filter(|l| l.starts_with("v ")).count();
        assert!(
            text.lines()
                .nth(2)
                .unwrap()
                .ends_with(&format!(", {vt} texture coordinates")),
            "{name}: {}",
            text.lines().nth(2).unwrap()
        );
        // No seam in the grid's coordinates: one vt per vertex.
        assert_eq!(vt, v, "{name}");
        let mesh = load(&text, name);
        assert_eq!(mesh.texcoords.len(), v, "{name}");
        check_corners(&mesh, name, on_grid);
    }
    // A curved surface: the same coordinates at the same samples (pn moves the points, not the
    // sample), so each vertex's vt is where the flat export put the same vertex's (x, y).
    let (flat, _) = export(
        &grid,
        "grid-flat-2.obj",
        &["--surface", "flat", "--level", "2"],
    );
    let (pn, _) = export(&grid, "grid-pn-2.obj", &["--surface", "pn", "--level", "2"]);
    let (flat, pn) = (load(&flat, "f.obj"), load(&pn, "p.obj"));
    assert_eq!(flat.triangles.len(), pn.triangles.len());
    for (a, b) in flat.triangles.iter().zip(&pn.triangles) {
        for k in 0..3 {
            let want = on_grid(flat.positions[a.p[k] as usize]);
            let got = pn.texcoords[b.t.unwrap()[k] as usize];
            assert!(
                (got - want).abs().max_element() <= UV_TOLERANCE,
                "pn: {got} against {want}"
            );
        }
    }
}

/// A square of two triangles whose diagonal is (`seam`) or is not a seam of the texture
/// coordinates: the second triangle's coordinates are the first's moved by 2 in u.
fn square(seam: bool) -> String {
    let shift = if seam { 2.0 } else { 0.0 };
    format!(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
         vt 0 0\nvt 1 0\nvt 1 1\nvt {shift} 0\nvt {} 1\nvt {shift} 1\n\
         f 1/1 2/2 3/3\nf 1/4 3/5 4/6\n",
        1.0 + shift
    )
}

#[test]
fn a_texture_seam_doubles_vt_but_not_v() {
    for seam in [false, true] {
        let input = tmp(&format!("square-seam-{seam}.obj"));
        std::fs::write(&input, square(seam)).unwrap();
        let name = format!("square-seam-{seam}-out.obj");
        let (text, _) = export(&input, &name, &["--surface", "flat", "--level", "4"]);
        let mesh = load(&text, &name);
        // Level 4: 15 vertices per triangle, 5 on the shared diagonal.
        assert_eq!(mesh.positions.len(), 25, "seam {seam}");
        assert_eq!(
            mesh.texcoords.len(),
            if seam { 30 } else { 25 },
            "seam {seam}"
        );
        // Welded across the diagonal: only the square's outline is open.
        assert_eq!(mesh.stats().boundary_edges, 16, "seam {seam}");
        // Each triangle's corners carry its own interpolation: (x, y), moved by 2 in u on the
        // second triangle (y > x) when there is a seam.
        for tri in &mesh.triangles {
            let c = tri.p.map(|i| mesh.positions[i as usize]);
            let second = c.iter().any(|p| p.y > p.x + 1e-6);
            let shift = if seam && second { 2.0 } else { 0.0 };
            for (p, &ti) in c.iter().zip(&tri.t.unwrap()) {
                let uv = mesh.texcoords[ti as usize];
                let want = glam::Vec2::new(p.x + shift, p.y);
                assert!(
                    (uv - want).abs().max_element() <= UV_TOLERANCE,
                    "seam {seam}: {p} has vt {uv}, expected {want}"
                );
            }
        }
    }
}

#[test]
fn exports_without_texture_coordinates_are_unchanged() {
    // No vt in, no vt out: the same lines as ever (v, vn, f v//vn after the header).
    let tet = model_path("tetrahedron.obj");
    let (text, _) = export(&tet, "tet.obj", &["--level", "2"]);
    assert!(text.lines().nth(2).unwrap().ends_with(" triangles"));
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let ok = line.starts_with("v ")
            || line.starts_with("vn ")
            || (line.starts_with("f ")
                && line[2..].split(' ').all(|c| {
                    let (a, b) = c.split_once("//").unwrap();
                    a.parse::<u32>().is_ok() && b.parse::<u32>().is_ok()
                }));
        assert!(ok, "{line}");
    }
    // With texture coordinates, the tess driver (whose triangles are read back without their
    // samples) and loop (whose elements carry none) write none and say so.
    let grid = model_path("grid_uv_8x8.obj");
    for (name, extra) in [
        ("grid-tess.obj", vec!["--driver", "tess", "--level", "2"]),
        ("grid-loop.obj", vec!["--surface", "loop", "--level", "2"]),
    ] {
        let (text, stderr) = export(&grid, name, &extra);
        assert!(!text.contains("\nvt "), "{name}");
        assert!(
            stderr.contains("warning: 'grid_uv_8x8' has texture coordinates, but")
                && stderr.contains("writes none (vt)"),
            "{name}: {stderr}"
        );
    }
}
