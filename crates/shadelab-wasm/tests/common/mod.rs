//! What the engine's test files share.

use shadelab_core::Image;

/// An image's pixels as the engine hands them to the page: RGBA, opaque.
pub fn rgba(image: &Image) -> Vec<u8> {
    image
        .pixels()
        .iter()
        .flat_map(|p| [p.0[0], p.0[1], p.0[2], 255])
        .collect()
}
