//! What Loop subdivision cannot take in a loaded mesh, said in the file's own terms.
//!
//! `subdiv::Topology` reports problems with the welded mesh's 0-based indices, and for M1 (the
//! mesh after one Loop step) with vertices the file does not have. Before anything is built,
//! the command checks M0 and M1 here and names the file's vertices (by the number of their
//! first `v` line) and faces (by their line), from the [`LoadReport`]. Faces on the same three
//! vertices as an earlier one, which make M1 non-manifold though M0 is, are refused earlier, as
//! dropped faces ([`loop_refusal`]).
#![forbid(unsafe_code)]

use meshrefine::mesh::{LoadReport, Mesh};
use meshrefine::subdiv::bft::{control_estimate_m0, CONTROL_LIMIT};
use meshrefine::subdiv::{Topology, TopologyError};

/// Loop subdivides the file's topology, which a dropped face would change (a hole where it
/// was): with `--surface loop` the first dropped face is an error, not a warning. With
/// `topology`, also what Loop cannot subdivide in the faces kept ([`loop_check`]).
pub fn loop_refusal(
    shown: &str,
    mesh: &Mesh,
    report: &LoadReport,
    topology: bool,
) -> Option<String> {
    let Some(d) = report.dropped_degenerate.first() else {
        return topology
            .then(|| topology_refusal(mesh, report))
            .flatten()
            .map(|why| format!("'{shown}': the loop surface cannot subdivide it: {why}"));
    };
    let face = match d.line {
        Some(l) => format!("the face at line {l}"),
        None => format!("face {}", d.face),
    };
    if d.reason == meshrefine::mesh::DUPLICATE_FACE {
        return Some(format!(
            "'{shown}': the loop surface cannot subdivide it: {face} {}: Loop subdivision cannot take two faces on the same three vertices (after one step their edges would be shared by four faces), and dropping one, as the other surfaces do, would open a hole",
            d.reason
        ));
    }
    Some(format!(
        "'{shown}': the loop surface cannot subdivide it: {face} {}, {} degenerate face(s) in all: Loop subdivision needs every face of the file, and dropping it, as the other surfaces do, would open a hole",
        d.reason,
        report.dropped_degenerate.len()
    ))
}

/// The faces (their names in messages, first two at most) that use edge (a, b), either way.
fn faces_on_edge(mesh: &Mesh, report: &LoadReport, a: u32, b: u32) -> Vec<String> {
    mesh.triangles
        .iter()
        .enumerate()
        .filter(|(_, t)| t.p.contains(&a) && t.p.contains(&b))
        .map(|(i, _)| report.face(i))
        .collect()
}

/// The first face that uses vertex `v`.
fn face_at(mesh: &Mesh, report: &LoadReport, v: u32) -> Option<String> {
    let i = mesh.triangles.iter().position(|t| t.p.contains(&v))?;
    Some(report.face(i))
}

/// Why Loop cannot subdivide `mesh` (one clause for "'x.obj': the loop surface cannot subdivide
/// it: ..."), or None when it can.
pub fn topology_refusal(mesh: &Mesh, report: &LoadReport) -> Option<String> {
    let m0 = match Topology::of_mesh(mesh) {
        Ok(t) => t,
        Err(e) => return Some(m0_message(mesh, report, &e)),
    };
    // M1's size is known from M0 (M1 of a million triangles takes seconds to build).
    if let Some(why) = size_refusal(&m0, report) {
        return Some(why);
    }
    // M0 passed: M1 can only fail where M0 is manifold but one step is not (not expected once
    // duplicate faces are gone); said without M1's indices, which mean nothing to the user.
    drop(m0);
    match meshrefine::subdiv::m1_topology(mesh) {
        Err(e) => Some(format!(
            "after one Loop step its topology breaks ({}), which Loop subdivision cannot continue from",
            match e {
                TopologyError::RepeatedVertex { .. } => "a face repeats a vertex",
                TopologyError::NonManifoldEdge { .. } => "an edge is shared by more than two faces",
                TopologyError::OrientationConflict { .. } => "the faces are not consistently oriented",
                TopologyError::NonManifoldVertex { .. } => "a vertex joins separate fans of faces",
                TopologyError::TooManyControlPoints { .. } => "its faces list too many control points",
            }
        )),
        Ok(_) => None,
    }
}

/// Why the basis function tables of M1 would be too large to build, estimated from M0 (`m0`)
/// before building anything ([`control_estimate_m0`]): the faces' control lists past
/// [`CONTROL_LIMIT`].
fn size_refusal(m0: &Topology, report: &LoadReport) -> Option<String> {
    let (total, most) = control_estimate_m0(m0);
    if total <= CONTROL_LIMIT {
        return None;
    }
    // M1's vertex points keep M0's numbers (the file's vertices); an edge point's valence is
    // at most 6 inside, so the vertex listed most is one of the file's. Named where its faces
    // list a tenth of the whole or more: otherwise the faces are simply too many.
    let vertex = most
        .filter(|&(_, listed)| listed * 10 >= total)
        .map(|(v, _)| {
            let (ring, on_boundary) = m0.one_ring(v);
            format!(
                "{} has {} neighbours{}, and each face around it lists them all",
                report.vertex(v),
                ring.len(),
                if on_boundary { " on the boundary" } else { "" }
            )
        });
    Some(size_sentence(total, 4 * m0.faces.len() as u64, vertex))
}

/// [`size_refusal`]'s sentence: `total` control points listed by `faces` faces of M1, and the
/// vertex whose faces list the most, where it dominates.
fn size_sentence(total: u64, faces: u64, vertex: Option<String>) -> String {
    const MIB: u64 = 1 << 20;
    let head = format!("its faces after one Loop step would list about {total} control points",);
    let limit = format!(
        "{} MiB, past the limit of {CONTROL_LIMIT} control points ({} MiB) that the loop surface's basis function tables take",
        (4 * total).div_ceil(MIB),
        4 * CONTROL_LIMIT / MIB
    );
    match vertex {
        Some(v) => {
            format!("{head} ({v}), {limit} (the lists grow with the square of a vertex's valence)")
        }
        None => {
            // Each triangle makes four faces of M1, each listing about the mean.
            let per_face = total as f64 / faces.max(1) as f64;
            let fits = (CONTROL_LIMIT as f64 / per_face / 4.0) as u64;
            format!(
                "{head} ({faces} faces of about {per_face:.0} each), {limit}: the mesh has too many triangles for it (about {fits} of such valences fit)"
            )
        }
    }
}

fn m0_message(mesh: &Mesh, report: &LoadReport, e: &TopologyError) -> String {
    let v = |i: u32| report.vertex(i);
    match *e {
        TopologyError::RepeatedVertex { face, vertex } => format!(
            "{} repeats {}: Loop subdivision needs triangles of three distinct vertices",
            report.face(face),
            v(vertex)
        ),
        TopologyError::NonManifoldEdge { a, b } => {
            let faces = faces_on_edge(mesh, report, a, b);
            format!(
                "the edge between {} and {} is shared by more than two faces ({}): Loop subdivision needs a manifold mesh",
                v(a),
                v(b),
                list(&faces)
            )
        }
        TopologyError::OrientationConflict { a, b } => {
            let faces: Vec<String> = mesh
                .triangles
                .iter()
                .enumerate()
                .filter(|(_, t)| (0..3).any(|k| t.p[k] == a && t.p[(k + 1) % 3] == b))
                .map(|(i, _)| report.face(i))
                .collect();
            format!(
                "{} both run from {} to {}: the faces around that edge are not consistently oriented, which Loop subdivision needs (flip one of them; a one-sided surface, such as a Möbius strip, has no consistent orientation)",
                list(&faces),
                v(a),
                v(b)
            )
        }
        // Only M1 is checked for its size (`size_refusal`).
        TopologyError::TooManyControlPoints { .. } => e.to_string(),
        TopologyError::NonManifoldVertex { vertex, fans } => format!(
            "{}{} is non-manifold: its faces form {fans} separate fans, not one disk or half-disk, which Loop subdivision needs",
            v(vertex),
            face_at(mesh, report, vertex)
                .map(|f| format!(" (used by {f})"))
                .unwrap_or_default()
        ),
    }
}

/// "A and B", "A, B and C", or the first three and how many more.
fn list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [a] => a.clone(),
        [rest @ .., last] if rest.len() < 3 => format!("{} and {last}", rest.join(", ")),
        _ => format!("{} and {} more", items[..3].join(", "), items.len() - 3),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refusal(text: &str) -> Option<String> {
        let (mesh, report) = Mesh::from_obj_str("x.obj", text).unwrap();
        topology_refusal(&mesh, &report)
    }

    #[test]
    fn messages_use_the_files_numbers_and_lines() {
        // Three faces on the edge between vertices 1 and 2 (a fin), listed after a vertex that
        // no face uses: the file's numbering, not the welded one.
        let fin =
            "v 9 9 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 2 3 4\nf 3 2 5\nf 2 3 6\n";
        let e = refusal(fin).unwrap();
        assert_eq!(
            e,
            "the edge between vertex 2 and vertex 3 is shared by more than two faces (the face at line 7, the face at line 8 and the face at line 9): Loop subdivision needs a manifold mesh"
        );
        // Three faces the same way round on one edge: still a fin, not a flipped face.
        let fin = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 0 -1\nf 1 2 3\nf 1 2 4\nf 1 2 5\n";
        let e = refusal(fin).unwrap();
        assert_eq!(
            e,
            "the edge between vertex 1 and vertex 2 is shared by more than two faces (the face at line 6, the face at line 7 and the face at line 8): Loop subdivision needs a manifold mesh"
        );
        let flipped = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 3 4\n";
        let e = refusal(flipped).unwrap();
        assert!(
            e.starts_with(
                "the face at line 5 and the face at line 6 both run from vertex 2 to vertex 3"
            ),
            "{e}"
        );
        // Two fans meeting at vertex 1 (a bow tie).
        let bowtie = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n";
        let e = refusal(bowtie).unwrap();
        assert!(
            e.starts_with("vertex 1 (used by the face at line 6) is non-manifold: its faces form 2 separate fans"),
            "{e}"
        );
        assert_eq!(refusal("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), None);
    }

    /// A mesh past the limit through its size alone (no vertex dominating) is told so, with
    /// about how many triangles fit.
    #[test]
    fn too_many_faces_are_not_blamed_on_a_vertex() {
        let e = size_sentence(84_000_000, 4_000_000, None);
        assert_eq!(
            e,
            "its faces after one Loop step would list about 84000000 control points (4000000 faces of about 21 each), 321 MiB, past the limit of 33554432 control points (128 MiB) that the loop surface's basis function tables take: the mesh has too many triangles for it (about 399457 of such valences fit)"
        );
    }

    /// A bicone of 2n triangles: two poles of valence n (the file's vertices 1 and 2).
    fn bicone(n: u32) -> String {
        let mut obj = String::from("v 0 0 1\nv 0 0 -1\n");
        for i in 0..n {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            obj += &format!("v {} {} 0\n", a.cos(), a.sin());
        }
        for i in 0..n {
            let (a, b) = (3 + i, 3 + (i + 1) % n);
            obj += &format!("f 1 {a} {b}\nf 2 {b} {a}\n");
        }
        obj
    }

    /// An absurd valence is refused before anything is built, naming the limit and the vertex;
    /// a high one within the limit is not.
    #[test]
    fn an_absurd_valence_is_refused_naming_the_limit() {
        let e = refusal(&bicone(20_000)).unwrap();
        assert!(
            e.starts_with(
                "its faces after one Loop step would list about 802960000 control points"
            ),
            "{e}"
        );
        assert!(e.contains("vertex 1 has 20000 neighbours"), "{e}");
        assert!(
            e.contains("past the limit of 33554432 control points (128 MiB)"),
            "{e}"
        );
        assert_eq!(refusal(&bicone(3000)), None);
    }
}
