//! The tables' lattice and a face's frame in it: [`Lattice`] (2^lmax segments per M1-face edge,
//! one row per lattice point, numbered by [`crate::pattern::lattice_index`], the one function
//! that numbers a triangular lattice), [`Orient`] (how a face's stored corners map to its
//! configuration's canonical corners), where a face's corners and its children's corners lie
//! in the lattice as the configuration mesh is refined, and the lattice's reflections (which a
//! symmetric table is read across).
#![forbid(unsafe_code)]

/// The tables' default level: 2^5 = 32 segments per M1-face edge (`--bft-level`).
pub const DEFAULT_LMAX: u32 = 5;

/// The highest level offered: 2^7 = 128 segments, 8,385 rows a table.
pub const MAX_LMAX: u32 = 7;

/// The tables' lattice: 2^lmax segments per M1-face edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Lattice {
    pub lmax: u32,
}

impl Default for Lattice {
    fn default() -> Self {
        Self { lmax: DEFAULT_LMAX }
    }
}

impl Lattice {
    pub fn new(lmax: u32) -> Self {
        assert!(
            (1..=MAX_LMAX).contains(&lmax),
            "lmax {lmax} out of 1..={MAX_LMAX}"
        );
        Self { lmax }
    }

    /// Segments per M1-face edge.
    pub fn segments(self) -> u32 {
        1 << self.lmax
    }

    /// Lattice points per face: (S + 1)(S + 2) / 2.
    pub fn rows(self) -> usize {
        crate::pattern::vertex_count(self.segments()) as usize
    }

    /// The row of lattice point (i, j): weight i/S on the face's canonical corner 1, j/S on
    /// corner 2: the lattice's vertex index, as a refinement pattern of S segments numbers its
    /// vertices ([`crate::pattern::lattice_index`]). Mirror of `bft_row` in glsl/include/loop.glsl.
    pub fn row(self, i: u32, j: u32) -> usize {
        debug_assert!(i + j <= self.segments());
        crate::pattern::lattice_index(self.segments(), i, j) as usize
    }
}

/// How a face's stored corners map to its configuration's canonical corners: canonical corner i
/// is stored corner `rot + i` (mod 3), or `rot - i` when the face is the configuration's mirror
/// image (its table is the mirror's, read with u and v swapped).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Orient {
    pub rot: u8,
    pub mirror: bool,
}

impl Orient {
    /// The stored corner that is canonical corner `i`. Mirror of `loop_stored` in loop.glsl.
    pub fn stored(self, i: usize) -> usize {
        let r = self.rot as usize;
        if self.mirror {
            (r + 3 - i) % 3
        } else {
            (r + i) % 3
        }
    }

    /// The canonical corner stored corner `k` is.
    pub fn canonical(self, k: usize) -> usize {
        (0..3).find(|&i| self.stored(i) == k).unwrap()
    }

    /// All six.
    pub fn all() -> impl Iterator<Item = Orient> {
        [false, true]
            .into_iter()
            .flat_map(|mirror| (0..3).map(move |rot| Orient { rot, mirror }))
    }

    /// As the GPU's face entry stores it: rotation in bits 0-1, mirror in bit 2.
    pub fn bits(self) -> u32 {
        self.rot as u32 | (self.mirror as u32) << 2
    }
}

/// Lattice coordinates (units of 1/S) of a face's stored corners in orientation `o`.
pub fn lattice_corners(o: Orient, lattice: Lattice) -> [[u32; 2]; 3] {
    let s = lattice.segments();
    let base = [[0, 0], [s, 0], [0, s]];
    [0, 1, 2].map(|k| base[o.canonical(k)])
}

/// Faces with their corners' lattice coordinates, after one more step: each face's four
/// children (numbered as [`crate::subdiv::loop_step`] does, `4f + k`) with the midpoints.
pub fn children_in_lattice(faces: &[(usize, [[u32; 2]; 3])]) -> Vec<(usize, [[u32; 2]; 3])> {
    let mid = |a: [u32; 2], b: [u32; 2]| [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
    faces
        .iter()
        .flat_map(|&(face, [a, b, c])| {
            let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
            [
                (4 * face, [a, ab, ca]),
                (4 * face + 1, [b, bc, ab]),
                (4 * face + 2, [c, ca, bc]),
                (4 * face + 3, [ab, bc, ca]),
            ]
        })
        .collect()
}

/// The lattice reflection that fixes canonical corner `a`: it swaps the other two corners'
/// weights. Row r's mirror image, for every row.
pub(super) fn reflection(lattice: Lattice, a: u8) -> Vec<usize> {
    let s = lattice.segments();
    let mut image = vec![0; lattice.rows()];
    for j in 0..=s {
        for i in 0..=s - j {
            let k = s - i - j;
            let (x, y) = match a {
                0 => (j, i),
                1 => (i, k),
                _ => (k, j),
            };
            image[lattice.row(i, j)] = lattice.row(x, y);
        }
    }
    image
}
