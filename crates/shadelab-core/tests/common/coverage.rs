//! Coverage by brute force: twice the signed area, edge functions with the
//! top-left rule, pixel centres, and the convex hull, all in exact integer
//! arithmetic on snapped window coordinates.

#![allow(dead_code)]

use super::SUB;

/// Twice the signed area of a window polygon (snapped units), positive when
/// the viewer sees it counter-clockwise (window y points down).
pub fn area2_ccw(poly: &[(i64, i64)]) -> i128 {
    let n = poly.len();
    let mut sum = 0i128;
    for i in 0..n {
        let (ax, ay) = poly[i];
        let (bx, by) = poly[(i + 1) % n];
        sum += ax as i128 * by as i128 - bx as i128 * ay as i128;
    }
    -sum
}

/// The edge function of `a → b` at `p`: positive on the inside of a polygon
/// wound counter-clockwise as seen (window y down), zero on the edge's line.
pub fn edge_function(a: (i64, i64), b: (i64, i64), p: (i64, i64)) -> i128 {
    (b.1 - a.1) as i128 * (p.0 - a.0) as i128 - (b.0 - a.0) as i128 * (p.1 - a.1) as i128
}

/// An edge whose points belong to the polygon under the top-left rule: a left
/// edge (it runs down the screen) or a top edge (horizontal, running left).
pub fn is_top_left(a: (i64, i64), b: (i64, i64)) -> bool {
    b.1 > a.1 || (b.1 == a.1 && b.0 < a.0)
}

/// Brute-force coverage of a convex polygon wound counter-clockwise as seen:
/// is the point `p` (snapped units) inside, with the top-left rule on ties?
pub fn covers(poly: &[(i64, i64)], p: (i64, i64)) -> bool {
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if a == b {
            continue;
        }
        let e = edge_function(a, b, p);
        if e < 0 || (e == 0 && !is_top_left(a, b)) {
            return false;
        }
    }
    true
}

/// The centre of pixel (`i`, `j`) in snapped units.
pub fn centre(i: i64, j: i64) -> (i64, i64) {
    (i * SUB + SUB / 2, j * SUB + SUB / 2)
}

/// The pixels of a `width` × `height` image a convex CCW polygon covers, by brute force.
pub fn brute_force_coverage(poly: &[(i64, i64)], width: u32, height: u32) -> Vec<u32> {
    let mut out = vec![0; (width * height) as usize];
    if poly.len() < 3 || area2_ccw(poly) <= 0 {
        return out;
    }
    for j in 0..height {
        for i in 0..width {
            if covers(poly, centre(i.into(), j.into())) {
                out[(j * width + i) as usize] = 1;
            }
        }
    }
    out
}

/// The smallest signed distance, in pixels, from a window point to the edges'
/// lines of a convex CCW polygon given in snapped units: positive inside.
pub fn inside_distance(poly: &[(i64, i64)], x: f64, y: f64) -> f64 {
    let n = poly.len();
    let (x, y) = (x * SUB as f64, y * SUB as f64);
    let mut min = f64::INFINITY;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if a == b {
            continue;
        }
        let (ax, ay, bx, by) = (a.0 as f64, a.1 as f64, b.0 as f64, b.1 as f64);
        let len = (bx - ax).hypot(by - ay);
        let e = ((by - ay) * (x - ax) - (bx - ax) * (y - ay)) / len;
        min = min.min(e / SUB as f64);
    }
    min
}

/// The convex hull of points (monotone chain), counter-clockwise as seen in
/// window coordinates (y down), without collinear points.
pub fn convex_hull(points: &[(i64, i64)]) -> Vec<(i64, i64)> {
    let mut pts = points.to_vec();
    pts.sort_unstable();
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    // z of (a − o) × (b − o) in y-down coordinates; > 0 is a clockwise turn as seen.
    let cross = |o: (i64, i64), a: (i64, i64), b: (i64, i64)| {
        (a.0 - o.0) as i128 * (b.1 - o.1) as i128 - (a.1 - o.1) as i128 * (b.0 - o.0) as i128
    };
    let mut hull: Vec<(i64, i64)> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(i64, i64)>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) >= 0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    if area2_ccw(&hull) < 0 {
        hull.reverse();
    }
    hull
}
