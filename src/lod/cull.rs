//! Culling helpers, conservative for curved and displaced patches: a bounding sphere against
//! the view frustum, and a normal cone against the eye (back faces of closed surfaces).

use super::net::Net;
use super::Sphere;
use crate::mesh::Mesh;
use glam::{Mat4, Vec3, Vec4};

/// The six planes of a view-projection (Vulkan clip space: `-w <= x, y <= w`, `0 <= z <= w`),
/// each `n·p + d >= 0` inside, `|n| = 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    pub planes: [Vec4; 6],
}

impl Frustum {
    pub fn from_view_proj(m: Mat4) -> Self {
        let r = [0, 1, 2, 3].map(|i| m.row(i));
        let planes = [
            r[3] + r[0],
            r[3] - r[0],
            r[3] + r[1],
            r[3] - r[1],
            r[2],
            r[3] - r[2],
        ]
        .map(|p| p / p.truncate().length());
        Self { planes }
    }

    /// Whether the whole sphere lies outside one of the planes.
    pub fn outside(&self, s: &Sphere) -> bool {
        self.planes
            .iter()
            .any(|p| p.truncate().dot(s.centre) + p.w < -s.radius)
    }
}

/// A cone of directions: every direction within `acos(cos)` of the unit `axis`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalCone {
    pub axis: Vec3,
    pub cos: f32,
}

/// The cone of the normals of a Bézier patch's drawn triangles, oriented as the stored corners
/// wind (`flip`: the net's corner order is an odd permutation of the stored one). `P_u` and
/// `P_v` lie in the convex hulls of the first differences `U_β = b_{β+e1} − b_{β+e0}` and
/// `V_β = b_{β+e2} − b_{β+e0}` (with the same convex weights), so `P_u × P_v` lies in the convex
/// cone of the products `U_β × V_γ`, and so does a drawn triangle's normal (its edges are
/// averages of `P_u`, `P_v`). `None` when that cone is not within a half-space.
pub fn normal_cone(net: &Net, flip: bool) -> Option<NormalCone> {
    let m = net.degree;
    let diff = |to: usize| -> Vec<Vec3> {
        Net::multi(m - 1)
            .map(|g| {
                let (mut a, mut b) = (g, g);
                a[0] += 1;
                b[to] += 1;
                net.at(b) - net.at(a)
            })
            .collect()
    };
    let (u, v) = (diff(1), diff(2));
    let sign = if flip { -1.0 } else { 1.0 };
    let mut dirs = Vec::with_capacity(u.len() * v.len());
    for a in &u {
        for b in &v {
            let c = a.cross(*b) * sign;
            if c != Vec3::ZERO {
                dirs.push(c.normalize());
            }
        }
    }
    let axis = dirs
        .iter()
        .fold(Vec3::ZERO, |s, &d| s + d)
        .normalize_or_zero();
    if axis == Vec3::ZERO {
        return None;
    }
    let cos = dirs.iter().map(|d| d.dot(axis)).fold(1.0f32, f32::min);
    // A margin for the rounding of the products.
    let cos = cos - 1e-5;
    (cos > 0.0).then_some(NormalCone { axis, cos })
}

impl NormalCone {
    /// Whether every triangle drawn inside sphere `s` with a normal in this cone faces away from
    /// `eye` (`(p − eye)·n > 0`): the angle between the eye's direction to the sphere's centre and
    /// the axis, plus the sphere's angular radius, plus the cone's half-angle, is below 90°.
    pub fn back_facing(&self, s: &Sphere, eye: Vec3) -> bool {
        let v = s.centre - eye;
        let d = v.length();
        if d <= s.radius {
            return false;
        }
        let beta = (v.dot(self.axis) / d).clamp(-1.0, 1.0).acos();
        let gamma = (s.radius / d).asin();
        let theta = self.cos.clamp(-1.0, 1.0).acos();
        beta + gamma + theta < std::f32::consts::FRAC_PI_2 - 1e-4
    }
}

/// Whether `eye` sees a closed mesh wound outwards ([`Mesh::closed_outward`]) from outside, so
/// that its faces facing away are hidden behind its own front and may be culled: the eye lies
/// outside every element's sphere (`records`, the spheres of the drawn surface) and the coarse
/// mesh's winding number about it is zero. Every element's sphere contains its coarse triangle
/// and its drawn patch (a net's hull holds its corners; displacement grows the sphere), hence
/// every point between the two; blending each coarse triangle into its patch (shared edges
/// stay shared: the surfaces are watertight) moves the surface only inside the spheres, so the
/// winding number about an eye outside them is the drawn surface's. From inside (an eye in a
/// room, or closer to the surface than a sphere's reach) the visible faces may face away: no
/// culling for facing away then, only for lying outside the view.
pub fn eye_outside(eye: Vec3, records: &[super::frame::LodRecord], mesh: &Mesh) -> bool {
    let clear = records.iter().all(|r| {
        let s = Vec4::from(r.sphere);
        (s.truncate() - eye).length() > s.w
    });
    clear && mesh.winding_number(eye).abs() < 0.5
}
