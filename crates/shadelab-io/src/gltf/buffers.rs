//! The bytes a glTF file's buffers hold, and the files its URIs name.
//!
//! A buffer is the GLB `BIN` chunk, a base64 `data:` URI, or a relative
//! file URI, percent-decoded and resolved inside the folder that holds the
//! glTF file with every symbolic link followed ([`resolve_inside`]); all of
//! them together are read within the budget [`super::parse_gltf`] gives
//! ([`crate::MAX_MESH_BYTES`] less the file itself). Another scheme, an
//! absolute path or a path out of the folder is an error naming the URI,
//! and the file it names is never opened. Images are never read, but their
//! URIs are held to the same rule.

use std::path::{Path, PathBuf};

use ::gltf::buffer::Source;
use base64::Engine;
use shadelab_core::escape_token;

use crate::input::{read_capped, resolve_inside, Refusal};
use crate::mesh_file::{invalid, MAX_MESH_BYTES};
use crate::LoadError;

/// Fails when an image names a file outside the model's folder. Images are
/// never read (textures are not drawn), but a file that names one is held
/// to the same rule as its buffers.
pub(super) fn check_images(
    gltf: &::gltf::Gltf,
    name: &str,
    base_dir: Option<&Path>,
) -> Result<(), LoadError> {
    for image in gltf.images() {
        let ::gltf::image::Source::Uri { uri, .. } = image.source() else {
            continue;
        };
        if uri.starts_with("data:") {
            continue;
        }
        match resolve_uri(uri, base_dir) {
            Ok(_) | Err(UriError::Refused(Refusal::Missing)) | Err(UriError::NoFolder) => {}
            Err(e) => {
                return Err(invalid(
                    name,
                    format!("image {}: {}", image.index(), e.describe(uri)),
                ));
            }
        }
    }
    Ok(())
}

/// Every buffer's bytes, in order.
pub(super) fn load_buffers(
    gltf: &::gltf::Gltf,
    name: &str,
    base_dir: Option<&Path>,
    mut budget: u64,
) -> Result<Vec<Vec<u8>>, LoadError> {
    let mut buffers = Vec::new();
    for buffer in gltf.buffers() {
        let k = buffer.index();
        let (data, what) = match buffer.source() {
            Source::Bin => {
                let blob = gltf.blob.as_deref().ok_or_else(|| {
                    invalid(
                        name,
                        format!("buffer {k} refers to the GLB binary chunk, but there is none"),
                    )
                })?;
                (blob.to_vec(), "the GLB binary chunk".to_owned())
            }
            Source::Uri(uri) if uri.starts_with("data:") => {
                let (_, payload) = uri.split_once(";base64,").ok_or_else(|| {
                    invalid(
                        name,
                        format!("buffer {k}: a data URI must be base64 (`;base64,`)"),
                    )
                })?;
                let data = base64::engine::general_purpose::STANDARD
                    .decode(payload)
                    .map_err(|e| invalid(name, format!("buffer {k}: bad base64 data URI: {e}")))?;
                (data, "its data URI".to_owned())
            }
            Source::Uri(uri) => {
                let path = resolve_uri(uri, base_dir)
                    .map_err(|e| invalid(name, format!("buffer {k}: {}", e.describe(uri))))?;
                let data = read_capped(&path, budget)
                    .map_err(|e| invalid(name, format!("buffer {k}: {e}")))?;
                (data, format!("file {}", path.display()))
            }
        };
        budget = budget.saturating_sub(data.len() as u64);
        if data.len() < buffer.length() {
            return Err(invalid(
                name,
                format!(
                    "buffer {k}: byteLength is {} but {what} has only {} bytes",
                    buffer.length(),
                    data.len()
                ),
            ));
        }
        buffers.push(data);
    }
    Ok(buffers)
}

/// The files a glTF file's buffers name (not its data URIs) inside its
/// folder; none when it cannot be read or parsed.
pub(crate) fn external_buffers(path: &Path, base: &Path) -> Vec<PathBuf> {
    let Ok(bytes) = read_capped(path, MAX_MESH_BYTES) else {
        return Vec::new();
    };
    let Ok(gltf) = ::gltf::Gltf::from_slice_without_validation(&bytes) else {
        return Vec::new();
    };
    gltf.document
        .as_json()
        .buffers
        .iter()
        .filter_map(|buffer| buffer.uri.as_deref())
        .filter(|uri| !uri.starts_with("data:"))
        .filter_map(|uri| resolve_uri(uri, Some(base)).ok())
        .collect()
}

/// Why a URI does not name a file that may be read.
enum UriError {
    /// The file was not read from disk (the viewer's uploads).
    NoFolder,
    /// Not a relative file reference (`http:`, `file:`, a drive).
    Scheme,
    /// Malformed `%` escapes, or not UTF-8 once decoded.
    Encoding,
    /// Refused by [`resolve_inside`].
    Refused(Refusal),
}

impl UriError {
    fn describe(&self, uri: &str) -> String {
        let shown = escape_token(uri);
        match self {
            UriError::NoFolder => format!(
                "`{shown}` names an external file, which cannot be read here (only a .glb or \
                 data: URIs)"
            ),
            UriError::Scheme => {
                format!("`{shown}`: only relative file URIs and base64 data: URIs are read")
            }
            UriError::Encoding => format!("`{shown}`: malformed percent-encoding"),
            UriError::Refused(r) => r.describe(uri),
        }
    }
}

/// The file a URI names, percent-decoded, inside `base_dir`.
fn resolve_uri(uri: &str, base_dir: Option<&Path>) -> Result<PathBuf, UriError> {
    let base = base_dir.ok_or(UriError::NoFolder)?;
    if uri.contains(':') {
        return Err(UriError::Scheme);
    }
    let decoded = percent_decode(uri).ok_or(UriError::Encoding)?;
    if decoded.contains(':') || decoded.contains('\0') {
        return Err(UriError::Scheme);
    }
    resolve_inside(base, &decoded).map_err(UriError::Refused)
}

fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut k = 0;
    while k < bytes.len() {
        if bytes[k] == b'%' {
            let hex = std::str::from_utf8(bytes.get(k + 1..k + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            k += 3;
        } else {
            out.push(bytes[k]);
            k += 1;
        }
    }
    String::from_utf8(out).ok()
}
