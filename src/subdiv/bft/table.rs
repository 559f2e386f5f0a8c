//! One table: the limit-position weights of a configuration at every lattice point, computed on
//! the paper's configuration mesh (the faces within two rings of the face, cut out, fans split
//! where the cut pinches), `lmax` Loop steps applied to the weights and the limit masks at the
//! lattice points; then [`compact`] drops the columns no row weighs and lets equal tables be one.
#![forbid(unsafe_code)]

use super::classification::{label, Labels, Neighbourhoods};
use super::{children_in_lattice, lattice_corners, Lattice, Orient, RING_REACH};
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
/// refined `lmax` times carrying the weights, limit masks at the lattice points. Returns the
/// table and the weights its refinement computed (the build's work, linear in the valence).
pub(super) fn table(
    topo: &Topology,
    nb: &Neighbourhoods,
    labels: &mut Labels,
    f: usize,
    o: Orient,
    boundary: Boundary,
    lattice: Lattice,
) -> Result<(Config, u64), TopologyError> {
    table_reaching(topo, nb, labels, f, o, boundary, lattice, RING_REACH)
}

/// [`table`], with the ring vertices more than `reach` places from the face sharing a column.
#[allow(clippy::too_many_arguments)]
fn table_reaching(
    topo: &Topology,
    nb: &Neighbourhoods,
    labels: &mut Labels,
    f: usize,
    o: Orient,
    boundary: Boundary,
    lattice: Lattice,
    reach: usize,
) -> Result<(Config, u64), TopologyError> {
    label(topo, nb, f, o, labels);
    let control = labels.order.len();
    let (local, count) = configuration_mesh(topo, nb, labels, f, control);
    let far = far_ring(topo, nb, f, o, labels, control, &local, count, reach);
    // Columns: the control points not far, one for the far ring together, one for the other
    // cut-out vertices together.
    let mut column = vec![0u32; control];
    let mut near = 0;
    for (l, c) in column.iter_mut().enumerate() {
        if !far[l] {
            *c = near;
            near += 1;
        }
    }
    let (far_column, outside_column) = (near, near + 1);
    let far_count = control - near as usize;
    for (l, c) in column.iter_mut().enumerate() {
        if far[l] {
            *c = far_column;
        }
    }
    let dims = near as usize + 2;
    let (mesh, work) = refine_weights(
        local,
        count,
        dims,
        |v| column.get(v).copied().unwrap_or(outside_column),
        o,
        boundary,
        lattice,
    )?;
    let dense = limit_rows(&mesh, dims, boundary, lattice);
    // Each far vertex weighs the same (see `far_ring`): the far column's weight over their count.
    let (far, column) = (&far, &column);
    let weights = (0..lattice.rows())
        .flat_map(|r| {
            let row = &dense[r * dims..(r + 1) * dims];
            column.iter().enumerate().map(move |(l, &c)| {
                if far[l] {
                    row[c as usize] / far_count as f64
                } else {
                    row[c as usize]
                }
            })
        })
        .collect();
    let outside = (0..lattice.rows())
        .map(|r| dense[r * dims + outside_column as usize].abs())
        .fold(0.0, f64::max);
    let (valence, is_boundary) = corner_valence(topo, topo.faces[f], o);
    Ok((
        Config {
            control,
            valence,
            boundary: is_boundary,
            weights,
            outside,
            symmetry: None,
            pairs: 0,
        },
        work,
    ))
}

/// Which of the control points of face `f` in orientation `o` (labels 0 .. `control`) are far
/// round its corner 0's ring, where that corner is inside: more than `reach` edges of its
/// configuration mesh (`local`, over `count` vertices) from the face's other corners by paths
/// that avoid corner 0. Every rule treats the ring's vertices alike (the vertex rule and limit
/// mask weigh their sum, a spoke's edge point its two neighbours on the ring), and a far vertex
/// reaches the face only through corner 0's rules, so the far vertices' weights are equal in
/// every row: they can share one column, which makes a table's work linear in the valence.
#[allow(clippy::too_many_arguments)]
fn far_ring(
    topo: &Topology,
    nb: &Neighbourhoods,
    f: usize,
    o: Orient,
    labels: &Labels,
    control: usize,
    local: &[[u32; 3]],
    count: usize,
    reach: usize,
) -> Vec<bool> {
    let mut far = vec![false; control];
    let c0 = topo.faces[f][o.stored(0)];
    let (ring, on_boundary) = &nb.rings[c0 as usize];
    if *on_boundary || ring.len() <= 2 * reach + 2 {
        return far;
    }
    // Breadth first from corners 1 and 2 (labels 1 and 2), never through corner 0 (label 0).
    let mut adjacent: Vec<Vec<u32>> = vec![Vec::new(); count];
    for t in local {
        for k in 0..3 {
            adjacent[t[k] as usize].push(t[(k + 1) % 3]);
            adjacent[t[(k + 1) % 3] as usize].push(t[k]);
        }
    }
    let mut near = vec![false; count];
    let mut frontier: Vec<u32> = vec![1, 2];
    near[1] = true;
    near[2] = true;
    for _ in 0..reach {
        let mut next = Vec::new();
        for &v in &frontier {
            for &u in &adjacent[v as usize] {
                if u != 0 && !std::mem::replace(&mut near[u as usize], true) {
                    next.push(u);
                }
            }
        }
        frontier = next;
    }
    for &v in ring {
        let l = labels.of(v) as usize;
        far[l] = !near[l];
    }
    far
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

/// A configuration mesh after `lmax` Loop steps: its topology, every vertex's weights (sparse:
/// the columns it weighs), and the lattice coordinates of the faces that tile the face.
struct Refined {
    topo: Topology,
    w: Sparse,
    tracked: Vec<(usize, [[u32; 2]; 3])>,
}

/// Every vertex's weights, sparse: vertex v weighs `col[start[v]..start[v + 1]]` (ascending)
/// with `val[..]`. A column a vertex does not list it weighs exactly zero.
#[derive(Default)]
struct Sparse {
    start: Vec<usize>,
    col: Vec<u32>,
    val: Vec<f64>,
}

impl Sparse {
    fn row(&self, v: usize) -> (&[u32], &[f64]) {
        let (a, b) = (self.start[v], self.start[v + 1]);
        (&self.col[a..b], &self.val[a..b])
    }

    /// `rows` of `self`, in that order.
    fn gather(&self, rows: impl Iterator<Item = usize>) -> Sparse {
        let mut out = Sparse {
            start: vec![0],
            ..Sparse::default()
        };
        for v in rows {
            let (c, x) = self.row(v);
            out.col.extend_from_slice(c);
            out.val.extend_from_slice(x);
            out.start.push(out.col.len());
        }
        out
    }
}

/// Sums of weighted sparse rows over `dims` columns, each column's terms added in the parents'
/// order: a column a parent does not list adds its exact zero, which changes no non-negative
/// sum, so every weight has the same bits as the dense sum over all columns.
struct Accumulator {
    acc: Vec<f64>,
    seen: Vec<bool>,
    touched: Vec<u32>,
}

impl Accumulator {
    fn new(dims: usize) -> Self {
        Self {
            acc: vec![0.0; dims],
            seen: vec![false; dims],
            touched: Vec::new(),
        }
    }

    /// `Σ weights[i] · w[parents[i]]`, appended to `out` as its next row.
    fn push(&mut self, parents: &[u32], weights: &[f64], w: &Sparse, out: &mut Sparse) {
        for (&p, &wt) in parents.iter().zip(weights) {
            let (cols, xs) = w.row(p as usize);
            for (&c, &x) in cols.iter().zip(xs) {
                let c = c as usize;
                if !self.seen[c] {
                    self.seen[c] = true;
                    self.touched.push(c as u32);
                    self.acc[c] = 0.0;
                }
                self.acc[c] += wt * x;
            }
        }
        self.touched.sort_unstable();
        for &c in &self.touched {
            out.col.push(c);
            out.val.push(self.acc[c as usize]);
            self.seen[c as usize] = false;
        }
        self.touched.clear();
        out.start.push(out.col.len());
    }
}

/// `lmax` Loop steps on the configuration mesh `local` (over `count` vertices), applied to the
/// weights and pruned to the face's surroundings after each. Vertex v starts with weight one on
/// column `column(v)`. Returns the refined mesh and the weights computed (for [`Config::work`]).
fn refine_weights(
    local: Vec<[u32; 3]>,
    mut count: usize,
    dims: usize,
    column: impl Fn(usize) -> u32,
    o: Orient,
    boundary: Boundary,
    lattice: Lattice,
) -> Result<(Refined, u64), TopologyError> {
    // Every rule and limit mask weighs with non-negative weights, so a column shared by several
    // vertices (the other cut-out vertices together, or a far ring's vertices) is zero exactly
    // when each of theirs is, and the other columns are the same bits as with a column each.
    let mut w = Sparse {
        start: (0..=count).collect(),
        col: (0..count).map(&column).collect(),
        val: vec![1.0; count],
    };
    let mut acc = Accumulator::new(dims);
    let mut work = 0u64;
    let mut topo_l = Topology::new(&local, count)?;
    // Lattice coordinates (in units of 1/S) of the tracked faces' corners; the face's stored
    // corner k is canonical corner `o.canonical(k)`.
    let mut tracked: Vec<(usize, [[u32; 2]; 3])> = vec![(0, lattice_corners(o, lattice))];
    for _ in 0..lattice.lmax {
        let st = stencils(&topo_l, boundary);
        let mut next = Sparse {
            start: vec![0],
            ..Sparse::default()
        };
        for sv in &st {
            debug_assert!(sv.weights.iter().all(|&x| x >= 0.0), "negative rule weight");
            acc.push(&sv.parents, &sv.weights, &w, &mut next);
        }
        work += next.col.len() as u64;
        tracked = children_in_lattice(&tracked);
        // Only what is within PRUNE_RINGS rings of the face goes on (a valence-300 vertex
        // would otherwise make a million-face configuration mesh at the last level); the new
        // rim is subdivided wrongly too, and its error stays beyond the face as the first cut's.
        let (mut faces, old_of, rim) =
            prune(&refined_faces(&topo_l), st.len(), &mut tracked, PRUNE_RINGS);
        count = old_of.len();
        let origin = split_fans(&mut faces, &mut count, |v| rim[v as usize]);
        w = next.gather(
            old_of
                .iter()
                .chain(origin.iter().map(|&o| &old_of[o as usize]))
                .map(|&old| old as usize),
        );
        topo_l = Topology::new(&faces, count)?;
    }
    Ok((
        Refined {
            topo: topo_l,
            w,
            tracked,
        },
        work,
    ))
}

/// The table's rows over the `dims` columns: the limit mask at each lattice point applied to
/// the weights (`rows × dims`, dense).
fn limit_rows(mesh: &Refined, dims: usize, boundary: Boundary, lattice: Lattice) -> Vec<f64> {
    let Refined {
        topo: topo_l,
        w,
        tracked,
    } = mesh;
    // The lattice vertex at each row, then its limit mask.
    let rows = lattice.rows();
    let mut at_row = vec![u32::MAX; rows];
    for &(face, coords) in tracked {
        for k in 0..3 {
            at_row[lattice.row(coords[k][0], coords[k][1])] = topo_l.faces[face][k];
        }
    }
    let mut acc = Accumulator::new(dims);
    let mut weights = vec![0.0; rows * dims];
    for (r, &v) in at_row.iter().enumerate() {
        debug_assert_ne!(v, u32::MAX);
        let mask = limit_stencil(topo_l, v, boundary);
        debug_assert!(
            mask.weights.iter().all(|&x| x >= 0.0),
            "negative limit weight"
        );
        let mut full = Sparse {
            start: vec![0],
            ..Sparse::default()
        };
        acc.push(&mask.parents, &mask.weights, w, &mut full);
        let (cols, xs) = full.row(0);
        for (&c, &x) in cols.iter().zip(xs) {
            weights[r * dims + c as usize] = x;
        }
    }
    weights
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::sphere_mesh;

    /// A valence-60 pole's far ring sharing one column gives the table of a column each: the
    /// far vertices' weights are equal, and every weight agrees to 1e-15.
    #[test]
    fn a_far_ring_in_one_column_is_the_ring_column_by_column() {
        let mesh = sphere_mesh(60, 3);
        let t1 = crate::subdiv::m1_topology(&mesh).unwrap();
        let nb = Neighbourhoods::new(&t1);
        let mut labels = Labels::new(t1.vertex_count);
        // A face at the pole (M0's vertex 0, a vertex point of M1), the pole as corner 0.
        let (f, o) = (0..t1.faces.len())
            .flat_map(|f| Orient::all().map(move |o| (f, o)))
            .find(|&(f, o)| t1.faces[f][o.stored(0)] == 0)
            .unwrap();
        let lattice = Lattice::new(3);
        let build = |labels: &mut Labels, reach| {
            let b = Boundary::EdgeOnly;
            table_reaching(&t1, &nb, labels, f, o, b, lattice, reach).unwrap()
        };
        let (shared, shared_work) = build(&mut labels, RING_REACH);
        let (whole, whole_work) = build(&mut labels, usize::MAX / 4);
        assert_eq!(shared.control, whole.control);
        assert!(shared_work < whole_work, "{shared_work} of {whole_work}");
        label(&t1, &nb, f, o, &mut labels);
        let (local, count) = configuration_mesh(&t1, &nb, &mut labels, f, whole.control);
        let far = far_ring(
            &t1,
            &nb,
            f,
            o,
            &labels,
            whole.control,
            &local,
            count,
            RING_REACH,
        );
        assert!(far.iter().filter(|&&x| x).count() > 10);
        let k = whole.control;
        for r in 0..lattice.rows() {
            let far_weights: Vec<f64> = (0..k)
                .filter(|&j| far[j])
                .map(|j| whole.weights[r * k + j])
                .collect();
            for j in 0..k {
                let (a, b) = (shared.weights[r * k + j], whole.weights[r * k + j]);
                assert!((a - b).abs() <= 1e-15, "row {r} column {j}: {a} for {b}");
            }
            let (lo, hi) = far_weights
                .iter()
                .fold((f64::MAX, 0.0f64), |(l, h), &w| (l.min(w), h.max(w)));
            assert!(hi - lo <= 1e-15, "row {r}: far weights from {lo} to {hi}");
        }
    }
}
