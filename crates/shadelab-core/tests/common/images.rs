//! Comparing images and counts: a failed comparison writes the actual and
//! expected images as PPM files into the temporary directory.

#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::PathBuf;

use shadelab_core::{Image, Rgb8};

fn out_dir() -> PathBuf {
    let dir = std::env::temp_dir().join("shadelab-core-tests");
    let _ = std::fs::create_dir_all(&dir);
    dir
}

/// Writes a binary PPM into the temporary directory and returns its path.
pub fn write_ppm(
    name: &str,
    width: u32,
    height: u32,
    pixel: impl Fn(u32, u32) -> [u8; 3],
) -> PathBuf {
    let path = out_dir().join(format!("{name}.ppm"));
    let mut bytes = format!("P6\n{width} {height}\n255\n").into_bytes();
    for y in 0..height {
        for x in 0..width {
            bytes.extend_from_slice(&pixel(x, y));
        }
    }
    if let Err(e) = std::fs::write(&path, bytes) {
        eprintln!("could not write {}: {e}", path.display());
    }
    path
}

/// An expected image: per pixel an unrounded 0–255 colour, or `None` where
/// the test does not care.
pub struct Expected {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<Option<[f64; 3]>>,
}

impl Expected {
    pub fn new(width: u32, height: u32) -> Expected {
        Expected {
            width,
            height,
            pixels: vec![None; (width * height) as usize],
        }
    }

    pub fn set(&mut self, x: u32, y: u32, c: [f64; 3]) {
        self.pixels[(y * self.width + x) as usize] = Some(c);
    }

    pub fn set_rgb8(&mut self, x: u32, y: u32, c: Rgb8) {
        self.set(x, y, c.0.map(f64::from));
    }

    pub fn checked(&self) -> usize {
        self.pixels.iter().filter(|p| p.is_some()).count()
    }
}

/// Compares every pixel where `expected` has a value with `actual`, allowing
/// `tolerance` (0–255 units) per channel. On failure writes
/// `<name>-actual.ppm`, `<name>-expected.ppm` (don't-care pixels magenta) and
/// `<name>-diff.ppm`, and says where the first difference is.
pub fn compare_images(
    name: &str,
    actual: &Image,
    expected: &Expected,
    tolerance: f64,
) -> Result<usize, String> {
    assert_eq!(
        (actual.width(), actual.height()),
        (expected.width, expected.height),
        "{name}: image size"
    );
    let w = expected.width;
    let mut first = None;
    let mut bad = 0usize;
    let mut worst = 0f64;
    for y in 0..expected.height {
        for x in 0..w {
            let Some(e) = expected.pixels[(y * w + x) as usize] else {
                continue;
            };
            let a = actual.pixel(x, y).0;
            let diff = (0..3)
                .map(|k| (f64::from(a[k]) - e[k]).abs())
                .fold(0.0, f64::max);
            if diff > tolerance {
                bad += 1;
                worst = worst.max(diff);
                first.get_or_insert((x, y, a, e));
            }
        }
    }
    let Some((x, y, a, e)) = first else {
        return Ok(expected.checked());
    };
    let exp8 = |x: u32, y: u32| match expected.pixels[(y * w + x) as usize] {
        Some(c) => c.map(|v| v.round().clamp(0.0, 255.0) as u8),
        None => [255, 0, 255],
    };
    let pa = write_ppm(&format!("{name}-actual"), w, expected.height, |x, y| {
        actual.pixel(x, y).0
    });
    let pe = write_ppm(&format!("{name}-expected"), w, expected.height, exp8);
    let pd = write_ppm(
        &format!("{name}-diff"),
        w,
        expected.height,
        |x, y| match expected.pixels[(y * w + x) as usize] {
            None => [0, 0, 0],
            Some(e) => {
                let a = actual.pixel(x, y).0;
                let diff = (0..3)
                    .map(|k| (f64::from(a[k]) - e[k]).abs())
                    .fold(0.0, f64::max);
                if diff > tolerance {
                    [255, 0, 0]
                } else {
                    [(diff * 60.0).min(255.0) as u8; 3]
                }
            }
        },
    );
    let mut msg = String::new();
    let _ = write!(
        msg,
        "{name}: {bad} of {} checked pixels differ by more than {tolerance} (worst {worst:.2}); \
         first at ({x}, {y}): actual {a:?}, expected [{:.2}, {:.2}, {:.2}]\n  actual:   {}\n  expected: {}\n  diff:     {}",
        expected.checked(),
        e[0],
        e[1],
        e[2],
        pa.display(),
        pe.display(),
        pd.display()
    );
    Err(msg)
}

/// What a coverage count may be at one pixel.
pub type CountRange = std::ops::RangeInclusive<u32>;

/// Checks a coverage map against per-pixel expectations (`None`: any count).
/// On failure writes `<name>-counts.ppm` (black 0, grey 1, red more, blue
/// where the expectation fails) and reports the first failing pixel.
pub fn compare_counts(
    name: &str,
    counts: &[u32],
    width: u32,
    height: u32,
    expected: impl Fn(u32, u32) -> Option<CountRange>,
) -> Result<usize, String> {
    assert_eq!(counts.len(), (width * height) as usize, "{name}: map size");
    let mut first = None;
    let mut bad = 0usize;
    let mut checked = 0usize;
    for y in 0..height {
        for x in 0..width {
            let Some(range) = expected(x, y) else {
                continue;
            };
            checked += 1;
            let c = counts[(y * width + x) as usize];
            if !range.contains(&c) {
                bad += 1;
                first.get_or_insert((x, y, c, range));
            }
        }
    }
    let Some((x, y, c, range)) = first else {
        return Ok(checked);
    };
    let path = write_ppm(&format!("{name}-counts"), width, height, |x, y| {
        let c = counts[(y * width + x) as usize];
        if expected(x, y).is_some_and(|r| !r.contains(&c)) {
            [0, 0, 255]
        } else {
            match c {
                0 => [0, 0, 0],
                1 => [160, 160, 160],
                _ => [255, 0, 0],
            }
        }
    });
    Err(format!(
        "{name}: {bad} of {checked} checked pixels have a wrong coverage count; first at ({x}, {y}): \
         {c}, expected {range:?}\n  counts: {} (blue = wrong)",
        path.display()
    ))
}

/// Unwraps a comparison, panicking with its report.
pub fn ok(result: Result<usize, String>) -> usize {
    match result {
        Ok(n) => n,
        Err(msg) => panic!("{msg}"),
    }
}
