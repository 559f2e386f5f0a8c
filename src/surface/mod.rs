//! Surfaces: the functions that map a sample (an element and barycentric coordinates) to a
//! surface point: position, unit normal and the tangents dP/du, dP/dv. Each surface is written
//! once in GLSL (`glsl/include/<surface>.glsl`) and once here, its Rust mirror; the GPU tests pin
//! the two together by reading back what the drawing pipelines evaluated. Displacement
//! ([`displace`]) maps a surface point to a surface point and combines with every surface.
//!
//! The seam between drivers and surfaces (docs/architecture.md, "The seam"): a driver hands over
//! the element's [`ElementRecord`] (opaque to it) and a sample (barycentric coordinates of a point
//! of its pattern or patch); the surface decodes the record itself.
//!
//! Watertightness: the local surfaces first put the triangle's corners in a canonical order
//! ([`canonical`]): by global vertex index, with the corners whose weight is zero moved last. A
//! point on a shared coarse edge is then computed from the same two corners, in the same order,
//! with the same weights, by both triangles, and every term that involves the third corner is
//! multiplied by its exact zero weight: positions on shared edges are bit-identical whatever the
//! surface, and so are normals where the corners share them.
#![forbid(unsafe_code)]

pub mod bounds;
pub mod displace;
pub mod facts;
pub mod flat;
pub mod heightmap;
mod heightmap_bound;
mod inputs;
#[path = "loop.rs"]
pub mod loop_;
pub mod noise;
mod params;
pub mod phong;
pub mod pn;
mod record;
pub mod stpn;

pub use displace::Displace;
pub use facts::{DisplaceFacts, Elements, FragmentNormals, PrePass, SurfaceFacts};
pub use heightmap::Heightmap;
pub use inputs::{DisplaceInputs, Mirror, Sources, SurfaceInputs};
pub use params::{shown_number, SurfaceParams, MAX_FREQUENCY_RADII, MAX_PHASE, MAX_REACH_RADII};
pub use pn::NormalField;
pub use record::{
    build_records, corner_records, oct_decode, oct_encode, split_positions, CornerRecord,
    ElementRecord, RecordKind, RECORD_BYTES, SMOOTH_CORNER,
};

use glam::Vec3;

/// The surface each element defines. The discriminant is the `SURFACE` specialization constant
/// of every driver's evaluation stage (glsl/include/surface.glsl).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[repr(u32)]
pub enum Surface {
    /// Linear interpolation of the coarse triangle's positions and normals.
    #[default]
    Flat = 0,
    /// Phong tessellation (Boubekeur & Alexa 2008): the flat point pulled towards the corners'
    /// tangent planes by the shape factor --alpha.
    Phong = 1,
    /// Curved PN triangles (Vlachos et al. 2001, as in Boubekeur & Schlick 2005, appendix A):
    /// cubic Bézier geometry, quadratic normal field evaluated per fragment.
    Pn = 2,
    /// Scalar-tagged PN triangles (Boubekeur, Reuter & Schlick 2005): PN with per-vertex tension,
    /// sharpness, bias and crease direction (--tags, or derived from the mesh's hard edges).
    Stpn = 3,
    /// The limit surface of Loop subdivision (Holländer & Boubekeur 2010): elements are the faces
    /// of one Loop step M1, evaluated from basis function tables (src/surface/loop.rs).
    Loop = 4,
}

impl Surface {
    /// The local surfaces: defined by each coarse triangle's corners alone (corner records).
    pub const LOCAL: [Surface; 4] = [Surface::Flat, Surface::Phong, Surface::Pn, Surface::Stpn];
    pub const ALL: [Surface; 5] = [
        Surface::Flat,
        Surface::Phong,
        Surface::Pn,
        Surface::Stpn,
        Surface::Loop,
    ];

    /// What the window shows instead when a mesh cannot be drawn with the surface chosen
    /// (Loop refuses non-manifold meshes).
    pub const FALLBACK: Surface = Surface::Pn;

    /// What the surface declares about itself, in its own module (the one `match` on surfaces
    /// outside the evaluation).
    pub fn facts(self) -> &'static SurfaceFacts {
        match self {
            Surface::Flat => &flat::FACTS,
            Surface::Phong => &phong::FACTS,
            Surface::Pn => &pn::FACTS,
            Surface::Stpn => &stpn::FACTS,
            Surface::Loop => &loop_::FACTS,
        }
    }

    pub fn name(self) -> &'static str {
        self.facts().name
    }

    /// Whether the fragment stage evaluates this surface's normal field (instead of
    /// interpolating the vertices' normals) when drawn with `displace` at `level`, by a driver
    /// that evaluates on the GPU (`gpu`) or not.
    pub fn fragment_normal_field(self, displace: Displace, level: u32, gpu: bool) -> bool {
        match self.facts().fragment_normals {
            FragmentNormals::Never => false,
            FragmentNormals::Always => true,
            FragmentNormals::FromLevel(from) => displace == Displace::None && gpu && level >= from,
        }
    }

    /// The pass that makes the surface's elements before drawing, if any.
    pub fn pre_pass(self) -> Option<PrePass> {
        self.facts().pre_pass
    }

    /// Whether the surface's elements are Loop's M1 faces (made by a pre-pass every frame).
    pub fn uses_loop_faces(self) -> bool {
        self.facts().elements == Elements::LoopFaces
    }

    /// Why this surface cannot be drawn with `displace` on a mesh with (or without) texture
    /// coordinates on every face; `None` when it can.
    pub fn incompatibility(self, displace: Displace, mesh_has_texcoords: bool) -> Option<String> {
        facts::incompatibility(self.facts(), displace.facts(), mesh_has_texcoords)
    }

    /// [`Surface::incompatibility`] on `mesh` (`has_texcoords`: on every face), saying on how
    /// many of its faces the texture coordinates are where only some faces have them.
    pub fn incompatibility_on(
        self,
        displace: Displace,
        mesh: &crate::mesh::Mesh,
        has_texcoords: bool,
    ) -> Option<String> {
        let why = self.incompatibility(displace, has_texcoords)?;
        let with = mesh.triangles.iter().filter(|t| t.t.is_some()).count();
        if has_texcoords || with == 0 || !self.facts().texture_coordinates {
            return Some(why);
        }
        Some(format!(
            "the mesh has texture coordinates (vt) on {with} of its {} faces, not on every one: the {} displacement reads the map on every face",
            mesh.triangles.len(),
            displace.name()
        ))
    }
}

/// What the curved surfaces' geometry does at split normals (a position with several `vn`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Seams {
    /// Crack-free: the geometry uses one normal per split position (its area-weighted normal);
    /// shading keeps the corners' own normals.
    #[default]
    Closed,
    /// As the papers: the geometry uses each corner's own normal, which opens cracks there.
    Open,
}

/// Options that change what is built, not sent per frame: the mesh's data (the element records,
/// Loop's tables) and the pipelines (specialization constants); drawing with other options
/// rebuilds them ([`SurfaceParams`] holds the per-frame values, uploaded in the frame's uniforms).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BuildOptions {
    /// Geometry at split normals (built into the local surfaces' element records).
    pub seams: Seams,
    /// Loop subdivision's boundary rule (built into the `loop` surface's tables).
    pub boundary: loop_::Boundary,
    /// The `loop` surface's table level: 2^level segments per M1-face edge, the lattice whose
    /// points are exact (`--bft-level`, default 5).
    pub bft_level: u32,
    /// The normal field of `pn` and `stpn` (the `NORMAL_FIELD` specialization constant on the
    /// GPU, a pipeline of its own).
    pub normal_field: NormalField,
}

impl Default for BuildOptions {
    fn default() -> Self {
        Self {
            seams: Seams::Closed,
            boundary: loop_::Boundary::EdgeOnly,
            bft_level: loop_::DEFAULT_LMAX,
            normal_field: NormalField::default(),
        }
    }
}

impl BuildOptions {
    /// One sentence naming the first option out of its range.
    pub fn validate(&self) -> Result<(), String> {
        if !(1..=loop_::MAX_LMAX).contains(&self.bft_level) {
            return Err(format!(
                "--bft-level {} is not within [1, {}]",
                self.bft_level,
                loop_::MAX_LMAX
            ));
        }
        Ok(())
    }
}

/// A point of the refined surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    pub position: Vec3,
    /// Unit normal (of the surface's normal field, which need not be the geometric one).
    pub normal: Vec3,
    /// Unit direction displacement moves along: the normal field evaluated with the geometry
    /// normals (`normal` itself except at split normals with closed seams, where it is shared by
    /// the triangles meeting there, so displacement stays crack-free).
    pub direction: Vec3,
    /// dP/du and dP/dv for the sample `(w, u, v)`, w = 1 - u - v (corner 1 and corner 2 of the
    /// element as stored).
    pub dpdu: Vec3,
    pub dpdv: Vec3,
    /// Texture coordinates at the sample (zero when the element has none), and their
    /// derivatives by `u` and `v`.
    pub uv: glam::Vec2,
    pub duv: [glam::Vec2; 2],
}

/// Corner data of a coarse triangle in canonical order, with the sample's weights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corners {
    pub p: [Vec3; 3],
    /// Shading normals.
    pub n: [Vec3; 3],
    /// Position normals at split positions ([`CornerRecord::geometry_normal`]), `n` elsewhere.
    pub g: [Vec3; 3],
    /// Whether canonical edge `e` ([`edge_of`]) builds its PN / Phong geometry from `g`.
    pub seam_pn: [bool; 3],
    pub seam_phong: [bool; 3],
    /// Barycentric weight of each corner.
    pub w: [f32; 3],
    /// The stored corner each canonical corner is.
    pub order: [usize; 3],
}

/// What a local surface computes in canonical corner order: position, unit normal, and the
/// partial derivatives ∂P/∂b_i by each corner's weight (the seam turns them into dP/du, dP/dv).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Local {
    pub position: Vec3,
    pub normal: Vec3,
    pub grad: [Vec3; 3],
}

/// Dot product in the operation order the GLSL mirrors write out (`dot3` in corners.glsl): the
/// built-in `dot` leaves the order, and fused multiply-adds, to the implementation.
pub fn dot3(a: Vec3, b: Vec3) -> f32 {
    a.x * b.x + a.y * b.y + a.z * b.z
}

/// Below this squared length a normal field's value is taken to vanish ([`unit_field`]).
/// Mirror: `FIELD_MIN2` in glsl/include/corners.glsl.
pub const FIELD_MIN2: f32 = 1e-24;

/// Whether corner `i` weighs more than corner `j` at the sample, the larger normal (compared
/// x, then y, then z) on a tie. Mirror: `heavier` in corners.glsl.
fn heavier(c: &Corners, i: usize, j: usize) -> bool {
    if c.w[i] != c.w[j] {
        return c.w[i] > c.w[j];
    }
    let (a, b) = (c.n[i], c.n[j]);
    if a.x != b.x {
        return a.x > b.x;
    }
    if a.y != b.y {
        return a.y > b.y;
    }
    a.z > b.z
}

/// A normal field's value `v` at the sample, made unit length. Where it vanishes (corner
/// normals pointing opposite ways, as across a fold of the mesh), the normal of the corner
/// weighing most: chosen from the corners' weights and normals alone, whatever their order, so
/// that the two elements sharing an edge choose the same one there (displacement moves along
/// it). Mirror: `unit_field` in glsl/include/corners.glsl.
pub fn unit_field(v: Vec3, c: &Corners) -> Vec3 {
    if dot3(v, v) > FIELD_MIN2 {
        return v.normalize();
    }
    let best = (1..3).fold(0, |best, i| if heavier(c, i, best) { i } else { best });
    c.n[best]
}

/// Canonical corner order for barycentric sample `bary = (w, u, v)` (weights of corners 0, 1, 2):
/// ascending global vertex index, then zero-weight corners moved last (stable).
/// Mirror of `canonical()` in `glsl/include/corners.glsl`.
pub fn canonical(rec: &CornerRecord, bary: [f32; 3]) -> Corners {
    let mut order = [0usize, 1, 2];
    // Sorting key: zero weights last, then global index.
    let key = |c: usize| ((bary[c] == 0.0) as u64) << 32 | rec.idx[c] as u64;
    order.sort_by_key(|&c| key(c));
    corners_in(rec, bary, order)
}

/// The corners in their stored order, for `flat`: its points and normals are sums of products
/// of a weight and a corner, and on a shared edge the third weight is an exact zero, so both
/// triangles add the same two non-zero terms (addition commutes; the GLSL is `precise`) and
/// agree to the bit in any order. Mirror of `stored_corners()` in corners.glsl.
pub fn stored_order(rec: &CornerRecord, bary: [f32; 3]) -> Corners {
    corners_in(rec, bary, [0, 1, 2])
}

fn corners_in(rec: &CornerRecord, bary: [f32; 3], order: [usize; 3]) -> Corners {
    let flags = rec.seam_flags();
    // Canonical edge e joins canonical corners (e, e + 1 mod 3): its stored edge.
    let stored = |e: usize| stored_edge(order[e], order[(e + 1) % 3]);
    Corners {
        p: order.map(|c| rec.position(c)),
        n: order.map(|c| rec.normal(c)),
        g: order.map(|c| rec.geometry_normal(c)),
        seam_pn: [0, 1, 2].map(|e| flags.pn(stored(e))),
        seam_phong: [0, 1, 2].map(|e| flags.phong(stored(e))),
        w: order.map(|c| bary[c]),
        order,
    }
}

/// The edge (0: corners 0-1, 1: 1-2, 2: 2-0) joining corners `i` and `j`, either way round.
pub fn edge_of(i: usize, j: usize) -> usize {
    stored_edge(i, j)
}

fn stored_edge(i: usize, j: usize) -> usize {
    if (i + 1) % 3 == j {
        i
    } else {
        j
    }
}

/// The surface's normal field on already ordered corners (unit); `tags` are the corners' scalar
/// tags (used by `stpn`), `field` the normal field `pn` and `stpn` use.
pub fn normal_field(
    surface: Surface,
    field: NormalField,
    c: &Corners,
    tags: &[stpn::VertexTag; 3],
) -> Vec3 {
    match surface {
        Surface::Flat | Surface::Phong => flat::normal(c),
        Surface::Pn => pn::normal(c, field),
        Surface::Stpn => pn::normal(
            &Corners {
                n: stpn::shading_normals(c, tags),
                ..*c
            },
            field,
        ),
        Surface::Loop => unreachable!("loop is not a local surface"),
    }
}

/// Evaluate a local surface on already ordered corners.
pub fn eval_corners(
    surface: Surface,
    params: &SurfaceParams,
    field: NormalField,
    c: &Corners,
    tags: &[stpn::VertexTag; 3],
) -> Local {
    match surface {
        Surface::Flat => flat::eval(c),
        Surface::Phong => phong::eval(c, params.alpha),
        Surface::Pn => pn::eval(c, field),
        Surface::Stpn => stpn::eval(c, tags, field),
        Surface::Loop => unreachable!("loop is not a local surface"),
    }
}

/// Evaluate local `surface` (without displacement) at barycentric sample `bary` of element
/// `rec`, with normal field `field`, the vertices' scalar tags (`None`: neutral) and the
/// element's texture coordinates `uv` ([`Mirror::eval_surface`] hands its inputs on).
pub(crate) fn eval_local(
    surface: Surface,
    params: &SurfaceParams,
    field: NormalField,
    tags: Option<&[stpn::VertexTag]>,
    rec: &ElementRecord,
    bary: [f32; 3],
    uv: Option<&[[f32; 2]; 3]>,
) -> SurfacePoint {
    let r = CornerRecord::decode(rec);
    // `flat` needs no canonical order (see `stored_order`), and skipping the sort per vertex is
    // most of what the pattern driver does beyond the static buffer's work.
    let c = if surface == Surface::Flat {
        stored_order(&r, bary)
    } else {
        canonical(&r, bary)
    };
    let tags = tags.map_or([stpn::VertexTag::default(); 3], |t| {
        stpn::corner_tags(t, &r.idx, c.order)
    });
    let l = eval_corners(surface, params, field, &c, &tags);
    let mut g = [Vec3::ZERO; 3];
    for i in 0..3 {
        g[c.order[i]] = l.grad[i];
    }
    let direction = if c.g == c.n {
        l.normal
    } else {
        normal_field(surface, field, &Corners { n: c.g, ..c }, &tags)
    };
    // Texture coordinates in canonical order, so both sides of a shared edge (with the same
    // coordinates at its ends) read the same point of the map.
    let (uv, duv) = match uv {
        Some(t) => {
            let t = t.map(glam::Vec2::from);
            let o = c.order;
            (
                t[o[0]] * c.w[0] + t[o[1]] * c.w[1] + t[o[2]] * c.w[2],
                [t[1] - t[0], t[2] - t[0]],
            )
        }
        None => (glam::Vec2::ZERO, [glam::Vec2::ZERO; 2]),
    };
    SurfacePoint {
        position: l.position,
        normal: l.normal,
        direction,
        uv,
        duv,
        dpdu: g[1] - g[0],
        dpdv: g[2] - g[0],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `s` with `d` at sample `bary` of `rec`, whose corners have texture coordinates `uv` on the
    /// generated height map (the height map displacement reads them).
    fn eval_uv(
        s: Surface,
        d: Displace,
        params: &SurfaceParams,
        rec: &ElementRecord,
        bary: [f32; 3],
        uv: [[f32; 2]; 3],
    ) -> SurfacePoint {
        let map = Heightmap::generated();
        let uvs = [uv];
        let sources = Sources {
            uvs: Some(&uvs),
            heightmap: Some(&map),
            lod: 0.0,
            ..Sources::default()
        };
        Mirror::new(s, d, &BuildOptions::default(), &sources)
            .unwrap()
            .eval(params, 0, rec, bary)
    }

    /// [`eval_uv`] on coordinates spanning a fifth of the map.
    fn eval(
        s: Surface,
        d: Displace,
        params: &SurfaceParams,
        rec: &ElementRecord,
        bary: [f32; 3],
    ) -> SurfacePoint {
        eval_uv(
            s,
            d,
            params,
            rec,
            bary,
            [[0.1, 0.2], [0.3, 0.25], [0.15, 0.4]],
        )
    }

    fn rec() -> CornerRecord {
        CornerRecord::new(
            [
                Vec3::new(0.1, 0.2, 0.3),
                Vec3::new(1.7, -0.3, 0.2),
                Vec3::new(0.3, 1.9, -0.7),
            ],
            [Vec3::Z, Vec3::X, Vec3::Y],
            [7, 2, 5],
        )
    }

    #[test]
    fn canonical_sorts_by_index_zero_weights_last() {
        let r = rec();
        let c = canonical(&r, [0.25, 0.5, 0.25]);
        assert_eq!(c.w, [0.5, 0.25, 0.25]); // indices 2, 5, 7
        assert_eq!(c.order, [1, 2, 0]);
        let c = canonical(&r, [0.25, 0.0, 0.75]);
        assert_eq!(c.w, [0.75, 0.25, 0.0]); // 5, 7, then the zero-weight corner (2)
        let c = canonical(&r, [0.0, 1.0, 0.0]);
        assert_eq!(c.w, [1.0, 0.0, 0.0]);
        assert_eq!(c.p[0], Vec3::new(1.7, -0.3, 0.2));
    }

    #[test]
    fn records_round_trip() {
        let r = rec();
        assert_eq!(CornerRecord::decode(&r.encode()), r);
    }

    /// Finite differences of the evaluated position agree with the returned tangents, for every
    /// surface and displacement, at samples in canonical orders that differ from the stored one.
    /// Displaced tangents hold the normal constant (src/surface/displace.rs), which is exact where
    /// the normal field is constant: displacement is checked on a planar triangle with its face
    /// normal at every corner, where every surface is the plane itself.
    /// At the displacement limits every local surface's points and normals are finite (the
    /// triangle's radius is about 1); just past them the parameters are refused up front, with
    /// the option named.
    #[test]
    fn displacement_within_the_limits_is_finite_and_beyond_them_refused() {
        let r = rec().encode();
        let radius = 1.0f32;
        let at_limit = SurfaceParams {
            amplitude: (MAX_REACH_RADII / 2.0) as f32,
            frequency: MAX_FREQUENCY_RADII as f32 / 4.0,
            octaves: 3,
            ..Default::default()
        };
        for d in [Displace::Sine, Displace::Noise] {
            at_limit.check_displacement(d, radius, 2.0).unwrap();
            for s in Surface::LOCAL {
                for bary in [[0.2, 0.3, 0.5], [0.6, 0.1, 0.3], [1.0, 0.0, 0.0]] {
                    let p = eval(s, d, &at_limit, &r, bary);
                    assert!(
                        p.position.is_finite() && (p.normal.length() - 1.0).abs() < 1e-3,
                        "{} + {}: {p:?}",
                        s.name(),
                        d.name()
                    );
                }
            }
        }
        let refused = |p: SurfaceParams, d, needle: &str| {
            let e = p.check_displacement(d, radius, 2.0).unwrap_err();
            assert!(e.contains(needle), "{e}");
        };
        // A mesh far from its origin: the phase, not the frequency per radius, is too large.
        let far = SurfaceParams {
            frequency: 20.0,
            ..Default::default()
        };
        for d in [Displace::Sine, Displace::Noise] {
            far.check_displacement(d, radius, 1e4).unwrap();
            let e = far.check_displacement(d, radius, 1.7e7).unwrap_err();
            assert!(e.contains("phases of") && e.contains("origin"), "{e}");
        }
        // The last octave's phase: fewer octaves are a way out.
        let octaves = SurfaceParams { octaves: 8, ..far };
        let e = octaves
            .check_displacement(Displace::Noise, radius, 2e3)
            .unwrap_err();
        assert!(e.ends_with("lower --frequency or --octaves"), "{e}");
        far.check_displacement(Displace::Noise, radius, 2e3)
            .unwrap();
        let big = SurfaceParams {
            amplitude: 3.4e38,
            ..Default::default()
        };
        refused(
            big,
            Displace::Sine,
            "--amplitude 3.4e38 moves the surface up to 3.400e38 times",
        );
        let fast = SurfaceParams {
            frequency: 1e25,
            ..Default::default()
        };
        refused(fast, Displace::Sine, "--frequency 1e25 is 1.000e25 radians");
        // Octaves double the frequency: the last one counts.
        let octaves = SurfaceParams {
            frequency: 2e5,
            octaves: 4,
            ..Default::default()
        };
        octaves
            .check_displacement(Displace::Sine, radius, 2.0)
            .unwrap();
        refused(octaves, Displace::Noise, "with --octaves 4");
        let bias = SurfaceParams {
            amplitude: 1.0,
            bias: 1e7,
            ..Default::default()
        };
        refused(bias, Displace::Heightmap, "--amplitude 1 with --bias 1e7");
        // A mesh near f32's range leaves no room to displace outwards.
        let e = SurfaceParams::default()
            .check_displacement(Displace::Sine, 1e38, 3e38)
            .unwrap_err();
        assert!(e.contains("beyond the range of f32"), "{e}");
        SurfaceParams::default()
            .check_displacement(Displace::None, radius, f32::MAX as f64)
            .unwrap();
    }

    /// The tangents are the positions' derivatives (central differences) on every surface and
    /// displacement, and on a planar element the displaced normal is the displaced positions'.
    #[test]
    fn tangents_are_the_derivatives() {
        let curved = rec().encode();
        let n = Vec3::new(0.2, -0.3, 0.9).normalize();
        let (t, b) = n.any_orthonormal_pair();
        let planar = CornerRecord::new(
            [t * 0.3 + b * 0.1, t * 1.9 - b * 0.2, t * 0.4 + b * 1.6],
            [n; 3],
            [7, 2, 5],
        )
        .encode();
        let params = SurfaceParams {
            amplitude: 0.05,
            frequency: 3.0,
            ..Default::default()
        };
        let h = 1e-3f32;
        for s in Surface::LOCAL {
            for d in Displace::ALL {
                let r = if d == Displace::None { curved } else { planar };
                for (u, v) in [(0.2f32, 0.3f32), (0.6, 0.1), (0.15, 0.7)] {
                    let at = |u: f32, v: f32| eval(s, d, &params, &r, [1.0 - u - v, u, v]);
                    let p = at(u, v);
                    let du = (at(u + h, v).position - at(u - h, v).position) / (2.0 * h);
                    let dv = (at(u, v + h).position - at(u, v - h).position) / (2.0 * h);
                    let tol = 2e-2 * (1.0 + p.dpdu.length().max(p.dpdv.length()));
                    assert!(
                        (du - p.dpdu).length() < tol && (dv - p.dpdv).length() < tol,
                        "{} + {}: at ({u}, {v}) dP/du {} vs {du}, dP/dv {} vs {dv}",
                        s.name(),
                        d.name(),
                        p.dpdu,
                        p.dpdv
                    );
                    // On the planar element the normal field is constant, so the displaced
                    // normal (Blinn's, from the height's gradient) is the geometric one: the
                    // normal of the displaced positions' differences, on the normal's side.
                    if d != Displace::None {
                        let geometric = du.cross(dv).normalize();
                        let geometric = geometric * geometric.dot(n).signum();
                        // Exact up to the differences' rounding; the height map's bilinear
                        // texels kink where the differences straddle them.
                        let tol = if d == Displace::Heightmap { 2e-2 } else { 2e-3 };
                        assert!(
                            (p.normal - geometric).length() < tol,
                            "{} + {}: at ({u}, {v}) normal {} vs {geometric}",
                            s.name(),
                            d.name(),
                            p.normal
                        );
                    }
                }
            }
        }
    }

    /// Two triangles sharing the edge (vertex 3, vertex 9), listed in opposite directions, with
    /// different third corners and shared normals at the edge's ends.
    fn edge_pair() -> (ElementRecord, ElementRecord) {
        let a = Vec3::new(0.31, -1.7, 2.9);
        let b = Vec3::new(-4.1, 0.77, 0.013);
        let na = Vec3::new(0.3, 0.9, 0.1).normalize();
        let nb = Vec3::new(-0.2, 0.7, 0.6).normalize();
        let t1 = CornerRecord::new(
            [a, b, Vec3::new(5.0, 5.0, 5.0)],
            [na, nb, Vec3::new(0.1, 0.2, 0.9).normalize()],
            [3, 9, 4],
        );
        let t2 = CornerRecord::new(
            [b, a, Vec3::new(-5.0, 2.0, 1.0)],
            [nb, na, Vec3::new(0.8, -0.1, 0.3).normalize()],
            [9, 3, 11],
        );
        (t1.encode(), t2.encode())
    }

    #[test]
    fn shared_edge_points_are_bit_identical() {
        let (t1, t2) = edge_pair();
        let params = SurfaceParams::default();
        let n = 37;
        for k in 0..=n {
            let wa = crate::pattern::weight(n - k, n);
            let wb = crate::pattern::weight(k, n);
            for s in Surface::LOCAL {
                for d in Displace::ALL {
                    // The shared corners have the same texture coordinates on both sides.
                    let (ua, ub) = ([0.1, 0.2], [0.3, 0.25]);
                    let p1 = eval_uv(s, d, &params, &t1, [wa, wb, 0.0], [ua, ub, [0.5, 0.9]]);
                    let p2 = eval_uv(s, d, &params, &t2, [wb, wa, 0.0], [ub, ua, [0.2, 0.8]]);
                    let what = format!("{} + {} at k = {k}", s.name(), d.name());
                    assert_eq!(
                        p1.position.to_array().map(f32::to_bits),
                        p2.position.to_array().map(f32::to_bits),
                        "{what}"
                    );
                    if d == Displace::None {
                        assert_eq!(p1.normal, p2.normal, "{what}");
                    }
                }
            }
        }
    }

    /// The canonical order is what makes PN triangles watertight: evaluated in each triangle's own
    /// corner order, the same edge point comes out with different bits (the cubic's weight
    /// products, `(w0·w0)·w1` against `(w1·w0)·w0`, round differently). Flat and Phong edge points
    /// are sums of two non-zero terms, and addition commutes: they stay bit-identical in any
    /// order, so only `pn` can show it (and the GPU watertight tests run on `pn` for this reason).
    #[test]
    fn stored_order_breaks_bit_identity_on_curved_surfaces() {
        let (t1, t2) = edge_pair();
        let (r1, r2) = (CornerRecord::decode(&t1), CornerRecord::decode(&t2));
        let stored = |r: &CornerRecord, w: [f32; 3]| Corners {
            p: [0, 1, 2].map(|i| r.position(i)),
            n: [0, 1, 2].map(|i| r.normal(i)),
            g: [0, 1, 2].map(|i| r.normal(i)),
            seam_pn: [false; 3],
            seam_phong: [false; 3],
            w,
            order: [0, 1, 2],
        };
        let params = SurfaceParams::default();
        let n = 37;
        for s in [Surface::Pn] {
            let mut differ = 0;
            for k in 1..n {
                let wa = crate::pattern::weight(n - k, n);
                let wb = crate::pattern::weight(k, n);
                let field = NormalField::default();
                let p1 = eval_corners(
                    s,
                    &params,
                    field,
                    &stored(&r1, [wa, wb, 0.0]),
                    &Default::default(),
                )
                .position;
                let p2 = eval_corners(
                    s,
                    &params,
                    field,
                    &stored(&r2, [wb, wa, 0.0]),
                    &Default::default(),
                )
                .position;
                if p1.to_array().map(f32::to_bits) != p2.to_array().map(f32::to_bits) {
                    differ += 1;
                }
                // The two are the same point up to rounding.
                assert!((p1 - p2).length() < 1e-5, "{}: {p1} vs {p2}", s.name());
            }
            assert!(
                differ > 0,
                "{}: the stored order happened to be watertight too; the test lost its power",
                s.name()
            );
        }
    }
}
