//! Culling's view of the surface: which eyes are outside it (facing-away culling, the
//! wireframe's front-only test), from the bounds' spheres or the spheres alone.

use super::view::close_camera;
use super::*;

/// Faces facing away are culled only for an eye outside the surface: not from inside spot, not
/// from just outside its cage (inside an element's sphere, where the curved surface may bulge
/// past the eye), and again from the close camera and from far away.
#[test]
fn back_faces_are_culled_only_from_outside() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let (eye, _, _, _) = close_camera(&spot);
    let case = Case::plain(Surface::Pn, Displace::None, SurfaceParams::default());
    let records = crate::lod::frame::lod_records(&case.lod(), &recs);
    let outside = |e: Vec3| crate::lod::cull::eye_outside(e, &records, &spot);
    let (lo, hi) = spot.bounds();
    let centre = (lo + hi) * 0.5;
    assert!(outside(eye));
    assert!(outside(
        centre + Vec3::new(0.0, 0.0, 50.0 * spot.bounding_radius())
    ));
    assert!(!outside(centre));
    // A hair outside the cage, off a face's centre along its normal.
    let t = spot.triangles[10].p.map(|i| spot.positions[i as usize]);
    let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
    let near = (t[0] + t[1] + t[2]) / 3.0 + n * 1e-3;
    assert!(spot.winding_number(near).abs() < 1e-6);
    assert!(!outside(near));
}

/// The spheres the wireframe tells an eye outside the surface from, where no bounds are at hand
/// (`Lod::undisplaced_sphere`), are the very spheres of the elements' bounds, for every local
/// surface undisplaced, so both give the same answer; a displaced surface and `loop` have none.
#[test]
fn undisplaced_spheres_are_the_bounds_spheres() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    for surface in [Surface::Flat, Surface::Phong, Surface::Pn, Surface::Stpn] {
        for displace in [Displace::None, Displace::Sine] {
            let params = SurfaceParams::for_radius(spot.bounding_radius());
            let case = Case::plain(surface, displace, params);
            let lod = case.lod();
            for (t, rec) in recs.iter().enumerate() {
                let sphere = lod.for_element(t).undisplaced_sphere(rec);
                match displace {
                    Displace::None => assert_eq!(
                        sphere,
                        Some(lod.for_element(t).element(rec).sphere),
                        "{} element {t}",
                        surface.name()
                    ),
                    _ => assert_eq!(sphere, None, "{} + sine", surface.name()),
                }
            }
        }
    }
    let (eye, _, _, _) = close_camera(&spot);
    let case = Case::plain(Surface::Pn, Displace::None, SurfaceParams::default());
    let (lod, records) = (
        case.lod(),
        crate::lod::frame::lod_records(&case.lod(), &recs),
    );
    let (lo, hi) = spot.bounds();
    for e in [eye, (lo + hi) * 0.5, hi * 1.01, lo * 3.0] {
        let spheres = recs.iter().map(|r| lod.undisplaced_sphere(r).unwrap());
        assert_eq!(
            crate::lod::cull::eye_outside_spheres(e, spheres, &spot),
            crate::lod::cull::eye_outside(e, &records, &spot),
            "{e}"
        );
    }
}
