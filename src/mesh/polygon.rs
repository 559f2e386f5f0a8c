//! Triangulating an OBJ polygon (a face of more than three corners): a convex polygon as a fan
//! from its first corner (`0 1 2`, `0 2 3`, ...: what `tobj` makes, and what a reader of the file
//! expects; from another corner where that fan would hold a triangle of zero area, which the
//! loader would drop, opening a hole), a concave one by ear clipping in its plane, so that its triangles cover it exactly,
//! without overlapping or turning over where a fan would. A polygon that crosses itself, or
//! touches itself at a corner it lists twice, has no such triangulation: it gets triangles for
//! every corner but two all the same, which may overlap, and [`triangulate`] says so (the
//! loader warns, naming its line).
#![forbid(unsafe_code)]

use glam::{DVec2, DVec3, Vec3};

/// Concave polygons with more corners than this are fanned (ear clipping takes a time that grows
/// with the square of the corners, and with their cube at worst); convex ones are cut corner by
/// corner in linear time where their first corner's fan would hold a flat triangle.
pub const MAX_CLIPPED_CORNERS: usize = 256;

/// A turn this small against the product of its two sides' lengths is no turn (the projection
/// into the plane, in `f64`), nor one within the rounding of the corners' `f32` coordinates
/// ([`Plane::slack`]): corners on a line with their neighbours, as a T-junction's, either way.
const STRAIGHT: f64 = 1e-9;

/// A polygon's corners in its plane, and how far off it rounding may have put them.
struct Plane {
    p: Vec<DVec2>,
    /// `4 ε` times the largest coordinate: what a straight corner's turn may be off, per unit
    /// length of its two sides.
    slack: f64,
}

/// The triangles of the polygon with corner positions `corners` (in the face's order), as
/// triples of corner numbers wound as the polygon is: a fan where the polygon is convex (corners
/// on a line with their neighbours included) or has no plane (every corner on a line, or lobes
/// whose areas cancel), else its ears clipped one by one (what is left fanned where no ear can
/// be found: a polygon crossing itself), or fanned where it is concave with more corners than
/// [`MAX_CLIPPED_CORNERS`]. With whether they cover it without turning over: false where a
/// triangle is wound against the polygon's plane (a polygon crossing or touching itself, or
/// too large to clip), or has area where the polygon has no plane.
pub fn triangulate(corners: &[Vec3]) -> (Vec<[usize; 3]>, bool) {
    let n = corners.len();
    let fan = || -> Vec<[usize; 3]> { (2..n).map(|k| [0, k - 1, k]).collect() };
    if n <= 3 {
        return (fan(), true);
    }
    let largest = corners
        .iter()
        .map(|c| c.abs().max_element())
        .fold(0.0f32, f32::max);
    let slack = 4.0 * f32::EPSILON as f64 * largest as f64;
    let Some(p) = in_plane(corners) else {
        let triangles = fan();
        let flat = triangles.iter().all(|&t| !has_area(corners, t, slack));
        return (triangles, flat);
    };
    let flat = Plane { p, slack };
    if (0..n).all(|i| corner_turn(&flat, i) >= 0) {
        // Convex where it turns once round; a pentagram's fan overlaps.
        return (convex(&flat), turns_once(&flat));
    }
    if n > MAX_CLIPPED_CORNERS {
        return (fan(), false);
    }
    let triangles = clip_ears(&flat);
    let covers = triangles.iter().all(|&[a, b, c]| turn(&flat, a, b, c) >= 0) && simple(&flat);
    (triangles, covers)
}

/// A convex polygon's triangles: the fan from its first corner, unless a side on a line with
/// that corner (beside a corner on a line with its neighbours, as at a T-junction) would make a
/// triangle of zero area, which the loader would drop, opening a hole: then the fan from the
/// first corner that makes none, else (several corners in a line on more than one side) its
/// ears clipped, which take turning corners first; with more corners than
/// [`MAX_CLIPPED_CORNERS`], zipped between two chains in linear time ([`clip_convex`]). Where
/// every choice leaves a flat triangle, the first corner's fan.
fn convex(plane: &Plane) -> Vec<[usize; 3]> {
    let n = plane.p.len();
    let fan = |c: usize| -> Vec<[usize; 3]> {
        (2..n).map(|k| [c, (c + k - 1) % n, (c + k) % n]).collect()
    };
    let flat = |t: &[[usize; 3]]| t.iter().any(|&[a, b, c]| turn(plane, a, b, c) <= 0);
    let first = fan(0);
    if !flat(&first) {
        return first;
    }
    if n > MAX_CLIPPED_CORNERS {
        // Where rounding leaves the zip without a move (a corner straight within rounding
        // beside its short sides turns off a long diagonal), the fan from a turning corner
        // that makes no flat triangle, a few tried (linear time still).
        let turning = |&c: &usize| corner_turn(plane, c) > 0;
        return clip_convex(plane)
            .filter(|t| !flat(t))
            .or_else(|| (0..n).filter(turning).take(64).map(fan).find(|t| !flat(t)))
            .unwrap_or(first);
    }
    (1..n)
        .map(fan)
        .find(|t| !flat(t))
        .or_else(|| Some(clip_ears(plane)).filter(|t| !flat(t)))
        .unwrap_or(first)
}

/// A convex counter-clockwise polygon's triangles without a flat one, in time linear in its
/// corners (for polygons too large for the fans' search and [`clip_ears`]): zipped between its
/// two chains from a corner `u` that turns, each triangle a diagonal across the polygon and the
/// next corner of one chain: the chain that is behind (by the share of its corners passed, the
/// chains meeting about opposite `u`), unless its triangle would be flat or leave the rest
/// flat, then the other (one of the two always does neither). Triangles across the polygon
/// keep their height where a side holds many corners on a line (cutting corners one by one
/// leaves slivers there, flat within rounding). `None` where no corner turns.
fn clip_convex(plane: &Plane) -> Option<Vec<[usize; 3]>> {
    let n = plane.p.len();
    let turns: Vec<bool> = (0..n).map(|i| corner_turn(plane, i) > 0).collect();
    // Turning corners before each index, and strictly between l and r counter-clockwise: the
    // rest of the polygon, l to r, has area exactly where one of its corners but those turns
    // (in a convex polygon a corner between two others on a line goes straight on).
    let mut before = vec![0usize; n + 1];
    for i in 0..n {
        before[i + 1] = before[i] + usize::from(turns[i]);
    }
    let between = |l: usize, r: usize| {
        if l < r {
            before[r] - before[l + 1]
        } else {
            before[n] - before[l + 1] + before[r]
        }
    };
    let (next, prev) = (|i: usize| (i + 1) % n, |i: usize| (i + n - 1) % n);
    let u = (0..n).find(|&i| turns[i] && between(next(i), prev(i)) > 0)?;
    let far = |i: usize| (i + n - u) % n;
    let mut out = Vec::with_capacity(n - 2);
    let (mut l, mut r) = (next(u), prev(u));
    out.push([r, u, l]);
    while next(l) != r {
        let (l2, r2) = (next(l), prev(r));
        let last = next(l2) == r;
        let flat = |[a, b, c]: [usize; 3]| turn(plane, a, b, c) <= 0;
        let left_ok = !flat([r, l, l2]) && (last || between(l2, r) > 0);
        let right_ok = !flat([r2, r, l]) && (last || between(l, r2) > 0);
        // The left chain (counter-clockwise from u) is behind when it has passed fewer corners.
        let behind = far(l) <= n - far(r);
        let left = match (left_ok, right_ok) {
            (false, false) => return None,
            (true, true) => behind,
            (ok, _) => ok,
        };
        if left {
            out.push([r, l, l2]);
            l = l2;
        } else {
            out.push([r2, r, l]);
            r = r2;
        }
    }
    Some(out)
}

/// Whether the polygon turns once round (its exterior angles sum to one turn, not two or more
/// as a pentagram's): with no corner turning right, it is then convex. Only the corners that
/// [`turn`] finds turning left count: a corner straight within rounding (a zigzag of `f32`
/// crumbs, a repeated corner) turns by nothing.
fn turns_once(plane: &Plane) -> bool {
    let (p, n) = (&plane.p, plane.p.len());
    let total: f64 = (0..n)
        .filter(|&i| corner_turn(plane, i) > 0)
        .map(|i| {
            let (u, v) = (p[i] - p[(i + n - 1) % n], p[(i + 1) % n] - p[i]);
            cross(u, v).atan2(u.dot(v))
        })
        .sum();
    total < 3.0 * std::f64::consts::PI
}

/// Whether no two sides of the polygon cross (beyond rounding; sides meeting at a corner, or
/// touching, do not count).
fn simple(plane: &Plane) -> bool {
    let (p, n) = (&plane.p, plane.p.len());
    let side = |a: DVec2, b: DVec2, q: DVec2| {
        let (u, v) = (b - a, q - a);
        let t = cross(u, v);
        let (lu, lv) = (u.length(), v.length());
        if t.abs() <= STRAIGHT * lu * lv + plane.slack * (lu + lv) {
            0
        } else {
            t.signum() as i32
        }
    };
    (0..n).all(|i| {
        let (a, b) = (p[i], p[(i + 1) % n]);
        (i + 2..n).filter(|&j| (j + 1) % n != i).all(|j| {
            let (c, d) = (p[j], p[(j + 1) % n]);
            side(a, b, c) * side(a, b, d) >= 0 || side(c, d, a) * side(c, d, b) >= 0
        })
    })
}

/// Whether triangle `t` of `corners` has an area beyond rounding (as [`turn`] judges a turn).
fn has_area(corners: &[Vec3], t: [usize; 3], slack: f64) -> bool {
    let [a, b, c] = t.map(|i| corners[i].as_dvec3());
    let (u, v) = (b - a, c - a);
    let (lu, lv) = (u.length(), v.length());
    u.cross(v).length() > STRAIGHT * lu * lv + slack * (lu + lv)
}

/// Whether corner `b` (between `a` and `c`) turns left (1), right (-1) or goes straight on (0)
/// within rounding ([`STRAIGHT`], [`Plane::slack`]).
fn turn(plane: &Plane, a: usize, b: usize, c: usize) -> i32 {
    let p = &plane.p;
    let (u, v) = (p[b] - p[a], p[c] - p[b]);
    let t = cross(u, v);
    let (lu, lv) = (u.length(), v.length());
    if t.abs() <= STRAIGHT * lu * lv + plane.slack * (lu + lv) {
        0
    } else if t > 0.0 {
        1
    } else {
        -1
    }
}

/// The corners in the polygon's plane (Newell's normal: counter-clockwise seen from it), in
/// `f64`; `None` where the polygon has no area to give a plane.
fn in_plane(corners: &[Vec3]) -> Option<Vec<DVec2>> {
    let p: Vec<DVec3> = corners.iter().map(|c| c.as_dvec3()).collect();
    let centre = p.iter().sum::<DVec3>() / p.len() as f64;
    let mut normal = DVec3::ZERO;
    for (i, &a) in p.iter().enumerate() {
        let b = p[(i + 1) % p.len()];
        normal += (a - centre).cross(b - centre);
    }
    let normal = normal.try_normalize()?;
    let u = normal.any_orthonormal_vector();
    let v = normal.cross(u);
    Some(
        p.iter()
            .map(|&q| DVec2::new((q - centre).dot(u), (q - centre).dot(v)))
            .collect(),
    )
}

fn cross(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// How corner `i` of the polygon turns between its neighbours ([`turn`]).
fn corner_turn(plane: &Plane, i: usize) -> i32 {
    let n = plane.p.len();
    turn(plane, (i + n - 1) % n, i, (i + 1) % n)
}

/// Whether `p` lies inside triangle `a b c` (counter-clockwise) or on its sides.
fn inside(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    cross(b - a, p - a) >= 0.0 && cross(c - b, p - b) >= 0.0 && cross(a - c, p - c) >= 0.0
}

/// Ear clipping of a counter-clockwise polygon: each step cuts off a corner that turns left and
/// whose triangle holds no other remaining corner that turns right (only those can lie inside a
/// simple polygon's ear; corners at the same position as the ear's own are its own), searching
/// on from the last ear; a corner on a line with its neighbours is cut off as a sliver only
/// where no ear is left. Where no corner can be cut at all (the polygon crosses itself), what
/// is left is fanned.
fn clip_ears(plane: &Plane) -> Vec<[usize; 3]> {
    let p = &plane.p;
    let mut left: Vec<usize> = (0..p.len()).collect();
    let mut out = Vec::with_capacity(p.len() - 2);
    let mut from = 0;
    while left.len() > 3 {
        let m = left.len();
        let corner = |k: usize| (left[(k + m - 1) % m], left[k], left[(k + 1) % m]);
        let ear = |k: usize, strict: bool| {
            let (a, b, c) = corner(k);
            let t = turn(plane, a, b, c);
            (t > 0 || (!strict && t == 0))
                && left.iter().enumerate().all(|(j, &q)| {
                    q == a
                        || q == b
                        || q == c
                        || p[q] == p[a]
                        || p[q] == p[b]
                        || p[q] == p[c]
                        || turn(plane, left[(j + m - 1) % m], q, left[(j + 1) % m]) > 0
                        || !inside(p[q], p[a], p[b], p[c])
                })
        };
        let order = |k: usize| (from + k) % m;
        let found = (0..m)
            .map(order)
            .find(|&k| ear(k, true))
            .or_else(|| (0..m).map(order).find(|&k| ear(k, false)));
        let Some(k) = found else {
            break;
        };
        let (a, b, c) = corner(k);
        out.push([a, b, c]);
        left.remove(k);
        from = k.min(left.len() - 1).saturating_sub(1);
    }
    out.extend((2..left.len()).map(|k| [left[0], left[k - 1], left[k]]));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Twice the signed area of triangle `t` of `p` in the plane z = 0.
    fn area(p: &[Vec3], t: [usize; 3]) -> f64 {
        let [a, b, c] = t.map(|i| p[i].as_dvec3().truncate());
        cross(b - a, c - a)
    }

    fn polygon_area(p: &[Vec3]) -> f64 {
        (0..p.len())
            .map(|i| {
                cross(
                    p[i].as_dvec3().truncate(),
                    p[(i + 1) % p.len()].as_dvec3().truncate(),
                )
            })
            .sum()
    }

    /// A convex polygon whose first corner lies on a line with a side (a T-junction's corner
    /// beside it) is fanned from a corner that makes no flat triangle, or ear-clipped where no
    /// fan does: every triangle has area and together they cover it. Where the first corner's
    /// fan has none flat, it is kept, straight corners and all.
    #[test]
    fn convex_polygons_with_straight_corners_get_no_flat_triangles() {
        let at = |c: &[(f32, f32)]| -> Vec<Vec3> {
            c.iter().map(|&(x, y)| Vec3::new(x, y, 0.0)).collect()
        };
        let t_junction = at(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (2.0, 1.0), (0.0, 1.0)]);
        let quad = at(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (1.0, 1.0)]);
        // Two corners on a line inside each side of a triangle: no fan avoids a flat triangle.
        let sides = at(&[
            (0.0, 0.0),
            (1.0, 0.0),
            (2.0, 0.0),
            (3.0, 0.0),
            (2.0, 1.0),
            (1.0, 2.0),
            (0.0, 3.0),
            (0.0, 2.0),
            (0.0, 1.0),
        ]);
        for (name, p) in [
            ("T-junction", &t_junction),
            ("quad", &quad),
            ("sides", &sides),
        ] {
            let (t, covers) = triangulate(p);
            assert!(covers, "{name}");
            assert_eq!(t.len(), p.len() - 2, "{name}");
            assert!(t.iter().all(|&x| area(p, x) > 1e-6), "{name}: {t:?}");
            let total: f64 = t.iter().map(|&x| area(p, x)).sum();
            assert!((total - polygon_area(p)).abs() < 1e-9, "{name}: {total}");
        }
        assert_eq!(
            triangulate(&t_junction).0,
            [[1, 2, 3], [1, 3, 4], [1, 4, 0]]
        );
        // Straight corners on a side away from the first corner: its fan as before.
        let square = at(&[(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (1.0, 2.0), (0.0, 2.0)]);
        assert_eq!(
            triangulate(&square),
            (vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]], true)
        );
    }

    /// Past [`MAX_CLIPPED_CORNERS`], a convex polygon whose fans hold flat triangles (a square
    /// with 64 corners along each side, a triangle with 300 along one, a square of 100,000
    /// corners a unit apart) is zipped between two chains: no triangle flat, together they
    /// cover it, in linear time.
    #[test]
    fn large_convex_polygons_with_straight_corners_get_no_flat_triangles() {
        let square: Vec<Vec3> = (0..4)
            .flat_map(|side| {
                (0..65).map(move |k| {
                    let t = k as f32 / 65.0;
                    let [x, y] = [[t, 0.0], [1.0, t], [1.0 - t, 1.0], [0.0, 1.0 - t]][side];
                    Vec3::new(x, y, 0.0)
                })
            })
            .collect();
        let mut triangle: Vec<Vec3> = (0..=300).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
        triangle.push(Vec3::new(150.0, 100.0, 0.0));
        let large: Vec<Vec3> = (0..4)
            .flat_map(|side| {
                (0..25_000).map(move |k| {
                    let t = k as f32;
                    let [x, y] = [[t, 0.0], [25e3, t], [25e3 - t, 25e3], [0.0, 25e3 - t]][side];
                    Vec3::new(x, y, 0.0)
                })
            })
            .collect();
        // A square whose right side starts a hair above its bottom corner: that corner is
        // straight within rounding beside its short side, and the zip finds no move (a fan
        // from the top left corner has no flat triangle).
        let mut hair: Vec<Vec3> = (0..=200)
            .map(|i| Vec3::new(i as f32 * 5.0, 0.0, 0.0))
            .collect();
        hair.push(Vec3::new(1000.0, 0.01, 0.0));
        hair.extend((1..=100).map(|i| Vec3::new(1000.0, i as f32 * 9.99, 0.0)));
        hair.extend([Vec3::new(1000.0, 1000.0, 0.0), Vec3::new(0.0, 1000.0, 0.0)]);
        let mut shapes = vec![
            ("square".to_string(), square),
            ("triangle".to_string(), triangle),
            ("large".to_string(), large),
            ("hair".to_string(), hair),
        ];
        // Random convex polygons: 3 to 14 corners on a circle, up to 40 more along each side.
        let mut seed = 7u64;
        let mut random = move |m: u64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) % m
        };
        for k in 0..40 {
            let hull = 3 + random(12) as usize;
            let mut angles: Vec<f32> = (0..hull).map(|_| random(100_000) as f32 / 1e5).collect();
            angles.sort_by(f32::total_cmp);
            angles.dedup();
            let at = |a: f32| {
                let a = a * std::f32::consts::TAU;
                Vec3::new(a.cos(), a.sin(), 0.0) * 100.0
            };
            let mut p = Vec::new();
            for i in 0..angles.len() {
                let (a, b) = (at(angles[i]), at(angles[(i + 1) % angles.len()]));
                let m = random(41) as usize;
                p.extend((0..=m).map(|j| a.lerp(b, j as f32 / (m + 1) as f32)));
            }
            if p.len() > MAX_CLIPPED_CORNERS {
                shapes.push((format!("random {k}"), p));
            }
        }
        assert!(shapes.len() > 10, "{}", shapes.len());
        for (name, p) in &shapes {
            assert!(p.len() > MAX_CLIPPED_CORNERS);
            let (t, covers) = triangulate(p);
            assert!(covers, "{name}");
            assert_eq!(t.len(), p.len() - 2, "{name}");
            assert!(t.iter().all(|&x| area(p, x) > 0.0), "{name}");
            let total: f64 = t.iter().map(|&x| area(p, x)).sum();
            let want = polygon_area(p);
            assert!((total - want).abs() < 1e-6 * want, "{name}: {total} {want}");
        }
    }

    #[test]
    fn convex_polygons_are_fans() {
        let hexagon: Vec<Vec3> = (0..6)
            .map(|k| {
                let a = k as f32 * std::f32::consts::TAU / 6.0;
                Vec3::new(a.cos(), a.sin(), 0.3)
            })
            .collect();
        assert_eq!(
            triangulate(&hexagon),
            (vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]], true)
        );
        // A quad with a corner on the line of its neighbours is still a fan, from that corner
        // (from the first, the fan's first triangle would be flat).
        let quad = [
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
        ];
        assert_eq!(triangulate(&quad), (vec![[1, 2, 3], [1, 3, 0]], true));
        // Past MAX_CLIPPED_CORNERS a convex polygon is still a fan that covers it.
        let round: Vec<Vec3> = (0..1000)
            .map(|k| {
                let a = k as f32 * std::f32::consts::TAU / 1000.0;
                Vec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        let (tris, covers) = triangulate(&round);
        assert!(covers && tris.len() == 998 && tris[997] == [0, 998, 999]);
    }

    /// A star and an arrow, counter-clockwise and clockwise: their triangles are as many as a
    /// fan's, wound as the polygon is, and cover exactly its area (no overlap, none turned
    /// over), in any plane.
    #[test]
    fn concave_polygons_are_covered_exactly() {
        let star: Vec<Vec3> = (0..10)
            .map(|k| {
                let (r, a) = (
                    if k % 2 == 0 { 1.0 } else { 0.3 },
                    k as f32 * 0.2 * std::f32::consts::PI,
                );
                Vec3::new(r * a.cos(), r * a.sin(), 0.0)
            })
            .collect();
        let arrow = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::new(0.7, 1.0, 0.0),
        ];
        for shape in [star, arrow] {
            for reversed in [false, true] {
                let mut p = shape.clone();
                if reversed {
                    p.reverse();
                }
                let (tris, covers) = triangulate(&p);
                assert!(covers);
                assert_eq!(tris.len(), p.len() - 2);
                let whole = polygon_area(&p);
                let sum: f64 = tris.iter().map(|&t| area(&p, t)).sum();
                assert!((sum - whole).abs() < 1e-6 * whole.abs(), "{sum} {whole}");
                for &t in &tris {
                    assert!(area(&p, t) * whole > 0.0, "{t:?} turned over");
                }
                // Tilted out of z = 0 (a rotation keeps which triangles it makes).
                let q = glam::Quat::from_rotation_x(0.7) * glam::Quat::from_rotation_y(-1.2);
                let tilted: Vec<Vec3> = p.iter().map(|&v| q * v + Vec3::splat(5.0)).collect();
                assert_eq!(triangulate(&tilted), (tris, true));
            }
        }
    }

    /// A rectangle with its sides' midpoints as corners (T-junctions), placed in random planes:
    /// its midpoints are on a line with their neighbours up to rounding, and it is fanned as a
    /// convex polygon every time, from its first midpoint (the first corner's fan would hold
    /// the flat triangle of its first side's three corners).
    #[test]
    fn corners_on_a_line_keep_the_fan() {
        let rect = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.5, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(3.0, 1.0, 0.0),
            Vec3::new(1.5, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let fan: Vec<[usize; 3]> = (2..6).map(|k| [1, k, (k + 1) % 6]).collect();
        for k in 0..300 {
            let a = k as f32 * 0.731;
            let q = glam::Quat::from_rotation_x(a) * glam::Quat::from_rotation_z(1.3 * a);
            let placed: Vec<Vec3> = rect.iter().map(|&v| q * v + Vec3::splat(a)).collect();
            assert_eq!(triangulate(&placed), (fan.clone(), true), "placement {k}");
        }
    }

    /// A pentagram crosses itself: no corner turns right, so it is fanned (a triangle for every
    /// corner but two), said not to cover it as it turns twice round; so are a bow tie (whose
    /// lobes' areas cancel: no plane) and a concave star past MAX_CLIPPED_CORNERS (fanned).
    #[test]
    fn a_polygon_crossing_itself_still_gets_its_triangles() {
        let star: Vec<Vec3> = (0..5)
            .map(|k| {
                let a = k as f32 * 0.8 * std::f32::consts::PI;
                Vec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        let (tris, covers) = triangulate(&star);
        assert!(!covers);
        assert_eq!(tris.len(), 3);
        let mut used: Vec<usize> = tris.iter().flatten().copied().collect();
        used.sort();
        used.dedup();
        assert_eq!(used, vec![0, 1, 2, 3, 4]);
        let bow_tie = [Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0), Vec3::X, Vec3::Y];
        assert_eq!(triangulate(&bow_tie), (vec![[0, 1, 2], [0, 2, 3]], false));
        let star = |n: usize| -> Vec<Vec3> {
            (0..n)
                .map(|k| {
                    let r = 1.0 - 0.5 * (k % 2) as f32;
                    let a = k as f32 * std::f32::consts::TAU / n as f32;
                    Vec3::new(r * a.cos(), r * a.sin(), 0.0)
                })
                .collect()
        };
        let (tris, covers) = triangulate(&star(1000));
        assert!(!covers && tris.len() == 998);
        // At the limit it is clipped, and covered.
        assert!(triangulate(&star(MAX_CLIPPED_CORNERS)).1);
    }

    #[test]
    fn polygons_without_a_plane_are_fans() {
        let line = [
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
        ];
        assert_eq!(triangulate(&line), (vec![[0, 1, 2], [0, 2, 3]], true));
    }
}
