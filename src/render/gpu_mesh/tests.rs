//! Unit tests of the mesh upload's limits and chunks.

use super::*;

/// A height map whose pyramid is over maxTexelBufferElements is one sentence naming the
/// file, its size, the texels and the limit.
#[test]
fn a_heightmap_over_the_texel_limit_is_refused_naming_it() {
    // 4 x 4 with its pyramid: 16 + 4 + 1 texels.
    let map = Heightmap::from_heights("bumps.png", 4, 4, vec![0.5; 16]);
    let mut limits = vk::PhysicalDeviceLimits {
        max_texel_buffer_elements: 21,
        ..Default::default()
    };
    check_heightmap(&map, &limits).unwrap();
    limits.max_texel_buffer_elements = 20;
    assert_eq!(
        check_heightmap(&map, &limits).unwrap_err().to_string(),
        "height map 'bumps.png' (4 x 4 pixels, with its mip pyramid) needs 21 texels, over \
         this device's maxTexelBufferElements (20): use a smaller height map"
    );
}

/// Scalar tags past maxTexelBufferElements (three texels a vertex) are one sentence naming the
/// vertices, the texels and the limit.
#[test]
fn tags_over_the_texel_limit_are_refused_naming_them() {
    let mut limits = vk::PhysicalDeviceLimits {
        max_texel_buffer_elements: 21,
        ..Default::default()
    };
    check_tags(7, &limits).unwrap();
    limits.max_texel_buffer_elements = 20;
    assert_eq!(
        check_tags(7, &limits).unwrap_err().to_string(),
        "the scalar-tag buffer of 7 vertices needs 21 texels, over this device's \
         maxTexelBufferElements (20): use a mesh with fewer vertices"
    );
}

/// Tags past the limit are not uploaded (one zero entry is bound instead), so a mesh drawn with
/// a surface that reads none is not refused for them; tags within it are uploaded whole.
#[test]
fn tags_over_the_texel_limit_are_left_out_of_the_upload() {
    let tags = vec![VertexTag::default(); 7];
    let mut limits = vk::PhysicalDeviceLimits {
        max_texel_buffer_elements: 21,
        ..Default::default()
    };
    assert_eq!(uploaded_tags(&tags, &limits).len(), 7);
    limits.max_texel_buffer_elements = 20;
    assert!(uploaded_tags(&tags, &limits).is_empty());
}

/// Chunks hold as many records as the range spans, in whole steps that keep every array's
/// offsets aligned (records 112 bytes, texture coordinates 32, levels 16), and at least one
/// step where the range holds less.
#[test]
fn chunks_keep_every_arrays_offsets_aligned() {
    let sizes = [RECORD_BYTES as u64, UV_BYTES, LEVELS_BYTES];
    // lavapipe: 128 MiB at an alignment of 16.
    assert_eq!(chunk_elements(1 << 27, 16, &sizes), 1_198_372);
    for align in [16u64, 64, 256] {
        for range in [1u64, 100, 448, 1_000, 1 << 20] {
            let n = chunk_elements(range, align, &sizes) as u64;
            assert!(n >= 1);
            for s in sizes {
                assert_eq!(
                    n * s % align,
                    0,
                    "align {align}, range {range}: {n} elements"
                );
            }
            // Within the range where a step fits.
            let step = [1u64, 4, 16][[16, 64, 256].iter().position(|&a| a == align).unwrap()];
            if range >= step * 112 {
                assert!(
                    n * 112 <= range,
                    "align {align}, range {range}: {n} elements"
                );
            }
        }
    }
}

/// On a device at Vulkan's least texel range (65,536 texels) with 256-byte offset alignments,
/// a chunk of records spans at most that many texels (seven a record), in whole steps of 16
/// records that keep the records', texture coordinates' and levels' offsets aligned: 9,360.
#[test]
fn chunks_follow_the_texel_limit() {
    let limits = least_texel_range();
    let chunk = chunk_size(&limits, None) as u64;
    assert_eq!(chunk, 9_360);
    assert!(chunk * RECORD_BYTES as u64 / 16 <= 65_536);
    for size in [RECORD_BYTES as u64, UV_BYTES, LEVELS_BYTES] {
        assert_eq!(chunk * size % 256, 0);
    }
    // The storage range binds first where it is the smaller.
    let small = vk::PhysicalDeviceLimits {
        max_storage_buffer_range: 112 * 1_000,
        ..limits
    };
    assert_eq!(chunk_size(&small, None), 992);
}

/// Vulkan's least texel range (65,536 texels), a 128 MiB storage range and 256-byte offset
/// alignments (the largest Vulkan allows): what the chunk tests size chunks for.
pub(in crate::render) fn least_texel_range() -> vk::PhysicalDeviceLimits {
    vk::PhysicalDeviceLimits {
        max_texel_buffer_elements: 65_536,
        max_storage_buffer_range: 1 << 27,
        min_texel_buffer_offset_alignment: 256,
        min_storage_buffer_offset_alignment: 256,
        ..Default::default()
    }
}
