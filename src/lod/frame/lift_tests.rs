//! The lift (src/lod/frame/lift.rs) on Spot close up: what it lifts and to what, checked from
//! the first pass's levels, and one level per edge from both sides; the pixel error it keeps in
//! `pixel_error_holds_end_to_end` (src/lod/tests/view.rs, the snapped integer levels), and the
//! GPU's second dispatch against this mirror in tests/level_pass.rs.

use super::lift::{Before, BOUNDARY, SHARED};
use super::*;
use crate::lod::levels::drawn_level;
use crate::mesh::test_support::load_model;
use crate::surface::{build_records, Displace, RecordKind, Seams, Sources, Surface, SurfaceParams};

/// Every edge the lift changes is drawn at the unraised inner level of one of its elements whose
/// transition triangles along it did not fit there, above its first level, where the element
/// across draws at least as fine (or draws nothing); every other edge keeps its first level; an
/// element without a lifted edge keeps its levels; both elements of an edge (a closed mesh: all
/// have two) hold the same bits for it; and the frame draws fewer triangles.
#[test]
fn lifted_edges_take_an_inner_level_the_element_across_already_draws() {
    let (mesh, _) = load_model("spot_control_tri.obj");
    let recs = build_records(RecordKind::Corners, &mesh, Seams::Closed);
    let params = SurfaceParams::for_radius(mesh.bounding_radius());
    let lod = Lod::of(Surface::Pn, Displace::None, &params, &Sources::default());
    let lr = lod_records(&lod, &recs);
    let max = 64;
    let (mut lifted, mut proposals, mut saved) = (0, 0, 0);
    for px in [0.5, 1.0, 2.0, 4.0] {
        let view = View::new(
            Vec3::new(0.35, 0.65, -1.3),
            45f32.to_radians(),
            1080,
            px,
            max,
        );
        let lv = LodView::new(
            &view,
            None,
            false,
            Rounding::SnappedInteger,
            lr.len() as u32,
        );
        assert!(lv.flags & LIFT != 0);
        let first: Vec<(ElementLevels, Before)> = lr.iter().map(|r| first_levels(&lv, r)).collect();
        let after = frame_levels(&lv, &lr);
        let d = |x: f32| drawn_level(x, false, max);
        let tris = |l: &mut dyn Iterator<Item = f32>| l.map(|x| (d(x) as u64).pow(2)).sum::<u64>();
        let (before_tris, after_tris) = (
            tris(&mut first.iter().map(|f| f.0.inner)),
            tris(&mut after.iter().map(|l| l.inner)),
        );
        assert!(
            after_tris < before_tris,
            "{px} px: {after_tris} >= {before_tris}"
        );
        for (i, (r, l)) in lr.iter().zip(&after).enumerate() {
            let (f, me) = first[i];
            // One level per edge, the same bits from both sides.
            for e in 0..3 {
                let (j, f2) = (
                    (r.neighbours[e] / 4) as usize,
                    (r.neighbours[e] % 4) as usize,
                );
                assert_eq!(l.edges[e].to_bits(), after[j].edges[f2].to_bits());
            }
            if l.edges == f.edges {
                assert_eq!(*l, f, "{px} px: element {i} without a lifted edge");
                continue;
            }
            saved += (d(l.inner) < d(f.inner)) as usize;
            for e in 0..3 {
                if l.edges[e] == f.edges[e] {
                    continue;
                }
                lifted += 1;
                let n = l.edges[e];
                assert_eq!(n, n.round(), "{px} px: element {i} edge {e} lifted to {n}");
                let n = n as u32;
                assert!(n > d(f.edges[e]) && n <= d(l.inner));
                assert_ne!(r.neighbours[e], SHARED);
                // The proposer: this element, or the one across.
                let nb = r.neighbours[e];
                let across = (nb != BOUNDARY).then_some(((nb / 4) as usize, (nb % 4) as usize));
                let proposed = |b: &Before, slot: usize, other: Option<&Before>| {
                    b.failing >> slot & 1 == 1
                        && d(b.own) == n
                        && other.is_none_or(|o| o.inner == 0.0 || d(o.inner) >= n)
                };
                let by_me = proposed(&me, e, across.map(|(j, _)| &first[j].1));
                let by_other = across.is_some_and(|(j, f2)| proposed(&first[j].1, f2, Some(&me)));
                assert!(
                    by_me || by_other,
                    "{px} px: element {i} edge {e} lifted to {n}"
                );
                proposals += by_me as usize;
            }
        }
    }
    eprintln!(
        "{lifted} edge slots lifted ({proposals} by their own element), {saved} raises saved"
    );
    assert!(lifted > 100 && proposals > 50 && saved > 50);
}
