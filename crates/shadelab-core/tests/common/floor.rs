//! A floor quad to the horizon and the pixels a convex polygon must cover,
//! from pixel rays (the clipping and extreme-coordinate tests).

use glam::{DVec3, Vec3};
use shadelab_core::Mesh;

use super::{CountRange, View};

/// A floor quad y = −1, x in ±`half_width`, z in ±`depth`, seen by a
/// camera at the origin: as one quad and as two triangles.
pub fn floor(half_width: f32, depth: f32) -> [Mesh; 2] {
    let positions = vec![
        Vec3::new(-half_width, -1.0, depth),
        Vec3::new(half_width, -1.0, depth),
        Vec3::new(half_width, -1.0, -depth),
        Vec3::new(-half_width, -1.0, -depth),
    ];
    [
        Mesh::from_polygons(positions.clone(), [[0u32, 1, 2, 3]]).unwrap(),
        Mesh::from_polygons(positions, [[0u32, 1, 2], [0, 2, 3]]).unwrap(),
    ]
}

/// Expected coverage of a convex planar polygon: pixel rays that meet its
/// plane inside it, at a view depth between near and far. Pixels within
/// `margin` pixels of a change (probed around the centre) are not checked.
pub fn polygon_expectation(
    view: &View,
    polygon: Vec<DVec3>,
    margin: f64,
) -> impl Fn(u32, u32) -> Option<CountRange> + '_ {
    let normal = (polygon[1] - polygon[0]).cross(polygon[2] - polygon[0]);
    let covered = move |x: f64, y: f64| {
        let Some((t, p)) = view.hit_plane(x, y, polygon[0], normal) else {
            return false;
        };
        let n = polygon.len();
        t >= view.near
            && t <= view.far
            && (0..n).all(|k| {
                (polygon[(k + 1) % n] - polygon[k])
                    .cross(p - polygon[k])
                    .dot(normal)
                    >= 0.0
            })
    };
    move |i, j| {
        let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
        let centre = covered(x, y);
        let stable = (0..16).all(|k| {
            let a = f64::from(k) * std::f64::consts::TAU / 16.0;
            covered(x + margin * a.cos(), y + margin * a.sin()) == centre
        });
        stable.then_some(if centre { 1..=1 } else { 0..=0 })
    }
}

pub fn floor_corners(half_width: f64, depth: f64) -> Vec<DVec3> {
    vec![
        DVec3::new(-half_width, -1.0, depth),
        DVec3::new(half_width, -1.0, depth),
        DVec3::new(half_width, -1.0, -depth),
        DVec3::new(-half_width, -1.0, -depth),
    ]
}
