//! The scanline rasterizer on its own: exact coverage with the top-left rule,
//! worked out by hand for small cases and checked against a brute-force
//! edge-function rasterizer, shared edges and vertices, and the interpolation
//! of depth and attributes.

mod common;

use common::*;
use proptest::prelude::*;
use proptest::test_runner::Config;
use shadelab_core::raster::scanline::rasterize_polygon;
use shadelab_core::raster::{FragmentSink, ScreenVertex};
use shadelab_core::Interpolation;

/// Counts fragments per pixel, and insists they fall inside the image.
struct Counter {
    width: u32,
    height: u32,
    counts: Vec<u32>,
}

impl Counter {
    fn new(width: u32, height: u32) -> Counter {
        Counter {
            width,
            height,
            counts: vec![0; (width * height) as usize],
        }
    }
}

impl<const N: usize> FragmentSink<N> for Counter {
    fn fragment(&mut self, x: u32, y: u32, _depth: f32, _attrs: &[f32; N]) {
        assert!(
            x < self.width && y < self.height,
            "fragment ({x}, {y}) outside the image"
        );
        self.counts[(y * self.width + x) as usize] += 1;
    }
}

fn vertex(p: (i64, i64)) -> ScreenVertex<0> {
    ScreenVertex {
        x: p.0,
        y: p.1,
        depth: 0.5,
        inv_w: 1.0,
        attrs: [],
    }
}

/// Draws polygons (snapped units) through the rasterizer, counting fragments.
fn draw(polygons: &[&[(i64, i64)]], width: u32, height: u32) -> Vec<u32> {
    let mut counter = Counter::new(width, height);
    for poly in polygons {
        let poly: Vec<ScreenVertex<0>> = poly.iter().map(|&p| vertex(p)).collect();
        rasterize_polygon(
            &poly,
            width,
            height,
            Interpolation::Perspective,
            &mut counter,
        );
    }
    counter.counts
}

/// Points given in pixels, to snapped units.
fn px(points: &[(f64, f64)]) -> Vec<(i64, i64)> {
    points.iter().map(|&(x, y)| (snap(x), snap(y))).collect()
}

/// A coverage picture: one string per row, `#` covered, `.` not.
fn picture(rows: &[&str]) -> (u32, u32, Vec<u32>) {
    let (w, h) = (rows[0].len() as u32, rows.len() as u32);
    let counts = rows
        .iter()
        .flat_map(|r| r.bytes().map(|b| u32::from(b == b'#')))
        .collect();
    (w, h, counts)
}

fn render_picture(counts: &[u32], width: u32) -> String {
    counts
        .chunks(width as usize)
        .map(|row| {
            row.iter()
                .map(|&c| match c {
                    0 => '.',
                    1 => '#',
                    _ => '2',
                })
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn check_picture(name: &str, polygons: &[Vec<(i64, i64)>], rows: &[&str]) {
    let (w, h, expected) = picture(rows);
    let refs: Vec<&[(i64, i64)]> = polygons.iter().map(|p| p.as_slice()).collect();
    let actual = draw(&refs, w, h);
    assert_eq!(
        actual,
        expected,
        "{name}: rasterizer\n{}\nexpected\n{}",
        render_picture(&actual, w),
        render_picture(&expected, w)
    );
    // The brute-force reference agrees with the hand-derived picture too.
    let mut brute = vec![0; (w * h) as usize];
    for poly in polygons {
        for (b, c) in brute.iter_mut().zip(brute_force_coverage(poly, w, h)) {
            *b += c;
        }
    }
    assert_eq!(
        brute,
        expected,
        "{name}: brute force\n{}",
        render_picture(&brute, w)
    );
}

#[test]
fn top_left_rule_by_hand() {
    // Vertices on pixel centres: the left and top edges are in, the
    // hypotenuse (a right edge) is out, so row j covers i + j < 4.
    let upper = px(&[(0.5, 0.5), (0.5, 4.5), (4.5, 0.5)]);
    check_picture(
        "upper triangle on centres",
        std::slice::from_ref(&upper),
        &[
            "####....", "###.....", "##......", "#.......", "........", "........",
        ],
    );
    // Its complement in the square: the hypotenuse is now a left edge (in),
    // x = 4.5 a right edge and y = 4.5 a bottom edge (both out).
    let lower = px(&[(4.5, 0.5), (0.5, 4.5), (4.5, 4.5)]);
    check_picture(
        "lower triangle on centres",
        std::slice::from_ref(&lower),
        &[
            "........", "...#....", "..##....", ".###....", "........", "........",
        ],
    );
    // Together: the 4 × 4 square of centres in [0.5, 4.5), each exactly once.
    check_picture(
        "square split on its diagonal",
        &[upper, lower],
        &[
            "####....", "####....", "####....", "####....", "........", "........",
        ],
    );
    // Vertices on pixel corners: centres with x + y < 4 (x + y = 4 is on the right edge).
    check_picture(
        "triangle on pixel corners",
        &[px(&[(0.0, 0.0), (0.0, 4.0), (4.0, 0.0)])],
        &["###..", "##...", "#....", ".....", "....."],
    );
    // A quad with vertices on centres: left and top edges in, right and bottom out.
    check_picture(
        "quad on centres",
        &[px(&[(0.5, 0.5), (0.5, 2.5), (2.5, 2.5), (2.5, 0.5)])],
        &["##..", "##..", "....", "...."],
    );
    // Top vertex on a centre: between a left and a right edge, so out; the
    // bottom edge through row 2's centres is out too.
    check_picture(
        "apex on a centre",
        &[px(&[(2.5, 0.5), (0.5, 2.5), (4.5, 2.5)])],
        &[".....", ".##..", ".....", "....."],
    );
    // A diamond with all four vertices on centres: the left vertex (two left
    // edges) is in, the top, right and bottom vertices are out.
    check_picture(
        "diamond on centres",
        &[px(&[(2.5, 0.5), (0.5, 2.5), (2.5, 4.5), (4.5, 2.5)])],
        &[".....", ".##..", "####.", ".##..", "....."],
    );
    // Mostly outside the image: clipped to it, same rule (centres x + y < 8).
    check_picture(
        "beyond the image",
        &[px(&[(-2.0, -2.0), (-2.0, 10.0), (10.0, -2.0)])],
        &["######", "######", "#####.", "####..", "###..."],
    );
    // A sliver between pixel centres covers nothing.
    check_picture(
        "sliver",
        &[px(&[(1.0, 1.0), (1.2, 3.0), (1.4, 1.0)])],
        &["....", "....", "....", "...."],
    );
    // Clockwise and degenerate polygons draw nothing.
    check_picture(
        "clockwise",
        &[px(&[(0.5, 0.5), (4.5, 0.5), (0.5, 4.5)])],
        &[".....", ".....", ".....", ".....", "....."],
    );
    check_picture(
        "collinear",
        &[px(&[(0.5, 0.5), (2.5, 2.5), (4.5, 4.5)])],
        &[".....", ".....", ".....", ".....", "....."],
    );
    // Four triangles around a vertex on a pixel centre: it is covered once.
    let c = (2.5, 2.5);
    let ring = [(2.5, 0.5), (0.5, 2.5), (2.5, 4.5), (4.5, 2.5)];
    let fan: Vec<Vec<(i64, i64)>> = (0..4)
        .map(|k| px(&[c, ring[k], ring[(k + 1) % 4]]))
        .collect();
    check_picture(
        "fan around a centre",
        &fan,
        &[".....", ".##..", "####.", ".##..", "....."],
    );
}

// ---------------------------------------------------------------- properties

const W: u32 = 24;
const H: u32 = 20;

/// A snapped coordinate between `lo` and `hi` pixels; one time in two on a
/// multiple of half a pixel, so that ties with pixel centres are frequent.
fn coord(lo: i64, hi: i64) -> impl Strategy<Value = i64> {
    prop_oneof![
        lo * SUB..hi * SUB,
        (lo * 2..hi * 2).prop_map(|k| k * SUB / 2)
    ]
}

fn point() -> impl Strategy<Value = (i64, i64)> {
    (coord(-6, W as i64 + 6), coord(-6, H as i64 + 6))
}

fn ccw(mut poly: Vec<(i64, i64)>) -> Vec<(i64, i64)> {
    if area2_ccw(&poly) < 0 {
        poly.reverse();
    }
    poly
}

fn config(cases: u32) -> Config {
    Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    }
}

/// Point in a simple polygon by winding number, `None` on its boundary.
fn strictly_inside(poly: &[(i64, i64)], p: (i64, i64)) -> Option<bool> {
    let mut winding = 0;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let cross =
            (b.0 - a.0) as i128 * (p.1 - a.1) as i128 - (p.0 - a.0) as i128 * (b.1 - a.1) as i128;
        let within = p.0 >= a.0.min(b.0)
            && p.0 <= a.0.max(b.0)
            && p.1 >= a.1.min(b.1)
            && p.1 <= a.1.max(b.1);
        if cross == 0 && within {
            return None;
        }
        if a.1 <= p.1 {
            if b.1 > p.1 && cross > 0 {
                winding += 1;
            }
        } else if b.1 <= p.1 && cross < 0 {
            winding -= 1;
        }
    }
    Some(winding != 0)
}

proptest! {
    #![proptest_config(config(2000))]

    /// Any triangle covers exactly the pixels the brute-force edge functions
    /// with the top-left rule give, each once.
    #[test]
    fn triangle_matches_brute_force(a in point(), b in point(), c in point()) {
        let tri = ccw(vec![a, b, c]);
        let actual = draw(&[&tri], W, H);
        let expected = brute_force_coverage(&tri, W, H);
        prop_assert_eq!(&actual, &expected, "{:?}\n{}\nexpected\n{}", tri, render_picture(&actual, W), render_picture(&expected, W));
    }
}

proptest! {
    #![proptest_config(config(1000))]

    /// A convex quad split along either diagonal: no pixel twice, no gap along
    /// the shared edge, the same pixels as the quad drawn whole.
    #[test]
    fn quad_split_on_a_diagonal_is_watertight(a in point(), b in point(), c in point(), d in point()) {
        let quad = convex_hull(&[a, b, c, d]);
        prop_assume!(quad.len() == 4);
        let whole = draw(&[&quad], W, H);
        prop_assert_eq!(&whole, &brute_force_coverage(&quad, W, H));
        for k in 0..2 {
            let (p, q, r, s) = (quad[k], quad[k + 1], quad[k + 2], quad[(k + 3) % 4]);
            let split = draw(&[&[p, q, r], &[p, r, s]], W, H);
            prop_assert!(split.iter().all(|&n| n <= 1), "overlap\n{}", render_picture(&split, W));
            prop_assert_eq!(&split, &whole, "{:?}\nsplit\n{}\nwhole\n{}", quad, render_picture(&split, W), render_picture(&whole, W));
        }
    }

    /// A convex polygon (with collinear points now and then) drawn whole covers
    /// exactly the pixels of its fan of triangles, and of the brute force.
    #[test]
    fn convex_polygon_equals_its_fan(points in prop::collection::vec(point(), 3..12), midpoints in any::<bool>()) {
        let mut poly = convex_hull(&points);
        prop_assume!(poly.len() >= 3);
        if midpoints {
            // Put a vertex in the middle of each edge where that is exact.
            let mut with = Vec::new();
            for i in 0..poly.len() {
                let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
                with.push(a);
                if (a.0 + b.0) % 2 == 0 && (a.1 + b.1) % 2 == 0 {
                    with.push(((a.0 + b.0) / 2, (a.1 + b.1) / 2));
                }
            }
            poly = with;
        }
        let whole = draw(&[&poly], W, H);
        prop_assert_eq!(&whole, &brute_force_coverage(&poly, W, H), "{:?}", poly);
        let triangles: Vec<Vec<(i64, i64)>> = (1..poly.len() - 1).map(|k| vec![poly[0], poly[k], poly[k + 1]]).collect();
        let refs: Vec<&[(i64, i64)]> = triangles.iter().map(|t| t.as_slice()).collect();
        let fan = draw(&refs, W, H);
        prop_assert!(fan.iter().all(|&n| n <= 1), "overlap\n{}", render_picture(&fan, W));
        prop_assert_eq!(&fan, &whole, "{:?}\nfan\n{}\nwhole\n{}", poly, render_picture(&fan, W), render_picture(&whole, W));
    }

    /// A fan of triangles around a hub (a star-shaped polygon, often not
    /// convex): every pixel centre strictly inside is covered exactly once,
    /// spokes and hub included; outside nothing is.
    #[test]
    fn triangle_fan_is_watertight(
        hub in (coord(2, W as i64 - 2), coord(2, H as i64 - 2)),
        spokes in prop::collection::vec((0.3f64..1.0, 1.0f64..16.0, any::<bool>()), 3..12),
    ) {
        let total: f64 = spokes.iter().map(|s| s.0).sum();
        let gaps: Vec<f64> = spokes.iter().map(|s| s.0 / total * std::f64::consts::TAU).collect();
        prop_assume!(gaps.iter().all(|&g| g < std::f64::consts::PI - 0.05));
        let mut angle = 0.0;
        let rim: Vec<(i64, i64)> = spokes
            .iter()
            .zip(&gaps)
            .map(|(&(_, radius, half), &gap)| {
                angle += gap;
                // Whole or half pixels now and then, for ties.
                let r = if half { (radius * 2.0).round() / 2.0 } else { radius };
                (hub.0 + snap(r * angle.cos()), hub.1 - snap(r * angle.sin()))
            })
            .collect();
        let triangles: Vec<Vec<(i64, i64)>> =
            (0..rim.len()).map(|k| vec![hub, rim[k], rim[(k + 1) % rim.len()]]).collect();
        prop_assume!(triangles.iter().all(|t| area2_ccw(t) > 0));
        let refs: Vec<&[(i64, i64)]> = triangles.iter().map(|t| t.as_slice()).collect();
        let counts = draw(&refs, W, H);
        for j in 0..H {
            for i in 0..W {
                let n = counts[(j * W + i) as usize];
                let expected = match strictly_inside(&rim, centre(i.into(), j.into())) {
                    Some(true) => 1..=1,
                    Some(false) => 0..=0,
                    None => 0..=1,
                };
                prop_assert!(expected.contains(&n), "pixel ({}, {}) covered {} times; hub {:?} rim {:?}\n{}", i, j, n, hub, rim, render_picture(&counts, W));
            }
        }
    }
}

/// Records every fragment with its attributes.
struct Recorder<const N: usize> {
    fragments: Vec<(u32, u32, f32, [f32; N])>,
}

impl<const N: usize> FragmentSink<N> for Recorder<N> {
    fn fragment(&mut self, x: u32, y: u32, depth: f32, attrs: &[f32; N]) {
        self.fragments.push((x, y, depth, *attrs));
    }
}

proptest! {
    #![proptest_config(config(500))]

    /// Depth is linear in window space; attributes are too in screen mode, and
    /// attribute/w and 1/w are in perspective mode. Checked per fragment against
    /// 2D barycentrics of the snapped vertices.
    #[test]
    fn interpolation_matches_barycentrics(
        a in point(), b in point(), c in point(),
        values in prop::array::uniform3((0.0f32..1.0, 0.05f32..2.0, -10.0f32..10.0, -10.0f32..10.0)),
    ) {
        let tri = ccw(vec![a, b, c]);
        prop_assume!(area2_ccw(&tri) > 0);
        // After ccw() the vertex order may have changed: pair values with points by position.
        let verts: Vec<ScreenVertex<2>> = tri
            .iter()
            .zip(values)
            .map(|(&(x, y), (depth, inv_w, s, t))| ScreenVertex { x, y, depth, inv_w, attrs: [s, t] })
            .collect();
        for interpolation in [Interpolation::Perspective, Interpolation::Screen] {
            let mut rec = Recorder { fragments: Vec::new() };
            rasterize_polygon(&verts, W, H, interpolation, &mut rec);
            let brute = brute_force_coverage(&tri, W, H);
            prop_assert_eq!(rec.fragments.len() as u32, brute.iter().sum::<u32>());
            let total = area2_ccw(&tri) as f64;
            for &(x, y, depth, attrs) in &rec.fragments {
                let p = centre(x.into(), y.into());
                // Barycentric weight of vertex k: the sub-triangle opposite it.
                let weight = |k: usize| {
                    let (u, v) = (tri[(k + 1) % 3], tri[(k + 2) % 3]);
                    area2_ccw(&[p, u, v]) as f64 / total
                };
                let w = [weight(0), weight(1), weight(2)];
                prop_assert!(w.iter().all(|&x| x >= -1e-12), "fragment outside: {:?}", w);
                let lin = |f: &dyn Fn(&ScreenVertex<2>) -> f64| (0..3).map(|k| w[k] * f(&verts[k])).sum::<f64>();
                let exp_depth = lin(&|v| v.depth.into());
                prop_assert!((f64::from(depth) - exp_depth).abs() < 1e-5, "depth {} vs {}", depth, exp_depth);
                for (m, &got) in attrs.iter().enumerate() {
                    let expected = match interpolation {
                        Interpolation::Screen => lin(&|v| v.attrs[m].into()),
                        Interpolation::Perspective => {
                            lin(&|v| f64::from(v.attrs[m]) * f64::from(v.inv_w)) / lin(&|v| v.inv_w.into())
                        }
                    };
                    prop_assert!(
                        (f64::from(got) - expected).abs() < 1e-4,
                        "{:?} attribute {} at ({}, {}): {} vs {}", interpolation, m, x, y, got, expected
                    );
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(config(500))]

    /// Convex polygons are walked whole, not split: an attribute that is
    /// affine in window space (screen mode), or whose attribute/w and 1/w are
    /// (perspective mode), comes out exact at every fragment.
    #[test]
    fn polygon_interpolation_of_affine_attributes(
        points in prop::collection::vec(point(), 4..10),
        q in (0.2f64..1.0, -0.01f64..0.01, -0.01f64..0.01),
        r in (-5.0f64..5.0, -0.3f64..0.3, -0.3f64..0.3),
        z in (0.2f64..0.8, -0.005f64..0.005, -0.005f64..0.005),
    ) {
        let poly = convex_hull(&points);
        prop_assume!(poly.len() >= 4);
        let affine = |c: (f64, f64, f64), x: f64, y: f64| c.0 + c.1 * x + c.2 * y;
        let at = |p: (i64, i64)| (p.0 as f64 / SUB as f64 - W as f64 / 2.0, p.1 as f64 / SUB as f64 - H as f64 / 2.0);
        for interpolation in [Interpolation::Perspective, Interpolation::Screen] {
            let verts: Vec<ScreenVertex<1>> = poly
                .iter()
                .map(|&p| {
                    let (x, y) = at(p);
                    let inv_w = affine(q, x, y);
                    let attr = match interpolation {
                        Interpolation::Perspective => affine(r, x, y) / inv_w,
                        Interpolation::Screen => affine(r, x, y),
                    };
                    ScreenVertex { x: p.0, y: p.1, depth: affine(z, x, y) as f32, inv_w: inv_w as f32, attrs: [attr as f32] }
                })
                .collect();
            let mut rec = Recorder { fragments: Vec::new() };
            rasterize_polygon(&verts, W, H, interpolation, &mut rec);
            prop_assert_eq!(rec.fragments.len() as u32, brute_force_coverage(&poly, W, H).iter().sum::<u32>());
            for &(i, j, depth, [attr]) in &rec.fragments {
                let (x, y) = at(centre(i.into(), j.into()));
                let expected = match interpolation {
                    Interpolation::Perspective => affine(r, x, y) / affine(q, x, y),
                    Interpolation::Screen => affine(r, x, y),
                };
                let scale = 1.0 + expected.abs();
                prop_assert!((f64::from(attr) - expected).abs() < 1e-4 * scale, "{:?} at ({}, {}): {} vs {}", interpolation, i, j, attr, expected);
                prop_assert!((f64::from(depth) - affine(z, x, y)).abs() < 1e-5);
            }
        }
    }
}

/// Coverage of a simple polygon by the winding number of each pixel centre:
/// the fan from its first vertex, counter-clockwise triangles counted +1 and
/// clockwise ones −1, each by the brute-force top-left rule on its
/// counter-clockwise version (the rule is a consistent tie-break, so the sum
/// is the winding number at every centre).
fn winding_coverage(poly: &[(i64, i64)], width: u32, height: u32) -> Vec<i32> {
    let mut out = vec![0i32; (width * height) as usize];
    for k in 1..poly.len() - 1 {
        let tri = vec![poly[0], poly[k], poly[k + 1]];
        let sign = area2_ccw(&tri).signum() as i32;
        let ccw_tri = ccw(tri);
        for (o, c) in out
            .iter_mut()
            .zip(brute_force_coverage(&ccw_tri, width, height))
        {
            *o += sign * c as i32;
        }
    }
    out
}

proptest! {
    #![proptest_config(config(1000))]

    /// A convex polygon with one vertex pushed in (as snapping does to nearly
    /// straight corners, only more): still drawn exactly, each pixel once.
    #[test]
    fn dented_polygon_is_drawn_exactly(points in prop::collection::vec(point(), 4..10), which in any::<prop::sample::Index>(), depth in 0.05f64..1.0) {
        let mut poly = convex_hull(&points);
        prop_assume!(poly.len() >= 4);
        let n = poly.len();
        let c = poly.iter().fold((0i64, 0i64), |s, p| (s.0 + p.0, s.1 + p.1));
        let c = (c.0 as f64 / n as f64, c.1 as f64 / n as f64);
        let i = which.index(n);
        let p = poly[i];
        // Towards the centroid: the polygon stays star-shaped around it, so simple.
        poly[i] = ((p.0 as f64 + (c.0 - p.0 as f64) * depth).round() as i64, (p.1 as f64 + (c.1 - p.1 as f64) * depth).round() as i64);
        prop_assume!(area2_ccw(&poly) > 0);
        // Every rotation of the vertex list: the dent next to the first vertex too.
        for r in 0..n {
            let rotated: Vec<(i64, i64)> = (0..n).map(|k| poly[(k + r) % n]).collect();
            let expected = winding_coverage(&rotated, W, H);
            prop_assert!(expected.iter().all(|&w| w == 0 || w == 1), "not simple: {:?}", rotated);
            let actual = draw(&[&rotated], W, H);
            let expected: Vec<u32> = expected.iter().map(|&w| w as u32).collect();
            prop_assert_eq!(&actual, &expected, "{:?}\n{}\nexpected\n{}", rotated, render_picture(&actual, W), render_picture(&expected, W));
        }
    }
}
