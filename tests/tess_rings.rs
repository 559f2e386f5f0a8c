//! The tessellator's triangles are the ones the tess driver's chord bound allows for
//! (src/lod/mod.rs, "The tessellator's inside"): one flat unit triangle, whose positions are its
//! parameters, exported through the real tess pipeline (transform feedback) at every level 1
//! to 9, validation layer on. Every triangle side, in the integers `K` of the weights `K/(3n)`,
//! is a lattice side (`|ΔK|` 0, 3, 3), a step between rings (1, 1, 2) or a ring diagonal
//! (2, 2, 4); the diagonals are drawn at every level from 2 (so the bound's diagonal term is
//! needed, not only allowed for), and every vertex lies on the rings' grid.

mod common;

use std::collections::BTreeSet;
use std::process::Command;

#[test]
fn tessellator_sides_are_lattice_sides_ring_steps_or_ring_diagonals() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("tess_rings");
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("unit.obj");
    std::fs::write(&input, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    for n in 1..=9u32 {
        let out = dir.join(format!("unit-{n}.obj"));
        let run = {
            let _guard = common::gpu_lock();
            Command::new(env!("CARGO_BIN_EXE_meshrefine"))
                .env("MESHREFINE_VALIDATE", "1")
                .args(["export", input.to_str().unwrap(), "--surface", "flat"])
                .args(["--driver", "tess", "--level", &n.to_string(), "-o"])
                .arg(&out)
                .output()
                .unwrap()
        };
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let text = std::fs::read_to_string(&out).unwrap();
        let mut k = vec![];
        let mut sides = BTreeSet::new();
        for line in text.lines() {
            let t: Vec<&str> = line.split_whitespace().collect();
            match t.first() {
                Some(&"v") => {
                    let [u, v] = [1, 2].map(|i| t[i].parse::<f64>().unwrap() * 3.0 * n as f64);
                    let w = 3.0 * n as f64 - u - v;
                    let ki = [w, u, v].map(|x| x.round() as i64);
                    for (x, r) in [w, u, v].iter().zip(ki) {
                        assert!(
                            (x - r as f64).abs() < 1e-3,
                            "level {n}: {line} off the grid"
                        );
                    }
                    k.push(ki);
                }
                Some(&"f") => {
                    let f: Vec<usize> = t[1..]
                        .iter()
                        .map(|s| s.split('/').next().unwrap().parse::<usize>().unwrap() - 1)
                        .collect();
                    for i in 0..3 {
                        let (a, b) = (k[f[i]], k[f[(i + 1) % 3]]);
                        let mut d = [0, 1, 2].map(|c| (b[c] - a[c]).abs());
                        d.sort();
                        sides.insert(d);
                    }
                }
                _ => {}
            }
        }
        for d in &sides {
            assert!(
                [[0, 3, 3], [1, 1, 2], [2, 2, 4]].contains(d),
                "level {n}: a side {d:?} (in K/(3n)) the bound does not allow for"
            );
        }
        // Both diagonals of a parallelogram between rings are ring diagonals, and so are the
        // centre's spokes at level 2: every level from 2 draws some.
        assert_eq!(
            sides.contains(&[2, 2, 4]),
            n >= 2,
            "level {n}: ring diagonals {:?}",
            sides
        );
    }
}
