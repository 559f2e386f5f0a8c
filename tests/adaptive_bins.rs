//! The adaptive pattern driver's bins (glsl/pattern/bins.comp), read back after a frame: each
//! chunk's bin of a level holds exactly the elements drawn at that level, in element order, and
//! its draw's instance count is their number; every element's own command draws its level. The
//! order is what makes the frame the same every time: where a surface folds onto itself, drawn
//! triangles tie in depth and the one drawn last wins, so bins filled in the order the GPU
//! happened to run them (atomics, on several threads) changed a few pixels from run to run.
//!
//! Levels: random per element (culled among them), uniform on its edges; Spot's 5856 elements
//! make many blocks of the pass, in one chunk and in chunks of 1000 (not a multiple of the
//! blocks' 64), at powers of two (geomorphing) and at integer levels.

mod common;

use common::{model, with_gpu};
use meshrefine::gpu::{vk, Buffer, BufferDesc};
use meshrefine::lod::levels::{drawn_level, ElementLevels};
use meshrefine::pattern::PatternSet;
use meshrefine::render::{Camera, Capture, DrawConfig, Driver, Scene, Submit};
use meshrefine::surface::{Displace, Surface};

/// `buffer` (a GPU-only one) copied back to the host.
fn read_back(h: &meshrefine::render::Headless, buffer: &Buffer) -> Vec<u32> {
    let usage = vk::BufferUsageFlags::TRANSFER_DST;
    let host = Buffer::new(
        &h.ctx,
        BufferDesc::new_readback(buffer.size(), usage),
        "bins read back",
    )
    .unwrap();
    (h.pool)
        .submit_and_wait(|cmd| {
            cmd.copy_buffer(buffer, &host, buffer.size());
            cmd.barrier_to_host();
        })
        .unwrap();
    host.read_pod()
}

#[test]
fn adaptive_bins_hold_their_elements_in_order() {
    const MAX: u32 = 32;
    with_gpu(64, 64, |h| {
        for chunk in [None, Some(1000)] {
            let mut scene = Scene::with_chunks(
                &h.ctx,
                &h.pool,
                &h.renderer,
                model("spot_tri.obj"),
                PatternSet::from_levels(&[MAX]),
                chunk,
            )
            .unwrap();
            let (c, r) = scene.bounding_sphere();
            let camera = Camera::framing(c, r);
            for geomorph in [true, false] {
                let mut cfg = DrawConfig::new(Driver::Pattern(Submit::Instanced), MAX)
                    .with_surface(Surface::Pn, Displace::None);
                cfg.geomorph = geomorph;
                let dyadic = cfg.dyadic_levels();
                h.prepared_elements(&mut scene, &cfg, Capture::None)
                    .unwrap();
                let n = scene.gpu.element_count;
                // Deterministic "random" levels, a tenth culled.
                let mut s = 0x9e37_79b9_u64 + geomorph as u64;
                let levels: Vec<ElementLevels> = (0..n)
                    .map(|_| {
                        s = s
                            .wrapping_mul(6364136223846793005)
                            .wrapping_add(1442695040888963407);
                        let x = (s >> 33) as f32 / (1u64 << 31) as f32;
                        if x < 0.1 {
                            ElementLevels::CULLED
                        } else {
                            ElementLevels::uniform(1.0 + (x - 0.1) / 0.9 * (MAX - 1) as f32)
                        }
                    })
                    .collect();
                scene.gpu.upload_levels(&levels);
                h.adaptive = true;
                h.draw(&mut scene, &cfg, &camera).unwrap();
                h.adaptive = false;
                let a = scene.gpu.adaptive.as_ref().expect("adaptive patterns");
                let (commands, lists) = (read_back(h, &a.commands), read_back(h, &a.lists));
                let what = format!("chunk {chunk:?}, {}", cfg.label());
                let per_chunk = scene.gpu.chunk.min(n);
                let bin = |level: u32| {
                    if dyadic {
                        level.trailing_zeros()
                    } else {
                        level - 1
                    }
                };
                let drawn: Vec<u32> = levels
                    .iter()
                    .map(|l| drawn_level(l.inner, dyadic, MAX))
                    .collect();
                for (e, &d) in drawn.iter().enumerate() {
                    assert_eq!(commands[5 * e], 3 * d * d, "{what}: element {e}'s indices");
                }
                for base in (0..n).step_by(per_chunk as usize) {
                    let end = (base + per_chunk).min(n);
                    for l in 0..a.levels() {
                        let want: Vec<u32> = (base..end)
                            .filter(|&e| drawn[e as usize] != 0 && bin(drawn[e as usize]) == l)
                            .collect();
                        let word = (a.bin_command(base, l) / 4) as usize;
                        assert_eq!(
                            commands[word + 1] as usize,
                            want.len(),
                            "{what}: chunk at {base}, bin {l}'s instances"
                        );
                        let from = (a.bin_list(base, l) / 4) as usize;
                        assert_eq!(
                            &lists[from..from + want.len()],
                            &want[..],
                            "{what}: chunk at {base}, bin {l}'s elements"
                        );
                    }
                }
                // Some culled, most drawn, at several levels.
                let visible = drawn.iter().filter(|&&d| d != 0).count();
                assert!(visible < n as usize && visible > n as usize / 2, "{what}");
            }
        }
    });
}
