//! Chord-error bounds of an element and its edges from the element's record alone, for every
//! surface and displacement: each declares its own part (src/surface/bounds.rs) and this module
//! combines them; the proofs are in the module notes of src/lod/mod.rs and beside each surface.
//! A local surface is written as a triangular Bézier net ([`Net`]) in canonical corner order
//! (src/surface/mod.rs), the order the surfaces evaluate in, so an edge's net is the very same
//! on both sides of the edge.

pub use super::net::Net;
use super::{
    Chord, Sphere, CUBIC_FACTOR, EDGE_FACTOR, EDGE_KINK_FACTOR, ELEMENT_FACTOR, KINK_FACTOR,
    QUADRATIC_FACTOR,
};
use crate::surface::bounds::{DisplaceBound, Height, Patch, Radial, SurfaceBound};
use crate::surface::{
    canonical, edge_of, stpn, CornerRecord, Corners, Displace, DisplaceInputs, ElementRecord,
    Mirror, Surface, SurfaceInputs, SurfaceParams,
};
use glam::Vec2;

/// Bounds of one element or edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub chord: Chord,
    /// Contains every point of the patch (displaced).
    pub sphere: Sphere,
    /// `M_k >= sup |D²P[d_k, d_k]|` per lattice direction, in stored order (`d0`: corner 0 → 1,
    /// `d1`: 1 → 2, `d2`: 2 → 0), displacement included (its kinks excepted); for an edge, the
    /// curve's in `[0]`.
    pub second: [f32; 3],
    /// `B_k >= sup |D²P[d_k, d_{k+1}]|`, the mixed second derivative of stored directions `k`
    /// and `k + 1`, displacement included (its kinks excepted): the surface's own bound where it
    /// has one, never above `Σ/2` (`Σ = M_0 + M_1 + M_2`, polarization: `2 D²P[d_k, d_{k+1}] =
    /// D²P[d_{k+2}, d_{k+2}] − D²P[d_k, d_k] − D²P[d_{k+1}, d_{k+1}]`, as `d_k + d_{k+1} =
    /// −d_{k+2}`). Not used for an edge.
    pub mixed: [f32; 3],
    /// The height map's kink terms for lattice segments of unit size (`chord` holds them at
    /// `h = 1/N`: `c1 h + c2 h²`), zero for every other surface.
    pub kink: Chord,
    /// The cone of the drawn triangles' normals (elements of undisplaced Bézier surfaces only).
    pub cone: Option<super::NormalCone>,
    /// Where the element's surface is a polynomial of degree at most 3 (`flat`, `phong`, `pn`,
    /// `stpn` where no displacement moves it), its lattice triangles are also within `max_k M_k / (6N²) +
    /// cubic / N³` ([`Bounds::element_error`]): `cubic = 4/81 · C̄` ([`Net::third`]; the proof
    /// is in src/lod/mod.rs, "A polynomial patch"). Infinity elsewhere, and for an edge.
    pub cubic: f32,
}

impl Bounds {
    /// The element's chord error at level `n`: the smaller of [`Bounds::chord`]'s and, for a
    /// polynomial patch, `max_k M_k / (6n²) + cubic / n³` ([`Bounds::cubic`]). Mirror of what
    /// `lod::frame::own_level` turns into a level (for the lattice).
    pub fn element_error(&self, n: f32) -> f32 {
        let general = self.chord.error(n);
        if !self.cubic.is_finite() {
            return general;
        }
        let mx = self.second.iter().fold(0.0f32, |a, &b| a.max(b));
        let x = 1.0 / n;
        general.min((QUADRATIC_FACTOR * mx + self.cubic * x) * x * x)
    }

    /// A bound of `|D²P[e, e]|` for a parameter vector `e = (du, dv)` of an element, from the
    /// three directions' bounds and the mixed ones: `e = α a + β b` for two lattice directions
    /// `a`, `b` whose sum or difference is the third, so `|Q(e)| <= α² M_a + β² M_b + 2|αβ|
    /// B_ab` ([`Bounds::mixed`], at most `ΣM/2`); the least of the three choices.
    pub fn second_along(&self, e: [f32; 2]) -> f32 {
        second_along(self.second, self.mixed, e)
    }

    /// The chord error of any triangle of an element's parameter domain, corners `(u, v)` (the
    /// weights of corners 1 and 2): what the transition triangles between an element's inner
    /// level and its edges' levels need. `9/40 · max` over its sides of [`Bounds::second_along`],
    /// plus the kink terms at the size `h = max (|du| + |dv|)` of its sides (a side's texel
    /// extent is at most `h` times the lattice directions' largest, and `h` bounds its extent in
    /// lattice directions: `(du, dv) = du d0 − dv d2`); for a polynomial patch the smaller of
    /// that and `max / 6 + cubic · h³` (src/lod/frame/transitions.rs, "Polynomial patches").
    /// Element bounds only.
    pub fn triangle_error(&self, uv: [[f32; 2]; 3]) -> f32 {
        let (mut q, mut h) = (0.0f32, 0.0f32);
        for i in 0..3 {
            let (a, b) = (uv[i], uv[(i + 1) % 3]);
            let e = [b[0] - a[0], b[1] - a[1]];
            q = q.max(self.second_along(e));
            h = h.max(e[0].abs() + e[1].abs());
        }
        let general = ELEMENT_FACTOR * q + (self.kink.c1 + self.kink.c2 * h) * h;
        if !self.cubic.is_finite() {
            return general;
        }
        general.min(QUADRATIC_FACTOR * q + self.cubic * h * h * h)
    }
}

/// [`Bounds::second_along`] from the directional bounds `m` (`M_k`) and the mixed ones `b`
/// (`B_k`). Mirror: `second_along` in glsl/lod/levels.comp.
pub fn second_along(m: [f32; 3], b: [f32; 3], e: [f32; 2]) -> f32 {
    let [m0, m1, m2] = m;
    let [b0, b1, b2] = b;
    let (x, y) = (e[0], e[1]);
    let w = x + y;
    // e = x d0 − y d2 (B_2), e = (x + y) d0 + y d1 (B_0), e = −x d1 − (x + y) d2 (B_1).
    let a = x * x * m0 + y * y * m2 + 2.0 * (x * y).abs() * b2;
    let b = w * w * m0 + y * y * m1 + 2.0 * (w * y).abs() * b0;
    let c = x * x * m1 + w * w * m2 + 2.0 * (x * w).abs() * b1;
    a.min(b).min(c)
}

/// What bounds need besides the records, built once per mesh and parameters.
#[derive(Clone, Copy)]
pub struct Lod<'a> {
    pub surface: Surface,
    pub displace: Displace,
    pub params: SurfaceParams,
    /// The surface and displacement with their inputs (what the bounds bound).
    pub mirror: Mirror<'a>,
    /// The texture coordinates of the element bounded (the height map reads them; set per
    /// element by `lod::frame::lod_records`, the first element's to begin with).
    pub uv: Option<&'a [[f32; 2]; 3]>,
    /// The two pyramid levels the height map reads (the same level twice when it reads one).
    pub map_levels: Option<[usize; 2]>,
    /// How the driver rounds levels and meets coarser edges: `loop`'s bounds depend on whether
    /// its drawn samples are lattice points (src/surface/loop_bound.rs). [`Lod::new`] takes the
    /// tessellator's integer levels, which are not; [`Lod::drawn_as`] sets it.
    pub rounding: super::frame::Rounding,
}

impl<'a> Lod<'a> {
    pub fn new(mirror: &Mirror<'a>, params: &SurfaceParams) -> Self {
        let displace = mirror.displace();
        let map_levels = match (displace.facts().bound, mirror.displace) {
            (DisplaceBound::Texture(t), DisplaceInputs::Heightmap(h)) => {
                Some((t.levels)(h.map, h.lod))
            }
            _ => None,
        };
        Self {
            surface: mirror.surface(),
            displace,
            params: *params,
            mirror: *mirror,
            uv: mirror.uv(0),
            map_levels,
            rounding: super::frame::Rounding::Integer,
        }
    }

    /// This `Lod` for a driver that rounds as `rounding` ([`Lod::rounding`]).
    pub fn drawn_as(self, rounding: super::frame::Rounding) -> Self {
        Self { rounding, ..self }
    }

    /// [`Lod::new`] of `surface` with `displace`, their inputs from `sources` and the default
    /// build options (the unit tests' shorthand).
    #[cfg(test)]
    pub(crate) fn of(
        surface: Surface,
        displace: Displace,
        params: &SurfaceParams,
        sources: &crate::surface::Sources<'a>,
    ) -> Self {
        let build = crate::surface::BuildOptions::default();
        Self::new(
            &Mirror::new(surface, displace, &build, sources).unwrap(),
            params,
        )
    }

    /// This `Lod` for element `t` (its texture coordinates).
    pub fn for_element(&self, t: usize) -> Self {
        Self {
            uv: self.mirror.uv(t),
            ..*self
        }
    }

    /// The bounds of element `rec`.
    pub fn element(&self, rec: &ElementRecord) -> Bounds {
        if let SurfaceBound::Own { element, .. } = self.surface.facts().bound {
            return element(self, rec);
        }
        let r = CornerRecord::decode(rec);
        let c = canonical(&r, [1.0 / 3.0; 3]);
        self.local(&r, &c, None)
    }

    /// The bounds of stored edge `e` (corners `e` and `e + 1`) of element `rec`: from the edge's
    /// data alone, the same bits from either element that has it.
    pub fn edge(&self, rec: &ElementRecord, e: usize) -> Bounds {
        if let SurfaceBound::Own { edge, .. } = self.surface.facts().bound {
            return edge(self, rec, e);
        }
        let r = CornerRecord::decode(rec);
        let mut bary = [0.5f32; 3];
        bary[(e + 2) % 3] = 0.0;
        // The edge's corners first, by global index: canonical edge 0.
        let c = canonical(&r, bary);
        self.local(&r, &c, Some(0))
    }

    fn tags(&self, r: &CornerRecord, c: &Corners) -> [stpn::VertexTag; 3] {
        let tags = match self.mirror.surface {
            SurfaceInputs::Stpn(i) => i.tags,
            _ => None,
        };
        tags.map_or([stpn::VertexTag::default(); 3], |t| {
            stpn::corner_tags(t, &r.idx, c.order)
        })
    }

    /// Bounds on canonical corners `c`, of the whole element or (`edge = Some(0)`) of canonical
    /// edge 0.
    fn local(&self, r: &CornerRecord, c: &Corners, edge: Option<usize>) -> Bounds {
        let tags = self.tags(r, c);
        let (net, exact, sphere) = self.patch(c, &tags, edge);
        let exact = exact.then_some(net);
        let dirs: Vec<usize> = match edge {
            Some(k) => vec![k],
            None => vec![0, 1, 2],
        };
        let mut m: Vec<f32> = dirs.iter().map(|&k| net.second(k, edge)).collect();
        // Canonical pairs (k, k + 1): the net's mixed differences (elements only).
        let mut mixed: Vec<f32> = match edge {
            Some(_) => vec![],
            None => dirs.iter().map(|&k| net.mixed(k)).collect(),
        };
        if exact.is_none() {
            m.iter_mut().for_each(|x| *x = f32::INFINITY);
            mixed.iter_mut().for_each(|x| *x = f32::INFINITY);
        }
        let displaced = !matches!(self.displace.facts().bound, DisplaceBound::Zero);
        let (mut kink, mut grow) = (Chord::ZERO, 0.0f32);
        if displaced {
            let (extra, k, g) = self.displacement(c, &tags, &net, &sphere, edge);
            // The displacement's own mixed term by polarization of its directional ones:
            // `|D²(hN)[d_k, d_{k+1}]| <= (E_0 + E_1 + E_2)/2` (a sum of the two bilinear forms).
            let half: f32 = 0.5 * extra.iter().sum::<f32>();
            mixed.iter_mut().for_each(|b| *b += half);
            for (mk, e) in m.iter_mut().zip(extra) {
                *mk += e;
            }
            kink = k;
            grow = g;
        }
        let worst = m.iter().fold(0.0f32, |a, &b| a.max(b));
        let factor = if edge.is_some() {
            EDGE_FACTOR
        } else {
            ELEMENT_FACTOR
        };
        let mut second = [0.0f32; 3];
        let mut stored_mixed = [0.0f32; 3];
        match edge {
            Some(_) => second[0] = m[0],
            None => {
                let dir = |k: usize| edge_of(c.order[k % 3], c.order[(k + 1) % 3]);
                for k in 0..3 {
                    second[dir(k)] = m[k];
                }
                // Canonical directions k, k + 1 are stored directions `dir(k)`, `dir(k + 1)`
                // up to sign (which `|D²P[·, ·]|` ignores): the stored pair starting at
                // whichever of the two the other follows.
                let half = 0.5 * (m[0] + m[1] + m[2]);
                for (k, &b) in mixed.iter().enumerate() {
                    let (x, y) = (dir(k), dir(k + 1));
                    let j = if y == (x + 1) % 3 { x } else { y };
                    stored_mixed[j] = b.min(half);
                }
            }
        }
        // The normal cone is the undisplaced surface's: only where nothing moves it.
        let cone = match (edge, exact, self.params.moves(self.displace)) {
            (None, Some(net), false) => super::cull::normal_cone(&net, odd_permutation(c.order)),
            _ => None,
        };
        // A polynomial of degree at most 3 where nothing displaces it: the lattice's own
        // tighter bound (src/lod/mod.rs, "A polynomial patch").
        let cubic = match (edge, exact) {
            (None, Some(net)) if !self.params.moves(self.displace) && net.degree <= 3 => {
                CUBIC_FACTOR * net.third()
            }
            _ => f32::INFINITY,
        };
        Bounds {
            chord: Chord {
                c1: kink.c1,
                c2: factor * worst + kink.c2,
            },
            sphere: sphere.grown(grow),
            second,
            mixed: stored_mixed,
            kink,
            cone,
            cubic,
        }
    }

    /// The undisplaced patch on canonical corners `c` (the whole element, or with `edge`
    /// canonical edge 0): its net, whether the net is the surface exactly, and a sphere holding
    /// the patch (the net's hull, grown by how far the surface may lie from a net that is not).
    fn patch(
        &self,
        c: &Corners,
        tags: &[stpn::VertexTag; 3],
        edge: Option<usize>,
    ) -> (Net, bool, Sphere) {
        let SurfaceBound::Nets { geometry, .. } = self.surface.facts().bound else {
            unreachable!("surfaces with bounds of their own return before");
        };
        match geometry(&self.params, c, tags, edge.is_some()) {
            Patch::Exact(net) => (net, true, Sphere::around(&net.hull(edge))),
            Patch::Near(net, d) => (net, false, Sphere::around(&net.hull(edge)).grown(d)),
        }
    }

    /// The sphere [`Lod::element`] gives element `rec` where nothing displaces the surface,
    /// without the rest of its bounds (what telling an eye outside the surface needs); `None`
    /// for a surface with bounds of its own (`loop`) or a displaced one.
    pub fn undisplaced_sphere(&self, rec: &ElementRecord) -> Option<Sphere> {
        let own = matches!(self.surface.facts().bound, SurfaceBound::Own { .. });
        let displaced = !matches!(self.displace.facts().bound, DisplaceBound::Zero);
        if own || displaced {
            return None;
        }
        let r = CornerRecord::decode(rec);
        let c = canonical(&r, [1.0 / 3.0; 3]);
        Some(self.patch(&c, &self.tags(&r, &c), None).2)
    }

    /// What displacement adds to each direction's `M_k`, its kink terms, and how far it moves
    /// points (the sphere's growth).
    fn displacement(
        &self,
        c: &Corners,
        tags: &[stpn::VertexTag; 3],
        net: &Net,
        sphere: &Sphere,
        edge: Option<usize>,
    ) -> (Vec<f32>, Chord, f32) {
        let dirs: Vec<usize> = match edge {
            Some(k) => vec![k],
            None => vec![0, 1, 2],
        };
        let p = &self.params;
        // The direction field's nets (several on a scalar-tagged edge with crease corners, whose
        // sharp normal depends on the side).
        let SurfaceBound::Nets { direction, .. } = self.surface.facts().bound else {
            unreachable!("surfaces with bounds of their own return before");
        };
        let nets = direction(p, self.mirror.normal_field(), c, tags, edge.is_some());
        let mut extra = vec![0.0f32; dirs.len()];
        let mut kink = Chord::ZERO;
        let bound = self.displace.facts().bound;
        let mut max_h = bound.max_height(p, sphere);
        // Height derivative bounds per direction: |h'| and the smooth part of |h''|.
        let mut h1 = vec![0.0f32; dirs.len()];
        let mut h2 = vec![0.0f32; dirs.len()];
        match bound {
            DisplaceBound::Texture(t) => {
                let uv = self
                    .uv
                    .map(|x| c.order.map(|i| Vec2::from(x[i])))
                    .unwrap_or([Vec2::ZERO; 3]);
                let (Some(levels), DisplaceInputs::Heightmap(h)) = (
                    self.map_levels.filter(|_| self.uv.is_some()),
                    self.mirror.displace,
                ) else {
                    // No map or no coordinates: the displacement is the constant a·(0 − b)... but
                    // the evaluation reads h = 0 then: a constant offset along the normal.
                    return self.smooth_only(&dirs, &nets, edge, max_h);
                };
                let f = if edge.is_some() {
                    EDGE_KINK_FACTOR
                } else {
                    KINK_FACTOR
                };
                (h1, kink, max_h) = (t.slopes)(p, h.map, levels, uv, &dirs, f);
            }
            DisplaceBound::OfPoint(height) => {
                let hb = height(p, sphere);
                let mut firsts = [0.0f32; 3];
                dirs.iter()
                    .for_each(|&k| firsts[k] = net.first_sup(k, edge));
                for (i, &k) in dirs.iter().enumerate() {
                    let (v, m) = (firsts[k], net.second(k, edge));
                    h1[i] = hb.grad * v;
                    h2[i] = hb.hess * v * v + hb.grad * m;
                    if let Some(r) = hb.radial {
                        let at = Along { k, edge, firsts, m };
                        (h1[i], h2[i]) = radial_height(&hb, r, net, sphere, at, [h1[i], h2[i]]);
                    }
                }
            }
            DisplaceBound::Zero => {}
        }
        for dn in &nets {
            let rho = dn.min_length(edge);
            for (i, &k) in dirs.iter().enumerate() {
                let (n1, n2) = (dn.first(k, edge), dn.second(k, edge));
                let e = moved_second(h1[i], h2[i], max_h, n1, n2, rho);
                extra[i] = extra[i].max(e);
            }
        }
        (extra, kink, max_h)
    }

    /// A height that does not vary along the surface (a height map without coordinates):
    /// only the moving direction's terms.
    fn smooth_only(
        &self,
        dirs: &[usize],
        nets: &[Net],
        edge: Option<usize>,
        max_h: f32,
    ) -> (Vec<f32>, Chord, f32) {
        let mut extra = vec![0.0f32; dirs.len()];
        for dn in nets {
            let rho = dn.min_length(edge);
            for (i, &k) in dirs.iter().enumerate() {
                let (n1, n2) = (dn.first(k, edge), dn.second(k, edge));
                let e = moved_second(0.0, 0.0, max_h, n1, n2, rho);
                extra[i] = extra[i].max(e);
            }
        }
        (extra, Chord::ZERO, max_h)
    }
}

/// A lattice direction `k` of a patch (of edge `k`'s curve with `edge`), with its net's
/// [`Net::first_sup`] per direction bounded and `M_k`.
#[derive(Clone, Copy)]
struct Along {
    k: usize,
    edge: Option<usize>,
    firsts: [f32; 3],
    m: f32,
}

/// `|h'|` and `|h''|` along direction `k` for a height of the distance from a point
/// ([`Radial`]), where that bounds them better than `plain` (the general bounds): with
/// `R >= sup |r'|` (`r = |P − o|`, [`Net::radial_first`] over the least distance `r_min`, at
/// most `|P'|`'s bound `V`), `|h'| <= G R` and, where `φ''`'s bound `C >= G/r_min`,
/// `|h''| <= C r'² + G (|P'|² − r'²)/r + G |P''| <= C R² + G (V² − R²)/r_min + G |P''|` (the
/// middle expression grows with `r'²` then). Mirror: the sine branch of `lod_local` in
/// glsl/include/lod.glsl.
fn radial_height(
    hb: &Height,
    r: Radial,
    net: &Net,
    sphere: &Sphere,
    at: Along,
    plain: [f32; 2],
) -> (f32, f32) {
    let d = (sphere.centre - r.origin).length();
    let (r_min, r_max) = (d - sphere.radius, d + sphere.radius);
    if !(r_min > 0.0 && r.curve * r_min >= hb.grad) {
        return (plain[0], plain[1]);
    }
    let Along { k, edge, firsts, m } = at;
    let v = firsts[k];
    let rate = (net.radial_first(k, edge, r.origin, r_max, firsts) / r_min).min(v);
    let second = r.curve * rate * rate + hb.grad * (v * v - rate * rate) / r_min + hb.grad * m;
    (plain[0].min(hb.grad * rate), plain[1].min(second))
}

/// Whether canonical order `o` is an odd permutation of the stored corners (it flips the
/// orientation of the parametrization).
fn odd_permutation(o: [usize; 3]) -> bool {
    !matches!(o, [0, 1, 2] | [1, 2, 0] | [2, 0, 1])
}

/// `|(hN)''| <= |h''| + 2|h'||N'| + |h||N''|` along a lattice direction, from bounds of `|h'|`,
/// `|h''|`, `|h|`, the direction polynomial's `|n'|`, `|n''|` and its least length `ρ`
/// (src/lod/mod.rs): `|N'| <= |n'|/ρ`, `|N''| <= |n''|/ρ + 2|n'|²/ρ²`; zero where the height and
/// its derivatives are (nothing moves), else infinite where `ρ` is not positive. Mirror: the
/// displacement term of `lod_local` in glsl/include/lod.glsl.
pub(crate) fn moved_second(h1: f32, h2: f32, h: f32, n1: f32, n2: f32, rho: f32) -> f32 {
    if h == 0.0 && h1 == 0.0 && h2 == 0.0 {
        // Nothing moves: nothing added, whatever the direction field.
        0.0
    } else if rho > 0.0 {
        h2 + 2.0 * h1 * n1 / rho + h * (n2 / rho + 2.0 * n1 * n1 / (rho * rho))
    } else {
        f32::INFINITY
    }
}
