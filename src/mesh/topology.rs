//! Edge and vertex topology statistics ([`MeshStats`]).
//!
//! Edges are keyed by their unordered pair of position indices, so normal seams do not split
//! edges. Definitions:
//! - a *boundary* edge is used by exactly one triangle, a *non-manifold* edge by more than two;
//! - an *inconsistently oriented* edge is an interior edge (two triangles) that both triangles
//!   traverse in the same direction;
//! - a *non-manifold* vertex is one whose incident triangles do not form a single
//!   edge-connected fan (umbrella), or that lies on a non-manifold edge;
//! - the *valence* of a vertex is its number of distinct neighbouring vertices; a vertex is
//!   *interior* when none of its edges is a boundary edge.
//!
//! Only vertices used by at least one triangle are counted.

use std::borrow::Cow;
use std::collections::{BTreeMap, HashMap};

use super::MeshStats;

#[derive(Clone, Copy, Default)]
struct EdgeUse {
    /// Triangles using the edge.
    count: u32,
    /// Of those, how many traverse it from the smaller to the larger index.
    forward: u32,
}

/// Topology statistics of any triangle list over `vertex_count` positions.
///
/// Works on raw index lists too (this is what [`Mesh::stats`](super::Mesh::stats) calls):
/// triangles with an index at or above `vertex_count` are left out (also from the triangle
/// count), and self-loop edges of triangles that repeat an index are skipped. Never panics.
pub fn mesh_stats(vertex_count: usize, tris: &[[u32; 3]]) -> MeshStats {
    let n = vertex_count;
    let tris = in_range(n, tris);
    let edges = edge_uses(&tris);
    let mut stats = MeshStats {
        triangles: tris.len(),
        edges: edges.len(),
        ..MeshStats::default()
    };
    let marks = count_edges(n, &edges, &mut stats);
    let links = Links::new(n, &tris);
    count_vertices(&links, &marks, &mut stats);
    stats
}

/// The triangles whose indices are all below `n` (borrowed when that is all of them).
fn in_range(n: usize, tris: &[[u32; 3]]) -> Cow<'_, [[u32; 3]]> {
    if tris.iter().flatten().all(|&i| (i as usize) < n) {
        Cow::Borrowed(tris)
    } else {
        tris.iter()
            .copied()
            .filter(|t| t.iter().all(|&i| (i as usize) < n))
            .collect()
    }
}

/// How the triangles use each edge (self-loops skipped).
fn edge_uses(tris: &[[u32; 3]]) -> HashMap<(u32, u32), EdgeUse> {
    let mut edges: HashMap<(u32, u32), EdgeUse> = HashMap::with_capacity(tris.len() * 3 / 2);
    for t in tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if a == b {
                continue;
            }
            let e = edges.entry((a.min(b), a.max(b))).or_default();
            e.count += 1;
            e.forward += u32::from(a < b);
        }
    }
    edges
}

/// Which vertices lie on a boundary edge and which on a non-manifold edge.
struct EdgeMarks {
    on_boundary: Vec<bool>,
    on_nonmanifold_edge: Vec<bool>,
}

/// Counts the boundary, inconsistently oriented and non-manifold edges into `stats`, and marks
/// the vertices on them.
fn count_edges(n: usize, edges: &HashMap<(u32, u32), EdgeUse>, stats: &mut MeshStats) -> EdgeMarks {
    let mut on_boundary = vec![false; n];
    let mut on_nonmanifold_edge = vec![false; n];
    for (&(a, b), e) in edges {
        match e.count {
            1 => {
                stats.boundary_edges += 1;
                on_boundary[a as usize] = true;
                on_boundary[b as usize] = true;
            }
            2 if e.forward != 1 => stats.inconsistently_oriented_edges += 1,
            2 => {}
            _ => {
                stats.nonmanifold_edges += 1;
                on_nonmanifold_edge[a as usize] = true;
                on_nonmanifold_edge[b as usize] = true;
            }
        }
    }
    EdgeMarks {
        on_boundary,
        on_nonmanifold_edge,
    }
}

/// The link of each vertex: for every incident triangle, the edge between the two other
/// corners. Stored CSR-style (offsets into one flat array).
struct Links {
    offsets: Vec<usize>,
    links: Vec<(u32, u32)>,
}

impl Links {
    fn new(n: usize, tris: &[[u32; 3]]) -> Self {
        let mut offsets = vec![0usize; n + 1];
        for t in tris {
            for &i in t {
                offsets[i as usize + 1] += 1;
            }
        }
        for i in 0..n {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut links = vec![(0u32, 0u32); offsets[n]];
        for t in tris {
            for k in 0..3 {
                let v = t[k] as usize;
                links[fill[v]] = (t[(k + 1) % 3], t[(k + 2) % 3]);
                fill[v] += 1;
            }
        }
        Self { offsets, links }
    }

    fn of(&self, v: usize) -> &[(u32, u32)] {
        &self.links[self.offsets[v]..self.offsets[v + 1]]
    }
}

/// Counts the used vertices, their valences (all, and interior), the boundary vertices and the
/// non-manifold vertices into `stats`.
fn count_vertices(links: &Links, marks: &EdgeMarks, stats: &mut MeshStats) {
    let n = links.offsets.len() - 1;
    let mut neighbours = Vec::new();
    let mut parent = Vec::new();
    for v in 0..n {
        let link = links.of(v);
        if link.is_empty() {
            continue;
        }
        stats.vertices += 1;
        neighbours.clear();
        neighbours.extend(
            link.iter()
                .flat_map(|&(a, b)| [a, b])
                .filter(|&w| w as usize != v),
        );
        neighbours.sort_unstable();
        neighbours.dedup();
        let valence = u32::try_from(neighbours.len()).unwrap_or(u32::MAX);
        *stats.valence_histogram.entry(valence).or_default() += 1;
        if marks.on_boundary[v] {
            stats.boundary_vertices += 1;
        } else {
            *stats.interior_valence_histogram.entry(valence).or_default() += 1;
        }
        let components = link_components(link, &neighbours, &mut parent);
        if components > 1 || marks.on_nonmanifold_edge[v] {
            stats.nonmanifold_vertices += 1;
        }
    }
}

/// The connected components of a vertex's link graph over its sorted `neighbours` (`parent`
/// is scratch space): the fan is one umbrella iff there is one.
fn link_components(link: &[(u32, u32)], neighbours: &[u32], parent: &mut Vec<usize>) -> usize {
    // Union the two link ends of each incident triangle.
    parent.clear();
    parent.extend(0..neighbours.len());
    let slot = |w: u32| neighbours.binary_search(&w).ok();
    for &(a, b) in link {
        if let (Some(x), Some(y)) = (slot(a), slot(b)) {
            let (rx, ry) = (find(parent, x), find(parent, y));
            parent[rx] = ry;
        }
    }
    (0..parent.len()).filter(|&i| find(parent, i) == i).count()
}

/// The connected piece of each triangle (triangles sharing a position are one piece), numbered
/// by first appearance. Indices past `vertex_count` count as their own positions.
pub fn pieces(vertex_count: usize, tris: &[[u32; 3]]) -> Vec<u32> {
    let n = tris
        .iter()
        .flatten()
        .map(|&i| i as usize + 1)
        .max()
        .unwrap_or(0)
        .max(vertex_count);
    let mut parent: Vec<usize> = (0..n).collect();
    for t in tris {
        let a = find(&mut parent, t[0] as usize);
        for &i in &t[1..] {
            let b = find(&mut parent, i as usize);
            parent[b] = a;
        }
    }
    let mut number: HashMap<usize, u32> = HashMap::new();
    tris.iter()
        .map(|t| {
            let root = find(&mut parent, t[0] as usize);
            let next = number.len() as u32;
            *number.entry(root).or_insert(next)
        })
        .collect()
}

fn find(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

impl MeshStats {
    /// No non-manifold edges and no non-manifold vertices.
    pub fn is_manifold(&self) -> bool {
        self.nonmanifold_edges == 0 && self.nonmanifold_vertices == 0
    }

    /// Manifold and without boundary edges.
    pub fn is_closed(&self) -> bool {
        self.is_manifold() && self.boundary_edges == 0
    }

    /// `V - E + F` over the used vertices (2 for a closed sphere, 0 for a torus).
    pub fn euler_characteristic(&self) -> i64 {
        self.vertices as i64 - self.edges as i64 + self.triangles as i64
    }

    /// The set of valences of interior vertices (as listed in `assets/models/MANIFEST.txt`).
    pub fn interior_valences(&self) -> Vec<u32> {
        self.interior_valence_histogram.keys().copied().collect()
    }
}

/// One line: counts, then `valence:count` pairs of all vertices.
impl std::fmt::Display for MeshStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} vertices, {} triangles, {} edges ({} boundary, {} non-manifold, {} inconsistently oriented), {} non-manifold vertices, valences {}",
            self.vertices,
            self.triangles,
            self.edges,
            self.boundary_edges,
            self.nonmanifold_edges,
            self.inconsistently_oriented_edges,
            self.nonmanifold_vertices,
            histogram_string(&self.valence_histogram)
        )
    }
}

fn histogram_string(h: &BTreeMap<u32, usize>) -> String {
    h.iter()
        .map(|(v, c)| format!("{v}:{c}"))
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{test_support::load_model, Mesh};

    /// One line of MANIFEST.txt for a well-formed model.
    struct Expected {
        file: String,
        v: usize,
        f: usize,
        boundary_edges: usize,
        interior_valences: Vec<u32>,
    }

    fn field(line: &str, key: &str) -> usize {
        let start = line.find(key).unwrap_or_else(|| panic!("{key} in {line}")) + key.len();
        line[start..]
            .split(|c: char| !c.is_ascii_digit())
            .next()
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| panic!("number after {key} in {line}"))
    }

    fn manifest() -> (Vec<Expected>, Vec<String>) {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/assets/models/MANIFEST.txt"
        ))
        .expect("MANIFEST.txt");
        let mut good = Vec::new();
        let mut refused = Vec::new();
        for line in text
            .lines()
            .filter(|l| !l.starts_with('#') && l.contains(':'))
        {
            let (file, rest) = line.split_once(':').unwrap();
            if rest.contains("not Loop-ready") {
                refused.push(file.to_string());
                continue;
            }
            let list = &rest[rest.find('[').unwrap() + 1..rest.find(']').unwrap()];
            good.push(Expected {
                file: file.to_string(),
                v: field(rest, "V="),
                f: field(rest, "F="),
                boundary_edges: field(rest, "boundary_edges="),
                interior_valences: list.split(',').map(|s| s.trim().parse().unwrap()).collect(),
            });
        }
        (good, refused)
    }

    #[test]
    fn every_model_matches_the_manifest() {
        let (good, refused) = manifest();
        assert!(
            good.len() >= 17,
            "manifest lists {} good models",
            good.len()
        );
        for e in &good {
            let (mesh, report) = load_model(&e.file);
            let s = mesh.stats();
            assert_eq!(s.vertices, e.v, "{} vertices", e.file);
            assert_eq!(s.triangles, e.f, "{} faces", e.file);
            assert_eq!(s.boundary_edges, e.boundary_edges, "{} boundary", e.file);
            assert_eq!(s.interior_valences(), e.interior_valences, "{}", e.file);
            assert!(s.is_manifold(), "{}: {s:?}", e.file);
            assert_eq!(s.inconsistently_oriented_edges, 0, "{}", e.file);
            assert!(report.dropped_degenerate.is_empty(), "{}", e.file);
            assert!(mesh.require_manifold().is_ok());
        }
        // Every model in the folder is described.
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/models");
        for entry in std::fs::read_dir(dir).unwrap() {
            let name = entry.unwrap().file_name().into_string().unwrap();
            if name.ends_with(".obj") {
                assert!(
                    good.iter().any(|e| e.file == name) || refused.contains(&name),
                    "{name} missing from MANIFEST.txt"
                );
            }
        }
        assert!(refused.contains(&"nonmanifold_edge.obj".to_string()));
        assert!(refused.contains(&"degenerate_faces.obj".to_string()));
    }

    #[test]
    fn closed_models_have_the_expected_genus() {
        for (file, chi) in [
            ("tetrahedron.obj", 2),
            ("icosahedron.obj", 2),
            ("spot_tri.obj", 2),
            ("torus_16x8.obj", 0),
        ] {
            let s = load_model(file).0.stats();
            assert!(s.is_closed(), "{file}");
            assert_eq!(s.euler_characteristic(), chi, "{file}");
        }
    }

    #[test]
    fn nonmanifold_edge_model() {
        let (mesh, _) = load_model("nonmanifold_edge.obj");
        let s = mesh.stats();
        assert_eq!(s.nonmanifold_edges, 1);
        // Both ends of the edge 1-2.
        assert_eq!(s.nonmanifold_vertices, 2);
        assert!(!s.is_manifold());
        let err = mesh.require_manifold().unwrap_err();
        assert_eq!(
            err.to_string(),
            "'nonmanifold_edge' is not a manifold mesh: 1 edge(s) shared by more than two triangles, 2 non-manifold vertex(es)"
        );
    }

    #[test]
    fn degenerate_model_raw_faces_include_an_inconsistent_edge() {
        // Before the loader drops the degenerate faces, faces `4 17 18` and `17 18 19`
        // both traverse 17 -> 18.
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/assets/models/degenerate_faces.obj"
        ))
        .unwrap();
        let tris: Vec<[u32; 3]> = text
            .lines()
            .filter_map(|l| l.strip_prefix("f "))
            .map(|f| {
                let v: Vec<u32> = f.split_whitespace().map(|i| i.parse().unwrap()).collect();
                [v[0] - 1, v[1] - 1, v[2] - 1]
            })
            .collect();
        let s = mesh_stats(19, &tris);
        assert_eq!(s.inconsistently_oriented_edges, 1);
        // After loading, those faces are gone.
        let s = load_model("degenerate_faces.obj").0.stats();
        assert_eq!(s.inconsistently_oriented_edges, 0);
        assert_eq!(s.triangles, 18);
        assert_eq!(s.vertices, 16);
        assert!(s.is_manifold());
    }

    #[test]
    fn bowtie_vertex_is_nonmanifold() {
        // Two triangles touching only at vertex 0.
        let p = [
            glam::Vec3::ZERO,
            glam::Vec3::new(1.0, 0.0, 0.0),
            glam::Vec3::new(1.0, 1.0, 0.0),
            glam::Vec3::new(-1.0, 0.0, 0.0),
            glam::Vec3::new(-1.0, -1.0, 0.0),
        ];
        let (mesh, _) =
            Mesh::from_parts("bowtie", p.to_vec(), None, vec![[0, 1, 2], [0, 3, 4]]).unwrap();
        let s = mesh.stats();
        assert_eq!(s.nonmanifold_edges, 0);
        assert_eq!(s.nonmanifold_vertices, 1);
        assert_eq!(s.boundary_edges, 6);
        assert_eq!(s.valence_histogram, BTreeMap::from([(2, 4), (4, 1)]));
        assert!(s.interior_valence_histogram.is_empty());
        assert!(matches!(
            mesh.require_manifold(),
            Err(crate::mesh::MeshError::NonManifold {
                edges: 0,
                vertices: 1,
                ..
            })
        ));
    }

    #[test]
    fn orientation_flip_is_counted_once_per_edge() {
        // Tetrahedron with one face flipped: its three edges become inconsistent.
        let tris = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 2, 3]];
        let s = mesh_stats(4, &tris);
        assert_eq!(s.inconsistently_oriented_edges, 3);
        assert_eq!(s.valence_histogram, BTreeMap::from([(3, 4)]));
        let fixed = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]];
        assert_eq!(mesh_stats(4, &fixed).inconsistently_oriented_edges, 0);
    }

    #[test]
    fn raw_lists_never_panic() {
        let s = mesh_stats(7, &[[0, 0, 0], [5, 6, 5], [u32::MAX - 1, 1, 2], [1, 2, 3]]);
        assert_eq!(s.triangles, 3);
        assert_eq!(s.vertices, 6);
        assert_eq!(mesh_stats(0, &[[0, 1, 2]]), MeshStats::default());
        assert_eq!(mesh_stats(3, &[]), MeshStats::default());
    }

    #[test]
    fn display_is_one_line() {
        let s = mesh_stats(4, &[[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]);
        assert_eq!(
            s.to_string(),
            "4 vertices, 4 triangles, 6 edges (0 boundary, 0 non-manifold, 0 inconsistently oriented), 0 non-manifold vertices, valences 3:4"
        );
    }
}
