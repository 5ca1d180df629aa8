#![no_main]
//! Arbitrary convex polygons through the scanline rasterizer: no panic, no
//! pixel outside the image, and a polygon covers exactly the pixels of its
//! fan of triangles, each once.
use libfuzzer_sys::{arbitrary::Arbitrary, fuzz_target};
use shadelab_core::raster::scanline::rasterize_polygon;
use shadelab_core::raster::{signed_area_ccw, FragmentSink, ScreenVertex};
use shadelab_core::Interpolation;

const W: u32 = 24;
const H: u32 = 20;
/// Snapped coordinates stay within the guard band the pipeline guarantees.
const LIMIT: i64 = 1 << 28;

#[derive(Debug, Arbitrary)]
struct Input {
    points: Vec<(i32, i32, u8)>,
    screen: bool,
}

struct Counter([u32; (W * H) as usize]);

impl FragmentSink<1> for Counter {
    fn fragment(&mut self, x: u32, y: u32, depth: f32, attrs: &[f32; 1]) {
        assert!(x < W && y < H, "fragment ({x}, {y}) outside the image");
        let _ = (depth, attrs);
        self.0[(y * W + x) as usize] += 1;
    }
}

fuzz_target!(|input: Input| {
    if input.points.len() < 3 || input.points.len() > 8 {
        return;
    }
    // Small coordinates most of the time, so polygons land on the image.
    let polygon: Vec<ScreenVertex<1>> = input
        .points
        .iter()
        .map(|&(x, y, z)| {
            let scale = |v: i32| {
                if z & 1 == 0 {
                    i64::from(v) % (32 * 256)
                } else {
                    i64::from(v).clamp(-LIMIT, LIMIT)
                }
            };
            ScreenVertex {
                x: scale(x),
                y: scale(y),
                depth: f32::from(z) / 255.0,
                inv_w: 1.0,
                attrs: [f32::from(z)],
            }
        })
        .collect();
    let interpolation = if input.screen {
        Interpolation::Screen
    } else {
        Interpolation::Perspective
    };
    let mut whole = Counter([0; (W * H) as usize]);
    rasterize_polygon(&polygon, W, H, interpolation, &mut whole);
    // Compare with the fan only for convex polygons (where the two must agree).
    if signed_area_ccw(&polygon) > 0 && is_strictly_convex(&polygon) {
        let mut fan = Counter([0; (W * H) as usize]);
        for k in 1..polygon.len() - 1 {
            rasterize_polygon(
                &[polygon[0], polygon[k], polygon[k + 1]],
                W,
                H,
                interpolation,
                &mut fan,
            );
        }
        assert_eq!(whole.0, fan.0, "polygon and fan cover different pixels");
        assert!(whole.0.iter().all(|&c| c <= 1), "a pixel covered twice");
    }
});

fn is_strictly_convex(p: &[ScreenVertex<1>]) -> bool {
    let n = p.len();
    (0..n).all(|i| {
        let (a, b, c) = (&p[i], &p[(i + 1) % n], &p[(i + 2) % n]);
        let turn =
            (b.x - a.x) as i128 * (c.y - b.y) as i128 - (b.y - a.y) as i128 * (c.x - b.x) as i128;
        turn < 0
    }) && {
        // Winds once: the y direction changes sign exactly twice.
        let dirs: Vec<i64> = (0..n)
            .map(|i| (p[(i + 1) % n].y - p[i].y).signum())
            .filter(|&d| d != 0)
            .collect();
        (0..dirs.len())
            .filter(|&i| dirs[i] != dirs[(i + 1) % dirs.len()])
            .count()
            == 2
    }
}
