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

use super::{limit_stencil, refined_faces, stencils, Boundary, Topology, TopologyError};
use std::collections::HashMap;

/// The tables' default level: 2^5 = 32 segments per M1-face edge (`--bft-level`).
pub const DEFAULT_LMAX: u32 = 5;
/// The highest level offered: 2^7 = 128 segments, 8,385 rows a table.
pub const MAX_LMAX: u32 = 7;

/// The tables' lattice: 2^lmax segments per M1-face edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Lattice {
    pub lmax: u32,
}

impl Default for Lattice {
    fn default() -> Self {
        Self { lmax: DEFAULT_LMAX }
    }
}

impl Lattice {
    pub fn new(lmax: u32) -> Self {
        assert!(
            (1..=MAX_LMAX).contains(&lmax),
            "lmax {lmax} out of 1..={MAX_LMAX}"
        );
        Self { lmax }
    }

    /// Segments per M1-face edge.
    pub fn segments(self) -> u32 {
        1 << self.lmax
    }

    /// Lattice points per face: (S + 1)(S + 2) / 2.
    pub fn rows(self) -> usize {
        let s = self.segments() as usize;
        (s + 1) * (s + 2) / 2
    }

    /// The row of lattice point (i, j): weight i/S on the face's canonical corner 1, j/S on
    /// corner 2. Mirror of `bft_row` in glsl/include/loop.glsl.
    pub fn row(self, i: u32, j: u32) -> usize {
        debug_assert!(i + j <= self.segments());
        let s = self.segments() + 1;
        (j * s - j * (j.saturating_sub(1)) / 2 + i) as usize
    }
}

/// A table: the limit-position weights of a configuration (of every configuration that shares it).
#[derive(Clone, Debug)]
pub struct Config {
    /// Control points: the columns of `weights` (built as labels 0 .. control, the face's
    /// corners first; [`build`] then keeps only the labels some row weighs, in the order
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
    /// then the columns it fixes, so that [`pack`] stores only the rows on one side of the axis
    /// and reads the others as their mirror images with each pair's weights swapped.
    pub symmetry: Option<u8>,
    /// With a `symmetry`, columns 2m and 2m + 1 for m < `pairs` are the pairs it swaps, and the
    /// columns after them those it fixes.
    pub pairs: usize,
}

/// How a face's stored corners map to its configuration's canonical corners: canonical corner i
/// is stored corner `rot + i` (mod 3), or `rot - i` when the face is the configuration's mirror
/// image (its table is the mirror's, read with u and v swapped).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Orient {
    pub rot: u8,
    pub mirror: bool,
}

impl Orient {
    /// The stored corner that is canonical corner `i`. Mirror of `loop_stored` in loop.glsl.
    pub fn stored(self, i: usize) -> usize {
        let r = self.rot as usize;
        if self.mirror {
            (r + 3 - i) % 3
        } else {
            (r + i) % 3
        }
    }

    /// The canonical corner stored corner `k` is.
    pub fn canonical(self, k: usize) -> usize {
        (0..3).find(|&i| self.stored(i) == k).unwrap()
    }

    /// All six.
    pub fn all() -> impl Iterator<Item = Orient> {
        [false, true]
            .into_iter()
            .flat_map(|mirror| (0..3).map(move |rot| Orient { rot, mirror }))
    }

    /// As the GPU's face entry stores it: rotation in bits 0-1, mirror in bit 2.
    pub fn bits(self) -> u32 {
        self.rot as u32 | (self.mirror as u32) << 2
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
}

impl Tables {
    /// Bytes of the tables as stored on the GPU.
    pub fn bytes(&self) -> u64 {
        self.packed.bytes()
    }
}

/// Tables as the drawing stages read them: distinct rows stored once in `pool`, and for every
/// table a map from its rows to theirs. Two tables share a row where their faces' neighbourhoods
/// agree as far as that lattice point reaches (a boundary fan's faces far from its extraordinary
/// vertex, whatever the fan's width), and a symmetric table ([`Config::symmetry`]) reads the rows
/// on one side of its axis as its own with every column pair swapped.
#[derive(Clone, Debug, Default)]
pub struct Packed {
    /// The distinct rows, f32, each padded with zeros to the longest (multiple of four) of the
    /// tables that read it, so every row starts at a multiple of four.
    pub pool: Vec<f32>,
    /// Table t's row r at `t * rows + r`: the row's first weight in `pool` over four, times
    /// two, plus one where the row is read as its mirror image ([`ROW_SWAPPED`]).
    pub rows: Vec<u32>,
}

/// Bit 0 of a [`Packed::rows`] entry: the row is the mirror image of the stored one, read with
/// the weights of columns 2m and 2m + 1 swapped for m < [`Config::pairs`] (a symmetric table's
/// row across its axis).
pub const ROW_SWAPPED: u32 = 1;

impl Packed {
    /// Bytes on the GPU: the pool and the row maps.
    pub fn bytes(&self) -> u64 {
        (self.pool.len() + self.rows.len()) as u64 * 4
    }

    /// Entry `i` of [`Packed::rows`] (table t's row r is `t * rows + r`): where its weights
    /// start in `pool`, and whether it is read as its mirror image.
    pub fn entry(&self, i: usize) -> (usize, bool) {
        let e = self.rows[i];
        ((e >> 1) as usize * 4, e & ROW_SWAPPED != 0)
    }

    /// Weight `c` of a row at `entry` of a table with `pairs` column pairs, as the GPU reads
    /// it. Mirror of `bft_weights` in loop.glsl.
    pub fn weight(&self, (at, swapped): (usize, bool), c: usize, pairs: usize) -> f32 {
        self.pool[at + if swapped && c < 2 * pairs { c ^ 1 } else { c }]
    }
}

/// Faces incident to each vertex.
fn vertex_faces(topo: &Topology) -> Vec<Vec<u32>> {
    let mut vf = vec![Vec::new(); topo.vertex_count];
    for (f, t) in topo.faces.iter().enumerate() {
        for &v in t {
            vf[v as usize].push(f as u32);
        }
    }
    vf
}

/// What classification reads of M1 again and again: the faces at each vertex and each vertex's
/// one-ring (counter-clockwise, with its boundary flag).
struct Neighbourhoods {
    faces: Vec<Vec<u32>>,
    rings: Vec<(Vec<u32>, bool)>,
}

impl Neighbourhoods {
    fn new(topo: &Topology) -> Self {
        Self {
            faces: vertex_faces(topo),
            rings: (0..topo.vertex_count as u32)
                .map(|v| topo.one_ring(v))
                .collect(),
        }
    }
}

/// A labelling in progress: the vertices in label order, and the label of every M1 vertex
/// (`u32::MAX` for none). Reused face after face: [`Labels::clear`] resets only what was set.
struct Labels {
    of: Vec<u32>,
    order: Vec<u32>,
}

impl Labels {
    fn new(vertex_count: usize) -> Self {
        Self {
            of: vec![u32::MAX; vertex_count],
            order: Vec::new(),
        }
    }

    /// Labels `v` next unless it has a label.
    fn add(&mut self, v: u32) {
        if self.of[v as usize] == u32::MAX {
            self.of[v as usize] = self.order.len() as u32;
            self.order.push(v);
        }
    }

    fn of(&self, v: u32) -> u32 {
        self.of[v as usize]
    }

    fn clear(&mut self) {
        for &v in &self.order {
            self.of[v as usize] = u32::MAX;
        }
        self.order.clear();
    }
}

/// Canonical labelling of face `f` in orientation `o` into `labels` (cleared first): the corners,
/// then each corner's one-ring (counter-clockwise, or clockwise for the mirror image, from the
/// next canonical corner).
fn label(topo: &Topology, nb: &Neighbourhoods, f: usize, o: Orient, labels: &mut Labels) {
    labels.clear();
    let t = topo.faces[f];
    let corners = [0, 1, 2].map(|i| t[o.stored(i)]);
    for &c in &corners {
        labels.add(c);
    }
    for k in 0..3 {
        let (ring, on_boundary) = &nb.rings[corners[k] as usize];
        let n = ring.len();
        // The ring as walked: reversed for the mirror image, and (inside) started at the face's
        // next corner, a neighbour since the face is (c_k, c_k+1, ...).
        let at = |i: usize| if o.mirror { ring[n - 1 - i] } else { ring[i] };
        let next = corners[(k + 1) % 3];
        let start = if *on_boundary {
            0
        } else {
            (0..n).find(|&i| at(i) == next).unwrap_or(0)
        };
        for i in 0..n {
            labels.add(at((start + i) % n));
        }
    }
}

/// How well orientation `o` of face `f` frames it, smaller first: canonical corner 0 is its
/// extraordinary vertex where it has one (else a boundary vertex, else any), and where that
/// corner is on the boundary, canonical corner 1 is on the side of its fan's nearer end.
/// Topological, so alike configurations take alike frames: the rows of two tables for faces
/// whose neighbourhoods agree near the face (a boundary fan's middle faces, whatever the fan's
/// width) then agree far from corner 0, and [`pack`] stores them once.
fn frame(topo: &Topology, nb: &Neighbourhoods, f: usize, o: Orient) -> (u8, usize) {
    let t = topo.faces[f];
    let (c0, c1) = (t[o.stored(0)], t[o.stored(1)]);
    let (ring, on_boundary) = &nb.rings[c0 as usize];
    let class = match (*on_boundary, ring.len()) {
        (false, 6) => 2,
        (true, 4) => 1,
        _ => 0,
    };
    if !on_boundary {
        return (class, 0);
    }
    // The ring as `label` walks it: from the boundary, reversed for the mirror image.
    let n = ring.len();
    let at = |i: usize| if o.mirror { ring[n - 1 - i] } else { ring[i] };
    (class, (0..n).find(|&i| at(i) == c1).unwrap_or(n))
}

/// A face's key in labels (reversed for a mirror image): rotated to start at its smallest label.
fn labelled(t: &[u32; 3], labels: &Labels, mirror: bool) -> [u32; 3] {
    let mut l = t.map(|v| labels.of(v));
    if mirror {
        l.swap(1, 2);
    }
    let m = (0..3).min_by_key(|&k| l[k]).unwrap();
    [l[m], l[(m + 1) % 3], l[(m + 2) % 3]]
}

/// The key of face `f` in orientation `o`, its labels left in `labels`.
fn key_of(
    topo: &Topology,
    nb: &Neighbourhoods,
    f: usize,
    o: Orient,
    labels: &mut Labels,
) -> Vec<[u32; 3]> {
    label(topo, nb, f, o, labels);
    let mut faces: Vec<u32> = labels.order[..3]
        .iter()
        .flat_map(|&c| nb.faces[c as usize].iter().copied())
        .collect();
    faces.sort_unstable();
    faces.dedup();
    let mut key: Vec<[u32; 3]> = faces
        .iter()
        .map(|&g| labelled(&topo.faces[g as usize], labels, o.mirror))
        .collect();
    key.sort_unstable();
    key
}

/// An orientation's [`frame`] rank and key: the smallest is the face's canonical orientation.
type Framed = ((u8, usize), Vec<[u32; 3]>);

/// One thread's share of the faces, classified: its distinct keys in order of first appearance
/// (with the face and orientation that showed each first), and every face's key (an index into
/// those), orientation and control points.
struct Classified {
    keys: Vec<(Vec<[u32; 3]>, usize, Orient)>,
    faces: Vec<(u32, Orient, Vec<u32>)>,
}

/// Classifies `range`'s faces; every 1,024 faces adds them to `done` and calls `tick`.
fn classify(
    topo: &Topology,
    nb: &Neighbourhoods,
    range: std::ops::Range<usize>,
    done: &std::sync::atomic::AtomicUsize,
    tick: &mut dyn FnMut(),
) -> Classified {
    let mut labels = Labels::new(topo.vertex_count);
    let mut ids: HashMap<Vec<[u32; 3]>, u32> = HashMap::new();
    let mut out = Classified {
        keys: Vec::new(),
        faces: Vec::with_capacity(range.len()),
    };
    for (i, f) in range.enumerate() {
        if i % 1024 == 1023 {
            done.fetch_add(1024, std::sync::atomic::Ordering::Relaxed);
            tick();
        }
        // The smallest (frame, key) over the three rotations and the mirror image: a
        // configuration and its mirror share one table, and faces alike near their
        // extraordinary vertex are in the same frame ([`frame`]).
        let mut best: Option<(Framed, Orient, Vec<u32>)> = None;
        for o in Orient::all() {
            let framed = (frame(topo, nb, f, o), key_of(topo, nb, f, o, &mut labels));
            if best.as_ref().is_none_or(|b| framed < b.0) {
                best = Some((framed, o, labels.order.clone()));
            }
        }
        let ((_, key), orient, order) = best.expect("six orientations");
        let next = out.keys.len() as u32;
        let id = *ids.entry(key).or_insert_with_key(|key| {
            out.keys.push((key.clone(), f, orient));
            next
        });
        out.faces.push((id, orient, order));
    }
    out
}

/// How far [`build`] is: faces classified, then tables built (done, total).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    Faces(usize, usize),
    Tables(usize, usize),
}

impl std::fmt::Display for Progress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Progress::Faces(d, t) => write!(f, "{d} of {t} M1 faces classified"),
            Progress::Tables(d, t) => write!(f, "{d} of {t} basis function tables built"),
        }
    }
}

/// `report` behind a throttle, for [`build`]'s `progress`: quiet in the first second (most builds
/// take less), then at most one report a second, and the last one (every table built) when it
/// has reported anything.
pub fn throttled(mut report: impl FnMut(Progress)) -> impl FnMut(Progress) {
    let start = std::time::Instant::now();
    let second = std::time::Duration::from_secs(1);
    let mut last: Option<(std::time::Instant, Progress)> = None;
    move |p| {
        let now = std::time::Instant::now();
        let finished = matches!(p, Progress::Tables(d, t) if d == t);
        let due = match last {
            None => now - start >= second,
            Some((at, prev)) => prev != p && (finished || now - at >= second),
        };
        if due {
            last = Some((now, p));
            report(p);
        }
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

/// [`build`] with faces classified on `threads` threads and tables built on up to `cores`.
fn build_on(
    topo: &Topology,
    boundary: Boundary,
    lattice: Lattice,
    mut progress: impl FnMut(Progress),
    threads: usize,
    cores: usize,
) -> Result<Tables, TopologyError> {
    let nb = Neighbourhoods::new(topo);
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
                let (nb, done) = (&nb, &done);
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
        let first = classify(topo, &nb, ranges[0].clone(), &done, &mut report);
        std::iter::once(first)
            .chain(
                others
                    .into_iter()
                    .map(|h| h.join().expect("classification thread")),
            )
            .collect()
    });
    progress(Progress::Faces(n, n));
    let mut ids: HashMap<Vec<[u32; 3]>, u32> = HashMap::new();
    // The representative face and orientation of each configuration.
    let mut reps: Vec<(usize, Orient, Vec<[u32; 3]>)> = Vec::new();
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
    let total = reps.len();
    let keys: Vec<Vec<[u32; 3]>> = reps.iter().map(|r| r.2.clone()).collect();
    // Tables too are independent: thread t builds configurations t, t + T, t + 2T, ...
    let builders = cores.min(total).max(1);
    let done = std::sync::atomic::AtomicUsize::new(0);
    let build_share = |t: usize, tick: &mut dyn FnMut()| {
        let mut labels = Labels::new(topo.vertex_count);
        let mut out = Vec::new();
        for (i, (f, orient, _)) in reps.iter().enumerate().skip(t).step_by(builders) {
            out.push((
                i,
                table(topo, &nb, &mut labels, *f, *orient, boundary, lattice),
            ));
            done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            tick();
        }
        out
    };
    progress(Progress::Tables(0, total));
    let mut built: Vec<(usize, Result<Config, TopologyError>)> = std::thread::scope(|s| {
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
        .collect::<Result<Vec<Config>, TopologyError>>()?;
    progress(Progress::Tables(total, total));
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
    Ok(Tables {
        lattice,
        keys,
        configs,
        faces,
        packed,
    })
}

/// A weight rounded to a multiple of 1 / TABLE_EQUAL: equal tables, built on different
/// configuration meshes, round alike.
pub fn rounded(w: f64) -> i64 {
    (w * TABLE_EQUAL).round() as i64
}

/// The lattice reflection that fixes canonical corner `a`: it swaps the other two corners'
/// weights. Row r's mirror image, for every row.
fn reflection(lattice: Lattice, a: u8) -> Vec<usize> {
    let s = lattice.segments();
    let mut image = vec![0; lattice.rows()];
    for j in 0..=s {
        for i in 0..=s - j {
            let k = s - i - j;
            let (x, y) = match a {
                0 => (j, i),
                1 => (i, k),
                _ => (k, j),
            };
            image[lattice.row(i, j)] = lattice.row(x, y);
        }
    }
    image
}

/// Puts `c`'s columns in an order that depends only on their weights, so that two tables whose
/// rows agree far from canonical corner 0 order the columns weighing there alike and [`pack`]
/// can share those rows: by their weights at the lattice points from the edge opposite corner
/// 0 inwards, larger first, a column that weighs nothing there after those that do. Where the
/// table is its own mirror image under a reflection (found from the weights: every column
/// reflected is another column), the columns come in the pairs it swaps instead
/// ([`Config::symmetry`]). Rewrites `c` and returns its new columns as indices of its old.
fn arrange(c: &mut Config, lattice: Lattice) -> Vec<usize> {
    let (rows, k) = (lattice.rows(), c.control);
    // Far from corner 0 first: the rows by decreasing i + j, then by i.
    let s = lattice.segments();
    let mut far: Vec<usize> = Vec::with_capacity(rows);
    for d in (0..=s).rev() {
        for i in (0..=d).rev() {
            far.push(lattice.row(i, d - i));
        }
    }
    // Larger weights first (negated), so a column weighing nothing there comes after.
    let keys: Vec<Vec<i64>> = (0..k)
        .map(|j| {
            far.iter()
                .map(|&r| -rounded(c.weights[r * k + j]))
                .collect()
        })
        .collect();
    let mut order: Vec<usize> = (0..k).collect();
    order.sort_by(|&a, &b| keys[a].cmp(&keys[b]).then(a.cmp(&b)));
    // A reflection under which every column is another column's mirror image, to 1e-12 of
    // each weight (the two are summed in different orders, every term non-negative; a far
    // column's weights are as small as 1e-13).
    let w = &c.weights;
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs());
    // Only inside faces fold: a boundary face's far rows are shared with its neighbours'
    // tables, which the pairs' order would lose (for every configuration to valence 18,
    // folding the boundary's symmetric tables too takes 0.82 MiB instead of 0.77).
    let symmetric = (0..3u8).filter(|_| !c.boundary).find_map(|a| {
        let image = reflection(lattice, a);
        let mirrors =
            |j: usize, d: usize| (0..rows).all(|r| same(w[image[r] * k + j], w[r * k + d]));
        // Paired greedily: columns can be equal (the far ring of a high valence vertex, reached
        // only through the vertex's own rule), and any of equal columns will do.
        let mut sigma = vec![usize::MAX; k];
        for j in 0..k {
            if sigma[j] == usize::MAX {
                let d = (j + 1..k)
                    .chain([j])
                    .find(|&d| sigma[d] == usize::MAX && mirrors(j, d))?;
                sigma[j] = d;
                sigma[d] = j;
            }
        }
        // The reflection is an involution, so d mirrors j exactly when j mirrors d.
        (0..k).all(|j| mirrors(sigma[j], j)).then_some((a, sigma))
    });
    let (layout, pairs) = match &symmetric {
        None => (order, 0),
        Some((_, sigma)) => {
            // The pairs (j, σj) in the order of their first column, then the fixed columns.
            let mut layout: Vec<usize> = Vec::with_capacity(k);
            for &j in &order {
                if sigma[j] != j && !layout.contains(&j) {
                    layout.extend([j, sigma[j]]);
                }
            }
            let pairs = layout.len() / 2;
            layout.extend(order.iter().filter(|&&j| sigma[j] == j));
            (layout, pairs)
        }
    };
    c.weights = (0..rows)
        .flat_map(|r| layout.iter().map(move |&j| r * k + j))
        .map(|i| c.weights[i])
        .collect();
    c.symmetry = symmetric.map(|(a, _)| a);
    c.pairs = pairs;
    layout
}

/// Stores `tables` as the GPU reads them ([`Packed`]): every row once, rows with the same
/// weights (as f32, trailing zeros aside) shared among tables, a symmetric table's rows across
/// its axis read as their mirror images with the column pairs swapped.
pub fn pack(tables: &[&Config], lattice: Lattice) -> Packed {
    let rows = lattice.rows();
    let images: Vec<Vec<usize>> = (0..3u8).map(|a| reflection(lattice, a)).collect();
    // The distinct rows (f32 bits, trailing zeros trimmed) and the longest table reading each.
    let mut ids: HashMap<Vec<u32>, usize> = HashMap::new();
    let mut distinct: Vec<(Vec<u32>, usize)> = Vec::new();
    // Per table row: (distinct row, swapped).
    let mut refs: Vec<(usize, bool)> = Vec::with_capacity(tables.len() * rows);
    for (t, c) in tables.iter().enumerate() {
        let k = c.control;
        let image = c.symmetry.map(|a| &images[a as usize]);
        for r in 0..rows {
            if let Some(image) = image {
                if image[r] < r {
                    let (id, _) = refs[t * rows + image[r]];
                    refs.push((id, true));
                    continue;
                }
            }
            let mut bits: Vec<u32> = c.weights[r * k..(r + 1) * k]
                .iter()
                .map(|&w| (w as f32).to_bits())
                .collect();
            while bits.last() == Some(&0) {
                bits.pop();
            }
            let next = distinct.len();
            let id = *ids.entry(bits).or_insert_with_key(|bits| {
                distinct.push((bits.clone(), 0));
                next
            });
            distinct[id].1 = distinct[id].1.max(k.next_multiple_of(4));
            refs.push((id, false));
        }
    }
    let mut first = Vec::with_capacity(distinct.len());
    let mut pool = Vec::new();
    for (bits, len) in &distinct {
        first.push(pool.len());
        pool.extend(bits.iter().map(|&b| f32::from_bits(b)));
        pool.resize(first.last().unwrap() + len, 0.0);
    }
    let rows = refs
        .iter()
        .map(|&(id, swapped)| (first[id] / 4) as u32 * 2 + swapped as u32)
        .collect();
    Packed { pool, rows }
}

/// Drops the columns no row weighs (a boundary vertex's fan beyond the face's reach: its rule
/// does not mix the sectors of its fan, so over `lmax` steps a sector reaches only a few
/// sectors on), then lets configurations whose remaining tables are equal share one (their
/// topology differs only where the face does not reach). Dropping a column changes no sum: its
/// terms were zero weights, and the others keep their order. Returns the tables and, per
/// configuration, its table and kept columns.
/// Tables whose weights round to the same multiples of 1 / TABLE_EQUAL are shared.
const TABLE_EQUAL: f64 = (1u64 << 40) as f64;

fn compact(built: Vec<Config>, lattice: Lattice) -> (Vec<Config>, Vec<(u32, Vec<usize>)>) {
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

/// The table of face `f` in orientation `o`, from its two-ring configuration mesh.
fn table(
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
    // The lattice vertex at each row, then its limit mask.
    let rows = lattice.rows();
    let mut at_row = vec![u32::MAX; rows];
    for &(face, coords) in &tracked {
        for k in 0..3 {
            at_row[lattice.row(coords[k][0], coords[k][1])] = topo_l.faces[face][k];
        }
    }
    let mut weights = vec![0.0; rows * control];
    let mut outside: f64 = 0.0;
    for (r, &v) in at_row.iter().enumerate() {
        debug_assert_ne!(v, u32::MAX);
        let mask = limit_stencil(&topo_l, v, boundary);
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
    // Valence and boundary of the face's corners.
    let corners = [0, 1, 2].map(|i| t[o.stored(i)]);
    let rings = corners.map(|c| topo.one_ring(c));
    let is_boundary = rings.iter().any(|r| r.1);
    let valence = rings
        .iter()
        .map(|(ring, b)| (ring.len(), *b))
        .find(|&(n, b)| n != if b { 4 } else { 6 })
        .map_or(rings[0].0.len(), |(n, _)| n);
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

/// Lattice coordinates (units of 1/S) of a face's stored corners in orientation `o`.
pub fn lattice_corners(o: Orient, lattice: Lattice) -> [[u32; 2]; 3] {
    let s = lattice.segments();
    let base = [[0, 0], [s, 0], [0, s]];
    [0, 1, 2].map(|k| base[o.canonical(k)])
}

/// Faces with their corners' lattice coordinates, after one more step: each face's four
/// children (numbered as [`super::loop_step`] does, `4f + k`) with the midpoints.
pub fn children_in_lattice(faces: &[(usize, [[u32; 2]; 3])]) -> Vec<(usize, [[u32; 2]; 3])> {
    let mid = |a: [u32; 2], b: [u32; 2]| [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
    faces
        .iter()
        .flat_map(|&(face, [a, b, c])| {
            let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
            [
                (4 * face, [a, ab, ca]),
                (4 * face + 1, [b, bc, ab]),
                (4 * face + 2, [c, ca, bc]),
                (4 * face + 3, [ab, bc, ca]),
            ]
        })
        .collect()
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
    use crate::mesh::test_support::load_model;
    use crate::subdiv::{loop_step, subdivide_to_limit};
    use glam::DVec3;

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
            let lattice = Lattice::new(lmax);
            for &boundary in boundaries {
                let topo0 = Topology::of_mesh(&mesh).unwrap();
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
                let reference = subdivide_to_limit(&mesh, 1 + lmax, boundary).unwrap();
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
                            .map(|k| {
                                m1.positions[fc.control[k] as usize] * c.weights[r * c.control + k]
                            })
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
            }
        }
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
        let (keys, union) = crate::bench::every_configuration(18, Boundary::EdgeOnly, lattice);
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

    /// Reports wait a second, then come at most once a second, and never twice the same.
    #[test]
    fn progress_is_throttled() {
        let mut heard = Vec::new();
        {
            let mut p = throttled(|p| heard.push(p));
            p(Progress::Faces(0, 10));
            std::thread::sleep(std::time::Duration::from_millis(1050));
            p(Progress::Faces(5, 10));
            p(Progress::Faces(6, 10));
            p(Progress::Tables(2, 2));
            p(Progress::Tables(2, 2));
        }
        assert_eq!(heard, [Progress::Faces(5, 10), Progress::Tables(2, 2)]);
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
