//! glTF 2.0 meshes, `.gltf` (JSON) and `.glb` (binary), read with the `gltf`
//! crate.
//!
//! `gltf` is used with its default features off and only `utils` (accessor
//! readers) on: its `import` feature would pull in `image` (with JPEG and
//! PNG decoders) to load textures shadelab never uses. So
//! [`gltf::Gltf::from_slice`](::gltf::Gltf::from_slice) parses and validates
//! the document (JSON or GLB, told by the `glTF` magic, not by extension),
//! and `buffers.rs` loads the buffers itself: the GLB `BIN` chunk,
//! `data:…;base64,` URIs (decoded with the `base64` crate), and relative
//! file URIs (percent-decoded, all files together within
//! [`crate::MAX_MESH_BYTES`]). A file URI must name a regular file inside
//! the folder that holds the glTF file, with every symbolic link resolved
//! (`crate::input`); an absolute path, `..` out of the folder, a link
//! pointing out, another URI scheme are errors naming the reference, and the
//! referenced file is not opened, so none of its bytes can reach a message.
//! Image URIs are held to the same rule, though images are never read.
//!
//! The triangles and vertices the scene draws are counted from the JSON,
//! after instancing (a mesh drawn by several nodes counts once per node),
//! and checked against [`Mesh::MAX_TRIANGLES`], [`Mesh::MAX_VERTICES`] and
//! [`MAX_MEMORY_BYTES`] before any buffer is read: a small file cannot make
//! gigabytes of vertices.
//!
//! What is read: the default scene (or, without one, the first scene; a file
//! with no scene at all uses every root node), walked from its root nodes
//! with each node's transform multiplied into its parent's; every primitive
//! of mode `TRIANGLES` (other modes are skipped), indexed or not; its
//! `POSITION`s transformed to world space. `NORMAL`s, transformed by the
//! inverse transpose of the node's matrix, become file normals when every
//! triangle primitive has them (and every transform is invertible, and no
//! normal is zero). Under a
//! transform with a negative determinant the winding is reversed, as the
//! glTF specification says. Vertices of different primitives are not welded.
//! Materials, textures, skins, morph targets and cameras are ignored; sparse
//! accessors and accessors without a buffer view are refused.
//!
//! Every accessor used is checked here (type, component type, count, stride
//! and that it lies inside its buffer view and buffer) before `gltf`'s
//! reader sees it: that reader slices and asserts on what it is given
//! (`count - 1` underflows for an empty accessor, a too-small stride trips
//! a debug assertion), so checking first keeps malformed files from
//! panicking; and the counts they declare are checked against
//! [`Mesh::MAX_VERTICES`] and [`Mesh::MAX_TRIANGLES`] before anything is read
//! into memory. `gltf-json`'s own validation was found (by fuzzing) to panic
//! when a primitive's `POSITION` names an accessor that does not exist, so
//! the file is parsed without validation first, those indices are checked,
//! and only then is it validated.

use std::collections::HashSet;
use std::path::Path;

use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::mesh::{Mode, Semantic};
use glam::{Mat3, Mat4, Vec3};
use shadelab_core::limits::{mesh_memory, MAX_MEMORY_BYTES};
use shadelab_core::{CornerNormals, Mesh};

use crate::input::read_capped;
use crate::mesh_file::{invalid, mesh_error, MAX_MESH_BYTES};
use crate::LoadError;

mod buffers;

pub(crate) use buffers::external_buffers;
use buffers::{check_images, load_buffers};

/// Reads a glTF 2.0 file, `.gltf` or `.glb`; external buffers are read
/// from the file's directory.
///
/// # Errors
/// [`LoadError`] naming the file (and the buffer, accessor, mesh or node at
/// fault): unreadable, too large, not glTF, invalid JSON or GLB, missing or
/// short buffers, bad accessors, indices out of range, non-finite values,
/// no triangles.
pub fn load_gltf(path: &Path) -> Result<Mesh, LoadError> {
    let bytes = read_capped(path, MAX_MESH_BYTES)?;
    let base = path.parent().unwrap_or(Path::new("."));
    parse_gltf(&bytes, &path.display().to_string(), Some(base))
}

/// Parses glTF (JSON or GLB) bytes; `name` is used in error messages and
/// external buffers are read from `base_dir` (none: they are refused).
///
/// # Errors
/// As [`load_gltf`].
pub fn parse_gltf(bytes: &[u8], name: &str, base_dir: Option<&Path>) -> Result<Mesh, LoadError> {
    let gltf = ::gltf::Gltf::from_slice_without_validation(bytes)
        .map_err(|e| invalid(name, format!("not a valid glTF 2.0 file: {e}")))?;
    // `gltf-json` 1.4.1's validation indexes `accessors` with each POSITION
    // attribute's value before checking it (mesh.rs, `primitive_validate_hook`)
    // and panics on a missing one: check those indices first.
    let json = gltf.document.as_json();
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let position = primitive
                .attributes
                .get(&::gltf::json::validation::Checked::Valid(
                    ::gltf::json::mesh::Semantic::Positions,
                ));
            if let Some(index) = position.filter(|i| i.value() >= json.accessors.len()) {
                return Err(invalid(
                    name,
                    format!(
                        "not a valid glTF 2.0 file: meshes[{m}].primitives[{p}] POSITION names \
                         accessor {}, but there are {} accessors",
                        index.value(),
                        json.accessors.len()
                    ),
                ));
            }
        }
    }
    // Now the crate's own validation is safe to run (it parses again).
    let gltf = ::gltf::Gltf::from_slice(bytes)
        .map_err(|e| invalid(name, format!("not a valid glTF 2.0 file: {e}")))?;
    let instances = instances(&gltf, name)?;
    check_budget(&instances, name)?;
    check_images(&gltf, name, base_dir)?;
    let budget = MAX_MESH_BYTES.saturating_sub(bytes.len() as u64);
    let buffers = load_buffers(&gltf, name, base_dir, budget)?;

    let mut out = Builder::default();
    for (node, world) in &instances {
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                let at = format!("mesh {}, primitive {}", mesh.index(), primitive.index());
                if primitive.mode() != Mode::Triangles {
                    out.skipped += 1;
                    continue;
                }
                out.add(&primitive, *world, &buffers, name, &at)?;
            }
        }
    }
    out.finish(name)
}

/// Every node of the scene drawn, in drawing order, with its transform to
/// world space.
fn instances<'a>(
    gltf: &'a ::gltf::Gltf,
    name: &str,
) -> Result<Vec<(::gltf::Node<'a>, Mat4)>, LoadError> {
    // The nodes to start from.
    let roots: Vec<::gltf::Node> = match gltf.default_scene().or_else(|| gltf.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => {
            let children: HashSet<usize> = gltf
                .nodes()
                .flat_map(|n| n.children().map(|c| c.index()))
                .collect();
            gltf.nodes()
                .filter(|n| !children.contains(&n.index()))
                .collect()
        }
    };
    let mut instances = Vec::new();
    let mut visited = HashSet::new();
    let mut stack: Vec<(::gltf::Node, Mat4)> = roots
        .into_iter()
        .rev()
        .map(|n| (n, Mat4::IDENTITY))
        .collect();
    while let Some((node, parent)) = stack.pop() {
        if !visited.insert(node.index()) {
            return Err(invalid(
                name,
                format!(
                    "node {} is reached twice: the node hierarchy is not a tree",
                    node.index()
                ),
            ));
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if !world.is_finite() {
            return Err(invalid(
                name,
                format!("node {}: its transform is not finite", node.index()),
            ));
        }
        for child in node.children().collect::<Vec<_>>().into_iter().rev() {
            stack.push((child, world));
        }
        instances.push((node, world));
    }
    Ok(instances)
}

/// Fails, before any buffer is read or any vertex kept, when the scene
/// draws more triangles or vertices than a mesh may have, counted after
/// instancing (a mesh drawn by many nodes counts each time), or more than
/// [`MAX_MEMORY_BYTES`] would hold: the counts are the accessors' own,
/// from the JSON.
fn check_budget(instances: &[(::gltf::Node, Mat4)], name: &str) -> Result<(), LoadError> {
    let (mut triangles, mut vertices, mut drawing) = (0u64, 0u64, 0usize);
    for (node, _) in instances {
        let Some(mesh) = node.mesh() else { continue };
        drawing += 1;
        for primitive in mesh.primitives() {
            let Some(position) = primitive.get(&Semantic::Positions) else {
                continue;
            };
            if primitive.mode() != Mode::Triangles {
                continue;
            }
            let count = claimed(&position);
            triangles += primitive.indices().map_or(count, |i| claimed(&i)) / 3;
            vertices += count;
        }
    }
    let after = format!("after instancing ({drawing} nodes draw a mesh)");
    if triangles > Mesh::MAX_TRIANGLES as u64 {
        return Err(invalid(
            name,
            format!(
                "the scene draws {triangles} triangles {after}; at most {} are supported",
                Mesh::MAX_TRIANGLES
            ),
        ));
    }
    if vertices > Mesh::MAX_VERTICES as u64 {
        return Err(invalid(
            name,
            format!(
                "the scene draws {vertices} vertices {after}; at most {} are supported",
                Mesh::MAX_VERTICES
            ),
        ));
    }
    let bytes = mesh_memory(vertices as usize, triangles as usize);
    if bytes > MAX_MEMORY_BYTES {
        return Err(invalid(
            name,
            format!(
                "the scene draws {triangles} triangles and {vertices} vertices {after}, which \
                 would take about {} MiB, more than the limit of {} MiB",
                bytes >> 20,
                MAX_MEMORY_BYTES >> 20
            ),
        ));
    }
    Ok(())
}

/// An accessor's element count as far as its buffer view's declared length
/// can hold it (a count beyond that is an error found later, when the
/// accessor is checked against its buffer).
fn claimed(accessor: &::gltf::Accessor) -> u64 {
    let Some(view) = accessor.view() else {
        return 0;
    };
    let size = accessor.size() as u64;
    let stride = view.stride().map_or(size, |s| s as u64).max(size).max(1);
    let room = (view.length() as u64).saturating_sub(accessor.offset() as u64);
    let fits = if room >= size {
        (room - size) / stride + 1
    } else {
        0
    };
    (accessor.count() as u64).min(fits)
}

/// The triangles gathered so far.
#[derive(Default)]
struct Builder {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    /// Whether every triangle primitive so far had usable normals.
    all_normals: bool,
    primitives: usize,
    skipped: usize,
}

impl Builder {
    fn add(
        &mut self,
        primitive: &::gltf::Primitive,
        world: Mat4,
        buffers: &[Vec<u8>],
        name: &str,
        at: &str,
    ) -> Result<(), LoadError> {
        let error = |message: String| invalid(name, format!("{at}: {message}"));
        let position = primitive
            .get(&Semantic::Positions)
            .ok_or_else(|| error("no POSITION attribute".into()))?;
        check_accessor(&position, &[Dimensions::Vec3], &[DataType::F32], buffers)
            .map_err(|m| error(format!("POSITION accessor {}: {m}", position.index())))?;
        let normal = primitive.get(&Semantic::Normals);
        if let Some(n) = &normal {
            check_accessor(n, &[Dimensions::Vec3], &[DataType::F32], buffers)
                .map_err(|m| error(format!("NORMAL accessor {}: {m}", n.index())))?;
            if n.count() != position.count() {
                return Err(error(format!(
                    "NORMAL accessor {} has {} elements, POSITION has {}",
                    n.index(),
                    n.count(),
                    position.count()
                )));
            }
        }
        if let Some(i) = primitive.indices() {
            check_accessor(
                &i,
                &[Dimensions::Scalar],
                &[DataType::U8, DataType::U16, DataType::U32],
                buffers,
            )
            .map_err(|m| error(format!("index accessor {}: {m}", i.index())))?;
        }

        let triangles = primitive.indices().map_or(position.count(), |i| i.count()) / 3;
        if self.triangles.len() + triangles > Mesh::MAX_TRIANGLES {
            return Err(error(format!(
                "more than {} triangles in the scene: that is the most supported",
                Mesh::MAX_TRIANGLES
            )));
        }
        if self.positions.len() + position.count() > Mesh::MAX_VERTICES {
            return Err(error(format!(
                "more than {} vertices in the scene: that is the most supported",
                Mesh::MAX_VERTICES
            )));
        }

        let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
        let local: Vec<Vec3> = reader
            .read_positions()
            .ok_or_else(|| error("POSITION data could not be read".into()))?
            .map(Vec3::from_array)
            .collect();
        let count = local.len();
        let indices: Vec<u32> = match reader.read_indices() {
            Some(i) => i.into_u32().collect(),
            None if primitive.indices().is_some() => {
                return Err(error("index data could not be read".into()));
            }
            None => (0..count as u32).collect(),
        };
        if !indices.len().is_multiple_of(3) {
            return Err(error(format!(
                "{} indices: TRIANGLES needs a multiple of 3",
                indices.len()
            )));
        }
        if let Some((k, &i)) = indices
            .iter()
            .enumerate()
            .find(|(_, &i)| i as usize >= count)
        {
            return Err(error(format!(
                "index {k} is {i}, but the primitive has {count} vertices"
            )));
        }

        let base = self.positions.len() as u32;
        self.positions
            .extend(local.iter().map(|&p| world.transform_point3(p)));
        let flip = world.determinant() < 0.0;
        self.triangles.extend(indices.chunks_exact(3).map(|t| {
            let t = [base + t[0], base + t[1], base + t[2]];
            if flip {
                [t[0], t[2], t[1]]
            } else {
                t
            }
        }));

        let normal_matrix = Mat3::from_mat4(world);
        let invertible = normal_matrix.determinant() != 0.0;
        let normals = match (normal, reader.read_normals()) {
            (Some(_), Some(n)) if invertible => Some(n),
            (Some(_), None) => return Err(error("NORMAL data could not be read".into())),
            _ => None,
        };
        self.all_normals = (self.primitives == 0 || self.all_normals) && normals.is_some();
        if let Some(n) = normals {
            let m = normal_matrix.inverse().transpose();
            self.normals.extend(n.map(|n| m * Vec3::from_array(n)));
        } else {
            self.normals.extend(std::iter::repeat_n(Vec3::ZERO, count));
        }
        self.primitives += 1;
        Ok(())
    }

    fn finish(self, name: &str) -> Result<Mesh, LoadError> {
        if self.triangles.is_empty() {
            return Err(invalid(
                name,
                format!(
                    "no triangles in the scene ({} triangle primitives, {} primitives of other modes skipped)",
                    self.primitives, self.skipped
                ),
            ));
        }
        let mesh = Mesh::from_polygons(self.positions, self.triangles).map_err(mesh_error(name))?;
        // A non-finite normal is an error (from `with_file_normals`); a zero
        // one means the file's normals are not usable.
        let usable = |n: &Vec3| !n.is_finite() || n.try_normalize().is_some();
        if self.all_normals && self.normals.iter().all(usable) {
            let corner = mesh.corners().to_vec();
            mesh.with_file_normals(CornerNormals::new(self.normals, corner))
                .map_err(mesh_error(name))
        } else {
            Ok(mesh)
        }
    }
}

/// Checks an accessor so that `gltf`'s reader can read it without panicking.
fn check_accessor(
    accessor: &::gltf::Accessor,
    dimensions: &[Dimensions],
    types: &[DataType],
    buffers: &[Vec<u8>],
) -> Result<(), String> {
    if !dimensions.contains(&accessor.dimensions()) || !types.contains(&accessor.data_type()) {
        return Err(format!(
            "type {:?} of {:?} is not supported here (expected {:?} of {:?})",
            accessor.dimensions(),
            accessor.data_type(),
            dimensions,
            types
        ));
    }
    if accessor.normalized() {
        return Err("normalized integer data is not supported here".into());
    }
    if accessor.sparse().is_some() {
        return Err("sparse accessors are not supported".into());
    }
    let view = accessor
        .view()
        .ok_or("it has no bufferView (all zeros); not supported")?;
    let count = accessor.count();
    if count == 0 {
        return Err("count is 0".into());
    }
    let size = accessor.size();
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err(format!(
            "buffer view {} has a stride of {stride} bytes, less than the element size {size}",
            view.index()
        ));
    }
    let end = (count as u128 - 1) * stride as u128 + size as u128 + accessor.offset() as u128;
    if end > view.length() as u128 {
        return Err(format!(
            "{count} elements from byte {} with stride {stride} end at byte {end}, \
             past the end of buffer view {} ({} bytes)",
            accessor.offset(),
            view.index(),
            view.length()
        ));
    }
    let buffer = view.buffer().index();
    let available = buffers.get(buffer).map_or(0, Vec::len);
    let view_end = view.offset() as u128 + view.length() as u128;
    if view_end > available as u128 {
        return Err(format!(
            "buffer view {} ends at byte {view_end} of buffer {buffer}, which has {available} bytes",
            view.index()
        ));
    }
    Ok(())
}
