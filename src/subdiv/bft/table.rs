//! One table: the limit-position weights of a configuration at every lattice point, computed on
//! the paper's configuration mesh (the faces within two rings of the face, cut out, fans split
//! where the cut pinches), `lmax` Loop steps applied to the weights and the limit masks at the
//! lattice points; then [`compact`] drops the columns no row weighs and lets equal tables be one.
#![forbid(unsafe_code)]

use super::classification::{label, Labels, Neighbourhoods};
use super::{children_in_lattice, lattice_corners, Lattice, Orient};
use crate::subdiv::{limit_stencil, refined_faces, stencils, Boundary, Topology, TopologyError};
use std::collections::HashMap;

/// A table: the limit-position weights of a configuration (of every configuration that shares it).
#[derive(Clone, Debug)]
pub struct Config {
    /// Control points: the columns of `weights` (built as labels 0 .. control, the face's
    /// corners first; [`build`](super::build) then keeps only the labels some row weighs, in the order
    /// `arrange` gives them).
    pub control: usize,
    /// The largest valence among the face's corners that is not regular (6 inside, 4 on a
    /// boundary), or the regular valence of corner 0.
    pub valence: usize,
    /// Whether any corner of the face is on the boundary.
    pub boundary: bool,
    /// `rows × control` weights, row-major.
    pub weights: Vec<f64>,
    /// The weight found on the cut-out vertices beyond the control points, all together, at the
    /// lattice point where it is largest (exactly zero by the argument above).
    pub outside: f64,
    /// The canonical corner a reflection of the lattice fixes, where the table is its own
    /// mirror image under it (an inside face at its extraordinary vertex: the reflection swaps
    /// the other two corners). Its columns then come as the pairs that the reflection swaps,
    /// then the columns it fixes, so that [`pack`](super::pack) stores only the rows on one side of the axis
    /// and reads the others as their mirror images with each pair's weights swapped.
    pub symmetry: Option<u8>,
    /// With a `symmetry`, columns 2m and 2m + 1 for m < `pairs` are the pairs it swaps, and the
    /// columns after them those it fixes.
    pub pairs: usize,
}

/// A weight rounded to a multiple of 1 / TABLE_EQUAL: equal tables, built on different
/// configuration meshes, round alike.
pub fn rounded(w: f64) -> i64 {
    (w * TABLE_EQUAL).round() as i64
}

/// Drops the columns no row weighs (a boundary vertex's fan beyond the face's reach: its rule
/// does not mix the sectors of its fan, so over `lmax` steps a sector reaches only a few
/// sectors on), then lets configurations whose remaining tables are equal share one (their
/// topology differs only where the face does not reach). Dropping a column changes no sum: its
/// terms were zero weights, and the others keep their order. Returns the tables and, per
/// configuration, its table and kept columns.
/// Tables whose weights round to the same multiples of 1 / TABLE_EQUAL are shared.
const TABLE_EQUAL: f64 = (1u64 << 40) as f64;

pub(super) fn compact(
    built: Vec<Config>,
    lattice: Lattice,
) -> (Vec<Config>, Vec<(u32, Vec<usize>)>) {
    let rows = lattice.rows();
    let mut ids: HashMap<(usize, Vec<u64>), u32> = HashMap::new();
    let mut configs: Vec<Config> = Vec::new();
    let mut kept = Vec::with_capacity(built.len());
    for c in built {
        let k = c.control;
        let columns: Vec<usize> = (0..k)
            .filter(|&j| (0..rows).any(|r| c.weights[r * k + j] != 0.0))
            .collect();
        let all = &c.weights;
        let weights: Vec<f64> = (0..rows)
            .flat_map(|r| columns.iter().map(move |&j| all[r * k + j]))
            .collect();
        // Equal to 2^-40 (weights are within [0, 1]): the same table computed on two
        // configuration meshes can differ in the last bits of f64.
        let bits = (
            columns.len(),
            weights.iter().map(|&w| rounded(w) as u64).collect(),
        );
        let next = configs.len() as u32;
        let id = *ids.entry(bits).or_insert_with(|| {
            configs.push(Config {
                control: columns.len(),
                weights,
                ..c
            });
            next
        });
        kept.push((id, columns));
    }
    (configs, kept)
}

/// The table of face `f` in orientation `o`, from its two-ring configuration mesh: cut out,
/// refined `lmax` times carrying the weights, limit masks at the lattice points.
pub(super) fn table(
    topo: &Topology,
    nb: &Neighbourhoods,
    labels: &mut Labels,
    f: usize,
    o: Orient,
    boundary: Boundary,
    lattice: Lattice,
) -> Result<Config, TopologyError> {
    label(topo, nb, f, o, labels);
    let control = labels.order.len();
    let (local, count) = configuration_mesh(topo, nb, labels, f, control);
    let mesh = refine_weights(local, count, control, o, boundary, lattice)?;
    let (weights, outside) = limit_rows(&mesh, control, boundary, lattice);
    let (valence, is_boundary) = corner_valence(topo, topo.faces[f], o);
    Ok(Config {
        control,
        valence,
        boundary: is_boundary,
        weights,
        outside,
        symmetry: None,
        pairs: 0,
    })
}

/// The configuration mesh of face `f` (labelled, its `control` points first): the faces
/// around the control points, in labels, with fans that the cut pinches split. Returns the
/// faces and the vertex count.
fn configuration_mesh(
    topo: &Topology,
    nb: &Neighbourhoods,
    labels: &mut Labels,
    f: usize,
    control: usize,
) -> (Vec<[u32; 3]>, usize) {
    // Faces within two rings: those around the control points (the face first).
    let t = topo.faces[f];
    let mut local: Vec<[u32; 3]> = vec![t];
    let mut seen: std::collections::HashSet<u32> = [f as u32].into();
    for i in 0..control {
        for &g in &nb.faces[labels.order[i] as usize] {
            if seen.insert(g) {
                local.push(topo.faces[g as usize]);
            }
        }
    }
    for face in &local {
        for &v in face {
            labels.add(v);
        }
    }
    let mut local: Vec<[u32; 3]> = local.iter().map(|t| t.map(|v| labels.of(v))).collect();
    let mut count = labels.order.len();
    split_fans(&mut local, &mut count, |v| v >= control as u32);
    (local, count)
}

/// A configuration mesh after `lmax` Loop steps: its topology, every vertex's weights (`dims`
/// a vertex: one per control point, then the rest together), and the lattice coordinates of
/// the faces that tile the face.
struct Refined {
    topo: Topology,
    w: Vec<f64>,
    dims: usize,
    tracked: Vec<(usize, [[u32; 2]; 3])>,
}

/// `lmax` Loop steps on the configuration mesh `local` (over `count` vertices), applied to the
/// weights and pruned to the face's surroundings after each.
fn refine_weights(
    local: Vec<[u32; 3]>,
    mut count: usize,
    control: usize,
    o: Orient,
    boundary: Boundary,
    lattice: Lattice,
) -> Result<Refined, TopologyError> {
    // Weights of every local vertex on the control points, level by level, and in one more
    // column its weight on all the other cut-out vertices together: every rule and limit mask
    // weighs with non-negative weights, so that sum is zero exactly when each of them is (the
    // columns are independent: the control points' weights are the same bits as with a column
    // for each cut-out vertex, at a fraction of the work).
    let dims = control + 1;
    let mut w: Vec<f64> = vec![0.0; count * dims];
    for v in 0..count {
        w[v * dims + v.min(control)] = 1.0;
    }
    let mut topo_l = Topology::new(&local, count)?;
    // Lattice coordinates (in units of 1/S) of the tracked faces' corners; the face's stored
    // corner k is canonical corner `o.canonical(k)`.
    let mut tracked: Vec<(usize, [[u32; 2]; 3])> = vec![(0, lattice_corners(o, lattice))];
    for _ in 0..lattice.lmax {
        let st = stencils(&topo_l, boundary);
        let mut next = vec![0.0; st.len() * dims];
        for (i, sv) in st.iter().enumerate() {
            debug_assert!(sv.weights.iter().all(|&x| x >= 0.0), "negative rule weight");
            let out = &mut next[i * dims..(i + 1) * dims];
            for (&p, &wt) in sv.parents.iter().zip(&sv.weights) {
                let src = &w[p as usize * dims..(p as usize + 1) * dims];
                for (o, &x) in out.iter_mut().zip(src) {
                    *o += wt * x;
                }
            }
        }
        tracked = children_in_lattice(&tracked);
        // Only what is within PRUNE_RINGS rings of the face goes on (a valence-300 vertex
        // would otherwise make a million-face configuration mesh at the last level); the new
        // rim is subdivided wrongly too, and its error stays beyond the face as the first cut's.
        let (mut faces, old_of, rim) =
            prune(&refined_faces(&topo_l), st.len(), &mut tracked, PRUNE_RINGS);
        count = old_of.len();
        let origin = split_fans(&mut faces, &mut count, |v| rim[v as usize]);
        w = old_of
            .iter()
            .chain(origin.iter().map(|&o| &old_of[o as usize]))
            .flat_map(|&old| {
                next[old as usize * dims..(old as usize + 1) * dims]
                    .iter()
                    .copied()
            })
            .collect();
        topo_l = Topology::new(&faces, count)?;
    }
    Ok(Refined {
        topo: topo_l,
        w,
        dims,
        tracked,
    })
}

/// The table's rows: the limit mask at each lattice point applied to the weights (`rows ×
/// control`), and the largest weight on the other cut-out vertices.
fn limit_rows(
    mesh: &Refined,
    control: usize,
    boundary: Boundary,
    lattice: Lattice,
) -> (Vec<f64>, f64) {
    let Refined {
        topo: topo_l,
        w,
        dims,
        tracked,
    } = mesh;
    let dims = *dims;
    // The lattice vertex at each row, then its limit mask.
    let rows = lattice.rows();
    let mut at_row = vec![u32::MAX; rows];
    for &(face, coords) in tracked {
        for k in 0..3 {
            at_row[lattice.row(coords[k][0], coords[k][1])] = topo_l.faces[face][k];
        }
    }
    let mut weights = vec![0.0; rows * control];
    let mut outside: f64 = 0.0;
    for (r, &v) in at_row.iter().enumerate() {
        debug_assert_ne!(v, u32::MAX);
        let mask = limit_stencil(topo_l, v, boundary);
        debug_assert!(
            mask.weights.iter().all(|&x| x >= 0.0),
            "negative limit weight"
        );
        let mut full = vec![0.0; dims];
        for (&p, &wt) in mask.parents.iter().zip(&mask.weights) {
            for (o, &x) in full
                .iter_mut()
                .zip(&w[p as usize * dims..(p as usize + 1) * dims])
            {
                *o += wt * x;
            }
        }
        weights[r * control..(r + 1) * control].copy_from_slice(&full[..control]);
        outside = outside.max(full[control].abs());
    }
    (weights, outside)
}

/// The valence [`Config::valence`] names, and whether any corner of face `t` (in orientation
/// `o`) is on the boundary.
fn corner_valence(topo: &Topology, t: [u32; 3], o: Orient) -> (usize, bool) {
    let corners = [0, 1, 2].map(|i| t[o.stored(i)]);
    let rings = corners.map(|c| topo.one_ring(c));
    let is_boundary = rings.iter().any(|r| r.1);
    let valence = rings
        .iter()
        .map(|(ring, b)| (ring.len(), *b))
        .find(|&(n, b)| n != if b { 4 } else { 6 })
        .map_or(rings[0].0.len(), |(n, _)| n);
    (valence, is_boundary)
}

/// Rings of faces kept around the face after each step of a configuration mesh.
const PRUNE_RINGS: usize = 3;

/// The faces of `faces` (over `count` vertices) within `rings` rings of the tracked faces'
/// vertices, renumbered: the kept faces (tracked face indices updated), each new vertex's old
/// index, and which new vertices are on the rim (their neighbourhoods cut).
fn prune(
    faces: &[[u32; 3]],
    count: usize,
    tracked: &mut [(usize, [[u32; 2]; 3])],
    rings: usize,
) -> (Vec<[u32; 3]>, Vec<u32>, Vec<bool>) {
    let mut vf: Vec<Vec<u32>> = vec![Vec::new(); count];
    for (f, t) in faces.iter().enumerate() {
        for &v in t {
            vf[v as usize].push(f as u32);
        }
    }
    let mut dist = vec![usize::MAX; count];
    let mut frontier: Vec<u32> = Vec::new();
    for &(f, _) in tracked.iter() {
        for &v in &faces[f] {
            if dist[v as usize] == usize::MAX {
                dist[v as usize] = 0;
                frontier.push(v);
            }
        }
    }
    for r in 0..rings {
        let mut next = Vec::new();
        for &v in &frontier {
            for &f in &vf[v as usize] {
                for &u in &faces[f as usize] {
                    if dist[u as usize] == usize::MAX {
                        dist[u as usize] = r + 1;
                        next.push(u);
                    }
                }
            }
        }
        frontier = next;
    }
    let mut new_of = vec![u32::MAX; count];
    let mut old_of = Vec::new();
    let mut face_of = vec![u32::MAX; faces.len()];
    let mut kept = Vec::new();
    for (f, t) in faces.iter().enumerate() {
        if t.iter().any(|&v| dist[v as usize] < rings) {
            face_of[f] = kept.len() as u32;
            kept.push(t.map(|v| {
                if new_of[v as usize] == u32::MAX {
                    new_of[v as usize] = old_of.len() as u32;
                    old_of.push(v);
                }
                new_of[v as usize]
            }));
        }
    }
    for (f, _) in tracked.iter_mut() {
        *f = face_of[*f] as usize;
    }
    let rim = old_of.iter().map(|&v| dist[v as usize] >= rings).collect();
    (kept, old_of, rim)
}

/// Split every vertex `splittable` says may be (on a cut's rim, which can pinch) whose faces form
/// several fans into one vertex per fan, so the configuration mesh is a manifold. Returns the
/// original of each vertex added (numbered from the old `count` on).
fn split_fans(
    faces: &mut [[u32; 3]],
    count: &mut usize,
    splittable: impl Fn(u32) -> bool,
) -> Vec<u32> {
    let mut at: Vec<Vec<usize>> = vec![Vec::new(); *count];
    for (f, t) in faces.iter().enumerate() {
        for &v in t {
            at[v as usize].push(f);
        }
    }
    let mut origin = Vec::new();
    for (v, fs) in at.iter().enumerate() {
        if fs.len() < 2 || !splittable(v as u32) {
            continue;
        }
        // Union faces that share an edge at v.
        let mut parent: Vec<usize> = (0..fs.len()).collect();
        fn find(p: &mut [usize], i: usize) -> usize {
            let mut i = i;
            while p[i] != i {
                p[i] = p[p[i]];
                i = p[i];
            }
            i
        }
        let others = |f: usize| {
            let t = faces[f];
            let k = t.iter().position(|&x| x == v as u32).unwrap();
            [t[(k + 1) % 3], t[(k + 2) % 3]]
        };
        for a in 0..fs.len() {
            for b in a + 1..fs.len() {
                let (oa, ob) = (others(fs[a]), others(fs[b]));
                if oa.iter().any(|x| ob.contains(x)) {
                    let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
                    parent[ra] = rb;
                }
            }
        }
        let mut fan_label: HashMap<usize, u32> = HashMap::new();
        let fs = fs.clone();
        for (i, &f) in fs.iter().enumerate() {
            let root = find(&mut parent, i);
            let first = fan_label.is_empty();
            let l = *fan_label.entry(root).or_insert_with(|| {
                if first {
                    v as u32
                } else {
                    origin.push(v as u32);
                    *count += 1;
                    (*count - 1) as u32
                }
            });
            for x in faces[f].iter_mut() {
                if *x == v as u32 {
                    *x = l;
                }
            }
        }
    }
    origin
}
