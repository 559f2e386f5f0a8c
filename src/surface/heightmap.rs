//! Height maps for the `heightmap` displacement: a grayscale image as heights in [0, 1] with its
//! mip pyramid, sampled at texture coordinates with level-aware filtering. Mirror of
//! `glsl/include/heightmap.glsl`.
//!
//! The GPU samples the pyramid by hand from a texel buffer, its layout a uniform block (bilinear within a level, linear
//! between the two levels around the requested one, coordinates repeating), not through a
//! sampler: hardware filtering's sub-texel precision differs between devices (Vulkan requires only
//! 4 bits), and this way the CPU mirror computes the same arithmetic. The level is chosen from the
//! refinement level (see [`Heightmap::lod_for`]), so coarse refinement reads a correspondingly
//! blurred map instead of aliasing (the 2005 paper's complaint about unfiltered vertex-texture
//! reads).

use super::heightmap_bound::FactsCache;
pub use super::heightmap_bound::{MapLevel, BOUND};
use glam::Vec2;
use std::path::Path;

/// Largest accepted image side.
pub const MAX_SIDE: u32 = 8192;

/// Most pyramid levels the GPU layout holds (a 8192² image has 14).
pub const MAX_LEVELS: usize = 16;

/// One pyramid level: `w` × `h` heights, row-major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    pub w: u32,
    pub h: u32,
    pub texels: Vec<f32>,
}

/// What the `heightmap` displacement's mirror reads besides the surface point (whose texture
/// coordinates come from the element's, which [`super::Mirror::new`] makes sure exist): the
/// map and the pyramid level to read.
#[derive(Clone, Copy, Debug)]
pub struct Inputs<'a> {
    pub map: &'a Heightmap,
    /// One per mesh and refinement level ([`Heightmap::lod_for`]).
    pub lod: f32,
}

/// A height map and its mip pyramid (level 0 first, each half the size of the one before, down
/// to 1 × 1; 2 × 2 box filter, the last row or column of an odd side folded into its neighbour).
#[derive(Clone, Debug, PartialEq)]
pub struct Heightmap {
    /// Where it came from, for messages (a path, or "generated").
    pub source: String,
    pub levels: Vec<Level>,
    /// Each level's texel facts for the bounds, made when first asked for.
    pub(crate) facts: FactsCache,
}

/// The width and height a PNG file's header (its signature and `IHDR` chunk) gives, if it has
/// one; the file is left at its start either way.
fn png_sides(file: &mut std::fs::File) -> Option<(u32, u32)> {
    use std::io::{Read, Seek};
    let mut head = [0u8; 24];
    let read = file.read_exact(&mut head);
    file.seek(std::io::SeekFrom::Start(0)).ok()?;
    read.ok()?;
    let be = |i: usize| u32::from_be_bytes([head[i], head[i + 1], head[i + 2], head[i + 3]]);
    (head[..8] == [0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a] && &head[12..16] == b"IHDR")
        .then(|| (be(16), be(20)))
}

impl Heightmap {
    /// From heights (row-major `w` × `h`, each in [0, 1]).
    pub fn from_heights(source: &str, w: u32, h: u32, texels: Vec<f32>) -> Self {
        assert_eq!(texels.len(), (w * h) as usize);
        let mut levels = vec![Level { w, h, texels }];
        while levels.len() < MAX_LEVELS {
            let l = levels.last().unwrap();
            if l.w == 1 && l.h == 1 {
                break;
            }
            let (nw, nh) = ((l.w / 2).max(1), (l.h / 2).max(1));
            let mut t = Vec::with_capacity((nw * nh) as usize);
            for y in 0..nh {
                for x in 0..nw {
                    // The source texels this one covers (3 on an odd side's last one).
                    let xs = 2 * x..(2 * x + 2 + (x + 1 == nw && l.w % 2 == 1) as u32).min(l.w);
                    let ys = 2 * y..(2 * y + 2 + (y + 1 == nh && l.h % 2 == 1) as u32).min(l.h);
                    let (mut sum, mut n) = (0.0f64, 0u32);
                    for sy in ys.clone() {
                        for sx in xs.clone() {
                            sum += l.texels[(sy * l.w + sx) as usize] as f64;
                            n += 1;
                        }
                    }
                    t.push((sum / n as f64) as f32);
                }
            }
            levels.push(Level {
                w: nw,
                h: nh,
                texels: t,
            });
        }
        Self {
            source: source.to_string(),
            facts: FactsCache::new(levels.len()),
            levels,
        }
    }

    /// The map used when no file is given: 256 × 256 smooth bumps, 8 × 8 of them over the unit
    /// square, periodic (so repeating coordinates do not show a seam).
    pub fn generated() -> Self {
        let n = 256u32;
        let mut t = Vec::with_capacity((n * n) as usize);
        for y in 0..n {
            for x in 0..n {
                let (u, v) = (
                    (x as f64 + 0.5) / n as f64 * std::f64::consts::TAU,
                    (y as f64 + 0.5) / n as f64 * std::f64::consts::TAU,
                );
                let h =
                    0.5 + 0.25 * ((8.0 * u).sin() * (8.0 * v).sin() + (3.0 * u + 2.0 * v).cos());
                t.push(h.clamp(0.0, 1.0) as f32);
            }
        }
        Self::from_heights("the generated default height map", n, n, t)
    }

    /// Reads a grayscale PNG (8 or 16 bits per sample, with or without alpha, which is ignored):
    /// one sentence naming the file on any problem.
    pub fn load_png(path: &Path) -> Result<Self, String> {
        let shown = path.display();
        // Checked before opening: opening a FIFO would block (crate::paths).
        let (mut file, meta) = crate::paths::open_input(path, "height map")?;
        if meta.len() == 0 {
            return Err(format!("height map '{shown}' is empty (0 bytes)"));
        }
        let sides = |w: u32, h: u32| {
            if w == 0 || h == 0 || w > MAX_SIDE || h > MAX_SIDE {
                return Err(format!(
                    "height map '{shown}' is {w} x {h} pixels: each side must be within 1 to {MAX_SIDE}"
                ));
            }
            Ok(())
        };
        // The sides from the header first: the decoder refuses an image too large for its
        // memory limit before saying how large it is.
        if let Some((w, h)) = png_sides(&mut file) {
            sides(w, h)?;
        }
        let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
        decoder.set_transformations(png::Transformations::IDENTITY);
        let mut reader = decoder
            .read_info()
            .map_err(|e| png_problem(&shown.to_string(), e))?;
        let info = reader.info();
        let (w, h) = (info.width, info.height);
        sides(w, h)?;
        let (color, depth) = (info.color_type, info.bit_depth);
        let channels = match color {
            png::ColorType::Grayscale => 1,
            png::ColorType::GrayscaleAlpha => 2,
            other => {
                let what = match other {
                    png::ColorType::Rgb => "an RGB colour",
                    png::ColorType::Rgba => "an RGBA colour",
                    png::ColorType::Indexed => "a palette (indexed colour)",
                    _ => "a colour",
                };
                return Err(format!(
                    "height map '{shown}' is {what} PNG image: a height map must be grayscale (8 or 16 bits per sample)"
                ));
            }
        };
        if !matches!(depth, png::BitDepth::Eight | png::BitDepth::Sixteen) {
            let bits = match depth {
                png::BitDepth::One => 1,
                png::BitDepth::Two => 2,
                png::BitDepth::Four => 4,
                png::BitDepth::Eight => 8,
                png::BitDepth::Sixteen => 16,
            };
            return Err(format!(
                "height map '{shown}' has {bits}-bit samples: a height map must have 8 or 16 bits per sample"
            ));
        }
        let mut buf = vec![0u8; reader.output_buffer_size()];
        let frame = reader
            .next_frame(&mut buf)
            .map_err(|e| png_problem(&shown.to_string(), e))?;
        let bytes = &buf[..frame.buffer_size()];
        let row = frame.line_size;
        let mut t = Vec::with_capacity((w * h) as usize);
        for y in 0..h as usize {
            let line = &bytes[y * row..];
            for x in 0..w as usize {
                let v = if depth == png::BitDepth::Eight {
                    line[x * channels] as f32 / 255.0
                } else {
                    let i = 2 * x * channels;
                    u16::from_be_bytes([line[i], line[i + 1]]) as f32 / 65535.0
                };
                t.push(v);
            }
        }
        Ok(Self::from_heights(&shown.to_string(), w, h, t))
    }

    /// The pyramid level to read when each refined triangle spans `uv_extent` of texture space
    /// along its edges (the mesh's mean coarse-triangle UV edge length over `level` segments):
    /// `log2` of that footprint in level-0 texels, at least 0, at most the last level. One value
    /// for the whole mesh, so both sides of every shared edge read the same level.
    pub fn lod_for(&self, uv_extent: f32, level: u32) -> f32 {
        let side = self.levels[0].w.max(self.levels[0].h) as f32;
        let texels = uv_extent * side / level.max(1) as f32;
        let lod = if texels > 1.0 { texels.log2() } else { 0.0 };
        lod.min((self.levels.len() - 1) as f32)
    }

    /// The pyramid's layout as the GPU reads it (`HeightmapData` block in heightmap.glsl):
    /// `uvec4` header (level count), [`MAX_LEVELS`] `uvec4` (offset in texels, width, height,
    /// 0).
    pub fn gpu_header(&self) -> Vec<u32> {
        let mut out = vec![0u32; 4 + 4 * MAX_LEVELS];
        out[0] = self.levels.len() as u32;
        let mut offset = 0u32;
        for (i, l) in self.levels.iter().enumerate() {
            out[4 + 4 * i] = offset;
            out[5 + 4 * i] = l.w;
            out[6 + 4 * i] = l.h;
            offset += l.w * l.h;
        }
        out
    }

    /// Every level's heights, level after level (the `hm_texels` texel buffer).
    pub fn gpu_texels(&self) -> Vec<f32> {
        let mut out = Vec::with_capacity(self.texel_count() as usize);
        for l in &self.levels {
            out.extend_from_slice(&l.texels);
        }
        out
    }

    /// Texels in the whole pyramid.
    pub fn texel_count(&self) -> u64 {
        self.levels.iter().map(|l| l.w as u64 * l.h as u64).sum()
    }

    /// Bilinear sample of level `l` at `uv` (repeating) and its derivative by `uv`.
    /// Mirror of `heightmap_bilinear`.
    fn bilinear(&self, l: usize, uv: Vec2) -> (f32, Vec2) {
        let lv = &self.levels[l];
        let (w, h) = (lv.w as f32, lv.h as f32);
        let x = uv.x * w - 0.5;
        let y = uv.y * h - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let wrap = |i: f32, n: u32| (i as i64).rem_euclid(n as i64) as u32;
        let (ix0, iy0) = (wrap(x0, lv.w), wrap(y0, lv.h));
        let (ix1, iy1) = ((ix0 + 1) % lv.w, (iy0 + 1) % lv.h);
        let t = |ix: u32, iy: u32| lv.texels[(iy * lv.w + ix) as usize];
        let (t00, t10, t01, t11) = (t(ix0, iy0), t(ix1, iy0), t(ix0, iy1), t(ix1, iy1));
        let top = t00 + fx * (t10 - t00);
        let bottom = t01 + fx * (t11 - t01);
        let value = top + fy * (bottom - top);
        let dx = (t10 - t00) + fy * ((t11 - t01) - (t10 - t00));
        let dy = bottom - top;
        (value, Vec2::new(dx * w, dy * h))
    }

    /// Height at `uv` (repeating) read at pyramid level `lod` (linear between the two levels
    /// around it), and its derivative by `uv`. Mirror of `heightmap_sample` in heightmap.glsl.
    pub fn sample(&self, uv: Vec2, lod: f32) -> (f32, Vec2) {
        let last = self.levels.len() - 1;
        let l0 = (lod.max(0.0).floor() as usize).min(last);
        let l1 = (l0 + 1).min(last);
        let f = (lod.max(0.0) - l0 as f32).clamp(0.0, 1.0);
        let (a, da) = self.bilinear(l0, uv);
        if l1 == l0 || f == 0.0 {
            return (a, da);
        }
        let (b, db) = self.bilinear(l1, uv);
        (a + f * (b - a), da + (db - da) * f)
    }
}

/// One sentence for a PNG the decoder cannot read: what is wrong in words, not the decoder's
/// internals (its chunk structures, its closing full stop).
fn png_problem(shown: &str, e: png::DecodingError) -> String {
    let why = match e {
        png::DecodingError::IoError(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => {
            "it ends early (the file is truncated)".to_string()
        }
        png::DecodingError::IoError(e) => return format!("cannot read height map '{shown}': {e}"),
        png::DecodingError::LimitsExceeded => {
            "decoding it needs more memory than the decoder allows (an image or a chunk too large)"
                .to_string()
        }
        png::DecodingError::Format(f) => {
            let text = f.to_string();
            if text.contains("signature") {
                "it does not start with the PNG signature".to_string()
            } else if text.contains("CRC") {
                "a chunk's checksum is wrong: the file is damaged".to_string()
            } else if text.contains("deflate") || text.contains("Zlib") {
                "its compressed image data is damaged".to_string()
            } else if text.contains("is missing") {
                "it holds no image data".to_string()
            } else if text.contains("not have enough data") {
                "it holds less image data than its header's sides declare".to_string()
            } else {
                "its structure is damaged".to_string()
            }
        }
        png::DecodingError::Parameter(p) => p.to_string().trim_end_matches('.').to_string(),
    };
    format!("height map '{shown}' is not a readable PNG image: {why}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pyramid_halves_to_one_texel_and_keeps_the_mean() {
        let (w, h) = (7u32, 4u32);
        let t: Vec<f32> = (0..w * h).map(|i| (i % 5) as f32 / 4.0).collect();
        let mean = t.iter().map(|&x| x as f64).sum::<f64>() / t.len() as f64;
        let m = Heightmap::from_heights("t", w, h, t);
        let sizes: Vec<(u32, u32)> = m.levels.iter().map(|l| (l.w, l.h)).collect();
        assert_eq!(sizes, [(7, 4), (3, 2), (1, 1)]);
        assert!((m.levels[2].texels[0] as f64 - mean).abs() < 0.05);
    }

    #[test]
    fn texel_centres_read_their_texel_and_the_gradient_is_the_derivative() {
        let m = Heightmap::generated();
        let l = &m.levels[0];
        for (x, y) in [(3u32, 5u32), (100, 17), (255, 255)] {
            let uv = Vec2::new((x as f32 + 0.5) / l.w as f32, (y as f32 + 0.5) / l.h as f32);
            assert!((m.sample(uv, 0.0).0 - l.texels[(y * l.w + x) as usize]).abs() < 1e-6);
        }
        // A small step: the filtered map's derivative jumps at texel boundaries.
        let e = 2e-5;
        for uv in [Vec2::new(0.3, 0.7), Vec2::new(0.91, 0.12)] {
            for lod in [0.0, 1.5] {
                let (_, g) = m.sample(uv, lod);
                let fx = (m.sample(uv + Vec2::X * e, lod).0 - m.sample(uv - Vec2::X * e, lod).0)
                    / (2.0 * e);
                let fy = (m.sample(uv + Vec2::Y * e, lod).0 - m.sample(uv - Vec2::Y * e, lod).0)
                    / (2.0 * e);
                assert!(
                    (fx - g.x).abs() < 0.05 * (1.0 + g.x.abs()),
                    "{fx} vs {}",
                    g.x
                );
                assert!(
                    (fy - g.y).abs() < 0.05 * (1.0 + g.y.abs()),
                    "{fy} vs {}",
                    g.y
                );
            }
        }
        // Coordinates repeat.
        assert_eq!(
            m.sample(Vec2::new(0.25, 0.5), 0.0).0,
            m.sample(Vec2::new(1.25, -0.5), 0.0).0
        );
    }

    #[test]
    fn lod_follows_the_refinement_level() {
        let m = Heightmap::generated();
        // A coarse triangle spanning the whole map: 256 texels per edge.
        assert_eq!(m.lod_for(1.0, 256), 0.0);
        assert_eq!(m.lod_for(1.0, 16), 4.0);
        assert_eq!(m.lod_for(1.0, 1), 8.0);
    }

    #[test]
    fn png_errors_name_the_file() {
        let dir = std::env::temp_dir().join("meshrefine-heightmap-test");
        std::fs::create_dir_all(&dir).unwrap();
        let missing = dir.join("missing.png");
        assert!(Heightmap::load_png(&missing)
            .unwrap_err()
            .contains("missing.png"));
        let text = dir.join("text.png");
        std::fs::write(&text, "not a png").unwrap();
        assert!(Heightmap::load_png(&text)
            .unwrap_err()
            .ends_with("is not a readable PNG image: it does not start with the PNG signature"));
        // A damaged checksum and a header claiming 2³¹ − 1 pixels a side: said in words.
        let gray = dir.join("gray.png");
        {
            let mut e = png::Encoder::new(std::fs::File::create(&gray).unwrap(), 2, 1);
            e.set_color(png::ColorType::Grayscale);
            e.write_header().unwrap().write_image_data(&[0, 9]).unwrap();
        }
        let mut bytes = std::fs::read(&gray).unwrap();
        bytes[29] ^= 0xff; // IHDR's CRC (8 signature + 8 length/type + 13 data)
        let damaged = dir.join("damaged.png");
        std::fs::write(&damaged, &bytes).unwrap();
        let e = Heightmap::load_png(&damaged).unwrap_err();
        assert!(
            e.ends_with("a chunk's checksum is wrong: the file is damaged"),
            "{e}"
        );
        let huge = dir.join("huge.png");
        {
            let mut e = png::Encoder::new(
                std::fs::File::create(&huge).unwrap(),
                i32::MAX as u32,
                i32::MAX as u32,
            );
            e.set_color(png::ColorType::Grayscale);
            drop(e.write_header().unwrap());
        }
        let e = Heightmap::load_png(&huge).unwrap_err();
        assert!(
            e.ends_with(
                "huge.png' is 2147483647 x 2147483647 pixels: each side must be within 1 to 8192"
            ),
            "{e}"
        );
        // A header and no pixels.
        let bare = dir.join("bare.png");
        {
            let mut e = png::Encoder::new(std::fs::File::create(&bare).unwrap(), 4, 4);
            e.set_color(png::ColorType::Grayscale);
            drop(e.write_header().unwrap());
        }
        let e = Heightmap::load_png(&bare).unwrap_err();
        assert!(
            e.ends_with("bare.png' is not a readable PNG image: it holds no image data"),
            "{e}"
        );
        // A 4x4 image's data under a header that says 4x64 (its checksum mended): short data.
        let mut bytes = Vec::new();
        {
            let mut e = png::Encoder::new(&mut bytes, 4, 4);
            e.set_color(png::ColorType::Grayscale);
            let mut w = e.write_header().unwrap();
            w.write_image_data(&[7u8; 16]).unwrap();
        }
        bytes[20..24].copy_from_slice(&64u32.to_be_bytes());
        let crc = |data: &[u8]| {
            let mut c = !0u32;
            for &b in data {
                c ^= b as u32;
                for _ in 0..8 {
                    c = if c & 1 != 0 {
                        (c >> 1) ^ 0xEDB8_8320
                    } else {
                        c >> 1
                    };
                }
            }
            !c
        };
        let sum = crc(&bytes[12..29]);
        bytes[29..33].copy_from_slice(&sum.to_be_bytes());
        let short = dir.join("short.png");
        std::fs::write(&short, &bytes).unwrap();
        let e = Heightmap::load_png(&short).unwrap_err();
        assert!(
            e.ends_with("it holds less image data than its header's sides declare"),
            "{e}"
        );
        // Cut short: truncated, not an I/O failure.
        let cut = dir.join("cut.png");
        std::fs::write(&cut, &std::fs::read(&gray).unwrap()[..40]).unwrap();
        let e = Heightmap::load_png(&cut).unwrap_err();
        assert!(e.ends_with("it ends early (the file is truncated)"), "{e}");
        // Nothing at all: empty, not truncated.
        let empty = dir.join("empty.png");
        std::fs::write(&empty, b"").unwrap();
        let e = Heightmap::load_png(&empty).unwrap_err();
        assert!(e.ends_with("empty.png' is empty (0 bytes)"), "{e}");
        // An RGB image is refused; a 16-bit grayscale one loads.
        let write = |name: &str, color, depth, data: &[u8]| {
            let p = dir.join(name);
            let mut e = png::Encoder::new(std::fs::File::create(&p).unwrap(), 2, 1);
            e.set_color(color);
            e.set_depth(depth);
            e.write_header().unwrap().write_image_data(data).unwrap();
            p
        };
        let rgb = write(
            "rgb.png",
            png::ColorType::Rgb,
            png::BitDepth::Eight,
            &[0; 6],
        );
        let e = Heightmap::load_png(&rgb).unwrap_err();
        assert!(
            e.contains("is an RGB colour PNG image: a height map must be grayscale"),
            "{e}"
        );
        let indexed = dir.join("indexed.png");
        {
            let mut e = png::Encoder::new(std::fs::File::create(&indexed).unwrap(), 2, 1);
            e.set_color(png::ColorType::Indexed);
            e.set_depth(png::BitDepth::Eight);
            e.set_palette(vec![0u8; 6]);
            e.write_header().unwrap().write_image_data(&[0, 1]).unwrap();
        }
        let e = Heightmap::load_png(&indexed).unwrap_err();
        assert!(e.contains("is a palette (indexed colour) PNG image"), "{e}");
        let one_bit = write(
            "one-bit.png",
            png::ColorType::Grayscale,
            png::BitDepth::One,
            &[0b1000_0000],
        );
        let e = Heightmap::load_png(&one_bit).unwrap_err();
        assert!(
            e.contains("has 1-bit samples: a height map must have 8 or 16"),
            "{e}"
        );
        assert!(!e.contains("One"), "{e}");
        // Not a regular file: refused without opening (a FIFO would block).
        let e = Heightmap::load_png(&dir).unwrap_err();
        assert!(e.contains("is a directory, not a regular file"), "{e}");
        let g16 = write(
            "g16.png",
            png::ColorType::Grayscale,
            png::BitDepth::Sixteen,
            &[0, 0, 0xff, 0xff],
        );
        let m = Heightmap::load_png(&g16).unwrap();
        assert_eq!(m.levels[0].texels, [0.0, 1.0]);
        // Alpha is read past: the heights are the grey samples'.
        let ga = write(
            "ga.png",
            png::ColorType::GrayscaleAlpha,
            png::BitDepth::Eight,
            &[0, 0x80, 0xff, 0x10],
        );
        assert_eq!(
            Heightmap::load_png(&ga).unwrap().levels[0].texels,
            [0.0, 1.0]
        );
        // A side past MAX_SIDE is refused from the header, before its pixels are read.
        let wide = dir.join("wide.png");
        {
            let mut e = png::Encoder::new(std::fs::File::create(&wide).unwrap(), MAX_SIDE + 1, 1);
            e.set_color(png::ColorType::Grayscale);
            e.set_depth(png::BitDepth::Eight);
            let row = vec![0u8; MAX_SIDE as usize + 1];
            e.write_header().unwrap().write_image_data(&row).unwrap();
        }
        let e = Heightmap::load_png(&wide).unwrap_err();
        assert!(
            e.ends_with("is 8193 x 1 pixels: each side must be within 1 to 8192"),
            "{e}"
        );
        // So is one whose header claims more than the decoder's memory limit allows: the
        // header of a 16 x 16 image with its width made 2^31 − 1 (its checksum made again).
        let small = dir.join("small.png");
        {
            let mut e = png::Encoder::new(std::fs::File::create(&small).unwrap(), 16, 16);
            e.set_color(png::ColorType::Grayscale);
            e.set_depth(png::BitDepth::Eight);
            e.write_header()
                .unwrap()
                .write_image_data(&[0; 256])
                .unwrap();
        }
        let mut bytes = std::fs::read(&small).unwrap();
        bytes[16..20].copy_from_slice(&(i32::MAX as u32).to_be_bytes());
        let crc = crc32(&bytes[12..29]);
        bytes[29..33].copy_from_slice(&crc.to_be_bytes());
        let huge = dir.join("huge-claim.png");
        std::fs::write(&huge, &bytes).unwrap();
        let e = Heightmap::load_png(&huge).unwrap_err();
        assert!(
            e.ends_with("is 2147483647 x 16 pixels: each side must be within 1 to 8192"),
            "{e}"
        );
    }

    /// The CRC-32 a PNG chunk ends with (of its type and data).
    fn crc32(bytes: &[u8]) -> u32 {
        let mut c = !0u32;
        for &b in bytes {
            c ^= b as u32;
            for _ in 0..8 {
                c = if c & 1 != 0 {
                    0xedb8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
            }
        }
        !c
    }
}
