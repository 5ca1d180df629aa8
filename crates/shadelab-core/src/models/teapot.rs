//! The Utah teapot, tessellated from Martin Newell's 32 bicubic Bézier patches.
//!
//! # Data
//! Newell measured a real Melitta teapot in 1975 and described it with 306
//! control points and 32 patches of 4×4 points each: rim (4), body (8), handle
//! (4), spout (4), lid knob (4) and lid (4). The four bottom patches came later;
//! the 1975 teapot had no bottom. The data set is public domain and is reproduced
//! here as published, one-based indices and all, so that it can be compared with
//! other copies line by line; the coordinates are not rescaled (no Blinn squash).
//! The teapot stands on the plane *y* = 0, is 3.15 units tall, reaches from
//! *x* = −3 (handle) to *x* ≈ 3.434 (spout lip) and from *z* = −2 to 2. Nothing is
//! centred: the renderer normalises models itself.
//!
//! # Axes
//! Newell's data is *z*-up. Every point (*x*, *y*, *z*) becomes (*x*, *z*, −*y*):
//! a rotation by −90° about *x*, so the frame stays right-handed, the teapot
//! stands on *y* = 0 and the spout points to +*x*.
//!
//! # Tessellation and welding
//! Each patch is evaluated with the cubic Bernstein basis on a
//! (*n* + 1) × (*n* + 1) grid of (*u*, *v*), in `f64`, and every grid cell
//! becomes a quad. Neighbouring patches evaluate the same boundary curve, so
//! grid points on patch borders coincide (up to rounding). Points closer than
//! 10⁻⁵ are welded into one vertex; that is under 2·10⁻⁶ of the teapot's size,
//! while distinct grid points are at least 8·10⁻⁴ apart even at detail 64. The
//! welder hashes quantised positions and also probes the neighbouring cells, so
//! rounding can never split a pair. Welding is what makes averaged vertex
//! normals smooth across patch borders.
//!
//! Welding happens within each separately modelled piece: the shell (rim, body
//! and bottom), the lid, the handle and the spout. These pieces share no edge,
//! but the lower end of the handle touches the body at one point,
//! (−2, 0.9, 0); merging the two vertices there would mix the handle's normals
//! into the body's and tilt the body's averaged normal by about 30°, a visible
//! blemish, so that point is kept as two vertices.
//!
//! # Degenerate corners
//! The first control row of each lid-knob patch is four copies of the knob's top
//! centre, and likewise for each bottom patch and the bottom centre. After
//! welding, the first row of quads of those eight patches has two corners on the
//! same vertex; the repeated corner is dropped and the quad becomes a triangle
//! (8*n* triangles in all). A polygon left with fewer than three distinct
//! corners would be dropped, but none is. (The third row of the knob patches is
//! also a single repeated point, but that row is only a control row, not on the
//! surface.) A polygon without area is dropped too, and so are vertices that no
//! polygon uses: this happens only at detail 1, where the four corners of each
//! of the two spout-lip patches lie on one line.
//!
//! # Winding
//! Every polygon is counter-clockwise seen from outside: its normal by the
//! right-hand rule points away from the teapot. A quad emitted in grid order
//! (*u*, *v*) → (*u* + 1, *v*) → (*u* + 1, *v* + 1) → (*u*, *v* + 1) faces along
//! ∂P/∂*u* × ∂P/∂*v*. Each patch is tested on its own: its vector area (the sum
//! of its cells' area vectors, on a fixed 8 × 8 sample grid) is compared with the
//! direction from the centre of the control points' bounding box to the
//! patch's centroid, and the patch is reversed when they disagree. A local test
//! at one point would not do: the rim and the spout's lip curl over, so their
//! outside faces the axis on one side of the lip. With Newell's data every
//! patch comes out inward-facing in grid order, so all 32 are reversed; the
//! weakest margin is the handle's (the cosine is about −0.19). The tests check
//! the result independently: every interior edge is walked once in each
//! direction (so neighbouring patches agree), and each piece, closed with caps
//! over its open boundary loops, encloses a positive signed volume.

use std::collections::HashMap;

use glam::{DVec3, Vec3};

use crate::mesh::Mesh;

/// Default patch subdivision (quads per patch edge).
pub const DEFAULT_DETAIL: u32 = 8;

/// The finest subdivision [`teapot`] accepts (131 072 polygons).
const MAX_DETAIL: u32 = 64;

/// Positions closer than this (in every coordinate) are one vertex.
const WELD_TOLERANCE: f64 = 1e-5;

/// Polygons with less area than this (squared units) are dropped. The
/// smallest real polygons, at the knob's top at detail 64, have about 10⁻⁵.
const MIN_AREA: f64 = 1e-10;

/// Cells per patch edge for the orientation test, whatever the detail.
const ORIENTATION_SAMPLES: usize = 8;

/// Newell's 32 patches: 16 one-based indices into [`CONTROL_POINTS`] each, four
/// rows of four. A row is a curve around the piece (a quarter circle about the
/// teapot's axis, or half a cross-section of the handle or spout); the rows
/// follow each other along the other parameter.
#[rustfmt::skip]
const PATCHES: [[u16; 16]; 32] = [
    // Rim.
    [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16],
    [4, 17, 18, 19, 8, 20, 21, 22, 12, 23, 24, 25, 16, 26, 27, 28],
    [19, 29, 30, 31, 22, 32, 33, 34, 25, 35, 36, 37, 28, 38, 39, 40],
    [31, 41, 42, 1, 34, 43, 44, 5, 37, 45, 46, 9, 40, 47, 48, 13],
    // Body, upper half.
    [13, 14, 15, 16, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60],
    [16, 26, 27, 28, 52, 61, 62, 63, 56, 64, 65, 66, 60, 67, 68, 69],
    [28, 38, 39, 40, 63, 70, 71, 72, 66, 73, 74, 75, 69, 76, 77, 78],
    [40, 47, 48, 13, 72, 79, 80, 49, 75, 81, 82, 53, 78, 83, 84, 57],
    // Body, lower half.
    [57, 58, 59, 60, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96],
    [60, 67, 68, 69, 88, 97, 98, 99, 92, 100, 101, 102, 96, 103, 104, 105],
    [69, 76, 77, 78, 99, 106, 107, 108, 102, 109, 110, 111, 105, 112, 113, 114],
    [78, 83, 84, 57, 108, 115, 116, 85, 111, 117, 118, 89, 114, 119, 120, 93],
    // Handle.
    [121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136],
    [124, 137, 138, 121, 128, 139, 140, 125, 132, 141, 142, 129, 136, 143, 144, 133],
    [133, 134, 135, 136, 145, 146, 147, 148, 149, 150, 151, 152, 69, 153, 154, 155],
    [136, 143, 144, 133, 148, 156, 157, 145, 152, 158, 159, 149, 155, 160, 161, 69],
    // Spout.
    [162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176, 177],
    [165, 178, 179, 162, 169, 180, 181, 166, 173, 182, 183, 170, 177, 184, 185, 174],
    [174, 175, 176, 177, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196, 197],
    [177, 184, 185, 174, 189, 198, 199, 186, 193, 200, 201, 190, 197, 202, 203, 194],
    // Lid knob: the first row is one point, the top centre.
    [204, 204, 204, 204, 207, 208, 209, 210, 211, 211, 211, 211, 212, 213, 214, 215],
    [204, 204, 204, 204, 210, 217, 218, 219, 211, 211, 211, 211, 215, 220, 221, 222],
    [204, 204, 204, 204, 219, 224, 225, 226, 211, 211, 211, 211, 222, 227, 228, 229],
    [204, 204, 204, 204, 226, 230, 231, 207, 211, 211, 211, 211, 229, 232, 233, 212],
    // Lid.
    [212, 213, 214, 215, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244, 245],
    [215, 220, 221, 222, 237, 246, 247, 248, 241, 249, 250, 251, 245, 252, 253, 254],
    [222, 227, 228, 229, 248, 255, 256, 257, 251, 258, 259, 260, 254, 261, 262, 263],
    [229, 232, 233, 212, 257, 264, 265, 234, 260, 266, 267, 238, 263, 268, 269, 242],
    // Bottom: the first row is one point, the bottom centre.
    [270, 270, 270, 270, 279, 280, 281, 282, 275, 276, 277, 278, 271, 272, 273, 274],
    [270, 270, 270, 270, 282, 289, 290, 291, 278, 286, 287, 288, 274, 283, 284, 285],
    [270, 270, 270, 270, 291, 298, 299, 300, 288, 295, 296, 297, 285, 292, 293, 294],
    [270, 270, 270, 270, 300, 305, 306, 279, 297, 303, 304, 275, 294, 301, 302, 271],
];

/// Newell's 306 control points, (*x*, *y*, *z*) with *z* up, as published.
const CONTROL_POINTS: [[f32; 3]; 306] = [
    // 1-48: rim.
    [1.4, 0.0, 2.4],
    [1.4, -0.784, 2.4],
    [0.784, -1.4, 2.4],
    [0.0, -1.4, 2.4],
    [1.3375, 0.0, 2.53125],
    [1.3375, -0.749, 2.53125],
    [0.749, -1.3375, 2.53125],
    [0.0, -1.3375, 2.53125],
    [1.4375, 0.0, 2.53125],
    [1.4375, -0.805, 2.53125],
    [0.805, -1.4375, 2.53125],
    [0.0, -1.4375, 2.53125],
    [1.5, 0.0, 2.4],
    [1.5, -0.84, 2.4],
    [0.84, -1.5, 2.4],
    [0.0, -1.5, 2.4],
    [-0.784, -1.4, 2.4],
    [-1.4, -0.784, 2.4],
    [-1.4, 0.0, 2.4],
    [-0.749, -1.3375, 2.53125],
    [-1.3375, -0.749, 2.53125],
    [-1.3375, 0.0, 2.53125],
    [-0.805, -1.4375, 2.53125],
    [-1.4375, -0.805, 2.53125],
    [-1.4375, 0.0, 2.53125],
    [-0.84, -1.5, 2.4],
    [-1.5, -0.84, 2.4],
    [-1.5, 0.0, 2.4],
    [-1.4, 0.784, 2.4],
    [-0.784, 1.4, 2.4],
    [0.0, 1.4, 2.4],
    [-1.3375, 0.749, 2.53125],
    [-0.749, 1.3375, 2.53125],
    [0.0, 1.3375, 2.53125],
    [-1.4375, 0.805, 2.53125],
    [-0.805, 1.4375, 2.53125],
    [0.0, 1.4375, 2.53125],
    [-1.5, 0.84, 2.4],
    [-0.84, 1.5, 2.4],
    [0.0, 1.5, 2.4],
    [0.784, 1.4, 2.4],
    [1.4, 0.784, 2.4],
    [0.749, 1.3375, 2.53125],
    [1.3375, 0.749, 2.53125],
    [0.805, 1.4375, 2.53125],
    [1.4375, 0.805, 2.53125],
    [0.84, 1.5, 2.4],
    [1.5, 0.84, 2.4],
    // 49-120: body.
    [1.75, 0.0, 1.875],
    [1.75, -0.98, 1.875],
    [0.98, -1.75, 1.875],
    [0.0, -1.75, 1.875],
    [2.0, 0.0, 1.35],
    [2.0, -1.12, 1.35],
    [1.12, -2.0, 1.35],
    [0.0, -2.0, 1.35],
    [2.0, 0.0, 0.9],
    [2.0, -1.12, 0.9],
    [1.12, -2.0, 0.9],
    [0.0, -2.0, 0.9],
    [-0.98, -1.75, 1.875],
    [-1.75, -0.98, 1.875],
    [-1.75, 0.0, 1.875],
    [-1.12, -2.0, 1.35],
    [-2.0, -1.12, 1.35],
    [-2.0, 0.0, 1.35],
    [-1.12, -2.0, 0.9],
    [-2.0, -1.12, 0.9],
    [-2.0, 0.0, 0.9],
    [-1.75, 0.98, 1.875],
    [-0.98, 1.75, 1.875],
    [0.0, 1.75, 1.875],
    [-2.0, 1.12, 1.35],
    [-1.12, 2.0, 1.35],
    [0.0, 2.0, 1.35],
    [-2.0, 1.12, 0.9],
    [-1.12, 2.0, 0.9],
    [0.0, 2.0, 0.9],
    [0.98, 1.75, 1.875],
    [1.75, 0.98, 1.875],
    [1.12, 2.0, 1.35],
    [2.0, 1.12, 1.35],
    [1.12, 2.0, 0.9],
    [2.0, 1.12, 0.9],
    [2.0, 0.0, 0.45],
    [2.0, -1.12, 0.45],
    [1.12, -2.0, 0.45],
    [0.0, -2.0, 0.45],
    [1.5, 0.0, 0.225],
    [1.5, -0.84, 0.225],
    [0.84, -1.5, 0.225],
    [0.0, -1.5, 0.225],
    [1.5, 0.0, 0.15],
    [1.5, -0.84, 0.15],
    [0.84, -1.5, 0.15],
    [0.0, -1.5, 0.15],
    [-1.12, -2.0, 0.45],
    [-2.0, -1.12, 0.45],
    [-2.0, 0.0, 0.45],
    [-0.84, -1.5, 0.225],
    [-1.5, -0.84, 0.225],
    [-1.5, 0.0, 0.225],
    [-0.84, -1.5, 0.15],
    [-1.5, -0.84, 0.15],
    [-1.5, 0.0, 0.15],
    [-2.0, 1.12, 0.45],
    [-1.12, 2.0, 0.45],
    [0.0, 2.0, 0.45],
    [-1.5, 0.84, 0.225],
    [-0.84, 1.5, 0.225],
    [0.0, 1.5, 0.225],
    [-1.5, 0.84, 0.15],
    [-0.84, 1.5, 0.15],
    [0.0, 1.5, 0.15],
    [1.12, 2.0, 0.45],
    [2.0, 1.12, 0.45],
    [0.84, 1.5, 0.225],
    [1.5, 0.84, 0.225],
    [0.84, 1.5, 0.15],
    [1.5, 0.84, 0.15],
    // 121-161: handle.
    [-1.6, 0.0, 2.025],
    [-1.6, -0.3, 2.025],
    [-1.5, -0.3, 2.25],
    [-1.5, 0.0, 2.25],
    [-2.3, 0.0, 2.025],
    [-2.3, -0.3, 2.025],
    [-2.5, -0.3, 2.25],
    [-2.5, 0.0, 2.25],
    [-2.7, 0.0, 2.025],
    [-2.7, -0.3, 2.025],
    [-3.0, -0.3, 2.25],
    [-3.0, 0.0, 2.25],
    [-2.7, 0.0, 1.8],
    [-2.7, -0.3, 1.8],
    [-3.0, -0.3, 1.8],
    [-3.0, 0.0, 1.8],
    [-1.5, 0.3, 2.25],
    [-1.6, 0.3, 2.025],
    [-2.5, 0.3, 2.25],
    [-2.3, 0.3, 2.025],
    [-3.0, 0.3, 2.25],
    [-2.7, 0.3, 2.025],
    [-3.0, 0.3, 1.8],
    [-2.7, 0.3, 1.8],
    [-2.7, 0.0, 1.575],
    [-2.7, -0.3, 1.575],
    [-3.0, -0.3, 1.35],
    [-3.0, 0.0, 1.35],
    [-2.5, 0.0, 1.125],
    [-2.5, -0.3, 1.125],
    [-2.65, -0.3, 0.9375],
    [-2.65, 0.0, 0.9375],
    [-2.0, -0.3, 0.9],
    [-1.9, -0.3, 0.6],
    [-1.9, 0.0, 0.6],
    [-3.0, 0.3, 1.35],
    [-2.7, 0.3, 1.575],
    [-2.65, 0.3, 0.9375],
    [-2.5, 0.3, 1.125],
    [-1.9, 0.3, 0.6],
    [-2.0, 0.3, 0.9],
    // 162-203: spout.
    [1.7, 0.0, 1.425],
    [1.7, -0.66, 1.425],
    [1.7, -0.66, 0.6],
    [1.7, 0.0, 0.6],
    [2.6, 0.0, 1.425],
    [2.6, -0.66, 1.425],
    [3.1, -0.66, 0.825],
    [3.1, 0.0, 0.825],
    [2.3, 0.0, 2.1],
    [2.3, -0.25, 2.1],
    [2.4, -0.25, 2.025],
    [2.4, 0.0, 2.025],
    [2.7, 0.0, 2.4],
    [2.7, -0.25, 2.4],
    [3.3, -0.25, 2.4],
    [3.3, 0.0, 2.4],
    [1.7, 0.66, 0.6],
    [1.7, 0.66, 1.425],
    [3.1, 0.66, 0.825],
    [2.6, 0.66, 1.425],
    [2.4, 0.25, 2.025],
    [2.3, 0.25, 2.1],
    [3.3, 0.25, 2.4],
    [2.7, 0.25, 2.4],
    [2.8, 0.0, 2.475],
    [2.8, -0.25, 2.475],
    [3.525, -0.25, 2.49375],
    [3.525, 0.0, 2.49375],
    [2.9, 0.0, 2.475],
    [2.9, -0.15, 2.475],
    [3.45, -0.15, 2.5125],
    [3.45, 0.0, 2.5125],
    [2.8, 0.0, 2.4],
    [2.8, -0.15, 2.4],
    [3.2, -0.15, 2.4],
    [3.2, 0.0, 2.4],
    [3.525, 0.25, 2.49375],
    [2.8, 0.25, 2.475],
    [3.45, 0.15, 2.5125],
    [2.9, 0.15, 2.475],
    [3.2, 0.15, 2.4],
    [2.8, 0.15, 2.4],
    // 204-269: lid (205, 206, 216 and 223 are not used by any patch).
    [0.0, 0.0, 3.15],
    [0.0, -0.002, 3.15],
    [0.002, 0.0, 3.15],
    [0.8, 0.0, 3.15],
    [0.8, -0.45, 3.15],
    [0.45, -0.8, 3.15],
    [0.0, -0.8, 3.15],
    [0.0, 0.0, 2.85],
    [0.2, 0.0, 2.7],
    [0.2, -0.112, 2.7],
    [0.112, -0.2, 2.7],
    [0.0, -0.2, 2.7],
    [-0.002, 0.0, 3.15],
    [-0.45, -0.8, 3.15],
    [-0.8, -0.45, 3.15],
    [-0.8, 0.0, 3.15],
    [-0.112, -0.2, 2.7],
    [-0.2, -0.112, 2.7],
    [-0.2, 0.0, 2.7],
    [0.0, 0.002, 3.15],
    [-0.8, 0.45, 3.15],
    [-0.45, 0.8, 3.15],
    [0.0, 0.8, 3.15],
    [-0.2, 0.112, 2.7],
    [-0.112, 0.2, 2.7],
    [0.0, 0.2, 2.7],
    [0.45, 0.8, 3.15],
    [0.8, 0.45, 3.15],
    [0.112, 0.2, 2.7],
    [0.2, 0.112, 2.7],
    [0.4, 0.0, 2.55],
    [0.4, -0.224, 2.55],
    [0.224, -0.4, 2.55],
    [0.0, -0.4, 2.55],
    [1.3, 0.0, 2.55],
    [1.3, -0.728, 2.55],
    [0.728, -1.3, 2.55],
    [0.0, -1.3, 2.55],
    [1.3, 0.0, 2.4],
    [1.3, -0.728, 2.4],
    [0.728, -1.3, 2.4],
    [0.0, -1.3, 2.4],
    [-0.224, -0.4, 2.55],
    [-0.4, -0.224, 2.55],
    [-0.4, 0.0, 2.55],
    [-0.728, -1.3, 2.55],
    [-1.3, -0.728, 2.55],
    [-1.3, 0.0, 2.55],
    [-0.728, -1.3, 2.4],
    [-1.3, -0.728, 2.4],
    [-1.3, 0.0, 2.4],
    [-0.4, 0.224, 2.55],
    [-0.224, 0.4, 2.55],
    [0.0, 0.4, 2.55],
    [-1.3, 0.728, 2.55],
    [-0.728, 1.3, 2.55],
    [0.0, 1.3, 2.55],
    [-1.3, 0.728, 2.4],
    [-0.728, 1.3, 2.4],
    [0.0, 1.3, 2.4],
    [0.224, 0.4, 2.55],
    [0.4, 0.224, 2.55],
    [0.728, 1.3, 2.55],
    [1.3, 0.728, 2.55],
    [0.728, 1.3, 2.4],
    [1.3, 0.728, 2.4],
    // 270-306: bottom.
    [0.0, 0.0, 0.0],
    [1.5, 0.0, 0.15],
    [1.5, 0.84, 0.15],
    [0.84, 1.5, 0.15],
    [0.0, 1.5, 0.15],
    [1.5, 0.0, 0.075],
    [1.5, 0.84, 0.075],
    [0.84, 1.5, 0.075],
    [0.0, 1.5, 0.075],
    [1.425, 0.0, 0.0],
    [1.425, 0.798, 0.0],
    [0.798, 1.425, 0.0],
    [0.0, 1.425, 0.0],
    [-0.84, 1.5, 0.15],
    [-1.5, 0.84, 0.15],
    [-1.5, 0.0, 0.15],
    [-0.84, 1.5, 0.075],
    [-1.5, 0.84, 0.075],
    [-1.5, 0.0, 0.075],
    [-0.798, 1.425, 0.0],
    [-1.425, 0.798, 0.0],
    [-1.425, 0.0, 0.0],
    [-1.5, -0.84, 0.15],
    [-0.84, -1.5, 0.15],
    [0.0, -1.5, 0.15],
    [-1.5, -0.84, 0.075],
    [-0.84, -1.5, 0.075],
    [0.0, -1.5, 0.075],
    [-1.425, -0.798, 0.0],
    [-0.798, -1.425, 0.0],
    [0.0, -1.425, 0.0],
    [0.84, -1.5, 0.15],
    [1.5, -0.84, 0.15],
    [0.84, -1.5, 0.075],
    [1.5, -0.84, 0.075],
    [0.798, -1.425, 0.0],
    [1.425, -0.798, 0.0],
];

/// The separately modelled pieces of the teapot; vertices are welded only
/// within a piece.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Piece {
    /// Rim, body and bottom: one shell, open only inside the rim.
    Shell,
    Handle,
    Spout,
    Lid,
}

/// The piece that patch `patch` (zero-based) belongs to.
fn piece_of(patch: usize) -> Piece {
    match patch {
        12..=15 => Piece::Handle,
        16..=19 => Piece::Spout,
        20..=27 => Piece::Lid,
        _ => Piece::Shell,
    }
}

/// Newell's *z*-up point (*x*, *y*, *z*) as *y*-up (*x*, *z*, −*y*).
fn y_up([x, y, z]: [f32; 3]) -> DVec3 {
    DVec3::new(f64::from(x), f64::from(z), -f64::from(y))
}

/// The 16 control points of patch `patch` (zero-based), *y*-up, row by row.
fn control_net(patch: usize) -> [DVec3; 16] {
    PATCHES[patch].map(|i| y_up(CONTROL_POINTS[usize::from(i) - 1]))
}

/// The centre of the bounding box of all control points, *y*-up.
fn control_centre() -> DVec3 {
    let (lo, hi) = CONTROL_POINTS.iter().map(|&p| y_up(p)).fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    );
    (lo + hi) * 0.5
}

/// The four cubic Bernstein polynomials at `t`.
fn bernstein(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t]
}

/// The point of a Bézier patch at (`u`, `v`); `u` runs across the rows, `v` along them.
fn evaluate(net: &[DVec3; 16], u: f64, v: f64) -> DVec3 {
    let (bu, bv) = (bernstein(u), bernstein(v));
    let mut point = DVec3::ZERO;
    for (row, wu) in net.chunks_exact(4).zip(bu) {
        for (&p, wv) in row.iter().zip(bv) {
            point += p * (wu * wv);
        }
    }
    point
}

/// Whether the patch, with quads in grid order (facing along ∂P/∂u × ∂P/∂v),
/// faces into the teapot: its vector area points against the direction from
/// `centre` to its centroid.
fn faces_inward(net: &[DVec3; 16], centre: DVec3) -> bool {
    let n = ORIENTATION_SAMPLES;
    let at = |i: usize, j: usize| evaluate(net, i as f64 / n as f64, j as f64 / n as f64);
    let mut area = DVec3::ZERO;
    let mut sum = DVec3::ZERO;
    for i in 0..=n {
        for j in 0..=n {
            sum += at(i, j);
            if i < n && j < n {
                // Twice the vector area of the quad (i, j), (i+1, j), (i+1, j+1), (i, j+1).
                area += (at(i + 1, j + 1) - at(i, j)).cross(at(i, j + 1) - at(i + 1, j));
            }
        }
    }
    let centroid = sum / ((n + 1) * (n + 1)) as f64;
    area.dot(centroid - centre) < 0.0
}

/// Merges positions that coincide within [`WELD_TOLERANCE`], piece by piece.
#[derive(Default)]
struct Welder {
    positions: Vec<DVec3>,
    cells: HashMap<(Piece, [i64; 3]), Vec<u32>>,
}

impl Welder {
    /// The index of the vertex at `p` in `piece`, added if there is none yet.
    fn index(&mut self, piece: Piece, p: DVec3) -> u32 {
        let cell = (p / WELD_TOLERANCE).round().to_array().map(|c| c as i64);
        // A position within the tolerance lies in the same or an adjacent cell.
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let key = (piece, [cell[0] + dx, cell[1] + dy, cell[2] + dz]);
                    let found = self.cells.get(&key).and_then(|list| {
                        list.iter().copied().find(|&i| {
                            (self.positions[i as usize] - p).abs().max_element() <= WELD_TOLERANCE
                        })
                    });
                    if let Some(i) = found {
                        return i;
                    }
                }
            }
        }
        let index = self.positions.len() as u32;
        self.positions.push(p);
        self.cells.entry((piece, cell)).or_default().push(index);
        index
    }
}

/// A quad's corners without repeats: a corner equal to the next one is dropped.
/// `None` when fewer than three distinct corners remain (or a corner would
/// repeat out of turn, which would make a bow-tie).
fn distinct_corners(quad: [u32; 4]) -> Option<Vec<u32>> {
    let polygon: Vec<u32> = (0..4)
        .filter(|&k| quad[k] != quad[(k + 1) % 4])
        .map(|k| quad[k])
        .collect();
    let repeats = (0..polygon.len()).any(|a| polygon[a + 1..].contains(&polygon[a]));
    (polygon.len() >= 3 && !repeats).then_some(polygon)
}

/// The area of a planar polygon, by Newell's method.
fn area(positions: &[DVec3], polygon: &[u32]) -> f64 {
    let at = |k: usize| positions[polygon[k % polygon.len()] as usize];
    let twice: DVec3 = (0..polygon.len()).map(|k| at(k).cross(at(k + 1))).sum();
    twice.length() * 0.5
}

/// The welded, consistently wound tessellation, before it becomes a [`Mesh`].
struct Tessellation {
    positions: Vec<Vec3>,
    polygons: Vec<Vec<u32>>,
    /// The zero-based patch each polygon comes from (for the tests).
    #[cfg_attr(not(test), allow(dead_code))]
    patch_of: Vec<usize>,
}

/// Evaluates, welds and winds all 32 patches at `detail` (clamped to 1..=64).
fn tessellate(detail: u32) -> Tessellation {
    let n = detail.clamp(1, MAX_DETAIL) as usize;
    let centre = control_centre();
    let mut welder = Welder::default();
    let mut polygons = Vec::with_capacity(PATCHES.len() * n * n);
    let mut patch_of = Vec::with_capacity(PATCHES.len() * n * n);
    let mut grid = vec![0u32; (n + 1) * (n + 1)];
    for patch in 0..PATCHES.len() {
        let net = control_net(patch);
        let piece = piece_of(patch);
        for i in 0..=n {
            for j in 0..=n {
                let p = evaluate(&net, i as f64 / n as f64, j as f64 / n as f64);
                grid[i * (n + 1) + j] = welder.index(piece, p);
            }
        }
        let reverse = faces_inward(&net, centre);
        let at = |i: usize, j: usize| grid[i * (n + 1) + j];
        for i in 0..n {
            for j in 0..n {
                let mut quad = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                if reverse {
                    quad.reverse();
                }
                if let Some(polygon) = distinct_corners(quad)
                    .filter(|polygon| area(&welder.positions, polygon) >= MIN_AREA)
                {
                    polygons.push(polygon);
                    patch_of.push(patch);
                }
            }
        }
    }
    // Keep only the vertices that polygons use, in order of first use.
    let mut renumbered = vec![u32::MAX; welder.positions.len()];
    let mut positions = Vec::with_capacity(welder.positions.len());
    for index in polygons.iter_mut().flatten() {
        let new = &mut renumbered[*index as usize];
        if *new == u32::MAX {
            *new = positions.len() as u32;
            positions.push(welder.positions[*index as usize].as_vec3());
        }
        *index = *new;
    }
    Tessellation {
        positions,
        polygons,
        patch_of,
    }
}

/// The Utah teapot with `detail` (clamped to 1..=64) quads along each patch edge.
///
/// For *n* = `detail` ≥ 2 the result has 32·*n*² polygons: quads, except for
/// 8·*n* triangles around the lid knob's top and the bottom centre, all wound
/// counter-clockwise seen from outside, on 32·*n*² + 4·*n* + 2 vertices
/// (welded as the [module documentation](self) describes). At detail 1 the
/// two spout-lip quads have no area and are left out: 30 polygons on 36
/// vertices. *y* is up; the teapot stands on *y* = 0 with its spout towards +*x*.
///
/// # Panics
/// Never: [`Mesh::from_polygons`] could only fail on a mesh without polygons,
/// a polygon with fewer than three corners, an index out of range, a position
/// that is not finite or more corners than it supports, and none of these can
/// happen with the fixed patch data and at most 64 × 64 quads per patch (the
/// tests build the mesh at details from 1 to 64).
pub fn teapot(detail: u32) -> Mesh {
    let Tessellation {
        positions,
        polygons,
        ..
    } = tessellate(detail);
    Mesh::from_polygons(positions, polygons).expect("the teapot's fixed data makes a valid mesh")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Twice the vector area of a polygon, by Newell's method (Σ pₖ × pₖ₊₁).
    fn polygon_normal(positions: &[Vec3], polygon: &[u32]) -> DVec3 {
        let at = |k: usize| positions[polygon[k % polygon.len()] as usize].as_dvec3();
        (0..polygon.len()).map(|k| at(k).cross(at(k + 1))).sum()
    }

    /// Signed volume of triangle (a, b, c) with the origin.
    fn cone(a: DVec3, b: DVec3, c: DVec3) -> f64 {
        a.dot(b.cross(c)) / 6.0
    }

    /// Σ a·(b×c)/6 over the fan triangles of every polygon.
    fn signed_volume(positions: &[Vec3], polygons: &[&[u32]]) -> f64 {
        let p = |i: u32| positions[i as usize].as_dvec3();
        polygons
            .iter()
            .flat_map(|poly| {
                (1..poly.len() - 1).map(move |k| cone(p(poly[0]), p(poly[k]), p(poly[k + 1])))
            })
            .sum()
    }

    fn mesh_volume(mesh: &Mesh) -> f64 {
        let polygons: Vec<&[u32]> = (0..mesh.polygon_count()).map(|f| mesh.polygon(f)).collect();
        signed_volume(mesh.positions(), &polygons)
    }

    /// Each directed edge of `polygons` and how often it occurs.
    fn directed_edges(polygons: &[&[u32]]) -> HashMap<(u32, u32), usize> {
        let mut edges = HashMap::new();
        for poly in polygons {
            for k in 0..poly.len() {
                *edges
                    .entry((poly[k], poly[(k + 1) % poly.len()]))
                    .or_insert(0) += 1;
            }
        }
        edges
    }

    /// The polygons of one piece.
    fn piece_polygons(t: &Tessellation, piece: Piece) -> Vec<&[u32]> {
        t.polygons
            .iter()
            .zip(&t.patch_of)
            .filter(|&(_, &patch)| piece_of(patch) == piece)
            .map(|(poly, _)| poly.as_slice())
            .collect()
    }

    /// The open boundary of `polygons` as closed loops of vertex indices, in
    /// the direction the polygons walk them.
    fn boundary_loops(polygons: &[&[u32]]) -> Vec<Vec<u32>> {
        let edges = directed_edges(polygons);
        let mut next: HashMap<u32, u32> = HashMap::new();
        for &(a, b) in edges.keys() {
            if !edges.contains_key(&(b, a)) {
                assert!(
                    next.insert(a, b).is_none(),
                    "two boundary edges leave vertex {a}"
                );
            }
        }
        let mut loops = Vec::new();
        while let Some(&start) = next.keys().min() {
            let mut lp = vec![start];
            let mut v = next.remove(&start).unwrap();
            while v != start {
                lp.push(v);
                v = next.remove(&v).expect("boundary edges form closed loops");
            }
            loops.push(lp);
        }
        loops
    }

    const PIECES: [Piece; 4] = [Piece::Shell, Piece::Lid, Piece::Handle, Piece::Spout];

    /// (vertices, polygons, triangles among them, triangles after fan triangulation)
    fn counts(detail: u32) -> (usize, usize, usize, usize) {
        let mesh = teapot(detail);
        let triangles = (0..mesh.polygon_count())
            .filter(|&f| mesh.polygon(f).len() == 3)
            .count();
        (
            mesh.positions().len(),
            mesh.polygon_count(),
            triangles,
            mesh.triangle_count(),
        )
    }

    #[test]
    fn counts_after_welding() {
        // With n quads per patch edge, rings of 4n points around the axis:
        // shell: rim n+1 rings, each body half n more, bottom n-1 more and the
        //   bottom centre: 16n² + 1;
        // lid: knob n rings and its top centre, lid n rings: 8n² + 1;
        // handle and spout: 2n+1 cross-sections of 2n points: 4n² + 2n each.
        // 32n² + 4n + 2 vertices (the handle touches the body at one point,
        // which stays two vertices); 32n² polygons, 8n of them triangles.
        // At detail 1 the two spout-lip quads are flat lines and are dropped,
        // with the two vertices only they used.
        assert_eq!(counts(1), (36, 30, 8, 52));
        assert_eq!(counts(DEFAULT_DETAIL), (2082, 2048, 64, 4032));
        for n in [2usize, 3, 5, 16] {
            let expected = (
                32 * n * n + 4 * n + 2,
                32 * n * n,
                8 * n,
                64 * n * n - 8 * n,
            );
            assert_eq!(counts(n as u32), expected, "detail {n}");
        }
    }

    #[test]
    fn detail_is_clamped() {
        assert_eq!(teapot(0), teapot(1));
        let finest = teapot(64);
        assert_eq!(finest.polygon_count(), 32 * 64 * 64);
        assert_eq!(finest.positions().len(), 32 * 64 * 64 + 4 * 64 + 2);
        assert_eq!(teapot(u32::MAX), finest);
    }

    #[test]
    fn positions_finite_and_polygons_without_repeated_corners() {
        for detail in [1, 2, 3, 4, 7, 8, 13, 64] {
            let t = tessellate(detail);
            assert!(t.positions.iter().all(|p| p.is_finite()));
            let mut used = vec![false; t.positions.len()];
            t.polygons
                .iter()
                .flatten()
                .for_each(|&i| used[i as usize] = true);
            assert!(used.iter().all(|&u| u), "every vertex is used");
            assert_eq!(t.polygons.len(), t.patch_of.len());
            for poly in &t.polygons {
                assert!(poly.len() == 3 || poly.len() == 4, "{poly:?}");
                assert!(poly.iter().all(|&i| (i as usize) < t.positions.len()));
                for a in 0..poly.len() {
                    assert!(
                        !poly[a + 1..].contains(&poly[a]),
                        "{poly:?} repeats a corner"
                    );
                }
                let area = polygon_normal(&t.positions, poly).length() * 0.5;
                assert!(area > MIN_AREA, "{poly:?} has no area");
            }
        }
    }

    #[test]
    fn axes_are_converted_to_y_up_right_handed() {
        let (x, y, z) = (
            y_up([1.0, 0.0, 0.0]),
            y_up([0.0, 1.0, 0.0]),
            y_up([0.0, 0.0, 1.0]),
        );
        assert_eq!((x, y, z), (DVec3::X, DVec3::NEG_Z, DVec3::Y));
        assert_eq!(x.cross(y), z);
        // The knob's top centre is a vertex, on the y axis.
        let mesh = teapot(DEFAULT_DETAIL);
        assert!(mesh.positions().contains(&Vec3::new(0.0, 3.15, 0.0)));
    }

    #[test]
    fn bounding_box_matches_the_teapot() {
        let (lo, hi) = teapot(DEFAULT_DETAIL).bounds();
        // The handle's back (x = -3), the bottom (y = 0), the knob's top
        // (y = 3.15) and the body's widest points (z = ±2) are all grid points.
        assert!(
            (lo - Vec3::new(-3.0, 0.0, -2.0)).abs().max_element() < 1e-5,
            "{lo}"
        );
        assert!(
            (hi.y - 3.15).abs() < 1e-5 && (hi.z - 2.0).abs() < 1e-5,
            "{hi}"
        );
        // The spout's lip peaks at x ≈ 3.43408 (u ≈ 0.41 on patches 19 and 20),
        // between grid points; at detail 8 the grid comes within 1e-3.
        assert!(hi.x > 3.433 && hi.x < 3.4341, "{hi}");
        let (_, fine) = teapot(64).bounds();
        assert!((fine.x - 3.43408).abs() < 1e-4, "{fine}");
    }

    #[test]
    fn spout_points_to_plus_x_and_handle_to_minus_x() {
        let t = tessellate(DEFAULT_DETAIL);
        let extreme = |sign: f32| {
            let (f, _) = t
                .polygons
                .iter()
                .enumerate()
                .flat_map(|(f, poly)| poly.iter().map(move |&i| (f, i)))
                .max_by(|a, b| {
                    let xa = sign * t.positions[a.1 as usize].x;
                    let xb = sign * t.positions[b.1 as usize].x;
                    xa.total_cmp(&xb)
                })
                .unwrap();
            piece_of(t.patch_of[f])
        };
        assert_eq!(extreme(1.0), Piece::Spout);
        assert_eq!(extreme(-1.0), Piece::Handle);
    }

    #[test]
    fn only_the_handle_body_contact_point_is_not_welded() {
        let t = tessellate(DEFAULT_DETAIL);
        let mut by_position: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
        for (i, p) in t.positions.iter().enumerate() {
            let key = (p.as_dvec3() * 1e4).round().to_array().map(|c| c as i64);
            by_position.entry(key).or_default().push(i as u32);
        }
        let shared: Vec<&Vec<u32>> = by_position.values().filter(|v| v.len() > 1).collect();
        assert_eq!(shared.len(), 1, "{shared:?}");
        assert_eq!(shared[0].len(), 2);
        let p = t.positions[shared[0][0] as usize];
        assert!(
            (p - Vec3::new(-2.0, 0.9, 0.0)).abs().max_element() < 1e-5,
            "{p}"
        );
    }

    #[test]
    fn edges_are_shared_in_opposite_directions_except_known_boundaries() {
        let n = DEFAULT_DETAIL as usize;
        let t = tessellate(DEFAULT_DETAIL);
        let all: Vec<&[u32]> = t.polygons.iter().map(Vec::as_slice).collect();
        let edges = directed_edges(&all);
        // No directed edge twice: neighbouring polygons (and patches) agree on
        // the winding, and no edge has more than two polygons.
        assert!(edges.values().all(|&c| c == 1));
        let boundary = edges.keys().filter(|&&(a, b)| !edges.contains_key(&(b, a)));
        assert_eq!(boundary.count(), 16 * n);

        let radius = |i: u32| {
            let p = t.positions[i as usize];
            (p.x.hypot(p.z), p.y)
        };
        for piece in PIECES {
            let loops = boundary_loops(&piece_polygons(&t, piece));
            let lengths: Vec<usize> = loops.iter().map(Vec::len).collect();
            match piece {
                // The gap between lid and rim: the rim's inner edge (r = 1.4)
                // and the lid's outer edge (r = 1.3), both at y = 2.4.
                Piece::Shell | Piece::Lid => {
                    assert_eq!(lengths, [4 * n], "{piece:?}");
                    let r = if piece == Piece::Shell { 1.4 } else { 1.3 };
                    for &v in &loops[0] {
                        let (rv, y) = radius(v);
                        // Bézier quarter circles bulge by up to 0.4%.
                        assert!((rv - r).abs() < 0.01 && (y - 2.4).abs() < 1e-5, "{piece:?}");
                    }
                }
                // Both ends of each tube: where it meets the body, and the
                // handle's other end or the spout's mouth.
                Piece::Handle | Piece::Spout => assert_eq!(lengths, [2 * n, 2 * n], "{piece:?}"),
            }
        }
    }

    #[test]
    fn each_piece_closed_with_caps_encloses_positive_volume() {
        let t = tessellate(DEFAULT_DETAIL);
        let p = |i: u32| t.positions[i as usize].as_dvec3();
        let mut volumes = Vec::new();
        for piece in PIECES {
            let polygons = piece_polygons(&t, piece);
            let mut volume = signed_volume(&t.positions, &polygons);
            // Close every boundary loop with a fan around its centroid, walking
            // each boundary edge the other way, so the volume no longer
            // depends on the origin; it is positive if and only if the piece
            // faces outward.
            for lp in boundary_loops(&polygons) {
                let centre = lp.iter().map(|&i| p(i)).sum::<DVec3>() / lp.len() as f64;
                for k in 0..lp.len() {
                    let (a, b) = (lp[k], lp[(k + 1) % lp.len()]);
                    volume += cone(p(b), p(a), centre);
                }
            }
            volumes.push(volume);
        }
        let [shell, lid, handle, spout] = volumes[..] else {
            unreachable!()
        };
        assert!(shell > 20.0 && shell < 40.0, "shell {shell}");
        assert!(lid > 0.5 && lid < 2.0, "lid {lid}");
        assert!(handle > 0.1 && handle < 1.0, "handle {handle}");
        assert!(spout > 0.2 && spout < 2.0, "spout {spout}");
    }

    #[test]
    fn signed_volume_positive_and_converges() {
        // About 25.68 at detail 8, 25.91 at detail 32: flat quads cut the
        // convex body a little, less so the finer they are.
        let coarse = mesh_volume(&teapot(DEFAULT_DETAIL));
        let middle = mesh_volume(&teapot(16));
        let fine = mesh_volume(&teapot(32));
        assert!(coarse > 0.0);
        assert!(coarse < middle && middle < fine, "{coarse} {middle} {fine}");
        assert!((coarse - fine).abs() < 0.02 * fine, "{coarse} vs {fine}");
    }

    #[test]
    fn newell_patches_all_face_inward_in_grid_order() {
        let centre = control_centre();
        assert!((0..PATCHES.len()).all(|patch| faces_inward(&control_net(patch), centre)));
    }

    #[test]
    fn every_patch_faces_outward_by_the_orientation_test() {
        let t = tessellate(DEFAULT_DETAIL);
        let centre = control_centre().as_vec3().as_dvec3();
        for patch in 0..PATCHES.len() {
            let polygons: Vec<&Vec<u32>> = t
                .polygons
                .iter()
                .zip(&t.patch_of)
                .filter(|&(_, &q)| q == patch)
                .map(|(poly, _)| poly)
                .collect();
            assert_eq!(polygons.len(), 64);
            let area: DVec3 = polygons
                .iter()
                .map(|poly| polygon_normal(&t.positions, poly))
                .sum();
            let corners = polygons.iter().flat_map(|poly| poly.iter());
            let count = corners.clone().count() as f64;
            let centroid = corners
                .map(|&i| t.positions[i as usize].as_dvec3())
                .sum::<DVec3>()
                / count;
            let cos = area.normalize().dot((centroid - centre).normalize());
            assert!(cos > 0.1, "patch {} cos {cos}", patch + 1);
        }
    }

    #[test]
    fn seams_are_welded_so_corners_are_shared_by_neighbouring_patches() {
        // The body's widest point towards the spout is a corner of the four
        // body patches 5, 8, 9 and 12: one vertex, four polygons from four patches.
        let t = tessellate(DEFAULT_DETAIL);
        let target = Vec3::new(2.0, 0.9, 0.0);
        let v = t
            .positions
            .iter()
            .position(|&p| (p - target).abs().max_element() < 1e-5)
            .unwrap() as u32;
        let mut patches: Vec<usize> = t
            .polygons
            .iter()
            .zip(&t.patch_of)
            .filter(|(poly, _)| poly.contains(&v))
            .map(|(_, &patch)| patch + 1)
            .collect();
        patches.sort_unstable();
        assert_eq!(patches, [5, 8, 9, 12]);
    }
}
