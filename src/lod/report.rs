//! What adaptive refinement draws for one camera: every element's level (from its bounds and
//! its edges' bounds, [`View::levels`]) or its culling, tallied against the smallest uniform
//! level that meets the same pixel error everywhere.

use super::{integer_level, Frustum, Lod, View};
use crate::surface::ElementRecord;
use std::collections::BTreeMap;

/// The levels one camera asks for.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LevelReport {
    /// Elements per inner level (segments per edge), visible elements only.
    pub histogram: BTreeMap<u32, u64>,
    /// Elements outside the view frustum (their bounding spheres are).
    pub culled: u64,
    /// Triangles the visible elements make at their inner levels (`N²` each).
    pub adaptive_triangles: u64,
    /// The smallest level that, given to every element, meets the same pixel error everywhere:
    /// the largest inner level any visible element needs (1 when none is visible).
    pub uniform_level: u32,
    /// Triangles every element makes at [`LevelReport::uniform_level`].
    pub uniform_triangles: u64,
}

impl LevelReport {
    /// `L:n` pairs, level ascending (`4:120 8:30`).
    pub fn histogram_line(&self) -> String {
        let pairs: Vec<String> = self
            .histogram
            .iter()
            .map(|(l, n)| format!("{l}:{n}"))
            .collect();
        pairs.join(" ")
    }
}

/// The levels `view` gives each of `records` (bounded by `lod`), culling against `frustum` when
/// given.
pub fn report(
    lod: &Lod,
    records: &[ElementRecord],
    view: &View,
    frustum: Option<&Frustum>,
) -> LevelReport {
    let mut r = LevelReport {
        uniform_level: 1,
        ..LevelReport::default()
    };
    for rec in records {
        let element = lod.element(rec);
        if frustum.is_some_and(|f| f.outside(&element.sphere)) {
            r.culled += 1;
            continue;
        }
        let edges = [0, 1, 2].map(|e| lod.edge(rec, e));
        let (_, inner) = view.levels(&element, &edges);
        let n = integer_level(inner).max(1);
        *r.histogram.entry(n).or_default() += 1;
        r.adaptive_triangles += n as u64 * n as u64;
        r.uniform_level = r.uniform_level.max(n);
    }
    let u = r.uniform_level as u64;
    r.uniform_triangles = records.len() as u64 * u * u;
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lod::Sphere;
    use crate::mesh::test_support::load_model;
    use crate::surface::{build_records, BuildOptions, Displace, Inputs, Surface, SurfaceParams};
    use glam::Vec3;

    /// Every element is counted once, the uniform level is the largest inner level, and a
    /// camera twice as far asks for no more triangles.
    #[test]
    fn report_tallies_every_element() {
        let (mesh, _) = load_model("spot_control_tri.obj");
        let records = build_records(
            Surface::Pn.record_kind(),
            &mesh,
            BuildOptions::default().seams,
        );
        let inputs = Inputs::default();
        let params = SurfaceParams::default();
        let lod = Lod::new(Surface::Pn, Displace::None, &params, &inputs);
        let s = Sphere::around(&mesh.positions);
        let at = |d: f32| {
            let view = View::new(s.centre + Vec3::Z * d, 0.8, 720, 1.0, 64);
            report(&lod, &records, &view, None)
        };
        let near = at(3.0 * s.radius);
        let drawn: u64 = near.histogram.values().sum();
        assert_eq!(drawn + near.culled, records.len() as u64);
        assert_eq!(near.uniform_level, *near.histogram.keys().max().unwrap());
        let tris: u64 = near.histogram.iter().map(|(l, n)| (l * l) as u64 * n).sum();
        assert_eq!(tris, near.adaptive_triangles);
        let far = at(6.0 * s.radius);
        assert!(far.adaptive_triangles <= near.adaptive_triangles);
        assert!(far.uniform_level <= near.uniform_level);
    }
}
