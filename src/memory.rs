//! The memory a command will need, estimated before it allocates.
//!
//! Each command knows how many pixels it will draw and at what cost per
//! pixel (the measured constants of `shadelab_core::limits`), and the mesh
//! it draws; [`check`] adds them up and refuses, before any frame is
//! allocated, a command that would need more than
//! [`shadelab_core::limits::MAX_MEMORY_BYTES`].

use shadelab_core::limits::{memory_estimate, MAX_MEMORY_BYTES};
use shadelab_core::Mesh;

use crate::{input_error, Failure};

/// Fails when `command` drawing `pixels` pixels at `bytes_per_pixel`, with
/// `mesh`, would need more than the memory limit.
pub fn check(
    command: &str,
    mesh: Option<&Mesh>,
    pixels: u64,
    bytes_per_pixel: u64,
) -> Result<(), Failure> {
    let (vertices, triangles) = mesh.map_or((0, 0), |m| (m.positions().len(), m.triangle_count()));
    let bytes = memory_estimate(vertices, triangles, pixels, bytes_per_pixel);
    if bytes <= MAX_MEMORY_BYTES {
        return Ok(());
    }
    Err(input_error(anyhow::anyhow!(
        "{command} would need about {} of memory for {pixels} pixels{}, more than the limit \
         of {} (see docs/limits.md): ask for a smaller size",
        gib(bytes),
        mesh.map_or(String::new(), |_| format!(
            " and a mesh of {triangles} triangles"
        )),
        gib(MAX_MEMORY_BYTES)
    )))
}

fn gib(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / f64::from(1u32 << 30))
}
