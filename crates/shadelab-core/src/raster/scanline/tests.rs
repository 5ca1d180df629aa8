use super::*;

fn v(x: i64, y: i64) -> ScreenVertex<0> {
    ScreenVertex {
        x,
        y,
        depth: 0.0,
        inv_w: 1.0,
        attrs: [],
    }
}

/// The DDA's first pixel per row equals `ceil(x_cross − ½)` computed
/// afresh for each row in exact integer arithmetic.
#[test]
fn edge_bound_steps_exactly() {
    let mut seed = 12345u64;
    let mut next = |range: i64| {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 33) as i64).rem_euclid(2 * range) - range
    };
    for _ in 0..2000 {
        let (ax, ay) = (next(1 << 16), next(1 << 16));
        let (bx, by) = (next(1 << 16), ay + 1 + next(1 << 12).abs());
        let first_row = (ay - SUBPIXEL_HALF + SUBPIXEL_ONE - 1).div_euclid(SUBPIXEL_ONE);
        let (dx, dy) = (bx - ax, by - ay);
        let cy = |row: i64| row * SUBPIXEL_ONE + SUBPIXEL_HALF;
        let mut bound = EdgeBound::new(
            (ax - SUBPIXEL_HALF) * dy + (cy(first_row) - ay) * dx,
            SUBPIXEL_ONE * dy,
            SUBPIXEL_ONE * dx,
        );
        for row in first_row..first_row + 64 {
            // x_cross − ½ pixel, in snapped units, is (ax − ½)·dy + (cy − ay)·dx over dy.
            let num = i128::from(ax - SUBPIXEL_HALF) * i128::from(dy)
                + i128::from(cy(row) - ay) * i128::from(dx);
            let den = i128::from(SUBPIXEL_ONE * dy);
            let expected = -((-num).div_euclid(den)); // ceil
            assert_eq!(
                i128::from(bound.first_pixel()),
                expected,
                "edge ({ax}, {ay}) → ({bx}, {by}), row {row}"
            );
            let exact = num as f64 / den as f64 + 0.5;
            assert!((bound.crossing() - exact).abs() < 1e-9 * (1.0 + exact.abs()));
            bound.step();
        }
    }
}

#[test]
fn rows_between_takes_centres_in_a_half_open_range() {
    // Row r's centre is at r·256 + 128.
    assert_eq!(rows_between(128, 384), 0..1);
    assert_eq!(rows_between(127, 385), 0..2);
    assert_eq!(rows_between(129, 384), 1..1);
    assert_eq!(rows_between(-1000, 0), -4..0);
    assert_eq!(rows_between(0, 0), 0..0);
}

#[test]
fn convexity() {
    let square = [v(0, 0), v(0, 256), v(256, 256), v(256, 0)];
    assert!(signed_area_ccw(&square) > 0);
    assert!(is_convex(&square));
    assert!(is_convex(&[v(0, 0), v(0, 256), v(256, 0)]));
    // Collinear points along an edge are still convex.
    assert!(is_convex(&[
        v(0, 0),
        v(0, 128),
        v(0, 256),
        v(256, 256),
        v(256, 0)
    ]));
    // A dart: the fourth vertex is pushed in.
    let dart = [v(0, 0), v(0, 512), v(512, 512), v(200, 300)];
    assert!(signed_area_ccw(&dart) > 0);
    assert!(!is_convex(&dart));
    // A pentagram turns the same way at every vertex but winds twice.
    let star: Vec<ScreenVertex<0>> = [0, 2, 4, 1, 3]
        .iter()
        .map(|&k| {
            let a = std::f64::consts::FRAC_PI_2 + f64::from(k) * std::f64::consts::TAU / 5.0;
            v(
                (2000.0 + 1000.0 * a.cos()) as i64,
                (2000.0 - 1000.0 * a.sin()) as i64,
            )
        })
        .collect();
    assert!(signed_area_ccw(&star) > 0);
    assert!(!is_convex(&star));
}

struct Count(u32);

impl FragmentSink<0> for Count {
    fn fragment(&mut self, _: u32, _: u32, _: f32, _: &[f32; 0]) {
        self.0 += 1;
    }
}

/// A dart is drawn as a fan from its first vertex: exactly its pixels.
#[test]
fn non_convex_polygon_is_drawn_as_a_fan() {
    let dart = [
        v(0, 0),
        v(0, 8 * 256),
        v(8 * 256, 8 * 256),
        v(3 * 256, 5 * 256),
    ];
    let mut whole = Count(0);
    rasterize_polygon(&dart, 16, 16, Interpolation::Screen, &mut whole);
    let mut parts = Count(0);
    rasterize_polygon(
        &[dart[0], dart[1], dart[3]],
        16,
        16,
        Interpolation::Screen,
        &mut parts,
    );
    rasterize_polygon(
        &[dart[3], dart[1], dart[2]],
        16,
        16,
        Interpolation::Screen,
        &mut parts,
    );
    assert!(whole.0 > 0);
    assert_eq!(whole.0, parts.0);
}
