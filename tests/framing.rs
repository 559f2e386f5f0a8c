//! The default camera (`Scene::framing_camera`) shows the whole refined surface, displacement
//! included, fills the image and centres it: for bundled models and surfaces, a headless render
//! at that camera has no covered pixel on the image's border, covers more than 15% of it, and
//! leaves margins left and right, and top and bottom, within two pixels of each other, in wide
//! and tall images.

mod common;

use common::{model, output_dir, with_gpu};
use meshrefine::gpu::Readback;
use meshrefine::render::{covered_pixels_on, DrawConfig, Driver, Headless};
use meshrefine::surface::{Displace, Surface};

/// The least fraction of the image a framed mesh covers.
const MIN_COVERED: f64 = 0.15;

/// Covered pixels on the image's border, the fraction covered, and the uncovered margins
/// (left, right, top, bottom) in pixels.
fn coverage(h: &Headless, image: &Readback) -> (usize, f64, [usize; 4]) {
    let (w, ht) = (image.width as usize, image.height as usize);
    let bg = meshrefine::render::background_srgb8(h.background);
    let covered = |x: usize, y: usize| {
        let px = &image.rgba[(y * w + x) * 4..][..4];
        px.iter().zip(bg).any(|(&p, c)| p.abs_diff(c) > 1)
    };
    let border = (0..w)
        .flat_map(|x| [(x, 0), (x, ht - 1)])
        .chain((0..ht).flat_map(|y| [(0, y), (w - 1, y)]))
        .filter(|&(x, y)| covered(x, y))
        .count();
    let all = covered_pixels_on(image, h.background);
    let (mut lo, mut hi) = ([w, ht], [0, 0]);
    for y in 0..ht {
        for x in (0..w).filter(|&x| covered(x, y)) {
            (lo, hi) = ([lo[0].min(x), lo[1].min(y)], [hi[0].max(x), hi[1].max(y)]);
        }
    }
    let margins = [lo[0], w - 1 - hi[0], lo[1], ht - 1 - hi[1]];
    (border, all as f64 / (w * ht) as f64, margins)
}

/// Renders each model with each surface (and displacement) at the framing camera and checks
/// the border and the covered fraction.
fn check_framing(h: &mut Headless, aspect: f32, cases: &[(&str, Surface, Displace)], tag: &str) {
    let level = 4;
    for &(name, surface, displace) in cases {
        let mesh = model(name).for_viewing();
        let mut scene = h.scene(mesh, level).unwrap();
        let mut cfg = DrawConfig::new(Driver::default(), level).with_surface(surface, displace);
        if displace == Displace::Heightmap {
            // Far beyond the mesh's size: the framing follows the displaced surface.
            cfg.params.amplitude = 0.5;
            cfg.params.bias = 3.0;
        }
        h.prepared_elements(&mut scene, &cfg, meshrefine::render::Capture::None)
            .unwrap();
        let camera = scene.framing_camera(&cfg, aspect);
        let image = h.render(&mut scene, &cfg, &camera).unwrap();
        let (border, fraction, [left, right, top, bottom]) = coverage(h, &image);
        let what = format!("{name} {} {} ({tag})", surface.name(), displace.name());
        if border > 0 || fraction <= MIN_COVERED {
            let file = output_dir().join(format!(
                "framing-{}-{}-{}-{tag}.png",
                name.trim_end_matches(".obj"),
                surface.name(),
                displace.name()
            ));
            image.save_png(&file).unwrap();
        }
        assert_eq!(border, 0, "{what}: {border} covered pixels on the border");
        // Centred: the margins left and right, and top and bottom, within two pixels (the
        // camera is fitted to points of the surface, not its drawn outline).
        assert!(
            left.abs_diff(right) <= 2 && top.abs_diff(bottom) <= 2,
            "{what}: margins {left} {right} {top} {bottom}"
        );
        assert!(
            fraction > MIN_COVERED,
            "{what}: covers {:.1}% of the image",
            fraction * 100.0
        );
    }
}

#[test]
fn the_default_camera_frames_every_surface_of_the_bundled_models() {
    let models = [
        "cube_tri.obj",
        "tetrahedron.obj",
        "grid_open_8x8.obj",
        "spot_control_tri.obj",
    ];
    let mut cases = Vec::new();
    for name in models {
        for surface in [Surface::Flat, Surface::Pn, Surface::Loop] {
            cases.push((name, surface, Displace::None));
        }
    }
    cases.push(("grid_uv_8x8.obj", Surface::Flat, Displace::Heightmap));
    cases.push(("spot_control_tri.obj", Surface::Pn, Displace::Sine));
    with_gpu(128, 72, |h| check_framing(h, 128.0 / 72.0, &cases, "wide"));
    let tall = [
        ("spot_control_tri.obj", Surface::Loop, Displace::None),
        ("cube_tri.obj", Surface::Pn, Displace::None),
        ("grid_open_8x8.obj", Surface::Flat, Displace::None),
    ];
    with_gpu(72, 128, |h| check_framing(h, 72.0 / 128.0, &tall, "tall"));
}
