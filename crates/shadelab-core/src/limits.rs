//! Every limit shadelab enforces on what it is given, in one place.
//!
//! A file may come from anywhere, so each resource an input can make
//! shadelab spend has a ceiling here, checked before the resource is spent:
//! bytes read, triangles (after instancing), image pixels, memory, threads,
//! the viewer's connections and how long a client may take, and the length
//! of what a message repeats. `docs/limits.md` lists the same numbers and
//! what happens when each is crossed; the code names these constants and no
//! other copies of the numbers.

use std::time::Duration;

/// Largest image side, in pixels.
pub const MAX_IMAGE_SIDE: u32 = 16384;
/// Largest image, in pixels (64 Mpixel, about 450 MiB of colour and depth).
pub const MAX_IMAGE_PIXELS: u64 = 1 << 26;

/// Largest mesh file read, in bytes, whatever its format: 1 GiB. For glTF it
/// bounds the `.gltf` file and every external buffer together; an OBJ
/// file's material libraries are each bounded by it too.
pub const MAX_MESH_BYTES: u64 = 1 << 30;
/// Largest scene file read, in bytes: 1 MiB (a scene file is a few hundred
/// bytes of TOML).
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

/// The most triangles a mesh may have, a polygon of `n` corners counting as
/// `n − 2`, and for glTF counted after instancing (every node that draws a
/// mesh adds its triangles again): 2^24, 16,777,216.
pub const MAX_TRIANGLES: usize = 1 << 24;
/// The most vertices a mesh may have: three per triangle of
/// [`MAX_TRIANGLES`], enough for a triangle soup.
pub const MAX_VERTICES: usize = 3 * MAX_TRIANGLES;
/// The most face corners (polygon vertices, all polygons together) a mesh
/// may have: 2^28.
pub const MAX_CORNERS: usize = 1 << 28;

/// The largest coordinate a scene file may give a camera, a light or a
/// direction, either way.
pub const MAX_SCENE_COORDINATE: f32 = 1e30;
/// The largest coordinate of a model drawn in its own coordinates (a scene
/// with a `[camera]`), either way: 2^30, about 1.07e9. Face normals of
/// larger triangles overflow `f32`. Without a camera the model is scaled to
/// fit the view first, and any finite coordinates are drawn.
pub const MAX_MODEL_COORDINATE_WITH_CAMERA: f32 = (1u32 << 30) as f32;
/// The smallest distance between a camera's eye and its target: the view
/// direction's squared length must be a normal `f32` (2^−126), so the
/// distance must be at least 2^−63, about 1.1e-19.
pub const MIN_EYE_DISTANCE: f32 = 1.0842022e-19;
/// The largest distance between a camera's eye and its target: the view
/// direction's squared length must not overflow `f32`, so the distance must
/// be under 2^64, about 1.8e19.
pub const MAX_EYE_DISTANCE: f32 = 1.8446743e19;

/// The most memory a command may plan to use, in bytes: 8 GiB. Each command
/// estimates its peak from the mesh's counts and the pixels it will draw
/// ([`mesh_memory`] plus its own bytes per pixel) before it allocates, and
/// refuses with an error saying the estimate when it is over.
pub const MAX_MEMORY_BYTES: u64 = 8 << 30;
/// Bytes a mesh costs per vertex while it is loaded and prepared for
/// drawing (positions, file normals, computed normals and the renderer's
/// transformed vertices), rounded up from measurements.
pub const MESH_BYTES_PER_VERTEX: u64 = 96;
/// Bytes a mesh costs per triangle while it is loaded and prepared for
/// drawing (corners, polygon offsets, smoothing groups, face normals and
/// the renderer's bins), rounded up from measurements.
pub const MESH_BYTES_PER_TRIANGLE: u64 = 160;

/// The estimated peak memory of loading and drawing a mesh of `vertices`
/// and `triangles`, in bytes (pixels not included).
pub const fn mesh_memory(vertices: usize, triangles: usize) -> u64 {
    vertices as u64 * MESH_BYTES_PER_VERTEX + triangles as u64 * MESH_BYTES_PER_TRIANGLE
}

// Any mesh within the triangle and vertex limits fits the memory limit, so
// loaders bound memory by bounding counts.
const _: () = assert!(mesh_memory(MAX_VERTICES, MAX_TRIANGLES) <= MAX_MEMORY_BYTES);

/// Memory every command needs whatever it draws (the program, plot
/// canvases, fonts), in bytes.
pub const BASE_MEMORY_BYTES: u64 = 64 << 20;
/// Bytes per pixel of `render`, `cost`, `explain` and `profile` (the
/// frame, its depth and the rasterizer's buffers, the PNG being encoded):
/// about 7 measured, doubled.
pub const RENDER_BYTES_PER_PIXEL: u64 = 16;
/// Bytes per panel pixel of `compare` (three frames and the sheet): about
/// 25 measured, doubled.
pub const COMPARE_BYTES_PER_PIXEL: u64 = 48;
/// Bytes per panel pixel of `errors` (the exact surface ray-traced per
/// pixel, three error maps, the four-panel sheet and its plot): about 143
/// measured, rounded up.
pub const ERRORS_BYTES_PER_PIXEL: u64 = 200;
/// Bytes per pixel of `accuracy` (one tessellation level's frames and
/// error maps at a time): about 110 measured, rounded up.
pub const ACCURACY_BYTES_PER_PIXEL: u64 = 160;
/// Bytes per panel pixel of `quad` (two panels per turn and the sheet):
/// about 12.5 measured, rounded up.
pub const QUAD_BYTES_PER_PIXEL: u64 = 16;

/// The estimated peak memory of a command drawing `pixels` pixels at
/// `bytes_per_pixel` with a mesh of `vertices` and `triangles`, in bytes.
pub const fn memory_estimate(
    vertices: usize,
    triangles: usize,
    pixels: u64,
    bytes_per_pixel: u64,
) -> u64 {
    BASE_MEMORY_BYTES
        .saturating_add(mesh_memory(vertices, triangles))
        .saturating_add(pixels.saturating_mul(bytes_per_pixel))
}

/// The most threads a command runs at once (`RAYON_NUM_THREADS`,
/// `bench --threads`).
pub const MAX_THREADS: usize = 256;

/// The most characters of one token (a word of a file, a name, a value) a
/// message repeats; the rest is cut and counted.
pub const MAX_ECHOED_CHARS: usize = 80;
/// The most characters of one line of a message printed; the rest is cut
/// and counted.
pub const MAX_MESSAGE_LINE_CHARS: usize = 400;

/// The most connections the viewer's server holds at once. A connection
/// over the limit makes room by closing the one that has waited longest
/// for its request, or is answered 503 when every one is being answered.
pub const MAX_CONNECTIONS: usize = 128;
/// The longest request head (request line and headers) read, in bytes;
/// longer ones are answered 431. Bodies are never read.
pub const MAX_REQUEST_HEAD_BYTES: usize = 8 * 1024;
/// How long a client may take to send its whole request head before the
/// connection is closed.
pub const REQUEST_HEAD_TIMEOUT: Duration = Duration::from_secs(5);
/// How long a client may take to read a whole response before the
/// connection is closed.
pub const RESPONSE_TIMEOUT: Duration = Duration::from_secs(60);

/// The smallest panel `shadelab quad --size` draws, in pixels a side.
pub const MIN_QUAD_SIZE: u32 = 9;
/// The largest panel `shadelab quad --size` draws, in pixels a side.
pub const MAX_QUAD_SIZE: u32 = 1024;
/// The most turns `shadelab quad --angles` draws.
pub const MAX_QUAD_ANGLES: usize = 36;
/// The largest turn `shadelab quad --angles` takes, in degrees either way.
pub const MAX_QUAD_DEGREES: f32 = 360.0;
/// The most tessellation levels `shadelab accuracy --details` renders.
pub const MAX_ACCURACY_DETAILS: usize = 32;
/// The most renders per method `shadelab cost --runs` takes.
pub const MAX_COST_RUNS: u32 = 1000;
/// The longest time budget of one row of `shadelab bench`, in seconds.
pub const MAX_BENCH_BUDGET_SECONDS: f64 = 3600.0;
