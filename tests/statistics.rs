//! Pipeline statistics of each driver match the counts its geometry implies.
//! Exact: input-assembly and clipping primitives, tessellation-control patches. Vertex-shader and
//! evaluation-shader invocations may legally repeat (post-transform caches differ between
//! implementations), so those are bounded: at least one per distinct vertex, at most one per
//! index (pattern/static) or twice per distinct vertex (tess).

mod common;

use common::{model, with_gpu};
use meshrefine::pattern::{index_count, triangle_count, vertex_count, PatternSet};
use meshrefine::render::tess::{tess_triangle_count, tess_vertex_count};
use meshrefine::render::{Camera, DrawConfig, Driver, Scene, Submit};

#[test]
fn statistics_match_geometry() {
    with_gpu(128, 128, |h| {
        assert!(
            h.queries.has_statistics(),
            "lavapipe offers pipelineStatisticsQuery"
        );
        let levels = [4u32, 7];
        let mut scene = Scene::with_patterns(
            &h.ctx,
            &h.pool,
            &h.renderer,
            model("icosahedron.obj"),
            PatternSet::from_levels(&levels),
        )
        .unwrap();
        let (c, r) = scene.bounding_sphere();
        let camera = Camera::framing(c, r);
        let t = scene.gpu.element_count as u64;
        for n in levels {
            let configs = [
                DrawConfig::new(Driver::Static, n),
                DrawConfig::new(Driver::Pattern(Submit::Push), n),
                DrawConfig::new(Driver::Pattern(Submit::Ubo), n),
                DrawConfig::new(Driver::Pattern(Submit::Instanced), n),
                DrawConfig::new(Driver::Tess, n),
            ];
            for cfg in configs {
                let s = h.draw(&mut scene, &cfg, &camera).unwrap().stats.unwrap();
                let what = format!("{} level {n}: {s:?}", cfg.label());
                eprintln!("{what}");
                match cfg.driver {
                    Driver::Static | Driver::Pattern(_) => {
                        let tris = t * triangle_count(n) as u64;
                        assert_eq!(s.input_assembly_primitives, tris, "{what}");
                        assert_eq!(s.clipping_primitives, tris, "{what}");
                        assert!(
                            s.vertex_shader_invocations >= t * vertex_count(n) as u64,
                            "{what}"
                        );
                        assert!(
                            s.vertex_shader_invocations <= t * index_count(n) as u64,
                            "{what}"
                        );
                        assert_eq!(s.tess_control_patches, 0, "{what}");
                        assert_eq!(s.tess_evaluation_invocations, 0, "{what}");
                    }
                    Driver::Tess => {
                        assert_eq!(
                            s.input_assembly_primitives, t,
                            "{what}: one patch per coarse triangle"
                        );
                        assert_eq!(s.tess_control_patches, t, "{what}");
                        assert_eq!(s.vertex_shader_invocations, 3 * t, "{what}");
                        assert_eq!(
                            s.clipping_primitives,
                            t * tess_triangle_count(n) as u64,
                            "{what}"
                        );
                        let distinct = t * tess_vertex_count(n) as u64;
                        assert!(s.tess_evaluation_invocations >= distinct, "{what}");
                        assert!(s.tess_evaluation_invocations <= 2 * distinct, "{what}");
                    }
                }
            }
        }
    });
}
