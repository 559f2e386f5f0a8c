//! Images from every driver and submission mode agree.
//!
//! Metric, per pair of RGBA8 images of the same size: the number of pixels whose largest channel
//! difference exceeds 1/255, and the largest channel difference.
//! - `pattern` push / ubo / instanced: identical (same shader, same data; only the submission differs).
//! - `static` vs `pattern`: identical. Positions are bit-identical (tests/gpu_mirror.rs); only the
//!   normal's last bit may differ (CPU vs GPU normalize), which must not move any pixel by more
//!   than 1/255.
//! - `tess` vs `pattern`: the tessellator triangulates differently, so rasterization differs
//!   along refined edges by a pixel at most: at most 0.5% of pixels may differ by more than 1/255
//!   (3% with sine displacement, which level 8 under-samples, so other samples move it more;
//!   noise is not compared with tess).
//!
//! On failure the images and a diff are written to target/test-output/.

mod common;

use common::{output_dir, with_gpu};
use meshrefine::gpu::{sample_count, vk, Readback};
use meshrefine::mesh::default_mesh;
use meshrefine::render::{Camera, DrawConfig, Driver, Headless, Submit, View};
use meshrefine::surface::{Displace, NormalField, Surface};

struct Diff {
    over_one: usize,
    max: u8,
}

fn diff(a: &Readback, b: &Readback) -> Diff {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let mut d = Diff {
        over_one: 0,
        max: 0,
    };
    for (pa, pb) in a.rgba.chunks_exact(4).zip(b.rgba.chunks_exact(4)) {
        let m = (0..3).map(|c| pa[c].abs_diff(pb[c])).max().unwrap();
        d.max = d.max.max(m);
        if m > 1 {
            d.over_one += 1;
        }
    }
    d
}

fn save_failure(name: &str, a: &Readback, b: &Readback) {
    let dir = output_dir();
    a.save_png(&dir.join(format!("{name}-expected.png")))
        .unwrap();
    b.save_png(&dir.join(format!("{name}-actual.png"))).unwrap();
    let rgba = a
        .rgba
        .chunks_exact(4)
        .zip(b.rgba.chunks_exact(4))
        .flat_map(|(x, y)| {
            let m = (0..3)
                .map(|c| x[c].abs_diff(y[c]))
                .max()
                .unwrap()
                .saturating_mul(16);
            [m, m, m, 255]
        })
        .collect();
    Readback {
        width: a.width,
        height: a.height,
        rgba,
    }
    .save_png(&dir.join(format!("{name}-diff.png")))
    .unwrap();
}

fn check(name: &str, a: &Readback, b: &Readback, max_over_one: usize) {
    let d = diff(a, b);
    eprintln!(
        "{name}: {} pixels differ by more than 1/255, largest difference {}",
        d.over_one, d.max
    );
    if d.over_one > max_over_one {
        save_failure(name, a, b);
        panic!("{name}: {} pixels differ by more than 1/255 (allowed {max_over_one}); images in target/test-output", d.over_one);
    }
}

#[test]
fn drivers_render_the_same_image() {
    let (w, h_px) = (320u32, 240u32);
    with_gpu(w, h_px, |h| {
        let level = 8;
        let mut scene = h.scene(default_mesh(), level).unwrap();
        let (c, r) = scene.bounding_sphere();
        let camera = Camera::framing(c, r);
        // Every surface (loop included), and pn displaced; pn's normal (field or displaced) is evaluated per
        // fragment in every driver (static through its vertices' element and sample attributes).
        let combos = Surface::ALL.iter().map(|&s| (s, Displace::None)).chain([
            (Surface::Pn, Displace::Sine),
            (Surface::Pn, Displace::Noise),
        ]);
        for (surface, displace) in combos {
            let mut render = |driver| {
                let cfg = DrawConfig::new(driver, level).with_surface(surface, displace);
                h.render(&mut scene, &cfg, &camera).unwrap()
            };
            let instanced = render(Driver::Pattern(Submit::Instanced));
            let push = render(Driver::Pattern(Submit::Push));
            let ubo = render(Driver::Pattern(Submit::Ubo));
            let stat = render(Driver::Static);
            let tess = render(Driver::Tess);
            // The mesh covers a good part of the image (not an empty or black frame).
            let background = instanced.rgba[..4].to_vec();
            let covered = instanced
                .rgba
                .chunks_exact(4)
                .filter(|p| *p != &background[..])
                .count();
            assert!(
                covered > (w * h_px / 10) as usize,
                "only {covered} pixels show the mesh"
            );
            let name = format!("{}+{}", surface.name(), displace.name());
            assert_eq!(
                push.rgba, instanced.rgba,
                "{name}: push and instanced differ"
            );
            assert_eq!(ubo.rgba, instanced.rgba, "{name}: ubo and instanced differ");
            check(&format!("{name}-static-vs-pattern"), &instanced, &stat, 0);
            // The tessellator samples the surface elsewhere inside each coarse triangle; with
            // displacement at level 8 (under-sampled) that moves the surface more: 3 % of pixels
            // for sine. Noise at its default frequency is too under-sampled there for a
            // comparison to mean anything, so only the pattern and static drivers are compared.
            let tess_allowed = match displace {
                Displace::None => Some(w * h_px / 200),
                Displace::Sine => Some(w * h_px * 3 / 100),
                _ => None,
            };
            if let Some(allowed) = tess_allowed {
                check(
                    &format!("{name}-tess-vs-pattern"),
                    &instanced,
                    &tess,
                    allowed as usize,
                );
            }
        }
    });
}

/// `pn`'s normal field is evaluated per fragment with the chosen field (the NORMAL_FIELD
/// specialization constant reaches the fragment stage of every driver): for each field,
/// `static` equals `pattern` and `tess` is within the tolerance above, and on the default mesh
/// (a control cage, where the fields differ most) each pair of fields shades visibly apart.
/// The per-vertex values of each field are compared with the CPU mirror in tests/gpu_mirror.rs.
#[test]
fn every_normal_field_renders_alike_on_every_driver() {
    let (w, h_px) = (320u32, 240u32);
    with_gpu(w, h_px, |h| {
        let level = 8;
        let mut scene = h.scene(default_mesh(), level).unwrap();
        let (c, r) = scene.bounding_sphere();
        let camera = Camera::framing(c, r);
        let mut images = Vec::new();
        for field in NormalField::ALL {
            let mut render = |driver| {
                let mut cfg =
                    DrawConfig::new(driver, level).with_surface(Surface::Pn, Displace::None);
                cfg.build.normal_field = field;
                h.render(&mut scene, &cfg, &camera).unwrap()
            };
            let instanced = render(Driver::Pattern(Submit::Instanced));
            let stat = render(Driver::Static);
            let tess = render(Driver::Tess);
            let name = format!("pn-{}", field.name());
            check(&format!("{name}-static-vs-pattern"), &instanced, &stat, 0);
            check(
                &format!("{name}-tess-vs-pattern"),
                &instanced,
                &tess,
                (w * h_px / 200) as usize,
            );
            images.push((field, instanced));
        }
        for (i, (a, ia)) in images.iter().enumerate() {
            for (b, ib) in &images[i + 1..] {
                let d = diff(ia, ib);
                assert!(
                    d.over_one > 1000 && d.max > 16,
                    "{} and {} shade alike: {} pixels differ, by at most {}",
                    a.name(),
                    b.name(),
                    d.over_one,
                    d.max
                );
            }
        }
    });
}

/// From `LOOP_FRAGMENT_NORMALS` up, loop's subdivision-shading normal is summed per fragment
/// instead of per vertex (pattern and tess, no displacement): every submission mode gives the
/// same image, tess nearly, and it shades like the per-vertex normals one level below (the
/// triangles there are about a pixel, so interpolating their normals changes little).
#[test]
fn loop_normals_per_fragment_shade_as_per_vertex() {
    let (w, h_px) = (320u32, 240u32);
    with_gpu(w, h_px, |h| {
        let high = meshrefine::render::LOOP_FRAGMENT_NORMALS;
        let mut scene = meshrefine::render::Scene::with_patterns(
            &h.ctx,
            &h.pool,
            &h.renderer,
            default_mesh(),
            meshrefine::pattern::PatternSet::from_levels(&[high - 1, high]),
        )
        .unwrap();
        let (c, r) = scene.bounding_sphere();
        let camera = Camera::framing(c, r);
        let mut render = |driver, level| {
            let cfg = DrawConfig::new(driver, level).with_surface(Surface::Loop, Displace::None);
            assert_eq!(cfg.fragment_normal_field(), level >= high, "{level}");
            h.render(&mut scene, &cfg, &camera).unwrap()
        };
        let instanced = render(Driver::Pattern(Submit::Instanced), high);
        let push = render(Driver::Pattern(Submit::Push), high);
        let ubo = render(Driver::Pattern(Submit::Ubo), high);
        let tess = render(Driver::Tess, high);
        let per_vertex = render(Driver::Pattern(Submit::Instanced), high - 1);
        assert_eq!(push.rgba, instanced.rgba, "push and instanced differ");
        assert_eq!(ubo.rgba, instanced.rgba, "ubo and instanced differ");
        check(
            "loop-fragment-normals-tess-vs-pattern",
            &instanced,
            &tess,
            (w * h_px / 200) as usize,
        );
        check(
            "loop-fragment-normals-vs-vertex-normals",
            &instanced,
            &per_vertex,
            (w * h_px / 500) as usize,
        );
    });
}

/// Silhouette pixels of `image`: not the background, with a background pixel beside them.
/// Returns how many of them show an intermediate colour, one that no interior pixel has (within
/// 1/255): a blend of the mesh and the background.
fn intermediate_silhouette_pixels(image: &Readback, background: [u8; 4]) -> (usize, usize) {
    let (w, h) = (image.width as i64, image.height as i64);
    let px = |x: i64, y: i64| -> [u8; 4] {
        if x < 0 || y < 0 || x >= w || y >= h {
            return background;
        }
        let i = 4 * (y * w + x) as usize;
        image.rgba[i..i + 4].try_into().unwrap()
    };
    let near = |a: [u8; 4], b: [u8; 4]| (0..3).all(|c| a[c].abs_diff(b[c]) <= 1);
    let neighbours = |x: i64, y: i64| [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)];
    // Interior colours: pixels whose eight neighbours all have their colour.
    let mut interior: Vec<[u8; 4]> = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let c = px(x, y);
            let inside = (-1..=1).all(|dy| (-1..=1).all(|dx| px(x + dx, y + dy) == c));
            if !near(c, background) && inside && !interior.iter().any(|&i| near(i, c)) {
                interior.push(c);
            }
        }
    }
    let (mut silhouette, mut blended) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            let c = px(x, y);
            if near(c, background)
                || !neighbours(x, y)
                    .iter()
                    .any(|&(a, b)| near(px(a, b), background))
            {
                continue;
            }
            silhouette += 1;
            if !interior.iter().any(|&i| near(i, c)) {
                blended += 1;
            }
        }
    }
    (silhouette, blended)
}

/// Multisampling smooths silhouettes: a cube with face normals, shown as its normals (one
/// colour per face), has no colour but its faces' and the background's on its silhouette with
/// one sample per pixel, and blends of the two on most of it with the default sample count
/// (4 on lavapipe), resolved into the image read back. The wireframe pass draws into the
/// multisampled target too.
#[test]
fn msaa_blends_silhouettes() {
    let (w, h_px) = (160u32, 120u32);
    with_gpu(w, h_px, |h| {
        let samples = sample_count(&h.ctx, None).unwrap();
        assert_ne!(
            samples,
            vk::SampleCountFlags::TYPE_1,
            "no multisampling on this device"
        );
        let mut msaa = Headless::multisampled(h.ctx.clone(), w, h_px, samples).unwrap();
        let mesh = common::model("cube_face_normals.obj");
        let cfg = DrawConfig::new(Driver::Pattern(Submit::Instanced), 1);
        let background = meshrefine::render::clear_color_srgb8();
        let mut images = Vec::new();
        for target in [&mut *h, &mut msaa] {
            target.view = View::Normals;
            let mut scene = target.scene(mesh.clone(), 1).unwrap();
            let (c, r) = scene.bounding_sphere();
            let camera = Camera::framing(c, r);
            images.push(target.render(&mut scene, &cfg, &camera).unwrap());
            target.wireframe = true;
            let wire = target.render(&mut scene, &cfg, &camera).unwrap();
            target.wireframe = false;
            target.view = View::Shaded;
            assert!(
                diff(&images[images.len() - 1], &wire).over_one > 100,
                "wireframe"
            );
        }
        let (one, many) = (
            intermediate_silhouette_pixels(&images[0], background),
            intermediate_silhouette_pixels(&images[1], background),
        );
        eprintln!("silhouette pixels, intermediate: 1x {one:?}, {samples:?} {many:?}");
        assert!(one.0 > 100, "1x: only {} silhouette pixels", one.0);
        assert_eq!(one.1, 0, "1x: intermediate colours on the silhouette");
        assert!(
            many.1 * 2 > many.0,
            "{samples:?}: only {} of {} silhouette pixels are blended",
            many.1,
            many.0
        );
    });
}

/// Multisampled, a fragment is shaded where its triangle covers the pixel (centroid), not at a
/// pixel centre outside it: loop's per-fragment normal near a vertex of valence 200 (a bicone's
/// poles, whose sliver triangles cover some of a pixel's samples and not its centre) would be
/// extrapolated from a sample outside its element and speckle the surface. Inside the surface
/// (every pixel within two of it drawn) the multisampled image is the single-sampled one within
/// 10/255 but for a handful of pixels (about 160 speckles without centroid sampling, none with).
#[test]
fn msaa_shades_inside_sliver_triangles() {
    let (w, h_px) = (320u32, 240u32);
    with_gpu(w, h_px, |h| {
        let samples = sample_count(&h.ctx, None).unwrap();
        let mut msaa = Headless::multisampled(h.ctx.clone(), w, h_px, samples).unwrap();
        let n = 200u32;
        let mut positions = vec![glam::Vec3::Z];
        positions.extend((0..n).map(|i| {
            let a = std::f32::consts::TAU * i as f32 / n as f32;
            glam::Vec3::new(a.cos(), a.sin(), 0.0)
        }));
        positions.push(-glam::Vec3::Z);
        let ring = |i: u32| 1 + i % n;
        let mut tris: Vec<[u32; 3]> = (0..n).map(|i| [0, ring(i), ring(i + 1)]).collect();
        tris.extend((0..n).map(|i| [n + 1, ring(i + 1), ring(i)]));
        let (mesh, _) =
            meshrefine::mesh::Mesh::from_parts("bicone", positions, None, tris).unwrap();
        let level = meshrefine::render::LOOP_FRAGMENT_NORMALS;
        let cfg = DrawConfig::new(Driver::Pattern(Submit::Instanced), level)
            .with_surface(Surface::Loop, Displace::None);
        assert!(cfg.fragment_normal_field());
        let mut images = Vec::new();
        for target in [&mut *h, &mut msaa] {
            let mut scene = target.scene(mesh.clone(), level).unwrap();
            let (c, r) = scene.bounding_sphere();
            let eye = c + glam::Vec3::new(0.3, 0.2, 1.0).normalize() * (1.2 * r);
            let camera = Camera::looking(eye, c, 45f32.to_radians(), r).unwrap();
            images.push(target.render(&mut scene, &cfg, &camera).unwrap());
        }
        let background = meshrefine::render::clear_color_srgb8();
        let (one, many) = (&images[0], &images[1]);
        let px = |img: &Readback, x: u32, y: u32| {
            let i = 4 * (y * w + x) as usize;
            [
                img.rgba[i],
                img.rgba[i + 1],
                img.rgba[i + 2],
                img.rgba[i + 3],
            ]
        };
        let (mut inside, mut speckles) = (0, 0);
        for y in 2..h_px - 2 {
            for x in 2..w - 2 {
                let drawn =
                    (y - 2..=y + 2).all(|j| (x - 2..=x + 2).all(|i| px(one, i, j) != background));
                if !drawn {
                    continue;
                }
                inside += 1;
                let (a, b) = (px(one, x, y), px(many, x, y));
                let d = (0..3).map(|k| a[k].abs_diff(b[k])).max().unwrap();
                speckles += usize::from(d > 10);
            }
        }
        eprintln!("{inside} pixels inside the surface, {speckles} shaded apart");
        assert!(inside > 20_000, "only {inside} pixels inside the surface");
        assert!(speckles <= 5, "{speckles} speckles inside the surface");
    });
}

#[test]
fn wireframe_pass_draws_edges() {
    with_gpu(320, 240, |h| {
        let mut scene = h.scene(default_mesh(), 4).unwrap();
        let (c, r) = scene.bounding_sphere();
        let camera = Camera::framing(c, r);
        for driver in Driver::ALL {
            let cfg = DrawConfig::new(driver, 4);
            h.wireframe = false;
            let plain = h.render(&mut scene, &cfg, &camera).unwrap();
            h.wireframe = true;
            let wire = h.render(&mut scene, &cfg, &camera).unwrap();
            let d = diff(&plain, &wire);
            // Lines over a 320x240 view of 372 triangles x 16: thousands of pixels darken.
            assert!(
                d.over_one > 2000,
                "{}: wireframe changed only {} pixels",
                cfg.label(),
                d.over_one
            );
        }
        h.wireframe = false;
    });
}

/// Mean (r, g, b) of the pixels that differ from the background.
fn mean_mesh_color(img: &Readback) -> [f64; 3] {
    let bg = &img.rgba[..3];
    let (mut sum, mut n) = ([0.0f64; 3], 0usize);
    for px in img.rgba.chunks_exact(4) {
        if px[..3] != *bg {
            for c in 0..3 {
                sum[c] += px[c] as f64;
            }
            n += 1;
        }
    }
    assert!(n > 1000, "only {n} mesh pixels");
    sum.map(|s| s / n as f64)
}

/// The levels view colours each element by the level it is drawn at: bluer at level 1, redder at
/// level 64, on every driver (uniform levels here; adaptive frames read each element's own),
/// while the shaded view keeps the surface colour.
#[test]
fn levels_view_colours_by_level() {
    use meshrefine::render::View;
    with_gpu(320, 240, |h| {
        let mut scene = h.scene(default_mesh(), 64).unwrap();
        let (c, r) = scene.bounding_sphere();
        let camera = Camera::framing(c, r);
        for driver in [
            Driver::Static,
            Driver::Pattern(Submit::Instanced),
            Driver::Tess,
        ] {
            let at = |h: &mut meshrefine::render::Headless,
                      scene: &mut meshrefine::render::Scene,
                      level: u32,
                      view: View| {
                h.view = view;
                let img = h
                    .render(scene, &DrawConfig::new(driver, level), &camera)
                    .unwrap();
                mean_mesh_color(&img)
            };
            let low = at(h, &mut scene, 1, View::Levels);
            let high = at(h, &mut scene, 64, View::Levels);
            let shaded = at(h, &mut scene, 1, View::Shaded);
            let name = driver.name();
            if driver != Driver::Static {
                // Drawn adaptively, each element shows its own level: all at 1 here, though
                // the draw's largest level is 64.
                let n = scene.elements(Surface::Flat).element_count as usize;
                let ones = vec![meshrefine::lod::levels::ElementLevels::uniform(1.0); n];
                scene.elements_mut(Surface::Flat).upload_levels(&ones);
                h.adaptive = true;
                let own = at(h, &mut scene, 64, View::Levels);
                h.adaptive = false;
                assert!(
                    own[2] > 1.5 * own[0],
                    "{name}: adaptive level 1 not blue: {own:?}"
                );
            }
            assert!(low[2] > 1.5 * low[0], "{name}: level 1 not blue: {low:?}");
            assert!(
                high[0] > 1.5 * high[2],
                "{name}: level 64 not red: {high:?}"
            );
            assert!(
                shaded[0] > shaded[2],
                "{name}: the shaded view lost the surface colour: {shaded:?}"
            );
        }
        h.view = View::Shaded;
    });
}

/// What the fragment stage shows is a specialization constant: on one target, each view is
/// drawn with pipelines of its own, created once (returning to a view compiles nothing and
/// draws the same image), and every view draws an image of its own.
#[test]
fn views_have_pipelines_of_their_own_created_once() {
    with_gpu(320, 240, |h| {
        let mut scene = h.scene(default_mesh(), 8).unwrap();
        let (c, r) = scene.bounding_sphere();
        let camera = Camera::framing(c, r);
        let cfg = DrawConfig::new(Driver::Pattern(Submit::Instanced), 8)
            .with_surface(Surface::Pn, Displace::None);
        let views = [
            View::Shaded,
            View::Plain,
            View::Normals,
            View::Levels,
            View::Shaded,
            View::Plain,
        ];
        let (mut images, mut pipelines) = (Vec::new(), Vec::new());
        for view in views {
            h.view = view;
            images.push(h.render(&mut scene, &cfg, &camera).unwrap());
            pipelines.push(h.renderer.pipeline_count());
        }
        h.view = View::Shaded;
        eprintln!("pipelines after each view: {pipelines:?}");
        for k in 1..4 {
            assert!(
                pipelines[k] > pipelines[k - 1],
                "{:?}: {pipelines:?}",
                views[k]
            );
            for j in 0..k {
                assert!(
                    diff(&images[j], &images[k]).over_one > 1000,
                    "{:?} draws {:?}'s image",
                    views[k],
                    views[j]
                );
            }
        }
        assert_eq!(
            pipelines[4], pipelines[3],
            "shaded again compiled: {pipelines:?}"
        );
        assert_eq!(
            pipelines[5], pipelines[3],
            "plain again compiled: {pipelines:?}"
        );
        assert!(images[4].rgba == images[0].rgba, "shaded again differs");
        assert!(images[5].rgba == images[1].rgba, "plain again differs");
    });
}

/// Drawn adaptively, the static driver's levels view colours each element by its own level, as
/// the pattern driver does at the same integer levels (`--geomorph off`): the CPU's levels reach
/// the fragment stage, with or without the vertices' element attributes (`pn` evaluates its
/// normal field per fragment, `phong` does not). Spot at 1 px: the images differ only where the
/// two evaluations round differently; a static image coloured by the largest level differs on
/// most of the mesh.
#[test]
fn levels_view_shows_the_static_drivers_own_levels() {
    use meshrefine::render::LevelView;
    let (w, h_px) = (320u32, 180u32);
    with_gpu(w, h_px, |h| {
        let mut scene = h.scene(default_mesh(), 64).unwrap();
        let (c, r) = scene.bounding_sphere();
        let camera = Camera::framing(c, r);
        h.view = View::Levels;
        h.adaptive = true;
        for surface in [Surface::Phong, Surface::Pn] {
            let mut render = |driver| {
                let mut cfg = DrawConfig::new(driver, 64).with_surface(surface, Displace::None);
                cfg.geomorph = false;
                let view = LevelView {
                    camera,
                    width: w,
                    height: h_px,
                    pixel_error: 1.0,
                    cull: true,
                };
                let chosen = scene.set_levels(&cfg, &view).unwrap();
                let levels = chosen.report().histogram.len();
                assert!(levels > 3, "{surface:?}: only {levels} distinct levels");
                h.render(&mut scene, &cfg, &camera).unwrap()
            };
            let pattern = render(Driver::Pattern(Submit::Instanced));
            let stat = render(Driver::Static);
            let name = format!("levels-view-static-{}", surface.name());
            check(&name, &pattern, &stat, (w * h_px / 400) as usize);
        }
        h.view = View::Shaded;
        h.adaptive = false;
    });
}

/// The `plain` view writes one colour wherever the surface is and nothing else: every pixel is
/// the background or that one colour (one sample per pixel), the same for every driver and
/// surface, and it covers exactly the pixels the shaded image covers (same triangles, same depth
/// test; only the fragment stage's work is gone).
#[test]
fn plain_view_is_one_colour_over_the_shaded_coverage() {
    with_gpu(320, 240, |h| {
        let background = meshrefine::render::clear_color_srgb8();
        let mut scene = h.scene(default_mesh(), 8).unwrap();
        let (c, r) = scene.bounding_sphere();
        let camera = Camera::framing(c, r);
        let mut colour = None;
        for driver in [Driver::Static, Driver::Pattern(Submit::Push), Driver::Tess] {
            for surface in [Surface::Flat, Surface::Pn] {
                let cfg = DrawConfig::new(driver, 8).with_surface(surface, Displace::None);
                let name = format!("{} {}", driver.name(), surface.name());
                h.view = View::Shaded;
                let shaded = h.render(&mut scene, &cfg, &camera).unwrap();
                h.view = View::Plain;
                let plain = h.render(&mut scene, &cfg, &camera).unwrap();
                h.view = View::Shaded;
                let mut covered = 0;
                for (p, q) in plain.rgba.chunks_exact(4).zip(shaded.rgba.chunks_exact(4)) {
                    let (on_p, on_q) = (p != background, q != background);
                    assert_eq!(on_p, on_q, "{name}: the plain view's coverage differs");
                    if on_p {
                        covered += 1;
                        let c = *colour.get_or_insert([p[0], p[1], p[2], p[3]]);
                        assert_eq!(p, c, "{name}: a second colour in the plain view");
                    }
                }
                assert!(covered > 5000, "{name}: only {covered} pixels covered");
            }
        }
    });
}

/// The cage overlay draws the coarse mesh's edges in its light cyan over the surface, for every
/// driver (Loop's limit surface too, whose cage is its control mesh), alone or with the refined
/// wireframe.
#[test]
fn cage_overlay_draws_the_coarse_edges() {
    with_gpu(320, 240, |h| {
        let mut scene = h.scene(default_mesh(), 4).unwrap();
        let (c, r) = scene.bounding_sphere();
        let camera = Camera::framing(c, r);
        let cyan = |img: &Readback| {
            img.rgba
                .chunks_exact(4)
                // Bluer and greener than red by a margin: neither the surface (red first) nor
                // the dark background is.
                .filter(|p| p[2] as i32 > p[0] as i32 + 40 && p[1] as i32 > p[0] as i32 + 30)
                .count()
        };
        for (driver, surface) in [
            (Driver::Static, Surface::Flat),
            (Driver::Pattern(Submit::Instanced), Surface::Pn),
            (Driver::Tess, Surface::Loop),
        ] {
            let cfg = DrawConfig::new(driver, 4).with_surface(surface, Displace::None);
            h.cage = false;
            let plain = h.render(&mut scene, &cfg, &camera).unwrap();
            h.cage = true;
            let caged = h.render(&mut scene, &cfg, &camera).unwrap();
            h.wireframe = true;
            let both = h.render(&mut scene, &cfg, &camera).unwrap();
            h.wireframe = false;
            let name = cfg.label();
            assert_eq!(cyan(&plain), 0, "{name}: cyan without the cage");
            // Curved surfaces hide part of their cage (pn bulges out of it); flat shows all.
            assert!(cyan(&caged) > 400, "{name}: {} cage pixels", cyan(&caged));
            assert!(cyan(&both) > 400, "{name}: {} cage pixels", cyan(&both));
            assert!(
                diff(&caged, &both).over_one > 1000,
                "{name}: no refined edges"
            );
        }
        h.cage = false;
    });
}

/// Only front faces are taken to be visible (the level pass culls elements facing away, the
/// wireframe the lines of faces turned away) on a closed, undisplaced, non-loop surface seen
/// from outside: Spot as `pn` from the benchmark's close-up, not from inside its head, not
/// with open seams, not as `loop` (its elements' bounds do not hold the coarse mesh) nor
/// displaced by a sine (it may fold).
#[test]
fn only_front_faces_show_on_closed_undisplaced_surfaces_from_outside() {
    with_gpu(64, 64, |h| {
        let mut scene = h.scene(default_mesh(), 16).unwrap();
        let (c, r) = scene.bounding_sphere();
        let outside = glam::Vec3::new(0.35, 0.65, -1.3);
        let cfg = |surface, displace| {
            let mut cfg = DrawConfig::new(Driver::Pattern(Submit::Instanced), 16)
                .with_surface(surface, displace);
            cfg.params = meshrefine::surface::SurfaceParams::for_radius(r);
            cfg
        };
        let pn = cfg(Surface::Pn, Displace::None);
        assert!(scene.front_only(&pn, outside).unwrap());
        // Told from the elements' spheres alone: no bounds were computed.
        assert!(scene.level_bounds().is_none());
        assert!(!scene.front_only(&pn, c).unwrap(), "from inside");
        let mut open = pn;
        open.build.seams = meshrefine::surface::Seams::Open;
        assert!(!scene.front_only(&open, outside).unwrap(), "open seams");
        let looped = cfg(Surface::Loop, Displace::None);
        assert!(!scene.front_only(&looped, outside).unwrap(), "loop");
        let sine = cfg(Surface::Pn, Displace::Sine);
        assert!(sine.params.moves(Displace::Sine));
        assert!(!scene.front_only(&sine, outside).unwrap(), "displaced");
    });
}

/// The wireframe's lines lie on the surface they are drawn over, never on a sheet behind it
/// seen through it. Two causes are excluded: the lines' slope-scaled depth offset, unclamped,
/// pulled lines of steep and zero-area triangles (snapping makes those: adaptive drawing on
/// every driver) of the far side in front of the surface; and within the clamped offset, lines
/// of sheets just behind the surface (snapped slivers folded under their neighbours, the inside
/// of the ears beyond their rims) showed unless the lines of faces turned away are culled where
/// only front faces can be seen. Spot close up (`pn`, 640x360, geomorphing where the driver
/// glides), the normals view: each line pixel's normal (the line's colour, 0.6 of the fill's)
/// against the fill's there; a line of a sheet behind the surface faces away from it. Pixels on
/// silhouettes, where a line's half-pixel width overhangs another surface, may disagree.
/// Measured: with closed seams (front faces only), the benchmark's camera, every driver at 2
/// and 8 px, 35 to 84 of each frame's 22,000 to 70,000 line pixels (676 to 852 on the pattern
/// and tess drivers without the culling); with open seams (every line kept) from the side, 7
/// and 14 on pattern and tess (971 on pattern without the clamp).
#[test]
fn wireframe_lines_stay_on_the_visible_surface() {
    use meshrefine::render::LevelView;
    let (w, h_px) = (640u32, 360u32);
    with_gpu(w, h_px, |h| {
        let mut scene = h.scene(default_mesh(), 64).unwrap();
        let (c, r) = scene.bounding_sphere();
        // The benchmark's close-up (docs/benchmarks.md), in Spot's coordinates.
        let (eye, target) = (
            glam::Vec3::new(0.35, 0.65, -1.3),
            glam::Vec3::new(0.0, 0.5, -0.5),
        );
        let close_up = Camera::looking(eye, target, 45f32.to_radians(), r).unwrap();
        // Another close-up, from the side.
        let side = Camera::looking(
            c + glam::Vec3::new(0.3, 0.25, -1.0).normalize() * (1.3 * r),
            c + glam::Vec3::new(-0.2 * r, 0.0, 0.0),
            50f32.to_radians(),
            r,
        )
        .unwrap();
        let decode = |img: &Readback, i: usize, scale: f32| {
            let lin = |b: u8| {
                let x = b as f32 / 255.0;
                if x <= 0.04045 {
                    x / 12.92
                } else {
                    ((x + 0.055) / 1.055).powf(2.4)
                }
            };
            glam::Vec3::new(lin(img.rgba[i]), lin(img.rgba[i + 1]), lin(img.rgba[i + 2])) / scale
                * 2.0
                - glam::Vec3::ONE
        };
        let background = meshrefine::render::clear_color_srgb8();
        h.view = View::Normals;
        h.adaptive = true;
        let drivers = [
            Driver::Pattern(Submit::Instanced),
            Driver::Tess,
            Driver::Static,
        ];
        // (driver, pixel error, seams, camera, the most line pixels facing away): closed seams
        // show only front faces, and every line of a face turned away is culled; open seams
        // (the same surface: Spot has no hard edges) keep every line, and only the clamped
        // depth offset keeps those of the far side behind the surface.
        let closed = meshrefine::surface::Seams::Closed;
        let open = meshrefine::surface::Seams::Open;
        let cases = (drivers.into_iter())
            .flat_map(|d| {
                [
                    (d, 2.0, closed, close_up, 150),
                    (d, 8.0, closed, close_up, 150),
                ]
            })
            .chain(drivers[..2].iter().map(|&d| (d, 2.0, open, side, 40)));
        for (driver, pixel_error, seams, camera, most) in cases {
            let mut cfg = DrawConfig::new(driver, 64).with_surface(Surface::Pn, Displace::None);
            cfg.params = meshrefine::surface::SurfaceParams::for_radius(r);
            cfg.geomorph = true;
            cfg.build.seams = seams;
            let view = LevelView {
                camera,
                width: w,
                height: h_px,
                pixel_error,
                cull: true,
            };
            scene.set_levels(&cfg, &view).unwrap();
            h.wireframe = false;
            let fill = h.render(&mut scene, &cfg, &camera).unwrap();
            h.wireframe = true;
            let wire = h.render(&mut scene, &cfg, &camera).unwrap();
            let (mut lines, mut through) = (0, 0);
            for p in 0..(w * h_px) as usize {
                let i = 4 * p;
                if fill.rgba[i..i + 4] == background || fill.rgba[i..i + 3] == wire.rgba[i..i + 3] {
                    continue;
                }
                lines += 1;
                let (n_fill, n_line) = (decode(&fill, i, 1.0), decode(&wire, i, 0.6));
                through += usize::from(n_fill.dot(n_line) < 0.0);
            }
            let name = format!("{} at {pixel_error} px, {seams:?} seams", cfg.label());
            eprintln!("{name}: {lines} line pixels, {through} facing away from the fill");
            assert!(lines > 3000, "{name}: only {lines} line pixels");
            assert!(
                through <= most,
                "{name}: {through} line pixels behind the surface"
            );
        }
        h.wireframe = false;
        h.adaptive = false;
        h.view = View::Shaded;
    });
}

/// Near a silhouette a smooth normal field may turn slightly away from the eye while the
/// triangle drawn still faces it: two-sided lighting then keeps the normal (the triangle's side
/// decides), where turning it toward the eye shaded a band along the outline as the surface's
/// back, a sharp step in the middle of smooth shading. Spot as `pn` from its front left, one
/// sample per pixel: steps of more than 20/255 between horizontal neighbours, both at least
/// two pixels from the background. Measured: 235 of 34,949 pairs (the edges where a part of
/// the mesh passes in front of another), 372 with the normal turned by the view direction.
#[test]
fn outlines_are_shaded_as_the_surface_they_border() {
    with_gpu(480, 360, |h| {
        let mut scene = h.scene(default_mesh(), 16).unwrap();
        let (c, r) = scene.bounding_sphere();
        let eye = c + glam::Vec3::new(2.0, 1.0, -1.6) * r / 1.2;
        let camera = Camera::looking(eye, c, 45f32.to_radians(), r).unwrap();
        let cfg = DrawConfig::new(Driver::Pattern(Submit::Instanced), 16)
            .with_surface(Surface::Pn, Displace::None);
        let img = h.render(&mut scene, &cfg, &camera).unwrap();
        let (w, hgt) = (img.width as usize, img.height as usize);
        let px = |x: usize, y: usize| &img.rgba[(y * w + x) * 4..(y * w + x) * 4 + 3];
        let bg = px(0, 0).to_vec();
        let inner = |x: usize, y: usize| {
            (y - 2..=y + 2).all(|j| (x - 2..=x + 2).all(|i| px(i, j) != &bg[..]))
        };
        let luma = |p: &[u8]| (p[0] as i32 + p[1] as i32 + p[2] as i32) / 3;
        let (mut steps, mut pairs) = (0, 0);
        for y in 3..hgt - 3 {
            for x in 3..w - 3 {
                if inner(x, y) && inner(x + 1, y) {
                    pairs += 1;
                    steps += usize::from((luma(px(x, y)) - luma(px(x + 1, y))).abs() > 20);
                }
            }
        }
        assert!(pairs > 20_000, "only {pairs} pairs of mesh pixels");
        assert!(
            steps <= 320,
            "{steps} sharp steps in {pairs} pairs of mesh pixels"
        );
        // The other side: an open surface seen from behind (the 8x8 grid in z = 0, from -z)
        // still has its normals turned toward the eye, lit about as its front is from +z.
        // Measured: a mean channel of 160 from behind, 174 from the front; 89 from behind with
        // no normal ever turned.
        let grid = common::model("grid_open_8x8.obj");
        let mut scene = h.scene(grid, 4).unwrap();
        let (c, r) = scene.bounding_sphere();
        let cfg = DrawConfig::new(Driver::Pattern(Submit::Instanced), 4);
        let mut mean = |eye: glam::Vec3| {
            let camera = Camera::looking(c + eye * r, c, 45f32.to_radians(), r).unwrap();
            let img = h.render(&mut scene, &cfg, &camera).unwrap();
            let [red, green, blue] = mean_mesh_color(&img);
            (red + green + blue) / 3.0
        };
        let front = mean(glam::Vec3::new(0.4, 0.6, 2.5));
        let back = mean(glam::Vec3::new(0.4, 0.6, -2.5));
        assert!(
            back > 0.8 * front,
            "from behind {back:.1}, from the front {front:.1}"
        );
    });
}

/// Pixels of `img` at least two pixels from the background (its top-left pixel's colour) and
/// how many of them are speckles: brighter or darker by more than 24/255 than the mean of their
/// eight neighbours (the outline's blended pixels differ from their neighbours on the mesh, so
/// they are left out).
fn count_speckles(img: &Readback) -> (usize, usize) {
    let (w, hgt) = (img.width as usize, img.height as usize);
    let px = |x: usize, y: usize| &img.rgba[(y * w + x) * 4..(y * w + x) * 4 + 3];
    let bg = px(0, 0).to_vec();
    let luma = |p: &[u8]| (p[0] as i32 + p[1] as i32 + p[2] as i32) / 3;
    let (mut speckles, mut mesh_pixels) = (0, 0);
    for y in 2..hgt - 2 {
        for x in 2..w - 2 {
            let around = || (y - 1..=y + 1).flat_map(|j| (x - 1..=x + 1).map(move |i| (i, j)));
            let near = (y - 2..=y + 2).flat_map(|j| (x - 2..=x + 2).map(move |i| (i, j)));
            if near.into_iter().any(|(i, j)| px(i, j) == &bg[..]) {
                continue;
            }
            mesh_pixels += 1;
            let sum: i32 = around().map(|(i, j)| luma(px(i, j))).sum();
            let mean = (sum - luma(px(x, y))) / 8;
            speckles += usize::from((luma(px(x, y)) - mean).abs() > 24);
        }
    }
    (speckles, mesh_pixels)
}

/// Two-sided lighting does not speckle a closed surface seen nearly edge-on: two tetrahedra
/// apart as `pn` at level 8, seen as `render` frames them at 320x240, where the nearer one turns
/// a face almost edge-on to the eye. The sign of the screen derivatives the fragment stage asks
/// which side of a triangle it sees flips there in a speckled pattern, and turning the normal
/// by it lit single pixels on the dark face where v_position is sampled at the centroid of
/// the covered samples (14 here); on a closed surface wound outwards the rasteriser's side of
/// the triangle decides. So it does on Spot (its file's normals), whose smooth normals point
/// against a steep face of their own at 42 corners: close up, as the README's example sees
/// it, the surface turning away from the eye speckled dark where the derivatives decided
/// (94 pixels here).
#[test]
fn a_face_seen_edge_on_is_not_speckled() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 0 0\nv 6 0 0\nv 5 1 0\nv 5 0 1\n\
                f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n";
    let (mesh, _) = meshrefine::mesh::Mesh::from_obj_str("two.obj", text).unwrap();
    assert!(mesh.closed_outward());
    // render's camera for this mesh, in the mesh's coordinates (`info --pixel-error 1 --width
    // 320 --height 240` prints it), moved into the drawn frame.
    let (centre, scale) = mesh.viewing_transform();
    let drawn = |p: glam::Vec3| ((p.as_dvec3() - centre) * scale).as_vec3();
    let eye = drawn(glam::Vec3::new(6.5348926, 0.98406744, -1.2179321));
    let target = drawn(glam::Vec3::new(3.527982, -0.37352446, 0.97078586));
    with_gpu(320, 240, |h| {
        // Four samples a pixel, as render draws by default (one sample shows none).
        let samples = sample_count(&h.ctx, Some(4)).unwrap();
        let mut msaa = Headless::multisampled(h.ctx.clone(), 320, 240, samples).unwrap();
        let mut scene = msaa.scene(mesh.for_viewing(), 8).unwrap();
        let cfg = DrawConfig::new(Driver::Pattern(Submit::Instanced), 8)
            .with_surface(Surface::Pn, Displace::None);
        let (_, r) = scene.bounding_sphere();
        let camera = Camera::looking(eye, target, 45f32.to_radians(), r).unwrap();
        let img = msaa.render(&mut scene, &cfg, &camera).unwrap();
        let (speckles, mesh_pixels) = count_speckles(&img);
        eprintln!("{speckles} speckles in {mesh_pixels} mesh pixels");
        assert!(mesh_pixels > 5000, "only {mesh_pixels} mesh pixels");
        assert!(
            speckles <= 3,
            "{speckles} speckles in {mesh_pixels} mesh pixels"
        );
        drop(scene);
        // Spot close up (`--eye 0.3,0.2,0.6 --look-at 0,0.1,0.3`, the mesh's coordinates).
        let spot = default_mesh();
        let (centre, scale) = spot.viewing_transform();
        let drawn = |p: glam::Vec3| ((p.as_dvec3() - centre) * scale).as_vec3();
        let mut msaa = Headless::multisampled(h.ctx.clone(), 640, 360, samples).unwrap();
        let mut scene = msaa.scene(spot.for_viewing(), 16).unwrap();
        assert!(scene.normals_outward);
        let cfg = DrawConfig::new(Driver::Pattern(Submit::Instanced), 16)
            .with_surface(Surface::Pn, Displace::None);
        let (_, r) = scene.bounding_sphere();
        let eye = drawn(glam::Vec3::new(0.3, 0.2, 0.6));
        let target = drawn(glam::Vec3::new(0.0, 0.1, 0.3));
        let camera = Camera::looking(eye, target, 45f32.to_radians(), r).unwrap();
        let img = msaa.render(&mut scene, &cfg, &camera).unwrap();
        let (speckles, mesh_pixels) = count_speckles(&img);
        eprintln!("Spot: {speckles} speckles in {mesh_pixels} mesh pixels");
        assert!(mesh_pixels > 100_000, "only {mesh_pixels} mesh pixels");
        assert!(
            speckles <= 10,
            "Spot: {speckles} speckles in {mesh_pixels} mesh pixels"
        );
    });
}
