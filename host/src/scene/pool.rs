//! The scene's meshes as the GPU's vertex and index buffers see them: one after another, each
//! at its base, without copying them. A million-triangle scene keeps its geometry once in
//! host memory (the meshes it loaded, shared by every clone of the scene and every build of
//! its GPU data) and once in the mapped buffers each upload writes it to.

use super::mesh::MeshData;
use std::ops::Index;
use std::sync::Arc;

/// The meshes' vertices (or indices) end to end: element `i` of the whole is element
/// `i - base` of the mesh whose range holds it.
#[derive(Clone)]
pub struct Pooled<T: 'static> {
    meshes: Vec<Arc<MeshData>>,
    /// Each mesh's first element in the whole, ascending.
    bases: Vec<usize>,
    len: usize,
    part: fn(&MeshData) -> &[T],
}

impl<T> Pooled<T> {
    /// An empty pool of what `part` picks from each mesh.
    pub fn new(part: fn(&MeshData) -> &[T]) -> Self {
        Pooled { meshes: Vec::new(), bases: Vec::new(), len: 0, part }
    }

    /// Adds `mesh`'s elements at the end; returns their base.
    pub fn push(&mut self, mesh: Arc<MeshData>) -> usize {
        let base = self.len;
        self.len += (self.part)(&mesh).len();
        self.bases.push(base);
        self.meshes.push(mesh);
        base
    }

    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Element `i` of the whole, if there is one.
    pub fn get(&self, i: usize) -> Option<&T> {
        let k = self.bases.partition_point(|&b| b <= i).checked_sub(1)?;
        (self.part)(&self.meshes[k]).get(i - self.bases[k])
    }

    /// `count` elements from `base`, all of one mesh (as a BLAS's range is); `None` where they
    /// are not.
    pub fn range(&self, base: usize, count: usize) -> Option<&[T]> {
        let k = self.bases.partition_point(|&b| b <= base).checked_sub(1)?;
        (self.part)(&self.meshes[k]).get(base - self.bases[k]..base - self.bases[k] + count)
    }

    /// Lets go of the meshes, leaving the pool empty: an upload does once its buffers hold
    /// them, so that a scene that gave its meshes up (`render::render_owned`) frees them.
    pub fn release(&mut self) {
        *self = Pooled::new(self.part);
    }

    /// Every mesh's elements, in order: what a buffer of the whole holds end to end.
    pub fn parts(&self) -> impl Iterator<Item = &[T]> + Clone {
        self.meshes.iter().map(|m| (self.part)(m))
    }
}

impl<T> Index<usize> for Pooled<T> {
    type Output = T;

    fn index(&self, i: usize) -> &T {
        self.get(i).unwrap_or_else(|| panic!("element {i} of a pool of {}", self.len))
    }
}

impl<T: std::fmt::Debug> std::fmt::Debug for Pooled<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} elements of {} meshes", self.len, self.meshes.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(indices: &[u32]) -> Arc<MeshData> {
        Arc::new(MeshData { vertices: Vec::new(), indices: indices.to_vec() })
    }

    #[test]
    fn elements_are_found_in_the_mesh_that_holds_them() {
        let mut pool = Pooled::new(|m: &MeshData| &m.indices[..]);
        assert_eq!((pool.push(mesh(&[0, 1, 2])), pool.push(mesh(&[])), pool.push(mesh(&[7, 8]))), (0, 3, 3));
        assert_eq!(pool.len(), 5);
        let all: Vec<u32> = (0..5).map(|i| pool[i]).collect();
        assert_eq!(all, [0, 1, 2, 7, 8]);
        assert_eq!(pool.get(5), None);
        assert_eq!(pool.range(3, 2), Some(&[7, 8][..]));
        assert_eq!(pool.range(1, 3), None, "a range across two meshes");
        assert_eq!(pool.parts().flatten().count(), 5);
        let held = mesh(&[4]);
        pool.push(held.clone());
        pool.release();
        assert_eq!((pool.len(), pool.parts().count(), Arc::strong_count(&held)), (0, 0, 1));
    }
}
