//! `stpn` surface: scalar-tagged PN triangles (Boubekeur, Reuter & Schlick 2005; the 2005
//! refinement paper's appendix B). Mirror of `glsl/include/stpn.glsl`.
//!
//! Each vertex carries a tension q, a sharpness σ, a bias β and a crease direction D (zero for a
//! smooth vertex; a crease vertex also has the shared normal N of the position). The tangent
//! coefficient of edge (j, k) next to vertex j is `b = d + e` with `d = P_j + (1 − q_j)/3 ·
//! (P_k − P_j)` and, with `Π(p, n, q) = −n·(q − p)`:
//! - at a smooth vertex, `e = Π(P_j, N_j, d) N_j`: d projected on the tangent plane, which for
//!   q = 0 is PN's edge point (neutral tags give PN triangles);
//! - at a crease vertex, `e = Π(P_j, N_j, d) Y_j` with `Y_j = (N_j + β_j D_j)/|N_j + β_j D_j|`
//!   and N_j the shared normal: both triangles along the crease build the same edge, so the
//!   crease stays closed, and the bias tilts it.
//!
//! Shading: at a crease vertex a triangle uses the sharp normal of its side,
//! `N′± = (N ± σ D)/|N ± σ D|`, the side being the sign of `(centroid − P_j)·D_j`; the normal
//! field is then PN's quadratic one on those normals (per fragment, like `pn`).
//!
//! Appendix B's restrictions: at most one crease through a vertex (one D per vertex, by
//! construction) and at most two crease vertices per triangle ([`check`]).
//!
//! Tags come from a sidecar file ([`parse`]) or, without one, from the mesh's hard edges
//! ([`derive()`]): a position carrying exactly two distinct normals N_a, N_b becomes a crease
//! vertex with N = (N_a + N_b)/|…|, D = (N_a − N_b)/|…| and σ = tan(θ/2), θ the angle between them,
//! so that N′± are N_a and N_b again.

use super::bounds::{Patch, SurfaceBound};
use super::facts::{Elements, FragmentNormals, SurfaceFacts};
use super::{dot3, Corners, Local, SurfaceParams};
use crate::lod::Net;
use crate::mesh::Mesh;
use glam::Vec3;

/// What `stpn` declares about itself (docs/architecture.md, "Surfaces as plug-ins").
pub const FACTS: SurfaceFacts = SurfaceFacts {
    name: "stpn",
    help: "Scalar-tagged PN triangles (Boubekeur, Reuter & Schlick 2005): PN with per-vertex tension, sharpness, bias and crease direction (from --tags where the command takes it, else derived from the mesh's hard edges)",
    elements: Elements::CoarseTriangles,
    pre_pass: None,
    options: &["pn_seams", "normal_field", "tags", "crease_angle"],
    texture_coordinates: true,
    needs_every_face: false,
    tags: true,
    fragment_normals: FragmentNormals::Always,
    bindings: &["BINDING_TAGS"],
    bound: SurfaceBound::Nets {
        geometry: net,
        direction,
    },
};

/// One vertex's tags.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexTag {
    pub tension: f32,
    pub sharpness: f32,
    pub bias: f32,
    /// Crease direction (unit), zero for a smooth vertex.
    pub direction: Vec3,
    /// The position's shared normal at a crease vertex (unit; unused when smooth).
    pub normal: Vec3,
}

impl Default for VertexTag {
    fn default() -> Self {
        Self {
            tension: 0.0,
            sharpness: 0.0,
            bias: 0.0,
            direction: Vec3::ZERO,
            normal: Vec3::ZERO,
        }
    }
}

impl VertexTag {
    pub fn crease(&self) -> bool {
        self.direction != Vec3::ZERO
    }

    /// As the GPU reads it (`vertex_tags` in stpn.glsl): three `vec4` per vertex.
    pub fn to_gpu(&self) -> [f32; 12] {
        let (d, n) = (self.direction, self.normal);
        [
            self.tension,
            self.sharpness,
            self.bias,
            self.crease() as u32 as f32,
            d.x,
            d.y,
            d.z,
            0.0,
            n.x,
            n.y,
            n.z,
            0.0,
        ]
    }
}

/// Tags derived from the mesh's hard edges (see the module documentation); a position with
/// three or more distinct normals (a corner where several creases meet, which appendix B cannot
/// express) stays smooth and is counted in the second value.
pub fn derive(mesh: &Mesh) -> (Vec<VertexTag>, usize) {
    derive_with_angle(mesh, None)
}

/// A crease tag from the two normals either side of it (`None` if they are degenerate).
fn crease_tag(a: Vec3, b: Vec3) -> Option<VertexTag> {
    let n = (a + b).normalize_or_zero();
    let d = (a - b).normalize_or_zero();
    if n == Vec3::ZERO || d == Vec3::ZERO {
        return None;
    }
    Some(VertexTag {
        sharpness: (0.5 * a.angle_between(b)).tan(),
        direction: d,
        normal: n,
        ..VertexTag::default()
    })
}

/// [`derive()`], and with `crease_angle` (degrees) also from the geometry: at a position with one
/// normal, the faces around it are grouped across the edges whose dihedral angle is at most
/// `crease_angle`; exactly two groups make a crease through it, N_a and N_b being the groups'
/// area-weighted face normals.
/// A position counts once among the corners that stay smooth, whichever finds it (a mesh with
/// split normals whose corners the dihedral angles find again), and not where the normals
/// give it a crease.
pub fn derive_with_angle(mesh: &Mesh, crease_angle: Option<f32>) -> (Vec<VertexTag>, usize) {
    let (mut tags, mut corners) = derive_from_normals(mesh);
    if let Some(angle) = crease_angle {
        let (more, more_corners) = derive_from_dihedrals(mesh, angle.to_radians());
        for ((t, m), (c, mc)) in tags
            .iter_mut()
            .zip(more)
            .zip(corners.iter_mut().zip(more_corners))
        {
            if !t.crease() {
                // A crease the dihedral angles find keeps the position from staying smooth.
                *c = !m.crease() && (*c || mc);
                *t = m;
            }
        }
    }
    (tags, corners.iter().filter(|&&c| c).count())
}

/// Tags from dihedral angles, and which positions are corners that stay smooth.
fn derive_from_dihedrals(mesh: &Mesh, angle: f32) -> (Vec<VertexTag>, Vec<bool>) {
    let face_normal = |t: &crate::mesh::Triangle| {
        let [a, b, c] = t.p.map(|i| mesh.positions[i as usize]);
        (b - a).cross(c - a) // area-weighted
    };
    let normals: Vec<Vec3> = mesh.triangles.iter().map(face_normal).collect();
    // Faces of every undirected edge.
    let mut edge_faces: std::collections::HashMap<(u32, u32), Vec<usize>> =
        std::collections::HashMap::new();
    for (f, t) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t.p[k], t.p[(k + 1) % 3]);
            edge_faces.entry((a.min(b), a.max(b))).or_default().push(f);
        }
    }
    let mut around: Vec<Vec<usize>> = vec![Vec::new(); mesh.positions.len()];
    for (f, t) in mesh.triangles.iter().enumerate() {
        for &p in &t.p {
            around[p as usize].push(f);
        }
    }
    let mut corners = vec![false; around.len()];
    let tags = around
        .iter()
        .enumerate()
        .map(|(v, faces)| {
            let groups = smooth_groups(mesh, &edge_faces, &normals, angle, v, faces);
            match groups.as_slice() {
                [(_, a), (_, b)] => {
                    crease_tag(a.normalize_or_zero(), b.normalize_or_zero()).unwrap_or_default()
                }
                s if s.len() > 2 => {
                    corners[v] = true;
                    VertexTag::default()
                }
                _ => VertexTag::default(),
            }
        })
        .collect();
    (tags, corners)
}

/// The faces around vertex `v` grouped across the smooth edges at `v` (two faces, dihedral
/// angle at most `angle`): each group's root and the sum of its area-weighted face normals.
fn smooth_groups(
    mesh: &Mesh,
    edge_faces: &std::collections::HashMap<(u32, u32), Vec<usize>>,
    normals: &[Vec3],
    angle: f32,
    v: usize,
    faces: &[usize],
) -> Vec<(usize, Vec3)> {
    // Union-find over the faces around v, joined across smooth edges at v.
    let mut parent: Vec<usize> = (0..faces.len()).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    // The edges at v, each once: those of the faces around it that contain v.
    let mut edges: Vec<(u32, u32)> = faces
        .iter()
        .flat_map(|&f| {
            let t = &mesh.triangles[f];
            (0..3).map(move |k| (t.p[k], t.p[(k + 1) % 3]))
        })
        .filter(|&(a, b)| a as usize == v || b as usize == v)
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    for e in edges {
        let fs = &edge_faces[&e];
        if fs.len() != 2 {
            continue;
        }
        if normals[fs[0]].angle_between(normals[fs[1]]) > angle {
            continue;
        }
        let (i, j) = (
            faces.iter().position(|&f| f == fs[0]),
            faces.iter().position(|&f| f == fs[1]),
        );
        if let (Some(i), Some(j)) = (i, j) {
            let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
            parent[ri] = rj;
        }
    }
    let mut sums: Vec<(usize, Vec3)> = Vec::new();
    for i in 0..faces.len() {
        let r = root(&mut parent, i);
        match sums.iter_mut().find(|(k, _)| *k == r) {
            Some((_, s)) => *s += normals[faces[i]],
            None => sums.push((r, normals[faces[i]])),
        }
    }
    sums
}

/// Tags from split normals, and which positions are corners that stay smooth.
fn derive_from_normals(mesh: &Mesh) -> (Vec<VertexTag>, Vec<bool>) {
    let mut groups: Vec<Vec<Vec3>> = vec![Vec::new(); mesh.positions.len()];
    for t in &mesh.triangles {
        for k in 0..3 {
            let n = mesh.normals[t.n[k] as usize];
            let g = &mut groups[t.p[k] as usize];
            if !g
                .iter()
                .any(|m| m.to_array().map(f32::to_bits) == n.to_array().map(f32::to_bits))
            {
                g.push(n);
            }
        }
    }
    let corners: Vec<bool> = groups.iter().map(|g| g.len() > 2).collect();
    let tags = groups
        .iter()
        .map(|g| match g.as_slice() {
            [a, b] => crease_tag(*a, *b).unwrap_or_default(),
            _ => VertexTag::default(),
        })
        .collect();
    (tags, corners)
}

/// Largest sharpness and bias magnitude a tags file may give: `N ± σD` and `N + βD` are
/// normalized in `f32`, whose squares overflow near 1.8e19 (NaN normals); beyond 1e6 the sharp
/// normal is within 0.0001° of ±D anyway.
pub const MAX_SHARPNESS: f32 = 1e6;

/// A crease direction is refused when its part across the normal is less than this fraction
/// of its length (within about 0.06° of the normal): what is left is rounding, not a direction.
const MIN_ACROSS: f32 = 1e-3;

/// Reads a tags file for `mesh`. Format (documented in docs/surfaces.md): `#` comments and blank lines;
/// one line per tagged vertex, `t X Y Z TENSION [SHARPNESS BIAS DX DY DZ]`, the vertex named by
/// its coordinates exactly as its `v` line gives them. Untagged vertices keep `base`.
pub fn parse(
    shown: &str,
    text: &str,
    mesh: &Mesh,
    base: &[VertexTag],
) -> Result<Vec<VertexTag>, String> {
    let index = position_index(mesh);
    let normals =
        crate::mesh::compute_area_weighted_normals(&mesh.positions, &mesh.position_indices());
    let mut tags = base.to_vec();
    // The line that tagged each vertex so far.
    let mut tagged_at: std::collections::HashMap<usize, usize> = std::collections::HashMap::new();
    // A byte order mark (some Windows editors write one) is not part of the first line.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    for (i, line) in text.lines().enumerate() {
        let at = |msg: String| format!("tags file '{shown}' line {}: {msg}", i + 1);
        let Some(v) = tag_numbers(line).map_err(at)? else {
            continue;
        };
        let vi = tagged_vertex(&index, &v, &mut tagged_at, i + 1).map_err(at)?;
        tags[vi] = tag_of(&v, tags[vi], normals[vi]).map_err(at)?;
    }
    Ok(tags)
}

/// Each position's vertex, keyed by its bits (`-0` as `0`).
fn position_index(mesh: &Mesh) -> std::collections::HashMap<[u32; 3], usize> {
    mesh.positions
        .iter()
        .enumerate()
        .map(|(i, p)| ((*p + Vec3::ZERO).to_array().map(f32::to_bits), i))
        .collect()
}

/// The numbers of a tag line (4 or 9), or `None` for a blank or comment line.
fn tag_numbers(line: &str) -> Result<Option<Vec<f32>>, String> {
    // A `#` starts a comment, at the start of a line or after the numbers.
    let line = line.split('#').next().unwrap_or("").trim();
    if line.is_empty() {
        return Ok(None);
    }
    let words: Vec<&str> = line.split_whitespace().collect();
    if words[0] != "t" {
        return Err(format!(
            "'{}' is not a tag line (expected `t X Y Z TENSION [SHARPNESS BIAS DX DY DZ]`)",
            crate::mesh::shown_word(words[0])
        ));
    }
    // Each word a number first, so that a count names numbers only.
    let mut v = Vec::with_capacity(9);
    for w in &words[1..] {
        match w.parse::<f32>() {
            Ok(x) if x.is_finite() => v.push(x),
            _ => {
                let w = crate::mesh::shown_word(w);
                return Err(format!("'{w}' is not a finite number"));
            }
        }
    }
    if v.len() != 4 && v.len() != 9 {
        return Err(format!(
            "{} numbers, expected 4 (X Y Z TENSION) or 9 (with SHARPNESS BIAS DX DY DZ)",
            v.len()
        ));
    }
    Ok(Some(v))
}

/// The vertex at the line's position (`line`, counted from 1), which no earlier line tagged.
fn tagged_vertex(
    index: &std::collections::HashMap<[u32; 3], usize>,
    v: &[f32],
    tagged_at: &mut std::collections::HashMap<usize, usize>,
    line: usize,
) -> Result<usize, String> {
    let p = Vec3::new(v[0], v[1], v[2]) + Vec3::ZERO;
    let Some(&vi) = index.get(&p.to_array().map(f32::to_bits)) else {
        return Err(format!(
            "no vertex of the mesh's faces is at ({}, {}, {})",
            v[0], v[1], v[2]
        ));
    };
    if let Some(first) = tagged_at.insert(vi, line) {
        return Err(format!(
            "the vertex at ({}, {}, {}) was already tagged at line {first}: one line per vertex (a vertex has at most one crease)",
            v[0], v[1], v[2]
        ));
    }
    Ok(vi)
}

/// The tag a line's numbers `v` give a vertex tagged `old` whose area-weighted normal is
/// `area_normal`: its tension, and with nine numbers its crease.
fn tag_of(v: &[f32], old: VertexTag, area_normal: Vec3) -> Result<VertexTag, String> {
    if !(-1.0..=1.0).contains(&v[3]) {
        return Err(format!("tension {} is not within [-1, 1]", v[3]));
    }
    let mut tag = VertexTag {
        tension: v[3],
        ..old
    };
    if v.len() == 9 {
        if !(0.0..=MAX_SHARPNESS).contains(&v[4]) {
            return Err(format!(
                "sharpness {} is not within [0, {MAX_SHARPNESS:e}]",
                super::shown_number(v[4])
            ));
        }
        if v[5].abs() > MAX_SHARPNESS {
            return Err(format!(
                "bias {} is not within [-{MAX_SHARPNESS:e}, {MAX_SHARPNESS:e}]",
                super::shown_number(v[5])
            ));
        }
        let n = if old.crease() {
            old.normal
        } else {
            area_normal
        };
        tag.sharpness = v[4];
        tag.bias = v[5];
        tag.direction = crease_direction([v[6], v[7], v[8]], n)?;
        tag.normal = n;
    }
    Ok(tag)
}

/// The crease direction `given` at a vertex of normal `n`, put in the tangent plane and
/// normalized; refused where it is zero or (nearly) parallel to `n`.
fn crease_direction(given: [f32; 3], n: Vec3) -> Result<Vec3, String> {
    let [x, y, z] = given;
    let given = Vec3::from(given);
    // The crease direction lies in the tangent plane. Scaled to a largest component of
    // 1 first, so a huge direction does not overflow.
    let largest = given.abs().max_element();
    if largest == 0.0 {
        return Err(format!(
            "crease direction ({x}, {y}, {z}) is zero: give a direction across the crease, or only X Y Z TENSION for a smooth vertex"
        ));
    }
    let d = given / largest;
    let across = d - n * d.dot(n);
    if across.length() < MIN_ACROSS * d.length() {
        return Err(format!(
            "crease direction ({x}, {y}, {z}) is parallel to the vertex's normal ({}, {}, {}): it must point across the crease, in the tangent plane",
            n.x, n.y, n.z
        ));
    }
    Ok(across.normalize())
}

/// Appendix B's restriction that tags must meet: at most two crease vertices per triangle.
pub fn check(mesh: &Mesh, tags: &[VertexTag]) -> Result<(), String> {
    match three_creases(mesh, tags) {
        Some(t) => Err(format!(
            "triangle {} {}",
            t + 1,
            three_creases_message(mesh, t)
        )),
        None => Ok(()),
    }
}

/// The first triangle whose three corners are crease vertices (appendix B's restriction).
pub fn three_creases(mesh: &Mesh, tags: &[VertexTag]) -> Option<usize> {
    mesh.triangles
        .iter()
        .position(|tri| tri.p.iter().all(|&p| tags[p as usize].crease()))
}

/// "has three crease vertices (P, Q, R): ..." for triangle `t`, after the caller names it.
pub fn three_creases_message(mesh: &Mesh, t: usize) -> String {
    let p = mesh.triangles[t].p.map(|i| mesh.positions[i as usize]);
    format!(
        "has three crease vertices ({}, {}, {}): scalar-tagged PN triangles allow at most two per triangle",
        p[0], p[1], p[2]
    )
}

/// The tags of a triangle's canonical corners (`Corners::order` into the record's stored
/// corners, whose global indices are `idx`).
pub fn corner_tags(tags: &[VertexTag], idx: &[u32; 4], order: [usize; 3]) -> [VertexTag; 3] {
    order.map(|c| tags.get(idx[c] as usize).copied().unwrap_or_default())
}

const THIRD: f32 = 1.0 / 3.0;

/// The tangent coefficient of edge (i, j) next to corner i. Mirror of `stpn_edge`.
pub fn edge_point(c: &Corners, t: &[VertexTag; 3], i: usize, j: usize) -> Vec3 {
    let d = c.p[i] + (c.p[j] - c.p[i]) * ((1.0 - t[i].tension) * THIRD);
    if t[i].crease() {
        let n = t[i].normal;
        let y = (n + t[i].direction * t[i].bias).normalize_or_zero();
        d + y * -dot3(n, d - c.p[i])
    } else {
        let n = c.n[i];
        d + n * -dot3(n, d - c.p[i])
    }
}

/// The shading normals of the corners: a crease corner's sharp normal of this triangle's side.
pub fn shading_normals(c: &Corners, t: &[VertexTag; 3]) -> [Vec3; 3] {
    let centroid = (c.p[0] + c.p[1] + c.p[2]) * THIRD;
    [0, 1, 2].map(|i| {
        if !t[i].crease() {
            return c.n[i];
        }
        let side = if dot3(centroid - c.p[i], t[i].direction) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        (t[i].normal + t[i].direction * (side * t[i].sharpness)).normalize_or_zero()
    })
}

/// What the `stpn` mirror reads besides the record: its normal field (a per-build option) and
/// every vertex's scalar tags (`None`: neutral tags, where the surface is `pn`).
#[derive(Clone, Copy, Debug)]
pub struct Inputs<'a> {
    pub field: super::NormalField,
    pub tags: Option<&'a [VertexTag]>,
}

pub fn eval(c: &Corners, t: &[VertexTag; 3], field: super::NormalField) -> Local {
    let shaded = Corners {
        n: shading_normals(c, t),
        ..*c
    };
    super::pn::eval_with_edges(&shaded, &|i, j| edge_point(c, t, i, j), field)
}

/// Chord-error bound: the cubic Bézier net of `pn` ([`super::pn::net`]) with the tagged edge
/// points.
pub fn net(_: &SurfaceParams, c: &Corners, tags: &[VertexTag; 3], _: bool) -> Patch {
    let b = super::pn::control_with(c, &|i, j| edge_point(c, tags, i, j));
    Patch::Exact(super::pn::bezier_net(c, &b))
}

/// The direction field displacement moves along: `pn`'s of the shading normals; on an edge with
/// crease corners every side's choice of sharp normal (the side is the element's to know).
pub fn direction(
    _: &SurfaceParams,
    field: super::NormalField,
    c: &Corners,
    tags: &[VertexTag; 3],
    edge: bool,
) -> Vec<Net> {
    let cg = Corners { n: c.g, ..*c };
    if !edge {
        return vec![super::pn::field_net(field, &cg, shading_normals(&cg, tags))];
    }
    let sides = |i: usize| -> Vec<Vec3> {
        let t = &tags[i];
        if !t.crease() {
            return vec![cg.n[i]];
        }
        [1.0f32, -1.0]
            .iter()
            .map(|s| (t.normal + t.direction * (s * t.sharpness)).normalize_or_zero())
            .collect()
    };
    let mut out = Vec::new();
    for a in sides(0) {
        for b in sides(1) {
            out.push(super::pn::field_net(field, &cg, [a, b, cg.n[2]]));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_support::load_model;
    use crate::surface::{BuildOptions, Mirror, Sources, Surface, SurfaceParams};

    /// A tag line's words are read as numbers before they are counted: a count names numbers
    /// only, and a word that is none is named.
    #[test]
    fn tag_lines_name_what_is_wrong_with_them() {
        let err = |l: &str| tag_numbers(l).unwrap_err();
        assert_eq!(
            err("t 1 1 1 0.5 1 0 1 0 0 junk"),
            "'junk' is not a finite number"
        );
        assert!(err("t 1 2 3").starts_with("3 numbers, expected 4"));
        assert!(err("t 1 2 3 4 5").starts_with("5 numbers, expected 4"));
        assert_eq!(
            tag_numbers("t 1 2 3 0.5 # a comment")
                .unwrap()
                .unwrap()
                .len(),
            4
        );
        assert_eq!(tag_numbers("  # only a comment").unwrap(), None);
    }

    /// Neutral tags give PN triangles: the same points to 4 ulp of the mesh's radius (the edge
    /// coefficient is the same point computed another way: `P + (Q − P)/3` projected, not
    /// `(2P + Q − sN)/3`).
    #[test]
    fn neutral_tags_are_pn() {
        let (mesh, _) = load_model("icosahedron_vn.obj");
        let records = crate::surface::build_records(
            crate::surface::RecordKind::Corners,
            &mesh,
            crate::surface::Seams::Open,
        );
        let tags = vec![VertexTag::default(); mesh.positions.len()];
        let sources = Sources {
            tags: Some(&tags),
            ..Default::default()
        };
        let mirror = |s| {
            Mirror::new(
                s,
                crate::surface::Displace::None,
                &BuildOptions::default(),
                &sources,
            )
            .unwrap()
        };
        let (pn, stpn) = (mirror(Surface::Pn), mirror(Surface::Stpn));
        let p = SurfaceParams::default();
        let tol = 4.0 * f32::EPSILON * mesh.bounding_radius();
        for (t, r) in records.iter().enumerate() {
            for b in [[0.2f32, 0.3, 0.5], [0.5, 0.5, 0.0], [0.1, 0.1, 0.8]] {
                let a = pn.eval(&p, t, r, b);
                let s = stpn.eval(&p, t, r, b);
                assert!(
                    (a.position - s.position).abs().max_element() <= tol,
                    "{} vs {}",
                    a.position,
                    s.position
                );
                assert!((a.normal - s.normal).length() < 1e-6);
            }
        }
    }

    /// Without split normals, the crease angle finds the same creases from the geometry: a
    /// cylinder whose normals are computed (one per position) gets creases at its rims with a
    /// 60° crease angle, and none without one.
    #[test]
    fn crease_angle_finds_creases_from_dihedral_angles() {
        let (hard, _) = load_model("cylinder_hard_normals.obj");
        let (mesh, _) =
            Mesh::from_parts("cyl", hard.positions.clone(), None, hard.position_indices()).unwrap();
        let (none, _) = derive_with_angle(&mesh, None);
        assert!(none.iter().all(|t| !t.crease()));
        let (tags, corners) = derive_with_angle(&mesh, Some(60.0));
        assert_eq!(corners, 0);
        let (expected, _) = derive(&hard);
        let creases: Vec<bool> = tags.iter().map(VertexTag::crease).collect();
        let want: Vec<bool> = expected.iter().map(VertexTag::crease).collect();
        assert_eq!(creases, want);
        check(&mesh, &tags).unwrap();
    }

    /// A cube's corners stay smooth (three hard edges meet at each), counted once each whether
    /// its split normals find them, its dihedral angles, or both.
    #[test]
    fn corners_found_twice_count_once() {
        let (split, _) = load_model("cube_face_normals.obj");
        let (one, _) = Mesh::from_parts(
            "cube",
            split.positions.clone(),
            None,
            split.position_indices(),
        )
        .unwrap();
        assert_eq!(derive(&split).1, 8);
        assert_eq!(derive_with_angle(&split, Some(30.0)).1, 8);
        assert_eq!(derive_with_angle(&one, Some(30.0)).1, 8);
    }

    /// Tags derived from the cylinder's hard rims: its rim vertices become creases whose sharp
    /// normals are the two given ones, the other vertices stay smooth, and the restrictions hold.
    #[test]
    fn derived_tags_reproduce_the_hard_normals() {
        let (mesh, _) = load_model("cylinder_hard_normals.obj");
        let (tags, corners) = derive(&mesh);
        assert_eq!(corners, 0);
        let creases = tags.iter().filter(|t| t.crease()).count();
        assert!(creases > 0 && creases < mesh.positions.len());
        for t in tags.iter().filter(|t| t.crease()) {
            let a = (t.normal + t.direction * t.sharpness).normalize();
            let b = (t.normal - t.direction * t.sharpness).normalize();
            assert!((a.angle_between(b) - 2.0 * t.sharpness.atan()).abs() < 1e-5);
        }
        check(&mesh, &tags).unwrap();
    }

    #[test]
    fn tag_files_are_parsed_with_line_errors() {
        let (mesh, _) = load_model("tetrahedron.obj");
        let base = vec![VertexTag::default(); mesh.positions.len()];
        let p = mesh.positions[0];
        let ok = format!("# tags\n\nt {} {} {} 0.5\n", p.x, p.y, p.z);
        let tags = parse("t.tags", &ok, &mesh, &base).unwrap();
        assert_eq!(tags[0].tension, 0.5);
        // A byte order mark before the first line (Windows editors write one) is read past.
        let marked = format!("\u{feff}t {} {} {} 0.5\n", p.x, p.y, p.z);
        assert_eq!(parse("t.tags", &marked, &mesh, &base).unwrap(), tags);
        let n0 =
            crate::mesh::compute_area_weighted_normals(&mesh.positions, &mesh.position_indices())
                [0];
        // Comments after the numbers; a huge direction is the same direction, not dropped.
        let small = format!("t {} {} {} 0.5 2 0 1 0 0 # note\n", p.x, p.y, p.z);
        let huge = format!("t {} {} {} 0.5 2 0 1e30 0 0\n", p.x, p.y, p.z);
        let small = parse("t.tags", &small, &mesh, &base).unwrap();
        let huge = parse("t.tags", &huge, &mesh, &base).unwrap();
        assert!(small[0].crease() && small[0].direction.is_normalized());
        assert!(
            (huge[0].direction - small[0].direction).length() < 1e-6,
            "{:?} {:?}",
            huge[0].direction,
            small[0].direction
        );
        assert!((huge[0].direction.dot(n0)).abs() < 1e-6);
        for (text, needle) in [
            ("x 1 2 3 0\n".to_string(), "line 1: 'x' is not a tag line"),
            ("\nt 1 2\n".to_string(), "line 2: 2 numbers"),
            (
                "t 9 9 9 0\n".to_string(),
                "no vertex of the mesh's faces is at (9, 9, 9)",
            ),
            (
                format!("t {} {} {} 2\n", p.x, p.y, p.z),
                "tension 2 is not within [-1, 1]",
            ),
            (
                format!("t {} {} {} nan\n", p.x, p.y, p.z),
                "'nan' is not a finite number",
            ),
            (
                format!("t {} {} {} 0 -1 0 1 0 0\n", p.x, p.y, p.z),
                "sharpness -1 is not within [0, 1e6]",
            ),
            // Overflowing sharpness or bias would normalize to NaN normals.
            (
                format!("t {} {} {} 0 1e20 0 1 0 0\n", p.x, p.y, p.z),
                "line 1: sharpness 1e20 is not within [0, 1e6]",
            ),
            (
                format!("t {} {} {} 0 1 -1e20 1 0 0\n", p.x, p.y, p.z),
                "bias -1e20 is not within [-1e6, 1e6]",
            ),
            (
                format!("t {} {} {} 0 1 0 0 0 0\n", p.x, p.y, p.z),
                "line 1: crease direction (0, 0, 0) is zero",
            ),
            (
                format!(
                    "t {} {} {} 0 1 0 {} {} {}\n",
                    p.x,
                    p.y,
                    p.z,
                    -n0.x * 5.0,
                    -n0.y * 5.0,
                    -n0.z * 5.0
                ),
                "is parallel to the vertex's normal",
            ),
            // A comment after the numbers is not counted as numbers; a second line for the
            // same vertex is an error naming the first.
            (
                format!(
                    "t {} {} {} 0 1 0 1 0 0 # x\n\nt {} {} {} 0.5\n",
                    p.x, p.y, p.z, p.x, p.y, p.z
                ),
                "line 3: the vertex at",
            ),
            (
                format!(
                    "t {} {} {} 0\nt {} {} {} 0.5\n",
                    p.x, p.y, p.z, p.x, p.y, p.z
                ),
                "was already tagged at line 1: one line per vertex",
            ),
        ] {
            let e = parse("t.tags", &text, &mesh, &base).unwrap_err();
            assert!(
                e.contains("tags file 't.tags'") && e.contains(needle),
                "{e}"
            );
        }
        // Three crease vertices in one triangle break appendix B's restriction.
        let all = mesh
            .positions
            .iter()
            .map(|q| format!("t {} {} {} 0 1 0 1 0 0\n", q.x, q.y, q.z))
            .collect::<String>();
        let tags = parse("t.tags", &all, &mesh, &base).unwrap();
        assert!(check(&mesh, &tags)
            .unwrap_err()
            .contains("three crease vertices"));
    }
}
