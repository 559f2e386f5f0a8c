//! The height map's bounds on the textured grid: kink terms tight where every kink bends one
//! way, read from the texels under each patch, none far out.

use super::*;

/// A 64 × 64 map of piecewise parabolas, `t = 0.5 + (q(x) + q(y)) / 4` with `q` rising and
/// falling over 8 texels each, C1 where they meet: every texel line is a kink of one sign over
/// an element of `grid_uv_8x8.obj` (8 texels across), as in a sampled curved height field, the
/// case where the kink terms are nearly exact.
fn parabola_map() -> Heightmap {
    let q = |x: u32| {
        let s = x as f32 + 0.5;
        let r = s % 8.0;
        let up = r * (8.0 - r) / 16.0;
        if s % 16.0 < 8.0 {
            up
        } else {
            -up
        }
    };
    let texels = (0..64 * 64)
        .map(|i| 0.5 + 0.25 * (q(i % 64) + q(i / 64)))
        .collect();
    Heightmap::from_heights("parabolas", 64, 64, texels)
}

/// The grid's element `t` displaced by `map` (10% of the grid's radius about mid-height),
/// read at pyramid level 0 alone.
pub(super) fn grid_case<'a>(
    grid: &Mesh,
    uvs: &'a [[[f32; 2]; 3]],
    map: &'a Heightmap,
    t: usize,
) -> Case<'a> {
    Case {
        surface: Surface::Flat,
        field: NormalField::default(),
        displace: Displace::Heightmap,
        params: SurfaceParams {
            amplitude: 0.1 * grid.bounding_radius(),
            bias: 0.5,
            ..Default::default()
        },
        inputs: Sources {
            uvs: Some(std::slice::from_ref(&uvs[t])),
            heightmap: Some(map),
            lod: 0.0,
            ..Default::default()
        },
    }
}

/// `grid_uv_8x8.obj`, its records and its elements' texture coordinates.
pub(super) fn uv_grid() -> (Mesh, Vec<ElementRecord>, Vec<[[f32; 2]; 3]>) {
    textured("grid_uv_8x8.obj")
}

/// A model with texture coordinates on every face, its records and each element's
/// coordinates.
pub(super) fn textured(file: &str) -> (Mesh, Vec<ElementRecord>, Vec<[[f32; 2]; 3]>) {
    let (mesh, _) = load_model(file);
    let recs = build_records(RecordKind::Corners, &mesh, Seams::Closed);
    let uvs = (mesh.triangles.iter())
        .map(|t| t.t.unwrap().map(|i| mesh.texcoords[i as usize].to_array()))
        .collect();
    (mesh, recs, uvs)
}

/// The height map's kink terms are tight where every kink bends the same way: on the parabola
/// map, read at one pyramid level, the bounds hold, the elements' come within 2.2x of the truth
/// and half of the edges' is caught (the peak-weight jump and the rest at the mean weight: a
/// total-variation bound at the peak weight alone would be about twice the truth).
#[test]
fn height_map_kink_bounds_are_tight() {
    let (grid, recs, uvs) = uv_grid();
    let map = parabola_map();
    let (r, levels) = (grid.bounding_radius(), [1, 2, 4, 8]);
    let (mut caught, mut tightest, mut checked) = (0, f32::INFINITY, 0);
    for t in (0..recs.len()).step_by(7) {
        let case = grid_case(&grid, &uvs, &map, t);
        let one = std::slice::from_ref(&recs[t]);
        let (min, _) = case.check(one, &levels, r, "parabola map");
        tightest = tightest.min(min);
        let half =
            std::panic::catch_unwind(|| case.check_lod(&case.lod(), one, &levels, r, "half", 0.5));
        caught += half.is_err() as usize;
        checked += 1;
    }
    // Elements whose edges bend one way inside (no lattice direction along which the two
    // families' kinks cancel) come within 2.2x; the edges, 1D, within about 1.3x everywhere,
    // so half of every element's edges' bounds is caught.
    eprintln!("height map on the parabola map: tightest element bound {tightest}x the truth");
    assert!(
        tightest <= 2.2,
        "the element bounds are {tightest}x the truth or more"
    );
    assert_eq!(
        caught, checked,
        "half the edges' bounds went unnoticed on some elements"
    );
}

/// An element's height-map bound reads the texels under it: on a 256 × 256 map flat but for a
/// rough 2 × 2 patch of texels (175 and 176 both ways, inside the grid's quad 5, 5, which
/// covers texels 160 to 191), the two elements of that quad get kink terms and the others none
/// (and no height: their spheres are the undisplaced patch's), and every bound holds against
/// dense sampling, the patch's elements and their edges included.
#[test]
fn height_map_bounds_are_local() {
    let (grid, recs, uvs) = uv_grid();
    let rough = [0.05, 0.9, 0.7, 0.0];
    let texels = (0..256 * 256)
        .map(|i| match (i % 256, i / 256) {
            (x @ 175..=176, y @ 175..=176) => rough[(x - 175) + 2 * (y - 175)],
            _ => 0.5,
        })
        .collect();
    let map = Heightmap::from_heights("rough patch", 256, 256, texels);
    let (r, levels) = (grid.bounding_radius(), [1, 3, 8]);
    let mut kinked = Vec::new();
    for (t, rec) in recs.iter().enumerate() {
        let case = grid_case(&grid, &uvs, &map, t);
        case.check(std::slice::from_ref(rec), &levels, r, "rough patch");
        let b = case.lod().element(rec);
        if b.kink.c1 > 1e-5 || b.kink.c2 > 1e-5 {
            kinked.push(t);
            continue;
        }
        // Nothing moves there: the sphere is the undisplaced patch's.
        let still = Case {
            displace: Displace::None,
            ..grid_case(&grid, &uvs, &map, t)
        };
        let r0 = still.lod().element(rec).sphere.radius;
        assert!(
            b.sphere.radius <= r0 * (1.0 + 1e-6),
            "element {t}: sphere {b:?}"
        );
    }
    let quad = |t: &usize| {
        uvs[*t]
            .iter()
            .all(|c| c.iter().all(|&u| (0.625..=0.75).contains(&u)))
    };
    assert_eq!(kinked.len(), 2, "elements with kink terms: {kinked:?}");
    assert!(
        kinked.iter().all(quad),
        "elements with kink terms: {kinked:?}"
    );
}

/// Texture coordinates past `2^18` texels of the level read (the grid's shifted by 10^4 map
/// widths, 2.56 M texels of a 256-texel map): the sampler's heights step by fractions of a
/// texel and more, so a map with any relief gives no finite bound, and a flat one the
/// undisplaced patch's.
#[test]
fn height_map_far_out_is_unbounded_unless_flat() {
    let (grid, recs, uvs) = uv_grid();
    let far: Vec<[[f32; 2]; 3]> = uvs.iter().map(|t| t.map(|c| c.map(|u| u + 1e4))).collect();
    let bumps = Heightmap::generated();
    let flat = Heightmap::from_heights("flat", 256, 256, vec![0.25; 256 * 256]);
    for t in [0, 37, 127] {
        let near = grid_case(&grid, &uvs, &bumps, t).lod().element(&recs[t]);
        assert!(near.chord.c2.is_finite(), "element {t}: {near:?}");
        let b = grid_case(&grid, &far, &bumps, t).lod().element(&recs[t]);
        assert!(b.chord.c2.is_infinite(), "element {t}: {b:?}");
        let b = grid_case(&grid, &far, &flat, t).lod().element(&recs[t]);
        assert!(
            b.kink == Chord::ZERO && b.chord.c2.is_finite(),
            "element {t}: {b:?}"
        );
    }
}

/// The height map on a curved, textured mesh, on every surface that carries it: the terrain
/// (its own texture coordinates and normals, so `phong`, `pn` and `stpn` bend away from the
/// flat triangles, `stpn` with the tags derived from its mesh) displaced by the generated map,
/// read at pyramid levels 0 and 1.5; every element and edge bound holds against dense sampling.
#[test]
fn height_map_bounds_hold_on_every_surface() {
    let (terrain, recs, uvs) = textured("terrain_16x16.obj");
    let (tags, _) = crate::surface::stpn::derive(&terrain);
    let map = Heightmap::generated();
    let r = terrain.bounding_radius();
    for surface in [Surface::Flat, Surface::Phong, Surface::Pn, Surface::Stpn] {
        for lod in [0.0, 1.5] {
            let what = format!(
                "heightmap on the terrain as {} at lod {lod}",
                surface.name()
            );
            let case = Case {
                surface,
                field: NormalField::default(),
                displace: Displace::Heightmap,
                params: SurfaceParams {
                    amplitude: 0.05 * r,
                    bias: 0.5,
                    ..Default::default()
                },
                inputs: Sources {
                    uvs: Some(&uvs),
                    heightmap: Some(&map),
                    tags: Some(&tags),
                    lod,
                    ..Default::default()
                },
            };
            for t in (0..recs.len()).step_by(23) {
                let one = std::slice::from_ref(&recs[t]);
                case.element(t).check(one, &[1, 2, 5], r, &what);
            }
        }
    }
}
