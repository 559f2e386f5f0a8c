//! Shared edges from both sides: the same bound bits in both slots, the same levels.

use super::tests::{spot, view_at};
use super::*;
use crate::subdiv::bft::Lattice;
use crate::subdiv::Boundary;
use crate::surface::loop_::LoopData;
use crate::surface::{Displace, Sources, Surface, SurfaceParams};

/// Every edge two elements share holds the same bits in both slots, so both compute the same
/// level: for the local surfaces with displacement and for loop's M1 faces.
#[test]
fn shared_edges_hold_identical_bits() {
    let (mesh, recs) = spot();
    let r = mesh.bounding_radius();
    let data = LoopData::new(&mesh, Boundary::EdgeOnly, Lattice::default(), |_| {}).unwrap();
    let frame = data.frame(&mesh.positions);
    let params = SurfaceParams::for_radius(r);
    for (surface, displace) in [
        (Surface::Pn, Displace::Sine),
        (Surface::Phong, Displace::None),
        (Surface::Loop, Displace::None),
    ] {
        let inputs = Sources {
            loop_: Some((&data, &frame)),
            ..Default::default()
        };
        let lod = Lod::of(surface, displace, &params, &inputs);
        let records = if surface == Surface::Loop {
            &data.records
        } else {
            &recs
        };
        let lr = lod_records(&lod, records);
        // The gliding levels, and the integer ones with the lift (src/lod/frame/lift.rs).
        for rounding in [Rounding::Snapped, Rounding::SnappedInteger] {
            let mut seen: HashMap<(u32, u32), LodEdge> = HashMap::new();
            let mut shared = 0;
            let view = LodView::new(
                &view_at(Vec3::new(0.0, 0.3, 3.0 * r), 64),
                None,
                false,
                rounding,
                lr.len() as u32,
            );
            let levels = frame_levels(&view, &lr);
            let mut level_of: HashMap<(u32, u32), u32> = HashMap::new();
            for (i, rec) in records.iter().enumerate() {
                for e in 0..3 {
                    let key = edge_key(&lod, rec, e);
                    let slot = lr[i].edges[e];
                    let bits = levels[i].edges[e].to_bits();
                    if let Some(old) = seen.insert(key, slot) {
                        assert_eq!(bytemuck::bytes_of(&old), bytemuck::bytes_of(&slot));
                        assert_eq!(level_of[&key], bits);
                        shared += 1;
                    }
                    level_of.insert(key, bits);
                }
            }
            assert_eq!(shared * 2, 3 * records.len(), "{}", surface.name());
        }
    }
}
