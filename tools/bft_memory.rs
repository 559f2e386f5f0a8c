//! The basis function tables' memory for every configuration up to a valence (default 18): the
//! union of the configurations of closed spheres whose poles have valence n = 3 .. max (interior
//! extraordinary vertices) and of open half-disc fans of k = 1 .. max - 1 triangles (boundary
//! vertices of k + 1 edges), configurations deduplicated by key and tables by content, as one
//! mesh's are.
//! For table levels 4 and 5 (and 6 when asked: `cargo run --release --example bft_memory
//! [MAX_VALENCE] [LEVEL...]`).

use meshrefine::subdiv::bft::{every_configuration, pack, Config, Lattice};
use meshrefine::subdiv::Boundary;

fn main() {
    let args: Vec<u32> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let max = args.first().copied().unwrap_or(18);
    let levels = if args.len() > 1 {
        args[1..].to_vec()
    } else {
        vec![4, 5]
    };
    for lmax in levels {
        let lattice = Lattice::new(lmax);
        let boundary = Boundary::EdgeOnly;
        let (keys, union) = every_configuration(max, boundary, lattice);
        let bytes = pack(&union.iter().collect::<Vec<_>>(), lattice).bytes();
        // Each table whole, rows padded to a multiple of four weights (as before the rows
        // were shared).
        let whole: usize = union
            .iter()
            .map(|c| lattice.rows() * c.control.next_multiple_of(4) * 4)
            .sum();
        let (inside, boundary_tables): (Vec<&Config>, Vec<&Config>) =
            union.iter().partition(|c| !c.boundary);
        let part = |t: &[&Config]| pack(t, lattice).bytes();
        let mib = |b: u64| b as f64 / (1 << 20) as f64;
        println!(
            "table level {lmax} ({} segments): {} configurations in {} tables up to valence {max}, {bytes} bytes ({:.2} MiB; inside {} bytes, boundary {} bytes; each table whole: {whole} bytes, {:.2} MiB)",
            lattice.segments(),
            keys,
            union.len(),
            mib(bytes),
            part(&inside),
            part(&boundary_tables),
            mib(whole as u64),
        );
    }
}
