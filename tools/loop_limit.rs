//! Prints Loop limit positions of a mesh by meshrefine's CPU reference (`src/subdiv`), or with
//! `--osd-input` the mesh in the plain format `tools/osd_limit.cpp` reads, for the comparison
//! with OpenSubdiv in `scripts/check-loop-osd.sh`.
//!
//! `cargo run --example loop_limit -- MESH.obj STEPS [edge-only|edge-and-corner] [--osd-input]`

use meshrefine::mesh::Mesh;
use meshrefine::subdiv::{subdivide_to_limit, Boundary};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let fail = |m: String| -> ! {
        eprintln!("error: {m}");
        std::process::exit(1)
    };
    if args.len() < 2 {
        fail("usage: loop_limit MESH.obj STEPS [edge-only|edge-and-corner] [--osd-input]".into());
    }
    let (mesh, _) =
        Mesh::load_obj(std::path::Path::new(&args[0])).unwrap_or_else(|e| fail(e.to_string()));
    let steps: u32 = args[1]
        .parse()
        .unwrap_or_else(|_| fail(format!("'{}' is not a step count", args[1])));
    let boundary_name = args.get(2).map(String::as_str).unwrap_or("edge-only");
    let boundary = match boundary_name {
        "edge-only" => Boundary::EdgeOnly,
        "edge-and-corner" => Boundary::EdgeAndCorner,
        other => fail(format!("'{other}' is no boundary rule")),
    };
    if args.iter().any(|a| a == "--osd-input") {
        println!("{steps} {boundary_name}");
        for p in &mesh.positions {
            println!("v {:.9e} {:.9e} {:.9e}", p.x, p.y, p.z);
        }
        for t in &mesh.triangles {
            println!("f {} {} {}", t.p[0], t.p[1], t.p[2]);
        }
        return;
    }
    let r = subdivide_to_limit(&mesh, steps, boundary)
        .unwrap_or_else(|e| fail(format!("'{}': {e}", args[0])));
    for p in &r.positions {
        println!("v {:.17e} {:.17e} {:.17e}", p.x, p.y, p.z);
    }
}
