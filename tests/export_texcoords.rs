//! `export` keeps texture coordinates: where the input has them, every refined vertex gets the
//! coordinates its surface interpolates there (the corners' coordinates, linearly by the
//! sample's barycentric weights; computed on the CPU from the captured element and sample, on
//! both GPU drivers), and faces index them (`f v/vt/vn`). Positions still weld on their bits
//! alone: a seam of the input's texture coordinates gives its vertices two `vt` each, one `v`,
//! no crack; without a seam, one `vt` per vertex. Input without texture coordinates exports as
//! before: no `vt`, faces `f v//vn`.

mod common;

use common::model_path;
use meshrefine::mesh::Mesh;
use std::collections::{BTreeSet, HashMap};
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
        (
            "grid-flat-tess-8.obj",
            vec!["--surface", "flat", "--driver", "tess", "--level", "8"],
        ),
        (
            "grid-flat-tess-adaptive.obj",
            vec![
                "--surface",
                "flat",
                "--driver",
                "tess",
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

/// Every position of an export, as its text, with the texture coordinates its face corners
/// give it, as their text.
fn vt_by_position(text: &str) -> HashMap<String, BTreeSet<String>> {
    let (mut v, mut vt, mut out) = (vec![], vec![], HashMap::new());
    for line in text.lines() {
        if let Some(p) = line.strip_prefix("v ") {
            v.push(p.to_string());
        } else if let Some(t) = line.strip_prefix("vt ") {
            vt.push(t.to_string());
        } else if let Some(f) = line.strip_prefix("f ") {
            for corner in f.split(' ') {
                let ids: Vec<usize> = corner.split('/').map(|i| i.parse().unwrap()).collect();
                let set: &mut BTreeSet<String> = out.entry(v[ids[0] - 1].clone()).or_default();
                set.insert(vt[ids[1] - 1].clone());
            }
        }
    }
    out
}

/// The tess driver's export writes the texture coordinates the pattern driver's writes for the
/// same sample: at level 8 both sample every coarse edge on the same lattice (the tessellator's
/// edge samples are snapped onto it), so every vertex on a coarse edge is in both files, with
/// the same `vt` text; interior samples differ (the tessellator's rings), and where a position
/// is still in both, its `vt` is the same too.
#[test]
fn tess_exports_write_the_pattern_exports_texture_coordinates() {
    let grid = model_path("grid_uv_8x8.obj");
    for surface in ["flat", "pn"] {
        let level = ["--surface", surface, "--level", "8"];
        let (pattern, _) = export(&grid, &format!("grid-{surface}-pattern-8.obj"), &level);
        let tess_args = [&level[..], &["--driver", "tess"]].concat();
        let (tess, _) = export(&grid, &format!("grid-{surface}-tess-8.obj"), &tess_args);
        let (pattern, tess) = (vt_by_position(&pattern), vt_by_position(&tess));
        let mut shared = 0;
        for (p, uv) in &tess {
            if let Some(want) = pattern.get(p) {
                assert_eq!(uv, want, "{surface}: vertex {p}");
                shared += 1;
            }
        }
        // The grid's 81 corners and 208 coarse edges of 7 inner samples each.
        assert!(
            shared >= 81 + 208 * 7,
            "{surface}: {shared} shared vertices"
        );
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
    // Level 4: 15 vertices per triangle on the pattern, 19 on the tessellator's rings; 5 on the
    // shared diagonal on both.
    for (driver, v) in [("pattern", 25), ("tess", 33)] {
        for seam in [false, true] {
            let what = format!("{driver}, seam {seam}");
            let input = tmp(&format!("square-seam-{seam}.obj"));
            std::fs::write(&input, square(seam)).unwrap();
            let name = format!("square-seam-{seam}-{driver}-out.obj");
            let args = ["--surface", "flat", "--level", "4", "--driver", driver];
            let (text, _) = export(&input, &name, &args);
            check_square(&load(&text, &name), seam, v, &what);
        }
    }
}

/// [`a_texture_seam_doubles_vt_but_not_v`]'s checks of an export of [`square`] with `v`
/// vertices.
fn check_square(mesh: &Mesh, seam: bool, v: usize, what: &str) {
    assert_eq!(mesh.positions.len(), v, "{what}");
    let vt = if seam { v + 5 } else { v };
    assert_eq!(mesh.texcoords.len(), vt, "{what}");
    // Welded across the diagonal: only the square's outline is open.
    assert_eq!(mesh.stats().boundary_edges, 16, "{what}");
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
                "{what}: {p} has vt {uv}, expected {want}"
            );
        }
    }
}

#[test]
fn exports_without_texture_coordinates_are_unchanged() {
    // No vt in, no vt out: the same lines as ever (v, vn, f v//vn after the header), on both
    // GPU drivers.
    let tet = model_path("tetrahedron.obj");
    for driver in ["pattern", "tess"] {
        let name = format!("tet-{driver}.obj");
        let (text, _) = export(&tet, &name, &["--level", "2", "--driver", driver]);
        assert!(
            text.lines().nth(2).unwrap().ends_with(" triangles"),
            "{driver}"
        );
        for line in text.lines().filter(|l| !l.starts_with('#')) {
            let ok = line.starts_with("v ")
                || line.starts_with("vn ")
                || (line.starts_with("f ")
                    && line[2..].split(' ').all(|c| {
                        let (a, b) = c.split_once("//").unwrap();
                        a.parse::<u32>().is_ok() && b.parse::<u32>().is_ok()
                    }));
            assert!(ok, "{driver}: {line}");
        }
    }
    // With texture coordinates, loop (whose elements carry none) writes none and says so, on
    // both GPU drivers, naming the file as given, as every message does.
    let grid = model_path("grid_uv_8x8.obj");
    for driver in ["pattern", "tess"] {
        let name = format!("grid-loop-{driver}.obj");
        let args = ["--surface", "loop", "--level", "2", "--driver", driver];
        let (text, stderr) = export(&grid, &name, &args);
        assert!(!text.contains("\nvt "), "{name}");
        assert!(
            stderr.contains(&format!(
                "warning: '{}' has texture coordinates, but --surface loop writes none (vt)",
                grid.display()
            )),
            "{name}: {stderr}"
        );
    }
}

/// Texture coordinates on some triangles only are not written (they would leave vertices
/// without any), and a warning says so, naming the file and how many triangles have them.
#[test]
fn texture_coordinates_on_some_triangles_only_are_said_dropped() {
    let mesh = tmp("some-vt.obj");
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
                f 1/1 2/2 3/3\nf 2 4 3\n";
    std::fs::write(&mesh, text).unwrap();
    for driver in ["pattern", "tess"] {
        let name = format!("some-vt-{driver}.obj");
        let (text, stderr) = export(&mesh, &name, &["--level", "2", "--driver", driver]);
        let faces = text.lines().filter(|l| l.starts_with("f "));
        assert!(!text.contains("\nvt "), "{name}");
        assert!(faces.clone().count() > 0, "{name}");
        assert!(
            faces
                .flat_map(|l| l[2..].split(' '))
                .all(|c| c.contains("//")),
            "{name}"
        );
        assert!(
            stderr.contains(&format!(
                "warning: '{}' gives texture coordinates (vt) on 1 of its 2 triangles, not on every one: the export writes none",
                mesh.display()
            )),
            "{name}: {stderr}"
        );
    }
}

/// Texture coordinates change nothing else: an export of the grid without its `vt` is the
/// export with them less the `vt` lines, the faces' `vt` indices and the counts line's
/// `, N texture coordinates` (and but for the command lines, which name other files), on both
/// GPU drivers (the tess driver's transform feedback
/// carries every vertex's sample either way).
#[test]
fn texture_coordinates_change_nothing_else() {
    let grid = model_path("grid_uv_8x8.obj");
    let without_vt = |text: &str| -> String {
        let mut out = String::new();
        // The command lines name other files.
        let kept = text.lines().filter(|l| !l.starts_with("# command: "));
        for line in kept.filter(|l| !l.starts_with("vt ")) {
            let line = match line.strip_prefix("f ") {
                Some(f) => {
                    let corner = |c: &str| {
                        let ids: Vec<&str> = c.split('/').collect();
                        match ids.as_slice() {
                            [v, _, n] => format!("{v}//{n}"),
                            [v, ..] => v.to_string(),
                            [] => unreachable!(),
                        }
                    };
                    let corners: Vec<String> = f.split(' ').map(corner).collect();
                    format!("f {}", corners.join(" "))
                }
                // The counts line, `# V vertices, N normals, T triangles, C texture coordinates`.
                None if line.ends_with(" texture coordinates") => {
                    line[..line.rfind(", ").unwrap()].to_string()
                }
                None => line.to_string(),
            };
            out.push_str(&line);
            out.push('\n');
        }
        out
    };
    let plain = tmp("plain");
    std::fs::create_dir_all(&plain).unwrap();
    let plain = plain.join("grid_uv_8x8.obj");
    std::fs::write(&plain, without_vt(&std::fs::read_to_string(&grid).unwrap())).unwrap();
    for driver in ["pattern", "tess"] {
        let args = ["--surface", "pn", "--level", "4", "--driver", driver];
        let (with, _) = export(&grid, &format!("uv-{driver}.obj"), &args);
        let (without, _) = export(&plain, &format!("no-uv-{driver}.obj"), &args);
        assert!(with.contains("\nvt "), "{driver}");
        assert!(
            without_vt(&with) == without_vt(&without),
            "{driver}: the export with vt differs in more than its vt"
        );
    }
}
