//! Making an object's pieces: its polygons, and the bodies they form,
//! with the volumes and discontinuity planes each casts.
//!
//! The pieces are made first, from the polygons and the lights alone
//! ([`DmScene::prepare`]: nothing in the scene changes, so a build makes
//! every object's side by side, and an object's own polygons and bodies
//! are made side by side too), then enter the scene in the order made
//! ([`DmScene::commit`]: keys, receivers and overlap entries, the same
//! whatever the number of threads). A move takes the object's old units
//! out of the receivers while its new pieces are made (module `update`).

use super::contact::ContactPlanes;
use super::silhouette::SolidCorners;
use super::{DmScene, Member, ObjectId, Piece, PieceId, PieceKind, bounds_of};
use crate::critical::{UnitPlanes, body_internal_planes, internal_planes};
use crate::illuminate::ReceiverIllum;
use crate::surface::{Surroundings, surroundings};
use crate::tree::ReceiverDm;
use area_shadow::{
    AreaSource, ConvexGroup, FlatUnion, SourceSide, VolumePlanes, closed_parts, convex_groups,
    flat_unions, section_unions, volume_planes,
};
use bsp_core::{ConvexPolygon, Plane};
use rayon::prelude::*;
use svbsp::PieceFlags;

/// An object's pieces, made and not yet in the scene.
pub(super) struct Prepared {
    /// Its polygons' pieces, in order, with their empty receivers.
    polygons: Vec<(Piece, ReceiverDm<PieceId>)>,
    /// Its convex bodies, each with its polygons (indices into `polygons`).
    bodies: Vec<(Piece, Vec<u32>)>,
    /// The bodies of umbrae its polygons make only together
    /// ([`DmScene::umbra_part_bodies`]), likewise.
    parts: Vec<(Piece, Vec<u32>)>,
    /// The groups its polygons form, for the joints ([`DmScene::list_planes`]).
    groups: Vec<ConvexGroup>,
}

/// A body's penumbra volume under a light if it casts in place of its
/// polygons, and its umbra volume if it has one.
type BodyVolumes = (Option<Vec<Plane>>, Option<Vec<Plane>>);

/// A body of an object's polygons (convex, or a part of a flat union's
/// umbra), as [`DmScene::body_piece`] makes its occluder from it.
pub(super) struct BodyCast<'a> {
    /// Each polygon's plane, facing out of the body (a flat one's as it
    /// is).
    pub(super) outward: Vec<Plane>,
    /// Its polygons, with their surroundings when internal discontinuities
    /// are made.
    pub(super) members: &'a [(&'a ConvexPolygon, Option<&'a Surroundings>)],
    /// Per light, its volumes.
    pub(super) volumes: Vec<BodyVolumes>,
    /// Whether the polygons are the whole boundary of a convex polyhedron.
    pub(super) solid: bool,
}

impl<'a> BodyCast<'a> {
    /// A body that casts only an umbra: under each light the `i`-th convex
    /// part of its umbra (`parts`, per light), none where that light's has
    /// fewer.
    pub(super) fn umbra_part(
        outward: Vec<Plane>,
        members: &'a [(&'a ConvexPolygon, Option<&'a Surroundings>)],
        parts: &[Vec<Vec<Plane>>],
        i: usize,
    ) -> Self {
        Self {
            outward,
            members,
            volumes: parts.iter().map(|p| (None, p.get(i).cloned())).collect(),
            solid: false,
        }
    }
}

impl DmScene {
    /// Makes the pieces of object `id`'s polygons (validated: their
    /// vertices are grid points, [`Self::validate`]) and of the bodies
    /// they form, leaving the scene as it is.
    pub(super) fn prepare(
        &self,
        id: ObjectId,
        polygons: Vec<ConvexPolygon>,
        flags: PieceFlags,
    ) -> Prepared {
        let sources: Vec<AreaSource> = self.lights.iter().map(|l| l.source.clone()).collect();
        let casts = flags.casts_shadows;
        let one = vec![Some(0); polygons.len()];
        // The polygons' surroundings, convex groups, flat unions and
        // closed faces, found side by side: each walks all the polygons
        // (one after another, a tenth of moving an office desk).
        let ((surface, groups), (unions, closed)) = rayon::join(
            || {
                rayon::join(
                    || {
                        if casts && self.options.internal_discontinuities {
                            surroundings(&polygons)
                        } else {
                            Vec::new()
                        }
                    },
                    || {
                        if casts {
                            convex_groups(&polygons, &one)
                        } else {
                            Vec::new()
                        }
                    },
                )
            },
            || {
                rayon::join(
                    || {
                        if casts {
                            let mut unions = flat_unions(&polygons, &one);
                            unions.extend(section_unions(&polygons, &one));
                            unions
                        } else {
                            Vec::new()
                        }
                    },
                    || closed_faces(&polygons, flags, &sources),
                )
            },
        );
        // Per body and light, its umbra volume, and its penumbra volume
        // where it casts in place of its polygons (never without an umbra:
        // cells where it hides all of the light must be umbra); per
        // polygon, the lights its body casts for it.
        let volumes: Vec<Vec<BodyVolumes>> = groups
            .par_iter()
            .map(|body| {
                sources
                    .iter()
                    .map(|light| {
                        let umbra = body.umbra_planes(light);
                        let penumbra = (self.options.convex_bodies && umbra.is_some())
                            .then(|| body.penumbra_planes(light))
                            .flatten();
                        (penumbra, umbra)
                    })
                    .collect()
            })
            .collect();
        let mut in_body = vec![0_u32; polygons.len()];
        for (body, volumes) in groups.iter().zip(&volumes) {
            let whole = light_mask(volumes.iter().map(|(penumbra, _)| penumbra.is_some()));
            for &k in &body.pieces {
                in_body[k as usize] |= whole;
            }
        }
        let pieces: Vec<(Piece, ReceiverDm<PieceId>)> = polygons
            .par_iter()
            .enumerate()
            .map(|(i, polygon)| {
                let volumes = if flags.casts_shadows {
                    self.polygon_units(polygon, closed[i], in_body[i], surface.get(i), &sources)
                } else {
                    vec![UnitPlanes::default(); sources.len()]
                };
                let outline = polygon.vertices_f64();
                let receiver = ReceiverDm::new(polygon.clone(), flags.two_sided, &sources);
                let piece = Piece {
                    polygon: polygon.clone(),
                    kind: PieceKind::Polygon,
                    object: id,
                    flags,
                    volumes,
                    bounds: bounds_of(&outline),
                    outline,
                    members: Vec::new(),
                    whole: 0,
                    solid: false,
                    corners: None,
                    movable: self.objects[id].movable,
                };
                (piece, receiver)
            })
            .collect();
        let bodies: Vec<(Piece, Vec<u32>)> = groups
            .par_iter()
            .zip(volumes)
            .map(|(body, volumes)| {
                let members: Vec<(&ConvexPolygon, Option<&Surroundings>)> = body
                    .pieces
                    .iter()
                    .map(|&k| (&polygons[k as usize], surface.get(k as usize)))
                    .collect();
                let cast = BodyCast {
                    outward: members
                        .iter()
                        .map(|(polygon, _)| body.outward(polygon.support()))
                        .collect(),
                    members: &members,
                    volumes,
                    solid: body.is_closed_convex(),
                };
                (
                    self.body_piece(id, flags, cast, &sources),
                    body.pieces.clone(),
                )
            })
            .collect();
        let parts = self.umbra_part_bodies(id, flags, &polygons, &groups, &unions, &sources);
        Prepared {
            polygons: pieces,
            bodies,
            parts,
            groups,
        }
    }

    /// Puts object `id`'s pieces made by [`Self::prepare`] in the scene;
    /// returns them (receivers first).
    pub(super) fn commit(&mut self, id: ObjectId, prepared: Prepared) -> Vec<PieceId> {
        let Prepared {
            polygons,
            bodies,
            parts,
            groups,
        } = prepared;
        let mut added = Vec::with_capacity(polygons.len() + bodies.len() + parts.len());
        for (piece, receiver) in polygons {
            let key = self.pieces.insert(piece);
            self.receivers.insert(key, receiver);
            self.changed_at.insert(key, self.revision);
            self.illum.insert(key, ReceiverIllum::default());
            self.contacts.insert(key, ContactPlanes::default());
            self.unlit.insert(key);
            self.overlap.insert(key, &self.pieces[key], true);
            added.push(key);
        }
        self.objects[id].pieces.extend(&added);
        let mut insert = |(piece, members): (Piece, Vec<u32>)| {
            self.insert_body(piece, members.iter().map(|&k| added[k as usize]))
        };
        let made: Vec<PieceId> = bodies.into_iter().map(&mut insert).collect();
        let parts: Vec<PieceId> = parts.into_iter().map(&mut insert).collect();
        self.objects[id].bodies.extend(&made);
        self.objects[id].bodies.extend(&parts);
        self.list_planes(id, groups);
        added.extend(parts);
        added.extend(made);
        added
    }

    /// The bodies of the object's polygons for the umbrae they make only
    /// together that are no convex volume: of a flat union that is no
    /// convex polygon (`unions`: [`flat_unions`], [`section_unions`]), of a body that holds a light in,
    /// and of one a face short ([`ConvexGroup::umbra_parts`]). Each convex
    /// part of such an umbra is a body of the polygons (indices into
    /// `polygons`) with only that umbra.
    fn umbra_part_bodies(
        &self,
        id: ObjectId,
        flags: PieceFlags,
        polygons: &[ConvexPolygon],
        bodies: &[ConvexGroup],
        unions: &[FlatUnion],
        sources: &[AreaSource],
    ) -> Vec<(Piece, Vec<u32>)> {
        // Per group: its pieces, per light its umbra's parts, and each
        // piece's plane facing out (a flat union's as it is).
        let umbra = |pieces: &'_ [u32],
                     parts: &dyn Fn(&AreaSource) -> Vec<Vec<Plane>>,
                     outward: &dyn Fn(&Plane) -> Plane| {
            let parts: Vec<Vec<Vec<Plane>>> = sources.iter().map(parts).collect();
            let outward: Vec<Plane> = pieces
                .iter()
                .map(|&k| outward(polygons[k as usize].support()))
                .collect();
            (pieces.to_vec(), parts, outward)
        };
        let of_bodies = bodies.iter().map(|body| {
            umbra(&body.pieces, &|light| body.umbra_parts(light), &|s| {
                body.outward(s)
            })
        });
        let of_unions = unions
            .iter()
            .map(|union| umbra(&union.pieces, &|light| union.umbra_parts(light), &|s| *s));
        let umbrae: Vec<_> = of_bodies.chain(of_unions).collect();
        let mut made = Vec::new();
        for (pieces, parts, outward) in umbrae {
            let members: Vec<(&ConvexPolygon, Option<&Surroundings>)> = pieces
                .iter()
                .map(|&k| (&polygons[k as usize], None))
                .collect();
            // Per light its parts; body `i` takes each light's `i`-th.
            let count = parts.iter().map(Vec::len).max().unwrap_or(0);
            for i in 0..count {
                let cast = BodyCast::umbra_part(outward.clone(), &members, &parts, i);
                made.push((self.body_piece(id, flags, cast, sources), pieces.clone()));
            }
        }
        made
    }

    /// What a polygon of a shadow-casting object casts under each light:
    /// nothing under a light it is turned away from when `closed` (a face
    /// of a closed surface facing out that no light lies in), nor under a
    /// light whose bit `in_body` sets (its body casts in its place), else
    /// its own volumes and internal discontinuities (given its
    /// surroundings).
    fn polygon_units(
        &self,
        polygon: &ConvexPolygon,
        closed: bool,
        in_body: u32,
        around: Option<&Surroundings>,
        sources: &[AreaSource],
    ) -> Vec<UnitPlanes> {
        sources
            .iter()
            .enumerate()
            .map(|(l, light)| {
                let turned_away = closed
                    && matches!(
                        light.side_of(polygon.support()),
                        SourceSide::Back | SourceSide::In
                    );
                if turned_away || in_body & (1 << l) != 0 {
                    return UnitPlanes::default();
                }
                let volumes = volume_planes(polygon, light);
                let internal = match around {
                    Some(around) => internal_planes(polygon, light, &volumes, around),
                    None => Vec::new(),
                };
                UnitPlanes::new(volumes, internal)
            })
            .collect()
    }

    /// The occluder of a body of object `id`'s polygons; its members'
    /// pieces are left unset ([`PieceId::default`]), for
    /// [`Self::insert_body`] to name.
    pub(super) fn body_piece(
        &self,
        id: ObjectId,
        flags: PieceFlags,
        cast: BodyCast,
        sources: &[AreaSource],
    ) -> Piece {
        let BodyCast {
            outward,
            members,
            volumes: body_volumes,
            solid,
        } = cast;
        // The lights with some area in front of each member's outward
        // plane.
        let facing: Vec<u32> = outward
            .iter()
            .map(|plane| {
                light_mask(sources.iter().map(|light| {
                    !matches!(light.side_of(plane), SourceSide::Back | SourceSide::In)
                }))
            })
            .collect();
        let whole = light_mask(body_volumes.iter().map(|(penumbra, _)| penumbra.is_some()));
        let volumes = sources
            .iter()
            .zip(body_volumes)
            .enumerate()
            .map(|(l, (light, found))| match found {
                (Some(penumbra), umbra @ Some(_)) => {
                    let volumes = VolumePlanes {
                        penumbra: [penumbra].into_iter().collect(),
                        umbra,
                    };
                    let lit: Vec<(&ConvexPolygon, &Surroundings)> = members
                        .iter()
                        .zip(&facing)
                        .filter(|(_, f)| *f & (1 << l) != 0)
                        .filter_map(|((polygon, around), _)| Some((*polygon, (*around)?)))
                        .collect();
                    let internal = body_internal_planes(&lit, light, &volumes);
                    UnitPlanes::new(volumes, internal)
                }
                // All of the region is umbra: penumbra and umbra planes
                // alike.
                (_, Some(planes)) => UnitPlanes::new(
                    VolumePlanes {
                        penumbra: [planes.clone()].into_iter().collect(),
                        umbra: Some(planes),
                    },
                    Vec::new(),
                ),
                (_, None) => UnitPlanes::default(),
            })
            .collect();
        let faces: Vec<Vec<[f64; 3]>> = members
            .iter()
            .map(|(polygon, _)| polygon.vertices_f64())
            .collect();
        // A solid's faces counter-clockwise seen from outside: reversed
        // where the outward plane is the polygon's turned.
        let corners = if solid {
            let outside: Vec<Vec<[f64; 3]>> = faces
                .iter()
                .zip(members)
                .zip(&outward)
                .map(|((corners, (polygon, _)), outward)| {
                    let mut corners = corners.clone();
                    if polygon.support() != outward {
                        corners.reverse();
                    }
                    corners
                })
                .collect();
            SolidCorners::new(outside.iter().map(Vec::as_slice))
        } else {
            None
        };
        let outline: Vec<[f64; 3]> = faces.into_iter().flatten().collect();
        Piece {
            polygon: members[0].0.clone(),
            kind: PieceKind::Body,
            object: id,
            flags,
            volumes,
            bounds: bounds_of(&outline),
            outline,
            members: outward
                .into_iter()
                .zip(facing)
                .map(|(outward, facing)| Member {
                    piece: PieceId::default(),
                    outward,
                    facing,
                })
                .collect(),
            whole,
            solid,
            corners,
            movable: self.objects[id].movable,
        }
    }

    /// Puts a body's piece in the scene, its members' pieces named by
    /// `members`, in order.
    pub(super) fn insert_body(
        &mut self,
        mut piece: Piece,
        members: impl IntoIterator<Item = PieceId>,
    ) -> PieceId {
        for (member, key) in piece.members.iter_mut().zip(members) {
            member.piece = key;
        }
        let key = self.pieces.insert(piece);
        self.overlap.insert(key, &self.pieces[key], false);
        key
    }
}

/// Per polygon, whether it is a face of a closed surface facing out that
/// no light lies on or in: such faces turned away from a light cast
/// nothing. The object's closed parts, when its flags say it has some (the
/// whole object, or a mesh and a floor in one); a part some light is not
/// clear of casts every face under every light, as the flag's meaning asks
/// ("no light lies in it"), so that an object of several parts casts as
/// its parts would as objects of their own. Decided as the object is
/// added, so a move into a light decides again.
fn closed_faces(
    polygons: &[ConvexPolygon],
    flags: PieceFlags,
    sources: &[AreaSource],
) -> Vec<bool> {
    let mut closed = vec![false; polygons.len()];
    if flags.closed_surface && flags.casts_shadows {
        for part in closed_parts(polygons, &vec![0; polygons.len()]) {
            let corners = part.corners(polygons);
            if part.six_volume > 0 && sources.iter().all(|light| light.clear_of(&corners)) {
                for &k in &part.pieces {
                    closed[k as usize] = true;
                }
            }
        }
    }
    closed
}

/// One bit per light, set where `set` holds.
fn light_mask(set: impl Iterator<Item = bool>) -> u32 {
    set.enumerate()
        .filter(|(_, on)| *on)
        .fold(0, |mask, (l, _)| mask | 1 << l)
}
