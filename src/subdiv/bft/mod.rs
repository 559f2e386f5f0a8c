//! Basis function tables (Holländer & Boubekeur 2010, §4): after one Loop step every M1 face has
//! at most one extraordinary vertex, and the limit surface over it is a fixed linear combination
//! of the face's *control points* (the vertices of the faces around its corners, M1's one-ring of
//! the face), with weights that depend only on the topology there: the face's *configuration*.
//! For every configuration the table holds, at every point of the face's level-`lmax` lattice
//! ([`Lattice`]; [`DEFAULT_LMAX`] = 5: 32 segments per edge, 561 points),
//! the weight of each control point in the limit position there.
//!
//! Configurations are found, not enumerated: each M1 face's neighbourhood is labelled
//! canonically (the face's corners, then each corner's one-ring counter-clockwise from the next
//! corner), and the labelled faces around the corners are its key. Of the face's three rotations
//! and their three mirror images (corners and rings in the opposite order) the one with the
//! smallest key is used, so a configuration is stored once whatever corner the face starts at,
//! and a configuration and its mirror image (a boundary face and its reflection across the
//! extraordinary vertex) share one table, read with u and v swapped ([`Orient`]). Any valence and
//! any boundary case works, and only the configurations the mesh has are built.
//!
//! A table is computed as the paper's configuration meshes: the faces within two rings of the face
//! are cut out (vertices where the cut makes two fans are split), each vertex carries its weights
//! on the control points and on the rest of the cut-out vertices together (the identity at
//! first), `lmax` Loop steps apply the computational entries to the weights, and the limit masks
//! at the face's lattice vertices give the rows. The cut's own boundary is subdivided as a
//! boundary, which is wrong, but the error travels at most one ring inwards over all steps (half
//! a ring, then a quarter, ...), so the face, two rings in, is exact; the weights on the second
//! ring come out exactly zero (checked by the tests), so they are dropped, and so are the control
//! points a face does not reach (a wide boundary fan's far sectors, `compact`). All in f64,
//! stored as f32.
//!
//! Stored ([`pack`]), a table is a map from its rows to distinct rows kept once. A table that is
//! its own mirror image (every inside face: the reflection through its extraordinary vertex)
//! keeps the rows on one side of its axis and reads the others as their mirror images, its
//! columns in the pairs the reflection swaps (`arrange`); and tables whose faces look alike as
//! far as a lattice point's limit reaches (a boundary fan's faces far from the fan's ends,
//! whatever its width) share that row, their columns put in an order that depends only on the
//! weights far from corner 0, in frames that put the extraordinary vertex at corner 0
//! (`frame`). Stored so, every configuration up to valence 18 takes 0.77 MiB at level 5;
//! as whole tables, 1.91 MiB.
//!
//! At high valence the build stays linear in the valence ([`RING_REACH`]): weights are sparse
//! (each summed in the dense sum's order: the same bits), an inside vertex's ring beyond the
//! face's reach shares one column (it enters only through the vertex's own rule, the ring's
//! sum), and a wide boundary fan's middle faces are labelled only as far as they reach, one
//! configuration known before building. The faces' control lists grow with the square of an
//! inside vertex's valence (each face around it lists its whole ring); [`check_size`] refuses
//! a mesh past [`CONTROL_LIMIT`] before anything is built.
//!
//! One idea a file: `lattice.rs` (the lattice, a face's orientation in it), `classification.rs`
//! (which configuration each face has), `table.rs` (one configuration's table, and sharing equal
//! ones), `packing.rs` (rows stored once, as the drawing stages read them); this file builds them
//! for a mesh on every core and reports how far it is.
#![forbid(unsafe_code)]

mod classification;
mod lattice;
mod packing;
mod progress;
mod table;

pub use progress::{progress_line, throttled, Progress, PLAIN_PROGRESS_EVERY};

pub use lattice::{children_in_lattice, lattice_corners, Lattice, Orient, DEFAULT_LMAX, MAX_LMAX};
pub use packing::{pack, Packed, ROW_SWAPPED};
pub use table::{rounded, Config};

use super::{Boundary, Topology, TopologyError};
use classification::{classify, Classified, Labels, Neighbourhoods};
use packing::arrange;
use std::collections::HashMap;
use table::{compact, table};

/// How far round a vertex's ring a face's own weights reach, in places (edges) from the face:
/// the limit over the face's sub-faces sees the ring at most `lmax` + 2 places away (one a step,
/// one for the limit mask, one for the sub-face), other than through the vertex's own rule,
/// which weighs the sum of its whole ring inside and its two ends on a boundary. Beyond it an
/// inside ring's vertices share one column of the table, and a boundary fan's faces share one
/// table (`far_ring` in table.rs, `truncated` in classification.rs). A wide margin over
/// [`MAX_LMAX`] + 2: rings of up to 2 · 20 + 2 vertices are taken whole.
pub const RING_REACH: usize = 20;

/// The most control points the faces of M1 may list together ([`control_estimate`]): 2^25, 128
/// MiB as the drawing stages read them. A face around an inside vertex of valence n lists all
/// n of its ring (its limit near the vertex weighs them all), so the lists grow with the square
/// of the valence: two poles of valence 4,000 list 2^25; the build holds them about twice.
pub const CONTROL_LIMIT: u64 = 1 << 25;

/// How many control points the faces around one vertex of M1 list: `n` its valence, on a
/// boundary or not ([`control_estimate`]).
fn listed_around(n: u64, on_boundary: bool) -> u64 {
    let reach = RING_REACH as u64;
    if !on_boundary {
        n * (n + 1)
    } else if n <= 2 * reach + 2 {
        n.saturating_sub(1) * (n + 1)
    } else {
        // Each face lists its fan only as far as it reaches, and the two ends.
        (n - 1) * (2 * reach + 4)
    }
}

/// About how many control points the faces of `topo` (M1) will list, known before anything is
/// built: each face lists its corners' one-rings, a wide boundary fan only as far as
/// [`RING_REACH`] (an overestimate by the rings' overlaps, at most a few a face).
/// Returns the estimate and the vertex whose faces list the most with their count.
pub fn control_estimate(topo: &Topology) -> (u64, Option<(u32, u64)>) {
    let mut total = 0;
    let mut most: Option<(u32, u64)> = None;
    for v in 0..topo.vertex_count as u32 {
        let (ring, on_boundary) = topo.one_ring(v);
        let listed = listed_around(ring.len() as u64, on_boundary);
        total += listed;
        if most.is_none_or(|(_, m)| listed > m) {
            most = Some((v, listed));
        }
    }
    (total, most)
}

/// [`control_estimate`] of M1 from M0 (`m0`), without building M1: M1's vertex points keep
/// their vertices' valences and boundaries, an edge point inside has six neighbours and one on
/// the boundary four. The same total; the vertex that lists the most is among M0's (an edge
/// point lists at most 42, which decides nothing).
pub fn control_estimate_m0(m0: &Topology) -> (u64, Option<(u32, u64)>) {
    let (vertices, most) = control_estimate(m0);
    let boundary = m0.twin.iter().filter(|t| t.is_none()).count() as u64;
    let inside = (m0.twin.len() as u64 - boundary) / 2;
    let edges = inside * listed_around(6, false) + boundary * listed_around(4, true);
    (vertices + edges, most)
}

/// [`TopologyError::TooManyControlPoints`] where the faces of `topo` (M1) would list more than
/// [`CONTROL_LIMIT`] control points ([`control_estimate`]).
pub fn check_size(topo: &Topology) -> Result<(), TopologyError> {
    let (listed, most) = control_estimate(topo);
    match most {
        Some((vertex, _)) if listed > CONTROL_LIMIT => Err(TopologyError::TooManyControlPoints {
            listed,
            vertex,
            valence: topo.one_ring(vertex).0.len(),
            limit: CONTROL_LIMIT,
        }),
        _ => Ok(()),
    }
}

/// The configuration of one face: which table, how its corners map to the table's, and its
/// control points (M1 vertex indices, one per column of the table).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FaceConfig {
    pub config: u32,
    pub orient: Orient,
    pub control: Vec<u32>,
}

/// Every face of a mesh (M1) with its table, and the tables.
#[derive(Clone, Debug)]
pub struct Tables {
    pub lattice: Lattice,
    /// The key of every configuration found (the faces around the canonical corners, in canonical
    /// labels, each rotated to start at its smallest label, sorted); those whose tables are equal
    /// share one, so `configs` may be fewer.
    pub keys: Vec<Vec<[u32; 3]>>,
    /// The distinct tables.
    pub configs: Vec<Config>,
    pub faces: Vec<FaceConfig>,
    /// The tables as stored on the GPU.
    pub packed: Packed,
    /// The weights the build computed: every vertex's non-zero weights, summed over every
    /// table's refinement steps (its work and, step by step, its memory; linear in the valence).
    pub work: u64,
}

impl Tables {
    /// Bytes of the tables as stored on the GPU.
    pub fn bytes(&self) -> u64 {
        self.packed.bytes()
    }
}

/// Find every face's configuration in `topo` (M1) and build the tables of those it has.
/// `progress` hears how far it is as the work goes (faces classified, tables built), always on
/// the calling thread, while the work is shared among the cores.
pub fn build(
    topo: &Topology,
    boundary: Boundary,
    lattice: Lattice,
    progress: impl FnMut(Progress),
) -> Result<Tables, TopologyError> {
    let cores = std::thread::available_parallelism().map_or(1, |t| t.get());
    // A thread for at most every 4,096 faces: fewer are not worth a thread.
    let threads = cores.clamp(1, topo.faces.len().div_ceil(4096).max(1));
    build_on(topo, boundary, lattice, progress, threads, cores)
}

/// A configuration found in the faces: its representative face and orientation, and its key.
type Rep = (usize, Orient, Vec<[u32; 3]>);

/// [`build`] with faces classified on `threads` threads and tables built on up to `cores`:
/// classify, number the configurations, build their tables, then share equal tables and pack.
fn build_on(
    topo: &Topology,
    boundary: Boundary,
    lattice: Lattice,
    mut progress: impl FnMut(Progress),
    threads: usize,
    cores: usize,
) -> Result<Tables, TopologyError> {
    let nb = Neighbourhoods::new(topo);
    let shares = classify_faces(topo, &nb, threads, &mut progress);
    let (reps, faces) = number_configurations(shares, topo.faces.len());
    let keys: Vec<Vec<[u32; 3]>> = reps.iter().map(|r| r.2.clone()).collect();
    let (built, work) = build_tables(topo, &nb, &reps, boundary, lattice, cores, &mut progress)?;
    let mut tables = share_and_pack(built, faces, keys, lattice);
    tables.work = work;
    Ok(tables)
}

/// Every face's configuration key, classified on `threads` threads in contiguous shares (one a
/// thread, in face order), this thread taking the first share and reporting for all.
fn classify_faces(
    topo: &Topology,
    nb: &Neighbourhoods,
    threads: usize,
    progress: &mut impl FnMut(Progress),
) -> Vec<Classified> {
    let n = topo.faces.len();
    // Faces are classified independently: in contiguous shares, one a thread, merged in face
    // order, so configurations are numbered by first appearance whatever the thread count.
    let share = n.div_ceil(threads);
    let ranges: Vec<_> = (0..threads)
        .map(|t| t * share..((t + 1) * share).min(n))
        .collect();
    let done = std::sync::atomic::AtomicUsize::new(0);
    progress(Progress::Faces(0, n));
    let shares: Vec<Classified> = std::thread::scope(|s| {
        let others: Vec<_> = ranges[1..]
            .iter()
            .map(|r| {
                let done = &done;
                s.spawn(move || classify(topo, nb, r.clone(), done, &mut || {}))
            })
            .collect();
        // This thread takes the first share and reports how far all of them are.
        let mut ticks = 0;
        let mut report = || {
            ticks += 1;
            if ticks % 16 == 0 {
                let d = done.load(std::sync::atomic::Ordering::Relaxed);
                progress(Progress::Faces(d.min(n), n));
            }
        };
        let first = classify(topo, nb, ranges[0].clone(), &done, &mut report);
        std::iter::once(first)
            .chain(
                others
                    .into_iter()
                    .map(|h| h.join().expect("classification thread")),
            )
            .collect()
    });
    progress(Progress::Faces(n, n));
    shares
}

/// The shares merged in face order: configurations numbered by first appearance (each with
/// its representative), and every face with its configuration's number.
fn number_configurations(shares: Vec<Classified>, n: usize) -> (Vec<Rep>, Vec<FaceConfig>) {
    let mut ids: HashMap<Vec<[u32; 3]>, u32> = HashMap::new();
    // The representative face and orientation of each configuration.
    let mut reps: Vec<Rep> = Vec::new();
    let mut faces = Vec::with_capacity(n);
    for share in shares {
        let global: Vec<u32> = share
            .keys
            .into_iter()
            .map(|(key, f, orient)| {
                let next = reps.len() as u32;
                *ids.entry(key).or_insert_with_key(|key| {
                    reps.push((f, orient, key.clone()));
                    next
                })
            })
            .collect();
        faces.extend(
            share
                .faces
                .into_iter()
                .map(|(id, orient, control)| FaceConfig {
                    config: global[id as usize],
                    orient,
                    control,
                }),
        );
    }
    (reps, faces)
}

/// A table and the weights its build computed.
type Built = (Config, u64);

/// The table of every configuration, in their order, built on up to `cores` threads, and the
/// weights their builds computed.
fn build_tables(
    topo: &Topology,
    nb: &Neighbourhoods,
    reps: &[Rep],
    boundary: Boundary,
    lattice: Lattice,
    cores: usize,
    progress: &mut impl FnMut(Progress),
) -> Result<(Vec<Config>, u64), TopologyError> {
    let total = reps.len();
    // Tables too are independent: thread t builds configurations t, t + T, t + 2T, ...
    let builders = cores.min(total).max(1);
    let done = std::sync::atomic::AtomicUsize::new(0);
    let build_share = |t: usize, tick: &mut dyn FnMut()| {
        let mut labels = Labels::new(topo.vertex_count);
        let mut out = Vec::new();
        for (i, (f, orient, _)) in reps.iter().enumerate().skip(t).step_by(builders) {
            out.push((
                i,
                table(topo, nb, &mut labels, *f, *orient, boundary, lattice),
            ));
            done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            tick();
        }
        out
    };
    progress(Progress::Tables(0, total));
    let mut built: Vec<(usize, Result<Built, TopologyError>)> = std::thread::scope(|s| {
        let others: Vec<_> = (1..builders)
            .map(|t| {
                let build_share = &build_share;
                s.spawn(move || build_share(t, &mut || {}))
            })
            .collect();
        let mut report = || {
            let d = done.load(std::sync::atomic::Ordering::Relaxed);
            progress(Progress::Tables(d.min(total), total));
        };
        let mut all = build_share(0, &mut report);
        for h in others {
            all.extend(h.join().expect("table thread"));
        }
        all
    });
    built.sort_by_key(|b| b.0);
    let built = built
        .into_iter()
        .map(|b| b.1)
        .collect::<Result<Vec<Built>, TopologyError>>()?;
    progress(Progress::Tables(total, total));
    let work = built.iter().map(|b| b.1).sum();
    Ok((built.into_iter().map(|b| b.0).collect(), work))
}

/// Equal tables shared, columns arranged and cut to those weighed, each face's control points
/// put in its table's column order, and the tables packed.
fn share_and_pack(
    built: Vec<Config>,
    mut faces: Vec<FaceConfig>,
    keys: Vec<Vec<[u32; 3]>>,
    lattice: Lattice,
) -> Tables {
    let (mut configs, kept) = compact(built, lattice);
    // Columns in the order `arrange` gives them.
    let layouts: Vec<Vec<usize>> = configs.iter_mut().map(|c| arrange(c, lattice)).collect();
    // Control points: only those the table weighs, in its columns' order.
    for fc in &mut faces {
        let (id, columns) = &kept[fc.config as usize];
        fc.control = layouts[*id as usize]
            .iter()
            .map(|&l| fc.control[columns[l]])
            .collect();
        fc.config = *id;
    }
    let packed = pack(&configs.iter().collect::<Vec<_>>(), lattice);
    Tables {
        lattice,
        keys,
        configs,
        faces,
        packed,
        work: 0,
    }
}

/// Every configuration up to valence `max`, as the 2010 paper counts its tables: the union of
/// the configurations of closed spheres whose poles have valence 3 ..= max (inside
/// extraordinary vertices) and of half-disc fans of 1 .. max triangles (boundary vertices of 2
/// ..= max edges). Returns the number of configurations (distinct keys) and the distinct
/// tables (by content), as one mesh with all of them would have them (for
/// [`pack`]).
pub fn every_configuration(max: u32, boundary: Boundary, lattice: Lattice) -> (usize, Vec<Config>) {
    use crate::mesh::generate::{half_disc_fan_mesh, sphere_mesh};
    use crate::subdiv::loop_step;
    let meshes = (3..=max)
        .map(|n| sphere_mesh(n, 8))
        .chain((1..max).map(half_disc_fan_mesh));
    let mut keys = std::collections::HashSet::new();
    let mut seen = std::collections::HashSet::new();
    let mut tables = Vec::new();
    for mesh in meshes {
        let topo = Topology::of_mesh(&mesh).expect("a manifold mesh");
        let p: Vec<glam::DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        let m1 = loop_step(&topo, &p, boundary);
        let t1 = Topology::new(&m1.faces, m1.positions.len()).expect("a manifold M1");
        let built = build(&t1, boundary, lattice, |_| {}).expect("tables");
        keys.extend(built.keys);
        for c in built.configs {
            let bits: Vec<i64> = c.weights.iter().map(|&w| rounded(w)).collect();
            if seen.insert(bits) {
                tables.push(c);
            }
        }
    }
    (keys.len(), tables)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_support::load_model;
    use crate::subdiv::{loop_step, subdivide_to_limit};
    use glam::DVec3;
    use lattice::reflection;

    #[test]
    fn rows_cover_the_lattice_once() {
        for lmax in 1..=MAX_LMAX {
            let l = Lattice::new(lmax);
            let mut seen = vec![false; l.rows()];
            for j in 0..=l.segments() {
                for i in 0..=l.segments() - j {
                    assert!(!std::mem::replace(&mut seen[l.row(i, j)], true));
                }
            }
            assert!(seen.iter().all(|&s| s));
        }
        assert_eq!(Lattice::default().rows(), 561);
    }

    /// Tables evaluated at the lattice are the limit positions of M^(1 + lmax), face by face, on
    /// closed and open meshes with both boundary rules; the second ring's weights are zero, and
    /// each row's weights sum to one.
    #[test]
    fn tables_give_the_limit_surface() {
        for (file, boundaries, lmax) in [
            ("tetrahedron.obj", &[Boundary::EdgeOnly][..], DEFAULT_LMAX),
            (
                "grid_open_8x8.obj",
                &[Boundary::EdgeOnly, Boundary::EdgeAndCorner][..],
                DEFAULT_LMAX,
            ),
            ("fan24_open.obj", &[Boundary::EdgeOnly][..], DEFAULT_LMAX),
            (
                "halfdisc17_open.obj",
                &[Boundary::EdgeOnly, Boundary::EdgeAndCorner][..],
                DEFAULT_LMAX,
            ),
            // Other table levels (--bft-level).
            ("spot_control_tri.obj", &[Boundary::EdgeOnly][..], 3),
            ("fan24_open.obj", &[Boundary::EdgeAndCorner][..], 2),
        ] {
            let (mesh, _) = load_model(file);
            for &boundary in boundaries {
                assert_limit_surface(file, &mesh, boundary, Lattice::new(lmax));
            }
        }
    }

    /// Past [`RING_REACH`]: a valence-48 pole's far ring shares a column, and a fan of 50 faces
    /// truncates its middle faces' labels; the tables are still the limit surface.
    #[test]
    fn high_valence_tables_give_the_limit_surface() {
        use crate::mesh::generate::{half_disc_fan_mesh, sphere_mesh};
        let lattice = Lattice::new(3);
        assert_limit_surface("sphere48", &sphere_mesh(48, 3), Boundary::EdgeOnly, lattice);
        let fan = half_disc_fan_mesh(50);
        for boundary in [Boundary::EdgeOnly, Boundary::EdgeAndCorner] {
            let tables = assert_limit_surface("fan50", &fan, boundary, lattice);
            // The fan's middle faces (places 21 to 28 of its 51) share one configuration.
            assert!(
                tables.keys.len() < 40,
                "{} configurations",
                tables.keys.len()
            );
        }
    }

    /// The tables of `mesh` evaluated at the lattice are the limit positions of M^(1 + lmax),
    /// face by face; the weight outside the control points is zero and each row sums to one.
    fn assert_limit_surface(
        file: &str,
        mesh: &crate::mesh::Mesh,
        boundary: Boundary,
        lattice: Lattice,
    ) -> Tables {
        let lmax = lattice.lmax;
        let topo0 = Topology::of_mesh(mesh).unwrap();
        let p0: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        let m1 = loop_step(&topo0, &p0, boundary);
        let t1 = Topology::new(&m1.faces, m1.positions.len()).unwrap();
        let tables = build(&t1, boundary, lattice, |_| {}).unwrap();
        for c in &tables.configs {
            assert_eq!(c.outside, 0.0, "{file}: weight outside the control points");
            for r in 0..lattice.rows() {
                let s: f64 = c.weights[r * c.control..(r + 1) * c.control].iter().sum();
                assert!((s - 1.0).abs() < 1e-12, "{file}: row {r} sums to {s}");
            }
        }
        // The reference: lmax more steps, then limits; the lattice vertices of each M1
        // face are found by the same face numbering (4f + child).
        let reference = subdivide_to_limit(mesh, 1 + lmax, boundary).unwrap();
        let diag = {
            let (lo, hi) = mesh.bounds();
            (hi - lo).length() as f64
        };
        let mut worst: f64 = 0.0;
        for (f, fc) in tables.faces.iter().enumerate() {
            let c = &tables.configs[fc.config as usize];
            let eval = |i: u32, j: u32| -> DVec3 {
                let r = lattice.row(i, j);
                (0..c.control)
                    .map(|k| m1.positions[fc.control[k] as usize] * c.weights[r * c.control + k])
                    .sum()
            };
            // Canonical corners of the face, by the sub-face walk from face f.
            let mut tracked: Vec<(usize, [[u32; 2]; 3])> =
                vec![(f, lattice_corners(fc.orient, lattice))];
            for _ in 0..lmax {
                tracked = children_in_lattice(&tracked);
            }
            for (face, coords) in tracked {
                for (&v, c) in reference.faces[face].iter().zip(coords) {
                    let d = (eval(c[0], c[1]) - reference.positions[v as usize]).length();
                    worst = worst.max(d / diag);
                }
            }
        }
        assert!(
            worst < 1e-12,
            "{file} {boundary:?} lmax {lmax}: {worst:e} of the diagonal"
        );
        tables
    }

    /// Building the tables computes weights in proportion to the valence, not its square: a
    /// bicone's two poles of valence 200 and 400 (a far ring in one column) and a boundary fan
    /// of 200 and 400 faces (its middle faces one configuration). The weights computed are the
    /// build's work and, step by step, its memory.
    #[test]
    fn building_is_linear_in_the_valence() {
        use crate::mesh::generate::{half_disc_fan_mesh, sphere_mesh};
        let build_of = |mesh: crate::mesh::Mesh| {
            let t1 = crate::subdiv::m1_topology(&mesh).unwrap();
            build(&t1, Boundary::EdgeOnly, Lattice::default(), |_| {}).unwrap()
        };
        // Weights per unit of valence, at most: a pole's configuration mesh keeps its ring
        // about three rings deep through five steps, with up to 2 · RING_REACH + 3 weights a
        // vertex; the fan builds 29 tables, each over the whole fan with a few weights a vertex.
        for (name, n, per) in [("bicone", 200, 4_000), ("fan", 200, 25_000)] {
            let mesh = |n| match name {
                "bicone" => sphere_mesh(n, 2),
                _ => half_disc_fan_mesh(n),
            };
            let (small, large) = (build_of(mesh(n)), build_of(mesh(2 * n)));
            assert!(
                large.work * 100 < small.work * 205,
                "{name}: {} weights at {n}, {} at {}",
                small.work,
                large.work,
                2 * n
            );
            // As many tables either way: the configurations do not grow with the valence.
            assert_eq!(small.configs.len(), large.configs.len(), "{name}");
            assert!(small.work < per * n as u64, "{name}: {}", small.work);
        }
    }

    /// M1's estimate from M0 alone is the one M1's topology gives, inside and on boundaries,
    /// with a fan wider than [`RING_REACH`] reaches and poles.
    #[test]
    fn the_estimate_from_m0_is_m1s() {
        use crate::mesh::generate::{grid_mesh, half_disc_fan_mesh, sphere_mesh, torus_mesh};
        for mesh in [
            grid_mesh(50),
            half_disc_fan_mesh(60),
            half_disc_fan_mesh(5),
            sphere_mesh(70, 3),
            torus_mesh(7, 5),
        ] {
            let m0 = Topology::of_mesh(&mesh).unwrap();
            let m1 = crate::subdiv::m1_topology(&mesh).unwrap();
            let (total, most) = control_estimate_m0(&m0);
            assert_eq!(total, control_estimate(&m1).0);
            let (v, listed) = most.unwrap();
            assert_eq!(listed, control_estimate(&m0).1.unwrap().1);
            assert_eq!(m0.one_ring(v).0.len(), m1.one_ring(v).0.len());
        }
    }

    /// Two poles of valence 20,000 would list 8 · 10^8 control points: refused before anything
    /// is built, naming the limit; two of valence 3,000 are not.
    #[test]
    fn an_absurd_valence_is_refused_before_building() {
        use crate::mesh::generate::sphere_mesh;
        let m1 = |n| crate::subdiv::m1_topology(&sphere_mesh(n, 2)).unwrap();
        let e = check_size(&m1(20_000)).unwrap_err();
        assert!(
            matches!(
                e,
                TopologyError::TooManyControlPoints {
                    valence: 20_000,
                    limit: CONTROL_LIMIT,
                    ..
                }
            ),
            "{e}"
        );
        assert!(
            e.to_string()
                .contains("past the limit of 33554432 control points"),
            "{e}"
        );
        check_size(&m1(3_000)).unwrap();
    }

    /// M1 of a model (`EdgeOnly` boundaries).
    fn m1_of(file: &str) -> Topology {
        let (mesh, _) = load_model(file);
        let topo0 = Topology::of_mesh(&mesh).unwrap();
        let p0: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        let m1 = loop_step(&topo0, &p0, Boundary::EdgeOnly);
        Topology::new(&m1.faces, m1.positions.len()).unwrap()
    }

    /// M1 of a model and its tables at the default level, `EdgeOnly` boundaries.
    fn default_tables(file: &str) -> (Topology, Tables) {
        let t1 = m1_of(file);
        let tables = build(&t1, Boundary::EdgeOnly, Lattice::default(), |_| {}).unwrap();
        (t1, tables)
    }

    /// A boundary vertex's rule does not mix its fan's sectors, so a face of a wide boundary fan
    /// does not reach its far sectors: those columns are exactly zero and dropped, and faces
    /// whose tables are then equal share one. (That the compacted tables are still the limit
    /// surface: `tables_give_the_limit_surface`.)
    #[test]
    fn wide_boundary_fans_keep_only_the_columns_they_weigh() {
        let (t1, tables) = default_tables("halfdisc17_open.obj");
        let mut dropped = 0;
        for (f, fc) in tables.faces.iter().enumerate() {
            let c = &tables.configs[fc.config as usize];
            assert_eq!(fc.control.len(), c.control);
            // The face's one-ring: what the tables weighed before the zero columns went.
            let mut ring: Vec<u32> = t1.faces[f]
                .iter()
                .flat_map(|&v| t1.one_ring(v).0.into_iter().chain([v]))
                .collect();
            ring.sort_unstable();
            ring.dedup();
            assert!(fc.control.iter().all(|v| ring.contains(v)));
            dropped = dropped.max(ring.len() - fc.control.len());
            for j in 0..c.control {
                assert!(
                    (0..Lattice::default().rows()).any(|r| c.weights[r * c.control + j] != 0.0),
                    "face {f}: kept column {j} weighs nothing"
                );
            }
        }
        // The centre's faces: 17 in its fan; the middle one weighs 9 fewer of its 24.
        assert_eq!(dropped, 9, "columns dropped from the widest face");
        assert!(
            tables.configs.len() < tables.keys.len(),
            "{} tables for {} configurations",
            tables.configs.len(),
            tables.keys.len()
        );
    }

    /// The packed tables, read as the GPU reads them (the shared rows, a symmetric table's rows
    /// across its axis as their mirror images), are every table's own rows in f32: the same
    /// bits, or for a mirror image within an ulp (its weights were summed in another order).
    #[test]
    fn packed_rows_are_the_tables() {
        for file in [
            "tetrahedron.obj",
            "spot_control_tri.obj",
            "fan24_open.obj",
            "halfdisc17_open.obj",
            "grid_open_8x8.obj",
        ] {
            let (_, tables) = default_tables(file);
            let lattice = tables.lattice;
            let p = &tables.packed;
            assert_eq!(p.rows.len(), tables.configs.len() * lattice.rows());
            let mut swapped = 0;
            for (t, c) in tables.configs.iter().enumerate() {
                for r in 0..lattice.rows() {
                    let at = p.entry(t * lattice.rows() + r);
                    swapped += at.1 as usize;
                    assert!(!at.1 || c.symmetry.is_some(), "{file}: table {t} swaps");
                    for j in 0..c.control.next_multiple_of(4) {
                        let want = if j < c.control {
                            c.weights[r * c.control + j] as f32
                        } else {
                            0.0
                        };
                        let got = p.weight(at, j, c.pairs);
                        let ulp = if at.1 { want.abs() * f32::EPSILON } else { 0.0 };
                        assert!(
                            (got - want).abs() <= ulp,
                            "{file}: table {t} row {r} column {j}: {got} for {want}"
                        );
                    }
                }
            }
            // Every inside table folds: the rows across its axis are mirror images.
            for c in tables.configs.iter().filter(|c| !c.boundary) {
                assert!(
                    c.symmetry.is_some(),
                    "{file}: an inside table does not fold"
                );
            }
            if tables.configs.iter().any(|c| !c.boundary) {
                assert!(swapped > 0, "{file}: no row is a mirror image");
            }
        }
    }

    /// A symmetric table's columns are the pairs its reflection swaps, then the columns it
    /// fixes: the reflected lattice point's weight on column j is the weight on its partner.
    #[test]
    fn symmetric_tables_pair_their_columns() {
        let (_, tables) = default_tables("spot_control_tri.obj");
        let lattice = tables.lattice;
        let mut folded = 0;
        for c in &tables.configs {
            let Some(a) = c.symmetry else { continue };
            folded += 1;
            let image = reflection(lattice, a);
            let k = c.control;
            let partner = |j: usize| if j < 2 * c.pairs { j ^ 1 } else { j };
            for (r, &m) in image.iter().enumerate() {
                for j in 0..k {
                    let (x, y) = (c.weights[m * k + j], c.weights[r * k + partner(j)]);
                    assert!(
                        (x - y).abs() <= 1e-12 * x.abs().max(y.abs()),
                        "row {r} column {j}"
                    );
                }
            }
        }
        assert_eq!(
            folded,
            tables.configs.len(),
            "Spot is closed: every table folds"
        );
    }

    /// Boundary fans' tables share the rows far from their extraordinary vertex: the half disc's
    /// 14 tables (8 of them for faces of its 18-edge fan) store two thirds of their rows.
    #[test]
    fn boundary_tables_share_rows() {
        let (_, tables) = default_tables("halfdisc17_open.obj");
        let p = &tables.packed;
        let mut distinct: Vec<u32> = p.rows.iter().map(|e| e >> 1).collect();
        distinct.sort_unstable();
        distinct.dedup();
        let rows = p.rows.len();
        assert!(
            distinct.len() * 10 < rows * 7,
            "{} distinct rows of {rows}",
            distinct.len()
        );
        // And the pool, with the row maps, is smaller than the tables whole.
        let whole: usize = tables
            .configs
            .iter()
            .map(|c| c.control.next_multiple_of(4) * tables.lattice.rows() * 4)
            .sum();
        assert!(p.bytes() * 4 < whole as u64 * 3, "{} of {whole}", p.bytes());
    }

    /// The 2010 paper's set, every configuration up to valence 18 inside and on the boundary,
    /// fits in 1 MiB at the default level (it stored about 9 MB).
    #[test]
    fn every_configuration_to_valence_18_fits_in_a_mebibyte() {
        let lattice = Lattice::default();
        let (keys, union) = every_configuration(18, Boundary::EdgeOnly, lattice);
        assert_eq!((keys, union.len()), (99, 54));
        let bytes = pack(&union.iter().collect::<Vec<_>>(), lattice).bytes();
        assert!(bytes <= 1 << 20, "{bytes} bytes");
    }

    /// However many threads classify the faces and build the tables, the result is the same.
    #[test]
    fn threads_do_not_change_the_tables() {
        let t1 = m1_of("spot_open.obj");
        let lattice = Lattice::new(3);
        let one = build_on(&t1, Boundary::EdgeOnly, lattice, |_| {}, 1, 1).unwrap();
        let three = build_on(&t1, Boundary::EdgeOnly, lattice, |_| {}, 3, 3).unwrap();
        assert_eq!(one.keys, three.keys);
        assert_eq!(one.faces, three.faces);
        assert_eq!(one.configs.len(), three.configs.len());
        for (a, b) in one.configs.iter().zip(&three.configs) {
            assert_eq!(a.weights, b.weights);
        }
        assert_eq!(one.packed.pool, three.packed.pool);
        assert_eq!(one.packed.rows, three.packed.rows);
    }

    /// The tetrahedron's M1 has two configurations: the corner faces (one vertex of valence 3,
    /// in any rotation) and the middle faces (regular corners; the one-ring wraps round the small
    /// mesh, so 9 control points, not 12).
    #[test]
    fn configurations_are_few_and_canonical() {
        let (_, tables) = default_tables("tetrahedron.obj");
        let mut valences: Vec<usize> = tables.configs.iter().map(|c| c.valence).collect();
        valences.sort();
        assert_eq!(valences, [3, 6]);
        // Each M0 face's three corner children share one table, rotated to their EV.
        for f in 0..4 {
            let c = &tables.faces[4 * f..4 * f + 3];
            assert!(c.iter().all(|fc| fc.config == c[0].config));
        }
        assert!(valences.contains(&3), "{valences:?}");
    }
}
