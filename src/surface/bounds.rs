//! What each surface and displacement declares for the adaptive bounds (src/lod): how its chord
//! error is bounded. Each surface's `FACTS.bound` ([`SurfaceBound`]) and each displacement's
//! `facts().bound` ([`DisplaceBound`]) name its own functions, written beside it
//! (`flat.rs`, `phong.rs`, `pn.rs`, `stpn.rs`, `loop_bound.rs`; `displace.rs`, `noise.rs`,
//! `heightmap_bound.rs`) with their proofs; src/lod asks these instead of naming surfaces, and keeps
//! what is common to all of them (nets' differences and hulls, the displacement's chain rule,
//! the metric, levels).

use super::stpn::VertexTag;
use super::{Corners, ElementRecord, Heightmap, NormalField, SurfaceParams};
use crate::lod::{Bounds, Chord, Lod, Net, Sphere};
use glam::Vec2;

/// A local surface's geometry on canonical corners, as a Bézier net.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Patch {
    /// The surface is this net.
    Exact(Net),
    /// Not a polynomial: the surface lies within `distance` of this net's points (no finite
    /// second-derivative bound).
    Near(Net, f32),
}

/// How a surface's chord error is bounded.
#[derive(Clone, Copy, Debug)]
pub enum SurfaceBound {
    /// A polynomial patch per coarse triangle: src/lod bounds the nets the surface writes itself
    /// as (src/lod/bound.rs).
    Nets {
        /// The geometry's net on canonical corners; `edges_only`: only the edges' curves are
        /// wanted (edge 0's with `edge = true` of `direction`).
        geometry: fn(&SurfaceParams, &Corners, &[VertexTag; 3], bool) -> Patch,
        /// The unnormalized direction field displacement moves along (`SurfacePoint::direction`),
        /// as nets: several where it depends on the side (`edge`: canonical edge 0 only); it
        /// reads the normal field of the build options.
        direction: fn(&SurfaceParams, NormalField, &Corners, &[VertexTag; 3], bool) -> Vec<Net>,
    },
    /// Bounds of its own for an element and for its stored edge `e`.
    Own {
        element: fn(&Lod, &ElementRecord) -> Bounds,
        edge: fn(&Lod, &ElementRecord, usize) -> Bounds,
    },
}

/// Bounds of a height `η(p)` of the point over a sphere: `|η| <= max`, `|∇η| <= grad`,
/// `|∇²η[u, u]| <= hess` for every unit `u` (what `|h''| <= hess |P'|² + grad |P''|` along a
/// curve `P` needs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Height {
    pub max: f32,
    pub grad: f32,
    pub hess: f32,
    /// A height of the distance from a point alone, where it is one (`sine`).
    pub radial: Option<Radial>,
}

/// `η(p) = φ(|p − origin|)` with `|φ'| <= grad` ([`Height::grad`]) and `|φ''| <= curve`: along a
/// curve `P` with `r = |P − origin|`, `h'' = φ''(r) r'² + φ'(r) r''` and
/// `|r''| <= (|P'|² − r'²)/r + |P''|`, so a patch whose distance from `origin` changes slowly
/// (`r'` small) gets a bound far below `hess |P'|²` (src/lod/bound.rs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Radial {
    pub origin: glam::Vec3,
    pub curve: f32,
}

/// How a displacement's height is bounded.
#[derive(Clone, Copy, Debug)]
pub enum DisplaceBound {
    /// Nothing moves.
    Zero,
    /// A height of the point (`sine`, `noise`): bounds over the patch's sphere.
    OfPoint(fn(&SurfaceParams, &Sphere) -> Height),
    /// A height read from a map at the element's texture coordinates (`heightmap`).
    Texture(TextureBound),
}

/// A texture height's bound.
#[derive(Clone, Copy, Debug)]
pub struct TextureBound {
    /// `|h| <=` this.
    pub max: fn(&SurfaceParams) -> f32,
    /// The pyramid levels read at level of detail `lod` (once per mesh; the same level twice
    /// where one is read).
    pub levels: fn(&Heightmap, f32) -> [usize; 2],
    /// `|h'|` per lattice direction `dirs` (corner `k` to `k + 1`, texture coordinates `uv` in
    /// canonical order), the kink terms, `kink_factor` times the slope's weighted jumps along a
    /// lattice segment of unit size (src/lod/mod.rs, "One dimension"), and `|h|`, over the
    /// texels the patch reads.
    pub slopes: Slopes,
}

/// [`TextureBound::slopes`].
pub type Slopes =
    fn(&SurfaceParams, &Heightmap, [usize; 2], [Vec2; 3], &[usize], f32) -> (Vec<f32>, Chord, f32);

impl DisplaceBound {
    /// The largest distance the displacement moves a point of a patch inside `s`.
    pub fn max_height(&self, params: &SurfaceParams, s: &Sphere) -> f32 {
        match self {
            DisplaceBound::Zero => 0.0,
            DisplaceBound::OfPoint(f) => f(params, s).max,
            DisplaceBound::Texture(t) => (t.max)(params),
        }
    }
}
