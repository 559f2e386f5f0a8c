//! The bounds against the surfaces themselves: dense sampling of the real evaluation
//! (`surface::Mirror::eval`, what every driver mirrors) on real meshes and random elements.

use super::*;
use crate::lod::frame::Rounding;
use crate::mesh::test_support::load_model;
use crate::mesh::Mesh;
use crate::pattern::weight;
use crate::subdiv::bft::Lattice;
use crate::subdiv::Boundary;
use crate::surface::loop_::LoopData;
use crate::surface::{
    build_records, BuildOptions, CornerRecord, Displace, ElementRecord, Heightmap, Mirror,
    NormalField, RecordKind, Seams, Sources, Surface, SurfaceParams, SurfacePoint,
};
use glam::{Mat4, Vec3, Vec4};

/// Interior sample grid per lattice triangle (points `a/R, b/R, c/R`).
const R: u32 = 6;
/// Samples per segment along an edge.
const RE: u32 = 16;

fn lattice_bary(n: u32, i: u32, j: u32) -> [f32; 3] {
    [weight(n - i - j, n), weight(i, n), weight(j, n)]
}

fn mix(b: [[f32; 3]; 3], l: [f32; 3]) -> [f32; 3] {
    [0, 1, 2].map(|c| b[0][c] * l[0] + b[1][c] * l[1] + b[2][c] * l[2])
}

/// The lattice triangles of level `n` as lattice coordinates.
fn lattice_triangles(n: u32) -> Vec<[(u32, u32); 3]> {
    let mut out = Vec::new();
    for j in 0..n {
        for i in 0..n - j {
            out.push([(i, j), (i + 1, j), (i, j + 1)]);
            if i + j + 1 < n {
                out.push([(i + 1, j), (i + 1, j + 1), (i, j + 1)]);
            }
        }
    }
    out
}

/// A surface, its normal field and a displacement, with the inputs they read (the texture
/// coordinates, when given, are those of every element checked: element 0's).
struct Case<'a> {
    surface: Surface,
    field: NormalField,
    displace: Displace,
    params: SurfaceParams,
    inputs: Sources<'a>,
}

impl Case<'_> {
    /// `surface` displaced by `displace` with the default normal field, parameters and inputs
    /// (`params` as given).
    fn plain(surface: Surface, displace: Displace, params: SurfaceParams) -> Self {
        Case {
            surface,
            field: NormalField::default(),
            displace,
            params,
            inputs: Sources::default(),
        }
    }
}

impl<'a> Case<'a> {
    /// `loop` on `data`'s faces posed as `frame`, displaced by `displace` with `params`.
    fn loop_(
        data: &'a LoopData,
        frame: &'a crate::surface::loop_::LoopFrame,
        displace: Displace,
        params: SurfaceParams,
    ) -> Self {
        Case {
            inputs: Sources {
                loop_: Some((data, frame)),
                ..Default::default()
            },
            ..Case::plain(Surface::Loop, displace, params)
        }
    }

    fn mirror(&self) -> Mirror<'_> {
        let build = BuildOptions {
            normal_field: self.field,
            ..BuildOptions::default()
        };
        Mirror::new(self.surface, self.displace, &build, &self.inputs).unwrap()
    }

    /// The case for element `t` alone: its own texture coordinates, where every element's are
    /// given (they are then the ones evaluated, as element 0's).
    fn element(&self, t: usize) -> Case<'_> {
        Case {
            inputs: Sources {
                uvs: (self.inputs.uvs).map(|u| std::slice::from_ref(&u[t])),
                ..self.inputs
            },
            ..*self
        }
    }

    fn point(&self, rec: &ElementRecord, b: [f32; 3]) -> SurfacePoint {
        self.mirror().eval(&self.params, 0, rec, b)
    }

    fn at(&self, rec: &ElementRecord, b: [f32; 3]) -> Vec3 {
        self.point(rec, b).position
    }

    fn lod(&self) -> Lod<'_> {
        Lod::new(&self.mirror(), &self.params)
    }

    /// The largest distance between the surface and the flat triangle through its points at
    /// weights `b` (of the element's corners), sampled densely over the triangle.
    fn triangle_error(&self, rec: &ElementRecord, b: [[f32; 3]; 3]) -> f32 {
        let p = b.map(|b| self.at(rec, b));
        let mut worst = 0.0f32;
        for c in 0..=R {
            for a in 0..=R - c {
                let l = [(R - a - c) as f32, a as f32, c as f32].map(|x| x / R as f32);
                let lin = p[0] * l[0] + p[1] * l[1] + p[2] * l[2];
                worst = worst.max((self.at(rec, mix(b, l)) - lin).length());
            }
        }
        worst
    }

    /// The true largest distance between the surface and its interpolation at level `n`, over
    /// the element (dense samples of every lattice triangle) and along each stored edge.
    fn true_error(&self, rec: &ElementRecord, n: u32) -> (f32, [f32; 3]) {
        let mut inner = 0.0f32;
        for t in lattice_triangles(n) {
            inner = inner.max(self.triangle_error(rec, t.map(|(i, j)| lattice_bary(n, i, j))));
        }
        let mut edges = [0.0f32; 3];
        for (e, out) in edges.iter_mut().enumerate() {
            let on = |t: f32| {
                let mut b = [0.0f32; 3];
                b[e] = 1.0 - t;
                b[(e + 1) % 3] = t;
                b
            };
            for k in 0..n {
                let (b0, b1) = (on(k as f32 / n as f32), on((k + 1) as f32 / n as f32));
                let (p0, p1) = (self.at(rec, b0), self.at(rec, b1));
                for s in 1..RE {
                    let f = s as f32 / RE as f32;
                    let b = [0, 1, 2].map(|c| b0[c] * (1.0 - f) + b1[c] * f);
                    *out = out.max((self.at(rec, b) - (p0 * (1.0 - f) + p1 * f)).length());
                }
            }
        }
        (inner, edges)
    }

    /// Checks every bound of `records` at `levels` against sampling; returns the smallest and
    /// the median ratio bound / truth over the elements whose true error is above rounding.
    fn check(
        &self,
        records: &[ElementRecord],
        levels: &[u32],
        scale: f32,
        what: &str,
    ) -> (f32, f32) {
        self.check_lod(&self.lod(), records, levels, scale, what, 1.0)
    }

    /// [`Case::check`] with the bounds of `lod` (this case's, or made for a driver's rounding:
    /// [`Lod::drawn_as`]), each multiplied by `shrink` (below 1: a bound made too small, which
    /// the check must catch).
    fn check_lod(
        &self,
        lod: &Lod,
        records: &[ElementRecord],
        levels: &[u32],
        scale: f32,
        what: &str,
        shrink: f32,
    ) -> (f32, f32) {
        let slack = 64.0 * f32::EPSILON * scale;
        let mut ratios = Vec::new();
        for (ix, rec) in records.iter().enumerate() {
            let b = lod.element(rec);
            let eb = [0, 1, 2].map(|e| lod.edge(rec, e));
            for &n in levels {
                let (inner, edges) = self.true_error(rec, n);
                let bound = b.element_error(n as f32) * shrink;
                assert!(
                    inner <= bound + slack,
                    "{what}: element {ix} at level {n}: true chord error {inner} above the bound {bound}"
                );
                for e in 0..3 {
                    let eb = eb[e].chord.error(n as f32) * shrink;
                    assert!(
                        edges[e] <= eb + slack,
                        "{what}: element {ix} edge {e} at level {n}: true {} above the bound {eb}",
                        edges[e]
                    );
                }
                if inner > 1e3 * slack && bound.is_finite() {
                    ratios.push(bound / inner);
                }
            }
        }
        ratios.sort_by(f32::total_cmp);
        let min = ratios.first().copied().unwrap_or(1.0);
        let median = ratios.get(ratios.len() / 2).copied().unwrap_or(1.0);
        eprintln!("{what}: bound / truth smallest {min}, median {median}");
        (min, median)
    }
}

fn corner_records(file: &str) -> (Mesh, Vec<ElementRecord>) {
    let (mesh, _) = load_model(file);
    let recs = build_records(RecordKind::Corners, &mesh, Seams::Closed);
    (mesh, recs)
}

/// Random triangles of size about 1 with normals up to ~45° off the face normal.
fn random_records(count: usize, seed: u64) -> Vec<ElementRecord> {
    let mut s = seed;
    let mut rnd = move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 33) as f32 / (1u64 << 31) as f32) * 2.0 - 1.0
    };
    (0..count)
        .map(|i| {
            let p = [0; 3].map(|_| Vec3::new(rnd(), rnd(), rnd()));
            let f = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
            let n = [0; 3].map(|_| (f + Vec3::new(rnd(), rnd(), rnd()) * 0.55).normalize());
            let i = i as u32 * 3;
            CornerRecord::new(p, n, [i + 2, i, i + 1]).encode()
        })
        .collect()
}

fn every(v: &[ElementRecord], step: usize) -> Vec<ElementRecord> {
    v.iter().step_by(step).copied().collect()
}

mod bounds;
mod cull;
mod heightmap;
mod levels;
mod loop_bounds;
mod polynomial;
mod view;
