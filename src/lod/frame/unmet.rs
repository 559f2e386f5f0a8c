//! Where the levels chosen do not meet the pixel error, and why: what `render`'s and
//! `export`'s `note:` lines, `info`'s and the window's counts report.
#![forbid(unsafe_code)]

use super::{
    drawn_level, element_levels, own_need, transitions, ElementLevels, LodRecord, LodView, DYADIC,
    HUGE,
};
use glam::Vec4;

/// A largest level no finite bound reaches in practice: levels chosen under it are uncapped
/// ([`unmet`]).
pub const UNCAPPED: u32 = 1 << 20;

/// The visible elements on which the pixel error is not met, because the largest level keeps
/// them from it ([`unmet`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Unmet {
    /// Elements with a finite bound whose bounding sphere (or an edge's) holds the eye: no
    /// distance bounds their error in pixels, no level meets it.
    pub near: u64,
    /// Other elements with no finite bound (a Phong corner blending seam normals, a normal field
    /// that may vanish): at the largest level whatever the pixel error.
    pub unbounded: u64,
    /// Elements whose bound needs a level above the largest.
    pub capped: u64,
    /// Of the `capped`, those whose own bounds need a level above the largest as a uniform
    /// frame draws them (the others need it only for their transitions to coarser neighbours,
    /// or for gliding, which a uniform frame does neither of).
    pub beyond_uniform: u64,
}

impl Unmet {
    /// Whether the pixel error is not met on some element.
    pub fn any(&self) -> bool {
        self.near + self.unbounded + self.capped > 0
    }

    /// Whether no uniform level up to the largest meets the pixel error either (the uniform
    /// level is then the largest).
    pub fn uniform_unmet(&self) -> bool {
        self.near + self.unbounded + self.beyond_uniform > 0
    }
}

/// Where the levels `levels`, chosen by `view` for `records`, do not meet the pixel error
/// ([`element_unmet`] summed over the elements).
pub fn unmet(view: &LodView, records: &[LodRecord], levels: &[ElementLevels]) -> Unmet {
    let mut u = Unmet::default();
    for (r, l) in records.iter().zip(levels) {
        if let Some(e) = element_unmet(view, r, l) {
            u.near += e.near;
            u.unbounded += e.unbounded;
            u.capped += e.capped;
            u.beyond_uniform += e.beyond_uniform;
        }
    }
    u
}

/// Why a visible element drawn at the largest level (its levels `l` as `view` chose them) does
/// not meet the pixel error, as one count of [`Unmet`]; `None` where it does (or is culled, or
/// drawn below the largest level). Chosen again without the cap: no finite bound, or a sphere
/// holding the eye, else its own bounds (chord and edge curves) or its transitions to coarser
/// edges need a level above the largest; else it is met there, raised to it only by a
/// neighbour's need on a shared edge (then at the largest level too, with no transition on it).
pub fn element_unmet(view: &LodView, r: &LodRecord, l: &ElementLevels) -> Option<Unmet> {
    let (dyadic, max) = (view.dyadic(), view.max_level);
    if l.culled() || drawn_level(l.inner, dyadic, max) < max {
        return None;
    }
    let free = LodView {
        max_level: UNCAPPED,
        ..*view
    };
    let n = drawn_level(element_levels(&free, r).inner, dyadic, UNCAPPED);
    let huge = |c: &[f32; 4]| c[0] >= HUGE || c[1] >= HUGE;
    // The metric's tolerance is zero where a sphere holds the eye (`View::tolerance`).
    let holds_eye = |s: &[f32; 4]| {
        let s = Vec4::from(*s);
        (s.truncate() - view.eye()).length() <= s.w
    };
    let own = own_need(&free, r);
    // What a uniform frame needs of it: the same without gliding (`uniform_level`).
    let uniform = own_need(
        &LodView {
            flags: free.flags & !DYADIC,
            ..free
        },
        r,
    );
    let mut u = Unmet::default();
    if n >= UNCAPPED && (huge(&r.chord) || r.edges.iter().any(|e| huge(&e.curve))) {
        u.unbounded = 1;
    } else if n >= UNCAPPED
        && (holds_eye(&r.sphere) || r.edges.iter().any(|e| holds_eye(&e.sphere)))
    {
        u.near = 1;
    } else if drawn_level(own, false, UNCAPPED) > max {
        u.capped = 1;
        u.beyond_uniform = (view.uniform_drawn(uniform, UNCAPPED) > max) as u64;
    } else if transitions::transitions_beyond(view, r, &l.edges) {
        u.capped = 1;
    } else {
        return None;
    }
    Some(u)
}
