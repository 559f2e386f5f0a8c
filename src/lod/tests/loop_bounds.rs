//! `loop`'s bounds against dense sampling: undisplaced and displaced, at powers of two and at
//! integer levels, for each way a driver rounds (src/surface/loop_bound.rs).

use super::bounds::sampled_mixed;
use super::view::{rounding_name, Screen};
use super::*;

/// Loop: spot's M1 faces, at dyadic and other levels, with extraordinary vertices of valence 3
/// to 10; and its mixed bounds against its lattice.
#[test]
fn loop_bounds_hold() {
    let (mesh, _) = load_model("spot_control_tri.obj");
    let data = LoopData::new(&mesh, Boundary::EdgeOnly, Lattice::default(), |_| {}).unwrap();
    let frame = data.frame(&mesh.positions);
    let case = Case::loop_(&data, &frame, Displace::None, SurfaceParams::default());
    // Every 23rd face, and a face beside an extraordinary vertex of every valence Spot has
    // (3 to 10): a face's control points are 12 where its corners are regular, `n + 6` beside
    // one of valence `n`.
    let k = |f: usize| data.faces[f][1] & 0xFFFF;
    let mut sampled: Vec<usize> = (0..data.faces.len()).step_by(23).collect();
    for n in [3, 4, 5, 7, 8, 9, 10] {
        let f = (0..data.faces.len()).find(|&f| k(f) == n + 6);
        sampled.push(f.unwrap_or_else(|| panic!("no face beside valence {n}")));
    }
    let records: Vec<ElementRecord> = sampled.iter().map(|&f| data.records[f]).collect();
    let (_, m) = case.check(&records, &[1, 2, 3, 4, 8], mesh.bounding_radius(), "loop");
    assert!(m <= 20.0, "loop: median bound / truth {m}");
    // Integer levels whose samples are not lattice points, up to and past the lattice's (the
    // tessellator's integer levels, which `Lod::new` takes); and the powers of two of the
    // pattern driver, whose samples are, without the kink terms that pay for that.
    let r = mesh.bounding_radius();
    let some = every(&data.records, 61);
    case.check(&some, &[6, 12, 24, 31, 40, 63], r, "loop at integer levels");
    let snapped = case.lod().drawn_as(Rounding::Snapped);
    case.check_lod(
        &snapped,
        &some,
        &[16, 32, 64],
        r,
        "loop at powers of two",
        1.0,
    );
    case.check_lod(
        &snapped,
        &every(&data.records, 23),
        &[1, 2, 4, 8],
        r,
        "loop at powers of two",
        1.0,
    );
    // Not vacuous: without those terms the integer levels pass their bound (the edges' first).
    let bare = std::panic::catch_unwind(|| {
        case.check_lod(
            &snapped,
            &some,
            &[24, 31],
            r,
            "loop's powers of two at integers",
            1.0,
        )
    });
    assert!(
        bare.is_err(),
        "integer levels met the bound of powers of two"
    );
    // The mixed bounds are the lattice's mixed differences (or polarization's `Σ/2` where
    // smaller): sampled on that lattice they agree, which pins the pairs' order, and they are
    // below `Σ/2` somewhere (else the lattice's own would add nothing).
    let lod = case.lod();
    let mut tighter = 0;
    for rec in every(&data.records, 17) {
        let s = 1i32 << (data.faces[rec.words[0] as usize][3] >> 3);
        let b = lod.element(&rec);
        let (lattice, _) = sampled_mixed(&case, &rec, s);
        let half = 0.5 * b.second.iter().sum::<f32>();
        for (k, (&got, &sampled)) in b.mixed.iter().zip(&lattice).enumerate() {
            let want = sampled.min(half);
            assert!(
                (got - want).abs() <= 1e-5 * want,
                "pair {k}: bound {got} against the lattice's {want}"
            );
            tighter += usize::from(sampled < 0.9 * half);
        }
    }
    assert!(tighter > 10, "only {tighter} pairs below Σ/2");
    // A displacement that moves nothing (zero amplitude, a sine or noise of frequency zero)
    // keeps the limit surface's bounds, edges and elements alike; one that moves has its own.
    let moving = SurfaceParams::for_radius(r);
    let still = [
        (
            Displace::Sine,
            SurfaceParams {
                amplitude: 0.0,
                ..moving
            },
        ),
        (
            Displace::Sine,
            SurfaceParams {
                frequency: 0.0,
                ..moving
            },
        ),
        (
            Displace::Noise,
            SurfaceParams {
                frequency: 0.0,
                ..moving
            },
        ),
    ];
    let with = |displace, params| Case::loop_(&data, &frame, displace, params);
    for rec in every(&data.records, 29) {
        for (displace, params) in still {
            let c = with(displace, params);
            let what = format!("{} {params:?}", displace.name());
            assert_eq!(c.lod().element(&rec), lod.element(&rec), "{what}");
            for e in 0..3 {
                assert_eq!(c.lod().edge(&rec, e), lod.edge(&rec, e), "{what}");
            }
        }
        let b = with(Displace::Sine, moving).lod().element(&rec);
        let still = lod.element(&rec);
        assert!(
            b.chord.c2.is_finite() && b.chord.c2 != still.chord.c2,
            "{b:?}"
        );
        assert!(b.sphere.radius > still.sphere.radius, "{b:?}");
    }
    // Displaced: `sine` and `noise` at their default amplitude and frequency, at integer levels
    // up to the tables' lattice (32) and beyond, every edge too, and at powers of two as the
    // pattern driver draws them; and the bound is not loose everywhere: an eighth of it fails
    // somewhere (the share inside the cells, E_k, counts at every level as at the lattice's).
    // Noise's bounds are the loosest (its scanned constants hold for every gradient choice).
    for (displace, loose) in [(Displace::Sine, 20.0), (Displace::Noise, 40.0)] {
        let case = with(displace, moving);
        let what = format!("loop + {}", displace.name());
        let some = every(&data.records, 97);
        case.check(&some, &[3, 5, 24, 31, 48], r, &what);
        let snapped = case.lod().drawn_as(Rounding::Snapped);
        let (_, m) = case.check_lod(&snapped, &some, &[1, 2, 4, 8, 16, 32, 64], r, &what, 1.0);
        assert!(m <= loose, "{what}: median bound / truth {m}");
        let less = std::panic::catch_unwind(|| {
            case.check_lod(&snapped, &some, &[2, 4, 8], r, "less", 0.125)
        });
        assert!(
            less.is_err(),
            "{what}: an eighth of the bound went unnoticed"
        );
    }
}

/// `loop`'s bounds built for a gliding driver (no kink terms for samples off the tables'
/// lattice) hold at its powers of two alone, so the uniform level its adaptive frames are
/// compared with is the smallest power of two meeting them. Read as any integer, as the other
/// surfaces' are, they would claim integer levels that the bounds built for integer levels
/// (which hold there, `loop_bounds_hold`) say miss the pixel error.
#[test]
fn loops_uniform_level_while_gliding_is_a_power_of_two() {
    use crate::lod::frame::{frame_levels, lod_records, uniform_level, LodView};
    let (mesh, _) = load_model("spot_control_tri.obj");
    let data = LoopData::new(&mesh, Boundary::EdgeOnly, Lattice::default(), |_| {}).unwrap();
    let frame = data.frame(&mesh.positions);
    let case = Case::loop_(&data, &frame, Displace::None, SurfaceParams::default());
    let count = data.records.len() as u32;
    let records = |rounding| lod_records(&case.lod().drawn_as(rounding), &data.records);
    let pairs = [
        (Rounding::Snapped, Rounding::SnappedInteger),
        (Rounding::TessSnapped, Rounding::Integer),
    ];
    let mut understated = 0;
    for (gliding, integer) in pairs {
        let (lr, li) = (records(gliding), records(integer));
        for px in [0.5, 1.0, 2.0, 4.0] {
            let screen = Screen::new(&mesh, px);
            let view = |rounding| {
                LodView::new(&screen.view, Some(&screen.frustum), false, rounding, count)
            };
            let lv = view(gliding).with_lattice_bounds(true);
            let levels = frame_levels(&lv, &lr);
            let uniform = uniform_level(&lv, &lr, &levels);
            // As any integer, from the same records, and what integer levels need of the same
            // elements by their own records.
            let any = uniform_level(&view(gliding), &lr, &levels);
            let at_integers = uniform_level(&view(integer), &li, &levels);
            eprintln!(
                "loop{} at {px} px: uniform {uniform}, as any integer {any}, integer levels need {at_integers}",
                rounding_name(gliding)
            );
            assert_eq!(uniform, any.next_power_of_two().min(screen.view.max_level));
            assert!(uniform.is_power_of_two() && uniform <= screen.view.max_level);
            understated += usize::from(any < at_integers && !any.is_power_of_two());
        }
    }
    assert!(
        understated > 0,
        "any integer claimed nothing integer levels miss"
    );
}
