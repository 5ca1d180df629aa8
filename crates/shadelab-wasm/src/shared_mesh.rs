//! A parsed mesh as flat bytes, so that the user's file is parsed once, by
//! one panel's engine, and handed to the others as the mesh it became.
//!
//! Each panel's worker has its own WebAssembly instance, and an instance's
//! memory is its own: the panels cannot share one `Mesh`. What they can
//! share is its arrays. [`encode`] writes them one after another (positions,
//! polygons, the file's normals, smoothing groups); [`decode`] builds the
//! same [`Mesh`] from them through the core's checked constructors, so a
//! mesh that arrives this way is held to the same rules as any mesh.
//!
//! One thing does not survive the trip by itself: the file's normals.
//! [`Mesh::with_file_normals`] normalises what it is given, and normalising
//! a unit vector again moves a third of them by an ulp (glam's
//! `normalize` is not idempotent in f32). So [`decode`] also returns the
//! normals exactly as they were sent, and the engine draws with those (see
//! `Engine::prepare`): the adopted mesh then draws exactly the pixels of the
//! parsed one (the native tests compare them, file normals included).
//!
//! Layout, little-endian 32-bit words: the magic [`MAGIC`], then the counts
//! `positions, corners, polygons, normals, flags` (flag 1: the file's
//! normals follow, flag 2: smoothing groups follow), then `3·positions` f32,
//! `corners` u32 indices, `polygons + 1` u32 offsets into the corners, and
//! when flagged `3·normals` f32 with `corners` u32 normal indices, and
//! `polygons` u32 groups. The bytes come from another instance of this same
//! module, but are read as untrusted all the same: every count is checked
//! against the length before anything is allocated, and a mismatch is an
//! error, never a panic.

use glam::Vec3;
use shadelab_core::{CornerNormals, Mesh};

use crate::engine::EngineError;

/// The first word: "SLM1".
pub const MAGIC: u32 = u32::from_le_bytes(*b"SLM1");
const HAS_NORMALS: u32 = 1;
const HAS_GROUPS: u32 = 2;
const HEADER_WORDS: usize = 6;

/// `mesh` as bytes for [`decode`].
pub fn encode(mesh: &Mesh) -> Vec<u8> {
    let normals = mesh.file_normals();
    let groups = mesh.smoothing_groups();
    let polygons = mesh.polygon_count();
    let flags = if normals.is_some() { HAS_NORMALS } else { 0 }
        | if groups.is_some() { HAS_GROUPS } else { 0 };
    let words = HEADER_WORDS
        + 3 * mesh.positions().len()
        + mesh.corners().len()
        + polygons
        + 1
        + normals.map_or(0, |n| 3 * n.normals.len() + n.corner().len())
        + groups.map_or(0, <[u32]>::len);
    let mut out = Vec::with_capacity(4 * words);
    let mut word = |w: u32| out.extend_from_slice(&w.to_le_bytes());
    for w in [
        MAGIC,
        len32(mesh.positions().len()),
        len32(mesh.corners().len()),
        len32(polygons),
        len32(normals.map_or(0, |n| n.normals.len())),
        flags,
    ] {
        word(w);
    }
    for p in mesh.positions() {
        p.to_array().into_iter().for_each(|x| word(x.to_bits()));
    }
    mesh.corners().iter().for_each(|&i| word(i));
    word(0);
    for face in 0..polygons {
        word(len32(mesh.corner_range(face).end));
    }
    if let Some(n) = normals {
        for v in &n.normals {
            v.to_array().into_iter().for_each(|x| word(x.to_bits()));
        }
        n.corner().iter().for_each(|&i| word(i));
    }
    if let Some(g) = groups {
        g.iter().for_each(|&x| word(x));
    }
    out
}

/// A mesh's counts fit in u32 ([`Mesh::MAX_CORNERS`] and the others are far below).
fn len32(n: usize) -> u32 {
    u32::try_from(n).expect("a mesh's counts fit in 32 bits")
}

/// Reads words from the front of a byte slice.
struct Words<'a>(&'a [u8]);

impl Words<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], EngineError> {
        let bytes = n
            .checked_mul(4)
            .filter(|&b| b <= self.0.len())
            .ok_or_else(|| bad("it is shorter than its counts say"))?;
        let (head, tail) = self.0.split_at(bytes);
        self.0 = tail;
        Ok(head)
    }

    fn u32s(&mut self, n: usize) -> Result<Vec<u32>, EngineError> {
        Ok(self
            .take(n)?
            .chunks_exact(4)
            .map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]))
            .collect())
    }

    fn vec3s(&mut self, n: usize) -> Result<Vec<Vec3>, EngineError> {
        let count = n
            .checked_mul(3)
            .ok_or_else(|| bad("a count is too large"))?;
        Ok(self
            .take(count)?
            .chunks_exact(12)
            .map(|v| {
                let f = |k: usize| f32::from_le_bytes([v[k], v[k + 1], v[k + 2], v[k + 3]]);
                Vec3::new(f(0), f(4), f(8))
            })
            .collect())
    }
}

fn bad(why: &str) -> EngineError {
    EngineError(format!("the shared mesh is malformed: {why}"))
}

/// The mesh [`encode`] wrote into `bytes`, with its file normals exactly as
/// they were sent when the mesh's own (normalised again) differ from them.
///
/// # Errors
/// When the bytes are not such a mesh (wrong magic, counts that disagree
/// with the length or with each other), or the mesh breaks the core's rules
/// (an index out of range, a position not finite: [`shadelab_core::MeshError`]).
pub fn decode(bytes: &[u8]) -> Result<(Mesh, Option<CornerNormals>), EngineError> {
    let mut words = Words(bytes);
    let header = words.u32s(HEADER_WORDS)?;
    let [magic, positions, corners, polygons, normals, flags] = header[..] else {
        unreachable!("six words were read")
    };
    if magic != MAGIC {
        return Err(bad("it does not start with SLM1"));
    }
    let positions = words.vec3s(positions as usize)?;
    let corners = words.u32s(corners as usize)?;
    let offsets = words.u32s(polygons as usize + 1)?;
    let file_normals = if flags & HAS_NORMALS != 0 {
        let normals = words.vec3s(normals as usize)?;
        let corner = words.u32s(corners.len())?;
        Some(CornerNormals::new(normals, corner))
    } else {
        None
    };
    let groups = if flags & HAS_GROUPS != 0 {
        Some(words.u32s(polygons as usize)?)
    } else {
        None
    };
    if !words.0.is_empty() {
        return Err(bad("it is longer than its counts say"));
    }
    let in_order = offsets.first() == Some(&0)
        && offsets.last().is_some_and(|&e| e as usize == corners.len())
        && offsets.windows(2).all(|w| w[0] <= w[1]);
    if !in_order {
        return Err(bad("its polygons' offsets are out of order"));
    }
    let polygon_list = offsets
        .windows(2)
        .map(|w| &corners[w[0] as usize..w[1] as usize]);
    let mut mesh = Mesh::from_polygons(positions, polygon_list).map_err(mesh_error)?;
    let mut exact = None;
    if let Some(n) = file_normals {
        mesh = mesh.with_file_normals(n.clone()).map_err(mesh_error)?;
        if mesh.file_normals() != Some(&n) {
            exact = Some(n);
        }
    }
    if let Some(g) = groups {
        mesh = mesh.with_smoothing_groups(g).map_err(mesh_error)?;
    }
    Ok((mesh, exact))
}

fn mesh_error(e: shadelab_core::MeshError) -> EngineError {
    bad(&e.to_string())
}
