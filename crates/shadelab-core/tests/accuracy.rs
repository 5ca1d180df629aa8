//! The textbook's claim made measurable: on a tessellated sphere, Phong
//! shading is closer to the exact image than Gouraud shading, which is closer
//! than flat shading, and all three get closer as the tessellation gets finer.
//!
//! The exact image is computed per pixel in the test: the pixel's ray meets
//! the analytic unit sphere, and the full Phong model is evaluated there with
//! the true normal. Errors are mean absolute differences in 0–255 units over
//! the pixels both the mesh and the sphere cover.

mod common;

use common::*;
use glam::DVec3;
use shadelab_core::{
    builtin_model, coverage, render, vertex_normals, Interpolation, NormalWeighting, RenderOptions,
    Shading,
};

const DETAILS: [u32; 5] = [6, 12, 24, 48, 96];

/// The methods compared: a label, the shading and Gouraud's specular flag.
const METHODS: [(&str, Shading, bool); 4] = [
    ("flat", Shading::Flat, false),
    ("gouraud (no specular)", Shading::Gouraud, false),
    ("gouraud (specular)", Shading::Gouraud, true),
    ("phong", Shading::Phong, false),
];

/// Mean absolute error of each method at each detail: `errors[method][detail]`.
fn measure(interpolation: Interpolation) -> (Vec<Vec<f64>>, Vec<usize>) {
    let (w, h) = (200u32, 200u32);
    let cam = camera(DVec3::new(0.6, 0.9, 3.4), DVec3::ZERO, 40.0, 0.5, 10.0);
    let view = View::new(&cam, w, h);
    let mut errors = vec![Vec::new(); METHODS.len()];
    let mut pixels = Vec::new();
    for detail in DETAILS {
        let mesh = builtin_model("sphere", Some(detail)).unwrap();
        let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
        let scene = scene(mesh, normals, cam);
        let model = PhongModel::of_scene(&scene);
        // The exact image, where the ray meets the sphere.
        let exact: Vec<Option<[f64; 3]>> = (0..h)
            .flat_map(|j| (0..w).map(move |i| (i, j)))
            .map(|(i, j)| {
                let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                view.hit_sphere(x, y, DVec3::ZERO, 1.0)
                    .map(|(_, p)| to_255(model.eval(p, p.normalize(), true)))
            })
            .collect();
        let base = RenderOptions {
            interpolation,
            ..options(w, h, Shading::Flat)
        };
        let counts = coverage(&scene, &base).unwrap();
        let both: Vec<usize> = (0..exact.len())
            .filter(|&k| counts[k] > 0 && exact[k].is_some())
            .collect();
        pixels.push(both.len());
        for (m, &(_, shading, gouraud_specular)) in METHODS.iter().enumerate() {
            let options = RenderOptions {
                shading,
                gouraud_specular,
                ..base
            };
            let (image, _) = render(&scene, &options).unwrap();
            let total: f64 = both
                .iter()
                .map(|&k| {
                    let e = exact[k].unwrap();
                    let a = image.pixels()[k].0;
                    (0..3).map(|c| (f64::from(a[c]) - e[c]).abs()).sum::<f64>() / 3.0
                })
                .sum();
            errors[m].push(total / both.len() as f64);
        }
    }
    (errors, pixels)
}

fn table(title: &str, errors: &[Vec<f64>], pixels: &[usize]) -> String {
    let mut s =
        format!("\n{title}\nmean absolute error per channel (0–255) against the analytic sphere\n");
    s += &format!("{:<24}", "sphere detail");
    for d in DETAILS {
        s += &format!("{d:>9}");
    }
    s += "\n";
    for (m, (label, _, _)) in METHODS.iter().enumerate() {
        s += &format!("{label:<24}");
        for e in &errors[m] {
            s += &format!("{e:>9.3}");
        }
        s += "\n";
    }
    s += &format!("{:<24}", "pixels compared");
    for p in pixels {
        s += &format!("{p:>9}");
    }
    s + "\n"
}

/// Phong < Gouraud (with specular) < flat. On the coarsest sphere (6 slices,
/// 3 stacks) Gouraud loses to flat: no vertex is near the highlight, and the
/// facing quad interpolates its four grazing-angle vertices, darker than the
/// centroid flat shading samples; there only Phong's lead is required.
fn assert_order(detail: u32, flat: f64, gouraud: f64, phong: f64, report: &str) {
    let holds = if detail >= 12 {
        phong < gouraud && gouraud < flat
    } else {
        phong < gouraud && phong < flat
    };
    assert!(
        holds,
        "detail {detail}: phong {phong:.3}, gouraud {gouraud:.3}, flat {flat:.3}{report}"
    );
}

#[test]
fn phong_beats_gouraud_beats_flat_and_all_converge() {
    let (errors, pixels) = measure(Interpolation::Perspective);
    let report = table("perspective-correct interpolation", &errors, &pixels);
    println!("{report}");
    eprintln!("{report}");
    let [flat, _gouraud_plain, gouraud, phong] = [0, 1, 2, 3].map(|m| &errors[m]);
    for (k, &detail) in DETAILS.iter().enumerate() {
        assert_order(detail, flat[k], gouraud[k], phong[k], &report);
        if k > 0 {
            for (m, (label, _, _)) in METHODS.iter().enumerate() {
                if m == 1 {
                    continue; // without the specular term it converges to the wrong image
                }
                assert!(
                    errors[m][k] < errors[m][k - 1],
                    "{label}: error does not decrease from detail {} to {detail}{report}",
                    DETAILS[k - 1]
                );
            }
        }
    }
    // Phong at the finest detail is within a couple of levels of exact.
    assert!(phong[DETAILS.len() - 1] < 2.0, "{report}");
}

/// The same measurement with screen-linear interpolation: reported, and the
/// methods keep their order.
#[test]
fn screen_interpolation_keeps_the_order() {
    let (errors, pixels) = measure(Interpolation::Screen);
    let report = table("screen-linear interpolation", &errors, &pixels);
    println!("{report}");
    eprintln!("{report}");
    for (k, &detail) in DETAILS.iter().enumerate() {
        assert_order(detail, errors[0][k], errors[2][k], errors[3][k], &report);
    }
}
