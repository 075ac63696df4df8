//! The closed surface around a shell's core ([`Body::shell`](super::Body::shell)): where a
//! region or a light lies for it, and what that lets the shell block.

use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{GridPoint, Plane};

/// The closed surface around a shell's core: occluders, and caps over
/// the hole they leave (see [`Body::shell`](super::Body::shell)).
#[derive(Debug, Clone, PartialEq)]
pub struct ShellSurface {
    /// Its faces, the occluders' and the caps': each a convex polygon's
    /// corners and its plane, facing out.
    pub faces: Vec<(Vec<GridPoint>, Plane)>,
    /// The caps: each a convex polygon's corners and its plane, facing
    /// out.
    pub caps: Vec<(Vec<GridPoint>, Plane)>,
    /// Its corners.
    pub corners: Vec<GridPoint>,
    /// The planes of its convex hull, facing out.
    pub hull: Vec<Plane>,
    /// A grid point strictly behind every face's plane, if one is known.
    pub inner: Option<GridPoint>,
}

/// For a shell, planes that put points outside its surface's hull: a
/// point of the receiver's plane (of the light's) on or in front of
/// `region` (`light`) is outside it ([`ShellSurface::separator`]).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Clearance {
    pub(super) region: Option<Plane>,
    pub(super) light: Option<Plane>,
}

/// Where a set of points (a region's or a light's corners) lies for a
/// [`ShellSurface`].
#[derive(Clone, Copy)]
pub(super) struct ShellEnd {
    /// Outside the hull: on or in front of a separator (see
    /// [`Clearance`]), or strictly in front of one of the hull's planes.
    pub(super) outside: bool,
    /// Strictly on one side of every cap's plane, the same for all.
    beside_caps: bool,
}

impl ShellSurface {
    /// Where points whose sides of a plane `sides` gives lie, with a
    /// plane that puts those on or in front of it outside the hull.
    pub(super) fn end<S: IntoIterator<Item = Side>>(
        &self,
        sides: impl Fn(&Plane) -> S,
        separator: Option<&Plane>,
    ) -> ShellEnd {
        let all = |plane: &Plane, side: Side| sides(plane).into_iter().all(|s| s == side);
        let ahead = |plane: &Plane| sides(plane).into_iter().all(|s| s != Side::Back);
        // Each cap's sides once: all strictly in front of every cap, or
        // all strictly behind.
        let (mut all_front, mut all_back) = (true, true);
        for (_, cap) in &self.caps {
            for side in sides(cap) {
                all_front &= side == Side::Front;
                all_back &= side == Side::Back;
            }
            if !all_front && !all_back {
                break;
            }
        }
        ShellEnd {
            outside: separator.is_some_and(ahead) || self.hull.iter().any(|f| all(f, Side::Front)),
            beside_caps: all_front || all_back,
        }
    }

    /// Among `own` (a plane), the hull's planes and `more`, one that puts
    /// every point of `own` on or in front of it outside the hull, and the
    /// points whose sides `sides` gives (in `own`) on or in front: the
    /// hull behind or on it, and where it touches the hull (the hull of
    /// its corners there) strictly on one side of `own`.
    pub(super) fn separator<S: IntoIterator<Item = Side>>(
        &self,
        own: &Plane,
        sides: impl Fn(&Plane) -> S,
        more: impl Iterator<Item = Plane>,
    ) -> Option<Plane> {
        let separates = |plane: Plane| -> Option<Plane> {
            let plane = facing_away(plane, &self.corners)?;
            let mut touching = self
                .corners
                .iter()
                .filter(|&&p| side_of_point(&plane, p) == Side::On)
                .map(|&p| side_of_point(own, p));
            let apart = match touching.next() {
                None => true,
                Some(Side::On) => false,
                Some(first) => touching.all(|s| s == first),
            };
            (apart && sides(&plane).into_iter().all(|s| s != Side::Back)).then_some(plane)
        };
        std::iter::once(*own)
            .chain(self.hull.iter().copied())
            .chain(more)
            .find_map(separates)
    }

    /// Whether a segment between these ends that meets the core meets an
    /// occluder (see the type's docs).
    pub(super) fn blocks(&self, region: ShellEnd, light: ShellEnd) -> bool {
        region.outside
            && light.outside
            && (self.caps.len() <= 1 || region.beside_caps || light.beside_caps)
    }
}

impl ShellSurface {
    /// Whether every segment from the region (its corners' sides of a
    /// plane given by `region`) to the light (`light`, outside the hull
    /// when `light_outside`) meets an occluder from inside the surface
    /// (see [`Body::shell`](super::Body::shell)).
    pub(super) fn hides_from_inside<S: IntoIterator<Item = Side>>(
        &self,
        region: impl Fn(&Plane) -> S + Copy,
        light: &[GridPoint],
        light_outside: bool,
    ) -> bool {
        if !light_outside {
            return false;
        }
        let light_all =
            |plane: &Plane, side: Side| light.iter().all(|&l| side_of_point(plane, l) == side);
        // From just past each point of the region towards the light, a
        // segment to `inner` meets no face: past it behind the face's
        // plane (the region behind or on it, the light strictly behind
        // where the region touches it), or a plane through an edge of the
        // face and `inner` keeps the face behind and the region in front.
        for (corners, plane) in &self.faces {
            let (mut front, mut on) = (false, false);
            for side in region(plane) {
                front |= side == Side::Front;
                on |= side == Side::On;
            }
            // Behind or on it, and the light strictly behind where touched.
            if !front && (!on || light_all(plane, Side::Back)) {
                continue;
            }
            let Some(inner) = self.inner else {
                return false;
            };
            let n = corners.len();
            let apart = (0..n).any(|i| {
                Plane::through(corners[i], corners[(i + 1) % n], inner)
                    .and_then(|through| facing_away(through, corners))
                    .is_some_and(|through| region(&through).into_iter().all(|s| s == Side::Front))
            });
            if !apart {
                return false;
            }
        }
        self.caps
            .iter()
            .all(|(corners, plane)| Self::window_shut(corners, plane, region, light))
    }

    /// Whether a plane separates the cap with `corners` in `plane`
    /// (facing out) from every segment between the region and the light:
    /// the cap's plane, both strictly behind it; or a plane through an
    /// edge of the cap and a corner of the light, the cap behind or on
    /// it, the light on or in front and strictly in front of the cap's
    /// plane (so it meets the cap nowhere on the plane), the region
    /// strictly in front.
    fn window_shut<S: IntoIterator<Item = Side>>(
        corners: &[GridPoint],
        plane: &Plane,
        region: impl Fn(&Plane) -> S,
        light: &[GridPoint],
    ) -> bool {
        let region_all = |plane: &Plane, side: Side| region(plane).into_iter().all(|s| s == side);
        let light_all =
            |plane: &Plane, side: Side| light.iter().all(|&l| side_of_point(plane, l) == side);
        if region_all(plane, Side::Back) && light_all(plane, Side::Back) {
            return true;
        }
        if !light_all(plane, Side::Front) {
            return false;
        }
        let n = corners.len();
        (0..n).any(|i| {
            light.iter().any(|&l| {
                let Some(through) = Plane::through(corners[i], corners[(i + 1) % n], l)
                    .and_then(|plane| facing_away(plane, corners))
                else {
                    return false;
                };
                light
                    .iter()
                    .all(|&p| side_of_point(&through, p) != Side::Back)
                    && region_all(&through, Side::Front)
            })
        })
    }
}

/// `plane`, or its flip, with all of `points` behind or on it; `None`
/// when they lie on both sides.
fn facing_away(plane: Plane, points: &[GridPoint]) -> Option<Plane> {
    let (mut front, mut back) = (false, false);
    for &p in points {
        match side_of_point(&plane, p) {
            Side::Front => front = true,
            Side::Back => back = true,
            Side::On => {}
        }
    }
    match (front, back) {
        (true, true) => None,
        (true, false) => Some(plane.flipped()),
        _ => Some(plane),
    }
}
