//! Convex bodies as blockers: the solid of a convex surface of occluders,
//! open on some faces, and the shell a surface closed over its hole
//! bounds ([`Body::shell`]).

use bsp_core::predicates::{Side, side_of_point};
use bsp_core::{ConvexPolygon, GridPoint, Plane};
use smallvec::SmallVec;

use super::shell::{Clearance, ShellSurface};
use super::{Bounds, Occluder, Pairs, bounds};

/// A convex body that blocks segments meeting it, in one of two ways.
///
/// *Surface*: the body's boundary is made of occluders, but for some
/// *open* faces (the caps that close a bent quad into a thin tetrahedron,
/// say). From a point outside the body that is behind (or on) every open
/// face, the faces it sees are occluders, so a segment from it that meets
/// the body crosses one of them; and for a fixed end, the ends whose
/// segment meets a convex body form a convex set. So when the corners of
/// `K` (or of `L`) are all outside the body and behind every open face,
/// and every segment between corners crosses one of the body's occluders,
/// so does every segment from `K` to `L`.
///
/// *Shell* ([`Self::shell`]): the body is a convex *core* inside a closed
/// surface of occluders and caps over its hole (a cup, its rim closed),
/// or of occluders only (a closed surface that is concave, or that the
/// grid bent), its boundary polygons no occluders. A segment whose ends
/// are both outside the surface's hull and that meets the core crosses
/// the surface, and not only its caps (see [`Self::shell`]); the
/// convex-set argument carries that from the corner pairs to all of
/// `K x L`.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// The box around the corners.
    pub(super) bounds: Bounds,
    /// Each face's plane, the body behind it (planes may repeat).
    faces: Vec<Plane>,
    /// The open faces' planes, the body behind them.
    open: Vec<Plane>,
    /// The occluders on the body's boundary.
    pub(super) surface: Vec<Occluder>,
    /// Per surface occluder: its support's front, in or out of the body
    /// (`Some(true)`: out), or `None` if the body is on both sides.
    outward: Vec<Option<bool>>,
    /// For a shell: the closed surface around the core (`surface` is then
    /// the core's boundary, not occluders).
    shell: Option<Box<ShellSurface>>,
}

/// Which end of a segment is outside the body, for segments that enter it
/// through a face that end sees (see [`Body::crossings`]).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Entry {
    Light,
    Region,
    Either,
    /// Every segment is blocked (a shell's region inside it).
    Hidden,
}

impl Body {
    /// The body with face planes `faces` and `open` (each with the body
    /// behind it) whose boundary, but for the open faces, the polygons
    /// `surface` cover. `None` when one of them has a corner that is no
    /// grid point.
    pub fn new(faces: Vec<Plane>, open: Vec<Plane>, surface: &[&ConvexPolygon]) -> Option<Self> {
        let surface: Vec<Occluder> = surface
            .iter()
            .map(|p| Occluder::new(p))
            .collect::<Option<_>>()?;
        let outward = surface
            .iter()
            .map(|o| {
                let sides = surface
                    .iter()
                    .flat_map(|other| other.corners.iter())
                    .map(|&p| side_of_point(&o.support, p));
                let (mut front, mut back) = (false, false);
                for side in sides {
                    front |= side == Side::Front;
                    back |= side == Side::Back;
                }
                match (front, back) {
                    (false, true) => Some(true),
                    (true, false) => Some(false),
                    _ => None,
                }
            })
            .collect();
        Some(Self {
            outward,
            bounds: bounds(
                surface
                    .iter()
                    .flat_map(|o| o.corners.iter().map(|p| p.to_f64())),
            ),
            faces,
            open,
            surface,
            shell: None,
        })
    }

    /// The shell (see the type's docs) of a closed `surface` (occluders
    /// and caps over their hole), about a convex core with boundary
    /// polygons `core` (facing out) that lies inside the surface: behind
    /// every face plane of the surface, or where its winding number is
    /// at least 1 (off the surface). `None` when a core polygon has a
    /// corner that is no grid point.
    ///
    /// Why it blocks: the surface's *winding number* about a point off it
    /// counts how many times it wraps the point (faces oriented out); a
    /// segment meets the surface wherever that number changes along it.
    /// It is 0 outside the hull, and at least 1 at a point strictly behind
    /// every face plane (every face turns its back to it), and at every
    /// point of the core off the surface.
    ///
    /// *From outside*: take a segment with both ends outside the hull that
    /// meets the core at `b`, and suppose it meets no occluder. Then every
    /// point where it meets the surface is on a cap, off the occluders
    /// (which hold the hole's rim). Either the segment lies in a cap's
    /// plane, and then it meets the rim (it passes a point of the cap and
    /// ends outside the hull), or it crosses each cap's plane at most
    /// once; the number changes at `b` or between `b` and each end, so
    /// the segment meets the caps at two points or more, in two caps:
    ///
    /// - With no cap (a closed surface, concave or bent by the grid,
    ///   about a core inside it), every point where it meets the surface
    ///   is on an occluder.
    /// - With one cap, that cannot be.
    /// - With several (the two triangles closing a bent hole), when all of
    ///   one end's side (`K` or `L`) lies strictly on one side of every
    ///   cap's plane, the same for all, the segment crosses every cap in
    ///   the same direction, and each crossing changes the number by one
    ///   the same way: it cannot come back to 0 at the other end.
    ///
    /// *From inside* (a region in the cup, or on its walls facing in): take
    /// a point `c` strictly behind every face plane (the number is at
    /// least 1 there). When, for every face, either the region is behind
    /// or on its plane (the light strictly behind it where the region
    /// touches it) or a plane through an edge of the face and `c` keeps
    /// the face behind and the region strictly in front, a segment from
    /// just past any point of the region towards the light to `c` meets
    /// no face: the number is at least 1 there too. With the light
    /// outside the hull, it goes to 0 on the way, so a segment from the
    /// region meets the surface strictly between its ends. When no
    /// segment from the region to the light meets a cap (a plane
    /// separates each cap from them all), that is an occluder. (The
    /// second way serves a wall of a cup the grid left concave: at a
    /// crease it stands in front of the neighbour's plane.)
    ///
    /// So such segments meet an occluder.
    pub fn shell(core: &[&ConvexPolygon], surface: ShellSurface) -> Option<Self> {
        let faces = core.iter().map(|p| *p.support()).collect();
        Some(Self {
            shell: Some(Box::new(surface)),
            ..Self::new(faces, Vec::new(), core)?
        })
    }

    /// For a shell, planes that put all of `region` and of `light` (with
    /// support `light_plane`), and the parts of them a proof takes,
    /// outside its surface's hull when they can (see [`Clearance`]).
    pub(super) fn clearance(
        &self,
        region: &ConvexPolygon,
        light: &[GridPoint],
        light_plane: &Plane,
    ) -> Clearance {
        let Some(shell) = &self.shell else {
            return Clearance::default();
        };
        let region_sides = region_sides(region);
        let light_sides = light_sides(light);
        // Planes through an edge of the light and a corner of the hull.
        let n = light.len();
        let through_edges = (0..n).flat_map(|i| {
            shell
                .corners
                .iter()
                .filter_map(move |&h| Plane::through(light[i], light[(i + 1) % n], h))
        });
        Clearance {
            region: shell.separator(region.support(), region_sides, std::iter::empty()),
            light: shell.separator(light_plane, light_sides, through_edges),
        }
    }

    /// Whether the body is closed: its boundary is all occluders (no open
    /// faces, not a shell).
    pub fn is_closed(&self) -> bool {
        self.open.is_empty() && self.shell.is_none()
    }

    /// When the corners of the light or of the region may enter the body
    /// (see the type's docs), which corner pairs cross one of its
    /// occluders (as [`Self::pair_crossings`]); `None` otherwise.
    pub(super) fn candidate_pairs(
        &self,
        region: &ConvexPolygon,
        light: &[GridPoint],
        clear: Clearance,
    ) -> Option<Pairs> {
        let entry = self.entry(region, light, clear)?;
        let sides = self.surface_sides(region, light);
        Some(
            light
                .iter()
                .enumerate()
                .flat_map(|(j, &l)| {
                    let none: SmallVec<[bool; 8]> = smallvec::smallvec![false; region.len()];
                    self.crossings(region, l, j, &sides, entry, none)
                })
                .collect(),
        )
    }

    /// Which corners are all outside the body and may enter it (see the
    /// type's docs): the light's, else the region's, else none.
    fn entry(
        &self,
        region: &ConvexPolygon,
        light: &[GridPoint],
        clear: Clearance,
    ) -> Option<Entry> {
        let region_sides = region_sides(region);
        let light_sides = light_sides(light);
        if let Some(shell) = &self.shell {
            // The light is outside the core: a segment from it meeting the
            // core enters by a face it sees.
            let region_end = shell.end(region_sides, clear.region.as_ref());
            let light_end = shell.end(light_sides, clear.light.as_ref());
            // A region outside the hull is never inside the surface.
            if !region_end.outside
                && shell.hides_from_inside(region_sides, light, light_end.outside)
            {
                return Some(Entry::Hidden);
            }
            return shell.blocks(region_end, light_end).then_some(Entry::Light);
        }
        if self.enters_from(light_sides) {
            Some(Entry::Light)
        } else if self.enters_from(region_sides) {
            Some(Entry::Region)
        } else {
            None
        }
    }

    /// As [`Occluder::pair_crossings`], a pair crossing when it crosses
    /// one of the body's occluders. When the corners of the region or
    /// those of the light may enter the body (see the type's docs) and
    /// every pair crosses, every segment from `region` to `light` crosses
    /// the body's occluders.
    pub(super) fn pair_crossings(
        &self,
        region: &ConvexPolygon,
        light: &[GridPoint],
        known: &Pairs,
        clear: Clearance,
    ) -> Pairs {
        let entry = self.entry(region, light, clear).unwrap_or(Entry::Either);
        let sides = self.surface_sides(region, light);
        let nk = region.len();
        let mut pairs = Pairs::new();
        for (j, &l) in light.iter().enumerate() {
            let known = SmallVec::from_slice(&known[j * nk..(j + 1) * nk]);
            pairs.extend_from_slice(&self.crossings(region, l, j, &sides, entry, known));
        }
        pairs
    }

    /// The sides of the region's and the light's corners for each surface
    /// polygon's plane.
    fn surface_sides(&self, region: &ConvexPolygon, light: &[GridPoint]) -> Vec<CornerSides> {
        self.surface
            .iter()
            .map(|o| {
                (
                    (0..region.len())
                        .map(|i| region.vertex_side(i, &o.support))
                        .collect(),
                    light
                        .iter()
                        .map(|&p| side_of_point(&o.support, p))
                        .collect(),
                )
            })
            .collect()
    }

    /// For each region corner, whether the segment from it to light corner
    /// `l` (number `j`) crosses a surface polygon, or is known to cross a
    /// blocker (`crossed` on entry: not looked at). A segment from outside
    /// the body that meets it enters through a face its outer end sees, so
    /// with that end known (`entry`) only those faces are tried.
    fn crossings(
        &self,
        region: &ConvexPolygon,
        l: GridPoint,
        j: usize,
        sides: &[CornerSides],
        entry: Entry,
        mut crossed: SmallVec<[bool; 8]>,
    ) -> SmallVec<[bool; 8]> {
        if entry == Entry::Hidden || !crossed.contains(&false) {
            crossed.fill(true);
            return crossed;
        }
        for ((o, (ks, ls)), outward) in self.surface.iter().zip(sides).zip(&self.outward) {
            if ls[j] == Side::On {
                continue;
            }
            // The side a face's outer end must be on.
            let seen_from = match outward {
                Some(true) => Some(Side::Front),
                Some(false) => Some(Side::Back),
                None => None,
            };
            if entry == Entry::Light && seen_from.is_some_and(|s| ls[j] != s) {
                continue;
            }
            // (Filled in place: collecting small flag lists from iterators
            // was a tenth of a dense mesh's proofs.)
            let mut test: SmallVec<[bool; 8]> = SmallVec::from_elem(false, region.len());
            for (i, t) in test.iter_mut().enumerate() {
                *t = !crossed[i]
                    && ks[i] == ls[j].flipped()
                    && !(entry == Entry::Region && seen_from.is_some_and(|s| ks[i] != s));
            }
            if !test.contains(&true) {
                continue;
            }
            for (c, now) in crossed.iter_mut().zip(o.crossings(region, l, &test)) {
                *c |= now;
            }
            if !crossed.contains(&false) {
                break;
            }
        }
        crossed
    }

    /// A test of single light points against `region`, with the region's
    /// part of [`Self::candidate_pairs`] (its sides of every plane) done
    /// once: whether the body may hide the point from all of the region
    /// and every corner's segment to it crosses the body's occluders.
    pub(super) fn point_test<'r>(
        &'r self,
        region: &'r ConvexPolygon,
        clear: Clearance,
    ) -> impl Fn(GridPoint) -> bool + 'r {
        let region_sides = region_sides(region);
        let region_enters = self.enters_from(region_sides);
        let region_end = self
            .shell
            .as_ref()
            .map(|shell| shell.end(region_sides, clear.region.as_ref()));
        let surface: Vec<SmallVec<[Side; 8]>> = self
            .surface
            .iter()
            .map(|o| region_sides(&o.support))
            .collect();
        move |l: GridPoint| {
            let light_sides = |plane: &Plane| [side_of_point(plane, l)];
            let entry = if let (Some(shell), Some(region)) = (&self.shell, region_end) {
                let light = shell.end(light_sides, clear.light.as_ref());
                if !region.outside && shell.hides_from_inside(region_sides, &[l], light.outside) {
                    return true;
                }
                if !shell.blocks(region, light) {
                    return false;
                }
                Entry::Light
            } else if self.enters_from(light_sides) {
                Entry::Light
            } else if region_enters {
                Entry::Region
            } else {
                return false;
            };
            let sides: Vec<CornerSides> = self
                .surface
                .iter()
                .zip(&surface)
                .map(|(o, ks)| {
                    (
                        ks.clone(),
                        smallvec::smallvec![side_of_point(&o.support, l)],
                    )
                })
                .collect();
            let none: SmallVec<[bool; 8]> = smallvec::smallvec![false; region.len()];
            !self
                .crossings(region, l, 0, &sides, entry, none)
                .contains(&false)
        }
    }

    /// Whether the corners whose sides of a plane `sides` gives are all
    /// strictly outside the body (in front of one face) and behind or on
    /// every open face.
    fn enters_from<S: IntoIterator<Item = Side>>(&self, sides: impl Fn(&Plane) -> S) -> bool {
        self.open
            .iter()
            .all(|f| sides(f).into_iter().all(|s| s != Side::Front))
            && self
                .faces
                .iter()
                .any(|f| sides(f).into_iter().all(|s| s == Side::Front))
    }
}

/// The sides of a region's corners and of a light's corners of a plane.
type CornerSides = (SmallVec<[Side; 8]>, SmallVec<[Side; 8]>);

/// The sides of the region's corners of a plane.
fn region_sides(region: &ConvexPolygon) -> impl Fn(&Plane) -> SmallVec<[Side; 8]> + Copy + '_ {
    move |plane| {
        (0..region.len())
            .map(|i| region.vertex_side(i, plane))
            .collect()
    }
}

/// The sides of the light's corners of a plane.
fn light_sides(light: &[GridPoint]) -> impl Fn(&Plane) -> SmallVec<[Side; 8]> + Copy + '_ {
    move |plane| light.iter().map(|&p| side_of_point(plane, p)).collect()
}
