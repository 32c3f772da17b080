//! Vertex accessors read once per model, and each primitive's vertices cut down to those its
//! indices name. Exporters often give all primitives of a mesh one set of vertex accessors and
//! each its own indices: reading the shared accessors whole for every primitive, and keeping
//! them whole in every primitive's mesh, made loading and memory grow with the square of the
//! primitives (`tests::a_shared_vertex_accessor_is_read_once`).

use glam::Vec4;
use std::collections::HashMap;
use std::rc::Rc;

/// How an accessor's elements were turned into `Vec4`s: the same accessor may be read as two
/// attributes (a file may name one accessor as TEXCOORD_0 and as COLOR_0).
#[derive(Clone, Copy, Hash, PartialEq, Eq)]
pub enum As {
    Position,
    Normal,
    TexCoord,
    Color,
}

/// The accessors read so far, and a scratch list for [`Decoded::compact`].
#[derive(Default)]
pub struct Decoded {
    /// Whether the file declares KHR_mesh_quantization (`quantized`): which types its vertex
    /// accessors may have.
    pub quantized: bool,
    read: HashMap<(usize, As), Rc<Vec<Vec4>>>,
    /// For each vertex of the accessor being compacted, its new index (`u32::MAX`: not yet
    /// named); only the entries a primitive names are set, and reset after it.
    renumber: Vec<u32>,
}

impl Decoded {
    /// Nothing read yet of `doc`'s accessors.
    pub fn of(doc: &gltf::Document) -> Decoded {
        Decoded { quantized: doc.extensions_used().any(|e| e == super::quantized::EXTENSION), ..Decoded::default() }
    }

    /// Accessor `index` read `as_`, by `read` the first time.
    pub fn get(
        &mut self,
        index: usize,
        as_: As,
        read: impl FnOnce() -> Result<Vec<Vec4>, String>,
    ) -> Result<Rc<Vec<Vec4>>, String> {
        if let Some(v) = self.read.get(&(index, as_)) {
            return Ok(v.clone());
        }
        let v = Rc::new(read()?);
        self.read.insert((index, as_), v.clone());
        Ok(v)
    }

    /// The vertices of the `count` an accessor holds that `order` names, ascending, and
    /// `order` renumbered to them; `None` where it names all of them (nothing to cut). Time
    /// in the length of `order`, not in `count`. Every index is below `count`.
    pub fn compact(&mut self, order: &mut [u32], count: usize) -> Option<Vec<u32>> {
        let mut used: Vec<u32> = Vec::new();
        if self.renumber.len() < count {
            self.renumber.resize(count, u32::MAX);
        }
        for &i in order.iter() {
            if std::mem::replace(&mut self.renumber[i as usize], 0) == u32::MAX {
                used.push(i);
            }
        }
        if used.len() == count {
            used.iter().for_each(|&i| self.renumber[i as usize] = u32::MAX);
            return None;
        }
        used.sort_unstable();
        for (new, &old) in used.iter().enumerate() {
            self.renumber[old as usize] = new as u32;
        }
        for i in order.iter_mut() {
            *i = self.renumber[*i as usize];
        }
        used.iter().for_each(|&i| self.renumber[i as usize] = u32::MAX);
        Some(used)
    }
}

/// The elements of `all` that `used` keeps (all of them where it is `None`), in turn, with no
/// copy of the list made.
pub fn kept<'a>(all: &'a [Vec4], used: Option<&'a [u32]>) -> impl Iterator<Item = Vec4> + 'a {
    let picked = used.map(|used| used.iter().map(|&i| all[i as usize]));
    let whole = used.is_none().then(|| all.iter().copied());
    picked.into_iter().flatten().chain(whole.into_iter().flatten())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compacting_keeps_the_named_vertices_in_order_and_renumbers_the_indices() {
        let mut d = Decoded::default();
        let mut order = vec![7, 3, 5, 3, 7, 9];
        assert_eq!(d.compact(&mut order, 10), Some(vec![3, 5, 7, 9]));
        assert_eq!(order, [2, 0, 1, 0, 2, 3]);
        // The scratch list is clean for the next primitive: all named is nothing to cut.
        let mut all = vec![2, 1, 0, 0, 1, 2];
        assert_eq!(d.compact(&mut all, 3), None);
        assert_eq!(all, [2, 1, 0, 0, 1, 2]);
        assert!(d.renumber.iter().all(|&r| r == u32::MAX));
    }

    #[test]
    fn an_accessor_is_read_once_per_way_of_reading_it() {
        let mut d = Decoded::default();
        let mut reads = 0;
        for _ in 0..3 {
            d.get(4, As::Position, || {
                reads += 1;
                Ok(vec![Vec4::ONE])
            })
            .unwrap();
        }
        d.get(4, As::Color, || Ok(vec![Vec4::ZERO])).unwrap();
        assert_eq!(reads, 1);
        assert_eq!(d.get(4, As::Color, || Err("read again".into())).unwrap()[0], Vec4::ZERO);
    }
}
