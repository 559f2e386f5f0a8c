//! The lift (src/lod/frame/lift.rs) on Spot close up: what it lifts and to what, checked from
//! the first pass's levels, and one level per edge from both sides; the pixel error it keeps in
//! `pixel_error_holds_end_to_end` (src/lod/tests/view.rs, the snapped integer levels), and the
//! GPU's second dispatch against this mirror in tests/level_pass.rs.

use super::lift::{Before, BOUNDARY, SHARED};
use super::*;
use crate::lod::frame::own_level;
use crate::lod::levels::drawn_level;
use crate::mesh::test_support::load_model;
use crate::surface::{build_records, Displace, RecordKind, Seams, Sources, Surface, SurfaceParams};

/// The bundled mesh `file` as `pn`: its bounding radius and its records' bounds.
fn pn_records(file: &str) -> (f32, Vec<LodRecord>) {
    let (mesh, _) = load_model(file);
    let recs = build_records(RecordKind::Corners, &mesh, Seams::Closed);
    let r = mesh.bounding_radius();
    let params = SurfaceParams::for_radius(r);
    let lod = Lod::of(Surface::Pn, Displace::None, &params, &Sources::default());
    (r, lod_records(&lod, &recs))
}

/// Every edge the lift changes is drawn at the unraised inner level of one of its elements whose
/// transition triangles along it did not fit there, above its first level, where the element
/// across draws at least as fine (or draws nothing); every other edge keeps its first level; an
/// element without a lifted edge keeps its levels; both elements of an edge (a closed mesh: all
/// have two) hold the same bits for it; and the frame draws fewer triangles.
#[test]
fn lifted_edges_take_an_inner_level_the_element_across_already_draws() {
    let (_, lr) = pn_records("spot_control_tri.obj");
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

/// Where levels glide, every edge of a drawn element takes the largest of its first level and
/// the insides' own needs of both its elements, a culled one's included (so culling changes no
/// drawn element's levels), the same bits from both sides, so that every vertex of an element
/// glides at least as far as its inside needs; and levels change with the camera continuously,
/// with elements turning away and leaving the view on the way (no edge jumps).
#[test]
fn gliding_edges_follow_the_insides_beside_them() {
    let (r, lr) = pn_records("spot_control_tri.obj");
    let count = lr.len() as u32;
    let target = Vec3::new(0.0, 0.5, -0.5);
    let frame = |eye: Vec3, px: f32, rounding: Rounding| {
        let mut proj = glam::Mat4::perspective_rh(0.8, 16.0 / 9.0, 0.01 * r, 10.0 * r);
        proj.y_axis.y = -proj.y_axis.y;
        let frustum = crate::lod::Frustum::from_view_proj(
            proj * glam::Mat4::look_at_rh(eye, target, Vec3::Y),
        );
        let view = View::new(eye, 0.8, 1080, px, 64);
        LodView::new(&view, Some(&frustum), true, rounding, count)
    };
    for rounding in [Rounding::Snapped, Rounding::TessSnapped] {
        let mut lifted = 0;
        for px in [0.5, 1.0, 4.0] {
            let lv = frame(Vec3::new(0.35, 0.65, -1.3), px, rounding);
            assert!(super::lift::gliding(&lv));
            let first: Vec<ElementLevels> = lr.iter().map(|x| first_levels(&lv, x).0).collect();
            let after = frame_levels(&lv, &lr);
            let culled = after.iter().filter(|l| l.culled()).count();
            assert!(culled > 20, "{px} px: {culled} culled");
            for (i, (x, l)) in lr.iter().zip(&after).enumerate() {
                if l.culled() {
                    continue;
                }
                let inside = own_level(&lv, x);
                for e in 0..3 {
                    let nb = x.neighbours[e];
                    assert!(nb != BOUNDARY && nb != SHARED);
                    let (j, f) = ((nb / 4) as usize, (nb % 4) as usize);
                    let want = first[i].edges[e].max(inside.max(own_level(&lv, &lr[j])));
                    assert_eq!(l.edges[e].to_bits(), want.to_bits(), "element {i} edge {e}");
                    if !after[j].culled() {
                        assert_eq!(l.edges[e].to_bits(), after[j].edges[f].to_bits());
                    }
                    lifted += (l.edges[e] > first[i].edges[e]) as usize;
                }
                assert!(l.inner >= l.edges.iter().copied().fold(inside, f32::max));
            }
        }
        assert!(lifted > 100, "{rounding:?}: {lifted} edge slots lifted");
        // Continuity: the eye moves toward and past the head in steps of 0.2 % of its distance;
        // an edge's level changes by about half that (levels go as the root of the distance).
        let mut eye = Vec3::new(1.2, 0.9, -2.6);
        let step = (target - eye) * 0.002;
        let mut last: Option<Vec<ElementLevels>> = None;
        let (mut worst, mut turned) = (0.0f32, 0);
        for _ in 0..300 {
            let now = frame_levels(&frame(eye, 1.0, rounding), &lr);
            if let Some(prev) = &last {
                for (a, b) in prev.iter().zip(&now) {
                    turned += (a.culled() != b.culled()) as usize;
                    if a.culled() || b.culled() {
                        continue;
                    }
                    for e in 0..3 {
                        worst = worst.max((b.edges[e] / a.edges[e]).ln().abs());
                    }
                }
            }
            last = Some(now);
            eye += step;
        }
        eprintln!("{rounding:?}: worst edge step {worst}, {turned} culling changes");
        assert!(turned > 5, "{rounding:?}: {turned} culling changes");
        assert!(
            worst < 0.01,
            "{rounding:?}: an edge level jumped by {worst}"
        );
    }
}

/// On an open mesh (the terrain) a gliding boundary edge takes the largest of its first level
/// and its one element's inside need, and a shared edge the largest of both insides'.
#[test]
fn gliding_boundary_edges_follow_their_one_inside() {
    let (_, lr) = pn_records("terrain_16x16.obj");
    let view = View::new(Vec3::new(0.0, 0.45, -2.6), 0.8, 1080, 1.0, 64);
    let (mut boundary, mut lifted) = (0, 0);
    for rounding in [Rounding::Snapped, Rounding::TessSnapped] {
        let lv = LodView::new(&view, None, false, rounding, lr.len() as u32);
        let first: Vec<ElementLevels> = lr.iter().map(|x| first_levels(&lv, x).0).collect();
        let after = frame_levels(&lv, &lr);
        for (i, (x, l)) in lr.iter().zip(&after).enumerate() {
            let inside = own_level(&lv, x);
            for e in 0..3 {
                let nb = x.neighbours[e];
                assert_ne!(nb, SHARED);
                let other = if nb == BOUNDARY {
                    boundary += 1;
                    inside
                } else {
                    own_level(&lv, &lr[(nb / 4) as usize])
                };
                let want = first[i].edges[e].max(inside.max(other));
                assert_eq!(l.edges[e].to_bits(), want.to_bits(), "element {i} edge {e}");
                lifted += (nb == BOUNDARY && l.edges[e] > first[i].edges[e]) as usize;
            }
        }
    }
    assert!(
        boundary > 100 && lifted > 10,
        "{boundary} boundary slots, {lifted} lifted"
    );
}
