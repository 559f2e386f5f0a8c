//! How exact the basis function tables stay when their weights are stored smaller: every lattice
//! point of every M1 face of a few test meshes, summed with the weights rounded to f32 (as
//! stored), to 16-bit unorm (the weights are within [0, 1]), to 16-bit unorm with each row
//! rounded to sum to exactly one (largest remainders rounded up), and to half floats, against
//! the f64 sum; the largest distance as a fraction of the mesh's bounding-box diagonal. The
//! dyadic exports must be within 1e-5 of it (`cargo run --release --example bft_precision`).

use glam::DVec3;
use meshrefine::subdiv::{bft, loop_step, Boundary, Topology};

/// Round to a half float's 11 significant bits (normal range; the weights are within [0, 1]).
fn half(x: f64) -> f64 {
    if x == 0.0 {
        return 0.0;
    }
    let q = 2f64.powf(10.0 - x.abs().log2().floor().max(-14.0));
    (x * q).round() / q
}

/// A storage format: its name and how it rounds a weight.
type Format = (&'static str, fn(f64) -> f64);

fn main() {
    let formats: [Format; 3] = [
        ("f32", |w| w as f32 as f64),
        ("unorm16", |w| (w * 65535.0).round() / 65535.0),
        ("f16", half),
    ];
    for file in [
        "icosahedron",
        "spot_control_tri",
        "spot_open",
        "fan24_open",
        "halfdisc17_open",
    ] {
        let path = format!("{}/assets/models/{file}.obj", env!("CARGO_MANIFEST_DIR"));
        let (mesh, _) = meshrefine::mesh::Mesh::load_obj(std::path::Path::new(&path)).unwrap();
        let t0 = Topology::of_mesh(&mesh).unwrap();
        let p0: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        let m1 = loop_step(&t0, &p0, Boundary::EdgeOnly);
        let t1 = Topology::new(&m1.faces, m1.positions.len()).unwrap();
        let lattice = bft::Lattice::default();
        let tables = bft::build(&t1, Boundary::EdgeOnly, lattice, |_| {}).unwrap();
        let (lo, hi) = mesh.bounds();
        let diag = (hi - lo).length() as f64;
        let mut worst = [0.0f64; 3];
        let mut worst_lr = 0.0f64;
        for fc in &tables.faces {
            let c = &tables.configs[fc.config as usize];
            for row in c.weights.chunks(c.control) {
                let sum = |q: &dyn Fn(f64) -> f64| -> DVec3 {
                    row.iter()
                        .zip(&fc.control)
                        .map(|(&w, &v)| m1.positions[v as usize] * q(w))
                        .sum()
                };
                let exact = sum(&|w| w);
                for (k, (_, q)) in formats.iter().enumerate() {
                    worst[k] = worst[k].max((sum(q) - exact).length() / diag);
                }
                // Rounded down, then the largest remainders up: the row sums to exactly 65535.
                let mut q: Vec<i64> = row.iter().map(|&w| (w * 65535.0).floor() as i64).collect();
                let mut rem: Vec<(f64, usize)> = row
                    .iter()
                    .enumerate()
                    .map(|(i, &w)| (w * 65535.0 - (w * 65535.0).floor(), i))
                    .collect();
                rem.sort_by(|a, b| b.0.partial_cmp(&a.0).unwrap());
                let short = 65535 - q.iter().sum::<i64>();
                for k in 0..short.max(0) as usize {
                    q[rem[k].1] += 1;
                }
                let p: DVec3 = q
                    .iter()
                    .zip(&fc.control)
                    .map(|(&qq, &v)| m1.positions[v as usize] * ((qq as f32 / 65535.0) as f64))
                    .sum();
                worst_lr = worst_lr.max((p - exact).length() / diag);
            }
        }
        let figures: Vec<String> = formats
            .iter()
            .zip(worst)
            .map(|((name, _), w)| format!("{name} {w:.1e}"))
            .collect();
        println!(
            "{file}: {}, unorm16 summing to one {worst_lr:.1e} of the diagonal",
            figures.join(", ")
        );
    }
}
