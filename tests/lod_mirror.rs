//! The GPU mirror of the level-of-detail bounds (glsl/include/lod.glsl, run by
//! glsl/lod/bounds.comp) against src/lod on spot and a hard-edged cube, for `flat`, `phong` (at
//! alpha 0.75, and at 0 where it is the flat triangle, blended seam normals or not) and `pn`
//! (with each normal field) with no, sine and noise displacement: every element's and edge's
//! chord bound and sphere. The two evaluate the
//! same formulas in f32 with different rounding (GLSL's `length`, `normalize` and `sqrt` are not
//! correctly rounded), so they agree to a relative 1e-3 on the bounds, 1e-5 of the mesh's radius
//! on the spheres' centres and 1e-4 on the normal cones of undisplaced elements.

mod common;

use bytemuck::Zeroable;
use common::{model, with_gpu};
use glam::Vec3;
use meshrefine::gpu::{
    vk, Buffer, BufferDesc, DescriptorPool, DescriptorSetLayout, Pipeline, PipelineLayout,
};
use meshrefine::lod::{Bounds, Lod};
use meshrefine::render::bindings::*;
use meshrefine::render::FrameUniforms;
use meshrefine::surface::{
    build_records, BuildOptions, Displace, Mirror, NormalField, RecordKind, Seams, Sources,
    Surface, SurfaceParams,
};

/// Equal to a relative `rel`; the CPU's infinity (no finite bound) is the mirror's `LOD_HUGE`
/// (3e38), or a term of it scaled by the rest of the bound (above 1e30, which no finite bound
/// comes near: a level past any cap either way).
fn close(gpu: f32, cpu: f32, rel: f32) -> bool {
    if cpu.is_infinite() {
        return gpu >= 1.0e30;
    }
    // Or both under 1e-6 (both meshes have radii about 1): a bound that is rounding noise on a
    // flat face (PN over the cube's faces) is a few ulp of the coordinates, differently rounded.
    gpu == cpu
        || (gpu - cpu).abs() <= rel * gpu.abs().max(cpu.abs())
        || gpu.abs().max(cpu.abs()) <= 1e-6
}

#[test]
fn gpu_bounds_match_the_cpu() {
    with_gpu(16, 16, |h| {
        let mesh = model("spot_control_tri_vn.obj");
        let mut recs = build_records(RecordKind::Corners, &mesh, Seams::Closed);
        let r = mesh.bounding_radius();
        // The hard-edged cube's elements after Spot's: corners whose two edges pick different
        // normals (a seam and the face's diagonal), Phong's blended seam normals.
        let spot = recs.len();
        let cube = model("cube_face_normals.obj");
        recs.extend(build_records(RecordKind::Corners, &cube, Seams::Closed));
        let n = recs.len();
        let ctx = &h.ctx;
        let c = vk::ShaderStageFlags::COMPUTE;
        use vk::DescriptorType as T;
        let frame_layout =
            DescriptorSetLayout::new(ctx, &[(BINDING_FRAME, T::UNIFORM_BUFFER, c)], "lod frame")
                .unwrap();
        let mesh_layout = DescriptorSetLayout::new(
            ctx,
            &[(BINDING_ELEMENTS, T::STORAGE_BUFFER, c)],
            "lod records",
        )
        .unwrap();
        let out_layout = DescriptorSetLayout::new(
            ctx,
            &[(BINDING_LOD_BOUNDS, T::STORAGE_BUFFER, c)],
            "lod bounds",
        )
        .unwrap();
        let layout = PipelineLayout::new(
            ctx,
            &[&frame_layout, &mesh_layout, &out_layout],
            128,
            c,
            "lod bounds",
        )
        .unwrap();
        let pipeline =
            Pipeline::new_compute(ctx, &layout, "lod/bounds.comp", "lod bounds").unwrap();
        let storage = vk::BufferUsageFlags::STORAGE_BUFFER;
        let records = Buffer::new_with_data(ctx, &h.pool, storage, &recs, "records").unwrap();
        let mut frame = Buffer::new(
            ctx,
            BufferDesc::new_upload(
                std::mem::size_of::<FrameUniforms>() as u64,
                vk::BufferUsageFlags::UNIFORM_BUFFER,
            ),
            "frame",
        )
        .unwrap();
        let out = Buffer::new(
            ctx,
            BufferDesc::new_readback(n as u64 * 12 * 16, storage),
            "bounds",
        )
        .unwrap();
        let pool = DescriptorPool::new(
            ctx,
            3,
            &[(T::UNIFORM_BUFFER, 1), (T::STORAGE_BUFFER, 2)],
            "lod",
        )
        .unwrap();
        let sets = [
            pool.allocate(&frame_layout, "lod frame").unwrap(),
            pool.allocate(&mesh_layout, "lod records").unwrap(),
            pool.allocate(&out_layout, "lod bounds").unwrap(),
        ];
        pool.write_buffer(
            sets[0],
            BINDING_FRAME,
            T::UNIFORM_BUFFER,
            frame.raw,
            vk::WHOLE_SIZE,
        );
        pool.write_buffer(
            sets[1],
            BINDING_ELEMENTS,
            T::STORAGE_BUFFER,
            records.raw,
            vk::WHOLE_SIZE,
        );
        pool.write_buffer(
            sets[2],
            BINDING_LOD_BOUNDS,
            T::STORAGE_BUFFER,
            out.raw,
            vk::WHOLE_SIZE,
        );
        let params = SurfaceParams {
            octaves: 2,
            ..SurfaceParams::for_radius(r)
        };
        let (mut compared, mut cones, mut still_cones, mut cubics) = (0, 0, 0, 0);
        let (mut blended, mut flat_phong) = (0, 0);
        // pn with each normal field (the direction displacement moves along).
        let cases = [Surface::Flat, Surface::Phong]
            .map(|s| (s, NormalField::default()))
            .into_iter()
            .chain(NormalField::ALL.map(|f| (Surface::Pn, f)));
        for (surface, field) in cases {
            // A sine or noise of frequency zero displaces nothing (`sin 0`, `noise(0)`): bounds
            // as undisplaced, on both sides, whatever the direction field's least length. Nor
            // does any displacement of amplitude zero: all keep the undisplaced cones.
            let flat_sine = SurfaceParams {
                frequency: 0.0,
                ..params
            };
            let still = SurfaceParams {
                amplitude: 0.0,
                ..params
            };
            // Phong at alpha 0 is the flat triangle, blended seam normals or not: bounded.
            let unbent = SurfaceParams {
                alpha: 0.0,
                ..params
            };
            for (displace, params) in [
                (Displace::None, params),
                (Displace::Sine, params),
                (Displace::Noise, params),
                (Displace::Sine, flat_sine),
                (Displace::Noise, flat_sine),
                (Displace::Noise, still),
                (Displace::None, unbent),
            ] {
                let mut f = FrameUniforms::zeroed();
                f.params = params.to_gpu();
                f.origin = params.origin.extend(0.0).to_array();
                frame.write_pod(0, &[f]);
                let mut push = [0u32; 32];
                push[28] = surface as u32;
                push[29] = displace as u32;
                push[30] = field as u32;
                h.pool
                    .submit_and_wait(|cmd| {
                        cmd.bind_compute_pipeline(pipeline.raw);
                        for (i, &s) in sets.iter().enumerate() {
                            cmd.bind_compute_descriptor_set(layout.raw, i as u32, s);
                        }
                        cmd.push_constants(layout.raw, c, 0, bytemuck::cast_slice(&push));
                        cmd.dispatch((n as u32).div_ceil(64), 1, 1);
                        cmd.barrier_to_host();
                    })
                    .unwrap();
                let got: Vec<[f32; 4]> = out.read_pod();
                let build = BuildOptions {
                    normal_field: field,
                    ..BuildOptions::default()
                };
                let mirror = Mirror::new(surface, displace, &build, &Sources::default()).unwrap();
                let lod = Lod::new(&mirror, &params);
                let plain = Mirror::new(surface, Displace::None, &build, &Sources::default());
                let plain = Lod::new(&plain.unwrap(), &params);
                let what = format!(
                    "{} ({}) + {}",
                    surface.name(),
                    field.name(),
                    displace.name()
                );
                for (i, rec) in recs.iter().enumerate() {
                    let want: [Bounds; 4] = [
                        lod.element(rec),
                        lod.edge(rec, 0),
                        lod.edge(rec, 1),
                        lod.edge(rec, 2),
                    ];
                    if surface == Surface::Phong && displace == Displace::None && i >= spot {
                        if params.alpha == 0.0 {
                            // Zero on both sides, exactly.
                            assert_eq!(want[0].chord.c1 + want[0].chord.c2, 0.0, "{what}: {i}");
                            let gpu = got[12 * i];
                            assert_eq!((gpu[0], gpu[1]), (0.0, 0.0), "{what}: {i} on the GPU");
                            flat_phong += 1;
                        } else {
                            blended += want[0].chord.c2.is_infinite() as usize;
                        }
                    }
                    if params.frequency == 0.0 {
                        let undisplaced = plain.element(rec).chord;
                        assert_eq!(want[0].chord, undisplaced, "{what}: element {i}");
                        for e in 0..3 {
                            assert_eq!(want[e + 1].chord, plain.edge(rec, e).chord, "{what}");
                        }
                    }
                    for (k, w) in want.iter().enumerate() {
                        let at = 12 * i + 3 * k;
                        let (ch, sp, cone) = (got[at], got[at + 1], got[at + 2]);

                        assert!(
                            close(ch[0], w.chord.c1, 1e-3) && close(ch[1], w.chord.c2, 1e-3),
                            "{what}: element {i} bound {k}: GPU ({}, {}) {sp:?} vs CPU {:?}",
                            ch[0],
                            ch[1],
                            w
                        );
                        // The polynomial patch's cubic term (elements only).
                        assert!(
                            close(ch[2], w.cubic, 1e-3),
                            "{what}: element {i} bound {k}: GPU cubic {} vs CPU {}",
                            ch[2],
                            w.cubic
                        );
                        cubics += w.cubic.is_finite() as usize;
                        let centre = Vec3::new(sp[0], sp[1], sp[2]);
                        assert!(
                            (centre - w.sphere.centre).abs().max_element() <= 1e-5 * r
                                && close(sp[3], w.sphere.radius, 1e-3),
                            "{what}: element {i} bound {k}: GPU sphere {sp:?} vs CPU {:?}",
                            w.sphere
                        );
                        // The cone, where the CPU has one (or the GPU does, away from 90°).
                        match w.cone {
                            Some(cc) => assert!(
                                (Vec3::new(cone[0], cone[1], cone[2]) - cc.axis).length() <= 1e-4
                                    && (cone[3] - cc.cos).abs() <= 1e-4,
                                "{what}: element {i}: GPU cone {cone:?} vs CPU {cc:?}"
                            ),
                            None => assert!(
                                cone[3] <= 1e-3,
                                "{what}: element {i} bound {k}: GPU cone {cone:?}, none on the CPU"
                            ),
                        }
                        cones += w.cone.is_some() as usize;
                        if displace != Displace::None && !params.moves(displace) {
                            still_cones += w.cone.is_some() as usize;
                        }
                        compared += 1;
                    }
                }
            }
        }
        assert_eq!(compared, 20 * 7 * n);
        // The cube's blended elements have no finite bound at alpha 0.75, and zero at 0 (on the
        // GPU too: asserted above).
        assert!(blended >= 6, "{blended} blended Phong elements");
        assert_eq!(flat_phong, n - spot);
        assert!(cones > n, "{cones} cones");
        // Polynomial patches (undisplaced, or displaced by nothing) have a cubic term.
        assert!(cubics > 2 * n, "{cubics} cubic terms");
        // Displacement that moves nothing keeps the cones (facing-away culling stays on).
        assert!(
            still_cones > n,
            "{still_cones} cones without a moving displacement"
        );
    });
}
