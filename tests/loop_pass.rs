//! The Loop step M0 -> M1 on the GPU (the compute pass applying the computational entries)
//! equals the CPU step (`subdiv::loop_step`) to f32 precision: within 4e-7 of the mesh's radius
//! per coordinate (the entries' weights are f32, the sums have at most 25 terms). Animated M0
//! positions are re-uploaded alone: the bytes per frame are M0's 16 per vertex, whatever the level.
//! M1's one-ring normals (the second pass) equal their CPU mirror within 1e-5.
//! Validation (synchronization included) is on: the pass's barrier to the draws is checked.

mod common;

use common::{model, with_gpu};
use glam::{DVec3, Vec3};
use meshrefine::render::loop_gpu::LoopPass;
use meshrefine::subdiv::LoopData;
use meshrefine::subdiv::{loop_step, Boundary, Topology};

#[test]
fn gpu_loop_step_matches_the_cpu() {
    with_gpu(16, 16, |h| {
        for file in ["spot_control_tri.obj", "fan24_open.obj"] {
            let mesh = model(file);
            let topo = Topology::of_mesh(&mesh).unwrap();
            let r = mesh.bounding_radius();
            let data =
                LoopData::new(&mesh, Boundary::EdgeOnly, Default::default(), |_| {}).unwrap();
            let mut pass = LoopPass::new(&h.ctx, &h.pool, &data, &mesh.positions).unwrap();
            assert_eq!(pass.upload_bytes(), mesh.positions.len() as u64 * 16);
            for frame in 0..2 {
                // The second frame moves every vertex (an animated coarse mesh).
                let m0: Vec<Vec3> = mesh
                    .positions
                    .iter()
                    .map(|p| *p + Vec3::new(0.1, -0.2, 0.05) * (frame as f32 * p.x))
                    .collect();
                pass.upload_m0(&m0);
                if frame == 1 {
                    // Rows of 5 workgroups: the second dispatch dimension, which only meshes of
                    // millions of M1 vertices need on a device, indexes M1 as the first does.
                    pass.narrow_grid(5);
                }
                h.pool
                    .submit_and_wait(|cmd| {
                        pass.cmd_apply(cmd);
                        cmd.barrier_to_host();
                    })
                    .unwrap();
                let got: Vec<[f32; 4]> = pass.m1.read_pod();
                // The normals pass against its mirror, on the GPU's own M1 (unit normals, f32
                // sums of up to 2 x valence cross products).
                let m1: Vec<Vec3> = got.iter().map(|g| Vec3::new(g[0], g[1], g[2])).collect();
                let normals: Vec<[f32; 4]> = pass.n1.read_pod();
                for (i, (g, w)) in normals.iter().zip(data.m1_normals(&m1)).enumerate() {
                    let d = (Vec3::new(g[0], g[1], g[2]) - w).abs().max_element();
                    assert!(
                        d <= 1e-5,
                        "{file} frame {frame}: M1 normal {i} {g:?} vs {w}"
                    );
                }
                let want = loop_step(
                    &topo,
                    &m0.iter().map(|p| p.as_dvec3()).collect::<Vec<DVec3>>(),
                    Boundary::EdgeOnly,
                );
                assert_eq!(got.len(), want.positions.len());
                let tol = 4e-7 * r as f64;
                for (i, (g, w)) in got.iter().zip(&want.positions).enumerate() {
                    let d = (DVec3::new(g[0] as f64, g[1] as f64, g[2] as f64) - *w)
                        .abs()
                        .max_element();
                    assert!(
                        d <= tol,
                        "{file} frame {frame}: M1 vertex {i} {g:?} vs {w} ({d:e} > {tol:e})"
                    );
                }
            }
        }
    });
}
